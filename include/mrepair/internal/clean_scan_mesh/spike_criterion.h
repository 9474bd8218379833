// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The one definition of a spiked vertex, shared by relax_spikes() (halfedge
// statistics) and inspect() (flat arrays of meshes and soups), so that the
// inspection counts exactly what the cleaning relaxes:
//  1. an incident edge has a dihedral angle above `spike_angle`, or
//  2. an interior vertex lies farther than `spike_height_factor` x the mean
//     link edge length from the plane of its link (centroid of the link
//     vertices, Newell normal of the link polygon).
// Light on purpose: no mesh type, only doubles.
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKE_CRITERION_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKE_CRITERION_H

#include <mrepair/parameters.h>

#include <cmath>
#include <cstddef>

namespace mrepair {
namespace internal {

/// default of `spike_height_factor`.
constexpr double default_spike_height_factor = 2.0;

/// The height test runs only where the largest incident dihedral angle
/// exceeds 15 degrees. A vertex at least 2 link lengths above its link has
/// steep faces whose normals turn by about 360/valence x sin(slope) > 15
/// degrees between neighbours (valence up to ~20), so no such spike is
/// skipped, and full-mesh scans look at the links of few vertices.
constexpr double spike_height_prefilter_radians = 0.2617993877991494;

/// Sums over the link edges (a, b) of a vertex p, in coordinates relative to
/// p. The link polygon is closed, so its Newell normal does not depend on the
/// origin, and p as origin keeps the sums local (no cancellation). Link edges
/// may come in any order and either orientation, as long as all have the same.
struct Spike_link_sums
{
  double start[3] = {0, 0, 0};   // sum of (a - p): the link vertices, each once
  double newell[3] = {0, 0, 0};  // sum of (a - p) x (b - p)
  double length = 0;             // sum of |b - a|
  std::size_t edges = 0;

  void add(const double* p, const double* a, const double* b)
  {
    const double u[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]};
    const double w[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
    for (int j = 0; j < 3; ++j) start[j] += u[j];
    newell[0] += u[1] * w[2] - u[2] * w[1];
    newell[1] += u[2] * w[0] - u[0] * w[2];
    newell[2] += u[0] * w[1] - u[1] * w[0];
    const double d[3] = {w[0] - u[0], w[1] - u[1], w[2] - u[2]};
    length += std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    ++edges;
  }
};

/// criterion 2 on the sums of a closed link: distance of p from the link
/// plane over the mean link edge length, compared with `height_factor`.
inline bool link_exceeds_spike_height(const Spike_link_sums& s, double height_factor)
{
  if (!(height_factor > 0) || s.edges < 3) return false;
  const double k = static_cast<double>(s.edges);
  const double c[3] = {s.start[0] / k, s.start[1] / k, s.start[2] / k};  // centroid - p
  const double nn = std::sqrt(s.newell[0] * s.newell[0] + s.newell[1] * s.newell[1] +
                              s.newell[2] * s.newell[2]);
  const double link = s.length / k;
  if (!(nn > 0) || !(link > 0)) return false;
  const double dist = std::abs(c[0] * s.newell[0] + c[1] * s.newell[1] + c[2] * s.newell[2]) / nn;
  return dist > height_factor * link;
}

/// criterion 2 with its pre-filter. `gather(Spike_link_sums&)` adds the link
/// edges of the vertex and returns false when it has no closed link (border,
/// non-finite or inconsistently oriented neighbourhood): then it is not spiked
/// by height. `gather` runs only when the pre-filter passes.
template <typename Gather>
bool spiked_by_height(double max_dihedral_radians, double height_factor, Gather&& gather)
{
  if (!(height_factor > 0) || !(max_dihedral_radians > spike_height_prefilter_radians))
    return false;
  Spike_link_sums s;
  if (!gather(s)) return false;
  return link_exceeds_spike_height(s, height_factor);
}

/// criterion 1.
inline bool spiked_by_dihedral(double max_dihedral_radians, double spike_angle_radians)
{
  return max_dihedral_radians > spike_angle_radians;  // false for NaN
}

/// the whole definition.
template <typename Gather>
bool is_spiked_vertex(double max_dihedral_radians, double spike_angle_radians,
                      double height_factor, Gather&& gather)
{
  return spiked_by_dihedral(max_dihedral_radians, spike_angle_radians) ||
         spiked_by_height(max_dihedral_radians, height_factor, gather);
}

}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SPIKE_CRITERION_H
