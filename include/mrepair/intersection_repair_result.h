// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The result of resolve_intersections(), apart from the algorithm so that the
// repair job's result and its worker can hold one.
#ifndef MREPAIR_INTERSECTION_REPAIR_RESULT_H
#define MREPAIR_INTERSECTION_REPAIR_RESULT_H

#include <mrepair/report.h>
#include <mrepair/status.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace mrepair {

/// \ingroup mrepair_clean
/// what `resolve_intersections()` did.
struct Intersection_repair_result
{
  /// `ok`: no crossing pair left; `partial`: some left (see
  /// `crossing_left_by_reason`); `empty_input`, `invalid_mesh` (not a valid
  /// triangle mesh) and `non_finite_input` (a NaN or infinite coordinate, or
  /// coordinates beyond 1e100) leave the mesh as it was; `cancelled` keeps
  /// the rounds done (the mesh is valid).
  Status status = Status::ok;
  std::string message;
  std::size_t crossing_pairs_before = 0;  ///< pairs of faces that cross (not only touching)
  std::size_t touching_pairs_before = 0;  ///< pairs that only touch at coincident vertices
  std::size_t local_rounds = 0;           ///< rounds of the local repair that ran
  std::size_t local_faces_removed = 0;    ///< around crossings of a shell with itself
  std::size_t local_faces_added = 0;      ///< the patches that replaced them
  std::size_t local_holes_left_open = 0;  ///< loops the local repair could not refill
  /// rounds undone: they left more border loops or components, or no fewer crossings
  std::size_t local_rounds_taken_back = 0;
  std::size_t shells_merged = 0;          ///< closed shells that went into a union
  std::size_t solids_from_unions = 0;     ///< the unions they made
  std::size_t nested_shells_merged = 0;   ///< of the merged: outward shells inside another
  std::size_t union_faces_removed = 0;    ///< the merged shells' faces
  std::size_t union_faces_added = 0;      ///< the unions' faces
  std::size_t unions_failed = 0;          ///< unions refused (non-manifold result, rounding): shells kept
  std::size_t shells_solidified = 0;      ///< closed shells replaced by one solid (winding numbers)
  std::size_t solid_faces_removed = 0;    ///< their faces
  std::size_t solid_faces_added = 0;      ///< the solid's faces
  /// open parts resting on a solid without crossing it (a dome on a body,
  /// its rim on or near the body's surface), closed by caps of their loops
  std::size_t open_parts_capped = 0;
  std::size_t cap_faces_added = 0;        ///< those caps' faces
  /// open shells crossing the solid that bound nothing (sheets): cut where
  /// they enter it, their part inside absorbed (their faces are counted in
  /// the solid's faces removed and added)
  std::size_t sheets_cut = 0;
  std::size_t arrangement_faces = 0;      ///< faces of the (last) exact arrangement
  /// why the solidification left the closed shells as they were (empty: it did
  /// not, or did not run): `arrangement_too_large`, `arrangement_failed`,
  /// `arrangement_not_closed`, `arrangement_empty`, `rounding_left_crossings`
  std::string solidify_note;
  std::size_t crossing_pairs_after = 0;
  std::size_t touching_pairs_after = 0;
  bool intersection_free = false;         ///< no crossing pair left
  /// the crossing pairs left, by reason: `shell_crosses_itself` (the local
  /// repair could not remove it), `open_shells_cross` (a shell with a border
  /// bounds no volume: no union), `inward_shell_crosses` (a cavity shell),
  /// `shells_kept_separate` (merging switched off), `union_failed`
  std::vector<std::pair<std::string, std::size_t>> crossing_left_by_reason;
  /// one line per union: "3 shells of 1200 340 12 (nested) faces -> 1490 faces"
  std::vector<std::string> unions;
  double seconds = 0.;

  template <typename F>
  static void for_each_field(F&& f)
  {
    using R = Intersection_repair_result;
    f("crossing_pairs_before", &R::crossing_pairs_before);
    f("touching_pairs_before", &R::touching_pairs_before);
    f("local_rounds", &R::local_rounds);
    f("local_faces_removed", &R::local_faces_removed);
    f("local_faces_added", &R::local_faces_added);
    f("local_holes_left_open", &R::local_holes_left_open);
    f("local_rounds_taken_back", &R::local_rounds_taken_back);
    f("shells_merged", &R::shells_merged);
    f("solids_from_unions", &R::solids_from_unions);
    f("nested_shells_merged", &R::nested_shells_merged);
    f("union_faces_removed", &R::union_faces_removed);
    f("union_faces_added", &R::union_faces_added);
    f("unions_failed", &R::unions_failed);
    f("shells_solidified", &R::shells_solidified);
    f("solid_faces_removed", &R::solid_faces_removed);
    f("solid_faces_added", &R::solid_faces_added);
    f("open_parts_capped", &R::open_parts_capped);
    f("cap_faces_added", &R::cap_faces_added);
    f("sheets_cut", &R::sheets_cut);
    f("arrangement_faces", &R::arrangement_faces);
    f("crossing_pairs_after", &R::crossing_pairs_after);
    f("touching_pairs_after", &R::touching_pairs_after);
    f("intersection_free", &R::intersection_free);
  }

  void to_report(Report& r) const
  {
    r.add("status", to_string(status));
    if (!message.empty()) r.add("message", message);
    for_each_field([&](const char* name, auto member) { r.add(name, this->*member); });
    if (!solidify_note.empty()) r.add("solidify_note", solidify_note);
    if (!unions.empty()) {
      Report& s = r.section("unions");
      for (std::size_t i = 0; i < unions.size(); ++i) s.add(std::to_string(i + 1), unions[i]);
    }
    if (!crossing_left_by_reason.empty()) {
      Report& s = r.section("crossing_left_by_reason");
      for (const auto& x : crossing_left_by_reason) s.add(x.first, x.second);
    }
    r.add("seconds", seconds);
  }
};

} // namespace mrepair

#endif // MREPAIR_INTERSECTION_REPAIR_RESULT_H
