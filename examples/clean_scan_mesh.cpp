// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Cleans a scanned mesh with the RameshCleaner pipeline and prints what each
// step did; also shows the steps used alone.
// usage: example_clean_scan_mesh [INPUT [OUTPUT]]
// Without INPUT: a 40x40 grid with a hole, a jagged border ear, a small
// floating component and an isolated vertex.
#include <mrepair/clean_boundaries.h>
#include <mrepair/clean_scan_mesh.h>
#include <mrepair/fill_small_holes.h>
#include <mrepair/io.h>
#include <mrepair/remove_small_components.h>

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
    mrepair::Io_result io = mrepair::read_polygon_mesh(argv[1], mesh);
    if (!mrepair::succeeded(io.status)) {
      std::cerr << "cannot read " << argv[1] << ": " << io.message << "\n";
      return 1;
    }
  } else {
    CGAL::make_grid(40, 40, mesh, [](int i, int j) { return K::Point_3(i, j, 0); }, true);
    // a hole: the faces around vertex (20, 20)
    Mesh::Vertex_index c(20 * 41 + 20);
    std::vector<Mesh::Face_index> ring;
    for (auto f : CGAL::faces_around_target(mesh.halfedge(c), mesh))
      if (f != Mesh::null_face()) ring.push_back(f);
    for (auto f : ring) CGAL::Euler::remove_face(mesh.halfedge(f), mesh);
    // a small floating triangle and an isolated vertex
    auto a = mesh.add_vertex(K::Point_3(50, 0, 0)), b = mesh.add_vertex(K::Point_3(51, 0, 0)),
         d = mesh.add_vertex(K::Point_3(50, 1, 0));
    mesh.add_face(a, b, d);
    mesh.add_vertex(K::Point_3(60, 60, 60));
  }

  // The whole pipeline (mesh is collected on return).
  mrepair::Scan_cleaning_result r =
      mrepair::clean_scan_mesh(mesh, MP::max_hole_vertices(100, MP::min_component_faces(400)));
  mrepair::Report report;
  r.to_report(report);
  std::cout << report.to_text();
  if (!mrepair::succeeded(r.status)) {
    std::cerr << "clean_scan_mesh: " << mrepair::to_string(r.status) << ": " << r.message << "\n";
    return 1;
  }

  // The steps are public functions too; on the cleaned mesh they find nothing left.
  mrepair::Small_components_result c = mrepair::remove_small_components(mesh);
  mrepair::Boundary_cleaning_result b = mrepair::clean_boundaries(mesh);
  mrepair::Hole_filling_result h = mrepair::fill_small_holes(mesh);
  std::cout << "again: components removed " << c.components_removed << ", bad boundary vertices "
            << b.bad_vertices_removed << ", holes filled " << h.holes_filled << "\n";

  if (argc > 2) {
    mesh.collect_garbage();
    mrepair::Io_result out = mrepair::write_polygon_mesh(argv[2], mesh);
    if (!mrepair::succeeded(out.status)) {
      std::cerr << "cannot write " << argv[2] << ": " << out.message << "\n";
      return 1;
    }
  }
  return 0;
}
