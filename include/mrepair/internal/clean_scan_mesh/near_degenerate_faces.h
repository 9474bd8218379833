// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Worker of repair_near_degenerate_faces() (RameshCleaner 3.6, Algorithm 1).
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_NEAR_DEGENERATE_FACES_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_NEAR_DEGENERATE_FACES_H

#include <mrepair/cleaning_results.h>
#include <mrepair/definitions.h>
#include <mrepair/geometric_statistics.h>
#include <mrepair/status.h>
#include <mrepair/parameters.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/internal/clean_scan_mesh/common.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <vector>

namespace mrepair {
namespace internal {
namespace clean_pipeline {

struct Near_degenerate_settings
{
  Near_degenerate_criterion criterion;  // definitions.h
  double max_normal_deviation = 0.0; // radians
  std::size_t max_operations = 0;
};

// Counts faces with a zero edge, or a skinny edge whose opposite angle in the
// face is below the skinny angle (the definition of inspect.h). When `flagged`
// is given, it receives the halfedges that make their face near-degenerate:
// their edges are exactly the collapsible edges, so this one pass also scores.
template <typename Mesh, typename VPM>
std::size_t count_near_degenerate_faces(
    const Geometric_statistics<Mesh, VPM>& st, const Near_degenerate_settings& s,
    std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor>* flagged = nullptr)
{
  const Mesh& m = st.mesh();
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;
  std::vector<face_descriptor> fs(faces(m).begin(), faces(m).end());
  std::vector<unsigned char> bad(fs.size(), 0); // bit i: i-th halfedge of the face
  const double global_mean = st.global_mean_edge_length();
  parallel_for_mesh_elements<Mesh>(fs.size(), [&](std::size_t i) {
    unsigned char bit = 1, mask = 0;
    for (auto h : CGAL::halfedges_around_face(halfedge(fs[i], m), m)) {
      if (s.criterion.edge_makes_face_near_degenerate(st.length(h), st.opposite_angle(h), global_mean,
                                                      st.local_mean_edge_length(h)))
        mask |= bit;
      bit = static_cast<unsigned char>(bit << 1);
    }
    bad[i] = mask;
  });
  std::size_t n = 0;
  for (std::size_t i = 0; i < fs.size(); ++i) {
    if (!bad[i]) continue;
    ++n;
    if (!flagged) continue;
    unsigned char bit = 1;
    for (auto h : CGAL::halfedges_around_face(halfedge(fs[i], m), m)) {
      if (bad[i] & bit) flagged->push_back(h);
      bit = static_cast<unsigned char>(bit << 1);
    }
  }
  return n;
}

template <typename Mesh, typename VPM, typename VisitorHandle>
class Near_degenerate_repairer
{
  using GT = boost::graph_traits<Mesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Stats = Geometric_statistics<Mesh, VPM>;
  using Vec = Vec3;
  using Stamp_map =
      typename boost::property_map<Mesh, CGAL::dynamic_halfedge_property_t<std::uint32_t>>::type;

  struct Entry
  {
    double priority;
    halfedge_descriptor h;
    std::uint32_t stamp;
    bool operator<(const Entry& o) const { return priority < o.priority; }
  };

  enum Outcome { done, rejected_link, rejected_normal, rejected_boundary };

  Local_operations<Mesh, VPM>& ops_;
  Mesh& tm_;
  Stats& st_;
  VisitorHandle& vis_;
  Near_degenerate_settings s_;
  Near_degenerate_faces_result& c_;  // the public counters, written in place
  bool cancelled_ = false;
  bool hit_operation_cap_ = false;
  Stamp_map stamp_;
  std::priority_queue<Entry> q_;
  double cos_dev_;

public:
  // `ops` keeps `st` current (Local_operations::keep_current).
  Near_degenerate_repairer(Local_operations<Mesh, VPM>& ops, Stats& st, VisitorHandle& vis,
                           const Near_degenerate_settings& s, Near_degenerate_faces_result& c)
    : ops_(ops), tm_(ops.mesh()), st_(st), vis_(vis), s_(s), c_(c),
      stamp_(get(CGAL::dynamic_halfedge_property_t<std::uint32_t>(), tm_)),
      cos_dev_(std::cos(s.max_normal_deviation))
  {}

  // `flagged`: halfedges found by count_near_degenerate_faces (collapsible edges)
  void run(const std::vector<halfedge_descriptor>& flagged)
  {
    // stamps start at 0 (Surface_mesh value-initialises, Polyhedron's map inserts 0)
    for (halfedge_descriptor h : flagged) {
      if (get(stamp_, h) != 0 || get(stamp_, opposite(h, tm_)) != 0) continue; // edge seen
      push(h);
      ++c_.collapsible_edges_initial;
    }
    if (vis_.stop_requested()) {  // polled before any change, even with nothing to do
      cancelled_ = true;
      return;
    }
    const double total = static_cast<double>(c_.collapsible_edges_initial) + 1.0;
    std::size_t pops = 0, ops = 0;
    // bounded: entries are pushed at the start and after an edit, and edits
    // stop at max_operations (3 x edges + 100 unless given)
    while (!q_.empty()) {
      Entry en = q_.top();
      q_.pop();
      // stale or removed: only the stamp is read, the halfedge is not dereferenced
      if (get(stamp_, en.h) != en.stamp) continue;
      ++pops;
      if (pops == 1 || (pops & 255u) == 0) { // poll the visitor now and then
        if (vis_.stop_requested()) {
          cancelled_ = true;
          return;
        }
        vis_.progress((std::min)(1.0, static_cast<double>(pops) / total));
      }
      if (ops >= s_.max_operations) {
        hit_operation_cap_ = true;
        return;
      }
      halfedge_descriptor h = en.h;
      if (!collapsible(h)) continue;
      Outcome o = try_collapse(h);
      if (o == done) {
        ++ops;
        continue;
      }
      if (try_flip(h)) {
        ++ops;
        continue;
      }
      if (o == rejected_link) ++c_.rejected_link_condition;
      else if (o == rejected_normal) ++c_.rejected_normal_test;
      else ++c_.rejected_boundary;
    }
  }

private:
  // the criterion of definitions.h in either face of the edge
  bool collapsible(halfedge_descriptor h) const
  {
    const double l = st_.length(h), global_mean = st_.global_mean_edge_length();
    const double local_mean = st_.local_mean_edge_length(h);
    for (halfedge_descriptor x : {h, opposite(h, tm_)})
      if (!is_border(x, tm_) &&
          s_.criterion.edge_makes_face_near_degenerate(l, st_.opposite_angle(x), global_mean, local_mean))
        return true;
    return s_.criterion.is_zero_edge(l, global_mean);  // a zero border edge
  }

  void bump(halfedge_descriptor h)
  {
    put(stamp_, h, get(stamp_, h) + 1);
    halfedge_descriptor o = opposite(h, tm_);
    put(stamp_, o, get(stamp_, o) + 1);
  }

  void push(halfedge_descriptor h)
  {
    bump(h); // older entries of this edge become stale
    const double l = st_.length(h);
    q_.push(Entry{1.0 / (l + 1e-12 * st_.global_mean_edge_length() + 1e-300), h, get(stamp_, h)});
  }

  // edges incident to v and to its neighbours: their lengths, local means or
  // opposite angles may have changed
  void push_around(vertex_descriptor v)
  {
    if (halfedge(v, tm_) == GT::null_halfedge()) return;
    for (halfedge_descriptor hv : CGAL::halfedges_around_source(v, tm_)) {
      vertex_descriptor x = target(hv, tm_);
      for (halfedge_descriptor hx : CGAL::halfedges_around_source(x, tm_))
        if (collapsible(hx)) push(hx);
    }
  }

  Outcome try_collapse(halfedge_descriptor h)
  {
    const vertex_descriptor u = source(h, tm_), w = target(h, tm_);
    const bool bu = is_border_vertex(u, tm_), bw = is_border_vertex(w, tm_);
    using Check = typename Local_operations<Mesh, VPM>::Collapse_check;
    const Check check = ops_.check_collapse(h);
    if (check == Check::would_pinch_border) return rejected_boundary;
    if (check == Check::fails_link_condition) return rejected_link;
    const Vec pu = st_.point(u), pw = st_.point(w);
    const Vec mid{{0.5 * (pu[0] + pw[0]), 0.5 * (pu[1] + pw[1]), 0.5 * (pu[2] + pw[2])}};
    std::array<Vec, 3> cand;
    std::size_t n = 0;
    if (bu != bw) {
      cand[n++] = bu ? pu : pw; // a boundary vertex stays on the boundary
    } else {
      const bool u_first = st_.max_dihedral(u) >= st_.max_dihedral(w); // more featured first
      cand[n++] = u_first ? pu : pw;
      cand[n++] = mid;
      cand[n++] = u_first ? pw : pu;
    }
    for (std::size_t i = 0; i < n; ++i)
      if (normals_ok(h, cand[i])) {
        collapse(h, cand[i]);
        return done;
      }
    return rejected_normal;
  }

  // No face of the surviving 1-rings of source(h) and target(h) turns by more
  // than the limit or becomes degenerate when both move to p.
  bool normals_ok(halfedge_descriptor h, const Vec& p) const
  {
    const face_descriptor fa = face(h, tm_), fb = face(opposite(h, tm_), tm_);
    for (vertex_descriptor x : {source(h, tm_), target(h, tm_)})
      for (halfedge_descriptor hx : CGAL::halfedges_around_target(x, tm_)) {
        const face_descriptor f = face(hx, tm_);
        if (f == GT::null_face() || f == fa || f == fb) continue;
        // f = (x, a, b) in order, starting at the corner x
        const Vec a = st_.point(target(next(hx, tm_), tm_));
        const Vec b = st_.point(source(hx, tm_));
        const Vec n = triangle_normal(p, a, b);
        const double nn = norm(n);
        const double scale = dot(sub(a, p), sub(a, p)) +
                             dot(sub(b, p), sub(b, p)) +
                             dot(sub(a, b), sub(a, b));
        const Vec& old = st_.normal(f);
        const bool old_degenerate = is_zero(old);
        if (!(nn > 1e-12 * scale)) {
          if (!old_degenerate) return false; // becomes degenerate
          continue;
        }
        if (old_degenerate) continue;
        if (dot(n, old) < cos_dev_ * nn) return false;
      }
    return true;
  }

  void bump_around(vertex_descriptor x)
  {
    for (halfedge_descriptor hx : CGAL::halfedges_around_target(x, tm_)) bump(hx);
  }

  void collapse(halfedge_descriptor h, const Vec& p)
  {
    const vertex_descriptor u = source(h, tm_), w = target(h, tm_);
    bump_around(u); // covers every halfedge the collapse removes
    bump_around(w);
    const vertex_descriptor v = ops_.collapse_edge(h, p);
    ++c_.edges_collapsed;
    push_around(v);
  }

  // Cap fallback: flip the edge opposite the obtuse angle of a face incident
  // to h, when the flip raises the minimum angle and passes the normal test.
  bool try_flip(halfedge_descriptor h)
  {
    for (halfedge_descriptor side : {h, opposite(h, tm_)}) {
      if (is_border(side, tm_)) continue;
      halfedge_descriptor g = side;
      for (halfedge_descriptor x : CGAL::halfedges_around_face(side, tm_))
        if (st_.opposite_angle(x) > st_.opposite_angle(g)) g = x;
      if (st_.opposite_angle(g) <= 0.5 * pi) continue; // not a cap
      if (!ops_.flip_keeps_manifold(g, 3)) continue;
      const halfedge_descriptor og = opposite(g, tm_);
      const vertex_descriptor a = source(g, tm_), b = target(g, tm_);
      const vertex_descriptor c = target(next(g, tm_), tm_), d = target(next(og, tm_), tm_);
      const Vec pa = st_.point(a), pb = st_.point(b), pc = st_.point(c), pd = st_.point(d);
      // reference: area-weighted normal of the two old faces (a,b,c), (b,a,d)
      const Vec n1 = triangle_normal(pa, pb, pc);
      const Vec n2 = triangle_normal(pb, pa, pd);
      const Vec ref{{n1[0] + n2[0], n1[1] + n2[1], n1[2] + n2[2]}};
      const double nref = norm(ref);
      if (!(nref > 0)) continue;
      // new faces (a,d,c) and (d,b,c)
      const Vec m1 = triangle_normal(pa, pd, pc);
      const Vec m2 = triangle_normal(pd, pb, pc);
      const double nm1 = norm(m1), nm2 = norm(m2);
      if (!(nm1 > 0) || !(nm2 > 0)) continue;
      if (dot(m1, ref) < cos_dev_ * nm1 * nref || dot(m2, ref) < cos_dev_ * nm2 * nref)
        continue;
      const double old_min = (std::min)(st_.min_angle(face(g, tm_)), st_.min_angle(face(og, tm_)));
      const double new_min = (std::min)(min_angle(pa, pd, pc), min_angle(pd, pb, pc));
      if (!(new_min > old_min)) continue;
      for (vertex_descriptor x : {a, b}) bump_around(x);
      ops_.flip_edge(g);
      ++c_.edges_flipped;
      for (vertex_descriptor x : {a, b, c, d}) push_around(x);
      return true;
    }
    return false;
  }

public:
  bool cancelled() const { return cancelled_; }
  bool hit_operation_cap() const { return hit_operation_cap_; }

private:
  static double min_angle(const Vec& a, const Vec& b, const Vec& c)
  {
    const double x = angle(sub(b, a), sub(c, a));
    const double y = angle(sub(c, b), sub(a, b));
    const double z = angle(sub(a, c), sub(b, c));
    return (std::min)(x, (std::min)(y, z));
  }
};

// The worker behind repair_near_degenerate_faces(): `ops` keeps `st` current;
// `vis` gives progress and cancellation. The public face reads the settings.
template <typename Mesh, typename VPM, typename VisitorHandle>
Near_degenerate_faces_result repair_near_degenerate_faces_with(
    Local_operations<Mesh, VPM>& ops, Geometric_statistics<Mesh, VPM>& st,
    const Near_degenerate_settings& s, VisitorHandle& vis)
{
  Near_degenerate_faces_result r;
  Mesh& tm = ops.mesh();
  r.faces_before = internal::face_count(tm);
  std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor> flagged;
  r.near_degenerate_faces_before = count_near_degenerate_faces(st, s, &flagged);
  // Nothing flagged (the pipeline's later iterations, usually): no worker,
  // whose stamp map is a zero-filled array over every halfedge (136 MB of a
  // 10M-face scan), and no second count. The visitor is still polled, as the
  // worker does before any change.
  if (flagged.empty()) {
    r.faces_after = r.faces_before;
    if (vis.stop_requested()) {
      r.status = Status::cancelled;
      r.message = "cancelled by the visitor";
    }
    vis.progress(1.0);
    return r;
  }
  Near_degenerate_repairer<Mesh, VPM, VisitorHandle> worker(ops, st, vis, s, r);
  worker.run(flagged);
  r.faces_after = internal::face_count(tm);
  // no collapse and no flip: the mesh and its statistics are those counted
  r.near_degenerate_faces_after = r.edges_collapsed + r.edges_flipped == 0
                                      ? r.near_degenerate_faces_before
                                      : count_near_degenerate_faces(st, s);
  if (worker.cancelled()) {
    r.status = Status::cancelled;
    r.message = "cancelled by the visitor";
  } else if (r.near_degenerate_faces_after > 0) {
    r.status = Status::partial;
    if (worker.hit_operation_cap()) r.message = "max_degenerate_operations reached";
  }
  vis.progress(1.0);
  return r;
}

// ---- Settings: read once from the named parameters of the public call or
// of the pipeline, which forwards its own.
// `max_degenerate_operations` defaults to 3 x edges + 100: collapses alone
// cannot exceed |E|; the cap bounds flip sequences.
template <typename NP>
bool read_near_degenerate_settings(const NP& np, std::size_t edge_count,
                                   Near_degenerate_settings& s, std::string& message)
{
  Near_degenerate_criterion& k = s.criterion;
  k.zero_edge_factor = get_or<double>(np, internal_np::zero_edge_factor, defaults::zero_edge_factor);
  k.skinny_edge_factor =
      get_or<double>(np, internal_np::skinny_edge_factor, defaults::skinny_edge_factor);
  const double skinny_deg = get_or<double>(np, internal_np::skinny_angle, defaults::skinny_angle);
  const double dev_deg = get_or<double>(np, internal_np::max_normal_deviation, defaults::max_normal_deviation);
  s.max_operations =
      get_or<std::size_t>(np, internal_np::max_degenerate_operations, 3 * edge_count + 100);
  if (!(k.zero_edge_factor >= 0) || !std::isfinite(k.zero_edge_factor) ||
      !(k.skinny_edge_factor >= 0) || !std::isfinite(k.skinny_edge_factor) ||
      !(skinny_deg >= 0 && skinny_deg <= 180) || !(dev_deg > 0 && dev_deg <= 180)) {
    message = "zero_edge_factor, skinny_edge_factor >= 0; skinny_angle in [0,180]; "
              "max_normal_deviation in (0,180]";
    return false;
  }
  k.skinny_angle = to_radians(skinny_deg);
  s.max_normal_deviation = to_radians(dev_deg);
  return true;
}

} // namespace clean_pipeline
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_NEAR_DEGENERATE_FACES_H
