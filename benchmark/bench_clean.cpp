// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Task "clean": the whole RameshCleaner pipeline (clean_scan_mesh) beside the
// best CGAL 5.5 chain for the same job:
//   PMP::remove_isolated_vertices, PMP::keep_large_connected_components (400),
//   PMP::triangulate_refine_and_fair_hole on every boundary loop with fewer
//   than 100 vertices ("CGAL chain"), plus the experimental stages
//   PMP::experimental::remove_almost_degenerate_faces and
//   PMP::experimental::remove_self_intersections ("CGAL chain + experimental").
// Both sides report the RameshCleaner table computed by the same code
// (mrepair::inspect) on the input and on the output: isolated vertices,
// components (small ones), small holes, near-degenerate faces, spiked
// vertices, self-intersecting pairs; plus the Hausdorff distance to the input
// (sampled, PMP::approximate_Hausdorff_distance, each direction) in percent of
// the input's bbox diagonal. With `--reference BASE` (the clean base surface
// from `mrepair-generate scan --clean-output`) also the distances to the
// surface that was scanned, each direction and symmetric, in percent of its
// diagonal: unlike the input, it has no spike tips or islands whose deletion
// counts as an error. CGAL has no NaN handling: its variants get the faces
// around non-finite vertices removed before the timer starts.
#include "bench.h"
#include "cgal_chain.h"

#include <mrepair/clean_scan_mesh.h>
#include <mrepair/inspect.h>
#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/bounding_box.h>

#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace clean_task {  // a namespace of its own: the harness is a unity build

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace MP = mrepair::parameters;

constexpr std::size_t kMinComponent = 400;
constexpr std::size_t kMaxHole = 100;

// Reads the file as a soup (NaN points accepted) and builds the mesh.
Mesh load(const std::string& path, double* seconds = nullptr)
{
  CGAL::Real_timer t;
  t.start();
  std::vector<Point> pts;
  std::vector<std::vector<std::size_t>> polys;
  mrepair::Io_result r = mrepair::read_polygon_soup(path, pts, polys);
  if (r.status != mrepair::Status::ok && r.status != mrepair::Status::non_finite_input)
    throw std::runtime_error("cannot read " + path + ": " + r.message);
  if (!mrepair::is_polygon_soup_a_polygon_mesh(polys, pts.size()))
    throw std::runtime_error(path + " is not a manifold polygon mesh");
  Mesh m;
  PMP::polygon_soup_to_polygon_mesh(pts, polys, m);
  t.stop();
  if (seconds) *seconds = t.time();
  return m;
}

// The RameshCleaner table (same code for every variant).
void table(const Mesh& m, mrepair::Report& r)
{
  mrepair::Inspection_report i = mrepair::inspect(
      m, MP::max_hole_vertices(kMaxHole, MP::min_component_faces(kMinComponent)));
  r.add("faces", i.faces);
  r.add("non_finite_vertices", i.non_finite_vertices);
  r.add("isolated_vertices", i.isolated_vertices);
  r.add("components", i.connected_components);
  r.add("small_components", i.small_components);
  r.add("small_holes", i.small_holes);
  r.add("boundary_loops", i.boundary_loops);
  r.add("near_degenerate_faces", i.near_degenerate_faces);
  r.add("spiked_vertices", i.spiked_vertices);
  r.add("self_intersecting_pairs", i.self_intersecting_pairs);
  r.add("valid", CGAL::is_valid_polygon_mesh(m));
}

double diagonal(const Mesh& m)
{
  auto box = CGAL::bbox_3(m.points().begin(), m.points().end());
  return std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                   CGAL::square(box.zmax() - box.zmin()));
}

// Sampled one-sided Hausdorff distance from `from` to `to` in percent of
// `diag`. The samples include every vertex of `from` (where spike tips and
// fill patches peak) plus 200k random points on its faces and edges. Output to
// input measures what the cleaning invented or moved (fills, relaxation);
// input to output also counts what it deleted on purpose (spike tips,
// islands), so both are reported.
double hausdorff_percent(const Mesh& from, const Mesh& to, double diag)
{
  if (faces(from).size() == 0 || faces(to).size() == 0 || !(diag > 0)) return std::nan("");
  return 100.0 *
         PMP::approximate_Hausdorff_distance<CGAL::Parallel_if_available_tag>(
             from, to, CGAL::parameters::number_of_points_on_faces(200000)) /
         diag;
}

// Distances of the output to the input and, when given, to the clean base surface.
void distances(const Mesh& out, const Mesh& input, mrepair::Report& r)
{
  const double d_in = diagonal(input);
  r.add("hausdorff_output_to_input_pct", hausdorff_percent(out, input, d_in));
  r.add("hausdorff_input_to_output_pct", hausdorff_percent(input, out, d_in));
  const std::string& ref = mrepair::bench::reference_path();
  if (ref.empty()) return;
  const Mesh base = load(ref);
  const double d_base = diagonal(base);
  const double ob = hausdorff_percent(out, base, d_base), bo = hausdorff_percent(base, out, d_base);
  r.add("hausdorff_output_to_base_pct", ob);
  r.add("hausdorff_base_to_output_pct", bo);
  r.add("hausdorff_symmetric_base_pct", std::max(ob, bo));
}

// Input with the faces around non-finite vertices removed (CGAL cannot).
Mesh finite_copy(const Mesh& in)
{
  Mesh m = in;
  mrepair::clean_scan_mesh(m, MP::clean_steps(unsigned(mrepair::clean_step_remove_degenerate_vertices)));
  return m;
}

mrepair::bench::Measurement run_mrepair(const std::string& path)
{
  mrepair::bench::Measurement out;
  double t_read = 0;
  Mesh m = load(path, &t_read);
  table(m, out.before);
  const Mesh reference = finite_copy(m);
  CGAL::Real_timer t;
  t.start();
  mrepair::Scan_cleaning_result r = mrepair::clean_scan_mesh(m);
  t.stop();
  out.seconds = t.time();
  CGAL::Real_timer tw;
  tw.start();
  mrepair::Io_result w = mrepair::write_polygon_mesh("/tmp/mrepair_bench_clean_out.ply", m, true);
  tw.stop();
  r.to_report(out.result);
  out.result.add("read_seconds", t_read);
  out.result.add("write_seconds", tw.time());
  out.result.add("seconds_with_io", t_read + out.seconds + tw.time());
  out.result.add("write_status", w.status);
  out.status = mrepair::to_string(r.status);
  table(m, out.after);
  distances(m, reference, out.after);
  return out;
}

mrepair::bench::Measurement run_cgal(const std::string& path, bool experimental)
{
  mrepair::bench::Measurement out;
  Mesh m0 = load(path);
  table(m0, out.before);
  Mesh m = finite_copy(m0);
  m0.clear();
  const Mesh reference = m;
  double sum = 0;
  for (auto e : edges(m))
    sum += std::sqrt(CGAL::squared_distance(m.point(source(e, m)), m.point(target(e, m))));
  const double mean = sum / double(std::max<std::size_t>(1, edges(m).size()));

  CGAL::Real_timer t, t1, t2, t3, t4, t5;
  t.start();
  t1.start();
  std::size_t isolated = PMP::remove_isolated_vertices(m);
  t1.stop();
  t2.start();
  std::size_t comps_removed =
      PMP::keep_large_connected_components(m, kMinComponent);
  t2.stop();
  t3.start();
  const auto [filled, failed] = mrepair::bench::fill_small_holes_with_cgal(m, kMaxHole);
  t3.stop();
  bool deg_ok = true, si_ok = true;
  if (experimental) {
    t4.start();
    deg_ok = mrepair::bench::remove_almost_degenerate_faces_with_cgal(
        m, std::cos(160.0 / 180.0 * CGAL_PI), 4.0, 0.5 * mean);
    t4.stop();
    t5.start();
    si_ok = PMP::experimental::remove_self_intersections(m);
    t5.stop();
  }
  t.stop();
  out.seconds = t.time();
  out.result.add("remove_isolated_vertices", isolated);
  out.result.add("remove_isolated_vertices_s", t1.time());
  out.result.add("components_removed", comps_removed);
  out.result.add("keep_large_connected_components_s", t2.time());
  out.result.add("holes_filled", filled);
  out.result.add("holes_failed", failed);
  out.result.add("triangulate_refine_and_fair_hole_s", t3.time());
  if (experimental) {
    out.result.add("remove_almost_degenerate_faces_s", t4.time());
    out.result.add("remove_almost_degenerate_faces_ok", deg_ok);
    out.result.add("remove_self_intersections_s", t5.time());
    out.result.add("remove_self_intersections_ok", si_ok);
  }
  m.collect_garbage();
  table(m, out.after);
  distances(m, reference, out.after);
  return out;
}

mrepair::bench::Task_registrar reg{
    {"clean",
     "RameshCleaner pipeline vs CGAL isolated/components/hole filling (+ experimental stages)",
     {{"mrepair clean_scan_mesh", run_mrepair},
      {"CGAL chain", [](const std::string& p) { return run_cgal(p, false); }},
      {"CGAL chain + experimental", [](const std::string& p) { return run_cgal(p, true); }}}}};

} // namespace clean_task
}  // namespace
