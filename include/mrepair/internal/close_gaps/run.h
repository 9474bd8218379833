// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_CLOSE_GAPS_RUN_H
#define MREPAIR_INTERNAL_CLOSE_GAPS_RUN_H

// The two stages of `close_gaps()` after the pairing: stepping a
// `Gap_closing_sequence` to its distance limit under the visitor, then
// splitting the pinched vertices left.

#include <mrepair/gap_closing_result.h>
#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/close_gaps/gap_closer.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/internal/patch_guard.h>
#include <mrepair/internal/utility.h>
#include <mrepair/visitors.h>

#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/version.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <iterator>
#include <map>
#include <queue>
#include <set>
#include <utility>
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
  Local_operations<TriangleMesh, VertexPointMap> ops(tm, vpm);
  r.pinched_vertices_split = ops.split_non_manifold_vertices();
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
/// T-junction vertex whose faces are thinner than its offset. Nothing moves.
/// A bridge goes in through the local operations, as a hole patch does, and
/// is taken back when it would make a degenerate face or pass through a
/// clean stretch of the surface (internal/patch_guard.h; counted in
/// `bridges_rejected_intersecting`).
template <class TriangleMesh, class VertexPointMap, class VisitorHandle>
void bridge_narrow_loops(TriangleMesh& tm, const VertexPointMap& vpm, double tolerance,
                         std::size_t max_edges, VisitorHandle& visitor, Gap_closing_result& r)
{
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Operations = Local_operations<TriangleMesh, VertexPointMap>;
  Phase_scope<VisitorHandle> phase(visitor, "bridging");
  // the narrow loops, one halfedge each
  std::vector<halfedge_descriptor> loops;
  {
    std::vector<halfedge_descriptor> border;
    border_halfedges(tm, border);
    std::vector<Vec3> c;
    const bool closed = for_each_border_cycle(tm, border, [&](halfedge_descriptor h) {
      c.clear();
      halfedge_descriptor g = h;  // a cycle: for_each_border_cycle walked it back to h
      do {
        c.push_back(point(vpm, target(g, tm)));
        g = next(g, tm);
      } while (g != h && c.size() <= max_edges);
      if (c.size() < 3 || c.size() > max_edges) return;
      Vec3 area{{0, 0, 0}};
      double perimeter = 0;
      for (std::size_t i = 0; i < c.size(); ++i) {
        const Vec3& a = c[i];
        const Vec3& b = c[(i + 1) % c.size()];
        area = add(area, triangle_normal(c[0], a, b));
        perimeter += distance(a, b);
      }
      // |area| is twice the vector area
      if (perimeter > 0 && norm(area) / perimeter <= 0.5 * tolerance) loops.push_back(h);
    });
    if (!closed) {  // a border walk hit its bound: no bridge on a broken border
      r.status = Status::invalid_mesh;
      r.message = walk_bound_message("close_gaps: the border walk of the bridging");
      return;
    }
  }
  Operations ops(tm, vpm);
  Patch_intersection_guard<TriangleMesh, VertexPointMap> guard(tm, vpm);
  if (!loops.empty()) guard.prepare(loops, [](std::size_t) { return true; }, 0.);
  for (std::size_t index = 0; index < loops.size(); ++index) {
    const halfedge_descriptor h = loops[index];
    if (!is_border(h, tm)) continue;  // closed by an earlier bridge
    std::size_t added_faces = 0;
    // Near the loop a bridge may meet faces, and its own faces may fold
    // over each other: the two sides of a seam overlap there by up to the
    // tolerance (a patch shifted across its neighbour, over strips thinner
    // than the shift), and leaving the crack open for that would leave
    // T-junctions (a 1M-face blade soup, faces within two rings tolerated:
    // 3 of 86 bridges refused, 3 -> 27 T-junctions). "Near" is along the
    // surface: the faces around the vertices reached from the loop by paths
    // of edges no longer than twice the tolerance. A face met beyond that is
    // the bridge cutting through another part of the model.
    std::set<face_descriptor> near;
    {
      using Entry = std::pair<double, vertex_descriptor>;
      std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
      std::map<vertex_descriptor, double> reached;
      for (halfedge_descriptor g : CGAL::halfedges_around_face(h, tm))
        if (reached.emplace(target(g, tm), 0.).second) queue.push(Entry(0., target(g, tm)));
      const double radius = 2. * tolerance;
      while (!queue.empty()) {
        const Entry e = queue.top();
        queue.pop();
        if (e.first > reached[e.second]) continue;
        for (halfedge_descriptor g : CGAL::halfedges_around_target(e.second, tm)) {
          if (!is_border(g, tm)) near.insert(face(g, tm));
          const vertex_descriptor w = source(g, tm);
          const double d = e.first + distance(point(vpm, w), point(vpm, e.second));
          if (!(d <= radius)) continue;
          auto it = reached.find(w);
          if (it != reached.end() && it->second <= d) continue;
          reached[w] = d;
          queue.push(Entry(d, w));
        }
      }
    }
    const bool bridged = ops.insert_patch(h, [&](Patch_operations<TriangleMesh, VertexPointMap>& patch_ops, std::vector<vertex_descriptor>&,
                                                 std::vector<vertex_descriptor>&) {
      std::vector<face_descriptor> added;
      if (!triangulate_hole_checked(tm, h, vpm, true, added)) return false;
      for (face_descriptor f : added) {
        const halfedge_descriptor fh = halfedge(f, tm);
        const Vec3 p = point(vpm, source(fh, tm)), q = point(vpm, target(fh, tm)),
                   s = point(vpm, target(next(fh, tm), tm));
        const double l2 = std::max({squared_norm(sub(p, q)), squared_norm(sub(q, s)), squared_norm(sub(s, p))});
        const Vec3 n = triangle_normal(p, q, s);
        if (!(dot(n, n) > 1e-24 * l2 * l2)) {
          patch_ops.remove_patch(added);
          return false;
        }
      }
      if (guard.patch_intersects(index, added, &near, false)) {
        patch_ops.remove_patch(added);
        ++r.bridges_rejected_intersecting;
        return false;
      }
      guard.accept(added);
      added_faces = added.size();
      return true;
    });
    if (!bridged) continue;
    ++r.loops_bridged;
    r.bridge_faces += added_faces;
  }
  auto counts = count_boundary(tm);
  r.boundary_edges_after = counts.first;
  r.boundary_loops_after = counts.second;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CLOSE_GAPS_RUN_H
