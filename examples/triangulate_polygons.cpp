// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Triangulates the quads and n-gons of a polygon mesh by ear clipping, the
// first step of every mrepair call that needs triangles. It takes no named
// parameters.
// usage: example_triangulate_polygons [INPUT [OUTPUT]]
// Without INPUT: a closed L-shaped prism (two non-convex hexagons and six
// quads) and a 4x3 grid of quads beside it.
#include <mrepair/triangulate_polygons.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/boost/graph/helpers.h>

#include <iostream>
#include <vector>

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

int main(int argc, char** argv)
{
  Mesh mesh;
  if (argc > 1) {
    if (!read_mesh(argv[1], mesh)) return 1;
  } else {
    const double L[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};  // counterclockwise
    std::vector<Mesh::Vertex_index> bottom, top;
    for (const auto& p : L) {
      bottom.push_back(mesh.add_vertex(Point(p[0], p[1], 0)));
      top.push_back(mesh.add_vertex(Point(p[0], p[1], 1)));
    }
    mesh.add_face(top);                                     // faces up
    mesh.add_face(std::vector<Mesh::Vertex_index>(bottom.rbegin(), bottom.rend()));  // faces down
    for (int k = 0; k < 6; ++k) mesh.add_face(bottom[k], bottom[(k + 1) % 6], top[(k + 1) % 6], top[k]);
    CGAL::make_grid(4, 3, mesh, [](int i, int j) { return Point(4 + i, j, 0); }, false);
  }

  mrepair::Triangulation_result r = mrepair::triangulate_polygons(mesh);
  mrepair::Report report;
  r.to_report(report);
  std::cout << "status: " << mrepair::to_string(r.status) << "\n" << report.to_text();
  std::cout << "triangle mesh: " << std::boolalpha << CGAL::is_triangle_mesh(mesh) << "\n";
  if (!mrepair::succeeded(r.status)) {
    std::cerr << "triangulate_polygons: " << r.message << "\n";
    return 1;
  }
  if (argc > 2 && !write_mesh(argv[2], mesh)) return 1;
  return 0;
}
