// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_REPAIR_H
#define MREPAIR_REPAIR_H

/// \file repair.h
/// The whole repair job on a polygon soup, as `mrepair repair` and the Python
/// `mrepair.repair` run it: soup to manifold mesh (when the input is not one),
/// gap closing (with a tolerance derived from the input on CAD exports and
/// print models, or the one given), the cleaning pipeline with the steps of the
/// input's profile (a scan gets RameshCleaner, a CAD export or print model
/// keeps its geometry and parts and gets its holes closed), then the validity
/// check; inspection before and after, and a face accounting that reconciles.
/// The job itself is in internal/repair/job.h; its result in repair_result.h.

#include <mrepair/clean_scan_mesh.h>
#include <mrepair/close_gaps.h>
#include <mrepair/fill_small_holes.h>
#include <mrepair/input_profile.h>
#include <mrepair/inspect.h>
#include <mrepair/internal/repair/job.h>
#include <mrepair/io.h>
#include <mrepair/parameters.h>
#include <mrepair/repair_result.h>
#include <mrepair/report.h>
#include <mrepair/resolve_intersections.h>
#include <mrepair/status.h>
#include <mrepair/stitch_soup.h>
#include <mrepair/triangulate_polygons.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {

// The public calls the job composes, handed to its worker (job.h), which
// includes no public algorithm header.
struct Repair_stages
{
  template <typename... A>
  static auto inspect_polygon_soup(A&&... a) { return mrepair::inspect_polygon_soup(std::forward<A>(a)...); }
  template <typename... A>
  static auto inspect(A&&... a) { return mrepair::inspect(std::forward<A>(a)...); }
  template <typename... A>
  static auto polygon_soup_to_manifold_mesh(A&&... a)
  {
    return mrepair::polygon_soup_to_manifold_mesh(std::forward<A>(a)...);
  }
  template <typename PolygonMesh>
  static auto triangulate_polygons(PolygonMesh& pm) { return mrepair::triangulate_polygons(pm); }
  template <typename TriangleMesh, typename NP>
  static auto close_gaps(TriangleMesh& tm, double tolerance, const NP& np) { return mrepair::close_gaps(tm, tolerance, np); }
  template <typename TriangleMesh, typename NP>
  static auto close_gaps_automatic(TriangleMesh& tm, const NP& np)
  {
    return mrepair::close_gaps(tm, automatic_gap_tolerance, np);
  }
  template <typename TriangleMesh, typename NP>
  static auto resolve_intersections(TriangleMesh& tm, const NP& np) { return mrepair::resolve_intersections(tm, np); }
};

} // namespace internal

/// \ingroup mrepair_clean
/// repairs a polygon soup into a valid manifold triangle mesh `out`, keeping
/// the user's model (the safety policy of `clean_scan_mesh()`).
///
/// \code
/// before <- inspect_polygon_soup(points, polygons)      -- beside the next
///   step up to concurrent_inspection_polygons polygons
/// if every point is finite and the soup is a manifold, consistently oriented mesh:
///   build it directly
/// else:
///   polygon_soup_to_manifold_mesh (merge_epsilon)         -- stops on failure
/// points, polygons <- cleared (the mesh holds the data)
/// triangulate polygons with more than three sides          -- stops on failure
/// close_gaps(gap_tolerance) when gap_tolerance > 0, else
///   close_gaps(automatic_gap_tolerance) when automatic_gap_tolerance and
///   classify_input(profile) is cad                          -- stops on failure
/// clean_scan_mesh with the input's profile                  -- stops on failure
/// face accounting over every stage; after <- inspect(out)
/// \endcode
/// The visitor is polled between the stages; the soup stage and the gap
/// closing get its progress and stop requests (their own phases are dropped),
/// the cleaning pipeline gets it whole.
///
/// \tparam PolygonMesh model of `MutableFaceGraph` (`CGAL::Surface_mesh`, ...)
/// \param points, polygons the soup; cleared once the mesh is built, to keep
///   the peak memory down. Non-finite points and polygons with out-of-range
///   indices are repaired away (counted in the report).
/// \param out the output mesh, cleared first
/// \param np optional named parameters (an empty `std::optional` value counts
///   as absent, so a front end passes what its user gave as it is); each
///   stage gets `np` whole, so the parameters of `polygon_soup_to_manifold_mesh()`,
///   `close_gaps()`, `clean_scan_mesh()` (and its steps) and
///   `resolve_intersections()` reach them. The job's own:
///   - `input_profile` (`Input_profile`, default `automatic`: which cleaning steps apply)
///   - `gap_tolerance` (double, model units, default 0): close boundary gaps
///     narrower than this; 0: see `automatic_gap_tolerance`
///   - `automatic_gap_tolerance` (bool, default true): with no gap tolerance,
///     an input of the `cad` profile (chosen or classified) gets its gaps
///     closed with the tolerance of `estimate_gap_tolerance()`; scans are left
///     alone. false: no gap closing unless `gap_tolerance` > 0
///   - `gap_bridge_first` (bool, default true here, false in `close_gaps()`):
///     the facing rims of a crack are joined by a strip of triangles before
///     the contractions, so that their vertices keep their input positions
///   - `gap_keep_input_points` (bool, default true here, false in `close_gaps()`):
///     each contraction takes, where it can, the placement that leaves the
///     input positions of its vertices on the surface (close_gaps.h)
///   - `merge_epsilon` (double, default 0): soup points closer than this are merged
///   - `spike_angle` (degrees, default 100), `max_hole_vertices` (default: the
///     profile's, 100 for a scan and 500 for cad; the inspections count
///     against 100), `min_component_faces` (400), `max_clean_iterations` (5):
///     the cleaning's, also the inspections' thresholds
///   - `resolve_intersections` (bool, default true): after the cleaning,
///     `resolve_intersections()`: a shell crossing itself is repaired locally,
///     overlapping closed shells become their union, and the small holes it
///     leaves or that were kept open beside a crossing are filled. Meshes
///     without crossings and nested shells pay the detection only.
///   - `merge_overlapping_shells` (bool, default true): false keeps crossing
///     closed shells apart (no union; their crossings stay)
///   - `count_self_intersections` (bool, default true): count self-intersecting
///     face pairs in the inspection of the output, the evidence that the
///     repair left none (about 1 s of a 1M-face job)
///   - `count_input_self_intersections` (bool, default false): ... and in the
///     inspection of the input (1.9 s of a 6.8 s job at 1M faces: the soup's
///     pairs are informative only, the cleaning does not aim at them)
///   - `concurrent_inspection_polygons` (std::size_t, default 4,000,000): up
///     to this many input polygons the inspection of the input runs beside
///     the soup stage (both only read the input, and the soup stage is mostly
///     sequential); above, one after the other, so that their memory peaks do
///     not add up (10M faces: 1.1 and 1.0 GB beside the 0.6 GB input); 0: never
///   - `after_stage` (callable `void(const char* stage, const Repair_result&
///     so_far)`): called after the stages "before" (input inspected),
///     "soup_to_manifold" (the mesh built, the soup's memory freed),
///     "close_gaps" (when it ran), "clean" (profile chosen),
///     "resolve_intersections" (when it ran, or when the output inspection,
///     made first on a mesh of one shell, found nothing for it to do) and
///     "after" (output inspected):
///     lets a caller print while the job runs, write `out` once
///     `output_final`, or hand freed memory back to the system
///   - `visitor` (`Default_visitor`): phases "soup_to_manifold", "close_gaps"
///     and those of `clean_scan_mesh()`
/// \return `Repair_result`; `out` is a valid mesh whatever the status
template <typename Point, typename Polygon, typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Repair_result repair_polygon_soup(std::vector<Point>& points, std::vector<Polygon>& polygons,
                                  PolygonMesh& out,
                                  const NamedParameters& np = CGAL::parameters::default_values())
{
  using internal::get_or;
  // The job's own settings; the cleaning's and the other stages' are read by
  // them from `np`, which each stage gets whole.
  internal::Repair_settings s;
  s.profile = get_or(np, internal_np::input_profile, Input_profile::automatic);
  s.gap = get_or(np, internal_np::gap_tolerance, 0.);
  s.merge = get_or(np, internal_np::merge_epsilon, 0.);
  s.spike = get_or(np, internal_np::spike_angle, defaults::spike_angle);
  s.automatic_gap = get_or(np, internal_np::automatic_gap_tolerance, true);
  s.resolve = get_or(np, internal_np::resolve_intersections, true);
  s.count_output_pairs = get_or(np, internal_np::count_self_intersections, true);
  s.count_input_pairs = get_or(np, internal_np::count_input_self_intersections, false);
  s.concurrent_below = get_or(np, internal_np::concurrent_inspection_polygons,
                              defaults::concurrent_inspection_polygons);
  s.after_stage = get_or(np, internal_np::after_stage, std::function<void(const char*, const Repair_result&)>());
  // the inspections count against the cleaning's thresholds (the profile's
  // hole limit when one is given, else the scan's)
  s.hole_n = get_or(np, internal_np::max_hole_vertices, defaults::max_hole_vertices);
  s.comp_n = get_or(np, internal_np::min_component_faces, defaults::min_component_faces);
  CGAL::clear(out);
  // the other settings are checked by the stages that use them
  if (!(s.gap >= 0.) || !std::isfinite(s.gap) || !(s.merge >= 0.) || !std::isfinite(s.merge) || s.comp_n < 1)
    return internal::failed_repair(
        Repair_result(), "options", Status::invalid_parameter,
        "gap_tolerance and merge_epsilon must be finite and >= 0, min_component_faces >= 1");
  return internal::run_repair_job<internal::Repair_stages>(points, polygons, out, s, np);
}

} // namespace mrepair

#endif // MREPAIR_REPAIR_H
