// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Shells (connected components) of a triangle mesh for the intersection
// repair: which faces, closed or not, signed volume, box; a component copied
// out into a mesh of its own (the operand of a Boolean) and a mesh copied
// back in.
#ifndef MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_SHELLS_H
#define MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_SHELLS_H

#include <mrepair/internal/io/build_mesh.h>
#include <mrepair/internal/utility.h>

#include <CGAL/Bbox_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Kernel/global_functions.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace mrepair {
namespace internal {
namespace solid {

template <typename PolygonMesh>
struct Shell
{
  using face_descriptor = typename boost::graph_traits<PolygonMesh>::face_descriptor;
  std::vector<face_descriptor> faces;
  bool closed = true;   ///< no border edge
  double volume = 0.;   ///< signed: positive when the normals point outwards
  CGAL::Bbox_3 box;
};

// Labels the faces of `pm` by component (`component`, a face property map
// written for every face) and returns the shells, in the order their first
// face is met.
template <typename PolygonMesh, typename VertexPointMap, typename ComponentMap>
std::vector<Shell<PolygonMesh>> label_shells(const PolygonMesh& pm, VertexPointMap vpm, ComponentMap component)
{
  using GT = boost::graph_traits<PolygonMesh>;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  constexpr std::size_t unset = std::size_t(-1);
  std::vector<Shell<PolygonMesh>> shells;
  for (face_descriptor f : faces(pm)) put(component, f, unset);
  std::vector<face_descriptor> stack;
  for (face_descriptor f0 : faces(pm)) {
    if (get(component, f0) != unset) continue;
    const std::size_t c = shells.size();
    shells.emplace_back();
    Shell<PolygonMesh>& s = shells.back();
    put(component, f0, c);
    stack.assign(1, f0);
    bool origin_set = false;
    Vec3 origin{{0, 0, 0}};
    double v6 = 0.;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    while (!stack.empty()) {
      const face_descriptor f = stack.back();
      stack.pop_back();
      s.faces.push_back(f);
      std::array<Vec3, 3> p;
      int k = 0;
      for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, pm), pm)) {
        const Vec3 q = point(vpm, target(h, pm));
        for (int d = 0; d < 3; ++d) {
          lo[d] = std::min(lo[d], q[d]);
          hi[d] = std::max(hi[d], q[d]);
        }
        if (k < 3) p[k] = q;
        ++k;
        const halfedge_descriptor o = opposite(h, pm);
        if (is_border(o, pm)) {
          s.closed = false;
          continue;
        }
        const face_descriptor g = face(o, pm);
        if (get(component, g) == unset) {
          put(component, g, c);
          stack.push_back(g);
        }
      }
      if (k != 3) continue;
      if (!origin_set) {
        origin = p[0];
        origin_set = true;
      }
      // the volume about a point of the shell: small terms, little cancellation
      v6 += dot(sub(p[0], origin), cross(sub(p[1], origin), sub(p[2], origin)));
    }
    s.volume = v6 / 6.;
    s.box = CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  }
  return shells;
}

// The closed shells of `pm` that enclose no volume: |signed volume| at most
// 1e-9 x the cube of their box's diagonal (a flat one, or a pillow of two
// coincident copies of a surface stitched along their borders).
template <typename PolygonMesh, typename VertexPointMap>
std::size_t count_empty_closed_shells(const PolygonMesh& pm, VertexPointMap vpm)
{
  auto component = get(CGAL::dynamic_face_property_t<std::size_t>(), pm);
  std::size_t n = 0;
  for (const Shell<PolygonMesh>& s : label_shells(pm, vpm, component)) {
    if (!s.closed) continue;
    const CGAL::Bbox_3& b = s.box;
    const double d = std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                               CGAL::square(b.zmax() - b.zmin()));
    n += std::abs(s.volume) <= 1e-9 * d * d * d;
  }
  return n;
}

// Whether every vertex of `shell` lies in one plane (exact predicates on
// the coordinates as doubles). A flat closed shell encloses no volume: every
// point off it has winding number 0, so the winding-number solidification
// can only remove it, after an arrangement of coplanar triangles that costs
// far more than its size suggests (nested rational constructions).
template <typename PolygonMesh, typename VertexPointMap>
bool shell_is_flat(const PolygonMesh& pm, VertexPointMap vpm, const Shell<PolygonMesh>& shell)
{
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using P = K::Point_3;
  auto to_point = [&](typename boost::graph_traits<PolygonMesh>::vertex_descriptor v) {
    const Vec3 q = point(vpm, v);
    return P(q[0], q[1], q[2]);
  };
  // a plane through three corners that are not collinear, then every corner
  std::vector<P> plane;
  for (auto f : shell.faces) {
    for (auto v : CGAL::vertices_around_face(halfedge(f, pm), pm)) {
      const P q = to_point(v);
      if (plane.size() == 0 || (plane.size() == 1 && q != plane[0]) ||
          (plane.size() == 2 && !CGAL::collinear(plane[0], plane[1], q))) {
        plane.push_back(q);
        continue;
      }
      if (plane.size() == 3 && CGAL::orientation(plane[0], plane[1], plane[2], q) != CGAL::COPLANAR) return false;
    }
  }
  return true;
}

// Builds the empty mesh `out` from the triangles `triangles` over `points`
// (a soup that is a polygon mesh), in their order: with the reader's
// builder, a third of the time of polygon_soup_to_polygon_mesh.
template <typename PolygonMesh, typename Point>
void build_from_triangles(const std::vector<Point>& points, const std::vector<std::array<std::size_t, 3>>& triangles,
                          PolygonMesh& out)
{
  using vertex_descriptor = typename boost::graph_traits<PolygonMesh>::vertex_descriptor;
  std::vector<std::int64_t> corners;
  corners.reserve(3 * triangles.size());
  std::vector<std::size_t> starts(1, 0);
  starts.reserve(triangles.size() + 1);
  for (const std::array<std::size_t, 3>& t : triangles) {
    corners.insert(corners.end(), t.begin(), t.end());
    starts.push_back(corners.size());
  }
  io::with_soup_topology(points.size(), corners.size(), [&](auto& topology) {
    std::string why;
    if (!topology.compute(points.size(), corners.data(), starts.data(), triangles.size(), why)) {
      CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, triangles, out);
      return;
    }
    auto out_points = get(CGAL::vertex_point, out);
    io::build_mesh(topology, points.size(), corners.data(), starts.data(), triangles.size(), out,
                   [&](vertex_descriptor v, std::size_t i) { put(out_points, v, points[i]); });
  });
}

// Copies the faces `fs` of `pm` (one or more whole components, triangles)
// into the empty mesh `out`, through a soup so that the face order does not
// matter.
template <typename PolygonMesh, typename VertexPointMap, typename FaceRange>
void copy_faces_out(const PolygonMesh& pm, VertexPointMap vpm, const FaceRange& fs, PolygonMesh& out)
{
  using GT = boost::graph_traits<PolygonMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using Point = typename boost::property_traits<VertexPointMap>::value_type;
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::map<vertex_descriptor, std::size_t> index;
  for (const auto& f : fs) {
    std::array<std::size_t, 3> t;
    int k = 0;
    for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm), pm)) {
      auto it = index.find(v);
      if (it == index.end()) {
        it = index.emplace(v, points.size()).first;
        points.push_back(get(vpm, v));
      }
      if (k < 3) t[k] = it->second;
      ++k;
    }
    if (k == 3) triangles.push_back(t);
  }
  build_from_triangles(points, triangles, out);
}

// Copies the triangle mesh `in` (its own point map) into the empty mesh
// `out` in an order that depends on the geometry of `in` alone, not on the
// order of its elements: the faces sorted by their corners (each face
// starting at its least corner in xyz order, its orientation kept), the
// vertices numbered as the sorted faces first use them. Two faces with the
// same three corner points keep their order; no valid union has them.
//
// CGAL 5.5's corefinement numbers the vertices and faces it creates in an
// order that depends on heap addresses: its box intersection breaks ties
// between boxes with equal coordinates by the boxes' addresses
// (`ID_FROM_BOX_ADDRESS` in Corefinement/intersection_impl.h), two vectors
// allocated apart, and the intersections it finds go through unordered
// containers whose iteration follows the order they were found in.
template <typename PolygonMesh>
void copy_in_canonical_order(const PolygonMesh& in, PolygonMesh& out)
{
  using GT = boost::graph_traits<PolygonMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Point_map = typename boost::property_map<PolygonMesh, CGAL::vertex_point_t>::const_type;
  using Point = typename boost::property_traits<Point_map>::value_type;
  using Triangle = std::array<std::size_t, 3>;
  const Point_map vpm = get(CGAL::vertex_point, in);
  auto index = get(CGAL::dynamic_vertex_property_t<std::size_t>(), in);
  std::vector<Point> points;
  points.reserve(vertices(in).size());
  for (vertex_descriptor v : vertices(in)) {
    put(index, v, points.size());
    points.push_back(get(vpm, v));
  }
  auto less = [&](std::size_t a, std::size_t b) { return CGAL::compare_xyz(points[a], points[b]) == CGAL::SMALLER; };
  std::vector<Triangle> triangles;
  triangles.reserve(faces(in).size());
  for (face_descriptor f : faces(in)) {
    Triangle t;
    int k = 0;
    for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, in), in)) {
      if (k < 3) t[k] = get(index, v);
      ++k;
    }
    if (k != 3) continue;
    const int first = less(t[1], t[0]) ? (less(t[2], t[1]) ? 2 : 1) : (less(t[2], t[0]) ? 2 : 0);
    std::rotate(t.begin(), t.begin() + first, t.end());
    triangles.push_back(t);
  }
  std::stable_sort(triangles.begin(), triangles.end(), [&](const Triangle& s, const Triangle& t) {
    for (int i = 0; i < 3; ++i) {
      const CGAL::Comparison_result c = CGAL::compare_xyz(points[s[i]], points[t[i]]);
      if (c != CGAL::EQUAL) return c == CGAL::SMALLER;
    }
    return false;
  });
  constexpr std::size_t unset = std::size_t(-1);
  std::vector<std::size_t> renumbered(points.size(), unset);
  std::vector<Point> sorted_points;
  sorted_points.reserve(points.size());
  for (Triangle& t : triangles)
    for (std::size_t& c : t) {
      if (renumbered[c] == unset) {
        renumbered[c] = sorted_points.size();
        sorted_points.push_back(points[c]);
      }
      c = renumbered[c];
    }
  build_from_triangles(sorted_points, triangles, out);
}

} // namespace solid
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_SHELLS_H
