// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_SCAN_CLEANING_RESULT_H
#define MREPAIR_SCAN_CLEANING_RESULT_H

#include <mrepair/cleaning_results.h>
#include <mrepair/input_classification.h>
#include <mrepair/report.h>
#include <mrepair/status.h>

#include <array>
#include <cstddef>
#include <string>

/// \file scan_cleaning_result.h
/// The steps of `clean_scan_mesh()` (clean_scan_mesh.h) and what it did.

namespace mrepair {

/// \ingroup mrepair_clean
/// the steps of `clean_scan_mesh()`, in pipeline order; combine as a mask.
enum Clean_step : unsigned {
  clean_step_remove_degenerate_vertices = 1u << 0,  ///< non-finite and isolated vertices (preprocessing)
  clean_step_relax_spikes = 1u << 1,                ///< 3.7
  clean_step_remove_unrelaxable_spikes = 1u << 2,   ///< 3.8
  clean_step_clean_boundaries = 1u << 3,            ///< 3.3
  clean_step_remove_small_components = 1u << 4,     ///< 3.2
  clean_step_fill_small_holes = 1u << 5,            ///< 3.4, 3.5
  clean_step_fix_near_degenerate_faces = 1u << 6,   ///< 3.6
  clean_step_relax_spikes_again = 1u << 7,          ///< 3.7 at the end of each iteration
  clean_step_ensure_valid = 1u << 8,                ///< ensure_valid_mesh.h, once at the end
  clean_step_all = 0x1FFu,
  /// the steps of the `cad` profile: the geometry and the parts stay, holes
  /// are closed, validity is restored
  clean_steps_cad = clean_step_remove_degenerate_vertices | clean_step_remove_small_components |
                    clean_step_fill_small_holes | clean_step_ensure_valid
};

constexpr std::size_t number_of_clean_steps = 9;

/// returns the stable name of step number `i` (0 = remove_degenerate_vertices).
inline const char* clean_step_name(std::size_t i)
{
  static const char* names[number_of_clean_steps] = {
      "remove_degenerate_vertices", "relax_spikes",     "remove_unrelaxable_spikes",
      "clean_boundaries",           "remove_small_components", "fill_small_holes",
      "fix_near_degenerate_faces",  "relax_spikes_again",      "ensure_valid_mesh"};
  return i < number_of_clean_steps ? names[i] : "unknown";
}

/// parses a step name (as printed by `clean_step_name`; "relax_spikes" also
/// selects "relax_spikes_again") into a mask; 0 when unknown.
inline unsigned parse_clean_step(const std::string& name)
{
  unsigned m = 0;
  for (std::size_t i = 0; i < number_of_clean_steps; ++i)
    if (name == clean_step_name(i)) m |= 1u << i;
  if (name == "relax_spikes") m |= clean_step_relax_spikes_again;
  return m;
}

/// \ingroup mrepair_clean
/// per-step totals over all iterations of `clean_scan_mesh()`.
struct Clean_step_stats
{
  bool enabled = false;
  bool available = true;   ///< false when the step's implementation is not built in
  std::size_t runs = 0;
  std::size_t changes = 0; ///< elements moved, removed, collapsed or added
  std::size_t faces_removed = 0;  ///< as the local operations counted the step's edits
  std::size_t faces_added = 0;
  double seconds = 0;
  Status last_status = Status::ok;
  Report last_report;      ///< result of the last run
};

/// \ingroup mrepair_clean
/// what `clean_scan_mesh()` did.
struct Scan_cleaning_result
{
  Status status = Status::ok;
  std::string message;
  std::size_t iterations = 0;
  bool converged = false;  ///< the last iteration changed nothing (else the cap was hit)
  std::size_t vertices_before = 0, faces_before = 0, vertices_after = 0, faces_after = 0;
  std::size_t non_finite_vertices_removed = 0;   ///< vertices with a NaN/infinite coordinate
  std::size_t isolated_vertices_removed = 0;     ///< finite vertices without a face (also those the removal of non-finite faces left without one)
  std::size_t faces_removed_with_non_finite = 0; ///< faces of non-finite vertices (and fans removed to avoid pinched vertices)
  std::array<Clean_step_stats, number_of_clean_steps> steps;
  Small_components_result components;   ///< totals over iterations
  Boundary_cleaning_result boundaries;  ///< totals over iterations
  Hole_filling_result holes;            ///< totals; open_holes from the last run
  Validity_result validity;             ///< the final check
  Input_classification profile;         ///< the profile the steps ran with, and why
  double seconds = 0;

  /// faces removed by every step, as the steps counted them
  std::size_t faces_removed() const
  {
    std::size_t n = 0;
    for (const Clean_step_stats& s : steps) n += s.faces_removed;
    return n;
  }
  std::size_t faces_added() const
  {
    std::size_t n = 0;
    for (const Clean_step_stats& s : steps) n += s.faces_added;
    return n;
  }
  /// faces before = faces after + removed - added: no face lost without a reason
  bool faces_reconcile() const
  {
    return faces_before + faces_added() == faces_after + faces_removed();
  }

  void to_report(Report& r) const
  {
    r.add("status", status);
    if (!message.empty()) r.add("message", message);
    r.add("iterations", iterations);
    r.add("converged", converged);
    r.add("vertices_before", vertices_before);
    r.add("faces_before", faces_before);
    r.add("vertices_after", vertices_after);
    r.add("faces_after", faces_after);
    r.add("non_finite_vertices_removed", non_finite_vertices_removed);
    r.add("isolated_vertices_removed", isolated_vertices_removed);
    r.add("faces_removed_with_non_finite", faces_removed_with_non_finite);
    r.add("seconds", seconds);
    profile.to_report(r.section("profile"));
    {
      Report& fa = r.section("face_accounting");
      fa.add("faces_in", faces_before);
      fa.add("faces_out", faces_after);
      Report& rm = fa.section("removed");
      Report& ad = fa.section("added");
      for (std::size_t i = 0; i < number_of_clean_steps; ++i) {
        if (steps[i].faces_removed) rm.add(clean_step_name(i), steps[i].faces_removed);
        if (steps[i].faces_added) ad.add(clean_step_name(i), steps[i].faces_added);
      }
      fa.add("reconciles", faces_reconcile());
    }
    Report& st = r.section("steps");
    for (std::size_t i = 0; i < number_of_clean_steps; ++i) {
      const Clean_step_stats& s = steps[i];
      Report& x = st.section(clean_step_name(i));
      x.add("enabled", s.enabled);
      if (!s.available) x.add("available", false);
      x.add("runs", s.runs);
      x.add("changes", s.changes);
      x.add("seconds", s.seconds);
      if (s.runs) x.section("last") = s.last_report;
    }
    validity.to_report(r.section("validity"));
    components.to_report(r.section("small_components"));
    boundaries.to_report(r.section("boundaries"));
    holes.to_report(r.section("holes"));
  }
};

}  // namespace mrepair

#endif  // MREPAIR_SCAN_CLEANING_RESULT_H
