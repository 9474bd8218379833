// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_GAP_CLOSING_RESULT_H
#define MREPAIR_GAP_CLOSING_RESULT_H

/// \file gap_closing_result.h
/// What `close_gaps()` and `Gap_closing_sequence` report.

#include <mrepair/report.h>
#include <mrepair/status.h>

#include <cstddef>
#include <string>

namespace mrepair {

/// \ingroup mrepair_gaps
/// what `estimate_gap_tolerance()` found: the tolerance and the figures behind it.
struct Gap_tolerance_estimate
{
  Status status = Status::ok;
  double tolerance = 0;                   ///< absolute; 0 when no boundary vertex has a near partner
  std::size_t boundary_vertices = 0;
  std::size_t boundary_edges = 0;
  std::size_t candidates = 0;             ///< boundary vertices with another boundary nearer than their longest boundary edge
  std::size_t not_facing = 0;             ///< near pairs left out: the partner's surface folds back on the vertex's side or its boundary runs the same way
  std::size_t above_knee = 0;             ///< candidates farther than the knee (left open)
  double knee_distance = 0;               ///< the candidate distance the tolerance is derived from
  double largest_candidate_distance = 0;
  double median_edge_length = 0;          ///< of the longest boundary edge at each boundary vertex

  void to_report(Report& r) const
  {
    r.add("status", to_string(status));
    r.add("tolerance", tolerance);
    r.add("boundary_vertices", boundary_vertices);
    r.add("boundary_edges", boundary_edges);
    r.add("candidates", candidates);
    r.add("not_facing", not_facing);
    r.add("above_knee", above_knee);
    r.add("knee_distance", knee_distance);
    r.add("largest_candidate_distance", largest_candidate_distance);
    r.add("median_edge_length", median_edge_length);
  }
};

/// \ingroup mrepair_gaps
/// what `close_gaps()` or a `Gap_closing_sequence` did.
struct Gap_closing_result
{
  Status status = Status::ok;
  std::string message;
  double tolerance = 0;                      ///< absolute distance limit used
  bool tolerance_estimated = false;          ///< chosen by `estimate_gap_tolerance()` (then `estimate` is filled)
  Gap_tolerance_estimate estimate;
  std::size_t operations = 0;                ///< contractions applied (net, at the current position)
  std::size_t vertex_vertex = 0;             ///< of which vertex-vertex contractions
  std::size_t vertex_edge = 0;               ///< of which vertex-edge contractions
  std::size_t alternative_placements = 0;    ///< contractions placed at one side (the merged position would flip a face)
  std::size_t rejected_flip = 0;             ///< pairs skipped: a face would flip
  std::size_t rejected_degenerate = 0;       ///< pairs skipped: a face would get zero area
  std::size_t rejected_non_manifold = 0;     ///< pairs skipped: an edge with >2 faces / broken fan
  std::size_t rejected_failed = 0;           ///< pairs skipped: the halfedge update failed (rolled back)
  std::size_t rejected_displacement = 0;     ///< pairs skipped: a vertex would move farther than the tolerance
  std::size_t boundary_edges_before = 0;
  std::size_t boundary_edges_after = 0;
  std::size_t boundary_loops_before = 0;
  std::size_t boundary_loops_after = 0;
  std::size_t pinched_vertices = 0;          ///< boundary vertices with several fans (left in the mesh)
  std::size_t pinched_vertices_split = 0;    ///< vertices created by splitting pinched vertices
  std::size_t loops_bridged = 0;             ///< narrow loops left by the contractions, filled (nothing moved)
  std::size_t seam_edges_zipped = 0;         ///< pairs of facing border edges joined by a quad before the contractions (`gap_bridge_first`)
  std::size_t seam_faces = 0;                ///< faces of those quads (nothing moved)
  std::size_t bridge_faces = 0;              ///< faces added by those bridges
  std::size_t bridges_rejected_intersecting = 0;  ///< bridges taken back: they passed through a clean stretch of the surface
  double max_displacement = 0;               ///< largest distance a vertex moved from its input position
  double final_distance = 0;                 ///< error level of the last applied contraction

  void to_report(Report& r) const
  {
    r.add("status", to_string(status));
    if (!message.empty()) r.add("message", message);
    r.add("tolerance", tolerance);
    r.add("tolerance_chosen_by", tolerance_estimated ? "auto" : "user");
    if (tolerance_estimated) estimate.to_report(r.section("tolerance_estimate"));
    r.add("operations", operations);
    r.add("vertex_vertex", vertex_vertex);
    r.add("vertex_edge", vertex_edge);
    r.add("alternative_placements", alternative_placements);
    Report& rj = r.section("rejected");
    rj.add("flip", rejected_flip);
    rj.add("degenerate", rejected_degenerate);
    rj.add("non_manifold", rejected_non_manifold);
    rj.add("failed", rejected_failed);
    rj.add("displacement", rejected_displacement);
    r.add("boundary_edges_before", boundary_edges_before);
    r.add("boundary_edges_after", boundary_edges_after);
    r.add("boundary_loops_before", boundary_loops_before);
    r.add("boundary_loops_after", boundary_loops_after);
    r.add("pinched_vertices", pinched_vertices);
    r.add("pinched_vertices_split", pinched_vertices_split);
    r.add("loops_bridged", loops_bridged);
    r.add("seam_edges_zipped", seam_edges_zipped);
    r.add("seam_faces", seam_faces);
    r.add("bridge_faces", bridge_faces);
    r.add("bridges_rejected_intersecting", bridges_rejected_intersecting);
    r.add("max_displacement", max_displacement);
    r.add("final_distance", final_distance);
  }
};

} // namespace mrepair

#endif // MREPAIR_GAP_CLOSING_RESULT_H
