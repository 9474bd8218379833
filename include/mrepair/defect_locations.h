// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_DEFECT_LOCATIONS_H
#define MREPAIR_DEFECT_LOCATIONS_H

#include <mrepair/inspection_report.h>

#include <array>
#include <cstddef>
#include <limits>
#include <vector>

/// \file defect_locations.h
/// The result of `mrepair::locate_defects()` (see `locate_defects.h`): where
/// the defects that `inspect()` counts are, as vertex and face indices.

namespace mrepair {

/// \ingroup mrepair_inspect
/// the defects of a polygon soup or mesh as index lists, found by the same
/// pass that fills `report` (an `Inspection_report`), so that every list has
/// exactly as many instances as the report's count for that defect:
///
/// | member                    | instances                 | report count              |
/// |---------------------------|---------------------------|---------------------------|
/// | `boundary_loops`          | loops                     | `boundary_loops`          |
/// | `small_holes`             | indices of loops          | `small_holes`             |
/// | `non_manifold_edges`      | vertex pairs              | `non_manifold_edges`      |
/// | `non_manifold_vertices`   | vertices                  | `non_manifold_vertices`   |
/// | `spiked_vertices`         | vertices                  | `spiked_vertices`         |
/// | `near_degenerate_faces`   | faces                     | `near_degenerate_faces`   |
/// | `small_components`        | face lists                | `small_components`        |
/// | `self_intersecting_pairs` | face pairs                | `self_intersecting_pairs` |
/// | `t_junction_vertices`     | vertices (+ their edges)  | `t_junctions`             |
///
/// Vertices and faces are numbered as the input lists them: soup points and
/// the usable polygons in order (polygons with an invalid index are skipped
/// in the numbering: face i is the i-th valid polygon; with `report.invalid_polygons`
/// equal to 0 it is polygon i); mesh vertices and faces in the order of
/// `vertices(pmesh)` and `faces(pmesh)`.
struct Defect_locations
{
  using Index = std::size_t;
  /// separates the open walks of a boundary loop that is not one closed walk
  static constexpr Index walk_end = std::numeric_limits<Index>::max();

  /// the inspection the lists come from (its status says whether they are filled)
  Inspection_report report;

  /// each loop's vertices in walk order; consecutive vertices, and the last
  /// and the first, are joined by a boundary edge of the loop. A soup loop
  /// (a connected component of the graph of boundary edges) that is not one
  /// closed walk (vertices with an odd number of boundary edges, next to
  /// non-manifold edges) lists open walks instead, each followed by `walk_end`.
  std::vector<std::vector<Index>> boundary_loops;
  /// the loops of `boundary_loops` with fewer than `max_hole_vertices` edges
  std::vector<Index> small_holes;
  std::vector<std::array<Index, 2>> non_manifold_edges;  ///< edges with more than two faces
  std::vector<Index> non_manifold_vertices;
  std::vector<Index> spiked_vertices;
  std::vector<Index> near_degenerate_faces;
  /// the faces of each component with fewer than `min_component_faces` faces
  std::vector<std::vector<Index>> small_components;
  /// filled when `report.self_intersections_counted`: the intersecting pairs
  /// of distinct faces, lower index first
  std::vector<std::array<Index, 2>> self_intersecting_pairs;
  /// per pair: 1 when the pair only touches at coincident vertices of its own
  /// (counted in `report.self_intersecting_pairs_touching`)
  std::vector<unsigned char> self_intersecting_pairs_touching;
  /// the boundary vertices that lie on another boundary edge, and one such
  /// edge of each (its two vertices)
  std::vector<Index> t_junction_vertices;
  std::vector<std::array<Index, 2>> t_junction_edges;

  /// the number of edges of loop `i`
  std::size_t loop_edges(std::size_t i) const
  {
    const std::vector<Index>& l = boundary_loops[i];
    std::size_t ends = 0;
    for (Index v : l) ends += v == walk_end;
    return ends == 0 ? l.size() : l.size() - 2 * ends;
  }
};

} // namespace mrepair

#endif // MREPAIR_DEFECT_LOCATIONS_H
