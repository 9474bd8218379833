// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Fills the small holes of a triangle mesh (Liepa's triangulation, refined to
// the density around the hole) and leaves large holes and sheet borders open.
// usage: example_fill_small_holes [INPUT [OUTPUT]]
// Without INPUT: a bumpy 30x30 grid with two holes (a 1-ring and a 2-ring),
// whose outer border is too long to count as a hole, and a small floating
// sheet whose border is not a hole either.
#include <mrepair/fill_small_holes.h>
#include <mrepair/triangulate_polygons.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <cmath>
#include <iostream>
#include <set>

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace MP = mrepair::parameters;

// removes the faces within `rings` rings of the vertex (i, j) of a 30x30 grid
static void punch(Mesh& m, int i, int j, int rings)
{
  std::set<Mesh::Vertex_index> ring = {Mesh::Vertex_index(j * 31 + i)};
  std::set<Mesh::Face_index> doomed;
  for (int r = 0; r < rings; ++r) {
    for (auto v : std::set<Mesh::Vertex_index>(ring))
      for (auto f : CGAL::faces_around_target(m.halfedge(v), m))
        if (f != Mesh::null_face()) doomed.insert(f);
    for (auto f : doomed)
      for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) ring.insert(v);
  }
  for (auto f : doomed) CGAL::Euler::remove_face(m.halfedge(f), m);
}

int main(int argc, char** argv)
{
  Mesh mesh;
  if (argc > 1) {
    if (!read_mesh(argv[1], mesh)) return 1;
    mrepair::triangulate_polygons(mesh);  // the algorithm expects triangles
  } else {
    CGAL::make_grid(30, 30, mesh, [](int i, int j) {
      return K::Point_3(i, j, 2 * std::sin(i / 5.) * std::cos(j / 7.));
    }, true);
    punch(mesh, 8, 8, 1);    // 6 boundary vertices
    punch(mesh, 20, 18, 2);  // 12 boundary vertices
    CGAL::make_grid(2, 2, mesh, [](int i, int j) { return K::Point_3(40 + i, j, 0); }, true);
  }
  const std::size_t faces_before = faces(mesh).size();

  // holes with fewer than 50 boundary vertices, patches faired (smooth, not flat)
  mrepair::Hole_filling_result r =
      mrepair::fill_small_holes(mesh, MP::max_hole_vertices(50, MP::fair_hole_patches(true)));
  mrepair::Report report;
  r.to_report(report);
  std::cout << report.to_text();
  for (const mrepair::Open_hole& h : r.open_holes)
    std::cout << "left open: " << h.vertices << " vertices (" << h.reason << ")\n";
  // faces are removed only to enlarge holes whose first fill failed
  std::cout << "faces: " << faces_before << " - " << r.enlargement_faces_removed << " + "
            << r.faces_added << " = " << faces(mesh).size() << "\n";
  if (!mrepair::succeeded(r.status)) return 1;
  if (argc > 2) {
    mesh.collect_garbage();
    if (!write_mesh(argv[2], mesh)) return 1;
  }
  return 0;
}
