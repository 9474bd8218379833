// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Turns a polygon soup into an oriented manifold triangle mesh, once as a
// Surface_mesh and once as a Polyhedron_3, and prints what was done.
// usage: example_stitch_soup [INPUT [EPSILON]]
// Without INPUT: a cube whose faces are separate quads with cracked corners,
// one of them reversed, plus a fin and a duplicated face.
#include <mrepair/io.h>
#include <mrepair/stitch_soup.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Polyhedron_items_with_id_3.h>
#include <CGAL/Surface_mesh.h>

#include <cstdlib>
#include <iostream>
#include <vector>

using K = CGAL::Epick;
using Point = K::Point_3;
using Polygon = std::vector<std::size_t>;
namespace MP = mrepair::parameters;

int main(int argc, char** argv)
{
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  double eps = 1e-3;
  if (argc > 1) {
    mrepair::Io_result io = mrepair::read_polygon_soup(argv[1], points, polygons);
    if (io.status != mrepair::Status::ok && io.status != mrepair::Status::non_finite_input &&
        io.status != mrepair::Status::invalid_index) {
      std::cerr << "cannot read " << argv[1] << ": " << io.message << "\n";
      return 1;
    }
    eps = argc > 2 ? std::atof(argv[2]) : 0.0;
  } else {
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int q = 0; q < 6; ++q) {
      Polygon p;
      for (int k : quads[q]) {  // every face has its own, slightly moved corners
        double jitter = 1e-4 * ((q * 4 + int(p.size())) % 3 - 1);
        points.emplace_back((k & 1) + jitter, ((k >> 1) & 1) - jitter, ((k >> 2) & 1) + jitter);
        p.push_back(points.size() - 1);
      }
      if (q == 2) std::reverse(p.begin(), p.end());
      polygons.push_back(p);
    }
    polygons.push_back(polygons[1]);  // a duplicate
    points.emplace_back(0.5, 0.5, 2.0);  // a fin on an edge of the top face
    polygons.push_back({polygons[1][0], polygons[1][1], points.size() - 1});
  }

  auto np = MP::snap_epsilon(eps, MP::keep_two_sided(false));
  CGAL::Surface_mesh<Point> sm;
  mrepair::Soup_repair_result r = mrepair::polygon_soup_to_manifold_mesh(points, polygons, sm, np);
  mrepair::Report report;
  r.to_report(report);
  std::cout << "Surface_mesh:\n" << report.to_text();
  if (!mrepair::succeeded(r.status)) return 1;

  CGAL::Polyhedron_3<K, CGAL::Polyhedron_items_with_id_3> poly;
  mrepair::Soup_repair_result r2 = mrepair::polygon_soup_to_manifold_mesh(points, polygons, poly, np);
  std::cout << "Polyhedron_3: " << r2.faces_out << " faces, " << r2.components << " components, valid "
            << CGAL::is_valid_polygon_mesh(poly) << "\n";
  return mrepair::succeeded(r2.status) ? 0 : 1;
}
