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

struct Repair_result;

/// \ingroup mrepair_clean
/// the options of `repair_polygon_soup()`, with the defaults of `mrepair repair`.
struct Repair_options
{
  Input_profile profile = Input_profile::automatic;  ///< which cleaning steps apply
  /// close boundary gaps narrower than this (model units); 0: see `automatic_gap_tolerance`
  double gap_tolerance = 0.;
  /// with `gap_tolerance` 0: on an input of the `cad` profile (chosen or
  /// classified), close gaps with the tolerance of `estimate_gap_tolerance()`;
  /// scans are left alone. false: no gap closing unless `gap_tolerance` > 0.
  bool automatic_gap_tolerance = true;
  double merge_epsilon = 0.;           ///< merge soup points closer than this before stitching
  /// dihedral angle (degrees) of a spiked vertex; NaN: the default of
  /// `relax_spikes()` for cleaning and 100 for the inspections
  double spike_angle = std::numeric_limits<double>::quiet_NaN();
  /// holes with fewer boundary vertices are filled; 0: the profile decides
  /// (100 scan, 500 cad) and the inspections count against 100
  std::size_t max_hole_vertices = 0;
  std::size_t min_component_faces = 400;   ///< components with fewer faces are removed
  std::size_t max_clean_iterations = 5;    ///< cleaning iteration cap
  /// after the cleaning, `resolve_intersections()`: a shell crossing itself
  /// is repaired locally, overlapping closed shells become their union, and
  /// small holes it leaves or that were kept open beside a crossing are
  /// filled. Meshes without crossing and nested shells pay the detection only.
  bool resolve_intersections = true;
  /// false: crossing closed shells are kept apart (no union; their crossings stay)
  bool merge_overlapping_shells = true;
  /// count self-intersecting face pairs in the inspection of the output: the
  /// evidence that the repair left none (about 1 s of a 1M-face job)
  bool count_self_intersections = true;
  /// ... and in the inspection of the input. Off by default: on a 1M-face
  /// scan it took 1.9 s of a 6.8 s job (the soup's pairs are informative only:
  /// the cleaning does not aim at them), so the report costs less than the repair.
  bool count_input_self_intersections = false;
  /// up to this many input polygons, the inspection of the input runs beside
  /// the soup stage: both only read the input, and the soup stage is mostly
  /// sequential, so the inspection uses the cores it leaves idle (TBB). Above
  /// it they run one after the other, so that their memory peaks do not add
  /// up (10M faces: 1.1 and 1.0 GB beside the 0.6 GB input). 0: never.
  std::size_t concurrent_inspection_polygons = 4000000;
  /// called after the stages "before" (input inspected), "soup_to_manifold"
  /// (the mesh built, the soup's memory freed), "close_gaps" (when it ran),
  /// "clean" (profile chosen), "resolve_intersections" (when it ran) and
  /// "after" (output inspected), with the result
  /// so far: lets a caller print while the job runs, or hand freed memory back
  /// to the system
  std::function<void(const char* stage, const Repair_result& so_far)> after_stage;
};

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
/// \param options see `Repair_options`
/// \param np optional: `visitor` (`Default_visitor`): phases "soup_to_manifold",
///   "close_gaps" and those of `clean_scan_mesh()`
/// \return `Repair_result`; `out` is a valid mesh whatever the status
template <typename Point, typename Polygon, typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Repair_result repair_polygon_soup(std::vector<Point>& points, std::vector<Polygon>& polygons,
                                  PolygonMesh& out, const Repair_options& options,
                                  const NamedParameters& np = CGAL::parameters::default_values())
{
  namespace MP = mrepair::parameters;
  using Handle = internal::Visitor_handle<NamedParameters>;
  Handle visitor(np);
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
    if (options.after_stage) options.after_stage(stage, result);
  };

  const double gap = options.gap_tolerance, merge = options.merge_epsilon,
               spike = options.spike_angle;
  // the other options are checked by the stages that use them
  if (!(gap >= 0.) || !std::isfinite(gap) || !(merge >= 0.) || !std::isfinite(merge) ||
      options.min_component_faces < 1)
    return fail("options", Status::invalid_parameter,
                "gap_tolerance and merge_epsilon must be finite and >= 0, min_component_faces >= 1");
  const bool hole_given = options.max_hole_vertices > 0;
  const std::size_t hole_n = hole_given ? options.max_hole_vertices : 100,
                    comp_n = options.min_component_faces;

  const double inspect_spike = std::isnan(spike) ? 100. : spike;  // inspect's default is 100
  // Each stage's wall time goes into its report section ("seconds"): the
  // phase breakdown of the whole job.
  internal::Stopwatch stage_clock;
  auto thresholds = MP::max_hole_vertices(
      hole_n, MP::min_component_faces(comp_n, MP::spike_angle(
                                                  inspect_spike, MP::count_self_intersections(
                                                                     options.count_self_intersections &&
                                                                     options.count_input_self_intersections))));
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
  const bool beside = polygons.size() <= options.concurrent_inspection_polygons;
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
                                      MP::merge_epsilon(merge).visitor(std::ref(forward)));
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
  if (!(gap > 0.) && options.automatic_gap_tolerance) {
    classification = classify_input(out, MP::input_profile(options.profile));
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
      g = gap > 0. ? close_gaps(out, gap, CGAL::parameters::visitor(std::ref(forward)))
                   : close_gaps(out, automatic_gap_tolerance, CGAL::parameters::visitor(std::ref(forward)));
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

  // 3. The cleaning pipeline, with the steps of the input's profile.
  auto clean = [&](const auto& np_hole) {
    const Input_classification* known = classified ? &classification : nullptr;
    return clean_scan_mesh(
        out, MP::min_component_faces(
                 comp_n, MP::max_clean_iterations(
                             options.max_clean_iterations,
                             MP::spike_angle(spike, MP::input_profile(
                                                        options.profile,
                                                        MP::input_classification(known, np_hole)))))
                 .visitor(std::ref(visitor.get())));
  };
  // without a hole limit the profile picks it
  result.clean = hole_given ? clean(MP::max_hole_vertices(hole_n))
                            : clean(CGAL::parameters::default_values());
  const Scan_cleaning_result& c = result.clean;
  c.to_report(report.section("clean"));
  const bool cleaned = succeeded(c.status) || c.status == Status::empty_input;
  // the solid repair, when it runs, edits `out` after this callback
  result.output_final = cleaned && !(options.resolve_intersections && c.status != Status::empty_input);
  stage_done("clean");
  if (!cleaned) return fail("clean", c.status, c.message);
  for (std::size_t i = 0; i < number_of_clean_steps; ++i) {
    if (c.steps[i].faces_removed) removed.emplace_back(clean_step_name(i), c.steps[i].faces_removed);
    if (c.steps[i].faces_added) added.emplace_back(clean_step_name(i), c.steps[i].faces_added);
  }
  // 4. Solid repair: the crossings the cleaning left, then the holes beside
  // them (the hole filler refuses a patch into a surface that crosses itself).
  bool crossings_known = false;
  if (options.resolve_intersections && c.status != Status::empty_input) {
    stage_clock.restart();
    const bool cad = c.profile.profile == Input_profile::cad;
    Intersection_repair_result& ir = result.intersections;
    {
      internal::Phase_scope<Handle> phase(visitor, "resolve_intersections");
      ir = resolve_intersections(
          out, MP::merge_overlapping_shells(options.merge_overlapping_shells,
                                            MP::refine_hole_patches(!cad, CGAL::parameters::visitor(std::ref(forward)))));
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
      // the profile's hole limit and way of filling (clean_scan_mesh.h)
      const std::size_t limit = hole_given ? hole_n : cad ? defaults::max_cad_hole_vertices : hole_n;
      Hole_filling_result& h = result.holes_after_intersections;
      h = fill_small_holes(out, MP::max_hole_vertices(
                                    limit, MP::refine_hole_patches(
                                               !cad, MP::max_hole_enlargements(cad ? std::size_t(0) : std::size_t(3)))));
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
  const bool count_again = options.count_self_intersections && !crossings_known;
  result.after = inspect(
      out, MP::max_hole_vertices(
               hole_n, MP::min_component_faces(
                           comp_n, MP::spike_angle(inspect_spike, MP::count_self_intersections(count_again)))));
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
