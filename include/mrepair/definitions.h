// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_DEFINITIONS_H
#define MREPAIR_DEFINITIONS_H

#include <mrepair/internal/utility.h>

#include <cstddef>

/// \file definitions.h
/// The defect criteria and default thresholds, written once: `inspect()`
/// counts with them, every fixer repairs with them and the command line
/// offers them, so that what the report calls a defect is what the cleaning
/// removes.

namespace mrepair {

/// \ingroup mrepair_core
/// default thresholds (RameshCleaner's values where the paper gives them).
namespace defaults {
/// dihedral angle (degrees) above which an edge makes its vertices spiked (3.7)
constexpr double spike_angle = 100.;
/// zero edge: shorter than this times the global mean edge length (3.6, epsilon)
constexpr double zero_edge_factor = 0.1;
/// skinny edge: shorter than this times its local mean edge length (3.6, delta)
constexpr double skinny_edge_factor = 0.25;
/// a skinny edge makes its face near-degenerate when the opposite angle is
/// below this (degrees)
constexpr double skinny_angle = 10.;
/// boundary loops with fewer vertices are small holes (3.4)
constexpr std::size_t max_hole_vertices = 100;
/// ... for CAD and print models, whose holes are long loops around flat cuts
constexpr std::size_t max_cad_hole_vertices = 500;
/// components with fewer faces are small (3.2, the paper's tables)
constexpr std::size_t min_component_faces = 400;
/// ... and removed only when also under this share of the largest one
constexpr double relative_component_size = 0.01;
/// border faces folded by more than this dihedral angle (degrees) are bad (3.3)
constexpr double boundary_dihedral_angle = 120.;
/// Laplacian iterations of the boundary smoothing (3.3)
constexpr std::size_t boundary_smoothing_iterations = 10;
/// ... and their step (share of the Laplacian applied per iteration)
constexpr double boundary_smoothing_step = 0.02;
/// the n of the n-ring region around bad boundary vertices (3.3)
constexpr std::size_t confidence_rings = 4;
/// rounds of bad boundary vertex removal (3.3)
constexpr std::size_t max_boundary_rounds = 30;
/// components with fewer faces inside a boundary region are removed (3.3)
constexpr std::size_t boundary_component_faces = 40;
/// loops whose jaggedness exceeds this x 2 pi are eroded
constexpr double jagged_loop_turning = 1.;
/// share of a loop's region faces the boundary erosion may remove
constexpr double boundary_erosion_share = 0.5;
/// n of the working region of the spike relaxation (3.7)
constexpr std::size_t relax_rings = 3;
/// relaxation iterations (3.7)
constexpr std::size_t max_relax_iterations = 10;
/// rounds of unrelaxable spike removal along the new boundary (3.8)
constexpr std::size_t max_spike_removal_rounds = 3;
/// degrees a collapse or flip may turn a surviving face (3.6)
constexpr double max_normal_deviation = 45.;
/// hole patch edge length / hole border mean edge length (3.5)
constexpr double hole_density_factor = 1.;
/// enlargements of an aborted fill (3.4)
constexpr std::size_t max_hole_enlargements = 3;
/// loops with more vertices are triangulated in the 3D Delaunay search space
constexpr std::size_t hole_delaunay_above = 30;
/// a loop whose cap exceeds this share of its component's area is a border
constexpr double max_hole_area_share = 0.4;
/// iterations of the cleaning pipeline (section 4: the paper runs 3 to 5)
constexpr std::size_t max_clean_iterations = 5;
/// degrees: a dihedral angle above this makes an edge a feature of the remeshing
constexpr double remesh_feature_angle = 44.;
/// polygons up to which `repair_polygon_soup()` inspects the input beside the soup stage
constexpr std::size_t concurrent_inspection_polygons = 4000000;
}  // namespace defaults

namespace internal {

/// the dihedral angle of an edge from its two face normals (any length):
/// radians in [0, pi], 0 = flat. Next to a zero-area face (zero normal) the
/// angle is undefined and taken as 0: such a face is a near-degenerate or
/// degenerate defect, handled as one, not as a fold.
inline double face_normal_angle(const Vec3& n1, const Vec3& n2)
{
  if (is_zero(n1) || is_zero(n2)) return 0.;
  return angle(n1, n2);
}

/// RameshCleaner 3.6. An edge is a zero edge when it is shorter than
/// `zero_edge_factor` x the global mean edge length, a skinny edge when
/// shorter than `skinny_edge_factor` x its local mean (the mean of its two
/// vertices' mean incident edge lengths). A face is near-degenerate when one
/// of its edges is a zero edge, or a skinny edge whose opposite angle in that
/// face is below `skinny_angle`; such an edge is collapsible.
struct Near_degenerate_criterion
{
  double zero_edge_factor = defaults::zero_edge_factor;
  double skinny_edge_factor = defaults::skinny_edge_factor;
  /// in the unit of the opposite angles given to the tests: radians in the
  /// fixers (halfedge statistics), degrees in `inspect()` (its corner arrays)
  double skinny_angle = to_radians(defaults::skinny_angle);

  bool is_zero_edge(double length, double global_mean) const
  {
    return length < zero_edge_factor * global_mean;
  }
  bool is_skinny_edge(double length, double local_mean) const
  {
    return length < skinny_edge_factor * local_mean;
  }
  bool is_skinny_angle(double angle) const { return angle < skinny_angle; }  // false for NaN
  /// `opposite_is_skinny`: `is_skinny_angle` of the corner facing the edge in
  /// one face (decided once per corner where the angles are computed).
  bool edge_makes_face_near_degenerate(double length, bool opposite_is_skinny, double global_mean,
                                       double local_mean) const
  {
    return is_zero_edge(length, global_mean) || (opposite_is_skinny && is_skinny_edge(length, local_mean));
  }
  /// `opposite_angle`: the corner facing the edge in one face.
  bool edge_makes_face_near_degenerate(double length, double opposite_angle, double global_mean,
                                       double local_mean) const
  {
    return edge_makes_face_near_degenerate(length, is_skinny_angle(opposite_angle), global_mean, local_mean);
  }
};

}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_DEFINITIONS_H
