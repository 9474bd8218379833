// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_LOCATE_DEFECTS_H
#define MREPAIR_LOCATE_DEFECTS_H

#include <mrepair/defect_locations.h>
#include <mrepair/inspect.h>

#include <CGAL/Named_function_parameters.h>

#include <type_traits>

/// \file locate_defects.h
/// Where the defects that `inspect()` counts are: the same inspection, run
/// with a location sink, so that each list holds exactly as many instances
/// as the report's count (`Defect_locations`, doc/studio.md).

namespace mrepair {

namespace internal {
template <typename T>
struct Is_named_parameters : std::false_type
{};
template <typename T, typename Tag, typename Base>
struct Is_named_parameters<CGAL::Named_function_parameters<T, Tag, Base>> : std::true_type
{};
} // namespace internal

/// \ingroup mrepair_inspect
/// lists the defects of a polygon soup: boundary loops (vertex walks), small
/// holes, non-manifold edges and vertices, spiked vertices, near-degenerate
/// faces, small components (face lists), self-intersecting face pairs and
/// T-junctions (the vertex and the boundary edge it lies on), with the
/// `Inspection_report` of `inspect_polygon_soup(points, polygons, np)` that
/// counted them (member `report`). Same definitions and thresholds.
///
/// \tparam PointRange random-access range of points with `x()`, `y()`, `z()`
/// \tparam PolygonRange range of ranges of integer indices
/// \param np the named parameters of `inspect_polygon_soup()`
///   (`count_self_intersections(false)` leaves the pairs out, as in the report)
/// \return the lists, empty unless `report.status` is `ok`, `non_finite_input`
///   or `invalid_index` (invalid polygons are skipped, see `Defect_locations`)
template <typename PointRange, typename PolygonRange,
          typename NamedParameters = CGAL::parameters::Default_named_parameters,
          typename = std::enable_if_t<!internal::Is_named_parameters<PolygonRange>::value>>
Defect_locations locate_defects(const PointRange& points, const PolygonRange& polygons,
                                const NamedParameters& np = CGAL::parameters::default_values())
{
  Defect_locations d;
  d.report = internal::inspect_soup(points, polygons, np, &d);
  return d;
}

/// \ingroup mrepair_inspect
/// the same on a polygon mesh, with the report of `inspect(pmesh, np)`:
/// boundary loops are the border halfedge cycles (the source vertices of
/// their halfedges in `next()` order); vertices and faces are numbered in the order
/// of `vertices(pmesh)` and `faces(pmesh)`.
///
/// \tparam PolygonMesh model of `FaceListGraph` (`Surface_mesh`, `Polyhedron_3`, ...)
/// \param np the named parameters of `inspect()`
/// \pre `CGAL::is_valid_polygon_mesh(pmesh)`
template <typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters,
          typename = std::enable_if_t<internal::Is_named_parameters<NamedParameters>::value>>
Defect_locations locate_defects(const PolygonMesh& pmesh,
                                const NamedParameters& np = CGAL::parameters::default_values())
{
  Defect_locations d;
  d.report = internal::inspect_mesh(pmesh, np, &d);
  return d;
}

} // namespace mrepair

#endif // MREPAIR_LOCATE_DEFECTS_H
