// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_ADAPTIVE_REMESH_H
#define MREPAIR_ADAPTIVE_REMESH_H

#include <mrepair/internal/remesh/remesher.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/Bbox_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/tags.h>

#include <cmath>
#include <string>
#include <type_traits>

/// \file adaptive_remesh.h
/// Uniform and curvature-adaptive isotropic remeshing with feature and
/// boundary preservation and back-projection (Botsch-Kobbelt 2004, Dunyach et
/// al. 2013), for every CGAL 5.5 triangle mesh. The algorithm:
/// \code
/// features = dihedral angle > feature_angle  (or the user's edge map); boundary = line
/// corners  = vertices with 1 or > 2 line edges (never move)
/// sizing L(v) = uniform L, or sqrt(6 eps / kappa(v) - 3 eps^2) clamped to [Lmin, Lmax]
/// repeat number_of_iterations times:
///   split edges longer than 4/3 L(e); collapse edges shorter than 4/5 L(e);
///   flip towards valence 6 (4 on boundary); tangential relaxation;
///   project onto the input (line vertices onto the input lines)
/// \endcode

// Algorithm-specific named parameters (defaults in the function docs).
MREPAIR_ADD_NAMED_PARAMETER(remesh_feature_angle)    // degrees; dihedral angle of a feature edge
MREPAIR_ADD_NAMED_PARAMETER(remesh_min_edge_length)  // adaptive mode: lower clamp of L
MREPAIR_ADD_NAMED_PARAMETER(remesh_max_edge_length)  // adaptive mode: upper clamp of L
MREPAIR_ADD_NAMED_PARAMETER(remesh_gamma)            // adaptive mode: curvature rescaling exponent
MREPAIR_ADD_NAMED_PARAMETER(remesh_density_factor)   // target lengths are divided by this

namespace mrepair {

/// \ingroup mrepair_remesh
/// outcome of a remeshing call.
struct Remeshing_result
{
  Status status = Status::ok;
  std::string message;
  std::string mode;                   ///< "uniform", "adaptive" or "face_count"
  std::size_t faces_before = 0;
  std::size_t faces_after = 0;
  std::size_t vertices_after = 0;
  std::size_t iterations = 0;         ///< iterations run
  std::size_t splits = 0, collapses = 0, flips = 0;
  std::size_t feature_edges = 0;      ///< input feature edges (user or detected, not boundary)
  std::size_t corners = 0;            ///< vertices kept fixed as corners
  double target_edge_length = 0;      ///< uniform L (final L in face-count mode)
  double tolerance = 0;               ///< adaptive epsilon
  double min_target = 0, max_target = 0;  ///< sizing field range (adaptive)
  std::size_t target_faces = 0;       ///< face-count mode

  void to_report(Report& r) const
  {
    r.add("status", std::string(to_string(status)));
    if (!message.empty()) r.add("message", message);
    r.add("mode", mode);
    r.add("faces_before", faces_before);
    r.add("faces_after", faces_after);
    r.add("vertices_after", vertices_after);
    r.add("iterations", iterations);
    r.add("splits", splits);
    r.add("collapses", collapses);
    r.add("flips", flips);
    r.add("feature_edges", feature_edges);
    r.add("corners", corners);
    if (mode != "adaptive") r.add("target_edge_length", target_edge_length);
    if (mode == "adaptive") {
      r.add("tolerance", tolerance);
      r.add("min_target", min_target);
      r.add("max_target", max_target);
    }
    if (mode == "face_count") r.add("target_faces", target_faces);
  }
};

namespace internal {

enum class Remesh_mode { uniform, adaptive, face_count };

template <typename P>
void remesh_collect_garbage(CGAL::Surface_mesh<P>& m) { m.collect_garbage(); }
template <typename M>
void remesh_collect_garbage(M&) {}

// Shared driver of every public overload. `part` is null for the whole mesh.
template <typename ConcurrencyTag, typename TriangleMesh, typename FaceRange, typename NP>
Remeshing_result remesh_driver(TriangleMesh& tm, const FaceRange* part, Remesh_mode mode,
                               double value, const NP& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using VPM = typename CGAL::GetVertexPointMap<TriangleMesh, NP>::type;
#ifdef CGAL_LINKED_WITH_TBB
  constexpr bool parallel = std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value;
#else
  static_assert(!std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value,
                "Parallel_tag needs TBB (CGAL_LINKED_WITH_TBB)");
  constexpr bool parallel = false;
#endif
  using remesh::Vec3;

  Remeshing_result res;
  res.mode = mode == Remesh_mode::uniform ? "uniform"
             : mode == Remesh_mode::adaptive ? "adaptive" : "face_count";
  res.faces_before = static_cast<std::size_t>(faces(tm).size());
  res.faces_after = res.faces_before;
  res.vertices_after = static_cast<std::size_t>(vertices(tm).size());
  auto fail = [&](Status s, const std::string& m) {
    res.status = s;
    res.message = m;
    return res;
  };

  VPM vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                             get_property_map(CGAL::vertex_point, tm));
  const int iterations = choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), 10);
  const bool protect = choose_parameter(get_parameter(np, CGAL::internal_np::protect_constraints), false);
  const bool relax_lines = choose_parameter(get_parameter(np, CGAL::internal_np::relax_constraints), true);
  const bool project = choose_parameter(get_parameter(np, CGAL::internal_np::do_project), true);
  const double density = choose_parameter(get_parameter(np, internal_np::remesh_density_factor), 1.);
  const double gamma = choose_parameter(get_parameter(np, internal_np::remesh_gamma), 1.);
  const bool has_ecm = !is_default_parameter<NP, CGAL::internal_np::edge_is_constrained_t>::value;
  // with a user edge map, detect sharp edges only when the angle is given too
  const double feature_angle =
      choose_parameter(get_parameter(np, internal_np::remesh_feature_angle), has_ecm ? -1. : 44.);

  // ---- validation: nothing is touched before every check passed
  if (!std::isfinite(value) || value <= 0)
    return fail(Status::invalid_parameter, "target must be a positive finite number");
  if (iterations < 0) return fail(Status::invalid_parameter, "number_of_iterations must be >= 0");
  if (!(density > 0) || !std::isfinite(density))
    return fail(Status::invalid_parameter, "remesh_density_factor must be positive");
  if (!(gamma > 0) || !std::isfinite(gamma))
    return fail(Status::invalid_parameter, "remesh_gamma must be positive");
  if (faces(tm).size() == 0) return fail(Status::empty_input, "the mesh has no faces");
  if (!CGAL::is_triangle_mesh(tm))
    return fail(Status::invalid_mesh, "the mesh is not a triangle mesh");
  CGAL::Bbox_3 bb;
  for (vertex_descriptor v : vertices(tm)) {
    const auto& p = get(vpm, v);
    double x = CGAL::to_double(p.x()), y = CGAL::to_double(p.y()), z = CGAL::to_double(p.z());
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      return fail(Status::non_finite_input, "a vertex coordinate is NaN or infinite");
    bb += CGAL::Bbox_3(x, y, z, x, y, z);
  }
  const double diag = std::sqrt(CGAL::square(bb.xmax() - bb.xmin()) +
                                CGAL::square(bb.ymax() - bb.ymin()) +
                                CGAL::square(bb.zmax() - bb.zmin()));
  // products of up to three coordinate differences must stay finite (NaN positions otherwise)
  if (!(diag <= 1e100))
    return fail(Status::non_finite_input, "coordinates too large: bounding-box diagonal above 1e100");

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
  const double cos_feature = feature_angle > 0 && feature_angle < 180
                                 ? std::cos(feature_angle * CGAL_PI / 180.) : 2.;
  auto pt = [&](vertex_descriptor v) {
    const auto& p = get(vpm, v);
    return Vec3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  };
  auto fnormal = [&](typename GT::halfedge_descriptor h) {
    Vec3 a = pt(source(h, tm)), b = pt(target(h, tm)), c = pt(target(next(h, tm), tm));
    return remesh::cross(b - a, c - a);
  };
  using ECM = typename CGAL::internal_np::Lookup_named_param_def<
      CGAL::internal_np::edge_is_constrained_t, NP,
      CGAL::Static_boolean_property_map<edge_descriptor, false>>::type;
  ECM ecm = choose_parameter(get_parameter(np, CGAL::internal_np::edge_is_constrained),
                             CGAL::Static_boolean_property_map<edge_descriptor, false>());
  auto is_feature = [&](edge_descriptor e) {
    if (has_ecm && get(ecm, e)) return true;
    if (cos_feature > 1.) return false;
    auto h = halfedge(e, tm);
    Vec3 n1 = fnormal(h), n2 = fnormal(opposite(h, tm));
    double l = remesh::len(n1) * remesh::len(n2);
    return l > 0 && remesh::dot(n1, n2) < cos_feature * l;
  };
  using VCM = typename CGAL::internal_np::Lookup_named_param_def<
      CGAL::internal_np::vertex_is_constrained_t, NP,
      CGAL::Static_boolean_property_map<vertex_descriptor, false>>::type;
  VCM vcm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_is_constrained),
                             CGAL::Static_boolean_property_map<vertex_descriptor, false>());
  auto is_fixed = [&](vertex_descriptor v) { return bool(get(vcm, v)); };

  Visitor_handle<NP> vis(np);
  Status st = Status::ok;
  {
    remesh::Remesher<TriangleMesh, VPM, parallel> R(tm, vpm);
    R.set_relax_lines(relax_lines);
    vis.start_phase("setup");
    R.setup(in_part, is_feature, is_fixed, protect,
            cos_feature <= 1. ? cos_feature : std::cos(44. * CGAL_PI / 180.));
    vis.end_phase("setup");
    res.feature_edges = R.feature_edges;
    res.corners = R.corners;
    if (mode == Remesh_mode::uniform) {
      res.target_edge_length = value / density;
      R.set_uniform(res.target_edge_length);
      st = R.run(iterations, project, vis);
    } else if (mode == Remesh_mode::adaptive) {
      res.tolerance = value;
      double lmin = choose_parameter(get_parameter(np, internal_np::remesh_min_edge_length), value);
      double lmax =
          choose_parameter(get_parameter(np, internal_np::remesh_max_edge_length), diag / 20.);
      if (!(lmin > 0) || !(lmax >= lmin) || !std::isfinite(lmax))
        return fail(Status::invalid_parameter, "need 0 < remesh_min_edge_length <= remesh_max_edge_length");
      R.set_adaptive(value, lmin / density, lmax / density, gamma);
      const auto& s = R.reference().sizing;
      res.min_target = s.empty() ? 0 : *std::min_element(s.begin(), s.end());
      res.max_target = s.empty() ? 0 : *std::max_element(s.begin(), s.end());
      st = R.run(iterations, project, vis);
    } else {
      // face count: L from the area (equilateral triangles), then corrected
      double area = 0;
      const auto& rf = R.reference();
      for (const auto& t : rf.triangles)
        area += 0.5 * remesh::len(remesh::cross(rf.points[t[1]] - rf.points[t[0]],
                                                rf.points[t[2]] - rf.points[t[0]]));
      const double N = value;
      res.target_faces = static_cast<std::size_t>(N);
      double L = std::sqrt(4. * area / (std::sqrt(3.) * N));
      // a few very long, thin triangles have little area but would be split
      // into edge length / L pieces (out of memory): keep the splits to ~100 N
      double perimeters = 0;
      for (const auto& t : rf.triangles)
        for (int k = 0; k < 3; ++k)
          perimeters += remesh::len(rf.points[t[(k + 1) % 3]] - rf.points[t[k]]);
      L = std::max(L, perimeters / (200. * N));
      const std::size_t outside = whole ? 0 : res.faces_before - rf.triangles.size();
      // Surfaces far thinner than L in one direction (a stray far vertex) make
      // splits and collapses undo each other without converging: a budget of
      // ~100 operations per input and output face bounds the time.
      R.set_operation_budget(100 * (rf.triangles.size() + static_cast<std::size_t>(N)));
      R.set_uniform(L);
      st = R.run(std::max(iterations, 1), project, vis);
      for (int round = 0; round < 6 && st == Status::ok; ++round) {
        double F = static_cast<double>(faces(tm).size() - outside);
        if (std::abs(F - N) <= 0.04 * N) break;
        L *= std::sqrt(F / N);
        R.set_uniform(L);
        st = R.run(3, project, vis);
      }
      res.target_edge_length = L;
    }
    if (st == Status::ok || st == Status::cancelled || st == Status::partial) R.write_back();
    if (has_ecm)
      for (edge_descriptor e : edges(tm)) put(ecm, e, R.is_feature(e));
    res.iterations = R.counters.iterations;
    res.splits = R.counters.splits;
    res.collapses = R.counters.collapses;
    res.flips = R.counters.flips;
  }
  // descriptors of the untouched rest stay valid when remeshing a part
  if (whole) remesh_collect_garbage(tm);
  res.status = st;
  if (st == Status::cancelled) res.message = "cancelled by the visitor; the mesh is valid";
  if (st == Status::partial)
    res.message = "operation budget spent before reaching the face count (surface too thin or "
                  "anisotropic for the target); the mesh is valid";
  res.faces_after = static_cast<std::size_t>(faces(tm).size());
  res.vertices_after = static_cast<std::size_t>(vertices(tm).size());
  return res;
}

} // namespace internal

/// \ingroup mrepair_remesh
/// remeshes `tm` into a uniform isotropic mesh of edge length `target_edge_length`,
/// keeping features, corners and boundaries (see the file docs for the loop).
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (default) or `CGAL::Parallel_tag`
///         (relaxation and projection in parallel; Surface_mesh only, others run sequentially)
/// \tparam TriangleMesh model of `MutableFaceGraph`, triangulated
/// \param np optional:
///   - `vertex_point_map` (default `get(CGAL::vertex_point, tm)`)
///   - `number_of_iterations` (int, 10)
///   - `mrepair::parameters::remesh_feature_angle` (degrees, 44; edges whose face normals
///     differ by more are features; <= 0 disables; default -1 when an edge map is given)
///   - `edge_is_constrained_map` (read-write edge -> bool; its edges are features; updated
///     on output to the remeshed features; default none)
///   - `vertex_is_constrained_map` (vertex -> bool, vertices that never move; default none)
///   - `protect_constraints` (bool, false: features and boundary are neither split,
///     collapsed nor moved)
///   - `relax_constraints` (bool, true: feature/boundary vertices slide along their line)
///   - `do_project` (bool, true: back-projection onto the input surface)
///   - `mrepair::parameters::remesh_density_factor` (double, 1: target lengths divided by it)
///   - `visitor` (`mrepair::Default_visitor`; phases "setup", "split", "collapse", "flip", "relax",
///     "cleanup")
/// \pre `CGAL::is_valid_polygon_mesh(tm)`
/// \return `Remeshing_result`; `tm` untouched when `status` reports bad input
///         (`empty_input`, `invalid_mesh`, `non_finite_input`, `invalid_parameter`);
///         `non_finite_input` also when the bounding-box diagonal exceeds 1e100.
///         On `Surface_mesh`, garbage is collected.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename CGAL_NP_TEMPLATE_PARAMETERS>
Remeshing_result isotropic_remesh(TriangleMesh& tm, double target_edge_length,
                                  const CGAL_NP_CLASS& np = CGAL::parameters::default_values())
{
  using Range = std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>;
  return internal::remesh_driver<ConcurrencyTag, TriangleMesh, Range>(
      tm, nullptr, internal::Remesh_mode::uniform, target_edge_length, np);
}

/// \ingroup mrepair_remesh
/// remeshes only the faces of `face_range` (for example a hole patch) to edge length
/// `target_edge_length`; the rest of `tm` keeps its vertices, positions and faces, and
/// vertices on the border of the part stay fixed. Remesh several patches in one call:
/// each call scans the whole mesh once per phase.
/// \param np as `isotropic_remesh(tm, L, np)`
/// \return `Remeshing_result`. Surface_mesh garbage is *not* collected, so that the
///         caller's descriptors of the rest stay valid.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename FaceRange, typename TriangleMesh,
          typename CGAL_NP_TEMPLATE_PARAMETERS>
Remeshing_result isotropic_remesh(const FaceRange& face_range, TriangleMesh& tm,
                                  double target_edge_length,
                                  const CGAL_NP_CLASS& np = CGAL::parameters::default_values())
{
  return internal::remesh_driver<ConcurrencyTag>(tm, &face_range, internal::Remesh_mode::uniform,
                                                 target_edge_length, np);
}

/// \ingroup mrepair_remesh
/// remeshes `tm` with a curvature-adaptive sizing field for approximation tolerance
/// `tolerance` (thesis 3.7: L = sqrt(6 eps / kappa - 3 eps^2), kappa the largest
/// absolute principal curvature of the input).
/// \param np as `isotropic_remesh`, plus
///   - `mrepair::parameters::remesh_min_edge_length` (double, `tolerance`)
///   - `mrepair::parameters::remesh_max_edge_length` (double, bounding-box diagonal / 20)
///   - `mrepair::parameters::remesh_gamma` (double, 1: kappa <- (kappa/kappa_max)^gamma kappa_max)
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename CGAL_NP_TEMPLATE_PARAMETERS>
Remeshing_result adaptive_remesh(TriangleMesh& tm, double tolerance,
                                 const CGAL_NP_CLASS& np = CGAL::parameters::default_values())
{
  using Range = std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>;
  return internal::remesh_driver<ConcurrencyTag, TriangleMesh, Range>(
      tm, nullptr, internal::Remesh_mode::adaptive, tolerance, np);
}

/// \ingroup mrepair_remesh
/// adaptive remeshing of the faces of `face_range` only (see the part overload of
/// `isotropic_remesh`).
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename FaceRange, typename TriangleMesh,
          typename CGAL_NP_TEMPLATE_PARAMETERS>
Remeshing_result adaptive_remesh(const FaceRange& face_range, TriangleMesh& tm, double tolerance,
                                 const CGAL_NP_CLASS& np = CGAL::parameters::default_values())
{
  return internal::remesh_driver<ConcurrencyTag>(tm, &face_range, internal::Remesh_mode::adaptive,
                                                 tolerance, np);
}

/// \ingroup mrepair_remesh
/// uniform remeshing to about `target_faces` faces (within 10% on closed smooth
/// shapes): L is estimated from the area, then corrected from the face count
/// reached, 3 more iterations per correction. Splits plus collapses are capped
/// at 100 per input and per target face: a surface far thinner than the target
/// length in one direction returns `partial` (valid mesh, count not reached).
/// \param np as `isotropic_remesh`
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename CGAL_NP_TEMPLATE_PARAMETERS>
Remeshing_result remesh_to_face_count(TriangleMesh& tm, std::size_t target_faces,
                                      const CGAL_NP_CLASS& np = CGAL::parameters::default_values())
{
  using Range = std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>;
  return internal::remesh_driver<ConcurrencyTag, TriangleMesh, Range>(
      tm, nullptr, internal::Remesh_mode::face_count, static_cast<double>(target_faces), np);
}

} // namespace mrepair

#endif // MREPAIR_ADAPTIVE_REMESH_H
