// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_CLOSE_GAPS_H
#define MREPAIR_CLOSE_GAPS_H

/// \file close_gaps.h
/// Progressive gap closing (Borodin, Novotni, Klein, "Progressive Gap Closing
/// for Mesh Repairing"): boundary vertices are contracted with their nearest
/// boundary vertex or edge in order of distance, so that cracks, narrow gaps
/// and T-junctions between patches close while wider gaps stay open.
/// `close_gaps()` runs it once; `Gap_closing_sequence` steps forward and
/// backward through the contractions.

#include <mrepair/gap_closing_result.h>
#include <mrepair/gap_closing_sequence.h>
#include <mrepair/internal/close_gaps/run.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <limits>
#include <memory>

namespace mrepair {

/// \ingroup mrepair_gaps
/// closes boundary gaps not wider than `tolerance` by vertex-vertex and
/// vertex-edge contraction, nearest pairs first.
///
/// \code
///   seq = Gap_closing_sequence(tm, tolerance, np)
///   while seq.step(tolerance): poll visitor (progress, stop)
///   split pinched vertices (duplicate_non_manifold_vertices) so the output is manifold
/// \endcode
///
/// \tparam TriangleMesh model of `MutableFaceGraph`, triangulated
/// \param tm the mesh, modified in place
/// \param tolerance largest gap closed: absolute, or a fraction of the
///   bounding-box diagonal with `gap_relative_tolerance(true)`. Vertices move by at
///   most `tolerance`.
/// \param np optional named parameters:
///   - `vertex_point_map` (default `get(CGAL::vertex_point, tm)`)
///   - `visitor` (`Default_visitor`): phases "pairing", "closing", "manifold"; progress;
///     stop polled before the first contraction and every 256 contractions
///   - `mrepair::parameters::gap_relative_tolerance(bool)` (false)
///   - `gap_lambda(double)` in [0,1] (0.5): a contracted vertex moves to λv + (1-λ)v'
///   - `gap_snap_distance(double)` (`tolerance`): a projection closer than
///     min(snap, edge length / 3) to an edge end becomes a vertex-vertex contraction
///   - `gap_vertex_selection(map)` / `gap_face_selection(map)` (all): bool property
///     maps restricting the closing to a region
///   - `gap_max_operations(std::size_t)` (unlimited)
///   - `gap_split_pinched_vertices(bool)` (true): split vertices left with several
///     fans at the end, so that the output is manifold
/// \pre `CGAL::is_valid_polygon_mesh(tm)` (checked in debug builds only)
/// \return `Gap_closing_result`; `tm` untouched when `status` reports bad input
///   (`empty_input`, `non_finite_input`, `invalid_mesh`, `invalid_parameter`;
///   `non_finite_input` also when the bounding-box diagonal exceeds 1e100);
///   `cancelled` when the visitor stopped it (the mesh is valid).
template <typename TriangleMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Gap_closing_result close_gaps(TriangleMesh& tm, double tolerance,
                              const NamedParameters& np = CGAL::parameters::default_values())
{
  using VPM = typename CGAL::GetVertexPointMap<TriangleMesh, NamedParameters>::type;
  internal::Visitor_handle<NamedParameters> visitor(np);
  const std::size_t max_ops = internal::get_or(np, internal_np::gap_max_operations,
                                               std::numeric_limits<std::size_t>::max());
  const bool split = internal::get_or(np, internal_np::gap_split_pinched_vertices, true);

  std::unique_ptr<Gap_closing_sequence<TriangleMesh, VPM>> seq;
  {
    internal::Phase_scope<decltype(visitor)> phase(visitor, "pairing");
    seq.reset(new Gap_closing_sequence<TriangleMesh, VPM>(tm, tolerance, np));
  }
  if (seq->status() != Status::ok) return seq->result();
  const bool cancelled = internal::step_to_limit(*seq, visitor, max_ops);
  Gap_closing_result r = seq->result();
  if (split && r.pinched_vertices > 0 && r.status == Status::ok) {
    VPM vpm = CGAL::parameters::choose_parameter(
        CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
        get_property_map(CGAL::vertex_point, tm));
    internal::split_pinched_vertices(tm, vpm, visitor, r);
  }
  if (cancelled) r.status = Status::cancelled;
  return r;
}

} // namespace mrepair

#endif // MREPAIR_CLOSE_GAPS_H
