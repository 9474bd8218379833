// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Removes the small floating pieces of a mesh (scanner debris), keeping the
// pieces that are small in faces but not next to the largest one.
// This example runs on a CGAL::Polyhedron_3 with the default items: mrepair
// keeps its scratch data in dynamic property maps and numbers vertices itself
// when it writes, so no ids are needed (Polyhedron_items_with_id_3 works too).
// usage: example_remove_small_components [INPUT [OUTPUT]]
// Without INPUT: a 30x30 grid (1800 faces), a tetrahedron and a 2x2 patch
// floating above it (debris), a 6x6 patch of 72 faces, coarse and large (kept:
// not small next to the grid), and an 8x8 patch of 128 faces (kept: big enough).
#include <mrepair/remove_small_components.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/generators.h>

#include <iostream>

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Polyhedron_3<K>;
namespace MP = mrepair::parameters;

// appends an n x n triangulated grid of cell size s at (x, y, z)
static void add_patch(Mesh& m, int n, double s, double x, double y, double z)
{
  CGAL::make_grid(n, n, m, [=](int i, int j) { return Point(x + s * i, y + s * j, z); }, true);
}

int main(int argc, char** argv)
{
  Mesh mesh;
  if (argc > 1) {
    if (!read_mesh(argv[1], mesh)) return 1;
  } else {
    add_patch(mesh, 30, 1.0, 0, 0, 0);
    CGAL::make_tetrahedron(Point(5, 5, 2), Point(6, 5, 2), Point(5, 6, 2), Point(5, 5, 3), mesh);
    add_patch(mesh, 2, 0.5, 20, 20, 1);
    add_patch(mesh, 6, 5.0, 40, 0, 0);
    add_patch(mesh, 8, 1.0, 0, 40, 0);
  }
  const std::size_t faces_before = faces(mesh).size();

  // pieces under 100 faces go, unless they reach 5% of the largest piece's
  // faces or area
  mrepair::Small_components_result r = mrepair::remove_small_components(
      mesh, MP::min_component_faces(100, MP::relative_component_size(0.05)));
  mrepair::Report report;
  r.to_report(report);
  std::cout << report.to_text();
  std::cout << "faces: " << faces_before << " -> " << faces(mesh).size() << "\n";
  if (!mrepair::succeeded(r.status)) return 1;
  if (argc > 2 && !write_mesh(argv[2], mesh)) return 1;
  return 0;
}
