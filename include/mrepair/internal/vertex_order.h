// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_VERTEX_ORDER_H
#define MREPAIR_INTERNAL_VERTEX_ORDER_H

// An order in which parallel per-vertex passes walk a Surface_mesh fastest.
// A pass over the vertices in index order reads each vertex's halfedges; where
// a file lists its faces in another order than its vertices (a generated or
// re-exported scan), those halfedges lie anywhere in the 48 MB of halfedges
// of a 1M-face mesh, and the walks wait on memory. In the order of the
// vertices' own halfedges, neighbours in the pass read neighbouring
// halfedges (and the per-face and per-halfedge data beside them). A pass
// whose vertices each write only their own result gives the same results in
// any order.

#include <mrepair/internal/inspect/parallel.h>
#include <mrepair/internal/utility.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mrepair {
namespace internal {

/// The positions 0..n-1 of `vs` (vertices of `m` with a halfedge) by their
/// halfedges' indices, to a block of 16; empty (the order as it is) on meshes
/// other than Surface_mesh and below 2^16 vertices, where it cannot pay.
template <class Mesh, class VertexVector>
std::vector<std::uint32_t> halfedge_order(const Mesh& m, const VertexVector& vs)
{
  std::vector<std::uint32_t> first, order;
  if constexpr (Is_surface_mesh<Mesh>::value) {
    if (vs.size() < (std::size_t(1) << 16) || vs.size() >= (std::size_t(1) << 31)) return order;
    constexpr int block = 4;
    bucket_items(vs.size(), (static_cast<std::size_t>(m.num_halfedges()) >> block) + 1, std::uint32_t(-1),
                 [&](std::size_t i) {
                   return static_cast<std::uint32_t>(static_cast<std::size_t>(m.halfedge(vs[i])) >> block);
                 },
                 first, order);
  }
  return order;
}

/// `vs` put in that order, in place (`buffer`: scratch space kept by the caller).
template <class Mesh, class Vertex>
void sort_by_halfedge(const Mesh& m, std::vector<Vertex>& vs, std::vector<Vertex>& buffer)
{
  const std::vector<std::uint32_t> order = halfedge_order(m, vs);
  if (order.empty()) return;
  buffer.resize(vs.size());
  parallel_for_index(vs.size(), 1 << 14, [&](std::size_t k) { buffer[k] = vs[order[k]]; });
  vs.swap(buffer);
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_VERTEX_ORDER_H
