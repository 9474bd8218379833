// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_CLOSE_GAPS_H
#define MREPAIR_CLOSE_GAPS_H

/// \file close_gaps.h
/// Progressive gap closing (Borodin, Novotni, Klein, "Progressive Gap Closing
/// for Mesh Repairing"): boundary vertices are contracted with their nearest
/// boundary vertex or edge in order of distance, so that cracks, narrow gaps
/// and T-junctions between patches close while wider gaps stay open.
/// `close_gaps()` runs it once; `Gap_closing_sequence` steps forward and
/// backward through the contractions. `estimate_gap_tolerance()` derives the
/// tolerance from the input (doc/close_gaps.md), and
/// `close_gaps(tm, automatic_gap_tolerance)` uses it.

#include <mrepair/gap_closing_result.h>
#include <mrepair/gap_closing_sequence.h>
#include <mrepair/internal/close_gaps/run.h>
#include <mrepair/internal/close_gaps/tolerance.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/Polygon_mesh_processing/bbox.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace mrepair {

/// \ingroup mrepair_gaps
/// closes boundary gaps not wider than `tolerance` by vertex-vertex and
/// vertex-edge contraction, nearest pairs first.
///
/// \code
///   seq = Gap_closing_sequence(tm, tolerance, np)
///   while seq.step(tolerance): poll visitor (progress, stop)
///   split pinched vertices (duplicate_non_manifold_vertices) so the output is manifold
///   bridge the loops left that are narrower than tolerance / 2 (triangulate_hole)
/// \endcode
///
/// \tparam TriangleMesh model of `MutableFaceGraph`, triangulated
/// \param tm the mesh, modified in place
/// \param tolerance largest gap closed: absolute, or a fraction of the
///   bounding-box diagonal with `gap_relative_tolerance(true)`. Vertices move by at
///   most `tolerance`.
/// \param np optional named parameters:
///   - `vertex_point_map` (default `get(CGAL::vertex_point, tm)`)
///   - `visitor` (`Default_visitor`): phases "pairing", "closing", "manifold"; progress;
///     stop polled before the first contraction and every 256 contractions
///   - `mrepair::parameters::gap_relative_tolerance(bool)` (false)
///   - `gap_lambda(double)` in [0,1] (0.5): a contracted vertex moves to λv + (1-λ)v'
///   - `gap_snap_distance(double)` (`tolerance`): a projection closer than
///     min(snap, edge length / 3) to an edge end becomes a vertex-vertex contraction
///   - `gap_vertex_selection(map)` / `gap_face_selection(map)` (all): bool property
///     maps restricting the closing to a region
///   - `gap_max_operations(std::size_t)` (unlimited)
///   - `gap_split_pinched_vertices(bool)` (true): split vertices left with several
///     fans at the end, so that the output is manifold
///   - `gap_bridge_max_edges(std::size_t)` (400): at the end, fill the boundary loops
///     of at most that many edges that are narrower than tolerance / 2 (twice
///     their area over their perimeter): cracks whose contractions all flip a
///     sliver face; nothing moves (0: no bridging)
///   - `gap_keep_input_points(bool)` (false; `repair()` sets it): a contraction
///     takes the placement that leaves the input positions of the vertices it
///     moves or removes on its new faces (within 1e-6 x the bounding-box
///     diagonal) before the λ point: a vertex-edge contraction bends the edge
///     to the vertex, a vertex-vertex one keeps the end whose partner stays on
///     the merged surface (a crack across a flat side). The λ point when no
///     candidate does (the rims of a crack along a crease)
///   - `gap_bridge_first(bool)` (false; `repair()` sets it): before any
///     contraction, join the two sides of a crack whose border edges face
///     each other with a strip: a border edge a-b whose ends have, as mutual
///     nearest border vertices farther apart than 1e-6 x the bounding-box
///     diagonal, the ends d, c of a border edge c-d gets the quad a-b-c-d,
///     when the quad continues the surface (its triangles and both sides'
///     faces within 45 degrees). Nothing moves there: a vertex-vertex contraction
///     moves both vertices by half the gap, which loses them by
///     `compare_to_reference()`'s measure (two rims 0.0018 apart: each vertex
///     0.0009 off, 85x that tolerance). Skipped with a `gap_vertex_selection`
///     or `gap_face_selection` region.
/// \pre `CGAL::is_valid_polygon_mesh(tm)` (checked in debug builds only)
/// \return `Gap_closing_result`; `tm` untouched when `status` reports bad input
///   (`empty_input`, `non_finite_input`, `invalid_mesh`, `invalid_parameter`;
///   `non_finite_input` also when the bounding-box diagonal exceeds 1e100);
///   `cancelled` when the visitor stopped it (the mesh is valid).
template <typename TriangleMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Gap_closing_result close_gaps(TriangleMesh& tm, double tolerance,
                              const NamedParameters& np = CGAL::parameters::default_values())
{
  using VPM = typename CGAL::GetVertexPointMap<TriangleMesh, NamedParameters>::type;
  internal::Visitor_handle<NamedParameters> visitor(np);
  const std::size_t max_ops = internal::get_or(np, internal_np::gap_max_operations,
                                               std::numeric_limits<std::size_t>::max());
  const bool split = internal::get_or(np, internal_np::gap_split_pinched_vertices, true);
  const std::size_t bridge = internal::get_or(np, internal_np::gap_bridge_max_edges, std::size_t(400));

  using CGAL::parameters::is_default_parameter;
  constexpr bool whole_mesh = is_default_parameter<NamedParameters, internal_np::gap_vertex_selection_t>::value &&
                              is_default_parameter<NamedParameters, internal_np::gap_face_selection_t>::value;
  const bool bridge_first = whole_mesh && internal::get_or(np, internal_np::gap_bridge_first, false);
  VPM vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, tm));

  std::unique_ptr<Gap_closing_sequence<TriangleMesh, VPM>> seq;
  auto pair_boundaries = [&]() {
    internal::Phase_scope<decltype(visitor)> phase(visitor, "pairing");
    seq.reset(new Gap_closing_sequence<TriangleMesh, VPM>(tm, tolerance, np));
  };
  pair_boundaries();  // also checks the input and makes the tolerance absolute
  if (seq->status() != Status::ok) return seq->result();
  Gap_closing_result first;  // the strips before the contractions
  if (bridge_first && seq->result().boundary_edges_before > 0) {
    const double absolute = seq->result().tolerance;
    const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(tm, CGAL::parameters::vertex_point_map(vpm));
    const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                      CGAL::square(box.zmax() - box.zmin()));
    first.boundary_edges_before = seq->result().boundary_edges_before;
    first.boundary_loops_before = seq->result().boundary_loops_before;
    internal::zip_facing_border_edges(tm, vpm, absolute, 1e-6 * diagonal, first);
    if (first.seam_faces > 0) {  // the border changed: pair it again (else the pairs stand)
      pair_boundaries();
      if (seq->status() != Status::ok) return seq->result();
    }
  }
  const bool cancelled = internal::step_to_limit(*seq, visitor, max_ops);
  Gap_closing_result r = seq->result();
  if (first.seam_faces > 0) {
    r.seam_edges_zipped = first.seam_edges_zipped;
    r.seam_faces = first.seam_faces;
    r.boundary_edges_before = first.boundary_edges_before;
    r.boundary_loops_before = first.boundary_loops_before;
  }
  if (split && r.pinched_vertices > 0 && r.status == Status::ok)
    internal::split_pinched_vertices(tm, vpm, visitor, r);
  // a pinched vertex left (keep-pinched) would make a bridge non-manifold
  if (bridge >= 3 && !cancelled && r.status == Status::ok && r.pinched_vertices == 0 &&
      r.boundary_edges_after > 0)
    internal::bridge_narrow_loops(tm, vpm, r.tolerance, bridge, visitor, r);
  if (cancelled) r.status = Status::cancelled;
  return r;
}

/// \ingroup mrepair_gaps
/// the tag of `close_gaps(tm, automatic_gap_tolerance, np)`.
struct Automatic_gap_tolerance {};
constexpr Automatic_gap_tolerance automatic_gap_tolerance{};

/// \ingroup mrepair_gaps
/// derives a gap-closing tolerance from the mesh itself.
///
/// \code
///   for each boundary vertex v:
///     l(v) = its longest boundary edge
///     d(v) = distance to the nearest boundary edge touching neither v nor a loop
///            neighbour of v; a candidate when d(v) < l(v)
///   fewer than 16 candidates: tolerance 0 (no seams to read a distribution from)
///   sort the candidate distances; knee = the first jump by 2x above their 90% quantile
///   (the largest one when there is none)
///   tolerance = 1.5 x knee
/// \endcode
/// Seam partners (both sides of a crack, a T-junction vertex and the edge it
/// sits on) are far nearer than the edges around them; the rim of a real hole is
/// not nearer than an edge length to itself, so it is no candidate; the few
/// narrow features above the knee stay open.
///
/// \tparam TriangleMesh model of `FaceGraph`
/// \param np optional: `vertex_point_map`
/// \return `Gap_tolerance_estimate`; `tolerance` 0 when the mesh has no boundary
///   vertex with a near partner (closed meshes, real holes only);
///   `status` `non_finite_input` when a boundary vertex is not finite
template <typename TriangleMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Gap_tolerance_estimate estimate_gap_tolerance(const TriangleMesh& tm,
                                              const NamedParameters& np = CGAL::parameters::default_values())
{
  auto vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_const_property_map(CGAL::vertex_point, tm));
  return internal::estimate_tolerance(tm, vpm);
}

/// \ingroup mrepair_gaps
/// `close_gaps()` with the tolerance of `estimate_gap_tolerance()`
/// (`gap_relative_tolerance` is ignored). The result says `tolerance_estimated`
/// and carries the estimate; with no candidate the mesh is left untouched and
/// the result reports zero operations.
template <typename TriangleMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Gap_closing_result close_gaps(TriangleMesh& tm, Automatic_gap_tolerance,
                              const NamedParameters& np = CGAL::parameters::default_values())
{
  Gap_closing_result r;
  // the estimate reads each halfedge and its neighbours, walking no cycle;
  // the closing checks the halfedge structure before its walks, and so does
  // the count below (one check per path, not two)
  const Gap_tolerance_estimate e = estimate_gap_tolerance(tm, np);
  if (e.status != Status::ok) {
    r.status = e.status;
    r.message = "a boundary vertex coordinate is NaN or infinite";
  } else if (e.tolerance > 0) {
    // the estimate is absolute: the outermost option wins over a caller's relative flag
    r = close_gaps(tm, e.tolerance, parameters::gap_relative_tolerance(false, np));
  } else if (std::string broken = internal::halfedge_structure_defect(tm); !broken.empty()) {
    r.status = Status::invalid_mesh;
    r.message = "close_gaps: the input's halfedge structure is broken: " + broken;
  } else {
    const auto counts = internal::count_boundary(tm);
    r.boundary_edges_before = r.boundary_edges_after = counts.first;
    r.boundary_loops_before = r.boundary_loops_after = counts.second;
  }
  r.tolerance_estimated = true;
  r.estimate = e;
  return r;
}

} // namespace mrepair

#endif // MREPAIR_CLOSE_GAPS_H
