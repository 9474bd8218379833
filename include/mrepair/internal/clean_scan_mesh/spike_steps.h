// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Adaptor from the pipeline (clean_scan_mesh.h) to the workers of the
// scan-cleaning-I steps (internal/clean_scan_mesh/: spikes, near-degenerate faces),
// called on the pipeline's own local operations without the public faces'
// input checks: each call returns a uniform outcome (status, number of
// changes, report). The geometric
// statistics are computed on first need and attached to the pipeline's local
// operations, which keep them current through every other step's edits;
// they are detached when the adaptor goes.
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKE_STEPS_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKE_STEPS_H

#include <mrepair/geometric_statistics.h>
#include <mrepair/internal/clean_scan_mesh/near_degenerate_faces.h>
#include <mrepair/internal/clean_scan_mesh/spikes.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/parameters.h>
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
  Report report;
};

// the outcome of a step whose result `r` has a status and a report
template <typename Result>
Step_outcome step_outcome(const Result& r, std::size_t changes)
{
  Step_outcome o;
  o.status = r.status;
  o.changes = changes;
  r.to_report(o.report);
  return o;
}

// `NP`: the pipeline's named parameters, forwarded: the steps read their
// settings from them as the public calls do (relax_spikes.h,
// repair_near_degenerate_faces.h).
template <typename PM, typename VPM, typename NP>
class Spike_steps
{
  using Stats = Geometric_statistics<PM, VPM>;
  Local_operations<PM, VPM>& ops_;
  PM& pm_;
  const NP& np_;
  Spike_settings spike_settings_;
  std::unique_ptr<Stats> stats_;
  // the spiked vertices, found again from the statistics' journal (declared
  // after stats_: goes first, and detaches the journal)
  std::unique_ptr<Spike_tracker<PM, VPM>> tracker_;

  Stats& stats()
  {
    if (!stats_) {
      stats_.reset(new Stats(pm_, ops_.vertex_point_map()));
      stats_->compute_all();
      ops_.keep_current(stats_.get());
      tracker_.reset(new Spike_tracker<PM, VPM>(*stats_));
    }
    return *stats_;
  }

public:
  // The pipeline has checked the settings (`settings_are_valid`).
  Spike_steps(Local_operations<PM, VPM>& ops, const NP& np) : ops_(ops), pm_(ops.mesh()), np_(np)
  {
    std::string unused;
    read_spike_settings(np, spike_settings_, unused);
  }
  // true when the settings of both steps read without error
  static bool settings_are_valid(const NP& np, std::string& message)
  {
    Spike_settings s;
    Near_degenerate_settings d;
    return read_spike_settings(np, s, message) && read_near_degenerate_settings(np, 0, d, message);
  }
  Spike_steps(const Spike_steps&) = delete;
  Spike_steps& operator=(const Spike_steps&) = delete;
  ~Spike_steps()
  {
    if (stats_) ops_.keep_current(nullptr);
  }

  template <typename Visitor>
  Step_outcome relax(Visitor& vis)
  {
    Spike_relaxation_result r =
        relax_spikes_with(ops_, stats(), spike_settings_, vis, tracker_.get());
    return step_outcome(r, r.vertices_relaxed);
  }

  template <typename Visitor>
  Step_outcome remove_unrelaxable(Visitor& vis)
  {
    Spike_removal_result r =
        remove_unrelaxable_spikes_with(ops_, stats(), spike_settings_, vis, tracker_.get());
    return step_outcome(r, r.faces_removed + r.dangling_faces_removed);
  }

  template <typename Visitor>
  Step_outcome fix_near_degenerate(Visitor& vis)
  {
    Near_degenerate_settings s;  // the operation cap depends on the current edge count
    std::string unused;
    read_near_degenerate_settings(np_, stats().edge_count(), s, unused);
    Near_degenerate_faces_result r =
        repair_near_degenerate_faces_with(ops_, stats(), s, vis);
    return step_outcome(r, r.edges_collapsed + r.edges_flipped);
  }
};

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKE_STEPS_H
