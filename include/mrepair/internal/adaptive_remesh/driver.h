// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_ADAPTIVE_REMESH_DRIVER_H
#define MREPAIR_INTERNAL_ADAPTIVE_REMESH_DRIVER_H

// The driver of every remeshing call of adaptive_remesh.h, once the named
// parameters are read and the input is checked: the part to remesh, the
// feature edges, then the Remesher in the mode asked for (uniform, adaptive,
// or face count with its corrections of the target length), and the write
// back.

#include <mrepair/definitions.h>
#include <mrepair/internal/adaptive_remesh/remesher.h>
#include <mrepair/internal/utility.h>
#include <mrepair/remeshing_result.h>
#include <mrepair/status.h>

#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>

namespace mrepair {
namespace internal {

enum class Remesh_mode { uniform, adaptive, face_count };

template <typename P>
void remesh_collect_garbage(CGAL::Surface_mesh<P>& m) { m.collect_garbage(); }
template <typename M>
void remesh_collect_garbage(M&) {}

/// what the public calls read from their named parameters (see adaptive_remesh.h).
struct Remesh_options
{
  int iterations = 10;
  bool protect = false;      ///< protect_constraints
  bool relax_lines = true;   ///< relax_constraints
  bool project = true;       ///< do_project
  double density = 1.;       ///< remesh_density_factor
  double gamma = 1.;         ///< remesh_gamma
  double feature_angle = defaults::remesh_feature_angle;  ///< degrees; <= 0 or >= 180: no detection
  bool has_ecm = false;      ///< an edge_is_constrained_map was given
  double min_edge_length = 0, max_edge_length = 0;  ///< adaptive mode
  bool has_min_edge_length = false;  ///< remesh_min_edge_length was given
  bool collect_garbage = true;       ///< collect_garbage
};

/// a result with the mode and the counts of the input filled in.
template <typename TriangleMesh>
Remeshing_result start_remeshing_result(const TriangleMesh& tm, Remesh_mode mode)
{
  Remeshing_result res;
  res.mode = mode == Remesh_mode::uniform ? "uniform"
             : mode == Remesh_mode::adaptive ? "adaptive" : "face_count";
  res.faces_before = internal::face_count(tm);
  res.faces_after = res.faces_before;
  res.vertices_after = internal::vertex_count(tm);
  return res;
}

/// `res` refused with status `s` and message `m`.
inline Remeshing_result refuse_remeshing(Remeshing_result res, Status s, const std::string& m)
{
  res.status = s;
  res.message = m;
  return res;
}

/// after the last iteration: the faces still deviating more than `limit`
/// have their longest edge split at the input surface, at most `max_splits`
/// of them, worst first (Remesher::split_deviating_faces; a split may make an
/// angle down to `deviation_split_min_deg`), then the min-angle pass raises
/// the angles the splits made small again, up to the smallest angle before
/// them (at least 30 degrees), guarded by the tolerance.
constexpr double deviation_split_min_deg = 20.;

template <typename Remesher>
std::size_t split_faces_over(Remesher& R, double limit, std::size_t max_splits, bool project)
{
  const double min_before = R.min_angle_deg();
  // first toward input points the mesh cut off (half the splits at most),
  // then the faces over the limit, the new ones included
  std::size_t n = R.split_toward_far_input_points(limit, max_splits / 2, deviation_split_min_deg);
  n += R.split_deviating_faces(limit, max_splits - n, deviation_split_min_deg);
  if (n > 0) R.finish(project, std::max(30., min_before));
  return n;
}

/// `iterations` of adaptive remeshing at tolerance `eps`, with the sizing
/// lowered around the faces that deviate more than `limit` (to reach `goal`)
/// after 2/5 and 7/10 of them (Remesher::refine_deviating_faces). With
/// `last_run` false the final min-angle pass is left to Remesher::finish.
template <typename Remesher, typename VisitorHandle>
Status run_with_error_control(Remesher& R, int iterations, bool project, double limit, double goal,
                              double lmin, VisitorHandle& vis, bool last_run = true)
{
  if (iterations < 4) return R.run(iterations, project, vis, last_run);
  const int first = (2 * iterations) / 5, second = (7 * iterations) / 10 - first;
  Status st = R.run(first, project, vis, false);
  if (st != Status::ok) return st;
  R.refine_deviating_faces(limit, goal, lmin);
  st = R.run(second, project, vis, false);
  if (st != Status::ok) return st;
  R.refine_deviating_faces(limit, goal, lmin);
  st = R.run(iterations - first - second, project, vis, last_run);
  if (st == Status::ok && last_run) split_faces_over(R, limit, std::numeric_limits<std::size_t>::max(), project);
  return st;
}

/// adaptive remeshing to `value` faces with the adaptive mode's own schedule
/// (its error control at the tolerance, 0.7 x the tolerance as the goal), so
/// that a count gets the accuracy the adaptive mode gives at that count:
///  1. the tolerance whose sizing field predicts the count (bisection);
///  2. a pilot of 4 iterations at it, refining only the outliers: the count
///     it reaches differs from the prediction by a factor that depends on
///     the shape (the gradation around flat CAD faces and the error control
///     add faces the curvature does not predict: 2-3x on fandisk);
///  3. the tolerance that predicts the count over that factor, and the full
///     schedule with the adaptive mode's error control at it, continuing from
///     the pilot's mesh;
///  4. the sizing scaled by the square root of the count reached over 0.99 x
///     the target (3 iterations each) until the count is within 0.01 x the
///     target of that aim (`outside`: faces not remeshed);
///  5. the faces left up to 1.01 x the target spent on the faces that deviate
///     most: their longest edges split at the input, worst first.
/// Splits plus collapses are capped at 100 per input and per target face (a
/// surface far thinner than the target length: `partial`).
template <typename Remesher, typename TriangleMesh, typename VisitorHandle>
Status remesh_to_count(Remesher& R, const Remesh_options& o, double value, std::size_t outside,
                       TriangleMesh& tm, VisitorHandle& vis, Remeshing_result& res)
{
  auto& rf = R.reference();
  const double N = value;
  res.target_faces = static_cast<std::size_t>(N);
  double area = 0, perimeters = 0;
  for (const auto& t : rf.triangles) {
    area += 0.5 * norm(triangle_normal(rf.points[t[0]], rf.points[t[1]], rf.points[t[2]]));
    for (int k = 0; k < 3; ++k) perimeters += norm(rf.points[t[(k + 1) % 3]] - rf.points[t[k]]);
  }
  const double lmax = o.max_edge_length / o.density;
  // a few very long, thin triangles have little area but would be split into
  // edge length / L pieces (out of memory): no length below ~perimeters / 200 N
  const double uniform_L = std::sqrt(4. * area / (std::sqrt(3.) * N));
  const double floor_L = std::max(perimeters / (200. * N), 1e-3 * uniform_L);
  R.set_operation_budget(100 * (rf.triangles.size() + static_cast<std::size_t>(N)));
  if (!(area > 0) || !(uniform_L < std::numeric_limits<double>::infinity())) {
    // nothing to adapt to (all faces degenerate): uniform
    res.target_edge_length = std::max(uniform_L, perimeters / (200. * N));
    if (!std::isfinite(res.target_edge_length)) res.target_edge_length = 0;
    R.set_uniform(res.target_edge_length);
    return R.run(std::max(o.iterations, 1), o.project, vis);
  }
  auto lmin_for = [&](double eps) {
    return std::max(o.has_min_edge_length ? o.min_edge_length / o.density : eps, floor_L);
  };
  rf.prepare_curvature();
  // the tolerance whose field predicts `faces`, by bisection in log space
  auto tolerance_predicting = [&](double faces) {
    double lo = 1e-9 * uniform_L, hi = 10. * uniform_L;
    for (int i = 0; i < 40; ++i) {
      const double mid = std::sqrt(lo * hi), lmin = lmin_for(mid);
      rf.sizing_from_curvature(mid, lmin, std::max(lmax, lmin), o.gamma);
      (rf.predicted_faces() > faces ? lo : hi) = mid;
    }
    return hi;
  };
  auto count = [&] { return static_cast<double>(internal::face_count(tm) - outside); };
  double eps = 0, predicted = N;  // the prediction of the last schedule's tolerance
  // `strict`: the adaptive mode's error control; else only the outliers
  // (3 x eps, refined to 2 x eps), which keeps the pilot cheap
  auto schedule = [&](double faces_predicted, int iterations, bool strict) {
    eps = tolerance_predicting(faces_predicted);
    predicted = faces_predicted;
    const double lmin = lmin_for(eps);
    R.set_adaptive(eps, lmin, std::max(lmax, lmin), o.gamma);
    R.guard_min_angle_pass(eps);
    Status s = strict ? run_with_error_control(R, iterations, o.project, eps, 0.7 * eps, lmin, vis, false)
                      : run_with_error_control(R, iterations, o.project, 3. * eps, 2. * eps, lmin, vis, false);
    return s;
  };
  // the factor between the count reached and the count predicted, kept in a
  // sane range (a pilot on a mesh far from its target can be far off)
  auto refit = [&] { return predicted * std::clamp(N / std::max(count(), 1.), 0.25, 4.); };
  Status st = schedule(N, 4, false);
  if (st == Status::ok) st = schedule(refit(), std::max(o.iterations, 4), true);
  // the scaling aims 1% under the count: the last 1-2% go to the faces that
  // deviate most (below)
  const double aim = 0.99 * N;
  for (int round = 0; round < 8 && st == Status::ok; ++round) {
    const double F = count();
    if (std::abs(F - aim) <= 0.01 * N) break;
    const double lmin = lmin_for(eps), low = std::min(lmin, floor_L);
    // Where the tolerance found (the smallest length unless one is given)
    // is above the maximum, the count has already taken the field past the
    // maximum; holding it at that tolerance would stop the count a few
    // percent short (the 1M scan at 1,146 faces: 1,174). Otherwise the
    // user's maximum bounds the field.
    const double high = lmin > lmax ? std::numeric_limits<double>::infinity() : lmax;
    if (R.scale_sizing(std::sqrt(F / aim), low, high) == 0) {
      // the whole field sits at the maximum (F > N: the field was scaled
      // up), or at the floor: more rounds cannot move the count
      if (F > N && std::abs(F - N) > 0.02 * N) {
        st = Status::partial;
        std::ostringstream m;
        m << "the face count needs edges longer than remesh_max_edge_length (" << high * o.density
          << "), which every target length is at: " << static_cast<std::size_t>(F) << " faces; the mesh is valid";
        res.message = m.str();
      }
      break;
    }
    st = R.run(3, o.project, vis, false);
  }
  if (st == Status::ok) {
    // the room up to 1% over the count goes to the faces that deviate most,
    // worst first (split_faces_over), so that the count's Hausdorff distance
    // is not one face's
    const double room = 1.01 * N - count();
    if (room >= 2.) split_faces_over(R, 0., static_cast<std::size_t>(room / 2.), o.project);
  }
  if (st == Status::ok || (st == Status::partial && !res.message.empty())) R.finish(o.project);
  res.tolerance = eps;
  res.target_edge_length = R.mean_sizing();
  return st;
}

/// remeshes `tm` (or the faces of `part` when not null) on checked input;
/// `diag` is the bounding-box diagonal, `value` the target of `mode`.
template <bool parallel, typename TriangleMesh, typename FaceRange, typename VPM, typename ECM,
          typename VCM, typename VisitorHandle>
Remeshing_result remesh_driver(TriangleMesh& tm, const FaceRange* part, Remesh_mode mode,
                               double value, const Remesh_options& o, VPM vpm, ECM ecm, VCM vcm,
                               VisitorHandle& vis, Remeshing_result res)
{
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  auto fail = [&](Status s, const std::string& m) { return refuse_remeshing(res, s, m); };

  // ---- part selection
  auto in_part_map = get(CGAL::dynamic_face_property_t<char>(), tm);
  const bool whole = part == nullptr;
  if (!whole) {
    for (face_descriptor f : faces(tm)) put(in_part_map, f, char(0));
    std::size_t n = 0;
    for (face_descriptor f : *part) { put(in_part_map, f, char(1)); ++n; }
    if (n == 0) return fail(Status::empty_input, "the face range is empty");
  }
  auto in_part = [&](face_descriptor f) { return whole || get(in_part_map, f) != 0; };

  // ---- features
  const double cos_feature = o.feature_angle > 0 && o.feature_angle < 180
                                 ? std::cos(o.feature_angle * pi / 180.) : 2.;
  auto fnormal = [&](typename GT::halfedge_descriptor h) {
    return triangle_normal(point(vpm, source(h, tm)), point(vpm, target(h, tm)),
                           point(vpm, target(next(h, tm), tm)));
  };
  auto is_feature = [&](edge_descriptor e) {
    if (o.has_ecm && get(ecm, e)) return true;
    if (cos_feature > 1.) return false;
    auto h = halfedge(e, tm);
    Vec3 n1 = fnormal(h), n2 = fnormal(opposite(h, tm));
    double l = norm(n1) * norm(n2);
    return l > 0 && dot(n1, n2) < cos_feature * l;
  };
  auto is_fixed = [&](vertex_descriptor v) { return bool(get(vcm, v)); };

  Status st = Status::ok;
  {
    remesh::Remesher<TriangleMesh, VPM, parallel> R(tm, vpm);
    R.set_relax_lines(o.relax_lines);
    vis.start_phase("setup");
    R.setup(in_part, is_feature, is_fixed, o.protect,
            cos_feature <= 1. ? cos_feature : std::cos(defaults::remesh_feature_angle * pi / 180.));
    vis.end_phase("setup");
    res.feature_edges = R.feature_edges;
    res.corners = R.corners;
    if (mode == Remesh_mode::uniform) {
      res.target_edge_length = value / o.density;
      R.set_uniform(res.target_edge_length);
      st = R.run(o.iterations, o.project, vis);
    } else if (mode == Remesh_mode::adaptive) {
      res.tolerance = value;
      const double lmin = o.min_edge_length, lmax = o.max_edge_length;
      if (!(lmin > 0) || !(lmax >= lmin) || !std::isfinite(lmax))
        return fail(Status::invalid_parameter, "need 0 < remesh_min_edge_length <= remesh_max_edge_length");
      R.set_adaptive(value, lmin / o.density, lmax / o.density, o.gamma);
      R.guard_min_angle_pass(value);
      const auto& s = R.reference().sizing;
      res.min_target = s.empty() ? 0 : *std::min_element(s.begin(), s.end());
      res.max_target = s.empty() ? 0 : *std::max_element(s.begin(), s.end());
      // deviations over the tolerance are refined to 0.7 x the tolerance
      st = run_with_error_control(R, o.iterations, o.project, value, 0.7 * value, lmin / o.density, vis);
    } else {
      st = remesh_to_count(R, o, value, whole ? 0 : res.faces_before - R.reference().triangles.size(),
                           tm, vis, res);
    }
    if (st == Status::ok || st == Status::cancelled || st == Status::partial) R.write_back();
    if (o.has_ecm)
      for (edge_descriptor e : edges(tm)) put(ecm, e, R.is_feature(e));
    res.iterations = R.counters.iterations;
    res.splits = R.counters.splits;
    res.collapses = R.counters.collapses;
    res.flips = R.counters.flips;
  }
  // descriptors of the untouched rest stay valid when remeshing a part
  if (whole && o.collect_garbage) remesh_collect_garbage(tm);
  res.status = st;
  if (st == Status::cancelled) res.message = "cancelled by the visitor; the mesh is valid";
  if (st == Status::partial && res.message.empty())
    res.message = "operation budget spent before reaching the face count (surface too thin or "
                  "anisotropic for the target); the mesh is valid";
  res.faces_after = internal::face_count(tm);
  res.vertices_after = internal::vertex_count(tm);
  return res;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_ADAPTIVE_REMESH_DRIVER_H
