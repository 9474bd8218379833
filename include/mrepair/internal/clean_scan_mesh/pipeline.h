// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The RameshCleaner pipeline (section 4), the worker of clean_scan_mesh():
// the preprocessing, the iterations over the steps and the last validity
// check, on one set of local operations (local_operations.h), the one place
// the steps edit the mesh.
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_PIPELINE_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_PIPELINE_H

#include <mrepair/definitions.h>
#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/clean_scan_mesh/boundaries.h>
#include <mrepair/internal/clean_scan_mesh/hole_filler.h>
#include <mrepair/internal/clean_scan_mesh/small_components.h>
#include <mrepair/internal/clean_scan_mesh/spike_steps.h>
#include <mrepair/internal/coordinate_range.h>
#include <mrepair/internal/ensure_valid_mesh/fixer.h>
#include <mrepair/internal/input_profile/classifier.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/internal/utility.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/scan_cleaning_result.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace mrepair {
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


// clean_scan_mesh() (clean_scan_mesh.h); `np` is forwarded to the steps.
template <typename PolygonMesh, typename NamedParameters>
Scan_cleaning_result run_pipeline(PolygonMesh& pmesh, const NamedParameters& np)
{
  using GT = boost::graph_traits<PolygonMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Handle = Visitor_handle<NamedParameters>;
  using VPM = typename CGAL::GetVertexPointMap<PolygonMesh, NamedParameters>::type;
  namespace MP = mrepair::parameters;
  const Stopwatch job_clock;

  Handle visitor(np);
  VPM vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, pmesh));
  // Each setting is read once, here or by the step that uses it from the
  // forwarded `np` (as the step's public call reads it), so a parameter given
  // to the pipeline reaches its step with the step's own default otherwise.
  unsigned mask = get_or(np, internal_np::clean_steps, unsigned(clean_step_all));
  const bool steps_given = is_given(np, internal_np::clean_steps);
  const Input_profile asked = get_or(np, internal_np::input_profile, Input_profile::automatic);
  const std::size_t max_it =
      get_or(np, internal_np::max_clean_iterations, defaults::max_clean_iterations);
  const double spike_angle = get_or(np, internal_np::spike_angle, defaults::spike_angle);
  const std::size_t min_comp =
      get_or(np, internal_np::min_component_faces, defaults::min_component_faces);
  const double relative_comp =
      get_or(np, internal_np::relative_component_size, defaults::relative_component_size);
  const bool gc = get_or(np, internal_np::collect_garbage, true);
  Boundary_settings boundary_settings;
  Hole_filling_settings hole_settings;  // read again once the profile is known
  std::string bad_setting;
  const bool settings_valid =
      spike_angle > 0. && spike_angle < 180. && min_comp > 0 && relative_comp >= 0. &&
      relative_comp <= 1. && read_boundary_settings(np, boundary_settings) &&
      read_hole_filling_settings(np, false, hole_settings) &&
      Spike_steps<PolygonMesh, VPM, NamedParameters>::settings_are_valid(np, bad_setting);

  Scan_cleaning_result r;
  for (std::size_t i = 0; i < number_of_clean_steps; ++i)
    r.steps[i].enabled = (mask >> i) & 1u;
  r.vertices_before = vertex_count(pmesh);
  r.faces_before = face_count(pmesh);
  auto finish = [&](Status s, const std::string& msg = std::string()) {
    r.status = s;
    r.message = msg;
    r.vertices_after = vertex_count(pmesh);
    r.faces_after = face_count(pmesh);
    r.seconds = job_clock.seconds();
    return r;
  };

  if (!settings_valid)
    return finish(Status::invalid_parameter, "a parameter is out of range");
  if (r.vertices_before == 0) return finish(Status::empty_input, "the mesh has no vertex");
  // every walk of the steps ends on a sound structure (bounded_walks.h)
  if (std::string broken = halfedge_structure_defect(pmesh); !broken.empty())
    return finish(Status::invalid_mesh, "the mesh's halfedge structure is broken: " + broken);
  if (!CGAL::is_triangle_mesh(pmesh))
    return finish(Status::invalid_mesh, "clean_scan_mesh needs a triangle mesh");
  // NaN vertices are removed below; finite ones must stay in range
  if (coordinates_too_large(pmesh, vpm))
    return finish(Status::non_finite_input, coordinates_too_large_message);

  // The input kind decides which steps run, unless the caller chose them.
  const Input_classification* known = get_or(
      np, internal_np::input_classification, static_cast<const Input_classification*>(nullptr));
  r.profile = known && asked == Input_profile::automatic
                  ? *known
                  : classify_input(pmesh, vpm, asked);
  const bool cad = r.profile.profile == Input_profile::cad;
  if (!steps_given) mask = cad ? unsigned(clean_steps_cad) : unsigned(clean_step_all);
  // CAD holes can be long loops around a flat cut; Liepa's triangulation
  // restricted to the 3D Delaunay edges handles them (hole_filler.h).
  read_hole_filling_settings(np, cad, hole_settings);
  for (std::size_t i = 0; i < number_of_clean_steps; ++i) r.steps[i].enabled = (mask >> i) & 1u;

  if (mask & clean_step_fill_small_holes) reserve_room_for_fills(pmesh);
  Forwarding_visitor<Handle> fwd(&visitor);
  // Every edit of the steps goes through `ops`, which keeps the statistics
  // of the spike and near-degenerate steps current once they exist: they are
  // computed once per call.
  Local_operations<PolygonMesh, VPM> ops(pmesh, vpm);
  auto spikes = std::make_unique<Spike_steps<PolygonMesh, VPM, NamedParameters>>(ops, np);

  // Runs step `i` with `body` (returning the number of changes) in a phase.
  auto run_step = [&](std::size_t i, auto&& body) -> bool {
    if (!r.steps[i].enabled) return true;
    Phase_scope<Handle> phase(visitor, clean_step_name(i));
    const Stopwatch step_clock;
    const Local_operation_counts before = ops.counts();
    Step_outcome o = body();
    Clean_step_stats& s = r.steps[i];
    s.seconds += step_clock.seconds();
    s.available = o.available;
    if (!o.available) return true;
    ++s.runs;
    s.changes += o.changes;
    // the face accounting: what the layer saw the step remove and add
    s.faces_removed += ops.counts().faces_removed - before.faces_removed;
    s.faces_added += ops.counts().faces_added - before.faces_added;
    s.last_status = o.status;
    s.last_report = std::move(o.report);
    return o.status != Status::cancelled;
  };

  // ---- Preprocessing: degenerate (non-finite, isolated) vertices ----------
  {
    std::vector<vertex_descriptor> bad;
    for (vertex_descriptor v : vertices(pmesh))
      if (!is_finite_point(vpm, v)) bad.push_back(v);
    if (!bad.empty() && !r.steps[0].enabled)
      return finish(Status::non_finite_input,
                    "non-finite coordinates and the remove_degenerate_vertices step is disabled");
    bool ok = run_step(0, [&]() {
      Step_outcome o;
      if (!bad.empty()) {
        std::vector<face_descriptor> doomed;
        for (vertex_descriptor v : bad)
          if (halfedge(v, pmesh) != GT::null_halfedge())
            for (auto h : CGAL::halfedges_around_target(halfedge(v, pmesh), pmesh))
              if (!is_border(h, pmesh)) doomed.push_back(face(h, pmesh));
        // Vertices left without faces are removed by Euler::remove_face; the
        // isolated ones are among the isolated vertices below.
        const std::size_t nv = vertex_count(pmesh);
        r.faces_removed_with_non_finite = ops.remove_faces_without_pinches(doomed);
        // the removal also drops finite vertices left without faces: those
        // count as isolated, not as non-finite
        std::size_t non_finite_left = 0;
        for (vertex_descriptor v : vertices(pmesh))
          if (!is_finite_point(vpm, v)) ++non_finite_left;
        const std::size_t gone = nv - vertex_count(pmesh);
        r.non_finite_vertices_removed = bad.size() - non_finite_left;
        r.isolated_vertices_removed = gone - r.non_finite_vertices_removed;
      }
      std::vector<vertex_descriptor> isolated;
      for (vertex_descriptor v : vertices(pmesh))
        if (halfedge(v, pmesh) == GT::null_halfedge()) isolated.push_back(v);
      for (vertex_descriptor v : isolated) {
        if (!is_finite_point(vpm, v))
          ++r.non_finite_vertices_removed;
        else
          ++r.isolated_vertices_removed;
        ops.remove_isolated_vertex(v);
      }
      o.changes = r.faces_removed_with_non_finite + r.non_finite_vertices_removed +
                  r.isolated_vertices_removed;
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
    if (face_count(pmesh) == 0) break;
    Phase_scope<Handle> iteration_phase(
        visitor, it < 9 ? iteration_names[it] : "iteration");
    std::vector<std::size_t> before(number_of_clean_steps);
    for (std::size_t i = 0; i < number_of_clean_steps; ++i) before[i] = r.steps[i].changes;

    bool ok =
        run_step(1, [&]() { return spikes->relax(fwd); }) &&
        run_step(2, [&]() { return spikes->remove_unrelaxable(fwd); }) &&
        run_step(3, [&]() {
          Boundary_cleaning_result b = clean_boundaries_with(ops, boundary_settings, fwd);
          add_totals(r.boundaries, b);
          return step_outcome(b, b.faces_removed + b.component_faces_removed);
        }) &&
        run_step(4, [&]() {
          Small_components_result c = remove_small_components_seeded(
              ops, faces(pmesh), min_comp, relative_comp, static_cast<const std::nullptr_t*>(nullptr),
              cad);
          add_totals(r.components, c);
          return step_outcome(c, c.faces_removed);
        }) &&
        run_step(5, [&]() {
          Small_hole_filler<PolygonMesh, VPM> filler(ops, hole_settings);
          filler.result.status = filler.run(fwd);
          const Hole_filling_result& h = filler.result;
          add_totals(r.holes, h);
          return step_outcome(h, h.holes_filled + h.enlargement_faces_removed);
        }) &&
        run_step(6, [&]() { return spikes->fix_near_degenerate(fwd); }) &&
        run_step(7, [&]() { return spikes->relax(fwd); });
    ++r.iterations;
    if (!ok) {
      spikes.reset();  // detaches the statistics and drops their maps
      if (gc) collect_garbage_of(pmesh);
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
    r.validity = ensure_valid_mesh_with(ops, np, false);
    return step_outcome(r.validity, r.validity.operations + r.validity.duplicate_faces_removed +
                                        r.validity.non_manifold_vertices_split);
  });
  (void)valid_ok;
  // relax_spikes (step 1) is expected to leave unrelaxable spikes to step 2
  for (std::size_t i = 2; i < number_of_clean_steps; ++i)
    if (r.steps[i].runs && r.steps[i].last_status == Status::partial) partial = true;
  if (r.validity.degenerate_faces_left > 0) r.message = r.validity.message;
  if (gc) collect_garbage_of(pmesh);
  return finish(partial ? Status::partial : Status::ok, r.message);
}

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_PIPELINE_H
