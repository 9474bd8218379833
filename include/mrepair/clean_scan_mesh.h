// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_CLEAN_SCAN_MESH_H
#define MREPAIR_CLEAN_SCAN_MESH_H

#include <mrepair/clean_boundaries.h>
#include <mrepair/ensure_valid_mesh.h>
#include <mrepair/fill_small_holes.h>
#include <mrepair/input_profile.h>
#include <mrepair/definitions.h>
#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/clean_scan_mesh/spike_steps.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/internal/utility.h>
#include <mrepair/parameters.h>
#include <mrepair/remove_small_components.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <limits>
#include <string>
#include <vector>

/// \file clean_scan_mesh.h
/// The RameshCleaner pipeline (section 4): preprocessing, then iterations of
/// relax spikes, remove unrelaxable spikes, clean boundaries, remove small
/// components, fill small holes, fix near-degenerate faces, relax spikes
/// again; garbage collection at the end.

MREPAIR_ADD_NAMED_PARAMETER(clean_steps)           // unsigned mask of mrepair::Clean_step (all)
MREPAIR_ADD_NAMED_PARAMETER(max_clean_iterations)  // iteration cap (5)
MREPAIR_ADD_NAMED_PARAMETER(collect_garbage)       // bool, Surface_mesh::collect_garbage at the end (true)

namespace mrepair {

/// \ingroup mrepair_clean
/// the steps of `clean_scan_mesh()`, in pipeline order; combine as a mask.
enum Clean_step : unsigned {
  clean_step_remove_degenerate_vertices = 1u << 0,  ///< non-finite and isolated vertices (preprocessing)
  clean_step_relax_spikes = 1u << 1,                ///< 3.7
  clean_step_remove_unrelaxable_spikes = 1u << 2,   ///< 3.8
  clean_step_clean_boundaries = 1u << 3,            ///< 3.3
  clean_step_remove_small_components = 1u << 4,     ///< 3.2
  clean_step_fill_small_holes = 1u << 5,            ///< 3.4, 3.5
  clean_step_fix_near_degenerate_faces = 1u << 6,   ///< 3.6
  clean_step_relax_spikes_again = 1u << 7,          ///< 3.7 at the end of each iteration
  clean_step_ensure_valid = 1u << 8,                ///< ensure_valid_mesh.h, once at the end
  clean_step_all = 0x1FFu,
  /// the steps of the `cad` profile: the geometry and the parts stay, holes
  /// are closed, validity is restored
  clean_steps_cad = clean_step_remove_degenerate_vertices | clean_step_remove_small_components |
                    clean_step_fill_small_holes | clean_step_ensure_valid
};

constexpr std::size_t number_of_clean_steps = 9;

/// returns the stable name of step number `i` (0 = remove_degenerate_vertices).
inline const char* clean_step_name(std::size_t i)
{
  static const char* names[number_of_clean_steps] = {
      "remove_degenerate_vertices", "relax_spikes",     "remove_unrelaxable_spikes",
      "clean_boundaries",           "remove_small_components", "fill_small_holes",
      "fix_near_degenerate_faces",  "relax_spikes_again",      "ensure_valid_mesh"};
  return i < number_of_clean_steps ? names[i] : "unknown";
}

/// parses a step name (as printed by `clean_step_name`; "relax_spikes" also
/// selects "relax_spikes_again") into a mask; 0 when unknown.
inline unsigned parse_clean_step(const std::string& name)
{
  unsigned m = 0;
  for (std::size_t i = 0; i < number_of_clean_steps; ++i)
    if (name == clean_step_name(i)) m |= 1u << i;
  if (name == "relax_spikes") m |= clean_step_relax_spikes_again;
  return m;
}

/// \ingroup mrepair_clean
/// per-step totals over all iterations of `clean_scan_mesh()`.
struct Clean_step_stats
{
  bool enabled = false;
  bool available = true;   ///< false when the step's implementation is not built in
  std::size_t runs = 0;
  std::size_t changes = 0; ///< elements moved, removed, collapsed or added
  std::size_t faces_removed = 0;  ///< by the step's own counters
  std::size_t faces_added = 0;
  double seconds = 0;
  Status last_status = Status::ok;
  Report last_report;      ///< result of the last run
};

/// \ingroup mrepair_clean
/// what `clean_scan_mesh()` did.
struct Scan_cleaning_result
{
  Status status = Status::ok;
  std::string message;
  std::size_t iterations = 0;
  bool converged = false;  ///< the last iteration changed nothing (else the cap was hit)
  std::size_t vertices_before = 0, faces_before = 0, vertices_after = 0, faces_after = 0;
  std::size_t non_finite_vertices_removed = 0;   ///< vertices with a NaN/infinite coordinate
  std::size_t isolated_vertices_removed = 0;     ///< finite vertices without a face (also those the removal of non-finite faces left without one)
  std::size_t faces_removed_with_non_finite = 0; ///< faces of non-finite vertices (and fans removed to avoid pinched vertices)
  std::array<Clean_step_stats, number_of_clean_steps> steps;
  Small_components_result components;   ///< totals over iterations
  Boundary_cleaning_result boundaries;  ///< totals over iterations
  Hole_filling_result holes;            ///< totals; open_holes from the last run
  Validity_result validity;             ///< the final check
  Input_classification profile;         ///< the profile the steps ran with, and why
  double seconds = 0;

  /// faces removed by every step, as the steps counted them
  std::size_t faces_removed() const
  {
    std::size_t n = 0;
    for (const Clean_step_stats& s : steps) n += s.faces_removed;
    return n;
  }
  std::size_t faces_added() const
  {
    std::size_t n = 0;
    for (const Clean_step_stats& s : steps) n += s.faces_added;
    return n;
  }
  /// faces before = faces after + removed - added: no face lost without a reason
  bool faces_reconcile() const
  {
    return faces_before + faces_added() == faces_after + faces_removed();
  }

  void to_report(Report& r) const
  {
    r.add("status", status);
    if (!message.empty()) r.add("message", message);
    r.add("iterations", iterations);
    r.add("converged", converged);
    r.add("vertices_before", vertices_before);
    r.add("faces_before", faces_before);
    r.add("vertices_after", vertices_after);
    r.add("faces_after", faces_after);
    r.add("non_finite_vertices_removed", non_finite_vertices_removed);
    r.add("isolated_vertices_removed", isolated_vertices_removed);
    r.add("faces_removed_with_non_finite", faces_removed_with_non_finite);
    r.add("seconds", seconds);
    profile.to_report(r.section("profile"));
    {
      Report& fa = r.section("face_accounting");
      fa.add("faces_in", faces_before);
      fa.add("faces_out", faces_after);
      Report& rm = fa.section("removed");
      Report& ad = fa.section("added");
      for (std::size_t i = 0; i < number_of_clean_steps; ++i) {
        if (steps[i].faces_removed) rm.add(clean_step_name(i), steps[i].faces_removed);
        if (steps[i].faces_added) ad.add(clean_step_name(i), steps[i].faces_added);
      }
      fa.add("reconciles", faces_reconcile());
    }
    Report& st = r.section("steps");
    for (std::size_t i = 0; i < number_of_clean_steps; ++i) {
      const Clean_step_stats& s = steps[i];
      Report& x = st.section(clean_step_name(i));
      x.add("enabled", s.enabled);
      if (!s.available) x.add("available", false);
      x.add("runs", s.runs);
      x.add("changes", s.changes);
      x.add("seconds", s.seconds);
      if (s.runs) x.section("last") = s.last_report;
    }
    validity.to_report(r.section("validity"));
    components.to_report(r.section("small_components"));
    boundaries.to_report(r.section("boundaries"));
    holes.to_report(r.section("holes"));
  }
};

namespace internal {
namespace clean_pipeline {

// Hands progress and cancellation of a sub-step to the pipeline's visitor;
// phases are the pipeline's own (one per step), so nested ones are dropped.
template <typename Handle>
struct Forwarding_visitor : Default_visitor
{
  Handle* h;
  explicit Forwarding_visitor(Handle* handle) : h(handle) {}
  void start_phase(const char*) {}
  void end_phase(const char*) {}
  void progress(double f) { h->progress(f); }
  bool stop_requested() { return h->stop_requested(); }
};

template <typename P>
void collect_garbage_of(CGAL::Surface_mesh<P>& m) { m.collect_garbage(); }
template <typename PM>
void collect_garbage_of(PM&) {}

// Hole filling adds elements once the statistics and the steps' marks exist.
// On Surface_mesh the first addition beyond the capacity reallocates every
// property array, those maps included, while a map added later is created
// with the container's capacity: so room is reserved once, before any of
// them exists (with_room_for_fills; a mesh built by the soup repair has it
// already, and then this is no copy). On a generated 1M-face scan this took fill_small_holes from 0.095 s to
// 0.023 s for 0.034 s of reserve. Beyond the room the arrays grow as before,
// and a grown array is copied whole: 3% of room was too little for the noisy
// scan (fills add 4.3% of the faces, removals free 0.8%), whose face
// statistics were then copied during the fills, 818 MB at 10M faces, the
// job's memory peak (2,618 MiB).
template <typename P>
void reserve_room_for_fills(CGAL::Surface_mesh<P>& m)
{
  const Element_counts n = with_room_for_fills(m.num_vertices(), m.num_edges(), m.num_faces());
  m.reserve(n.vertices, n.edges, n.faces);
}
template <typename PM>
void reserve_room_for_fills(PM&) {}

}  // namespace clean_pipeline
}  // namespace internal

/// \ingroup mrepair_clean
/// cleans a scanned triangle mesh with the RameshCleaner pipeline (section 4).
///
/// \code
/// profile <- input_profile, or classify_input(pmesh) when automatic
/// steps <- clean_steps if given, else all for a scan and, for a CAD or
///          print model, only: degenerate vertices, open debris next to a
///          closed largest component (remove_small_components with
///          open_debris_only), hole filling (Liepa's
///          patch, no refinement, no enlargement, loops up to 500 vertices),
///          the final validity check
/// remove non-finite vertices (with their faces) and isolated vertices
/// repeat at most max_clean_iterations times:
///   relax spikes                     (relax_spikes.h, 3.7)
///   remove unrelaxable spikes        (relax_spikes.h, 3.8)
///   clean boundaries                 (clean_boundaries.h, 3.3)
///   remove small components          (remove_small_components.h, 3.2)
///   fill small holes                 (fill_small_holes.h, 3.4, 3.5)
///   fix near-degenerate faces        (repair_near_degenerate_faces.h, 3.6)
///   relax spikes again               (3.7)
///   stop when the iteration changed nothing, or changed exactly what the
///   previous one did (a cycle: nothing will converge further)
/// ensure a valid output                 (ensure_valid_mesh.h)
/// collect garbage (Surface_mesh)
/// \endcode
/// Safety policy (doc/guarantees.md): the largest component is never
/// removed, and others only when small next to it too; boundary erosion
/// touches jagged loops only and never takes more than `boundary_erosion_share`
/// of a loop's region; a loop whose cap would be large next to its component
/// is a sheet's border and stays open; `faces_reconcile()` holds: every face
/// removed or added is counted by the step that did it.
/// Holes with `max_hole_vertices` vertices or more are never filled and
/// components with `min_component_faces` faces or more never removed: large
/// holes are only polished, as the paper argues. Every step can be disabled.
///
/// \tparam PolygonMesh model of `MutableFaceGraph`, a triangle mesh
/// \param pmesh a valid triangle mesh (manifold, as CGAL halfedge meshes are)
/// \param np optional:
///   - `vertex_point_map` (default: internal point map)
///   - `input_profile` (`Input_profile`, default `automatic`: `classify_input()`)
///   - `clean_steps` (unsigned mask of `Clean_step`; default: by profile)
///   - `max_clean_iterations` (std::size_t, default 5; the paper runs 3 to 5)
///   - `spike_angle` (double, degrees; default: that of `relax_spikes()`)
///   - `min_component_faces` (std::size_t, default 400), `relative_component_size` (0.01)
///   - `max_hole_vertices` (std::size_t, default 100; 500 for the cad profile),
///     `max_hole_area_share` (0.4)
///   - `jagged_loop_turning` (1), `boundary_erosion_share` (0.5): see `clean_boundaries()`
///   - `boundary_dihedral_angle` (double, degrees, default 120)
///   - `hole_density_factor` (double, default 1), `fair_hole_patches` (bool, default false)
///   - `collect_garbage` (bool, default true)
///   - `visitor`: one phase per step ("relax_spikes", ...), inside one phase
///     per iteration ("iteration 1", ...); `stop_requested()` polled by every step
/// \return `Scan_cleaning_result`: status `ok`, `partial` (small holes left
///   open or a step left defects), `empty_input`, `invalid_mesh` (not a
///   triangle mesh; untouched), `non_finite_input` (non-finite coordinates with
///   the preprocessing step disabled, or finite ones spanning more than 1e100;
///   untouched), `invalid_parameter`,
///   `cancelled` (the mesh is valid)
template <typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Scan_cleaning_result clean_scan_mesh(PolygonMesh& pmesh,
                                     const NamedParameters& np = CGAL::parameters::default_values())
{
  using GT = boost::graph_traits<PolygonMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Handle = internal::Visitor_handle<NamedParameters>;
  namespace SC = internal::clean_pipeline;
  namespace MP = mrepair::parameters;
  const internal::Stopwatch job_clock;

  Handle visitor(np);
  auto vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, pmesh));
  unsigned mask = internal::get_or(np, internal_np::clean_steps, unsigned(clean_step_all));
  const bool steps_given =
      !CGAL::parameters::is_default_parameter<NamedParameters, internal_np::clean_steps_t>::value;
  const Input_profile asked =
      internal::get_or(np, internal_np::input_profile, Input_profile::automatic);
  const std::size_t max_it =
      internal::get_or(np, internal_np::max_clean_iterations, std::size_t(5));
  const double spike_angle = internal::get_or(np, internal_np::spike_angle,
                                              std::numeric_limits<double>::quiet_NaN());
  const std::size_t min_comp =
      internal::get_or(np, internal_np::min_component_faces, defaults::min_component_faces);
  const double relative_comp =
      internal::get_or(np, internal_np::relative_component_size, defaults::relative_component_size);
  const bool hole_limit_given =
      !CGAL::parameters::is_default_parameter<NamedParameters,
                                              internal_np::max_hole_vertices_t>::value;
  std::size_t max_hole = internal::get_or(np, internal_np::max_hole_vertices, defaults::max_hole_vertices);
  const double hole_share = internal::get_or(np, internal_np::max_hole_area_share, 0.4);
  const double boundary_angle =
      internal::get_or(np, internal_np::boundary_dihedral_angle, defaults::boundary_dihedral_angle);
  const double jag_turning = internal::get_or(np, internal_np::jagged_loop_turning, 1.);
  const double erosion_share = internal::get_or(np, internal_np::boundary_erosion_share, 0.5);
  const double density = internal::get_or(np, internal_np::hole_density_factor, 1.);
  const bool fair = internal::get_or(np, internal_np::fair_hole_patches, false);
  const bool gc = internal::get_or(np, internal_np::collect_garbage, true);

  Scan_cleaning_result r;
  for (std::size_t i = 0; i < number_of_clean_steps; ++i)
    r.steps[i].enabled = (mask >> i) & 1u;
  r.vertices_before = internal::vertex_count(pmesh);
  r.faces_before = internal::face_count(pmesh);
  auto finish = [&](Status s, const std::string& msg = std::string()) {
    r.status = s;
    r.message = msg;
    r.vertices_after = internal::vertex_count(pmesh);
    r.faces_after = internal::face_count(pmesh);
    r.seconds = job_clock.seconds();
    return r;
  };

  if ((!std::isnan(spike_angle) && !(spike_angle > 0. && spike_angle < 180.)) ||
      min_comp == 0 || max_hole == 0 || !(density > 0.) || !std::isfinite(density) ||
      !(boundary_angle >= 0. && boundary_angle <= 180.) ||
      !(relative_comp >= 0. && relative_comp <= 1.) || !(hole_share >= 0.) ||
      !(erosion_share >= 0. && erosion_share <= 1.) || !(jag_turning >= 0.))
    return finish(Status::invalid_parameter, "a parameter is out of range");
  if (r.vertices_before == 0) return finish(Status::empty_input, "the mesh has no vertex");
  // every walk of the steps ends on a sound structure (bounded_walks.h)
  if (std::string broken = internal::halfedge_structure_defect(pmesh); !broken.empty())
    return finish(Status::invalid_mesh, "the mesh's halfedge structure is broken: " + broken);
  if (!CGAL::is_triangle_mesh(pmesh))
    return finish(Status::invalid_mesh, "clean_scan_mesh needs a triangle mesh");
  // NaN vertices are removed below; finite ones must stay in range
  if (internal::coordinates_too_large(pmesh, vpm))
    return finish(Status::non_finite_input, internal::coordinates_too_large_message);

  // The input kind decides which steps run, unless the caller chose them.
  const Input_classification* known = internal::get_or(
      np, internal_np::input_classification, static_cast<const Input_classification*>(nullptr));
  r.profile = known && asked == Input_profile::automatic
                  ? *known
                  : classify_input(pmesh, MP::input_profile(asked, CGAL::parameters::vertex_point_map(vpm)));
  const bool cad = r.profile.profile == Input_profile::cad;
  if (!steps_given) mask = cad ? unsigned(clean_steps_cad) : unsigned(clean_step_all);
  // CAD holes can be long loops around a flat cut; Liepa's triangulation
  // restricted to the 3D Delaunay edges handles them.
  if (cad && !hole_limit_given) max_hole = defaults::max_cad_hole_vertices;
  for (std::size_t i = 0; i < number_of_clean_steps; ++i) r.steps[i].enabled = (mask >> i) & 1u;

  if (mask & clean_step_fill_small_holes) SC::reserve_room_for_fills(pmesh);
  SC::Forwarding_visitor<Handle> fwd(&visitor);
  // Every edit of the steps goes through `ops`, which keeps the statistics
  // of the spike and near-degenerate steps current once they exist: they are
  // computed once per call.
  internal::Local_operations<PolygonMesh, decltype(vpm)> ops(pmesh, vpm);
  auto spikes = std::make_unique<SC::Spike_steps<PolygonMesh, decltype(vpm)>>(ops, spike_angle);
  SC::Boundary_settings boundary_settings;
  boundary_settings.max_angle = boundary_angle;
  boundary_settings.jagged_loop_turning = jag_turning;
  boundary_settings.erosion_share = erosion_share;

  // Runs step `i` with `body` (returning the number of changes) in a phase.
  auto run_step = [&](std::size_t i, auto&& body) -> bool {
    if (!r.steps[i].enabled) return true;
    internal::Phase_scope<Handle> phase(visitor, clean_step_name(i));
    const internal::Stopwatch step_clock;
    SC::Step_outcome o = body();
    Clean_step_stats& s = r.steps[i];
    s.seconds += step_clock.seconds();
    s.available = o.available;
    if (!o.available) return true;
    ++s.runs;
    s.changes += o.changes;
    s.faces_removed += o.faces_removed;
    s.faces_added += o.faces_added;
    s.last_status = o.status;
    s.last_report = std::move(o.report);
    return o.status != Status::cancelled;
  };

  // ---- Preprocessing: degenerate (non-finite, isolated) vertices ----------
  {
    std::vector<vertex_descriptor> bad;
    for (vertex_descriptor v : vertices(pmesh))
      if (!internal::is_finite_point(vpm, v)) bad.push_back(v);
    if (!bad.empty() && !r.steps[0].enabled)
      return finish(Status::non_finite_input,
                    "non-finite coordinates and the remove_degenerate_vertices step is disabled");
    bool ok = run_step(0, [&]() {
      SC::Step_outcome o;
      if (!bad.empty()) {
        std::vector<face_descriptor> doomed;
        for (vertex_descriptor v : bad)
          if (halfedge(v, pmesh) != GT::null_halfedge())
            for (auto h : CGAL::halfedges_around_target(halfedge(v, pmesh), pmesh))
              if (!is_border(h, pmesh)) doomed.push_back(face(h, pmesh));
        // Vertices left without faces are removed by Euler::remove_face; the
        // isolated ones are among the isolated vertices below.
        const std::size_t nv = internal::vertex_count(pmesh);
        r.faces_removed_with_non_finite = ops.remove_faces_without_pinches(doomed);
        // the removal also drops finite vertices left without faces: those
        // count as isolated, not as non-finite
        std::size_t non_finite_left = 0;
        for (vertex_descriptor v : vertices(pmesh))
          if (!internal::is_finite_point(vpm, v)) ++non_finite_left;
        const std::size_t gone = nv - internal::vertex_count(pmesh);
        r.non_finite_vertices_removed = bad.size() - non_finite_left;
        r.isolated_vertices_removed = gone - r.non_finite_vertices_removed;
      }
      std::vector<vertex_descriptor> isolated;
      for (vertex_descriptor v : vertices(pmesh))
        if (halfedge(v, pmesh) == GT::null_halfedge()) isolated.push_back(v);
      for (vertex_descriptor v : isolated) {
        if (!internal::is_finite_point(vpm, v))
          ++r.non_finite_vertices_removed;
        else
          ++r.isolated_vertices_removed;
        ops.remove_isolated_vertex(v);
      }
      o.changes = r.faces_removed_with_non_finite + r.non_finite_vertices_removed +
                  r.isolated_vertices_removed;
      o.faces_removed = r.faces_removed_with_non_finite;
      o.report.add("non_finite_vertices_removed", r.non_finite_vertices_removed);
      o.report.add("isolated_vertices_removed", r.isolated_vertices_removed);
      o.report.add("faces_removed_with_non_finite", r.faces_removed_with_non_finite);
      return o;
    });
    if (!ok) return finish(Status::cancelled);
  }

  // ---- Iterations ---------------------------------------------------------
  static const char* iteration_names[] = {"iteration 1", "iteration 2", "iteration 3",
                                          "iteration 4", "iteration 5", "iteration 6",
                                          "iteration 7", "iteration 8", "iteration 9"};
  std::vector<std::size_t> previous;
  bool partial = false;
  for (std::size_t it = 0; it < max_it; ++it) {
    if (internal::face_count(pmesh) == 0) break;
    internal::Phase_scope<Handle> iteration_phase(
        visitor, it < 9 ? iteration_names[it] : "iteration");
    std::vector<std::size_t> before(number_of_clean_steps);
    for (std::size_t i = 0; i < number_of_clean_steps; ++i) before[i] = r.steps[i].changes;

    bool ok =
        run_step(1, [&]() { return spikes->relax(fwd); }) &&
        run_step(2, [&]() { return spikes->remove_unrelaxable(fwd); }) &&
        run_step(3, [&]() {
          Boundary_cleaning_result b = SC::clean_boundaries_with(ops, boundary_settings, fwd);
          internal::add_totals(r.boundaries, b);
          SC::Step_outcome o;
          o.status = b.status;
          o.changes = b.faces_removed + b.component_faces_removed;
          o.faces_removed = o.changes;
          b.to_report(o.report);
          return o;
        }) &&
        run_step(4, [&]() {
          Small_components_result c = SC::remove_small_components_seeded(
              ops, faces(pmesh), min_comp, relative_comp, static_cast<const std::nullptr_t*>(nullptr),
              cad);
          internal::add_totals(r.components, c);
          SC::Step_outcome o;
          o.status = c.status;
          o.changes = c.faces_removed;
          o.faces_removed = c.faces_removed;
          c.to_report(o.report);
          return o;
        }) &&
        run_step(5, [&]() {
          // CAD: Liepa's patch only (no refinement to a density the part
          // does not have) and no enlargement (it removes the user's faces)
          SC::Small_hole_filler<PolygonMesh, decltype(vpm)> filler(
              ops, max_hole, density, !cad, fair && !cad, std::size_t(30), hole_share);
          filler.result.status = filler.run(cad ? std::size_t(0) : std::size_t(3), fwd);
          const Hole_filling_result& h = filler.result;
          internal::add_totals(r.holes, h);
          SC::Step_outcome o;
          o.status = h.status;
          o.changes = h.holes_filled + h.enlargement_faces_removed;
          o.faces_removed = h.enlargement_faces_removed;
          o.faces_added = h.faces_added;
          h.to_report(o.report);
          return o;
        }) &&
        run_step(6, [&]() { return spikes->fix_near_degenerate(fwd); }) &&
        run_step(7, [&]() { return spikes->relax(fwd); });
    ++r.iterations;
    if (!ok) {
      spikes.reset();  // detaches the statistics and drops their maps
      if (gc) SC::collect_garbage_of(pmesh);
      return finish(Status::cancelled);
    }
    std::vector<std::size_t> delta(number_of_clean_steps);
    std::size_t total = 0;
    for (std::size_t i = 0; i < number_of_clean_steps; ++i) {
      delta[i] = r.steps[i].changes - before[i];
      if (i > 0) total += delta[i];
    }
    if (total == 0 || delta == previous) {
      r.converged = total == 0;
      break;
    }
    previous = delta;
  }
  spikes.reset();  // detaches the statistics and drops their maps before the garbage collection
  // The last check: whatever the steps left, no exactly degenerate or
  // duplicate face and no non-manifold vertex goes out.
  const bool valid_ok = run_step(8, [&]() {
    // the structure was checked on entry; only the steps above edited it since
    r.validity = internal::ensure_valid_mesh(pmesh, CGAL::parameters::vertex_point_map(vpm), false);
    SC::Step_outcome o;
    o.status = r.validity.status;
    o.changes = r.validity.operations + r.validity.duplicate_faces_removed +
                r.validity.non_manifold_vertices_split;
    o.faces_removed = r.validity.faces_removed();
    r.validity.to_report(o.report);
    return o;
  });
  (void)valid_ok;
  // relax_spikes (step 1) is expected to leave unrelaxable spikes to step 2
  for (std::size_t i = 2; i < number_of_clean_steps; ++i)
    if (r.steps[i].runs && r.steps[i].last_status == Status::partial) partial = true;
  if (r.validity.degenerate_faces_left > 0) r.message = r.validity.message;
  if (gc) SC::collect_garbage_of(pmesh);
  return finish(partial ? Status::partial : Status::ok, r.message);
}

}  // namespace mrepair

#endif  // MREPAIR_CLEAN_SCAN_MESH_H
