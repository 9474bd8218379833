// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_RESOLVE_INTERSECTIONS_H
#define MREPAIR_RESOLVE_INTERSECTIONS_H

/// \file resolve_intersections.h
/// Solid repair: the crossings of a triangle mesh resolved without losing
/// the model. A shell that crosses itself is repaired locally (its crossing
/// faces and a few rings removed and the holes refilled, MeshFix's method
/// kept local); closed, outward shells
/// that pass through, touch or contain one another become the boundary of
/// their union (CGAL's exact corefinement). Choices and their reasons:
/// doc/solids.md.

#include <mrepair/fill_small_holes.h>
#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/resolve_intersections/crossings.h>
#include <mrepair/internal/resolve_intersections/resolver.h>
#include <mrepair/internal/utility.h>
#include <mrepair/intersection_repair_result.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace mrepair {

/// \ingroup mrepair_clean
/// resolves the crossings of a triangle mesh, keeping every part of the
/// model (doc/solids.md).
///
/// \code
/// pairs <- the crossing face pairs (exact predicates; pairs that only touch
///          at coincident vertices are not crossings)
/// shells that cross themselves, up to max_local_rounds rounds r = 0, 1, ...:
///   remove the faces of their crossing pairs and r rings around them, with
///     the pieces that removal would cut off
///   refill the loops with the hole filler (Liepa, refined; a patch that would
///     cross the surface is taken back; an aborted fill grows by a ring, twice)
///   pairs <- the crossing pairs left
///   a round that leaves more border loops, another number of components, no
///     fewer crossings, more vertices with an edge folded beyond the spike
///     angle around its region, or removes over a third of the shells it touches, is
///     undone (the mesh rebuilt from a copy) and ends the local repair
/// if merge_overlapping_shells:
///   clusters <- closed outward shells joined by crossing pairs, and each
///               closed outward shell with the smallest such shell containing it
///   each cluster -> union by CGAL's corefinement, largest shell first; a
///               shell whose union CGAL refuses stays as it was
/// pairs <- the crossing pairs left (intersection_free when none)
/// \endcode
/// Open shells and inward shells (cavities) take part in no union; a shell
/// that crosses itself takes part only once its local repair removed every
/// crossing. Meshes without crossing and without nested shells are not
/// changed (the cost is the detection).
///
/// \tparam TriangleMesh model of `MutableFaceGraph`, copyable (`CGAL::Surface_mesh`,
///   `CGAL::Polyhedron_3`)
/// \param np optional: `vertex_point_map`; `solidify_closed_shells` (bool,
///   default true); `merge_overlapping_shells` (bool, default true); `max_local_rounds` (std::size_t, default 3; 0: no local
///   repair); `refine_hole_patches` (bool, default true: the local repair's
///   patches are remeshed to the density around them; false keeps Liepa's
///   patch, as the CAD profile does); `visitor` (phase "resolve_intersections", stop polled between rounds)
template <typename TriangleMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Intersection_repair_result resolve_intersections(TriangleMesh& tm,
                                                 const NamedParameters& np = CGAL::parameters::default_values())
{
  using Handle = internal::Visitor_handle<NamedParameters>;
  Handle visitor(np);
  internal::Phase_scope<Handle> phase(visitor, "resolve_intersections");
  internal::Stopwatch clock;
  Intersection_repair_result r;
  auto vpm = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                                get_property_map(CGAL::vertex_point, tm));
  internal::solid::Resolver_settings settings;
  settings.merge_shells = internal::get_or(np, internal_np::merge_overlapping_shells, true);
  settings.solidify = internal::get_or(np, internal_np::solidify_closed_shells, true);
  settings.local_rounds = internal::get_or(np, internal_np::max_local_rounds, std::size_t(3));
  settings.refine_patches = internal::get_or(np, internal_np::refine_hole_patches, true);
  auto finish = [&](Status s, const std::string& message) {
    r.status = s;
    r.message = message;
    r.seconds = clock.seconds();
    visitor.progress(1.);
    return r;
  };
  if (internal::face_count(tm) == 0) return finish(Status::empty_input, "no faces");
  // a NaN corner has no side: no crossing test, no union can use it
  bool finite = true;
  for (auto v : vertices(tm)) {
    const auto& p = get(vpm, v);
    finite = finite && std::isfinite(CGAL::to_double(p.x())) && std::isfinite(CGAL::to_double(p.y())) &&
             std::isfinite(CGAL::to_double(p.z()));
  }
  if (!finite || internal::coordinates_too_large(tm, vpm))
    return finish(Status::non_finite_input, "coordinates not finite or beyond 1e100: mesh left as it was");
  const std::string defect = internal::halfedge_structure_defect(tm);
  if (!defect.empty()) return finish(Status::invalid_mesh, defect);
  // the local structure check above stands for is_valid_polygon_mesh (seconds at 1M faces)
  if (!CGAL::is_triangle_mesh(tm)) return finish(Status::invalid_mesh, "not a triangle mesh: mesh left as it was");
  auto scan = internal::solid::scan_crossings(tm, vpm);
  if (scan.status != Status::ok) return finish(scan.status, "the crossing test could not run");
  internal::solid::Intersection_resolver<TriangleMesh, decltype(vpm)> resolver(tm, vpm, settings);
  const Status s = resolver.run(std::move(scan), visitor);
  const auto& c = resolver.counts;
  r.crossing_pairs_before = c.crossing_before;
  r.touching_pairs_before = c.touching_before;
  r.local_rounds = c.local_rounds;
  r.local_faces_removed = c.local_faces_removed;
  r.local_faces_added = c.local_faces_added;
  r.local_holes_left_open = c.local_holes_left_open;
  r.local_rounds_taken_back = c.local_rounds_taken_back;
  r.shells_merged = c.shells_merged;
  r.solids_from_unions = c.solids_from_unions;
  r.nested_shells_merged = c.nested_shells_merged;
  r.union_faces_removed = c.union_faces_removed;
  r.union_faces_added = c.union_faces_added;
  r.unions_failed = c.unions_failed;
  r.shells_solidified = c.shells_solidified;
  r.solid_faces_removed = c.solid_faces_removed;
  r.solid_faces_added = c.solid_faces_added;
  r.open_parts_capped = c.open_parts_capped;
  r.cap_faces_added = c.cap_faces_added;
  r.sheets_cut = c.sheets_cut;
  r.arrangement_faces = c.arrangement_faces;
  r.solidify_note = c.solidify_note;
  r.crossing_pairs_after = c.crossing_after;
  r.touching_pairs_after = c.touching_after;
  r.intersection_free = s == Status::ok;
  r.crossing_left_by_reason = c.left_by_reason;
  r.unions = c.unions;
  return finish(s, s == Status::partial ? std::to_string(c.crossing_after) + " crossing pairs left" : "");
}

} // namespace mrepair

#endif // MREPAIR_RESOLVE_INTERSECTIONS_H
