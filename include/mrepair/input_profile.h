// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INPUT_PROFILE_H
#define MREPAIR_INPUT_PROFILE_H

#include <mrepair/input_classification.h>
#include <mrepair/internal/input_profile/classifier.h>
#include <mrepair/parameters.h>

#include <CGAL/boost/graph/properties.h>
#include <CGAL/Named_function_parameters.h>

/// \file input_profile.h
/// Tells a dense scan from a CAD export or print model, so that the
/// scan-cleaning steps of RameshCleaner (spike relaxation, boundary erosion,
/// small-component removal, near-degenerate collapses) run only where their
/// assumptions hold: a surface sampled densely with near-uniform edges, whose
/// defects are noise. On a CAD tessellation the same steps read sharp
/// features as spikes, long thin triangles as defects and separate parts as
/// islands.

namespace mrepair {

/// \ingroup mrepair_clean
/// classifies a triangle mesh as a dense scan or as a CAD / print / modelled
/// mesh.
///
/// A mesh is a scan when all of these hold:
/// - at least 2000 faces (a scan samples a surface densely; small meshes are
///   patches, parts and test cases whose every face matters);
/// - edge lengths are near-uniform: coefficient of variation at most 0.6
///   (scanner and reconstruction output is sampled at one density; CAD
///   tessellations mix long and short edges, with CVs of 0.8 and more);
/// - at most 20% of the interior edges join coplanar faces (within 0.01
///   degree): measured surfaces are noisy, tessellated planes are exact;
/// - at most 10% of the triangles have an angle under 5 degrees (CAD
///   tessellation fans are full of slivers, scans are not).
///
/// Anything else is `cad`. Non-finite points are skipped.
///
/// \param np optional: `vertex_point_map`, `input_profile` (a value other
///   than `automatic` is returned as chosen by the user, with the measures)
template <typename TriangleMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Input_classification classify_input(const TriangleMesh& tm,
                                    const NamedParameters& np = CGAL::parameters::default_values())
{
  auto vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_const_property_map(CGAL::vertex_point, tm));
  const Input_profile asked =
      internal::get_or(np, internal_np::input_profile, Input_profile::automatic);
  return internal::classify_input(tm, vpm, asked);
}

}  // namespace mrepair

#endif  // MREPAIR_INPUT_PROFILE_H
