// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_STITCH_SOUP_H
#define MREPAIR_STITCH_SOUP_H

/// \file stitch_soup.h
/// Polygon soup to oriented manifold triangle mesh, after Gueziec, Taubin,
/// Lazarus and Horn, "Cutting and stitching: converting sets of polygons to
/// manifold surfaces".
///
/// \code
/// clean:   merge equal points (sort), then points within merge_epsilon (grid + union-find);
///          drop polygons with invalid indices or non-finite points; triangulate n-gons
///          (ear clipping in the best-fit plane); drop triangles with a repeated vertex,
///          collinear triangles (exact predicate) and duplicates (same vertex set); a
///          set given exactly twice whose edges each have four faces, a body on each
///          side (an internal wall between two solids), loses both copies
/// cut:     sort face sides by edge; an edge with more than two faces (fin) pairs its
///          faces by angle around the edge: a face pairs with the oppositely directed
///          face met next around the edge (the wedge between them is the inside of a
///          solid or the continuation of a sheet), then leftovers by flattest turn;
///          unpaired faces are cut off along the edge
/// orient:  per component, BFS spanning tree over faces, flipping as needed; a
///          disagreeing non-tree edge is cut (Moebius band: one cut); an open component
///          keeps the orientation most of its input faces had
/// split:   each fan of faces around a vertex but the first gets a copy of the vertex
/// stitch:  (snap_epsilon > 0) boundary edges whose two endpoints lie within epsilon of
///          another boundary edge's endpoints are glued, smallest distance first; the
///          smaller of two components with opposite orientations is flipped; merges that
///          would collapse a face are refused; cut/orient/split run again, so stitching
///          never leaves a complex edge or vertex
/// outward: (orient_outward) a closed component inside no other closed component gets
///          positive signed volume; a nested one keeps the orientation most of its input
///          faces had (outward: an overlap for a later union; inward: a cavity), unlike
///          PMP::orient_to_bound_a_volume, which inverts odd depths (depth by ray parity)
/// build:   halfedges written directly from the side-pairing table
/// \endcode
/// No face is lost except degenerate and duplicate ones, internal walls and
/// polygons whose indices or points are invalid; every removal is counted by reason.

#include <mrepair/internal/stitch_soup/driver.h>
#include <mrepair/internal/stitch_soup/soup_repairer.h>
#include <mrepair/parameters.h>
#include <mrepair/status.h>
#include <mrepair/stitch_soup_result.h>
#include <mrepair/visitors.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <cmath>

namespace mrepair {

namespace internal {

template <class NamedParameters>
bool read_soup_options(const NamedParameters& np, Soup_repairer::Options& o, Soup_repair_result& r)
{
  o.merge_epsilon = get_or(np, internal_np::merge_epsilon, 0.0);
  o.snap_epsilon = get_or(np, internal_np::snap_epsilon, 0.0);
  o.keep_two_sided = get_or(np, internal_np::keep_two_sided, false);
  o.orient_outward = get_or(np, internal_np::orient_outward, true);
  if (!(std::isfinite(o.merge_epsilon) && o.merge_epsilon >= 0)) {
    r.status = Status::invalid_parameter;
    r.message = "merge_epsilon must be finite and >= 0";
    return false;
  }
  if (!(std::isfinite(o.snap_epsilon) && o.snap_epsilon >= 0)) {
    r.status = Status::invalid_parameter;
    r.message = "snap_epsilon must be finite and >= 0";
    return false;
  }
  return true;
}

// The in-place entry points: options, then `stages(w, vis, r)` (false when
// `r` holds the final status), then the status and the triangles written back.
template <class PointRange, class PolygonRange, class NamedParameters, class Stages>
Soup_repair_result soup_in_place(PointRange& points, PolygonRange& polygons,
                                 const NamedParameters& np, const Stages& stages)
{
  Soup_repair_result r;
  Soup_repairer::Options o;
  if (!read_soup_options(np, o, r)) return r;
  Visitor_handle<NamedParameters> vis(np);
  Soup_repairer w(r, o);
  if (!stages(w, vis, r)) return r;
  finish_soup_status(r);
  write_back_soup(w, points, polygons);
  return r;
}

} // namespace internal

/// \ingroup mrepair_soup
/// cleans a polygon soup in place: merges equal points (and points within
/// `merge_epsilon`), drops polygons with out-of-range indices or non-finite
/// points, unreferenced points, triangulates polygons with more than three
/// vertices, and drops degenerate (repeated index, collinear) and duplicate
/// triangles, and both copies of an internal wall (see the file comment). The
/// result is a triangle soup; it may still be non-manifold.
/// \tparam PointRange `std::vector`-like of points with `x()`, `y()`, `z()`
///         and a constructor from three doubles
/// \tparam PolygonRange `std::vector`-like of ranges of integer indices
///         (`std::vector<std::size_t>`, `std::array<int, 3>`, ...)
/// \param np optional: `merge_epsilon` (double, 0: exact merging only, absolute
///        distance), `keep_two_sided` (bool, false: of two faces with the same
///        vertex set and opposite orientations only the first is kept),
///        `visitor` (`Default_visitor`)
/// \return `Soup_repair_result` (only the cleaning counters are set); the soup
///         is untouched when the status is `invalid_parameter` or `cancelled`
template <class PointRange, class PolygonRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Soup_repair_result clean_polygon_soup(PointRange& points, PolygonRange& polygons,
                                      const NamedParameters& np = CGAL::parameters::default_values())
{
  return internal::soup_in_place(points, polygons, np, [&](auto& w, auto& vis, auto& r) {
    return internal::load_and_clean_soup(w, points, polygons, vis, r);
  });
}

/// \ingroup mrepair_soup
/// turns a polygon soup into a consistently oriented manifold triangle soup, in
/// place (see the file comment for the steps). The output soup is a valid
/// polygon mesh in the sense of `PMP::is_polygon_soup_a_polygon_mesh`.
/// \param np as `polygon_soup_to_manifold_mesh`, without `vertex_point_map`
template <class PointRange, class PolygonRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Soup_repair_result repair_polygon_soup_to_manifold(PointRange& points, PolygonRange& polygons,
                                                   const NamedParameters& np = CGAL::parameters::default_values())
{
  return internal::soup_in_place(points, polygons, np, [&](auto& w, auto& vis, auto& r) {
    return internal::load_and_repair_soup(w, points, polygons, vis, r);
  });
}

/// \ingroup mrepair_soup
/// builds a consistently oriented, manifold triangle mesh from a polygon soup
/// that may hold anything: duplicate points, NaN points, out-of-range indices,
/// degenerate and duplicate polygons, n-gons, fins (edges with more than two
/// faces), bowties (vertices with several fans), mixed orientations, Moebius
/// bands, cracks. See the file comment for the steps.
///
/// \tparam PointRange random-access range of points with `x()`, `y()`, `z()`
/// \tparam PolygonRange range of ranges of integer indices into `points`
/// \tparam PolygonMesh model of `MutableFaceGraph`
/// \param points, polygons the soup (not modified)
/// \param out the output mesh; cleared first. Left untouched when the status is
///        `invalid_parameter` or `cancelled`.
/// \param np optional named parameters:
///   - `merge_epsilon` (double, default 0): points closer than this (absolute
///     distance) are merged before anything else; chains merge transitively.
///     0 merges only equal points.
///   - `snap_epsilon` (double, default 0): after cutting and orienting,
///     boundary edges whose endpoints lie within this distance of another
///     boundary edge's endpoints are stitched. 0 disables stitching.
///   - `keep_two_sided` (bool, default false): keep both of two faces with the
///     same vertices and opposite orientations (a two-sided sheet becomes a
///     closed zero-volume surface); otherwise the first is kept, or neither
///     when they are an internal wall (file comment). Keeping both also keeps
///     such a wall, so two glued solids stay two closed shells.
///   - `orient_outward` (bool, default true): closed components inside no
///     other closed component get outward normals; nested shells keep the
///     orientation of most of their input faces.
///   - `vertex_point_map` (default `get(CGAL::vertex_point, out)`): output points.
///   - `visitor` (`Default_visitor`): phases "clean", "cut", "orient", "split",
///     "stitch", "outward", "build"; `stop_requested()` is polled between them.
/// \return `Soup_repair_result`: status `ok`; `partial` when polygons were
///         dropped for invalid indices or non-finite points (see `message`);
///         `empty_input` when there are no polygons or no points (mesh
///         cleared); `invalid_parameter`; `cancelled`. Always
///         `faces_in == faces_out + faces_removed()`.
template <class PointRange, class PolygonRange, class PolygonMesh,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Soup_repair_result polygon_soup_to_manifold_mesh(const PointRange& points, const PolygonRange& polygons,
                                                 PolygonMesh& out,
                                                 const NamedParameters& np = CGAL::parameters::default_values())
{
  Soup_repair_result r;
  internal::Soup_repairer::Options o;
  if (!internal::read_soup_options(np, o, r)) return r;
  internal::Visitor_handle<NamedParameters> vis(np);
  internal::Soup_repairer w(r, o);
  if (!internal::load_and_repair_soup(w, points, polygons, vis, r)) return r;
  {
    internal::Phase_scope<internal::Visitor_handle<NamedParameters>> phase(vis, "build");
    auto vpm = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                                  get_property_map(CGAL::vertex_point, out));
    w.build(out, vpm);
  }
  internal::finish_soup_status(r);
  return r;
}

} // namespace mrepair

#endif // MREPAIR_STITCH_SOUP_H
