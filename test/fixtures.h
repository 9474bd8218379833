// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Shared test fixtures: the mesh-type matrix for typed tests and small meshes
// built in code (grid, cube, icosphere), as soups or in any MutableFaceGraph.
#ifndef MREPAIR_TEST_FIXTURES_H
#define MREPAIR_TEST_FIXTURES_H

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Polyhedron_items_with_id_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/graph_concepts.h>
#include <CGAL/boost/graph/helpers.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace mrepair_test {

using K = CGAL::Epick;
using Point = K::Point_3;
using Surface_mesh = CGAL::Surface_mesh<Point>;
using Polyhedron = CGAL::Polyhedron_3<K, CGAL::Polyhedron_items_with_id_3>;
using Polygon = std::vector<std::size_t>;

template <class Kernel_, class Mesh_>
struct Config
{
  using Kernel = Kernel_;
  using Mesh = Mesh_;
};

/// the matrix every algorithm is tested on.
using Mesh_configs = ::testing::Types<Config<K, Surface_mesh>, Config<K, Polyhedron>>;

/// the exact-kernel row (issue 16): exact predicates and constructions.
using EK = CGAL::Epeck;
using Exact_surface_mesh = CGAL::Surface_mesh<EK::Point_3>;
/// Applied to one suite only (test_exact_kernel.cpp: every algorithm once,
/// compared with the Epick run), not added to `Mesh_configs`: each mesh type
/// adds the compile time of a whole suite, and the library computes in
/// doubles whatever the kernel, so one test per algorithm shows the support.
using Exact_configs = ::testing::Types<Config<EK, Exact_surface_mesh>>;

/// a soup: points and polygons (indices into points).
struct Soup
{
  std::vector<Point> points;
  std::vector<Polygon> polygons;
};

// `s` moved by (dx, dy, dz).
inline Soup translated(Soup s, double dx, double dy, double dz)
{
  for (Point& p : s.points) p = Point(p.x() + dx, p.y() + dy, p.z() + dz);
  return s;
}

// The polygons of `a` and of `b` in one soup (separate components).
inline Soup merged(const Soup& a, const Soup& b)
{
  Soup s = a;
  const std::size_t off = a.points.size();
  s.points.insert(s.points.end(), b.points.begin(), b.points.end());
  for (Polygon p : b.polygons) {
    for (std::size_t& i : p) i += off;
    s.polygons.push_back(p);
  }
  return s;
}

/// `nx` x `ny` squares of side `step` in the plane z = 0, each split in two
/// triangles (quads when `quads`), counter-clockwise seen from +z.
inline Soup grid(std::size_t nx, std::size_t ny, double step = 1.0, bool quads = false)
{
  Soup s;
  for (std::size_t j = 0; j <= ny; ++j)
    for (std::size_t i = 0; i <= nx; ++i) s.points.emplace_back(i * step, j * step, 0.);
  auto id = [nx](std::size_t i, std::size_t j) { return j * (nx + 1) + i; };
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      std::size_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (quads) {
        s.polygons.push_back({a, b, c, d});
      } else {
        s.polygons.push_back({a, b, c});
        s.polygons.push_back({a, c, d});
      }
    }
  return s;
}

/// axis-aligned cube [0,size]^3 as 12 outward triangles (6 quads when `quads`).
inline Soup cube(double size = 1.0, bool quads = false)
{
  Soup s;
  for (int k = 0; k < 8; ++k)
    s.points.emplace_back((k & 1) * size, ((k >> 1) & 1) * size, ((k >> 2) & 1) * size);
  const std::size_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                               {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (auto& f : q) {
    if (quads)
      s.polygons.push_back({f[0], f[1], f[2], f[3]});
    else {
      s.polygons.push_back({f[0], f[1], f[2]});
      s.polygons.push_back({f[0], f[2], f[3]});
    }
  }
  return s;
}

/// unit icosahedron subdivided `levels` times and projected on the sphere of
/// `radius`: closed, genus 0, outward, 20 * 4^levels triangles.
inline Soup icosphere(int levels = 2, double radius = 1.0)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                          {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                          {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<std::size_t, 3>> f = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  auto normalize = [](std::array<double, 3> a) {
    double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return std::array<double, 3>{a[0] / n, a[1] / n, a[2] / n};
  };
  for (auto& q : p) q = normalize(q);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> mid;
    auto midpoint = [&](std::size_t a, std::size_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      p.push_back(normalize({(p[a][0] + p[b][0]) / 2, (p[a][1] + p[b][1]) / 2,
                             (p[a][2] + p[b][2]) / 2}));
      mid[key] = p.size() - 1;
      return p.size() - 1;
    };
    std::vector<std::array<std::size_t, 3>> g;
    for (auto& tr : f) {
      std::size_t a = midpoint(tr[0], tr[1]), b = midpoint(tr[1], tr[2]),
                  c = midpoint(tr[2], tr[0]);
      g.push_back({tr[0], a, c});
      g.push_back({tr[1], b, a});
      g.push_back({tr[2], c, b});
      g.push_back({a, b, c});
    }
    f.swap(g);
  }
  Soup s;
  for (auto& q : p) s.points.emplace_back(radius * q[0], radius * q[1], radius * q[2]);
  for (auto& tr : f) s.polygons.push_back({tr[0], tr[1], tr[2]});
  return s;
}

/// builds `mesh` from a soup that is already a valid polygon mesh.
template <class Mesh>
Mesh to_mesh(const Soup& s)
{
  Mesh m;
  std::vector<typename boost::property_traits<
      typename boost::property_map<Mesh, CGAL::vertex_point_t>::type>::value_type>
      pts;
  for (const Point& p : s.points) pts.emplace_back(p.x(), p.y(), p.z());
  EXPECT_TRUE(CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(s.polygons));
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, s.polygons, m);
  return m;
}

/// CGAL::is_valid_polygon_mesh as CGAL 5.5 has it on both releases: 6.0's
/// accepts an isolated vertex, 5.5's rejects it, and the tests hold every
/// output to the stricter rule.
template <class Mesh>
bool valid_polygon_mesh(const Mesh& m)
{
  if (!CGAL::is_valid_polygon_mesh(m)) return false;
  for (auto v : vertices(m))
    if (halfedge(v, m) == boost::graph_traits<Mesh>::null_halfedge()) return false;
  return true;
}

/// number of live faces (num_faces on Surface_mesh counts removed ones).
template <class Mesh>
std::size_t face_count(const Mesh& m)
{
  return static_cast<std::size_t>(faces(m).size());
}

} // namespace mrepair_test

#endif // MREPAIR_TEST_FIXTURES_H
