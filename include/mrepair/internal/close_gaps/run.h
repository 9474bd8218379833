// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_CLOSE_GAPS_RUN_H
#define MREPAIR_INTERNAL_CLOSE_GAPS_RUN_H

// The two stages of `close_gaps()` after the pairing: stepping a
// `Gap_closing_sequence` to its distance limit under the visitor, then
// splitting the pinched vertices left.

#include <mrepair/gap_closing_result.h>
#include <mrepair/internal/close_gaps/gap_closer.h>
#include <mrepair/visitors.h>

#include <CGAL/Polygon_mesh_processing/manifoldness.h>

#include <algorithm>
#include <cstddef>

namespace mrepair {
namespace internal {

/// applies the contractions of `seq` up to its distance limit, at most
/// `max_ops` of them; returns true when the visitor stopped it. The stop is
/// polled before the first contraction (small meshes never reach 256) and
/// every 256 contractions, with the progress.
template <class Sequence, class VisitorHandle>
bool step_to_limit(Sequence& seq, VisitorHandle& visitor, std::size_t max_ops)
{
  Phase_scope<VisitorHandle> phase(visitor, "closing");
  const double limit = seq.max_distance();
  std::size_t n = 0;
  bool cancelled = visitor.stop_requested();
  while (!cancelled && n < max_ops && seq.step(limit)) {
    ++n;
    if ((n & 255) == 0) {
      if (visitor.stop_requested()) {
        cancelled = true;
        break;
      }
      visitor.progress(limit > 0 ? std::min(1.0, seq.current_distance() / limit) : 1.0);
    }
  }
  return cancelled;
}

/// splits the pinched vertices of `tm` (several fans) so that it is manifold,
/// and updates the boundary figures of `r`.
template <class TriangleMesh, class VertexPointMap, class VisitorHandle>
void split_pinched_vertices(TriangleMesh& tm, const VertexPointMap& vpm, VisitorHandle& visitor,
                            Gap_closing_result& r)
{
  Phase_scope<VisitorHandle> phase(visitor, "manifold");
  r.pinched_vertices_split = CGAL::Polygon_mesh_processing::duplicate_non_manifold_vertices(
      tm, CGAL::parameters::vertex_point_map(vpm));
  r.pinched_vertices = 0;
  auto counts = count_boundary(tm);
  r.boundary_edges_after = counts.first;
  r.boundary_loops_after = counts.second;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CLOSE_GAPS_RUN_H
