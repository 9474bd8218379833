// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The worker of repair_polygon_soup() (repair.h): the stages of the job, the
// inspection of the input beside the soup stage (a TBB task group), the face
// accounting over every stage. The stages that are public calls of their own
// (inspection, soup to manifold mesh, triangulation, gap closing, solid
// repair) come through `Stages`, which repair.h fills with those calls: no
// internal header includes a public algorithm header. The cleaning, the
// classification and the hole filling after the solid repair are called on
// their workers directly.
#ifndef MREPAIR_INTERNAL_REPAIR_JOB_H
#define MREPAIR_INTERNAL_REPAIR_JOB_H

#include <mrepair/definitions.h>
#include <mrepair/input_classification.h>
#include <mrepair/inspection_report.h>
#include <mrepair/intersection_repair_result.h>
#include <mrepair/internal/clean_scan_mesh/hole_filler.h>
#include <mrepair/internal/clean_scan_mesh/pipeline.h>
#include <mrepair/internal/coordinate_range.h>
#include <mrepair/internal/input_profile/classifier.h>
#include <mrepair/internal/io/convert.h>
#include <mrepair/internal/repair/repeated_components.h>
#include <mrepair/internal/resolve_intersections/shells.h>
#include <mrepair/internal/utility.h>
#include <mrepair/parameters.h>
#include <mrepair/repair_result.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/stitch_soup_result.h>
#include <mrepair/visitors.h>

#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/graph/graph_traits.hpp>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_group.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {

/// the job's own settings, read and checked by repair_polygon_soup(); the
/// stages read theirs from the `np` they get whole.
struct Repair_settings
{
  Input_profile profile = Input_profile::automatic;
  double gap = 0., merge = 0., spike = defaults::spike_angle;  // merge: read by the soup stage, checked here
  bool automatic_gap = true, resolve = true, count_output_pairs = true, count_input_pairs = false;
  std::size_t concurrent_below = defaults::concurrent_inspection_polygons;
  std::size_t hole_n = defaults::max_hole_vertices, comp_n = defaults::min_component_faces;
  std::function<void(const char*, const Repair_result&)> after_stage;
};

/// a result that says `stage` failed with `s` (`reason` may be empty).
inline Repair_result failed_repair(Repair_result result, const std::string& stage, Status s,
                                   const std::string& reason)
{
  result.status = s;
  result.failed_stage = stage;
  result.message = stage + ": " + to_string(s) + (reason.empty() ? "" : ": " + reason);
  return result;
}

/// the number of components of `pm` whose faces are joined across edges (a
/// union-find over the edges, milliseconds at 1M faces).
template <typename PolygonMesh>
std::size_t face_connected_components(const PolygonMesh& pm)
{
  using GT = boost::graph_traits<PolygonMesh>;
  auto fim = CGAL::get_initialized_face_index_map(pm);
  std::size_t slots = 0;
  for (auto f : faces(pm)) slots = (std::max)(slots, static_cast<std::size_t>(get(fim, f)) + 1);
  Union_find<std::size_t> uf(slots);
  for (auto e : edges(pm)) {
    const auto h = halfedge(e, pm);
    const auto f0 = face(h, pm), f1 = face(opposite(h, pm), pm);
    if (f0 != GT::null_face() && f1 != GT::null_face()) uf.unite(get(fim, f0), get(fim, f1));
  }
  std::size_t n = 0;
  for (auto f : faces(pm)) n += uf.find(get(fim, f)) == get(fim, f);
  return n;
}

/// the job on a cleared `out` (see repair_polygon_soup()).
template <typename Stages, typename Point, typename Polygon, typename PolygonMesh, typename NamedParameters>
Repair_result run_repair_job(std::vector<Point>& points, std::vector<Polygon>& polygons, PolygonMesh& out,
                             const Repair_settings& settings, const NamedParameters& np)
{
  namespace MP = mrepair::parameters;
  using Handle = Visitor_handle<NamedParameters>;
  Handle visitor(np);
  const Input_profile profile = settings.profile;
  const double gap = settings.gap, spike = settings.spike;
  const bool automatic_gap = settings.automatic_gap, resolve = settings.resolve,
             count_output_pairs = settings.count_output_pairs, count_input_pairs = settings.count_input_pairs;
  const std::size_t concurrent_below = settings.concurrent_below, hole_n = settings.hole_n, comp_n = settings.comp_n;
  const auto& after_stage = settings.after_stage;
  // the soup stage and the gap closing report progress and poll stop, but
  // their inner phases are not the job's
  clean_pipeline::Forwarding_visitor<Handle> forward(&visitor);
  Repair_result result;
  Report& report = result.sections;

  auto fail = [&](const std::string& stage, Status s, const std::string& reason) {
    return failed_repair(result, stage, s, reason);
  };
  auto stop_requested = [&] { return visitor.stop_requested(); };
  auto stage_done = [&](const char* stage) {
    if (after_stage) after_stage(stage, result);
  };

  // Each stage's wall time goes into its report section ("seconds"): the
  // phase breakdown of the whole job.
  Stopwatch stage_clock;
  auto thresholds = MP::max_hole_vertices(
      hole_n, MP::min_component_faces(
                  comp_n, MP::spike_angle(spike, MP::count_self_intersections(count_output_pairs &&
                                                                                 count_input_pairs))));
  double before_seconds = 0.;
  auto inspect_input = [&] {
    Stopwatch clock;
    result.before = Stages::inspect_polygon_soup(points, polygons, thresholds);
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
  // it removed and added, by reason. The cleaning and the hole filling after
  // the solid repair edit through the local-operations layer and report its
  // counts; the other stages cannot: the soup stage builds a new mesh from
  // arrays, the gap closer contracts with its own recorded primitives (so
  // the job compares face counts around it), and the solid repair's unions
  // are CGAL corefinements copied in (its local rounds read the layer).
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
  std::string why_not;
  bool direct = finite && !polygons.empty() && io::is_soup_a_mesh(polygons, points.size(), why_not);
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
    Phase_scope<Handle> phase(visitor, "soup_to_manifold");
    s = Stages::polygon_soup_to_manifold_mesh(soup_points, soup_polygons, out,
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
  free_memory(points, polygons);
  decltype(Stages::triangulate_polygons(out)) triangulation;
  if (direct) {
    triangulation = Stages::triangulate_polygons(out);
    if (triangulation.status != Status::ok) {
      // a polygon mesh whose polygons cannot all be cut without doubling an
      // edge (two quads on the same four vertices): the soup stage
      // triangulates and stitches it instead
      std::vector<typename boost::property_traits<
          typename boost::property_map<PolygonMesh, CGAL::vertex_point_t>::type>::value_type>
          mesh_points;
      std::vector<std::vector<std::size_t>> mesh_polygons;
      CGAL::Polygon_mesh_processing::polygon_mesh_to_polygon_soup(out, mesh_points, mesh_polygons);
          direct = false;
      result.soup_needed = true;
      triangulation = decltype(triangulation)();
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
    classification = classify_input(out, get_const_property_map(CGAL::vertex_point, out), profile);
    classified = true;
    automatic = classification.profile == Input_profile::cad;
  }
  if (gap > 0. || automatic) {
    classified = false;
    stage_clock.restart();
    // A file that reads as a mesh skipped the soup stage, which drops the
    // second copy of a face: a part written twice (a sheet once in each
    // orientation, each copy with its own points) is two coincident layers
    // crossing everywhere. The copy holds no point of its own.
    if (direct) {
      const std::size_t repeated =
          remove_repeated_components(out, get_const_property_map(CGAL::vertex_point, out));
      if (repeated > 0) removed.emplace_back("repeated_components", repeated);
    }
    Gap_closing_result g;
    const std::size_t f0 = face_count(out);
    {
      Phase_scope<Handle> phase(visitor, "close_gaps");
      // the facing rims of a crack are joined by a strip before the
      // contractions, which would move their vertices (close_gaps.h)
      const auto gap_np = MP::gap_keep_input_points(
          get_or(np, internal_np::gap_keep_input_points, true),
          MP::gap_bridge_first(get_or(np, internal_np::gap_bridge_first, true), np.visitor(std::ref(forward))));
      g = gap > 0. ? Stages::close_gaps(out, gap, gap_np) : Stages::close_gaps_automatic(out, gap_np);
      // Without seams to read a tolerance from (fewer than 16 candidates),
      // border vertices that coincide are still stitched: within 1e-6 x the
      // diagonal, which moves no point farther than the reference tolerance
      // (two cubes on one edge whose split corners coincide, CGAL's
      // nm_cubes.off: each cube closes, the two touch along the edge). Taken
      // back when it closes a shell around no volume: two coincident copies
      // of a sheet stitched into a pillow that crosses itself.
      if (!(gap > 0.) && g.status == Status::ok && g.tolerance_estimated && !(g.estimate.tolerance > 0.) &&
          g.boundary_edges_before > 0) {
        const auto vpm = get_const_property_map(CGAL::vertex_point, out);
        const std::size_t empty_before = solid::count_empty_closed_shells(out, vpm);
        PolygonMesh unstitched;
        CGAL::copy_face_graph(out, unstitched);
        Gap_closing_result stitched = Stages::close_gaps(out, 1e-6, MP::gap_relative_tolerance(true, gap_np));
        if (succeeded(stitched.status) && solid::count_empty_closed_shells(out, vpm) <= empty_before) {
          stitched.tolerance_estimated = true;
          stitched.estimate = g.estimate;
          g = stitched;
        } else {
          if constexpr (Is_surface_mesh<PolygonMesh>::value) out.clear_without_removing_property_maps();
          else CGAL::clear(out);
          CGAL::copy_face_graph(unstitched, out);
        }
      }
    }
    result.gaps_closed = true;
    result.gaps = g;
    const std::size_t f1 = face_count(out);
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
  result.clean = clean_pipeline::run_pipeline(out, MP::input_classification(known, np));
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
  // The output inspection counts the crossing pairs with the test the solid
  // repair's scan uses (same faces, same pairs): on one shell the inspection
  // runs first, and when it finds no crossing the solid repair has nothing
  // to do and is not run. Its scan and the inspection built the same arrays
  // and certified the same stars: 0.45 of 1.2 s on the 1M-face scan.
  auto inspect_output = [&](bool count_pairs) {
    stage_clock.restart();
    Inspection_report i = Stages::inspect(
        out, MP::max_hole_vertices(
                 hole_n, MP::min_component_faces(
                             comp_n, MP::spike_angle(spike, MP::count_self_intersections(count_pairs)))));
    return std::make_pair(i, stage_clock.seconds());
  };
  std::pair<Inspection_report, double> inspected;
  bool inspected_current = false;  // `inspected` is of `out` as it is now
  if (resolve && c.status != Status::empty_input &&
      face_connected_components(out) == 1) {
    inspected = inspect_output(true);
    inspected_current = true;
    const Inspection_report& i = inspected.first;
    const bool nothing_to_resolve =
        i.status == Status::ok && i.self_intersections_counted &&
        i.self_intersecting_pairs == i.self_intersecting_pairs_touching && i.connected_components == 1 &&
        !coordinates_too_large(out, get_const_property_map(CGAL::vertex_point, out));
    if (nothing_to_resolve) {
      Intersection_repair_result& ir = result.intersections;
      ir = Intersection_repair_result();
      ir.touching_pairs_before = ir.touching_pairs_after = i.self_intersecting_pairs_touching;
      ir.intersection_free = true;
      ir.message = "one shell without crossing pairs (the output inspection's count): nothing to resolve";
      result.intersections_resolved = true;
      ir.to_report(report.section("resolve_intersections"));
      result.output_final = true;
      crossings_known = true;
      stage_done("resolve_intersections");
    }
  }
  if (resolve && c.status != Status::empty_input && !crossings_known) {
    stage_clock.restart();
    const bool cad = c.profile.profile == Input_profile::cad;
    Intersection_repair_result& ir = result.intersections;
    {
      Phase_scope<Handle> phase(visitor, "resolve_intersections");
      // the cad profile's patches keep to the loop (no refinement), as its hole filling
      // scans keep the local repair alone (a closed scan is a sheet that
      // happens to close; its output stays as it was)
      const bool scan = c.profile.profile == Input_profile::scan;
      ir = Stages::resolve_intersections(
          out, MP::solidify_closed_shells(
                   get_or(np, internal_np::solidify_closed_shells, !scan),
                   MP::refine_hole_patches(get_or(np, internal_np::refine_hole_patches, !cad), np))
                   .visitor(std::ref(forward)));
    }
    result.intersections_resolved = true;
    removed.emplace_back("resolve_intersections_local", ir.local_faces_removed);
    added.emplace_back("resolve_intersections_local", ir.local_faces_added);
    removed.emplace_back("resolve_intersections_union", ir.union_faces_removed);
    added.emplace_back("resolve_intersections_union", ir.union_faces_added);
    removed.emplace_back("resolve_intersections_solid", ir.solid_faces_removed);
    added.emplace_back("resolve_intersections_solid", ir.solid_faces_added);
    added.emplace_back("resolve_intersections_caps", ir.cap_faces_added);
    Report& rr = report.section("resolve_intersections");
    ir.to_report(rr);
    const bool changed =
        ir.local_faces_removed + ir.local_faces_added + ir.union_faces_removed + ir.solid_faces_removed +
            ir.cap_faces_added > 0;
    // its last count is of its output (taken after its last change)
    crossings_known = succeeded(ir.status);
    if (changed && succeeded(ir.status)) {
      // with the profile's hole limit and way of filling, as the cleaning's
      Hole_filling_result& h = result.holes_after_intersections;
      Local_operation_counts filled;
      h = clean_pipeline::fill_small_holes_of_profile(out, np, cad, &filled);
      removed.emplace_back("fill_holes_after_intersections", filled.faces_removed);
      added.emplace_back("fill_holes_after_intersections", filled.faces_added);
      h.to_report(rr.section("holes_filled_after"));
      crossings_known = crossings_known && h.faces_added == 0 && h.enlargement_faces_removed == 0;
    }
    inspected_current = inspected_current && !changed;
    rr.add("seconds", stage_clock.seconds());
    result.output_final = true;
    stage_done("resolve_intersections");
    if (ir.status == Status::cancelled) return fail("resolve_intersections", ir.status, ir.message);
  }

  result.faces_in = faces_in;
  result.faces_out = face_count(out);
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

  // the solid repair's last count stands when nothing changed the mesh since
  if (!inspected_current) inspected = inspect_output(count_output_pairs && !crossings_known);
  result.after = inspected.first;
  // (then even without count_self_intersections: the step counted anyway)
  if (crossings_known) {
    result.after.self_intersections_counted = true;
    result.after.self_intersecting_pairs =
        result.intersections.crossing_pairs_after + result.intersections.touching_pairs_after;
    result.after.self_intersecting_pairs_touching = result.intersections.touching_pairs_after;
  }
  result.after.to_report(report.section("after"));
  report.section("after").add("seconds", inspected.second);
  stage_done("after");
  result.status = c.status;
  return result;
}

}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_REPAIR_JOB_H
