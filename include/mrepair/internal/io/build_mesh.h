// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_BUILD_MESH_H
#define MREPAIR_INTERNAL_IO_BUILD_MESH_H

// A fast polygon-soup-to-mesh builder on flat arrays. It checks what
// CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh checks
// (polygons of >= 3 distinct vertices, every directed edge used once, every
// vertex's faces forming one fan) with sorted per-vertex halfedge lists
// instead of a std::set, then builds the mesh with the halfedge builder
// (internal/halfedge_builder.h). Points not used by any
// polygon are left out (polygon_soup_to_polygon_mesh would add them as
// isolated vertices, which CGAL 5.5's is_valid_polygon_mesh rejects and
// mrepair never outputs).

#include <mrepair/internal/halfedge_builder.h>
#include <mrepair/internal/inspect/parallel.h>
#include <mrepair/internal/utility.h>

#include <boost/graph/graph_traits.hpp>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace mrepair {
namespace internal {
namespace io {

/// the halfedge topology of a soup: corner c is the halfedge from vertex
/// indices[c] to the next vertex of its polygon. `Index` holds corner and
/// vertex numbers: 32 bits for every soup below 4G corners and points (half
/// the memory to fill, and its page faults, at 1M faces 60 MB fewer), 64
/// bits beyond (with_soup_topology chooses).
template <class Index>
class Basic_soup_topology
{
  // a corner and the target of its edge, grouped by source
  struct Out
  {
    Index dst, corner;
  };

public:
  static constexpr std::size_t none = no_corner;   ///< "no element" among the results of the checks
  static constexpr Index absent = Index(-1);       ///< no opposite corner (a border edge)
  std::vector<Index> next, prev, opposite;  // per corner
  std::vector<Index> out_start, out;        // corners leaving each vertex (CSR)

  /// the opposite of corner c, or no_corner on the border
  std::size_t opposite_of(std::size_t c) const
  {
    return opposite[c] == absent ? no_corner : static_cast<std::size_t>(opposite[c]);
  }
  bool used(std::size_t v) const { return out_start[v + 1] != out_start[v]; }

  /// returns false with a reason when the soup is not a polygon mesh. The
  /// passes over polygons and vertices run in parallel blocks; the reason is
  /// the one of the first element that fails, as a sequential scan gives it.
  bool compute(std::size_t num_points, const std::int64_t* indices, const std::size_t* starts,
               std::size_t num_polygons, std::string& why)
  {
    const std::size_t nc = starts[num_polygons];
    next.resize(nc);
    prev.resize(nc);
    auto polygon_ok = [&](std::size_t f, std::string& reason) {
      const std::size_t b = starts[f], e = starts[f + 1];
      if (e - b < 3) {
        reason = "polygon " + std::to_string(f) + " has fewer than 3 vertices";
        return false;
      }
      for (std::size_t c = b; c < e; ++c) {
        if (indices[c] < 0 || static_cast<std::uint64_t>(indices[c]) >= num_points) {
          reason = "polygon " + std::to_string(f) + " has an index out of range";
          return false;
        }
        next[c] = static_cast<Index>(c + 1 < e ? c + 1 : b);
        prev[c] = static_cast<Index>(c > b ? c - 1 : e - 1);
      }
      // no vertex twice in a polygon (small polygons: pairwise; large: sorted copy)
      bool repeated = false;
      if (e - b <= 8) {
        for (std::size_t i = b; i < e && !repeated; ++i)
          for (std::size_t j = i + 1; j < e && !repeated; ++j) repeated = indices[i] == indices[j];
      } else {
        thread_local std::vector<std::int64_t> sorted;  // reused: large polygons are few but may be many
        sorted.assign(indices + b, indices + e);
        std::sort(sorted.begin(), sorted.end());
        repeated = std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
      }
      if (repeated) {
        reason = "polygon " + std::to_string(f) + " repeats a vertex";
        return false;
      }
      return true;
    };
    if (first_failure(num_polygons, polygon_ok, why) != none) return false;
    if (!link_corners(num_points, indices, nc, why)) return false;
    // one fan per vertex: corners at v chained by c -> next[opposite[c]]
    auto fan_ok = [&](std::size_t v, std::string& reason) {
      const std::size_t deg = out_start[v + 1] - out_start[v];
      if (deg == 0) return true;
      std::size_t start = none, starts_count = 0;
      for (std::size_t k = out_start[v]; k < out_start[v + 1]; ++k) {
        const std::size_t c = out[k];
        if (opposite[prev[c]] == absent) {
          ++starts_count;
          start = c;
        }
      }
      if (starts_count > 1) {
        reason = "vertex " + std::to_string(v) + " is non-manifold (several fans of faces)";
        return false;
      }
      if (start == none) start = out[out_start[v]];
      std::size_t steps = 0, c = start;
      do {
        ++steps;
        c = opposite[c] == absent ? none : static_cast<std::size_t>(next[opposite[c]]);
      } while (c != none && c != start && steps <= deg);
      if (steps != deg) {
        reason = "vertex " + std::to_string(v) + " is non-manifold (several fans of faces)";
        return false;
      }
      return true;
    };
    return first_failure(num_points, fan_ok, why) == none;
  }

private:
  /// the corners grouped by source vertex (out_start, out) and each corner's
  /// opposite, with the checks of the groups (no edge used twice in the same
  /// direction, no degenerate edge); false with the first failure in `why`.
  bool link_corners(std::size_t num_points, const std::int64_t* indices, std::size_t nc, std::string& why)
  {
    auto src = [&](std::size_t c) { return static_cast<std::size_t>(indices[c]); };
    auto dst = [&](std::size_t c) { return static_cast<std::size_t>(indices[next[c]]); };

    // corners grouped by source vertex, each group sorted by target; the
    // target is stored beside the corner so that lookups stay in one group
    // (a stable counting sort by source, parallel at 1M corners and up: each
    // group keeps its corners in increasing order, as one sequential pass)
    bucket_items(nc, num_points, absent, [&](std::size_t c) { return static_cast<Index>(src(c)); },
                 out_start, out);
    std::vector<Out> adj(nc);
    parallel_blocks(nc, [&](std::size_t k) {
      const std::size_t c = out[k];
      adj[k] = Out{static_cast<Index>(dst(c)), static_cast<Index>(c)};
    });
    auto group_ok = [&](std::size_t v, std::string& reason) {
      if (out_start[v] == out_start[v + 1]) return true;  // no corner (adj may be empty: no pointer arithmetic)
      Out* b = adj.data() + out_start[v];
      Out* e = adj.data() + out_start[v + 1];
      if (e - b <= 16) {  // insertion sort: groups are small (valence)
        for (Out* i = b + 1; i < e; ++i)
          for (Out* j = i; j > b && j->dst < (j - 1)->dst; --j) std::swap(*j, *(j - 1));
      } else {
        std::sort(b, e, [](const Out& x, const Out& y) { return x.dst < y.dst; });
      }
      for (Out* it = b; it != e; ++it) {
        if (it->dst == v) {
          reason = "a polygon repeats vertex " + std::to_string(v);
          return false;
        }
        if (it + 1 != e && it->dst == (it + 1)->dst) {
          reason = "edge (" + std::to_string(v) + ", " + std::to_string(it->dst) +
                   ") is used twice in the same direction (non-manifold edge or inconsistent orientation)";
          return false;
        }
      }
      return true;
    };
    if (first_failure(num_points, group_ok, why) != none) return false;
    // opposite of corner c (u -> w): the corner w -> u
    opposite.assign(nc, absent);
    parallel_blocks(num_points, [&](std::size_t u) {
      for (std::size_t k = out_start[u]; k < out_start[u + 1]; ++k) {
        out[k] = adj[k].corner;
        const std::size_t w = adj[k].dst;
        const Out* b = adj.data() + out_start[w];
        const Out* e = adj.data() + out_start[w + 1];
        const Out* it =
            e - b <= 16 ? std::find_if(b, e, [u](const Out& o) { return o.dst == u; })
                        : std::lower_bound(b, e, u, [](const Out& o, std::size_t t) { return o.dst < t; });
        if (it != e && it->dst == u) opposite[adj[k].corner] = it->corner;
      }
    });
    return true;
  }

  static constexpr std::size_t block_size = std::size_t(1) << 14;

  // calls f(i) for i in [0, n), in parallel blocks
  template <class F>
  static void parallel_blocks(std::size_t n, const F& f)
  {
    const std::size_t blocks = (n + block_size - 1) / block_size;
    parallel_for_index(blocks, 1, [&](std::size_t b) {
      for (std::size_t i = b * block_size; i < std::min(n, (b + 1) * block_size); ++i) f(i);
    });
  }

  // runs ok(i, reason) for i in [0, n) in parallel blocks, each block up to
  // its first failure; returns the smallest failing i (its reason in `why`),
  // or none
  template <class Check>
  static std::size_t first_failure(std::size_t n, const Check& ok, std::string& why)
  {
    const std::size_t blocks = (n + block_size - 1) / block_size;
    std::vector<std::size_t> failed(blocks, none);
    std::vector<std::string> reasons(blocks);
    parallel_for_index(blocks, 1, [&](std::size_t b) {
      for (std::size_t i = b * block_size; i < std::min(n, (b + 1) * block_size); ++i)
        if (!ok(i, reasons[b])) {
          failed[b] = i;
          return;
        }
    });
    for (std::size_t b = 0; b < blocks; ++b)
      if (failed[b] != none) {
        why = reasons[b];
        return failed[b];
      }
    return none;
  }
};

using Soup_topology = Basic_soup_topology<std::size_t>;

/// calls f(topology) with an empty topology of the narrowest index type that
/// holds `num_points` points and `num_corners` corners
template <class F>
void with_soup_topology(std::size_t num_points, std::size_t num_corners, const F& f)
{
  if (num_corners < std::numeric_limits<std::uint32_t>::max() &&
      num_points < std::numeric_limits<std::uint32_t>::max()) {
    Basic_soup_topology<std::uint32_t> t;
    f(t);
  } else {
    Basic_soup_topology<std::size_t> t;
    f(t);
  }
}

/// builds `g` (assumed empty) from a soup whose topology `t` was computed
/// successfully; `put_point(v, i)` stores point i at vertex v.
template <class Topology, class PolygonMesh, class PutPoint>
void build_mesh(const Topology& t, std::size_t num_points, const std::int64_t* indices,
                const std::size_t* starts, std::size_t num_polygons, PolygonMesh& g,
                PutPoint put_point)
{
  // the soup as a corner table for the halfedge builder
  struct Corners
  {
    const Topology& t;
    std::size_t np;
    const std::int64_t* indices;
    const std::size_t* starts;
    std::size_t nf;
    std::size_t num_points() const { return np; }
    std::size_t num_faces() const { return nf; }
    std::size_t num_corners() const { return starts[nf]; }
    std::size_t begin(std::size_t f) const { return starts[f]; }
    std::size_t end(std::size_t f) const { return starts[f + 1]; }
    std::size_t source(std::size_t c) const { return static_cast<std::size_t>(indices[c]); }
    std::size_t next(std::size_t c) const { return t.next[c]; }
    std::size_t opposite(std::size_t c) const { return t.opposite_of(c); }
    // only points used by a polygon: no isolated vertex (5.5's validity check rejects one)
    bool used(std::size_t v) const { return t.used(v); }
  };
  const Corners m{t, num_points, indices, starts, num_polygons};
  std::size_t num_used = 0;
  for (std::size_t i = 0; i < num_points; ++i) num_used += m.used(i);
  // an edge per pair of opposite corners and per border corner
  const std::size_t border =
      static_cast<std::size_t>(std::count(t.opposite.begin(), t.opposite.end(), Topology::absent));
  const std::size_t num_edges = (m.num_corners() + border) / 2;
  build_halfedge_mesh(g, m, Element_counts{num_used, num_edges, num_polygons}, put_point);
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_BUILD_MESH_H
