// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Mesh types and invariant checks shared by the fuzz targets and the
// regression test. A check returns an empty string when all is well, else
// what was violated (the fuzz targets abort on it, the test fails on it).
#ifndef MREPAIR_FUZZ_CHECK_H
#define MREPAIR_FUZZ_CHECK_H

#include "fuzz_decode.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Polyhedron_items_with_id_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <string>
#include <vector>

namespace mrepair_fuzz {

using K = CGAL::Epick;
using Point = K::Point_3;
using Surface_mesh = CGAL::Surface_mesh<Point>;
using Polyhedron = CGAL::Polyhedron_3<K, CGAL::Polyhedron_items_with_id_3>;

inline bool finite(const Point& p)
{
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

/// valid halfedge structure without an isolated vertex (and triangles only,
/// when asked), finite points.
template <class Mesh>
std::string check_mesh(const Mesh& m, const std::string& what, bool triangles, bool need_finite = true)
{
  if (!CGAL::is_valid_polygon_mesh(m)) return what + ": output fails is_valid_polygon_mesh";
  // CGAL 5.5's validity check rejects an isolated vertex, 6.0's accepts it:
  // the targets reject it on both
  for (auto v : vertices(m))
    if (halfedge(v, m) == boost::graph_traits<Mesh>::null_halfedge())
      return what + ": output has an isolated vertex";
  if (triangles && !faces(m).empty() && !CGAL::is_triangle_mesh(m))
    return what + ": output is not a triangle mesh";
  if (need_finite)
    for (auto v : vertices(m))
      if (!finite(get(CGAL::vertex_point, m, v))) return what + ": output has a non-finite point";
  return {};
}

/// the points of `m` in vertex order, and its face count: to tell that a call
/// left the mesh untouched.
template <class Mesh>
struct Snapshot
{
  std::vector<Point> points;
  std::size_t face_count = 0;
  explicit Snapshot(const Mesh& m)
  {
    for (auto v : vertices(m)) points.push_back(get(CGAL::vertex_point, m, v));
    face_count = static_cast<std::size_t>(faces(m).size());
  }
  bool same(const Mesh& m) const
  {
    Snapshot now(m);
    if (now.face_count != face_count || now.points.size() != points.size()) return false;
    for (std::size_t i = 0; i < points.size(); ++i)
      for (int d = 0; d < 3; ++d) {
        const double a = points[i][d], b = now.points[i][d];
        if (!(a == b || (std::isnan(a) && std::isnan(b)))) return false;
      }
    return true;
  }
};

} // namespace mrepair_fuzz

#endif // MREPAIR_FUZZ_CHECK_H
