// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Helpers shared by repair_near_degenerate_faces.h and relax_spikes.h: input
// checks and a parallel loop over a vector of descriptors.
#ifndef MREPAIR_INTERNAL_SCAN_CLEAN_COMMON_H
#define MREPAIR_INTERNAL_SCAN_CLEAN_COMMON_H

#include <mrepair/geometric_statistics.h>
#include <mrepair/internal/coordinate_range.h>
#include <mrepair/status.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/number_utils.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

#include <cmath>
#include <string>
#include <vector>

namespace mrepair {
namespace internal {
namespace scan_clean {

// Runs f(i) for i in [0, n); in parallel on Surface_mesh (array-backed dynamic
// maps) when TBB is linked and n is large enough to pay for the threads.
template <typename Mesh, typename F>
void parallel_for_index(std::size_t n, const F& f)
{
#ifdef CGAL_LINKED_WITH_TBB
  if (Is_surface_mesh<Mesh>::value && n > 20000) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                      [&](const tbb::blocked_range<std::size_t>& b) {
                        for (std::size_t i = b.begin(); i != b.end(); ++i) f(i);
                      });
    return;
  }
#endif
  for (std::size_t i = 0; i < n; ++i) f(i);
}

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

inline double to_radians(double deg) { return deg * 3.14159265358979323846 / 180.0; }

} // namespace scan_clean
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_SCAN_CLEAN_COMMON_H
