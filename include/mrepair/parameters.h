// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_PARAMETERS_H
#define MREPAIR_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <optional>
#include <type_traits>

/// \file parameters.h
/// mrepair's named parameters. CGAL generates its member builders
/// (`.geom_traits()`, ...) from a fixed list, so mrepair adds free builders in
/// `mrepair::parameters` with tags in `mrepair::internal_np`; CGAL's own
/// builders are reachable through the same namespace.
///
/// Put mrepair options first in a chain, then CGAL member builders:
/// \code
/// namespace MP = mrepair::parameters;
/// clean(mesh, MP::spike_angle(100., MP::max_hole_vertices(50)).visitor(std::ref(v)));
/// \endcode
/// A `.spike_angle()` member after a CGAL option does not exist.

/// Declares tag `mrepair::internal_np::NAME_t NAME` and the two builders
/// `mrepair::parameters::NAME(value)` (starts a pack) and
/// `mrepair::parameters::NAME(value, pack)` (extends one). Each tag is declared
/// once, here or in the algorithm header that owns it.
#define MREPAIR_ADD_NAMED_PARAMETER(NAME)                                                  \
  namespace mrepair {                                                                       \
  namespace internal_np {                                                                   \
  enum NAME##_t { NAME };                                                                   \
  }                                                                                         \
  namespace parameters {                                                                    \
  template <typename T>                                                                     \
  CGAL::Named_function_parameters<T, mrepair::internal_np::NAME##_t> NAME(const T& t)       \
  {                                                                                         \
    return CGAL::Named_function_parameters<T, mrepair::internal_np::NAME##_t>(t);           \
  }                                                                                         \
  template <typename T, typename CGAL_NP_TEMPLATE_PARAMETERS_NO_DEFAULT>                    \
  CGAL::Named_function_parameters<T, mrepair::internal_np::NAME##_t, CGAL_NP_CLASS> NAME(   \
      const T& t, const CGAL_NP_CLASS& np)                                                  \
  {                                                                                         \
    return CGAL::Named_function_parameters<T, mrepair::internal_np::NAME##_t, CGAL_NP_CLASS>( \
        t, np);                                                                             \
  }                                                                                         \
  }                                                                                         \
  }

namespace mrepair {
namespace parameters {
using namespace CGAL::parameters; // mrepair::parameters::geom_traits, visitor, ...
} // namespace parameters

namespace internal {
template <typename T> struct Is_optional : std::false_type {};
template <typename T> struct Is_optional<std::optional<T>> : std::true_type {};

// The value of parameter `tag` in pack `np`, or `fallback` when the pack
// lacks it. A `std::optional` value counts as absent when empty: a front end
// (the CLI, Python) passes what the user gave, as given or not, and the
// default stays in one place, the algorithm's.
template <typename T, typename NamedParameters, typename Tag>
T get_or(const NamedParameters& np, Tag tag, const T& fallback)
{
  using Value = std::decay_t<decltype(CGAL::parameters::get_parameter(np, tag))>;
  if constexpr (std::is_same_v<Value, CGAL::internal_np::Param_not_found>) {
    return fallback;
  } else {
    const Value& v = CGAL::parameters::get_parameter(np, tag);
    if constexpr (Is_optional<Value>::value)
      return v ? T(*v) : fallback;
    else
      return v;
  }
}

// true when pack `np` holds parameter `tag` with a value (a non-empty
// optional): for the defaults that depend on something else, such as the hole
// limit of the cleaning, which depends on the input's profile.
template <typename NamedParameters, typename Tag>
bool is_given(const NamedParameters& np, Tag tag)
{
  using Value = std::decay_t<decltype(CGAL::parameters::get_parameter(np, tag))>;
  if constexpr (std::is_same_v<Value, CGAL::internal_np::Param_not_found>)
    return false;
  else if constexpr (Is_optional<Value>::value)
    return CGAL::parameters::get_parameter(np, tag).has_value();
  else
    return true;
}
} // namespace internal
} // namespace mrepair

// ---- Parameters shared by several algorithms --------------------------------
// Thresholds used by inspection and by the algorithms that fix the same defect,
// so that `inspect` and the fixer agree on what a defect is.
MREPAIR_ADD_NAMED_PARAMETER(spike_angle)            // degrees, dihedral angle of a spike
MREPAIR_ADD_NAMED_PARAMETER(zero_edge_factor)       // RameshCleaner epsilon (0.1) x global mean
MREPAIR_ADD_NAMED_PARAMETER(skinny_edge_factor)     // RameshCleaner delta (0.25) x local mean
MREPAIR_ADD_NAMED_PARAMETER(skinny_angle)           // degrees, opposite angle of a skinny edge (10)
MREPAIR_ADD_NAMED_PARAMETER(max_hole_vertices)      // small hole: fewer boundary vertices than this
MREPAIR_ADD_NAMED_PARAMETER(min_component_faces)    // small component: fewer faces than this
MREPAIR_ADD_NAMED_PARAMETER(t_junction_tolerance)   // absolute distance for T-junctions/gaps
MREPAIR_ADD_NAMED_PARAMETER(merge_epsilon)          // absolute distance for merging points
MREPAIR_ADD_NAMED_PARAMETER(count_self_intersections) // bool: inspection runs the (costly) test

// ---- Parameters of one algorithm, by the header that documents them --------
// Every tag is declared here, so that a worker in internal/ reads its
// settings without including a public algorithm header. The defaults are
// in definitions.h (`mrepair::defaults`), each written once.
// input_profile.h
MREPAIR_ADD_NAMED_PARAMETER(input_profile)  // mrepair::Input_profile (automatic)
// const Input_classification*: classify_input() of this very mesh, already
// computed by the caller (repair.h), which clean_scan_mesh() then reuses
MREPAIR_ADD_NAMED_PARAMETER(input_classification)
// inspect.h
// Share of triangle angles below this many degrees (quality figure, 30).
MREPAIR_ADD_NAMED_PARAMETER(inspect_small_angle)
// relax_spikes.h
MREPAIR_ADD_NAMED_PARAMETER(relax_start_angle)    // a, degrees (spike_angle / 2)
MREPAIR_ADD_NAMED_PARAMETER(relax_full_angle)     // b, degrees (spike_angle)
MREPAIR_ADD_NAMED_PARAMETER(relax_rings)          // n of the working region (3)
MREPAIR_ADD_NAMED_PARAMETER(max_relax_iterations) // (10)
MREPAIR_ADD_NAMED_PARAMETER(max_spike_removal_rounds) // (3)
MREPAIR_ADD_NAMED_PARAMETER(spike_height_factor)  // second spike criterion (2; 0 disables)
// repair_near_degenerate_faces.h
MREPAIR_ADD_NAMED_PARAMETER(max_normal_deviation)  // degrees; collapse/flip normal test (45)
MREPAIR_ADD_NAMED_PARAMETER(max_degenerate_operations) // cap on collapses + flips
// clean_boundaries.h
MREPAIR_ADD_NAMED_PARAMETER(boundary_dihedral_angle)       // degrees (120)
MREPAIR_ADD_NAMED_PARAMETER(confidence_rings)              // n of the n-ring region (4)
MREPAIR_ADD_NAMED_PARAMETER(max_boundary_rounds)           // removal rounds (30)
MREPAIR_ADD_NAMED_PARAMETER(boundary_component_faces)      // components removed in the region (40)
MREPAIR_ADD_NAMED_PARAMETER(boundary_smoothing_iterations) // (10)
MREPAIR_ADD_NAMED_PARAMETER(boundary_smoothing_step)       // (0.02)
MREPAIR_ADD_NAMED_PARAMETER(jagged_loop_turning)           // loops whose jaggedness exceeds this x 2 pi are eroded (1)
MREPAIR_ADD_NAMED_PARAMETER(boundary_erosion_share)        // share of a loop's region faces removable (0.5)
// remove_small_components.h
MREPAIR_ADD_NAMED_PARAMETER(relative_component_size)  // share of the largest component (0.01)
MREPAIR_ADD_NAMED_PARAMETER(open_debris_only)         // bool: only open bits of < 4 faces enclosing nothing, next to a closed largest component (false)
// fill_small_holes.h
MREPAIR_ADD_NAMED_PARAMETER(hole_density_factor)    // patch edge length / hole boundary mean (1)
MREPAIR_ADD_NAMED_PARAMETER(fair_hole_patches)      // bool, fair patches after refinement (false)
MREPAIR_ADD_NAMED_PARAMETER(refine_hole_patches)    // bool, refine patches (true)
MREPAIR_ADD_NAMED_PARAMETER(max_hole_enlargements)  // enlargements of an aborted fill (3)
MREPAIR_ADD_NAMED_PARAMETER(hole_delaunay_above)    // loops with more vertices use the DT3 search space (30)
MREPAIR_ADD_NAMED_PARAMETER(max_hole_area_share)    // a loop whose cap exceeds this share of its component's area is a border (0.4)
// ensure_valid_mesh.h
MREPAIR_ADD_NAMED_PARAMETER(max_validity_operations)  // operation cap (10 x degenerate faces + 1000)
// clean_scan_mesh.h
MREPAIR_ADD_NAMED_PARAMETER(clean_steps)           // unsigned mask of mrepair::Clean_step (all)
MREPAIR_ADD_NAMED_PARAMETER(max_clean_iterations)  // iteration cap (5)
MREPAIR_ADD_NAMED_PARAMETER(collect_garbage)       // bool, Surface_mesh::collect_garbage at the end (true)
// stitch_soup.h
MREPAIR_ADD_NAMED_PARAMETER(snap_epsilon)     // absolute stitch distance for boundary edges
MREPAIR_ADD_NAMED_PARAMETER(keep_two_sided)   // bool: keep both orientations of a face
MREPAIR_ADD_NAMED_PARAMETER(orient_outward)   // bool: closed components bound a volume
// gap_closing_sequence.h (their meaning: close_gaps.h)
MREPAIR_ADD_NAMED_PARAMETER(gap_lambda)                 // in [0,1], merged position λv+(1-λ)v'
MREPAIR_ADD_NAMED_PARAMETER(gap_snap_distance)          // absolute snap distance to edge endpoints
MREPAIR_ADD_NAMED_PARAMETER(gap_relative_tolerance)     // bool: tolerance x bbox diagonal
MREPAIR_ADD_NAMED_PARAMETER(gap_vertex_selection)       // vertex property map of bool (region)
MREPAIR_ADD_NAMED_PARAMETER(gap_face_selection)         // face property map of bool (region)
MREPAIR_ADD_NAMED_PARAMETER(gap_split_pinched_vertices) // bool: close_gaps makes the output manifold
MREPAIR_ADD_NAMED_PARAMETER(gap_max_operations)         // std::size_t cap on contractions
MREPAIR_ADD_NAMED_PARAMETER(gap_fingerprint_input)      // bool: hash the input so that save() works
MREPAIR_ADD_NAMED_PARAMETER(gap_keep_input_points)      // bool: placements that keep input points on the surface first (false)
// close_gaps.h
MREPAIR_ADD_NAMED_PARAMETER(gap_bridge_max_edges)  // std::size_t: narrow loops bridged at the end (400; 0: none)
MREPAIR_ADD_NAMED_PARAMETER(gap_bridge_first)      // bool: join facing crack rims by strips before contracting (false)
// repair.h
MREPAIR_ADD_NAMED_PARAMETER(gap_tolerance)                  // close gaps narrower than this (model units; 0)
MREPAIR_ADD_NAMED_PARAMETER(automatic_gap_tolerance)        // bool: cad inputs get a derived tolerance (true)
MREPAIR_ADD_NAMED_PARAMETER(resolve_intersections)          // bool: run the solid repair after the cleaning (true)
MREPAIR_ADD_NAMED_PARAMETER(count_input_self_intersections) // bool: ... in the inspection of the input (false)
MREPAIR_ADD_NAMED_PARAMETER(concurrent_inspection_polygons) // std::size_t (4,000,000)
MREPAIR_ADD_NAMED_PARAMETER(after_stage)                    // callable (const char* stage, const Repair_result&)
// resolve_intersections.h
MREPAIR_ADD_NAMED_PARAMETER(merge_overlapping_shells)  // bool: union of overlapping closed shells (true)
MREPAIR_ADD_NAMED_PARAMETER(solidify_closed_shells)    // bool: crossing closed shells -> one solid by winding numbers (true)
MREPAIR_ADD_NAMED_PARAMETER(max_local_rounds)          // rounds of the local repair of a shell crossing itself (3)
// compare_to_reference.h
MREPAIR_ADD_NAMED_PARAMETER(reference_tolerance)  // distance under which a reference vertex is on the output (1e-6 x diagonal)
// adaptive_remesh.h
MREPAIR_ADD_NAMED_PARAMETER(remesh_feature_angle)    // degrees; dihedral angle of a feature edge
MREPAIR_ADD_NAMED_PARAMETER(remesh_min_edge_length)  // adaptive mode: lower clamp of L
MREPAIR_ADD_NAMED_PARAMETER(remesh_max_edge_length)  // adaptive mode: upper clamp of L
MREPAIR_ADD_NAMED_PARAMETER(remesh_gamma)            // adaptive mode: curvature rescaling exponent
MREPAIR_ADD_NAMED_PARAMETER(remesh_density_factor)   // target lengths are divided by this

#endif // MREPAIR_PARAMETERS_H
