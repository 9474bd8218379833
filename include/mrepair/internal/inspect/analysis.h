// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_INSPECT_ANALYSIS_H
#define MREPAIR_INTERNAL_INSPECT_ANALYSIS_H

#include <mrepair/defect_locations.h>
#include <mrepair/definitions.h>
#include <mrepair/inspection_report.h>
#include <mrepair/internal/inspect/parallel.h>
#include <mrepair/internal/inspect/self_intersections.h>
#include <mrepair/internal/inspect/surface_arrays.h>
#include <mrepair/internal/clean_scan_mesh/spike_criterion.h>
#include <mrepair/internal/cgal_compat.h>
#include <mrepair/internal/utility.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#ifdef MREPAIR_INSPECT_VERBOSE
#include <CGAL/Real_timer.h>
#include <iostream>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace mrepair {
namespace internal {

// Thresholds of the inspection, defaults resolved (see inspect.h).
struct Inspect_thresholds
{
  double spike_angle = defaults::spike_angle;
  double spike_height_factor = default_spike_height_factor;
  double zero_edge_factor = defaults::zero_edge_factor;
  double skinny_edge_factor = defaults::skinny_edge_factor;
  double skinny_angle = defaults::skinny_angle;  // degrees
  double small_angle = 30.0;
  std::size_t max_hole_vertices = defaults::max_hole_vertices;
  std::size_t min_component_faces = defaults::min_component_faces;
  double t_junction_tolerance = -1;        // < 0: relative default
  double t_junction_relative = 1e-4;       // x bounding-box diagonal
};

// Does all the counting that soups and meshes share, on flattened arrays.
// The caller supplies border cycle lengths for meshes (halfedge cycles);
// for soups (`border_cycles == nullptr`) loops are the connected components
// of the graph of boundary edges.
//
// With a location sink (`set_sink()`), each count also lists its instances
// where it counts them (locate_defects.h), so that a count and its list
// cannot disagree; without one, nothing is listed and the passes are those
// of the counts alone (a null test per instance counted).
class Surface_analysis
{
  using K = CGAL::Epick;
  const Surface_arrays& a_;
  const Inspect_thresholds& t_;
  Inspection_report& r_;

  std::vector<double> normal_;         // 3 per face, zero when not computable
  std::vector<unsigned char> face_ok_; // all vertices finite
  std::vector<unsigned char> repeated_;
  std::vector<unsigned char> collinear_;
  // per corner: is_skinny_angle (triangles only): all the near-degenerate
  // test reads of the angles, 1 byte instead of a double
  // (240 MB at 10M faces, alive at the inspection's memory peak)
  std::vector<unsigned char> skinny_corner_;
  std::vector<double> edge_len_;       // NaN when an endpoint is not finite
  std::vector<double> vertex_mean_len_;
  std::vector<Inspect_index> valence_;
  std::vector<unsigned char> not_interior_, boundary_vertex_, spiked_, referenced_;
  double bbox_diag_ = 0;
  Defect_locations* sink_ = nullptr;
  // mesh border cycles as vertex lists (with a sink), from build_mesh_arrays
  const std::vector<std::vector<Inspect_index>>* cycle_vertices_ = nullptr;

public:
  std::size_t non_finite_referenced = 0;

  // lists the instances of each counted defect into `sink` (its `report` is
  // not touched: the counts go to the report given to the constructor).
  // For meshes, `cycle_vertices` are the border cycles' vertices, in the
  // order of the cycle lengths given to run().
  void set_sink(Defect_locations* sink, const std::vector<std::vector<Inspect_index>>* cycle_vertices = nullptr)
  {
    sink_ = sink;
    cycle_vertices_ = cycle_vertices;
  }

  Surface_analysis(const Surface_arrays& a, const Inspect_thresholds& t, Inspection_report& r)
    : a_(a), t_(t), r_(r)
  {}

  void run(const std::vector<std::size_t>* border_cycles)
  {
    r_.vertices = a_.num_vertices;
    r_.faces = a_.num_faces();
    r_.edges = a_.num_edges();
#ifdef MREPAIR_INSPECT_VERBOSE
    CGAL::Real_timer timer;
    timer.start();
#define MREPAIR_INSPECT_STEP(f)                                                   \
  f;                                                                              \
  std::cerr << "  " #f ": " << timer.time() << " s\n";                          \
  timer.reset();
#else
#define MREPAIR_INSPECT_STEP(f) f;
#endif
    MREPAIR_INSPECT_STEP(vertex_pass())
    MREPAIR_INSPECT_STEP(duplicate_points())
    MREPAIR_INSPECT_STEP(face_pass())
    MREPAIR_INSPECT_STEP(duplicate_faces())
    MREPAIR_INSPECT_STEP(edge_pass())
    free_memory(normal_);  // read by the edge pass only; the peak is in the next step
    MREPAIR_INSPECT_STEP(vertex_accumulation())
    free_memory(edge_dihedral_);
    MREPAIR_INSPECT_STEP(near_degenerate())
    MREPAIR_INSPECT_STEP(components())
    MREPAIR_INSPECT_STEP(non_manifold_vertices())
    if (border_cycles) {
      MREPAIR_INSPECT_STEP(count_loops(*border_cycles))
    } else {
      MREPAIR_INSPECT_STEP(soup_loops())
    }
    MREPAIR_INSPECT_STEP(t_junctions())
    MREPAIR_INSPECT_STEP(valence_and_closedness())
#undef MREPAIR_INSPECT_STEP
    release_per_element_arrays();
  }

  // The corners of each vertex, in corner order: built by the vertex pass,
  // kept after run() for certify_flat_stars(), then released.
  const std::vector<Inspect_index>& vertex_corner_first() const { return vertex_corner_first_; }
  const std::vector<Inspect_index>& vertex_corners() const { return vertex_corners_; }
  void release_vertex_corners() { free_memory(vertex_corner_first_, vertex_corners_); }

  // Self-intersecting pairs of distinct triangles (see self_intersections.h);
  // run after `run()`, only when every face is a triangle with finite corners.
  // With a sink, every pair is listed into it.
  Self_intersection_counts self_intersecting_pairs() const
  {
    const std::size_t nf = a_.num_faces();
    std::vector<unsigned char> eligible(nf);
    for (std::size_t f = 0; f < nf; ++f)
      eligible[f] = a_.degree(f) == 3 && face_ok_[f] && !repeated_[f] && !collinear_[f];
    Self_intersection_counts c = Self_intersection_counter(a_).count(eligible, false, sink_ != nullptr);
    if (sink_) {
      // in face order, whatever the threads did
      std::vector<std::size_t> order(c.listed.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return c.listed[x] < c.listed[y]; });
      for (std::size_t i : order) {
        sink_->self_intersecting_pairs.push_back({c.listed[i].first, c.listed[i].second});
        sink_->self_intersecting_pairs_touching.push_back(c.listed_touching[i]);
      }
      free_memory(c.listed, c.listed_touching);
    }
    return c;
  }

private:
  // The counts are in the report once run() is done; only the face flags of
  // self_intersecting_pairs() are read after it. The rest goes before the
  // self-intersection counter allocates its own (about 77 of the 395 MB of a
  // 1M-face repair's peak, which is at that count).
  void release_per_element_arrays()
  {
    free_memory(skinny_corner_, edge_len_, vertex_mean_len_, valence_, not_interior_, boundary_vertex_,
                spiked_, referenced_, non_manifold_vertex_);
  }

  // ---- vertices ---------------------------------------------------------------
  void vertex_pass()
  {
    const std::size_t nv = a_.num_vertices;
    referenced_.assign(nv, 0);
    for (Inspect_index v : a_.corner_v) referenced_[v] = 1;
    struct Acc
    {
      std::size_t non_finite = 0, non_finite_ref = 0, isolated = 0;
      double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity()};
      double hi[3] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                      -std::numeric_limits<double>::infinity()};
    };
    auto acc = chunked<Acc>(nv, [&](std::size_t b, std::size_t e, Acc& s) {
      for (std::size_t v = b; v < e; ++v) {
        if (!referenced_[v]) ++s.isolated;
        if (!a_.finite[v]) {
          ++s.non_finite;
          if (referenced_[v]) ++s.non_finite_ref;
          continue;
        }
        const double* p = a_.point(v);
        for (int i = 0; i < 3; ++i) {
          s.lo[i] = std::min(s.lo[i], p[i]);
          s.hi[i] = std::max(s.hi[i], p[i]);
        }
      }
    });
    Acc tot;
    for (const Acc& s : acc) {
      tot.non_finite += s.non_finite;
      tot.non_finite_ref += s.non_finite_ref;
      tot.isolated += s.isolated;
      for (int i = 0; i < 3; ++i) {
        tot.lo[i] = std::min(tot.lo[i], s.lo[i]);
        tot.hi[i] = std::max(tot.hi[i], s.hi[i]);
      }
    }
    r_.non_finite_vertices = tot.non_finite;
    r_.isolated_vertices = tot.isolated;
    non_finite_referenced = tot.non_finite_ref;
    double d2 = 0;
    if (tot.lo[0] <= tot.hi[0])
      for (int i = 0; i < 3; ++i) d2 += (tot.hi[i] - tot.lo[i]) * (tot.hi[i] - tot.lo[i]);
    bbox_diag_ = std::sqrt(d2);
  }

  static std::uint64_t bits(double x)
  {
    x += 0.0; // -0.0 and +0.0 are the same location
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
  }

  // Exactly coincident finite points: hash buckets (counting sort), then an
  // exact sort inside each bucket. Linear on average.
  void duplicate_points()
  {
    const std::size_t nv = a_.num_vertices;
    if (nv == 0) return;
    std::vector<Inspect_index> h(nv);
    parallel_for_index(nv, 16384, [&](std::size_t v) {
      if (!a_.finite[v]) {
        h[v] = inspect_npos;
        return;
      }
      const double* p = a_.point(v);
      std::uint64_t k = bits(p[0]) * 0x9E3779B97F4A7C15ull;
      k = (k ^ (k >> 29) ^ bits(p[1])) * 0xBF58476D1CE4E5B9ull;
      k = (k ^ (k >> 31) ^ bits(p[2])) * 0x94D049BB133111EBull;
      k ^= k >> 32;
      h[v] = static_cast<Inspect_index>(k % nv);
    });
    std::vector<Inspect_index> off, order;
    bucket_items(nv, nv, inspect_npos, [&](std::size_t v) { return h[v]; }, off, order);
    auto less = [&](Inspect_index x, Inspect_index y) {
      const double *p = a_.point(x), *q = a_.point(y);
      if (p[0] != q[0]) return p[0] < q[0];
      if (p[1] != q[1]) return p[1] < q[1];
      return p[2] < q[2];
    };
    auto acc = chunked<std::size_t>(nv, [&](std::size_t b, std::size_t e, std::size_t& dup) {
      for (std::size_t k = b; k < e; ++k) {
        auto first = order.begin() + off[k], last = order.begin() + off[k + 1];
        if (last - first < 2) continue;
        std::sort(first, last, less);
        for (auto it = first + 1; it != last; ++it)
          if (!less(*(it - 1), *it)) ++dup;
      }
    });
    for (std::size_t d : acc) r_.duplicate_points += d;
  }

  // ---- faces ------------------------------------------------------------------
  static bool all_collinear(const std::vector<K::Point_3>& p)
  {
    std::size_t j = 1;
    while (j < p.size() && p[j] == p[0]) ++j;
    if (j == p.size()) return true;
    for (std::size_t i = j + 1; i < p.size(); ++i)
      if (!CGAL::collinear(p[0], p[j], p[i])) return false;
    return true;
  }

  // the criterion of definitions.h; corner angles here are in degrees
  Near_degenerate_criterion near_degenerate_criterion() const
  {
    Near_degenerate_criterion crit;
    crit.zero_edge_factor = t_.zero_edge_factor;
    crit.skinny_edge_factor = t_.skinny_edge_factor;
    crit.skinny_angle = t_.skinny_angle;
    return crit;
  }

  // A threshold below 90 degrees on corner angles atan2(len, d), compared
  // through its tangent: below it when len < d tan(t). Within 1e-9 of the
  // threshold, and for non-finite or degenerate values, the angle itself
  // decides (atan2 once, kept in `angle`), so the answers are the atan2 ones;
  // most corners never need it (atan2 was a third of the face pass).
  struct Angle_threshold
  {
    double degrees = 0, tangent = 0;
    bool by_tangent = false;
    void set(double t)
    {
      degrees = t;
      by_tangent = t > 0 && t < 89;
      tangent = by_tangent ? std::tan(t / degrees_per_radian) : 0;
    }
    bool below(double len, double d, double& angle) const
    {
      if (by_tangent && len > 0 && std::isfinite(len) && std::isfinite(d)) {
        if (d <= 0) return false;  // 90 degrees or more
        const double x = d * tangent;
        if (len < x * (1 - 1e-9)) return true;
        if (len > x * (1 + 1e-9)) return false;
      }
      if (std::isnan(angle)) angle = std::atan2(len, d) * degrees_per_radian;
      return angle < degrees;
    }
  };

  void face_pass()
  {
    const Near_degenerate_criterion crit = near_degenerate_criterion();
    const std::size_t nf = a_.num_faces();
    normal_.assign(3 * nf, 0.0);
    face_ok_.assign(nf, 0);
    repeated_.assign(nf, 0);
    collinear_.assign(nf, 0);
    skinny_corner_.assign(a_.corner_v.size(), 0);
    struct Acc
    {
      std::size_t triangles = 0, repeated = 0, collinear = 0, angles = 0, small = 0;
      double min_angle = std::numeric_limits<double>::infinity(), area = 0, volume = 0;
    };
    Angle_threshold skinny_t, small_t;
    skinny_t.set(crit.skinny_angle);
    small_t.set(t_.small_angle);
    auto acc = chunked<Acc>(nf, [&](std::size_t b, std::size_t e, Acc& s) {
      std::vector<K::Point_3> poly;
      Angle_threshold min_t;  // the chunk's smallest angle so far
      min_t.set(s.min_angle);
      for (std::size_t f = b; f < e; ++f) {
        const std::size_t k = a_.degree(f), c0 = a_.face_off[f];
        const Inspect_index* v = &a_.corner_v[c0];
        if (k == 3) ++s.triangles;
        repeated_[f] = a_.face_skip[f] || has_repeated_index(v, k);
        if (repeated_[f]) ++s.repeated;
        bool ok = true;
        for (std::size_t i = 0; i < k; ++i) ok = ok && a_.finite[v[i]];
        face_ok_[f] = ok;
        if (!ok) continue;
        double* n = &normal_[3 * f];
        if (k == 3) {
          const double *p = a_.point(v[0]), *q = a_.point(v[1]), *w = a_.point(v[2]);
          const Vec3 vp = load_vec3(p), vq = load_vec3(q), vw = load_vec3(w);
          const Vec3 u0 = sub(vq, vp), u1 = sub(vw, vq), u2 = sub(vp, vw);
          const Vec3 nf = cross(u0, u1);
          std::copy(nf.begin(), nf.end(), n);
          const double len = norm(nf);
          s.area += 0.5 * len;
          // corner angle at a vertex: between the edge leaving it and the
          // reversed edge entering it; |cross| is 2 x area at every corner.
          const double d[3] = {-dot(u0, u2), -dot(u1, u0), -dot(u2, u1)};
          for (int i = 0; i < 3; ++i) {
            double ang = std::numeric_limits<double>::quiet_NaN();  // computed when needed
            skinny_corner_[c0 + i] = skinny_t.below(len, d[i], ang);
            if (small_t.below(len, d[i], ang)) ++s.small;
            if (min_t.below(len, d[i], ang)) {
              if (std::isnan(ang)) ang = std::atan2(len, d[i]) * degrees_per_radian;
              s.min_angle = std::min(s.min_angle, ang);
              min_t.set(s.min_angle);
            }
          }
          s.angles += 3;
          s.volume += dot(vp, cross(vq, vw)) / 6.0;
          if (!repeated_[f] &&
              CGAL::collinear(K::Point_3(p[0], p[1], p[2]), K::Point_3(q[0], q[1], q[2]),
                              K::Point_3(w[0], w[1], w[2]))) {
            ++s.collinear;
            collinear_[f] = 1;
          }
        } else {
          // Newell normal: twice the vector area of a (possibly non-planar) polygon
          const Vec3 p0 = load_vec3(a_.point(v[0]));
          Vec3 nf{{0, 0, 0}};
          for (std::size_t i = 0; i < k; ++i) {
            const Vec3 p = load_vec3(a_.point(v[i])), q = load_vec3(a_.point(v[(i + 1) % k]));
            nf += newell_term(p, q);
            if (i >= 1 && i + 1 < k) s.volume += dot(p0, cross(p, q)) / 6.0;
          }
          std::copy(nf.begin(), nf.end(), n);
          s.area += 0.5 * norm(nf);
          if (!repeated_[f]) {
            poly.clear();
            for (std::size_t i = 0; i < k; ++i) {
              const double* p = a_.point(v[i]);
              poly.emplace_back(p[0], p[1], p[2]);
            }
            if (all_collinear(poly)) {
              ++s.collinear;
              collinear_[f] = 1;
            }
          }
        }
      }
    });
    Acc tot;
    for (const Acc& s : acc) {
      tot.triangles += s.triangles;
      tot.repeated += s.repeated;
      tot.collinear += s.collinear;
      tot.angles += s.angles;
      tot.small += s.small;
      tot.min_angle = std::min(tot.min_angle, s.min_angle);
      tot.area += s.area;
      tot.volume += s.volume;
    }
    r_.triangles = tot.triangles;
    r_.repeated_index_faces = tot.repeated;
    r_.degenerate_faces = tot.repeated + tot.collinear;
    if (tot.angles > 0) {
      r_.min_angle = tot.min_angle;
      r_.small_angle_share = double(tot.small) / double(tot.angles);
    }
    r_.area = tot.area;
    volume_sum_ = tot.volume;
  }
  double volume_sum_ = 0;

  // Faces with the same vertex set as an earlier face: faces bucketed by their
  // smallest vertex, each bucket sorted by the sorted vertex list.
  void duplicate_faces()
  {
    const std::size_t nf = a_.num_faces(), nv = a_.num_vertices;
    if (nf < 2) return;
    std::vector<Inspect_index> sv(a_.corner_v);
    parallel_for_index(nf, 4096, [&](std::size_t f) {
      std::sort(sv.begin() + a_.face_off[f], sv.begin() + a_.face_off[f + 1]);
    });
    std::vector<Inspect_index> off, order;
    bucket_items(nf, nv, inspect_npos,
                 [&](std::size_t f) { return repeated_[f] ? inspect_npos : sv[a_.face_off[f]]; }, off, order);
    auto cmp = [&](Inspect_index x, Inspect_index y) -> int {
      std::size_t kx = a_.degree(x), ky = a_.degree(y);
      if (kx != ky) return kx < ky ? -1 : 1;
      for (std::size_t i = 0; i < kx; ++i) {
        Inspect_index p = sv[a_.face_off[x] + i], q = sv[a_.face_off[y] + i];
        if (p != q) return p < q ? -1 : 1;
      }
      return 0;
    };
    // cyclic orders of two faces with the same vertex set: +1 same, -1 reversed, 0 other
    auto orientation = [&](Inspect_index x, Inspect_index y) -> int {
      const std::size_t k = a_.degree(x);
      const Inspect_index *vx = &a_.corner_v[a_.face_off[x]], *vy = &a_.corner_v[a_.face_off[y]];
      std::size_t j = 0;
      while (vy[j] != vx[0]) ++j;
      bool same = true, rev = true;
      for (std::size_t i = 0; i < k; ++i) {
        same = same && vx[i] == vy[(j + i) % k];
        rev = rev && vx[i] == vy[(j + k - i) % k];
      }
      return same ? 1 : (rev ? -1 : 0);
    };
    struct Acc
    {
      std::size_t dup = 0, opposite = 0;
    };
    auto acc = chunked<Acc>(nv, [&](std::size_t b, std::size_t e, Acc& s) {
      for (std::size_t k = b; k < e; ++k) {
        auto first = order.begin() + off[k], last = order.begin() + off[k + 1];
        if (last - first < 2) continue;
        std::sort(first, last, [&](Inspect_index x, Inspect_index y) {
          int c = cmp(x, y);
          return c != 0 ? c < 0 : x < y;
        });
        auto run = first;
        for (auto it = first + 1; it != last; ++it) {
          if (cmp(*run, *it) != 0) {
            run = it;
            continue;
          }
          ++s.dup;
          if (orientation(*run, *it) < 0) ++s.opposite;
        }
      }
    });
    for (const Acc& s : acc) {
      r_.duplicate_faces += s.dup;
      r_.duplicate_faces_opposite += s.opposite;
    }
  }

  // ---- edges ------------------------------------------------------------------
  bool forward(std::size_t c, std::size_t e) const { return a_.corner_v[c] == a_.edge_v[2 * e]; }

  void edge_pass()
  {
    const std::size_t ne = a_.num_edges();
    edge_len_.assign(ne, std::numeric_limits<double>::quiet_NaN());
    edge_dihedral_.assign(ne, std::numeric_limits<double>::quiet_NaN());
    struct Acc
    {
      std::size_t boundary = 0, non_manifold = 0, inconsistent = 0, lengths = 0;
      double sum = 0, max_dihedral = -1;
      std::vector<Inspect_index> non_manifold_edges;  // with a sink
    };
    auto acc = chunked<Acc>(ne, [&](std::size_t b, std::size_t e_end, Acc& s) {
      for (std::size_t e = b; e < e_end; ++e) {
        const std::size_t nfe = a_.edge_off[e + 1] - a_.edge_off[e];
        const Inspect_index v0 = a_.edge_v[2 * e], v1 = a_.edge_v[2 * e + 1];
        if (nfe == 1) ++s.boundary;
        if (nfe > 2) {
          ++s.non_manifold;
          if (sink_) s.non_manifold_edges.push_back(static_cast<Inspect_index>(e));
        }
        if (a_.finite[v0] && a_.finite[v1]) {
          const double *p = a_.point(v0), *q = a_.point(v1);
          edge_len_[e] = distance(load_vec3(q), load_vec3(p));
          s.sum += edge_len_[e];
          ++s.lengths;
        }
        if (nfe != 2) continue;
        const Inspect_index c0 = a_.edge_corners[a_.edge_off[e]],
                            c1 = a_.edge_corners[a_.edge_off[e] + 1];
        const bool same_direction = forward(c0, e) == forward(c1, e);
        if (same_direction) ++s.inconsistent;
        const Inspect_index f0 = a_.corner_f[c0], f1 = a_.corner_f[c1];
        if (!face_ok_[f0] || !face_ok_[f1]) continue;
        const Vec3 n0 = load_vec3(&normal_[3 * f0]), n1 = load_vec3(&normal_[3 * f1]);
        // faces of inconsistent orientation: compare with one normal reversed,
        // so that the angle measures the fold of the surface, not the labels
        const double sg = same_direction ? -1.0 : 1.0;
        if (is_zero(n0) || is_zero(n1)) continue;
        const double ang = std::atan2(norm(cross(n0, n1)), sg * dot(n0, n1)) * degrees_per_radian;
        edge_dihedral_[e] = ang;
        s.max_dihedral = std::max(s.max_dihedral, ang);
      }
    });
    Acc tot;
    for (const Acc& s : acc) {
      tot.boundary += s.boundary;
      tot.non_manifold += s.non_manifold;
      tot.inconsistent += s.inconsistent;
      tot.lengths += s.lengths;
      tot.sum += s.sum;
      tot.max_dihedral = std::max(tot.max_dihedral, s.max_dihedral);
      if (sink_)
        for (Inspect_index e : s.non_manifold_edges)
          sink_->non_manifold_edges.push_back({a_.edge_v[2 * std::size_t(e)], a_.edge_v[2 * std::size_t(e) + 1]});
    }
    r_.boundary_edges = tot.boundary;
    r_.non_manifold_edges = tot.non_manifold;
    r_.inconsistent_orientation_edges = tot.inconsistent;
    if (tot.max_dihedral >= 0) r_.max_dihedral_angle = tot.max_dihedral;
    if (tot.lengths > 0) {
      const double mean = tot.sum / double(tot.lengths);
      r_.edge_length_mean = mean;
      auto var = chunked<double>(ne, [&](std::size_t b, std::size_t e_end, double& s) {
        for (std::size_t e = b; e < e_end; ++e)
          if (!std::isnan(edge_len_[e])) s += (edge_len_[e] - mean) * (edge_len_[e] - mean);
      });
      double v = 0;
      for (double x : var) v += x;
      r_.edge_length_stddev = std::sqrt(v / double(tot.lengths));
    }
  }
  std::vector<double> edge_dihedral_;

  void vertex_accumulation()
  {
    const std::size_t nv = a_.num_vertices, ne = a_.num_edges();
    valence_.assign(nv, 0);
    not_interior_.assign(nv, 0);
    boundary_vertex_.assign(nv, 0);
    spiked_.assign(nv, 0);
    vertex_mean_len_.assign(nv, std::numeric_limits<double>::quiet_NaN());
    std::vector<double> max_dihedral(nv, -1.0);       // degrees, for the height criterion
    std::vector<unsigned char> inconsistent(nv, 0);   // no consistently oriented link
    std::vector<double> sum(nv, 0.0);
    std::vector<Inspect_index> cnt(nv, 0);
    // what edge e gives its end v (an edge on one vertex twice counts twice)
    auto add_edge = [&](std::size_t e, Inspect_index v) {
      const std::size_t nfe = a_.edge_off[e + 1] - a_.edge_off[e];
      ++valence_[v];
      if (edge_dihedral_[e] > max_dihedral[v]) max_dihedral[v] = edge_dihedral_[e];
      if (nfe == 2 && forward(a_.edge_corners[a_.edge_off[e]], e) ==
                          forward(a_.edge_corners[a_.edge_off[e] + 1], e))
        inconsistent[v] = 1;
      if (nfe != 2) not_interior_[v] = 1;
      if (nfe == 1) boundary_vertex_[v] = 1;
      if (edge_dihedral_[e] > t_.spike_angle) spiked_[v] = 1;  // false for NaN
      if (!std::isnan(edge_len_[e])) {
        sum[v] += edge_len_[e];
        ++cnt[v];
      }
    };
    if (2 * ne < inspect_npos) {
      // per vertex its edge ends in edge order (a stable counting sort of
      // the 2 ne ends), then the vertices in parallel: each sums its edges in
      // the order of one loop over the edges, so the sums are that loop's
      // (the loop, scattered writes on one core, was 0.06 s at 1M faces)
      std::vector<Inspect_index> first, ends;
      bucket_items(2 * ne, nv, inspect_npos, [&](std::size_t i) { return a_.edge_v[i]; }, first, ends);
      parallel_for_index(nv, 4096, [&](std::size_t v) {
        for (Inspect_index j = first[v]; j < first[v + 1]; ++j) add_edge(ends[j] / 2, static_cast<Inspect_index>(v));
      });
    } else {
      for (std::size_t e = 0; e < ne; ++e)
        for (int k = 0; k < 2; ++k) add_edge(e, a_.edge_v[2 * e + k]);
    }
    for (std::size_t v = 0; v < nv; ++v)
      if (cnt[v]) vertex_mean_len_[v] = sum[v] / double(cnt[v]);
    free_memory(sum, cnt);
    vertex_corner_table();
    spikes_by_height(max_dihedral, inconsistent);
    std::size_t spiked = 0;
    if (sink_) {
      for (std::size_t v = 0; v < nv; ++v)
        if (spiked_[v]) {
          ++spiked;
          sink_->spiked_vertices.push_back(v);
        }
    } else {
      for (std::size_t v = 0; v < nv; ++v) spiked += spiked_[v];
    }
    r_.spiked_vertices = spiked;
  }

  // The corners of each vertex in corner order (a counting sort), read by the
  // spike test and the fans of non_manifold_vertices.
  void vertex_corner_table() { internal::vertex_corner_table(a_, vertex_corner_first_, vertex_corners_); }
  std::vector<Inspect_index> vertex_corner_first_, vertex_corners_;

  // The second spike criterion (spike_criterion.h, shared with relax_spikes):
  // interior vertices far above the plane of their link. Its pre-filter
  // leaves the candidates; on a noisy scan they are many, so their links are
  // summed in parallel, each over its corners in corner order (the order of
  // one pass over all corners: same sums with any thread count).
  void spikes_by_height(const std::vector<double>& max_dihedral_deg,
                        const std::vector<unsigned char>& inconsistent)
  {
    const std::size_t nv = a_.num_vertices;
    if (!(t_.spike_height_factor > 0)) return;
    auto radians = [&](std::size_t v) { return max_dihedral_deg[v] / degrees_per_radian; };
    // the candidates in vertex order, chunk by chunk
    auto found = chunked<std::vector<Inspect_index>>(nv, [&](std::size_t b, std::size_t e,
                                                             std::vector<Inspect_index>& out) {
      for (std::size_t v = b; v < e; ++v) {
        if (spiked_[v] || not_interior_[v] || inconsistent[v] || !a_.finite[v]) continue;
        // the predicate's pre-filter selects the candidates (gather runs only past it)
        spiked_by_height(radians(v), t_.spike_height_factor, [&](Spike_link_sums&) {
          out.push_back(static_cast<Inspect_index>(v));
          return false;
        });
      }
    });
    std::vector<Inspect_index> candidates;
    for (std::vector<Inspect_index>& f : found) candidates.insert(candidates.end(), f.begin(), f.end());
    free_memory(found);
    if (candidates.empty()) return;
    const std::size_t nk = candidates.size();
    parallel_for_index(nk, 1024, [&](std::size_t k) {
      const Inspect_index v = candidates[k];
      spiked_[v] = spiked_by_height(radians(v), t_.spike_height_factor, [&](Spike_link_sums& sums) {
        for (Inspect_index i = vertex_corner_first_[v]; i < vertex_corner_first_[v + 1]; ++i) {
          const std::size_t c = vertex_corners_[i], f = a_.corner_f[c];
          if (!face_ok_[f] || a_.face_skip[f] || repeated_[f]) return false;
          // the link edges of this face: the chain from next(c) round to prev(c)
          const double* p = a_.point(a_.corner_v[c]);
          for (std::size_t j = a_.next_corner(c); a_.next_corner(j) != c; j = a_.next_corner(j))
            sums.add(p, a_.point(a_.corner_v[j]), a_.point(a_.corner_v[a_.next_corner(j)]));
        }
        return true;
      });
    });
  }

  // RameshCleaner 3.6. Edge e is short when |e| < eps * l_g (zero edge) or
  // |e| < delta * l_e with l_e the mean of the mean incident edge lengths of
  // its two endpoints (skinny edge). A triangle is near-degenerate when one
  // of its edges is a zero edge, or a skinny edge whose opposite angle in this
  // triangle is below `skinny_angle`. An edge is collapsible when it is a zero
  // edge, or a skinny edge with such a small opposite angle in an incident triangle.
  void near_degenerate()
  {
    if (std::isnan(r_.edge_length_mean)) return;
    const Near_degenerate_criterion crit = near_degenerate_criterion();
    const double mean = r_.edge_length_mean;
    auto local_mean = [&](std::size_t e) {
      return 0.5 * (vertex_mean_len_[a_.edge_v[2 * e]] + vertex_mean_len_[a_.edge_v[2 * e + 1]]);
    };
    auto zero = [&](std::size_t e) { return crit.is_zero_edge(edge_len_[e], mean); };
    auto skinny = [&](std::size_t e) { return crit.is_skinny_edge(edge_len_[e], local_mean(e)); };
    const std::size_t nf = a_.num_faces(), ne = a_.num_edges();
    std::vector<unsigned char> small_opposite(ne, 0);
    struct Acc
    {
      std::size_t n = 0;
      std::vector<Inspect_index> faces;  // with a sink
    };
    auto acc = chunked<Acc>(nf, [&](std::size_t b, std::size_t e_end, Acc& s) {
      for (std::size_t f = b; f < e_end; ++f) {
        if (a_.degree(f) != 3 || !face_ok_[f] || repeated_[f]) continue;
        const std::size_t c0 = a_.face_off[f];
        for (std::size_t i = 0; i < 3; ++i) {
          const Inspect_index e = a_.corner_e[c0 + i];
          if (e == inspect_npos) continue;
          const bool opposite_is_skinny = skinny_corner_[c0 + (i + 2) % 3];
          if (crit.edge_makes_face_near_degenerate(edge_len_[e], opposite_is_skinny, mean, local_mean(e))) {
            ++s.n;
            if (sink_) s.faces.push_back(static_cast<Inspect_index>(f));
            break;
          }
        }
      }
    });
    for (const Acc& s : acc) {
      r_.near_degenerate_faces += s.n;
      if (sink_) sink_->near_degenerate_faces.insert(sink_->near_degenerate_faces.end(), s.faces.begin(), s.faces.end());
    }
    for (std::size_t f = 0; f < nf; ++f) {
      if (a_.degree(f) != 3 || !face_ok_[f] || repeated_[f]) continue;
      const std::size_t c0 = a_.face_off[f];
      for (std::size_t i = 0; i < 3; ++i)
        if (skinny_corner_[c0 + (i + 2) % 3] && a_.corner_e[c0 + i] != inspect_npos)
          small_opposite[a_.corner_e[c0 + i]] = 1;
    }
    auto acc2 = chunked<std::size_t>(ne, [&](std::size_t b, std::size_t e_end, std::size_t& s) {
      for (std::size_t e = b; e < e_end; ++e) {
        if (std::isnan(edge_len_[e])) continue;
        if (zero(e) || (small_opposite[e] && skinny(e))) ++s;
      }
    });
    for (std::size_t s : acc2) r_.collapsible_edges += s;
  }

  // ---- topology -----------------------------------------------------------------
  // Faces linked through shared edges (of any multiplicity); faces with a
  // repeated index are left out.
  void components()
  {
    const std::size_t nf = a_.num_faces(), ne = a_.num_edges();
    Union_find<Inspect_index> uf(nf);
    for (std::size_t e = 0; e < ne; ++e) {
      const Inspect_index f0 = a_.corner_f[a_.edge_corners[a_.edge_off[e]]];
      for (Inspect_index i = a_.edge_off[e] + 1; i < a_.edge_off[e + 1]; ++i)
        uf.unite(f0, a_.corner_f[a_.edge_corners[i]]);
    }
    std::vector<Inspect_index> size(nf, 0);
    for (std::size_t f = 0; f < nf; ++f)
      if (!a_.face_skip[f]) ++size[uf.find(static_cast<Inspect_index>(f))];
    std::vector<Inspect_index> slot;  // with a sink: per root, its small component's list + 1
    if (sink_) slot.assign(nf, 0);
    for (std::size_t f = 0; f < nf; ++f) {
      if (size[f] == 0) continue;
      ++r_.connected_components;
      if (size[f] < t_.min_component_faces) {
        ++r_.small_components;
        if (sink_) {
          sink_->small_components.emplace_back();
          sink_->small_components.back().reserve(size[f]);
          slot[f] = static_cast<Inspect_index>(sink_->small_components.size());
        }
      }
    }
    if (sink_ && !sink_->small_components.empty())
      for (std::size_t f = 0; f < nf; ++f) {
        if (a_.face_skip[f]) continue;
        const Inspect_index k = slot[uf.find(static_cast<Inspect_index>(f))];
        if (k) sink_->small_components[k - 1].push_back(f);
      }
  }

  // A vertex is non-manifold when the faces around it, linked through the
  // edges incident to the vertex, form more than one group (fan).
  void non_manifold_vertices()
  {
    const std::size_t nv = a_.num_vertices;
    non_manifold_vertex_.assign(nv, 0);
    auto acc = chunked<std::size_t>(nv, [&](std::size_t b, std::size_t e, std::size_t& s) {
      std::vector<std::pair<Inspect_index, Inspect_index>> link; // (edge, local face)
      std::vector<Inspect_index> vc;   // the corners at v that have edges
      Union_find<Inspect_index> fans;  // local faces of v joined through its edges
      for (std::size_t v = b; v < e; ++v) {
        vc.clear();
        for (Inspect_index i = vertex_corner_first_[v]; i < vertex_corner_first_[v + 1]; ++i)
          if (a_.corner_e[vertex_corners_[i]] != inspect_npos) vc.push_back(vertex_corners_[i]);
        const std::size_t k = vc.size();
        if (k < 2) continue;
        link.clear();
        for (std::size_t i = 0; i < k; ++i) {
          const Inspect_index c = vc[i];
          link.emplace_back(a_.corner_e[c], static_cast<Inspect_index>(i));
          link.emplace_back(a_.corner_e[a_.prev_corner(c)], static_cast<Inspect_index>(i));
        }
        std::sort(link.begin(), link.end());
        fans.reset(k);
        std::size_t groups = k;
        for (std::size_t i = 1; i < link.size(); ++i)
          if (link[i].first == link[i - 1].first && fans.unite(link[i].second, link[i - 1].second))
            --groups;
        if (groups > 1) {
          non_manifold_vertex_[v] = 1;
          ++s;
        }
      }
    });
    for (std::size_t s : acc) r_.non_manifold_vertices += s;
    if (sink_)
      for (std::size_t v = 0; v < nv; ++v)
        if (non_manifold_vertex_[v]) sink_->non_manifold_vertices.push_back(v);
  }
  std::vector<unsigned char> non_manifold_vertex_;

  void count_loops(const std::vector<std::size_t>& loops)
  {
    r_.boundary_loops = loops.size();
    for (std::size_t i = 0; i < loops.size(); ++i)
      if (loops[i] < t_.max_hole_vertices) {
        ++r_.small_holes;
        if (sink_) sink_->small_holes.push_back(i);
      }
    if (sink_ && cycle_vertices_)
      for (const std::vector<Inspect_index>& c : *cycle_vertices_)
        sink_->boundary_loops.emplace_back(c.begin(), c.end());
  }

  // Soup: a loop is a connected component of the graph of boundary edges; its
  // size is its number of boundary edges.
  void soup_loops()
  {
    const std::size_t nv = a_.num_vertices, ne = a_.num_edges();
    Union_find<Inspect_index> uf(nv);
    for (std::size_t e = 0; e < ne; ++e)
      if (a_.edge_off[e + 1] - a_.edge_off[e] == 1) uf.unite(a_.edge_v[2 * e], a_.edge_v[2 * e + 1]);
    std::vector<Inspect_index> size(nv, 0);
    for (std::size_t e = 0; e < ne; ++e)
      if (a_.edge_off[e + 1] - a_.edge_off[e] == 1) ++size[uf.find(a_.edge_v[2 * e])];
    std::vector<std::size_t> loops;
    for (std::size_t v = 0; v < nv; ++v)
      if (size[v]) loops.push_back(size[v]);
    if (sink_) soup_loop_walks(uf, size);
    count_loops(loops);
  }

  // With a sink: the vertices of each soup loop (roots in vertex order, as
  // soup_loops() lists the loop sizes) in walk order. Each loop is walked by
  // Hierholzer's algorithm from a vertex of odd boundary degree if it has
  // one; a loop whose walk does not use every edge is listed as open walks.
  void soup_loop_walks(Union_find<Inspect_index>& uf, const std::vector<Inspect_index>& size)
  {
    const std::size_t nv = a_.num_vertices, ne = a_.num_edges();
    std::vector<Inspect_index> bedges;  // the boundary edges
    for (std::size_t e = 0; e < ne; ++e)
      if (a_.edge_off[e + 1] - a_.edge_off[e] == 1) bedges.push_back(static_cast<Inspect_index>(e));
    // incidences (vertex -> boundary edge ids)
    std::vector<Inspect_index> first, inc;
    bucket_items(2 * bedges.size(), nv, inspect_npos,
                 [&](std::size_t i) { return a_.edge_v[2 * std::size_t(bedges[i / 2]) + i % 2]; }, first, inc);
    std::vector<Inspect_index> next_inc(first.begin(), first.end() - 1);  // per vertex: next unused incidence
    std::vector<unsigned char> used(bedges.size(), 0);
    auto other = [&](std::size_t i, Inspect_index v) {
      const std::size_t e = bedges[i / 2];
      return a_.edge_v[2 * e] == v ? a_.edge_v[2 * e + 1] : a_.edge_v[2 * e];
    };
    // vertices of each loop (by root), in vertex order
    std::vector<Inspect_index> slot(nv, inspect_npos);
    std::size_t nloops = 0;
    for (std::size_t v = 0; v < nv; ++v)
      if (size[v]) slot[v] = static_cast<Inspect_index>(nloops++);
    std::vector<std::vector<Inspect_index>> members(nloops);
    for (std::size_t v = 0; v < nv; ++v)
      if (first[v + 1] != first[v]) members[slot[uf.find(static_cast<Inspect_index>(v))]].push_back(static_cast<Inspect_index>(v));
    auto has_unused = [&](Inspect_index v) {
      while (next_inc[v] < first[v + 1] && used[inc[next_inc[v]] / 2]) ++next_inc[v];
      return next_inc[v] < first[v + 1];
    };
    std::vector<Inspect_index> stack, walk;
    for (std::size_t l = 0; l < nloops; ++l) {
      std::vector<Defect_locations::Index> out;
      const std::vector<Inspect_index>& m = members[l];
      std::size_t walks = 0;
      bool open = false;
      for (;;) {
        // start: an odd vertex with unused edges, else any vertex with unused edges
        Inspect_index start = inspect_npos;
        for (Inspect_index v : m) {
          if (!has_unused(v)) continue;
          std::size_t unused = 0;
          for (Inspect_index i = first[v]; i < first[v + 1]; ++i) unused += !used[inc[i] / 2];
          if (unused % 2) {
            start = v;
            break;
          }
          if (start == inspect_npos) start = v;
        }
        if (start == inspect_npos) break;
        walk.clear();
        stack.assign(1, start);
        while (!stack.empty()) {
          const Inspect_index v = stack.back();
          if (has_unused(v)) {
            const Inspect_index i = inc[next_inc[v]];
            used[i / 2] = 1;
            stack.push_back(other(i, v));
          } else {
            walk.push_back(v);
            stack.pop_back();
          }
        }
        ++walks;
        if (walk.front() != walk.back()) open = true;
        out.insert(out.end(), walk.begin(), walk.end());
        out.push_back(Defect_locations::walk_end);
      }
      if (walks == 1 && !open) {
        out.pop_back();  // walk_end
        out.pop_back();  // the closing vertex, listed first
      }
      sink_->boundary_loops.push_back(std::move(out));
    }
  }

  // A boundary vertex lying within `tol` of the interior of a boundary edge it
  // is not an endpoint of: its projection falls strictly inside the edge, and
  // it is farther than `tol` from both endpoints. Counted once per vertex.
  void t_junctions()
  {
    const double tol = t_.t_junction_tolerance >= 0 ? t_.t_junction_tolerance
                                                    : t_.t_junction_relative * bbox_diag_;
    r_.t_junction_tolerance = tol;
    const std::size_t ne = a_.num_edges(), nv = a_.num_vertices;
    std::vector<K::Segment_3> segs;
    std::vector<Inspect_index> seg_edge;
    for (std::size_t e = 0; e < ne; ++e) {
      if (a_.edge_off[e + 1] - a_.edge_off[e] != 1) continue;
      const Inspect_index v0 = a_.edge_v[2 * e], v1 = a_.edge_v[2 * e + 1];
      if (!a_.finite[v0] || !a_.finite[v1]) continue;
      const double *p = a_.point(v0), *q = a_.point(v1);
      segs.emplace_back(K::Point_3(p[0], p[1], p[2]), K::Point_3(q[0], q[1], q[2]));
      seg_edge.push_back(static_cast<Inspect_index>(e));
    }
    if (segs.size() < 2) return;
    using Iterator = std::vector<K::Segment_3>::const_iterator;
    using Primitive = Aabb_segment_primitive<K, Iterator>;
    using Tree = Aabb_tree<K, Primitive>;
    Tree tree(segs.cbegin(), segs.cend());
    tree.build();
    std::vector<Inspect_index> bv;
    for (std::size_t v = 0; v < nv; ++v)
      if (boundary_vertex_[v] && a_.finite[v]) bv.push_back(static_cast<Inspect_index>(v));
    const double tol2 = tol * tol;
    struct Acc
    {
      std::size_t n = 0;
      std::vector<std::pair<Inspect_index, Inspect_index>> found;  // (vertex, edge), with a sink
    };
    auto acc = chunked<Acc>(bv.size(), [&](std::size_t b, std::size_t e_end, Acc& s) {
      std::vector<Primitive::Id> hits;
      for (std::size_t i = b; i < e_end; ++i) {
        const Inspect_index v = bv[i];
        const double* p = a_.point(v);
        hits.clear();
        tree.all_intersected_primitives(
            K::Iso_cuboid_3(p[0] - tol, p[1] - tol, p[2] - tol, p[0] + tol, p[1] + tol, p[2] + tol),
            std::back_inserter(hits));
        for (const auto& id : hits) {
          const std::size_t e = seg_edge[static_cast<std::size_t>(id - segs.cbegin())];
          const Inspect_index v0 = a_.edge_v[2 * e], v1 = a_.edge_v[2 * e + 1];
          if (v0 == v || v1 == v) continue;
          const Vec3 x = load_vec3(a_.point(v0)), y = load_vec3(a_.point(v1)), pv = load_vec3(p);
          const Vec3 d = sub(y, x), w = sub(pv, x);
          const double dd = squared_norm(d);
          if (dd == 0) continue;
          const double tpar = dot(w, d) / dd;
          if (tpar <= 0 || tpar >= 1) continue;
          if (squared_norm(sub(w, mul(d, tpar))) > tol2) continue;
          if (squared_norm(w) <= tol2) continue;
          if (squared_norm(sub(pv, y)) <= tol2) continue;
          ++s.n;
          if (sink_) s.found.emplace_back(v, static_cast<Inspect_index>(e));
          break;
        }
      }
    });
    for (const Acc& s : acc) {
      r_.t_junctions += s.n;
      if (sink_)
        for (const auto& ve : s.found) {
          sink_->t_junction_vertices.push_back(ve.first);
          sink_->t_junction_edges.push_back({a_.edge_v[2 * std::size_t(ve.second)], a_.edge_v[2 * std::size_t(ve.second) + 1]});
        }
    }
  }

  void valence_and_closedness()
  {
    const std::size_t nv = a_.num_vertices;
    double dev = 0;
    std::size_t n = 0;
    for (std::size_t v = 0; v < nv; ++v) {
      if (!referenced_[v] || valence_[v] == 0 || not_interior_[v] || non_manifold_vertex_[v]) continue;
      dev += std::abs(double(valence_[v]) - 6.0);
      ++n;
    }
    if (n > 0) r_.mean_valence_deviation = dev / double(n);
    r_.closed = r_.faces > 0 && r_.boundary_edges == 0;
    if (r_.closed && r_.non_manifold_edges == 0 && r_.inconsistent_orientation_edges == 0 &&
        r_.repeated_index_faces == 0 && non_finite_referenced == 0)
      r_.volume = volume_sum_;
  }
};

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_INSPECT_ANALYSIS_H
