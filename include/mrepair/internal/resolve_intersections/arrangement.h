// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Global solidification of closed shells by winding numbers (Zhou, Grinspun,
// Zorin and Jacobson 2016, "Mesh arrangements for solid geometry"):
//   1. the exact arrangement of the triangles: every crossing pair
//      intersected with exact constructions (Epeck), each triangle
//      triangulated with its intersection segments as constraints, and every
//      arrangement vertex that lies on a triangle inserted into it, so that
//      neighbouring pieces share their vertices (no T-junction);
//   2. patches: pieces joined across edges that exactly two pieces share
//      with opposite directions; the winding number on the front of a patch
//      is constant, so one exact ray cast per patch (signed crossings, a new
//      ray on a degenerate hit) gives it;
//   3. the jump across a piece is the net orientation of the coplanar pieces
//      that cover it (one is kept: the one of the lowest input triangle);
//      a piece between winding number 0 and a nonzero one is kept, facing
//      the 0 side (nonzero and not >= 1: a cap pushed through the rest of
//      its shell encloses w = -1, and its points must not be lost).
// The output is rounded to doubles; the caller checks it for crossings and
// runs the arrangement again on what rounding made cross.
#ifndef MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_ARRANGEMENT_H
#define MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_ARRANGEMENT_H

#include <mrepair/internal/utility.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {
namespace solid {

/// a triangle soup in doubles: the arrangement's input and output
struct Triangle_soup
{
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  /// per triangle (or empty: none): 1 for a sheet's triangle, which bounds
  /// no cell: it is cut by the arrangement but counts in no winding number
  std::vector<unsigned char> sheet;
};

struct Arrangement_outcome
{
  bool ok = false;
  std::string reason;               ///< why not, when !ok
  std::size_t pieces = 0;           ///< faces of the arrangement
  std::size_t patches = 0;
  std::size_t rays = 0, rays_shot_again = 0;
  Triangle_soup solid;              ///< the kept pieces, outward
  /// the sheets' pieces outside the solid (winding number 0, covered by no
  /// piece of it), oriented as their triangles; their ends on the solid's
  /// surface share its vertices
  Triangle_soup sheets;
};

// Builds the arrangement of `soup` whose crossing triangle pairs are `pairs`
// (indices into soup.triangles) and keeps the boundary of the cells of
// nonzero winding number; no more than `max_pieces` pieces. Sheet triangles
// (`soup.sheet`) are cut too and their pieces outside the solid kept apart
// (`sheets`): the part of an open surface inside the solid is absorbed.
//
// The exact arrangement (Epeck, three projected constrained triangulations)
// costs about a minute of compiler time in every translation unit that
// includes it. With MREPAIR_SEPARATE_ARRANGEMENT defined, this header only
// declares it, and one translation unit of the program defines it by
// compiling src/compile_once.cpp (the project's own build does so:
// MREPAIR_COMPILE_ONCE); by default, header-only, it is an inline function.
#ifdef MREPAIR_SEPARATE_ARRANGEMENT
#define MREPAIR_ARRANGEMENT_INLINE
#else
#define MREPAIR_ARRANGEMENT_INLINE inline
#endif
MREPAIR_ARRANGEMENT_INLINE Arrangement_outcome arrange_winding_number_solid(
    const Triangle_soup& soup, const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
    std::size_t max_pieces);

} // namespace solid
} // namespace internal
} // namespace mrepair

#if !defined(MREPAIR_SEPARATE_ARRANGEMENT) || defined(MREPAIR_ARRANGEMENT_DEFINITION)
#include <CGAL/Bbox_3.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Projection_traits_xz_3.h>
#include <CGAL/Projection_traits_yz_3.h>
#include <CGAL/version.h>

namespace mrepair {
namespace internal {
namespace solid {

namespace arrangement_detail {

using EK = CGAL::Epeck;
using EPoint = EK::Point_3;
using ESegment = EK::Segment_3;

template <class T, class Variant>
const T* variant_get(const Variant& v)
{
#if CGAL_VERSION_NR >= 1060000000
  return std::get_if<T>(&v);
#else
  return boost::get<T>(&v);
#endif
}

struct Less_xyz
{
  bool operator()(const EPoint& a, const EPoint& b) const { return CGAL::compare_xyz(a, b) == CGAL::SMALLER; }
};

// Triangulates the triangle `abc` with the constraint segments and points
// (all exactly on it) in the plane of its dominant normal axis; appends the
// pieces, oriented as `abc`.
template <class Traits>
void triangulate_in_plane(const EPoint& a, const EPoint& b, const EPoint& c, const std::vector<ESegment>& segments,
                          const std::vector<EPoint>& points, std::vector<std::array<EPoint, 3>>& out)
{
  using CDT = CGAL::Constrained_Delaunay_triangulation_2<Traits, CGAL::Default, CGAL::Exact_intersections_tag>;
  CDT cdt;
  auto va = cdt.insert(a), vb = cdt.insert(b), vc = cdt.insert(c);
  cdt.insert_constraint(va, vb);
  cdt.insert_constraint(vb, vc);
  cdt.insert_constraint(vc, va);
  for (const EPoint& p : points) cdt.insert(p);
  for (const ESegment& s : segments)
    if (s.source() != s.target()) cdt.insert_constraint(s.source(), s.target());
  const auto orient = Traits().orientation_2_object();
  const CGAL::Orientation parent = orient(a, b, c);
  for (auto f : cdt.finite_face_handles()) {
    const EPoint &p = f->vertex(0)->point(), &q = f->vertex(1)->point(), &r = f->vertex(2)->point();
    if (orient(p, q, r) == parent) out.push_back({{p, q, r}});
    else out.push_back({{p, r, q}});
  }
}

// A uniform grid of boxes over two or three axes, for candidate lists.
class Box_grid
{
  int dims_ = 3;
  std::array<double, 3> lo_{{0, 0, 0}}, cell_{{1, 1, 1}};
  std::array<long, 3> n_{{1, 1, 1}};
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;

  std::uint64_t key(const std::array<long, 3>& c) const
  {
    return (std::uint64_t(c[0]) * std::uint64_t(n_[1]) + std::uint64_t(c[1])) * std::uint64_t(n_[2]) +
           std::uint64_t(c[2]);
  }
  long cell_of(int d, double x) const
  {
    const double t = std::floor((x - lo_[d]) / cell_[d]);
    if (!(t > 0)) return 0;
    return t >= double(n_[d] - 1) ? n_[d] - 1 : long(t);
  }

public:
  // `axes`: the axes the grid divides (the others are one cell)
  void reset(const std::array<double, 3>& lo, const std::array<double, 3>& hi, std::size_t items, int axes_mask)
  {
    cells_.clear();
    int used = 0;
    for (int d = 0; d < 3; ++d) used += (axes_mask >> d) & 1;
    const double per_axis = std::pow(double(std::max<std::size_t>(items, 1)), 1. / std::max(used, 1));
    for (int d = 0; d < 3; ++d) {
      lo_[d] = lo[d];
      const double extent = std::max(hi[d] - lo[d], 1e-300);
      n_[d] = ((axes_mask >> d) & 1) ? std::max<long>(1, std::min<long>(long(per_axis / 2) + 1, 2048)) : 1;
      cell_[d] = extent / double(n_[d]);
    }
    dims_ = used;
  }
  template <class F>
  void for_cells(const std::array<double, 3>& lo, const std::array<double, 3>& hi, const F& f) const
  {
    std::array<long, 3> a, b, c;
    for (int d = 0; d < 3; ++d) {
      a[d] = cell_of(d, lo[d]);
      b[d] = cell_of(d, hi[d]);
    }
    for (c[0] = a[0]; c[0] <= b[0]; ++c[0])
      for (c[1] = a[1]; c[1] <= b[1]; ++c[1])
        for (c[2] = a[2]; c[2] <= b[2]; ++c[2]) f(key(c));
  }
  // cells a box covers, to tell a box that would flood the grid
  double cells_covered(const std::array<double, 3>& lo, const std::array<double, 3>& hi) const
  {
    double n = 1;
    for (int d = 0; d < 3; ++d) n *= double(cell_of(d, hi[d]) - cell_of(d, lo[d]) + 1);
    return n;
  }
  void insert(std::uint32_t item, const std::array<double, 3>& lo, const std::array<double, 3>& hi)
  {
    for_cells(lo, hi, [&](std::uint64_t k) { cells_[k].push_back(item); });
  }
  const std::vector<std::uint32_t>* at(std::uint64_t k) const
  {
    auto it = cells_.find(k);
    return it == cells_.end() ? nullptr : &it->second;
  }
};

struct Box
{
  std::array<double, 3> lo{{HUGE_VAL, HUGE_VAL, HUGE_VAL}}, hi{{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
  void add(const EPoint& p)
  {
    const std::pair<double, double> c[3] = {CGAL::to_interval(p.x()), CGAL::to_interval(p.y()),
                                            CGAL::to_interval(p.z())};
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], c[d].first);
      hi[d] = std::max(hi[d], c[d].second);
    }
  }
  bool overlaps(const Box& b) const
  {
    for (int d = 0; d < 3; ++d)
      if (b.hi[d] < lo[d] || b.lo[d] > hi[d]) return false;
    return true;
  }
  bool contains(const Box& b) const
  {
    for (int d = 0; d < 3; ++d)
      if (b.lo[d] < lo[d] || b.hi[d] > hi[d]) return false;
    return true;
  }
};

} // namespace arrangement_detail

// Where the kept solid touches itself (two cells of nonzero winding number
// meeting along an edge: four or more kept faces there), the faces around
// the edge are sorted about it (exact predicates on the exact points) and
// paired across the nonzero cell between them; every vertex is then split
// into one copy per umbrella (faces connected across paired edges). The
// result is a manifold soup over `points` (grown by the copies). False when
// an edge has an odd number of faces or the orientations do not alternate
// around it (the caller refuses the result).
template <class Point>
bool split_where_solid_touches_itself(std::vector<Point>& points, std::vector<std::array<std::size_t, 3>>& tris)
{
  const std::size_t F = tris.size();
  struct Use
  {
    std::size_t a, b, face;
    int k;  // the face's edge k: tris[face][k] -> tris[face][k+1]
  };
  std::vector<Use> uses;
  uses.reserve(3 * F);
  for (std::size_t f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k) {
      const std::size_t u = tris[f][k], v = tris[f][(k + 1) % 3];
      uses.push_back({std::min(u, v), std::max(u, v), f, k});
    }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
    return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.face != y.face ? x.face < y.face : x.k < y.k;
  });
  Union_find<std::size_t> corners(3 * F);
  auto corner = [](std::size_t f, int k) { return 3 * f + std::size_t((k + 3) % 3); };
  // the edge k of f is glued to the edge l of g (opposite directions)
  auto glue = [&](std::size_t f, int k, std::size_t g, int l) {
    corners.unite(corner(f, k), corner(g, l + 1));
    corners.unite(corner(f, k + 1), corner(g, l));
  };
  auto starts_at = [&](const Use& x, std::size_t u) { return tris[x.face][x.k] == u; };
  std::vector<Use> around;
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b) ++j;
    const std::size_t n = j - i, u = uses[i].a, v = uses[i].b;
    if (n % 2) return false;
    if (n == 2) {
      if (starts_at(uses[i], u) == starts_at(uses[i + 1], u)) return false;
      glue(uses[i].face, uses[i].k, uses[i + 1].face, uses[i + 1].k);
      i = j;
      continue;
    }
    // about the axis u -> v, angles from the first face's third corner
    around.assign(uses.begin() + std::ptrdiff_t(i), uses.begin() + std::ptrdiff_t(j));
    auto third = [&](const Use& x) -> const Point& { return points[tris[x.face][(x.k + 2) % 3]]; };
    const Point &pu = points[u], &pv = points[v], &ref = third(around[0]);
    auto half = [&](const Point& x) {
      switch (CGAL::orientation(pu, pv, ref, x)) {
      case CGAL::POSITIVE: return 1;
      case CGAL::NEGATIVE: return 3;
      default: return CGAL::coplanar_orientation(pu, pv, ref, x) == CGAL::NEGATIVE ? 2 : 0;
      }
    };
    std::stable_sort(around.begin(), around.end(), [&](const Use& x, const Use& y) {
      const Point &a = third(x), &b = third(y);
      const int ha = half(a), hb = half(b);
      if (ha != hb) return ha < hb;
      if (ha == 0 || ha == 2) return false;
      return CGAL::orientation(pu, pv, a, b) == CGAL::POSITIVE;
    });
    // a face with v -> u has its back (the solid) ahead in this rotation:
    // it pairs with the next face, which must run u -> v
    std::size_t first = n;
    for (std::size_t r = 0; r < n && first == n; ++r)
      if (!starts_at(around[r], u)) first = r;
    if (first == n) return false;
    for (std::size_t r = 0; r < n; r += 2) {
      const Use &x = around[(first + r) % n], &y = around[(first + r + 1) % n];
      if (starts_at(x, u) || !starts_at(y, u)) return false;
      glue(x.face, x.k, y.face, y.k);
    }
    i = j;
  }
  // one vertex per umbrella
  std::vector<std::size_t> copy_of(3 * F, std::size_t(-1));
  std::vector<unsigned char> used(points.size(), 0);
  for (std::size_t f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k) {
      const std::size_t root = corners.find(corner(f, k));
      if (copy_of[root] == std::size_t(-1)) {
        const std::size_t v = tris[f][k];
        if (!used[v]) {
          used[v] = 1;
          copy_of[root] = v;
        } else {
          copy_of[root] = points.size();
          points.push_back(points[v]);
        }
      }
    }
  for (std::size_t f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k) tris[f][k] = copy_of[corners.find(corner(f, k))];
  return true;
}

// The worker: builds the arrangement of `soup` whose crossing triangle
// pairs are `pairs` (indices into soup.triangles), and keeps the boundary
// of the cells of winding number >= 1. No more than `max_pieces` pieces.
class Winding_number_solidifier
{
  using EK = arrangement_detail::EK;
  using EPoint = arrangement_detail::EPoint;
  using ESegment = arrangement_detail::ESegment;
  using Box = arrangement_detail::Box;
  using Tri = std::array<std::size_t, 3>;

  std::vector<EPoint> points_;            // merged input points, then new ones
  std::vector<Tri> input_;                 // input triangles over points_
  std::vector<unsigned char> degenerate_;  // collinear or repeated corners
  std::vector<Tri> pieces_;                // the arrangement's faces
  std::vector<std::size_t> parent_;        // piece -> input triangle
  std::vector<unsigned char> sheet_;       // input triangle -> of a sheet (empty: none)
  std::vector<Box> piece_box_;
  Box all_;

public:
  Arrangement_outcome run(const Triangle_soup& soup, const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                          std::size_t max_pieces)
  {
    Arrangement_outcome out;
    try {
      if (!build(soup, pairs, max_pieces, out)) return out;
      classify(out);
    } catch (const std::exception& e) {
      out.ok = false;
      out.reason = std::string("arrangement_failed: ") + e.what();
    }
    return out;
  }

private:
  EK::Triangle_3 triangle(const Tri& t) const { return EK::Triangle_3(points_[t[0]], points_[t[1]], points_[t[2]]); }
  bool sheet_piece(std::size_t f) const { return !sheet_.empty() && sheet_[parent_[f]]; }

  // ------------------------------------------------------------ step 1
  bool build(const Triangle_soup& soup, const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
             std::size_t max_pieces, Arrangement_outcome& out)
  {
    // points equal in doubles are one vertex: edges that coincide are one edge
    {
      std::map<std::array<double, 3>, std::size_t> index;
      std::vector<std::size_t> merged(soup.points.size());
      for (std::size_t i = 0; i < soup.points.size(); ++i) {
        auto it = index.emplace(soup.points[i], points_.size());
        if (it.second) points_.emplace_back(soup.points[i][0], soup.points[i][1], soup.points[i][2]);
        merged[i] = it.first->second;
      }
      input_.reserve(soup.triangles.size());
      for (const Tri& t : soup.triangles) input_.push_back({{merged[t[0]], merged[t[1]], merged[t[2]]}});
    }
    const std::size_t T = input_.size();
    if (soup.sheet.size() == T) sheet_ = soup.sheet;
    degenerate_.assign(T, 0);
    for (std::size_t t = 0; t < T; ++t) {
      const Tri& x = input_[t];
      degenerate_[t] = x[0] == x[1] || x[1] == x[2] || x[0] == x[2] ||
                       CGAL::collinear(points_[x[0]], points_[x[1]], points_[x[2]]);
    }
    // the intersections of the crossing pairs: constraints of both triangles
    std::vector<std::vector<ESegment>> segments(T);
    std::vector<std::vector<EPoint>> on_triangle(T);
    std::vector<EPoint> found;  // every arrangement vertex that is not an input vertex (and some that are)
    std::size_t constraints = 0;
    for (const auto& p : pairs) {
      const std::size_t i = p.first, j = p.second;
      if (i >= T || j >= T || degenerate_[i] || degenerate_[j]) continue;
      const auto res = CGAL::intersection(triangle(input_[i]), triangle(input_[j]));
      if (!res) continue;
      auto add_segment = [&](const EPoint& a, const EPoint& b) {
        if (a == b) return;
        segments[i].emplace_back(a, b);
        segments[j].emplace_back(a, b);
        found.push_back(a);
        found.push_back(b);
        ++constraints;
      };
      using arrangement_detail::variant_get;
      if (const EPoint* q = variant_get<EPoint>(*res)) {
        on_triangle[i].push_back(*q);
        on_triangle[j].push_back(*q);
        found.push_back(*q);
      } else if (const ESegment* s = variant_get<ESegment>(*res)) {
        add_segment(s->source(), s->target());
      } else if (const EK::Triangle_3* r = variant_get<EK::Triangle_3>(*res)) {
        for (int k = 0; k < 3; ++k) add_segment(r->vertex(k), r->vertex(k + 1));
      } else if (const std::vector<EPoint>* poly = variant_get<std::vector<EPoint>>(*res)) {
        for (std::size_t k = 0; k < poly->size(); ++k) add_segment((*poly)[k], (*poly)[(k + 1) % poly->size()]);
      }
      if (constraints > max_pieces) {
        out.reason = "arrangement_too_large: more than " + std::to_string(max_pieces) + " intersection segments";
        return false;
      }
    }
    // where two constraints of a triangle cross: a vertex of every triangle it lies on
    for (std::size_t t = 0; t < T; ++t) {
      const std::vector<ESegment>& s = segments[t];
      if (s.size() < 2) continue;
      if (s.size() > 4000) {
        out.reason = "arrangement_too_large: a triangle with " + std::to_string(s.size()) + " intersection segments";
        return false;
      }
      std::vector<CGAL::Bbox_3> sb;
      for (const ESegment& x : s) sb.push_back(x.bbox());
      for (std::size_t a = 0; a < s.size(); ++a)
        for (std::size_t b = a + 1; b < s.size(); ++b) {
          if (!CGAL::do_overlap(sb[a], sb[b]) || !CGAL::do_intersect(s[a], s[b])) continue;
          const auto res = CGAL::intersection(s[a], s[b]);
          if (!res) continue;
          if (const EPoint* q = arrangement_detail::variant_get<EPoint>(*res)) found.push_back(*q);
        }
    }
    // the corners of a degenerate triangle lie on its neighbours' edges
    for (std::size_t t = 0; t < T; ++t)
      if (degenerate_[t])
        for (std::size_t v : input_[t]) found.push_back(points_[v]);
    std::sort(found.begin(), found.end(), arrangement_detail::Less_xyz());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    // every such vertex goes into each triangle it lies on (not a corner):
    // the pieces on both sides of a triangle edge then share their vertices
    std::vector<Box> box(T);
    for (std::size_t t = 0; t < T; ++t) {
      for (std::size_t v : input_[t]) box[t].add(points_[v]);
      for (std::size_t v : input_[t]) all_.add(points_[v]);
    }
    if (!found.empty()) {
      arrangement_detail::Box_grid grid;
      grid.reset(all_.lo, all_.hi, T, 7);
      std::vector<std::uint32_t> big;  // boxes that would flood the grid
      for (std::size_t t = 0; t < T; ++t) {
        if (degenerate_[t]) continue;
        if (grid.cells_covered(box[t].lo, box[t].hi) > 64) big.push_back(std::uint32_t(t));
        else grid.insert(std::uint32_t(t), box[t].lo, box[t].hi);
      }
      std::vector<std::size_t> stamp(T, std::size_t(-1));
      for (std::size_t k = 0; k < found.size(); ++k) {
        const EPoint& q = found[k];
        Box qb;
        qb.add(q);
        auto test = [&](std::uint32_t t) {
          if (stamp[t] == k) return;
          stamp[t] = k;
          if (!box[t].overlaps(qb)) return;
          const Tri& x = input_[t];
          if (q == points_[x[0]] || q == points_[x[1]] || q == points_[x[2]]) return;
          if (CGAL::orientation(points_[x[0]], points_[x[1]], points_[x[2]], q) != CGAL::COPLANAR) return;
          if (!triangle(x).has_on(q)) return;
          on_triangle[t].push_back(q);
        };
        grid.for_cells(qb.lo, qb.hi, [&](std::uint64_t key) {
          if (const auto* items = grid.at(key))
            for (std::uint32_t t : *items) test(t);
        });
        for (std::uint32_t t : big) test(t);
      }
    }
    // the pieces: a triangle without constraint stays whole
    std::map<EPoint, std::size_t, arrangement_detail::Less_xyz> vertex_of;
    for (std::size_t t = 0; t < T; ++t)
      if (!segments[t].empty() || !on_triangle[t].empty())
        for (std::size_t v : input_[t]) vertex_of.emplace(points_[v], v);
    std::vector<std::array<EPoint, 3>> split;
    for (std::size_t t = 0; t < T; ++t) {
      if (degenerate_[t]) continue;
      const Tri& x = input_[t];
      if (segments[t].empty() && on_triangle[t].empty()) {
        pieces_.push_back(x);
        parent_.push_back(t);
        continue;
      }
      split.clear();
      // copies (handles): points_ grows below
      const EPoint a = points_[x[0]], b = points_[x[1]], c = points_[x[2]];
      const CGAL::Vector_3<EK> n = CGAL::cross_product(b - a, c - a);
      const double nx = std::abs(CGAL::to_double(n.x())), ny = std::abs(CGAL::to_double(n.y())),
                   nz = std::abs(CGAL::to_double(n.z()));
      if (nx >= ny && nx >= nz)
        arrangement_detail::triangulate_in_plane<CGAL::Projection_traits_yz_3<EK>>(a, b, c, segments[t],
                                                                                   on_triangle[t], split);
      else if (ny >= nz)
        arrangement_detail::triangulate_in_plane<CGAL::Projection_traits_xz_3<EK>>(a, b, c, segments[t],
                                                                                   on_triangle[t], split);
      else
        arrangement_detail::triangulate_in_plane<CGAL::Projection_traits_xy_3<EK>>(a, b, c, segments[t],
                                                                                   on_triangle[t], split);
      for (const auto& s : split) {
        Tri piece;
        for (int k = 0; k < 3; ++k) {
          const EPoint& p = s[k];
          if (p == a) piece[k] = x[0];
          else if (p == b) piece[k] = x[1];
          else if (p == c) piece[k] = x[2];
          else {
            auto it = vertex_of.emplace(p, points_.size());
            if (it.second) points_.push_back(p);
            piece[k] = it.first->second;
          }
        }
        pieces_.push_back(piece);
        parent_.push_back(t);
      }
      if (pieces_.size() > max_pieces) {
        out.reason = "arrangement_too_large: more than " + std::to_string(max_pieces) + " faces";
        return false;
      }
    }
    out.pieces = pieces_.size();
    piece_box_.resize(pieces_.size());
    for (std::size_t f = 0; f < pieces_.size(); ++f)
      for (std::size_t v : pieces_[f]) piece_box_[f].add(points_[v]);
    return true;
  }

  // ------------------------------------------------------------ steps 2, 3
  struct Ray_answer
  {
    bool degenerate = false;
    int winding_front = 0;  // on the front of the piece the ray started on
    int jump = 0;           // net orientation of the pieces covering the start
    int covering = 0;       // how many pieces cover it (the start's own piece among them)
    std::size_t owner = 0;  // lowest input triangle among them
  };

  // The winding number in front of piece `f` and the pieces covering its
  // centroid, from the segment centroid -> `far` (outside every box).
  Ray_answer cast(std::size_t f, const std::array<double, 3>& far, const arrangement_detail::Box_grid& grid,
                  const std::vector<std::uint32_t>& big, std::vector<std::size_t>& stamp, std::size_t ticket) const
  {
    Ray_answer r;
    const Tri& x = pieces_[f];
    const EPoint c = CGAL::centroid(points_[x[0]], points_[x[1]], points_[x[2]]);
    const EPoint q(far[0], far[1], far[2]);
    const CGAL::Orientation side_of_far = CGAL::orientation(points_[x[0]], points_[x[1]], points_[x[2]], q);
    if (side_of_far == CGAL::COPLANAR) {
      r.degenerate = true;
      return r;
    }
    r.owner = parent_[f];
    int crossings = 0;
    bool degenerate = false;
    Box cb;
    cb.add(c);
    // the ray's footprint: the box of its segment
    Box footprint = cb;
    for (int d = 0; d < 3; ++d) {
      footprint.lo[d] = std::min(footprint.lo[d], far[d]);
      footprint.hi[d] = std::max(footprint.hi[d], far[d]);
    }
    auto test = [&](std::uint32_t g) {
      if (degenerate || stamp[g] == ticket) return;
      stamp[g] = ticket;
      if (sheet_piece(g)) return;  // bounds no cell
      const Box& gb = piece_box_[g];
      if (!gb.overlaps(footprint)) return;
      const Tri& y = pieces_[g];
      const EPoint &a = points_[y[0]], &b = points_[y[1]], &d = points_[y[2]];
      const CGAL::Orientation o1 = CGAL::orientation(a, b, d, c);
      if (o1 == CGAL::COPLANAR) {
        if (gb.overlaps(cb) && EK::Triangle_3(a, b, d).has_on(c)) {
          // covers the start: part of the jump, not a crossing
          r.jump += CGAL::orientation(a, b, d, q) == side_of_far ? 1 : -1;
          ++r.covering;
          r.owner = std::min(r.owner, parent_[g]);
          return;
        }
        if (CGAL::orientation(a, b, d, q) == CGAL::COPLANAR) degenerate = true;  // the ray lies in its plane
        return;
      }
      const CGAL::Orientation o2 = CGAL::orientation(a, b, d, q);
      if (o2 == CGAL::COPLANAR || o1 == o2) return;
      const CGAL::Orientation s1 = CGAL::orientation(c, q, a, b), s2 = CGAL::orientation(c, q, b, d),
                              s3 = CGAL::orientation(c, q, d, a);
      const bool has_pos = s1 == CGAL::POSITIVE || s2 == CGAL::POSITIVE || s3 == CGAL::POSITIVE;
      const bool has_neg = s1 == CGAL::NEGATIVE || s2 == CGAL::NEGATIVE || s3 == CGAL::NEGATIVE;
      if (has_pos && has_neg) return;  // passes beside it
      if (s1 == CGAL::COPLANAR || s2 == CGAL::COPLANAR || s3 == CGAL::COPLANAR) {
        degenerate = true;  // through an edge or a corner: shoot another ray
        return;
      }
      // leaving the front (POSITIVE side) enters the back: w grows along the ray
      crossings += o1 == CGAL::POSITIVE ? -1 : 1;
    };
    grid.for_cells(footprint.lo, footprint.hi, [&](std::uint64_t key) {
      if (const auto* items = grid.at(key))
        for (std::uint32_t g : *items) test(g);
    });
    for (std::uint32_t g : big) test(g);
    if (degenerate) {
      r.degenerate = true;
      return r;
    }
    // crossings is w at the start on the far side of the covering pieces
    if (side_of_far == CGAL::POSITIVE) r.winding_front = crossings;
    else r.winding_front = crossings - r.jump;
    return r;
  }

  void classify(Arrangement_outcome& out)
  {
    const std::size_t F = pieces_.size();
    // patches: pieces joined across edges two pieces share, in opposite directions
    Union_find<std::size_t> patches(F);
    {
      struct Edge_use
      {
        std::size_t a, b, face;
        bool forward;
      };
      std::vector<Edge_use> uses;
      uses.reserve(3 * F);
      for (std::size_t f = 0; f < F; ++f)
        for (int k = 0; k < 3; ++k) {
          const std::size_t u = pieces_[f][k], v = pieces_[f][(k + 1) % 3];
          uses.push_back({std::min(u, v), std::max(u, v), f, u < v});
        }
      std::sort(uses.begin(), uses.end(), [](const Edge_use& x, const Edge_use& y) {
        return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.face < y.face;
      });
      for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i;
        while (j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b) ++j;
        if (j - i == 2 && uses[i].forward != uses[i + 1].forward &&
            sheet_piece(uses[i].face) == sheet_piece(uses[i + 1].face))
          patches.unite(uses[i].face, uses[i + 1].face);
        i = j;
      }
    }
    std::vector<std::vector<std::size_t>> members;
    {
      std::unordered_map<std::size_t, std::size_t> id;
      for (std::size_t f = 0; f < F; ++f) {
        auto it = id.emplace(patches.find(f), members.size());
        if (it.second) members.emplace_back();
        members[it.first->second].push_back(f);
      }
    }
    out.patches = members.size();
    // the rays go to +x with a small tilt: a grid over y and z
    arrangement_detail::Box_grid grid;
    grid.reset(all_.lo, all_.hi, F, 6);
    std::vector<std::uint32_t> big;
    for (std::size_t f = 0; f < F; ++f) {
      if (grid.cells_covered(piece_box_[f].lo, piece_box_[f].hi) > 64) big.push_back(std::uint32_t(f));
      else grid.insert(std::uint32_t(f), piece_box_[f].lo, piece_box_[f].hi);
    }
    std::vector<std::size_t> stamp(F, std::size_t(-1));
    std::size_t ticket = 0;
    std::mt19937_64 random(20260128);
    std::uniform_real_distribution<double> tilt(-1., 1.);
    double extent = 0;
    for (int d = 0; d < 3; ++d) extent = std::max(extent, all_.hi[d] - all_.lo[d]);
    extent = std::max(extent, 1e-300);
    auto shoot = [&](std::size_t f, Ray_answer& answer) {
      for (int attempt = 0; attempt < 64; ++attempt) {
        ++out.rays;
        const Box& b = piece_box_[f];
        const double x0 = 0.5 * (b.lo[0] + b.hi[0]), y0 = 0.5 * (b.lo[1] + b.hi[1]), z0 = 0.5 * (b.lo[2] + b.hi[2]);
        const double length = all_.hi[0] - x0 + 0.25 * extent + 1.;
        // small tilts: the footprint stays in a few columns of the grid
        const double ty = 0.02 * tilt(random), tz = 0.02 * tilt(random);
        const std::array<double, 3> far{{x0 + length, y0 + ty * length, z0 + tz * length}};
        answer = cast(f, far, grid, big, stamp, ticket++);
        if (!answer.degenerate) return true;
        ++out.rays_shot_again;
      }
      return false;
    };
    std::vector<unsigned char> keep(F, 0), flip(F, 0);
    for (const std::vector<std::size_t>& patch : members) {
      Ray_answer rep;
      if (!shoot(patch.front(), rep)) {
        out.reason = "arrangement_failed: no ray without a degenerate hit";
        return;
      }
      if (sheet_piece(patch.front())) {
        // outside the solid and on none of its pieces (one on its surface
        // lies within rounding of the solid's face: nothing is lost)
        if (rep.covering == 0 && rep.winding_front == 0)
          for (std::size_t f : patch) keep[f] = 1;
        continue;
      }
      auto decide = [&](std::size_t f, const Ray_answer& a, bool covered) {
        if (covered && a.owner != parent_[f]) return;  // a coplanar copy of a lower triangle stands for it
        const int front = a.winding_front, back = a.winding_front + a.jump;
        // nonzero winding is inside: a piece pushed through the rest (w = -1)
        // stays part of the solid, so that its points are not lost
        if (front == 0 && back != 0) keep[f] = 1;
        else if (back == 0 && front != 0) keep[f] = flip[f] = 1;
      };
      if (rep.covering == 1) {  // covered by nothing else: one decision for the patch
        for (std::size_t f : patch) decide(f, rep, false);
        continue;
      }
      // coplanar copies: each piece knows which of them stands for it
      for (std::size_t f : patch) {
        Ray_answer a;
        if (f == patch.front()) a = rep;
        else if (!shoot(f, a)) {
          out.reason = "arrangement_failed: no ray without a degenerate hit";
          return;
        }
        decide(f, a, true);
      }
    }
    // the kept pieces; vertices numbered as first used
    std::vector<std::size_t> renumber(points_.size(), std::size_t(-1));
    std::vector<EPoint> kept_points;
    std::vector<Tri> kept;
    {
      std::vector<std::size_t> sheet_number(points_.size(), std::size_t(-1));
      std::vector<EPoint> sheet_points;
      for (std::size_t f = 0; f < F; ++f) {
        if (!keep[f] || !sheet_piece(f)) continue;
        Tri t = pieces_[f];
        for (std::size_t& v : t) {
          if (sheet_number[v] == std::size_t(-1)) {
            sheet_number[v] = sheet_points.size();
            sheet_points.push_back(points_[v]);
          }
          v = sheet_number[v];
        }
        out.sheets.triangles.push_back(t);
      }
      for (const EPoint& p : sheet_points)
        out.sheets.points.push_back({{CGAL::to_double(CGAL::exact(p.x())), CGAL::to_double(CGAL::exact(p.y())),
                                      CGAL::to_double(CGAL::exact(p.z()))}});
    }
    for (std::size_t f = 0; f < F; ++f) {
      if (!keep[f] || sheet_piece(f)) continue;
      Tri t = pieces_[f];
      if (flip[f]) std::swap(t[1], t[2]);
      for (std::size_t& v : t) {
        if (renumber[v] == std::size_t(-1)) {
          renumber[v] = kept_points.size();
          kept_points.push_back(points_[v]);
        }
        v = renumber[v];
      }
      kept.push_back(t);
    }
    // where the solid touches itself, split it while the points are exact:
    // rounded, the points of a short edge can no longer tell the order of
    // the faces about it
    if (!split_where_solid_touches_itself(kept_points, kept)) {
      out.reason = "arrangement_not_closed: the kept faces do not pair up around an edge";
      return;
    }
    for (const EPoint& p : kept_points)
      out.solid.points.push_back({{CGAL::to_double(CGAL::exact(p.x())), CGAL::to_double(CGAL::exact(p.y())),
                                   CGAL::to_double(CGAL::exact(p.z()))}});
    out.solid.triangles = std::move(kept);
    out.ok = true;
  }
};

MREPAIR_ARRANGEMENT_INLINE Arrangement_outcome arrange_winding_number_solid(
    const Triangle_soup& soup, const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
    std::size_t max_pieces)
{
  return Winding_number_solidifier().run(soup, pairs, max_pieces);
}

} // namespace solid
} // namespace internal
} // namespace mrepair
#endif // the definition

#endif // MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_ARRANGEMENT_H
