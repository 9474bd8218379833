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

namespace mrepair {
namespace internal {

using Epick_point = CGAL::Epick::Point_3;

/// two triangles (u, w, c) and (w, u, d) sharing the edge uw overlap.
inline bool overlap_across_shared_edge(const Epick_point& u, const Epick_point& w,
                                       const Epick_point& c, const Epick_point& d)
{
  return CGAL::coplanar(u, w, c, d) && CGAL::coplanar_orientation(u, w, c, d) == CGAL::POSITIVE;
}

/// triangles `f` and `g` sharing only the vertex f[i] == g[j] meet elsewhere.
inline bool intersect_beside_shared_vertex(const Epick_point f[3], int i, const Epick_point g[3],
                                           int j)
{
  using K = CGAL::Epick;
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
