// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The crossing pairs of a mesh, as face descriptors: the inspection's
// certified counter (inspect/self_intersections.h), asked for the list.
// A crossing pair intersects other than where the two faces touch at
// coincident vertices of their own (the copies of a split pinch, an unmerged
// seam): those touching pairs are counted, not listed, since no repair of the
// geometry removes them and none is needed.
#ifndef MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_CROSSINGS_H
#define MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_CROSSINGS_H

#include <mrepair/internal/inspect/mesh_arrays.h>
#include <mrepair/internal/inspect/self_intersections.h>
#include <mrepair/status.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {
namespace solid {

template <typename PolygonMesh>
struct Crossing_scan
{
  using face_descriptor = typename boost::graph_traits<PolygonMesh>::face_descriptor;
  Status status = Status::ok;
  std::vector<std::pair<face_descriptor, face_descriptor>> crossing;
  std::size_t touching = 0;  ///< pairs that only touch at coincident vertices
  std::size_t skipped = 0;   ///< faces not tested: not triangles, non-finite or collinear corners
  std::size_t components = 0;  ///< edge-connected components (no union needs looking for below 2)
};

// Lists the crossing pairs of `pm`. Faces that are not triangles with three
// distinct, finite, non-collinear corners take no part (counted in `skipped`).
template <typename PolygonMesh, typename VertexPointMap>
Crossing_scan<PolygonMesh> scan_crossings(const PolygonMesh& pm, VertexPointMap vpm)
{
  using face_descriptor = typename boost::graph_traits<PolygonMesh>::face_descriptor;
  Crossing_scan<PolygonMesh> scan;
  Surface_arrays a;
  std::vector<std::size_t> cycles;
  scan.status = build_mesh_arrays(pm, vpm, a, cycles);
  if (scan.status != Status::ok) return scan;
  // the arrays number the faces in iteration order (see build_mesh_arrays)
  std::vector<face_descriptor> F;
  F.reserve(a.num_faces());
  for (face_descriptor f : faces(pm)) F.push_back(f);
  const std::size_t nf = a.num_faces();
  std::vector<unsigned char> eligible(nf, 0);
  parallel_for_index(nf, 8192, [&](std::size_t f) {
    if (a.degree(f) != 3) return;
    const Inspect_index* v = &a.corner_v[a.face_off[f]];
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) return;
    if (!a.finite[v[0]] || !a.finite[v[1]] || !a.finite[v[2]]) return;
    auto p = [&](int i) {
      const double* x = a.point(v[i]);
      return CGAL::Epick::Point_3(x[0], x[1], x[2]);
    };
    if (CGAL::collinear(p(0), p(1), p(2))) return;
    eligible[f] = 1;
  });
  for (unsigned char e : eligible) scan.skipped += !e;
  {
    Union_find<Inspect_index> uf(nf);
    for (std::size_t e = 0; e < a.num_edges(); ++e)
      for (Inspect_index i = a.edge_off[e] + 1; i < a.edge_off[e + 1]; ++i)
        uf.unite(a.corner_f[a.edge_corners[a.edge_off[e]]], a.corner_f[a.edge_corners[i]]);
    for (std::size_t f = 0; f < nf; ++f) scan.components += uf.find(static_cast<Inspect_index>(f)) == f;
  }
  certify_flat_stars(a);
  keep_for_self_intersections(a);
  Self_intersection_counts counts = Self_intersection_counter(a).count(eligible, true);
  scan.touching = counts.touching;
  // the chunks' lists come in thread order: sorted, the repair is repeatable
  std::sort(counts.crossing.begin(), counts.crossing.end());
  scan.crossing.reserve(counts.crossing.size());
  for (const auto& p : counts.crossing) scan.crossing.emplace_back(F[p.first], F[p.second]);
  return scan;
}

} // namespace solid
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_CROSSINGS_H
