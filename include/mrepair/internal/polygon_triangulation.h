// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Ear clipping of one polygon, shared by the soup stage (triangles of a soup)
// and triangulate_polygons() (faces of a mesh, cut by Euler::split_face).
//
// CGAL 5.5's triangulate_faces cuts a face along a constrained Delaunay
// triangulation of its projection on the plane of its normal; on a
// non-planar pentagon (trimesh's polygonfaces.obj: four corners on a square,
// the fifth lifted above an edge) it left two triangles and a halfedge whose
// next started elsewhere, a structure every later walk circled forever
// (issue 36). Ear clipping cuts one corner at a time, so every step is a
// valid split whatever the geometry, and a polygon with no ear left is
// finished as a fan: it always ends.
#ifndef MREPAIR_INTERNAL_POLYGON_TRIANGULATION_H
#define MREPAIR_INTERNAL_POLYGON_TRIANGULATION_H

#include <mrepair/internal/utility.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <cstddef>
#include <numeric>
#include <vector>

namespace mrepair {
namespace internal {

/// cuts the polygon of corners `p` (in order; `id[k]`: the vertex of corner
/// k, equal ids are the same vertex visited twice) into triangles, one
/// corner at a time: `clip(a, b, c)` is called with the corner b cut off
/// and its two neighbours a, c on the ring left (counterclockwise in the
/// plane that drops the largest coordinate of the Newell normal; exact 2D
/// orientation on the projected coordinates). The last call's three corners
/// are the last triangle. `allowed(a, c)` vetoes a cut along the diagonal
/// between corners a and c (a mesh refuses one that exists as an edge, or
/// joins a vertex to itself).
///
/// Corners are cut as convex ears with no other corner inside first; a ring
/// with none left (self-overlapping, collinear, or out of the work budget)
/// is finished as a fan from the first corner whose diagonals are all
/// allowed. Returns false when no such corner exists: the ring left (the
/// corners not cut, in order) is in `rest` and no further clip is made.
template <typename Id, typename Allowed, typename Clip>
bool clip_ears(const std::vector<Vec3>& p, const std::vector<Id>& id, const Allowed& allowed,
               const Clip& clip, std::vector<std::size_t>* rest = nullptr)
{
  using K = CGAL::Epick;
  const std::size_t m = p.size();
  if (m < 3) return false;
  Vec3 nrm{{0, 0, 0}};
  for (std::size_t i = 0; i < m; ++i) nrm += newell_term(p[i], p[(i + 1) % m]);
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(nrm[k]) > std::abs(nrm[axis])) axis = k;
  int u = (axis + 1) % 3, v = (axis + 2) % 3;
  if (nrm[axis] < 0) std::swap(u, v);  // the polygon is counterclockwise in (u, v)
  std::vector<K::Point_2> q(m);
  for (std::size_t i = 0; i < m; ++i) q[i] = K::Point_2(p[i][u], p[i][v]);
  const auto orient = K().orientation_2_object();
  std::vector<std::size_t> ring(m);
  std::iota(ring.begin(), ring.end(), std::size_t(0));
  // each ear test reads the ring once: a budget of tests keeps a huge
  // polygon with few ears from costing cubic time (the fan takes over)
  std::size_t budget = 64 * m + 4096;
  std::size_t from = 0;  // resume where the last ear was cut
  while (ring.size() > 3 && budget > 0) {
    const std::size_t s = ring.size();
    bool clipped = false;
    for (std::size_t t = 0; t < s && !clipped && budget > 0; ++t, --budget) {
      const std::size_t k = (from + t) % s;
      const std::size_t a = ring[(k + s - 1) % s], b = ring[k], c = ring[(k + 1) % s];
      if (orient(q[a], q[b], q[c]) != CGAL::LEFT_TURN || !allowed(a, c)) continue;
      bool blocked = false;
      for (std::size_t j = 0; j < s && !blocked; ++j) {
        const std::size_t x = ring[j];
        if (x == a || x == b || x == c) continue;
        if (id[x] == id[a] || id[x] == id[b] || id[x] == id[c]) continue;
        if (orient(q[a], q[b], q[x]) != CGAL::RIGHT_TURN && orient(q[b], q[c], q[x]) != CGAL::RIGHT_TURN &&
            orient(q[c], q[a], q[x]) != CGAL::RIGHT_TURN)
          blocked = true;
      }
      if (blocked) continue;
      clip(a, b, c);
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
      from = k % ring.size();
      clipped = true;
    }
    if (!clipped) break;
  }
  if (ring.size() > 3) {
    // the fan from ring[r] cuts along (r, r+2), (r, r+3), ..., (r, r-2)
    const std::size_t s = ring.size();
    std::size_t root = s;
    for (std::size_t r = 0; r < s && root == s; ++r) {
      bool ok = true;
      for (std::size_t k = 2; k + 1 < s && ok; ++k) ok = allowed(ring[r], ring[(r + k) % s]);
      if (ok) root = r;
    }
    if (root == s) {
      if (rest) *rest = ring;
      return false;
    }
    std::rotate(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(root), ring.end());
    for (std::size_t k = 1; k + 2 < s; ++k) clip(ring[0], ring[k], ring[k + 1]);
    ring = {ring[0], ring[s - 2], ring[s - 1]};
  }
  clip(ring[0], ring[1], ring[2]);
  return true;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_POLYGON_TRIANGULATION_H
