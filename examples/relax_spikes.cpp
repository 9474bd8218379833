// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Relaxes spikes and foldovers, then removes the spikes that do not relax.
// usage: example_relax_spikes [INPUT [OUTPUT]]
// Without INPUT: a 20x20 grid with a tall narrow spike (6 edge lengths) and a foldover.
#include <mrepair/relax_spikes.h>

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
    mesh.point(Mesh::Vertex_index(5 * 21 + 5)) = K::Point_3(5, 5, 6);      // tall spike
    mesh.point(Mesh::Vertex_index(14 * 21 + 14)) = K::Point_3(15.4, 14.3, 0); // foldover
  }
  namespace MP = mrepair::parameters;
  // relax first (the paper's 3.7), then remove what did not relax (3.8)
  mrepair::Spike_relaxation_result r = mrepair::relax_spikes(mesh, MP::spike_angle(100.0));
  if (!mrepair::succeeded(r.status)) {
    std::cerr << "relax_spikes: " << mrepair::to_string(r.status) << ": " << r.message << "\n";
    return 1;
  }
  mrepair::Spike_removal_result rr = mrepair::remove_unrelaxable_spikes(mesh, MP::spike_angle(100.0));
  mrepair::Report report;
  r.to_report(report.section("relax_spikes"));
  rr.to_report(report.section("remove_unrelaxable_spikes"));
  std::cout << report.to_text();
  if (argc > 2) {
    mesh.collect_garbage();
    if (!write_mesh(argv[2], mesh)) return 1;
  }
  return 0;
}
