// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Pieces of the CGAL 5.5 chains the harness runs beside mrepair, written once
// for the tasks that share them (soup, clean, job).
#ifndef MREPAIR_BENCH_CGAL_CHAIN_H
#define MREPAIR_BENCH_CGAL_CHAIN_H

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/boost/graph/iterator.h>

#include <cmath>
#include <cstddef>
#include <iterator>
#include <tuple>
#include <utility>
#include <vector>

namespace mrepair {
namespace bench {

/// Drops the polygons CGAL has no guard against: fewer than three corners,
/// an index out of range, a non-finite corner. Returns how many went.
template <typename Point, typename Polygon>
std::size_t drop_unusable_polygons(const std::vector<Point>& pts, std::vector<Polygon>& polys)
{
  std::vector<Polygon> kept;
  kept.reserve(polys.size());
  for (Polygon& p : polys) {
    bool ok = p.size() >= 3;
    for (std::size_t i : p)
      ok = ok && i < pts.size() && std::isfinite(pts[i].x()) && std::isfinite(pts[i].y()) &&
           std::isfinite(pts[i].z());
    if (ok) kept.push_back(std::move(p));
  }
  const std::size_t dropped = polys.size() - kept.size();
  polys.swap(kept);
  return dropped;
}

/// PMP::triangulate_refine_and_fair_hole on every boundary loop with fewer
/// than `max_hole` edges, as mrepair's small-hole limit. Returns {filled, failed}.
template <typename Mesh>
std::pair<std::size_t, std::size_t> fill_small_holes_with_cgal(Mesh& m, std::size_t max_hole)
{
  using halfedge_descriptor = typename boost::graph_traits<Mesh>::halfedge_descriptor;
  using vertex_descriptor = typename boost::graph_traits<Mesh>::vertex_descriptor;
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;
  std::vector<halfedge_descriptor> loops;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(m, std::back_inserter(loops));
  std::size_t filled = 0, failed = 0;
  for (halfedge_descriptor h : loops) {
    if (CGAL::halfedges_around_face(h, m).size() >= max_hole) continue;
    std::vector<face_descriptor> fs;
    std::vector<vertex_descriptor> vs;
    if (std::get<0>(CGAL::Polygon_mesh_processing::triangulate_refine_and_fair_hole(
            m, h, std::back_inserter(fs), std::back_inserter(vs))))
      ++filled;
    else
      ++failed;
  }
  return {filled, failed};
}

}  // namespace bench
}  // namespace mrepair

#endif  // MREPAIR_BENCH_CGAL_CHAIN_H
