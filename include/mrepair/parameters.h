// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_PARAMETERS_H
#define MREPAIR_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

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
// Reads parameter `tag` of pack `np`, or `fallback` when the pack lacks it.
template <typename T, typename NamedParameters, typename Tag>
T get_or(const NamedParameters& np, Tag tag, const T& fallback)
{
  return CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tag), fallback);
}
} // namespace internal
} // namespace mrepair

// ---- Parameters shared by several algorithms (defaults are in each doc) -----
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

#endif // MREPAIR_PARAMETERS_H
