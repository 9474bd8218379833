// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Tells a dense scan from a CAD / print mesh, as the repair does before it
// chooses its steps, and prints the profile and the reason behind it.
// usage: example_input_profile [INPUT]
// Without INPUT: a noisy bumpy 40x40 grid (a scan), the same grid flat (a
// tessellated plane: CAD), and the flat grid again with the profile forced.
#include <mrepair/input_profile.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <cmath>
#include <iostream>

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace MP = mrepair::parameters;

static void print(const char* what, const mrepair::Input_classification& c)
{
  std::cout << what << ": " << mrepair::to_string(c.profile) << (c.chosen_by_user ? " (chosen)" : "")
            << ", " << c.reason << "\n";
}

int main(int argc, char** argv)
{
  if (argc > 1) {
    Mesh mesh;
    if (!read_mesh(argv[1], mesh)) return 1;
    mrepair::Input_classification c = mrepair::classify_input(mesh);
    mrepair::Report report;
    c.to_report(report);
    std::cout << report.to_text();
    return 0;
  }

  Mesh scan, plane;
  CGAL::make_grid(40, 40, scan, [](int i, int j) {
    const double noise = 0.02 * std::sin(12.9898 * i + 78.233 * j);  // deterministic
    return K::Point_3(i, j, 3 * std::sin(i / 6.) * std::cos(j / 9.) + noise);
  }, true);
  CGAL::make_grid(40, 40, plane, [](int i, int j) { return K::Point_3(i, j, 0); }, true);

  print("bumpy grid", mrepair::classify_input(scan));
  print("flat grid", mrepair::classify_input(plane));
  // a caller who knows better fixes the profile; the measures are still taken
  print("flat grid, forced", mrepair::classify_input(plane, MP::input_profile(mrepair::Input_profile::scan)));
  return 0;
}
