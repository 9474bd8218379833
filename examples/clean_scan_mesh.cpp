// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Cleans a scanned mesh with the RameshCleaner pipeline and prints what each
// step did; also shows the steps used alone.
// usage: example_clean_scan_mesh [INPUT [OUTPUT [auto|scan|cad]]]
// The profile decides the steps (a CAD export keeps its parts and features);
// without one it is read off the mesh (classify_input, input_profile.h).
// Without INPUT: a 40x40 grid with a hole, a jagged border ear, a small
// floating component and an isolated vertex.
#include <mrepair/clean_boundaries.h>
#include <mrepair/clean_scan_mesh.h>
#include <mrepair/fill_small_holes.h>
#include <mrepair/io.h>
#include <mrepair/remove_small_components.h>
#include <mrepair/triangulate_polygons.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <iostream>
#include <optional>
#include <vector>

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace MP = mrepair::parameters;

int main(int argc, char** argv)
{
  Mesh mesh;
  if (argc > 1) {
    // Read as a soup and built with CGAL's builder, as `mrepair clean` and
    // `mrepair repair` do: a scan's NaN points are accepted (read_polygon_mesh
    // refuses them), and the pipeline's first step removes them.
    std::vector<K::Point_3> points;
    std::vector<std::vector<std::size_t>> polygons;
    mrepair::Io_result io = mrepair::read_polygon_soup(argv[1], points, polygons);
    if (io.status != mrepair::Status::ok && io.status != mrepair::Status::non_finite_input) {
      std::cerr << "cannot read " << argv[1] << ": " << io.message << "\n";
      return 1;
    }
    if (!mrepair::is_polygon_soup_a_polygon_mesh(polygons, points.size())) {
      std::cerr << argv[1] << ": not a manifold mesh; repair it first (example_repair)\n";
      return 1;
    }
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);
    mrepair::triangulate_polygons(mesh);
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

  std::optional<mrepair::Input_profile> profile;  // absent: the library's default, automatic
  mrepair::Input_profile chosen;
  if (argc > 3 && mrepair::parse_input_profile(argv[3], chosen)) profile = chosen;

  // The whole pipeline (mesh is collected on return).
  mrepair::Scan_cleaning_result r = mrepair::clean_scan_mesh(mesh, MP::input_profile(profile));
  mrepair::Report report;
  r.to_report(report);
  std::cout << report.to_text();
  if (!mrepair::succeeded(r.status)) {
    std::cerr << "clean_scan_mesh: " << mrepair::to_string(r.status) << ": " << r.message << "\n";
    return 1;
  }

  if (argc > 2 && !write_mesh(argv[2], mesh)) return 1;

  // The steps are public functions too; on the cleaned mesh they find nothing left.
  mrepair::Small_components_result c = mrepair::remove_small_components(mesh);
  mrepair::Boundary_cleaning_result b = mrepair::clean_boundaries(mesh);
  mrepair::Hole_filling_result h = mrepair::fill_small_holes(mesh);
  std::cout << "again: components removed " << c.components_removed << ", bad boundary vertices "
            << b.bad_vertices_removed << ", holes filled " << h.holes_filled << "\n";
  return 0;
}
