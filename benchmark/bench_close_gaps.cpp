// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Task "close-gaps": mrepair::close_gaps beside CGAL 5.5 PMP::stitch_borders
// (exactly coincident borders only) and the experimental
// PMP::experimental::snap_borders (vertex-vertex and vertex-edge snapping within
// a tolerance) followed by stitch_borders, on the same input and tolerance.
//
// Reported for each: boundary edges before/after, seam edges closed (%),
// boundary loops, T-junctions left (boundary vertices within the tolerance of
// the inside of a boundary edge not incident to them), non-manifold vertices,
// validity, and the largest vertex-to-surface distance between input and output
// (both ways, an estimate of the Hausdorff distance).
//
// Each variant also reports `pipeline_seconds`: the whole job as a program does
// it (read and triangulate the input, close, write an OFF file), beside
// `seconds` (the call alone); and `boundary_edges` before and after for both
// sides. The input must be a valid polygon mesh (run `mrepair soup` on a soup).
//
// Environment: MREPAIR_GAP_TOLERANCE (relative to the bbox diagonal, default 5e-4);
// MREPAIR_GAP_PIPELINE_ONLY=1 skips the inspection and distance estimate and
// reports only the boundary edges before and after, so that a variant run
// alone (`--only`) is the job as a whole process, to time from outside.
#include "bench.h"

#include <mrepair/close_gaps.h>
#include <mrepair/internal/close_gaps/boundary_grid.h>
#include <mrepair/io.h>

#include <mrepair/internal/cgal_compat.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/internal/Snapping/snap.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace {
namespace close_gaps_task {  // a namespace of its own: the harness is a unity build

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

Mesh load(const std::string& path)
{
  Mesh m;
  mrepair::Io_result r = mrepair::read_polygon_mesh(path, m);
  if (!mrepair::succeeded(r.status) || faces(m).size() == 0)
    throw std::runtime_error("cannot read " + path + ": " + r.message);
  if (!CGAL::is_triangle_mesh(m)) PMP::triangulate_faces(m);
  return m;
}

using Clock = std::chrono::steady_clock;

// ends the whole-job timing begun at `t0` (before the load): writes `mesh` as
// OFF to a scratch file and records `pipeline_seconds`
void end_pipeline(Mesh& mesh, Clock::time_point t0, double untimed, mrepair::bench::Measurement& m)
{
  const std::string path = "/tmp/mrepair_bench_close_gaps_" + std::to_string(getpid()) + ".off";
  mesh.collect_garbage();
  mrepair::Io_result w = mrepair::write_polygon_mesh(path, mesh);
  const double s = std::chrono::duration<double>(Clock::now() - t0).count() - untimed;
  std::remove(path.c_str());
  if (!mrepair::succeeded(w.status)) throw std::runtime_error("cannot write " + path + ": " + w.message);
  m.result.add("pipeline_seconds", s);
}

double diagonal(const Mesh& m)
{
  CGAL::Bbox_3 b = PMP::bbox(m);
  return std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                   CGAL::square(b.zmax() - b.zmin()));
}

double tolerance(const Mesh& m)
{
  const char* s = std::getenv("MREPAIR_GAP_TOLERANCE");
  return (s ? std::atof(s) : 5e-4) * diagonal(m);
}

// boundary vertices within `tol` of the inside of a non-incident boundary edge
std::size_t t_junctions(const Mesh& m, double tol)
{
  using P3 = std::array<double, 3>;
  auto p3 = [&](Mesh::Vertex_index v) {
    const Point& p = m.point(v);
    return P3{p.x(), p.y(), p.z()};
  };
  CGAL::Bbox_3 b = PMP::bbox(m);
  mrepair::internal::Segment_grid grid;
  std::vector<Mesh::Halfedge_index> border;
  double len = 0;
  for (auto h : halfedges(m))
    if (is_border(h, m)) {
      border.push_back(h);
      len += std::sqrt(CGAL::squared_distance(m.point(source(h, m)), m.point(target(h, m))));
    }
  if (border.empty()) return 0;
  grid.init({b.xmin(), b.ymin(), b.zmin()}, std::max(tol, len / border.size()));
  for (std::size_t i = 0; i < border.size(); ++i)
    grid.insert(i, p3(source(border[i], m)), p3(target(border[i], m)));
  std::size_t n = 0;
  for (auto h : border) {
    auto v = target(h, m);
    P3 p = p3(v);
    bool found = false;
    grid.query(p, tol, [&](const mrepair::internal::Segment_grid::Item& it) {
      const std::uint64_t i = it.key;
      if (found) return;
      auto s = source(border[i], m), t = target(border[i], m);
      if (s == v || t == v) return;
      P3 a = p3(s), c = p3(t);
      P3 ab{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      double l2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
      if (l2 == 0) return;
      double u = ((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1] + (p[2] - a[2]) * ab[2]) / l2;
      double l = std::sqrt(l2), eps = std::min(tol, l / 3) / l;
      if (u <= eps || u >= 1 - eps) return;  // at an end: a gap vertex, not a T-junction
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += (p[k] - a[k] - u * ab[k]) * (p[k] - a[k] - u * ab[k]);
      found = d2 <= tol * tol;
    });
    n += found;
  }
  return n;
}

double one_sided(const Mesh& a, const Mesh& b)
{
  using Tree = mrepair::internal::Aabb_tree<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>;
  Tree tree(faces(b).first, faces(b).second, b);
  tree.accelerate_distance_queries();
  double d = 0;
  for (auto v : vertices(a)) d = std::max(d, tree.squared_distance(a.point(v)));
  return std::sqrt(d);
}

void inspect(const Mesh& m, double tol, mrepair::Report& r)
{
  auto c = mrepair::internal::count_boundary(m);
  r.add("faces", std::size_t(faces(m).size()));
  r.add("boundary_edges", c.first);
  r.add("boundary_loops", c.second);
  r.add("t_junctions", t_junctions(m, tol));
  std::vector<Mesh::Halfedge_index> nm;
  PMP::non_manifold_vertices(m, std::back_inserter(nm));
  r.add("non_manifold_vertices", nm.size());
  r.add("valid", CGAL::is_valid_polygon_mesh(m));
}

void compare(const Mesh& in, Mesh& out, double tol, mrepair::bench::Measurement& m)
{
  out.collect_garbage();
  const char* quick = std::getenv("MREPAIR_GAP_PIPELINE_ONLY");
  if (quick && std::string(quick) == "1") {
    m.before.add("boundary_edges", mrepair::internal::count_boundary(in).first);
    m.after.add("boundary_edges", mrepair::internal::count_boundary(out).first);
    return;
  }
  inspect(in, tol, m.before);
  inspect(out, tol, m.after);
  std::size_t b0 = mrepair::internal::count_boundary(in).first;
  std::size_t b1 = mrepair::internal::count_boundary(out).first;
  m.after.add("seam_edges_closed_percent", b0 ? 100.0 * double(b0 - std::min(b0, b1)) / b0 : 100.0);
  m.after.add("hausdorff_estimate", std::max(one_sided(in, out), one_sided(out, in)));
  m.after.add("tolerance", tol);
}

mrepair::bench::Measurement run_mrepair(const std::string& path)
{
  mrepair::bench::Measurement m;
  const Clock::time_point t0 = Clock::now();
  Mesh mesh = load(path);
  const Clock::time_point copy0 = Clock::now();
  const Mesh input = mesh;  // for the comparison below: not part of the job
  const double untimed = std::chrono::duration<double>(Clock::now() - copy0).count();
  const double tol = tolerance(mesh);
  CGAL::Real_timer t;
  std::clock_t c0 = std::clock();
  t.start();
  mrepair::Gap_closing_result res = mrepair::close_gaps(mesh, tol);
  t.stop();
  std::clock_t c1 = std::clock();
  m.seconds = t.time();
  m.result.add("cpu_seconds", double(c1 - c0) / CLOCKS_PER_SEC);  // all threads
  m.status = mrepair::to_string(res.status);
  res.to_report(m.result);
  end_pipeline(mesh, t0, untimed, m);
  compare(input, mesh, tol, m);
  return m;
}

mrepair::bench::Measurement run_stitch(const std::string& path)
{
  mrepair::bench::Measurement m;
  const Clock::time_point t0 = Clock::now();
  Mesh mesh = load(path);
  const Clock::time_point copy0 = Clock::now();
  const Mesh input = mesh;  // for the comparison below: not part of the job
  const double untimed = std::chrono::duration<double>(Clock::now() - copy0).count();
  const double tol = tolerance(mesh);
  CGAL::Real_timer t;
  std::clock_t c0 = std::clock();
  t.start();
  std::size_t n = PMP::stitch_borders(mesh);
  t.stop();
  std::clock_t c1 = std::clock();
  m.seconds = t.time();
  m.result.add("cpu_seconds", double(c1 - c0) / CLOCKS_PER_SEC);  // all threads
  m.result.add("stitched", n);
  end_pipeline(mesh, t0, untimed, m);
  compare(input, mesh, tol, m);
  return m;
}

mrepair::bench::Measurement run_snap(const std::string& path)
{
  mrepair::bench::Measurement m;
  const Clock::time_point t0 = Clock::now();
  Mesh mesh = load(path);
  const Clock::time_point copy0 = Clock::now();
  const Mesh input = mesh;  // for the comparison below: not part of the job
  const double untimed = std::chrono::duration<double>(Clock::now() - copy0).count();
  const double tol = tolerance(mesh);
  CGAL::Constant_property_map<Mesh::Vertex_index, double> tolerance_map(tol);
  CGAL::Real_timer t;
  std::clock_t c0 = std::clock();
  t.start();
  std::size_t snapped = PMP::experimental::snap_borders<CGAL::Parallel_if_available_tag>(mesh, tolerance_map);
  std::size_t stitched = PMP::stitch_borders(mesh);
  t.stop();
  std::clock_t c1 = std::clock();
  m.seconds = t.time();
  m.result.add("cpu_seconds", double(c1 - c0) / CLOCKS_PER_SEC);  // all threads
  m.result.add("snapped", snapped);
  m.result.add("stitched", stitched);
  end_pipeline(mesh, t0, untimed, m);
  compare(input, mesh, tol, m);
  return m;
}

mrepair::bench::Task_registrar reg{
    {"close-gaps",
     "close seams within MREPAIR_GAP_TOLERANCE x diagonal (default 5e-4): mrepair::close_gaps vs "
     "PMP::stitch_borders vs PMP::experimental::snap_borders + stitch_borders",
     {{"mrepair::close_gaps", run_mrepair},
      {"CGAL stitch_borders", run_stitch},
      {"CGAL snap_borders+stitch", run_snap}},
     "cad-mesh"}};

} // namespace close_gaps_task
} // namespace
