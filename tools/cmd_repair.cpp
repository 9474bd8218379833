// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// `mrepair repair INPUT OUTPUT`: the whole job for a mesh file: read, run
// `mrepair::repair_polygon_soup` (repair.h: soup to manifold mesh, gap
// closing, cleaning by input profile, validity, inspections, face
// accounting), print as it goes, write.
#include "cli.h"
#include "cli_io.h"
#include "repair_options.h"
#include "summary.h"

#include <mrepair/input_profile.h>
#include <mrepair/inspection_report.h>
#include <mrepair/io.h>
#include <mrepair/locate_defects.h>
#include <mrepair/repair.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <cmath>
#include <limits>
#include <optional>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_group.h>
#endif

namespace {

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace cli = mrepair::cli;

// repair's options and the HTML report's, which `batch` does not pass on
const std::vector<cli::Option>& repair_command_options()
{
  static const std::vector<cli::Option> o = [] {
    std::vector<cli::Option> all = cli::repair_options();
    all.push_back({"html", true, "also write an HTML report FILE: before/after meshes with their defects (doc/studio.md)"});
    all.push_back({"html-faces", true, "face budget of the meshes in the HTML report; larger ones are decimated (500000)"});
    return all;
  }();
  return o;
}

void print_inspection(const char* title, const mrepair::Inspection_report& i)
{
  std::cerr << title << ": " << i.vertices << " vertices, " << i.faces << " faces; "
            << "non-finite " << i.non_finite_vertices << ", isolated " << i.isolated_vertices
            << ", non-manifold edges " << i.non_manifold_edges << ", non-manifold vertices "
            << i.non_manifold_vertices << ", components " << i.connected_components << " ("
            << i.small_components << " small), boundary loops " << i.boundary_loops << " ("
            << i.small_holes << " small), near-degenerate " << i.near_degenerate_faces
            << ", spiked " << i.spiked_vertices;
  if (i.self_intersections_counted) {
    std::cerr << ", self-intersecting pairs " << i.self_intersecting_pairs;
    if (i.self_intersecting_pairs_touching)
      std::cerr << " (" << i.self_intersecting_pairs_touching << " only touching at coincident vertices)";
    std::cerr << ", intersection-free "
              << (i.self_intersecting_pairs == i.self_intersecting_pairs_touching ? "yes" : "no");
  }
  std::cerr << "\n";
}

int run_repair(int argc, char** argv)
{
  static const cli::Command self{"repair", "INPUT OUTPUT [options]", "", nullptr};
  cli::Arguments a = cli::parse(argc, argv, 1, repair_command_options(), 2, 2);
  if (a.has("help")) {
    cli::print_help(self, repair_command_options());
    return 0;
  }
  cli::Summary summary("repair");
  // Each option goes to the library as given or absent: the defaults are the
  // library's (definitions.h), and without --max-hole the profile picks the limit.
  const cli::Repair_option_values v = cli::parse_repair_options(a);
  const std::optional<double>& gap = v.gap, &merge = v.merge, &spike = v.spike;
  const std::optional<std::size_t>& max_hole = v.max_hole, &min_comp = v.min_component,
                                    &iterations = v.iterations;
  const std::optional<mrepair::Input_profile>& profile = v.profile;
  // --html: the template is found before any work (doc/studio.md)
  std::string html_template;
  const std::optional<std::size_t> html_faces = a.optional_count("html-faces", 1);
  if (a.has("html")) {
    std::string error;
    html_template = cli::studio_template(error);
    if (html_template.empty()) {
      std::cerr << "mrepair repair: " << error << "\n";
      return 2;
    }
  }
  const std::size_t face_budget = html_faces.value_or(500000), max_elements = 100000;
  // the lines on stderr as the job goes: --verbose (the default prints a summary at the end)
  const bool verbose = cli::verbosity(a) == cli::Verbosity::verbose;
  cli::Progress_printer printer(a);
  // Memory: the input inspection and the soup stage allocate and free
  // arrays of hundreds of MB at 10M faces; served from the heap they reuse
  // warm pages (1.1M fewer page faults at 10M). From the cleaning on, blocks
  // are mapped again and the heap is trimmed after each stage and step that
  // leaves more than `release_above` free, so that its fragments never add
  // to the job's peak (the cleaning's). On the noisy 10M-face scan:
  // 34.7 -> 33.7 s, peak 2,334 -> 2,277 MiB. A 1M-face job trims only once
  // more, after the output inspection (268 MB free then), before the write.
  cli::serve_large_blocks_from_heap(true);
  const std::size_t release_above = std::size_t(256) << 20;
  mrepair::Report report;

  // an all-triangle file (scans, STL, most exports) is read into fixed arrays
  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  std::vector<std::array<std::size_t, 3>> triangles;
  bool all_triangles = false;
  mrepair::Io_result in;
  double t = cli::timed([&] {
    in = mrepair::read_polygon_or_triangle_soup(a.positional[0], points, polygons, triangles,
                                                all_triangles);
  });
  if (verbose) std::cerr << "  read: " << std::to_string(t).substr(0, 6) << " s\n";
  if (in.status != mrepair::Status::ok && in.status != mrepair::Status::non_finite_input &&
      in.status != mrepair::Status::invalid_index)
    return cli::fail(in.message.empty() ? a.positional[0] + ": cannot read" : in.message);
  in.to_report(report.section("input"));
  report.section("input").add("seconds", t);

  Mesh& mesh = cli::kept_until_exit<Mesh>();
  // The output is final once the cleaning has succeeded (the inspection of
  // the output only reads it): it is written beside that inspection. On the
  // noisy 10M-face scan the write takes 0.46 s of a 33 s job.
  mrepair::Io_result out;
  double write_seconds = 0.;
  auto write_output = [&] {
    write_seconds = cli::timed(
        [&] { out = mrepair::write_polygon_mesh(a.positional[1], mesh, cli::write_binary(a, in, a.positional[1])); });
  };
  bool written_beside = false;
#ifdef CGAL_LINKED_WITH_TBB
  tbb::task_group writing;  // declared after `mesh`: an exception waits for the write
#endif
  auto start_write = [&](const mrepair::Repair_result& r) {
#ifdef CGAL_LINKED_WITH_TBB
    // a failed cleaning: the job ends without writing; once started, not again
    if (!r.output_final || written_beside) return;
    writing.run(write_output);
    written_beside = true;
#else
    (void)r;
#endif
  };
  auto after_stage = [&](const char* stage, const mrepair::Repair_result& r) {
    const std::string s = stage;
    if (s == "clean" || s == "resolve_intersections") start_write(r);
    if (s == "soup_to_manifold") {
      mrepair::cli::release_freed_memory();
      mrepair::cli::serve_large_blocks_from_heap(false);
      printer.release_memory_after_phases(release_above);
    } else if (s != "before") {  // the soup stage reuses the inspection's pages
      mrepair::cli::release_freed_memory_above(release_above);
    }
    if (!verbose) return;
    if (s == "before") print_inspection("before", r.before);
    if (s == "close_gaps") {
      const mrepair::Gap_closing_result& g = r.gaps;
      std::cerr << "close gaps: tolerance " << g.tolerance
                << (g.tolerance_estimated ? " (derived from the input)" : " (given)") << ", "
                << g.operations << " contractions, boundary edges " << g.boundary_edges_before << " -> "
                << g.boundary_edges_after << ", largest displacement " << g.max_displacement << "\n";
    }
    if (s == "clean")
      std::cerr << "profile: " << mrepair::to_string(r.clean.profile.profile)
                << (r.clean.profile.chosen_by_user ? " (chosen)" : "") << ": "
                << r.clean.profile.reason << "\n";
    if (s == "resolve_intersections") {
      const mrepair::Intersection_repair_result& x = r.intersections;
      std::cerr << "resolve intersections: crossing pairs " << x.crossing_pairs_before << " -> "
                << x.crossing_pairs_after << ", shells merged " << x.shells_merged << " into "
                << x.solids_from_unions << ", faces replaced locally " << x.local_faces_removed << " -> "
                << x.local_faces_added << ", holes filled after " << r.holes_after_intersections.holes_filled
                << "\n";
    }
    if (s == "after") print_inspection("after", r.after);
  };
  namespace MP = mrepair::parameters;
  // the thresholds of the job's inspections (repair.h), for the defects drawn
  auto inspect_thresholds = [&](bool count_pairs) {
    return MP::max_hole_vertices(
        max_hole.value_or(mrepair::defaults::max_hole_vertices),
        MP::min_component_faces(min_comp.value_or(mrepair::defaults::min_component_faces),
                                MP::spike_angle(spike.value_or(mrepair::defaults::spike_angle),
                                                MP::count_self_intersections(count_pairs))));
  };
  // --html: the input's defects, before the job takes the soup over
  cli::Studio_view html_before, html_after;
  mrepair::Inspection_report located_before;
  if (a.has("html")) {
    const double seconds = cli::timed([&] {
      const bool pairs = !a.has("no-self-intersections") && a.has("input-self-intersections");
      mrepair::Defect_locations d =
          all_triangles ? mrepair::locate_defects(points, triangles, inspect_thresholds(pairs))
                        : mrepair::locate_defects(points, polygons, inspect_thresholds(pairs));
      located_before = d.report;
      html_before = cli::studio_view(all_triangles ? mrepair::internal::indexed_faces_of_soup(points, triangles)
                                                   : mrepair::internal::indexed_faces_of_soup(points, polygons),
                                     d, face_budget, max_elements);
    });
    if (verbose) std::cerr << "  html: input defects: " << std::to_string(seconds).substr(0, 6) << " s\n";
  }
  const auto np =
      MP::input_profile(
          profile,
          MP::gap_tolerance(
              gap, MP::automatic_gap_tolerance(
                       !a.has("close-gaps"),  // --close-gaps 0 turns it off
                       MP::merge_epsilon(
                           merge,
                           MP::spike_angle(
                               spike,
                               MP::max_hole_vertices(
                                   max_hole,
                                   MP::min_component_faces(
                                       min_comp,
                                       MP::max_clean_iterations(
                                           iterations,
                                           MP::count_self_intersections(
                                               !a.has("no-self-intersections"),
                                               MP::count_input_self_intersections(
                                                   a.has("input-self-intersections"),
                                                   MP::resolve_intersections(
                                                       !a.has("no-resolve-intersections"),
                                                       MP::merge_overlapping_shells(
                                                           !a.has("keep-shells-separate"),
                                                           MP::after_stage(after_stage)))))))))))))
          .visitor(std::ref(printer));
  const mrepair::Repair_result r = all_triangles
                                       ? mrepair::repair_polygon_soup(points, triangles, mesh, np)
                                       : mrepair::repair_polygon_soup(points, polygons, mesh, np);
#ifdef CGAL_LINKED_WITH_TBB
  writing.wait();
#endif
  r.to_report(report);
  if (!r.failed_stage.empty()) {
    cli::emit_report(a, report);
    return cli::fail(r.message);  // it names the stage
  }

  if (!written_beside) write_output();
  if (verbose) std::cerr << "  write: " << std::to_string(write_seconds).substr(0, 6) << " s\n";
  out.to_report(report.section("output"));
  report.section("output").add("seconds", write_seconds);
  if (!cli::emit_report(a, report)) return 1;
  if (a.has("html")) {
    std::string error;
    const double seconds = cli::timed([&] {
      cli::check_located_counts(located_before, r.before, "input");
      const mrepair::Defect_locations d =
          mrepair::locate_defects(mesh, inspect_thresholds(r.after.self_intersections_counted));
      cli::check_located_counts(d.report, r.after, "output");
      html_after = cli::studio_view(mrepair::internal::indexed_faces_of_mesh(mesh), d, face_budget, max_elements);
      mrepair::Report settings;
      settings.add("profile", a.has("profile") ? a.get("profile") : std::string("auto"));
      settings.add("close_gaps", gap.value_or(std::numeric_limits<double>::quiet_NaN()));
      settings.add("merge_epsilon", merge.value_or(0.));
      settings.add("spike_angle", spike.value_or(mrepair::defaults::spike_angle));
      settings.add("max_hole", max_hole ? static_cast<double>(*max_hole) : std::numeric_limits<double>::quiet_NaN());
      settings.add("min_component", min_comp.value_or(mrepair::defaults::min_component_faces));
      settings.add("iterations", iterations ? static_cast<double>(*iterations) : std::numeric_limits<double>::quiet_NaN());
      settings.add("self_intersections", !a.has("no-self-intersections"));
      settings.add("input_self_intersections", a.has("input-self-intersections"));
      settings.add("resolve_intersections", !a.has("no-resolve-intersections"));
      settings.add("merge_overlapping_shells", !a.has("keep-shells-separate"));
      settings.add("preview_face_budget", face_budget);
      settings.add("overlay_max_elements", max_elements);
      std::string title = a.positional[0];
      const std::size_t slash = title.find_last_of("/\\");
      if (slash != std::string::npos) title = title.substr(slash + 1);
      error = cli::write_studio_report(html_template, a.get("html"), title, html_before, html_after, report, settings);
    });
    if (!error.empty()) return cli::fail(error);
    if (verbose) std::cerr << "  html: " << a.get("html") << ": " << std::to_string(seconds).substr(0, 6) << " s\n";
  }
  if (out.status != mrepair::Status::ok)
    return cli::fail(out.message.empty() ? a.positional[1] + ": cannot write" : out.message);
  summary.set_status(r.status, !r.message.empty() ? r.message : r.clean.message);
  summary.add_profile(std::string(mrepair::to_string(r.clean.profile.profile)) +
                      (r.clean.profile.chosen_by_user ? " (chosen)" : ""));
  summary.add_sizes(r.before.faces, r.after.faces, r.before.vertices, r.after.vertices);
  summary.add_changes(r.before, r.after);
  summary.add_closed(r.after.closed);
  summary.add_intersection_free(r.after);
  summary.add_output(a.positional[1], out);
  summary.add_report(a);
  if (a.has("html")) summary.add_line("html", a.get("html"));
  cli::print_summary(a, summary);
  if (r.status == mrepair::Status::empty_input)
    return cli::fail(a.positional[0] +
                     ": nothing to repair: no face is left once degenerate, duplicate and invalid "
                     "polygons are removed (the output is empty; the report counts them)");
  return cli::exit_code(r.status);
}

cli::Registrar reg{{"repair",
                    "INPUT OUTPUT [--profile auto|scan|cad] [--close-gaps T|0] [--max-hole N] [--min-component N]",
                    "soup to manifold, gap closing, cleaning by input profile, validity: the whole job",
                    run_repair}};

}  // namespace
