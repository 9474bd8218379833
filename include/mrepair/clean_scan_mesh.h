// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_CLEAN_SCAN_MESH_H
#define MREPAIR_CLEAN_SCAN_MESH_H

#include <mrepair/internal/clean_scan_mesh/pipeline.h>
#include <mrepair/parameters.h>
#include <mrepair/scan_cleaning_result.h>

#include <CGAL/Named_function_parameters.h>

/// \file clean_scan_mesh.h
/// The RameshCleaner pipeline (section 4): preprocessing, then iterations of
/// relax spikes, remove unrelaxable spikes, clean boundaries, remove small
/// components, fill small holes, fix near-degenerate faces, relax spikes
/// again; garbage collection at the end.

namespace mrepair {

/// \ingroup mrepair_clean
/// cleans a scanned triangle mesh with the RameshCleaner pipeline (section 4).
///
/// \code
/// profile <- input_profile, or classify_input(pmesh) when automatic
/// steps <- clean_steps if given, else all for a scan and, for a CAD or
///          print model, only: degenerate vertices, open debris of fewer
///          than 4 faces that encloses nothing, next to a closed largest
///          component (remove_small_components with open_debris_only: no
///          part goes for being small), hole filling (Liepa's
///          patch, no refinement, no enlargement, loops up to 500 vertices),
///          the final validity check
/// remove non-finite vertices (with their faces) and isolated vertices
/// repeat at most max_clean_iterations times:
///   relax spikes                     (relax_spikes.h, 3.7)
///   remove unrelaxable spikes        (relax_spikes.h, 3.8)
///   clean boundaries                 (clean_boundaries.h, 3.3)
///   remove small components          (remove_small_components.h, 3.2)
///   fill small holes                 (fill_small_holes.h, 3.4, 3.5)
///   fix near-degenerate faces        (repair_near_degenerate_faces.h, 3.6)
///   relax spikes again               (3.7)
///   stop when the iteration changed nothing, or changed exactly what the
///   previous one did (a cycle: nothing will converge further)
/// ensure a valid output                 (ensure_valid_mesh.h)
/// collect garbage (Surface_mesh)
/// \endcode
/// Safety policy (doc/guarantees.md): the largest component is never
/// removed, and others only when small next to it too; boundary erosion
/// touches jagged loops only and never takes more than `boundary_erosion_share`
/// of a loop's region; a loop whose cap would be large next to its component
/// is a sheet's border and stays open; `faces_reconcile()` holds: every face
/// removed or added is counted by the step that did it.
/// Holes with `max_hole_vertices` vertices or more are never filled and
/// components with `min_component_faces` faces or more never removed: large
/// holes are only polished, as the paper argues. Every step can be disabled.
///
/// \tparam PolygonMesh model of `MutableFaceGraph`, a triangle mesh
/// \param pmesh a valid triangle mesh (manifold, as CGAL halfedge meshes are)
/// \param np optional:
///   - `vertex_point_map` (default: internal point map)
///   - `input_profile` (`Input_profile`, default `automatic`: `classify_input()`)
///   - `clean_steps` (unsigned mask of `Clean_step`; default: by profile)
///   - `max_clean_iterations` (std::size_t, default 5; the paper runs 3 to 5)
///   - `spike_angle` (double, degrees; default: that of `relax_spikes()`)
///   - `min_component_faces` (std::size_t, default 400), `relative_component_size` (0.01)
///   - `max_hole_vertices` (std::size_t, default 100; 500 for the cad profile),
///     `max_hole_area_share` (0.4)
///   - `jagged_loop_turning` (1), `boundary_erosion_share` (0.5): see `clean_boundaries()`
///   - `boundary_dihedral_angle` (double, degrees, default 120)
///   - `hole_density_factor` (double, default 1), `fair_hole_patches` (bool, default false)
///   - `collect_garbage` (bool, default true)
///   - `visitor`: one phase per step ("relax_spikes", ...), inside one phase
///     per iteration ("iteration 1", ...); `stop_requested()` polled by every step
/// \return `Scan_cleaning_result`: status `ok`, `partial` (small holes left
///   open or a step left defects), `empty_input`, `invalid_mesh` (not a
///   triangle mesh; untouched), `non_finite_input` (non-finite coordinates with
///   the preprocessing step disabled, or finite ones spanning more than 1e100;
///   untouched), `invalid_parameter`,
///   `cancelled` (the mesh is valid)
template <typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Scan_cleaning_result clean_scan_mesh(PolygonMesh& pmesh,
                                     const NamedParameters& np = CGAL::parameters::default_values())
{
  return internal::clean_pipeline::run_pipeline(pmesh, np);
}

}  // namespace mrepair

#endif  // MREPAIR_CLEAN_SCAN_MESH_H
