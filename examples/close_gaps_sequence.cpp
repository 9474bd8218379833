// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Steps a gap-closing sequence back and forth and prints, for each distance,
// what a user plots to choose where to stop: contractions, open boundary
// edges, boundary loops and open boundary length.
// usage: example_close_gaps_sequence [INPUT [TOLERANCE [ROWS]]]
//   TOLERANCE relative to the bounding-box diagonal (default 1e-3), ROWS about
//   how many rows (default 16). INPUT may be a soup (e.g. `mrepair-generate cad`
//   output): it is made a manifold mesh first. Without INPUT: three grid
//   patches with gaps of 0.01 and 0.015 (a T-junction seam and a plain one).
#include <mrepair/close_gaps.h>
#include <mrepair/io.h>
#include <mrepair/stitch_soup.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <mrepair/triangulate_polygons.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <vector>

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace MP = mrepair::parameters;

// nx x ny triangulated grid over [x0, x0+1] x [0,1]
static void add_patch(Mesh& m, double x0, int nx, int ny)
{
  std::vector<Mesh::Vertex_index> v;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) v.push_back(m.add_vertex(K::Point_3(x0 + double(i) / nx, double(j) / ny, 0)));
  auto id = [&](int i, int j) { return v[j * (nx + 1) + i]; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      m.add_face(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m.add_face(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
}

// open boundary: edges, loops, length
static void print_row(const Mesh& m, const mrepair::Gap_closing_sequence<Mesh>& s)
{
  double length = 0;
  for (auto h : halfedges(m))
    if (is_border(h, m)) length += std::sqrt(CGAL::squared_distance(m.point(source(h, m)), m.point(target(h, m))));
  auto c = mrepair::internal::count_boundary(m);
  std::printf("%14.6g %12zu %14zu %8zu %16.6g\n", s.current_distance(), s.position(), c.first, c.second, length);
}

int main(int argc, char** argv)
{
  Mesh mesh;
  double tolerance = 1e-3;
  std::size_t rows = 16;
  if (argc > 1) {
    std::vector<K::Point_3> points;
    std::vector<std::vector<std::size_t>> polygons;
    mrepair::Io_result io = mrepair::read_polygon_soup(argv[1], points, polygons);
    if (!mrepair::succeeded(io.status)) {
      std::cerr << "cannot read " << argv[1] << ": " << io.message << "\n";
      return 1;
    }
    mrepair::Soup_repair_result sr = mrepair::polygon_soup_to_manifold_mesh(points, polygons, mesh);
    if (!mrepair::succeeded(sr.status) || faces(mesh).size() == 0) {
      std::cerr << argv[1] << ": the soup could not be made a mesh (" << mrepair::to_string(sr.status) << ")\n";
      return 1;
    }
    mrepair::triangulate_polygons(mesh);  // ear clipping: ends on any polygon
    mesh.collect_garbage();
    if (argc > 2) tolerance = std::atof(argv[2]);
    if (argc > 3) rows = std::size_t(std::max(1, std::atoi(argv[3])));
  } else {
    add_patch(mesh, 0.0, 10, 10);
    add_patch(mesh, 1.01, 10, 20);
    add_patch(mesh, 2.025, 10, 20);
    tolerance = 0.008;
  }
  std::cout << vertices(mesh).size() << " vertices, " << faces(mesh).size() << " faces\n";

  CGAL::Real_timer t;
  t.start();
  mrepair::Gap_closing_sequence<Mesh> seq(mesh, tolerance, MP::gap_relative_tolerance(true));
  if (seq.status() != mrepair::Status::ok) {
    std::cerr << "gap closing refused the mesh: " << mrepair::to_string(seq.status()) << "\n";
    return 1;
  }
  const double pairing = t.time();
  seq.forward_to_distance(seq.max_distance());  // the full closure, recorded
  t.stop();
  std::cout << "tolerance " << seq.max_distance() << " (absolute): " << seq.size() << " contractions in "
            << t.time() << " s (pairing " << pairing << " s)\n\n";

  // the table, from the full closure back to the input: each row is the mesh
  // forward_to_distance(distance) gives
  std::vector<std::size_t> at{0};
  for (std::size_t i = 1; i <= rows && seq.size() > 0; ++i)
    at.push_back(seq.count_within(seq.distance_at((i * seq.size()) / rows)));
  std::sort(at.begin(), at.end());
  at.erase(std::unique(at.begin(), at.end()), at.end());
  std::printf("%14s %12s %14s %8s %16s\n", "distance", "contractions", "boundary_edges", "loops", "boundary_length");
  t.reset();
  t.start();
  for (std::size_t i = at.size(); i-- > 0;) {
    seq.go_to(at[i]);
    print_row(mesh, seq);
  }
  t.stop();
  std::cout << "(stepped back through " << seq.size() << " contractions and printed the rows in " << t.time()
            << " s)\n\n";

  // forward again, to half the tolerance, then back a few and forward to all
  seq.forward_to_distance(seq.max_distance() / 2);
  std::cout << "forward to half the tolerance:\n";
  print_row(mesh, seq);
  seq.backward(std::min<std::size_t>(seq.position(), 10));
  std::cout << "10 contractions back:\n";
  print_row(mesh, seq);
  seq.forward_to_distance(seq.max_distance());
  std::cout << "forward to the tolerance:\n";
  print_row(mesh, seq);
  if (!CGAL::is_valid_polygon_mesh(mesh)) {
    std::cerr << "invalid mesh\n";
    return 1;
  }
  return 0;
}
