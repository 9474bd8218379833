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

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <istream>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace mrepair {

/// \ingroup mrepair_gaps
/// one recorded contraction of a `Gap_closing_sequence`.
struct Gap_contraction_record
{
  double distance = 0;                  ///< error level after it (running maximum of pair distances)
  std::array<double, 3> position{{0, 0, 0}};  ///< where the contracted vertex went
};

/// \ingroup mrepair_gaps
/// the content of a gap sequence file (`Gap_closing_sequence::save()`).
///
/// Format, version 1: UTF-8 text, one item per line, numbers written with 17
/// significant digits (they read back bit-identical):
/// \code
///   mrepair-gap-sequence 1
///   input <vertices> <faces> <fingerprint: 16 hex digits>
///   region <fingerprint: 16 hex digits>            (of the input boundary vertices left out
///                                                   of the region; 0000000000000000: none)
///   tolerance <absolute distance limit>
///   lambda <lambda>
///   snap <snap distance; -1: the tolerance>
///   contractions <n>
///   c <distance> <x> <y> <z>                        (n lines, in order)
///   end <FNV-1a 64 of every byte before this line: 16 hex digits>
/// \endcode
/// `x y z`: the new position of the vertex that moved (vertex-vertex: the one
/// kept; vertex-edge: the one inserted into the edge). The fingerprints do not
/// depend on the order of vertices and faces (sums of hashes of the bit
/// patterns of the positions, and of each face's three positions in cyclic
/// order).
///
/// `Gap_closing_sequence::replay()` runs the algorithm again and checks every
/// contraction against the file (it costs what the first run cost): a file
/// replays on the same mesh type read from the same input by the same version
/// of the algorithm; anything else is refused with the first contraction that
/// differs (ties between equal distances may be broken differently on another
/// mesh type).
struct Gap_sequence_file
{
  static constexpr int format_version = 1;
  std::size_t input_vertices = 0, input_faces = 0;
  std::uint64_t input_fingerprint = 0, region_fingerprint = 0;
  double tolerance = 0, lambda = 0.5, snap = -1;
  std::vector<Gap_contraction_record> contractions;

  /// writes the file; false when the stream fails.
  bool write(std::ostream& out) const;

  /// reads a file written by `write()`. Returns `Status::ok`, or
  /// `Status::parse_error` (with `error`: the line and what is wrong) for a file
  /// that is not a gap sequence, of another version, truncated or corrupt, or
  /// `Status::io_error` when the stream fails.
  Status read(std::istream& in, std::string& error);

  /// FNV-1a 64 of `s`.
  static std::uint64_t checksum(const std::string& s);
};

} // namespace mrepair

// the file's writer and parser, the fingerprint hashes and the recording point map
#include <mrepair/internal/close_gaps/sequence_file.h>

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
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  using Point = typename boost::property_traits<VertexPointMap>::value_type;
  using Recording_map = internal::Gap_recording_point_map<VertexPointMap>;

public:
  /// prepares the pairs of `tm` for closing gaps up to `max_distance`.
  /// \param np optional: `vertex_point_map` (of type `VertexPointMap`),
  ///   `mrepair::parameters::gap_relative_tolerance(bool)` (false: `max_distance` is
  ///   absolute; true: a fraction of the bounding-box diagonal),
  ///   `gap_lambda(double)` (0.5), `gap_snap_distance(double)` (`max_distance`; a
  ///   projection closer than min(snap, edge length / 3) to an edge end snaps to it),
  ///   `gap_vertex_selection(map)` / `gap_face_selection(map)` (bool property maps:
  ///   only boundary vertices of the region, and edges with both ends in it, are paired;
  ///   a vertex is in a face region when one of its faces is selected; default all),
  ///   `gap_fingerprint_input(bool)` (false: hash the input, O(size), so that `save()`
  ///   can write a file that `replay()` checks against its mesh),
  ///   `gap_keep_input_points(bool)` (false: the λ point first; true: a placement
  ///   that leaves the input positions of the vertices a contraction moves or
  ///   removes within 1e-6 x the bounding-box diagonal of its new faces is
  ///   taken before it, so the reference comparison loses none of them. A
  ///   file saved with it replays only with it: the file does not record it).
  /// \pre `CGAL::is_valid_polygon_mesh(tm)` (checked in debug builds only: the check costs
  ///   more than the closing). Bad data (no face, NaN/infinite coordinate, a non-triangle face,
  ///   bad parameters) sets `status()` and makes every step a no-op.
  template <class NamedParameters = CGAL::parameters::Default_named_parameters>
  Gap_closing_sequence(TriangleMesh& tm, double max_distance,
                       const NamedParameters& np = CGAL::parameters::default_values())
    : tm_(tm),
      vpm_(CGAL::parameters::choose_parameter(
          CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
          get_property_map(CGAL::vertex_point, tm))),
      last_(new Point()),
      closer_(tm, Recording_map{vpm_, last_.get()})
  {
    namespace inp = mrepair::internal_np;
    using CGAL::parameters::get_parameter;
    using CGAL::parameters::is_default_parameter;
    const double lambda = internal::get_or(np, inp::gap_lambda, 0.5);
    const bool relative = internal::get_or(np, inp::gap_relative_tolerance, false);
    const double snap = internal::get_or(np, inp::gap_snap_distance, -1.0);
    closer_.keep_input_points(internal::get_or(np, inp::gap_keep_input_points, false));
    file_.lambda = lambda;
    file_.snap = snap;
    if (!std::isfinite(max_distance) || max_distance < 0 || !(lambda >= 0 && lambda <= 1) ||
        !std::isfinite(snap)) {
      closer_.refuse(Status::invalid_parameter, "tolerance must be finite and >= 0, gap_lambda in [0,1]");
      return;
    }
    // the region: a vertex is in it when selected, or when one of its faces is
    // (the boundary vertices left out go into the region fingerprint: 0 when none is)
    auto note = [this](vertex_descriptor v, bool in) {
      if (in) return true;
      const Point& p = get(vpm_, v);
      file_.region_fingerprint += internal::gap_mix(internal::gap_hash_point(
          CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())));
      return false;
    };
    if constexpr (!is_default_parameter<NamedParameters, inp::gap_vertex_selection_t>::value) {
      auto m = get_parameter(np, inp::gap_vertex_selection);
      closer_.start(max_distance, lambda, relative, snap,
                    [m, note](vertex_descriptor v, const TriangleMesh&) { return note(v, bool(get(m, v))); });
    } else if constexpr (!is_default_parameter<NamedParameters, inp::gap_face_selection_t>::value) {
      auto m = get_parameter(np, inp::gap_face_selection);
      closer_.start(max_distance, lambda, relative, snap, [m, note](vertex_descriptor v, const TriangleMesh& g) {
        bool in = false;
        for (halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, g), g))
          if (!is_border(h, g) && get(m, face(h, g))) in = true;
        return note(v, in);
      });
    } else {
      closer_.start(max_distance, lambda, relative, snap, internal::Gap_whole_mesh());
    }
    file_.tolerance = closer_.max_distance();
    // after start(), which refuses a broken halfedge structure: the hash walks every face
    if (closer_.status() == Status::ok && internal::get_or(np, inp::gap_fingerprint_input, false))
      fingerprint_input();
  }

  Gap_closing_sequence(const Gap_closing_sequence&) = delete;
  Gap_closing_sequence& operator=(const Gap_closing_sequence&) = delete;

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
  /// error level after the first `k` contractions (0 for `k == 0`), `k <= size()`.
  double distance_at(std::size_t k) const
  {
    return k == 0 ? 0.0 : file_.contractions[std::min(k, file_.contractions.size()) - 1].distance;
  }
  /// number of recorded contractions whose error level is at most `d`: the
  /// position `forward_to_distance(d)` reaches once they are recorded.
  std::size_t count_within(double d) const
  {
    std::size_t lo = 0, hi = file_.contractions.size();
    while (lo < hi) {
      std::size_t mid = (lo + hi) / 2;
      if (file_.contractions[mid].distance <= d) lo = mid + 1; else hi = mid;
    }
    return lo;
  }

  /// applies up to `k` contractions (replaying recorded ones first); returns how many.
  std::size_t forward(std::size_t k)
  {
    std::size_t n = 0;
    while (n < k && step(max_distance())) ++n;
    return n;
  }
  /// applies contractions while the next pair is not farther than `d` (at most `max_distance()`).
  std::size_t forward_to_distance(double d)
  {
    std::size_t n = 0;
    d = std::min(d, max_distance());
    while (step(d)) ++n;
    return n;
  }
  /// undoes up to `k` contractions; returns how many.
  std::size_t backward(std::size_t k) { return closer_.backward(k); }
  /// undoes contractions until `current_distance() <= d`.
  std::size_t backward_to_distance(double d) { return closer_.backward_to_distance(d); }
  /// moves to position `k` (at most `size()` unless new contractions are found), forward or backward.
  std::size_t go_to(std::size_t k)
  {
    return k < position() ? backward(position() - k) : forward(k - position());
  }
  /// one forward step limited to pairs not farther than `limit`; false when none is left.
  bool step(double limit)
  {
    const bool fresh = closer_.position() == closer_.size();
    if (!closer_.step(limit)) return false;
    if (fresh) {
      const Point& p = *last_;
      file_.contractions.push_back(Gap_contraction_record{
          closer_.current_distance(),
          {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}}});
    }
    return true;
  }

  /// statistics of the mesh now (scans the mesh: O(size)).
  Gap_closing_result result() const { return closer_.result(); }

  /// the recorded contractions, the parameters and the fingerprints (see `Gap_sequence_file`).
  const Gap_sequence_file& record() const { return file_; }

  /// writes every recorded contraction (whatever the position) with the
  /// parameters and the fingerprints. Returns `Status::ok`,
  /// `Status::invalid_parameter` when the sequence was built without
  /// `gap_fingerprint_input(true)` or refused its input, or `Status::io_error`.
  Status save(std::ostream& out) const
  {
    if (status() != Status::ok || !fingerprinted_) return Status::invalid_parameter;
    return file_.write(out) ? Status::ok : Status::io_error;
  }

  /// applies the contractions of `file` (read by `Gap_sequence_file::read()`)
  /// to the input, checking each one against the record. The sequence must be at
  /// its start with nothing recorded, built on the same input (same vertex
  /// positions and faces), with `gap_fingerprint_input(true)`, the same region,
  /// and the tolerance, `gap_lambda` and `gap_snap_distance` of the file
  /// (absolute tolerance). The contractions are found again by the algorithm and
  /// must match the file: same order, distances and positions.
  /// \return `Status::ok` (then `position() == file.contractions.size()`), else
  ///   `Status::invalid_parameter` with `error`, the mesh back at its input.
  Status replay(const Gap_sequence_file& file, std::string& error)
  {
    auto refuse = [&](const std::string& why) {
      backward(position());
      error = why;
      return Status::invalid_parameter;
    };
    if (status() != Status::ok) return refuse("the sequence refused its input");
    if (size() != 0) return refuse("the sequence has contractions already");
    if (!fingerprinted_) return refuse("the sequence was built without gap_fingerprint_input(true)");
    if (file.input_vertices != file_.input_vertices || file.input_faces != file_.input_faces ||
        file.input_fingerprint != file_.input_fingerprint)
      return refuse("the sequence was recorded on another mesh (" + std::to_string(file.input_vertices) +
                    " vertices, " + std::to_string(file.input_faces) + " faces; this one has " +
                    std::to_string(file_.input_vertices) + " and " + std::to_string(file_.input_faces) +
                    (file.input_vertices == file_.input_vertices && file.input_faces == file_.input_faces
                         ? ", but other positions or faces)"
                         : ")"));
    if (file.region_fingerprint != file_.region_fingerprint)
      return refuse("the sequence was recorded with another region selection");
    if (file.tolerance != file_.tolerance || file.lambda != file_.lambda || file.snap != file_.snap)
      return refuse("the sequence was recorded with another tolerance, lambda or snap distance");
    for (std::size_t i = 0; i < file.contractions.size(); ++i) {
      if (!step(max_distance()))
        return refuse("contraction " + std::to_string(i + 1) + " of " +
                      std::to_string(file.contractions.size()) + " cannot be applied to this mesh");
      const Gap_contraction_record& want = file.contractions[i];
      const Gap_contraction_record& got = file_.contractions[i];
      if (want.distance != got.distance || want.position != got.position)
        return refuse("contraction " + std::to_string(i + 1) + " differs from the file (distance " +
                      std::to_string(want.distance) + " recorded, " + std::to_string(got.distance) +
                      " found): another mesh or another version of the algorithm");
    }
    return Status::ok;
  }

private:
  // order-independent hash of the vertex positions and of the faces (each as its
  // three positions in cyclic order, starting at the smallest hash).
  void fingerprint_input()
  {
    auto ph = [&](vertex_descriptor v) {
      const Point& p = get(vpm_, v);
      return internal::gap_hash_point(CGAL::to_double(p.x()), CGAL::to_double(p.y()),
                                      CGAL::to_double(p.z()));
    };
    std::uint64_t h = 0;
    std::size_t nv = 0, nf = 0;
    for (vertex_descriptor v : vertices(tm_)) {
      h += internal::gap_mix(ph(v));
      ++nv;
    }
    std::vector<std::uint64_t> c;
    for (face_descriptor f : faces(tm_)) {
      c.clear();
      for (halfedge_descriptor g : CGAL::halfedges_around_face(halfedge(f, tm_), tm_)) c.push_back(ph(target(g, tm_)));
      std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
      std::uint64_t fh = 0x51ed27;
      for (std::uint64_t x : c) fh = internal::gap_mix(fh ^ x);
      h += fh;
      ++nf;
    }
    file_.input_vertices = nv;
    file_.input_faces = nf;
    file_.input_fingerprint = h;
    fingerprinted_ = true;
  }

  TriangleMesh& tm_;
  VertexPointMap vpm_;
  std::unique_ptr<Point> last_;  // the last position the worker wrote
  internal::Gap_closer<TriangleMesh, Recording_map> closer_;
  Gap_sequence_file file_;
  bool fingerprinted_ = false;
};

} // namespace mrepair

#endif // MREPAIR_GAP_CLOSING_SEQUENCE_H
