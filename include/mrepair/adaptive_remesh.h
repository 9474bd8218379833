// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_ADAPTIVE_REMESH_H
#define MREPAIR_ADAPTIVE_REMESH_H

#include <mrepair/internal/coordinate_range.h>
#include <mrepair/internal/adaptive_remesh/driver.h>
#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/utility.h>
#include <mrepair/definitions.h>
#include <mrepair/parameters.h>
#include <mrepair/remeshing_result.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/tags.h>

#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

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

namespace mrepair {

namespace internal {

// Reads the named parameters of every public overload and checks the input
// (nothing is touched before every check passed), then runs the driver.
// `part` is null for the whole mesh.
template <typename ConcurrencyTag, typename TriangleMesh, typename FaceRange, typename NP>
Remeshing_result remesh_entry(TriangleMesh& tm, const FaceRange* part, Remesh_mode mode,
                              double value, const NP& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  using GT = boost::graph_traits<TriangleMesh>;
  using VPM = typename CGAL::GetVertexPointMap<TriangleMesh, NP>::type;
#ifdef CGAL_LINKED_WITH_TBB
  constexpr bool parallel = std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value;
#else
  static_assert(!std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value,
                "Parallel_tag needs TBB (CGAL_LINKED_WITH_TBB)");
  constexpr bool parallel = false;
#endif

  const Remeshing_result res = start_remeshing_result(tm, mode);
  auto fail = [&](Status s, const std::string& m) { return refuse_remeshing(res, s, m); };

  VPM vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                             get_property_map(CGAL::vertex_point, tm));
  Remesh_options o;
  o.iterations = internal::get_or(np, CGAL::internal_np::number_of_iterations, 10);
  o.protect = choose_parameter(get_parameter(np, CGAL::internal_np::protect_constraints), false);
  o.relax_lines = choose_parameter(get_parameter(np, CGAL::internal_np::relax_constraints), true);
  o.project = choose_parameter(get_parameter(np, CGAL::internal_np::do_project), true);
  o.density = internal::get_or(np, internal_np::remesh_density_factor, 1.);
  o.gamma = internal::get_or(np, internal_np::remesh_gamma, 1.);
  o.collect_garbage = internal::get_or(np, internal_np::collect_garbage, true);
  o.has_ecm = !is_default_parameter<NP, CGAL::internal_np::edge_is_constrained_t>::value;
  // with a user edge map, detect sharp edges only when the angle is given too
  o.feature_angle =
      internal::get_or(np, internal_np::remesh_feature_angle, o.has_ecm ? -1. : defaults::remesh_feature_angle);
  using ECM = typename CGAL::internal_np::Lookup_named_param_def<
      CGAL::internal_np::edge_is_constrained_t, NP,
      CGAL::Static_boolean_property_map<typename GT::edge_descriptor, false>>::type;
  ECM ecm = choose_parameter(get_parameter(np, CGAL::internal_np::edge_is_constrained),
                             CGAL::Static_boolean_property_map<typename GT::edge_descriptor, false>());
  using VCM = typename CGAL::internal_np::Lookup_named_param_def<
      CGAL::internal_np::vertex_is_constrained_t, NP,
      CGAL::Static_boolean_property_map<typename GT::vertex_descriptor, false>>::type;
  VCM vcm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_is_constrained),
                             CGAL::Static_boolean_property_map<typename GT::vertex_descriptor, false>());

  if (!std::isfinite(value) || value <= 0)
    return fail(Status::invalid_parameter, "target must be a positive finite number");
  if (o.iterations < 0) return fail(Status::invalid_parameter, "number_of_iterations must be >= 0");
  if (!(o.density > 0) || !std::isfinite(o.density))
    return fail(Status::invalid_parameter, "remesh_density_factor must be positive");
  if (!(o.gamma > 0) || !std::isfinite(o.gamma))
    return fail(Status::invalid_parameter, "remesh_gamma must be positive");
  if (internal::face_count(tm) == 0) return fail(Status::empty_input, "the mesh has no faces");
  if (std::string broken = internal::halfedge_structure_defect(tm); !broken.empty())
    return fail(Status::invalid_mesh, "the mesh's halfedge structure is broken: " + broken);
  if (!CGAL::is_triangle_mesh(tm))
    return fail(Status::invalid_mesh, "the mesh is not a triangle mesh");
  for (auto v : vertices(tm))
    if (!is_finite_point(vpm, v))
      return fail(Status::non_finite_input, "a vertex coordinate is NaN or infinite");
  const double diag = finite_bbox_diagonal(tm, vpm);
  if (!(diag <= max_bbox_diagonal)) return fail(Status::non_finite_input, coordinates_too_large_message);
  o.has_min_edge_length = !is_default_parameter<NP, internal_np::remesh_min_edge_length_t>::value;
  o.min_edge_length = internal::get_or(np, internal_np::remesh_min_edge_length, value);
  // face count: no upper clamp unless given (a small count needs long edges)
  o.max_edge_length = internal::get_or(np, internal_np::remesh_max_edge_length,
                                       mode == Remesh_mode::face_count ? 2. * diag : diag / 20.);

  Visitor_handle<NP> vis(np);
  return remesh_driver<parallel>(tm, part, mode, value, o, vpm, ecm, vcm, vis, res);
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
///   - `mrepair::parameters::collect_garbage` (bool, true: on `Surface_mesh`, the elements the
///     collapses removed are collected; false leaves them, as CGAL's remeshing does, and saves a
///     pass over every property array, 0.05 s at 1M faces, when the mesh is written next)
/// \pre `CGAL::is_valid_polygon_mesh(tm)`
/// \return `Remeshing_result`; `tm` untouched when `status` reports bad input
///         (`empty_input`, `invalid_mesh`, `non_finite_input`, `invalid_parameter`);
///         `non_finite_input` also when the bounding-box diagonal exceeds 1e100.
///         On `Surface_mesh`, garbage is collected unless `collect_garbage(false)`.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename CGAL_NP_TEMPLATE_PARAMETERS>
Remeshing_result isotropic_remesh(TriangleMesh& tm, double target_edge_length,
                                  const CGAL_NP_CLASS& np = CGAL::parameters::default_values())
{
  using Range = std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>;
  return internal::remesh_entry<ConcurrencyTag, TriangleMesh, Range>(
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
  return internal::remesh_entry<ConcurrencyTag>(tm, &face_range, internal::Remesh_mode::uniform,
                                                 target_edge_length, np);
}

/// \ingroup mrepair_remesh
/// remeshes `tm` with a curvature-adaptive sizing field for approximation tolerance
/// `tolerance` (thesis 3.7: L = sqrt(6 eps / kappa - 3 eps^2), kappa the largest
/// absolute principal curvature of the input). The sizing is lowered where
/// faces deviate more than `tolerance` from the input, and the faces still
/// over it after the last iteration have their longest edge split at the
/// input surface (doc/remeshing.md, items 3 and 7).
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
  return internal::remesh_entry<ConcurrencyTag, TriangleMesh, Range>(
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
  return internal::remesh_entry<ConcurrencyTag>(tm, &face_range, internal::Remesh_mode::adaptive,
                                                 tolerance, np);
}

/// \ingroup mrepair_remesh
/// adaptive remeshing to `target_faces` faces (within 2% on closed smooth
/// shapes): the curvature sizing field and the error control of
/// `adaptive_remesh`, at the tolerance whose field predicts `target_faces`
/// once corrected by a 4-iteration pilot (which measures how far the count
/// reached departs from the prediction on this shape); then the field is
/// scaled by sqrt(faces / (0.99 target)) until the count is within 1% of
/// 0.99 x the target, 3 iterations per correction, and the faces left up to
/// 1.01 x the target go to splits of the faces that deviate most from the
/// input. So a count gets about the accuracy the adaptive mode gives at that
/// count. Splits plus
/// collapses are capped at 100 per input and per target face: a surface far
/// thinner than the target length in one direction returns `partial` (valid
/// mesh, count not reached). So does a count that needs edges longer than
/// `remesh_max_edge_length`: once the whole field sits at it, `res.message`
/// says so and gives the count reached. `res.tolerance` is the tolerance found.
/// \param np as `adaptive_remesh`, except that `remesh_max_edge_length` has no
///        default clamp (twice the bounding-box diagonal) and
///        `remesh_min_edge_length` defaults to the tolerance found
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh,
          typename CGAL_NP_TEMPLATE_PARAMETERS>
Remeshing_result remesh_to_face_count(TriangleMesh& tm, std::size_t target_faces,
                                      const CGAL_NP_CLASS& np = CGAL::parameters::default_values())
{
  using Range = std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>;
  return internal::remesh_entry<ConcurrencyTag, TriangleMesh, Range>(
      tm, nullptr, internal::Remesh_mode::face_count, static_cast<double>(target_faces), np);
}

} // namespace mrepair

#endif // MREPAIR_ADAPTIVE_REMESH_H
