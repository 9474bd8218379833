// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_RELAX_SPIKES_H
#define MREPAIR_RELAX_SPIKES_H

#include <mrepair/cleaning_results.h>
#include <mrepair/geometric_statistics.h>
#include <mrepair/internal/clean_scan_mesh/common.h>
#include <mrepair/internal/clean_scan_mesh/spikes.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>

#include <string>

/// \file relax_spikes.h
/// Spikes and foldovers (RameshCleaner 3.7, Algorithm 2) and unrelaxable
/// spikes (3.8).
///
/// A vertex is *spiked* when
///  1. (paper) an incident edge has a dihedral angle (angle between the two
///     face normals) above `spike_angle` (default 100 degrees, as `inspect`), or
///  2. (mrepair, second criterion) it is an interior vertex whose distance from
///     the plane of its 1-ring (centroid and Newell normal of the link polygon)
///     exceeds `spike_height_factor` (default 2) x the mean length of its link
///     edges. A tall narrow spike (a vertex pushed 3 to 10 edge lengths off a
///     smooth surface) keeps every dihedral below 90 degrees and is found only
///     by this test; a regular vertex of a smooth or a CAD-like mesh (a cube
///     corner: ~0.6) stays far below 2.
///
/// Relaxation:
/// \code
/// S = spiked vertices; W = n-ring of S (n = relax_rings)
/// while S not empty and i < max_relax_iterations:
///   R = S and its 1-ring, sorted by decreasing weight (Gauss-Seidel: tips first)
///   for v in R: p(v) += w(theta(v)) L(v)     // L uniform Laplacian, boundary-restricted
///   update statistics around R; S = spiked vertices in W
/// w(theta) = 0 for theta <= a, min(1, (theta - a)/(b - a)) above; w = 1 for criterion 2
/// \endcode

namespace mrepair {


/// \ingroup mrepair_clean
/// relaxes spiked vertices and foldovers by a dihedral-weighted Laplacian in
/// an n-ring working region, using and updating `stats` (current for `tm`).
/// \tparam TriangleMesh model of `MutableFaceGraph`, triangulated
/// \param np optional:
///   - `spike_angle` (double, degrees, 100): dihedral criterion
///   - `spike_height_factor` (double, 2): height criterion (see file doc); 0 disables
///   - `relax_start_angle` (double, degrees, spike_angle/2): a of eq. (2)
///   - `relax_full_angle` (double, degrees, spike_angle): b of eq. (2)
///   - `relax_rings` (std::size_t, 3): n of the working region
///   - `max_relax_iterations` (std::size_t, 10)
///   - `visitor` (`Default_visitor`): phase "relax_spikes", progress, cancellation
/// \return ok when no spiked vertex is left in the working region, partial otherwise
///   (call `remove_unrelaxable_spikes()`), cancelled, invalid_parameter.
template <typename TriangleMesh, typename VPM, typename CGAL_NP_TEMPLATE_PARAMETERS>
Spike_relaxation_result relax_spikes(TriangleMesh& tm, Geometric_statistics<TriangleMesh, VPM>& stats,
                                     const CGAL_NP_CLASS& np = parameters::default_values())
{
  return internal::clean_pipeline::run_spike_call<Spike_relaxation_result>(
      tm, stats, np, "relax_spikes", [](auto& ops, auto& st, const auto& s, auto& vis) {
        return internal::clean_pipeline::relax_spikes_with(ops, st, s, vis);
      });
}

/// \ingroup mrepair_clean
/// same, computing the statistics itself.
/// \param np also `vertex_point_map`. Non-finite coordinates give
///   `non_finite_input`, non-triangle faces `invalid_mesh`, no faces
///   `empty_input`, the mesh untouched.
template <typename TriangleMesh, typename CGAL_NP_TEMPLATE_PARAMETERS>
Spike_relaxation_result relax_spikes(TriangleMesh& tm,
                                     const CGAL_NP_CLASS& np = parameters::default_values())
{
  return internal::clean_pipeline::with_fresh_statistics(
      tm, np, Spike_relaxation_result(), [&](auto& stats) { return relax_spikes(tm, stats, np); });
}

/// \ingroup mrepair_clean
/// removes the vertices that are still spiked (RameshCleaner 3.8: micro
/// tunnels, severe foldovers; run `relax_spikes()` first) with their incident
/// faces. A vertex left with two fans is made manifold by removing its smaller
/// fans. The holes are left for the hole filler and counted in `boundary_loops`.
/// Uses and updates `stats`.
/// \param np optional: `spike_angle` (100), `spike_height_factor` (2),
///   `max_spike_removal_rounds` (std::size_t, 3: vertices spiked along the new
///   boundary are removed in further rounds), `visitor` (phase "remove_unrelaxable_spikes").
template <typename TriangleMesh, typename VPM, typename CGAL_NP_TEMPLATE_PARAMETERS>
Spike_removal_result remove_unrelaxable_spikes(TriangleMesh& tm,
                                               Geometric_statistics<TriangleMesh, VPM>& stats,
                                               const CGAL_NP_CLASS& np = parameters::default_values())
{
  return internal::clean_pipeline::run_spike_call<Spike_removal_result>(
      tm, stats, np, "remove_unrelaxable_spikes", [](auto& ops, auto& st, const auto& s, auto& vis) {
        return internal::clean_pipeline::remove_unrelaxable_spikes_with(ops, st, s, vis);
      });
}

/// \ingroup mrepair_clean
/// same, computing the statistics itself (input checks as `relax_spikes()`).
template <typename TriangleMesh, typename CGAL_NP_TEMPLATE_PARAMETERS>
Spike_removal_result remove_unrelaxable_spikes(TriangleMesh& tm,
                                               const CGAL_NP_CLASS& np = parameters::default_values())
{
  return internal::clean_pipeline::with_fresh_statistics(
      tm, np, Spike_removal_result(), [&](auto& stats) { return remove_unrelaxable_spikes(tm, stats, np); });
}

} // namespace mrepair

#endif // MREPAIR_RELAX_SPIKES_H
