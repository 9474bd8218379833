// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_INSPECT_MESH_ARRAYS_H
#define MREPAIR_INTERNAL_INSPECT_MESH_ARRAYS_H

#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/inspect/parallel.h>
#include <mrepair/internal/inspect/surface_arrays.h>
#include <mrepair/internal/utility.h>
#include <mrepair/status.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/graph/graph_traits.hpp>

#include <cmath>
#include <vector>

namespace mrepair {
namespace internal {

// Flattens a FaceGraph into `Surface_arrays` (each edge has the corners of its
// non-border halfedges) and lists the length (number of border halfedges) of
// every border cycle in `border_cycles`. Works through the graph's index maps
// (initialised if needed: Polyhedron_3), remapped to compact indices so that
// Surface_mesh garbage does not matter. Returns `Status::ok`,
// `invalid_parameter` when the mesh is too large for 32-bit indices, or
// `invalid_mesh` when a border walk hit its bound (a broken next()).
// With `cycle_vertices`, also lists each border cycle's vertices (the
// sources of its halfedges, in next() order).
template <typename PolygonMesh, typename VertexPointMap>
Status build_mesh_arrays(const PolygonMesh& pm, VertexPointMap vpm, Surface_arrays& a,
                       std::vector<std::size_t>& border_cycles,
                       std::vector<std::vector<Inspect_index>>* cycle_vertices = nullptr)
{
  using GT = boost::graph_traits<PolygonMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;

  auto vim = CGAL::get_initialized_vertex_index_map(pm);
  auto him = CGAL::get_initialized_halfedge_index_map(pm);
  // A Surface_mesh without removed elements numbers its elements 0..n-1 in
  // iteration order: its element lists are then filled in parallel instead
  // of by sequential walks (30M halfedges on a 10M-face mesh).
  bool compact = false;
  std::vector<vertex_descriptor> V;
  std::vector<halfedge_descriptor> E;
  std::vector<face_descriptor> F;
  if constexpr (Is_surface_mesh<PolygonMesh>::value) {
    compact = !pm.has_garbage();
    if (compact) {
      using S = typename PolygonMesh::size_type;
      V.resize(pm.number_of_vertices());
      E.resize(pm.number_of_edges());
      F.resize(pm.number_of_faces());
      parallel_for_index(V.size(), 16384, [&](std::size_t i) { V[i] = vertex_descriptor(static_cast<S>(i)); });
      parallel_for_index(E.size(), 16384, [&](std::size_t i) {
        E[i] = halfedge(typename PolygonMesh::Edge_index(static_cast<S>(i)), pm);
      });
      parallel_for_index(F.size(), 16384, [&](std::size_t i) { F[i] = face_descriptor(static_cast<S>(i)); });
    }
  }

  // vertices: compact ids in iteration order
  std::size_t vslots = V.size();
  if (!compact) {
    V.reserve(internal::vertex_count(pm));
    for (vertex_descriptor v : vertices(pm)) {
      V.push_back(v);
      vslots = (std::max)(vslots, static_cast<std::size_t>(get(vim, v)) + 1);
    }
  }
  if (V.size() >= inspect_npos || vslots >= inspect_npos) return Status::invalid_parameter;
  std::vector<Inspect_index> vid(vslots, inspect_npos);
  parallel_for_index(V.size(), 16384, [&](std::size_t i) { vid[get(vim, V[i])] = static_cast<Inspect_index>(i); });
  a.num_vertices = V.size();
  a.xyz.resize(3 * V.size());
  a.finite.resize(V.size());
  parallel_for_index(V.size(), 8192, [&](std::size_t i) {
    const auto& p = get(vpm, V[i]);
    double x = CGAL::to_double(p.x()), y = CGAL::to_double(p.y()), z = CGAL::to_double(p.z());
    a.xyz[3 * i] = x;
    a.xyz[3 * i + 1] = y;
    a.xyz[3 * i + 2] = z;
    a.finite[i] = std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
  });

  // edges: one id for both halfedges
  std::size_t hslots = 2 * E.size();
  if (!compact) {
    for (halfedge_descriptor h : halfedges(pm))
      hslots = (std::max)(hslots, static_cast<std::size_t>(get(him, h)) + 1);
    E.reserve(edges(pm).size());
    for (auto e : edges(pm)) E.push_back(halfedge(e, pm));
  }
  if (hslots >= inspect_npos) return Status::invalid_parameter;
  std::vector<Inspect_index> eid(hslots, inspect_npos);
  const std::size_t ne = E.size();
  parallel_for_index(ne, 16384, [&](std::size_t e) {
    eid[get(him, E[e])] = eid[get(him, opposite(E[e], pm))] = static_cast<Inspect_index>(e);
  });
  a.edge_v.resize(2 * ne);
  parallel_for_index(ne, 8192, [&](std::size_t e) {
    a.edge_v[2 * e] = vid[get(vim, source(E[e], pm))];
    a.edge_v[2 * e + 1] = vid[get(vim, target(E[e], pm))];
  });

  // faces and corners: corner of halfedge h is source(h), its edge is edge(h)
  if (!compact) {
    F.reserve(internal::face_count(pm));
    for (face_descriptor f : faces(pm)) F.push_back(f);
  }
  const std::size_t nf = F.size();
  a.face_off.assign(nf + 1, 0);
  parallel_for_index(nf, 4096, [&](std::size_t f) {
    Inspect_index k = 0;
    for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(F[f], pm), pm)) {
      (void)h;
      ++k;
    }
    a.face_off[f] = k;
  });
  std::size_t nc = 0;
  for (std::size_t f = 0; f < nf; ++f) nc += a.face_off[f];
  if (nc >= inspect_npos) return Status::invalid_parameter;
  exclusive_scan_in_place(a.face_off);
  a.face_off[nf] = static_cast<Inspect_index>(nc);
  a.corner_v.resize(nc);
  a.corner_f.resize(nc);
  a.corner_e.resize(nc);
  a.face_skip.assign(nf, 0);
  std::vector<Inspect_index> corner_of_h(hslots, inspect_npos);
  parallel_for_index(nf, 4096, [&](std::size_t f) {
    Inspect_index c = a.face_off[f];
    for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(F[f], pm), pm)) {
      std::size_t hs = get(him, h);
      a.corner_v[c] = vid[get(vim, source(h, pm))];
      a.corner_f[c] = static_cast<Inspect_index>(f);
      a.corner_e[c] = eid[hs];
      corner_of_h[hs] = c;
      ++c;
    }
  });

  // incident corners of each edge: those of its non-border halfedges
  a.edge_off.assign(ne + 1, 0);
  parallel_for_index(ne, 8192, [&](std::size_t e) {
    a.edge_off[e] = (corner_of_h[get(him, E[e])] != inspect_npos) +
                    (corner_of_h[get(him, opposite(E[e], pm))] != inspect_npos);
  });
  const Inspect_index total = exclusive_scan_in_place(a.edge_off);
  a.edge_off[ne] = total;
  a.edge_corners.resize(total);
  parallel_for_index(ne, 8192, [&](std::size_t e) {
    Inspect_index o = a.edge_off[e];
    Inspect_index c0 = corner_of_h[get(him, E[e])];
    Inspect_index c1 = corner_of_h[get(him, opposite(E[e], pm))];
    if (c0 != inspect_npos) a.edge_corners[o++] = c0;
    if (c1 != inspect_npos) a.edge_corners[o++] = c1;
  });

  // border cycles, walked with next() as CGAL defines them
  border_cycles.clear();
  if (cycle_vertices) cycle_vertices->clear();
  std::vector<unsigned char> seen(hslots, 0);
  std::vector<halfedge_descriptor> border;
  border_halfedges(pm, border);
  for (halfedge_descriptor h : border) {
    if (seen[get(him, h)]) continue;
    std::size_t len = 0;
    halfedge_descriptor g = h;
    Walk_bound bound(hslots);
    if (cycle_vertices) cycle_vertices->emplace_back();
    do {
      seen[get(him, g)] = 1;
      ++len;
      if (cycle_vertices) cycle_vertices->back().push_back(vid[get(vim, source(g, pm))]);
      g = next(g, pm);
    } while (g != h && bound.step() && static_cast<std::size_t>(get(him, g)) < hslots);
    if (g != h) return Status::invalid_mesh;  // the walk left the halfedges or never came back
    border_cycles.push_back(len);
  }
  return Status::ok;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_INSPECT_MESH_ARRAYS_H
