// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The coordinate range the geometry code accepts. Past it, sums of a few
// coordinates (Laplacian averages, midpoints) and products of three coordinate
// differences (normals, areas) overflow to inf and then NaN, so the public
// calls refuse such input with `non_finite_input` before touching the mesh.
#ifndef MREPAIR_INTERNAL_COORDINATE_RANGE_H
#define MREPAIR_INTERNAL_COORDINATE_RANGE_H

#include <CGAL/boost/graph/iterator.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <cmath>

namespace mrepair {
namespace internal {

/// largest accepted bounding-box diagonal (cubes of it stay far below DBL_MAX).
constexpr double max_bbox_diagonal = 1e100;

/// the message of a refusal.
constexpr const char* coordinates_too_large_message =
    "coordinates too large: bounding-box diagonal above 1e100";

/// bounding-box diagonal of the vertices of `g` with finite coordinates
/// (inf when the extent itself overflows; 0 without finite vertices).
template <typename Graph, typename VertexPointMap>
double finite_bbox_diagonal(const Graph& g, const VertexPointMap& vpm)
{
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (auto v : vertices(g)) {
    const auto& p = get(vpm, v);
    const double c[3] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2])) continue;
    for (int d = 0; d < 3; ++d) {
      lo[d] = (std::min)(lo[d], c[d]);
      hi[d] = (std::max)(hi[d], c[d]);
    }
  }
  if (!(lo[0] <= hi[0])) return 0.;
  double s = 0;
  for (int d = 0; d < 3; ++d) s += (hi[d] - lo[d]) * (hi[d] - lo[d]);
  return std::sqrt(s);
}

/// true when the finite vertices of `g` span more than `max_bbox_diagonal`.
template <typename Graph, typename VertexPointMap>
bool coordinates_too_large(const Graph& g, const VertexPointMap& vpm)
{
  return !(finite_bbox_diagonal(g, vpm) <= max_bbox_diagonal);
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_COORDINATE_RANGE_H
