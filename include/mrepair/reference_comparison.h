// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_REFERENCE_COMPARISON_H
#define MREPAIR_REFERENCE_COMPARISON_H

#include <mrepair/report.h>
#include <mrepair/status.h>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace mrepair {

/// \ingroup mrepair_core
/// what `compare_to_reference()` found: how much of a reference (the input of
/// a repair) the output still holds. A reference vertex is *kept* when it lies
/// within `tolerance` of the output surface, or inside a closed part of the
/// output (a part absorbed by a union); otherwise it is *lost*.
struct Reference_comparison
{
  Status status = Status::ok;
  std::string message;
  std::size_t vertices = 0;           ///< reference vertices compared (finite ones)
  std::size_t vertices_skipped = 0;   ///< reference vertices not compared (non-finite)
  std::size_t vertices_lost = 0;      ///< neither within `tolerance` of the output nor inside it
  std::size_t vertices_inside = 0;    ///< farther than `tolerance`, inside a closed part of the output
  /// largest distance from a compared vertex to the output surface (absolute;
  /// infinite when the output has no face and there is a vertex to compare)
  double max_distance = 0.;
  double max_distance_relative = 0.;  ///< `max_distance` / `diagonal`
  double diagonal = 0.;               ///< bounding-box diagonal of the compared vertices
  double tolerance = 0.;              ///< distance under which a vertex is on the output
  /// the output has closed parts, so "inside" was tested (an open surface
  /// encloses nothing: there only the distance counts)
  bool inside_tested = false;
  /// indices (into the reference range) of the lost vertices, in increasing order
  std::vector<std::size_t> lost;

  /// writes the figures (not the list of lost vertices) into `r`.
  void to_report(Report& r) const
  {
    r.add("status", status);
    if (!message.empty()) r.add("message", message);
    r.add("vertices", vertices);
    r.add("vertices_lost", vertices_lost);
    r.add("max_distance", max_distance);
    r.add("max_distance_relative", max_distance_relative);
    r.add("vertices_inside", vertices_inside);
    if (vertices_skipped) r.add("vertices_skipped", vertices_skipped);
    r.add("tolerance", tolerance);
    r.add("diagonal", diagonal);
    r.add("inside_tested", inside_tested);
  }
};

}  // namespace mrepair

#endif  // MREPAIR_REFERENCE_COMPARISON_H
