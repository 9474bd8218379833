// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Erodes the bad vertices of a mesh's boundaries (teeth, ears, folds) and
// smooths what is left, as a scan cleaner does before filling holes.
// usage: example_clean_boundaries [INPUT [OUTPUT]]
// Without INPUT: a 30x30 grid whose bottom border is a saw (every other
// triangle of the bottom row removed), with an ear hanging into a square hole
// and a face folded back over the top border.
#include <mrepair/clean_boundaries.h>
#include <mrepair/triangulate_polygons.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <iostream>
#include <vector>

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace MP = mrepair::parameters;

int main(int argc, char** argv)
{
  Mesh mesh;
  if (argc > 1) {
    if (!read_mesh(argv[1], mesh)) return 1;
    mrepair::triangulate_polygons(mesh);  // the algorithm expects triangles
  } else {
    // make_grid: vertex (i, j) is j * 31 + i; quad (i, j) gives the faces
    // (i,j)(i+1,j)(i,j+1), then (i+1,j)(i+1,j+1)(i,j+1)
    CGAL::make_grid(30, 30, mesh, [](int i, int j) { return K::Point_3(i, j, 0); }, true);
    auto v = [](int i, int j) { return Mesh::Vertex_index(j * 31 + i); };
    auto f = [](int i, int j, int k) { return Mesh::Face_index(2 * (i * 30 + j) + k); };
    std::vector<Mesh::Face_index> doomed;
    for (int i = 0; i < 30; ++i) doomed.push_back(f(i, 0, 0));  // the saw
    for (int i = 12; i < 18; ++i)
      for (int j = 12; j < 18; ++j)
        for (int k = 0; k < 2; ++k) doomed.push_back(f(i, j, k));  // a 6x6 hole
    for (auto d : doomed) CGAL::Euler::remove_face(mesh.halfedge(d), mesh);
    // an ear on the hole's bottom edge (14,12)-(15,12), pointing into the hole
    mesh.add_face(v(14, 12), v(15, 12), mesh.add_vertex(K::Point_3(14.5, 13.2, 0)));
    // a face folded back over the grid on the top border edge (20,30)-(21,30)
    mesh.add_face(v(20, 30), v(21, 30), mesh.add_vertex(K::Point_3(20.5, 29.2, 0.01)));
  }

  // look 3 rings deep; give up after 10 removal rounds
  mrepair::Boundary_cleaning_result r =
      mrepair::clean_boundaries(mesh, MP::confidence_rings(3, MP::max_boundary_rounds(10)));
  mrepair::Report report;
  r.to_report(report);
  std::cout << report.to_text();
  if (!mrepair::succeeded(r.status)) return 1;
  if (argc > 2) {
    mesh.collect_garbage();
    if (!write_mesh(argv[2], mesh)) return 1;
  }
  return 0;
}
