// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// `mrepair clean INPUT OUTPUT`: the RameshCleaner pipeline on a manifold
// triangle mesh, one progress line per step.
#include "cli.h"
#include "cli_io.h"
#include "summary.h"

#include <mrepair/clean_scan_mesh.h>
#include <mrepair/input_profile.h>
#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/iterator.h>

#include <optional>
#include <sstream>

namespace {

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace MP = mrepair::parameters;
namespace cli = mrepair::cli;

const std::vector<cli::Option>& clean_options()
{
  static const std::vector<cli::Option> o = {
      {"profile", true, "scan|cad|auto: the steps that apply (scan: this command's purpose)"},
      {"spike-angle", true, "dihedral angle (degrees) of a spiked vertex (default of relax_spikes: 100)"},
      {"max-hole", true, "holes with fewer boundary vertices are filled (100; 500 for cad)"},
      {"min-component", true, "components with fewer faces are removed (400)"},
      {"iterations", true, "iteration cap (5)"},
      {"boundary-angle", true, "dihedral angle (degrees) of a bad boundary vertex (120)"},
      {"density", true, "hole patch edge length / hole border mean edge length (1)"},
      {"fair", false, "fair the hole patches"},
      {"only", true, "run only these steps (comma-separated; see below)"},
      {"skip", true, "skip these steps (comma-separated): remove_degenerate_vertices, "
                     "relax_spikes, remove_unrelaxable_spikes, clean_boundaries, "
                     "remove_small_components, fill_small_holes, fix_near_degenerate_faces, "
                     "relax_spikes_again, ensure_valid_mesh"},
      {"binary", false, "write a binary file (PLY, STL; default: the input's encoding for its own format, binary for another)"},
      {"ascii", false, "write an ASCII file"}};
  return o;
}

// the border cycles of `m`, for the summary
std::size_t count_boundary_loops(const Mesh& m)
{
  std::vector<char> seen(m.num_halfedges(), 0);
  std::size_t loops = 0;
  for (Mesh::Halfedge_index h : halfedges(m)) {
    if (!is_border(h, m) || seen[h.idx()]) continue;
    ++loops;
    for (Mesh::Halfedge_index g : CGAL::halfedges_around_face(h, m)) seen[g.idx()] = 1;
  }
  return loops;
}

unsigned parse_steps(const std::string& list)
{
  unsigned m = 0;
  std::stringstream ss(list);
  std::string name;
  while (std::getline(ss, name, ',')) {
    if (name.empty()) continue;
    unsigned s = mrepair::parse_clean_step(name);
    if (s == 0) throw cli::Usage_error("unknown step '" + name + "'");
    m |= s;
  }
  return m;
}

int run_clean(int argc, char** argv)
{
  static const cli::Command self{"clean", "INPUT OUTPUT [options]", "", nullptr};
  cli::Arguments a = cli::parse(argc, argv, 1, clean_options(), 2, 2);
  if (a.has("help")) {
    cli::print_help(self, clean_options());
    return 0;
  }
  cli::Summary summary("clean");
  mrepair::Input_profile profile = mrepair::Input_profile::scan;
  if (a.has("profile") && !mrepair::parse_input_profile(a.get("profile"), profile))
    throw cli::Usage_error("--profile must be scan, cad or auto");
  unsigned mask = profile == mrepair::Input_profile::cad ? unsigned(mrepair::clean_steps_cad)
                                                         : unsigned(mrepair::clean_step_all);
  if (a.has("only")) mask = parse_steps(a.get("only"));
  if (a.has("skip")) mask &= ~parse_steps(a.get("skip"));
  // given or absent: the defaults are the library's (definitions.h); without
  // --max-hole the profile picks the hole limit
  const std::optional<double> spike = a.optional_double("spike-angle"),
                              boundary_angle = a.optional_double("boundary-angle"),
                              density = a.optional_double("density");
  const std::optional<std::size_t> max_hole = a.optional_count("max-hole", 0),
                                   min_comp = a.optional_count("min-component", 0),
                                   iterations = a.optional_count("iterations", 0);
  const bool verbose = cli::verbosity(a) == cli::Verbosity::verbose;
  cli::Progress_printer printer(a);
  mrepair::Report report;

  // Read a soup (NaN points are accepted: the pipeline removes them), then
  // build the mesh if the polygons form a manifold mesh.
  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  mrepair::Io_result in;
  double t_read = cli::timed([&] { in = mrepair::read_polygon_soup(a.positional[0], points, polygons); });
  if (in.status != mrepair::Status::ok && in.status != mrepair::Status::non_finite_input)
    return cli::fail(in.message.empty() ? a.positional[0] + ": cannot read" : in.message);
  if (!mrepair::is_polygon_soup_a_polygon_mesh(polygons, points.size()))
    return cli::fail(a.positional[0] +
                     ": not a manifold, consistently oriented polygon mesh; run `mrepair repair`");
  Mesh& mesh = cli::kept_until_exit<Mesh>();
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  points.clear();
  polygons.clear();
  if (verbose) std::cerr << "  read: " << std::to_string(t_read).substr(0, 6) << " s\n";
  std::string error;
  if (!cli::triangulate_polygons(mesh, report, error)) {
    cli::emit_report(a, report);
    return cli::fail(a.positional[0] + ": " + error);
  }

  // the boundary of the input, for the summary (a pass over the halfedges)
  const std::size_t boundary_loops_before = count_boundary_loops(mesh);
  auto run = [&](const auto& steps_np) {
    return mrepair::clean_scan_mesh(
        mesh, MP::input_profile(
                  profile, MP::max_hole_vertices(
                               max_hole,
                               MP::min_component_faces(
                                   min_comp, MP::max_clean_iterations(
                                                 iterations, MP::boundary_dihedral_angle(
                                                                 boundary_angle,
                                                                 MP::hole_density_factor(
                                                                     density,
                                                                     MP::fair_hole_patches(
                                                                         a.has("fair"),
                                                                         MP::spike_angle(spike, steps_np))))))))
                  .visitor(std::ref(printer)));
  };
  // with auto and no step list, the profile picks the steps
  const bool profile_picks = profile == mrepair::Input_profile::automatic && !a.has("only") &&
                             !a.has("skip");
  mrepair::Scan_cleaning_result r = profile_picks ? run(CGAL::parameters::default_values())
                                                  : run(MP::clean_steps(mask));
  in.to_report(report.section("input"));
  r.to_report(report.section("clean"));
  if (!mrepair::succeeded(r.status)) {
    cli::emit_report(a, report);
    return cli::fail("clean: " + std::string(mrepair::to_string(r.status)) +
                     (r.message.empty() ? "" : ": " + r.message));
  }
  mrepair::Io_result out;
  double t_write =
      cli::timed([&] { out = mrepair::write_polygon_mesh(a.positional[1], mesh, cli::write_binary(a, in, a.positional[1])); });
  if (verbose) std::cerr << "  write: " << std::to_string(t_write).substr(0, 6) << " s\n";
  out.to_report(report.section("output"));
  if (!cli::emit_report(a, report)) return 1;
  if (out.status != mrepair::Status::ok)
    return cli::fail(out.message.empty() ? a.positional[1] + ": cannot write" : out.message);
  summary.set_status(r.status, r.message);
  summary.add_profile(std::string(mrepair::to_string(r.profile.profile)) + (r.profile.chosen_by_user ? " (chosen)" : ""));
  summary.add_sizes(r.faces_before, r.faces_after, r.vertices_before, r.vertices_after);
  // what the steps did (the cleaning counts no defects before and after)
  const std::size_t boundary_loops_after = count_boundary_loops(mesh);
  summary.add_change("boundary_loops", boundary_loops_before, boundary_loops_after);
  if (r.holes.holes_filled) summary.add_count("holes_filled", r.holes.holes_filled);
  if (r.components.components_removed) summary.add_count("small_components_removed", r.components.components_removed);
  for (std::size_t i = 0; i < mrepair::number_of_clean_steps; ++i) {
    const std::string step = mrepair::clean_step_name(i);
    if (step == "remove_small_components" || step == "fill_small_holes" || r.steps[i].changes == 0) continue;
    summary.add_count(step + "_changes", r.steps[i].changes);
  }
  summary.add_closed(boundary_loops_after == 0 && r.faces_after > 0);
  summary.add_output(a.positional[1], out);
  summary.add_report(a);
  cli::print_summary(a, summary);
  return cli::exit_code(r.status);
}

cli::Registrar reg{{"clean", "INPUT OUTPUT [--spike-angle A] [--max-hole N] [--min-component N] "
                             "[--iterations K] [--only STEP,..] [--skip STEP,..]",
                    "clean a scanned manifold mesh (RameshCleaner pipeline)", run_clean}};

}  // namespace
