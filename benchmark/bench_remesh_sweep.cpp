// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Task "remesh-adaptive-sweep" (issue 52): faces against approximation error
// over a range of tolerances, mrepair's adaptive_remesh beside CGAL 6's
// isotropic_remeshing with Adaptive_sizing_field (on CGAL 5.5 that variant
// reports "not available"), at equal settings: tolerance eps, edge lengths in
// [eps, MREPAIR_REMESH_LMAX], the same iterations, sharp edges over the same
// dihedral angle kept (CGAL: constrained edges from detect_sharp_edges, timed).
// A third variant is the face-count mode: mrepair::remesh_to_face_count at
// CGAL 6's face count of each tolerance (its own adaptive count on 5.5), so
// that the Hausdorff distances compare at equal face counts.
//
// Each tolerance is a section t1, t2, ... of the variant's result with
// tolerance_rel, faces, hausdorff_rel (both ways and each way), mean_distance_rel,
// min_angle_deg, share_angles_below_30, seconds. `mrepair-bench ... --json FILE`
// writes them for benchmark/plot_remesh_sweep.py.
//
// Environment: MREPAIR_SWEEP_TOLERANCES (comma-separated, x diagonal; default
// 0.0005,0.001,0.002,0.004,0.008), MREPAIR_REMESH_ITERATIONS (10),
// MREPAIR_REMESH_ANGLE (44), MREPAIR_REMESH_LMAX (0.05 x diagonal),
// MREPAIR_SWEEP_FACES (comma-separated face counts of the face-count mode,
// one per tolerance; default CGAL 6's counts, or mrepair's own on 5.5).
#include "bench.h"

#include <mrepair/adaptive_remesh.h>
#include <mrepair/io.h>

#include <mrepair/internal/cgal_compat.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/version.h>
#if CGAL_VERSION_NR >= 1060000000
#include <CGAL/Polygon_mesh_processing/Adaptive_sizing_field.h>
#endif

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace remesh_sweep_task {  // a namespace of its own: the harness is a unity build

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

double env_number(const char* name, double fallback)
{
  const char* s = std::getenv(name);
  return s ? std::atof(s) : fallback;
}

std::vector<double> env_list(const char* name, const std::string& fallback)
{
  const char* s = std::getenv(name);
  std::istringstream in(s ? std::string(s) : fallback);
  std::vector<double> out;
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(std::atof(item.c_str()));
  return out;
}

std::vector<double> sweep_tolerances()
{
  return env_list("MREPAIR_SWEEP_TOLERANCES", "0.0005,0.001,0.002,0.004,0.008");
}

Mesh load_triangle_mesh(const std::string& path)
{
  Mesh m;
  mrepair::Io_result r = mrepair::read_polygon_mesh(path, m);
  if (!mrepair::succeeded(r.status) || faces(m).size() == 0)
    throw std::runtime_error("cannot read " + path + ": " + r.message);
  if (!CGAL::is_triangle_mesh(m)) PMP::triangulate_faces(m);
  return m;
}

double diagonal(const Mesh& m)
{
  CGAL::Bbox_3 b = PMP::bbox(m);
  return std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                   CGAL::square(b.zmax() - b.zmin()));
}

struct Settings
{
  double diag = 1, lmax = 1, angle = 44;
  int iterations = 10;
};

Settings settings_for(const Mesh& m)
{
  Settings s;
  s.diag = diagonal(m);
  s.lmax = env_number("MREPAIR_REMESH_LMAX", 0.05 * s.diag);
  s.angle = env_number("MREPAIR_REMESH_ANGLE", 44);
  s.iterations = int(env_number("MREPAIR_REMESH_ITERATIONS", 10));
  return s;
}

using Tree = mrepair::internal::Aabb_tree<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>;

// distances from the samples of `a` (vertices, edge midpoints, centroids) to `b`: max and mean
std::pair<double, double> sampled_distance(const Mesh& a, const Tree& b)
{
  double worst = 0, sum = 0;
  std::size_t n = 0;
  for (auto f : faces(a)) {
    auto h = halfedge(f, a);
    const Point &p = a.point(source(h, a)), &q = a.point(target(h, a)),
                &r = a.point(target(next(h, a), a));
    for (const Point& x : {p, CGAL::midpoint(p, q), CGAL::centroid(p, q, r)}) {
      const double d = std::sqrt(b.squared_distance(x));
      worst = std::max(worst, d);
      sum += d;
      ++n;
    }
  }
  return {worst, n ? sum / double(n) : 0.};
}

// faces, distances both ways relative to the diagonal, angles
void add_quality(const Mesh& out, const Mesh& in, double diag, mrepair::Report& r)
{
  Tree in_tree(faces(in).first, faces(in).second, in), out_tree(faces(out).first, faces(out).second, out);
  in_tree.accelerate_distance_queries();
  out_tree.accelerate_distance_queries();
  const auto to_input = sampled_distance(out, in_tree), to_output = sampled_distance(in, out_tree);
  double min_angle = 180;
  std::size_t small = 0, angles = 0;
  for (auto f : faces(out)) {
    auto h = halfedge(f, out);
    const Point p[3] = {out.point(source(h, out)), out.point(target(h, out)),
                        out.point(target(next(h, out), out))};
    for (int i = 0; i < 3; ++i) {
      const K::Vector_3 u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
      const double c = u * v / std::sqrt(u.squared_length() * v.squared_length());
      double a = std::acos(std::max(-1., std::min(1., c))) * 180. / CGAL_PI;
      if (!std::isfinite(a)) a = 0;
      min_angle = std::min(min_angle, a);
      small += a < 30;
      ++angles;
    }
  }
  r.add("faces", std::size_t(faces(out).size()));
  r.add("hausdorff_rel", std::max(to_input.first, to_output.first) / diag);
  r.add("hausdorff_output_to_input_rel", to_input.first / diag);
  r.add("hausdorff_input_to_output_rel", to_output.first / diag);
  r.add("mean_distance_rel", 0.5 * (to_input.second + to_output.second) / diag);
  r.add("min_angle_deg", min_angle);
  r.add("share_angles_below_30", angles ? double(small) / double(angles) : 0.);
  r.add("valid", CGAL::is_valid_polygon_mesh(out));
}

std::string section_name(std::size_t i) { return "t" + std::to_string(i + 1); }

// runs `remesh(mesh, eps, report)` on a fresh copy per tolerance, timed
template <typename Remesh>
mrepair::bench::Measurement sweep(const std::string& path, Remesh&& remesh)
{
  mrepair::bench::Measurement m;
  const Mesh input = load_triangle_mesh(path);
  const Settings s = settings_for(input);
  const std::vector<double> tolerances = sweep_tolerances();
  m.result.add("input_faces", std::size_t(faces(input).size()));
  m.result.add("diagonal", s.diag);
  m.result.add("iterations", s.iterations);
  m.result.add("max_edge_length", s.lmax);
  for (std::size_t i = 0; i < tolerances.size(); ++i) {
    Mesh mesh = input;
    mrepair::Report& r = m.result.section(section_name(i));
    r.add("tolerance_rel", tolerances[i]);
    CGAL::Real_timer t;
    t.start();
    const std::string status = remesh(mesh, i, tolerances[i] * s.diag, s, r);
    t.stop();
    m.seconds += t.time();
    r.add("seconds", t.time());
    r.add("status", status);
    add_quality(mesh, input, s.diag, r);
  }
  return m;
}

std::string run_mrepair_adaptive(Mesh& mesh, double eps, const Settings& s)
{
  namespace MP = mrepair::parameters;
  auto res = mrepair::adaptive_remesh(
      mesh, eps,
      MP::remesh_max_edge_length(s.lmax, MP::remesh_feature_angle(s.angle).number_of_iterations(s.iterations)));
  return mrepair::to_string(res.status);
}

#if CGAL_VERSION_NR >= 1060000000
void run_cgal_adaptive(Mesh& mesh, double eps, const Settings& s)
{
  auto sharp = mesh.add_property_map<Mesh::Edge_index, bool>("e:sharp", false).first;
  PMP::detect_sharp_edges(mesh, s.angle, sharp);
  PMP::Adaptive_sizing_field<Mesh> field(eps, std::make_pair(eps, s.lmax), faces(mesh), mesh);
  PMP::isotropic_remeshing(
      faces(mesh), field, mesh,
      CGAL::parameters::number_of_iterations(s.iterations).edge_is_constrained_map(sharp));
  mesh.remove_property_map(sharp);
  mesh.collect_garbage();
}
#endif

mrepair::bench::Measurement sweep_mrepair(const std::string& path)
{
  return sweep(path, [](Mesh& mesh, std::size_t, double eps, const Settings& s, mrepair::Report&) {
    return run_mrepair_adaptive(mesh, eps, s);
  });
}

mrepair::bench::Measurement sweep_cgal(const std::string& path)
{
#if CGAL_VERSION_NR >= 1060000000
  return sweep(path, [](Mesh& mesh, std::size_t, double eps, const Settings& s, mrepair::Report&) {
    run_cgal_adaptive(mesh, eps, s);
    return std::string("ok");
  });
#else
  (void)path;
  mrepair::bench::Measurement m;
  m.status = "not available";  // Adaptive_sizing_field is new in CGAL 6.0
  m.result.add("cgal", CGAL_VERSION_STR);
  return m;
#endif
}

// face-count mode: remesh_to_face_count at CGAL 6's count of each tolerance
// (untimed CGAL run before), or at MREPAIR_SWEEP_FACES, or on 5.5 at
// mrepair's adaptive count
mrepair::bench::Measurement sweep_face_count(const std::string& path)
{
  const std::vector<double> given = env_list("MREPAIR_SWEEP_FACES", "");
  return sweep(path, [&](Mesh& mesh, std::size_t i, double eps, const Settings& s,
                         mrepair::Report& r) {
    std::size_t target = i < given.size() ? std::size_t(given[i]) : 0;
    if (target == 0) {
      // the timer of `sweep` runs: this reference run is taken out below
      CGAL::Real_timer reference;
      reference.start();
      Mesh other = mesh;
#if CGAL_VERSION_NR >= 1060000000
      run_cgal_adaptive(other, eps, s);
      r.add("target_from", "CGAL Adaptive_sizing_field");
#else
      run_mrepair_adaptive(other, eps, s);
      r.add("target_from", "mrepair::adaptive_remesh");
#endif
      target = faces(other).size();
      reference.stop();
      r.add("reference_seconds", reference.time());
    }
    r.add("target_faces", target);
    CGAL::Real_timer t;
    t.start();
    namespace MP = mrepair::parameters;
    auto res = mrepair::remesh_to_face_count(
        mesh, target,
        MP::remesh_max_edge_length(s.lmax, MP::remesh_feature_angle(s.angle).number_of_iterations(s.iterations)));
    t.stop();
    r.add("face_count_seconds", t.time());
    r.add("face_count_error", double(faces(mesh).size()) / double(target) - 1.);
    if (!res.message.empty()) r.add("face_count_message", res.message);
    return mrepair::to_string(res.status);
  });
}

mrepair::bench::Task_registrar reg_sweep{
    {"remesh-adaptive-sweep",
     "faces against Hausdorff over tolerances 0.0005..0.008 x diagonal: adaptive_remesh vs CGAL 6's "
     "Adaptive_sizing_field, and remesh_to_face_count at CGAL's counts (env MREPAIR_SWEEP_*, "
     "MREPAIR_REMESH_*)",
     {{"mrepair::adaptive_remesh", sweep_mrepair},
      {"CGAL Adaptive_sizing_field", sweep_cgal},
      {"mrepair::remesh_to_face_count", sweep_face_count}},
     "scan-clean"}};

} // namespace remesh_sweep_task
} // namespace
