// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The calls of the Python module that work on a polygon mesh: gap closing
// (once, or as a sequence to step through), cleaning and remeshing. Like the
// `mrepair` commands they triangulate polygons first; the reports are those
// of the commands without the sections that describe files.
#include "binding.h"

#include <mrepair/adaptive_remesh.h>
#include <mrepair/clean_scan_mesh.h>
#include <mrepair/close_gaps.h>
#include <mrepair/input_profile.h>
#include <mrepair/stitch_soup.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>

namespace mrepair {
namespace python {
namespace {

namespace MP = mrepair::parameters;

double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool all_finite(const std::vector<Point>& points)
{
  for (const Point& p : points)
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) return false;
  return true;
}

// ---- close_gaps ------------------------------------------------------------------------

// `mrepair close-gaps`: a soup that is not a valid mesh is repaired as a soup first.
py::tuple close_gaps(const py::object& vertices, const py::object& faces,
                     const std::optional<double>& tolerance, bool relative,
                     const std::optional<long long>& steps, double lambda, bool keep_pinched,
                     const py::object& progress)
{
  if (tolerance && (!(*tolerance >= 0) || !std::isfinite(*tolerance)))
    raise_value_error("tolerance must be finite and >= 0");
  if (!(lambda >= 0 && lambda <= 1)) raise_value_error("lambda_ must be in [0, 1]");
  if (steps && *steps < 0) raise_value_error("steps must be >= 0");
  Soup s = soup_from(vertices, faces);
  Python_visitor visitor(progress);
  Report report;
  Mesh mesh;
  if (!all_finite(s.points) || !is_polygon_soup_a_polygon_mesh(s.polygons, s.points.size())) {
    if (PyErr_WarnEx(PyExc_UserWarning,
                     "close_gaps: the input is not a valid polygon mesh; repairing it as a soup "
                     "first (see mrepair.soup_to_manifold)",
                     1) != 0)
      throw py::error_already_set();
    const Soup_repair_result sr =
        without_gil([&] { return polygon_soup_to_manifold_mesh(s.points, s.polygons, mesh); });
    sr.to_report(report.section("soup"));
    if (!succeeded(sr.status) || mesh.number_of_faces() == 0)
      raise_value_error(std::string("the soup could not be made a mesh (") + to_string(sr.status) +
                        ")");
    s = Soup();
    const Triangulation_result t = without_gil([&] { return triangulate_polygons(mesh); });
    if (t.polygons > 0) t.to_report(report.section("triangulation"));
    if (t.status != Status::ok) raise_value_error(t.message);
  } else {
    build_mesh(s, mesh, report, "run mrepair.soup_to_manifold first");
  }
  const std::size_t max_ops =
      steps ? static_cast<std::size_t>(*steps) : std::numeric_limits<std::size_t>::max();
  const auto t0 = std::chrono::steady_clock::now();
  const auto np =
      MP::gap_relative_tolerance(
          relative, MP::gap_lambda(lambda, MP::gap_split_pinched_vertices(
                                               !keep_pinched, MP::gap_max_operations(max_ops))))
          .visitor(std::ref(visitor));
  const Gap_closing_result r = without_gil([&] {
    return tolerance ? mrepair::close_gaps(mesh, *tolerance, np)
                     : mrepair::close_gaps(mesh, mrepair::automatic_gap_tolerance, np);
  });
  Report& section = report.section("close_gaps");
  r.to_report(section);
  section.add("seconds", seconds_since(t0));
  visitor.raise_if_stopped();
  if (!succeeded(r.status) && r.status != Status::cancelled)
    raise_value_error("close_gaps: " + status_line(r.status, r.message));
  mesh.collect_garbage();
  return result_of(mesh, report);
}

// ---- GapClosingSequence ---------------------------------------------------------------------

// The mesh and the sequence stepping through its contractions. The sequence
// refers to the mesh, so both live here and the mesh is never collected
// (its arrays skip the removed elements instead).
class Gap_sequence
{
  using Sequence = Gap_closing_sequence<Mesh>;
  Mesh mesh_;
  std::unique_ptr<Sequence> sequence_;
  std::mutex mutex_;  // calls release the GIL: two threads must not step at once

  template <typename F>
  auto locked(F&& f) -> decltype(f())
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    return f();
  }

public:
  Gap_sequence(const py::object& vertices, const py::object& faces, double tolerance,
               bool relative, double lambda)
  {
    Soup s = soup_from(vertices, faces);
    Report unused;
    build_mesh(s, mesh_, unused, "run mrepair.soup_to_manifold first");
    without_gil([&] {
      sequence_ = std::make_unique<Sequence>(
          mesh_, tolerance, MP::gap_relative_tolerance(relative, MP::gap_lambda(lambda)));
      return 0;
    });
    if (sequence_->status() != Status::ok) {
      const Gap_closing_result r = sequence_->result();
      raise_value_error(status_line(r.status, r.message));
    }
  }

  std::size_t forward(std::size_t k)
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    return sequence_->forward(k);
  }
  std::size_t backward(std::size_t k)
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    return sequence_->backward(k);
  }
  long long to_distance(double d)
  {
    if (std::isnan(d)) raise_value_error("distance must not be NaN");
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    if (d >= sequence_->current_distance())
      return static_cast<long long>(sequence_->forward_to_distance(d));
    return -static_cast<long long>(sequence_->backward_to_distance(d));
  }
  py::tuple mesh()
  {
    std::unique_lock<std::mutex> lock(mutex_, std::defer_lock);
    {
      py::gil_scoped_release release;
      lock.lock();
    }
    auto arrays = arrays_of(mesh_);
    return py::make_tuple(arrays.first, arrays.second);
  }
  py::object report()
  {
    std::unique_lock<std::mutex> lock(mutex_, std::defer_lock);
    Report r;
    {
      py::gil_scoped_release release;
      lock.lock();
      sequence_->result().to_report(r);
    }
    return dict_of(r);
  }
  // the sequence's own counters; another thread may be stepping
  std::size_t position() { return locked([&] { return sequence_->position(); }); }
  std::size_t size() { return locked([&] { return sequence_->size(); }); }
  double current_distance() { return locked([&] { return sequence_->current_distance(); }); }
  double max_distance() { return sequence_->max_distance(); }
};

// ---- clean ---------------------------------------------------------------------------------------

// step names, comma-separated or as a sequence, into a mask
unsigned steps_from(const py::object& names)
{
  std::vector<std::string> list;
  if (py::isinstance<py::str>(names)) {
    std::stringstream ss(names.cast<std::string>());
    std::string name;
    while (std::getline(ss, name, ',')) list.push_back(name);
  } else {
    for (py::handle n : names) list.push_back(py::str(n));
  }
  unsigned mask = 0;
  for (const std::string& name : list) {
    if (name.empty()) continue;
    const unsigned step = parse_clean_step(name);
    if (step == 0) raise_value_error("unknown step '" + name + "'");
    mask |= step;
  }
  return mask;
}

// `mrepair clean`: the RameshCleaner pipeline on a manifold mesh.
py::tuple clean(const py::object& vertices, const py::object& faces, const std::string& profile_name,
                const py::object& only, const py::object& skip,
                const std::optional<double>& spike_angle, const std::optional<long long>& max_hole,
                const std::optional<long long>& min_component,
                const std::optional<long long>& iterations,
                const std::optional<double>& boundary_angle, const std::optional<double>& density,
                bool fair, const py::object& progress)
{
  Input_profile profile = Input_profile::scan;
  if (!parse_input_profile(profile_name, profile))
    raise_value_error("profile must be 'scan', 'cad' or 'auto', got '" + profile_name + "'");
  unsigned mask = profile == Input_profile::cad ? unsigned(clean_steps_cad) : unsigned(clean_step_all);
  if (!only.is_none()) mask = steps_from(only);
  if (!skip.is_none()) mask &= ~steps_from(skip);
  if (max_hole.value_or(0) < 0 || min_component.value_or(0) < 0 || iterations.value_or(0) < 0)
    raise_value_error("max_hole, min_component and iterations must not be negative");
  Soup s = soup_from(vertices, faces);
  Report report;
  Mesh mesh;
  build_mesh(s, mesh, report, "run mrepair.repair");
  Python_visitor visitor(progress);
  // None: absent, the library's default (without max_hole the profile's limit)
  auto run = [&](const auto& steps_np) {
    return clean_scan_mesh(
        mesh, MP::input_profile(
                  profile, MP::max_hole_vertices(
                               max_hole,
                               MP::min_component_faces(
                                   min_component,
                                   MP::max_clean_iterations(
                                       iterations,
                                       MP::boundary_dihedral_angle(
                                           boundary_angle,
                                           MP::hole_density_factor(
                                               density, MP::fair_hole_patches(
                                                            fair, MP::spike_angle(spike_angle, steps_np))))))))
                  .visitor(std::ref(visitor)));
  };
  // with auto and no step list, the profile picks the steps
  const bool profile_picks = profile == Input_profile::automatic && only.is_none() && skip.is_none();
  const Scan_cleaning_result r = without_gil([&] {
    return profile_picks ? run(CGAL::parameters::default_values()) : run(MP::clean_steps(mask));
  });
  r.to_report(report.section("clean"));
  visitor.raise_if_stopped();
  if (!succeeded(r.status)) raise_value_error("clean: " + status_line(r.status, r.message));
  return result_of(mesh, report);
}

// ---- remesh --------------------------------------------------------------------------------------

// `mrepair remesh`: uniform (edge_length, faces) or curvature-adaptive (tolerance).
py::tuple remesh(const py::object& vertices, const py::object& faces,
                 const std::optional<double>& edge_length, const std::optional<double>& tolerance,
                 const std::optional<long long>& target_faces,
                 const std::optional<double>& feature_angle, const std::optional<long long>& iterations,
                 const std::optional<double>& min_edge_length,
                 const std::optional<double>& max_edge_length, bool protect_features,
                 const py::object& progress)
{
  if (int(bool(edge_length)) + int(bool(tolerance)) + int(bool(target_faces)) != 1)
    raise_value_error("give exactly one of edge_length, tolerance, faces");
  if (iterations && (*iterations < 0 || *iterations > 1000))
    raise_value_error("iterations must be in [0, 1000]");
  if (target_faces && *target_faces <= 0) raise_value_error("faces must be positive");
  Soup s = soup_from(vertices, faces);
  Report report;
  Mesh mesh;
  build_mesh(s, mesh, report, "run mrepair.repair or mrepair.soup_to_manifold first");
  Python_visitor visitor(progress);
  using Parallel = CGAL::Parallel_if_available_tag;
  // None: absent, the library's default; a feature angle of 0 turns detection off
  std::optional<double> angle;
  if (feature_angle) angle = *feature_angle > 0 ? *feature_angle : -1.;
  std::optional<int> rounds;
  if (iterations) rounds = int(*iterations);
  auto np = MP::remesh_feature_angle(angle)
                .number_of_iterations(rounds)
                .protect_constraints(protect_features)
                .visitor(std::ref(visitor));
  const auto t0 = std::chrono::steady_clock::now();
  const Remeshing_result r = without_gil([&] {
    if (edge_length) return isotropic_remesh<Parallel>(mesh, *edge_length, np);
    if (target_faces)
      return remesh_to_face_count<Parallel>(mesh, static_cast<std::size_t>(*target_faces), np);
    const double e = *tolerance;
    auto np2 = MP::remesh_min_edge_length(min_edge_length ? *min_edge_length : e, np);
    if (max_edge_length)
      return adaptive_remesh<Parallel>(mesh, e, MP::remesh_max_edge_length(*max_edge_length, np2));
    return adaptive_remesh<Parallel>(mesh, e, np2);
  });
  r.to_report(report.section("remesh"));
  report.add("seconds", seconds_since(t0));
  visitor.raise_if_stopped();
  if (!succeeded(r.status)) raise_value_error("remesh: " + status_line(r.status, r.message));
  return result_of(mesh, report);
}

} // namespace

void register_mesh_calls(py::module_& m)
{
  using namespace pybind11::literals;

  m.def("close_gaps", &close_gaps, "V"_a, "F"_a, "tolerance"_a = py::none(), py::kw_only(),
        "relative"_a = false, "steps"_a = py::none(), "lambda_"_a = 0.5, "keep_pinched"_a = false,
        "progress"_a = py::none(),
        R"doc(Returns (V, F, report).

Closes cracks, narrow gaps and T-junctions between boundaries by progressive
vertex-vertex and vertex-edge contraction, nearest pairs first (`mrepair
close-gaps`). An input that is not a valid polygon mesh is repaired as a soup
first (a UserWarning says so; section "soup" of the report).

tolerance: largest gap closed, in model units (a fraction of the bounding-box
  diagonal with relative=True). None: estimated from the input's boundaries
  (`mrepair close-gaps --tolerance auto`, doc/close_gaps.md); the report gives
  the estimate.
steps: stop after this many contractions (None: all within the tolerance).
lambda_: a contracted vertex moves to lambda_ v + (1 - lambda_) v'.
keep_pinched: do not split vertices left with several fans.
The report is that of the command: soup (when needed), triangulation (when
polygons were triangulated), close_gaps.
progress: None or progress(phase, fraction); returning False cancels
  (mrepair.Cancelled), as Ctrl-C does (KeyboardInterrupt).)doc");

  py::class_<Gap_sequence>(m, "GapClosingSequence", R"doc(
GapClosingSequence(V, F, tolerance, *, relative=False, lambda_=0.5)

The progressive gap closing as a sequence to scrub through: forward() and
backward() apply and undo contractions; after stepping back to position 0,
mesh() returns exactly the input (same vertices, bit for bit; the same faces,
possibly in another order). The input must be a valid polygon mesh
(ValueError otherwise, and for NaN coordinates); polygons are triangulated.)doc")
      .def(py::init<const py::object&, const py::object&, double, bool, double>(), "V"_a, "F"_a,
           "tolerance"_a, py::kw_only(), "relative"_a = false, "lambda_"_a = 0.5)
      .def("forward", &Gap_sequence::forward, "steps"_a = 1,
           "forward(steps=1) -> int: applies up to `steps` contractions; returns how many")
      .def("backward", &Gap_sequence::backward, "steps"_a = 1,
           "backward(steps=1) -> int: undoes up to `steps` contractions; returns how many")
      .def("to_distance", &Gap_sequence::to_distance, "distance"_a,
           "to_distance(distance) -> int: moves forward while the next pair is not farther "
           "than `distance` (at most the tolerance), or back until the current distance is "
           "not above it; returns the contractions applied (> 0) or undone (< 0)")
      .def("mesh", &Gap_sequence::mesh, "mesh() -> (V, F): the mesh at the current position")
      .def("report", &Gap_sequence::report,
           "report() -> dict: the counters of the current position (the close_gaps section)")
      .def_property_readonly("position", &Gap_sequence::position,
                             "contractions applied to the mesh now")
      .def_property_readonly("size", &Gap_sequence::size, "contractions recorded so far")
      .def_property_readonly("current_distance", &Gap_sequence::current_distance,
                             "error level now: the largest pair distance applied (0 at the input)")
      .def_property_readonly("max_distance", &Gap_sequence::max_distance,
                             "the absolute distance limit (the tolerance)");

  m.def("clean", &clean, "V"_a, "F"_a, py::kw_only(), "profile"_a = "scan", "only"_a = py::none(),
        "skip"_a = py::none(), "spike_angle"_a = py::none(), "max_hole"_a = py::none(),
        "min_component"_a = py::none(), "iterations"_a = py::none(), "boundary_angle"_a = py::none(),
        "density"_a = py::none(), "fair"_a = false, "progress"_a = py::none(),
        R"doc(Returns (V, F, report).

The RameshCleaner pipeline on a manifold mesh (`mrepair clean`): spikes,
unrelaxable spikes, jagged boundaries, small components, small holes,
near-degenerate faces, validity. The faces must form a manifold, consistently
oriented mesh (ValueError otherwise: run repair); NaN vertices are removed.

profile: "scan" (every step), "cad" (degenerate vertices, small components,
  holes, validity) or "auto" (decided from the mesh when only/skip are None).
only, skip: step names (a list, or one comma-separated string):
  remove_degenerate_vertices, relax_spikes, remove_unrelaxable_spikes,
  clean_boundaries, remove_small_components, fill_small_holes,
  fix_near_degenerate_faces, relax_spikes_again, ensure_valid_mesh.
spike_angle: dihedral angle (degrees) of a spiked vertex (None: the default, 100).
max_hole, min_component, iterations, boundary_angle, density, fair: as the
  command's --max-hole, --min-component, --iterations, --boundary-angle,
  --density, --fair.
The report is that of the command: triangulation (when needed), clean.
progress: None or progress(phase, fraction); returning False cancels
  (mrepair.Cancelled), as Ctrl-C does (KeyboardInterrupt).)doc");

  m.def("remesh", &remesh, "V"_a, "F"_a, py::kw_only(), "edge_length"_a = py::none(),
        "tolerance"_a = py::none(), "faces"_a = py::none(), "feature_angle"_a = py::none(),
        "iterations"_a = py::none(), "min_edge_length"_a = py::none(), "max_edge_length"_a = py::none(),
        "protect_features"_a = false, "progress"_a = py::none(),
        R"doc(Returns (V, F, report).

Isotropic remeshing with features kept (`mrepair remesh`); give exactly one of
edge_length (uniform), tolerance (curvature-adaptive, approximation
tolerance) or faces (uniform, about that many faces).

feature_angle: dihedral angle (degrees) of feature edges (0: none).
min_edge_length, max_edge_length: adaptive sizing clamps (defaults: the
  tolerance, and the bounding-box diagonal / 20).
protect_features: features and boundary are neither split nor collapsed.
The report is that of the command: triangulation (when needed), remesh, seconds.
progress: None or progress(phase, fraction); returning False cancels
  (mrepair.Cancelled), as Ctrl-C does (KeyboardInterrupt).)doc");
}

} // namespace python
} // namespace mrepair
