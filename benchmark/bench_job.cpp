// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Tasks "job" and "job-soup": the whole command a user times, file in to file
// out, beside the whole CGAL 5.5 chain for the same job, file I/O included on
// both sides.
//   job:      `mrepair repair INPUT OUT.ply --binary` (defaults: the inspection
//             report before and after, self-intersections counted) vs
//             CGAL::IO::read_polygon_soup, repair_polygon_soup,
//             orient_polygon_soup, polygon_soup_to_polygon_mesh,
//             duplicate_non_manifold_vertices, remove_isolated_vertices,
//             keep_large_connected_components (400),
//             triangulate_refine_and_fair_hole (loops < 100 vertices),
//             experimental::remove_almost_degenerate_faces,
//             experimental::remove_self_intersections, write_polygon_mesh.
//   job-soup: `mrepair soup INPUT OUT.off` vs read_polygon_soup,
//             repair_polygon_soup, orient_polygon_soup,
//             polygon_soup_to_polygon_mesh, stitch_borders,
//             duplicate_non_manifold_vertices, write_polygon_mesh.
//   job-remesh: `mrepair remesh INPUT OUT.ply --binary --edge-length L
//             --iterations 3` (uniform, sharp edges over 44 degrees kept,
//             threads) vs read_polygon_mesh, detect_sharp_edges (44 degrees),
//             isotropic_remeshing (L, 3 iterations, sharp edges constrained),
//             write_polygon_mesh (binary PLY). L is the input's mean edge
//             length, computed untimed and given to both (MREPAIR_REMESH_FACTOR
//             scales it, MREPAIR_REMESH_ITERATIONS sets the iterations).
//   job-gaps: `mrepair close-gaps INPUT OUT.off --tolerance auto` vs
//             read_polygon_mesh, experimental::snap_borders (parallel if
//             available) + stitch_borders, write_polygon_mesh. The CGAL side
//             is given mrepair's estimated tolerance, computed untimed (a CGAL
//             user has to know it); MREPAIR_GAP_TOLERANCE (x diagonal) sets
//             both sides instead. Both outputs: boundary edges and
//             T-junctions, beside the input's boundary edges.
// The mrepair side runs the `mrepair` program as a child process (found
// beside the harness in the build tree, tools/mrepair, or in $MREPAIR_CLI);
// its phase breakdown is every "...seconds" field of its JSON report. The
// CGAL side runs in the harness's own forked child, timed from before the
// read to after the write; its phases are timed one by one. Both outputs are
// read back and inspected by the same code (mrepair::inspect), untimed.
#include "bench.h"
#include "cgal_chain.h"

#include <mrepair/close_gaps.h>
#include <mrepair/inspect.h>
#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/internal/Snapping/snap.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>

#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace job_task {  // a namespace of its own: the harness is a unity build

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Polygon = std::vector<std::size_t>;
namespace PMP = CGAL::Polygon_mesh_processing;

constexpr std::size_t kMinComponent = 400;  // as `mrepair repair` on a scan
constexpr std::size_t kMaxHole = 100;

// A scratch directory for the outputs, removed with its files on exit.
struct Scratch
{
  std::string dir;
  Scratch()
  {
    char tmpl[] = "/tmp/mrepair-bench-job-XXXXXX";
    if (mkdtemp(tmpl)) dir = tmpl;
  }
  ~Scratch()
  {
    if (!dir.empty()) std::system(("rm -rf '" + dir + "'").c_str());
  }
  std::string file(const std::string& name) const { return dir + "/" + name; }
};

std::string mrepair_program() { return mrepair::bench::build_tool("MREPAIR_CLI", "mrepair"); }

// Every number of a JSON document whose key ends in "seconds", with its
// dotted path ("clean.steps.relax_spikes.seconds"): the phase breakdown the
// program reported. A small reader of the subset our reports use.
class Seconds_reader
{
  const std::string& s_;
  std::size_t i_ = 0;
  mrepair::Report& out_;

  void skip() { while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_; }
  std::string string()
  {
    std::string r;
    ++i_;  // opening quote
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\') ++i_;
      if (i_ < s_.size()) r += s_[i_++];
    }
    ++i_;
    return r;
  }
  void value(const std::string& path, const std::string& key)
  {
    skip();
    if (i_ >= s_.size()) return;
    const char c = s_[i_];
    if (c == '{') {
      ++i_;
      for (skip(); i_ < s_.size() && s_[i_] != '}'; skip()) {
        if (s_[i_] == ',') { ++i_; continue; }
        const std::string k = string();
        skip();
        ++i_;  // ':'
        value(path.empty() ? k : path + "." + k, k);
      }
      ++i_;
    } else if (c == '[') {
      ++i_;
      for (skip(); i_ < s_.size() && s_[i_] != ']'; skip()) {
        if (s_[i_] == ',') { ++i_; continue; }
        value(path + "[]", key);
      }
      ++i_;
    } else if (c == '"') {
      string();
    } else {
      const std::size_t b = i_;
      while (i_ < s_.size() && s_[i_] != ',' && s_[i_] != '}' && s_[i_] != ']' &&
             !std::isspace(static_cast<unsigned char>(s_[i_])))
        ++i_;
      const std::string tok = s_.substr(b, i_ - b);
      const std::string suffix = "seconds";
      if (key.size() >= suffix.size() && key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0 &&
          path.find("[]") == std::string::npos) {
        char* end = nullptr;
        const double v = std::strtod(tok.c_str(), &end);
        if (end != tok.c_str()) out_.add(path, v);
      }
    }
  }

public:
  Seconds_reader(const std::string& s, mrepair::Report& out) : s_(s), out_(out) {}
  void run() { value("", ""); }
};

std::string slurp(const std::string& path)
{
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The table both sides get, from the same code, on the file each wrote.
void inspect_file(const std::string& path, mrepair::Report& r, bool self_intersections)
{
  Mesh m;
  mrepair::Io_result io = mrepair::read_polygon_mesh(path, m);
  if (io.status != mrepair::Status::ok) {
    r.add("read_back", mrepair::to_string(io.status));
    return;
  }
  const mrepair::Inspection_report i = mrepair::inspect(
      m, mrepair::parameters::count_self_intersections(self_intersections));
  r.add("faces", i.faces);
  r.add("valid", CGAL::is_valid_polygon_mesh(m));
  r.add("closed", CGAL::is_closed(m));
  r.add("components", i.connected_components);
  r.add("small_components", i.small_components);
  r.add("boundary_edges", i.boundary_edges);
  r.add("boundary_loops", i.boundary_loops);
  r.add("t_junctions", i.t_junctions);
  r.add("small_holes", i.small_holes);
  r.add("non_manifold_vertices", i.non_manifold_vertices);
  r.add("near_degenerate_faces", i.near_degenerate_faces);
  r.add("spiked_vertices", i.spiked_vertices);
  if (self_intersections) r.add("self_intersecting_pairs", i.self_intersecting_pairs);
}

mrepair::bench::Measurement run_mrepair(const std::string& input, const char* command,
                                        const char* output_name, bool binary,
                                        const std::vector<std::string>& extra = {})
{
  mrepair::bench::Measurement out;
  Scratch dir;
  const std::string output = dir.file(output_name), report = dir.file("report.json");
  std::vector<std::string> args = {mrepair_program(), command, input, output, "--report", report, "--quiet"};
  if (binary) args.push_back("--binary");
  args.insert(args.end(), extra.begin(), extra.end());
  const mrepair::bench::Child_run c = mrepair::bench::run_program(args);
  out.seconds = c.seconds;
  out.result.add("program", args[0]);
  out.result.add("exit_code", c.exit_code);
  out.result.add("process_peak_mb", c.peak_mb);
  if (c.exit_code != 0) {
    out.status = "exit " + std::to_string(c.exit_code);
    return out;
  }
  Seconds_reader(slurp(report), out.result.section("phases")).run();
  inspect_file(output, out.after, true);
  return out;
}

// CGAL has no guard against non-finite points or bad indices: a user must
// drop those polygons before the chain (timed, as it is part of the job):
// mrepair::bench::drop_unusable_polygons (cgal_chain.h).

// Times each phase into `r` as "<name>_s".
struct Phases
{
  mrepair::Report& r;
  template <typename F>
  auto operator()(const char* name, F&& f)
  {
    CGAL::Real_timer t;
    t.start();
    auto v = f();
    t.stop();
    r.add(std::string(name) + "_s", t.time());
    return v;
  }
};

mrepair::bench::Measurement run_cgal(const std::string& input, bool scan)
{
  mrepair::bench::Measurement out;
  Scratch dir;
  const std::string output = dir.file(scan ? "out.ply" : "out.off");
  Phases phase{out.result};
  CGAL::Real_timer total;
  total.start();
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  if (!phase("read_polygon_soup", [&] { return CGAL::IO::read_polygon_soup(input, pts, polys); })) {
    out.status = "read failed";
    return out;
  }
  out.result.add("polygons_dropped",
                 phase("drop_non_finite", [&] { return mrepair::bench::drop_unusable_polygons(pts, polys); }));
  phase("repair_polygon_soup", [&] {
    PMP::repair_polygon_soup(pts, polys);
    return 0;
  });
  out.result.add("oriented", phase("orient_polygon_soup", [&] { return PMP::orient_polygon_soup(pts, polys); }));
  Mesh m;
  const bool is_mesh = phase("polygon_soup_to_polygon_mesh", [&] {
    if (!PMP::is_polygon_soup_a_polygon_mesh(polys)) return false;
    PMP::polygon_soup_to_polygon_mesh(pts, polys, m);
    return true;
  });
  pts.clear();
  polys.clear();
  if (!is_mesh) {
    out.status = "not_a_mesh";
    return out;
  }
  if (!scan) out.result.add("stitched", phase("stitch_borders", [&] { return PMP::stitch_borders(m); }));
  out.result.add("non_manifold_duplicated", phase("duplicate_non_manifold_vertices", [&] {
                   return PMP::duplicate_non_manifold_vertices(m);
                 }));
  if (scan) {
    phase("remove_isolated_vertices", [&] { return PMP::remove_isolated_vertices(m); });
    phase("keep_large_connected_components",
          [&] { return PMP::keep_large_connected_components(m, kMinComponent); });
    out.result.add("holes_filled", phase("triangulate_refine_and_fair_hole", [&] {
      return mrepair::bench::fill_small_holes_with_cgal(m, kMaxHole).first;
    }));
    const double mean = phase("mean_edge_length", [&] {
      double sum = 0;
      for (auto e : edges(m))
        sum += std::sqrt(CGAL::squared_distance(m.point(source(e, m)), m.point(target(e, m))));
      return sum / double(std::max<std::size_t>(1, m.number_of_edges()));
    });
    out.result.add("remove_almost_degenerate_faces_ok", phase("remove_almost_degenerate_faces", [&] {
      return mrepair::bench::remove_almost_degenerate_faces_with_cgal(m, std::cos(160.0 / 180.0 * CGAL_PI),
                                                                      4.0, 0.5 * mean);
    }));
    out.result.add("remove_self_intersections_ok", phase("remove_self_intersections", [&] {
      return PMP::experimental::remove_self_intersections(m);
    }));
    m.collect_garbage();
  }
  const bool written = phase("write_polygon_mesh", [&] {
    return scan ? CGAL::IO::write_polygon_mesh(output, m, CGAL::parameters::use_binary_mode(true))
                : CGAL::IO::write_polygon_mesh(output, m, CGAL::parameters::stream_precision(17));
  });
  total.stop();
  out.seconds = total.time();
  if (!written) out.status = "write failed";
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  out.result.add("process_peak_mb", ru.ru_maxrss / 1024.0);
  m.clear();
  inspect_file(output, out.after, true);
  return out;
}

// The gap tolerance of job-gaps: MREPAIR_GAP_TOLERANCE x the bounding-box
// diagonal when set, else 0 (mrepair estimates it).
double relative_gap_tolerance()
{
  const char* s = std::getenv("MREPAIR_GAP_TOLERANCE");
  return s ? std::atof(s) : 0.0;
}

// boundary edges of the input, untimed: the "before" of both sides
void input_boundary(const std::string& input, mrepair::Report& before)
{
  Mesh m;
  if (mrepair::read_polygon_mesh(input, m).status != mrepair::Status::ok) return;
  before.add("boundary_edges", mrepair::internal::count_boundary(m).first);
}

mrepair::bench::Measurement run_mrepair_gaps(const std::string& input)
{
  const double rel = relative_gap_tolerance();
  std::vector<std::string> extra = {"--tolerance", "auto"};
  if (rel > 0) extra = {"--tolerance", std::to_string(rel), "--relative"};
  mrepair::bench::Measurement out = run_mrepair(input, "close-gaps", "out.off", false, extra);
  input_boundary(input, out.before);
  return out;
}

mrepair::bench::Measurement run_cgal_gaps(const std::string& input)
{
  mrepair::bench::Measurement out;
  Scratch dir;
  const std::string output = dir.file("out.off");
  Phases phase{out.result};
  CGAL::Real_timer total;
  total.start();
  Mesh m;
  if (!phase("read_polygon_mesh", [&] { return CGAL::IO::read_polygon_mesh(input, m); })) {
    out.status = "read failed";
    return out;
  }
  // the tolerance a CGAL user would have to supply: not part of the job
  CGAL::Real_timer untimed;
  untimed.start();
  double tol = relative_gap_tolerance();
  if (tol > 0) {
    const CGAL::Bbox_3 b = PMP::bbox(m);
    tol *= std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                     CGAL::square(b.zmax() - b.zmin()));
  } else {
    tol = mrepair::estimate_gap_tolerance(m).tolerance;
  }
  untimed.stop();
  out.result.add("tolerance", tol);
  CGAL::Constant_property_map<Mesh::Vertex_index, double> tolerance_map(tol);
  out.result.add("snapped", phase("snap_borders", [&] {
    return PMP::experimental::snap_borders<CGAL::Parallel_if_available_tag>(m, tolerance_map);
  }));
  out.result.add("stitched", phase("stitch_borders", [&] { return PMP::stitch_borders(m); }));
  const bool written = phase("write_polygon_mesh", [&] {
    return CGAL::IO::write_polygon_mesh(output, m, CGAL::parameters::stream_precision(17));
  });
  total.stop();
  out.seconds = total.time() - untimed.time();
  if (!written) out.status = "write failed";
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  out.result.add("process_peak_mb", ru.ru_maxrss / 1024.0);
  m.clear();
  input_boundary(input, out.before);
  inspect_file(output, out.after, false);
  return out;
}

// job-remesh: the target length both sides get and the iterations
struct Remesh_job_settings
{
  double length = 0;
  int iterations = 3;
  double feature_angle = 44;
};

Remesh_job_settings remesh_job_settings(const std::string& input)
{
  Remesh_job_settings s;
  Mesh m;
  if (!CGAL::IO::read_polygon_mesh(input, m) || m.number_of_edges() == 0) return s;
  double sum = 0;
  for (auto e : edges(m)) sum += std::sqrt(CGAL::squared_distance(m.point(source(e, m)), m.point(target(e, m))));
  const char* factor = std::getenv("MREPAIR_REMESH_FACTOR");
  s.length = (factor ? std::atof(factor) : 1.0) * sum / double(m.number_of_edges());
  if (const char* it = std::getenv("MREPAIR_REMESH_ITERATIONS")) s.iterations = std::atoi(it);
  return s;
}

std::string exact_decimal(double v)
{
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

mrepair::bench::Measurement run_mrepair_remesh(const std::string& input)
{
  const Remesh_job_settings s = remesh_job_settings(input);  // untimed
  if (s.length <= 0) throw std::runtime_error("cannot read " + input + " as a polygon mesh");
  mrepair::bench::Measurement out = run_mrepair(
      input, "remesh", "out.ply", true,
      {"--edge-length", exact_decimal(s.length), "--iterations", std::to_string(s.iterations),
       "--feature-angle", exact_decimal(s.feature_angle)});
  out.result.add("target_length", s.length);
  return out;
}

mrepair::bench::Measurement run_cgal_remesh(const std::string& input)
{
  const Remesh_job_settings s = remesh_job_settings(input);  // untimed
  if (s.length <= 0) throw std::runtime_error("cannot read " + input + " as a polygon mesh");
  mrepair::bench::Measurement out;
  Scratch dir;
  const std::string output = dir.file("out.ply");
  Phases phase{out.result};
  CGAL::Real_timer total;
  total.start();
  Mesh m;
  if (!phase("read_polygon_mesh", [&] { return CGAL::IO::read_polygon_mesh(input, m); })) {
    out.status = "read failed";
    return out;
  }
  auto sharp = m.add_property_map<Mesh::Edge_index, bool>("e:sharp", false).first;
  phase("detect_sharp_edges", [&] {
    PMP::detect_sharp_edges(m, s.feature_angle, sharp);
    return 0;
  });
  phase("isotropic_remeshing", [&] {
    PMP::isotropic_remeshing(faces(m), s.length, m,
                             CGAL::parameters::number_of_iterations(s.iterations).edge_is_constrained_map(sharp));
    return 0;
  });
  m.collect_garbage();
  const bool written = phase("write_polygon_mesh", [&] {
    return CGAL::IO::write_polygon_mesh(output, m, CGAL::parameters::use_binary_mode(true));
  });
  total.stop();
  out.seconds = total.time();
  if (!written) out.status = "write failed";
  out.result.add("target_length", s.length);
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  out.result.add("process_peak_mb", ru.ru_maxrss / 1024.0);
  m.clear();
  inspect_file(output, out.after, false);
  return out;
}

mrepair::bench::Task_registrar job{
    {"job",
     "whole command with file I/O: `mrepair repair` vs the CGAL soup + cleaning chain with its "
     "experimental stages (run `mrepair` from $MREPAIR_CLI or <build>/tools)",
     {{"mrepair repair (process)",
       [](const std::string& p) { return run_mrepair(p, "repair", "out.ply", true); }},
      {"CGAL chain + experimental (process)", [](const std::string& p) { return run_cgal(p, true); }}},
     "scan"}};

mrepair::bench::Task_registrar job_soup{
    {"job-soup",
     "whole command with file I/O: `mrepair soup` vs the CGAL soup chain (repair, orient, build, "
     "stitch, split non-manifold vertices)",
     {{"mrepair soup (process)",
       [](const std::string& p) { return run_mrepair(p, "soup", "out.off", false); }},
      {"CGAL chain (process)", [](const std::string& p) { return run_cgal(p, false); }}},
     "cad-soup"}};

mrepair::bench::Task_registrar job_remesh{
    {"job-remesh",
     "whole command with file I/O: `mrepair remesh --edge-length L` vs CGAL read_polygon_mesh, "
     "detect_sharp_edges, isotropic_remeshing, write_polygon_mesh (L: the input's mean edge length)",
     {{"mrepair remesh (process)", run_mrepair_remesh}, {"CGAL isotropic_remeshing (process)", run_cgal_remesh}},
     "scan-clean"}};

mrepair::bench::Task_registrar job_gaps{
    {"job-gaps",
     "whole command with file I/O: `mrepair close-gaps --tolerance auto` vs CGAL read_polygon_mesh, "
     "snap_borders + stitch_borders (at mrepair's estimated tolerance, or MREPAIR_GAP_TOLERANCE x "
     "diagonal for both), write_polygon_mesh",
     {{"mrepair close-gaps (process)", run_mrepair_gaps},
      {"CGAL snap+stitch (process)", run_cgal_gaps}},
     "cad-soup"}};

} // namespace job_task
}  // namespace
