// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_GEOMETRIC_STATISTICS_H
#define MREPAIR_GEOMETRIC_STATISTICS_H

#include <mrepair/definitions.h>
#include <mrepair/internal/utility.h>
#include <mrepair/internal/vertex_order.h>

#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/number_utils.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

/// \file geometric_statistics.h
/// Per-element geometric statistics of a triangle mesh (RameshCleaner 3.1),
/// stored in CGAL dynamic property maps so that they follow the mesh through
/// local edits, computed globally in three passes and updated locally.
///
/// Stored values (angles in radians, lengths in mesh units):
/// - halfedge: angle of the corner opposite to it in its face (0 on a border halfedge);
/// - edge: length and dihedral angle = angle between the two face normals, in
///   [0, pi] (0 = flat; 0 on border edges and next to a zero-area face);
/// - face: area, unit normal (zero vector when the area is 0), minimum inner
///   angle (the barycenter is computed on demand: stored, it was 24 of the
///   64 bytes per face, and the statistics are the cleaning's memory peak);
/// - vertex: valence, mean length of the incident edges, maximum dihedral of
///   the incident edges;
/// - global: sum and count of edge lengths (a running sum kept by the local
///   updates), hence the global mean edge length.
///
/// Edge values live in a *halfedge* map (duplicated on both halfedges): on
/// `Polyhedron_3` a dynamic edge map is an `unordered_map` whose hash
/// dereferences the halfedge, which is unsafe once edges were removed.
///
/// Local updates: call `before_local_edit(B)` before an edit and
/// `after_local_edit(A)` after it, where B and A are vertex sets such that
/// every edge that disappears or changes length is incident to B, every new
/// edge or edge of changed length is incident to A, every face that is new or
/// whose vertices moved is incident to A, and every edge incident to A that
/// existed before is incident to B. The named wrappers below choose B and A
/// for the four elementary operations.
/// \code
/// stats.before_edge_collapse(e);
/// vertex_descriptor v = CGAL::Euler::collapse_edge(e, mesh);
/// put(vpm, v, p);
/// stats.after_edge_collapse(v);
/// \endcode

namespace mrepair {

/// \ingroup mrepair_core
/// statistics of one face.
struct Face_statistics
{
  double area = 0;
  std::array<double, 3> normal{{0, 0, 0}};     // unit, or zero when area is 0
  double min_angle = 0;                         // radians
};

/// \ingroup mrepair_core
/// statistics of one halfedge and of its edge.
struct Halfedge_statistics
{
  double opposite_angle = 0; // corner opposite to the halfedge in its face; 0 on border
  double length = 0;         // edge length
  double dihedral = 0;       // edge dihedral angle in [0, pi]
};

/// \ingroup mrepair_core
/// statistics of one vertex.
struct Vertex_statistics
{
  std::size_t valence = 0;
  double mean_edge_length = 0;
  double max_dihedral = 0; // max |dihedral| of the incident edges, radians
};

/// \ingroup mrepair_core
/// geometric statistics of a triangle mesh, kept in dynamic property maps.
/// \tparam TriangleMesh model of `FaceGraph` (triangulated)
/// \tparam VertexPointMap readable map vertex -> point with x(), y(), z()
template <typename TriangleMesh,
          typename VertexPointMap =
              typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::type>
class Geometric_statistics
{
public:
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Vec = std::array<double, 3>;

private:
  using Vmap = typename boost::property_map<TriangleMesh,
                                            CGAL::dynamic_vertex_property_t<Vertex_statistics>>::type;
  using Hmap = typename boost::property_map<
      TriangleMesh, CGAL::dynamic_halfedge_property_t<Halfedge_statistics>>::type;
  using Fmap = typename boost::property_map<TriangleMesh,
                                            CGAL::dynamic_face_property_t<Face_statistics>>::type;
  using Vstamp = typename boost::property_map<TriangleMesh,
                                              CGAL::dynamic_vertex_property_t<std::uint32_t>>::type;
  using Hstamp = typename boost::property_map<TriangleMesh,
                                              CGAL::dynamic_halfedge_property_t<std::uint32_t>>::type;
  using Fstamp = typename boost::property_map<TriangleMesh,
                                              CGAL::dynamic_face_property_t<std::uint32_t>>::type;

  TriangleMesh* tm_;
  VertexPointMap vpm_;
  Vmap vstats_;
  Hmap hstats_;
  Fmap fstats_;
  Vstamp vmark_;
  Hstamp hmark_;
  Fstamp fmark_;
  std::uint32_t gen_ = 0;
  double length_sum_ = 0;
  std::size_t edge_count_ = 0;
  bool parallel_ = true;
  // scratch for local updates
  std::vector<face_descriptor> sf_;
  std::vector<halfedge_descriptor> sh_;
  std::vector<vertex_descriptor> sv_;
  // vertices recomputed by local updates, when a caller asked for them
  std::vector<vertex_descriptor>* journal_ = nullptr;

public:
  /// attaches (uninitialised) statistics to `tm`; call `compute_all()` next.
  explicit Geometric_statistics(TriangleMesh& tm)
    : Geometric_statistics(tm, get(CGAL::vertex_point, tm))
  {}
  Geometric_statistics(TriangleMesh& tm, VertexPointMap vpm)
    : tm_(&tm), vpm_(vpm),
      vstats_(get(CGAL::dynamic_vertex_property_t<Vertex_statistics>(), tm)),
      hstats_(get(CGAL::dynamic_halfedge_property_t<Halfedge_statistics>(), tm)),
      fstats_(get(CGAL::dynamic_face_property_t<Face_statistics>(), tm)),
      vmark_(get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), tm)),
      hmark_(get(CGAL::dynamic_halfedge_property_t<std::uint32_t>(), tm)),
      fmark_(get(CGAL::dynamic_face_property_t<std::uint32_t>(), tm))
  {}

  /// allows (default) or forbids TBB in `compute_all()`; TBB is only used on
  /// `Surface_mesh`, whose dynamic maps are arrays (Polyhedron's are hash maps).
  /// Measured on a generated 1M-face scan: 0.21-0.23 s CPU sequential; on the
  /// shared 2-core machine (load 7-10) TBB gave no wall-time gain (0.64-0.90 s
  /// sequential, 0.78-0.83 s parallel), so the gain on an idle machine is unmeasured.
  void set_parallel(bool p) { parallel_ = p; }

  /// from now on, the local updates append to `*journal` every vertex whose
  /// statistics they recompute (with repeats; possibly vertices removed
  /// later): a vertex whose 1-ring changed in any way is among them, so a
  /// test that reads only a vertex's 1-ring need run again on these alone.
  /// `nullptr` stops the journal; `compute_all()` does not write to it.
  void set_journal(std::vector<vertex_descriptor>* journal) { journal_ = journal; }

  /// computes every statistic: faces (area, normal, corner angles,
  /// min angle), then edges (length, dihedral, which needs both normals), then
  /// vertices. Faces and edges and vertices run in parallel with TBB.
  void compute_all()
  {
    std::vector<face_descriptor> fs(faces(*tm_).begin(), faces(*tm_).end());
    for_each(fs, [this](face_descriptor f) { compute_face(f); });
    std::vector<halfedge_descriptor> es;
    es.reserve(edges(*tm_).size());
    for (edge_descriptor e : edges(*tm_)) es.push_back(halfedge(e, *tm_));
    for_each(es, [this](halfedge_descriptor h) { compute_edge(h); });
    // sequential, deterministic sum
    length_sum_ = 0;
    for (halfedge_descriptor h : es) length_sum_ += get(hstats_, h).length;
    edge_count_ = es.size();
    std::vector<vertex_descriptor> vs(vertices(*tm_).begin(), vertices(*tm_).end());
    if (parallel_) {
      // each vertex writes its own statistics: any order, the fastest
      std::vector<vertex_descriptor> buffer;
      internal::sort_by_halfedge(*tm_, vs, buffer);
    }
    for_each(vs, [this](vertex_descriptor v) { compute_vertex(v); });
    // The marks need no initialisation: Surface_mesh value-initialises new
    // property entries and Polyhedron's hash map inserts V() on first get.
  }

  // ---- accessors ------------------------------------------------------------
  const TriangleMesh& mesh() const { return *tm_; }
  const VertexPointMap& vertex_point_map() const { return vpm_; }
  const Halfedge_statistics& halfedge_stats(halfedge_descriptor h) const { return get(hstats_, h); }
  const Face_statistics& face_stats(face_descriptor f) const { return get(fstats_, f); }
  const Vertex_statistics& vertex_stats(vertex_descriptor v) const { return get(vstats_, v); }
  /// angle (radians) of the corner opposite to `h` in `face(h)`; 0 on border.
  double opposite_angle(halfedge_descriptor h) const { return get(hstats_, h).opposite_angle; }
  double length(halfedge_descriptor h) const { return get(hstats_, h).length; }
  double length(edge_descriptor e) const { return get(hstats_, halfedge(e, *tm_)).length; }
  /// angle between the two face normals (radians, [0, pi]); 0 on border.
  double dihedral(halfedge_descriptor h) const { return get(hstats_, h).dihedral; }
  double dihedral(edge_descriptor e) const { return get(hstats_, halfedge(e, *tm_)).dihedral; }
  double area(face_descriptor f) const { return get(fstats_, f).area; }
  const Vec& normal(face_descriptor f) const { return get(fstats_, f).normal; }
  /// computed from the current positions (not stored)
  Vec barycenter(face_descriptor f) const
  {
    const halfedge_descriptor h = halfedge(f, *tm_);
    const Vec a = point(source(h, *tm_)), b = point(target(h, *tm_)), c = point(target(next(h, *tm_), *tm_));
    return Vec{{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3}};
  }
  double min_angle(face_descriptor f) const { return get(fstats_, f).min_angle; }
  std::size_t valence(vertex_descriptor v) const { return get(vstats_, v).valence; }
  double mean_edge_length(vertex_descriptor v) const { return get(vstats_, v).mean_edge_length; }
  double max_dihedral(vertex_descriptor v) const { return get(vstats_, v).max_dihedral; }
  /// running mean of all edge lengths (0 on a mesh without edges).
  double global_mean_edge_length() const
  {
    return edge_count_ == 0 ? 0. : length_sum_ / static_cast<double>(edge_count_);
  }
  double edge_length_sum() const { return length_sum_; }
  std::size_t edge_count() const { return edge_count_; }
  /// local mean l_e of an edge: mean of its vertices' mean incident lengths.
  double local_mean_edge_length(halfedge_descriptor h) const
  {
    return 0.5 * (mean_edge_length(source(h, *tm_)) + mean_edge_length(target(h, *tm_)));
  }
  Vec point(vertex_descriptor v) const
  {
    const auto& p = get(vpm_, v);
    return Vec{{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
  }

  // ---- local updates --------------------------------------------------------
  /// subtracts from the running sum the lengths of the edges incident to `touched`.
  template <typename VertexRange>
  void before_local_edit(const VertexRange& touched)
  {
    const std::uint32_t in = next_gen(), done = next_gen();
    for (vertex_descriptor v : touched) put(vmark_, v, in);
    for (vertex_descriptor v : touched) {
      if (get(vmark_, v) == done) continue; // listed twice
      if (halfedge(v, *tm_) == GT::null_halfedge()) continue;
      for (halfedge_descriptor h : CGAL::halfedges_around_source(v, *tm_)) {
        if (get(vmark_, target(h, *tm_)) == done) continue; // counted from the other end
        length_sum_ -= get(hstats_, h).length;
        --edge_count_;
      }
      put(vmark_, v, done);
    }
  }

  /// recomputes faces incident to `touched`, the edges of those faces and their
  /// vertices, and adds to the running sum the lengths of edges incident to `touched`.
  template <typename VertexRange>
  void after_local_edit(const VertexRange& touched)
  {
    recompute_around(touched);
    const std::uint32_t in = next_gen(), done = next_gen();
    for (vertex_descriptor v : touched) put(vmark_, v, in);
    for (vertex_descriptor v : touched) {
      if (get(vmark_, v) == done) continue;
      if (halfedge(v, *tm_) != GT::null_halfedge())
        for (halfedge_descriptor h : CGAL::halfedges_around_source(v, *tm_)) {
          if (get(vmark_, target(h, *tm_)) == done) continue;
          length_sum_ += get(hstats_, h).length;
          ++edge_count_;
        }
      put(vmark_, v, done);
    }
  }

  /// recomputes faces incident to `touched`, the edges of those faces and the
  /// vertices of those faces; leaves the running sum alone.
  template <typename VertexRange>
  void recompute_around(const VertexRange& touched)
  {
    const std::uint32_t fgen = next_gen(), vgen = next_gen();
    sf_.clear();
    sh_.clear();
    sv_.clear();
    for (vertex_descriptor v : touched) {
      if (halfedge(v, *tm_) == GT::null_halfedge()) {
        compute_vertex(v);
        if (journal_) journal_->push_back(v);
        continue;
      }
      for (halfedge_descriptor h : CGAL::halfedges_around_target(v, *tm_)) {
        face_descriptor f = face(h, *tm_);
        if (f == GT::null_face() || get(fmark_, f) == fgen) continue;
        put(fmark_, f, fgen);
        sf_.push_back(f);
      }
      if (get(vmark_, v) != vgen) { // a vertex with only border halfedges around
        put(vmark_, v, vgen);
        sv_.push_back(v);
      }
    }
    // a large edit (the boundary smoothing moves 265k vertices of a 10M-face
    // scan) recomputes its elements in parallel: each writes only its own
    for_each(sf_, [&](face_descriptor f) { compute_face(f); });
    for (face_descriptor f : sf_)
      for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, *tm_), *tm_)) {
        if (get(hmark_, h) == fgen) continue;
        put(hmark_, h, fgen);
        put(hmark_, opposite(h, *tm_), fgen);
        sh_.push_back(h);
        vertex_descriptor t = target(h, *tm_);
        if (get(vmark_, t) != vgen) {
          put(vmark_, t, vgen);
          sv_.push_back(t);
        }
      }
    for_each(sh_, [&](halfedge_descriptor h) { compute_edge(h); });
    for_each(sv_, [&](vertex_descriptor v) { compute_vertex(v); });
    if (journal_) journal_->insert(journal_->end(), sv_.begin(), sv_.end());
  }

  /// before moving `v`.
  void before_vertex_move(vertex_descriptor v) { before_local_edit(std::array<vertex_descriptor, 1>{{v}}); }
  /// after moving `v`: recomputes its 1-ring.
  void after_vertex_move(vertex_descriptor v) { after_local_edit(std::array<vertex_descriptor, 1>{{v}}); }
  /// before `CGAL::Euler::flip_edge(halfedge(e))`.
  void before_edge_flip(edge_descriptor e)
  {
    length_sum_ -= length(e);
    --edge_count_;
  }
  /// after the flip (`e` is the same descriptor, now joining the other two vertices).
  void after_edge_flip(edge_descriptor e)
  {
    halfedge_descriptor h = halfedge(e, *tm_);
    recompute_around(std::array<vertex_descriptor, 2>{{source(h, *tm_), target(h, *tm_)}});
    length_sum_ += length(e);
    ++edge_count_;
  }
  /// before `Euler::split_edge` (+ triangulating the two faces) of `e`.
  void before_edge_split(edge_descriptor e)
  {
    length_sum_ -= length(e);
    --edge_count_;
  }
  /// after the split, with `v` the new vertex (its faces triangulated).
  void after_edge_split(vertex_descriptor v) { after_local_edit(std::array<vertex_descriptor, 1>{{v}}); }
  /// before `Euler::collapse_edge(e)`.
  void before_edge_collapse(edge_descriptor e)
  {
    halfedge_descriptor h = halfedge(e, *tm_);
    before_local_edit(std::array<vertex_descriptor, 2>{{source(h, *tm_), target(h, *tm_)}});
  }
  /// after the collapse (and after placing `v`), with `v` the surviving vertex.
  void after_edge_collapse(vertex_descriptor v) { after_local_edit(std::array<vertex_descriptor, 1>{{v}}); }

  // ---- element computations (public so that callers can refresh one element) --
  void compute_face(face_descriptor f)
  {
    halfedge_descriptor h0 = halfedge(f, *tm_), h1 = next(h0, *tm_), h2 = next(h1, *tm_);
    const Vec a = point(source(h0, *tm_)), b = point(target(h0, *tm_)), c = point(target(h1, *tm_));
    const Vec ab = internal::sub(b, a), bc = internal::sub(c, b), ca = internal::sub(a, c);
    Face_statistics fs;
    Vec n = internal::cross(ab, internal::sub(c, a));
    const double nn = internal::norm(n);
    fs.area = 0.5 * nn;
    if (nn > 0 && std::isfinite(nn)) fs.normal = Vec{{n[0] / nn, n[1] / nn, n[2] / nn}};
    // corner angles: at c opposite h0 (a->b), at a opposite h1, at b opposite h2
    // two corners by atan2, the third as pi minus their sum (atan2 dominates the
    // pass); |u x v| is twice the area at every corner, so nn serves all three
    const double aa = std::atan2(nn, -internal::dot(ab, ca)), ab_ = std::atan2(nn, -internal::dot(bc, ab));
    const double ac = (std::max)(0., internal::pi - aa - ab_);
    set_opposite_angle(h0, ac);
    set_opposite_angle(h1, aa);
    set_opposite_angle(h2, ab_);
    fs.min_angle = (std::min)(ac, (std::min)(aa, ab_));
    put(fstats_, f, fs);
    // a non-triangle face would be silently wrong: callers check is_triangle_mesh
  }

  /// computes length and dihedral of `edge(h)` on both halfedges (faces must be current).
  void compute_edge(halfedge_descriptor h)
  {
    halfedge_descriptor o = opposite(h, *tm_);
    const double l = internal::norm(internal::sub(point(target(h, *tm_)), point(source(h, *tm_))));
    double d = 0;
    face_descriptor f1 = face(h, *tm_), f2 = face(o, *tm_);
    if (f1 != GT::null_face() && f2 != GT::null_face()) {
      const Vec& n1 = get(fstats_, f1).normal;
      const Vec& n2 = get(fstats_, f2).normal;
      d = internal::face_normal_angle(n1, n2);  // 0 next to a zero-area face
    }
    for (halfedge_descriptor x : {h, o}) {
      Halfedge_statistics s = get(hstats_, x);
      s.length = l;
      s.dihedral = d;
      if (face(x, *tm_) == GT::null_face()) s.opposite_angle = 0;
      put(hstats_, x, s);
    }
  }

  void compute_vertex(vertex_descriptor v)
  {
    Vertex_statistics s;
    if (halfedge(v, *tm_) != GT::null_halfedge()) {
      double sum = 0;
      for (halfedge_descriptor h : CGAL::halfedges_around_target(v, *tm_)) {
        const Halfedge_statistics& hs = get(hstats_, h);
        ++s.valence;
        sum += hs.length;
        s.max_dihedral = (std::max)(s.max_dihedral, std::abs(hs.dihedral));
      }
      s.mean_edge_length = s.valence ? sum / static_cast<double>(s.valence) : 0.;
    }
    put(vstats_, v, s);
  }

private:
  std::uint32_t next_gen()
  {
    if (++gen_ == 0) { // wrapped: reset every mark
      for (vertex_descriptor v : vertices(*tm_)) put(vmark_, v, 0u);
      for (face_descriptor f : faces(*tm_)) put(fmark_, f, 0u);
      for (halfedge_descriptor h : halfedges(*tm_)) put(hmark_, h, 0u);
      gen_ = 1;
    }
    return gen_;
  }

  void set_opposite_angle(halfedge_descriptor h, double a)
  {
    Halfedge_statistics s = get(hstats_, h);
    s.opposite_angle = a;
    put(hstats_, h, s);
  }

  template <typename Range, typename F>
  void for_each(const Range& r, const F& f)
  {
    internal::parallel_for_mesh_elements<TriangleMesh>(
        r.size(), [&](std::size_t i) { f(r[i]); }, parallel_);
  }
};

} // namespace mrepair

#endif // MREPAIR_GEOMETRIC_STATISTICS_H
