// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Fixes what must never leave a repair: exactly degenerate faces, duplicate
// faces and non-manifold vertices; nothing else changes.
// usage: example_ensure_valid_mesh [INPUT [OUTPUT]]
// Without INPUT: a 10x10 grid with a zero-length edge (a vertex moved onto its
// neighbour), an interior cap (a vertex moved onto the opposite diagonal), a
// triangle pinched to the grid at one corner (a non-manifold vertex), and a
// detached two-face pillow (a duplicate pair).
#include <mrepair/ensure_valid_mesh.h>
#include <mrepair/triangulate_polygons.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <iostream>

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace MP = mrepair::parameters;

int main(int argc, char** argv)
{
  Mesh mesh;
  if (argc > 1) {
    if (!read_mesh(argv[1], mesh)) return 1;
    mrepair::triangulate_polygons(mesh);  // the algorithm expects triangles
  } else {
    // make_grid: vertex (i, j) is j * 11 + i; the diagonals join (i+1, j) to (i, j+1)
    CGAL::make_grid(10, 10, mesh, [](int i, int j) { return Point(i, j, 0); }, true);
    auto v = [](int i, int j) { return Mesh::Vertex_index(j * 11 + i); };
    mesh.point(v(2, 2)) = mesh.point(v(3, 2));   // zero-length edge
    mesh.point(v(6, 6)) = Point(6.5, 6.5, 0);    // on the diagonal (7,6)-(6,7): a cap
    mesh.add_face(v(10, 10), mesh.add_vertex(Point(11, 10.5, 0)), mesh.add_vertex(Point(10.5, 11, 0)));
    auto a = mesh.add_vertex(Point(12, 0, 0)), b = mesh.add_vertex(Point(13, 0, 0)),
         c = mesh.add_vertex(Point(12, 1, 0));
    mesh.add_face(a, b, c);
    mesh.add_face(c, b, a);
  }
  const std::size_t faces_before = faces(mesh).size();

  // a cap on the number of local operations (the default grows with the defects)
  mrepair::Validity_result r = mrepair::ensure_valid_mesh(mesh, MP::max_validity_operations(1000));
  mrepair::Report report;
  r.to_report(report);
  std::cout << report.to_text();
  std::cout << "faces: " << faces_before << " - " << r.faces_removed() << " -> " << faces(mesh).size()
            << "\n";
  if (!mrepair::succeeded(r.status)) {
    std::cerr << "ensure_valid_mesh: " << mrepair::to_string(r.status) << ": " << r.message << "\n";
    return 1;
  }
  if (argc > 2) {
    mesh.collect_garbage();
    if (!write_mesh(argv[2], mesh)) return 1;
  }
  return 0;
}
