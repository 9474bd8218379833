// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Task "inspect": mrepair::inspect on a Surface_mesh beside the same counts
// computed with CGAL 5.5 calls: PMP::connected_components,
// PMP::extract_boundary_cycles, PMP::border_halfedges,
// PMP::self_intersections<Parallel_if_available_tag>,
// PMP::is_degenerate_triangle_face, PMP::non_manifold_vertices,
// PMP::merge_duplicate_points/polygons_in_polygon_soup (on a soup copy),
// PMP::edge_length, CGAL::approximate_angle, CGAL::approximate_dihedral_angle,
// CGAL::is_closed, PMP::area, PMP::volume. Both fill `after` with the same
// keys as `Inspection_report::to_report` so that the table lines up; CGAL has
// nothing for T-junctions, so that row stays empty on its side.
#include "bench.h"

#include <mrepair/inspect.h>
#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace inspect_task {  // a namespace of its own: the harness is a unity build

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;
using mrepair::bench::Measurement;


Mesh load(const std::string& path)
{
  return mrepair::bench::load_mesh<Mesh>(
      path, [](const std::string& f, Mesh& m) { return mrepair::read_polygon_mesh(f, m); });
}

Measurement run_mrepair(const std::string& input)
{
  Mesh m = load(input);
  Measurement out;
  CGAL::Real_timer t;
  const double cpu0 = mrepair::bench::cpu_seconds();
  t.start();
  mrepair::Inspection_report r = mrepair::inspect(m);
  t.stop();
  out.seconds = t.time();
  out.result.add("cpu_seconds", mrepair::bench::cpu_seconds() - cpu0);
  out.status = mrepair::to_string(r.status);
  r.to_report(out.after);
  return out;
}

// The same figures with CGAL's functions, as a CGAL user would write them.
Measurement run_cgal(const std::string& input)
{
  using halfedge_descriptor = boost::graph_traits<Mesh>::halfedge_descriptor;
  using face_descriptor = boost::graph_traits<Mesh>::face_descriptor;
  using vertex_descriptor = boost::graph_traits<Mesh>::vertex_descriptor;
  Mesh m = load(input);
  Measurement out;
  mrepair::Report& in = out.after.section("input");
  mrepair::Report& d = out.after.section("defects");
  mrepair::Report& q = out.after.section("quality");
  const double spike_angle = 100, zero_factor = 0.1, skinny_factor = 0.25, skinny_angle = 10,
               small_angle = 30;
  const std::size_t max_hole = 100, min_component = 400;

  CGAL::Real_timer t;
  const double cpu0 = mrepair::bench::cpu_seconds();
  t.start();
  in.add("vertices", vertices(m).size());
  in.add("faces", faces(m).size());
  in.add("edges", edges(m).size());
  const bool triangle_mesh = CGAL::is_triangle_mesh(m);

  std::size_t non_finite = 0, isolated = 0;
  for (vertex_descriptor v : vertices(m)) {
    const Point& p = m.point(v);
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) ++non_finite;
    if (halfedge(v, m) == boost::graph_traits<Mesh>::null_halfedge()) ++isolated;
  }
  d.add("non_finite_vertices", non_finite);
  d.add("isolated_vertices", isolated);

  // duplicates: CGAL counts them on soups only
  {
    std::vector<Point> points(m.points().begin(), m.points().end());
    std::vector<std::vector<std::size_t>> polygons;
    polygons.reserve(faces(m).size());
    for (face_descriptor f : faces(m)) {
      polygons.emplace_back();
      for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, m), m))
        polygons.back().push_back(v.idx());
    }
    d.add("duplicate_faces", PMP::merge_duplicate_polygons_in_polygon_soup(points, polygons));
    d.add("duplicate_points", PMP::merge_duplicate_points_in_polygon_soup(points, polygons));
  }

  std::size_t degenerate = 0;
  if (triangle_mesh)
    for (face_descriptor f : faces(m)) degenerate += PMP::is_degenerate_triangle_face(f, m);
  d.add("degenerate_faces", degenerate);

  std::vector<halfedge_descriptor> nm;
  PMP::non_manifold_vertices(m, std::back_inserter(nm));
  std::set<vertex_descriptor> nm_vertices;
  for (halfedge_descriptor h : nm) nm_vertices.insert(target(h, m));
  d.add("non_manifold_vertices", nm_vertices.size());

  std::vector<halfedge_descriptor> border;
  PMP::border_halfedges(faces(m), m, std::back_inserter(border));
  d.add("boundary_edges", border.size());
  std::vector<halfedge_descriptor> cycles;
  PMP::extract_boundary_cycles(m, std::back_inserter(cycles));
  std::size_t small_holes = 0;
  for (halfedge_descriptor h : cycles)
    if (static_cast<std::size_t>(CGAL::halfedges_around_face(h, m).size()) < max_hole) ++small_holes;
  d.add("boundary_loops", cycles.size());
  d.add("small_holes", small_holes);

  auto fcc = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  const std::size_t ncc = PMP::connected_components(m, fcc);
  std::vector<std::size_t> cc_size(ncc, 0);
  for (face_descriptor f : faces(m)) ++cc_size[get(fcc, f)];
  d.add("connected_components", ncc);
  d.add("small_components",
        std::count_if(cc_size.begin(), cc_size.end(), [&](std::size_t s) { return s < min_component; }));

  // edge lengths, vertex mean lengths, near-degenerate faces (RameshCleaner 3.6)
  double sum = 0, sum2 = 0;
  for (auto e : edges(m)) {
    const double l = PMP::edge_length(e, m);
    sum += l;
    sum2 += l * l;
  }
  const double ne = double(edges(m).size());
  const double mean = sum / ne;
  auto vmean = get(CGAL::dynamic_vertex_property_t<double>(), m);
  for (vertex_descriptor v : vertices(m)) {
    double s = 0;
    int n = 0;
    if (halfedge(v, m) != boost::graph_traits<Mesh>::null_halfedge())
      for (halfedge_descriptor h : CGAL::halfedges_around_target(v, m)) {
        s += PMP::edge_length(h, m);
        ++n;
      }
    put(vmean, v, n ? s / n : 0.0);
  }
  std::size_t near_degenerate = 0, angles = 0, small = 0;
  double min_angle = 180;
  if (triangle_mesh)
    for (face_descriptor f : faces(m)) {
      bool bad = false;
      for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, m), m)) {
        const Point &a = m.point(source(h, m)), &b = m.point(target(h, m)),
                    &o = m.point(target(next(h, m), m));
        const double l = PMP::edge_length(h, m);
        const double opposite = CGAL::approximate_angle(a, o, b);
        const double le = 0.5 * (get(vmean, source(h, m)) + get(vmean, target(h, m)));
        if (l < zero_factor * mean || (opposite < skinny_angle && l < skinny_factor * le)) bad = true;
        min_angle = std::min(min_angle, opposite);
        ++angles;
        if (opposite < small_angle) ++small;
      }
      near_degenerate += bad;
    }
  d.add("near_degenerate_faces", near_degenerate);

  // spikes: CGAL's dihedral angle is the opening angle; the angle between
  // the face normals is 180 - |it|
  auto spiked = get(CGAL::dynamic_vertex_property_t<bool>(), m);
  for (vertex_descriptor v : vertices(m)) put(spiked, v, false);
  double max_dihedral = -1;
  for (auto e : edges(m)) {
    halfedge_descriptor h = halfedge(e, m);
    if (is_border_edge(h, m)) continue;
    const double a = 180.0 - std::abs(CGAL::approximate_dihedral_angle(
                                 m.point(source(h, m)), m.point(target(h, m)),
                                 m.point(target(next(h, m), m)),
                                 m.point(target(next(opposite(h, m), m), m))));
    max_dihedral = std::max(max_dihedral, a);
    if (a > spike_angle) {
      put(spiked, source(h, m), true);
      put(spiked, target(h, m), true);
    }
  }
  std::size_t spiked_count = 0;
  for (vertex_descriptor v : vertices(m)) spiked_count += get(spiked, v);
  d.add("spiked_vertices", spiked_count);

  std::size_t si = 0;
  if (triangle_mesh && non_finite == 0) {
    std::vector<std::pair<face_descriptor, face_descriptor>> pairs;
    PMP::self_intersections<CGAL::Parallel_if_available_tag>(faces(m), m, std::back_inserter(pairs));
    for (const auto& p : pairs) si += p.first != p.second;
    d.add("self_intersecting_pairs", si);
  } else
    d.add("self_intersecting_pairs", "not computed");
  const bool closed = CGAL::is_closed(m);
  d.add("closed", closed);

  // quality
  double dev = 0;
  std::size_t interior = 0;
  for (vertex_descriptor v : vertices(m)) {
    if (halfedge(v, m) == boost::graph_traits<Mesh>::null_halfedge() || is_border(v, m)) continue;
    dev += std::abs(double(CGAL::halfedges_around_target(v, m).size()) - 6.0);
    ++interior;
  }
  q.add("min_angle", min_angle);
  q.add("small_angle_share", angles ? double(small) / double(angles) : 0.0);
  q.add("max_dihedral_angle", max_dihedral);
  q.add("mean_valence_deviation", interior ? dev / double(interior) : 0.0);
  q.add("edge_length_mean", mean);
  q.add("edge_length_stddev", std::sqrt(std::max(0.0, sum2 / ne - mean * mean)));
  q.add("area", triangle_mesh ? PMP::area(m) : std::numeric_limits<double>::quiet_NaN());
  q.add("volume", closed && triangle_mesh ? PMP::volume(m) : std::numeric_limits<double>::quiet_NaN());
  t.stop();
  out.seconds = t.time();
  out.result.add("cpu_seconds", mrepair::bench::cpu_seconds() - cpu0);
  return out;
}

mrepair::bench::Task_registrar reg{{"inspect",
                                    "defect counts and quality figures of a mesh",
                                    {{"mrepair::inspect", run_mrepair}, {"CGAL PMP", run_cgal}}}};

} // namespace inspect_task
} // namespace
