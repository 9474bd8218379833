// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The input check and the statistics set-up shared by
// repair_near_degenerate_faces.h and relax_spikes.h.
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_COMMON_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_COMMON_H

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
namespace clean_pipeline {

// The checks every cleaning step's public call makes before it edits (the
// pipeline makes them once, on entry): a sound halfedge structure (every walk
// of the steps ends, bounded_walks.h), triangles when the step needs them,
// and coordinates within range. A NaN point is each step's own business
// (the pipeline removes those first). Returns ok, invalid_mesh or
// non_finite_input, with `message`.
template <typename Mesh, typename VPM>
Status check_step_input(const Mesh& m, const VPM& vpm, bool triangles_needed, std::string& message)
{
  if (std::string broken = halfedge_structure_defect(m); !broken.empty()) {
    message = "the mesh's halfedge structure is broken: " + broken;
    return Status::invalid_mesh;
  }
  if (triangles_needed && !CGAL::is_triangle_mesh(m)) {
    message = "the mesh is not triangulated";
    return Status::invalid_mesh;
  }
  if (coordinates_too_large(m, vpm)) {
    message = coordinates_too_large_message;
    return Status::non_finite_input;
  }
  return Status::ok;
}

// Checks what the spike and near-degenerate calls need besides: faces, and
// no non-finite coordinate (their statistics read every vertex). Returns ok,
// empty_input, invalid_mesh or non_finite_input.
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
  return check_step_input(m, vpm, true, message);
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

} // namespace clean_pipeline
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_COMMON_H
