// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Converts between OFF, OBJ, PLY and STL (by extension) through a polygon
// soup, so that defective files convert too, and prints both I/O reports.
// usage: example_convert [INPUT [OUTPUT [--binary]]]
// Defaults: the bundled sample scan, written to convert_out.ply (binary).
#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv)
{
  using Point = CGAL::Epick::Point_3;
  const std::string input = argc > 1 ? argv[1] : std::string(MREPAIR_SAMPLE_DIR) + "/sample_scan.off";
  const std::string output = argc > 2 ? argv[2] : "convert_out.ply";
  const bool binary = argc > 3 ? std::string(argv[3]) == "--binary" : argc <= 2;

  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  mrepair::Io_result in = mrepair::read_polygon_soup(input, points, polygons);
  mrepair::Report report;
  in.to_report(report.section("read"));
  // non-finite points are loaded and written as they are; polygons with bad
  // indices load too, but no format can hold them, so the write refuses them
  if (in.status != mrepair::Status::ok && in.status != mrepair::Status::non_finite_input &&
      in.status != mrepair::Status::invalid_index) {
    std::cout << report.to_text();
    std::cerr << in.message << "\n";
    return 1;
  }
  mrepair::Io_result out = mrepair::write_polygon_soup(output, points, polygons, binary);
  out.to_report(report.section("write"));
  std::cout << report.to_text();
  if (out.status != mrepair::Status::ok) {
    std::cerr << out.message << "\n";
    return 1;
  }
  return 0;
}
