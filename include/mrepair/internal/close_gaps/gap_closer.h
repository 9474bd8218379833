// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_CLOSE_GAPS_GAP_CLOSER_H
#define MREPAIR_INTERNAL_CLOSE_GAPS_GAP_CLOSER_H

#include <mrepair/gap_closing_result.h>
#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/close_gaps/boundary_grid.h>
#include <mrepair/internal/utility.h>
#include <mrepair/status.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#endif

namespace mrepair {

namespace internal {

/// the region of `Gap_closer::start` that is the whole mesh.
struct Gap_whole_mesh {};

// calls f(h) once per border cycle of `m`, with its first halfedge in
// halfedge order (`border`: all border halfedges, from border_halfedges).
// A walk that does not come back to its start within the halfedge count (a
// broken next(): issue 36's pentagon) stops there; returns false then.
template <class Mesh, class F>
bool for_each_border_cycle(const Mesh& m,
                           const std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor>& border,
                           const F& f)
{
  using halfedge_descriptor = typename boost::graph_traits<Mesh>::halfedge_descriptor;
  const std::size_t limit = walk_limit(m);
  bool closed = true;
  auto walk = [&](halfedge_descriptor h, auto&& visited, auto&& mark) {
    if (visited(h)) return;
    halfedge_descriptor g = h;
    Walk_bound bound(limit);
    do {
      mark(g);
      g = next(g, m);
    } while (g != h && !visited(g) && bound.step());
    if (g != h) {  // came back elsewhere, or never: not a cycle
      closed = false;
      return;
    }
    f(h);
  };
  if constexpr (Is_surface_mesh<Mesh>::value) {
    std::vector<char> seen(m.num_halfedges(), 0);  // a byte per halfedge, not a property map
    for (halfedge_descriptor h : border)
      walk(h, [&](halfedge_descriptor g) { return seen[std::size_t(g)] != 0; },
           [&](halfedge_descriptor g) { seen[std::size_t(g)] = 1; });
  } else {
    auto seen = get(CGAL::dynamic_halfedge_property_t<bool>(), m);
    for (halfedge_descriptor h : halfedges(m)) put(seen, h, false);
    for (halfedge_descriptor h : border)
      walk(h, [&](halfedge_descriptor g) { return get(seen, g); }, [&](halfedge_descriptor g) { put(seen, g, true); });
  }
  return closed;
}

// border halfedge count and border cycle count of a halfedge graph.
template <class Mesh>
std::pair<std::size_t, std::size_t> count_boundary(const Mesh& m)
{
  std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor> border;
  border_halfedges(m, border);
  std::size_t loops = 0;
  for_each_border_cycle(m, border, [&](typename boost::graph_traits<Mesh>::halfedge_descriptor) { ++loops; });
  return {border.size(), loops};
}

// The worker of `Gap_closing_sequence` (see gap_closing_sequence.h for the
// algorithm and what "exactly" means for backward steps): pairs, queue,
// contractions recorded as face edits, undo and redo.
template <class TriangleMesh, class VertexPointMap>
class Gap_closer
{
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Point = typename boost::property_traits<VertexPointMap>::value_type;
  using Id = std::uint32_t;
  using Tri = std::array<Id, 3>;
  using P3 = Vec3;
  using Id_map = typename boost::property_map<TriangleMesh,
                                              CGAL::dynamic_vertex_property_t<std::uint32_t>>::type;
  static constexpr Id npos = Id(-1);

  enum Kind : unsigned char { none = 0, vv = 1, ve = 2 };
  enum Outcome { done, flip, degenerate, non_manifold, failed, displaced, stale };

  struct Move
  {
    Id v;
    Point from, to;
  };
  struct Op
  {
    Kind kind;
    double level;            // running maximum of the pair distances
    Id removed_vertex;       // npos for vertex-edge
    Point removed_position;  // its position (undo re-creates it there)
    std::vector<Tri> removed, added;
    std::vector<Move> moves;
  };
  struct Pair
  {
    std::uint64_t edge = 0;
    Id target = npos;  // vertex-vertex: the other vertex
    Kind kind = none;
    double dist = 0;
  };
  struct Entry
  {
    double d;
    Id v;
    std::uint32_t ver;
    bool operator<(const Entry& o) const { return d > o.d || (d == o.d && v > o.v); }
  };

public:
  Gap_closer(TriangleMesh& tm, const VertexPointMap& vpm)
    : tm_(tm), vpm_(vpm), idmap_(get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), tm))
  {}

  /// prefers the placements that leave the input position of every vertex
  /// a contraction moves or removes within 1e-6 x the bounding-box diagonal
  /// of the new faces (the reference tolerance of compare_to_reference.h):
  /// a vertex-edge contraction that bends the edge to its vertex, a
  /// vertex-vertex one that keeps the end whose partner's input position
  /// stays on the merged surface. Set before start().
  void keep_input_points(bool keep) { keep_points_ = keep; }

  /// refuses the input: every step is a no-op.
  void refuse(Status status, const std::string& message)
  {
    status_ = status;
    message_ = message;
  }

  /// checks the mesh and prepares the pairs for closing gaps up to
  /// `max_distance` (the parameters are checked by the caller). `region` is
  /// `Gap_whole_mesh` or tells whether a vertex (of the input boundary) is in
  /// the region: `region(v, tm)`.
  template <class Region>
  void start(double max_distance, double lambda, bool relative, double snap, const Region& region)
  {
    TriangleMesh& tm = tm_;
    lambda_ = lambda;
    if (faces(tm).first == faces(tm).second) {
      refuse(Status::empty_input, "the mesh has no faces");
      return;
    }
    // bounding box and finiteness of every vertex (a NaN anywhere is bad input)
    std::array<double, 6> box;
    if (!bounding_box(box)) {
      refuse(Status::non_finite_input, "a vertex coordinate is NaN or infinite");
      return;
    }
    const double* lo = box.data();
    const double* hi = box.data() + 3;
    // a valid mesh has faces of degree >= 3, so it is a triangle mesh exactly
    // when its inner halfedges are 3 per face.
    std::vector<halfedge_descriptor> border;
    border_halfedges(tm, border);
    const std::size_t nh = halfedge_count(tm);
    // the local rules that make every walk end (bounded_walks.h), in
    // O(halfedges) in every build; CGAL::is_valid_polygon_mesh is slow
    const std::string broken = halfedge_structure_defect(tm);
    if (!broken.empty()) {
      refuse(Status::invalid_mesh, "the input's halfedge structure is broken: " + broken);
      return;
    }
    // face_count: BGL num_faces() counts the removed faces a Surface_mesh keeps
    // after stepping back, which refused every closing of a stepped mesh
    if (nh - border.size() != 3 * face_count(tm)) {
      refuse(Status::invalid_mesh, "the input is not a valid triangle mesh");
      return;
    }
    double diag = distance(load_vec3(hi), load_vec3(lo));
    if (!(diag <= max_bbox_diagonal)) {
      refuse(Status::non_finite_input, coordinates_too_large_message);
      return;
    }
    max_dist_ = relative ? max_distance * diag : max_distance;
    keep_tolerance_ = 1e-6 * diag;
    snap_ = snap < 0 ? max_dist_ : snap;

    // boundary vertices and edges get stable ids
    std::vector<std::uint64_t> edges;
    edges.reserve(border.size());
    double total = 0;
    for (halfedge_descriptor h : border) {
      Id a = id_of(source(h, tm)), b = id_of(target(h, tm));
      edges.push_back(key(a, b));
      total += distance(pos(a), pos(b));
    }
    const std::size_t nb = vd_.size();
    input_boundary_ = nb;
    std::size_t pinched = 0;
    if (!boundary_stats(boundary_edges_before_, boundary_loops_before_, pinched)) {
      refuse(Status::invalid_mesh, walk_bound_message("close_gaps: the border walk of the input"));
      return;
    }
    max_ops_ = 4 * walk_limit(tm);

    // region
    selected_.assign(vd_.size(), 1);
    select_region(region);

    double mean = edges.empty() ? 0 : total / edges.size();
    double cell = std::max({max_dist_, mean, diag * 1e-6, 1e-300});
    grid_.init({lo[0], lo[1], lo[2]}, cell, 2 * edges.size());
    for (std::uint64_t e : edges) grid_.insert(e, pos(ka(e)), pos(kb(e)));
    vgrid_.init({lo[0], lo[1], lo[2]}, cell, nb);
    for (Id v = 0; v < nb; ++v) vgrid_.insert(v, pos(v), pos(v));
    initial_pairs(nb);
  }

  /// `Status::ok`, or why the input was refused (then every step is a no-op).
  Status status() const { return status_; }
  /// the absolute distance limit of the sequence.
  double max_distance() const { return max_dist_; }
  /// number of contractions recorded (the farthest mesh reached).
  std::size_t size() const { return ops_.size(); }
  /// number of contractions applied to the mesh now.
  std::size_t position() const { return pos_; }
  /// error level of the mesh now: running maximum of the pair distances applied (0 at the input).
  double current_distance() const { return pos_ == 0 ? 0.0 : ops_[pos_ - 1].level; }

  /// applies up to `k` contractions (replaying recorded ones first); returns how many.
  std::size_t forward(std::size_t k)
  {
    std::size_t n = 0;
    while (n < k && step(max_dist_)) ++n;
    return n;
  }
  /// applies contractions while the next pair is not farther than `d` (at most `max_distance()`).
  std::size_t forward_to_distance(double d)
  {
    std::size_t n = 0;
    d = std::min(d, max_dist_);
    while (step(d)) ++n;
    return n;
  }
  /// undoes up to `k` contractions; returns how many.
  std::size_t backward(std::size_t k)
  {
    std::size_t n = 0;
    while (n < k && pos_ > 0 && undo()) ++n;
    return n;
  }
  /// undoes contractions until `current_distance() <= d`.
  std::size_t backward_to_distance(double d)
  {
    std::size_t n = 0;
    while (pos_ > 0 && ops_[pos_ - 1].level > d && undo()) ++n;
    return n;
  }

  /// one forward step limited to pairs not farther than `limit`; false when none is left.
  bool step(double limit)
  {
    if (status_ != Status::ok || broken_) return false;
    if (pos_ < ops_.size()) {
      if (ops_[pos_].level > limit) return false;
      return redo();
    }
    // each entry is popped once, and only a stale pair is pushed again, whose
    // recomputed pair is not stale (same mesh): at most 2x the queue in pops;
    // the bound is twice that
    Walk_bound pops(4 * queue_.size() + 4);
    while (!queue_.empty()) {
      if (!pops.step()) return stop_at_bound("close_gaps: the pair queue");
      Entry top = queue_.top();
      if (top.ver != ver_[top.v] || pair_[top.v].kind == none || !alive_[top.v]) {
        queue_.pop();
        continue;
      }
      if (top.d > limit) return false;
      // a vertex-vertex contraction removes an input boundary vertex, a
      // vertex-edge one adds a face: a closing never comes near 4x the
      // input's halfedges of them
      if (ops_.size() >= max_ops_) {
        broken_ = true;
        message_ = "close_gaps: stopped after " + std::to_string(ops_.size()) +
                   " contractions (4x the input's halfedges): they do not converge;" +
                   " the mesh is valid at the stop";
        return false;
      }
      queue_.pop();
      Outcome o = contract(top.v, top.d);
      if (broken_) return false;  // a face walk hit its bound (remove_face_keep_vertices)
      if (o != done && o != stale) rejected_[top.v] = 1;
      switch (o) {
        case done: return true;
        case flip: ++rejected_flip_; break;
        case degenerate: ++rejected_degenerate_; break;
        case non_manifold: ++rejected_non_manifold_; break;
        case failed: ++rejected_failed_; break;
        case displaced: ++rejected_displacement_; break;
        case stale: compute_pair(top.v); break;
      }
    }
    return false;
  }

  /// statistics of the mesh now (scans the mesh: O(size)).
  Gap_closing_result result() const
  {
    Gap_closing_result r;
    r.status = broken_ ? Status::invalid_mesh : status_;
    r.message = message_;
    r.tolerance = max_dist_;
    if (status_ != Status::ok) return r;
    r.operations = pos_;
    for (std::size_t i = 0; i < pos_; ++i) (ops_[i].kind == vv ? r.vertex_vertex : r.vertex_edge)++;
    r.alternative_placements = alternative_placements_;
    r.rejected_flip = rejected_flip_;
    r.rejected_degenerate = rejected_degenerate_;
    r.rejected_non_manifold = rejected_non_manifold_;
    r.rejected_failed = rejected_failed_;
    r.rejected_displacement = rejected_displacement_;
    r.boundary_edges_before = boundary_edges_before_;
    r.boundary_loops_before = boundary_loops_before_;
    if (!boundary_stats(r.boundary_edges_after, r.boundary_loops_after, r.pinched_vertices)) {
      r.status = Status::invalid_mesh;
      r.message = walk_bound_message("close_gaps: the border walk of the result");
    }
    for (Id i = 0; i < orig_.size(); ++i)
      if (has_orig_[i] && alive_[i])
        r.max_displacement = std::max(r.max_displacement, distance(pos(i), p3(orig_[i])));
    r.final_distance = current_distance();
    return r;
  }

private:
  // ---- ids, positions ------------------------------------------------------
  static std::uint64_t key(Id a, Id b) { return (std::uint64_t(a) << 32) | b; }
  static Id ka(std::uint64_t k) { return Id(k >> 32); }
  static Id kb(std::uint64_t k) { return Id(k & 0xffffffffu); }
  static double sqdist(const P3& a, const P3& b) { return squared_norm(sub(a, b)); }
  static P3 p3(const Point& p) { return to_vec3(p); }
  P3 pos(Id i) const { return p3(get(vpm_, vd_[i])); }

  // Surface_mesh: indices are dense, so the O(n) scans below run over index
  // ranges in parallel; other graphs are scanned through their iterators.
  static constexpr bool indexed = Is_surface_mesh<TriangleMesh>::value;

  // bounding box of all vertices as {lo, hi}; false when a coordinate is not finite.
  bool bounding_box(std::array<double, 6>& box) const
  {
    const double inf = std::numeric_limits<double>::infinity();
    std::array<double, 6> init{{inf, inf, inf, -inf, -inf, -inf}};
    auto add = [&](std::array<double, 6>& b, vertex_descriptor v) {
      const Point& p = get(vpm_, v);
      const double c[3] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
      for (int d = 0; d < 3; ++d) {
        if (!std::isfinite(c[d])) return false;
        b[d] = std::min(b[d], c[d]);
        b[d + 3] = std::max(b[d + 3], c[d]);
      }
      return true;
    };
    auto join = [](const std::array<double, 6>& a, const std::array<double, 6>& b) {
      std::array<double, 6> r;
      for (int d = 0; d < 3; ++d) {
        r[d] = std::min(a[d], b[d]);
        r[d + 3] = std::max(a[d + 3], b[d + 3]);
      }
      return r;
    };
    bool finite = true;
    if constexpr (indexed) {
#ifdef CGAL_LINKED_WITH_TBB
      std::atomic<bool> ok{true};
      const bool garbage = tm_.has_garbage();
      box = tbb::parallel_reduce(
          tbb::blocked_range<std::size_t>(0, tm_.num_vertices(), 1 << 15),
          init,
          [&](const tbb::blocked_range<std::size_t>& r, std::array<double, 6> b) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
              vertex_descriptor v(static_cast<typename vertex_descriptor::size_type>(i));
              if (!(garbage && tm_.is_removed(v)) && !add(b, v)) ok = false;
            }
            return b;
          },
          join);
      finite = ok;
      return finite;
#endif
    }
    box = init;
    for (vertex_descriptor v : vertices(tm_))
      if (!add(box, v)) return false;
    return finite;
  }

  // idmap_ is not initialised: 0 means "no id yet", which is also what an
  // unset entry of a dynamic map reads on both Surface_mesh and Polyhedron_3.
  Id id_of(vertex_descriptor v)
  {
    std::uint32_t s = get(idmap_, v);
    if (s != 0) return s - 1;
    Id i = Id(vd_.size());
    vd_.push_back(v);
    put(idmap_, v, i + 1);
    alive_.push_back(1);
    selected_.push_back(0);  // vertices met later were not on the input boundary
    pair_.emplace_back();
    ver_.push_back(0);
    has_orig_.push_back(0);
    orig_.emplace_back();
    rejected_.push_back(0);
    head_.push_back(npos);
    next_.push_back(npos);
    prev_.push_back(npos);
    owner_.push_back(npos);
    return i;
  }

  template <class Region>
  void select_region(const Region& region)
  {
    if constexpr (!std::is_same<Region, Gap_whole_mesh>::value)
      for (Id i = 0; i < vd_.size(); ++i) selected_[i] = region(vd_[i], tm_) ? 1 : 0;
  }

  // halfedge from u to v, generic (Polyhedron's edge(u,v) has no orientation).
  std::pair<halfedge_descriptor, bool> find_halfedge(Id u, Id v) const
  {
    halfedge_descriptor hv = halfedge(vd_[v], tm_);
    if (hv == GT::null_halfedge()) return {hv, false};
    for (halfedge_descriptor h : CGAL::halfedges_around_target(hv, tm_))
      if (source(h, tm_) == vd_[u]) return {h, true};
    return {hv, false};
  }
  bool is_border_edge(Id a, Id b) const
  {
    auto h = find_halfedge(a, b);
    return h.second && is_border(h.first, tm_);
  }
  bool is_boundary_vertex(Id i) const
  {
    halfedge_descriptor hv = halfedge(vd_[i], tm_);
    if (hv == GT::null_halfedge()) return false;
    for (halfedge_descriptor h : CGAL::halfedges_around_target(hv, tm_))
      if (is_border(h, tm_)) return true;
    return false;
  }
  // border halfedges, border cycles and pinched vertices. Every border
  // halfedge joins two vertices of the input boundary (contractions only glue
  // or split boundary edges), so a scan of those vertices (the first ids) suffices.
  // False when a cycle walk hit its bound (a broken next()).
  bool boundary_stats(std::size_t& edges, std::size_t& loops, std::size_t& pinched) const
  {
    edges = loops = pinched = 0;
    std::vector<halfedge_descriptor> border;
    const std::size_t n = input_boundary_ ? input_boundary_ : vd_.size();
    for (Id i = 0; i < n; ++i) {
      if (!alive_[i]) continue;
      halfedge_descriptor hv = halfedge(vd_[i], tm_);
      if (hv == GT::null_halfedge()) continue;
      std::size_t k = 0;
      for (halfedge_descriptor h : CGAL::halfedges_around_target(hv, tm_))
        if (is_border(h, tm_)) {
          border.push_back(h);
          ++k;
        }
      if (k > 1) ++pinched;
    }
    edges = border.size();
    // loops: walk each cycle once, marking its halfedges in a sorted key array
    auto hkey = [&](halfedge_descriptor h) {
      return key(get(idmap_, source(h, tm_)), get(idmap_, target(h, tm_)));
    };
    std::vector<std::uint64_t> keys(border.size());
    for (std::size_t i = 0; i < border.size(); ++i) keys[i] = hkey(border[i]);
    std::sort(keys.begin(), keys.end());
    // the last slot takes a halfedge whose key is not listed (a broken next()
    // leaving the border): written, never read
    std::vector<char> seen(keys.size() + 1, 0);
    auto mark = [&](halfedge_descriptor h) -> char& {
      const std::uint64_t k = hkey(h);
      const auto i = static_cast<std::size_t>(std::lower_bound(keys.begin(), keys.end(), k) - keys.begin());
      return seen[i < keys.size() && keys[i] == k ? i : keys.size()];
    };
    const std::size_t limit = walk_limit(tm_);
    for (halfedge_descriptor h : border) {
      if (mark(h)) continue;
      ++loops;
      halfedge_descriptor g = h;
      Walk_bound bound(limit);
      do {
        mark(g) = 1;
        g = next(g, tm_);
      } while (g != h && bound.step());
      if (bound.exceeded()) return false;
    }
    return true;
  }

  // ---- pairing -------------------------------------------------------------
  // the nearest boundary edge of `u` within max distance (kind none if there is
  // none). Read-only: the initial pairing runs it in parallel.
  Pair find_pair(Id u, const P3& p) const
  {
    Pair pr;
    double best = std::numeric_limits<double>::max(), best_t = 0;
    std::uint64_t best_e = 0;
    // distances on the registered copies; only a candidate that beats the best
    // is checked against the mesh (alive, same geometry, still a border edge)
    grid_.query_nearest_first(
        p, max_dist_,
        [&](const Segment_grid::Item& it) {
          const std::uint64_t e = it.key;
          Id a = ka(e), b = kb(e);
          if (a == u || b == u) return;
          double t = 0, d = seg_dist(p, it.a, it.b, t);
          if (d > max_dist_ || !(d < best || (d == best && e < best_e))) return;
          if (!alive_[a] || !alive_[b] || !selected_[a] || !selected_[b]) return;
          if (pos(a) != it.a || pos(b) != it.b) return;  // stale copy of a moved edge
          if (!is_border_edge(a, b)) return;              // stale grid entry
          best = d;
          best_t = t;
          best_e = e;
        },
        [&] { return std::min(best, max_dist_); });
    if (best > max_dist_) return pr;
    Id a = ka(best_e), b = kb(best_e);
    P3 pa = pos(a), pb = pos(b);
    double len = distance(pa, pb);
    double eps = std::min(snap_, len / 3);
    pr.edge = best_e;
    if (best_t * len <= eps) {
      pr.kind = vv;
      pr.target = a;
    } else if ((1 - best_t) * len <= eps) {
      pr.kind = vv;
      pr.target = b;
    } else {
      pr.kind = ve;
      pr.target = npos;
    }
    // the error is the distance to the edge, also when the projection snaps to an end
    pr.dist = best;
    return pr;
  }

  // every vertex paired with an edge leaving `a` is in the list head_[a]
  // (intrusive, doubly linked through next_/prev_), so that a changed edge finds
  // its vertices without a map.
  void link(Id u, Id a)
  {
    owner_[u] = a;
    prev_[u] = npos;
    next_[u] = head_[a];
    if (head_[a] != npos) prev_[head_[a]] = u;
    head_[a] = u;
  }
  void unlink(Id u)
  {
    const Id a = owner_[u];
    if (a == npos) return;
    if (prev_[u] != npos) next_[prev_[u]] = next_[u];
    else head_[a] = next_[u];
    if (next_[u] != npos) prev_[next_[u]] = prev_[u];
    owner_[u] = npos;
  }

  // finds the nearest boundary edge of `u` within max distance and queues it.
  void compute_pair(Id u)
  {
    ++ver_[u];
    rejected_[u] = 0;
    unlink(u);
    Pair& pr = pair_[u];
    pr.kind = none;
    if (!alive_[u] || !selected_[u] || !is_boundary_vertex(u)) return;
    pr = find_pair(u, pos(u));
    if (pr.kind == none) return;
    link(u, ka(pr.edge));
    queue_.push(Entry{pr.dist, u, ver_[u]});
  }

  // pairs of all input boundary vertices: the queries in parallel (read-only),
  // then lists and queue in id order.
  void initial_pairs(std::size_t nb)
  {
    auto run = [&](std::size_t i) {
      Id u = Id(i);
      ver_[u] = 1;
      if (selected_[u]) pair_[u] = find_pair(u, pos(u));
    };
    if (nb >= 2048)
      parallel_for_index(nb, 256, run);
    else
      for (std::size_t i = 0; i < nb; ++i) run(i);
    std::vector<Entry> entries;
    entries.reserve(nb);
    for (Id u = 0; u < nb; ++u)
      if (pair_[u].kind != none) {
        link(u, ka(pair_[u].edge));
        entries.push_back(Entry{pair_[u].dist, u, ver_[u]});
      }
    queue_ = std::priority_queue<Entry>(std::less<Entry>(), std::move(entries));
  }

  static double seg_dist(const P3& p, const P3& a, const P3& b, double& t)
  {
    const P3 ab = sub(b, a);
    const double l2 = squared_norm(ab);
    t = l2 > 0 ? dot(sub(p, a), ab) / l2 : 0;
    t = std::min(1.0, std::max(0.0, t));
    return distance(p, add(a, mul(ab, t)));
  }

  // ---- local checks --------------------------------------------------------
  // rotates t so that it starts with c; false when c is not in t.
  static bool rotate_to(const Tri& t, Id c, Id& a, Id& b)
  {
    for (int i = 0; i < 3; ++i)
      if (t[i] == c) {
        a = t[(i + 1) % 3];
        b = t[(i + 2) % 3];
        return true;
      }
    return false;
  }
  static bool same_face(const Tri& x, const Tri& y)
  {
    Id a, b;
    return rotate_to(y, x[0], a, b) && a == x[1] && b == x[2];
  }

  // faces around c as (c, a, b) triples, current mesh.
  void star(Id c, std::vector<Tri>& out)
  {
    out.clear();
    halfedge_descriptor hv = halfedge(vd_[c], tm_);
    if (hv == GT::null_halfedge()) return;
    for (halfedge_descriptor h : CGAL::halfedges_around_target(hv, tm_))
      if (!is_border(h, tm_)) out.push_back(Tri{c, id_of(target(next(h, tm_), tm_)), id_of(source(h, tm_))});
  }

  // the faces around c after removing `rem` and adding `add` must form either
  // one closed fan (of at least 3 faces) or open fans only, each directed
  // halfedge used once: what a halfedge graph can represent.
  bool star_ok(Id c, const std::vector<Tri>& rem, const std::vector<Tri>& add)
  {
    link_.clear();
    star(c, tmp_);
    for (const Tri& t : tmp_) {
      bool removed = false;
      for (const Tri& r : rem) removed = removed || same_face(t, r);
      if (!removed) link_.push_back({t[1], t[2]});
    }
    for (const Tri& t : add) {
      Id a, b;
      if (rotate_to(t, c, a, b)) link_.push_back({a, b});
    }
    const std::size_t n = link_.size();
    if (n == 0) return false;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (link_[i].first == link_[j].first || link_[i].second == link_[j].second) return false;
    auto succ = [&](Id x) -> std::size_t {
      for (std::size_t i = 0; i < n; ++i)
        if (link_[i].first == x) return i;
      return n;
    };
    std::size_t covered = 0, starts = 0;
    for (std::size_t i = 0; i < n; ++i) {
      bool has_pred = false;
      for (std::size_t j = 0; j < n; ++j) has_pred = has_pred || link_[j].second == link_[i].first;
      if (has_pred) continue;
      ++starts;
      for (std::size_t k = i; k < n; k = succ(link_[k].second)) {
        ++covered;
        if (covered > n) return false;
      }
    }
    if (starts > 0) return covered == n;  // open fans only
    // closed: a single cycle through every face, not a back-to-back pair
    std::size_t len = 0, k = 0;
    do {
      ++len;
      k = succ(link_[k].second);
    } while (k != 0 && k < n && len <= n);
    return k == 0 && len == n && n >= 3;
  }

  static P3 normal(const P3& a, const P3& b, const P3& c) { return cross(sub(b, a), sub(c, a)); }

  // geometry of one face before (ref, old positions) and after (t, new positions).
  Outcome check_face(const Tri& t, const Tri& ref, Id moved, const P3& to) const
  {
    auto np = [&](Id i) { return i == moved ? to : pos(i); };
    P3 a = np(t[0]), b = np(t[1]), c = np(t[2]);
    P3 n1 = normal(a, b, c);
    double l2 = std::max({sqdist(a, b), sqdist(b, c), sqdist(c, a)});
    double area2 = dot(n1, n1);
    if (!(area2 > 1e-24 * l2 * l2)) return degenerate;
    P3 n0 = normal(pos(ref[0]), pos(ref[1]), pos(ref[2]));
    double a0 = dot(n0, n0);
    if (a0 > 1e-24 * l2 * l2 && dot(n0, n1) <= 0) return flip;
    return done;
  }

  // ---- the contraction -----------------------------------------------------
  // One contraction of the pair of `u`, in the order of the paper's Algorithm 1:
  //   plan      the faces it removes and adds, the vertex that moves, and
  //             where it may go (plan_vertex_vertex, plan_vertex_edge)
  //   check     every vertex whose star changes keeps a fan (stars_stay_manifold)
  //   place     the first position that flips, degenerates and displaces
  //             nothing (choose_placement)
  //   apply     the edit, recorded for undo and redo (apply_contraction)
  //   re-pair   new pairs where the border changed (update_pairs)
  // The stages keep this order: their walks number the vertices they meet
  // (id_of), and ids break ties in the queue and order the re-pairing.

  // what the plan stage decides; the later stages read it
  struct Contraction
  {
    Op op;                      // removed and added faces, the removed vertex (recorded when applied)
    std::vector<Tri> ref;       // per added face: the face whose side it keeps
    Id moved = npos;            // the vertex that takes the new position
    std::array<P3, 3> place{};  // candidate positions: the λ point, then either end
  };

  Outcome contract(Id u, double dist)
  {
    Contraction c;
    Outcome o = plan_contraction(u, c);
    if (o != done) return o;
    collect_affected(c.op);
    if (!stars_stay_manifold(c)) return non_manifold;
    P3 to{};
    o = choose_placement(c, to);
    if (o != done) return o;
    if (!apply_contraction(c, to, dist)) return failed;
    update_pairs(c.moved);
    return done;
  }

  // plan: the pair is stale when its edge or vertex left the border since it
  // was queued (the caller pairs the vertex again); non_manifold when the
  // faces cannot be rewired at all.
  Outcome plan_contraction(Id u, Contraction& c)
  {
    const Pair pr = pair_[u];
    const Id a = ka(pr.edge), b = kb(pr.edge);
    if (!alive_[a] || !alive_[b] || !is_border_edge(a, b) || !is_boundary_vertex(u)) return stale;
    c.op.kind = pr.kind;
    c.op.removed_vertex = npos;
    if (pr.kind == vv) return plan_vertex_vertex(u, pr.target, c);
    return plan_vertex_edge(u, a, b, c);
  }

  // vertex-vertex: u's faces go to w (those on the edge u-w, if any, vanish
  // with it), u is removed and w moves. Candidates: the λ point, u, w.
  Outcome plan_vertex_vertex(Id u, Id w, Contraction& c)
  {
    if (!alive_[w] || w == u) return stale;
    const bool adjacent = find_halfedge(u, w).second || find_halfedge(w, u).second;
    star(u, tmp2_);
    for (const Tri& r : tmp2_) {
      c.op.removed.push_back(r);
      if (adjacent && (r[1] == w || r[2] == w)) continue;  // collapsed with the edge u-w
      c.op.added.push_back(Tri{w, r[1], r[2]});
      c.ref.push_back(r);
    }
    if (c.op.added.empty()) return non_manifold;
    c.op.removed_vertex = u;
    c.op.removed_position = get(vpm_, vd_[u]);
    c.moved = w;
    const P3 pu = pos(u), pw = pos(w);
    P3 to;
    for (int d = 0; d < 3; ++d) to[d] = lambda_ * pu[d] + (1 - lambda_) * pw[d];
    c.place = {{to, pu, pw}};
    return done;
  }

  // vertex-edge: the face on edge a-b splits in two at u, which moves.
  // Candidates: the λ point, u in place, u on its projection onto a-b.
  Outcome plan_vertex_edge(Id u, Id a, Id b, Contraction& c)
  {
    const halfedge_descriptor o = opposite(find_halfedge(a, b).first, tm_);
    const Id opp = id_of(target(next(o, tm_), tm_));
    if (opp == u) return non_manifold;
    c.op.removed.push_back(Tri{b, a, opp});
    c.op.added.push_back(Tri{b, u, opp});
    c.op.added.push_back(Tri{u, a, opp});
    c.ref.push_back(c.op.removed[0]);
    c.ref.push_back(c.op.removed[0]);
    c.moved = u;
    const P3 pu = pos(u), pa = pos(a), pb = pos(b);
    double t = 0;
    seg_dist(pu, pa, pb, t);
    P3 projection, to;
    for (int d = 0; d < 3; ++d) projection[d] = pa[d] + t * (pb[d] - pa[d]);
    for (int d = 0; d < 3; ++d) to[d] = lambda_ * pu[d] + (1 - lambda_) * projection[d];
    c.place = {{to, pu, projection}};
    return done;
  }

  // every vertex of the removed and added faces, once, sorted: whose star
  // changes, and near whom the border changes
  void collect_affected(const Op& op)
  {
    affected_.clear();
    for (const Tri& t : op.removed)
      for (Id i : t) affected_.push_back(i);
    for (const Tri& t : op.added)
      for (Id i : t) affected_.push_back(i);
    std::sort(affected_.begin(), affected_.end());
    affected_.erase(std::unique(affected_.begin(), affected_.end()), affected_.end());
  }

  // check: the edit must leave each affected vertex a star a halfedge graph
  // can hold (star_ok). Vertex-vertex: a neighbour of u not adjacent to w
  // only sees u renamed to w in its faces (w new in its link), so its fan
  // keeps its shape: skip its check.
  bool stars_stay_manifold(const Contraction& c)
  {
    const bool vertex_vertex = c.op.kind == vv;
    nbr_.clear();
    if (vertex_vertex) {
      halfedge_descriptor hw = halfedge(vd_[c.moved], tm_);
      if (hw != GT::null_halfedge())
        for (halfedge_descriptor h : CGAL::halfedges_around_target(hw, tm_)) nbr_.push_back(id_of(source(h, tm_)));
      std::sort(nbr_.begin(), nbr_.end());
    }
    for (Id x : affected_) {
      if (x == c.op.removed_vertex) continue;
      if (vertex_vertex && x != c.moved && !std::binary_search(nbr_.begin(), nbr_.end(), x)) continue;
      if (!star_ok(x, c.op.removed, c.op.added)) return false;
    }
    return true;
  }

  // place: the merged position λv + (1-λ)v' first, then either end (λ = 1,
  // λ = 0): a sliver on one side of a seam flips under the midpoint but not
  // when only the other side moves. The first candidate that passes wins;
  // when none does, the λ point's failure is the outcome.
  Outcome choose_placement(const Contraction& c, P3& to)
  {
    star(c.moved, tmp_);
    if (keep_points_) {
      // the candidate that leaves the input points nearest the new faces,
      // when that is within the reference tolerance (keep_input_points)
      int best = -1;
      double best_gap = keep_tolerance_;
      for (int k = 0; k < 3; ++k) {
        if (check_placement(c, c.place[k]) != done) continue;
        const double gap = distance_left_behind(c, c.place[k]);
        if (gap <= best_gap) {
          best = k;
          best_gap = gap;
          if (gap == 0) break;
        }
      }
      if (best >= 0) {
        to = c.place[best];
        if (best > 0) ++alternative_placements_;
        return done;
      }
    }
    Outcome first = done;
    for (int k = 0; k < 3; ++k) {
      if (k > 0 && c.place[k] == c.place[0]) continue;
      const Outcome o = check_placement(c, c.place[k]);
      if (o == done) {
        to = c.place[k];
        if (k > 0) ++alternative_placements_;
        return done;
      }
      if (k == 0) first = o;
    }
    return first;
  }

  // one candidate: no face around the moved vertex (its star is in tmp_)
  // flips or degenerates, an added face keeping the side of the face it
  // replaces; and no vertex drifts farther than the tolerance from its input
  // position (one not moved yet is at its input position)
  Outcome check_placement(const Contraction& c, const P3& cand) const
  {
    for (std::size_t i = 0; i < c.op.added.size(); ++i) {
      const Outcome o = check_face(c.op.added[i], c.ref[i], c.moved, cand);
      if (o != done) return o;
    }
    for (const Tri& t : tmp_) {
      bool removed = false;
      for (const Tri& r : c.op.removed) removed = removed || same_face(t, r);
      if (removed) continue;
      const Outcome o = check_face(t, t, c.moved, cand);
      if (o != done) return o;
    }
    const P3 origin = has_orig_[c.moved] ? p3(orig_[c.moved]) : pos(c.moved);
    if (sqdist(cand, origin) > max_dist_ * max_dist_) return displaced;
    return done;
  }

  // how far the input positions of the vertices the contraction removes or
  // moves end from the faces around the moved vertex at `cand` (its star
  // after the edit): 0 when they stay on the surface
  double distance_left_behind(const Contraction& c, const P3& cand) const
  {
    auto input_position = [&](Id i) { return has_orig_[i] ? p3(orig_[i]) : pos(i); };
    auto np = [&](Id i) { return i == c.moved ? cand : pos(i); };
    std::array<P3, 2> kept;
    std::size_t n = 0;
    kept[n++] = input_position(c.moved);
    if (c.op.removed_vertex != npos) kept[n++] = input_position(c.op.removed_vertex);
    double worst = 0;
    for (std::size_t k = 0; k < n; ++k) {
      double nearest = std::numeric_limits<double>::infinity();
      auto visit = [&](const Tri& t) {
        nearest = std::min(nearest, squared_distance_to_triangle(kept[k], np(t[0]), np(t[1]), np(t[2])));
      };
      for (const Tri& t : c.op.added) visit(t);
      for (const Tri& t : tmp_) {
        bool removed = false;
        for (const Tri& r : c.op.removed) removed = removed || same_face(t, r);
        if (!removed) visit(t);
      }
      worst = std::max(worst, std::sqrt(nearest));
    }
    return worst;
  }

  // apply: edits the mesh (moving `moved` to `to`) and records the edit for
  // undo and redo. The border edges around the affected vertices are taken
  // first (before_), for the re-pairing. False when the edit was refused.
  bool apply_contraction(Contraction& c, const P3& to, double dist)
  {
    border_edges_around(affected_, before_);
    Op& op = c.op;
    Point to_point(to[0], to[1], to[2]);
    op.moves.push_back(Move{c.moved, get(vpm_, vd_[c.moved]), to_point});
    if (!has_orig_[c.moved]) {
      has_orig_[c.moved] = 1;
      orig_[c.moved] = op.moves.back().from;
    }
    if (!run_edit(op.removed, op.added, npos, op.removed_position, op.removed_vertex, op.moves, true))
      return false;
    op.level = std::max(dist, current_distance());
    ops_.push_back(std::move(op));
    ++pos_;
    return true;
  }

  // re-pair (Algorithm 1, lines 8-14): the vertices whose nearest border edge
  // may have changed get a new pair.
  void update_pairs(Id moved)
  {
    border_edges_around(affected_, after_);
    recompute_.clear();
    collect_pairs_on_changed_edges(moved);
    register_changed_edges(moved);
    // of the affected vertices only the moved one needs a new pair: the others
    // keep their position and their paired edge (else it is in before_); one that
    // left the border or was removed is caught when its entry is popped (stale)
    // (a pair rejected earlier is retried whenever its neighbourhood changed)
    recompute_.push_back(moved);
    if (ops_.back().removed_vertex != npos) recompute_.push_back(ops_.back().removed_vertex);
    for (Id c : affected_)
      if (rejected_[c]) recompute_.push_back(c);
    collect_vertices_near_changed_edges(moved);
    std::sort(recompute_.begin(), recompute_.end());
    recompute_.erase(std::unique(recompute_.begin(), recompute_.end()), recompute_.end());
    for (Id v : recompute_) compute_pair(v);
  }

  // vertices paired with an edge that left the border or moved need a new
  // pair; an edge still on the border with both ends in place keeps its pairs
  // (but a pair rejected earlier is retried)
  void collect_pairs_on_changed_edges(Id moved)
  {
    for (std::uint64_t e : before_) {
      const bool changed =
          ka(e) == moved || kb(e) == moved || !std::binary_search(after_.begin(), after_.end(), e);
      for (Id v = head_[ka(e)]; v != npos; v = next_[v])
        if (pair_[v].edge == e && (changed || rejected_[v])) recompute_.push_back(v);
    }
  }

  // keeps in after_ only the new border edges and those that moved, and
  // registers them: the others are registered already and cannot be nearer
  // to anyone than before
  void register_changed_edges(Id moved)
  {
    after_.erase(std::remove_if(after_.begin(), after_.end(),
                                [&](std::uint64_t e) {
                                  return ka(e) != moved && kb(e) != moved &&
                                         std::binary_search(before_.begin(), before_.end(), e);
                                }),
                 after_.end());
    for (std::uint64_t e : after_) grid_.insert(e, pos(ka(e)), pos(kb(e)));
  }

  // The paper recomputes only the vertices paired with a changed edge; a
  // changed edge (after_) may also become the nearest one of other vertices
  // (or the first one within reach), so look for those too.
  void collect_vertices_near_changed_edges(Id moved)
  {
    vgrid_.insert(moved, pos(moved), pos(moved));
    for (std::uint64_t e : after_) {
      P3 pa = pos(ka(e)), pb = pos(kb(e));
      vgrid_.query_box(pa, pb, max_dist_, [&](const Segment_grid::Item& it) {
        Id v = Id(it.key);
        if (v == ka(e) || v == kb(e)) return;
        double t = 0, d = seg_dist(it.a, pa, pb, t);  // a stale copy only costs a recompute
        if (d > max_dist_ || !alive_[v] || !selected_[v]) return;
        if (pair_[v].kind == none || d < pair_[v].dist) recompute_.push_back(v);
      });
    }
  }

  void border_edges_around(const std::vector<Id>& vs, std::vector<std::uint64_t>& out)
  {
    out.clear();
    for (Id c : vs) {
      if (!alive_[c]) continue;
      halfedge_descriptor hv = halfedge(vd_[c], tm_);
      if (hv == GT::null_halfedge()) continue;
      for (halfedge_descriptor h : CGAL::halfedges_around_target(hv, tm_)) {
        if (is_border(h, tm_)) out.push_back(key(id_of(source(h, tm_)), c));
        if (is_border(opposite(h, tm_), tm_)) out.push_back(key(c, id_of(source(h, tm_))));
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

  // ---- face edits (forward, undo and redo all go through here) -------------
  // Euler::remove_face deletes vertices left without faces; re-create them at
  // once (same index on Surface_mesh: the free list is LIFO) so ids stay valid.
  // False (nothing removed) when the face is not a triangle after all.
  bool remove_face_keep_vertices(halfedge_descriptor h)
  {
    std::array<std::pair<Id, Point>, 3> lone;
    int n = 0;
    halfedge_descriptor g = h;
    Walk_bound bound(2);  // a triangle: three steps, which also keeps `lone` in bounds
    do {
      halfedge_descriptor ng = next(g, tm_);
      if (is_border(opposite(g, tm_), tm_) && is_border(opposite(ng, tm_), tm_) &&
          next(opposite(ng, tm_), tm_) == opposite(g, tm_)) {
        vertex_descriptor t = target(g, tm_);
        lone[n++] = {Id(get(idmap_, t) - 1), get(vpm_, t)};
      }
      g = ng;
    } while (g != h && bound.step());
    if (bound.exceeded()) return stop_at_bound("close_gaps: the walk around a removed face");
    CGAL::Euler::remove_face(h, tm_);
    for (int i = n - 1; i >= 0; --i) {
      vertex_descriptor v = add_vertex(tm_);
      put(vpm_, v, lone[i].second);
      put(idmap_, v, lone[i].first + 1);
      vd_[lone[i].first] = v;
    }
    return true;
  }
  bool add_tri(const Tri& t)
  {
    std::array<vertex_descriptor, 3> vs{{vd_[t[0]], vd_[t[1]], vd_[t[2]]}};
    return CGAL::Euler::add_face(vs, tm_) != GT::null_face();
  }
  bool remove_tri(const Tri& t)
  {
    auto h = find_halfedge(t[0], t[1]);
    if (!h.second || is_border(h.first, tm_) || target(next(h.first, tm_), tm_) != vd_[t[2]]) return false;
    return remove_face_keep_vertices(h.first);
  }

  // removes `rem`, adds `add`; re-creates vertex `readd` first (at `readd_pos`) and
  // deletes `drop` last; then sets the positions of `moves` (to, or from on undo).
  bool run_edit(const std::vector<Tri>& rem, const std::vector<Tri>& add, Id readd,
                const Point& readd_pos, Id drop, const std::vector<Move>& moves, bool forward)
  {
    if (readd != npos) {
      vertex_descriptor v = add_vertex(tm_);
      put(vpm_, v, readd_pos);
      put(idmap_, v, readd + 1);
      vd_[readd] = v;
      alive_[readd] = 1;
    }
    for (std::size_t i = 0; i < rem.size(); ++i)
      if (!remove_tri(rem[i])) {
        for (std::size_t j = i; j-- > 0;) add_tri(rem[j]);
        if (readd != npos) {
          remove_vertex(vd_[readd], tm_);
          alive_[readd] = 0;
        }
        if (!forward) broken_ = true;
        return false;
      }
    for (std::size_t i = 0; i < add.size(); ++i)
      if (!add_tri(add[i])) {
        bool ok = true;
        for (std::size_t j = i; j-- > 0;) ok = remove_tri(add[j]) && ok;
        for (const Tri& t : rem) ok = add_tri(t) && ok;
        if (readd != npos) {
          remove_vertex(vd_[readd], tm_);
          alive_[readd] = 0;
        }
        if (!ok || !forward) broken_ = true;
        return false;
      }
    if (drop != npos) {
      if (halfedge(vd_[drop], tm_) == GT::null_halfedge()) remove_vertex(vd_[drop], tm_);
      alive_[drop] = 0;
    }
    for (const Move& m : moves) put(vpm_, vd_[m.v], forward ? m.to : m.from);
    return true;
  }

  bool redo()
  {
    const Op& op = ops_[pos_];
    if (!run_edit(op.removed, op.added, npos, op.removed_position, op.removed_vertex, op.moves, true)) {
      broken_ = true;
      return false;
    }
    ++pos_;
    return true;
  }
  bool undo()
  {
    const Op& op = ops_[pos_ - 1];
    std::vector<Move> back(op.moves.rbegin(), op.moves.rend());
    if (!run_edit(op.added, op.removed, op.removed_vertex, op.removed_position, npos, back, false))
      return false;
    --pos_;
    return true;
  }

  // a walk or queue of `step` hit its bound (bounded_walks.h): no further
  // step, and the result says invalid_mesh; the mesh stays valid (run_edit
  // rolls back an edit the bound stopped)
  bool stop_at_bound(const char* step)
  {
    broken_ = true;
    message_ = walk_bound_message(step);
    return false;
  }

  // ---- state ---------------------------------------------------------------
  TriangleMesh& tm_;
  VertexPointMap vpm_;
  Id_map idmap_;
  Status status_ = Status::ok;
  std::string message_;
  bool broken_ = false;            // an undo failed, or a bound was hit: no further step
  std::size_t max_ops_ = 0;        // contraction cap (see step())
  double max_dist_ = 0, lambda_ = 0.5, snap_ = 0;
  bool keep_points_ = false;     // keep_input_points()
  double keep_tolerance_ = 0;    // 1e-6 x the bounding-box diagonal

  std::vector<vertex_descriptor> vd_;  // stable id -> current descriptor
  std::size_t input_boundary_ = 0;     // ids below it: the input boundary vertices
  std::vector<char> alive_, selected_, has_orig_;
  std::vector<char> rejected_;  // the vertex's pair was popped and refused (flip, non-manifold, ...)
  std::vector<Pair> pair_;
  std::vector<std::uint32_t> ver_;
  std::vector<Point> orig_;

  Segment_grid grid_;   // boundary edges (keys: edge keys)
  Segment_grid vgrid_;  // boundary vertices (keys: ids)
  std::vector<Id> head_, next_, prev_, owner_;  // vertices by the source of their paired edge
  std::priority_queue<Entry> queue_;
  std::vector<Op> ops_;
  std::size_t pos_ = 0;

  std::size_t alternative_placements_ = 0;  // contractions placed at an end, not at the λ point
  std::size_t rejected_flip_ = 0, rejected_degenerate_ = 0, rejected_non_manifold_ = 0,
              rejected_failed_ = 0, rejected_displacement_ = 0;
  std::size_t boundary_edges_before_ = 0, boundary_loops_before_ = 0;

  // scratch
  std::vector<std::uint64_t> before_, after_;
  std::vector<Id> affected_, recompute_, nbr_;
  std::vector<Tri> tmp_, tmp2_;
  std::vector<std::pair<Id, Id>> link_;
};

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CLOSE_GAPS_GAP_CLOSER_H
