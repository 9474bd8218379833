// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_REPAIR_NEAR_DEGENERATE_FACES_H
#define MREPAIR_REPAIR_NEAR_DEGENERATE_FACES_H

#include <mrepair/cleaning_results.h>
#include <mrepair/geometric_statistics.h>
#include <mrepair/internal/clean_scan_mesh/common.h>
#include <mrepair/internal/clean_scan_mesh/near_degenerate_faces.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>
#include <mrepair/internal/utility.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>

#include <limits>
#include <string>
#include <vector>

/// \file repair_near_degenerate_faces.h
/// Removes needles and caps by safe edge collapses (RameshCleaner 3.6, Algorithm 1):
/// \code
/// l_g = global mean edge length, l_e = mean of the two vertices' mean edge lengths
/// collapsible(e) = |e| < eps*l_g  or  (|e| < delta*l_e and an opposite angle < skinny_angle)
/// Q = { (1/(|e|+tiny), e, stamp(e)) : e collapsible }   // parallel scoring (with the count)
/// while Q not empty:
///   pop e; skip if its stamp changed (lazy deletion) or e is no longer collapsible
///   for p in [more featured end, midpoint, less featured end]   // boundary end only, if one
///     if link condition and no surviving face turns > max_normal_deviation or degenerates:
///       collapse e to p; update statistics on the 1-ring; push collapsible edges nearby; break
///   otherwise (a cap): flip the edge opposite an obtuse angle of a face of e if the
///     flip passes the same normal test and raises the minimum angle
/// \endcode

namespace mrepair {


/// \ingroup mrepair_clean
/// removes near-degenerate faces (needles, caps, slivers) by safe edge
/// collapses and, for caps, edge flips, using and updating `stats`
/// (which must be current for `tm`; it is current again on return).
/// \tparam TriangleMesh model of `MutableFaceGraph`, triangulated
/// \param np optional:
///   - `zero_edge_factor` (double, 0.1): epsilon; zero edge if shorter than epsilon x global mean
///   - `skinny_edge_factor` (double, 0.25): delta; skinny if shorter than delta x local mean ...
///   - `skinny_angle` (double, degrees, 10): ... with an opposite angle below this
///   - `max_normal_deviation` (double, degrees, 45): a collapse or flip may not turn a face more
///   - `max_degenerate_operations` (std::size_t, 3 x edges + 100): cap on collapses + flips
///   - `visitor` (`Default_visitor`): phase "near_degenerate_faces", progress, cancellation
/// \return `status` ok (none left), partial (some left, see rejected_*), cancelled,
///   invalid_parameter; the mesh is valid in every case.
template <typename TriangleMesh, typename VPM, typename CGAL_NP_TEMPLATE_PARAMETERS>
Near_degenerate_faces_result repair_near_degenerate_faces(
    TriangleMesh& tm, Geometric_statistics<TriangleMesh, VPM>& stats,
    const CGAL_NP_CLASS& np = parameters::default_values())
{
  namespace SC = internal::clean_pipeline;
  internal::Visitor_handle<CGAL_NP_CLASS> vis(np);
  internal::Phase_scope<internal::Visitor_handle<CGAL_NP_CLASS>> phase(vis, "near_degenerate_faces");
  SC::Near_degenerate_settings s;
  Near_degenerate_faces_result r;
  if (!SC::read_near_degenerate_settings(np, stats.edge_count(), s, r.message)) {
    r.status = Status::invalid_parameter;
    return r;
  }
  internal::Local_operations<TriangleMesh, VPM> ops(tm, stats.vertex_point_map());
  ops.keep_current(&stats);
  return SC::repair_near_degenerate_faces_with(ops, stats, s, vis);
}

/// \ingroup mrepair_clean
/// same, computing the statistics itself.
/// \param np also `vertex_point_map` (default: the mesh's); no finite check is
///   skipped: non-finite coordinates give `non_finite_input`, non-triangle faces
///   `invalid_mesh`, no faces `empty_input`, the mesh untouched.
template <typename TriangleMesh, typename CGAL_NP_TEMPLATE_PARAMETERS>
Near_degenerate_faces_result repair_near_degenerate_faces(
    TriangleMesh& tm, const CGAL_NP_CLASS& np = parameters::default_values())
{
  Near_degenerate_faces_result failed;  // the face counts of an untouched mesh
  failed.faces_before = failed.faces_after = internal::face_count(tm);
  return internal::clean_pipeline::with_fresh_statistics(
      tm, np, failed, [&](auto& stats) { return repair_near_degenerate_faces(tm, stats, np); });
}

} // namespace mrepair

#endif // MREPAIR_REPAIR_NEAR_DEGENERATE_FACES_H
