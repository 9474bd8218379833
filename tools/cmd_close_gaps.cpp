// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// mrepair close-gaps INPUT OUTPUT --tolerance T [--relative] [--lambda L]
//     [--steps K | --to-distance D] [--save-sequence S | --load-sequence S]
//     [--profile-table P.csv [--profile-rows N]] [--box x0,y0,z0,x1,y1,z1] [--faces F]
//     [--keep-pinched] [--binary] [--report R.json]
//
// Without --steps, --to-distance, sequences or a profile: one `close_gaps()`.
// With them: a `Gap_closing_sequence` runs to its full closure (or replays the
// saved one), writes the profile table and the sequence, then steps back (or
// forward) to the point asked for.
#include "cli.h"
#include "cli_io.h"
#include "summary.h"

#include <mrepair/close_gaps.h>
#include <mrepair/io.h>
#include <mrepair/stitch_soup.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace {

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace MP = mrepair::parameters;
using mrepair::cli::Option;
using mrepair::cli::Usage_error;

const std::vector<Option>& options()
{
  static const std::vector<Option> o = {
      {"tolerance", true, "largest gap closed (absolute; a fraction of the bbox diagonal with --relative; "
                          "auto: estimated from the input's boundaries)"},
      {"relative", false, "--tolerance and --to-distance are relative to the bounding-box diagonal"},
      {"steps", true, "stop after K contractions (of the sequence within the tolerance)"},
      {"to-distance", true,
       "stop after the contractions within distance D (D <= tolerance, same unit as --tolerance)"},
      {"lambda", true, "merged position lambda*v + (1-lambda)*v' (default 0.5)"},
      {"save-sequence", true,
       "write every contraction within the tolerance to FILE (text format 'mrepair-gap-sequence 1', "
       "see gap_closing_sequence.h), whatever --steps/--to-distance keep"},
      {"load-sequence", true,
       "replay a sequence saved from the same input (its tolerance and lambda; the same --box/--faces); "
       "each contraction is checked, a mismatch is an error"},
      {"profile-table", true,
       "write CSV rows 'distance,contractions,boundary_edges,boundary_loops,boundary_length' over the "
       "sequence (each row: the mesh --to-distance DISTANCE gives)"},
      {"profile-rows", true, "about N rows in the profile table (default 20)"},
      {"box", true, "close gaps only between boundary vertices inside xmin,ymin,zmin,xmax,ymax,zmax"},
      {"faces", true,
       "close gaps only at the vertices of the faces listed in FILE (0-based indices of the "
       "triangulated input, separated by spaces or newlines, '#' starts a comment)"},
      {"keep-pinched", false, "do not split vertices left with several fans"},
      {"binary", false, "write a binary file (PLY, STL; default: the input's encoding for its own format, binary for another)"},
      {"ascii", false, "write an ASCII file"}};
  return o;
}

int run(int argc, char** argv);
mrepair::cli::Command command()
{
  return {"close-gaps",
          "INPUT OUTPUT (--tolerance T [--relative] | --load-sequence S) [--steps K | --to-distance D] "
          "[--save-sequence S] [--profile-table P.csv] [--box ...] [--faces F]",
          "close cracks, narrow gaps and T-junctions between boundaries (progressive "
          "vertex-edge contraction), stepping through the sequence of contractions",
          run};
}
mrepair::cli::Registrar reg{command()};

std::array<double, 6> parse_box(const std::string& s)
{
  std::array<double, 6> b{};
  std::stringstream ss(s);
  std::string item;
  int n = 0;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    double v = std::strtod(item.c_str(), &end);
    if (n == 6 || end == item.c_str() || *end != '\0' || !std::isfinite(v))
      throw Usage_error("--box expects six finite numbers xmin,ymin,zmin,xmax,ymax,zmax, got '" + s + "'");
    b[n++] = v;
  }
  if (n != 6)
    throw Usage_error("--box expects six finite numbers xmin,ymin,zmin,xmax,ymax,zmax, got '" + s + "'");
  for (int d = 0; d < 3; ++d)
    if (b[d] > b[d + 3]) throw Usage_error("--box: a minimum exceeds its maximum in '" + s + "'");
  return b;
}

// face indices of FILE; false with `error` on an unreadable file or a bad token
bool read_face_list(const std::string& path, std::vector<std::size_t>& out, std::string& error)
{
  std::ifstream in(path);
  if (!in) {
    error = "--faces: cannot open '" + path + "'";
    return false;
  }
  std::string line;
  std::size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ss(line);
    std::string w;
    while (ss >> w) {
      if (w.size() > 18 || w.find_first_not_of("0123456789") != std::string::npos) {
        error = "--faces: " + path + " line " + std::to_string(lineno) + ": '" + w +
                "' is not a face index (a non-negative integer)";
        return false;
      }
      out.push_back(std::size_t(std::strtoull(w.c_str(), nullptr, 10)));
    }
  }
  if (in.bad()) {
    error = "--faces: cannot read '" + path + "'";
    return false;
  }
  if (out.empty()) {
    error = "--faces: " + path + " lists no face";
    return false;
  }
  return true;
}

struct Boundary_figures
{
  std::size_t edges = 0, loops = 0;
  double length = 0;
};
Boundary_figures boundary_figures(const Mesh& m)
{
  Boundary_figures b;
  for (auto h : halfedges(m))
    if (is_border(h, m)) b.length += std::sqrt(CGAL::squared_distance(m.point(source(h, m)), m.point(target(h, m))));
  auto c = mrepair::internal::count_boundary(m);
  b.edges = c.first;
  b.loops = c.second;
  return b;
}

// the positions of the profile rows: the input, then about `rows` points spread
// over the sequence, each moved to the last contraction of its distance (the
// mesh --to-distance gives)
template <class Sequence>
std::vector<std::size_t> profile_positions(const Sequence& seq, std::size_t rows)
{
  std::vector<std::size_t> p{0};
  const std::size_t n = seq.size();
  for (std::size_t i = 0; i <= rows && n > 0; ++i) {
    std::size_t k = std::min(n, (i * n + rows / 2) / std::max<std::size_t>(rows, 1));
    p.push_back(seq.count_within(seq.distance_at(k)));
  }
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  return p;
}

int run(int argc, char** argv)
{
  mrepair::cli::Arguments a = mrepair::cli::parse(argc, argv, 1, options(), 2, 2);
  if (a.has("help")) {
    mrepair::cli::print_help(command(), options());
    return 0;
  }
  mrepair::cli::Summary summary("close-gaps");
  const bool verbose = mrepair::cli::verbosity(a) == mrepair::cli::Verbosity::verbose;
  const bool load = a.has("load-sequence");
  if (load && (a.has("tolerance") || a.has("relative") || a.has("lambda")))
    throw Usage_error("--load-sequence takes the tolerance and lambda from the file: drop --tolerance, "
                      "--relative and --lambda");
  if (!load && !a.has("tolerance")) throw Usage_error("close-gaps needs --tolerance T (or --load-sequence S)");
  if (a.has("steps") && a.has("to-distance")) throw Usage_error("give --steps or --to-distance, not both");
  if (load && a.has("save-sequence") && a.get("load-sequence") == a.get("save-sequence"))
    throw Usage_error("--save-sequence would overwrite the --load-sequence file");
  // --tolerance auto: estimate_gap_tolerance() on the input (doc/close_gaps.md)
  const bool auto_tolerance = a.has("tolerance") && a.get("tolerance") == "auto";
  if (auto_tolerance && a.has("relative")) throw Usage_error("--tolerance auto is absolute: drop --relative");
  double tol = auto_tolerance ? 0. : a.get_double("tolerance", 0);
  const long long steps = a.get_int("steps", -1);
  const double to_distance = a.get_double("to-distance", -1);
  const double lambda = a.get_double("lambda", 0.5);
  const long long rows = a.get_int("profile-rows", 20);
  if (tol < 0) throw Usage_error("--tolerance must be >= 0");
  if (lambda < 0 || lambda > 1) throw Usage_error("--lambda must be in [0,1]");
  if (a.has("steps") && steps < 0) throw Usage_error("--steps must be >= 0");
  if (a.has("to-distance") && to_distance < 0) throw Usage_error("--to-distance must be >= 0");
  if (a.has("to-distance") && !load && !auto_tolerance && to_distance > tol)
    throw Usage_error("--to-distance must not exceed --tolerance");
  if (rows < 1 || rows > 100000) throw Usage_error("--profile-rows must be in [1, 100000]");
  const bool has_box = a.has("box");
  const std::array<double, 6> box = has_box ? parse_box(a.get("box")) : std::array<double, 6>{};
  std::vector<std::size_t> face_list;
  if (a.has("faces")) {
    std::string error;
    if (!read_face_list(a.get("faces"), face_list, error)) return mrepair::cli::fail(error);
  }
  mrepair::Gap_sequence_file loaded;
  if (load) {
    std::ifstream in(a.get("load-sequence"), std::ios::binary);
    if (!in) return mrepair::cli::fail("--load-sequence: cannot open '" + a.get("load-sequence") + "'");
    std::string error;
    mrepair::Status s = loaded.read(in, error);
    if (s != mrepair::Status::ok)
      return mrepair::cli::fail("--load-sequence: " + a.get("load-sequence") + ": " + error);
    if (a.has("to-distance") && to_distance > loaded.tolerance)
      throw Usage_error("--to-distance must not exceed the tolerance of the sequence (" +
                        std::to_string(loaded.tolerance) + ")");
  }

  mrepair::Report report;
  Mesh& mesh = mrepair::cli::kept_until_exit<Mesh>();
  mrepair::Io_result io;
  const double read_seconds = mrepair::cli::timed([&] { io = mrepair::read_polygon_mesh(a.positional[0], mesh); });
  if (verbose) std::cerr << "  read: " << std::to_string(read_seconds).substr(0, 6) << " s\n";
  io.to_report(report.section("input"));
  report.section("input").add("seconds", read_seconds);
  if (io.status == mrepair::Status::non_manifold_input || io.status == mrepair::Status::invalid_index ||
      io.status == mrepair::Status::non_finite_input) {
    // not a valid polygon mesh: make it one first (what `mrepair soup` does)
    if (!a.has("quiet"))
      std::cerr << "mrepair: " << a.positional[0]
              << " is not a valid polygon mesh; repairing it as a soup first (see `mrepair soup`)\n";
    if (!face_list.empty() && !a.has("quiet"))
      std::cerr << "mrepair: --faces indices refer to the faces of the repaired mesh\n";
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
  mesh.collect_garbage();  // face indices of --faces are those of the compact mesh

  // the region: inside the box (when given) and on a listed face (when given)
  auto region = get(CGAL::dynamic_vertex_property_t<unsigned char>(), mesh);
  for (auto v : vertices(mesh)) put(region, v, 1);
  if (has_box)
    for (auto v : vertices(mesh)) {
      const K::Point_3& p = mesh.point(v);
      bool in = true;
      for (int d = 0; d < 3; ++d) in = in && p[d] >= box[d] && p[d] <= box[d + 3];
      put(region, v, in ? 1 : 0);
    }
  if (!face_list.empty()) {
    auto listed = get(CGAL::dynamic_vertex_property_t<unsigned char>(), mesh);
    for (auto v : vertices(mesh)) put(listed, v, 0);
    const std::size_t nf = mesh.number_of_faces();
    for (std::size_t i : face_list) {
      if (i >= nf)
        return mrepair::cli::fail("--faces: face index " + std::to_string(i) + " out of range (the mesh has " +
                                  std::to_string(nf) + " faces)");
      for (auto v : CGAL::vertices_around_face(halfedge(Mesh::Face_index(Mesh::size_type(i)), mesh), mesh))
        put(listed, v, 1);
    }
    for (auto v : vertices(mesh)) put(region, v, get(region, v) && get(listed, v) ? 1 : 0);
  }

  if (auto_tolerance) {
    mrepair::Gap_tolerance_estimate e;
    const double seconds = mrepair::cli::timed([&] { e = mrepair::estimate_gap_tolerance(mesh); });
    e.to_report(report.section("tolerance_estimate"));
    report.section("tolerance_estimate").add("seconds", seconds);
    tol = e.tolerance;
    if (verbose)
      std::cerr << "  tolerance (estimated): " << tol << " from " << e.candidates << " candidates\n";
    if (a.has("to-distance") && to_distance > tol)
      throw Usage_error("--to-distance must not exceed the estimated tolerance (" + std::to_string(tol) + ")");
  }
  const bool sequence = a.has("steps") || a.has("to-distance") || a.has("save-sequence") || load ||
                        a.has("profile-table");
  const bool fingerprint = load || a.has("save-sequence");
  const double tolerance = load ? loaded.tolerance : tol;
  const auto np = MP::gap_relative_tolerance(!load && a.has("relative"),
                  MP::gap_lambda(load ? loaded.lambda : lambda,
                  MP::gap_snap_distance(load ? loaded.snap : -1.0,
                  MP::gap_vertex_selection(region,
                  MP::gap_fingerprint_input(fingerprint)))));

  mrepair::cli::Progress_printer printer(a);
  const std::size_t faces_in = mesh.number_of_faces(), vertices_in = mesh.number_of_vertices();
  mrepair::Gap_closing_result r;
  mrepair::Report& rr = report.section("close_gaps");
  if (!sequence) {
    double seconds = mrepair::cli::timed([&] {
      r = mrepair::close_gaps(mesh, tolerance,
                              MP::gap_split_pinched_vertices(!a.has("keep-pinched"), np).visitor(std::ref(printer)));
    });
    r.to_report(rr);
    rr.add("seconds", seconds);
  } else {
    mrepair::Report& rs = report.section("sequence");
    auto t0 = std::chrono::steady_clock::now();
    mrepair::Gap_closing_sequence<Mesh> seq(mesh, tolerance, np);
    if (seq.status() != mrepair::Status::ok) {
      r = seq.result();
      r.to_report(rr);
      mrepair::cli::emit_report(a, report);
      return mrepair::cli::fail("close-gaps: " + std::string(mrepair::to_string(r.status)) + ": " + r.message);
    }
    const bool full = load || a.has("save-sequence") || a.has("profile-table");
    // the distance asked for, absolute
    double d_abs = seq.max_distance();
    if (a.has("to-distance"))
      d_abs = load || !a.has("relative") ? to_distance : (tol > 0 ? seq.max_distance() * (to_distance / tol) : 0.0);
    if (load) {
      std::string error;
      if (seq.replay(loaded, error) != mrepair::Status::ok)
        return mrepair::cli::fail("--load-sequence: " + a.get("load-sequence") + ": " + error);
    } else if (full) {
      seq.forward_to_distance(seq.max_distance());
    } else if (a.has("steps")) {
      seq.forward(std::size_t(steps));
    } else {
      seq.forward_to_distance(d_abs);
    }
    rs.add("contractions_recorded", seq.size());
    rs.add("seconds_to_closure", mrepair::cli::internal_io::seconds_since(t0));
    if (a.has("save-sequence")) {
      std::ofstream out(a.get("save-sequence"), std::ios::binary);
      mrepair::Status s = out ? seq.save(out) : mrepair::Status::io_error;
      out.close();
      if (s != mrepair::Status::ok || !out)
        return mrepair::cli::fail("--save-sequence: cannot write '" + a.get("save-sequence") + "'");
      rs.add("saved", a.get("save-sequence"));
    }
    if (a.has("profile-table")) {
      std::vector<std::size_t> at = profile_positions(seq, std::size_t(rows));
      std::vector<Boundary_figures> fig(at.size());
      for (std::size_t i = at.size(); i-- > 0;) {  // from the full closure back to the input
        seq.go_to(at[i]);
        fig[i] = boundary_figures(mesh);
      }
      std::ofstream out(a.get("profile-table"));
      out << "distance,contractions,boundary_edges,boundary_loops,boundary_length\n";
      char buf[200];
      for (std::size_t i = 0; i < at.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%.17g,%zu,%zu,%zu,%.9g\n", seq.distance_at(at[i]), at[i], fig[i].edges,
                      fig[i].loops, fig[i].length);
        out << buf;
      }
      out.close();
      if (!out) return mrepair::cli::fail("--profile-table: cannot write '" + a.get("profile-table") + "'");
      rs.add("profile_rows", at.size());
    }
    // the point asked for: K contractions or all within D, stepping back or forward
    std::size_t target = seq.position();
    if (a.has("steps"))
      target = std::min(seq.size(), std::size_t(steps));
    else if (a.has("to-distance"))
      target = seq.count_within(d_abs);
    else if (full)
      target = seq.size();
    seq.go_to(target);
    rs.add("position", seq.position());
    rs.add("distance", seq.current_distance());
    r = seq.result();
    if (r.status == mrepair::Status::ok && !a.has("keep-pinched") && r.pinched_vertices > 0) {
      r.pinched_vertices_split = CGAL::Polygon_mesh_processing::duplicate_non_manifold_vertices(mesh);
      r.pinched_vertices = 0;
      auto c = mrepair::internal::count_boundary(mesh);
      r.boundary_edges_after = c.first;
      r.boundary_loops_after = c.second;
    }
    r.to_report(rr);
    rr.add("seconds", mrepair::cli::internal_io::seconds_since(t0));
  }
  if (!mrepair::succeeded(r.status) && r.status != mrepair::Status::cancelled) {
    mrepair::cli::emit_report(a, report);
    return mrepair::cli::fail("close-gaps: " + std::string(mrepair::to_string(r.status)) + ": " +
                              r.message);
  }
  mrepair::Io_result out;
  // the writer numbers the elements left after the contractions' removals:
  // no collect_garbage() (a sequential pass over every property array)
  const double write_seconds =
      mrepair::cli::timed([&] {
        out = mrepair::write_polygon_mesh(a.positional[1], mesh, mrepair::cli::write_binary(a, io, a.positional[1]));
      });
  if (verbose) std::cerr << "  write: " << std::to_string(write_seconds).substr(0, 6) << " s\n";
  out.to_report(report.section("output"));
  report.section("output").add("seconds", write_seconds);
  if (!mrepair::succeeded(out.status)) return mrepair::cli::fail(out.message);
  if (!mrepair::cli::emit_report(a, report)) return 1;
  summary.set_status(r.status, r.message);
  summary.add_sizes(faces_in, mesh.number_of_faces(), vertices_in, mesh.number_of_vertices());
  summary.add_change("boundary_edges", r.boundary_edges_before, r.boundary_edges_after);
  summary.add_change("boundary_loops", r.boundary_loops_before, r.boundary_loops_after);
  if (r.pinched_vertices) summary.add_count("pinched_vertices", r.pinched_vertices);
  summary.add_line("contractions", std::to_string(r.operations) + " within " + mrepair::cli::summary_number(r.tolerance) +
                                       (r.tolerance_estimated ? " (estimated)" : ""));
  summary.add_closed(r.boundary_edges_after == 0 && mesh.number_of_faces() > 0);
  summary.add_output(a.positional[1], out);
  summary.add_report(a);
  mrepair::cli::print_summary(a, summary);
  return mrepair::cli::exit_code(r.status);
}

} // namespace
