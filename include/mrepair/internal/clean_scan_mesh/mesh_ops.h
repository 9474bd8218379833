// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Face geometry shared by the scan-cleaning steps, on any vertex point map
// and any polygon (the edits themselves are in internal/local_operations.h).
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_MESH_OPS_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_MESH_OPS_H

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/number_utils.h>

#include <mrepair/definitions.h>
#include <mrepair/internal/utility.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace mrepair {
namespace internal {
namespace clean_pipeline {

// Non-normalised normal (twice the area) of the polygon of halfedge `h`'s face
// (Newell's method, so it also works on quads).
template <typename PM, typename VPM>
Vec3 face_normal(typename boost::graph_traits<PM>::halfedge_descriptor h, const PM& pm,
                 const VPM& vpm)
{
  Vec3 n{0, 0, 0};
  for (auto hh : CGAL::halfedges_around_face(h, pm)) {
    n += newell_term(point(vpm, source(hh, pm)), point(vpm, target(hh, pm)));
  }
  return n;
}

// Dihedral angle in degrees of the edge of `h`: the angle between the two
// face normals (0 = flat, 180 = folded back onto itself), 0 on a border edge
// and next to a zero-area face, as in Geometric_statistics (definitions.h).
template <typename PM, typename VPM>
double dihedral_angle_deg(typename boost::graph_traits<PM>::halfedge_descriptor h, const PM& pm,
                          const VPM& vpm)
{
  if (is_border_edge(h, pm)) return 0.;
  return to_degrees(face_normal_angle(face_normal(h, pm, vpm), face_normal(opposite(h, pm), pm, vpm)));
}

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_MESH_OPS_H
