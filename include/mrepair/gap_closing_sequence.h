// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_GAP_CLOSING_SEQUENCE_H
#define MREPAIR_GAP_CLOSING_SEQUENCE_H

/// \file gap_closing_sequence.h
/// Progressive gap closing as an object that steps forward and backward
/// through the contractions; `close_gaps()` (close_gaps.h) runs it once.

#include <mrepair/gap_closing_result.h>
#include <mrepair/internal/close_gaps/gap_closer.h>
#include <mrepair/parameters.h>
#include <mrepair/status.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>

#include <cmath>
#include <cstddef>

// Algorithm-specific named parameters (see close_gaps.h for their meaning).
MREPAIR_ADD_NAMED_PARAMETER(gap_lambda)                 // in [0,1], merged position λv+(1-λ)v'
MREPAIR_ADD_NAMED_PARAMETER(gap_snap_distance)          // absolute snap distance to edge endpoints
MREPAIR_ADD_NAMED_PARAMETER(gap_relative_tolerance)     // bool: tolerance x bbox diagonal
MREPAIR_ADD_NAMED_PARAMETER(gap_vertex_selection)       // vertex property map of bool (region)
MREPAIR_ADD_NAMED_PARAMETER(gap_face_selection)         // face property map of bool (region)
MREPAIR_ADD_NAMED_PARAMETER(gap_split_pinched_vertices) // bool: close_gaps makes the output manifold
MREPAIR_ADD_NAMED_PARAMETER(gap_max_operations)         // std::size_t cap on contractions

namespace mrepair {

/// \ingroup mrepair_gaps
/// the progressive gap closing of Borodin, Novotni and Klein as an object that
/// steps forward (contracting the nearest boundary vertex-vertex or
/// vertex-edge pair) and backward (undoing contractions) on a triangle mesh
/// with boundaries.
///
/// \code
///   pairs  <- for each boundary vertex v: nearest boundary edge e not incident to v (grid)
///             vertex-edge pair if the projection falls inside e (further than the snap
///             distance from its ends), else vertex-vertex with the nearer end
///   queue  <- pairs by distance
///   forward: pop nearest; check fans, flips, zero areas; contract (v moves to λv+(1-λ)v');
///            record removed/added faces and old positions; recompute the pairs of the
///            vertices projected on every boundary edge that changed
///   backward: replay the record in reverse (re-add the removed vertex, swap faces, restore positions)
/// \endcode
///
/// Contractions are recorded as face edits (faces removed, faces added, at most
/// one removed vertex, old and new positions), so "exactly" means: after
/// backward steps the mesh has the same vertex set with bit-identical
/// positions and the same set of faces as vertex triples (same orientation).
/// On `Surface_mesh` the vertex indices are identical too (the vertex free list
/// is last-in first-out); face and halfedge indices may be permuted.
/// Vertex descriptors are stable on both types except for vertices that a
/// contraction removed and its undo re-created (a new descriptor on `Polyhedron_3`).
///
/// Two patches first meet at a single vertex (a "pinched" vertex with two
/// fans, valid as a halfedge graph); their boundary edges then coincide and are
/// glued by the next contractions. Pinched vertices that remain can be split
/// with `CGAL::Polygon_mesh_processing::duplicate_non_manifold_vertices()`
/// (`close_gaps()` does so by default).
///
/// The mesh must not be modified by others while the sequence is in use.
template <class TriangleMesh,
          class VertexPointMap =
              typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::type>
class Gap_closing_sequence
{
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;

public:
  /// prepares the pairs of `tm` for closing gaps up to `max_distance`.
  /// \param np optional: `vertex_point_map` (of type `VertexPointMap`),
  ///   `mrepair::parameters::gap_relative_tolerance(bool)` (false: `max_distance` is
  ///   absolute; true: a fraction of the bounding-box diagonal),
  ///   `gap_lambda(double)` (0.5), `gap_snap_distance(double)` (`max_distance`; a
  ///   projection closer than min(snap, edge length / 3) to an edge end snaps to it),
  ///   `gap_vertex_selection(map)` / `gap_face_selection(map)` (bool property maps:
  ///   only boundary vertices of the region, and edges with both ends in it, are paired;
  ///   a vertex is in a face region when one of its faces is selected; default all).
  /// \pre `CGAL::is_valid_polygon_mesh(tm)` (checked in debug builds only: the check costs
  ///   more than the closing). Bad data (no face, NaN/infinite coordinate, a non-triangle face,
  ///   bad parameters) sets `status()` and makes every step a no-op.
  template <class NamedParameters = CGAL::parameters::Default_named_parameters>
  Gap_closing_sequence(TriangleMesh& tm, double max_distance,
                       const NamedParameters& np = CGAL::parameters::default_values())
    : closer_(tm, CGAL::parameters::choose_parameter(
                      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                      get_property_map(CGAL::vertex_point, tm)))
  {
    namespace inp = mrepair::internal_np;
    using CGAL::parameters::get_parameter;
    using CGAL::parameters::is_default_parameter;
    const double lambda = internal::get_or(np, inp::gap_lambda, 0.5);
    const bool relative = internal::get_or(np, inp::gap_relative_tolerance, false);
    const double snap = internal::get_or(np, inp::gap_snap_distance, -1.0);
    if (!std::isfinite(max_distance) || max_distance < 0 || !(lambda >= 0 && lambda <= 1) ||
        !std::isfinite(snap)) {
      closer_.refuse(Status::invalid_parameter, "tolerance must be finite and >= 0, gap_lambda in [0,1]");
      return;
    }
    // the region: a vertex is in it when selected, or when one of its faces is
    if constexpr (!is_default_parameter<NamedParameters, inp::gap_vertex_selection_t>::value) {
      auto m = get_parameter(np, inp::gap_vertex_selection);
      closer_.start(max_distance, lambda, relative, snap,
                    [m](vertex_descriptor v, const TriangleMesh&) { return bool(get(m, v)); });
    } else if constexpr (!is_default_parameter<NamedParameters, inp::gap_face_selection_t>::value) {
      auto m = get_parameter(np, inp::gap_face_selection);
      closer_.start(max_distance, lambda, relative, snap, [m](vertex_descriptor v, const TriangleMesh& g) {
        bool in = false;
        for (halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, g), g))
          if (!is_border(h, g) && get(m, face(h, g))) in = true;
        return in;
      });
    } else {
      closer_.start(max_distance, lambda, relative, snap, internal::Gap_whole_mesh());
    }
  }

  /// `Status::ok`, or why the input was refused (then every step is a no-op).
  Status status() const { return closer_.status(); }
  /// the absolute distance limit of the sequence.
  double max_distance() const { return closer_.max_distance(); }
  /// number of contractions recorded (the farthest mesh reached).
  std::size_t size() const { return closer_.size(); }
  /// number of contractions applied to the mesh now.
  std::size_t position() const { return closer_.position(); }
  /// error level of the mesh now: running maximum of the pair distances applied (0 at the input).
  double current_distance() const { return closer_.current_distance(); }

  /// applies up to `k` contractions (replaying recorded ones first); returns how many.
  std::size_t forward(std::size_t k) { return closer_.forward(k); }
  /// applies contractions while the next pair is not farther than `d` (at most `max_distance()`).
  std::size_t forward_to_distance(double d) { return closer_.forward_to_distance(d); }
  /// undoes up to `k` contractions; returns how many.
  std::size_t backward(std::size_t k) { return closer_.backward(k); }
  /// undoes contractions until `current_distance() <= d`.
  std::size_t backward_to_distance(double d) { return closer_.backward_to_distance(d); }
  /// one forward step limited to pairs not farther than `limit`; false when none is left.
  bool step(double limit) { return closer_.step(limit); }

  /// statistics of the mesh now (scans the mesh: O(size)).
  Gap_closing_result result() const { return closer_.result(); }

private:
  internal::Gap_closer<TriangleMesh, VertexPointMap> closer_;
};

} // namespace mrepair

#endif // MREPAIR_GAP_CLOSING_SEQUENCE_H
