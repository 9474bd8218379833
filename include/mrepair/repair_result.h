// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The result of repair_polygon_soup() (repair.h), apart from the job so that
// its worker (internal/repair/job.h) fills it without the public header.
#ifndef MREPAIR_REPAIR_RESULT_H
#define MREPAIR_REPAIR_RESULT_H

#include <mrepair/cleaning_results.h>
#include <mrepair/gap_closing_result.h>
#include <mrepair/inspection_report.h>
#include <mrepair/intersection_repair_result.h>
#include <mrepair/report.h>
#include <mrepair/scan_cleaning_result.h>
#include <mrepair/status.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace mrepair {

/// \ingroup mrepair_clean
/// what `repair_polygon_soup()` did.
struct Repair_result
{
  /// `ok` or `partial` (the cleaning's status); `empty_input` when cleaning
  /// found nothing to clean; on failure the status of the stage that failed
  /// (`invalid_parameter` for bad options, `cancelled`).
  Status status = Status::ok;
  std::string failed_stage;   ///< "options", "soup_to_manifold", "close_gaps", "clean" (a polygon mesh that cannot be triangulated takes the soup stage); empty when none failed
  std::string message;        ///< one line: `stage: status[: reason]` on failure
  bool soup_needed = false;   ///< the input was not a manifold, consistently oriented mesh
  /// `out` is final: the cleaning succeeded (or found nothing to clean) and
  /// the solid repair ran, so only the output inspection, which reads it, is
  /// left. Set before the "resolve_intersections" callback of `after_stage`
  /// (before "clean" when that step is off), so a caller may write `out` from there.
  bool output_final = false;
  Inspection_report before;   ///< the input soup
  Inspection_report after;    ///< the output mesh (filled when the job ran to its end)
  Scan_cleaning_result clean; ///< the cleaning pipeline (its `profile` says which ran and why)
  bool intersections_resolved = false;       ///< the step ran (`intersections` is filled)
  Intersection_repair_result intersections;  ///< what it did
  Hole_filling_result holes_after_intersections;  ///< the holes filled after it (when it changed the mesh)
  bool gaps_closed = false;   ///< the gap closing ran (`gaps` is filled)
  Gap_closing_result gaps;    ///< its result: tolerance (and whether estimated), largest displacement
  std::size_t faces_in = 0, faces_out = 0;  ///< in triangles
  std::vector<std::pair<std::string, std::size_t>> faces_removed, faces_added;  ///< by reason
  Report sections;            ///< the report sections of the stages reached, in order

  /// true when faces in + added = faces out + removed.
  bool faces_reconcile() const
  {
    std::size_t rm = 0, ad = 0;
    for (const auto& x : faces_removed) rm += x.second;
    for (const auto& x : faces_added) ad += x.second;
    return faces_in + ad == faces_out + rm;
  }

  /// writes the sections of the stages reached: `before`, `soup_to_manifold`,
  /// `triangulation` (when polygons were triangulated), `close_gaps` (when it ran),
  /// `clean`, `face_accounting`, `after` (the keys of `mrepair repair --json`
  /// without the file sections `input` and `output`).
  void to_report(Report& r) const { r.append(sections); }
};

} // namespace mrepair

#endif // MREPAIR_REPAIR_RESULT_H
