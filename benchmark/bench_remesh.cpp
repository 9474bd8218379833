// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Task "remesh": mrepair::isotropic_remesh (sequential and parallel) beside
// CGAL's PMP::isotropic_remeshing, same target length, same iterations, sharp
// edges from PMP::detect_sharp_edges given to CGAL as constrained edges (the
// same dihedral angle is mrepair's feature angle). Task "remesh_adaptive":
// adaptive_remesh beside remesh_to_face_count at the same face count (adaptive
// too since issue 52) and,
// built on CGAL 6, beside PMP::isotropic_remeshing with CGAL's
// Adaptive_sizing_field (curvature-adaptive after Dunyach et al. as well): the
// same tolerance, the same length clamps (mrepair's defaults: the tolerance and
// MREPAIR_REMESH_LMAX), the same iterations, the sharp edges at the same angle
// constrained.
//
// Environment: MREPAIR_REMESH_LENGTH (absolute L) or MREPAIR_REMESH_FACTOR
// (L = factor x mean input edge length, default 1), MREPAIR_REMESH_ITERATIONS
// (default 3), MREPAIR_REMESH_ANGLE (degrees, default 44),
// MREPAIR_REMESH_TOLERANCE (adaptive epsilon, default 0.001 x bbox diagonal),
// MREPAIR_REMESH_LMAX (adaptive largest length, default 0.05 x bbox diagonal),
// MREPAIR_REMESH_FACES (adaptive task: face count of the remesh_to_face_count
// run; default the adaptive result's). The sweep over tolerances is the task
// remesh-adaptive-sweep (bench_remesh_sweep.cpp).
#include "bench.h"

#include <mrepair/adaptive_remesh.h>
#include <mrepair/io.h>

#include <mrepair/internal/cgal_compat.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/version.h>
#if CGAL_VERSION_NR >= 1060000000
#include <CGAL/Polygon_mesh_processing/Adaptive_sizing_field.h>
#endif

#include <cmath>
#include <ctime>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace {
namespace remesh_task {  // a namespace of its own: the harness is a unity build

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

double env(const char* name, double fallback)
{
  const char* s = std::getenv(name);
  return s ? std::atof(s) : fallback;
}

Mesh load(const std::string& path)
{
  Mesh m;
  mrepair::Io_result r = mrepair::read_polygon_mesh(path, m);
  if (!mrepair::succeeded(r.status) || faces(m).size() == 0)
    throw std::runtime_error("cannot read " + path + ": " + r.message);
  if (!CGAL::is_triangle_mesh(m)) PMP::triangulate_faces(m);
  return m;
}

double mean_edge_length(const Mesh& m)
{
  double s = 0;
  for (auto e : edges(m)) s += std::sqrt(CGAL::squared_distance(m.point(source(e, m)), m.point(target(e, m))));
  return s / double(edges(m).size());
}

double bbox_diagonal(const Mesh& m)
{
  CGAL::Bbox_3 b = PMP::bbox(m);
  return std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                   CGAL::square(b.zmax() - b.zmin()));
}

double target_length(const Mesh& m)
{
  double L = env("MREPAIR_REMESH_LENGTH", 0);
  return L > 0 ? L : env("MREPAIR_REMESH_FACTOR", 1.0) * mean_edge_length(m);
}

// one-sided distance: max over the vertices, edge midpoints and centroids of `a` to `b`
double one_sided(const Mesh& a, const Mesh& b)
{
  using Tree = mrepair::internal::Aabb_tree<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>;
  Tree tree(faces(b).first, faces(b).second, b);
  tree.accelerate_distance_queries();
  double d = 0;
  for (auto f : faces(a)) {
    auto h = halfedge(f, a);
    const Point &p = a.point(source(h, a)), &q = a.point(target(h, a)),
                &r = a.point(target(next(h, a), a));
    for (const Point& x : {p, CGAL::midpoint(p, q), CGAL::centroid(p, q, r)})
      d = std::max(d, tree.squared_distance(x));
  }
  return std::sqrt(d);
}

// quality of the output and its distance to the input
void quality(const Mesh& out, const Mesh& in, mrepair::Report& r)
{
  double min_angle = 180;
  std::size_t small = 0, angles = 0;
  for (auto f : faces(out)) {
    auto h = halfedge(f, out);
    Point p[3] = {out.point(source(h, out)), out.point(target(h, out)),
                  out.point(target(next(h, out), out))};
    for (int i = 0; i < 3; ++i) {
      K::Vector_3 u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
      double c = u * v / std::sqrt(u.squared_length() * v.squared_length());
      double a = std::acos(std::max(-1., std::min(1., c))) * 180. / CGAL_PI;
      if (!std::isfinite(a)) a = 0;
      min_angle = std::min(min_angle, a);
      small += a < 30;
      ++angles;
    }
  }
  double dev = 0;
  for (auto v : vertices(out)) {
    int t = is_border(v, out) ? 4 : 6;
    dev += std::abs(int(degree(v, out)) - t);
  }
  r.add("faces", std::size_t(faces(out).size()));
  r.add("min_angle_deg", min_angle);
  r.add("share_angles_below_30", angles ? double(small) / angles : 0.);
  r.add("valence_deviation", vertices(out).size() ? dev / double(vertices(out).size()) : 0.);
  double h1 = one_sided(out, in), h2 = one_sided(in, out);
  r.add("hausdorff", std::max(h1, h2));
  r.add("hausdorff_rel_bbox", std::max(h1, h2) / bbox_diagonal(in));
  r.add("valid", CGAL::is_valid_polygon_mesh(out));
  // the input's count too: the remesher owes none only where the input had none
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> si_in, si_out;
  PMP::self_intersections<CGAL::Parallel_if_available_tag>(faces(in), in, std::back_inserter(si_in));
  PMP::self_intersections<CGAL::Parallel_if_available_tag>(faces(out), out, std::back_inserter(si_out));
  r.add("self_intersections_input", si_in.size());
  r.add("self_intersections", si_out.size());
}

template <typename Tag>
mrepair::bench::Measurement run_mrepair(const std::string& path)
{
  mrepair::bench::Measurement m;
  Mesh mesh = load(path);
  const Mesh input = mesh;
  const double L = target_length(mesh);
  const int it = int(env("MREPAIR_REMESH_ITERATIONS", 3));
  const double angle = env("MREPAIR_REMESH_ANGLE", 44);
  CGAL::Real_timer t;
  const std::clock_t c0 = std::clock();  // CPU time too: the machine may be shared
  t.start();
  mrepair::Remeshing_result res = mrepair::isotropic_remesh<Tag>(
      mesh, L, mrepair::parameters::remesh_feature_angle(angle).number_of_iterations(it));
  t.stop();
  const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
  m.seconds = t.time();
  m.result.add("cpu_seconds", cpu);
  m.status = mrepair::to_string(res.status);
  res.to_report(m.result);
  m.result.add("input_faces", std::size_t(faces(input).size()));
  quality(mesh, input, m.after);
  return m;
}

// CGAL's isotropic_remeshing of `mesh` with the sharp edges over the feature
// angle constrained: `remesh(mesh, np, result)` makes the call with its sizing
// (np: iterations and constrained edges), timed with the edge detection.
template <typename Remesh>
mrepair::bench::Measurement run_cgal_remeshing(Mesh mesh, int default_iterations, Remesh&& remesh)
{
  mrepair::bench::Measurement m;
  const Mesh input = mesh;
  const int it = int(env("MREPAIR_REMESH_ITERATIONS", default_iterations));
  const double angle = env("MREPAIR_REMESH_ANGLE", 44);
  auto eif = mesh.add_property_map<Mesh::Edge_index, bool>("e:sharp", false).first;
  CGAL::Real_timer t;
  const std::clock_t c0 = std::clock();  // CPU time too: the machine may be shared
  t.start();
  PMP::detect_sharp_edges(mesh, angle, eif);
  remesh(mesh, CGAL::parameters::number_of_iterations(it).edge_is_constrained_map(eif), m.result);
  t.stop();
  const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
  mesh.collect_garbage();
  m.seconds = t.time();
  m.result.add("cpu_seconds", cpu);
  m.result.add("iterations", it);
  m.result.add("input_faces", std::size_t(faces(input).size()));
  quality(mesh, input, m.after);
  return m;
}

mrepair::bench::Measurement run_cgal(const std::string& path)
{
  Mesh mesh = load(path);
  const double L = target_length(mesh);
  return run_cgal_remeshing(std::move(mesh), 3, [&](Mesh& tm, const auto& np, mrepair::Report& r) {
    PMP::isotropic_remeshing(faces(tm), L, tm, np);
    r.add("target_edge_length", L);
  });
}

// adaptive at tolerance eps
mrepair::bench::Measurement run_adaptive(const std::string& path)
{
  mrepair::bench::Measurement m;
  Mesh mesh = load(path);
  const Mesh input = mesh;
  const double eps = env("MREPAIR_REMESH_TOLERANCE", 0.001 * bbox_diagonal(mesh));
  const int it = int(env("MREPAIR_REMESH_ITERATIONS", 10));
  const double angle = env("MREPAIR_REMESH_ANGLE", 44);
  CGAL::Real_timer t;
  const std::clock_t c0 = std::clock();  // CPU time too: the machine may be shared
  t.start();
  const double lmax = env("MREPAIR_REMESH_LMAX", 0.05 * bbox_diagonal(mesh));
  auto res = mrepair::adaptive_remesh<CGAL::Parallel_if_available_tag>(
      mesh, eps,
      mrepair::parameters::remesh_max_edge_length(
          lmax, mrepair::parameters::remesh_feature_angle(angle).number_of_iterations(it)));
  t.stop();
  const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
  m.seconds = t.time();
  m.result.add("cpu_seconds", cpu);
  m.status = mrepair::to_string(res.status);
  res.to_report(m.result);
  quality(mesh, input, m.after);
  return m;
}

#if CGAL_VERSION_NR >= 1060000000
// CGAL 6's curvature-adaptive sizing field, on the adaptive run's settings
mrepair::bench::Measurement run_cgal_adaptive(const std::string& path)
{
  Mesh mesh = load(path);
  const double eps = env("MREPAIR_REMESH_TOLERANCE", 0.001 * bbox_diagonal(mesh));
  const double lmax = env("MREPAIR_REMESH_LMAX", 0.05 * bbox_diagonal(mesh));
  return run_cgal_remeshing(std::move(mesh), 10, [&](Mesh& tm, const auto& np, mrepair::Report& r) {
    PMP::Adaptive_sizing_field<Mesh> field(eps, std::make_pair(eps, lmax), faces(tm), tm);
    PMP::isotropic_remeshing(faces(tm), field, tm, np);
    r.add("tolerance", eps);
    r.add("min_edge_length", eps);
    r.add("max_edge_length", lmax);
  });
}
#endif

mrepair::bench::Measurement run_uniform_count(const std::string& path)
{
  mrepair::bench::Measurement m;
  Mesh mesh = load(path);
  const Mesh input = mesh;
  const int it = int(env("MREPAIR_REMESH_ITERATIONS", 10));
  const double angle = env("MREPAIR_REMESH_ANGLE", 44);
  std::size_t n = std::size_t(env("MREPAIR_REMESH_FACES", 0));
  if (n == 0) {  // the adaptive run's face count
    Mesh a = mesh;
    mrepair::adaptive_remesh<CGAL::Parallel_if_available_tag>(
        a, env("MREPAIR_REMESH_TOLERANCE", 0.001 * bbox_diagonal(mesh)),
        mrepair::parameters::remesh_max_edge_length(
            env("MREPAIR_REMESH_LMAX", 0.05 * bbox_diagonal(mesh)),
            mrepair::parameters::remesh_feature_angle(angle).number_of_iterations(it)));
    n = faces(a).size();
  }
  CGAL::Real_timer t;
  const std::clock_t c0 = std::clock();  // CPU time too: the machine may be shared
  t.start();
  auto res = mrepair::remesh_to_face_count<CGAL::Parallel_if_available_tag>(
      mesh, n, mrepair::parameters::remesh_feature_angle(angle).number_of_iterations(it));
  t.stop();
  const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
  m.seconds = t.time();
  m.result.add("cpu_seconds", cpu);
  m.status = mrepair::to_string(res.status);
  res.to_report(m.result);
  quality(mesh, input, m.after);
  return m;
}

mrepair::bench::Task_registrar reg{
    {"remesh",
     "uniform isotropic remeshing vs CGAL PMP::isotropic_remeshing (env MREPAIR_REMESH_*)",
     {{"mrepair::isotropic_remesh", run_mrepair<CGAL::Sequential_tag>},
      {"mrepair::isotropic_remesh<Parallel>", run_mrepair<CGAL::Parallel_if_available_tag>},
      {"CGAL PMP::isotropic_remeshing", run_cgal}},
     "scan-clean"}};

mrepair::bench::Task_registrar reg_adaptive{
    {"remesh_adaptive",
     "adaptive_remesh vs remesh_to_face_count at the same face count"
#if CGAL_VERSION_NR >= 1060000000
     " and CGAL 6's Adaptive_sizing_field"
#endif
     " (env MREPAIR_REMESH_*)",
     {{"mrepair::adaptive_remesh", run_adaptive},
      {"mrepair::remesh_to_face_count", run_uniform_count},
#if CGAL_VERSION_NR >= 1060000000
      {"CGAL Adaptive_sizing_field", run_cgal_adaptive},
#endif
     },
     "scan-clean"}};

} // namespace remesh_task
} // namespace
