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
