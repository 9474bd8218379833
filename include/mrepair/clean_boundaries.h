// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_CLEAN_BOUNDARIES_H
#define MREPAIR_CLEAN_BOUNDARIES_H

#include <mrepair/cleaning_results.h>
#include <mrepair/internal/clean_scan_mesh/boundaries.h>
#include <mrepair/internal/clean_scan_mesh/common.h>
#include <mrepair/internal/coordinate_range.h>
#include <mrepair/parameters.h>
#include <mrepair/remove_small_components.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>

#include <cstddef>

/// \file clean_boundaries.h
/// RameshCleaner 3.3: removal of bad boundary vertices inside a confidence
/// region around the boundaries, removal of the small components this leaves,
/// and restricted Laplacian smoothing of the boundary 1-ring.

namespace mrepair {

/// \ingroup mrepair_clean
/// cleans and smooths the boundaries of `pmesh` (RameshCleaner 3.3).
///
/// \code
/// R <- n-ring of the boundary vertices (the confidence region)
/// C <- boundary vertices
/// E <- vertices of jagged loops and of local teeth (the safety policy)
/// repeat at most max_boundary_rounds times:
///   B <- bad vertices of C inside R   (valence 2 and in E, or an incident
///                                      dihedral angle > boundary_dihedral_angle,
///                                      or more than 2 incident boundary edges)
///   if B is empty: stop
///   remove the faces of B, within each loop's budget; where a vertex would
///   be pinched (two fans), also remove its smaller fans;
///   C <- surviving vertices of removed faces (they join E)
/// remove the pieces with < boundary_component_faces faces the erosion split off
/// smooth the boundary 1-ring of E with the restricted uniform Laplacian
/// \endcode
/// The mesh stays a valid manifold mesh after every removal.
///
/// Safety policy (doc/guarantees.md): a loop is jagged when the turning it
/// undoes within a vertex or two exceeds `jagged_loop_turning` x 2 pi (a scan
/// border that zigzags); a tooth is a window of 5 border vertices whose
/// undone turning exceeds half that (a dangling ear). Straight and convex
/// borders, and the corners of sheets, are neither: they keep their shape.
/// Each loop loses at most `boundary_erosion_share` of the faces of its
/// confidence region, and components smaller than 4 x
/// `boundary_component_faces` are never removed here (the job of
/// `remove_small_components()`).
///
/// \tparam PolygonMesh model of `MutableFaceGraph` (triangles expected)
/// \param np optional:
///   - `vertex_point_map` (default: internal point map)
///   - `boundary_dihedral_angle` (double, degrees, default 120): dihedral angle
///     (between face normals) above which an incident edge makes a boundary vertex bad
///   - `confidence_rings` (std::size_t, default 4): n of the n-ring region
///   - `max_boundary_rounds` (std::size_t, default 30)
///   - `boundary_component_faces` (std::size_t, default 40): components with
///     fewer faces touching a boundary are removed afterwards (0: none)
///   - `boundary_smoothing_iterations` (std::size_t, default 10)
///   - `boundary_smoothing_step` (double, default 0.02)
///   - `jagged_loop_turning` (double, default 1): see the safety policy above
///   - `boundary_erosion_share` (double in [0, 1], default 0.5)
///   - `visitor`: phase "clean_boundaries"; `stop_requested()` polled between rounds
/// \return `Boundary_cleaning_result`: status `ok`, `partial` (round cap hit
///   with bad vertices left), `non_finite_input` (a region vertex has a
///   non-finite coordinate, or the coordinates span more than 1e100; mesh
///   untouched), `invalid_mesh` (a broken halfedge structure or a face that is
///   not a triangle; untouched), `invalid_parameter`, `cancelled`
template <typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Boundary_cleaning_result clean_boundaries(
    PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values())
{
  internal::Visitor_handle<NamedParameters> visitor(np);
  internal::Phase_scope<internal::Visitor_handle<NamedParameters>> phase(visitor,
                                                                         "clean_boundaries");
  auto vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, pmesh));
  internal::clean_pipeline::Boundary_settings s;
  Boundary_cleaning_result r;
  if (!internal::clean_pipeline::read_boundary_settings(np, s)) {
    r.status = Status::invalid_parameter;
    return r;
  }
  std::string unused;  // the result has no message
  r.status = internal::clean_pipeline::check_step_input(pmesh, vpm, true, unused);
  if (r.status != Status::ok) return r;
  internal::Local_operations<PolygonMesh, decltype(vpm)> ops(pmesh, vpm);
  return internal::clean_pipeline::clean_boundaries_with(ops, s, visitor);
}

}  // namespace mrepair

#endif  // MREPAIR_CLEAN_BOUNDARIES_H
