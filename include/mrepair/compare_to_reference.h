// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_COMPARE_TO_REFERENCE_H
#define MREPAIR_COMPARE_TO_REFERENCE_H

#include <mrepair/internal/compare_to_reference/worker.h>
#include <mrepair/internal/io/convert.h>
#include <mrepair/parameters.h>
#include <mrepair/reference_comparison.h>
#include <mrepair/status.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/tags.h>

#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

/// \file compare_to_reference.h
/// How much of a reference (the input of a repair) an output still holds:
/// the distance of every reference vertex to the output surface, and whether
/// a vertex farther than a tolerance lies inside the output. A repair may
/// move a vertex by its documented bound and a union may swallow a part
/// inside another, but a vertex that ends neither on the output nor inside it
/// was lost: part of the model was deleted (issue 50, "no model that loses input").

namespace mrepair {

/// \ingroup mrepair_core
/// compares the points `reference` (the vertices of the input of a repair)
/// with the triangle mesh `output`. A reference vertex is lost when it is
/// neither within `reference_tolerance` of the output surface nor inside the
/// closed components of `output`: inside where their winding number is not
/// zero (a ray cast decided by exact predicates), so a point inside two
/// overlapping shells is inside and one in a cavity (an inward shell within
/// an outward one) is not; a point on the surface counts as inside. Open
/// components enclose nothing: against them only the distance counts.
///
/// Distances use an AABB tree of the output's faces, the rays one of its
/// closed faces; both the distance and the inside queries run over the points in parallel with TBB when
/// `ConcurrencyTag` is `CGAL::Parallel_if_available_tag` (the default) or
/// `CGAL::Parallel_tag`.
/// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`
/// \tparam PointRange range of points convertible to the output's point type
/// \tparam TriangleMesh model of `FaceListGraph`, triangles only
/// \param np optional: `vertex_point_map` and `geom_traits` of `output`,
///   `reference_tolerance` (absolute distance; default 1e-6 x the bounding-box
///   diagonal of the finite reference points; a `std::optional<double>` that
///   is empty means the default)
/// \return `Reference_comparison`. Non-finite reference points are skipped
///   (`vertices_skipped`). An output without faces loses every vertex (status
///   `ok`, `max_distance` infinite). `empty_input`: no finite reference point;
///   `invalid_mesh`: `output` is not a triangle mesh; `non_finite_input`: an
///   output point is not finite; `invalid_parameter`: a negative or
///   non-finite tolerance. Nothing is compared on those statuses.
template <typename ConcurrencyTag = CGAL::Parallel_if_available_tag, typename PointRange,
          typename TriangleMesh, typename NamedParameters = CGAL::parameters::Default_named_parameters>
Reference_comparison compare_to_reference(const PointRange& reference, const TriangleMesh& output,
                                          const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using GT = typename CGAL::GetGeomTraits<TriangleMesh, NamedParameters>::type;
  using VPM = typename CGAL::GetVertexPointMap<TriangleMesh, NamedParameters>::const_type;
  using Point = typename GT::Point_3;
  const GT gt = choose_parameter<GT>(get_parameter(np, CGAL::internal_np::geom_traits));
  const VPM vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                   get_const_property_map(CGAL::vertex_point, output));
  Reference_comparison r;
  auto finite_point = [](const Point& p) {
    return std::isfinite(CGAL::to_double(p.x())) && std::isfinite(CGAL::to_double(p.y())) &&
           std::isfinite(CGAL::to_double(p.z()));
  };
  const bool tolerance_given = internal::is_given(np, internal_np::reference_tolerance);
  const double given_tolerance = internal::get_or<double>(np, internal_np::reference_tolerance, 0.);
  if (tolerance_given && !(given_tolerance >= 0. && std::isfinite(given_tolerance))) {
    r.status = Status::invalid_parameter;
    r.message = "reference_tolerance must be a finite distance >= 0";
    return r;
  }
  std::vector<Point> points;
  for (const auto& p : reference) points.push_back(Point(p));
  std::vector<char> finite(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    finite[i] = finite_point(points[i]);
    if (finite[i])
      ++r.vertices;
    else
      ++r.vertices_skipped;
  }
  if (r.vertices == 0) {
    r.status = Status::empty_input;
    r.message = "no finite reference point";
    return r;
  }
  if (!CGAL::is_triangle_mesh(output)) {
    r.status = Status::invalid_mesh;
    r.message = "the output is not a triangle mesh";
    return r;
  }
  for (auto v : vertices(output))
    if (!finite_point(get(vpm, v))) {
      r.status = Status::non_finite_input;
      r.message = "the output has a non-finite point";
      return r;
    }
  r.diagonal = internal::diagonal_of(points, finite);
  r.tolerance = tolerance_given ? given_tolerance : 1e-6 * r.diagonal;
  if (faces(output).empty()) {
    r.message = "the output has no face";
    r.max_distance = r.max_distance_relative = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < points.size(); ++i)
      if (finite[i]) r.lost.push_back(i);
    r.vertices_lost = r.lost.size();
    return r;
  }
  internal::compare_points_to_mesh<ConcurrencyTag>(points, finite, output, vpm, gt, r.tolerance, r);
  return r;
}

/// \ingroup mrepair_core
/// `compare_to_reference()` against an output given as a polygon soup (as a
/// file reads): polygons are cut into fans, and a soup that is not a
/// manifold, consistently oriented mesh is first made one by
/// `CGAL::Polygon_mesh_processing::orient_polygon_soup` (which duplicates
/// the points where that is impossible, so such a component may count as open).
/// Polygons of fewer than 3 corners are ignored.
/// \param np optional: `reference_tolerance`
/// \return as the mesh overload; `invalid_index` when a polygon refers to a
///   point that does not exist.
template <typename ConcurrencyTag = CGAL::Parallel_if_available_tag, typename PointRange,
          typename Point, typename PolygonRange,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Reference_comparison compare_to_reference(const PointRange& reference,
                                          const std::vector<Point>& output_points,
                                          const PolygonRange& output_polygons,
                                          const NamedParameters& np = CGAL::parameters::default_values())
{
  std::vector<Point> points(output_points);
  std::vector<std::vector<std::size_t>> triangles;
  for (const auto& polygon : output_polygons) {
    const std::size_t n = std::size(polygon);
    for (const auto i : polygon) {
      const long long index = static_cast<long long>(i);  // a huge unsigned one turns negative
      if (index < 0 || static_cast<std::size_t>(index) >= points.size()) {
        Reference_comparison r;
        r.status = Status::invalid_index;
        r.message = "a polygon of the output refers to a point that does not exist";
        return r;
      }
    }
    auto corner = [&](std::size_t k) { return std::size_t(*(std::begin(polygon) + k)); };
    // a fan; a triangle with a repeated corner covers nothing its neighbours do not
    for (std::size_t k = 1; k + 1 < n; ++k)
      if (corner(0) != corner(k) && corner(k) != corner(k + 1) && corner(0) != corner(k + 1))
        triangles.push_back({corner(0), corner(k), corner(k + 1)});
  }
  std::string why;
  if (!internal::io::is_soup_a_mesh(triangles, points.size(), why))
    CGAL::Polygon_mesh_processing::orient_polygon_soup(points, triangles);
  CGAL::Surface_mesh<Point> mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, triangles, mesh);
  return compare_to_reference<ConcurrencyTag>(reference, mesh, np);
}

}  // namespace mrepair

#endif  // MREPAIR_COMPARE_TO_REFERENCE_H
