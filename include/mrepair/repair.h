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

#include <mrepair/clean_scan_mesh.h>
#include <mrepair/close_gaps.h>
#include <mrepair/fill_small_holes.h>
#include <mrepair/input_profile.h>
#include <mrepair/inspect.h>
#include <mrepair/io.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/resolve_intersections.h>
#include <mrepair/status.h>
#include <mrepair/stitch_soup.h>
#include <mrepair/triangulate_polygons.h>
#include <mrepair/visitors.h>

#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_group.h>
#endif

#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace mrepair {

/// \ingroup mrepair_clean
/// what `repair_polygon_soup()` did.
struct Repair_result
{
  /// `ok` or `partial` (the cleaning's status); `empty_input` when cleaning
  /// found nothing to clean; on failure the status of the stage that failed
  /// (`invalid_parameter` for bad options, `cancelled`).
  Status status = Status::ok;
  std::string failed_stage;   ///< "options", "soup_to_manifold", "close_gaps", "clean" (a polygon mesh that cannot be triangulated takes the soup stage); empty when none failed
  std::string message;        ///< one line: `stage: status[: reason]` on failure
  bool soup_needed = false;   ///< the input was not a manifold, consistently oriented mesh
  /// `out` is final: the cleaning succeeded (or found nothing to clean) and
  /// the solid repair ran, so only the output inspection, which reads it, is
  /// left. Set before the "resolve_intersections" callback of `after_stage`
  /// (before "clean" when that step is off), so a caller may write `out` from there.
  bool output_final = false;
  Inspection_report before;   ///< the input soup
  Inspection_report after;    ///< the output mesh (filled when the job ran to its end)
  Scan_cleaning_result clean; ///< the cleaning pipeline (its `profile` says which ran and why)
  bool intersections_resolved = false;       ///< the step ran (`intersections` is filled)
  Intersection_repair_result intersections;  ///< what it did
  Hole_filling_result holes_after_intersections;  ///< the holes filled after it (when it changed the mesh)
  bool gaps_closed = false;   ///< the gap closing ran (`gaps` is filled)
  Gap_closing_result gaps;    ///< its result: tolerance (and whether estimated), largest displacement
  std::size_t faces_in = 0, faces_out = 0;  ///< in triangles
  std::vector<std::pair<std::string, std::size_t>> faces_removed, faces_added;  ///< by reason
  Report sections;            ///< the report sections of the stages reached, in order

  /// true when faces in + added = faces out + removed.
  bool faces_reconcile() const
  {
    std::size_t rm = 0, ad = 0;
    for (const auto& x : faces_removed) rm += x.second;
    for (const auto& x : faces_added) ad += x.second;
    return faces_in + ad == faces_out + rm;
  }

  /// writes the sections of the stages reached: `before`, `soup_to_manifold`,
  /// `triangulation` (when polygons were triangulated), `close_gaps` (when it ran),
  /// `clean`, `face_accounting`, `after` (the keys of `mrepair repair --json`
  /// without the file sections `input` and `output`).
  void to_report(Report& r) const { r.append(sections); }
};

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
///     "resolve_intersections" (when it ran) and "after" (output inspected):
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
  namespace MP = mrepair::parameters;
  using internal::get_or;
  using Handle = internal::Visitor_handle<NamedParameters>;
  Handle visitor(np);
  // The job's own settings; the cleaning's and the other stages' are read by
  // them from `np`, which each stage gets whole.
  const Input_profile profile = get_or(np, internal_np::input_profile, Input_profile::automatic);
  const double gap = get_or(np, internal_np::gap_tolerance, 0.),
               merge = get_or(np, internal_np::merge_epsilon, 0.),
               spike = get_or(np, internal_np::spike_angle, defaults::spike_angle);
  const bool automatic_gap = get_or(np, internal_np::automatic_gap_tolerance, true),
             resolve = get_or(np, internal_np::resolve_intersections, true),
             count_output_pairs = get_or(np, internal_np::count_self_intersections, true),
             count_input_pairs = get_or(np, internal_np::count_input_self_intersections, false);
  const std::size_t concurrent_below = get_or(np, internal_np::concurrent_inspection_polygons,
                                              defaults::concurrent_inspection_polygons);
  const std::function<void(const char*, const Repair_result&)> after_stage =
      get_or(np, internal_np::after_stage, std::function<void(const char*, const Repair_result&)>());
  // the soup stage and the gap closing report progress and poll stop, but
  // their inner phases are not the job's
  internal::clean_pipeline::Forwarding_visitor<Handle> forward(&visitor);
  Repair_result result;
  Report& report = result.sections;
  CGAL::clear(out);

  auto fail = [&](const std::string& stage, Status s, const std::string& reason) {
    result.status = s;
    result.failed_stage = stage;
    result.message = stage + ": " + to_string(s) + (reason.empty() ? "" : ": " + reason);
    return result;
  };
  auto stop_requested = [&] { return visitor.stop_requested(); };
  auto stage_done = [&](const char* stage) {
    if (after_stage) after_stage(stage, result);
  };

  // the inspections count against the cleaning's thresholds (the profile's
  // hole limit when one is given, else the scan's)
  const std::size_t hole_n = get_or(np, internal_np::max_hole_vertices, defaults::max_hole_vertices),
                    comp_n = get_or(np, internal_np::min_component_faces, defaults::min_component_faces);
  // the other settings are checked by the stages that use them
  if (!(gap >= 0.) || !std::isfinite(gap) || !(merge >= 0.) || !std::isfinite(merge) || comp_n < 1)
    return fail("options", Status::invalid_parameter,
                "gap_tolerance and merge_epsilon must be finite and >= 0, min_component_faces >= 1");
  // Each stage's wall time goes into its report section ("seconds"): the
  // phase breakdown of the whole job.
  internal::Stopwatch stage_clock;
  auto thresholds = MP::max_hole_vertices(
      hole_n, MP::min_component_faces(
                  comp_n, MP::spike_angle(spike, MP::count_self_intersections(count_output_pairs &&
                                                                                 count_input_pairs))));
  double before_seconds = 0.;
  auto inspect_input = [&] {
    internal::Stopwatch clock;
    result.before = inspect_polygon_soup(points, polygons, thresholds);
    before_seconds = clock.seconds();
  };
  auto report_input = [&] {
    result.before.to_report(report.section("before"));
    report.section("before").add("seconds", before_seconds);
    stage_done("before");
  };
  // 1. A manifold mesh, built directly when the soup already is one. Beside
  // it, on smaller inputs, the inspection of the input (see
  // `concurrent_inspection_polygons`); `waiting` outlives neither.
#ifdef CGAL_LINKED_WITH_TBB
  tbb::task_group waiting;
  const bool beside = polygons.size() <= concurrent_below;
  if (beside) waiting.run(inspect_input);
#else
  const bool beside = false;
#endif
  if (!beside) {
    inspect_input();
    report_input();
    if (stop_requested()) return fail("before", Status::cancelled, "");
  }

  // Face accounting over the whole job, in triangles: each stage adds what
  // it removed and added, by reason.
  auto& removed = result.faces_removed;
  auto& added = result.faces_added;
  std::size_t faces_in = 0;
  for (const auto& poly : polygons) faces_in += poly.size() >= 3 ? poly.size() - 2 : 1;

  stage_clock.restart();
  bool finite = true;
  for (const Point& p : points)
    finite = finite && std::isfinite(CGAL::to_double(p.x())) &&
             std::isfinite(CGAL::to_double(p.y())) && std::isfinite(CGAL::to_double(p.z()));
  // CGAL's builder keeps every point, so a point no polygon uses would stay
  // as an isolated vertex (an invalid mesh when no later step removes it: a
  // refused cleaning). Such soups, and those without polygons, take the soup
  // stage, which drops unused points (or says empty_input).
  bool direct = finite && !polygons.empty() && is_polygon_soup_a_polygon_mesh(polygons, points.size());
  if (direct) {
    std::vector<char> used(points.size(), 0);
    std::size_t distinct = 0;
    for (const auto& poly : polygons)
      for (const auto i : poly)
        if (!used[std::size_t(i)]) {
          used[std::size_t(i)] = 1;
          ++distinct;
        }
    direct = distinct == points.size();
  }
  result.soup_needed = !direct;
  Soup_repair_result s;
  auto soup_to_manifold = [&](auto& soup_points, auto& soup_polygons) {
    internal::Phase_scope<Handle> phase(visitor, "soup_to_manifold");
    s = polygon_soup_to_manifold_mesh(soup_points, soup_polygons, out,
                                      np.visitor(std::ref(forward)));
  };
  if (direct)
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, out);
  else
    soup_to_manifold(points, polygons);
  double soup_seconds = stage_clock.seconds();
#ifdef CGAL_LINKED_WITH_TBB
  if (beside) {
    waiting.wait();
    report_input();  // a stop asked for meanwhile is the soup stage's (polled there)
  }
#endif
  stage_clock.restart();
  // freed, not only emptied: clear() keeps the capacity (36 MB of a 1M-face scan)
  internal::free_memory(points, polygons);
  Triangulation_result triangulation;
  if (direct) {
    triangulation = triangulate_polygons(out);
    if (triangulation.status != Status::ok) {
      // a polygon mesh whose polygons cannot all be cut without doubling an
      // edge (two quads on the same four vertices): the soup stage
      // triangulates and stitches it instead
      std::vector<typename boost::property_traits<
          typename boost::property_map<PolygonMesh, CGAL::vertex_point_t>::type>::value_type>
          mesh_points;
      std::vector<std::vector<std::size_t>> mesh_polygons;
      CGAL::Polygon_mesh_processing::polygon_mesh_to_polygon_soup(out, mesh_points, mesh_polygons);
      CGAL::clear(out);
      direct = false;
      result.soup_needed = true;
      triangulation = Triangulation_result();
      soup_to_manifold(mesh_points, mesh_polygons);
    }
  }
  if (direct) {
    report.section("soup_to_manifold").add("needed", false);
  } else {
    Report& sr = report.section("soup_to_manifold");
    sr.add("needed", true);
    s.to_report(sr);
    removed.emplace_back("soup_invalid_index", s.removed_invalid_index);
    removed.emplace_back("soup_non_finite", s.removed_non_finite);
    removed.emplace_back("soup_degenerate", s.removed_degenerate_index + s.removed_collinear);
    removed.emplace_back("soup_duplicate", s.removed_duplicate);
    removed.emplace_back("soup_internal_wall", s.removed_internal_walls);
    faces_in = s.faces_in;  // the soup stage's count (triangles of distinct corners) rules
    if (!succeeded(s.status)) return fail("soup_to_manifold", s.status, s.message);
  }
  if (triangulation.polygons > 0) triangulation.to_report(report.section("triangulation"));
  soup_seconds += stage_clock.seconds();
  report.section("soup_to_manifold").add("seconds", soup_seconds);
  stage_done("soup_to_manifold");
  if (stop_requested()) return fail("soup_to_manifold", Status::cancelled, "");

  // 2. Gap closing: with the tolerance given, or derived from the input on
  // CAD exports and print models (their seams are what gap closing is for; a
  // scan's holes are not gaps).
  bool automatic = false;
  // the cleaning reuses the classification while the mesh is unchanged
  Input_classification classification;
  bool classified = false;
  if (!(gap > 0.) && automatic_gap) {
    classification = classify_input(out, MP::input_profile(profile));
    classified = true;
    automatic = classification.profile == Input_profile::cad;
  }
  if (gap > 0. || automatic) {
    classified = false;
    stage_clock.restart();
    Gap_closing_result g;
    const std::size_t f0 = internal::face_count(out);
    {
      internal::Phase_scope<Handle> phase(visitor, "close_gaps");
      g = gap > 0. ? close_gaps(out, gap, np.visitor(std::ref(forward)))
                   : close_gaps(out, automatic_gap_tolerance, np.visitor(std::ref(forward)));
    }
    result.gaps_closed = true;
    result.gaps = g;
    const std::size_t f1 = internal::face_count(out);
    // vertex-edge contractions split the faces they land on
    if (f1 > f0) added.emplace_back("close_gaps_splits", f1 - f0);
    if (f0 > f1) removed.emplace_back("close_gaps", f0 - f1);
    g.to_report(report.section("close_gaps"));
    report.section("close_gaps").add("seconds", stage_clock.seconds());
    stage_done("close_gaps");
    if (!succeeded(g.status)) return fail("close_gaps", g.status, "");
  }

  // 3. The cleaning pipeline, with the steps of the input's profile; without
  // a hole limit the profile picks it. It reuses the classification while the
  // mesh is unchanged.
  const Input_classification* known = classified ? &classification : nullptr;
  result.clean = clean_scan_mesh(out, MP::input_classification(known, np));
  const Scan_cleaning_result& c = result.clean;
  c.to_report(report.section("clean"));
  const bool cleaned = succeeded(c.status) || c.status == Status::empty_input;
  // the solid repair, when it runs, edits `out` after this callback
  result.output_final = cleaned && !(resolve && c.status != Status::empty_input);
  stage_done("clean");
  if (!cleaned) return fail("clean", c.status, c.message);
  for (std::size_t i = 0; i < number_of_clean_steps; ++i) {
    if (c.steps[i].faces_removed) removed.emplace_back(clean_step_name(i), c.steps[i].faces_removed);
    if (c.steps[i].faces_added) added.emplace_back(clean_step_name(i), c.steps[i].faces_added);
  }
  // 4. Solid repair: the crossings the cleaning left, then the holes beside
  // them (the hole filler refuses a patch into a surface that crosses itself).
  bool crossings_known = false;
  if (resolve && c.status != Status::empty_input) {
    stage_clock.restart();
    const bool cad = c.profile.profile == Input_profile::cad;
    Intersection_repair_result& ir = result.intersections;
    {
      internal::Phase_scope<Handle> phase(visitor, "resolve_intersections");
      // the cad profile's patches keep to the loop (no refinement), as its hole filling
      ir = resolve_intersections(
          out, MP::refine_hole_patches(get_or(np, internal_np::refine_hole_patches, !cad), np)
                   .visitor(std::ref(forward)));
    }
    result.intersections_resolved = true;
    removed.emplace_back("resolve_intersections_local", ir.local_faces_removed);
    added.emplace_back("resolve_intersections_local", ir.local_faces_added);
    removed.emplace_back("resolve_intersections_union", ir.union_faces_removed);
    added.emplace_back("resolve_intersections_union", ir.union_faces_added);
    Report& rr = report.section("resolve_intersections");
    ir.to_report(rr);
    const bool changed = ir.local_faces_removed + ir.local_faces_added + ir.union_faces_removed > 0;
    // its last count is of its output (taken after its last change)
    crossings_known = succeeded(ir.status);
    if (changed && succeeded(ir.status)) {
      // with the profile's hole limit and way of filling, as the cleaning's
      Hole_filling_result& h = result.holes_after_intersections;
      h = internal::clean_pipeline::fill_small_holes_of_profile(out, np, cad);
      removed.emplace_back("fill_holes_after_intersections", h.enlargement_faces_removed);
      added.emplace_back("fill_holes_after_intersections", h.faces_added);
      h.to_report(rr.section("holes_filled_after"));
      crossings_known = crossings_known && h.faces_added == 0 && h.enlargement_faces_removed == 0;
    }
    rr.add("seconds", stage_clock.seconds());
    result.output_final = true;
    stage_done("resolve_intersections");
    if (ir.status == Status::cancelled) return fail("resolve_intersections", ir.status, ir.message);
  }

  result.faces_in = faces_in;
  result.faces_out = internal::face_count(out);
  {
    Report& fa = report.section("face_accounting");
    fa.add("faces_in", result.faces_in);
    fa.add("faces_out", result.faces_out);
    Report& rs = fa.section("removed");
    for (const auto& x : removed)
      if (x.second) rs.add(x.first, x.second);
    Report& as = fa.section("added");
    for (const auto& x : added)
      if (x.second) as.add(x.first, x.second);
    fa.add("reconciles", result.faces_reconcile());
  }

  stage_clock.restart();
  // the solid repair's last count stands when nothing changed the mesh since
  const bool count_again = count_output_pairs && !crossings_known;
  result.after = inspect(
      out, MP::max_hole_vertices(
               hole_n, MP::min_component_faces(
                           comp_n, MP::spike_angle(spike, MP::count_self_intersections(count_again)))));
  // (then even without count_self_intersections: the step counted anyway)
  if (crossings_known) {
    result.after.self_intersections_counted = true;
    result.after.self_intersecting_pairs =
        result.intersections.crossing_pairs_after + result.intersections.touching_pairs_after;
    result.after.self_intersecting_pairs_touching = result.intersections.touching_pairs_after;
  }
  result.after.to_report(report.section("after"));
  report.section("after").add("seconds", stage_clock.seconds());
  stage_done("after");
  result.status = c.status;
  return result;
}

} // namespace mrepair

#endif // MREPAIR_REPAIR_H
