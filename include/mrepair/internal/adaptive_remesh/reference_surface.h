// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The input surface kept for back-projection: a triangle soup with an AABB
// tree, the input feature/boundary polylines as segments with their own tree,
// and the sizing field (target edge length per input vertex).
#ifndef MREPAIR_INTERNAL_ADAPTIVE_REMESH_REFERENCE_SURFACE_H
#define MREPAIR_INTERNAL_ADAPTIVE_REMESH_REFERENCE_SURFACE_H

#include <mrepair/internal/cgal_compat.h>
#include <mrepair/internal/utility.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <atomic>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {
namespace remesh {

// Positions are `Vec3` (internal/utility.h), as everywhere in the library.

class Reference_surface
{
  using K = CGAL::Epick;
  using Tri_vec = std::vector<K::Triangle_3>;
  using Seg_vec = std::vector<K::Segment_3>;
  using Tri_prim = Aabb_triangle_primitive<K, Tri_vec::const_iterator>;
  using Seg_prim = Aabb_segment_primitive<K, Seg_vec::const_iterator>;
  using Tri_tree = Aabb_tree<K, Tri_prim>;
  using Seg_tree = Aabb_tree<K, Seg_prim>;

  mutable Tri_vec tri_geo_;  // made with the tree (triangle_tree())
  Seg_vec seg_geo_;
  mutable std::vector<int> tri_of_prim_, prim_of_tri_;  // tree primitive <-> triangle index
  std::vector<int> seg_of_prim_, prim_of_seg_;
  // The triangle tree is only the fallback of the local descent (a vertex
  // that moved farther than its target length), which most runs never take:
  // it is built on first use (a third of the setup at 1M faces).
  std::size_t large_triangles_ = 0;  // triangles that go into the tree
  mutable std::unique_ptr<Tri_tree> tri_tree_;
  mutable std::atomic<bool> tri_tree_ready_{false};
  mutable std::mutex tri_tree_mutex_;
  std::unique_ptr<Seg_tree> seg_tree_;
  bool walk_edges_ = false;

  static K::Point_3 kp(const Vec3& p) { return K::Point_3(p[0], p[1], p[2]); }
  static Vec3 vp(const K::Point_3& p) { return to_vec3(p); }

public:
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 2>> segments;  // feature and boundary edges
  std::vector<char> on_line;                 // point lies on a segment (or is frozen)
  std::vector<double> sizing;                // target edge length per point
  int smoothing_passes = 3;                  // of the curvature before sizing

  std::vector<int> star_begin, star;  // triangles around each point (CSR)
  std::vector<std::array<int, 3>> neighbour;  // triangle across edge (t[k], t[k+1]), or -1

  /// The projection walks across edges (the uniform remesher: its vertices
  /// stay within a fraction of an input edge of the input) instead of
  /// descending through whole vertex stars. The adaptive modes keep the
  /// descent: their coarse faces sample points many input edges off the
  /// input, and their measured distances on armadillo (test_remesh) are the
  /// descent's. Call after build(), not during projections.
  void set_walk_edges(bool on)
  {
    walk_edges_ = on;
    if (!on || neighbour.size() == triangles.size()) return;
    // the triangle across each edge: -1 on a boundary edge and on an edge
    // that more than two triangles share (the walk then reads vertex stars)
    neighbour.assign(triangles.size(), {-1, -1, -1});
    parallel_for_index(neighbour.size(), 4096, [&](std::size_t i) {
      const auto& t = triangles[i];
      for (int k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        int across = -1, found = 0;
        for (int j = star_begin[a]; j < star_begin[a + 1]; ++j) {
          const int o = star[j];
          if (o == int(i)) continue;
          const auto& to = triangles[o];
          if (to[0] == b || to[1] == b || to[2] == b) { across = o; ++found; }
        }
        neighbour[i][k] = found == 1 ? across : -1;
      }
    });
  }

  /// builds both trees and the vertex stars; call once after filling
  /// points/triangles/segments.
  void build()
  {
    star_begin.assign(points.size() + 1, 0);
    for (const auto& t : triangles)
      for (int k = 0; k < 3; ++k) ++star_begin[t[k] + 1];
    for (std::size_t i = 0; i < points.size(); ++i) star_begin[i + 1] += star_begin[i];
    star.assign(star_begin.back(), 0);
    {
      std::vector<int> fill(star_begin.begin(), star_begin.end() - 1);
      for (std::size_t i = 0; i < triangles.size(); ++i)
        for (int k = 0; k < 3; ++k) star[fill[triangles[i][k]]++] = static_cast<int>(i);
    }
    neighbour.clear();
    walk_edges_ = false;
    // the tiny triangles and segments stay out of the trees (see is_large)
    std::vector<char> large(triangles.size());
    parallel_for_index(triangles.size(), 4096, [&](std::size_t i) { large[i] = is_large(i); });
    large_triangles_ = static_cast<std::size_t>(std::count(large.begin(), large.end(), char(1)));
    // the tree's primitives are made with the tree, when a projection first
    // needs it: most runs never do (every vertex has a hint), and 1M
    // Triangle_3 are 72 MB to fill
    tri_geo_.clear();
    tri_of_prim_.clear();
    prim_of_tri_.clear();
    seg_geo_.clear();
    seg_of_prim_.clear();
    prim_of_seg_.assign(segments.size(), -1);
    for (std::size_t i = 0; i < segments.size(); ++i) {
      const auto& sg = segments[i];
      if (!(squared_norm(points[sg[1]] - points[sg[0]]) > tiny)) continue;
      prim_of_seg_[i] = static_cast<int>(seg_geo_.size());
      seg_of_prim_.push_back(static_cast<int>(i));
      seg_geo_.emplace_back(kp(points[sg[0]]), kp(points[sg[1]]));
    }
    tri_tree_.reset();
    tri_tree_ready_.store(false);
    seg_tree_.reset();
    if (!seg_geo_.empty()) {
      seg_tree_.reset(new Seg_tree(seg_geo_.cbegin(), seg_geo_.cend()));
      seg_tree_->build();
      seg_tree_->accelerate_distance_queries();
    }
  }

  bool has_surface() const { return large_triangles_ > 0; }

  // Triangles and segments so small that the trees' closest-point
  // constructions would divide underflowed squares (|n|^2 below ~1e-290:
  // edges under ~1e-72) are left out of the trees: they produced NaN, which
  // the exact fallback of the distance comparison turned into SIGFPE. Their
  // points lie on their neighbours, and the local descent still visits them.
  static constexpr double tiny = 1e-290;
  bool is_large(std::size_t i) const
  {
    const auto& t = triangles[i];
    return squared_norm(triangle_normal(points[t[0]], points[t[1]], points[t[2]])) > tiny;
  }

  // thread-safe: relaxation projects in parallel
  const Tri_tree& triangle_tree() const
  {
    if (!tri_tree_ready_.load(std::memory_order_acquire)) {
      std::lock_guard<std::mutex> lock(tri_tree_mutex_);
      if (!tri_tree_ready_.load(std::memory_order_relaxed)) {
        prim_of_tri_.assign(triangles.size(), -1);
        tri_geo_.reserve(large_triangles_);
        for (std::size_t i = 0; i < triangles.size(); ++i) {
          if (!is_large(i)) continue;
          const auto& t = triangles[i];
          prim_of_tri_[i] = static_cast<int>(tri_geo_.size());
          tri_of_prim_.push_back(static_cast<int>(i));
          tri_geo_.emplace_back(kp(points[t[0]]), kp(points[t[1]]), kp(points[t[2]]));
        }
        tri_tree_.reset(new Tri_tree(tri_geo_.cbegin(), tri_geo_.cend()));
        tri_tree_->build();
        tri_tree_->accelerate_distance_queries();
        tri_tree_ready_.store(true, std::memory_order_release);
      }
    }
    return *tri_tree_;
  }
  bool has_lines() const { return seg_tree_ != nullptr; }

  /// closest point of the input surface to `q`; `size` gets the sizing field there.
  // closest point of triangle (a, b, c) to p with its barycentric coordinates
  // (Ericson, Real-Time Collision Detection, 5.1.5)
  static Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                                  double& u, double& v, double& w)
  {
    Vec3 ab = b - a, ac = c - a, ap = p - a;
    double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) { u = 1; v = w = 0; return a; }
    Vec3 bp = p - b;
    double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) { v = 1; u = w = 0; return b; }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      double t = d1 / (d1 - d3);
      u = 1 - t; v = t; w = 0;
      return a + t * ab;
    }
    Vec3 cp = p - c;
    double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) { w = 1; u = v = 0; return c; }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      double t = d2 / (d2 - d6);
      u = 1 - t; v = 0; w = t;
      return a + t * ac;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
      double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      u = 0; v = 1 - t; w = t;
      return b + t * (c - b);
    }
    double den = va + vb + vc;
    if (!(den > 0)) { u = 1; v = w = 0; return a; }  // degenerate triangle
    v = vb / den;
    w = vc / den;
    u = 1 - v - w;
    return a + v * ab + w * ac;
  }

  /// where a local search from a triangle ended; `converged` false when it
  /// ran out of steps (then it is no minimum)
  struct Local_closest
  {
    int t = -1;
    double d = std::numeric_limits<double>::infinity(), u = 0, v = 0, w = 0;
    Vec3 p{};
    bool converged = false;
  };

  /// closest point to `q` found locally from triangle `hint`, by the walk
  /// (set_walk_edges) or the descent through vertex stars (vertices move a
  /// fraction of an edge per iteration, so both are local); falls back to
  /// the AABB tree when there is no hint, the search ran out of steps, or its
  /// answer is farther than `max_dist`.
  Vec3 project_surface(const Vec3& q, double& size, int& hint, double max_dist) const
  {
    if (hint >= 0 && hint < int(triangles.size())) {
      // A search that ran out of steps is no minimum (a sample of a coarse
      // face many input edges from its hint, on a fine input): its point
      // overstated the face's deviation, and the error control refined a
      // 1M-face scan at 0.002 x diagonal to 17,456 faces within 0.18 x the
      // tolerance. The tree answers instead.
      const Local_closest c = walk_edges_ ? walk(q, hint) : descend(q, hint);
      if (c.converged && c.t >= 0 && c.d <= max_dist * max_dist) {
        hint = c.t;
        const auto& t = triangles[c.t];
        size = c.u * sizing[t[0]] + c.v * sizing[t[1]] + c.w * sizing[t[2]];
        return c.p;
      }
    }
    return project_surface_tree(q, size, hint);
  }

  /// A walk from `hint` to a triangle none of whose neighbours is closer:
  /// across the edges of the current triangle, and through the stars of its
  /// corners when the closest point lies on its edge or corner (a corner
  /// joins triangles that share no edge with it). 4 evaluations where the
  /// closest point lies inside a triangle, against ~25 for the descent.
  Local_closest walk(const Vec3& q, int hint) const
  {
    auto evaluate = [&](int t) {
      const auto& tr = triangles[t];
      Local_closest b;
      b.t = t;
      b.p = closest_on_triangle(q, points[tr[0]], points[tr[1]], points[tr[2]], b.u, b.v, b.w);
      b.d = squared_norm(b.p - q);
      return b;
    };
    Local_closest best = evaluate(hint);
    for (int step = 0; step < 64; ++step) {
      const int from = best.t;
      const auto& tr = triangles[from];
      const auto& nb = neighbour[from];
      auto consider = [&](int t) {
        if (t < 0 || t == from) return;
        const Local_closest b = evaluate(t);
        if (b.d < best.d) best = b;
      };
      for (int k = 0; k < 3; ++k) consider(nb[k]);
      if (best.t != from) continue;
      // the closest point on an edge or at a corner: a triangle that shares
      // only that corner (or a corner of that edge) can be closer, where the
      // surface folds towards the point (the edge may have no single neighbour too)
      const double bc[3] = {best.u, best.v, best.w};
      if (!(bc[0] > 0. && bc[1] > 0. && bc[2] > 0.))
        for (int k = 0; k < 3; ++k) {
          if (!(bc[k] > 0.)) continue;
          const int pv = tr[k];
          for (int j = star_begin[pv]; j < star_begin[pv + 1]; ++j) consider(star[j]);
        }
      if (best.t == from) { best.converged = true; break; }
    }
    return best;
  }

  /// descent from `hint` through the vertex stars of the current best triangle
  Local_closest descend(const Vec3& q, int hint) const
  {
    Local_closest best;
    int cur = hint;
    // Points whose star has been evaluated: a triangle with such a corner
    // was evaluated already, and evaluating it again never changes the
    // strict minimum (neighbouring stars overlap in most of their triangles).
    int done[48];
    int ndone = 0;
    auto is_done = [&](int p) {
      for (int i = 0; i < ndone; ++i)
        if (done[i] == p) return true;
      return false;
    };
    for (int step = 0; step < 16; ++step) {
      const int before = best.t;
      for (int k = 0; k < 3; ++k) {
        const int pv = triangles[cur][k];
        if (is_done(pv)) continue;
        for (int j = star_begin[pv]; j < star_begin[pv + 1]; ++j) {
          const int t = star[j];
          const auto& tr = triangles[t];
          if (is_done(tr[0]) || is_done(tr[1]) || is_done(tr[2])) continue;
          double u, v, w;
          const Vec3 p = closest_on_triangle(q, points[tr[0]], points[tr[1]], points[tr[2]], u, v, w);
          const double d = squared_norm(p - q);
          if (d < best.d) { best.d = d; best.t = t; best.p = p; best.u = u; best.v = v; best.w = w; }
        }
        if (ndone < 48) done[ndone++] = pv;  // when full, stars are evaluated again
      }
      if (best.t == before) { best.converged = true; break; }
      cur = best.t;
    }
    return best;
  }

  /// closest point by the AABB tree; `hint` gets the triangle found.
  Vec3 project_surface_tree(const Vec3& q, double& size, int& hint) const
  {
    const Tri_tree& tree = triangle_tree();  // makes prim_of_tri_ too
    const int ph = hint >= 0 && hint < int(triangles.size()) ? prim_of_tri_[hint] : -1;
    auto pp = ph >= 0 ? tree.closest_point_and_primitive(
                            kp(q), std::make_pair(tri_geo_[ph].vertex(0), tri_geo_.cbegin() + ph))
                      : tree.closest_point_and_primitive(kp(q));
    std::size_t i = static_cast<std::size_t>(tri_of_prim_[pp.second - tri_geo_.cbegin()]);
    hint = static_cast<int>(i);
    Vec3 p = vp(pp.first);
    const auto& t = triangles[i];
    // barycentric coordinates of p in the triangle (clamped: p lies on it)
    const Vec3 &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
    Vec3 v0 = b - a, v1 = c - a, v2 = p - a;
    double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0),
           d21 = dot(v2, v1);
    double den = d00 * d11 - d01 * d01;
    double u = 1. / 3, v = 1. / 3, w = 1. / 3;
    if (den > 0) {
      v = std::clamp((d11 * d20 - d01 * d21) / den, 0., 1.);
      w = std::clamp((d00 * d21 - d01 * d20) / den, 0., 1.);
      u = std::max(0., 1. - v - w);
      double s = u + v + w;
      u /= s; v /= s; w /= s;
    }
    size = u * sizing[t[0]] + v * sizing[t[1]] + w * sizing[t[2]];
    return p;
  }

  /// closest point of the input feature/boundary polylines to `q`.
  Vec3 project_line(const Vec3& q, double& size, int& hint) const
  {
    const int ph = hint >= 0 && hint < int(segments.size()) ? prim_of_seg_[hint] : -1;
    auto pp = ph >= 0 ? seg_tree_->closest_point_and_primitive(
                            kp(q), std::make_pair(seg_geo_[ph].source(), seg_geo_.cbegin() + ph))
                      : seg_tree_->closest_point_and_primitive(kp(q));
    std::size_t i = static_cast<std::size_t>(seg_of_prim_[pp.second - seg_geo_.cbegin()]);
    hint = static_cast<int>(i);
    Vec3 p = vp(pp.first);
    const auto& s = segments[i];
    Vec3 d = points[s[1]] - points[s[0]];
    double l2 = squared_norm(d);
    double t = l2 > 0 ? std::clamp(dot(p - points[s[0]], d) / l2, 0., 1.) : 0.5;
    size = (1 - t) * sizing[s[0]] + t * sizing[s[1]];
    return p;
  }

  /// per point, the largest absolute principal curvature: the cotangent
  /// mean curvature H and the angle-deficit Gaussian curvature K, both over
  /// the barycentric area; kappa = |H| + sqrt(max(H^2 - K, 0)).
  std::vector<double> estimate_curvature() const
  {
    const std::size_t n = points.size();
    std::vector<Vec3> lap(n);
    std::vector<double> area(n, 0.), angle(n, 0.);
    for (const auto& t : triangles) {
      double a2 = norm(triangle_normal(points[t[0]], points[t[1]], points[t[2]]));
      if (!(a2 > 0)) continue;
      for (int k = 0; k < 3; ++k) {
        int i = t[k], j = t[(k + 1) % 3], l = t[(k + 2) % 3];
        Vec3 e1 = points[j] - points[i], e2 = points[l] - points[i];
        double c = dot(e1, e2);
        double s = norm(cross(e1, e2));
        angle[i] += std::atan2(s, c);
        area[i] += a2 / 6.;
        // the angle at i is opposite edge (j,l): cot weight for that edge
        double cot = std::clamp(c / s, -1e3, 1e3);
        lap[j] += cot * (points[l] - points[j]);
        lap[l] += cot * (points[j] - points[l]);
      }
    }
    std::vector<double> kappa(n, 0.);
    for (std::size_t i = 0; i < n; ++i) {
      if (!(area[i] > 0)) continue;
      double H = norm(lap[i]) / (4. * area[i]);  // |Delta p| / 2 with Delta p = lap / (2A)
      double K = (two_pi - angle[i]) / area[i];
      kappa[i] = std::abs(H) + std::sqrt(std::max(H * H - K, 0.));
    }
    return kappa;
  }

  /// curvature-based sizing (thesis 3.7): kappa per point (estimate_curvature),
  /// smoothed over the interior one-ring, rescaled by gamma, then
  /// L = sqrt(6 eps / kappa - 3 eps^2) clamped to [lmin, lmax]. Points on
  /// lines take the mean of their non-line neighbours. The error control of
  /// the remesher (Remesher::refine_deviating_faces) lowers it where the
  /// estimate was too optimistic.
  void compute_adaptive_sizing(double eps, double lmin, double lmax, double gamma)
  {
    if (curvature_.size() != points.size()) prepare_curvature();
    sizing_from_curvature(eps, lmin, lmax, gamma);
  }

  /// the smoothed curvature per point (once per reference surface)
  void prepare_curvature()
  {
    const std::size_t n = points.size();
    std::vector<double> kappa = estimate_curvature();
    // smoothing passes over the interior one-ring (line points excluded):
    // the estimate is noisy on scans (thesis 5, Vorsatz et al. 2001)
    std::vector<double> sum(n, 0.), cnt(n, 0.);
    for (int pass = 0; pass < smoothing_passes; ++pass) {
      std::fill(sum.begin(), sum.end(), 0.);
      std::fill(cnt.begin(), cnt.end(), 0.);
      for (const auto& t : triangles)
        for (int k = 0; k < 3; ++k) {
          int i = t[k], j = t[(k + 1) % 3];
          if (!on_line[j]) { sum[i] += kappa[j]; cnt[i] += 1; }
          if (!on_line[i]) { sum[j] += kappa[i]; cnt[j] += 1; }
        }
      for (std::size_t i = 0; i < n; ++i)
        if (!on_line[i] && cnt[i] > 0) kappa[i] = 0.5 * kappa[i] + 0.5 * sum[i] / cnt[i];
    }
    curvature_ = std::move(kappa);
  }

  /// sizing from the prepared curvature for tolerance `eps`
  void sizing_from_curvature(double eps, double lmin, double lmax, double gamma)
  {
    const std::size_t n = points.size();
    const std::vector<double>& kappa = curvature_;
    std::vector<double> sum(n, 0.), cnt(n, 0.);
    double kmax = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (!on_line[i] && std::isfinite(kappa[i])) kmax = std::max(kmax, kappa[i]);
    sizing.assign(n, lmax);
    for (std::size_t i = 0; i < n; ++i) {
      double k = kappa[i];
      if (!std::isfinite(k)) k = kmax;
      if (gamma != 1. && kmax > 0) k = std::pow(k / kmax, gamma) * kmax;
      double L = lmax;
      if (k > 0) {
        double q = 6. * eps / k - 3. * eps * eps;
        L = q > 0 ? std::sqrt(q) : lmin;
      }
      sizing[i] = std::clamp(L, lmin, lmax);
    }
    // line points: mean of their non-line neighbours
    std::fill(sum.begin(), sum.end(), 0.);
    std::fill(cnt.begin(), cnt.end(), 0.);
    for (const auto& t : triangles)
      for (int k = 0; k < 3; ++k) {
        int i = t[k], j = t[(k + 1) % 3];
        if (on_line[i] && !on_line[j]) { sum[i] += sizing[j]; cnt[i] += 1; }
        if (on_line[j] && !on_line[i]) { sum[j] += sizing[i]; cnt[j] += 1; }
      }
    // curvature on a line is the feature's, not the surface's: a line point
    // without interior neighbours (a coarse CAD face) gets the largest length
    for (std::size_t i = 0; i < n; ++i)
      if (on_line[i]) sizing[i] = cnt[i] > 0 ? sum[i] / cnt[i] : lmax;
  }

  /// faces of an equilateral mesh following the sizing (area over the area
  /// of the equilateral triangle of the mean corner length, per triangle)
  double predicted_faces() const
  {
    double f = 0;
    for (const auto& t : triangles) {
      const double a = 0.5 * norm(triangle_normal(points[t[0]], points[t[1]], points[t[2]]));
      const double L = (sizing[t[0]] + sizing[t[1]] + sizing[t[2]]) / 3.;
      if (a > 0 && L > 0) f += a / (0.25 * std::sqrt(3.) * L * L);
    }
    return f;
  }

  /// lowers the sizing to at most `L` at the points within `radius` of `centre`,
  /// found by a walk over the triangles from triangle `hint` (bounded: a few
  /// thousand triangles); returns the points lowered.
  std::size_t lower_sizing_near(const Vec3& centre, double radius, int hint, double L)
  {
    if (hint < 0 || hint >= int(triangles.size())) return 0;
    if (visit_stamp_.size() != triangles.size()) visit_stamp_.assign(triangles.size(), 0u);
    if (++stamp_ == 0) {
      std::fill(visit_stamp_.begin(), visit_stamp_.end(), 0u);
      stamp_ = 1;
    }
    const double r2 = radius * radius;
    std::size_t lowered = 0;
    walk_.clear();
    walk_.push_back(hint);
    visit_stamp_[hint] = stamp_;
    for (std::size_t w = 0; w < walk_.size() && w < 4096; ++w) {
      const auto& t = triangles[walk_[w]];
      for (int k = 0; k < 3; ++k) {
        const int p = t[k];
        // the corners of the start triangle always: the sizing there is read at the face
        if (w > 0 && squared_norm(points[p] - centre) > r2) continue;
        if (sizing[p] > L) { sizing[p] = L; ++lowered; }
        for (int j = star_begin[p]; j < star_begin[p + 1]; ++j)
          if (visit_stamp_[star[j]] != stamp_) {
            visit_stamp_[star[j]] = stamp_;
            walk_.push_back(star[j]);
          }
      }
    }
    return lowered;
  }

private:
  std::vector<double> curvature_;
  std::vector<unsigned> visit_stamp_;
  std::vector<int> walk_;
  unsigned stamp_ = 0;
};

} // namespace remesh
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_ADAPTIVE_REMESH_REFERENCE_SURFACE_H
