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
/// what `close_gaps()` or a `Gap_closing_sequence` did.
struct Gap_closing_result
{
  Status status = Status::ok;
  std::string message;
  double tolerance = 0;                      ///< absolute distance limit used
  std::size_t operations = 0;                ///< contractions applied (net, at the current position)
  std::size_t vertex_vertex = 0;             ///< of which vertex-vertex contractions
  std::size_t vertex_edge = 0;               ///< of which vertex-edge contractions
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
  double max_displacement = 0;               ///< largest distance a vertex moved from its input position
  double final_distance = 0;                 ///< error level of the last applied contraction

  void to_report(Report& r) const
  {
    r.add("status", to_string(status));
    if (!message.empty()) r.add("message", message);
    r.add("tolerance", tolerance);
    r.add("operations", operations);
    r.add("vertex_vertex", vertex_vertex);
    r.add("vertex_edge", vertex_edge);
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
    r.add("max_displacement", max_displacement);
    r.add("final_distance", final_distance);
  }
};

} // namespace mrepair

#endif // MREPAIR_GAP_CLOSING_RESULT_H
