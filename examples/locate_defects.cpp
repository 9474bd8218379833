// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Where the defects are: lists them for a polygon soup and, when it is a
// polygon mesh, for a Surface_mesh and a Polyhedron_3, and prints the first
// instance of each kind with its coordinates.
// usage: example_locate_defects [INPUT]
// Without INPUT: the bundled generated scan (examples/data/sample_scan.off).
#include <mrepair/io.h>
#include <mrepair/locate_defects.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Polyhedron_items_with_id_3.h>
#include <CGAL/Surface_mesh.h>

#include <iostream>
#include <string>
#include <vector>

using K = CGAL::Epick;
using Point = K::Point_3;
using Polygon = std::vector<std::size_t>;
namespace PMP = CGAL::Polygon_mesh_processing;

// one line per kind: how many, and where the first one is
void print_locations(const mrepair::Defect_locations& d, const std::vector<Point>& points)
{
  auto at = [&](mrepair::Defect_locations::Index v) {
    std::cout << " (first at vertex " << v << ": " << points[v] << ")";
  };
  std::cout << "boundary loops          " << d.boundary_loops.size();
  if (!d.boundary_loops.empty() && !d.boundary_loops[0].empty()) at(d.boundary_loops[0][0]);
  std::cout << "\nsmall holes             " << d.small_holes.size()
            << "\nnon-manifold edges      " << d.non_manifold_edges.size();
  if (!d.non_manifold_edges.empty()) at(d.non_manifold_edges[0][0]);
  std::cout << "\nnon-manifold vertices   " << d.non_manifold_vertices.size();
  if (!d.non_manifold_vertices.empty()) at(d.non_manifold_vertices[0]);
  std::cout << "\nspiked vertices         " << d.spiked_vertices.size();
  if (!d.spiked_vertices.empty()) at(d.spiked_vertices[0]);
  std::cout << "\nnear-degenerate faces   " << d.near_degenerate_faces.size()
            << "\nsmall components        " << d.small_components.size()
            << "\nself-intersecting pairs " << d.self_intersecting_pairs.size()
            << "\nT-junctions             " << d.t_junction_vertices.size();
  if (!d.t_junction_vertices.empty()) at(d.t_junction_vertices[0]);
  std::cout << "\n";
}

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : std::string(MREPAIR_SAMPLE_DIR) + "/sample_scan.off";
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  mrepair::Io_result io = mrepair::read_polygon_soup(input, points, polygons);
  if (io.status != mrepair::Status::ok && io.status != mrepair::Status::non_finite_input &&
      io.status != mrepair::Status::invalid_index) {
    std::cerr << "cannot read " << input << ": " << io.message << "\n";
    return 1;
  }

  // The lists come from the inspection that counts them: d.report is
  // inspect_polygon_soup()'s report, and each list is as long as its count.
  mrepair::Defect_locations soup = mrepair::locate_defects(points, polygons);
  std::cout << "--- polygon soup (" << soup.report.faces << " faces) ---\n";
  print_locations(soup, points);
  if (soup.spiked_vertices.size() != soup.report.spiked_vertices) return 1;

  if (soup.report.invalid_polygons == 0 && soup.report.non_finite_vertices == 0 &&
      mrepair::is_polygon_soup_a_polygon_mesh(polygons, points.size())) {
    CGAL::Surface_mesh<Point> sm;
    PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
    mrepair::Defect_locations m = mrepair::locate_defects(sm, CGAL::parameters::default_values());
    std::cout << "--- Surface_mesh ---\n";
    print_locations(m, points);  // vertices keep the soup's numbering
    CGAL::Polyhedron_3<K, CGAL::Polyhedron_items_with_id_3> poly;
    PMP::polygon_soup_to_polygon_mesh(points, polygons, poly);
    mrepair::Defect_locations p = mrepair::locate_defects(poly, CGAL::parameters::default_values());
    std::cout << "--- Polyhedron_3 ---\nsame lists as the Surface_mesh: " << std::boolalpha
              << (p.spiked_vertices == m.spiked_vertices && p.boundary_loops == m.boundary_loops &&
                  p.self_intersecting_pairs == m.self_intersecting_pairs)
              << "\n";
  } else {
    std::cout << "(not a polygon mesh: soup lists only)\n";
  }
  return 0;
}
