// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The input check and the statistics set-up shared by
// repair_near_degenerate_faces.h and relax_spikes.h.
#ifndef MREPAIR_INTERNAL_SCAN_CLEAN_COMMON_H
#define MREPAIR_INTERNAL_SCAN_CLEAN_COMMON_H

#include <mrepair/geometric_statistics.h>
#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/utility.h>
#include <mrepair/status.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>
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
  if (internal::face_count(m) == 0) {
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
  if (std::string broken = halfedge_structure_defect(m); !broken.empty()) {
    message = "the mesh's halfedge structure is broken: " + broken;
    return Status::invalid_mesh;
  }
  if (!CGAL::is_triangle_mesh(m)) {
    message = "the mesh is not triangulated";
    return Status::invalid_mesh;
  }
  return Status::ok;
}

// The overloads that compute the statistics themselves: reads the vertex
// point map of `np`, checks the input (on failure `r` is returned with the
// status and message, the mesh untouched) and calls `run(stats)` with fresh
// statistics.
template <typename Result, typename Mesh, typename NP, typename Run>
Result with_fresh_statistics(Mesh& tm, const NP& np, Result r, Run&& run)
{
  using VPM = typename CGAL::GetVertexPointMap<Mesh, NP>::type;
  VPM vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, tm));
  r.status = check_input(tm, vpm, r.message);
  if (r.status != Status::ok) return r;
  Geometric_statistics<Mesh, VPM> stats(tm, vpm);
  stats.compute_all();
  return run(stats);
}

} // namespace scan_clean
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_SCAN_CLEAN_COMMON_H
