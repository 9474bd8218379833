// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Measures behind the safety policy of the cleaning steps (doc/guarantees.md,
// "What cleaning never does"): face-connected components with their face
// counts and areas, the turning of a boundary loop (jagged or clean), and the
// area of the cap that would close a loop (hole or sheet border).
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SAFETY_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SAFETY_H

#include <mrepair/internal/clean_scan_mesh/mesh_ops.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {
namespace clean_pipeline {

/// `label_components()` on a large Surface_mesh: the faces across each edge
/// are joined in a union-find, in parallel (lock-free: a root is linked under
/// the smaller root by compare-and-swap, so each component's root ends as its
/// smallest face index). Components are then numbered in the order of their
/// smallest face, which is the order in which the sequential search meets
/// them, and the counts and areas are summed in face order.
template <typename PM, typename VPM, typename FaceId>
std::size_t label_components_in_parallel(const PM& pm, const VPM& vpm, FaceId& id,
                                         std::vector<std::size_t>& faces_of,
                                         std::vector<double>& area_of)
{
  using face_descriptor = typename boost::graph_traits<PM>::face_descriptor;
  using edge_descriptor = typename boost::graph_traits<PM>::edge_descriptor;
  using Index = std::uint32_t;
  const std::size_t nf = pm.num_faces();  // index range, removed faces included
  std::unique_ptr<std::atomic<Index>[]> parent(new std::atomic<Index>[nf]);
  parallel_for_index(nf, 16384, [&](std::size_t f) { parent[f].store(Index(f), std::memory_order_relaxed); });
  // a parent is never larger than its child (links go under the smaller
  // root, halving skips to a grandparent): every chain ends within nf steps,
  // and a compare-and-swap below fails only when a root got linked meanwhile
  auto find = [&](Index x) {
    for (;;) {
      Index p = parent[x].load(std::memory_order_relaxed);
      if (p == x) return x;
      const Index g = parent[p].load(std::memory_order_relaxed);
      if (g != p) parent[x].compare_exchange_weak(p, g, std::memory_order_relaxed);  // path halving
      x = g;
    }
  };
  parallel_for_index(pm.num_edges(), 16384, [&](std::size_t i) {
    const edge_descriptor e(static_cast<typename edge_descriptor::size_type>(i));
    if (pm.is_removed(e)) return;
    const auto h = halfedge(e, pm), o = opposite(h, pm);
    if (is_border(h, pm) || is_border(o, pm)) return;
    Index a = Index(face(h, pm)), b = Index(face(o, pm));
    for (;;) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);
      Index expected = a;  // a is a root: link it under the smaller root b
      if (parent[a].compare_exchange_strong(expected, b, std::memory_order_relaxed)) return;
    }
  });
  std::vector<Index> root(nf);
  std::vector<double> area(nf, 0.);
  parallel_for_index(nf, 16384, [&](std::size_t i) {
    const face_descriptor f(static_cast<typename face_descriptor::size_type>(i));
    if (pm.is_removed(f)) return;
    root[i] = find(Index(i));
    area[i] = 0.5 * norm(face_normal(halfedge(f, pm), pm, vpm));
  });
  faces_of.clear();
  area_of.clear();
  // the union-find is done: a root's slot now holds its component's number
  // (no third array at the 10M-face peak)
  for (face_descriptor f : faces(pm)) {
    const Index i = Index(f);
    if (root[i] == i) {
      parent[i].store(Index(faces_of.size()), std::memory_order_relaxed);
      faces_of.push_back(0);
      area_of.push_back(0.);
    }
    const Index c = parent[root[i]].load(std::memory_order_relaxed);
    put(id, f, std::size_t(c));
    ++faces_of[c];
    if (std::isfinite(area[i])) area_of[c] += area[i];
  }
  return faces_of.size();
}

/// Face-connected components: `id` (a face property of std::size_t) gets the
/// component index of every face; `faces_of[c]` and `area_of[c]` the face
/// count and area of component c. Linear time.
template <typename PM, typename VPM, typename FaceId>
std::size_t label_components(const PM& pm, const VPM& vpm, FaceId& id,
                             std::vector<std::size_t>& faces_of, std::vector<double>& area_of)
{
  using face_descriptor = typename boost::graph_traits<PM>::face_descriptor;
  if constexpr (Is_surface_mesh<PM>::value) {
    if (pm.num_faces() >= 65536 && pm.num_faces() < std::size_t(std::uint32_t(-1)))
      return label_components_in_parallel(pm, vpm, id, faces_of, area_of);
  }
  const std::size_t none = std::size_t(-1);
  faces_of.clear();
  area_of.clear();
  for (face_descriptor f : faces(pm)) put(id, f, none);
  std::vector<face_descriptor> queue;
  for (face_descriptor seed : faces(pm)) {
    if (get(id, seed) != none) continue;
    const std::size_t c = faces_of.size();
    faces_of.push_back(0);
    area_of.push_back(0.);
    queue.assign(1, seed);
    put(id, seed, c);
    while (!queue.empty()) {
      face_descriptor f = queue.back();
      queue.pop_back();
      ++faces_of[c];
      const double a = 0.5 * norm(face_normal(halfedge(f, pm), pm, vpm));
      if (std::isfinite(a)) area_of[c] += a;
      for (auto h : CGAL::halfedges_around_face(halfedge(f, pm), pm)) {
        auto o = opposite(h, pm);
        if (is_border(o, pm)) continue;
        face_descriptor n = face(o, pm);
        if (get(id, n) == none) {
          put(id, n, c);
          queue.push_back(n);
        }
      }
    }
  }
  return faces_of.size();
}

/// The signed turning angle (radians) at the target of each border halfedge
/// of the loop of `h`, in loop order, with that target: the sign of each turn
/// is read against the surface normal at the vertex (the faces along its two
/// border edges). A zero-length edge gives no turn.
template <typename PM, typename VPM>
void loop_turns(typename boost::graph_traits<PM>::halfedge_descriptor h, const PM& pm,
                const VPM& vpm,
                std::vector<std::pair<typename boost::graph_traits<PM>::vertex_descriptor, double>>&
                    out)
{
  out.clear();
  for (auto g : CGAL::halfedges_around_face(h, pm)) {
    const Vec3 a = point(vpm, source(g, pm)), b = point(vpm, target(g, pm)),
               c = point(vpm, target(next(g, pm), pm));
    const Vec3 u = sub(b, a), w = sub(c, b);
    const double lu = norm(u), lw = norm(w);
    double t = 0.;
    if (lu > 0. && lw > 0.) {
      const double cs = std::max(-1., std::min(1., dot(u, w) / (lu * lw)));
      t = std::acos(cs);
      const Vec3 n = add(face_normal(opposite(g, pm), pm, vpm),
                         face_normal(opposite(next(g, pm), pm), pm, vpm));
      if (dot(cross(u, w), n) < 0.) t = -t;
    }
    out.emplace_back(target(g, pm), t);
  }
}

/// Jaggedness of a run of signed turns: their total absolute turning minus
/// the absolute value of their sum. A run that turns one way has none; a
/// turn and its undoing (a tooth, an ear) add twice their angle.
template <typename Iterator>
double jaggedness(Iterator first, Iterator last)
{
  double total = 0., signed_total = 0.;
  for (; first != last; ++first) {
    total += std::abs(first->second);
    signed_total += first->second;
  }
  return total - std::abs(signed_total);
}

/// Calls `f(i, j)` for each vertex i of `turns` (one loop, in order) with
/// the jaggedness j of the cyclic window of 2 * `half_width` + 1 turns
/// centred on it (the whole loop when it is shorter than that).
template <typename Turns, typename F>
void for_each_turn_window(const Turns& turns, std::size_t half_width, const F& f)
{
  const std::size_t n = turns.size();
  if (n == 0) return;
  if (n <= 2 * half_width + 1) {
    const double j = jaggedness(turns.begin(), turns.end());
    for (std::size_t i = 0; i < n; ++i) f(i, j);
    return;
  }
  double total = 0., signed_total = 0.;
  auto add_turn = [&](std::size_t i, double s) {
    total += s * std::abs(turns[i % n].second);
    signed_total += s * turns[i % n].second;
  };
  for (std::size_t i = 0; i <= 2 * half_width; ++i) add_turn(n - half_width + i, 1.);
  for (std::size_t c = 0; c < n; ++c) {
    f(c, std::max(0., total - std::abs(signed_total)));
    add_turn(n - half_width + c, -1.);
    add_turn(c + half_width + 1, 1.);
  }
}

/// Jaggedness (radians) of a boundary loop given by its turns: half the sum,
/// over its vertices, of the jaggedness of the 3 turns around each. Only a
/// turn undone within a vertex or two counts, so a loop that turns one way
/// (a convex sheet border, a CAD patch edge) has none, and so has a loop
/// whose turning changes sign slowly (the border of a cut Moebius strip,
/// curving one way on one side and the other way on the other); a tooth
/// (a turn and its undoing, an ear) adds twice its angle, and a scan border
/// that zigzags at the scale of its triangles adds at every vertex.
template <typename Turns>
double loop_jaggedness(const Turns& turns)
{
  double sum = 0.;
  for_each_turn_window(turns, std::size_t(1), [&](std::size_t, double j) { sum += j; });
  return 0.5 * sum;
}

/// Calls `mark(v)` for the vertices of `turns` (one loop, in order) at the
/// centre of a window of 2 * `half_width` + 1 turns whose jaggedness exceeds
/// `threshold`: a local tooth (a dangling ear) on a loop that is straight
/// elsewhere. A corner, however sharp, has no jaggedness of its own.
template <typename Turns, typename Mark>
void mark_local_teeth(const Turns& turns, std::size_t half_width, double threshold,
                      const Mark& mark)
{
  for_each_turn_window(turns, half_width, [&](std::size_t i, double j) {
    if (j > threshold) mark(turns[i].first);
  });
}

/// Area of the fan from the centroid of the loop of border halfedge `h` to
/// its edges: the area of a cap that closes the loop (exact for a planar
/// convex loop, an upper bound of the flattest cap otherwise, within the
/// loop's non-planarity).
template <typename PM, typename VPM>
double loop_cap_area(typename boost::graph_traits<PM>::halfedge_descriptor h, const PM& pm,
                     const VPM& vpm)
{
  Vec3 c{0, 0, 0};
  std::size_t n = 0;
  for (auto g : CGAL::halfedges_around_face(h, pm)) {
    c = add(c, point(vpm, target(g, pm)));
    ++n;
  }
  if (n == 0) return 0.;
  c = mul(c, 1. / double(n));
  double area = 0.;
  for (auto g : CGAL::halfedges_around_face(h, pm)) {
    const Vec3 a = point(vpm, source(g, pm)), b = point(vpm, target(g, pm));
    area += 0.5 * norm(triangle_normal(c, a, b));
  }
  return area;
}

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SAFETY_H
