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
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/version.h>

#include <algorithm>
#include <array>
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


/// joins the two sides of a crack with a strip of triangles, nothing moved:
/// a border edge a->b whose ends have, as mutual nearest border vertices
/// within `tolerance` (neighbours along an edge excluded), the ends of a
/// border edge c->d of the other side (d beside a, c beside b) gets the quad
/// a-b-c-d, split along its shorter diagonal. Only pairs farther apart than
/// `min_distance` (a contraction would move them by more than the reference
/// tolerance, compare_to_reference.h); a quad whose triangles would fold
/// against the faces they join (more than 45 degrees) or degenerate is left
/// to the contractions. Counts the quads in `r.seam_edges_zipped` and their
/// faces in `r.seam_faces`. Border vertices are found in a hash grid of
/// `tolerance` cells: O(border) expected.
template <class TriangleMesh, class VertexPointMap>
void zip_facing_border_edges(TriangleMesh& tm, const VertexPointMap& vpm, double tolerance,
                             double min_distance, Gap_closing_result& r)
{
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  if (!(tolerance > 0)) return;
  std::vector<halfedge_descriptor> border;
  border_halfedges(tm, border);
  // border vertices (a pinched one, with several border halfedges, is left out:
  // its fans are not one side of one crack)
  std::map<vertex_descriptor, halfedge_descriptor> out_of;  // the border halfedge leaving each vertex
  std::set<vertex_descriptor> pinched;
  for (halfedge_descriptor h : border)
    if (!out_of.emplace(source(h, tm), h).second) pinched.insert(source(h, tm));
  for (vertex_descriptor v : pinched) out_of.erase(v);
  if (out_of.size() < 4) return;
  using Cell = std::array<long long, 3>;
  auto cell_of = [&](const Vec3& p) {
    return Cell{{(long long)std::floor(p[0] / tolerance), (long long)std::floor(p[1] / tolerance),
                 (long long)std::floor(p[2] / tolerance)}};
  };
  std::map<Cell, std::vector<vertex_descriptor>> grid;
  for (const auto& vh : out_of) {
    const Vec3 p = point(vpm, vh.first);
    if (!is_finite(p) || std::abs(p[0] / tolerance) > 1e15 || std::abs(p[1] / tolerance) > 1e15 ||
        std::abs(p[2] / tolerance) > 1e15)
      return;  // cells out of range: no zipping
    grid[cell_of(p)].push_back(vh.first);
  }
  auto adjacent = [&](vertex_descriptor a, vertex_descriptor b) { return halfedge(a, b, tm).second; };
  // nearest border vertex within the tolerance, not a neighbour
  std::map<vertex_descriptor, vertex_descriptor> nearest;
  for (const auto& vh : out_of) {
    const vertex_descriptor v = vh.first;
    const Vec3 p = point(vpm, v);
    const Cell c = cell_of(p);
    double best = tolerance;
    vertex_descriptor found = GT::null_vertex();
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          auto it = grid.find(Cell{{c[0] + dx, c[1] + dy, c[2] + dz}});
          if (it == grid.end()) continue;
          for (vertex_descriptor w : it->second) {
            if (w == v) continue;
            const double d = distance(p, point(vpm, w));
            if (d < best && !adjacent(v, w)) {
              best = d;
              found = w;
            }
          }
        }
    if (found != GT::null_vertex()) nearest.emplace(v, found);
  }
  auto partner = [&](vertex_descriptor v) {
    auto it = nearest.find(v);
    if (it == nearest.end()) return GT::null_vertex();
    auto back = nearest.find(it->second);
    return back != nearest.end() && back->second == v ? it->second : GT::null_vertex();
  };
  auto face_normal = [&](halfedge_descriptor h) {
    return triangle_normal(point(vpm, source(h, tm)), point(vpm, target(h, tm)),
                           point(vpm, target(next(h, tm), tm)));
  };
  for (halfedge_descriptor h : border) {
    if (!is_border(h, tm)) continue;  // taken by an earlier quad
    const vertex_descriptor a = source(h, tm), b = target(h, tm);
    const vertex_descriptor d = partner(a), c = partner(b);
    if (d == GT::null_vertex() || c == GT::null_vertex() || c == d || c == a || d == b) continue;
    const auto cd = halfedge(c, d, tm);
    if (!cd.second || !is_border(cd.first, tm) || pinched.count(c) || pinched.count(d)) continue;
    const Vec3 pa = point(vpm, a), pb = point(vpm, b), pc = point(vpm, c), pd = point(vpm, d);
    if (!(distance(pa, pd) > min_distance || distance(pb, pc) > min_distance)) continue;
    // split along the shorter diagonal
    std::array<std::array<vertex_descriptor, 3>, 2> quad;
    std::array<std::array<Vec3, 3>, 2> corners;
    if (distance(pa, pc) <= distance(pb, pd)) {
      quad = {{{{a, b, c}}, {{a, c, d}}}};
      corners = {{{{pa, pb, pc}}, {{pa, pc, pd}}}};
    } else {
      quad = {{{{a, b, d}}, {{b, c, d}}}};
      corners = {{{{pa, pb, pd}}, {{pb, pc, pd}}}};
    }
    // the faces the quad joins: across a-b and across c-d
    // A strip continues the surface: the two sides' faces and the quad's
    // triangles within 45 degrees of one another. Sides that overlap or fold
    // (a seam whose vertices were pushed across each other) are left to the
    // contractions, whose placement checks see the flips.
    const Vec3 n_ab = normalized(face_normal(opposite(h, tm))), n_cd = normalized(face_normal(opposite(cd.first, tm)));
    const double cos_limit = std::cos(to_radians(45.));
    bool ok = dot(n_ab, n_cd) > cos_limit;
    for (const auto& t : corners) {
      const Vec3 n = triangle_normal(t[0], t[1], t[2]);
      const double l2 = std::max({squared_norm(sub(t[0], t[1])), squared_norm(sub(t[1], t[2])),
                                  squared_norm(sub(t[2], t[0]))});
      if (!(dot(n, n) > 1e-24 * l2 * l2)) {
        ok = false;
        break;
      }
      const Vec3 u = normalized(n);
      if (!(dot(u, n_ab) > cos_limit) || !(dot(u, n_cd) > cos_limit)) ok = false;
    }
    if (!ok) continue;
    // the second triangle is added only when the first was
    if (!CGAL::Euler::can_add_face(quad[0], tm)) continue;
    const auto f0 = CGAL::Euler::add_face(quad[0], tm);
    if (f0 == GT::null_face()) continue;
    if (!CGAL::Euler::can_add_face(quad[1], tm)) {
      CGAL::Euler::remove_face(halfedge(f0, tm), tm);
      continue;
    }
    const auto f1 = CGAL::Euler::add_face(quad[1], tm);
    if (f1 == GT::null_face()) {
      CGAL::Euler::remove_face(halfedge(f0, tm), tm);
      continue;
    }
    ++r.seam_edges_zipped;
    r.seam_faces += 2;
  }
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
