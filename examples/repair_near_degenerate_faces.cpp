// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Removes needles and caps from a triangle mesh by safe edge collapses.
// usage: example_repair_near_degenerate_faces [INPUT [OUTPUT]]
// Without INPUT: a 20x20 grid with a sliver pair (a vertex 0.01 from another).
#include <mrepair/repair_near_degenerate_faces.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <iostream>

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;

int main(int argc, char** argv)
{
  Mesh mesh;
  if (argc > 1) {
    if (!read_mesh(argv[1], mesh)) return 1;
  } else {
    CGAL::make_grid(20, 20, mesh, [](int i, int j) { return K::Point_3(i, j, 0); }, true);
    // move a vertex next to its neighbour: the faces around that edge become needles
    Mesh::Vertex_index v(10 * 21 + 10), w(10 * 21 + 11);
    mesh.point(v) = K::Point_3(mesh.point(w).x() - 0.01, mesh.point(w).y(), 0);
  }
  namespace MP = mrepair::parameters;
  mrepair::Near_degenerate_faces_result r =
      mrepair::repair_near_degenerate_faces(mesh, MP::max_normal_deviation(45.0));
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
