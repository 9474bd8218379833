// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Adaptor from the pipeline (clean_scan_mesh.h) to the scan-cleaning-I steps
// (relax_spikes.h, repair_near_degenerate_faces.h): each call returns a
// uniform outcome (status, number of changes, report). The geometric
// statistics are computed on first need and attached to the pipeline's local
// operations, which keep them current through every other step's edits;
// they are detached when the adaptor goes.
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKE_STEPS_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKE_STEPS_H

#include <mrepair/geometric_statistics.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/parameters.h>
#include <mrepair/relax_spikes.h>
#include <mrepair/repair_near_degenerate_faces.h>
#include <mrepair/report.h>
#include <mrepair/status.h>

#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>

namespace mrepair {
namespace internal {
namespace clean_pipeline {

struct Step_outcome
{
  bool available = true;
  Status status = Status::ok;
  std::size_t changes = 0;  // elements changed (moved, removed, collapsed)
  std::size_t faces_removed = 0, faces_added = 0;  // by the step's own counters
  Report report;
};

template <typename PM, typename VPM>
class Spike_steps
{
  using Stats = Geometric_statistics<PM, VPM>;
  Local_operations<PM, VPM>& ops_;
  PM& pm_;
  double spike_angle_;  // NaN: the default of relax_spikes.h
  std::unique_ptr<Stats> stats_;

  Stats& stats()
  {
    if (!stats_) {
      stats_.reset(new Stats(pm_, ops_.vertex_point_map()));
      stats_->compute_all();
      ops_.keep_current(stats_.get());
    }
    return *stats_;
  }

  // Calls `f(np)` with a pack carrying the visitor and, when set, the spike angle.
  template <typename Visitor, typename F>
  auto with_np(Visitor& vis, F&& f)
  {
    auto np = CGAL::parameters::visitor(std::ref(vis));
    if (std::isnan(spike_angle_)) return f(np);
    return f(mrepair::parameters::spike_angle(spike_angle_, np));
  }

public:
  Spike_steps(Local_operations<PM, VPM>& ops, double spike_angle)
    : ops_(ops), pm_(ops.mesh()), spike_angle_(spike_angle)
  {}
  Spike_steps(const Spike_steps&) = delete;
  Spike_steps& operator=(const Spike_steps&) = delete;
  ~Spike_steps()
  {
    if (stats_) ops_.keep_current(nullptr);
  }

  template <typename Visitor>
  Step_outcome relax(Visitor& vis)
  {
    Step_outcome o;
    Spike_relaxation_result r =
        with_np(vis, [&](const auto& np) { return relax_spikes(pm_, stats(), np); });
    o.status = r.status;
    o.changes = r.vertices_relaxed;
    r.to_report(o.report);
    return o;
  }

  template <typename Visitor>
  Step_outcome remove_unrelaxable(Visitor& vis)
  {
    Step_outcome o;
    Spike_removal_result r =
        with_np(vis, [&](const auto& np) { return remove_unrelaxable_spikes(pm_, stats(), np); });
    o.status = r.status;
    o.changes = r.faces_removed + r.dangling_faces_removed;
    o.faces_removed = r.faces_removed + r.dangling_faces_removed;
    r.to_report(o.report);
    return o;
  }

  template <typename Visitor>
  Step_outcome fix_near_degenerate(Visitor& vis)
  {
    Step_outcome o;
    Near_degenerate_faces_result r = repair_near_degenerate_faces(
        pm_, stats(), CGAL::parameters::visitor(std::ref(vis)));
    o.status = r.status;
    o.changes = r.edges_collapsed + r.edges_flipped;
    o.faces_removed = r.faces_before - r.faces_after;
    r.to_report(o.report);
    return o;
  }
};

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKE_STEPS_H
