// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// When two triangles of one surface intersect, written once for the
// inspection's self-intersection count and the hole filler's patch check.
// The semantics are those of CGAL 5.5's `PMP::self_intersections`
// (`do_faces_intersect` in <CGAL/Polygon_mesh_processing/self_intersections.h>):
// - sharing an edge: they intersect when the two opposite vertices are
//   coplanar with the edge and on the same side of it (overlap);
// - sharing a vertex only: when the segment opposite the shared vertex in one
//   triangle meets the other triangle (either way round);
// - sharing nothing: when the triangles meet (exact predicate).
// Points must be finite (the exact predicates need it).
#ifndef MREPAIR_INTERNAL_TRIANGLE_INTERSECTION_H
#define MREPAIR_INTERNAL_TRIANGLE_INTERSECTION_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <mrepair/internal/utility.h>

#include <algorithm>
#include <cmath>

namespace mrepair {
namespace internal {

using Epick_point = CGAL::Epick::Point_3;

// ---- certificates in doubles ---------------------------------------------------
// On a flat or finely subdivided surface (CAD faces, midpoint-subdivided parts)
// the four points of an orientation test are nearly coplanar, the filters of
// the exact predicates cannot decide, and every neighbouring pair is decided in
// exact arithmetic (8 s of a 10 s report on a 1M-face blade part). Most such
// pairs lie apart by a wide margin in another direction: a plane through the
// shared vertex between the two fans, the two normals of an unfolded edge, an
// axis between two disjoint triangles. The tests below evaluate that in
// doubles and answer only when the value clears its rounding error by a factor
// of about 1000 (a bound sum(|terms|) x 1e-12, against at most about 12
// rounding errors of 1.1e-16 per term); otherwise they return false and the
// exact predicates decide, so the answers are those of the exact code.
namespace certify {

inline double l1(const Vec3& a) { return std::abs(a[0]) + std::abs(a[1]) + std::abs(a[2]); }
constexpr double margin = 1e-12;

// m . x is surely positive (x: a difference of two input points)
inline bool surely_positive(const Vec3& m, const Vec3& x) { return dot(m, x) > margin * l1(m) * l1(x); }

/// triangles (u, w, c) and (w, u, d) surely do not overlap: their normals
/// surely point opposite ways (then they are not coplanar, and meet only
/// along uw, or they lie on both sides of uw).
inline bool apart_across_edge(const Epick_point& u, const Epick_point& w, const Epick_point& c,
                              const Epick_point& d)
{
  const Vec3 pu = to_vec3(u), a = sub(to_vec3(w), pu), b = sub(to_vec3(c), pu), e = sub(to_vec3(d), pu);
  const double scale = l1(a) * l1(a) * l1(b) * l1(e);
  return dot(cross(a, b), cross(a, e)) < -margin * scale;
}

/// triangles `f` and `g` sharing only f[i] == g[j] surely meet nowhere else:
/// a plane through the shared vertex has f's two other vertices surely on
/// one side and g's surely on the other (then f minus the vertex lies in one
/// open half-space and g minus it in the other).
inline bool apart_beside_vertex(const Epick_point f[3], int i, const Epick_point g[3], int j)
{
  const Vec3 v = to_vec3(f[i]);
  const Vec3 f1 = sub(to_vec3(f[(i + 1) % 3]), v), f2 = sub(to_vec3(f[(i + 2) % 3]), v);
  const Vec3 g1 = sub(to_vec3(g[(j + 1) % 3]), v), g2 = sub(to_vec3(g[(j + 2) % 3]), v);
  const double nf1 = std::sqrt(dot(f1, f1)), nf2 = std::sqrt(dot(f2, f2));
  const double ng1 = std::sqrt(dot(g1, g1)), ng2 = std::sqrt(dot(g2, g2));
  if (!(nf1 > 0 && nf2 > 0 && ng1 > 0 && ng2 > 0)) return false;
  // the normal: from the middle direction of g's corner to that of f's
  const Vec3 m = sub(add(mul(f1, 1 / nf1), mul(f2, 1 / nf2)), add(mul(g1, 1 / ng1), mul(g2, 1 / ng2)));
  return surely_positive(m, f1) && surely_positive(m, f2) && surely_positive(neg(m), g1) &&
         surely_positive(neg(m), g2);
}

/// triangles sharing no vertex surely do not meet: an axis (either normal,
/// or the line between the centroids) on which every vertex of one is surely
/// below every vertex of the other.
inline bool apart_disjoint(const Epick_point f[3], const Epick_point g[3])
{
  const Vec3 o = to_vec3(f[0]);
  Vec3 fp[3], gp[3];
  for (int k = 0; k < 3; ++k) {
    fp[k] = sub(to_vec3(f[k]), o);
    gp[k] = sub(to_vec3(g[k]), o);
  }
  // along m, every vertex of g surely beyond every vertex of f: each value
  // m . p is off by at most about 5 roundings of l1(m) l1(p)
  double lf = 0, lg = 0;
  for (int k = 0; k < 3; ++k) {
    lf = std::max(lf, l1(fp[k]));
    lg = std::max(lg, l1(gp[k]));
  }
  auto separates = [&](const Vec3& m) {
    const double f_max = std::max({dot(m, fp[0]), dot(m, fp[1]), dot(m, fp[2])});
    const double g_min = std::min({dot(m, gp[0]), dot(m, gp[1]), dot(m, gp[2])});
    return g_min - f_max > margin * l1(m) * (lf + lg);
  };
  auto either_way = [&](const Vec3& m) { return separates(m) || separates(neg(m)); };
  const Vec3 nf = cross(fp[1], fp[2]);
  const Vec3 ng = triangle_normal(gp[0], gp[1], gp[2]);
  const Vec3 cf = add(add(fp[0], fp[1]), fp[2]), cg = add(add(gp[0], gp[1]), gp[2]);
  return either_way(sub(cg, cf)) || either_way(nf) || either_way(ng);
}

}  // namespace certify

/// two triangles (u, w, c) and (w, u, d) sharing the edge uw overlap.
inline bool overlap_across_shared_edge(const Epick_point& u, const Epick_point& w,
                                       const Epick_point& c, const Epick_point& d)
{
  if (certify::apart_across_edge(u, w, c, d)) return false;
  return CGAL::coplanar(u, w, c, d) && CGAL::coplanar_orientation(u, w, c, d) == CGAL::POSITIVE;
}

/// triangles `f` and `g` sharing only the vertex f[i] == g[j] meet elsewhere.
inline bool intersect_beside_shared_vertex(const Epick_point f[3], int i, const Epick_point g[3],
                                           int j)
{
  using K = CGAL::Epick;
  if (certify::apart_beside_vertex(f, i, g, j)) return false;
  // quick exits with the exact orientation predicate: an opposite segment
  // strictly on one side of the other triangle's plane misses it
  const Epick_point& gd = g[(j + 1) % 3];
  const Epick_point& ge = g[(j + 2) % 3];
  const Epick_point& fd = f[(i + 1) % 3];
  const Epick_point& fe = f[(i + 2) % 3];
  const CGAL::Orientation o1 = CGAL::orientation(f[0], f[1], f[2], gd);
  if (o1 != CGAL::COPLANAR && o1 == CGAL::orientation(f[0], f[1], f[2], ge)) {
    const CGAL::Orientation o2 = CGAL::orientation(g[0], g[1], g[2], fd);
    if (o2 != CGAL::COPLANAR && o2 == CGAL::orientation(g[0], g[1], g[2], fe)) return false;
  }
  const K::Triangle_3 tf(f[0], f[1], f[2]), tg(g[0], g[1], g[2]);
  return CGAL::do_intersect(tf, K::Segment_3(gd, ge)) || CGAL::do_intersect(tg, K::Segment_3(fd, fe));
}

/// triangles sharing nothing meet.
inline bool disjoint_triangles_intersect(const Epick_point f[3], const Epick_point g[3])
{
  using K = CGAL::Epick;
  if (certify::apart_disjoint(f, g)) return false;
  return CGAL::do_intersect(K::Triangle_3(f[0], f[1], f[2]), K::Triangle_3(g[0], g[1], g[2]));
}

/// triangles `f` and `g` with vertex keys `fk`, `gk` (equal keys: the same
/// vertex) intersect other than through what they share. Two shared keys
/// are a shared edge; three, the same face twice (an intersection).
template <typename Key>
bool triangles_intersect(const Key fk[3], const Epick_point f[3], const Key gk[3],
                         const Epick_point g[3])
{
  int shared = 0, fi[3] = {0, 0, 0}, gj[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (fk[i] == gk[j]) { fi[shared] = i; gj[shared] = j; ++shared; }
  if (shared == 0) return disjoint_triangles_intersect(f, g);
  if (shared == 1) return intersect_beside_shared_vertex(f, fi[0], g, gj[0]);
  if (shared == 2) {
    const int c = 3 - fi[0] - fi[1], d = 3 - gj[0] - gj[1];
    return overlap_across_shared_edge(f[fi[0]], f[fi[1]], f[c], g[d]);
  }
  return true;
}

}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_TRIANGLE_INTERSECTION_H
