// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// `mrepair inspect INPUT [--json] [--report F] [thresholds]`: counts the
// defects of a file read as a polygon soup; when the soup is a polygon mesh,
// also builds a Surface_mesh and reports what only a mesh has (its border
// halfedge cycles).
#include "cli.h"
#include "cli_io.h"
#include "summary.h"

#include <mrepair/compare_to_reference.h>
#include <mrepair/definitions.h>
#include <mrepair/inspect.h>
#include <mrepair/io.h>
#include <mrepair/locate_defects.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Epick;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace MP = mrepair::parameters;
namespace cli = mrepair::cli;

const std::vector<cli::Option> options = {
    {"spike-angle", true, "dihedral angle in degrees above which an edge is spiked (100)"},
    {"small-hole", true, "boundary loops with fewer edges are small holes (100)"},
    {"small-component", true, "components with fewer faces are small (400)"},
    {"t-junction-tolerance", true, "distance of a T-junction (default 1e-4 x bbox diagonal)"},
    {"no-self-intersections", false, "skip the self-intersection test"},
    {"html", true, "also write an HTML report FILE: the mesh with its defects (doc/studio.md)"},
    {"html-faces", true, "face budget of the mesh in the HTML report; larger ones are decimated (500000)"},
    {"reference", true, "also compare with FILE (the input of a repair): its vertices kept and lost, in \"reference\""},
    {"reference-tolerance", true, "a reference vertex this close to the surface is on it (default 1e-6 x its bbox diagonal)"},
};

int run(int argc, char** argv);

const cli::Command command{"inspect", "INPUT [--json] [--report FILE] [--reference FILE] [thresholds]",
                           "count the defects of a mesh or polygon soup", run};
cli::Registrar reg{command};

long long non_negative(const cli::Arguments& a, const std::string& name, long long fallback)
{
  long long v = a.get_int(name, fallback);
  if (v < 0) throw cli::Usage_error("--" + name + " expects a non-negative integer");
  return v;
}

int run(int argc, char** argv)
{
  cli::Arguments args = cli::parse(argc, argv, 1, options, 1, 1);
  if (args.has("help")) {
    cli::print_help(command, options);
    return 0;
  }
  cli::Summary summary("inspect");
  const double spike = args.get_double("spike-angle", mrepair::defaults::spike_angle);
  if (spike < 0 || spike > 180) throw cli::Usage_error("--spike-angle expects degrees in [0, 180]");
  const std::size_t hole = static_cast<std::size_t>(non_negative(args, "small-hole", static_cast<long long>(mrepair::defaults::max_hole_vertices)));
  const std::size_t comp = static_cast<std::size_t>(non_negative(args, "small-component", static_cast<long long>(mrepair::defaults::min_component_faces)));
  const double tol = args.get_double("t-junction-tolerance", -1.0); // < 0: relative default
  if (args.has("t-junction-tolerance") && tol < 0)
    throw cli::Usage_error("--t-junction-tolerance expects a non-negative distance");
  const bool self_intersections = !args.has("no-self-intersections");
  const std::string input = args.positional[0];
  // --html: the template is found before any work (doc/studio.md)
  std::string html_template;
  const std::optional<std::size_t> html_faces = args.optional_count("html-faces", 1);
  if (args.has("html")) {
    std::string error;
    html_template = cli::studio_template(error);
    if (html_template.empty()) {
      std::cerr << "mrepair inspect: " << error << "\n";
      return 2;
    }
  }

  cli::Progress_printer printer(args);
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  mrepair::Io_result io;
  printer.start_phase("read");
  io = mrepair::read_polygon_soup(input, points, polygons);
  printer.end_phase("read");
  if (io.status != mrepair::Status::ok && io.status != mrepair::Status::non_finite_input &&
      io.status != mrepair::Status::invalid_index)
    return cli::fail(io.message.empty() ? input + ": " + mrepair::to_string(io.status) : io.message);

  auto thresholds = [&](bool count_si) {
    return MP::spike_angle(spike, MP::max_hole_vertices(hole, MP::min_component_faces(comp,
           MP::t_junction_tolerance(tol, MP::count_self_intersections(count_si)))))
        .visitor(std::ref(printer));
  };

  mrepair::Report report;
  io.to_report(report.section("file"));
  // with --html the same inspection, listing where the defects are
  mrepair::Defect_locations located;
  if (args.has("html"))
    located = mrepair::locate_defects(points, polygons, thresholds(self_intersections));
  else
    located.report = mrepair::inspect_polygon_soup(points, polygons, thresholds(self_intersections));
  const mrepair::Inspection_report& soup = located.report;
  soup.to_report(report);

  // The mesh view: only when the polygons form a valid polygon mesh.
  mrepair::Report& mesh_section = report.section("mesh");
  const bool is_mesh = soup.invalid_polygons == 0 && !polygons.empty() &&
                       mrepair::is_polygon_soup_a_polygon_mesh(polygons, points.size());
  mesh_section.add("built", is_mesh);
  if (is_mesh) {
    Mesh mesh;
    printer.start_phase("build mesh");
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);
    printer.end_phase("build mesh");
    // the soup pass counted everything else (self-intersections included)
    mrepair::Inspection_report m = mrepair::inspect(mesh, thresholds(false));
    mesh_section.add("boundary_loops", m.boundary_loops);
    mesh_section.add("small_holes", m.small_holes);
  } else {
    mesh_section.add("reason", soup.invalid_polygons > 0
                                   ? "invalid polygons"
                                   : "not a manifold, consistently oriented polygon mesh");
  }
  // --reference: how much of the repair's input this output still holds
  mrepair::Status reference_status = mrepair::Status::ok;
  std::string reference_summary;  // the summary's line
  if (args.has("reference")) {
    const std::optional<double> reference_tolerance = args.optional_double("reference-tolerance");
    if (reference_tolerance && *reference_tolerance < 0)
      throw cli::Usage_error("--reference-tolerance expects a non-negative distance");
    std::vector<Point> reference_points;
    std::vector<std::vector<std::size_t>> reference_polygons;
    printer.start_phase("read reference");
    const mrepair::Io_result rio =
        mrepair::read_polygon_soup(args.get("reference"), reference_points, reference_polygons);
    printer.end_phase("read reference");
    if (rio.status != mrepair::Status::ok && rio.status != mrepair::Status::non_finite_input &&
        rio.status != mrepair::Status::invalid_index)
      return cli::fail(rio.message.empty() ? args.get("reference") + ": " + mrepair::to_string(rio.status)
                                           : rio.message);
    // the vertices of the model: the points its polygons use (all of them for a point set)
    std::vector<char> used(reference_points.size(), reference_polygons.empty() ? 1 : 0);
    for (const auto& polygon : reference_polygons)
      for (std::size_t i : polygon)
        if (i < used.size()) used[i] = 1;
    std::vector<Point> model_points;
    for (std::size_t i = 0; i < reference_points.size(); ++i)
      if (used[i]) model_points.push_back(reference_points[i]);
    printer.start_phase("compare with reference");
    const mrepair::Reference_comparison c = mrepair::compare_to_reference(
        model_points, points, polygons, MP::reference_tolerance(reference_tolerance));
    printer.end_phase("compare with reference");
    c.to_report(report.section("reference"));
    reference_status = c.status;
    reference_summary = std::to_string(c.vertices_lost) + " of " + std::to_string(c.vertices) +
                        " input vertices lost, farthest " + std::to_string(100. * c.max_distance_relative) +
                        "% of the diagonal away";
  }
  if (!cli::emit_report(args, report)) return 1;
  if (args.has("html")) {
    const cli::Studio_view view = cli::studio_view(mrepair::internal::indexed_faces_of_soup(points, polygons), located,
                                                   html_faces.value_or(500000), 100000);
    mrepair::Report settings;
    settings.add("spike_angle", spike);
    settings.add("small_hole", hole);
    settings.add("small_component", comp);
    settings.add("t_junction_tolerance", soup.t_junction_tolerance);
    settings.add("self_intersections", self_intersections);
    settings.add("preview_face_budget", html_faces.value_or(500000));
    settings.add("overlay_max_elements", std::size_t(100000));
    std::string title = input;
    const std::size_t slash = title.find_last_of("/\\");
    if (slash != std::string::npos) title = title.substr(slash + 1);
    // no "after": the inspection changes nothing
    const std::string error =
        cli::write_studio_report(html_template, args.get("html"), title, view, cli::Studio_view(), report, settings);
    if (!error.empty()) return cli::fail(error);
  }
  // the summary: what the file holds and each defect found, with its count
  summary.set_status(soup.status, soup.message);
  summary.add_line("input", cli::describe_file(input, io) + (is_mesh ? ", a polygon mesh" : ", a polygon soup"));
  summary.add_count("faces", soup.faces);
  summary.add_count("vertices", soup.vertices);
  summary.add_count("connected_components", soup.connected_components);
  summary.add_defects(soup);
  summary.add_closed(soup.closed);
  summary.add_intersection_free(soup);
  if (!reference_summary.empty()) summary.add_line("reference", reference_summary);
  summary.add_report(args);
  if (args.has("html")) summary.add_line("html", args.get("html"));
  cli::print_summary(args, summary);
  return soup.status == mrepair::Status::invalid_parameter ||
                 reference_status == mrepair::Status::invalid_parameter
             ? 1
             : 0;
}

} // namespace
