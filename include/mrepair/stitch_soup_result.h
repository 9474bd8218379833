// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_STITCH_SOUP_RESULT_H
#define MREPAIR_STITCH_SOUP_RESULT_H

/// \file stitch_soup_result.h
/// What the polygon-soup repairs of `stitch_soup.h` report.

#include <mrepair/report.h>
#include <mrepair/status.h>

#include <cstddef>
#include <string>

namespace mrepair {

/// \ingroup mrepair_soup
/// what `polygon_soup_to_manifold_mesh` (and the soup stages) did.
///
/// Face accounting: polygons are triangulated first, so faces are counted in
/// triangles. A polygon with `m` distinct consecutive vertices counts as `m - 2`
/// faces; a polygon dropped whole (invalid index, non-finite point, fewer than
/// three distinct vertices) counts as one. Always
/// `faces_in == faces_out + faces_removed()`.
struct Soup_repair_result
{
  Status status = Status::ok;
  std::string message;  ///< why the status is not `ok`

  std::size_t points_in = 0;     ///< input points
  std::size_t polygons_in = 0;   ///< input polygons
  std::size_t faces_in = 0;      ///< input faces in triangles (see above)
  std::size_t faces_out = 0;     ///< output triangles
  std::size_t vertices_out = 0;  ///< output vertices

  // faces removed, by reason
  std::size_t removed_invalid_index = 0;     ///< polygon uses a negative or out-of-range index
  std::size_t removed_non_finite = 0;        ///< polygon uses a NaN/infinite point
  std::size_t removed_degenerate_index = 0;  ///< fewer than three distinct vertices (after merging)
  std::size_t removed_collinear = 0;         ///< three distinct but collinear points (exact test)
  std::size_t removed_duplicate = 0;         ///< same vertex set as a kept face
  std::size_t removed_internal_walls = 0;    ///< both copies of a doubled face between two bodies

  std::size_t polygons_triangulated = 0;  ///< polygons with more than three vertices
  std::size_t non_finite_points = 0;      ///< points with a NaN/infinite coordinate
  std::size_t points_merged = 0;          ///< finite points merged into another (exactly or within merge_epsilon)
  std::size_t points_unreferenced = 0;    ///< distinct finite points used by no kept face

  std::size_t complex_edges = 0;            ///< edges with more than two faces (after cleaning, before cutting)
  std::size_t complex_vertices = 0;         ///< vertices whose faces form more than one fan
  std::size_t vertices_duplicated = 0;      ///< vertex copies made, one per extra fan (every cutting pass; stitching may glue some again)
  std::size_t edges_cut_nonorientable = 0;  ///< edges cut to orient non-orientable components
  std::size_t edges_stitched = 0;           ///< boundary edge pairs stitched within snap_epsilon
  std::size_t components = 0;               ///< connected components of the output
  std::size_t closed_components = 0;        ///< components without boundary
  std::size_t components_flipped = 0;       ///< whole components reversed (outward rule, stitching)
  std::size_t faces_reoriented = 0;         ///< output faces whose orientation differs from the input
  std::size_t boundary_edges = 0;           ///< boundary edges of the output

  /// sum of the removal counters.
  std::size_t faces_removed() const
  {
    return removed_invalid_index + removed_non_finite + removed_degenerate_index +
           removed_collinear + removed_duplicate + removed_internal_walls;
  }

  void to_report(Report& r) const
  {
    r.add("status", to_string(status));
    if (!message.empty()) r.add("message", message);
    r.add("points_in", points_in);
    r.add("polygons_in", polygons_in);
    r.add("faces_in", faces_in);
    r.add("faces_out", faces_out);
    r.add("vertices_out", vertices_out);
    Report& rem = r.section("faces_removed");
    rem.add("invalid_index", removed_invalid_index);
    rem.add("non_finite", removed_non_finite);
    rem.add("degenerate_index", removed_degenerate_index);
    rem.add("collinear", removed_collinear);
    rem.add("duplicate", removed_duplicate);
    rem.add("internal_wall", removed_internal_walls);
    rem.add("total", faces_removed());
    Report& pts = r.section("points");
    pts.add("non_finite", non_finite_points);
    pts.add("merged", points_merged);
    pts.add("unreferenced", points_unreferenced);
    Report& top = r.section("topology");
    top.add("polygons_triangulated", polygons_triangulated);
    top.add("complex_edges", complex_edges);
    top.add("complex_vertices", complex_vertices);
    top.add("vertices_duplicated", vertices_duplicated);
    top.add("edges_cut_nonorientable", edges_cut_nonorientable);
    top.add("edges_stitched", edges_stitched);
    top.add("components", components);
    top.add("closed_components", closed_components);
    top.add("components_flipped", components_flipped);
    top.add("faces_reoriented", faces_reoriented);
    top.add("boundary_edges", boundary_edges);
  }
};

} // namespace mrepair

#endif // MREPAIR_STITCH_SOUP_RESULT_H
