// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// mrepair remesh INPUT OUTPUT (--edge-length L | --tolerance E | --faces N)
//                [--feature-angle A] [--iterations K] [--report R.json]
#include "cli.h"

#include <optional>
#include "cli_io.h"
#include "summary.h"

#include <mrepair/adaptive_remesh.h>
#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

namespace {

using Mesh = CGAL::Surface_mesh<CGAL::Epick::Point_3>;
namespace cli = mrepair::cli;

const std::vector<cli::Option> options = {
    {"edge-length", true, "uniform remeshing to target edge length L"},
    {"tolerance", true, "curvature-adaptive remeshing with approximation tolerance E"},
    {"faces", true, "curvature-adaptive remeshing to N faces (within 2%)"},
    {"feature-angle", true, "dihedral angle (degrees) of feature edges (default 44; 0 = none)"},
    {"iterations", true, "number of iterations (default 10)"},
    {"min-edge-length", true, "adaptive: smallest target length (default E)"},
    {"max-edge-length", true, "adaptive: largest target length (default bbox diagonal / 20)"},
    {"protect-features", false, "features and boundary are neither split nor collapsed"},
    {"sequential", false, "do not use threads"},
    {"binary", false, "write a binary file (PLY, STL; default: the input's encoding for its own format, binary for another)"},
    {"ascii", false, "write an ASCII file"},
};

int run(int argc, char** argv)
{
  static cli::Command self{"remesh", "", "", nullptr};
  cli::Arguments a = cli::parse(argc, argv, 1, options, 2, 2);
  if (a.has("help")) {
    self.synopsis = "INPUT OUTPUT (--edge-length L | --tolerance E | --faces N) [options]";
    self.summary = "uniform or curvature-adaptive isotropic remeshing with features kept";
    cli::print_help(self, options);
    return 0;
  }
  cli::Summary summary("remesh");
  int modes = a.has("edge-length") + a.has("tolerance") + a.has("faces");
  if (modes != 1) throw cli::Usage_error("give exactly one of --edge-length, --tolerance, --faces");
  // given or absent: the defaults are the library's (definitions.h)
  std::optional<double> feature_angle;
  if (a.has("feature-angle")) {
    const double angle = a.get_double("feature-angle", 0.);
    feature_angle = angle > 0 ? angle : -1.;  // 0: no feature detection
  }
  std::optional<int> iterations;
  if (a.has("iterations")) {
    const long long k = a.get_int("iterations", 0);
    if (k < 0 || k > 1000) throw cli::Usage_error("--iterations must be in [0, 1000]");
    iterations = int(k);
  }

  cli::Progress_printer printer(a);
  Mesh& mesh = cli::kept_until_exit<Mesh>();
  printer.start_phase("read");
  mrepair::Io_result io = mrepair::read_polygon_mesh(a.positional[0], mesh);
  printer.end_phase("read");
  if (!mrepair::succeeded(io.status))
    return cli::fail(a.positional[0] + ": " + mrepair::to_string(io.status) +
                     (io.message.empty() ? "" : " (" + io.message + ")"));
  mrepair::Report report;
  std::string error;
  if (!cli::triangulate_polygons(mesh, report, error))
    return cli::fail(a.positional[0] + ": " + error);

  const std::size_t vertices_in = mesh.number_of_vertices();
  // the writer skips the collapses' removed elements: no collect_garbage
  // (a sequential pass over every property array, 0.05 s at 1M faces)
  auto np = mrepair::parameters::collect_garbage(
      false, mrepair::parameters::remesh_feature_angle(feature_angle)
                 .number_of_iterations(iterations)
                 .protect_constraints(a.has("protect-features"))
                 .visitor(std::ref(printer)));
  mrepair::Remeshing_result r;
  const bool seq = a.has("sequential");
  double seconds = cli::timed([&] {
    if (a.has("edge-length")) {
      double L = a.get_double("edge-length", 0);
      r = seq ? mrepair::isotropic_remesh(mesh, L, np)
              : mrepair::isotropic_remesh<CGAL::Parallel_if_available_tag>(mesh, L, np);
    } else if (a.has("tolerance")) {
      double e = a.get_double("tolerance", 0);
      double lmin = a.get_double("min-edge-length", e);
      double lmax = a.get_double("max-edge-length", -1);
      auto np2 = mrepair::parameters::remesh_min_edge_length(lmin, np);
      if (lmax > 0) {
        auto np3 = mrepair::parameters::remesh_max_edge_length(lmax, np2);
        r = seq ? mrepair::adaptive_remesh(mesh, e, np3)
                : mrepair::adaptive_remesh<CGAL::Parallel_if_available_tag>(mesh, e, np3);
      } else {
        r = seq ? mrepair::adaptive_remesh(mesh, e, np2)
                : mrepair::adaptive_remesh<CGAL::Parallel_if_available_tag>(mesh, e, np2);
      }
    } else {
      long long n = a.get_int("faces", 0);
      if (n <= 0) throw cli::Usage_error("--faces must be positive");
      r = seq ? mrepair::remesh_to_face_count(mesh, std::size_t(n), np)
              : mrepair::remesh_to_face_count<CGAL::Parallel_if_available_tag>(mesh, std::size_t(n), np);
    }
  });
  report.add("input", a.positional[0]);
  report.add("output", a.positional[1]);
  r.to_report(report.section("remesh"));
  report.add("seconds", seconds);
  if (!mrepair::succeeded(r.status)) {
    cli::emit_report(a, report);
    return cli::fail(std::string("remesh: ") + mrepair::to_string(r.status) + ": " + r.message);
  }
  printer.start_phase("write");
  mrepair::Io_result w = mrepair::write_polygon_mesh(a.positional[1], mesh, cli::write_binary(a, io, a.positional[1]));
  printer.end_phase("write");
  if (!mrepair::succeeded(w.status))
    return cli::fail(a.positional[1] + ": " + mrepair::to_string(w.status) + " " + w.message);
  if (!cli::emit_report(a, report)) return 1;
  summary.set_status(r.status, r.message);
  summary.add_line("mode", r.mode + (r.mode == "adaptive" ? ", tolerance " + cli::summary_number(r.tolerance)
                                                          : ", edge length " + cli::summary_number(r.target_edge_length)));
  summary.add_sizes(r.faces_before, r.faces_after, vertices_in, r.vertices_after);
  if (r.feature_edges) summary.add_count("feature_edges", r.feature_edges);
  summary.add_closed(CGAL::is_closed(mesh) && r.faces_after > 0);
  summary.add_output(a.positional[1], w);
  summary.add_report(a);
  cli::print_summary(a, summary);
  return cli::exit_code(r.status);
}

cli::Registrar reg{{"remesh", "INPUT OUTPUT (--edge-length L | --tolerance E | --faces N) [options]",
                    "uniform or curvature-adaptive isotropic remeshing with features kept", run}};

} // namespace
