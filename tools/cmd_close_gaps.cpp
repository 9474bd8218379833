// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// mrepair close-gaps INPUT OUTPUT --tolerance T [--relative] [--steps K] [--lambda L] [--report R.json]
#include "cli.h"
#include "cli_io.h"

#include <mrepair/close_gaps.h>
#include <mrepair/io.h>
#include <mrepair/stitch_soup.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

namespace {

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace MP = mrepair::parameters;
using mrepair::cli::Option;

const std::vector<Option>& options()
{
  static const std::vector<Option> o = {
      {"tolerance", true, "largest gap closed (absolute; a fraction of the bbox diagonal with --relative)"},
      {"relative", false, "the tolerance is relative to the bounding-box diagonal"},
      {"steps", true, "stop after K contractions (default: all within the tolerance)"},
      {"lambda", true, "merged position lambda*v + (1-lambda)*v' (default 0.5)"},
      {"keep-pinched", false, "do not split vertices left with several fans"},
      {"binary", false, "write binary output (PLY/STL)"}};
  return o;
}

int run(int argc, char** argv);
mrepair::cli::Command command()
{
  return {"close-gaps", "INPUT OUTPUT --tolerance T [--relative] [--steps K]",
          "close cracks, narrow gaps and T-junctions between boundaries (progressive "
          "vertex-edge contraction)",
          run};
}
mrepair::cli::Registrar reg{command()};

int run(int argc, char** argv)
{
  mrepair::cli::Arguments a = mrepair::cli::parse(argc, argv, 1, options(), 2, 2);
  if (a.has("help")) {
    mrepair::cli::print_help(command(), options());
    return 0;
  }
  if (!a.has("tolerance")) throw mrepair::cli::Usage_error("close-gaps needs --tolerance T");
  const double tol = a.get_double("tolerance", 0);
  const long long steps = a.get_int("steps", -1);
  const double lambda = a.get_double("lambda", 0.5);
  if (tol < 0) throw mrepair::cli::Usage_error("--tolerance must be >= 0");
  if (lambda < 0 || lambda > 1) throw mrepair::cli::Usage_error("--lambda must be in [0,1]");

  mrepair::Report report;
  Mesh mesh;
  mrepair::Io_result io = mrepair::read_polygon_mesh(a.positional[0], mesh);
  io.to_report(report.section("input"));
  if (io.status == mrepair::Status::non_manifold_input || io.status == mrepair::Status::invalid_index ||
      io.status == mrepair::Status::non_finite_input) {
    // not a valid polygon mesh: make it one first (what `mrepair soup` does)
    std::cerr << "mrepair: " << a.positional[0]
              << " is not a valid polygon mesh; repairing it as a soup first (see `mrepair soup`)\n";
    std::vector<K::Point_3> points;
    std::vector<std::vector<std::size_t>> polygons;
    mrepair::Io_result sio = mrepair::read_polygon_soup(a.positional[0], points, polygons);
    if (!mrepair::succeeded(sio.status) && sio.status != mrepair::Status::non_finite_input &&
        sio.status != mrepair::Status::invalid_index)
      return mrepair::cli::fail(sio.message);
    mrepair::Soup_repair_result sr = mrepair::polygon_soup_to_manifold_mesh(points, polygons, mesh);
    sr.to_report(report.section("soup"));
    if (!mrepair::succeeded(sr.status) || faces(mesh).size() == 0)
      return mrepair::cli::fail(a.positional[0] + ": the soup could not be made a mesh (" +
                                mrepair::to_string(sr.status) + ")");
  } else if (!mrepair::succeeded(io.status)) {
    return mrepair::cli::fail(io.message);
  }
  {
    std::string error;
    if (!mrepair::cli::triangulate_polygons(mesh, report, error))
      return mrepair::cli::fail(a.positional[0] + ": " + error);
  }

  mrepair::cli::Progress_printer printer(!a.has("quiet"));
  mrepair::Gap_closing_result r;
  double seconds = mrepair::cli::timed([&] {
    r = mrepair::close_gaps(
        mesh, tol,
        MP::gap_relative_tolerance(a.has("relative"),
            MP::gap_lambda(lambda,
                MP::gap_split_pinched_vertices(!a.has("keep-pinched"),
                    MP::gap_max_operations(steps < 0 ? std::numeric_limits<std::size_t>::max()
                                                     : std::size_t(steps)))))
            .visitor(std::ref(printer)));
  });
  mrepair::Report& rr = report.section("close_gaps");
  r.to_report(rr);
  rr.add("seconds", seconds);
  if (!mrepair::succeeded(r.status) && r.status != mrepair::Status::cancelled) {
    mrepair::cli::emit_report(a, report);
    return mrepair::cli::fail("close-gaps: " + std::string(mrepair::to_string(r.status)) + ": " +
                              r.message);
  }
  mesh.collect_garbage();
  mrepair::Io_result out = mrepair::write_polygon_mesh(a.positional[1], mesh, a.has("binary"));
  out.to_report(report.section("output"));
  if (!mrepair::succeeded(out.status)) return mrepair::cli::fail(out.message);
  if (!mrepair::cli::emit_report(a, report)) return 1;
  return mrepair::cli::exit_code(r.status);
}

} // namespace
