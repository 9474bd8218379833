// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Counts the defects of a file, as a polygon soup and, when it is a polygon
// mesh, as a Surface_mesh and as a Polyhedron_3.
// usage: example_inspect [INPUT]
// Without INPUT: a small grid with a hole, a flipped face and a spike.
#include <mrepair/inspect.h>
#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Polyhedron_items_with_id_3.h>
#include <CGAL/Surface_mesh.h>

#include <iostream>
#include <vector>

using K = CGAL::Epick;
using Point = K::Point_3;
using Polygon = std::vector<std::size_t>;
namespace MP = mrepair::parameters;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv)
{
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  if (argc > 1) {
    mrepair::Io_result io = mrepair::read_polygon_soup(argv[1], points, polygons);
    if (io.status != mrepair::Status::ok && io.status != mrepair::Status::non_finite_input &&
        io.status != mrepair::Status::invalid_index) {
      std::cerr << "cannot read " << argv[1] << ": " << io.message << "\n";
      return 1;
    }
  } else {
    const std::size_t n = 8;
    for (std::size_t j = 0; j <= n; ++j)
      for (std::size_t i = 0; i <= n; ++i) points.emplace_back(double(i), double(j), 0.0);
    points[4 * (n + 1) + 4] = Point(4, 4, 3); // a spike
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        std::size_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
        if (i == 1 && j == 1) continue;                  // a hole of two triangles
        polygons.push_back({a, b, c});
        polygons.push_back(i == 6 && j == 6 ? Polygon{a, d, c} : Polygon{a, c, d}); // flipped
      }
  }

  // Thresholds are named parameters; here a lower spike angle and a smaller hole size.
  auto np = MP::spike_angle(60.0, MP::max_hole_vertices(20));
  mrepair::Inspection_report soup = mrepair::inspect_polygon_soup(points, polygons, np);
  mrepair::Report report;
  soup.to_report(report);
  std::cout << "--- polygon soup ---\n" << report.to_text();

  if (soup.invalid_polygons == 0 && mrepair::is_polygon_soup_a_polygon_mesh(polygons, points.size())) {
    CGAL::Surface_mesh<Point> sm;
    PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
    mrepair::Inspection_report r = mrepair::inspect(sm, np);
    std::cout << "--- Surface_mesh ---\nself-intersecting pairs: " << r.self_intersecting_pairs
              << "\nboundary loops: " << r.boundary_loops << "\n";
    CGAL::Polyhedron_3<K, CGAL::Polyhedron_items_with_id_3> poly;
    PMP::polygon_soup_to_polygon_mesh(points, polygons, poly);
    mrepair::Inspection_report rp = mrepair::inspect(poly, np);
    std::cout << "--- Polyhedron_3 ---\nsame counts: " << std::boolalpha
              << (mrepair::make_report(rp).to_json() == mrepair::make_report(r).to_json()) << "\n";
  } else {
    std::cout << "(not a polygon mesh: soup figures only)\n";
  }
  return 0;
}
