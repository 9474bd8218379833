// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_REMOVE_SMALL_COMPONENTS_H
#define MREPAIR_REMOVE_SMALL_COMPONENTS_H

#include <mrepair/cleaning_results.h>
#include <mrepair/internal/clean_scan_mesh/common.h>
#include <mrepair/internal/clean_scan_mesh/small_components.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Named_function_parameters.h>

#include <cstddef>

/// \file remove_small_components.h
/// RameshCleaner 3.2: removal of small face-connected components by a
/// region growing that stops as soon as a component reaches the threshold, so
/// that large components cost little. "Small" is also relative to the
/// largest component, which is never removed.

namespace mrepair {

/// \ingroup mrepair_clean
/// removes the face-connected components of `pmesh` with fewer than
/// `min_component_faces` faces (RameshCleaner 3.2).
///
/// Components are found by queue-based region growing that stops as soon as a
/// component reaches the threshold (or meets a face known to be in a large
/// component), so the cost is linear in the mesh size whatever the threshold.
/// A component is removed only when it is also small next to the largest
/// component: fewer than `relative_component_size` times its faces and less
/// than that share of its area. The largest component is never removed (so a
/// non-empty mesh is never emptied, and two equal parts both stay).
///
/// \tparam PolygonMesh model of `MutableFaceGraph`
/// \param pmesh a valid polygon mesh
/// \param np optional:
///   - `min_component_faces` (std::size_t, default 400, the paper's tables):
///     components with fewer faces are removed
///   - `relative_component_size` (double in [0, 1], default 0.01): ... and
///     fewer faces and less area than this share of the largest component
///   - `open_debris_only` (bool, default false): remove only open components
///     next to a closed largest component, when they have fewer than 4 faces
///     and enclose nothing (no border loop is a hole by the hole filler's
///     `max_hole_area_share` rule): the stray facets of a print model. Size
///     plays no part: a closed part, or an open one of 4 faces or more, stays
///     however small. The `cad` profile of `clean_scan_mesh()` uses this
///   - `vertex_point_map` (default: internal point map), for the areas
///   - `visitor` (default `Default_visitor`): phase "remove_small_components";
///     `stop_requested()` polled before any change
/// \return `Small_components_result`; `status` is `ok`, `cancelled`,
///   `invalid_parameter` (threshold 0, share outside [0, 1]), `invalid_mesh`
///   (a broken halfedge structure) or `non_finite_input` (coordinates spanning
///   more than 1e100), the last two with the mesh untouched; `pmesh` stays valid
template <typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Small_components_result remove_small_components(
    PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values())
{
  internal::Visitor_handle<NamedParameters> visitor(np);
  internal::Phase_scope<internal::Visitor_handle<NamedParameters>> phase(
      visitor, "remove_small_components");
  const std::size_t threshold =
      internal::get_or(np, internal_np::min_component_faces, defaults::min_component_faces);
  const double relative = internal::get_or(np, internal_np::relative_component_size, defaults::relative_component_size);
  const bool debris = internal::get_or(np, internal_np::open_debris_only, false);
  auto vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, pmesh));
  Small_components_result r;
  if (threshold == 0 || !(relative >= 0. && relative <= 1.)) {
    r.status = Status::invalid_parameter;
    return r;
  }
  std::string unused;  // the result has no message; polygon meshes are fine here
  r.status = internal::clean_pipeline::check_step_input(pmesh, vpm, false, unused);
  if (r.status != Status::ok) return r;
  if (visitor.stop_requested()) {
    r.status = Status::cancelled;
    return r;
  }
  internal::Local_operations<PolygonMesh, decltype(vpm)> ops(pmesh, vpm);
  r = internal::clean_pipeline::remove_small_components_seeded(
      ops, faces(pmesh), threshold, relative, static_cast<const std::nullptr_t*>(nullptr), debris);
  visitor.progress(1.);
  return r;
}

}  // namespace mrepair

#endif  // MREPAIR_REMOVE_SMALL_COMPONENTS_H
