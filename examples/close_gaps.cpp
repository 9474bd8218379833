// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Closes gaps progressively, steps back and forth, then closes everything within the tolerance.
// usage: example_close_gaps [INPUT [OUTPUT [TOLERANCE]]]   (TOLERANCE relative to the bbox diagonal)
// Without INPUT: two grid patches 1% apart, the right one twice as fine along the seam
// (T-junctions), and a third one 5% away (a slot that must stay open).
#include <mrepair/close_gaps.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <mrepair/triangulate_polygons.h>
#include <CGAL/Surface_mesh.h>

#include <cstdlib>
#include <iostream>

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

static void print(const char* what, const Mesh& m, const mrepair::Gap_closing_sequence<Mesh>& s)
{
  auto c = mrepair::internal::count_boundary(m);
  std::cout << what << ": position " << s.position() << "/" << s.size() << ", distance "
            << s.current_distance() << ", " << c.first << " boundary edges in " << c.second
            << " loops\n";
}

int main(int argc, char** argv)
{
  Mesh mesh;
  double tolerance = 0.005;  // relative to the bounding-box diagonal
  if (argc > 1) {
    if (!read_mesh(argv[1], mesh)) return 1;
    mrepair::triangulate_polygons(mesh);  // ear clipping: ends on any polygon
    if (argc > 3) tolerance = std::atof(argv[3]);
  } else {
    add_patch(mesh, 0.0, 10, 10);
    add_patch(mesh, 1.01, 10, 20);
    add_patch(mesh, 2.06, 10, 20);
  }

  // step through the closing: forward, back, forward to a distance
  {
    mrepair::Gap_closing_sequence<Mesh> seq(mesh, tolerance, MP::gap_relative_tolerance(true));
    if (seq.status() != mrepair::Status::ok) {
      std::cerr << "close_gaps: " << mrepair::to_string(seq.status()) << "\n";
      return 1;
    }
    print("input", mesh, seq);
    seq.forward(5);
    print("forward 5", mesh, seq);
    seq.forward_to_distance(seq.max_distance());
    print("all within tolerance", mesh, seq);
    seq.backward(seq.size() / 2);
    print("half way back", mesh, seq);
    seq.backward_to_distance(0);
    print("back to the input", mesh, seq);
  }

  // Stepping back left removed elements in the Surface_mesh (garbage): the
  // one-shot closing counts faces with num_faces(), which includes them, and
  // would refuse the mesh as invalid_mesh. Compact it first.
  mesh.collect_garbage();

  // one shot (also splits vertices left with several fans)
  mrepair::Gap_closing_result r = mrepair::close_gaps(mesh, tolerance, MP::gap_relative_tolerance(true));
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
