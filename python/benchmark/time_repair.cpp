// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// `mrepair-time-repair FILE`: the C++ side of the Python overhead measure.
// Reads FILE as a soup, then times the call `mrepair.repair(V, F)` makes:
// `repair_polygon_soup` with the default options, nothing else (no writing).
// Prints the seconds. compare_repair.py runs it beside the Python call.
#include <mrepair/io.h>
#include <mrepair/repair.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <cstdio>
#include <vector>

int main(int argc, char** argv)
{
  using Point = CGAL::Epick::Point_3;
  if (argc != 2) {
    std::fprintf(stderr, "usage: mrepair-time-repair FILE\n");
    return 2;
  }
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  const mrepair::Io_result in = mrepair::read_polygon_soup(argv[1], points, polygons);
  if (in.status != mrepair::Status::ok && in.status != mrepair::Status::non_finite_input) {
    std::fprintf(stderr, "%s\n", in.message.c_str());
    return 1;
  }
  CGAL::Surface_mesh<Point> mesh;
  const auto t0 = std::chrono::steady_clock::now();
  const mrepair::Repair_result r =
      mrepair::repair_polygon_soup(points, polygons, mesh);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%.4f %s %zu\n", seconds, mrepair::to_string(r.status),
              static_cast<std::size_t>(mesh.number_of_faces()));
  return r.failed_stage.empty() ? 0 : 1;
}
