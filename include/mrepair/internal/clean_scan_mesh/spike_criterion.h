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

#include <mrepair/internal/utility.h>
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
  Vec3 start{{0, 0, 0}};   // sum of (a - p): the link vertices, each once
  Vec3 newell{{0, 0, 0}};  // sum of (a - p) x (b - p)
  double length = 0;       // sum of |b - a|
  std::size_t edges = 0;

  void add(const double* p, const double* a, const double* b)
  {
    const Vec3 o = load_vec3(p), u = sub(load_vec3(a), o), w = sub(load_vec3(b), o);
    start += u;
    newell += cross(u, w);
    length += norm(sub(w, u));
    ++edges;
  }
};

/// criterion 2 on the sums of a closed link: distance of p from the link
/// plane over the mean link edge length, compared with `height_factor`.
inline bool link_exceeds_spike_height(const Spike_link_sums& s, double height_factor)
{
  if (!(height_factor > 0) || s.edges < 3) return false;
  const double k = static_cast<double>(s.edges);
  const Vec3 c{{s.start[0] / k, s.start[1] / k, s.start[2] / k}};  // centroid - p
  const double nn = norm(s.newell);
  const double link = s.length / k;
  if (!(nn > 0) || !(link > 0)) return false;
  const double dist = std::abs(dot(c, s.newell)) / nn;
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
