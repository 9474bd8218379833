// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// What the two translation units of the Python module share: the mesh type,
// NumPy arrays in and out, the report as a dict, errors as Python
// exceptions, and the visitor that drives a progress callable and turns
// Ctrl-C into a cancellation.
#ifndef MREPAIR_PYTHON_BINDING_H
#define MREPAIR_PYTHON_BINDING_H

#include <mrepair/io.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/triangulate_polygons.h>
#include <mrepair/visitors.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace mrepair {
namespace python {

namespace py = pybind11;
using Kernel = CGAL::Epick;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Polygon = std::vector<std::size_t>;

/// the caller's arrays, copied: the library never sees (or changes) them.
struct Soup
{
  std::vector<Point> points;
  std::vector<Polygon> polygons;
};

// ---- errors -------------------------------------------------------------------

/// the Python type `mrepair.Cancelled` (a KeyboardInterrupt), set up by the module.
inline PyObject*& cancelled_type()
{
  static PyObject* type = nullptr;
  return type;
}

[[noreturn]] inline void raise_error(PyObject* type, const std::string& message)
{
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}
[[noreturn]] inline void raise_value_error(const std::string& message)
{
  raise_error(PyExc_ValueError, message);
}

/// "status: message", the one line a failed call raises.
inline std::string status_line(Status s, const std::string& message)
{
  return std::string(to_string(s)) + (message.empty() ? "" : ": " + message);
}

// ---- progress and cancellation ----------------------------------------------------

/// Forwards the library's phases and progress to an optional Python callable
/// `progress(phase, fraction)` and polls Ctrl-C, while the computation runs
/// without the GIL. The callable returning False, or raising, stops the call
/// through `stop_requested()`; so does a pending signal whose handler raises
/// (Ctrl-C: KeyboardInterrupt). After the call, `raise_if_stopped()` raises
/// what stopped it. Python is touched only from the calling thread and at most
/// every few milliseconds (the library polls much more often).
class Python_visitor : public Default_visitor
{
  using Clock = std::chrono::steady_clock;
  py::object callback_;  // None or a callable
  std::thread::id caller_ = std::this_thread::get_id();
  std::vector<std::string> phases_;
  Clock::time_point last_callback_{}, last_signal_check_{};
  std::optional<py::error_already_set> error_;  // what the callable or a signal handler raised
  bool stop_ = false;
  bool declined_ = false;  // the callable returned False

  static constexpr std::chrono::milliseconds callback_interval{50};
  static constexpr std::chrono::milliseconds signal_interval{20};

  bool on_caller_thread() const { return std::this_thread::get_id() == caller_; }

  void check_signals()
  {
    const Clock::time_point now = Clock::now();
    if (now - last_signal_check_ < signal_interval) return;
    last_signal_check_ = now;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      error_.emplace();  // fetches the raised exception
      stop_ = true;
    }
  }

  void call(double fraction, bool always)
  {
    if (stop_) return;
    if (callback_.is_none()) {
      check_signals();
      return;
    }
    const Clock::time_point now = Clock::now();
    if (!always && now - last_callback_ < callback_interval) return;
    last_callback_ = now;
    py::gil_scoped_acquire gil;
    try {
      py::object answer =
          callback_(phases_.empty() ? std::string() : phases_.back(), fraction);
      if (answer.ptr() == Py_False) {
        declined_ = true;
        stop_ = true;
      }
    } catch (py::error_already_set& e) {
      error_.emplace(std::move(e));
      stop_ = true;
    }
    if (!stop_ && PyErr_CheckSignals() != 0) {
      error_.emplace();
      stop_ = true;
    }
  }

public:
  /// \param callback None or `progress(phase: str, fraction: float) -> bool | None`
  explicit Python_visitor(py::object callback) : callback_(std::move(callback))
  {
    if (!callback_.is_none() && !PyCallable_Check(callback_.ptr()))
      raise_error(PyExc_TypeError, "progress must be a callable progress(phase, fraction) or None");
  }

  void start_phase(const char* name)
  {
    if (!on_caller_thread()) return;
    phases_.push_back(name);
    call(0., true);
  }
  void end_phase(const char*)
  {
    if (!on_caller_thread() || phases_.empty()) return;
    call(1., true);
    phases_.pop_back();
  }
  void progress(double fraction)
  {
    if (on_caller_thread()) call(fraction, false);
  }
  bool stop_requested()
  {
    if (!stop_ && on_caller_thread()) check_signals();
    return stop_;
  }

  /// with the GIL: raises what stopped the call (the callable's exception,
  /// KeyboardInterrupt from a signal, or `Cancelled` when the callable
  /// returned False). Does nothing when nothing asked to stop.
  void raise_if_stopped()
  {
    if (error_) {
      py::error_already_set e = std::move(*error_);
      error_.reset();
      throw e;
    }
    if (declined_) raise_error(cancelled_type(), "cancelled: the progress callable returned False");
  }
};

/// runs `f` without the GIL (the library never touches Python objects).
template <typename F>
auto without_gil(F&& f)
{
  py::gil_scoped_release release;
  return f();
}

// ---- arrays in ------------------------------------------------------------------------

/// `numpy.asarray(obj)` without a copy when `obj` already is an array.
inline py::array as_array(const py::handle& obj)
{
  if (py::isinstance<py::array>(obj)) return py::reinterpret_borrow<py::array>(obj);
  return py::module_::import("numpy").attr("asarray")(obj);
}

/// copies the vertices: any real (float or integer) N x 3 array or nested sequence.
inline std::vector<Point> vertices_from(const py::handle& obj)
{
  py::array a = as_array(obj);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    raise_value_error("vertices must be a real N x 3 array (float64), got dtype " +
                      std::string(py::str(a.dtype())));
  if (a.ndim() == 1 && a.shape(0) == 0) return {};  // [] : no vertex
  if (a.ndim() != 2 || a.shape(1) != 3)
    raise_value_error("vertices must have shape (N, 3), got " +
                      std::string(py::str(py::getattr(a, "shape"))));
  // a C-contiguous float64 view, or copy (non-contiguous or other dtypes)
  auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!d) throw py::error_already_set();
  auto v = d.unchecked<2>();
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(v.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) points.emplace_back(v(i, 0), v(i, 1), v(i, 2));
  return points;
}

/// checks one corner; returns it as an index.
inline std::size_t checked_index(long long index, std::size_t face, std::size_t num_points)
{
  if (index < 0 || static_cast<unsigned long long>(index) >= num_points)
    raise_value_error("faces[" + std::to_string(face) + "] refers to vertex " +
                      std::to_string(index) + ", outside [0, " + std::to_string(num_points) + ")");
  return static_cast<std::size_t>(index);
}

/// copies the faces: an integer M x k array (k >= 3), or a sequence of index
/// sequences (polygons of any size >= 3). Every index must name a vertex.
inline std::vector<Polygon> faces_from(const py::handle& obj, std::size_t num_points)
{
  std::vector<Polygon> polygons;
  const bool array_like =
      py::isinstance<py::array>(obj) ||
      // a list of equal-length lists reads as a 2D array; ragged ones as polygons
      [&] {
        if (!py::isinstance<py::sequence>(obj) || py::isinstance<py::str>(obj)) return false;
        py::sequence s = py::reinterpret_borrow<py::sequence>(obj);
        if (s.size() == 0) return true;
        py::ssize_t k = -1;
        for (py::handle f : s) {
          if (!py::isinstance<py::sequence>(f) && !py::isinstance<py::array>(f)) return false;
          const py::ssize_t n = py::len(f);
          if (k >= 0 && n != k) return false;
          k = n;
        }
        return true;
      }();
  if (array_like) {
    py::array a = as_array(obj);
    const char kind = a.dtype().kind();
    if (a.ndim() == 1 && a.shape(0) == 0) return polygons;  // [] : no face
    if (kind != 'i' && kind != 'u')
      raise_value_error("faces must be an integer M x 3 array (or a list of index lists), got dtype " +
                        std::string(py::str(a.dtype())));
    if (a.ndim() != 2 || a.shape(1) < 3)
      raise_value_error("faces must have shape (M, 3) or (M, k) with k >= 3");
    auto d = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!d) throw py::error_already_set();
    auto f = d.unchecked<2>();
    const std::size_t m = static_cast<std::size_t>(f.shape(0)), k = static_cast<std::size_t>(f.shape(1));
    polygons.resize(m);
    for (std::size_t i = 0; i < m; ++i) {
      Polygon& poly = polygons[i];
      poly.resize(k);
      for (std::size_t j = 0; j < k; ++j)
        poly[j] = checked_index(f(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)), i,
                                num_points);
    }
    return polygons;
  }
  if (!py::isinstance<py::sequence>(obj))
    raise_value_error("faces must be an integer M x 3 array or a list of index lists");
  py::sequence s = py::reinterpret_borrow<py::sequence>(obj);
  polygons.resize(static_cast<std::size_t>(s.size()));
  std::size_t i = 0;
  for (py::handle f : s) {
    py::array a = as_array(f);
    const char kind = a.dtype().kind();
    if (a.ndim() != 1 || (kind != 'i' && kind != 'u'))
      raise_value_error("faces[" + std::to_string(i) + "] must be a list of vertex indices");
    if (a.shape(0) < 3)
      raise_value_error("faces[" + std::to_string(i) + "] has " + std::to_string(a.shape(0)) +
                        " vertices; a face needs at least 3");
    auto d = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
    auto v = d.unchecked<1>();
    for (py::ssize_t j = 0; j < v.shape(0); ++j)
      polygons[i].push_back(checked_index(v(j), i, num_points));
    ++i;
  }
  return polygons;
}

inline Soup soup_from(const py::handle& vertices, const py::handle& faces)
{
  Soup s;
  s.points = vertices_from(vertices);
  s.polygons = faces_from(faces, s.points.size());
  return s;
}

/// builds a triangle mesh from a soup that must already be a manifold,
/// consistently oriented polygon mesh; triangulates its polygons (section
/// "triangulation" of `report` when there were any). Raises ValueError otherwise.
inline void build_mesh(Soup& soup, Mesh& mesh, Report& report, const char* advice)
{
  std::string why;
  if (!is_polygon_soup_a_polygon_mesh(soup.polygons, soup.points.size(), &why))
    raise_value_error("not a manifold, consistently oriented polygon mesh (" + why + "); " + advice);
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(soup.points, soup.polygons, mesh);
  soup = Soup();
  const Triangulation_result t = without_gil([&] { return triangulate_polygons(mesh); });
  if (t.polygons > 0) t.to_report(report.section("triangulation"));
  if (t.status != Status::ok) raise_value_error(t.message);
}

// ---- arrays out ---------------------------------------------------------------------------

/// a new (N, 3) float64 array and a new (M, 3) int64 array (a list of index
/// lists when some face is not a triangle), numbered in the order of
/// `vertices(mesh)` and `faces(mesh)`; removed elements are skipped.
inline std::pair<py::object, py::object> arrays_of(const Mesh& mesh)
{
  std::vector<std::int64_t> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), -1);
  const py::ssize_t nv = static_cast<py::ssize_t>(mesh.number_of_vertices());
  py::array_t<double> V({nv, py::ssize_t(3)});
  double* out = V.mutable_data();
  std::int64_t next = 0;
  for (Mesh::Vertex_index v : mesh.vertices()) {
    index[v.idx()] = next++;
    const Point& p = mesh.point(v);
    *out++ = p.x();
    *out++ = p.y();
    *out++ = p.z();
  }
  bool triangles = true;
  for (Mesh::Face_index f : mesh.faces())
    if (mesh.degree(f) != 3) triangles = false;
  if (triangles) {
    py::array_t<std::int64_t> F({static_cast<py::ssize_t>(mesh.number_of_faces()), py::ssize_t(3)});
    std::int64_t* o = F.mutable_data();
    for (Mesh::Face_index f : mesh.faces())
      for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
        *o++ = index[v.idx()];
    return {std::move(V), std::move(F)};
  }
  py::list F;
  for (Mesh::Face_index f : mesh.faces()) {
    py::list poly;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      poly.append(index[v.idx()]);
    F.append(std::move(poly));
  }
  return {std::move(V), std::move(F)};
}

/// the same for a polygon soup.
inline std::pair<py::object, py::object> arrays_of(const std::vector<Point>& points,
                                                   const std::vector<Polygon>& polygons)
{
  py::array_t<double> V({static_cast<py::ssize_t>(points.size()), py::ssize_t(3)});
  double* out = V.mutable_data();
  for (const Point& p : points) {
    *out++ = p.x();
    *out++ = p.y();
    *out++ = p.z();
  }
  bool triangles = true;
  for (const Polygon& poly : polygons) triangles = triangles && poly.size() == 3;
  if (triangles) {
    py::array_t<std::int64_t> F({static_cast<py::ssize_t>(polygons.size()), py::ssize_t(3)});
    std::int64_t* o = F.mutable_data();
    for (const Polygon& poly : polygons)
      for (std::size_t i : poly) *o++ = static_cast<std::int64_t>(i);
    return {std::move(V), std::move(F)};
  }
  py::list F;
  for (const Polygon& poly : polygons) F.append(py::cast(poly));
  return {std::move(V), std::move(F)};
}

/// the report as the nested dict `json.loads` makes of the CLI's JSON.
inline py::object dict_of(const Report& report)
{
  return py::module_::import("json").attr("loads")(report.to_json());
}

/// (V, F, report) of a mesh.
inline py::tuple result_of(const Mesh& mesh, const Report& report)
{
  auto arrays = arrays_of(mesh);
  return py::make_tuple(arrays.first, arrays.second, dict_of(report));
}

/// registers the calls of mesh_calls.cpp: close_gaps, GapClosingSequence, clean, remesh.
void register_mesh_calls(py::module_& m);

} // namespace python
} // namespace mrepair

#endif // MREPAIR_PYTHON_BINDING_H
