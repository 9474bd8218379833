// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// mrepair-generate: seeded, deterministic generator of defective meshes for
// tests and benchmarks, with a JSON manifest of everything it injected.
//
//   mrepair-generate scan --faces N --seed S --output OUT.ply [--input CLEAN.off] [--manifest M.json]
//                         [--clean-output BASE.ply] ...
//   mrepair-generate cad  --faces N --seed S --output OUT.stl|off|ply [--manifest M.json] [--gap G] ...
//   mrepair-generate cad  --input PART.off --faces N --seed S --output OUT [--manifest M.json] [--gap G]
//                         [--gap-fraction F] [--patches K] [--refine-fraction R]
//
// Identical arguments give byte-identical files on any machine (own uniform
// numbers from std::mt19937_64 bits, own sin/cos, no FP contraction).
#include "cli.h"
#include "generator/cad.h"
#include "generator/common.h"
#include "generator/scan.h"
#include "generator/surface.h"

#include <mrepair/io.h>

#include <chrono>
#include <fstream>
#include <iostream>

namespace {

using namespace mrepair::generator;
using mrepair::cli::Usage_error;

/// point type for io.h: three doubles with x(), y(), z().
struct P3
{
  double c[3];
  P3() : c{0, 0, 0} {}
  P3(double x, double y, double z) : c{x, y, z} {}
  double x() const { return c[0]; }
  double y() const { return c[1]; }
  double z() const { return c[2]; }
};

const char* kUsage =
    "usage: mrepair-generate scan --output OUT [--faces N] [--seed S] [--input CLEAN] [--manifest M.json]\n"
    "         [--spikes K] [--foldovers K] [--tunnels K] [--holes K] [--jagged-holes K] [--islands K]\n"
    "         [--slivers K] [--isolated K] [--nan K] [--nan-referenced K] [--pinned-danglers K]\n"
    "         [--noise A] [--clean-output BASE] [--ascii]\n"
    "       mrepair-generate cad --output OUT [--faces N] [--seed S] [--manifest M.json] [--gap G]\n"
    "         [--gap-fraction F] [--flipped K] [--duplicates K] [--degenerate K] [--fins K] [--pinched K]\n"
    "         [--ascii]\n"
    "       mrepair-generate cad --input PART --output OUT [--faces N] [--seed S] [--manifest M.json]\n"
    "         [--gap G] [--gap-fraction F] [--patches K] [--refine-fraction R] [--ascii]\n"
    "Writes OFF/OBJ/PLY/STL by extension (binary PLY/STL unless --ascii) and a JSON manifest.\n"
    "scan: --input is a clean triangle mesh, upsampled by 1-to-4 midpoint subdivision to about N\n"
    "      faces; without it, a procedural bumpy sphere of about N faces. --nan adds unreferenced NaN\n"
    "      vertices, --nan-referenced turns surface vertices into NaN. --pinned-danglers adds faces\n"
    "      hanging by one vertex in jagged holes (non-manifold vertices; default 0). --noise moves\n"
    "      vertices along the normal by up to A mean edge lengths before the defects (default 0).\n"
    "      --clean-output also writes the clean base surface (upsampled, before noise and defects),\n"
    "      the reference for distance measurements; the other outputs do not change.\n"
    "cad:  a box and a silo as 9 independently tessellated patches; --gap G: seam vertices perturbed\n"
    "      by up to G x bbox diagonal (default 1e-4), gap seams pulled apart by 1-3 G;\n"
    "      --gap-fraction: share of seams with a gap (default 0.3).\n"
    "      With --input: a clean part, upsampled by midpoint subdivision to about N faces, split\n"
    "      into patches (region growing up to faces/K faces, K = --patches, default 48; never across\n"
    "      a dihedral turn over 30 degrees), each patch with its own vertices; seam vertices moved\n"
    "      by up to G x diagonal (at most 1/4 of their faces' heights); on a share R of the seams\n"
    "      (default 0.5) one side's edges split at midpoints (T-junctions); a share F of the\n"
    "      patches (default 0.3) shifted rigidly by 1-3 G (cracks). No other defects.\n"
    "Counts default to values proportional to N.\n";

std::size_t count_option(const mrepair::cli::Arguments& a, const char* name, std::size_t fallback)
{
  long long v = a.get_int(name, static_cast<long long>(fallback));
  if (v < 0) throw Usage_error(std::string("--") + name + " must be >= 0");
  return static_cast<std::size_t>(v);
}

void write_soup(const std::string& path, const Tri_soup& s, bool binary)
{
  std::vector<P3> pts;
  pts.reserve(s.points.size());
  for (const Vec3& p : s.points) pts.emplace_back(p[0], p[1], p[2]);
  mrepair::Io_result r = mrepair::write_polygon_soup(path, pts, s.faces, binary);
  if (!mrepair::succeeded(r.status)) throw std::runtime_error(r.message);
}

void write_text(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary);
  out << text << '\n';
  if (!out.good()) throw std::runtime_error(path + ": cannot write the manifest");
}

std::string base_name(const std::string& path)
{
  auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

Tri_soup load_clean(const std::string& path)
{
  std::vector<P3> pts;
  std::vector<std::vector<std::uint32_t>> polys;
  mrepair::Io_result r = mrepair::read_polygon_soup(path, pts, polys);
  if (r.status != mrepair::Status::ok)
    throw std::runtime_error(r.message.empty() ? path + ": cannot read a clean mesh" : r.message);
  Tri_soup s;
  for (const P3& p : pts) s.points.push_back({p.c[0], p.c[1], p.c[2]});
  for (const auto& poly : polys)
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)  // fan-triangulate polygons
      s.faces.push_back({poly[0], poly[k], poly[k + 1]});
  if (s.faces.empty()) throw std::runtime_error(path + ": no faces");
  if (s.points.size() >= 0xffffffffu / 8) throw std::runtime_error(path + ": too many vertices");
  return s;
}

int run_scan(const mrepair::cli::Arguments& a)
{
  auto t0 = std::chrono::steady_clock::now();
  const std::size_t N = count_option(a, "faces", 20000);
  const std::uint64_t seed = static_cast<std::uint64_t>(a.get_int("seed", 1));
  const std::string out = a.get("output");
  if (out.empty()) throw Usage_error("scan needs --output");
  if (N < 500) throw Usage_error("--faces must be at least 500");

  Tri_soup s;
  std::string input = "procedural:bumpy_sphere";
  std::size_t subdivisions = 0, base_faces = 0;
  if (a.has("input")) {
    s = load_clean(a.get("input"));
    input = base_name(a.get("input"));
    base_faces = s.faces.size();
    // subdivide while it brings the count closer to N (in ratio)
    while (static_cast<double>(s.faces.size()) * 4 <= static_cast<double>(N) * 2 &&
           s.faces.size() * 4 < (std::size_t(1) << 30)) {
      subdivide(s);
      ++subdivisions;
    }
  } else {
    s = bumpy_sphere(bumpy_sphere_resolution(N));
    base_faces = s.faces.size();
  }
  const std::size_t upsampled_faces = s.faces.size(), upsampled_vertices = s.points.size();
  // The reference surface: written before the injector touches `s` (it draws
  // no random numbers here, so the defective output stays byte-identical).
  const std::string clean_out = a.get("clean-output");
  if (!clean_out.empty()) write_soup(clean_out, s, !a.has("ascii"));

  const double k = static_cast<double>(s.faces.size());
  Scan_options o;
  o.spikes = count_option(a, "spikes", 3 + static_cast<std::size_t>(k / 50000));
  o.foldovers = count_option(a, "foldovers", 3 + static_cast<std::size_t>(k / 50000));
  o.tunnels = count_option(a, "tunnels", 1 + static_cast<std::size_t>(k / 200000));
  o.holes = count_option(a, "holes", 3 + static_cast<std::size_t>(k / 100000));
  o.jagged_holes = count_option(a, "jagged-holes", 2 + static_cast<std::size_t>(k / 200000));
  o.islands = count_option(a, "islands", 3 + static_cast<std::size_t>(k / 100000));
  o.slivers = count_option(a, "slivers", 5 + static_cast<std::size_t>(k / 20000));
  o.isolated = count_option(a, "isolated", 3 + static_cast<std::size_t>(k / 200000));
  o.nan_isolated = count_option(a, "nan", 1 + static_cast<std::size_t>(k / 1000000));
  o.nan_referenced = count_option(a, "nan-referenced", 0);
  o.pinned_danglers = count_option(a, "pinned-danglers", 0);
  o.noise = a.get_double("noise", 0);
  if (o.pinned_danglers > o.jagged_holes)
    throw Usage_error("--pinned-danglers cannot exceed --jagged-holes");

  Scan_injector inj(s, seed, !a.has("input"));
  inj.add_noise(o.noise);
  inj.run(o);
  inj.finish();
  auto t1 = std::chrono::steady_clock::now();
  write_soup(out, s, !a.has("ascii"));
  auto t2 = std::chrono::steady_clock::now();

  // manifest
  std::map<std::string, std::size_t> counts;
  std::size_t open_patches = 0, straight_spikes = 0, faces_in_islands = 0, pinned = 0;
  for (const Defect& d : inj.defects()) {
    ++counts[d.kind];
    if (d.kind == "island" && d.variant == "open_patch") ++open_patches;
    if (d.kind == "island") faces_in_islands += d.faces.size();
    if (d.kind == "spike" && d.variant == "straight") ++straight_spikes;
    if (d.kind == "pinned_dangler") ++pinned;
  }
  auto c = [&](const char* kind) { return counts.count(kind) ? counts[kind] : std::size_t(0); };
  Json j;
  j.begin_object();
  j.value("generator", "mrepair-generate").value("format_version", 1).value("mode", "scan");
  j.value("seed", static_cast<long long>(seed)).value("input", input);
  j.begin_object("base");
  j.value("faces", base_faces).value("subdivisions", subdivisions);
  j.value("upsampled_faces", upsampled_faces).value("upsampled_vertices", upsampled_vertices);
  j.value("mean_edge_length", inj.mean_edge_length());
  j.value("boundary_edges", inj.base_boundary_edges()).value("components", inj.base_components());
  j.value("boundary_loops", static_cast<long long>(inj.base_boundary_loops()));
  j.value("noise_over_mean_edge", o.noise);
  if (!clean_out.empty()) j.value("clean_output", base_name(clean_out));
  j.end_object();
  j.begin_object("output").value("vertices", s.points.size()).value("faces", s.faces.size()).end_object();
  j.begin_object("requested");
  j.value("spike", o.spikes).value("foldover", o.foldovers).value("tunnel", o.tunnels);
  j.value("hole", o.holes).value("jagged_hole", o.jagged_holes).value("island", o.islands);
  j.value("sliver", o.slivers).value("isolated_vertex", o.isolated).value("nan_vertex", o.nan_isolated);
  j.value("nan_referenced_vertex", o.nan_referenced).value("pinned_dangler", o.pinned_danglers);
  j.end_object();
  j.begin_object("counts");
  for (const char* kind : {"spike", "foldover", "tunnel", "hole", "jagged_hole", "island", "sliver",
                           "isolated_vertex", "nan_vertex", "nan_referenced_vertex", "pinned_dangler"})
    j.value(kind, c(kind));
  j.value("spike_straight", straight_spikes).value("spike_leaning", c("spike") - straight_spikes);
  j.value("island_open_patch", open_patches).value("island_tetrahedron", c("island") - open_patches);
  j.end_object();
  // What an inspection of the output should find (given a clean, closed, manifold base).
  j.begin_object("expected");
  j.value("isolated_vertices", c("isolated_vertex") + c("nan_vertex"));
  j.value("non_finite_vertices", c("nan_vertex") + c("nan_referenced_vertex"));
  if (inj.base_boundary_loops() >= 0 && pinned == 0)
    j.value("boundary_loops", static_cast<std::size_t>(inj.base_boundary_loops()) + c("hole") +
                                  c("jagged_hole") + open_patches);
  // edge-connected components: a face hanging by a single vertex counts as its own
  j.value("connected_components", inj.base_components() + c("island") + pinned);
  j.value("faces_in_small_components", faces_in_islands);
  j.value("added_genus", c("tunnel"));
  j.value("non_manifold_vertices", pinned);
  j.end_object();
  j.begin_object("shortfalls");
  for (const auto& sf : inj.shortfalls()) j.value(sf.first.c_str(), sf.second);
  j.end_object();
  j.begin_array("defects");
  for (const Defect& d : inj.defects()) {
    j.begin_object();
    j.value("kind", d.kind).value("variant", d.variant).value("position", d.position);
    j.ids("vertices", d.vertices).ids("faces", d.faces);
    for (const auto& f : d.figures) j.value(f.first.c_str(), f.second);
    j.end_object();
  }
  j.end_array();
  j.end_object();
  if (a.has("manifest")) write_text(a.get("manifest"), j.str());
  auto t3 = std::chrono::steady_clock::now();
  auto sec = [](auto x, auto y) { return std::chrono::duration<double>(y - x).count(); };
  if (!a.has("quiet"))
    std::fprintf(stderr, "scan: %zu faces, %zu vertices, %zu defects; generate %.2fs, write %.2fs, total %.2fs\n",
                 s.faces.size(), s.points.size(), inj.defects().size(), sec(t0, t1), sec(t1, t2), sec(t0, t3));
  return 0;
}

int run_cad(const mrepair::cli::Arguments& a)
{
  auto t0 = std::chrono::steady_clock::now();
  Cad_options o;
  o.faces = count_option(a, "faces", 20000);
  const std::uint64_t seed = static_cast<std::uint64_t>(a.get_int("seed", 1));
  const std::string out = a.get("output");
  if (out.empty()) throw Usage_error("cad needs --output");
  if (o.faces < 200) throw Usage_error("--faces must be at least 200");
  o.perturbation = a.get_double("gap", 1e-4);
  o.gap_fraction = a.get_double("gap-fraction", 0.3);
  if (o.perturbation < 0 || o.perturbation > 0.01) throw Usage_error("--gap must be in [0, 0.01]");
  if (o.gap_fraction < 0 || o.gap_fraction > 1) throw Usage_error("--gap-fraction must be in [0, 1]");
  const std::size_t k = o.faces;
  o.flipped = count_option(a, "flipped", 3 + k / 50000);
  o.duplicates = count_option(a, "duplicates", 3 + k / 50000);
  o.degenerate = count_option(a, "degenerate", 4 + k / 50000);
  o.fins = count_option(a, "fins", 2 + k / 100000);
  o.pinched = count_option(a, "pinched", 2 + k / 100000);

  Cad_result res;
  Tri_soup s = make_cad_soup(o, seed, res);
  auto t1 = std::chrono::steady_clock::now();
  write_soup(out, s, !a.has("ascii"));
  auto t2 = std::chrono::steady_clock::now();

  std::map<std::string, std::size_t> counts;
  for (const Cad_defect& d : res.defects) ++counts[d.kind + "." + d.variant], ++counts[d.kind];
  auto c = [&](const std::string& kind) { return counts.count(kind) ? counts[kind] : std::size_t(0); };
  std::size_t gap_seams = 0, mismatched = 0;
  for (const Cad_seam& sm : res.seams) {
    gap_seams += sm.gap;
    mismatched += sm.segments_a != sm.segments_b;
  }
  Json j;
  j.begin_object();
  j.value("generator", "mrepair-generate").value("format_version", 1).value("mode", "cad");
  j.value("seed", static_cast<long long>(seed));
  j.value("bbox_diagonal", res.diagonal).value("perturbation", o.perturbation);
  j.value("perturbation_absolute", o.perturbation * res.diagonal);
  j.begin_object("output").value("vertices", s.points.size()).value("faces", s.faces.size()).end_object();
  j.begin_object("counts");
  j.value("patches", res.patch_names.size()).value("bodies", 2).value("seams", res.seams.size());
  j.value("seam_edges", res.seam_edges).value("mismatched_seams", mismatched);
  j.value("gap_seams", gap_seams).value("max_gap_width", res.max_gap);
  j.value("t_junction_vertices", res.t_junction_vertices);
  j.value("curved_seam_unmatched_vertices", res.curved_unmatched_vertices);
  for (const char* kind : {"flipped_face", "duplicate_face", "degenerate_face", "degenerate_face.collinear",
                           "degenerate_face.repeated_index", "fin", "pinched_vertex"})
    j.value(kind, c(kind));
  j.end_object();
  j.begin_array("patches");
  for (std::size_t i = 0; i < res.patch_names.size(); ++i) {
    j.begin_object().value("name", res.patch_names[i]).value("faces", res.patch_faces[i]);
    j.value("boundary_edges", res.patch_boundary_edges[i]).end_object();
  }
  j.end_array();
  j.begin_array("seams");
  for (const Cad_seam& sm : res.seams) {
    j.begin_object();
    j.value("patches", res.patch_names[sm.patch_a] + " | " + res.patch_names[sm.patch_b]);
    j.value("segments_a", sm.segments_a).value("segments_b", sm.segments_b);
    j.value("curved", sm.curved).value("gap", sm.gap).value("gap_width", sm.gap_width);
    j.value("unmatched_vertices", sm.unmatched);
    j.end_object();
  }
  j.end_array();
  j.begin_array("defects");
  for (const Cad_defect& d : res.defects) {
    j.begin_object();
    j.value("kind", d.kind).value("variant", d.variant).value("position", d.position);
    j.ids("vertices", d.vertices).ids("faces", d.faces);
    j.end_object();
  }
  j.end_array();
  j.end_object();
  if (a.has("manifest")) write_text(a.get("manifest"), j.str());
  auto t3 = std::chrono::steady_clock::now();
  auto sec = [](auto x, auto y) { return std::chrono::duration<double>(y - x).count(); };
  if (!a.has("quiet"))
    std::fprintf(stderr, "cad: %zu faces, %zu vertices, %zu seams; generate %.2fs, write %.2fs, total %.2fs\n",
                 s.faces.size(), s.points.size(), res.seams.size(), sec(t0, t1), sec(t1, t2), sec(t0, t3));
  return 0;
}

int run_cad_part(const mrepair::cli::Arguments& a)
{
  auto t0 = std::chrono::steady_clock::now();
  const std::size_t N = count_option(a, "faces", 20000);
  const std::uint64_t seed = static_cast<std::uint64_t>(a.get_int("seed", 1));
  const std::string out = a.get("output");
  if (out.empty()) throw Usage_error("cad needs --output");
  for (const char* opt : {"flipped", "duplicates", "degenerate", "fins", "pinched"})
    if (a.has(opt)) throw Usage_error(std::string("--") + opt + " is not available with --input");
  Cad_part_options o;
  o.perturbation = a.get_double("gap", 1e-4);
  o.gap_fraction = a.get_double("gap-fraction", 0.3);
  o.refine_fraction = a.get_double("refine-fraction", 0.5);
  o.patches = count_option(a, "patches", 48);
  if (o.perturbation < 0 || o.perturbation > 0.01) throw Usage_error("--gap must be in [0, 0.01]");
  if (o.gap_fraction < 0 || o.gap_fraction > 1) throw Usage_error("--gap-fraction must be in [0, 1]");
  if (o.refine_fraction < 0 || o.refine_fraction > 1) throw Usage_error("--refine-fraction must be in [0, 1]");
  if (o.patches < 1) throw Usage_error("--patches must be at least 1");

  Tri_soup s = load_clean(a.get("input"));
  const std::size_t base_faces = s.faces.size();
  std::size_t subdivisions = 0;
  while (static_cast<double>(s.faces.size()) * 4 <= static_cast<double>(N) * 2 &&
         s.faces.size() * 4 < (std::size_t(1) << 30)) {
    subdivide(s);
    ++subdivisions;
  }
  const std::size_t upsampled_faces = s.faces.size();
  Cad_part_result res;
  Tri_soup soup = make_cad_soup_from_part(s, o, seed, res);
  auto t1 = std::chrono::steady_clock::now();
  write_soup(out, soup, !a.has("ascii"));
  auto t2 = std::chrono::steady_clock::now();

  Json j;
  j.begin_object();
  j.value("generator", "mrepair-generate").value("format_version", 1).value("mode", "cad_part");
  j.value("seed", static_cast<long long>(seed)).value("input", base_name(a.get("input")));
  j.begin_object("base");
  j.value("faces", base_faces).value("subdivisions", subdivisions).value("upsampled_faces", upsampled_faces);
  j.value("boundary_edges", res.clean_boundary_edges);
  j.end_object();
  j.value("bbox_diagonal", res.diagonal).value("perturbation", o.perturbation);
  j.value("perturbation_absolute", res.perturbation_absolute);
  j.begin_object("output").value("vertices", soup.points.size()).value("faces", soup.faces.size()).end_object();
  j.begin_object("counts");
  j.value("patches", res.patches).value("patches_bounded_by_sharp_edges", res.sharp_patches);
  j.value("seams", res.seams).value("refined_seams", res.refined_seams);
  j.value("seam_edges", res.seam_edges).value("t_junction_vertices", res.t_junction_vertices);
  j.value("shifted_patches", res.shifted_patches).value("max_gap_width", res.max_gap);
  j.end_object();
  j.begin_object("expected");
  // a perfect gap closing leaves the part's own boundary
  j.value("boundary_edges_before", res.seam_edges + res.clean_boundary_edges);
  j.value("boundary_edges_after_closing", res.clean_boundary_edges);
  j.end_object();
  j.end_object();
  if (a.has("manifest")) write_text(a.get("manifest"), j.str());
  auto t3 = std::chrono::steady_clock::now();
  auto sec = [](auto x, auto y) { return std::chrono::duration<double>(y - x).count(); };
  if (!a.has("quiet"))
    std::fprintf(stderr,
                 "cad: %zu faces, %zu vertices, %zu patches, %zu seam edges, %zu T-junction vertices; "
                 "generate %.2fs, write %.2fs, total %.2fs\n",
                 soup.faces.size(), soup.points.size(), res.patches, res.seam_edges, res.t_junction_vertices,
                 sec(t0, t1), sec(t1, t2), sec(t0, t3));
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  try {
    std::vector<mrepair::cli::Option> options = {
        {"input", true, ""}, {"faces", true, ""}, {"seed", true, ""}, {"output", true, ""},
        {"manifest", true, ""}, {"ascii", false, ""},
        {"spikes", true, ""}, {"foldovers", true, ""}, {"tunnels", true, ""}, {"holes", true, ""},
        {"jagged-holes", true, ""}, {"islands", true, ""}, {"slivers", true, ""},
        {"isolated", true, ""}, {"nan", true, ""}, {"nan-referenced", true, ""},
        {"pinned-danglers", true, ""}, {"noise", true, ""}, {"clean-output", true, ""},
        {"gap", true, ""}, {"gap-fraction", true, ""}, {"flipped", true, ""}, {"duplicates", true, ""},
        {"degenerate", true, ""}, {"fins", true, ""}, {"pinched", true, ""},
        {"patches", true, ""}, {"refine-fraction", true, ""}};
    mrepair::cli::Arguments a = mrepair::cli::parse(argc, argv, 1, options, 1, 1);
    if (a.has("help")) {
      std::fputs(kUsage, stdout);
      return 0;
    }
    const std::string mode = a.positional[0];
    static const char* scan_only[] = {"spikes", "foldovers", "tunnels", "holes", "jagged-holes",
                                      "islands", "slivers", "isolated", "nan", "nan-referenced",
                                      "pinned-danglers", "noise", "clean-output"};
    static const char* cad_only[] = {"gap", "gap-fraction", "flipped", "duplicates", "degenerate",
                                     "fins", "pinched", "patches", "refine-fraction"};
    if (mode == "scan") {
      for (const char* o : cad_only)
        if (a.has(o)) throw Usage_error(std::string("--") + o + " is a cad option");
      return run_scan(a);
    }
    if (mode == "cad") {
      for (const char* o : scan_only)
        if (a.has(o)) throw Usage_error(std::string("--") + o + " is a scan option");
      if (a.has("input")) return run_cad_part(a);
      for (const char* o : {"patches", "refine-fraction"})
        if (a.has(o)) throw Usage_error(std::string("--") + o + " needs --input");
      return run_cad(a);
    }
    throw Usage_error("unknown mode '" + mode + "' (scan or cad)");
  } catch (const Usage_error& e) {
    std::fprintf(stderr, "mrepair-generate: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrepair-generate: %s\n", e.what());
    return 1;
  }
}
