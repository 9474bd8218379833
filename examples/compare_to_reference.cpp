// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// How much of its input a repaired mesh still holds: every input vertex must
// lie on the output (within a tolerance) or inside it (a part absorbed by a
// union); the others were lost. `mrepair inspect OUTPUT --reference INPUT`
// reports the same figures.
// usage: example_compare_to_reference [OUTPUT REFERENCE [TOLERANCE]]
// Without files: the output is a sphere; the reference adds a small sphere
// inside it (absorbed: kept) and a small cube beside it (deleted: lost). Then
// the same comparison with many points, sequential and in parallel (TBB).
#include <mrepair/compare_to_reference.h>
#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/tags.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace MP = mrepair::parameters;

// a closed sphere of `radius` at `c`: an icosahedron split `levels` times, each
// new point projected on the sphere
static Mesh sphere(const Point& c, double radius, int levels)
{
  Mesh m;
  CGAL::make_icosahedron(m, c, radius);
  for (int l = 0; l < levels; ++l) {
    std::vector<Mesh::Face_index> fs(m.faces().begin(), m.faces().end());
    Mesh finer;
    std::vector<Point> pts;
    std::vector<std::vector<std::size_t>> tris;
    for (auto f : fs) {
      std::vector<Point> corner;
      for (auto v : vertices_around_face(m.halfedge(f), m)) corner.push_back(m.point(v));
      auto mid = [&](const Point& a, const Point& b) {
        const K::Vector_3 d = CGAL::midpoint(a, b) - c;
        return c + d * (radius / std::sqrt(d.squared_length()));
      };
      const Point ab = mid(corner[0], corner[1]), bc = mid(corner[1], corner[2]), ca = mid(corner[2], corner[0]);
      const std::size_t o = pts.size();
      for (const Point& p : {corner[0], corner[1], corner[2], ab, bc, ca}) pts.push_back(p);
      tris.push_back({o, o + 3, o + 5});
      tris.push_back({o + 3, o + 1, o + 4});
      tris.push_back({o + 5, o + 4, o + 2});
      tris.push_back({o + 3, o + 4, o + 5});
    }
    // the copies of shared points are merged by coordinates
    std::vector<Point> unique;
    std::vector<std::size_t> id(pts.size());
    std::map<Point, std::size_t> index;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      auto it = index.emplace(pts[i], unique.size());
      if (it.second) unique.push_back(pts[i]);
      id[i] = it.first->second;
    }
    for (auto& t : tris)
      for (auto& i : t) i = id[i];
    m.clear();
    std::vector<Mesh::Vertex_index> vs;
    for (const Point& p : unique) vs.push_back(m.add_vertex(p));
    for (const auto& t : tris) m.add_face(vs[t[0]], vs[t[1]], vs[t[2]]);
  }
  return m;
}

static void append_points(const Mesh& m, std::vector<Point>& out)
{
  for (auto v : m.vertices()) out.push_back(m.point(v));
}

static void print(const mrepair::Reference_comparison& r)
{
  mrepair::Report report;
  r.to_report(report);
  std::cout << report.to_text();
}

int main(int argc, char** argv)
{
  if (argc > 2) {
    std::vector<Point> out_points, ref_points;
    std::vector<std::vector<std::size_t>> out_polygons, ref_polygons;
    const mrepair::Io_result a = mrepair::read_polygon_soup(argv[1], out_points, out_polygons);
    const mrepair::Io_result b = mrepair::read_polygon_soup(argv[2], ref_points, ref_polygons);
    if (a.status != mrepair::Status::ok || b.status != mrepair::Status::ok) {
      std::cerr << a.message << " " << b.message << "\n";
      return 1;
    }
    const std::optional<double> tolerance =
        argc > 3 ? std::optional<double>(std::atof(argv[3])) : std::nullopt;
    const mrepair::Reference_comparison r = mrepair::compare_to_reference(
        ref_points, out_points, out_polygons, MP::reference_tolerance(tolerance));
    print(r);
    return mrepair::succeeded(r.status) ? 0 : 1;
  }

  // the output: a sphere of radius 1; the reference: that sphere, a small
  // sphere inside it and a small box beside it
  const Mesh output = sphere(Point(0, 0, 0), 1.0, 2);
  std::vector<Point> reference;
  append_points(output, reference);
  append_points(sphere(Point(0.3, 0, 0), 0.2, 1), reference);  // 42 points, inside
  Mesh box;
  CGAL::make_hexahedron(Point(2, 0, 0), Point(2.5, 0, 0), Point(2.5, 0.5, 0), Point(2, 0.5, 0),
                        Point(2, 0.5, 0.5), Point(2, 0, 0.5), Point(2.5, 0, 0.5), Point(2.5, 0.5, 0.5), box);
  append_points(box, reference);  // 8 points, lost
  const mrepair::Reference_comparison r = mrepair::compare_to_reference(reference, output);
  print(r);
  if (r.status != mrepair::Status::ok || r.vertices_lost != 8 || r.vertices_inside != 42) return 1;

  // timing: 163,842 reference points against a 20,480-face sphere
  const Mesh fine = sphere(Point(0, 0, 0), 1.0, 5);
  std::vector<Point> dense;
  append_points(sphere(Point(0, 0, 0), 1.0, 7), dense);
  for (Point& p : dense) p = Point(p.x() * 0.999, p.y() * 0.999, p.z() * 0.999);  // inside: both queries run
  auto time = [&](auto tag) {
    const auto t0 = std::chrono::steady_clock::now();
    const mrepair::Reference_comparison c = mrepair::compare_to_reference<decltype(tag)>(dense, fine);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << c.vertices << " points, " << c.vertices_inside << " inside, " << c.vertices_lost
              << " lost: " << s << " s\n";
    return c;
  };
  std::cout << "sequential: ";
  const mrepair::Reference_comparison seq = time(CGAL::Sequential_tag());
  std::cout << "parallel if available: ";
  const mrepair::Reference_comparison par = time(CGAL::Parallel_if_available_tag());
  return seq.lost == par.lost && seq.max_distance == par.max_distance ? 0 : 1;
}
