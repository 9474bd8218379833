// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// `mrepair repair INPUT OUTPUT`: the whole job for a mesh file: soup to
// manifold mesh (when the input is not one), gap closing (when asked), then
// the cleaning pipeline with the steps of the input's profile (a scan gets
// RameshCleaner, a CAD export or print model keeps its geometry and parts
// and gets its holes closed), then the validity check; inspection before and
// after, and a face accounting that reconciles.
#include "cli.h"
#include "cli_io.h"

#include <mrepair/clean_scan_mesh.h>
#include <mrepair/input_profile.h>
#include <mrepair/close_gaps.h>
#include <mrepair/inspect.h>
#include <mrepair/io.h>
#include <mrepair/stitch_soup.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <limits>

namespace {

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace MP = mrepair::parameters;
namespace cli = mrepair::cli;

const std::vector<cli::Option>& repair_options()
{
  static const std::vector<cli::Option> o = {
      {"profile", true, "auto|scan|cad: which cleaning steps apply (auto: decided from the mesh)"},
      {"close-gaps", true, "close boundary gaps narrower than T (model units; 0: off)"},
      {"merge-epsilon", true, "merge soup points closer than E before stitching (0)"},
      {"spike-angle", true, "dihedral angle (degrees) of a spiked vertex (relax_spikes default)"},
      {"max-hole", true, "holes with fewer boundary vertices are filled (100 scan, 500 cad)"},
      {"min-component", true, "components with fewer faces are removed (400)"},
      {"iterations", true, "cleaning iteration cap (5)"},
      {"no-self-intersections", false, "do not count self-intersections in the inspections"},
      {"binary", false, "write a binary file (PLY, STL)"}};
  return o;
}

void print_inspection(const char* title, const mrepair::Inspection_report& i, bool quiet)
{
  if (quiet) return;
  std::cerr << title << ": " << i.vertices << " vertices, " << i.faces << " faces; "
            << "non-finite " << i.non_finite_vertices << ", isolated " << i.isolated_vertices
            << ", non-manifold edges " << i.non_manifold_edges << ", non-manifold vertices "
            << i.non_manifold_vertices << ", components " << i.connected_components << " ("
            << i.small_components << " small), boundary loops " << i.boundary_loops << " ("
            << i.small_holes << " small), near-degenerate " << i.near_degenerate_faces
            << ", spiked " << i.spiked_vertices;
  if (i.self_intersections_counted)
    std::cerr << ", self-intersecting pairs " << i.self_intersecting_pairs;
  std::cerr << "\n";
}

int run_repair(int argc, char** argv)
{
  static const cli::Command self{"repair", "INPUT OUTPUT [options]", "", nullptr};
  cli::Arguments a = cli::parse(argc, argv, 1, repair_options(), 2, 2);
  if (a.has("help")) {
    cli::print_help(self, repair_options());
    return 0;
  }
  const double gap = a.get_double("close-gaps", 0.);
  const double merge = a.get_double("merge-epsilon", 0.);
  if (gap < 0. || merge < 0.) throw cli::Usage_error("--close-gaps and --merge-epsilon must be >= 0");
  const double spike = a.get_double("spike-angle", std::numeric_limits<double>::quiet_NaN());
  long long max_hole = a.get_int("max-hole", 100), min_comp = a.get_int("min-component", 400),
            iterations = a.get_int("iterations", 5);
  if (max_hole < 1 || min_comp < 1 || iterations < 0)
    throw cli::Usage_error("--max-hole and --min-component must be >= 1, --iterations >= 0");
  mrepair::Input_profile profile = mrepair::Input_profile::automatic;
  if (a.has("profile") && !mrepair::parse_input_profile(a.get("profile"), profile))
    throw cli::Usage_error("--profile must be auto, scan or cad");
  const bool quiet = a.has("quiet") || a.has("json");
  const bool count_si = !a.has("no-self-intersections");
  const std::size_t hole_n = static_cast<std::size_t>(max_hole),
                    comp_n = static_cast<std::size_t>(min_comp);
  cli::Progress_printer printer(!quiet);
  mrepair::Report report;

  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  mrepair::Io_result in;
  double t = cli::timed([&] { in = mrepair::read_polygon_soup(a.positional[0], points, polygons); });
  if (!quiet) std::cerr << "  read: " << std::to_string(t).substr(0, 6) << " s\n";
  if (in.status != mrepair::Status::ok && in.status != mrepair::Status::non_finite_input &&
      in.status != mrepair::Status::invalid_index)
    return cli::fail(in.message.empty() ? a.positional[0] + ": cannot read" : in.message);
  in.to_report(report.section("input"));

  const double inspect_spike = std::isnan(spike) ? 100. : spike;  // inspect's default is 100
  auto thresholds = MP::max_hole_vertices(
      hole_n, MP::min_component_faces(comp_n, MP::spike_angle(inspect_spike)));
  mrepair::Inspection_report before = mrepair::inspect_polygon_soup(points, polygons, thresholds);
  before.to_report(report.section("before"));
  print_inspection("before", before, quiet);

  // Face accounting over the whole job, in triangles: each stage adds what
  // it removed and added, by reason.
  std::size_t faces_in = 0;
  std::vector<std::pair<std::string, std::size_t>> removed, added;
  for (const auto& poly : polygons) faces_in += poly.size() >= 3 ? poly.size() - 2 : 1;

  // 1. A manifold mesh, built directly when the soup already is one.
  Mesh mesh;
  const bool direct = in.status == mrepair::Status::ok &&
                      mrepair::is_polygon_soup_a_polygon_mesh(polygons, points.size());
  if (direct) {
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);
    report.section("soup_to_manifold").add("needed", false);
  } else {
    mrepair::Soup_repair_result s;
    {
      mrepair::internal::Phase_scope<cli::Progress_printer> phase(printer, "soup_to_manifold");
      s = mrepair::polygon_soup_to_manifold_mesh(points, polygons, mesh,
                                                 MP::merge_epsilon(merge));
    }
    mrepair::Report& sr = report.section("soup_to_manifold");
    sr.add("needed", true);
    s.to_report(sr);
    removed.emplace_back("soup_invalid_index", s.removed_invalid_index);
    removed.emplace_back("soup_non_finite", s.removed_non_finite);
    removed.emplace_back("soup_degenerate", s.removed_degenerate_index + s.removed_collinear);
    removed.emplace_back("soup_duplicate", s.removed_duplicate);
    faces_in = s.faces_in;  // the soup stage's count (triangles of distinct corners) rules
    if (!mrepair::succeeded(s.status)) {
      cli::emit_report(a, report);
      return cli::fail("soup_to_manifold: " + std::string(mrepair::to_string(s.status)) +
                       (s.message.empty() ? "" : ": " + s.message));
    }
  }
  points.clear();
  polygons.clear();
  {
    std::string error;
    if (!cli::triangulate_polygons(mesh, report, error)) {
      cli::emit_report(a, report);
      return cli::fail(a.positional[0] + ": " + error);
    }
  }

  // 2. Gap closing, when asked.
  if (gap > 0.) {
    mrepair::Gap_closing_result g;
    const std::size_t f0 = static_cast<std::size_t>(faces(mesh).size());
    {
      mrepair::internal::Phase_scope<cli::Progress_printer> phase(printer, "close_gaps");
      g = mrepair::close_gaps(mesh, gap);
    }
    const std::size_t f1 = static_cast<std::size_t>(faces(mesh).size());
    // vertex-edge contractions split the faces they land on
    if (f1 > f0) added.emplace_back("close_gaps_splits", f1 - f0);
    if (f0 > f1) removed.emplace_back("close_gaps", f0 - f1);
    g.to_report(report.section("close_gaps"));
    if (!mrepair::succeeded(g.status)) {
      cli::emit_report(a, report);
      return cli::fail("close_gaps: " + std::string(mrepair::to_string(g.status)));
    }
  }

  // 3. The cleaning pipeline, with the steps of the input's profile.
  auto clean = [&](const auto& np) {
    return mrepair::clean_scan_mesh(
        mesh, MP::min_component_faces(
                  comp_n, MP::max_clean_iterations(
                              static_cast<std::size_t>(iterations),
                              MP::spike_angle(spike, MP::input_profile(profile, np))))
                  .visitor(std::ref(printer)));
  };
  // without --max-hole the profile picks the limit
  mrepair::Scan_cleaning_result c = a.has("max-hole")
                                        ? clean(MP::max_hole_vertices(hole_n))
                                        : clean(CGAL::parameters::default_values());
  c.to_report(report.section("clean"));
  if (!quiet)
    std::cerr << "profile: " << mrepair::to_string(c.profile.profile)
              << (c.profile.chosen_by_user ? " (chosen)" : "") << ": " << c.profile.reason << "\n";
  if (!mrepair::succeeded(c.status) && c.status != mrepair::Status::empty_input) {
    cli::emit_report(a, report);
    return cli::fail("clean: " + std::string(mrepair::to_string(c.status)) +
                     (c.message.empty() ? "" : ": " + c.message));
  }
  for (std::size_t i = 0; i < mrepair::number_of_clean_steps; ++i) {
    if (c.steps[i].faces_removed) removed.emplace_back(mrepair::clean_step_name(i), c.steps[i].faces_removed);
    if (c.steps[i].faces_added) added.emplace_back(mrepair::clean_step_name(i), c.steps[i].faces_added);
  }
  {
    const std::size_t faces_out = static_cast<std::size_t>(faces(mesh).size());
    std::size_t rm = 0, ad = 0;
    mrepair::Report& fa = report.section("face_accounting");
    fa.add("faces_in", faces_in);
    fa.add("faces_out", faces_out);
    mrepair::Report& rs = fa.section("removed");
    for (const auto& x : removed)
      if (x.second) { rs.add(x.first, x.second); rm += x.second; }
    mrepair::Report& as = fa.section("added");
    for (const auto& x : added)
      if (x.second) { as.add(x.first, x.second); ad += x.second; }
    fa.add("reconciles", faces_in + ad == faces_out + rm);
  }

  mrepair::Inspection_report after =
      mrepair::inspect(mesh, MP::max_hole_vertices(
                                 hole_n, MP::min_component_faces(
                                             comp_n, MP::spike_angle(
                                                         inspect_spike,
                                                         MP::count_self_intersections(count_si)))));
  after.to_report(report.section("after"));
  print_inspection("after", after, quiet);

  mrepair::Io_result out;
  t = cli::timed([&] { out = mrepair::write_polygon_mesh(a.positional[1], mesh, a.has("binary")); });
  if (!quiet) std::cerr << "  write: " << std::to_string(t).substr(0, 6) << " s\n";
  out.to_report(report.section("output"));
  if (!cli::emit_report(a, report)) return 1;
  if (out.status != mrepair::Status::ok)
    return cli::fail(out.message.empty() ? a.positional[1] + ": cannot write" : out.message);
  return cli::exit_code(c.status);
}

cli::Registrar reg{{"repair",
                    "INPUT OUTPUT [--profile auto|scan|cad] [--close-gaps T] [--max-hole N] [--min-component N]",
                    "soup to manifold, gap closing, cleaning by input profile, validity: the whole job",
                    run_repair}};

}  // namespace
