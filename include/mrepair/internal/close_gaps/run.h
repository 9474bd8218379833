// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_CLOSE_GAPS_RUN_H
#define MREPAIR_INTERNAL_CLOSE_GAPS_RUN_H

// The two stages of `close_gaps()` after the pairing: stepping a
// `Gap_closing_sequence` to its distance limit under the visitor, then
// splitting the pinched vertices left.

#include <mrepair/gap_closing_result.h>
#include <mrepair/internal/close_gaps/gap_closer.h>
#include <mrepair/internal/utility.h>
#include <mrepair/visitors.h>

#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/version.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <vector>

namespace mrepair {
namespace internal {

/// applies the contractions of `seq` up to its distance limit, at most
/// `max_ops` of them; returns true when the visitor stopped it. The stop is
/// polled before the first contraction (small meshes never reach 256) and
/// every 256 contractions, with the progress.
template <class Sequence, class VisitorHandle>
bool step_to_limit(Sequence& seq, VisitorHandle& visitor, std::size_t max_ops)
{
  Phase_scope<VisitorHandle> phase(visitor, "closing");
  const double limit = seq.max_distance();
  std::size_t n = 0;
  bool cancelled = visitor.stop_requested();
  while (!cancelled && n < max_ops && seq.step(limit)) {
    ++n;
    if ((n & 255) == 0) {
      if (visitor.stop_requested()) {
        cancelled = true;
        break;
      }
      visitor.progress(limit > 0 ? std::min(1.0, seq.current_distance() / limit) : 1.0);
    }
  }
  return cancelled;
}

/// splits the pinched vertices of `tm` (several fans) so that it is manifold,
/// and updates the boundary figures of `r`.
template <class TriangleMesh, class VertexPointMap, class VisitorHandle>
void split_pinched_vertices(TriangleMesh& tm, const VertexPointMap& vpm, VisitorHandle& visitor,
                            Gap_closing_result& r)
{
  Phase_scope<VisitorHandle> phase(visitor, "manifold");
  r.pinched_vertices_split = CGAL::Polygon_mesh_processing::duplicate_non_manifold_vertices(
      tm, CGAL::parameters::vertex_point_map(vpm));
  r.pinched_vertices = 0;
  auto counts = count_boundary(tm);
  r.boundary_edges_after = counts.first;
  r.boundary_loops_after = counts.second;
}


/// bridges the boundary loops left narrower than `tolerance` with triangles.
/// A loop of at most `max_edges` edges is narrow when twice its vector area
/// over its perimeter (the width of a strip) is at most tolerance / 2: the
/// crack between two sliver-tessellated patches (a blade's trailing edge)
/// whose every contraction would flip a sliver, or the flat triangle of a
/// T-junction vertex whose faces are thinner than its offset. Nothing moves;
/// a bridge that would make a degenerate face is taken back.
template <class TriangleMesh, class VertexPointMap, class VisitorHandle>
void bridge_narrow_loops(TriangleMesh& tm, const VertexPointMap& vpm, double tolerance,
                         std::size_t max_edges, VisitorHandle& visitor, Gap_closing_result& r)
{
  using GT = boost::graph_traits<TriangleMesh>;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  Phase_scope<VisitorHandle> phase(visitor, "bridging");
  std::vector<halfedge_descriptor> loops;
  {
    auto seen = get(CGAL::dynamic_halfedge_property_t<bool>(), tm);
    for (halfedge_descriptor h : halfedges(tm)) put(seen, h, false);
    for (halfedge_descriptor h : halfedges(tm)) {
      if (!is_border(h, tm) || get(seen, h)) continue;
      std::size_t n = 0;
      halfedge_descriptor g = h;
      do {
        put(seen, g, true);
        g = next(g, tm);
        ++n;
      } while (g != h);
      if (n >= 3 && n <= max_edges) loops.push_back(h);
    }
  }
  std::vector<Vec3> c;
  std::vector<face_descriptor> added;
  for (halfedge_descriptor h : loops) {
    if (!is_border(h, tm)) continue;  // closed by an earlier bridge
    c.clear();
    halfedge_descriptor g = h;
    do {
      c.push_back(point(vpm, target(g, tm)));
      g = next(g, tm);
    } while (g != h && c.size() <= max_edges);
    if (g != h) continue;
    Vec3 area{{0, 0, 0}};
    double perimeter = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const Vec3& a = c[i];
      const Vec3& b = c[(i + 1) % c.size()];
      area = add(area, cross(sub(a, c[0]), sub(b, c[0])));
      perimeter += distance(a, b);
    }
    // |area| is twice the vector area
    if (!(perimeter > 0) || !(norm(area) / perimeter <= 0.5 * tolerance)) continue;
    added.clear();
#if CGAL_VERSION_NR >= 1060000000
    CGAL::Polygon_mesh_processing::triangulate_hole(
        tm, h, CGAL::parameters::face_output_iterator(std::back_inserter(added)).vertex_point_map(vpm));
#else
    CGAL::Polygon_mesh_processing::triangulate_hole(tm, h, std::back_inserter(added),
                                                    CGAL::parameters::vertex_point_map(vpm));
#endif
    bool degenerate = added.empty();
    for (face_descriptor f : added) {
      halfedge_descriptor fh = halfedge(f, tm);
      const Vec3 p = point(vpm, source(fh, tm)), q = point(vpm, target(fh, tm)),
                 s = point(vpm, target(next(fh, tm), tm));
      const double l2 = std::max({squared_norm(sub(p, q)), squared_norm(sub(q, s)), squared_norm(sub(s, p))});
      const Vec3 n = cross(sub(q, p), sub(s, p));
      if (!(dot(n, n) > 1e-24 * l2 * l2)) degenerate = true;
    }
    if (degenerate) {
      for (face_descriptor f : added) CGAL::Euler::remove_face(halfedge(f, tm), tm);
      continue;
    }
    ++r.loops_bridged;
    r.bridge_faces += added.size();
  }
  auto counts = count_boundary(tm);
  r.boundary_edges_after = counts.first;
  r.boundary_loops_after = counts.second;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CLOSE_GAPS_RUN_H
