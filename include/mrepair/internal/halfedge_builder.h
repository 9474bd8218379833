// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_HALFEDGE_BUILDER_H
#define MREPAIR_INTERNAL_HALFEDGE_BUILDER_H

// The one builder of a halfedge mesh from polygons whose topology is already
// known (the file reader's Soup_topology, the soup repair's partnered
// sides). It wires the structure directly through the MutableFaceGraph
// primitives (add_edge, add_face, set_next, ...), much cheaper than
// Euler::add_face per polygon. The caller guarantees a polygon mesh: every
// directed edge once, one fan of faces per vertex.
//
// The input is a corner table: corner c runs from vertex `source(c)` to
// `source(next(c))`; the corners of polygon f are `begin(f)` .. `end(f) - 1`
// in order; `opposite(c)` is the corner running the other way along the same
// edge, or `none` on the border. Elements are created in a fixed order:
// used vertices by index, one edge per corner pair at its lower corner,
// faces by index; a face's halfedge is its first corner's, a vertex's the
// last corner (by index) entering it, or on the border the border halfedge
// entering it.

#include <mrepair/internal/utility.h>

#include <boost/graph/graph_traits.hpp>
#include <CGAL/boost/graph/helpers.h>

#include <cstddef>
#include <vector>

namespace mrepair {
namespace internal {

constexpr std::size_t no_corner = static_cast<std::size_t>(-1);

/// The builder below for an empty Surface_mesh: the same elements in the same
/// order, but its arrays are sized once and the halfedges wired in parallel
/// (each halfedge's next and face are written by its own corner, its prev by
/// its predecessor's), a third of the time of element-by-element additions at
/// 1M faces. The vertices' halfedges take the same rule as below: the last
/// corner entering the vertex, or the border halfedge entering it.
template <class SurfaceMesh, class CornerTable, class PutPoint>
void build_surface_mesh_in_parallel(SurfaceMesh& g, const CornerTable& m, PutPoint& put_point)
{
  using Vertex_index = typename SurfaceMesh::Vertex_index;
  using Halfedge_index = typename SurfaceMesh::Halfedge_index;
  using Face_index = typename SurfaceMesh::Face_index;
  using size_type = typename SurfaceMesh::size_type;
  const std::size_t np = m.num_points(), nc = m.num_corners(), nf = m.num_faces();
  std::vector<Vertex_index> vd(np);
  std::size_t nv = 0;
  for (std::size_t i = 0; i < np; ++i)
    if (m.used(i)) vd[i] = Vertex_index(static_cast<size_type>(nv++));
  // one edge per corner pair, numbered at its lower corner in corner order
  std::vector<Halfedge_index> hd(nc);
  std::size_t ne = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    const std::size_t o = m.opposite(c);
    if (o != no_corner && o < c) continue;
    hd[c] = Halfedge_index(static_cast<size_type>(2 * ne));
    if (o != no_corner) hd[o] = Halfedge_index(static_cast<size_type>(2 * ne + 1));
    ++ne;
  }
  g.resize(static_cast<size_type>(nv), static_cast<size_type>(ne), static_cast<size_type>(nf));
  for (std::size_t i = 0; i < np; ++i)
    if (m.used(i)) put_point(vd[i], i);
  // on the border, the halfedge leaving each vertex along the border (unique:
  // one fan per vertex)
  std::vector<Halfedge_index> border_out(np);
  parallel_for_index(nc, 1 << 14, [&](std::size_t c) {
    if (m.opposite(c) == no_corner) border_out[m.source(m.next(c))] = g.opposite(hd[c]);
  });
  parallel_for_index(nf, 1 << 13, [&](std::size_t f) {
    const Face_index fd(static_cast<size_type>(f));
    g.set_halfedge(fd, hd[m.begin(f)]);
    for (std::size_t c = m.begin(f); c < m.end(f); ++c) {
      const Halfedge_index h = hd[c];
      g.set_target(h, vd[m.source(m.next(c))]);
      g.set_next(h, hd[m.next(c)]);
      g.set_face(h, fd);
    }
  });
  for (std::size_t c = 0; c < nc; ++c) g.set_halfedge(vd[m.source(m.next(c))], hd[c]);
  parallel_for_index(nc, 1 << 14, [&](std::size_t c) {
    if (m.opposite(c) != no_corner) return;
    const std::size_t u = m.source(c);
    const Halfedge_index b = g.opposite(hd[c]);
    g.set_target(b, vd[u]);
    g.set_face(b, Face_index());
    g.set_next(b, border_out[u]);
  });
  for (std::size_t c = 0; c < nc; ++c)
    if (m.opposite(c) == no_corner) g.set_halfedge(vd[m.source(c)], g.opposite(hd[c]));
}

/// builds `g` (assumed empty) from the corner table `m`, which provides
/// `num_points()`, `num_faces()`, `num_corners()`, `begin(f)`, `end(f)`,
/// `source(c)`, `next(c)`, `opposite(c)` (or `no_corner`) and `used(v)`
/// (a point without a used mark gets no vertex). Reserves `room` first;
/// `put_point(v, i)` stores point i at vertex v.
template <class PolygonMesh, class CornerTable, class PutPoint>
void build_halfedge_mesh(PolygonMesh& g, const CornerTable& m, const Element_counts& room, PutPoint put_point)
{
  using GT = boost::graph_traits<PolygonMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  const std::size_t np = m.num_points(), nc = m.num_corners(), nf = m.num_faces();
  reserve(g, static_cast<typename GT::vertices_size_type>(room.vertices),
          static_cast<typename GT::edges_size_type>(room.edges),
          static_cast<typename GT::faces_size_type>(room.faces));
  if constexpr (Is_surface_mesh<PolygonMesh>::value) {
    if (g.num_vertices() == 0 && g.num_halfedges() == 0 && g.num_faces() == 0) {
      build_surface_mesh_in_parallel(g, m, put_point);
      return;
    }
  }

  std::vector<vertex_descriptor> vd(np, GT::null_vertex());
  for (std::size_t i = 0; i < np; ++i) {
    if (!m.used(i)) continue;
    vd[i] = add_vertex(g);
    put_point(vd[i], i);
  }
  // one edge per corner pair; on the border, the halfedge leaving each vertex
  // along the border (unique: one fan per vertex)
  std::vector<halfedge_descriptor> hd(nc);
  std::vector<halfedge_descriptor> border_out(np, GT::null_halfedge());
  for (std::size_t c = 0; c < nc; ++c) {
    const std::size_t o = m.opposite(c);
    if (o != no_corner && o < c) continue;
    const halfedge_descriptor h = halfedge(add_edge(g), g);
    hd[c] = h;
    if (o != no_corner)
      hd[o] = opposite(h, g);
    else
      border_out[m.source(m.next(c))] = opposite(h, g);
  }
  for (std::size_t f = 0; f < nf; ++f) {
    const face_descriptor fd = add_face(g);
    set_halfedge(fd, hd[m.begin(f)], g);
    for (std::size_t c = m.begin(f); c < m.end(f); ++c) {
      const halfedge_descriptor h = hd[c];
      const vertex_descriptor w = vd[m.source(m.next(c))];
      set_target(h, w, g);
      set_next(h, hd[m.next(c)], g);
      set_face(h, fd, g);
      set_halfedge(w, h, g);
    }
  }
  // border halfedges: the one of corner c (u -> w) runs w -> u and continues
  // with the border leaving u; border vertices point to a border halfedge
  for (std::size_t c = 0; c < nc; ++c) {
    if (m.opposite(c) != no_corner) continue;
    const std::size_t u = m.source(c);
    const halfedge_descriptor b = opposite(hd[c], g);
    set_target(b, vd[u], g);
    set_face(b, GT::null_face(), g);
    set_next(b, border_out[u], g);
    set_halfedge(vd[u], b, g);
  }
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_HALFEDGE_BUILDER_H
