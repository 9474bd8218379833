// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Pieces of the CGAL chains the harness runs beside mrepair, written once for
// the tasks that share them (soup, clean, scan-clean, job), in the form each
// CGAL release documents (5.5 and 6.x differ in two of them).
#ifndef MREPAIR_BENCH_CGAL_CHAIN_H
#define MREPAIR_BENCH_CGAL_CHAIN_H

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/version.h>

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
  std::vector<halfedge_descriptor> loops;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(m, std::back_inserter(loops));
  std::size_t filled = 0, failed = 0;
  for (halfedge_descriptor h : loops) {
    if (CGAL::halfedges_around_face(h, m).size() >= max_hole) continue;
#if CGAL_VERSION_NR >= 1060000000  // 6.0 deprecates the output-iterator form
    const bool ok = std::get<0>(CGAL::Polygon_mesh_processing::triangulate_refine_and_fair_hole(m, h));
#else
    std::vector<typename boost::graph_traits<Mesh>::face_descriptor> fs;
    std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor> vs;
    const bool ok = std::get<0>(CGAL::Polygon_mesh_processing::triangulate_refine_and_fair_hole(
        m, h, std::back_inserter(fs), std::back_inserter(vs)));
#endif
    ++(ok ? filled : failed);
  }
  return {filled, failed};
}

/// PMP's removal of almost degenerate faces: caps whose largest angle has a
/// cosine below `cap_cosine`, needles longer than `needle_ratio` times their
/// shortest edge, no collapse of an edge longer than `collapse_length`.
/// Experimental in 5.5 (thresholds as arguments), documented in 6.0 (named
/// parameters). Returns CGAL's answer: true when none is left.
template <typename Mesh>
bool remove_almost_degenerate_faces_with_cgal(Mesh& m, double cap_cosine, double needle_ratio,
                                              double collapse_length)
{
#if CGAL_VERSION_NR >= 1060000000
  return CGAL::Polygon_mesh_processing::remove_almost_degenerate_faces(
      m, CGAL::parameters::cap_threshold(cap_cosine)
             .needle_threshold(needle_ratio)
             .collapse_length_threshold(collapse_length));
#else
  return CGAL::Polygon_mesh_processing::experimental::remove_almost_degenerate_faces(
      m, cap_cosine, needle_ratio, collapse_length);
#endif
}

}  // namespace bench
}  // namespace mrepair

#endif  // MREPAIR_BENCH_CGAL_CHAIN_H
