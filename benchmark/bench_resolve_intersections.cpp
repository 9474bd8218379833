// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Task "resolve-intersections": mrepair::resolve_intersections beside CGAL
// 5.5's PMP::experimental::remove_self_intersections (undocumented; the same
// name and signature in CGAL 6), each with its defaults, on its own copy of
// the input (read from the file in its own process). Built on CGAL 6, a third
// column: PMP::autorefine_triangle_soup (new in 6.0), the mesh written out as
// a soup, refined so that no two triangles cross, and made a mesh again
// (orient_polygon_soup, which cuts the non-manifold edges the refinement
// creates where surfaces cross, then polygon_soup_to_polygon_mesh). It keeps
// every triangle, inner parts too: a refinement, not a union.
//
// Both sides are judged by the same code on the input and on the output
// (`before` / `after`): mrepair::inspect with the self-intersection count on
// gives the pairs of faces that intersect and, of those, the pairs that only
// touch at coincident vertices; crossing pairs = pairs - touching. Beside
// them: faces, components, boundary edges, area, volume,
// CGAL::is_valid_polygon_mesh and CGAL::is_closed. The timed section is the
// call alone (wall time; `result.cpu_seconds` is the CPU time of all threads
// in it); the harness prints CGAL time / mrepair time.
//
// A fourth column: CGAL's PMP::experimental::autorefine_and_remove_self_intersections
// (5.5 and 6.x, corefinement.h): refines the mesh against itself and keeps
// its outer patches.
//
// Input `generated:assembly:N` (instead of a file): N closed bodies made in
// code, boxes and UV spheres at seeded random places in a cube sized so that
// each overlaps a few others (std::mt19937 seed 50, the same on every run),
// the assembly case of issue 50.
//
// Time bound: with MREPAIR_BENCH_TIME_LIMIT=SECONDS in the environment, a
// variant whose call runs longer is stopped by SIGALRM (the harness then
// prints "over the time limit" in its column; the other column is kept).
#include "bench.h"

#include <mrepair/inspect.h>
#include <mrepair/io.h>
#include <mrepair/resolve_intersections.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/version.h>
#if CGAL_VERSION_NR >= 1060000000
#include <CGAL/Polygon_mesh_processing/autorefinement.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <array>
#include <vector>
#endif

#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <sys/resource.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace resolve_intersections_task {  // a namespace of its own: the harness is a unity build

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace MP = mrepair::parameters;
using mrepair::bench::Measurement;


// N overlapping closed bodies (boxes and UV spheres), seeded.
Mesh generated_assembly(std::size_t n)
{
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::mt19937 random(50);
  std::uniform_real_distribution<double> unit(0., 1.);
  const double side = std::cbrt(double(n)) * 0.9;  // about one neighbour per body side
  const double pi = 3.14159265358979323846;
  for (std::size_t b = 0; b < n; ++b) {
    const double cx = side * unit(random), cy = side * unit(random), cz = side * unit(random);
    const std::size_t base = points.size();
    if (b % 2 == 0) {
      const double hx = 0.3 + 0.4 * unit(random), hy = 0.3 + 0.4 * unit(random), hz = 0.3 + 0.4 * unit(random);
      for (int k = 0; k < 8; ++k)
        points.emplace_back(cx + (k & 1 ? hx : -hx), cy + (k & 2 ? hy : -hy), cz + (k & 4 ? hz : -hz));
      // outward: each face's corners counter-clockwise seen from outside
      const std::size_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
      for (const auto& q : quads) {
        triangles.push_back({base + q[0], base + q[1], base + q[2]});
        triangles.push_back({base + q[0], base + q[2], base + q[3]});
      }
    } else {
      const double r = 0.35 + 0.4 * unit(random);
      const std::size_t nlat = 10, nlon = 16;
      points.emplace_back(cx, cy, cz + r);
      for (std::size_t k = 1; k < nlat; ++k)
        for (std::size_t j = 0; j < nlon; ++j) {
          const double t = pi * double(k) / double(nlat), f = 2 * pi * double(j) / double(nlon);
          points.emplace_back(cx + r * std::sin(t) * std::cos(f), cy + r * std::sin(t) * std::sin(f),
                              cz + r * std::cos(t));
        }
      points.emplace_back(cx, cy, cz - r);
      auto id = [&](std::size_t k, std::size_t j) {
        if (k == 0) return base;
        if (k == nlat) return base + 1 + (nlat - 1) * nlon;
        return base + 1 + (k - 1) * nlon + j % nlon;
      };
      for (std::size_t j = 0; j < nlon; ++j) triangles.push_back({id(0, 0), id(1, j), id(1, j + 1)});
      for (std::size_t k = 1; k + 1 < nlat; ++k)
        for (std::size_t j = 0; j < nlon; ++j) {
          triangles.push_back({id(k, j), id(k + 1, j), id(k + 1, j + 1)});
          triangles.push_back({id(k, j), id(k + 1, j + 1), id(k, j + 1)});
        }
      for (std::size_t j = 0; j < nlon; ++j) triangles.push_back({id(nlat, 0), id(nlat - 1, j + 1), id(nlat - 1, j)});
    }
  }
  Mesh m;
  std::vector<Mesh::Vertex_index> v;
  for (const Point& p : points) v.push_back(m.add_vertex(p));
  for (const auto& t : triangles) m.add_face(v[t[0]], v[t[1]], v[t[2]]);
  return m;
}

Mesh load(const std::string& path)
{
  const std::string generated = "generated:assembly:";
  if (path.compare(0, generated.size(), generated) == 0)
    return generated_assembly(std::size_t(std::stoul(path.substr(generated.size()))));
  return mrepair::bench::load_mesh<Mesh>(
      path, [](const std::string& f, Mesh& m) { return mrepair::read_polygon_mesh(f, m); });
}

// The same figures for every variant, before and after.
void table(const Mesh& m, mrepair::Report& r)
{
  const mrepair::Inspection_report i = mrepair::inspect(m, MP::count_self_intersections(true));
  r.add("faces", i.faces);
  if (i.self_intersections_counted) {
    r.add("intersecting_pairs", i.self_intersecting_pairs);
    r.add("touching_pairs", i.self_intersecting_pairs_touching);
    r.add("crossing_pairs", i.self_intersecting_pairs - i.self_intersecting_pairs_touching);
  } else {
    r.add("intersecting_pairs", "not computed");
    r.add("touching_pairs", "not computed");
    r.add("crossing_pairs", "not computed");
  }
  r.add("components", i.connected_components);
  r.add("boundary_edges", i.boundary_edges);
  r.add("area", i.area);
  r.add("volume", i.volume);
  r.add("valid", CGAL::is_valid_polygon_mesh(m));
  r.add("closed", CGAL::is_closed(m));
}

// MREPAIR_BENCH_TIME_LIMIT (whole seconds, > 0) or 0 (no bound).
unsigned time_limit()
{
  const char* s = std::getenv("MREPAIR_BENCH_TIME_LIMIT");
  if (!s) return 0;
  const long v = std::strtol(s, nullptr, 10);
  return v > 0 ? static_cast<unsigned>(v) : 0u;
}

// Times `call(mesh)` (wall and CPU), under the optional time bound.
template <typename Call>
void timed(Mesh& m, Measurement& out, Call&& call)
{
  const unsigned bound = time_limit();
  CGAL::Real_timer t;
  const double cpu0 = mrepair::bench::cpu_seconds();
  if (bound) alarm(bound);
  t.start();
  call(m);
  t.stop();
  if (bound) alarm(0);
  out.seconds = t.time();
  out.result.add("cpu_seconds", mrepair::bench::cpu_seconds() - cpu0);
}

Measurement run_mrepair(const std::string& input)
{
  Mesh m = load(input);
  Measurement out;
  table(m, out.before);
  mrepair::Intersection_repair_result r;
  timed(m, out, [&](Mesh& mesh) { r = mrepair::resolve_intersections(mesh); });
  out.status = mrepair::to_string(r.status);
  r.to_report(out.result);
  m.collect_garbage();
  table(m, out.after);
  return out;
}

Measurement run_cgal(const std::string& input)
{
  Mesh m = load(input);
  Measurement out;
  table(m, out.before);
  bool fixed = false;
  timed(m, out, [&](Mesh& mesh) { fixed = PMP::experimental::remove_self_intersections(mesh); });
  out.status = fixed ? "ok" : "not all removed";
  out.result.add("returned", fixed);
  m.collect_garbage();
  table(m, out.after);
  return out;
}

Measurement run_cgal_autorefine_and_remove(const std::string& input)
{
  Mesh m = load(input);
  Measurement out;
  table(m, out.before);
  bool fixed = false;
  timed(m, out, [&](Mesh& mesh) {
    try {
      fixed = PMP::experimental::autorefine_and_remove_self_intersections(mesh);
    } catch (const std::exception&) {
      fixed = false;  // CGAL's autorefinement throws on some configurations
    }
  });
  out.status = fixed ? "ok" : "not all removed";
  out.result.add("returned", fixed);
  m.collect_garbage();
  table(m, out.after);
  return out;
}

#if CGAL_VERSION_NR >= 1060000000
Measurement run_cgal_autorefine(const std::string& input)
{
  Mesh m = load(input);
  Measurement out;
  table(m, out.before);
  std::size_t refined_triangles = 0;
  bool manifold_soup = false;
  CGAL::Real_timer refine;
  timed(m, out, [&](Mesh& mesh) {
    std::vector<Point> points;
    std::vector<std::array<std::size_t, 3>> triangles;
    PMP::polygon_mesh_to_polygon_soup(mesh, points, triangles);
    refine.start();
    PMP::autorefine_triangle_soup(points, triangles,
                                  CGAL::parameters::concurrency_tag(CGAL::Parallel_if_available_tag()));
    refine.stop();
    refined_triangles = triangles.size();
    manifold_soup = PMP::orient_polygon_soup(points, triangles);
    mesh.clear();
    PMP::polygon_soup_to_polygon_mesh(points, triangles, mesh);
  });
  out.status = "ok";
  out.result.add("autorefine_seconds", refine.time());
  out.result.add("refined_triangles", refined_triangles);
  out.result.add("soup_was_manifold", manifold_soup);
  m.collect_garbage();
  table(m, out.after);
  return out;
}
#endif

mrepair::bench::Task_registrar reg{
    {"resolve-intersections",
     "crossings of a triangle mesh: resolve_intersections vs "
     "PMP::experimental::remove_self_intersections and autorefine_and_remove_self_intersections; "
     "input generated:assembly:N for N overlapping bodies (env MREPAIR_BENCH_TIME_LIMIT=seconds bounds each call)",
     {{"mrepair::resolve", run_mrepair},
      {"CGAL remove_self_int", run_cgal},
      {"CGAL autoref+remove", run_cgal_autorefine_and_remove},
#if CGAL_VERSION_NR >= 1060000000
      {"CGAL autorefine_soup", run_cgal_autorefine},
#endif
     },
     "generated:assembly:20"}};

} // namespace resolve_intersections_task
} // namespace
