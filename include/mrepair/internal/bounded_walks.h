// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Why no walk of mrepair can run forever, and the two tools that make it so.
//
// A walk around a face or a border cycle follows next(); one around a vertex
// follows opposite(next()). When next() is a permutation of the halfedges
// (prev() is its inverse) and opposite() an involution without fixed points,
// both are permutations, so every walk comes back to its start after at most
// as many steps as there are halfedges. A broken structure (two halfedges
// with the same next, a prev that is not the inverse) is what makes a walk
// circle without reaching its start, as CGAL's triangulate_faces left a
// non-planar pentagon (issue 36).
//
// 1. `halfedge_structure_defect()` checks those local rules in O(halfedges)
//    (in parallel on a Surface_mesh): the public entries that take a mesh
//    call it and return `invalid_mesh` instead of walking a broken one.
// 2. `Walk_bound` counts the steps of a hand-written walk, and of every loop
//    that pops a queue or repeats until nothing changes, against a limit
//    derived from the mesh size: a walk that reaches it stops its step and
//    the step reports `invalid_mesh` with a message naming it.
#ifndef MREPAIR_INTERNAL_BOUNDED_WALKS_H
#define MREPAIR_INTERNAL_BOUNDED_WALKS_H

#include <mrepair/internal/utility.h>

#include <boost/graph/graph_traits.hpp>

#include <atomic>
#include <cstddef>
#include <limits>
#include <string>

namespace mrepair {
namespace internal {

/// the step limit of any walk by next() or around a vertex of `m`: every
/// halfedge slot once, plus one (Surface_mesh counts its removed slots too,
/// which only makes the bound looser).
template <typename Mesh>
std::size_t walk_limit(const Mesh& m)
{
  if constexpr (Is_surface_mesh<Mesh>::value)
    return static_cast<std::size_t>(m.number_of_halfedges() + m.number_of_removed_halfedges()) + 1;
  else if constexpr (Is_polyhedron<Mesh>::value)
    return static_cast<std::size_t>(m.size_of_halfedges()) + 1;
  else
    return static_cast<std::size_t>(num_halfedges(m)) + 1;
}

/// a step counter with a limit: `step()` is false once the limit is used up.
/// \code
/// Walk_bound bound(walk_limit(m));
/// do { ...; g = next(g, m); } while (g != h && bound.step());
/// if (bound.exceeded()) return fail("the border walk of <step>");
/// \endcode
class Walk_bound
{
public:
  explicit Walk_bound(std::size_t limit) : left_(limit) {}
  /// counts one step; false when the limit was already reached.
  bool step()
  {
    if (left_ == 0) {
      exceeded_ = true;
      return false;
    }
    --left_;
    return true;
  }
  bool exceeded() const { return exceeded_; }

private:
  std::size_t left_;
  bool exceeded_ = false;
};

/// the message of a step stopped by its bound.
inline std::string walk_bound_message(const char* step)
{
  return std::string(step) +
         ": stopped after more steps than the mesh has elements (the halfedge structure is broken); the mesh is left as it was at the stop";
}

/// an empty string when the halfedge structure of `m` is sound: for every
/// halfedge h, prev(next(h)) == h, opposite(opposite(h)) == h
/// != opposite(h), target(h) == source(next(h)), face(next(h)) == face(h);
/// every face's halfedge lies on it, every vertex's halfedge points to it.
/// Otherwise the first rule found broken. Then every walk by next() or
/// around a vertex returns to its start (see the top of this file).
template <typename Mesh>
std::string halfedge_structure_defect(const Mesh& m)
{
  using GT = boost::graph_traits<Mesh>;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  const auto check_halfedge = [&](halfedge_descriptor h) -> const char* {
    // prev(next(h)) == h for every h makes next() injective, so a
    // permutation of the finite set of halfedges with prev() its inverse:
    // next(prev(h)) == h needs no check (nor its random read)
    const halfedge_descriptor o = opposite(h, m), n = next(h, m);
    if (o == h || opposite(o, m) != h) return "opposite() is not an involution";
    if (prev(n, m) != h) return "prev() is not the inverse of next()";
    if (target(h, m) != target(opposite(n, m), m)) return "a halfedge's target is not its next's source";
    if (face(n, m) != face(h, m)) return "a face's cycle of next() leaves the face";
    return nullptr;
  };
  if constexpr (Is_surface_mesh<Mesh>::value) {
    using H = typename Mesh::Halfedge_index;
    const std::size_t slots = m.number_of_halfedges() + m.number_of_removed_halfedges();
    const std::size_t vslots = m.number_of_vertices() + m.number_of_removed_vertices();
    const std::size_t fslots = m.number_of_faces() + m.number_of_removed_faces();
    // the removed flags are bits: read them only when something was removed
    const bool garbage = m.has_garbage();
    std::atomic<const char*> found{nullptr};
    parallel_for_index(slots, 1 << 16, [&](std::size_t i) {
      const H h(static_cast<typename Mesh::size_type>(i));
      if ((garbage && m.is_removed(h)) || found.load(std::memory_order_relaxed)) return;
      for (H g : {m.next(h), m.prev(h)})  // opposite(h) is h's neighbour slot
        if (std::size_t(g) >= slots || (garbage && m.is_removed(g))) {
          found = "a halfedge refers to a missing halfedge";
          return;
        }
      const auto v = m.target(h);
      if (std::size_t(v) >= vslots || (garbage && m.is_removed(v))) {
        found = "a halfedge points to a missing vertex";
        return;
      }
      const auto f = m.face(h);
      if (f != typename Mesh::Face_index() && (std::size_t(f) >= fslots || (garbage && m.is_removed(f)))) {
        found = "a halfedge lies on a missing face";
        return;
      }
      if (const char* why = check_halfedge(h)) found = why;
    });
    if (const char* why = found.load()) return why;
    using F = typename Mesh::Face_index;
    using V = typename Mesh::Vertex_index;
    parallel_for_index(fslots, 1 << 16, [&](std::size_t i) {
      const F f(static_cast<typename Mesh::size_type>(i));
      if (garbage && m.is_removed(f)) return;
      const H h = m.halfedge(f);
      if (std::size_t(h) >= slots || m.face(h) != f) found = "a face's halfedge does not lie on it";
    });
    parallel_for_index(vslots, 1 << 16, [&](std::size_t i) {
      const V v(static_cast<typename Mesh::size_type>(i));
      if (garbage && m.is_removed(v)) return;
      const H h = m.halfedge(v);
      if (h != H() && (std::size_t(h) >= slots || m.target(h) != v))
        found = "a vertex's halfedge does not point to it";
    });
    if (const char* why = found.load()) return why;
  } else {
    for (halfedge_descriptor h : halfedges(m))
      if (const char* why = check_halfedge(h)) return why;
    for (auto f : faces(m))
      if (face(halfedge(f, m), m) != f) return "a face's halfedge does not lie on it";
    for (auto v : vertices(m)) {
      const halfedge_descriptor h = halfedge(v, m);
      if (h != GT::null_halfedge() && target(h, m) != v) return "a vertex's halfedge does not point to it";
    }
  }
  return {};
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_BOUNDED_WALKS_H
