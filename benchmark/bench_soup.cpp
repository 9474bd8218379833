// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Task "soup": polygon soup to oriented manifold mesh.
//   "mrepair::polygon_soup_to_manifold_mesh": one call (no stitching tolerance,
//      so that both sides do the same job: exact merging only).
//   "mrepair (snap 1e-4 diag)": the same with snap_epsilon = 1e-4 x bbox diagonal.
//   "CGAL chain": PMP::repair_polygon_soup, PMP::orient_polygon_soup,
//      PMP::polygon_soup_to_polygon_mesh, PMP::stitch_borders,
//      PMP::duplicate_non_manifold_vertices (CGAL 5.5).
// Every variant reports the same inspection (mrepair::inspect_polygon_soup of
// the input, mrepair::inspect of the output Surface_mesh): faces, non-manifold
// edges and vertices, inconsistent orientations, boundary edges, components,
// plus CGAL::is_valid_polygon_mesh. CGAL cannot take polygons with invalid
// indices or non-finite points: they are removed before its timer starts.
#include "bench.h"
#include "cgal_chain.h"

#include <mrepair/inspect.h>
#include <mrepair/io.h>
#include <mrepair/stitch_soup.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace soup_task {  // a namespace of its own: the harness is a unity build

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Polygon = std::vector<std::size_t>;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace MP = mrepair::parameters;

void load(const std::string& path, std::vector<Point>& pts, std::vector<Polygon>& polys)
{
  mrepair::Io_result r = mrepair::read_polygon_soup(path, pts, polys);
  if (r.status != mrepair::Status::ok && r.status != mrepair::Status::non_finite_input &&
      r.status != mrepair::Status::invalid_index)
    throw std::runtime_error("cannot read " + path + ": " + r.message);
}

void summary(const mrepair::Inspection_report& i, mrepair::Report& r)
{
  r.add("faces", i.faces);
  r.add("vertices", i.vertices);
  r.add("invalid_polygons", i.invalid_polygons);
  r.add("degenerate_faces", i.degenerate_faces);
  r.add("duplicate_faces", i.duplicate_faces);
  r.add("non_manifold_edges", i.non_manifold_edges);
  r.add("non_manifold_vertices", i.non_manifold_vertices);
  r.add("inconsistent_orientation_edges", i.inconsistent_orientation_edges);
  r.add("boundary_edges", i.boundary_edges);
  r.add("components", i.connected_components);
}

void before(const std::vector<Point>& pts, const std::vector<Polygon>& polys, mrepair::Report& r)
{
  summary(mrepair::inspect_polygon_soup(pts, polys, MP::count_self_intersections(false)), r);
}

void after(const Mesh& m, mrepair::Report& r)
{
  summary(mrepair::inspect(m, MP::count_self_intersections(false)), r);
  r.add("valid", CGAL::is_valid_polygon_mesh(m));
}

double diagonal(const std::vector<Point>& pts)
{
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const Point& p : pts)
    for (int k = 0; k < 3; ++k)
      if (std::isfinite(p[k])) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
  double d = 0;
  for (int k = 0; k < 3; ++k) d += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  return std::sqrt(d);
}

mrepair::bench::Measurement run_mrepair(const std::string& path, bool snap)
{
  mrepair::bench::Measurement out;
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  load(path, pts, polys);
  before(pts, polys, out.before);
  const double eps = snap ? 1e-4 * diagonal(pts) : 0.0;
  Mesh m;
  CGAL::Real_timer t;
  t.start();
  mrepair::Soup_repair_result r = mrepair::polygon_soup_to_manifold_mesh(pts, polys, m, MP::snap_epsilon(eps));
  t.stop();
  out.seconds = t.time();
  r.to_report(out.result);
  out.result.add("snap_epsilon", eps);
  out.status = mrepair::to_string(r.status);
  after(m, out.after);
  return out;
}

mrepair::bench::Measurement run_cgal(const std::string& path)
{
  mrepair::bench::Measurement out;
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  load(path, pts, polys);
  before(pts, polys, out.before);
  // CGAL has no guard against these: take them out untimed
  out.result.add("polygons_removed_before_timer", mrepair::bench::drop_unusable_polygons(pts, polys));
  const std::size_t faces_in = polys.size();
  Mesh m;
  CGAL::Real_timer t, t1, t2, t3, t4, t5;
  t.start();
  t1.start();
  const std::size_t polys_before = polys.size();
  PMP::repair_polygon_soup(pts, polys);
  const std::size_t removed = polys_before - polys.size();
  t1.stop();
  t2.start();
  bool oriented = PMP::orient_polygon_soup(pts, polys);
  t2.stop();
  t3.start();
  bool is_mesh = PMP::is_polygon_soup_a_polygon_mesh(polys);
  if (is_mesh) PMP::polygon_soup_to_polygon_mesh(pts, polys, m);
  t3.stop();
  t4.start();
  std::size_t stitched = is_mesh ? PMP::stitch_borders(m) : 0;
  t4.stop();
  t5.start();
  std::size_t duplicated = is_mesh ? PMP::duplicate_non_manifold_vertices(m) : 0;
  t5.stop();
  t.stop();
  out.seconds = t.time();
  out.result.add("faces_in", faces_in);
  out.result.add("faces_out", static_cast<std::size_t>(faces(m).size()));
  out.result.add("repair_polygon_soup_removed", removed);
  out.result.add("repair_polygon_soup_s", t1.time());
  out.result.add("orient_polygon_soup_ok", oriented);
  out.result.add("orient_polygon_soup_s", t2.time());
  out.result.add("soup_is_polygon_mesh", is_mesh);
  out.result.add("polygon_soup_to_polygon_mesh_s", t3.time());
  out.result.add("stitch_borders_stitched", stitched);
  out.result.add("stitch_borders_s", t4.time());
  out.result.add("duplicate_non_manifold_vertices", duplicated);
  out.result.add("duplicate_non_manifold_vertices_s", t5.time());
  out.status = is_mesh ? "ok" : "not_a_mesh";
  after(m, out.after);
  return out;
}

mrepair::bench::Task_registrar reg{
    {"soup",
     "polygon soup to oriented manifold mesh: polygon_soup_to_manifold_mesh vs the CGAL 5.5 chain",
     {{"mrepair::polygon_soup_to_manifold_mesh", [](const std::string& p) { return run_mrepair(p, false); }},
      {"CGAL chain", [](const std::string& p) { return run_cgal(p); }},
      {"mrepair (snap 1e-4 diag)", [](const std::string& p) { return run_mrepair(p, true); }}},
     "cad-soup"}};

} // namespace soup_task
} // namespace
