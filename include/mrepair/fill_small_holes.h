// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_FILL_SMALL_HOLES_H
#define MREPAIR_FILL_SMALL_HOLES_H

#include <mrepair/cleaning_results.h>
#include <mrepair/internal/clean_scan_mesh/hole_filler.h>
#include <mrepair/internal/coordinate_range.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

/// \file fill_small_holes.h
/// RameshCleaner 3.4 and 3.5: small boundary loops are triangulated with
/// Liepa's minimum-weight method (dihedral angle, then area), the patch is
/// refined to the density of the surrounding edges, and holes whose fill
/// would create a complex edge are enlarged by removing their boundary's
/// 1-ring and filled again.

namespace mrepair {

/// \ingroup mrepair_clean
/// fills the holes of `pmesh` whose boundary loop has fewer than
/// `max_hole_vertices` vertices (RameshCleaner 3.4, 3.5).
///
/// \code
/// for each border loop with n < max_hole_vertices vertices:
///   if the cap that closes it has more than max_hole_area_share of the area
///     of its component: leave it open (the border of a sheet, not a hole)
///   triangulate it with Liepa's minimum-weight method (min. max. dihedral
///     angle, then area; existing edges and degenerate triangles excluded)
///   if no valid triangulation exists (the fill would create a complex edge):
///     mark it aborted
///   else remesh the patch to the density of the loop's edges x hole_density_factor
///     (the library's isotropic remesher, 3 iterations, loop protected,
///     vertices projected onto Liepa's patch), fair it if asked
/// repeat at most max_hole_enlargements times while some fills aborted:
///   leave open the loops whose component is under 10x their 1-ring's faces
///   remove the 1-ring faces of the aborted loops (no pinched vertex left)
///   fill the loops this makes if they are still small, else leave them open
/// \endcode
/// A loop with a non-finite vertex is neither filled nor enlarged (listed in
/// `open_holes` with reason "non_finite"). Existing vertices never move;
/// unless the patch is faired, patch vertices lie on Liepa's patch, inside
/// the bounding box of the loop. A remeshed patch with a degenerate or
/// self-intersecting face is dropped and Liepa's patch stays. Faces are
/// removed only by enlargements, so always
/// faces after = faces before - `enlargement_faces_removed` + `faces_added`.
/// Holes at or above the limit are never filled: the paper only polishes
/// large holes (`clean_boundaries()`) and leaves completion to other tools.
///
/// \tparam PolygonMesh model of `MutableFaceGraph` (triangle mesh)
/// \param np optional:
///   - `vertex_point_map` (default: internal point map)
///   - `max_hole_vertices` (std::size_t, default 100, the paper's tables)
///   - `hole_density_factor` (double, default 1): patch edge length over the
///     mean edge length of the loop; above 1 coarser, below 1 denser
///   - `refine_hole_patches` (bool, default true)
///   - `fair_hole_patches` (bool, default false): `CGAL::PMP::fair` on the patch interior
///   - `max_hole_enlargements` (std::size_t, default 3)
///   - `max_hole_area_share` (double, default 0.4; 0: every small loop is a
///     hole): a loop whose cap (the fan from its centroid) has more area than
///     this share of its component is a sheet's border and stays open
///   - `hole_delaunay_above` (std::size_t, default 30): loops with more vertices
///     restrict Liepa's search to the edges of a 3D Delaunay triangulation
///   - `visitor`: phase "fill_small_holes"; `stop_requested()` polled between holes
/// \return `Hole_filling_result`; status `ok`, `partial` (small holes left
///   open, listed with their reason), `invalid_parameter`, `non_finite_input`
///   (coordinates spanning more than 1e100; untouched), `invalid_mesh` (a
///   broken halfedge structure or a face that is not a triangle; untouched)
///   or `cancelled`. The input checks are those of every cleaning step
///   (`check_step_input`, internal/clean_scan_mesh/common.h).
template <typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Hole_filling_result fill_small_holes(PolygonMesh& pmesh,
                                     const NamedParameters& np = CGAL::parameters::default_values())
{
  internal::Visitor_handle<NamedParameters> visitor(np);
  internal::Phase_scope<internal::Visitor_handle<NamedParameters>> phase(visitor,
                                                                         "fill_small_holes");
  Hole_filling_result r = internal::clean_pipeline::fill_small_holes_with(pmesh, np, false, visitor);
  visitor.progress(1.);
  return r;
}

}  // namespace mrepair

#endif  // MREPAIR_FILL_SMALL_HOLES_H
