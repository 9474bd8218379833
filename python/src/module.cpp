// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The Python module `mrepair._mrepair`: files, inspection, soup to manifold
// and the whole repair job. Each call copies the caller's arrays, runs the
// library without the GIL and returns new arrays and the report of the
// matching `mrepair` command as a dict (without the sections that describe
// files). The mesh calls are in mesh_calls.cpp.
#include "binding.h"

#include <mrepair/compare_to_reference.h>
#include <mrepair/inspect.h>
#include <mrepair/internal/studio/overlay.h>
#include <mrepair/io.h>
#include <mrepair/locate_defects.h>
#include <mrepair/repair.h>
#include <mrepair/stitch_soup.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace mrepair {
namespace python {
namespace {

namespace MP = mrepair::parameters;

// a str or an os.PathLike, as a path
std::string path_of(const py::object& path)
{
  return py::str(py::module_::import("os").attr("fspath")(path));
}

py::tuple read(const py::object& path_object)
{
  const std::string path = path_of(path_object);
  Soup s;
  const Io_result r = without_gil([&] { return read_polygon_soup(path, s.points, s.polygons); });
  // non-finite points are data a repair fixes; invalid indices cannot travel in arrays
  if (r.status == Status::io_error) raise_error(PyExc_OSError, r.message);
  if (r.status != Status::ok && r.status != Status::non_finite_input)
    raise_value_error(r.message.empty() ? path + ": " + to_string(r.status) : r.message);
  auto arrays = arrays_of(s.points, s.polygons);
  return py::make_tuple(arrays.first, arrays.second);
}

void write(const py::object& path_object, const py::object& vertices, const py::object& faces,
           bool binary)
{
  const std::string path = path_of(path_object);
  Soup s = soup_from(vertices, faces);
  const Io_result r =
      without_gil([&] { return write_polygon_soup(path, s.points, s.polygons, binary); });
  if (r.status == Status::io_error) raise_error(PyExc_OSError, r.message);
  if (r.status != Status::ok)
    raise_value_error(r.message.empty() ? path + ": " + to_string(r.status) : r.message);
}

// `mrepair inspect`: the soup's counts, and the border loops of the mesh
// view when the polygons form a mesh (the same sections as the command).
py::object inspect(const py::object& vertices, const py::object& faces,
                   const std::optional<double>& spike_angle, const std::optional<long long>& small_hole,
                   const std::optional<long long>& small_component,
                   const std::optional<double>& t_junction_tolerance, bool self_intersections,
                   const py::object& progress)
{
  if (spike_angle && !(*spike_angle >= 0 && *spike_angle <= 180))
    raise_value_error("spike_angle expects degrees in [0, 180]");
  if (small_hole.value_or(0) < 0 || small_component.value_or(0) < 0)
    raise_value_error("small_hole and small_component must not be negative");
  const double tol = t_junction_tolerance ? *t_junction_tolerance : -1.;  // < 0: relative default
  if (t_junction_tolerance && !(tol >= 0 && std::isfinite(tol)))
    raise_value_error("t_junction_tolerance expects a non-negative distance");
  Soup s = soup_from(vertices, faces);
  Python_visitor visitor(progress);
  auto thresholds = [&](bool count_si) {
    // None: absent, the library's default (parameters.h)
    return MP::spike_angle(
               spike_angle,
               MP::max_hole_vertices(
                   small_hole,
                   MP::min_component_faces(small_component,
                                           MP::t_junction_tolerance(
                                               tol, MP::count_self_intersections(count_si)))))
        .visitor(std::ref(visitor));
  };
  Report report;
  without_gil([&] {
    Inspection_report soup = inspect_polygon_soup(s.points, s.polygons, thresholds(self_intersections));
    soup.to_report(report);
    Report& mesh_section = report.section("mesh");
    const bool is_mesh = soup.invalid_polygons == 0 && !s.polygons.empty() &&
                         is_polygon_soup_a_polygon_mesh(s.polygons, s.points.size());
    mesh_section.add("built", is_mesh);
    if (is_mesh) {
      Mesh mesh;
      CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(s.points, s.polygons, mesh);
      // the soup pass counted everything else (self-intersections included)
      Inspection_report m = mrepair::inspect(mesh, thresholds(false));
      mesh_section.add("boundary_loops", m.boundary_loops);
      mesh_section.add("small_holes", m.small_holes);
    } else {
      mesh_section.add("reason", soup.invalid_polygons > 0
                                     ? "invalid polygons"
                                     : "not a manifold, consistently oriented polygon mesh");
    }
    return 0;
  });
  visitor.raise_if_stopped();
  return dict_of(report);
}

// `mrepair inspect OUTPUT --reference INPUT`: the "reference" section, plus the
// indices of the lost reference vertices.
py::object compare_to_reference_py(const py::object& vertices, const py::object& faces,
                                   const py::object& reference, const std::optional<double>& tolerance)
{
  if (tolerance && !(*tolerance >= 0 && std::isfinite(*tolerance)))
    raise_value_error("tolerance expects a finite, non-negative distance");
  Soup s = soup_from(vertices, faces);
  const std::vector<Point> reference_points = vertices_from(reference);
  const Reference_comparison r = without_gil([&] {
    return compare_to_reference(reference_points, s.points, s.polygons, MP::reference_tolerance(tolerance));
  });
  if (r.status == Status::invalid_parameter) raise_value_error(r.message);
  Report report;
  r.to_report(report);
  py::object d = dict_of(report);
  py::array_t<long long> lost(static_cast<py::ssize_t>(r.lost.size()));
  auto out = lost.mutable_unchecked<1>();
  for (std::size_t i = 0; i < r.lost.size(); ++i) out(static_cast<py::ssize_t>(i)) = static_cast<long long>(r.lost[i]);
  d["lost"] = lost;
  return d;
}

// ---- defect locations, overlay and preview (doc/studio.md) -----------------------------

struct Inspect_options
{
  std::optional<double> spike_angle;
  std::optional<long long> small_hole, small_component;
  std::optional<double> t_junction_tolerance;
  bool self_intersections = true;
  bool mesh = false;
};

// the defects of the soup (V, F), as mrepair.inspect counts them in "defects";
// with `o.mesh`, of the polygon mesh the faces form (inspect(mesh), as the
// "after" inspection of mrepair.repair), the elements numbered as in (V, F).
// `faces` (when given) gets the positions and faces the indices refer to.
Defect_locations locate(const Soup& s, const Inspect_options& o, internal::Indexed_faces* faces = nullptr)
{
  if (o.spike_angle && !(*o.spike_angle >= 0 && *o.spike_angle <= 180))
    raise_value_error("spike_angle expects degrees in [0, 180]");
  if (o.small_hole.value_or(0) < 0 || o.small_component.value_or(0) < 0)
    raise_value_error("small_hole and small_component must not be negative");
  const double tol = o.t_junction_tolerance ? *o.t_junction_tolerance : -1.;
  if (o.t_junction_tolerance && !(tol >= 0 && std::isfinite(tol)))
    raise_value_error("t_junction_tolerance expects a non-negative distance");
  const auto np = MP::spike_angle(
      o.spike_angle,
      MP::max_hole_vertices(o.small_hole,
                            MP::min_component_faces(o.small_component,
                                                    MP::t_junction_tolerance(
                                                        tol, MP::count_self_intersections(o.self_intersections)))));
  if (o.mesh && !is_polygon_soup_a_polygon_mesh(s.polygons, s.points.size()))
    raise_value_error("mesh=True: the faces do not form a manifold, consistently oriented polygon mesh");
  Defect_locations d = without_gil([&] {
    if (!o.mesh) {
      if (faces) *faces = internal::indexed_faces_of_soup(s.points, s.polygons);
      return locate_defects(s.points, s.polygons, np);
    }
    // polygon_soup_to_polygon_mesh adds the points, then the faces, in order
    Mesh mesh;
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(s.points, s.polygons, mesh);
    if (faces) *faces = internal::indexed_faces_of_mesh(mesh);
    return locate_defects(mesh, np);
  });
  if (d.report.status == Status::invalid_parameter) raise_value_error(status_line(d.report.status, d.report.message));
  return d;
}

py::array_t<std::int64_t> int_array(const std::vector<Defect_locations::Index>& v)
{
  py::array_t<std::int64_t> a(static_cast<py::ssize_t>(v.size()));
  std::int64_t* o = a.mutable_data();
  for (Defect_locations::Index x : v) *o++ = x == Defect_locations::walk_end ? -1 : static_cast<std::int64_t>(x);
  return a;
}

py::array_t<std::int64_t> pair_array(const std::vector<std::array<Defect_locations::Index, 2>>& v)
{
  py::array_t<std::int64_t> a({static_cast<py::ssize_t>(v.size()), py::ssize_t(2)});
  std::int64_t* o = a.mutable_data();
  for (const auto& p : v) {
    *o++ = static_cast<std::int64_t>(p[0]);
    *o++ = static_cast<std::int64_t>(p[1]);
  }
  return a;
}

py::list array_list(const std::vector<std::vector<Defect_locations::Index>>& v)
{
  py::list l;
  for (const auto& x : v) l.append(int_array(x));
  return l;
}

py::dict locate_defects_py(const py::object& vertices, const py::object& faces,
                           const std::optional<double>& spike_angle, const std::optional<long long>& small_hole,
                           const std::optional<long long>& small_component,
                           const std::optional<double>& t_junction_tolerance, bool self_intersections, bool mesh)
{
  const Soup s = soup_from(vertices, faces);
  const Defect_locations d =
      locate(s, {spike_angle, small_hole, small_component, t_junction_tolerance, self_intersections, mesh});
  const Inspection_report& r = d.report;
  auto kind = [](std::size_t count) {
    py::dict k;
    k["count"] = count;
    return k;
  };
  py::dict out;
  py::dict loops = kind(r.boundary_loops);
  loops["loops"] = array_list(d.boundary_loops);
  out["boundary_loops"] = loops;
  py::dict holes = kind(r.small_holes);
  py::list hole_loops;
  for (Defect_locations::Index i : d.small_holes) hole_loops.append(int_array(d.boundary_loops[i]));
  holes["loops"] = hole_loops;
  holes["indices"] = int_array(d.small_holes);
  out["small_holes"] = holes;
  py::dict nme = kind(r.non_manifold_edges);
  nme["edges"] = pair_array(d.non_manifold_edges);
  out["non_manifold_edges"] = nme;
  py::dict nmv = kind(r.non_manifold_vertices);
  nmv["vertices"] = int_array(d.non_manifold_vertices);
  out["non_manifold_vertices"] = nmv;
  py::dict spikes = kind(r.spiked_vertices);
  spikes["vertices"] = int_array(d.spiked_vertices);
  out["spikes"] = spikes;
  py::dict nd = kind(r.near_degenerate_faces);
  nd["faces"] = int_array(d.near_degenerate_faces);
  out["near_degenerate_faces"] = nd;
  py::dict comps = kind(r.small_components);
  std::vector<Defect_locations::Index> all_faces;
  for (const auto& c : d.small_components) all_faces.insert(all_faces.end(), c.begin(), c.end());
  comps["faces"] = int_array(all_faces);
  comps["components"] = array_list(d.small_components);
  out["small_components"] = comps;
  py::dict pairs = kind(r.self_intersecting_pairs);
  pairs["pairs"] = pair_array(d.self_intersecting_pairs);
  py::array_t<bool> touching(static_cast<py::ssize_t>(d.self_intersecting_pairs_touching.size()));
  for (std::size_t i = 0; i < d.self_intersecting_pairs_touching.size(); ++i)
    touching.mutable_data()[i] = d.self_intersecting_pairs_touching[i] != 0;
  pairs["touching"] = touching;
  pairs["computed"] = r.self_intersections_counted;
  out["crossing_pairs"] = pairs;
  py::dict tj = kind(r.t_junctions);
  tj["vertices"] = int_array(d.t_junction_vertices);
  tj["edges"] = pair_array(d.t_junction_edges);
  out["t_junctions"] = tj;
  return out;
}

py::array_t<float> float_array(const std::vector<float>& v, py::ssize_t width)
{
  py::array_t<float> a({static_cast<py::ssize_t>(v.size()) / width, width});
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict defect_overlay_py(const py::object& vertices, const py::object& faces,
                           const std::optional<double>& spike_angle, const std::optional<long long>& small_hole,
                           const std::optional<long long>& small_component,
                           const std::optional<double>& t_junction_tolerance, bool self_intersections,
                           bool mesh, long long max_elements)
{
  if (max_elements < 0) raise_value_error("max_elements must not be negative");
  const Soup s = soup_from(vertices, faces);
  internal::Indexed_faces drawn;
  const Defect_locations d =
      locate(s, {spike_angle, small_hole, small_component, t_junction_tolerance, self_intersections, mesh}, &drawn);
  const internal::Defect_overlay o = without_gil(
      [&] { return internal::make_defect_overlay(drawn, d, static_cast<std::size_t>(max_elements)); });
  py::dict kinds;
  for (const internal::Overlay_kind& k : o.kinds) {
    py::dict x;
    x["count"] = k.count;
    x["label"] = k.label;
    x["color"] = k.color;
    x["points"] = float_array(k.points, 3);
    x["segments"] = float_array(k.segments, 6);
    x["triangles"] = float_array(k.triangles, 9);
    if (k.has_first) {
      x["first"] = py::make_tuple(k.first[0], k.first[1], k.first[2]);
      x["first_radius"] = k.first_radius;
    } else {
      x["first"] = py::none();
      x["first_radius"] = py::none();
    }
    x["drawn"] = k.drawn;
    x["truncated"] = k.truncated;
    kinds[py::str(k.key)] = x;
  }
  py::dict out;
  out["kinds"] = kinds;
  return out;
}

py::tuple preview_mesh_py(const py::object& vertices, const py::object& faces, long long face_budget)
{
  if (face_budget < 0) raise_value_error("face_budget must not be negative");
  const Soup s = soup_from(vertices, faces);
  const internal::Mesh_preview p = without_gil([&] {
    return internal::make_preview(internal::indexed_faces_of_soup(s.points, s.polygons),
                                  static_cast<std::size_t>(face_budget));
  });
  py::array_t<std::uint32_t> F({static_cast<py::ssize_t>(p.indices.size() / 3), py::ssize_t(3)});
  std::copy(p.indices.begin(), p.indices.end(), F.mutable_data());
  return py::make_tuple(float_array(p.positions, 3), F, p.decimated);
}

// `mrepair soup`: polygon soup to oriented manifold triangle mesh.
py::tuple soup_to_manifold(const py::object& vertices, const py::object& faces, double epsilon,
                           double merge_epsilon, bool keep_two_sided, bool orient_outward,
                           const py::object& progress)
{
  if (!(epsilon >= 0) || !(merge_epsilon >= 0))
    raise_value_error("epsilon and merge_epsilon expect non-negative distances");
  Soup s = soup_from(vertices, faces);
  Python_visitor visitor(progress);
  Report report;
  Mesh mesh;
  const Soup_repair_result r = without_gil([&] {
    inspect_polygon_soup(s.points, s.polygons, MP::count_self_intersections(false))
        .to_summary_report(report.section("before"));
    Soup_repair_result result = polygon_soup_to_manifold_mesh(
        s.points, s.polygons, mesh,
        MP::snap_epsilon(epsilon, MP::merge_epsilon(merge_epsilon,
                                                    MP::keep_two_sided(keep_two_sided,
                                                                       MP::orient_outward(orient_outward))))
            .visitor(std::ref(visitor)));
    result.to_report(report.section("soup"));
    if (succeeded(result.status))
      mrepair::inspect(mesh, MP::count_self_intersections(false))
          .to_summary_report(report.section("after"));
    return result;
  });
  visitor.raise_if_stopped();
  if (!succeeded(r.status)) raise_value_error(status_line(r.status, r.message));
  return result_of(mesh, report);
}

// `mrepair repair`: the whole job of repair.h.
py::tuple repair(const py::object& vertices, const py::object& faces, const std::string& profile,
                 const std::optional<double>& close_gaps, const std::optional<double>& merge_epsilon,
                 const std::optional<double>& spike_angle, const std::optional<long long>& max_hole,
                 const std::optional<long long>& min_component,
                 const std::optional<long long>& iterations, bool self_intersections,
                 bool input_self_intersections, bool resolve_intersections,
                 bool merge_overlapping_shells, const py::object& progress)
{
  Input_profile input_profile = Input_profile::automatic;
  if (!parse_input_profile(profile, input_profile))
    raise_value_error("profile must be 'auto', 'scan' or 'cad', got '" + profile + "'");
  const double gap = close_gaps.value_or(0.), merge = merge_epsilon.value_or(0.);
  if (!(gap >= 0) || !(merge >= 0) || !std::isfinite(gap) || !std::isfinite(merge))
    raise_value_error("close_gaps and merge_epsilon must be finite and >= 0");
  if (max_hole.value_or(1) < 1 || min_component.value_or(1) < 1 || iterations.value_or(0) < 0)
    raise_value_error("max_hole and min_component must be >= 1, iterations >= 0");
  // The options reach the library as given or absent (None): the defaults
  // are the library's, as for `mrepair repair`. close_gaps None lets a
  // CAD-profile input get the automatic tolerance, 0 turns gap closing off,
  // T > 0 closes gaps up to T.
  const auto np =
      MP::input_profile(
          input_profile,
          MP::gap_tolerance(
              close_gaps,
              MP::automatic_gap_tolerance(
                  !close_gaps,
                  MP::merge_epsilon(
                      merge_epsilon,
                      MP::spike_angle(
                          spike_angle,
                          MP::max_hole_vertices(
                              max_hole,
                              MP::min_component_faces(
                                  min_component,
                                  MP::max_clean_iterations(
                                      iterations,
                                      MP::count_self_intersections(
                                          self_intersections,
                                          MP::count_input_self_intersections(
                                              input_self_intersections,
                                              MP::resolve_intersections(
                                                  resolve_intersections,
                                                  MP::merge_overlapping_shells(
                                                      merge_overlapping_shells))))))))))));
  Soup s = soup_from(vertices, faces);
  Python_visitor visitor(progress);
  Mesh mesh;
  const Repair_result r = without_gil([&] {
    return repair_polygon_soup(s.points, s.polygons, mesh, np.visitor(std::ref(visitor)));
  });
  visitor.raise_if_stopped();
  if (!r.failed_stage.empty()) raise_value_error(r.message);
  // the command writes its output and exits 1: nothing to return here
  if (!succeeded(r.status)) raise_value_error("clean: " + status_line(r.status, r.clean.message));
  Report report;
  r.to_report(report);
  return result_of(mesh, report);
}

} // namespace
} // namespace python
} // namespace mrepair

PYBIND11_MODULE(_mrepair, m)
{
  namespace py = pybind11;
  namespace mp = mrepair::python;
  using namespace pybind11::literals;
  m.doc() = "mrepair: mesh repair and remeshing on CGAL (the compiled part of the package)";

  PyObject* cancelled = PyErr_NewExceptionWithDoc(
      "mrepair.Cancelled",
      "raised when a progress callable returns False; a KeyboardInterrupt, so that "
      "code handling Ctrl-C handles it too",
      PyExc_KeyboardInterrupt, nullptr);
  if (!cancelled) throw py::error_already_set();
  mp::cancelled_type() = cancelled;
  m.attr("Cancelled") = py::handle(cancelled);

  m.def("read", &mp::read, "path"_a,
        R"doc(Reads an OFF, OBJ, PLY or STL file (by extension) as a polygon soup.

Returns V, a float64 (N, 3) array, and F, an int64 (M, 3) array when every
face is a triangle, else a list of index lists. Points with NaN or infinite
coordinates are returned as read (repair removes them). Raises OSError when
the file cannot be read, ValueError when it is malformed, empty, of an
unknown kind, or has faces with out-of-range indices.)doc");

  m.def("write", &mp::write, "path"_a, "V"_a, "F"_a, py::kw_only(), "binary"_a = false,
        R"doc(Writes vertices and faces to an OFF, OBJ, PLY or STL file (by extension);
binary=True writes binary PLY or STL. ASCII OFF, OBJ and PLY and binary PLY
keep every coordinate exactly. Raises OSError or ValueError.)doc");

  m.def("inspect", &mp::inspect, "V"_a, "F"_a, py::kw_only(), "spike_angle"_a = py::none(),
        "small_hole"_a = py::none(), "small_component"_a = py::none(), "t_junction_tolerance"_a = py::none(),
        "self_intersections"_a = true, "progress"_a = py::none(),
        R"doc(Returns the report, a dict.

Counts every defect mrepair fixes (doc/defects.md) and the quality figures;
returns the report of `mrepair inspect --json` as a dict: status, kind,
sections input, defects, quality, thresholds and mesh (border loops when
the faces form a mesh).

spike_angle: dihedral angle in degrees above which an edge is spiked.
small_hole: boundary loops with fewer edges are small holes.
small_component: components with fewer faces are small.
t_junction_tolerance: distance of a T-junction (None: 1e-4 x bbox diagonal).
self_intersections: count self-intersecting face pairs (the costly test).
progress: None or progress(phase: str, fraction: float); returning False cancels.)doc");

  m.def("compare_to_reference", &mp::compare_to_reference_py, "V"_a, "F"_a, "reference"_a, py::kw_only(),
        "tolerance"_a = py::none(),
        R"doc(Returns how much of a reference (the input of a repair) the mesh (V, F) holds, a dict.

The "reference" section of `mrepair inspect OUTPUT --reference INPUT`: vertices
(finite reference points compared), vertices_lost (neither within tolerance of
the surface nor inside a closed part of it), max_distance (absolute),
max_distance_relative (to the reference's bounding-box diagonal),
vertices_inside, tolerance, diagonal, inside_tested, status; and "lost", the
int64 indices of the lost reference points.

reference: an (N, 3) array, e.g. the V of the input.
tolerance: a reference point this close to the surface is on it (None: 1e-6 x
the diagonal).)doc");

  m.def("soup_to_manifold", &mp::soup_to_manifold, "V"_a, "F"_a, py::kw_only(),
        "epsilon"_a = 0.0, "merge_epsilon"_a = 0.0, "keep_two_sided"_a = false,
        "orient_outward"_a = true, "progress"_a = py::none(),
        R"doc(Returns (V, F, report).

Turns any polygon soup into a consistently oriented manifold triangle mesh
(cutting and stitching): merges points, drops invalid, degenerate and
duplicate faces, cuts non-manifold edges and vertices, orients, stitches.
The report is that of `mrepair soup --json`: before, soup, after.

epsilon: stitch boundary edges whose ends lie within this distance (0: off).
merge_epsilon: merge points within this distance first (0: equal points only).
keep_two_sided: keep both faces of a two-sided sheet.
orient_outward: closed components bound a volume.
Raises ValueError when the soup holds nothing to build (e.g. no face).
progress: None or progress(phase, fraction); returning False cancels
  (mrepair.Cancelled), as Ctrl-C does (KeyboardInterrupt).)doc");

  m.def("repair", &mp::repair, "V"_a, "F"_a, py::kw_only(), "profile"_a = "auto",
        "close_gaps"_a = py::none(), "merge_epsilon"_a = py::none(), "spike_angle"_a = py::none(),
        "max_hole"_a = py::none(), "min_component"_a = py::none(), "iterations"_a = py::none(),
        "self_intersections"_a = true, "input_self_intersections"_a = false,
        "resolve_intersections"_a = true, "merge_overlapping_shells"_a = true,
        "progress"_a = py::none(),
        R"doc(Returns (V, F, report).

The whole job of `mrepair repair`, keeping the user's model: soup to manifold
mesh when the input is not one, gap closing when asked, the cleaning steps of
the input's profile (a dense scan gets RameshCleaner, a CAD export or print
model keeps its geometry and parts and gets its holes closed), the validity
step. The report is that of `mrepair repair --json` without the file
sections: before, soup_to_manifold, triangulation (when polygons were
triangulated), close_gaps (when run), clean, resolve_intersections (when
run), face_accounting, after.

profile: "auto" (decided from the mesh), "scan" or "cad".
close_gaps: close boundary gaps narrower than this (model units); None: a CAD
  or print model gets the automatic tolerance (see doc/close_gaps.md), a scan
  none; 0: off.
merge_epsilon: merge soup points closer than this before stitching.
spike_angle: dihedral angle (degrees) of a spiked vertex (None: the default).
max_hole: holes with fewer boundary vertices are filled (None: 100 scan, 500 cad).
min_component: components with fewer faces are removed (relative to the largest).
iterations: cleaning iteration cap.
self_intersections: count self-intersections in the inspection after.
resolve_intersections: after the cleaning, repair a shell crossing itself
  locally and merge overlapping closed shells (doc/solids.md).
merge_overlapping_shells: False keeps crossing closed shells apart.
input_self_intersections: count them in the inspection before too (off by
  default: they cost more than the cleaning on a 1M-face scan).
Raises ValueError with the stage and the reason when a stage fails.
progress: None or progress(phase, fraction); returning False cancels
  (mrepair.Cancelled), as Ctrl-C does (KeyboardInterrupt).)doc");

  m.def("locate_defects", &mp::locate_defects_py, "V"_a, "F"_a, py::kw_only(), "spike_angle"_a = py::none(),
        "small_hole"_a = py::none(), "small_component"_a = py::none(), "t_junction_tolerance"_a = py::none(),
        "self_intersections"_a = true, "mesh"_a = false,
        R"doc(Returns where the defects that mrepair.inspect counts are, a dict.

One entry per kind (doc/studio.md): boundary_loops, small_holes,
non_manifold_edges, non_manifold_vertices, spikes, near_degenerate_faces,
small_components, crossing_pairs, t_junctions. Each is a dict with "count"
(equal to the count of mrepair.inspect(V, F) with the same options, in its
"defects" section) and int64 arrays: "vertices", "edges" (k, 2 vertices),
"faces", "pairs" (k, 2 faces), "loops" (a list of vertex arrays in walk
order; -1 ends each open walk of a loop that is not one closed walk).
small_holes also has "indices" (into boundary_loops' loops),
small_components "components" (one face array each), crossing_pairs
"touching" (bool per pair: only touching at coincident vertices) and
"computed" (False when self-intersections were not counted).
Options as in mrepair.inspect; mesh=True inspects the faces as a polygon
mesh (as the "after" inspection of mrepair.repair: boundary loops are the
border cycles), a ValueError when they do not form one; the indices are
those of (V, F) all the same.)doc");

  m.def("defect_overlay", &mp::defect_overlay_py, "V"_a, "F"_a, py::kw_only(), "spike_angle"_a = py::none(),
        "small_hole"_a = py::none(), "small_component"_a = py::none(), "t_junction_tolerance"_a = py::none(),
        "self_intersections"_a = true, "mesh"_a = false, "max_elements"_a = 100000,
        R"doc(Returns the defects as geometry to draw: {"kinds": {kind: dict}}.

Per kind, in the order of mrepair.locate_defects: count, label, color
("#rrggbb"), float32 arrays points (k, 3), segments (k, 6), triangles
(k, 9), first (centre of the first instance, or None), first_radius,
drawn (instances drawn) and truncated (at most max_elements points,
segments and triangles per kind). The HTML report embeds the same dict,
its arrays in base64 (doc/studio.md).)doc");

  m.def("preview_mesh", &mp::preview_mesh_py, "V"_a, "F"_a, "face_budget"_a,
        R"doc(Returns (V2 float32 (n, 3), F2 uint32 (m, 3), decimated: bool).

The mesh itself (polygons split into triangles) when it has at most
face_budget triangles; else a vertex clustering on a uniform grid with at
most face_budget triangles (decimated True), for drawing large meshes.)doc");

  mp::register_mesh_calls(m);
}
