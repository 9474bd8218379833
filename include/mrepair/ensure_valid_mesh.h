// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_ENSURE_VALID_MESH_H
#define MREPAIR_ENSURE_VALID_MESH_H

#include <mrepair/cleaning_results.h>
#include <mrepair/internal/ensure_valid_mesh/fixer.h>
#include <mrepair/parameters.h>

#include <CGAL/Named_function_parameters.h>

/// \file ensure_valid_mesh.h
/// The last step of every mrepair command and pipeline: whatever the steps
/// before did, the output has no exactly degenerate face (collinear by the
/// kernel's exact predicate, or with two equal points), no duplicate face
/// and no non-manifold vertex. Degenerate faces are fixed by operations that
/// change no geometry where possible (collapse of a zero-length edge, flip of
/// a cap's longest edge, removal of a zero-area border face), then by the
/// collapse of a cap's middle vertex onto the nearer end of its edge.

namespace mrepair {

/// \ingroup mrepair_core
/// the last check of every mrepair pipeline: fixes exactly degenerate
/// faces, duplicate faces and non-manifold vertices of a triangle mesh, and
/// says what is left.
///
/// \code
/// queue every exactly degenerate face (two equal points, or collinear)
/// while the queue is not empty and the operation cap is not reached:
///   a zero-length edge: collapse it (nothing moves)
///   else, with ab the longest edge and c the middle vertex:
///     ab interior and c not yet joined to the far vertex d: flip ab
///       (splits the triangle across ab at c; nothing moves)
///     ab on the border and c interior: remove the zero-area face
///     else collapse c onto the nearer of a and b when no face turns over
///     (then onto the farther; then either, when no face becomes degenerate)
///     else, when no vertex of the face is on a border, remove it (a slit of
///     zero width opens; no surface is lost)
///   queue the faces this made degenerate
/// remove duplicate faces (two faces on the same three vertices: both when
///   they form a closed two-face pillow, else one)
/// split non-manifold vertices (CGAL::PMP::duplicate_non_manifold_vertices)
/// \endcode
/// Faces with a non-finite point are skipped (the exact predicates need
/// finite input).
///
/// \tparam PolygonMesh model of `MutableFaceGraph`, a triangle mesh
/// \param np optional: `vertex_point_map`, `max_validity_operations`
///   (default 10 x degenerate faces + 1000)
/// \return `Validity_result`: `ok`, `partial` (degenerate faces left, counted
///   and named in `message`), `invalid_mesh` (not a triangle mesh; untouched)
template <typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Validity_result ensure_valid_mesh(PolygonMesh& pmesh,
                                  const NamedParameters& np = CGAL::parameters::default_values())
{
  return internal::ensure_valid_mesh(pmesh, np, true);
}

}  // namespace mrepair

#endif  // MREPAIR_ENSURE_VALID_MESH_H
