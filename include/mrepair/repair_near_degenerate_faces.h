// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_REPAIR_NEAR_DEGENERATE_FACES_H
#define MREPAIR_REPAIR_NEAR_DEGENERATE_FACES_H

#include <mrepair/geometric_statistics.h>
#include <mrepair/internal/scan_clean/common.h>
#include <mrepair/internal/scan_clean/near_degenerate_impl.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

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

MREPAIR_ADD_NAMED_PARAMETER(max_normal_deviation)  // degrees; collapse/flip normal test (45)
MREPAIR_ADD_NAMED_PARAMETER(max_degenerate_operations) // cap on collapses + flips

namespace mrepair {

/// \ingroup mrepair_clean
/// result of `repair_near_degenerate_faces()`.
struct Near_degenerate_faces_result
{
  Status status = Status::ok;
  std::string message;
  std::size_t near_degenerate_faces_before = 0; ///< definition of inspect.h
  std::size_t near_degenerate_faces_after = 0;
  std::size_t collapsible_edges_initial = 0;
  std::size_t edges_collapsed = 0;
  std::size_t edges_flipped = 0;   ///< cap fallback
  std::size_t rejected_link_condition = 0; ///< collapsible edges left: link condition failed
  std::size_t rejected_normal_test = 0;    ///< ... every destination failed the normal test
  std::size_t rejected_boundary = 0;       ///< ... interior edge joining two boundary vertices
  std::size_t faces_before = 0;
  std::size_t faces_after = 0;

  void to_report(Report& r) const
  {
    r.add("status", to_string(status));
    if (!message.empty()) r.add("message", message);
    r.add("near_degenerate_faces_before", near_degenerate_faces_before);
    r.add("near_degenerate_faces_after", near_degenerate_faces_after);
    r.add("collapsible_edges_initial", collapsible_edges_initial);
    r.add("edges_collapsed", edges_collapsed);
    r.add("edges_flipped", edges_flipped);
    r.add("rejected_link_condition", rejected_link_condition);
    r.add("rejected_normal_test", rejected_normal_test);
    r.add("rejected_boundary", rejected_boundary);
    r.add("faces_before", faces_before);
    r.add("faces_after", faces_after);
  }
};

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
  namespace SC = internal::scan_clean;
  Near_degenerate_faces_result r;
  internal::Visitor_handle<CGAL_NP_CLASS> vis(np);
  internal::Phase_scope<internal::Visitor_handle<CGAL_NP_CLASS>> phase(vis, "near_degenerate_faces");
  SC::Near_degenerate_settings s;
  internal::Near_degenerate_criterion& k = s.criterion;
  k.zero_edge_factor =
      internal::get_or<double>(np, internal_np::zero_edge_factor, defaults::zero_edge_factor);
  k.skinny_edge_factor =
      internal::get_or<double>(np, internal_np::skinny_edge_factor, defaults::skinny_edge_factor);
  const double skinny_deg = internal::get_or<double>(np, internal_np::skinny_angle, defaults::skinny_angle);
  const double dev_deg = internal::get_or<double>(np, internal_np::max_normal_deviation, 45.0);
  // default cap: collapses alone cannot exceed |E|; the cap bounds flip sequences
  s.max_operations = internal::get_or<std::size_t>(np, internal_np::max_degenerate_operations,
                                                   3 * stats.edge_count() + 100);
  if (!(k.zero_edge_factor >= 0) || !std::isfinite(k.zero_edge_factor) ||
      !(k.skinny_edge_factor >= 0) || !std::isfinite(k.skinny_edge_factor) ||
      !(skinny_deg >= 0 && skinny_deg <= 180) || !(dev_deg > 0 && dev_deg <= 180)) {
    r.status = Status::invalid_parameter;
    r.message = "zero_edge_factor, skinny_edge_factor >= 0; skinny_angle in [0,180]; "
                "max_normal_deviation in (0,180]";
    return r;
  }
  k.skinny_angle = internal::to_radians(skinny_deg);
  s.max_normal_deviation = internal::to_radians(dev_deg);
  r.faces_before = faces(tm).size();
  std::vector<typename boost::graph_traits<TriangleMesh>::halfedge_descriptor> flagged;
  r.near_degenerate_faces_before = SC::count_near_degenerate_faces(stats, s, &flagged);
  SC::Near_degenerate_counts c;
  internal::Local_operations<TriangleMesh, VPM> ops(tm, stats.vertex_point_map());
  ops.keep_current(&stats);
  SC::Near_degenerate_repairer<TriangleMesh, VPM, internal::Visitor_handle<CGAL_NP_CLASS>> worker(
      ops, stats, vis, s, c);
  worker.run(flagged);
  r.collapsible_edges_initial = c.collapsible_edges_initial;
  r.edges_collapsed = c.edges_collapsed;
  r.edges_flipped = c.edges_flipped;
  r.rejected_link_condition = c.rejected_link_condition;
  r.rejected_normal_test = c.rejected_normal_test;
  r.rejected_boundary = c.rejected_boundary;
  r.faces_after = faces(tm).size();
  r.near_degenerate_faces_after = SC::count_near_degenerate_faces(stats, s);
  if (c.cancelled) {
    r.status = Status::cancelled;
    r.message = "cancelled by the visitor";
  } else if (r.near_degenerate_faces_after > 0) {
    r.status = Status::partial;
    if (c.hit_operation_cap) r.message = "max_degenerate_operations reached";
  }
  vis.progress(1.0);
  return r;
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
  using VPM = typename CGAL::GetVertexPointMap<TriangleMesh, CGAL_NP_CLASS>::type;
  VPM vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, tm));
  Near_degenerate_faces_result r;
  r.status = internal::scan_clean::check_input(tm, vpm, r.message);
  if (r.status != Status::ok) {
    r.faces_before = r.faces_after = faces(tm).size();
    return r;
  }
  Geometric_statistics<TriangleMesh, VPM> stats(tm, vpm);
  stats.compute_all();
  return repair_near_degenerate_faces(tm, stats, np);
}

} // namespace mrepair

#endif // MREPAIR_REPAIR_NEAR_DEGENERATE_FACES_H
