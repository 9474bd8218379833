// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_CLEANING_RESULTS_H
#define MREPAIR_CLEANING_RESULTS_H

#include <mrepair/report.h>
#include <mrepair/status.h>

#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

/// \file cleaning_results.h
/// What the scan-cleaning steps report. Each counter is written once, in its
/// struct's `for_each_field` list: the report keys and the pipeline's totals
/// over iterations are generated from that list.

namespace mrepair {

/// how a field adds up over the iterations of `clean_scan_mesh()`.
namespace totals {
struct sum {};   ///< added
struct last {};  ///< the value of the last run
struct any {};   ///< true once true
}  // namespace totals

namespace internal {

/// writes every field of `x` (in list order) into `r`.
template <typename Result>
void report_fields(const Result& x, Report& r)
{
  Result::for_each_field([&](const char* name, auto member, auto) { r.add(name, x.*member); });
}

/// adds the run `b` to the totals `a`, field by field as the list says.
template <typename Result>
void add_totals(Result& a, const Result& b)
{
  Result::for_each_field([&](const char*, auto member, auto how) {
    using How = decltype(how);
    if constexpr (std::is_same<How, totals::sum>::value)
      a.*member += b.*member;
    else if constexpr (std::is_same<How, totals::any>::value)
      a.*member = a.*member || b.*member;
    else
      a.*member = b.*member;
  });
}

/// writes `status`, `message` when set, then the listed fields: the
/// results whose list leaves the status out (they are not summed).
template <typename Result>
void report_status_and_fields(const Result& x, Report& r)
{
  r.add("status", to_string(x.status));
  if (!x.message.empty()) r.add("message", x.message);
  report_fields(x, r);
}

}  // namespace internal

/// \ingroup mrepair_clean
/// what `relax_spikes()` did.
struct Spike_relaxation_result
{
  Status status = Status::ok;
  std::string message;
  std::size_t spiked_vertices_before = 0;   ///< by either criterion
  std::size_t spiked_by_height_before = 0;  ///< of which only by the height criterion
  std::size_t spiked_vertices_after = 0;    ///< whole mesh
  std::size_t spiked_in_region_after = 0;   ///< in the working region (unrelaxable)
  std::size_t vertices_relaxed = 0;         ///< distinct vertices moved
  std::size_t region_vertices = 0;
  std::size_t iterations = 0;

  template <typename F>
  static void for_each_field(F&& f)
  {
    using R = Spike_relaxation_result;
    f("spiked_vertices_before", &R::spiked_vertices_before, totals::last{});
    f("spiked_by_height_before", &R::spiked_by_height_before, totals::last{});
    f("spiked_vertices_after", &R::spiked_vertices_after, totals::last{});
    f("spiked_in_region_after", &R::spiked_in_region_after, totals::last{});
    f("vertices_relaxed", &R::vertices_relaxed, totals::sum{});
    f("region_vertices", &R::region_vertices, totals::last{});
    f("iterations", &R::iterations, totals::sum{});
  }

  void to_report(Report& r) const { internal::report_status_and_fields(*this, r); }
};

/// \ingroup mrepair_clean
/// what `remove_unrelaxable_spikes()` did.
struct Spike_removal_result
{
  Status status = Status::ok;
  std::string message;
  std::size_t spiked_vertices_found = 0;
  std::size_t vertices_removed = 0;        ///< spiked vertices and vertices left isolated
  std::size_t faces_removed = 0;           ///< faces incident to spiked vertices
  std::size_t dangling_faces_removed = 0;  ///< smaller fans of pinched vertices
  std::size_t pinched_vertices_fixed = 0;
  std::size_t boundary_loops = 0;          ///< boundary loops along the removed region (holes left)
  std::size_t spiked_vertices_after = 0;
  std::size_t rounds = 0;

  template <typename F>
  static void for_each_field(F&& f)
  {
    using R = Spike_removal_result;
    f("spiked_vertices_found", &R::spiked_vertices_found, totals::last{});
    f("vertices_removed", &R::vertices_removed, totals::sum{});
    f("faces_removed", &R::faces_removed, totals::sum{});
    f("dangling_faces_removed", &R::dangling_faces_removed, totals::sum{});
    f("pinched_vertices_fixed", &R::pinched_vertices_fixed, totals::sum{});
    f("boundary_loops", &R::boundary_loops, totals::sum{});
    f("spiked_vertices_after", &R::spiked_vertices_after, totals::last{});
    f("rounds", &R::rounds, totals::sum{});
  }

  void to_report(Report& r) const { internal::report_status_and_fields(*this, r); }
};

/// \ingroup mrepair_clean
/// what `repair_near_degenerate_faces()` did.
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

  template <typename F>
  static void for_each_field(F&& f)
  {
    using R = Near_degenerate_faces_result;
    f("near_degenerate_faces_before", &R::near_degenerate_faces_before, totals::last{});
    f("near_degenerate_faces_after", &R::near_degenerate_faces_after, totals::last{});
    f("collapsible_edges_initial", &R::collapsible_edges_initial, totals::sum{});
    f("edges_collapsed", &R::edges_collapsed, totals::sum{});
    f("edges_flipped", &R::edges_flipped, totals::sum{});
    f("rejected_link_condition", &R::rejected_link_condition, totals::sum{});
    f("rejected_normal_test", &R::rejected_normal_test, totals::sum{});
    f("rejected_boundary", &R::rejected_boundary, totals::sum{});
    f("faces_before", &R::faces_before, totals::last{});
    f("faces_after", &R::faces_after, totals::last{});
  }

  void to_report(Report& r) const { internal::report_status_and_fields(*this, r); }
};

/// \ingroup mrepair_clean
/// what `remove_small_components()` did.
struct Small_components_result
{
  Status status = Status::ok;
  std::size_t components_removed = 0;
  std::size_t faces_removed = 0;
  std::size_t vertices_removed = 0;
  /// small by face count but not small next to the largest component: kept
  std::size_t components_kept_relative = 0;
  /// the largest component was among the small candidates and was kept
  bool kept_largest = false;

  template <typename F>
  static void for_each_field(F&& f)
  {
    using R = Small_components_result;
    f("status", &R::status, totals::last{});
    f("components_removed", &R::components_removed, totals::sum{});
    f("faces_removed", &R::faces_removed, totals::sum{});
    f("vertices_removed", &R::vertices_removed, totals::sum{});
    f("components_kept_relative", &R::components_kept_relative, totals::sum{});
  }

  void to_report(Report& r) const
  {
    internal::report_fields(*this, r);
    if (kept_largest) r.add("kept_largest_small_component", true);
  }
};

/// \ingroup mrepair_clean
/// what `clean_boundaries()` did.
struct Boundary_cleaning_result
{
  Status status = Status::ok;
  std::size_t boundary_vertices = 0;     ///< boundary vertices found at the start
  std::size_t region_vertices = 0;       ///< vertices of the confidence region
  std::size_t rounds = 0;                ///< removal rounds run
  std::size_t bad_vertices_removed = 0;  ///< bad boundary vertices whose faces were removed
  std::size_t bad_vertices_left = 0;     ///< bad boundary vertices left when the round cap hit
  std::size_t faces_removed = 0;         ///< faces removed with bad vertices (pinch fixes included)
  std::size_t pinch_faces_removed = 0;   ///< of which: smaller fans removed at would-be pinched vertices
  std::size_t components_removed = 0;    ///< small components removed in the region
  std::size_t component_faces_removed = 0;
  std::size_t vertices_smoothed = 0;
  std::size_t loops = 0;                 ///< boundary loops found at the start
  std::size_t jagged_loops = 0;          ///< of which jagged: eroded along their length
  std::size_t tooth_vertices = 0;        ///< vertices of local teeth on the other loops: eroded there
  std::size_t loops_at_budget = 0;       ///< loops whose erosion stopped at `boundary_erosion_share`

  template <typename F>
  static void for_each_field(F&& f)
  {
    using R = Boundary_cleaning_result;
    f("status", &R::status, totals::last{});
    f("boundary_vertices", &R::boundary_vertices, totals::last{});
    f("region_vertices", &R::region_vertices, totals::last{});
    f("rounds", &R::rounds, totals::sum{});
    f("bad_vertices_removed", &R::bad_vertices_removed, totals::sum{});
    f("bad_vertices_left", &R::bad_vertices_left, totals::last{});
    f("faces_removed", &R::faces_removed, totals::sum{});
    f("pinch_faces_removed", &R::pinch_faces_removed, totals::sum{});
    f("components_removed", &R::components_removed, totals::sum{});
    f("component_faces_removed", &R::component_faces_removed, totals::sum{});
    f("vertices_smoothed", &R::vertices_smoothed, totals::sum{});
    f("loops", &R::loops, totals::last{});
    f("jagged_loops", &R::jagged_loops, totals::last{});
    f("tooth_vertices", &R::tooth_vertices, totals::sum{});
    f("loops_at_budget", &R::loops_at_budget, totals::sum{});
  }

  void to_report(Report& r) const { internal::report_fields(*this, r); }
};

/// \ingroup mrepair_clean
/// a small hole left open by `fill_small_holes()`.
struct Open_hole
{
  std::size_t vertices = 0;  ///< boundary loop size when it was given up
  std::string reason;        ///< "triangulation_failed", "patch_intersects_surface", "grew_too_large", "component_too_small", "non_finite"
};

/// \ingroup mrepair_clean
/// what `fill_small_holes()` did.
struct Hole_filling_result
{
  Status status = Status::ok;
  std::size_t holes_found = 0;      ///< boundary loops with fewer than max_hole_vertices vertices
  std::size_t holes_filled = 0;     ///< holes closed (after enlargement or not)
  std::size_t holes_too_large = 0;  ///< loops at or above the limit, left open on purpose
  std::size_t sheet_borders = 0;    ///< small loops left open because they border a sheet (cap too large for its component)
  std::size_t aborted_fills = 0;    ///< triangulations that failed (complex edge, degenerate loop) or were taken back
  /// patches taken back because they met the rest of the surface or
  /// themselves (a cap through the model would add self-intersections)
  std::size_t fills_rejected_intersecting = 0;
  std::size_t enlargements = 0;     ///< 1-ring enlargements of aborted holes
  std::size_t enlargement_faces_removed = 0;
  std::size_t faces_added = 0;      ///< net faces of the patches (after refinement)
  std::size_t vertices_added = 0;   ///< patch interior vertices
  std::vector<Open_hole> open_holes;  ///< small holes left open, with the reason (of the last run in totals)

  template <typename F>
  static void for_each_field(F&& f)
  {
    using R = Hole_filling_result;
    f("status", &R::status, totals::last{});
    f("holes_found", &R::holes_found, totals::sum{});
    f("holes_filled", &R::holes_filled, totals::sum{});
    f("holes_too_large", &R::holes_too_large, totals::last{});
    f("sheet_borders", &R::sheet_borders, totals::last{});
    f("aborted_fills", &R::aborted_fills, totals::sum{});
    f("fills_rejected_intersecting", &R::fills_rejected_intersecting, totals::sum{});
    f("enlargements", &R::enlargements, totals::sum{});
    f("enlargement_faces_removed", &R::enlargement_faces_removed, totals::sum{});
    f("faces_added", &R::faces_added, totals::sum{});
    f("vertices_added", &R::vertices_added, totals::sum{});
  }

  void to_report(Report& r) const
  {
    internal::report_fields(*this, r);
    r.add("holes_left_open", open_holes.size());
    std::size_t failed = 0, crossing = 0, grew = 0, nonfinite = 0;
    for (const Open_hole& h : open_holes) {
      if (h.reason == "triangulation_failed") ++failed;
      else if (h.reason == "patch_intersects_surface") ++crossing;
      else if (h.reason == "grew_too_large" || h.reason == "component_too_small") ++grew;
      else ++nonfinite;
    }
    if (!open_holes.empty()) {
      Report& s = r.section("left_open");
      s.add("triangulation_failed", failed);
      s.add("patch_intersects_surface", crossing);
      s.add("grew_too_large", grew);
      s.add("non_finite", nonfinite);
    }
  }
};

namespace internal {
/// totals of hole filling: the open holes are those of the last run.
inline void add_totals(Hole_filling_result& a, const Hole_filling_result& b)
{
  add_totals<Hole_filling_result>(a, b);
  a.open_holes = b.open_holes;
}
/// totals of small-component removal: the largest component was kept in
/// some run (reported only when true, so it is not in the field list).
inline void add_totals(Small_components_result& a, const Small_components_result& b)
{
  add_totals<Small_components_result>(a, b);
  a.kept_largest = a.kept_largest || b.kept_largest;
}
}  // namespace internal

/// \ingroup mrepair_core
/// what `ensure_valid_mesh()` found and did.
struct Validity_result
{
  Status status = Status::ok;
  std::string message;
  std::size_t degenerate_faces_found = 0;
  std::size_t zero_length_edges_collapsed = 0;  ///< no vertex moves
  std::size_t caps_flipped = 0;                 ///< no vertex moves
  std::size_t border_faces_removed = 0;         ///< zero-area faces removed (on a border, or opening a slit)
  std::size_t cap_vertices_collapsed = 0;       ///< a cap's middle vertex moved to an end of its edge
  std::size_t duplicate_faces_removed = 0;
  std::size_t non_manifold_vertices_split = 0;  ///< vertices added by the split
  std::size_t faces_removed_degenerate = 0;     ///< faces removed by the collapses and removals above
  std::size_t degenerate_faces_left = 0;
  std::size_t operations = 0;

  std::size_t faces_removed() const { return faces_removed_degenerate + duplicate_faces_removed; }

  void to_report(Report& r) const
  {
    r.add("status", status);
    if (!message.empty()) r.add("message", message);
    r.add("degenerate_faces_found", degenerate_faces_found);
    r.add("zero_length_edges_collapsed", zero_length_edges_collapsed);
    r.add("caps_flipped", caps_flipped);
    r.add("border_faces_removed", border_faces_removed);
    r.add("cap_vertices_collapsed", cap_vertices_collapsed);
    r.add("faces_removed_degenerate", faces_removed_degenerate);
    r.add("duplicate_faces_removed", duplicate_faces_removed);
    r.add("non_manifold_vertices_split", non_manifold_vertices_split);
    r.add("degenerate_faces_left", degenerate_faces_left);
  }
};

}  // namespace mrepair

#endif  // MREPAIR_CLEANING_RESULTS_H
