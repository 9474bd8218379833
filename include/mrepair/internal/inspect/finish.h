// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_INSPECT_FINISH_H
#define MREPAIR_INTERNAL_INSPECT_FINISH_H

// The steps of inspect.h around a `Surface_analysis`: the self-intersection
// count when it applies, the thresholds echoed in the report, and the status.

#include <mrepair/inspection_report.h>
#include <mrepair/internal/inspect/analysis.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <cstddef>
#include <string>

namespace mrepair {
namespace internal {

// Counts self-intersecting pairs when asked and possible: every face a
// triangle, every vertex of a face finite.
// Frees the arrays the counter does not read in any case.
template <typename VisitorHandle>
void count_self_intersections(Surface_arrays& a, Surface_analysis& analysis, bool asked,
                              VisitorHandle& visitor, Inspection_report& r)
{
  if (!asked || analysis.non_finite_referenced != 0 || r.faces == 0 || r.triangles != r.faces) {
    analysis.release_vertex_corners();
    keep_for_self_intersections(a);
    return;
  }
  Phase_scope<VisitorHandle> phase(visitor, "inspect: self-intersections");
  certify_flat_stars(a, analysis.vertex_corner_first(), analysis.vertex_corners());
  analysis.release_vertex_corners();
  keep_for_self_intersections(a);
  const Self_intersection_counts counts = analysis.self_intersecting_pairs();
  r.self_intersecting_pairs = counts.pairs;
  r.self_intersecting_pairs_touching = counts.touching;
  r.self_intersections_counted = true;
}

inline void copy_thresholds(const Inspect_thresholds& t, Inspection_report& r)
{
  r.spike_angle = t.spike_angle;
  r.spike_height_factor = t.spike_height_factor;
  r.zero_edge_factor = t.zero_edge_factor;
  r.skinny_edge_factor = t.skinny_edge_factor;
  r.skinny_angle = t.skinny_angle;
  r.small_angle = t.small_angle;
  r.max_hole_vertices = t.max_hole_vertices;
  r.min_component_faces = t.min_component_faces;
  r.t_junction_tolerance = t.t_junction_tolerance;
}

// Status of a filled report: the worst input problem found.
inline void finish_status(Inspection_report& r, std::size_t non_finite_referenced)
{
  if (r.vertices == 0 || r.faces == 0) {
    r.status = Status::empty_input;
    r.message = r.vertices == 0 ? "no vertices" : "no usable faces";
  } else if (r.invalid_polygons > 0) {
    r.status = Status::invalid_index;
    r.message = std::to_string(r.invalid_polygons) +
                " polygons with an invalid index or fewer than 3 vertices were left out";
  } else if (r.non_finite_vertices > 0) {
    r.status = Status::non_finite_input;
    r.message = std::to_string(r.non_finite_vertices) + " vertices have non-finite coordinates" +
                (non_finite_referenced ? " (faces on them left out of the geometric figures)" : "");
  }
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_INSPECT_FINISH_H
