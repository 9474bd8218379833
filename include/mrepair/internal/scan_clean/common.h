// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The input check shared by repair_near_degenerate_faces.h and relax_spikes.h.
#ifndef MREPAIR_INTERNAL_SCAN_CLEAN_COMMON_H
#define MREPAIR_INTERNAL_SCAN_CLEAN_COMMON_H

#include <mrepair/geometric_statistics.h>
#include <mrepair/internal/utility.h>
#include <mrepair/status.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/number_utils.h>

#include <cmath>
#include <string>
#include <vector>

namespace mrepair {
namespace internal {
namespace scan_clean {

// Checks what every scan-cleaning call needs: a triangle mesh with finite
// coordinates within `max_bbox_diagonal`. Returns ok, empty_input,
// invalid_mesh or non_finite_input.
template <typename Mesh, typename VPM>
Status check_input(const Mesh& m, const VPM& vpm, std::string& message)
{
  if (faces(m).size() == 0) {
    message = "the mesh has no faces";
    return Status::empty_input;
  }
  for (auto v : vertices(m)) {
    const auto& p = get(vpm, v);
    if (!std::isfinite(CGAL::to_double(p.x())) || !std::isfinite(CGAL::to_double(p.y())) ||
        !std::isfinite(CGAL::to_double(p.z()))) {
      message = "a vertex has a non-finite coordinate";
      return Status::non_finite_input;
    }
  }
  if (coordinates_too_large(m, vpm)) {
    message = coordinates_too_large_message;
    return Status::non_finite_input;
  }
  if (!CGAL::is_triangle_mesh(m)) {
    message = "the mesh is not triangulated";
    return Status::invalid_mesh;
  }
  return Status::ok;
}

} // namespace scan_clean
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_SCAN_CLEAN_COMMON_H
