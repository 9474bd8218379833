// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_INSPECT_SURFACE_ARRAYS_H
#define MREPAIR_INTERNAL_INSPECT_SURFACE_ARRAYS_H

#include <mrepair/internal/inspect/parallel.h>
#include <mrepair/internal/utility.h>

#include <CGAL/number_utils.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace mrepair {
namespace internal {

using Inspect_index = std::uint32_t;
constexpr Inspect_index inspect_npos = std::numeric_limits<Inspect_index>::max();

// A polygon soup or mesh flattened into index arrays, so that every inspection
// pass is a loop over a contiguous range (parallel where it pays) whatever the
// input type. Corner c of face f is vertex corner_v[c]; it starts the directed
// edge (corner_v[c], corner_v[next(c)]), whose undirected edge is corner_e[c].
// Edges list their incident corners in edge_corners[edge_off[e]..edge_off[e+1]).
struct Surface_arrays
{
  std::size_t num_vertices = 0;
  std::vector<double> xyz;             // 3 per vertex
  std::vector<unsigned char> finite;   // per vertex: all coordinates finite
  std::vector<Inspect_index> face_off{0};
  std::vector<Inspect_index> corner_v;
  std::vector<Inspect_index> corner_f;
  std::vector<Inspect_index> corner_e; // inspect_npos for faces left out of the topology
  std::vector<unsigned char> face_skip; // soup faces with a repeated index: no edges
  std::vector<Inspect_index> edge_v;   // 2 per edge
  std::vector<Inspect_index> edge_off{0};
  std::vector<Inspect_index> edge_corners;
  // per vertex, filled for the self-intersection counter (certify_flat_stars)
  std::vector<unsigned char> flat_star;

  std::size_t num_faces() const { return face_off.size() - 1; }
  std::size_t num_edges() const { return edge_off.size() - 1; }
  std::size_t degree(std::size_t f) const { return face_off[f + 1] - face_off[f]; }
  std::size_t next_corner(std::size_t c) const
  {
    std::size_t f = corner_f[c];
    return c + 1 == face_off[f + 1] ? face_off[f] : c + 1;
  }
  std::size_t prev_corner(std::size_t c) const
  {
    std::size_t f = corner_f[c];
    return c == face_off[f] ? face_off[f + 1] - 1 : c - 1;
  }
  const double* point(std::size_t v) const { return &xyz[3 * v]; }
};

// frees what the self-intersection counter does not read (it reads the
// points, the faces' corners and the corners' edges), before it allocates.
inline void keep_for_self_intersections(Surface_arrays& a)
{
  free_memory(a.corner_f, a.edge_v, a.edge_corners, a.face_skip, a.finite);
  a.edge_off.assign(1, 0);  // num_edges() is 0 from here on
}

// true when a face has the same vertex index twice.
inline bool has_repeated_index(const Inspect_index* v, std::size_t k)
{
  if (k == 3) return v[0] == v[1] || v[1] == v[2] || v[0] == v[2];
  if (k <= 16) {
    for (std::size_t i = 0; i < k; ++i)
      for (std::size_t j = i + 1; j < k; ++j)
        if (v[i] == v[j]) return true;
    return false;
  }
  std::vector<Inspect_index> s(v, v + k);
  std::sort(s.begin(), s.end());
  return std::adjacent_find(s.begin(), s.end()) != s.end();
}

// The corners of each vertex in corner order: corners[first[v]] ..
// corners[first[v+1]-1] (a counting sort on corner_v).
inline void vertex_corner_table(const Surface_arrays& a, std::vector<Inspect_index>& first,
                                std::vector<Inspect_index>& corners)
{
  bucket_items(a.corner_v.size(), a.num_vertices, inspect_npos,
               [&](std::size_t c) { return a.corner_v[c]; }, first, corners);
}

// Fills corner_f from face_off.
inline void fill_corner_faces(Surface_arrays& a)
{
  a.corner_f.resize(a.corner_v.size());
  parallel_for_index(a.num_faces(), 4096, [&](std::size_t f) {
    for (std::size_t c = a.face_off[f]; c < a.face_off[f + 1]; ++c)
      a.corner_f[c] = static_cast<Inspect_index>(f);
  });
}

// Builds the undirected edges of a soup from its corners in linear time:
// corners are bucketed by the smaller endpoint of their edge (counting sort),
// then each bucket, a handful of corners, is sorted by the larger endpoint.
inline void build_soup_edges(Surface_arrays& a)
{
  const std::size_t nv = a.num_vertices, nc = a.corner_v.size();
  a.corner_e.assign(nc, inspect_npos);
  std::vector<Inspect_index> lo(nc), hi(nc);
  parallel_for_index(nc, 16384, [&](std::size_t c) {
    Inspect_index u = a.corner_v[c], w = a.corner_v[a.next_corner(c)];
    lo[c] = std::min(u, w);
    hi[c] = std::max(u, w);
  });
  std::vector<Inspect_index> bucket, sorted;
  bucket_items(nc, nv, inspect_npos,
               [&](std::size_t c) { return a.face_skip[a.corner_f[c]] ? inspect_npos : lo[c]; }, bucket, sorted);
  const Inspect_index total = bucket[nv];
  std::vector<Inspect_index> count(nv + 1, 0);
  parallel_for_index(nv, 8192, [&](std::size_t v) {
    auto b = sorted.begin() + bucket[v], e = sorted.begin() + bucket[v + 1];
    if (e - b > 1)
      std::sort(b, e, [&](Inspect_index x, Inspect_index y) {
        return hi[x] != hi[y] ? hi[x] < hi[y] : x < y;
      });
    Inspect_index n = 0;
    for (auto it = b; it != e; ++it)
      if (it == b || hi[*it] != hi[*(it - 1)]) ++n;
    count[v] = n;
  });
  const Inspect_index ne = exclusive_scan_in_place(count);
  a.edge_v.resize(2 * std::size_t(ne));
  a.edge_off.resize(std::size_t(ne) + 1);
  a.edge_off[ne] = total;
  parallel_for_index(nv, 8192, [&](std::size_t v) {
    Inspect_index e = count[v];
    for (Inspect_index i = bucket[v]; i < bucket[v + 1]; ++i) {
      Inspect_index c = sorted[i];
      if (i == bucket[v] || hi[c] != hi[sorted[i - 1]]) {
        if (i != bucket[v]) ++e;
        a.edge_v[2 * std::size_t(e)] = static_cast<Inspect_index>(v);
        a.edge_v[2 * std::size_t(e) + 1] = hi[c];
        a.edge_off[e] = i;
      }
      a.corner_e[c] = e;
    }
  });
  a.edge_corners.swap(sorted);
}

// A soup polygon the inspection keeps: at least 3 indices, all in [0, nv).
template <typename Polygon>
bool is_kept_soup_polygon(const Polygon& poly, std::size_t nv)
{
  std::size_t k = 0;
  for (const auto& idx : poly) {
    using I = std::decay_t<decltype(idx)>;
    if constexpr (std::is_signed<I>::value) {
      if (idx < 0) return false;
    }
    if (static_cast<std::size_t>(idx) >= nv) return false;
    ++k;
  }
  return k >= 3;
}

// Flattens a polygon soup. Polygons with fewer than 3 vertices or an index out
// of [0, points.size()) are left out and counted in `invalid_polygons`.
// Returns false when the soup is too large for 32-bit indices.
template <typename PointRange, typename PolygonRange>
bool build_soup_arrays(const PointRange& points, const PolygonRange& polygons,
                       Surface_arrays& a, std::size_t& invalid_polygons)
{
  const std::size_t nv = static_cast<std::size_t>(std::distance(std::begin(points), std::end(points)));
  if (nv >= inspect_npos) return false;
  a.num_vertices = nv;
  a.xyz.resize(3 * nv);
  a.finite.resize(nv);
  std::size_t i = 0;
  for (const auto& p : points) {
    double x = CGAL::to_double(p.x()), y = CGAL::to_double(p.y()), z = CGAL::to_double(p.z());
    a.xyz[3 * i] = x;
    a.xyz[3 * i + 1] = y;
    a.xyz[3 * i + 2] = z;
    a.finite[i] = std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
    ++i;
  }
  invalid_polygons = 0;
  a.face_off.assign(1, 0);
  a.corner_v.clear();
  a.corner_v.reserve(3 * static_cast<std::size_t>(
                             std::distance(std::begin(polygons), std::end(polygons))));
  for (const auto& poly : polygons) {
    if (!is_kept_soup_polygon(poly, nv)) {
      ++invalid_polygons;
      continue;
    }
    for (const auto& idx : poly) a.corner_v.push_back(static_cast<Inspect_index>(idx));
    if (a.corner_v.size() >= inspect_npos) return false;
    a.face_off.push_back(static_cast<Inspect_index>(a.corner_v.size()));
  }
  fill_corner_faces(a);
  const std::size_t nf = a.num_faces();
  a.face_skip.assign(nf, 0);
  parallel_for_index(nf, 4096, [&](std::size_t f) {
    a.face_skip[f] = has_repeated_index(&a.corner_v[a.face_off[f]], a.degree(f));
  });
  build_soup_edges(a);
  return true;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_INSPECT_SURFACE_ARRAYS_H
