// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_INSPECT_SELF_INTERSECTIONS_H
#define MREPAIR_INTERNAL_INSPECT_SELF_INTERSECTIONS_H

#include <mrepair/internal/inspect/parallel.h>
#include <mrepair/internal/inspect/surface_arrays.h>
#include <mrepair/internal/spatial_grid.h>
#include <mrepair/internal/triangle_intersection.h>

#include <CGAL/Bbox_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {

// Per vertex: 1 when the faces around it form one fan, closed or open,
// consistently oriented, each edge at the vertex in at most two faces of it,
// that projects one-to-one along some direction n (the sum of the face
// normals): every face surely positively oriented about n, and the sectors'
// angles summing to one turn (closed) or surely less (open). The projected
// faces then lie in angular sectors that follow one another around the vertex
// without overlap, and each face projects one-to-one, so two faces of the fan
// meet only at the vertex or along their shared edge: no pair that shares a
// certified vertex intersects, and the counter skips those pairs untested
// (on a scan or a fine CAD mesh, most of the pairs whose boxes overlap).
// Reads the edges, so runs before keep_for_self_intersections().
//
// The corners of each vertex come from a vertex-corner table (the corners of
// v in increasing order in corners[first[v]] .. corners[first[v+1]-1]); the
// fan is put together in a small local array from each corner's outgoing and
// incoming edge: corner j follows corner i when j's incoming edge is i's
// outgoing one. A consistently oriented fan with at most two faces on each
// edge has every edge at most once outgoing and once incoming (a third face
// on an edge, or two faces running it the same way, repeat one of them), so
// the fan is one cycle (closed) or one chain from the corner whose outgoing
// edge is a border to the one whose incoming edge is (open). Walking the
// edges' corner lists instead made this pass 14x slower at 10M faces than at
// 1M (random reads). The fan is visited in the order of that walk: from the
// vertex's first corner (closed), from the border-ending corner backwards
// (open); the sums below, and so the answers, are the walk's.
inline void certify_flat_stars(Surface_arrays& a, const std::vector<Inspect_index>& first,
                               const std::vector<Inspect_index>& corners)
{
  const std::size_t nv = a.num_vertices, nc = a.corner_v.size();
  a.flat_star.assign(nv, 0);
  if (a.corner_f.size() != nc || a.corner_e.size() != nc || a.finite.size() != nv ||
      first.size() != nv + 1)
    return;
  constexpr int max_fan = 64;
  parallel_for_index(nv, 4096, [&](std::size_t v) {
    const Inspect_index base = first[v];
    const int k = static_cast<int>(first[v + 1] - base);
    if (k < 2 || k > max_fan || !a.finite[v]) return;
    Inspect_index corner[max_fan], out[max_fan], in[max_fan];
    int succ[max_fan], pred[max_fan];
    for (int i = 0; i < k; ++i) {
      const Inspect_index c = corners[base + i];
      if (a.degree(a.corner_f[c]) != 3) return;
      corner[i] = c;
      out[i] = a.corner_e[c];
      in[i] = a.corner_e[a.prev_corner(c)];
      if (out[i] == inspect_npos || in[i] == inspect_npos) return;
      succ[i] = pred[i] = -1;
    }
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) {
        if (j > i && (out[i] == out[j] || in[i] == in[j])) return;  // a repeated edge
        if (in[j] == out[i]) {
          succ[i] = j;
          pred[j] = i;
        }
      }
    int fan[max_fan];
    int m = 0, ends = 0, start = 0;
    for (int i = 0; i < k; ++i)
      if (succ[i] < 0) {
        ++ends;
        start = i;
      }
    if (ends > 1) return;  // more than one fan at the vertex
    const bool open = ends == 1;
    if (open) {
      for (int i = start; i >= 0 && m < k; i = pred[i]) fan[m++] = i;
    } else {
      int i = 0;
      do {
        fan[m++] = i;
        i = succ[i];
      } while (i != 0 && m < k);
      if (i != 0) return;
    }
    if (m != k) return;  // another fan at the vertex
    const Vec3 pv{{a.point(v)[0], a.point(v)[1], a.point(v)[2]}};
    auto spoke = [&](std::size_t c) {
      const Inspect_index w = a.corner_v[c];
      return sub(Vec3{{a.point(w)[0], a.point(w)[1], a.point(w)[2]}}, pv);
    };
    Vec3 n{{0, 0, 0}};
    for (int i = 0; i < m; ++i) {
      const std::size_t c = corner[fan[i]];
      if (!a.finite[a.corner_v[a.next_corner(c)]] || !a.finite[a.corner_v[a.prev_corner(c)]]) return;
      n = add(n, cross(spoke(a.next_corner(c)), spoke(a.prev_corner(c))));
    }
    const double nn = squared_norm(n), ln = std::sqrt(nn);
    if (!(nn > 0) || !std::isfinite(nn)) return;
    const double l1n = certify::l1(n);
    double turn = 0;
    for (int i = 0; i < m; ++i) {
      const std::size_t c = corner[fan[i]];
      const Vec3 x = spoke(a.next_corner(c)), y = spoke(a.prev_corner(c));
      const double o = dot(n, cross(x, y));
      // a margin of 1e-10 of the terms' size, far above their rounding error
      if (!(o > 1e-10 * l1n * certify::l1(x) * certify::l1(y))) return;
      turn += std::atan2(o / ln, dot(x, y) - dot(x, n) * dot(y, n) / nn);
    }
    // the angles are off by 1e-5 at most each (the margin above): one turn
    // and less than one turn are far apart from their neighbours
    const bool ok = open ? turn < 2 * pi - 0.01 : turn > pi && turn < 3 * pi;
    a.flat_star[v] = ok ? 1 : 0;
  });
}

// The same, building the vertex-corner table itself.
inline void certify_flat_stars(Surface_arrays& a)
{
  std::vector<Inspect_index> first, corners;
  vertex_corner_table(a, first, corners);
  certify_flat_stars(a, first, corners);
}

// Counts pairs of distinct triangles that intersect other than through what
// they share, with the semantics of CGAL 5.5's `PMP::self_intersections`
// (the pair test in internal/triangle_intersection.h).
// Only `eligible` faces take part (triangles with finite, non-collinear corners:
// CGAL reports a degenerate face only as the pair (f, f)).
//
// Broad phase: a uniform grid of cells twice the mean face extent (the
// spatial grid's cells and keys, internal/spatial_grid.h), built by a
// parallel counting sort of (cell, face) entries on a cell hash; each
// candidate pair is tested in the one cell that holds the lower corner of
// the overlap of the two boxes (owns_pair), so it is tested once. The rare
// faces spanning many cells are matched by CGAL's box_intersection_d
// instead. Cells are processed in parallel.
// the float next to `f` upwards or downwards: std::nextafter, inlined (a
// call per box side was a fifth of the boxes' time)
inline float float_step(float f, bool up)
{
  if (!std::isfinite(f) || f == 0) return std::nextafter(f, up ? HUGE_VALF : -HUGE_VALF);
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  if ((f > 0) == up)
    ++u;  // away from zero
  else
    --u;  // towards zero
  std::memcpy(&f, &u, sizeof u);
  return f;
}

// intersecting pairs, and how many of them only touch at coincident vertices
struct Self_intersection_counts
{
  std::size_t pairs = 0, touching = 0;
  // with count(eligible, true): the pairs that cross (not only touching),
  // as indices of the arrays' faces, lower index first, in no fixed order
  std::vector<std::pair<Inspect_index, Inspect_index>> crossing;
  // with count(eligible, _, true): every pair counted in `pairs` (lower index
  // first, in no fixed order), and per pair 1 when it only touches
  std::vector<std::pair<Inspect_index, Inspect_index>> listed;
  std::vector<unsigned char> listed_touching;
};

class Self_intersection_counter
{
  using K = CGAL::Epick;
  using Point = K::Point_3;
  const Surface_arrays& a_;

  Point point(Inspect_index v) const
  {
    const double* p = a_.point(v);
    return Point(p[0], p[1], p[2]);
  }

public:
  explicit Self_intersection_counter(const Surface_arrays& a) : a_(a) {}

  // 0: f and g do not intersect; 1: they do; 2: they do, but only where
  // they touch at coincident vertices of their own (the copies of a split
  // non-manifold vertex, duplicate points): taken as one shared vertex or
  // edge, the coincident corners would leave the two faces apart. The
  // shared vertex or edge may be part index, part copy: faces on one vertex
  // and on coincident copies of the edge's other end touch along that edge.
  int contact(Inspect_index f, Inspect_index g) const
  {
    const Inspect_index* fv = &a_.corner_v[a_.face_off[f]];
    const Inspect_index* gv = &a_.corner_v[a_.face_off[g]];
    const Inspect_index* fe = &a_.corner_e[a_.face_off[f]];
    const Inspect_index* ge = &a_.corner_e[a_.face_off[g]];
    // a shared edge is known by its index (two faces on the same two
    // vertices without a common edge are not adjacent)
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l)
        if (fe[k] == ge[l] && fe[k] != inspect_npos)
          return overlap_across_shared_edge(point(fv[k]), point(fv[(k + 1) % 3]),
                                            point(fv[(k + 2) % 3]), point(gv[(l + 2) % 3]));
    const Point fp[3] = {point(fv[0]), point(fv[1]), point(fv[2])};
    const Point gp[3] = {point(gv[0]), point(gv[1]), point(gv[2])};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (fv[i] == gv[j]) {
          if (!intersect_beside_shared_vertex(fp, i, gp, j)) return 0;
          // a second corner in common by position only (the copy of a vertex
          // where a solid touches itself along an edge, made when its fans
          // were split): the faces touch along that edge, as two faces on
          // copies of both its ends do (below)
          for (int k = 1; k < 3; ++k)
            for (int l = 1; l < 3; ++l) {
              const int i2 = (i + k) % 3, j2 = (j + l) % 3;
              if (fp[i2] == gp[j2])
                return overlap_across_shared_edge(fp[i], fp[i2], fp[3 - i - i2], gp[3 - j - j2]) ? 1 : 2;
            }
          return 1;
        }
    if (!disjoint_triangles_intersect(fp, gp)) return 0;
    int same = 0, fi[2] = {0, 0}, gj[2] = {0, 0};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (fp[i] == gp[j] && same < 2) {
          fi[same] = i;
          gj[same] = j;
          ++same;
        }
    if (same == 1) return intersect_beside_shared_vertex(fp, fi[0], gp, gj[0]) ? 1 : 2;
    if (same == 2 && fi[0] != fi[1] && gj[0] != gj[1]) {
      const int c = 3 - fi[0] - fi[1], d = 3 - gj[0] - gj[1];
      return overlap_across_shared_edge(fp[fi[0]], fp[fi[1]], fp[c], gp[d]) ? 1 : 2;
    }
    return 1;
  }

  Self_intersection_counts count(const std::vector<unsigned char>& eligible, bool list_crossing = false,
                                 bool list_all = false) const
  {
    std::vector<Inspect_index> F;
    for (std::size_t f = 0; f < a_.num_faces(); ++f)
      if (eligible[f]) F.push_back(static_cast<Inspect_index>(f));
    const std::size_t n = F.size();
    Self_intersection_counts counts;
    if (n < 2) return counts;
    // The boxes are floats relative to the lowest corner, rounded outwards:
    // half the memory of doubles (the counter's 10M-face peak), and a float
    // box only grows, so no pair is missed (the exact test follows).
    struct Ext
    {
      double extent = 0;
      double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    };
    auto face_range = [&](std::size_t i, int d, double& lo, double& hi) {
      const Inspect_index* v = &a_.corner_v[a_.face_off[F[i]]];
      const double x = a_.point(v[0])[d], y = a_.point(v[1])[d], z = a_.point(v[2])[d];
      lo = std::min(x, std::min(y, z));
      hi = std::max(x, std::max(y, z));
    };
    Ext tot;
    for (const Ext& e : chunked<Ext>(n, [&](std::size_t b, std::size_t e, Ext& s) {
           for (std::size_t i = b; i < e; ++i) {
             double extent = 0;
             for (int d = 0; d < 3; ++d) {
               double lo, hi;
               face_range(i, d, lo, hi);
               extent = std::max(extent, hi - lo);
               s.lo[d] = std::min(s.lo[d], lo);
               s.hi[d] = std::max(s.hi[d], hi);
             }
             s.extent += extent;
           }
         })) {
      tot.extent += e.extent;
      for (int d = 0; d < 3; ++d) {
        tot.lo[d] = std::min(tot.lo[d], e.lo[d]);
        tot.hi[d] = std::max(tot.hi[d], e.hi[d]);
      }
    }
    Parallel_filled_vector<float> box(6 * n);
    parallel_for_index(n, 8192, [&](std::size_t i) {
      float* b = &box[6 * i];
      for (int d = 0; d < 3; ++d) {
        double lo, hi;
        face_range(i, d, lo, hi);
        lo -= tot.lo[d];
        hi -= tot.lo[d];
        float flo = static_cast<float>(lo), fhi = static_cast<float>(hi);
        if (double(flo) > lo) flo = float_step(flo, false);
        if (double(fhi) < hi) fhi = float_step(fhi, true);
        b[d] = flo;
        b[3 + d] = fhi;
      }
    });
    double h = 2.0 * tot.extent / double(n);
    for (int d = 0; d < 3; ++d) h = std::max(h, (tot.hi[d] - tot.lo[d]) / double(1 << 20));
    if (!(h > 0)) h = 1.0;
    // Finite coordinates near +-DBL_MAX make ranges overflow to inf and h too;
    // the clamp keeps the cell index defined (everything then shares a cell).
    const double inv_h = 1.0 / h;  // a multiplication per coordinate (monotone, as the division)
    auto cell = [&](double x, int /*d*/) {
      const double t = std::floor(x * inv_h);
      if (!(t > 0)) return std::uint64_t(0);
      return static_cast<std::uint64_t>(std::min(t, double(1 << 20)));
    };
    // cells are below 2^21 on each axis: pack_cell keys them one to one
    auto key = [](std::uint64_t i, std::uint64_t j, std::uint64_t k) {
      return pack_cell(std::int64_t(i), std::int64_t(j), std::int64_t(k));
    };

    // cells covered by each face; faces covering many cells are "big"
    const std::uint64_t big_cells = 64;
    Parallel_filled_vector<Inspect_index> count(n + 1);
    count[n] = 0;
    parallel_for_index(n, 8192, [&](std::size_t i) {
      const float* x = &box[6 * i];
      std::uint64_t c = 1;
      for (int d = 0; d < 3; ++d) c *= cell(x[3 + d], d) - cell(x[d], d) + 1;
      count[i] = c > big_cells ? 0 : static_cast<Inspect_index>(c);
    });
    std::vector<std::size_t> big;
    for (std::size_t i = 0; i < n; ++i)
      if (count[i] == 0) big.push_back(i);
    const Inspect_index total = exclusive_scan_in_place(count);
    count[n] = total;
    Parallel_filled_vector<std::uint64_t> ekey(total);
    Parallel_filled_vector<Inspect_index> eface(total);
    parallel_for_index(n, 8192, [&](std::size_t i) {
      const float* x = &box[6 * i];
      Inspect_index o = count[i];
      if (o == count[i + 1]) return;
      for (std::uint64_t a = cell(x[0], 0); a <= cell(x[3], 0); ++a)
        for (std::uint64_t b = cell(x[1], 1); b <= cell(x[4], 1); ++b)
          for (std::uint64_t c = cell(x[2], 2); c <= cell(x[5], 2); ++c) {
            ekey[o] = key(a, b, c);
            eface[o++] = static_cast<Inspect_index>(i);
          }
    });
    // Counting sort of the entries on a hash of their cell. The hash is of a
    // block of 4 x 4 x 4 cells, and the block's cells take consecutive
    // buckets: the pair loop then visits neighbouring cells one after the
    // other, whose faces are mostly near each other in memory too. A bucket
    // per four entries: one per entry made the offsets as large as the
    // entries, and their random increments slower (10M faces: 0.15 s more).
    const std::size_t nb = std::max<std::size_t>(1, total / 4);
    auto bucket_of = [nb](std::uint64_t k) {
      const std::uint64_t m = (std::uint64_t(1) << 21) - 1;
      const std::uint64_t i = k >> 42, j = (k >> 21) & m, l = k & m;
      std::uint64_t block = ((i >> 2) << 42) | ((j >> 2) << 21) | (l >> 2);
      block *= 0x9E3779B97F4A7C15ull;
      block ^= block >> 29;
      return static_cast<std::size_t>((block * 64 + ((i & 3) << 4 | (j & 3) << 2 | (l & 3))) % nb);
    };
    std::vector<Inspect_index> boff, order;
    bucket_items(std::size_t(total), nb, inspect_npos,
                 [&](std::size_t e) { return static_cast<Inspect_index>(bucket_of(ekey[e])); }, boff, order);
    // Each bucket's entries are gathered with their boxes into a local array
    // first: the pair loop then reads contiguous memory instead of one random
    // box per pair (most of the counter's time on 1M faces).
    // `certified` marks the face's corners whose fan is certified, so that
    // the pair loop reads no per-vertex array
    struct Entry
    {
      std::uint64_t key;
      Inspect_index face;
      Inspect_index v[3];
      float b[6];
      unsigned char certified;
    };
    const bool flat = a_.flat_star.size() == a_.num_vertices;
    // the pair shares a vertex whose fan is certified (no intersection)
    auto certified = [](const Entry& p, const Entry& q) {
      for (int i = 0; i < 3; ++i)
        if ((p.certified >> i & 1) && (p.v[i] == q.v[0] || p.v[i] == q.v[1] || p.v[i] == q.v[2]))
          return true;
      return false;
    };
    auto add = [list_crossing, list_all](Self_intersection_counts& c, int contact, Inspect_index f, Inspect_index g) {
      c.pairs += contact != 0;
      c.touching += contact == 2;
      if (list_crossing && contact == 1) c.crossing.emplace_back(std::min(f, g), std::max(f, g));
      if (list_all && contact != 0) {
        c.listed.emplace_back(std::min(f, g), std::max(f, g));
        c.listed_touching.push_back(contact == 2);
      }
    };
    for (const Self_intersection_counts& s : chunked<Self_intersection_counts>(nb, [&](std::size_t b, std::size_t e,
                                                                                     Self_intersection_counts& s) {
           std::vector<Entry> local;
           for (std::size_t k = b; k < e; ++k) {
             if (boff[k + 1] - boff[k] < 2) continue;
             local.clear();
             for (Inspect_index t = boff[k]; t < boff[k + 1]; ++t) {
               const Inspect_index en = order[t], f = eface[en];
               Entry x;
               x.key = ekey[en];
               x.face = f;
               std::copy_n(&a_.corner_v[a_.face_off[F[f]]], 3, x.v);
               std::copy(&box[6 * std::size_t(f)], &box[6 * std::size_t(f)] + 6, x.b);
               x.certified = 0;
               if (flat)
                 for (int i = 0; i < 3; ++i) x.certified |= (a_.flat_star[x.v[i]] ? 1 : 0) << i;
               local.push_back(x);
             }
             // entries of one cell in face order (a face enters a cell once)
             std::sort(local.begin(), local.end(), [](const Entry& x, const Entry& y) {
               return x.key != y.key ? x.key < y.key : x.face < y.face;
             });
             for (auto r = local.begin(); r != local.end();) {
               auto r_end = r + 1;
               while (r_end != local.end() && r_end->key == r->key) ++r_end;
               const std::uint64_t ck = r->key;
               for (auto p = r; p != r_end; ++p)
                 for (auto q = p + 1; q != r_end; ++q) {
                   const float *x = p->b, *y = q->b;
                   if (!flat_boxes_meet(x, y)) continue;
                   // most overlapping pairs of a scan share a certified vertex:
                   // that test is cheaper than finding the pair's cell
                   if (certified(*p, *q)) continue;
                   if (!owns_pair(ck, x, y, cell)) continue;  // tested in another cell
                   add(s, contact(F[p->face], F[q->face]), F[p->face], F[q->face]);
                 }
               r = r_end;
             }
           }
         })) {
      counts.pairs += s.pairs;
      counts.touching += s.touching;
      counts.crossing.insert(counts.crossing.end(), s.crossing.begin(), s.crossing.end());
      counts.listed.insert(counts.listed.end(), s.listed.begin(), s.listed.end());
      counts.listed_touching.insert(counts.listed_touching.end(), s.listed_touching.begin(), s.listed_touching.end());
    }

    // big faces: against the others (box_intersection_d) and among themselves
    if (!big.empty()) {
      // explicit ids: box_self_intersection_d copies the boxes
      using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t,
                                                            CGAL::Box_intersection_d::ID_EXPLICIT>;
      auto make = [&](std::size_t i) {
        const float* x = &box[6 * i];
        return Box(CGAL::Bbox_3(x[0], x[1], x[2], x[3], x[4], x[5]), i);
      };
      std::vector<Box> bigs, rest;
      for (std::size_t i : big) bigs.push_back(make(i));
      for (std::size_t i = 0; i < n; ++i)
        if (count[i] != count[i + 1]) rest.push_back(make(i));
      auto report = [&](const Box& p, const Box& q) {
        add(counts, contact(F[p.info()], F[q.info()]), F[p.info()], F[q.info()]);
      };
      std::vector<Box> bigs2 = bigs;
      CGAL::box_intersection_d(bigs.begin(), bigs.end(), rest.begin(), rest.end(), report);
      CGAL::box_self_intersection_d(bigs2.begin(), bigs2.end(), report);
    }
    return counts;
  }
};

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_INSPECT_SELF_INTERSECTIONS_H
