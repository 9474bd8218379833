// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Workers of relax_spikes() and remove_unrelaxable_spikes() (RameshCleaner 3.7, 3.8).
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKES_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKES_H

#include <mrepair/cleaning_results.h>
#include <mrepair/geometric_statistics.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>
#include <mrepair/parameters.h>
#include <mrepair/definitions.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/internal/clean_scan_mesh/common.h>
#include <mrepair/internal/clean_scan_mesh/spike_criterion.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {
namespace clean_pipeline {

struct Spike_settings
{
  double spike_angle = 0;          // radians; dihedral criterion
  double height_factor = default_spike_height_factor;  // second criterion; <= 0 disables it
  double start_angle = 0;          // a, radians
  double full_angle = 0;           // b, radians
  std::size_t rings = defaults::relax_rings;  // n of the working region
  std::size_t max_iterations = defaults::max_relax_iterations;
  std::size_t max_removal_rounds = defaults::max_spike_removal_rounds;
};

// Spike tests on current statistics.
template <typename Mesh, typename VPM>
class Spike_detector
{
  using GT = boost::graph_traits<Mesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using Stats = Geometric_statistics<Mesh, VPM>;
  using Vec = typename Stats::Vec;
  const Stats& st_;
  const Spike_settings& s_;

public:
  Spike_detector(const Stats& st, const Spike_settings& s) : st_(st), s_(s) {}

  bool by_dihedral(vertex_descriptor v) const
  {
    return spiked_by_dihedral(st_.max_dihedral(v), s_.spike_angle);
  }

  // Tall narrow spikes keep every dihedral angle below 90 degrees, so the
  // dihedral test misses them: the height criterion of spike_criterion.h
  // (shared with inspect()), on the link of v walked around its halfedges.
  bool by_height(vertex_descriptor v) const
  {
    return spiked_by_height(st_.max_dihedral(v), s_.height_factor, [&](Spike_link_sums& sums) {
      const Mesh& m = st_.mesh();
      const halfedge_descriptor h0 = halfedge(v, m);
      if (h0 == GT::null_halfedge()) return false;
      const Vec p = st_.point(v);
      Vec first{{0, 0, 0}}, prev{{0, 0, 0}};
      bool started = false;
      for (halfedge_descriptor h : CGAL::halfedges_around_target(h0, m)) {
        if (is_border(h, m)) return false;  // interior vertices only
        const Vec a = st_.point(source(h, m));
        if (started) sums.add(p.data(), prev.data(), a.data());
        else first = a;
        prev = a;
        started = true;
      }
      if (started) sums.add(p.data(), prev.data(), first.data());  // close the link
      return true;
    });
  }

  bool spiked(vertex_descriptor v) const { return by_dihedral(v) || by_height(v); }
};

// The spiked vertices among `candidates`, in their order, in one parallel
// pass; `by_height` tells for each whether only the height criterion finds it.
template <typename Mesh, typename VPM>
void spiked_among(const Geometric_statistics<Mesh, VPM>& st, const Spike_settings& s,
                  const std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>& candidates,
                  std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>& spiked,
                  std::vector<unsigned char>& by_height)
{
  std::vector<unsigned char> flag(candidates.size(), 0);
  Spike_detector<Mesh, VPM> det(st, s);
  parallel_for_mesh_elements<Mesh>(candidates.size(), [&](std::size_t i) {
    if (det.by_dihedral(candidates[i])) flag[i] = 1;
    else if (det.by_height(candidates[i])) flag[i] = 2;
  });
  spiked.clear();
  by_height.clear();
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (flag[i]) {
      spiked.push_back(candidates[i]);
      by_height.push_back(flag[i] == 2);
    }
}

// The spiked vertices of the whole mesh, and how many of them only the
// height criterion finds.
template <typename Mesh, typename VPM>
std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>
collect_spiked(const Geometric_statistics<Mesh, VPM>& st, const Spike_settings& s,
               std::size_t* by_height_only = nullptr)
{
  const Mesh& m = st.mesh();
  using vertex_descriptor = typename boost::graph_traits<Mesh>::vertex_descriptor;
  const std::vector<vertex_descriptor> vs(vertices(m).begin(), vertices(m).end());
  std::vector<vertex_descriptor> out;
  std::vector<unsigned char> by_height;
  spiked_among(st, s, vs, out, by_height);
  if (by_height_only) *by_height_only = static_cast<std::size_t>(std::count(by_height.begin(), by_height.end(), 1));
  return out;
}

template <typename Mesh, typename VPM>
std::size_t count_spiked(const Geometric_statistics<Mesh, VPM>& st, const Spike_settings& s,
                         std::size_t* by_height_only = nullptr)
{
  return collect_spiked(st, s, by_height_only).size();
}

// The spiked vertices of a mesh whose statistics are kept current, found
// again after local edits by testing only the vertices those edits touched:
// a vertex's spike status reads its 1-ring alone, and the statistics'
// journal lists every vertex whose 1-ring changed (set_journal), so the set
// is the same as a whole-mesh pass gives, in the same (index) order. The
// pipeline looks for spikes four times an iteration; on a noisy 1M-face scan
// the whole-mesh passes were the cleaning's largest cost (13% of the job's
// CPU time). Removed vertices are told apart by `Surface_mesh::is_removed`;
// on other meshes every call is a whole-mesh pass.
template <typename Mesh, typename VPM>
class Spike_tracker
{
  using vertex_descriptor = typename boost::graph_traits<Mesh>::vertex_descriptor;
  using Stats = Geometric_statistics<Mesh, VPM>;
  static constexpr bool incremental = Is_surface_mesh<Mesh>::value;
  Stats& st_;
  bool primed_ = false;
  double angle_ = 0., height_ = 0.;  // the settings the set was found with
  std::vector<vertex_descriptor> spiked_, journal_;
  std::vector<unsigned char> by_height_;  // parallel to spiked_

public:
  explicit Spike_tracker(Stats& st) : st_(st) {}
  Spike_tracker(const Spike_tracker&) = delete;
  Spike_tracker& operator=(const Spike_tracker&) = delete;
  ~Spike_tracker() { st_.set_journal(nullptr); }

  std::vector<vertex_descriptor> collect(const Spike_settings& s, std::size_t* by_height_only = nullptr)
  {
    if (!incremental || !primed_ || s.spike_angle != angle_ || s.height_factor != height_)
      prime(s);
    else
      update(s);
    if (by_height_only)
      *by_height_only = static_cast<std::size_t>(std::count(by_height_.begin(), by_height_.end(), 1));
    return spiked_;
  }

private:
  void prime(const Spike_settings& s)
  {
    const Mesh& m = st_.mesh();
    spiked_among(st_, s, std::vector<vertex_descriptor>(vertices(m).begin(), vertices(m).end()), spiked_,
                 by_height_);
    angle_ = s.spike_angle;
    height_ = s.height_factor;
    journal_.clear();
    if (incremental) st_.set_journal(&journal_);
    primed_ = true;
  }

  // candidates: the vertices spiked last time and those touched since
  void update(const Spike_settings& s)
  {
    const Mesh& m = st_.mesh();
    journal_.insert(journal_.end(), spiked_.begin(), spiked_.end());
    std::sort(journal_.begin(), journal_.end());
    journal_.erase(std::unique(journal_.begin(), journal_.end()), journal_.end());
    journal_.erase(std::remove_if(journal_.begin(), journal_.end(),
                                  [&](vertex_descriptor v) { return is_removed_vertex(m, v); }),
                   journal_.end());
    spiked_among(st_, s, journal_, spiked_, by_height_);
    journal_.clear();
  }
};

// Whole-mesh passes without a tracker, the tracker's when there is one.
template <typename Mesh, typename VPM>
std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>
find_spiked(const Geometric_statistics<Mesh, VPM>& st, Spike_tracker<Mesh, VPM>* tracker,
            const Spike_settings& s, std::size_t* by_height_only = nullptr)
{
  return tracker ? tracker->collect(s, by_height_only) : collect_spiked(st, s, by_height_only);
}

template <typename Mesh, typename VPM, typename VisitorHandle>
class Spike_relaxer
{
  using GT = boost::graph_traits<Mesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using Stats = Geometric_statistics<Mesh, VPM>;
  using Vec = typename Stats::Vec;
  using Mark =
      typename boost::property_map<Mesh, CGAL::dynamic_vertex_property_t<std::uint32_t>>::type;

  Local_operations<Mesh, VPM>& ops_;
  Mesh& tm_;
  Stats& st_;
  VisitorHandle& vis_;
  const Spike_settings& s_;
  Spike_relaxation_result& c_;  // the public counters, written in place
  std::size_t spiked_in_region_before_ = 0;
  bool cancelled_ = false;
  Spike_detector<Mesh, VPM> det_;
  Mark mark_;     // generation marks for set building
  Mark in_w_;     // place in the working region plus 1 (0: outside)
  Mark moved_;    // 1 once moved
  std::uint32_t gen_ = 0;

public:
  // `ops` keeps `st` current (Local_operations::keep_current).
  Spike_relaxer(Local_operations<Mesh, VPM>& ops, Stats& st, VisitorHandle& vis,
                const Spike_settings& s, Spike_relaxation_result& c)
    : ops_(ops), tm_(ops.mesh()), st_(st), vis_(vis), s_(s), c_(c), det_(st, s),
      mark_(get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), tm_)),
      in_w_(get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), tm_)),
      moved_(get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), tm_))
  {}

  // w(theta) of eq. (2), with the bracket the paper misprints put right:
  // R(v) = 0 for theta <= a, min(1, (theta - a)/(b - a)) L(v) above
  // (the printed "(theta(v) - a/(b-a))" is not dimensionless and exceeds 1).
  // A vertex flagged by the height criterion is relaxed fully.
  double weight(vertex_descriptor v) const
  {
    if (det_.by_height(v)) return 1.0;
    const double t = st_.max_dihedral(v);
    if (!(t > s_.start_angle)) return 0.0;
    if (!(s_.full_angle > s_.start_angle)) return 1.0;
    return (std::min)(1.0, (t - s_.start_angle) / (s_.full_angle - s_.start_angle));
  }

  void run(std::vector<vertex_descriptor> S)
  {
    // working region W: n-ring of S; in_w_ holds a vertex's place in W plus 1
    std::vector<vertex_descriptor> W;
    auto enter = [&](vertex_descriptor x) {
      if (get(in_w_, x) != 0) return;
      W.push_back(x);
      put(in_w_, x, static_cast<std::uint32_t>(W.size()));
    };
    for (vertex_descriptor v : S) enter(v);
    std::size_t begin = 0;
    // stops once a ring adds no vertex: `relax_rings` is the caller's and may
    // exceed any mesh (the rings after that one would add nothing either)
    for (std::size_t ring = 0; ring < s_.rings && begin < W.size(); ++ring) {
      const std::size_t end = W.size();
      for (std::size_t i = begin; i < end; ++i)
        for (halfedge_descriptor h : CGAL::halfedges_around_target(W[i], tm_)) enter(source(h, tm_));
      begin = end;
    }
    c_.region_vertices = W.size();
    // The spike status of W's vertices, tested once here and then only where
    // a move can change it: a vertex's status reads its own and its 1-ring's
    // positions and statistics, and the statistics change only around moved
    // vertices (Geometric_statistics::recompute_around). Testing all of W
    // after each round made the rounds grow faster than the mesh (10M faces:
    // 0.26 s a round against 0.0095 s at 1M).
    std::vector<unsigned char> spiked_in_w(W.size(), 0);
    parallel_for_mesh_elements<Mesh>(W.size(), [&](std::size_t i) { spiked_in_w[i] = det_.spiked(W[i]); });
    spiked_in_region_before_ = static_cast<std::size_t>(std::count(spiked_in_w.begin(), spiked_in_w.end(), 1));
    struct Item
    {
      double w, l; // weight, |L| (tie-break: the most displaced first)
      vertex_descriptor v;
    };
    std::vector<Item> R;
    std::vector<vertex_descriptor> M;
    std::vector<std::uint32_t> retest; // places in W
    while (!S.empty() && c_.iterations < s_.max_iterations) {
      if (vis_.stop_requested()) {
        cancelled_ = true;
        break;
      }
      // R = S and its 1-ring; Gauss-Seidel in order of decreasing weight so
      // that the spike tip moves first and its neighbours see it relaxed
      const std::uint32_t g = ++gen_;
      R.clear();
      auto add = [&](vertex_descriptor x) {
        if (get(mark_, x) == g) return;
        put(mark_, x, g);
        const double w = weight(x);
        if (w > 0) R.push_back(Item{w, norm(laplacian(x, st_.point(x))), x});
      };
      for (vertex_descriptor v : S) {
        add(v);
        for (halfedge_descriptor h : CGAL::halfedges_around_target(v, tm_)) add(source(h, tm_));
      }
      std::sort(R.begin(), R.end(), [](const Item& a, const Item& b) {
        return a.w > b.w || (a.w == b.w && a.l > b.l);
      });
      M.clear();
      for (const Item& r : R) M.push_back(r.v);
      if (M.empty()) break;
      std::size_t k = 0;
      ops_.move_vertices_in_order(M, [&](vertex_descriptor v) {
        const Vec p = st_.point(v);
        const Vec L = laplacian(v, p);
        const double w = R[k++].w;
        if (get(moved_, v) != 1) {
          put(moved_, v, 1);
          ++c_.vertices_relaxed;
        }
        return Vec{{p[0] + w * L[0], p[1] + w * L[1], p[2] + w * L[2]}};
      });
      ++c_.iterations;
      // the moved vertices and their 1-rings, those in W
      const std::uint32_t t = ++gen_;
      retest.clear();
      auto touch = [&](vertex_descriptor x) {
        if (get(mark_, x) == t) return;
        put(mark_, x, t);
        if (const std::uint32_t place = get(in_w_, x)) retest.push_back(place - 1);
      };
      for (vertex_descriptor v : M) {
        touch(v);
        for (halfedge_descriptor h : CGAL::halfedges_around_target(v, tm_)) touch(source(h, tm_));
      }
      parallel_for_mesh_elements<Mesh>(retest.size(), [&](std::size_t i) {
        spiked_in_w[retest[i]] = det_.spiked(W[retest[i]]);
      });
      S.clear();
      for (std::size_t i = 0; i < W.size(); ++i)
        if (spiked_in_w[i]) S.push_back(W[i]);
      vis_.progress(static_cast<double>(c_.iterations) / static_cast<double>(s_.max_iterations));
    }
    c_.spiked_in_region_after = static_cast<std::size_t>(std::count(spiked_in_w.begin(), spiked_in_w.end(), 1));
  }

  std::size_t spiked_in_region_before() const { return spiked_in_region_before_; }
  bool cancelled() const { return cancelled_; }

private:
  // uniform Laplacian (1); on the boundary restricted to the boundary neighbours
  Vec laplacian(vertex_descriptor v, const Vec& p) const
  {
    Vec sum{{0, 0, 0}};
    std::size_t n = 0;
    bool border = false;
    for (halfedge_descriptor h : CGAL::halfedges_around_target(v, tm_))
      if (is_border_edge(h, tm_)) border = true;
    for (halfedge_descriptor h : CGAL::halfedges_around_target(v, tm_)) {
      if (border && !is_border_edge(h, tm_)) continue;
      const Vec q = st_.point(source(h, tm_));
      for (int j = 0; j < 3; ++j) sum[j] += q[j];
      ++n;
    }
    if (n == 0) return Vec{{0, 0, 0}};
    return Vec{{sum[0] / n - p[0], sum[1] / n - p[1], sum[2] / n - p[2]}};
  }
};

template <typename Mesh, typename VPM>
class Spike_remover
{
  using GT = boost::graph_traits<Mesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Stats = Geometric_statistics<Mesh, VPM>;
  using Vmark =
      typename boost::property_map<Mesh, CGAL::dynamic_vertex_property_t<std::uint32_t>>::type;
  using Fmark =
      typename boost::property_map<Mesh, CGAL::dynamic_face_property_t<std::uint32_t>>::type;
  using Hmark =
      typename boost::property_map<Mesh, CGAL::dynamic_halfedge_property_t<std::uint32_t>>::type;

  Local_operations<Mesh, VPM>& ops_;
  Mesh& tm_;
  const Spike_settings& s_;
  Spike_removal_result& c_;  // the public counters, written in place
  Spike_detector<Mesh, VPM> det_;
  Vmark vmark_, alive_;
  Fmark fmark_;
  Hmark hmark_;
  std::uint32_t gen_ = 0;
  std::vector<vertex_descriptor> region_; // surviving vertices next to removed faces

public:
  // `ops` keeps `st` current (Local_operations::keep_current).
  Spike_remover(Local_operations<Mesh, VPM>& ops, const Stats& st, const Spike_settings& s,
                Spike_removal_result& c)
    : ops_(ops), tm_(ops.mesh()), s_(s), c_(c), det_(st, s),
      vmark_(get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), tm_)),
      alive_(get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), tm_)),
      fmark_(get(CGAL::dynamic_face_property_t<std::uint32_t>(), tm_)),
      hmark_(get(CGAL::dynamic_halfedge_property_t<std::uint32_t>(), tm_))
  {}

  void run(const std::vector<vertex_descriptor>& spiked)
  {
    c_.spiked_vertices_found = spiked.size();
    std::vector<vertex_descriptor> S = spiked;
    while (!S.empty() && c_.rounds < s_.max_removal_rounds) {
      ++c_.rounds;
      std::vector<face_descriptor> F;
      const std::uint32_t g = ++gen_;
      for (vertex_descriptor v : S)
        for (halfedge_descriptor h : CGAL::halfedges_around_target(v, tm_)) {
          face_descriptor f = face(h, tm_);
          if (f != GT::null_face() && get(fmark_, f) != g) {
            put(fmark_, f, g);
            F.push_back(f);
          }
        }
      c_.faces_removed += F.size();
      remove_faces(F);
      // vertices still spiked next to the removal (new border vertices only)
      S.clear();
      for (vertex_descriptor v : live_region())
        if (det_.spiked(v)) S.push_back(v);
    }
    count_loops();
  }

  std::vector<vertex_descriptor> live_region()
  {
    std::vector<vertex_descriptor> out;
    const std::uint32_t g = ++gen_;
    for (vertex_descriptor v : region_) // only the mark is read for removed vertices
      if (get(alive_, v) == 1 && get(vmark_, v) != g) {
        put(vmark_, v, g);
        out.push_back(v);
      }
    region_ = out;
    return out;
  }

private:
  // Removes the faces F and, where a vertex would be pinched (two fans), its
  // smaller fans (counted as dangling faces).
  void remove_faces(std::vector<face_descriptor>& F)
  {
    std::vector<vertex_descriptor> survivors, gone;
    const std::size_t asked = F.size();
    const std::size_t pinches = ops_.counts().pinches_resolved;
    ops_.remove_faces_without_pinches(F, &survivors, &gone);
    c_.dangling_faces_removed += F.size() - asked;
    c_.pinched_vertices_fixed += ops_.counts().pinches_resolved - pinches;
    c_.vertices_removed += gone.size();
    // only the mark of a removed vertex is read from now on
    for (vertex_descriptor x : gone) put(alive_, x, 0u);
    for (vertex_descriptor x : survivors) put(alive_, x, 1u);
    region_.insert(region_.end(), survivors.begin(), survivors.end());
  }

  void count_loops()
  {
    const std::uint32_t g = ++gen_;
    for (vertex_descriptor v : live_region())
      for (halfedge_descriptor h : CGAL::halfedges_around_target(v, tm_)) {
        if (!is_border(h, tm_) || get(hmark_, h) == g) continue;
        ++c_.boundary_loops;
        for (halfedge_descriptor b : CGAL::halfedges_around_face(h, tm_)) put(hmark_, b, g);
      }
  }
};

// The workers behind relax_spikes() and remove_unrelaxable_spikes(): `ops`
// keeps `st` current (Local_operations::keep_current); `vis` gives progress
// and cancellation. The public faces read the settings and check the input.
template <typename Mesh, typename VPM, typename VisitorHandle>
Spike_relaxation_result relax_spikes_with(Local_operations<Mesh, VPM>& ops,
                                          Geometric_statistics<Mesh, VPM>& st,
                                          const Spike_settings& s, VisitorHandle& vis,
                                          Spike_tracker<Mesh, VPM>* tracker = nullptr)
{
  Spike_relaxation_result r;
  auto S = find_spiked(st, tracker, s, &r.spiked_by_height_before);
  r.spiked_vertices_before = S.size();
  std::size_t in_region_before = 0;
  bool cancelled = false;
  if (!S.empty()) {
    Spike_relaxer<Mesh, VPM, VisitorHandle> worker(ops, st, vis, s, r);
    worker.run(std::move(S));
    in_region_before = worker.spiked_in_region_before();
    cancelled = worker.cancelled();
  }
  // Only the working region changed: moved vertices are within 1 ring of S, and
  // a vertex's spike status depends on its 1-ring, so with n >= 2 rings every
  // vertex whose status can change lies in W; otherwise count everything again.
  if (s.rings >= 2)
    r.spiked_vertices_after = r.spiked_vertices_before - in_region_before + r.spiked_in_region_after;
  else
    r.spiked_vertices_after = find_spiked(st, tracker, s).size();
  if (cancelled) {
    r.status = Status::cancelled;
    r.message = "cancelled by the visitor";
  } else if (r.spiked_in_region_after > 0) {
    r.status = Status::partial;
    r.message = "unrelaxable spikes left (see remove_unrelaxable_spikes)";
  }
  vis.progress(1.0);
  return r;
}

template <typename Mesh, typename VPM, typename VisitorHandle>
Spike_removal_result remove_unrelaxable_spikes_with(Local_operations<Mesh, VPM>& ops,
                                                    Geometric_statistics<Mesh, VPM>& st,
                                                    const Spike_settings& s, VisitorHandle& vis,
                                                    Spike_tracker<Mesh, VPM>* tracker = nullptr)
{
  Spike_removal_result r;
  if (vis.stop_requested()) {
    r.status = Status::cancelled;
    r.message = "cancelled by the visitor";
    return r;
  }
  auto S = find_spiked(st, tracker, s);
  if (!S.empty()) {
    Spike_remover<Mesh, VPM> worker(ops, st, s, r);
    worker.run(S);
  }
  r.spiked_vertices_found = S.size();
  r.spiked_vertices_after = find_spiked(st, tracker, s).size();
  if (r.spiked_vertices_after > 0) r.status = Status::partial;
  vis.progress(1.0);
  return r;
}

// ---- Settings: read once from the named parameters of the public call or
// of the pipeline, which forwards its own.
template <typename NP>
bool read_spike_settings(const NP& np, Spike_settings& s, std::string& message)
{
  const double angle = get_or<double>(np, internal_np::spike_angle, defaults::spike_angle);
  const double a = get_or<double>(np, internal_np::relax_start_angle, angle / 2);
  const double b = get_or<double>(np, internal_np::relax_full_angle, angle);
  s.height_factor = get_or<double>(np, internal_np::spike_height_factor, default_spike_height_factor);
  s.rings = get_or<std::size_t>(np, internal_np::relax_rings, defaults::relax_rings);
  s.max_iterations = get_or<std::size_t>(np, internal_np::max_relax_iterations, defaults::max_relax_iterations);
  s.max_removal_rounds =
      get_or<std::size_t>(np, internal_np::max_spike_removal_rounds, defaults::max_spike_removal_rounds);
  if (!(angle >= 0 && angle <= 180) || !(a >= 0 && a <= 180) || !(b >= 0 && b <= 180) ||
      !std::isfinite(s.height_factor)) {
    message = "spike_angle, relax_start_angle, relax_full_angle in [0,180]; finite spike_height_factor";
    return false;
  }
  s.spike_angle = to_radians(angle);
  s.start_angle = to_radians(a);
  s.full_angle = to_radians(b);
  return true;
}

// Both spike calls on given statistics: phase, settings, then `worker` on
// local operations that keep `stats` current.
template <typename Result, typename Mesh, typename VPM, typename NP, typename Worker>
Result run_spike_call(Mesh& tm, Geometric_statistics<Mesh, VPM>& stats, const NP& np,
                      const char* phase_name, Worker&& worker)
{
  Visitor_handle<NP> vis(np);
  Phase_scope<Visitor_handle<NP>> phase(vis, phase_name);
  Spike_settings s;
  Result r;
  if (!read_spike_settings(np, s, r.message)) {
    r.status = Status::invalid_parameter;
    return r;
  }
  Local_operations<Mesh, VPM> ops(tm, stats.vertex_point_map());
  ops.keep_current(&stats);
  return worker(ops, stats, s, vis);
}

} // namespace clean_pipeline
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKES_H
