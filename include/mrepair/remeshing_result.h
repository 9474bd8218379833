// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_REMESHING_RESULT_H
#define MREPAIR_REMESHING_RESULT_H

/// \file remeshing_result.h
/// What the remeshing calls of `adaptive_remesh.h` report.

#include <mrepair/report.h>
#include <mrepair/status.h>

#include <cstddef>
#include <string>

namespace mrepair {

/// \ingroup mrepair_remesh
/// outcome of a remeshing call.
struct Remeshing_result
{
  Status status = Status::ok;
  std::string message;
  std::string mode;                   ///< "uniform", "adaptive" or "face_count"
  std::size_t faces_before = 0;
  std::size_t faces_after = 0;
  std::size_t vertices_after = 0;
  std::size_t iterations = 0;         ///< iterations run
  std::size_t splits = 0, collapses = 0, flips = 0;
  std::size_t feature_edges = 0;      ///< input feature edges (user or detected, not boundary)
  std::size_t corners = 0;            ///< vertices kept fixed as corners
  double target_edge_length = 0;      ///< uniform L (final L in face-count mode)
  double tolerance = 0;               ///< adaptive epsilon
  double min_target = 0, max_target = 0;  ///< sizing field range (adaptive)
  std::size_t target_faces = 0;       ///< face-count mode

  void to_report(Report& r) const
  {
    r.add("status", std::string(to_string(status)));
    if (!message.empty()) r.add("message", message);
    r.add("mode", mode);
    r.add("faces_before", faces_before);
    r.add("faces_after", faces_after);
    r.add("vertices_after", vertices_after);
    r.add("iterations", iterations);
    r.add("splits", splits);
    r.add("collapses", collapses);
    r.add("flips", flips);
    r.add("feature_edges", feature_edges);
    r.add("corners", corners);
    if (mode != "adaptive") r.add("target_edge_length", target_edge_length);
    if (mode == "adaptive") {
      r.add("tolerance", tolerance);
      r.add("min_target", min_target);
      r.add("max_target", max_target);
    }
    if (mode == "face_count") r.add("target_faces", target_faces);
  }
};

} // namespace mrepair

#endif // MREPAIR_REMESHING_RESULT_H
