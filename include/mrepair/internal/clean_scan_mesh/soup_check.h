// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// A linear-time version of `PMP::is_polygon_soup_a_polygon_mesh` on flat
// arrays (CGAL 5.5's builds node-based sets and maps: about 10 times slower
// on a million faces, which dominated `mrepair clean` on large inputs).
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SOUP_CHECK_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SOUP_CHECK_H

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mrepair {
namespace internal {
namespace clean_pipeline {

/// true when `polygons` (indices into `n_points` points) form a manifold,
/// consistently oriented polygon mesh: every polygon has at least 3 distinct,
/// in-range vertices; every directed edge is used once (so an undirected edge
/// has at most two polygons, with opposite directions); and the polygons
/// around every vertex form one fan (one cycle or one path of wedges).
template <typename PolygonRange>
bool is_soup_a_polygon_mesh(const PolygonRange& polygons, std::size_t n_points)
{
  // Outgoing corners per vertex (CSR): for the corner at v of a polygon
  // (.., p, v, n, ..), the wedge n -> p around v.
  std::vector<std::uint32_t> count(n_points + 1, 0);
  std::size_t corners = 0;
  for (const auto& poly : polygons) {
    const std::size_t k = poly.size();
    if (k < 3) return false;
    for (std::size_t i = 0; i < k; ++i) {
      const std::size_t v = static_cast<std::size_t>(poly[i]);
      if (v >= n_points) return false;
      ++count[v + 1];
      for (std::size_t j = i + 1; j < k; ++j)  // no repeated vertex (k is small)
        if (static_cast<std::size_t>(poly[j]) == v) return false;
    }
    corners += k;
  }
  for (std::size_t v = 0; v < n_points; ++v) count[v + 1] += count[v];
  std::vector<std::uint32_t> fill(count.begin(), count.end() - 1);
  std::vector<std::size_t> next_of(corners), prev_of(corners);
  for (const auto& poly : polygons) {
    const std::size_t k = poly.size();
    for (std::size_t i = 0; i < k; ++i) {
      const std::size_t v = static_cast<std::size_t>(poly[i]);
      const std::size_t n = static_cast<std::size_t>(poly[(i + 1) % k]);
      const std::size_t p = static_cast<std::size_t>(poly[(i + k - 1) % k]);
      if (n == v || p == v) return false;  // repeated consecutive vertex
      const std::uint32_t slot = fill[v]++;
      next_of[slot] = n;
      prev_of[slot] = p;
    }
  }
  std::vector<std::size_t> nx, pv, order;
  for (std::size_t v = 0; v < n_points; ++v) {
    const std::size_t b = count[v], e = count[v + 1], d = e - b;
    if (d == 0) continue;
    nx.assign(next_of.begin() + b, next_of.begin() + e);
    pv.assign(prev_of.begin() + b, prev_of.begin() + e);
    // Directed edges v->n unique and p->v unique (sorted copies).
    std::vector<std::size_t> s(nx);
    std::sort(s.begin(), s.end());
    if (std::adjacent_find(s.begin(), s.end()) != s.end()) return false;
    s = pv;
    std::sort(s.begin(), s.end());
    if (std::adjacent_find(s.begin(), s.end()) != s.end()) return false;
    if (d == 1) continue;
    // One fan: wedge i is followed by the wedge j whose n equals i's p.
    // Walk from a wedge no other wedge leads to (a path), else from wedge 0.
    std::size_t start = 0;
    for (std::size_t i = 0; i < d; ++i) {
      bool led = false;
      for (std::size_t j = 0; j < d && !led; ++j) led = pv[j] == nx[i];
      if (!led) { start = i; break; }
    }
    std::size_t seen = 1, cur = start;
    while (seen <= d) {
      std::size_t nxt = d;
      for (std::size_t j = 0; j < d; ++j)
        if (nx[j] == pv[cur]) { nxt = j; break; }
      if (nxt == d || nxt == start) break;
      cur = nxt;
      ++seen;
    }
    if (seen != d) return false;
  }
  return true;
}

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SOUP_CHECK_H
