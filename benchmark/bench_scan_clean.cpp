// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Task "degenerate+spikes": mrepair's scan-cleaning I steps (relax_spikes,
// remove_unrelaxable_spikes, repair_near_degenerate_faces, relax_spikes again,
// on one shared Geometric_statistics) beside CGAL's closest calls:
// PMP::remove_almost_degenerate_faces (experimental in 5.5, documented in
// 6.0; caps > 160 degrees, needles with longest/shortest > 4, collapsed edges
// < 0.5 x mean length),
// PMP::remove_degenerate_faces, and PMP::angle_and_area_smoothing (angle only:
// area smoothing needs Ceres) for spikes. Both sides report the same counts,
// computed by the same code on the output: near-degenerate faces (inspect.h
// definition), spiked vertices by dihedral (> 100 degrees, as inspect) and by
// the height criterion of relax_spikes.h, boundary edges, validity.
#include "bench.h"
#include "cgal_chain.h"

#include <mrepair/geometric_statistics.h>
#include <mrepair/io.h>
#include <mrepair/relax_spikes.h>
#include <mrepair/repair_near_degenerate_faces.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/angle_and_area_smoothing.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <ctime>
#include <stdexcept>
#include <string>

namespace {
namespace scan_clean_task {  // a namespace of its own: the harness is a unity build

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace SC = mrepair::internal::clean_pipeline;

Mesh load(const std::string& path)
{
  Mesh m;
  mrepair::Io_result r = mrepair::read_polygon_mesh(path, m);
  if (!mrepair::succeeded(r.status) || faces(m).size() == 0)
    throw std::runtime_error("cannot read " + path + ": " + r.message);
  if (!CGAL::is_triangle_mesh(m)) PMP::triangulate_faces(m);
  return m;
}

// the defect counts both variants report (same code on both outputs)
void defects(Mesh& m, mrepair::Report& r)
{
  mrepair::Geometric_statistics<Mesh> st(m);
  st.compute_all();
  // the defaults of the library's own parameter readers (definitions.h)
  std::string unused;
  SC::Near_degenerate_settings nd;
  SC::read_near_degenerate_settings(mrepair::parameters::default_values(), st.edge_count(), nd, unused);
  SC::Spike_settings sp;
  SC::read_spike_settings(mrepair::parameters::default_values(), sp, unused);
  std::size_t by_height = 0;
  const std::size_t spiked = SC::count_spiked(st, sp, &by_height);
  std::size_t border = 0;
  for (auto h : halfedges(m)) border += is_border(h, m);
  r.add("faces", std::size_t(faces(m).size()));
  r.add("near_degenerate_faces", SC::count_near_degenerate_faces(st, nd));
  r.add("spiked_vertices", spiked);
  r.add("spiked_by_dihedral_100", spiked - by_height);
  r.add("spiked_by_height_only", by_height);
  r.add("boundary_edges", border);
  r.add("valid", CGAL::is_valid_polygon_mesh(m));
}

mrepair::bench::Measurement run_mrepair(const std::string& path)
{
  mrepair::bench::Measurement out;
  Mesh m = load(path);
  defects(m, out.before);
  CGAL::Real_timer t, step;
  double ts[5];
  const std::clock_t c0 = std::clock(); // CPU time of all threads: stabler than wall time on a busy machine
  t.start();
  step.start();
  mrepair::Geometric_statistics<Mesh> st(m);
  st.compute_all();
  ts[0] = step.time();
  auto r1 = mrepair::relax_spikes(m, st);
  ts[1] = step.time();
  auto r2 = mrepair::remove_unrelaxable_spikes(m, st);
  ts[2] = step.time();
  auto r3 = mrepair::repair_near_degenerate_faces(m, st);
  ts[3] = step.time();
  auto r4 = mrepair::relax_spikes(m, st);
  ts[4] = step.time();
  t.stop();
  out.seconds = t.time();
  out.result.add("cpu_s", double(std::clock() - c0) / CLOCKS_PER_SEC);
  out.result.add("statistics_s", ts[0]);
  out.result.add("relax_spikes_s", ts[1] - ts[0]);
  out.result.add("remove_unrelaxable_spikes_s", ts[2] - ts[1]);
  out.result.add("repair_near_degenerate_faces_s", ts[3] - ts[2]);
  out.result.add("relax_spikes_again_s", ts[4] - ts[3]);
  r1.to_report(out.result.section("relax_spikes"));
  r2.to_report(out.result.section("remove_unrelaxable_spikes"));
  r3.to_report(out.result.section("repair_near_degenerate_faces"));
  r4.to_report(out.result.section("relax_spikes_again"));
  out.status = mrepair::to_string(r3.status);
  defects(m, out.after);
  return out;
}

mrepair::bench::Measurement run_cgal(const std::string& path)
{
  mrepair::bench::Measurement out;
  Mesh m = load(path);
  defects(m, out.before);
  double sum = 0;
  for (auto e : edges(m)) sum += std::sqrt(CGAL::squared_distance(m.point(source(e, m)), m.point(target(e, m))));
  const double mean = sum / double(edges(m).size());
  CGAL::Real_timer t, t1, t2, t3;
  const std::clock_t c0 = std::clock();
  t.start();
  t1.start();
  mrepair::bench::remove_almost_degenerate_faces_with_cgal(m, std::cos(160.0 / 180.0 * CGAL_PI), 4.0,
                                                          0.5 * mean);
  t1.stop();
  t2.start();
  const bool ok = PMP::remove_degenerate_faces(m);
  t2.stop();
  t3.start();
  PMP::angle_and_area_smoothing(m, CGAL::parameters::use_area_smoothing(false));
  t3.stop();
  t.stop();
  out.seconds = t.time();
  out.result.add("cpu_s", double(std::clock() - c0) / CLOCKS_PER_SEC);
  out.result.add("remove_almost_degenerate_faces_s", t1.time());
  out.result.add("remove_degenerate_faces_s", t2.time());
  out.result.add("remove_degenerate_faces_ok", ok);
  out.result.add("angle_and_area_smoothing_s", t3.time());
  m.collect_garbage();
  defects(m, out.after);
  return out;
}

mrepair::bench::Measurement run_cgal_degenerate_only(const std::string& path)
{
  mrepair::bench::Measurement out;
  Mesh m = load(path);
  defects(m, out.before);
  double sum = 0;
  for (auto e : edges(m)) sum += std::sqrt(CGAL::squared_distance(m.point(source(e, m)), m.point(target(e, m))));
  const double mean = sum / double(edges(m).size());
  CGAL::Real_timer t;
  const std::clock_t c0 = std::clock();
  t.start();
  mrepair::bench::remove_almost_degenerate_faces_with_cgal(m, std::cos(160.0 / 180.0 * CGAL_PI), 4.0,
                                                          0.5 * mean);
  PMP::remove_degenerate_faces(m);
  t.stop();
  out.seconds = t.time();
  out.result.add("cpu_s", double(std::clock() - c0) / CLOCKS_PER_SEC);
  m.collect_garbage();
  defects(m, out.after);
  return out;
}

mrepair::bench::Task_registrar reg{
    {"degenerate+spikes",
     "relax/remove spikes + near-degenerate faces vs CGAL almost-degenerate removal + smoothing",
     {{"mrepair scan clean I", run_mrepair},
      {"CGAL degenerate+smoothing", run_cgal},
      {"CGAL degenerate only", run_cgal_degenerate_only}}}};

} // namespace scan_clean_task
} // namespace
