// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Resolves the crossings of a triangle mesh: the closed shells that cross
// (each other or themselves) become one solid, the boundary of the cells of
// nonzero winding number of their exact arrangement; open shells crossing
// themselves are repaired locally; nested closed shells go into a union.
// usage: example_resolve_intersections [INPUT [OUTPUT]]
// Without INPUT: two unit cubes, the second shifted by half a unit along
// every axis, so that each passes through the other.
#include <mrepair/resolve_intersections.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
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
    for (double o : {0.0, 0.5}) {
      Mesh cube;
      CGAL::make_hexahedron(K::Point_3(o, o, o), K::Point_3(o + 1, o, o), K::Point_3(o + 1, o + 1, o),
                            K::Point_3(o, o + 1, o), K::Point_3(o, o + 1, o + 1), K::Point_3(o, o, o + 1),
                            K::Point_3(o + 1, o, o + 1), K::Point_3(o + 1, o + 1, o + 1), cube);
      CGAL::Polygon_mesh_processing::triangulate_faces(cube);
      mesh += cube;
    }
  }
  namespace MP = mrepair::parameters;
  // solidify_closed_shells(false): the local repair and the union alone, as
  // before issue 50; merge_overlapping_shells(false) keeps the shells apart
  mrepair::Intersection_repair_result r = mrepair::resolve_intersections(
      mesh, MP::solidify_closed_shells(true, MP::merge_overlapping_shells(true, MP::max_local_rounds(3))));
  // shells_solidified, arrangement_faces; solidify_note says why the shells
  // were left as they were (arrangement_too_large, rounding_left_crossings...)
  mrepair::Report report;
  r.to_report(report.section("resolve_intersections"));
  std::cout << report.to_text();
  if (!mrepair::succeeded(r.status)) return 1;
  if (argc > 2) {
    mesh.collect_garbage();
    if (!write_mesh(argv[2], mesh)) return 1;
  }
  return 0;
}
