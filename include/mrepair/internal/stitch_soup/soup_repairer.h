// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_STITCH_SOUP_SOUP_REPAIRER_H
#define MREPAIR_INTERNAL_STITCH_SOUP_SOUP_REPAIRER_H

// The cutting-and-stitching pipeline (Gueziec, Taubin, Lazarus, Horn) on flat
// arrays: points as double triples, faces as index triples, one "slot" per
// face side (3 * face + i is the side from corner i to corner i + 1). Edge
// tables come from sorting (min, max) keys, never from per-face maps.
//
//   load       merge points (exact sort, then grid + union-find within epsilon),
//              drop bad polygons, triangulate n-gons (ear clipping), drop
//              degenerate and duplicate triangles and internal walls (both copies)
//   pair       sort sides by edge; two sides: partners; more (a fin): pair
//              them by angle around the edge (see pair_fin)
//   orient     BFS spanning tree per component; a non-tree side pair that
//              disagrees is cut (Moebius bands)
//   split      corners glued across partnered sides form fans; each extra fan
//              of a vertex gets a copy of the vertex
//   stitch     optional: boundary sides whose ends lie within epsilon are glued
//              (flipping the smaller component when needed), then pair, orient
//              and split run again so that stitching never leaves a complex
//              edge or vertex
//   outward    optional: closed components inside no other get positive
//              volume; nested ones keep their input orientation (ray parity)
//   build      the halfedge builder (halfedge_builder.h) reads the partner table

#include <mrepair/internal/halfedge_builder.h>
#include <mrepair/internal/inspect/parallel.h>
#include <mrepair/internal/polygon_triangulation.h>
#include <mrepair/internal/spatial_grid.h>
#include <mrepair/internal/utility.h>
#include <mrepair/stitch_soup_result.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Bbox_3.h>
#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/number_utils.h>

#include <boost/graph/graph_traits.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {

using Soup_index = std::uint32_t;

template <typename I>
bool soup_index_is_valid(const I& id, std::size_t n)
{
  if constexpr (std::is_integral<I>::value) {
    if constexpr (std::is_signed<I>::value) {
      if (id < 0) return false;
    }
    return static_cast<unsigned long long>(id) < static_cast<unsigned long long>(n);
  } else {
    return false;
  }
}

class Soup_repairer
{
public:
  using Idx = Soup_index;
  using Vec = std::array<double, 3>;
  static constexpr Idx none = std::numeric_limits<Idx>::max();

  struct Options
  {
    double merge_epsilon = 0;
    double snap_epsilon = 0;
    bool keep_two_sided = false;
    bool orient_outward = true;
  };

  std::vector<Vec> P;                    // points (ids are indices)
  std::vector<std::array<Idx, 3>> T;     // triangles
  std::vector<Idx> partner;              // per slot: partner slot or none
  std::vector<unsigned char> reversed;   // per triangle: reversed w.r.t. its input polygon
  std::vector<Idx> comp;                 // per triangle: component (after orient)
  std::vector<Idx> comp_faces;           // per component: face count
  std::vector<unsigned char> comp_closed;

  Soup_repair_result& r;
  Options opt;
  std::size_t fins_ = 0;  // complex edges met by the last pair_edges()
  std::size_t cuts_ = 0;  // sides cut by the last orient()
  // sides of fins and cut sides since the last pair_edges(): after splitting,
  // only they can share a vertex pair with another side
  std::vector<Idx> suspect_;

  Soup_repairer(Soup_repair_result& result, const Options& o) : r(result), opt(o) {}

  // ---------------------------------------------------------------- small helpers
  static Idx src_corner(Idx s) { return s; }
  static Idx dst_corner(Idx s) { return 3 * (s / 3) + (s % 3 + 1) % 3; }
  Idx src(Idx s) const { return T[s / 3][s % 3]; }
  Idx dst(Idx s) const { return T[s / 3][(s % 3 + 1) % 3]; }
  static double dist2(const Vec& a, const Vec& b) { return squared_norm(sub(a, b)); }
  static std::uint64_t edge_key(Idx a, Idx b)
  {
    if (b < a) std::swap(a, b);
    return (std::uint64_t(a) << 32) | b;
  }

  // ---------------------------------------------------------------- load
  // Reads the soup: returns false (with status set) when the input cannot be indexed.
  template <class PointRange, class PolygonRange>
  bool load(const PointRange& points, const PolygonRange& polygons)
  {
    const std::size_t n = static_cast<std::size_t>(std::distance(std::begin(points), std::end(points)));
    r.points_in = n;
    r.polygons_in = static_cast<std::size_t>(std::distance(std::begin(polygons), std::end(polygons)));
    if (n >= std::size_t(none) / 4 || r.polygons_in >= std::size_t(none) / 8) {
      r.status = Status::invalid_parameter;
      r.message = "soup too large for 32-bit indices";
      return false;
    }
    P.resize(n);
    std::vector<unsigned char> finite(n, 1);
    std::size_t k = 0;
    for (const auto& p : points) {
      Vec v{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
      P[k] = v;
      if (!(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]))) {
        finite[k] = 0;
        ++r.non_finite_points;
      }
      ++k;
    }
    std::vector<Idx> rep = merge_points(finite);

    T.reserve(r.polygons_in + r.polygons_in / 4);
    std::vector<Idx> poly;
    std::vector<std::array<Idx, 3>> tris;
    for (const auto& polygon : polygons) {
      poly.clear();
      bool bad_index = false, bad_point = false;
      for (const auto& id : polygon) {
        if (!soup_index_is_valid(id, n)) {
          bad_index = true;
          continue;
        }
        std::size_t v = static_cast<std::size_t>(id);
        if (!finite[v]) bad_point = true;
        poly.push_back(rep[v]);
      }
      if (bad_index) {
        ++r.faces_in;
        ++r.removed_invalid_index;
        continue;
      }
      if (bad_point) {
        ++r.faces_in;
        ++r.removed_non_finite;
        continue;
      }
      // zero-length sides (repeated consecutive indices) are dropped, not the polygon
      std::size_t m = 0;
      for (std::size_t i = 0; i < poly.size(); ++i)
        if (m == 0 || poly[m - 1] != poly[i]) poly[m++] = poly[i];
      while (m > 1 && poly[m - 1] == poly[0]) --m;
      poly.resize(m);
      if (m < 3) {
        ++r.faces_in;
        ++r.removed_degenerate_index;
        continue;
      }
      if (m == 3) {
        add_triangle(poly[0], poly[1], poly[2]);
      } else {
        ++r.polygons_triangulated;
        tris.clear();
        triangulate(poly, tris);
        for (const auto& t : tris) add_triangle(t[0], t[1], t[2]);
      }
    }
    remove_duplicates();
    reversed.assign(T.size(), 0);
    std::size_t distinct = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (finite[i] && rep[i] == i) ++distinct;
    std::size_t used = compact_points();
    r.points_unreferenced = distinct - used;
    return true;
  }

  std::vector<Idx> merge_points(const std::vector<unsigned char>& finite)
  {
    const std::size_t n = P.size();
    std::vector<Idx> rep(n);
    std::iota(rep.begin(), rep.end(), Idx(0));
    // exact merging by open addressing on the coordinate bits (-0 == +0):
    // linear, and the first (smallest) index of a location is its representative
    std::vector<Idx> order;
    order.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      if (finite[i]) order.push_back(Idx(i));
    std::size_t cap = 16;
    while (cap < 2 * order.size()) cap <<= 1;
    std::vector<Idx> table(cap, none);
    auto bits = [](double d) {
      d += 0.0;  // -0.0 becomes +0.0
      std::uint64_t u;
      std::memcpy(&u, &d, sizeof u);
      return u;
    };
    for (Idx i : order) {
      const Vec& p = P[i];
      std::uint64_t h = bits(p[0]) * 0x9E3779B97F4A7C15ull;
      h = (h ^ (h >> 29)) + bits(p[1]) * 0xC2B2AE3D27D4EB4Full;
      h = (h ^ (h >> 31)) + bits(p[2]) * 0x165667B19E3779F9ull;
      h ^= h >> 32;
      std::size_t slot = std::size_t(h) & (cap - 1);
      while (table[slot] != none && P[table[slot]] != p) slot = (slot + 1) & (cap - 1);
      if (table[slot] == none)
        table[slot] = i;
      else
        rep[i] = table[slot];
    }
    std::vector<Idx>().swap(table);
    if (opt.merge_epsilon > 0) {
      std::vector<Idx> reps;
      for (std::size_t i = 0; i < order.size(); ++i)
        if (rep[order[i]] == order[i]) reps.push_back(order[i]);
      Union_find<Idx> uf(n);
      near_pairs(reps, opt.merge_epsilon, [&](Idx a, Idx b) { uf.unite(a, b); });
      for (Idx i : order) rep[i] = uf.find(rep[i]);
    }
    for (std::size_t i = 0; i < n; ++i)
      if (finite[i] && rep[i] != i) ++r.points_merged;
    return rep;
  }

  // Grid cell: eps, or larger when coordinates / eps would overflow 64-bit
  // cell indices (a larger cell still finds every pair within eps).
  double cell_size(double eps) const
  {
    double m = 0;
    for (const Vec& p : P)
      for (double x : p)
        if (std::isfinite(x)) m = std::max(m, std::abs(x));
    return std::max(eps, m * 1e-15);
  }

  // Calls f(a, b) for every pair of ids (a != b) whose points lie within eps, by a grid of cell eps.
  template <class F>
  void near_pairs(const std::vector<Idx>& ids, double eps, F f)
  {
    const Spatial_grid<Idx> grid(cell_size(eps), ids, [&](Idx i) -> const Vec& { return P[i]; });
    const double eps2 = eps * eps;
    for (const auto& e : grid.entries()) {
      const Idx a = e.id;
      grid.for_each_near(e.c, [&](Idx b) {
        if (b <= a) return;  // each pair once
        if (dist2(P[a], P[b]) <= eps2) f(a, b);
      });
    }
  }

  void add_triangle(Idx a, Idx b, Idx c)
  {
    ++r.faces_in;
    if (a == b || b == c || a == c) {
      ++r.removed_degenerate_index;
      return;
    }
    using K = CGAL::Epick;
    K::Point_3 pa(P[a][0], P[a][1], P[a][2]), pb(P[b][0], P[b][1], P[b][2]),
        pc(P[c][0], P[c][1], P[c][2]);
    if (K().collinear_3_object()(pa, pb, pc)) {
      ++r.removed_collinear;
      return;
    }
    T.push_back({a, b, c});
  }

  // Ear clipping (polygon_triangulation.h); a polygon with no ear left is
  // finished as a fan, whose collinear triangles are then dropped and counted.
  void triangulate(const std::vector<Idx>& poly, std::vector<std::array<Idx, 3>>& out)
  {
    std::vector<Vec3> corners(poly.size());
    for (std::size_t i = 0; i < poly.size(); ++i) corners[i] = P[poly[i]];
    clip_ears(corners, poly, [](std::size_t, std::size_t) { return true; },
              [&](std::size_t a, std::size_t b, std::size_t c) { out.push_back({poly[a], poly[b], poly[c]}); });
  }

  // Same vertex set: keep the first face (and with keep_two_sided, the first of
  // the opposite orientation too), in input order. A set given exactly twice
  // that walls off two bodies loses both copies (find_internal_walls).
  void remove_duplicates()
  {
    struct Key
    {
      std::uint64_t hi;
      Idx lo, t;
    };
    const std::size_t F = T.size();
    std::vector<Key> keys(F);
    std::vector<unsigned char> parity(F);
    parallel_for_index(F, 16384, [&](std::size_t t) {
      std::array<Idx, 3> s = T[t];
      int mi = 0;
      if (s[1] < s[mi]) mi = 1;
      if (s[2] < s[mi]) mi = 2;
      Idx a = s[mi], b = s[(mi + 1) % 3], c = s[(mi + 2) % 3];
      parity[t] = b < c;
      if (c < b) std::swap(b, c);
      keys[t] = {(std::uint64_t(a) << 32) | b, c, Idx(t)};
    });
    {  // counting sort on the smallest vertex (bucket_items), then each bucket by (b, c, t)
      std::vector<Idx> start, order;
      bucket_items(F, P.size(), none, [&](std::size_t t) { return Idx(keys[t].hi >> 32); }, start, order);
      std::vector<Key> sorted(F);
      parallel_for_index(F, 16384, [&](std::size_t j) { sorted[j] = keys[order[j]]; });
      free_memory(order);
      keys.swap(sorted);
      parallel_for_index(P.size(), 8192, [&](std::size_t v) {
        if (start[v + 1] - start[v] > 1)
          sort_small(keys.begin() + start[v], keys.begin() + start[v + 1], [](const Key& x, const Key& y) {
            if (x.hi != y.hi) return x.hi < y.hi;
            if (x.lo != y.lo) return x.lo < y.lo;
            return x.t < y.t;
          });
      });
    }
    std::vector<unsigned char> keep(F, 1);
    std::vector<std::array<Idx, 2>> twice;  // sets given exactly twice: decided after the wall test
    for (std::size_t i = 0; i < F;) {
      std::size_t j = i + 1;
      while (j < F && keys[j].hi == keys[i].hi && keys[j].lo == keys[i].lo) ++j;
      if (j - i == 2) {
        twice.push_back({keys[i].t, keys[i + 1].t});
        i = j;
        continue;
      }
      bool seen[2] = {false, false};
      bool any = false;
      for (std::size_t k = i; k < j; ++k) {
        Idx t = keys[k].t;
        unsigned char p = parity[t];
        if (!any || (opt.keep_two_sided && !seen[p])) {
          seen[p] = true;
          any = true;
        } else {
          keep[t] = 0;
          ++r.removed_duplicate;
        }
      }
      i = j;
    }
    free_memory(keys);
    const std::vector<unsigned char> wall = find_internal_walls(twice, parity);
    for (std::size_t p = 0; p < twice.size(); ++p) {
      const Idx a = twice[p][0], b = twice[p][1];  // a first in input order
      if (wall[p]) {
        keep[a] = keep[b] = 0;
        r.removed_internal_walls += 2;
      } else if (!(opt.keep_two_sided && parity[a] != parity[b])) {
        keep[b] = 0;
        ++r.removed_duplicate;
      }
    }
    std::size_t w = 0;
    for (std::size_t t = 0; t < F; ++t)
      if (keep[t]) T[w++] = T[t];
    T.resize(w);
  }

  // Which of the vertex sets given exactly twice (`twice`: the two faces, in
  // input order) are internal walls, as when two solids glued on a face are
  // written each with its own copy of it. Every edge of such a face has four
  // faces: the two copies and either one face on each side of the face's
  // plane (a body each side) or both copies of another such set (a wall of
  // several triangles). Decided per patch of sets joined by the latter edges:
  // one failing face keeps the whole patch, and so does a patch without a body
  // edge (a doubled closed shell), so a doubled patch on one shell keeps one
  // copy. With keep_two_sided a patch with an opposite pair is kept (the
  // option keeps those). Costs one parallel pass over the faces, and only
  // when some set is given twice.
  std::vector<unsigned char> find_internal_walls(const std::vector<std::array<Idx, 2>>& twice,
                                                 const std::vector<unsigned char>& parity) const
  {
    const std::size_t n = twice.size();
    std::vector<unsigned char> wall(n, 0);
    if (n == 0) return wall;
    std::vector<std::uint64_t> ek;  // the candidates' edges
    ek.reserve(3 * n);
    std::vector<unsigned char> marked(P.size(), 0);
    for (const auto& pr : twice) {
      const auto& f = T[pr[0]];
      for (int i = 0; i < 3; ++i) {
        ek.push_back(edge_key(f[i], f[(i + 1) % 3]));
        marked[f[i]] = 1;
      }
    }
    std::sort(ek.begin(), ek.end());
    ek.erase(std::unique(ek.begin(), ek.end()), ek.end());
    auto edge_id = [&](Idx a, Idx b) -> Idx {
      const std::uint64_t k = edge_key(a, b);
      auto it = std::lower_bound(ek.begin(), ek.end(), k);
      return (it != ek.end() && *it == k) ? Idx(it - ek.begin()) : none;
    };
    // the faces on those edges, by edge, in face order (the vertex marks skip
    // the search on almost every side)
    using Hits = std::vector<std::pair<Idx, Idx>>;  // (edge, face)
    const std::vector<Hits> parts = chunked<Hits>(T.size(), [&](std::size_t b, std::size_t e, Hits& h) {
      for (std::size_t t = b; t < e; ++t)
        for (int i = 0; i < 3; ++i) {
          const Idx u = T[t][i], v = T[t][(i + 1) % 3];
          if (!marked[u] || !marked[v]) continue;
          const Idx id = edge_id(u, v);
          if (id != none) h.push_back({id, Idx(t)});
        }
    });
    std::vector<Idx> first(ek.size() + 1, 0), on_edge;
    for (const Hits& h : parts)
      for (const auto& x : h) ++first[x.first + 1];
    for (std::size_t e = 0; e < ek.size(); ++e) first[e + 1] += first[e];
    on_edge.resize(first.back());
    {
      std::vector<Idx> pos(first.begin(), first.end() - 1);
      for (const Hits& h : parts)
        for (const auto& x : h) on_edge[pos[x.first]++] = x.second;
    }
    std::vector<std::pair<Idx, Idx>> set_of;  // (face, candidate), by face
    for (std::size_t p = 0; p < n; ++p) {
      set_of.push_back({twice[p][0], Idx(p)});
      set_of.push_back({twice[p][1], Idx(p)});
    }
    std::sort(set_of.begin(), set_of.end());
    auto candidate_of = [&](Idx t) -> Idx {
      auto it = std::lower_bound(set_of.begin(), set_of.end(), std::make_pair(t, Idx(0)));
      return (it != set_of.end() && it->first == t) ? it->second : none;
    };
    using K = CGAL::Epick;
    auto pt = [&](Idx v) { return K::Point_3(P[v][0], P[v][1], P[v][2]); };
    auto apex = [&](Idx t, Idx a, Idx b) {  // the corner of t off the edge (a, b)
      for (Idx v : T[t])
        if (v != a && v != b) return v;
      return T[t][0];
    };
    Union_find<Idx> patch(n);
    std::vector<unsigned char> bad(n, 0), body(n, 0);
    for (std::size_t p = 0; p < n; ++p) {
      const Idx t0 = twice[p][0], t1 = twice[p][1];
      if (opt.keep_two_sided && parity[t0] != parity[t1]) bad[p] = 1;
      const auto& f = T[t0];
      for (int i = 0; i < 3 && !bad[p]; ++i) {
        const Idx a = f[i], b = f[(i + 1) % 3], e = edge_id(a, b);
        if (first[e + 1] - first[e] != 4) {
          bad[p] = 1;
          break;
        }
        Idx other[2], k = 0;
        for (Idx j = first[e]; j < first[e + 1]; ++j)
          if (on_edge[j] != t0 && on_edge[j] != t1) other[k++] = on_edge[j];
        const Idx q0 = candidate_of(other[0]), q1 = candidate_of(other[1]);
        if (q0 == none && q1 == none) {
          const auto s0 = K().orientation_3_object()(pt(f[0]), pt(f[1]), pt(f[2]), pt(apex(other[0], a, b)));
          const auto s1 = K().orientation_3_object()(pt(f[0]), pt(f[1]), pt(f[2]), pt(apex(other[1], a, b)));
          if (s0 != CGAL::COPLANAR && s1 != CGAL::COPLANAR && s0 != s1)
            body[p] = 1;
          else
            bad[p] = 1;
        } else if (q0 == q1) {
          patch.unite(Idx(p), q0);
        } else {
          bad[p] = 1;
        }
      }
    }
    std::vector<unsigned char> patch_bad(n, 0), patch_body(n, 0);
    for (std::size_t p = 0; p < n; ++p) {
      const Idx root = patch.find(Idx(p));
      patch_bad[root] |= bad[p];
      patch_body[root] |= body[p];
    }
    for (std::size_t p = 0; p < n; ++p) {
      const Idx root = patch.find(Idx(p));
      wall[p] = !patch_bad[root] && patch_body[root];
    }
    return wall;
  }

  // Drops points used by no face; keeps the order of the others. Returns how many remain.
  std::size_t compact_points()
  {
    std::vector<Idx> id(P.size(), none);
    for (const auto& t : T)
      for (Idx v : t) id[v] = 0;
    Idx w = 0;
    for (std::size_t i = 0; i < P.size(); ++i)
      if (id[i] != none) {
        id[i] = w;
        P[w++] = P[i];
      }
    P.resize(w);
    for (auto& t : T)
      for (Idx& v : t) v = id[v];
    return w;
  }

  // ---------------------------------------------------------------- pair
  struct Side_key
  {
    std::uint64_t key;
    Idx slot;
  };

  // Sides ordered by (edge key, slot): a counting sort on the smaller vertex
  // (bucket_items: in parallel on large soups), then a sort of each (small)
  // bucket, the buckets in parallel; linear in practice, no comparison sort
  // over all sides.
  std::vector<Side_key> sorted_sides() const
  {
    const std::size_t S = 3 * T.size(), V = P.size();
    std::vector<Idx> start, order;
    bucket_items(S, V, none, [&](std::size_t s) { return std::min(src(Idx(s)), dst(Idx(s))); }, start, order);
    std::vector<Side_key> hes(S);
    parallel_for_index(S, 16384, [&](std::size_t j) {
      const Idx s = order[j];
      hes[j] = {edge_key(src(s), dst(s)), s};
    });
    free_memory(order);
    parallel_for_index(V, 8192, [&](std::size_t v) {
      if (start[v + 1] - start[v] > 1)
        sort_small(hes.begin() + start[v], hes.begin() + start[v + 1],
                   [](const Side_key& a, const Side_key& b) { return a.key < b.key || (a.key == b.key && a.slot < b.slot); });
    });
    return hes;
  }

  // insertion sort for the short buckets, std::sort for long ones
  template <class It, class Less>
  static void sort_small(It first, It last, Less less)
  {
    if (last - first > 32) {
      std::sort(first, last, less);
      return;
    }
    for (It i = first + 1; i < last; ++i) {
      auto x = *i;
      It j = i;
      for (; j > first && less(x, *(j - 1)); --j) *j = *(j - 1);
      *j = x;
    }
  }

  // Fills `partner`; returns the number of complex edges.
  std::size_t pair_edges()
  {
    const std::size_t S = 3 * T.size();
    partner.assign(S, none);
    suspect_.clear();
    std::vector<Side_key> hes = sorted_sides();
    std::size_t complex = 0;
    std::vector<Idx> run;
    for (std::size_t i = 0; i < S;) {
      std::size_t j = i + 1;
      while (j < S && hes[j].key == hes[i].key) ++j;
      if (j - i == 2) {
        partner[hes[i].slot] = hes[i + 1].slot;
        partner[hes[i + 1].slot] = hes[i].slot;
      } else if (j - i > 2) {
        ++complex;
        run.clear();
        for (std::size_t k = i; k < j; ++k) run.push_back(hes[k].slot);
        suspect_.insert(suspect_.end(), run.begin(), run.end());
        pair_fin(hes[i].key, run);
      }
      i = j;
    }
    fins_ = complex;
    return complex;
  }

  // Pairs the faces around a complex edge (u, v). Each face is a half-plane at
  // an angle around the axis u->v; its normal points towards increasing angle
  // when it runs u->v (dir +1). Pass 1 pairs a dir -1 face with a dir +1 face
  // met next counterclockwise (the wedge between them is the inside of a solid
  // bounded by both, and neighbours never cross), smallest gap first, so that
  // consistently oriented solids and sheets keep their faces. Pass 2 pairs what
  // is left by the flattest continuation, consistent pairs first. Coincident
  // faces (two-sided sheets) never pair with each other. Faces left over are
  // cut off along this edge (they become boundary).
  void pair_fin(std::uint64_t key, const std::vector<Idx>& run)
  {
    const std::size_t k = run.size();
    if (k > 256) return;  // pathological fan: cut every face apart
    const Idx u = Idx(key >> 32), v = Idx(key & 0xffffffffu);
    Vec d = sub(P[v], P[u]);
    double len = std::sqrt(dot(d, d));
    if (len > 0)
      for (double& x : d) x /= len;
    else
      d = {1, 0, 0};
    int small = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(d[c]) < std::abs(d[small])) small = c;
    Vec ax{0, 0, 0};
    ax[small] = 1;
    Vec e1 = cross(d, ax);
    double l1 = std::sqrt(dot(e1, e1));
    for (double& x : e1) x /= l1;
    Vec e2 = cross(d, e1);
    std::vector<double> ang(k);
    std::vector<int> dir(k);
    for (std::size_t i = 0; i < k; ++i) {
      Idx s = run[i];
      Idx w = T[s / 3][(s % 3 + 2) % 3];
      Vec rr = sub(P[w], P[u]);
      ang[i] = std::atan2(dot(rr, e2), dot(rr, e1));
      dir[i] = (src(s) == u) ? 1 : -1;
    }
    const double tiny = 1e-12;
    struct Cand
    {
      double score;
      std::size_t a, b;
    };
    std::vector<Cand> cand;
    for (std::size_t i = 0; i < k; ++i) {
      if (dir[i] != -1) continue;
      for (std::size_t j = 0; j < k; ++j) {
        if (dir[j] != 1) continue;
        double gap = ang[j] - ang[i];
        if (gap < 0) gap += two_pi;
        if (gap <= tiny || gap >= two_pi - tiny) continue;
        cand.push_back({gap, i, j});
      }
    }
    std::vector<unsigned char> used(k, 0);
    auto greedy = [&]() {
      std::sort(cand.begin(), cand.end(), [](const Cand& x, const Cand& y) {
        return x.score < y.score || (x.score == y.score && (x.a < y.a || (x.a == y.a && x.b < y.b)));
      });
      for (const Cand& c : cand) {
        if (used[c.a] || used[c.b]) continue;
        used[c.a] = used[c.b] = 1;
        partner[run[c.a]] = run[c.b];
        partner[run[c.b]] = run[c.a];
      }
    };
    greedy();
    cand.clear();
    for (std::size_t i = 0; i < k; ++i) {
      if (used[i]) continue;
      for (std::size_t j = i + 1; j < k; ++j) {
        if (used[j]) continue;
        double diff = std::abs(ang[j] - ang[i]);
        if (diff > two_pi / 2) diff = two_pi - diff;
        if (diff <= tiny) continue;
        double score = std::abs(two_pi / 2 - diff) + (dir[i] == dir[j] ? 10.0 : 0.0);
        cand.push_back({score, i, j});
      }
    }
    greedy();
  }

  // ---------------------------------------------------------------- orient
  // Reverses the flagged triangles and renumbers the partner table (side i of a
  // reversed triangle becomes side 2 - i).
  void apply_flips(const std::vector<unsigned char>& flip)
  {
    const std::size_t S = 3 * T.size();
    auto m = [&](Idx s) { return flip[s / 3] ? Idx(3 * (s / 3) + (2 - s % 3)) : s; };
    std::vector<Idx> np(S, none);
    for (std::size_t s = 0; s < S; ++s)
      np[m(Idx(s))] = partner[s] == none ? none : m(partner[s]);
    partner.swap(np);
    for (Idx& s : suspect_) s = m(s);
    for (std::size_t t = 0; t < T.size(); ++t)
      if (flip[t]) {
        std::swap(T[t][1], T[t][2]);
        reversed[t] ^= 1;
      }
  }

  // Orients every component by a BFS spanning tree, cutting disagreeing
  // non-tree sides; each open component then keeps the orientation of most of
  // its input faces. Fills comp, comp_faces, comp_closed.
  void orient()
  {
    const std::size_t F = T.size();
    comp.assign(F, none);
    cuts_ = 0;
    comp_faces.clear();
    comp_closed.clear();
    std::vector<unsigned char> flip(F, 0);
    std::vector<Idx> queue;
    queue.reserve(F);
    for (std::size_t seed = 0; seed < F; ++seed) {
      if (comp[seed] != none) continue;
      const Idx c = Idx(comp_faces.size());
      comp_faces.push_back(0);
      comp_closed.push_back(1);
      queue.clear();
      queue.push_back(Idx(seed));
      comp[seed] = c;
      for (std::size_t head = 0; head < queue.size(); ++head) {
        const Idx t = queue[head];
        ++comp_faces[c];
        for (Idx i = 0; i < 3; ++i) {
          const Idx s = 3 * t + i, p = partner[s];
          if (p == none) continue;
          const Idx g = p / 3;
          const unsigned char want = flip[t] ^ (src(s) == src(p) ? 1 : 0);
          if (comp[g] == none) {
            comp[g] = c;
            flip[g] = want;
            queue.push_back(g);
          } else if (flip[g] != want) {
            partner[s] = partner[p] = none;
            suspect_.push_back(s);
            suspect_.push_back(p);
            ++r.edges_cut_nonorientable;
            ++cuts_;
          }
        }
      }
    }
    // keep the input orientation of the majority of each component
    std::vector<std::size_t> against(comp_faces.size(), 0);
    for (std::size_t t = 0; t < F; ++t)
      if (flip[t] ^ reversed[t]) ++against[comp[t]];
    for (std::size_t t = 0; t < F; ++t)
      if (2 * against[comp[t]] > comp_faces[comp[t]]) flip[t] ^= 1;
    apply_flips(flip);
    for (std::size_t s = 0; s < 3 * F; ++s)
      if (partner[s] == none) comp_closed[comp[s / 3]] = 0;
  }

  bool unpartner(Idx s)
  {
    if (partner[s] == none) return false;
    suspect_.push_back(s);
    suspect_.push_back(partner[s]);
    partner[partner[s]] = none;
    partner[s] = none;
    return true;
  }

  // ---------------------------------------------------------------- split
  // Gives each fan of faces around a vertex its own vertex. Then any vertex
  // pair still joined by more than one edge (two-sided sheets whose interior
  // edge joins two border vertices, closed non-orientable pieces) has its
  // sides cut and the fans are recomputed, until every vertex pair has at most
  // one edge: the output is then a polygon mesh in the PMP sense.
  // Returns true when sides were cut (components may have changed).
  bool split_vertices(std::vector<unsigned char>& complex_flag)
  {
    bool cut_any = false;
    const std::size_t F = T.size();
    const std::size_t S = 3 * F;
    for (;;) {  // ends: every further round removes at least one partner
      Union_find<Idx> uf(S);
      for (std::size_t s = 0; s < S; ++s) {
        const Idx p = partner[s];
        if (p == none || p < s) continue;
        const Idx a = src(Idx(s));
        const Idx ga = (T[p / 3][p % 3] == a) ? p : dst_corner(p);
        const Idx gb = (ga == p) ? dst_corner(p) : p;
        uf.unite(Idx(s), ga);
        uf.unite(dst_corner(Idx(s)), gb);
      }
      std::vector<Idx> root_id(S, none);
      std::vector<unsigned char> claimed(P.size(), 0);
      complex_flag.resize(P.size(), 0);
      const std::size_t n0 = P.size();
      for (std::size_t c = 0; c < S; ++c) {
        const Idx root = uf.find(Idx(c));
        if (root_id[root] != none) continue;
        const Idx v = T[c / 3][c % 3];
        if (!claimed[v]) {
          claimed[v] = 1;
          root_id[root] = v;
        } else {
          root_id[root] = Idx(P.size());
          Vec pv = P[v];
          P.push_back(pv);
          ++r.vertices_duplicated;
          if (v < n0 && !complex_flag[v]) {
            complex_flag[v] = 1;
            ++r.complex_vertices;
          }
        }
      }
      for (std::size_t c = 0; c < S; ++c) T[c / 3][c % 3] = root_id[uf.find(Idx(c))];
      complex_flag.resize(P.size(), 1);  // copies are not counted again

      // two sides on one vertex pair that are not partners need a fin or a cut
      if (fins_ == 0 && cuts_ == 0) break;
      bool again = false;
      std::sort(suspect_.begin(), suspect_.end());
      suspect_.erase(std::unique(suspect_.begin(), suspect_.end()), suspect_.end());
      std::vector<Side_key> hes(suspect_.size());
      for (std::size_t k = 0; k < suspect_.size(); ++k)
        hes[k] = {edge_key(src(suspect_[k]), dst(suspect_[k])), suspect_[k]};
      std::sort(hes.begin(), hes.end(), [](const Side_key& a, const Side_key& b) {
        return a.key < b.key || (a.key == b.key && a.slot < b.slot);
      });
      const std::size_t H = hes.size();
      for (std::size_t i = 0; i < H;) {
        std::size_t j = i + 1;
        while (j < H && hes[j].key == hes[i].key) ++j;
        bool ok = (j - i == 1) || (j - i == 2 && partner[hes[i].slot] == hes[i + 1].slot);
        if (!ok) {
          bool cut = false;
          for (std::size_t k = i; k < j; ++k) cut = unpartner(hes[k].slot) || cut;
          if (!cut) {
            // only boundary sides join these two vertices (a slit, which CGAL
            // rejects as a two-edge hole): open the fan of the first face at
            // one end so that the vertex splits in the next round
            const Idx s = hes[i].slot, f = s / 3;
            cut = unpartner(3 * f + (s % 3 + 2) % 3) || unpartner(3 * f + (s % 3 + 1) % 3);
          }
          again = again || cut;
        }
        i = j;
      }
      cut_any = cut_any || again;
      if (!again) break;
    }
    return cut_any;
  }

  // ---------------------------------------------------------------- stitch
  // Glues boundary sides whose ends lie within eps. Each stage hands its
  // decisions to the next as a value:
  //   match    boundary side pairs, nearest first, each side in one pair at
  //            most (match_boundary_sides)
  //   orient   which components flip so that glued sides run opposite ways,
  //            and which pairs cannot agree (choose_component_flips)
  //   merge    the vertex pairs the agreeing side pairs join (vertex_merges),
  //            less those that would merge two corners of a face (surviving_merges)
  //   apply    flip the glued components, then merge (flip_glued_components)

  // two boundary sides to glue; `same` when they run the same way (then one
  // of their components must flip)
  struct Side_pair
  {
    double score;  // the larger squared distance between matched ends
    Idx a, b;      // slots, a < b
    bool same;
  };
  // the two vertex pairs {v[0], v[1]} and {v[2], v[3]} that side pair `pair` joins
  struct Vertex_merge
  {
    std::array<Idx, 4> v;
    std::size_t pair;
  };
  struct Component_flips
  {
    std::vector<unsigned char> flip;     // per component: 1 when it flips
    std::vector<unsigned char> pair_ok;  // per side pair: it agrees with the flips
  };
  struct Surviving_merges
  {
    std::vector<unsigned char> live;  // per merge
    std::vector<Idx> root;            // per vertex: the vertex it merges into (itself if none); filled when any
    bool any = false;
  };
  // what stitch() did, for the pipeline to record
  struct Stitch_outcome
  {
    bool merged = false;  // vertices were merged: pairing, orientation and splitting must run again
    std::size_t components_flipped = 0;
  };

  Stitch_outcome stitch(double eps)
  {
    Stitch_outcome out;
    const std::vector<Side_pair> pairs = match_boundary_sides(eps);
    if (pairs.empty()) return out;
    const Component_flips flips = choose_component_flips(pairs);
    const std::vector<Vertex_merge> merges = vertex_merges(pairs, flips.pair_ok);
    const Surviving_merges kept = surviving_merges(merges);
    if (!kept.any) return out;
    out.components_flipped = flip_glued_components(pairs, merges, kept.live, flips.flip);
    for (auto& t : T)
      for (Idx& v : t) v = kept.root[v];
    out.merged = true;
    return out;
  }

  // match: greedily, the nearest candidate first (ties by slots), each side
  // in one pair at most
  std::vector<Side_pair> match_boundary_sides(double eps) const
  {
    const std::size_t S = 3 * T.size();
    std::vector<Idx> bnd;
    for (std::size_t s = 0; s < S; ++s)
      if (partner[s] == none) bnd.push_back(Idx(s));
    if (bnd.size() < 2) return {};
    std::vector<Side_pair> cand = stitch_candidates(bnd, eps);
    std::sort(cand.begin(), cand.end(), [](const Side_pair& x, const Side_pair& y) {
      return x.score < y.score || (x.score == y.score && (x.a < y.a || (x.a == y.a && x.b < y.b)));
    });
    std::vector<unsigned char> matched(S, 0);
    std::vector<Side_pair> pairs;
    for (const Side_pair& c : cand) {
      if (matched[c.a] || matched[c.b]) continue;
      matched[c.a] = matched[c.b] = 1;
      pairs.push_back(c);
    }
    return pairs;
  }

  // the boundary side pairs whose ends lie within eps of each other, either
  // way round; found through a grid over the sides' source points
  std::vector<Side_pair> stitch_candidates(const std::vector<Idx>& bnd, double eps) const
  {
    const Spatial_grid<Idx> grid(cell_size(eps), bnd, [&](Idx slot) -> const Vec& { return P[src(slot)]; });
    std::vector<Side_pair> cand;
    const double eps2 = eps * eps;
    auto scan = [&](Idx s, const Vec& near_src, const Vec& near_dst, bool same) {
      grid.for_each_near(near_src, [&](Idx h) {
        if (h <= s || h / 3 == s / 3) return;  // each pair once, never within a face
        const double d1 = dist2(P[src(h)], near_src), d2 = dist2(P[dst(h)], near_dst);
        if (d1 > eps2 || d2 > eps2) return;
        // an edge that was cut on purpose (fin, Moebius, multi-edge) stays cut
        if (edge_key(src(h), dst(h)) == edge_key(src(s), dst(s))) return;
        cand.push_back({std::max(d1, d2), s, h, same});
      });
    };
    for (Idx s : bnd) {
      scan(s, P[dst(s)], P[src(s)], false);  // opposite direction: glues as is
      scan(s, P[src(s)], P[dst(s)], true);   // same direction: one side must flip
    }
    return cand;
  }

  // orient: a BFS over the glued components from the largest, so that of two
  // glued components the smaller one flips; a pair that disagrees with the
  // flips its group already chose is dropped (pair_ok 0)
  Component_flips choose_component_flips(const std::vector<Side_pair>& pairs) const
  {
    const std::size_t C = comp_faces.size();
    Component_flips f;
    f.pair_ok.assign(pairs.size(), 1);
    const std::vector<std::vector<std::pair<Idx, Idx>>> adj = glued_components(pairs, f.pair_ok);
    std::vector<Idx> corder(C);
    std::iota(corder.begin(), corder.end(), Idx(0));
    std::stable_sort(corder.begin(), corder.end(), [&](Idx x, Idx y) { return comp_faces[x] > comp_faces[y]; });
    f.flip.assign(C, 2);  // 2: not reached yet
    std::vector<Idx> queue;
    for (Idx root : corder) {
      if (f.flip[root] != 2) continue;
      f.flip[root] = 0;
      queue.assign(1, root);
      for (std::size_t h = 0; h < queue.size(); ++h) {
        Idx c = queue[h];
        for (auto [o, pi] : adj[c]) {
          unsigned char want = f.flip[c] ^ (pairs[pi].same ? 1 : 0);
          if (f.flip[o] == 2) {
            f.flip[o] = want;
            queue.push_back(o);
          } else if (f.flip[o] != want)
            f.pair_ok[pi] = 0;
        }
      }
      // of the glued group, flip the side with fewer faces
      std::size_t flipped = 0, total = 0;
      for (Idx c : queue) {
        total += comp_faces[c];
        if (f.flip[c]) flipped += comp_faces[c];
      }
      if (2 * flipped > total)
        for (Idx c : queue) f.flip[c] ^= 1;
    }
    return f;
  }

  // per component: (other component, pair id) for each pair that joins two
  // components; a same-way pair within one component would need a Moebius
  // twist and is dropped (pair_ok 0)
  std::vector<std::vector<std::pair<Idx, Idx>>> glued_components(const std::vector<Side_pair>& pairs,
                                                                 std::vector<unsigned char>& pair_ok) const
  {
    std::vector<std::vector<std::pair<Idx, Idx>>> adj(comp_faces.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      Idx ca = comp[pairs[i].a / 3], cb = comp[pairs[i].b / 3];
      if (ca == cb) {
        if (pairs[i].same) pair_ok[i] = 0;
        continue;
      }
      adj[ca].push_back({cb, Idx(i)});
      adj[cb].push_back({ca, Idx(i)});
    }
    return adj;
  }

  // merge: the vertex pairs each agreeing side pair joins (source to target
  // of the other side when they run opposite ways)
  std::vector<Vertex_merge> vertex_merges(const std::vector<Side_pair>& pairs,
                                          const std::vector<unsigned char>& pair_ok) const
  {
    std::vector<Vertex_merge> merges;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (!pair_ok[i]) continue;
      const Idx a = pairs[i].a, b = pairs[i].b;
      if (pairs[i].same)
        merges.push_back({{src(a), src(b), dst(a), dst(b)}, i});
      else
        merges.push_back({{src(a), dst(b), dst(a), src(b)}, i});
    }
    return merges;
  }

  // the vertices the merges name, numbered 0.. in order of appearance
  // (local: per vertex, none when not named; verts: back), and the faces
  // that touch them: only those can get two corners merged
  struct Merge_scope
  {
    std::vector<Idx> local, verts, touched;
  };
  Merge_scope merge_scope(const std::vector<Vertex_merge>& merges) const
  {
    Merge_scope m;
    m.local.assign(P.size(), none);
    for (const Vertex_merge& mg : merges)
      for (Idx v : mg.v)
        if (m.local[v] == none) {
          m.local[v] = Idx(m.verts.size());
          m.verts.push_back(v);
        }
    for (std::size_t t = 0; t < T.size(); ++t)
      if (m.local[T[t][0]] != none || m.local[T[t][1]] != none || m.local[T[t][2]] != none)
        m.touched.push_back(Idx(t));
    return m;
  }

  // never merge two corners of one face: the merges of a group that would
  // are dropped and the rest retried; when nothing can be dropped, or after
  // 18 rounds, none survives
  Surviving_merges surviving_merges(const std::vector<Vertex_merge>& merges) const
  {
    const Merge_scope scope = merge_scope(merges);
    const std::vector<Idx>& local = scope.local;
    Surviving_merges kept;
    kept.live.assign(merges.size(), 1);
    std::vector<Idx> lroot(scope.verts.size());
    for (int round = 0;; ++round) {
      Union_find<Idx> uf(scope.verts.size());
      for (std::size_t i = 0; i < merges.size(); ++i)
        if (kept.live[i]) {
          uf.unite(local[merges[i].v[0]], local[merges[i].v[1]]);
          uf.unite(local[merges[i].v[2]], local[merges[i].v[3]]);
        }
      for (std::size_t k = 0; k < scope.verts.size(); ++k) lroot[k] = uf.find(Idx(k));
      std::vector<unsigned char> bad(scope.verts.size(), 0);
      if (!mark_folded_groups(scope, lroot, bad)) break;
      bool changed = false;
      for (std::size_t i = 0; i < merges.size(); ++i)
        if (kept.live[i] && (bad[lroot[local[merges[i].v[0]]]] || bad[lroot[local[merges[i].v[2]]]])) {
          kept.live[i] = 0;
          changed = true;
        }
      if (!changed || round > 16) {
        std::fill(kept.live.begin(), kept.live.end(), 0);
        return kept;
      }
    }
    kept.any = std::find(kept.live.begin(), kept.live.end(), 1) != kept.live.end();
    if (!kept.any) return kept;
    kept.root.resize(P.size());
    for (std::size_t v = 0; v < P.size(); ++v)
      kept.root[v] = local[v] == none ? Idx(v) : scope.verts[lroot[local[v]]];
    return kept;
  }

  // marks in `bad` (by local root) each merged group that would hold two
  // corners of a touched face; false when there is none
  bool mark_folded_groups(const Merge_scope& scope, const std::vector<Idx>& lroot,
                          std::vector<unsigned char>& bad) const
  {
    auto root_of = [&](Idx v) {  // unmerged: itself, apart from every local root
      return scope.local[v] == none ? none - 1 - v : lroot[scope.local[v]];
    };
    bool any_bad = false;
    for (Idx t : scope.touched) {
      const Idx x = root_of(T[t][0]), y = root_of(T[t][1]), z = root_of(T[t][2]);
      if (x == y || y == z || x == z) {
        any_bad = true;
        bad[(x == y || x == z) ? x : y] = 1;  // a repeated root is always a merged vertex
      }
    }
    return any_bad;
  }

  // apply: the components a surviving merge glues get the flip chosen for
  // them; returns how many flip
  std::size_t flip_glued_components(const std::vector<Side_pair>& pairs, const std::vector<Vertex_merge>& merges,
                                    const std::vector<unsigned char>& live,
                                    const std::vector<unsigned char>& comp_flip)
  {
    std::vector<unsigned char> comp_used(comp_faces.size(), 0);
    for (std::size_t i = 0; i < merges.size(); ++i)
      if (live[i]) {
        comp_used[comp[pairs[merges[i].pair].a / 3]] = 1;
        comp_used[comp[pairs[merges[i].pair].b / 3]] = 1;
      }
    std::size_t flipped = 0;
    for (std::size_t c = 0; c < comp_used.size(); ++c)
      if (comp_used[c] && comp_flip[c] == 1) ++flipped;
    std::vector<unsigned char> flip(T.size(), 0);
    for (std::size_t t = 0; t < T.size(); ++t) flip[t] = comp_used[comp[t]] && comp_flip[comp[t]] == 1;
    apply_flips(flip);
    return flipped;
  }

  // ---------------------------------------------------------------- outward
  // Closed components inside no other closed component get positive volume.
  // A nested one keeps the orientation orient() gave it (its input's majority):
  // an outward shell inside another is an overlap for a later union, an
  // inward one a cavity, and only the input tells them apart (unlike the
  // orient_to_bound_a_volume convention, which inverts odd depths). Depth
  // counts the other closed components whose ray crossings from a point of
  // this one are odd (fixed generic direction; a ray through an edge is
  // unlikely but would miscount).
  void orient_outward()
  {
    const std::size_t F = T.size();
    const std::size_t C = comp_faces.size();
    std::vector<Idx> start(C + 1, 0), order(F);
    for (std::size_t t = 0; t < F; ++t) ++start[comp[t] + 1];
    for (std::size_t c = 0; c < C; ++c) start[c + 1] += start[c];
    {
      std::vector<Idx> pos(start.begin(), start.end() - 1);
      for (std::size_t t = 0; t < F; ++t) order[pos[comp[t]]++] = Idx(t);
    }
    std::vector<Idx> closed;
    std::vector<double> vol(C, 0);
    std::vector<std::array<double, 6>> box(C);
    for (std::size_t c = 0; c < C; ++c) {
      if (!comp_closed[c]) continue;
      const Vec o = P[T[order[start[c]]][0]];
      double v6 = 0;
      std::array<double, 6> b{o[0], o[1], o[2], o[0], o[1], o[2]};
      for (Idx k = start[c]; k < start[c + 1]; ++k) {
        const auto& t = T[order[k]];
        Vec p0 = sub(P[t[0]], o), p1 = sub(P[t[1]], o), p2 = sub(P[t[2]], o);
        v6 += dot(p0, cross(p1, p2));
        for (Idx vi : t)
          for (int a = 0; a < 3; ++a) {
            b[a] = std::min(b[a], P[vi][a]);
            b[a + 3] = std::max(b[a + 3], P[vi][a]);
          }
      }
      vol[c] = v6;
      box[c] = b;
      if (v6 != 0) closed.push_back(Idx(c));
    }
    r.closed_components = 0;
    for (std::size_t c = 0; c < C; ++c) r.closed_components += comp_closed[c];
    if (!opt.orient_outward || closed.empty()) return;
    const Vec dir{0.5773502691896258, 0.4082482904638631, 0.7071067811865476 * 1.0000001};
    // which closed components may contain a point of which: box_intersection_d
    // of each component's query point against the components' boxes
    using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Idx, CGAL::Box_intersection_d::ID_EXPLICIT>;
    std::vector<Vec> query(C);
    std::vector<Box> points, boxes;
    for (Idx c : closed) {
      const auto& t0 = T[order[start[c]]];
      Vec q{(P[t0[0]][0] + P[t0[1]][0] + P[t0[2]][0]) / 3, (P[t0[0]][1] + P[t0[1]][1] + P[t0[2]][1]) / 3,
            (P[t0[0]][2] + P[t0[1]][2] + P[t0[2]][2]) / 3};
      query[c] = q;
      points.emplace_back(CGAL::Bbox_3(q[0], q[1], q[2], q[0], q[1], q[2]), c);
      const auto& b = box[c];
      boxes.emplace_back(CGAL::Bbox_3(b[0], b[1], b[2], b[3], b[4], b[5]), c);
    }
    std::vector<int> depth(C, 0);
    if (closed.size() > 1)
      CGAL::box_intersection_d(
          points.begin(), points.end(), boxes.begin(), boxes.end(),
          [&](const Box& pt, const Box& bx) {
            const Idx c = pt.info(), d = bx.info();
            if (c == d) return;
            int crossings = 0;
            for (Idx k = start[d]; k < start[d + 1]; ++k)
              if (ray_hits(query[c], dir, T[order[k]])) ++crossings;
            depth[c] += crossings & 1;
          },
          std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED, CGAL::Box_intersection_d::BIPARTITE);
    std::vector<unsigned char> flip_c(C, 0);
    bool any = false;
    for (Idx c : closed) {
      if (depth[c] == 0 && vol[c] < 0) {
        flip_c[c] = 1;
        any = true;
        ++r.components_flipped;
      }
    }
    if (!any) return;
    std::vector<unsigned char> flip(F);
    for (std::size_t t = 0; t < F; ++t) flip[t] = flip_c[comp[t]];
    apply_flips(flip);
  }

  // Moeller-Trumbore, ray q + s dir with s > 0.
  bool ray_hits(const Vec& q, const Vec& dir, const std::array<Idx, 3>& t) const
  {
    const Vec& a = P[t[0]];
    Vec e1 = sub(P[t[1]], a), e2 = sub(P[t[2]], a);
    Vec h = cross(dir, e2);
    double det = dot(e1, h);
    if (det == 0) return false;
    double inv = 1.0 / det;
    Vec sv = sub(q, a);
    double uu = dot(sv, h) * inv;
    if (uu < 0 || uu > 1) return false;
    Vec qv = cross(sv, e1);
    double vv = dot(dir, qv) * inv;
    if (vv < 0 || uu + vv > 1) return false;
    return dot(e2, qv) * inv > 0;
  }

  // ---------------------------------------------------------------- pipeline
  template <class Visitor>
  bool run_topology(Visitor& vis)
  {
    std::vector<unsigned char> complex_flag;
    vis.start_phase("cut");
    r.complex_edges = pair_edges();
    vis.end_phase("cut");
    if (vis.stop_requested()) return false;
    vis.start_phase("orient");
    orient();
    vis.end_phase("orient");
    if (vis.stop_requested()) return false;
    vis.start_phase("split");
    bool stale = split_vertices(complex_flag);  // components may have changed
    vis.end_phase("split");
    if (vis.stop_requested()) return false;
    if (opt.snap_epsilon > 0) {
      vis.start_phase("stitch");
      if (stale) orient();
      stale = false;
      const std::size_t before = count_boundary();
      const Stitch_outcome stitched = stitch(opt.snap_epsilon);
      r.components_flipped += stitched.components_flipped;
      if (stitched.merged) {
        pair_edges();
        orient();
        stale = split_vertices(complex_flag);
        const std::size_t after = count_boundary();
        r.edges_stitched = before > after ? (before - after) / 2 : 0;
      }
      vis.end_phase("stitch");
      if (vis.stop_requested()) return false;
    }
    vis.start_phase("outward");
    if (stale) orient();  // components, closedness after cuts
    orient_outward();
    vis.end_phase("outward");
    compact_points();
    r.components = comp_faces.size();
    r.faces_out = T.size();
    r.vertices_out = P.size();
    r.boundary_edges = count_boundary();
    r.faces_reoriented = 0;
    for (unsigned char x : reversed) r.faces_reoriented += x;
    return true;
  }

  std::size_t count_boundary() const
  {
    std::size_t b = 0;
    for (Idx p : partner) b += (p == none);
    return b;
  }

  // ---------------------------------------------------------------- build
  // Writes the faces into `out` (cleared first) with the halfedge builder:
  // every partnered side pair is one edge, every other side a border edge.
  template <class PolygonMesh, class VPM>
  void build(PolygonMesh& out, VPM vpm) const
  {
    using Point = typename boost::property_traits<VPM>::value_type;
    // the triangles as a corner table: side s is corner s
    struct Corners
    {
      const Soup_repairer& r;
      std::size_t num_points() const { return r.P.size(); }
      std::size_t num_faces() const { return r.T.size(); }
      std::size_t num_corners() const { return 3 * r.T.size(); }
      std::size_t begin(std::size_t t) const { return 3 * t; }
      std::size_t end(std::size_t t) const { return 3 * t + 3; }
      std::size_t source(std::size_t s) const { return r.src(Idx(s)); }
      std::size_t next(std::size_t s) const { return dst_corner(Idx(s)); }
      std::size_t opposite(std::size_t s) const { return r.partner[s] == none ? no_corner : r.partner[s]; }
      bool used(std::size_t) const { return true; }
    };
    CGAL::clear(out);
    const std::size_t F = T.size(), S = 3 * F;
    build_halfedge_mesh(out, Corners{*this}, with_room_for_fills(P.size(), (S + count_boundary()) / 2, F),
                        [&](auto v, std::size_t i) { put(vpm, v, Point(P[i][0], P[i][1], P[i][2])); });
  }
};

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_STITCH_SOUP_SOUP_REPAIRER_H
