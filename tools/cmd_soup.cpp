// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// `mrepair soup INPUT OUTPUT [--epsilon E] [--merge-epsilon E] [--keep-two-sided]
// [--no-orient-outward] [--report R.json]`: turns any polygon soup (STL, OBJ,
// OFF, PLY) into an oriented manifold triangle mesh; prints the inspection of
// the input soup and of the output mesh beside the repair's own counters.
#include "cli.h"
#include "cli_io.h"
#include "summary.h"

#include <mrepair/inspect.h>
#include <mrepair/io.h>
#include <mrepair/stitch_soup.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Epick;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace MP = mrepair::parameters;
namespace cli = mrepair::cli;

const std::vector<cli::Option> options = {
    {"epsilon", true, "stitch boundary edges whose endpoints lie within this distance (0: off)"},
    {"merge-epsilon", true, "merge points within this distance before anything else (0: equal points only)"},
    {"keep-two-sided", false, "keep both faces of a two-sided sheet (same vertices, opposite orientations)"},
    {"orient-outward", false, "closed components bound a volume (the default)"},
    {"no-orient-outward", false, "keep the input orientation of most faces of each component"},
    {"binary", false, "write a binary file (PLY, STL; default: the input's encoding for its own format, binary for another)"},
    {"ascii", false, "write an ASCII file"},
};

int run(int argc, char** argv);

const cli::Command command{"soup", "INPUT OUTPUT [--epsilon E] [--merge-epsilon E] [--keep-two-sided] [options]",
                           "polygon soup to oriented manifold triangle mesh (cutting and stitching)", run};
cli::Registrar reg{command};

int run(int argc, char** argv)
{
  cli::Arguments args = cli::parse(argc, argv, 1, options, 2, 2);
  if (args.has("help")) {
    cli::print_help(command, options);
    return 0;
  }
  cli::Summary summary("soup");
  const double eps = args.get_double("epsilon", 0.0);
  const double merge = args.get_double("merge-epsilon", 0.0);
  if (eps < 0) throw cli::Usage_error("--epsilon expects a non-negative distance");
  if (merge < 0) throw cli::Usage_error("--merge-epsilon expects a non-negative distance");
  if (args.has("orient-outward") && args.has("no-orient-outward"))
    throw cli::Usage_error("--orient-outward and --no-orient-outward exclude each other");
  const std::string input = args.positional[0], output = args.positional[1];

  cli::Progress_printer printer(args);
  std::vector<Point> points;
  // an all-triangle file is read into fixed arrays (see read_polygon_or_triangle_soup)
  std::vector<std::vector<std::size_t>> polygons;
  std::vector<std::array<std::size_t, 3>> triangles;
  bool all_triangles = false;
  printer.start_phase("read");
  mrepair::Io_result io =
      mrepair::read_polygon_or_triangle_soup(input, points, polygons, triangles, all_triangles);
  printer.end_phase("read");
  if (io.status != mrepair::Status::ok && io.status != mrepair::Status::non_finite_input &&
      io.status != mrepair::Status::invalid_index)
    return cli::fail(io.message.empty() ? input + ": " + mrepair::to_string(io.status) : io.message);

  mrepair::Report report;
  io.to_report(report.section("file"));
  Mesh& mesh = cli::kept_until_exit<Mesh>();
  mrepair::Inspection_report before, after;
  auto inspect_and_repair = [&](auto& soup) {
    before = mrepair::inspect_polygon_soup(points, soup, MP::count_self_intersections(false));
    before.to_summary_report(report.section("before"));
    return mrepair::polygon_soup_to_manifold_mesh(
        points, soup, mesh,
        MP::snap_epsilon(eps, MP::merge_epsilon(merge, MP::keep_two_sided(args.has("keep-two-sided"),
                                                                           MP::orient_outward(!args.has("no-orient-outward")))))
            .visitor(std::ref(printer)));
  };
  mrepair::Soup_repair_result r =
      all_triangles ? inspect_and_repair(triangles) : inspect_and_repair(polygons);
  r.to_report(report.section("soup"));
  if (!mrepair::succeeded(r.status)) {
    cli::emit_report(args, report);
    return cli::fail(input + ": " + mrepair::to_string(r.status) + (r.message.empty() ? "" : " (" + r.message + ")"));
  }
  after = mrepair::inspect(mesh, MP::count_self_intersections(false));
  after.to_summary_report(report.section("after"));

  printer.start_phase("write");
  mrepair::Io_result wr = mrepair::write_polygon_mesh(output, mesh, cli::write_binary(args, io, output));
  printer.end_phase("write");
  if (wr.status != mrepair::Status::ok)
    return cli::fail(wr.message.empty() ? output + ": " + mrepair::to_string(wr.status) : wr.message);
  if (!cli::emit_report(args, report)) return 1;
  summary.set_status(r.status, r.message);
  summary.add_sizes(before.faces, after.faces, before.vertices, after.vertices);
  summary.add_changes(before, after);
  summary.add_closed(after.closed);
  summary.add_intersection_free(after);
  summary.add_output(output, wr);
  summary.add_report(args);
  cli::print_summary(args, summary);
  return cli::exit_code(r.status);
}

} // namespace
