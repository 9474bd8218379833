// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_IO_H
#define MREPAIR_IO_H

/// \file io.h
/// Reading and writing polygon soups and polygon meshes in OFF, OBJ, PLY and
/// STL, chosen by the file extension (case-insensitive).
///
/// | format | read                                   | write                          |
/// |--------|----------------------------------------|--------------------------------|
/// | OFF    | ASCII; `[ST][C][N][4][n]OFF` variants   | ASCII                          |
/// | OBJ    | `v`, `f` (`i`, `i/t`, `i//n`, `i/t/n`, negative = relative) | ASCII |
/// | PLY    | ascii, binary little and big endian     | ascii, binary_little_endian (doubles) |
/// | STL    | ASCII and binary; identical corners merged | ASCII, binary (float32; polygons fan-triangulated) |
///
/// Text is written with the shortest decimal that reads back to the same
/// double, so ASCII OFF/OBJ/PLY and binary PLY round-trip coordinates exactly.
///
/// What a reader keeps when the data is bad (status `non_finite_input` or
/// `invalid_index`, data loaded so that a repair can fix it):
/// - points with NaN or infinite coordinates are kept as read, and counted in
///   `non_finite_points`;
/// - polygons with fewer than 3 vertices or with an index outside
///   [0, points.size()) are kept as read, and counted in `invalid_polygons`.
///   Such an index is stored converted to the polygon's index type: negative
///   indices (OFF/PLY negative numbers, OBJ index 0 or relative indices before
///   the first vertex) wrap to huge values in an unsigned type, so that every
///   invalid index `i` of a `std::size_t` polygon satisfies `i >= points.size()`.
/// When both occur, the status is `invalid_index`.
/// PLY faces with fewer than 3 vertices (list count 0, 1 or 2) are left out
/// of the soup instead, counted in `polygons_skipped` and named in the message;
/// they alone do not change the status.
/// Files that cannot be read (`io_error`), are malformed or truncated
/// (`parse_error`), hold no point or no polygon (`empty_input`; points without
/// faces are named a point cloud) or are of an unknown kind
/// (`unsupported_format`) leave the outputs empty. The message is one line
/// `path[:line]: reason`.

#include <mrepair/internal/io/build_mesh.h>
#include <mrepair/internal/io/common.h>
#include <mrepair/internal/io/read_obj.h>
#include <mrepair/internal/io/read_off.h>
#include <mrepair/internal/io/read_ply.h>
#include <mrepair/internal/io/read_stl.h>
#include <mrepair/internal/io/write.h>
#include <mrepair/report.h>
#include <mrepair/status.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>

#include <new>
#include <string>
#include <type_traits>
#include <vector>

namespace mrepair {

/// \ingroup mrepair_io
/// outcome of reading or writing a file.
struct Io_result
{
  Status status = Status::ok;   ///< see the file comment for what each status keeps
  std::string message;          ///< one line `path[:line]: reason`; empty when all is well
  std::string format;           ///< "off", "obj", "ply" or "stl" (empty when unknown)
  bool binary = false;          ///< the file is (was written) binary
  std::size_t points = 0;       ///< points read (written)
  std::size_t polygons = 0;     ///< polygons read (written; for STL: triangles written)
  std::size_t non_finite_points = 0;  ///< points with a NaN or infinite coordinate
  std::size_t invalid_polygons = 0;   ///< polygons with < 3 vertices or an out-of-range index
  std::size_t polygons_skipped = 0;   ///< PLY faces with < 3 vertices, left out of the soup

  void to_report(Report& r) const
  {
    r.add("status", status);
    if (!message.empty()) r.add("message", message);
    r.add("format", format);
    r.add("binary", binary);
    r.add("points", points);
    r.add("polygons", polygons);
    r.add("non_finite_points", non_finite_points);
    r.add("invalid_polygons", invalid_polygons);
    r.add("polygons_skipped", polygons_skipped);
  }
};

namespace internal {
namespace io {

/// reads any supported file into `raw` and checks it; on io/parse/empty/format
/// failures `raw` is cleared and `r` tells why.
inline void read_raw(const std::string& path, Raw_soup& raw, Io_result& r)
{
  r = Io_result();
  Error err;
  const std::string ext = extension(path);
  r.format = ext;
  bool ok = false;
  Ply_skipped_faces skipped;
  try {
    if (ext != "off" && ext != "obj" && ext != "ply" && ext != "stl") {
      r.format.clear();
      err.set(Status::unsupported_format,
              path + ": unsupported file extension '" + ext + "' (use .off, .obj, .ply or .stl)");
    } else {
      File_buffer buf;
      if (read_file(path, buf, err)) {
        bool binary = false;
        if (ext == "off")
          ok = read_off(buf, path, raw, err, binary);
        else if (ext == "obj")
          ok = read_obj(buf, path, raw, err);
        else if (ext == "ply")
          ok = read_ply(buf, path, raw, err, binary, &skipped);
        else
          ok = read_stl(buf, path, raw, err, binary);
        r.binary = binary;
      }
    }
  } catch (const std::bad_alloc&) {
    ok = false;
    err.set(Status::io_error, path + ": out of memory");
  }
  // "N face(s) with fewer than 3 vertices skipped (first is face K)"
  const std::string skipped_note =
      skipped.count == 0 ? std::string()
                         : std::to_string(skipped.count) +
                               " face(s) with fewer than 3 vertices skipped (first is face " +
                               std::to_string(skipped.first) + ")";
  if (ok && raw.num_points() > 0 && raw.num_polygons() == 0) {
    ok = false;
    err.set(Status::empty_input,
            path + ": no faces (a point cloud of " + std::to_string(raw.num_points()) +
                (raw.num_points() == 1 ? " vertex" : " vertices") +
                (skipped.count ? "; " + skipped_note : std::string()) +
                "); mrepair repairs surface meshes");
  } else if (ok && (raw.num_points() == 0 || raw.num_polygons() == 0)) {
    ok = false;
    err.set(Status::empty_input, path + ": " + std::to_string(raw.num_points()) + " points and " +
                                     std::to_string(raw.num_polygons()) + " polygons, nothing to work on");
  }
  if (!ok) {
    raw = Raw_soup();
    r.status = err.status == Status::ok ? Status::parse_error : err.status;
    r.message = err.message;
    return;
  }

  r.points = raw.num_points();
  r.polygons = raw.num_polygons();
  std::size_t first_bad_point = 0;
  for (std::size_t i = raw.num_points(); i-- > 0;) {
    const double* q = &raw.xyz[3 * i];
    if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]))) {
      ++r.non_finite_points;
      first_bad_point = i;
    }
  }
  const std::int64_t np = static_cast<std::int64_t>(raw.num_points());
  std::size_t first_bad_polygon = 0;
  std::string why;
  for (std::size_t f = raw.num_polygons(); f-- > 0;) {
    std::size_t b = raw.starts[f], e = raw.starts[f + 1];
    bool bad = e - b < 3;
    std::string reason = bad ? "polygon with " + std::to_string(e - b) + " vertices" : std::string();
    if (!bad)
      for (std::size_t k = b; k < e; ++k)
        if (raw.indices[k] < 0 || raw.indices[k] >= np) {
          bad = true;
          reason = "vertex index " + std::to_string(raw.indices[k]) + " out of range [0, " +
                   std::to_string(np) + ")";
          break;
        }
    if (bad) {
      ++r.invalid_polygons;
      first_bad_polygon = f;
      why = std::move(reason);
    }
  }
  if (r.invalid_polygons) {
    r.status = Status::invalid_index;
    std::string where = raw.has_lines && first_bad_polygon < raw.polygon_line.size()
                            ? ":" + std::to_string(raw.polygon_line[first_bad_polygon])
                            : std::string();
    r.message = path + where + ": " + std::to_string(r.invalid_polygons) +
                " invalid polygon(s), first is polygon " + std::to_string(first_bad_polygon) +
                ": " + why;
    if (r.non_finite_points)
      r.message += "; also " + std::to_string(r.non_finite_points) + " non-finite point(s)";
  } else if (r.non_finite_points) {
    r.status = Status::non_finite_input;
    std::string where = raw.first_non_finite_line ? ":" + std::to_string(raw.first_non_finite_line)
                                                  : std::string();
    r.message = path + where + ": " + std::to_string(r.non_finite_points) +
                " point(s) with NaN or infinite coordinates, first is point " +
                std::to_string(first_bad_point);
  }
  r.polygons_skipped = skipped.count;
  if (skipped.count) {
    if (r.message.empty())
      r.message = path +
                  (skipped.first_line ? ":" + std::to_string(skipped.first_line) : std::string()) +
                  ": " + skipped_note;
    else
      r.message += "; " + skipped_note;
  }
}

/// writes `raw` to `path` in the format of its extension.
inline void write_raw(const std::string& path, const Raw_soup& raw, bool binary, Io_result& r)
{
  r = Io_result();
  const std::string ext = extension(path);
  r.format = ext;
  r.points = raw.num_points();
  r.polygons = raw.num_polygons();
  if (ext != "off" && ext != "obj" && ext != "ply" && ext != "stl") {
    r.format.clear();
    r.status = Status::unsupported_format;
    r.message = path + ": unsupported file extension '" + ext + "' (use .off, .obj, .ply or .stl)";
    return;
  }
  // refuse what the file could not represent faithfully
  const std::int64_t np = static_cast<std::int64_t>(raw.num_points());
  std::size_t first_bad = 0;
  for (std::size_t f = raw.num_polygons(); f-- > 0;) {
    std::size_t b = raw.starts[f], e = raw.starts[f + 1];
    bool bad = ext == "stl" && e - b < 3;
    for (std::size_t k = b; k < e && !bad; ++k) bad = raw.indices[k] < 0 || raw.indices[k] >= np;
    if (bad) {
      ++r.invalid_polygons;
      first_bad = f;
    }
  }
  for (std::size_t i = 0; i < raw.num_points(); ++i) {
    const double* q = &raw.xyz[3 * i];
    if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]))) ++r.non_finite_points;
  }
  if (r.invalid_polygons) {
    r.status = Status::invalid_index;
    r.message = path + ": not written: " + std::to_string(r.invalid_polygons) +
                " polygon(s) with an out-of-range index" +
                (ext == "stl" ? std::string(" or fewer than 3 vertices") : std::string()) +
                ", first is polygon " + std::to_string(first_bad);
    return;
  }
  if (ext == "stl" && fan_triangle_count(raw) > (std::numeric_limits<std::uint32_t>::max)() &&
      binary) {
    r.status = Status::unsupported_format;
    r.message = path + ": not written: too many triangles for binary STL";
    return;
  }
  r.binary = binary && (ext == "ply" || ext == "stl");
  if (binary && !r.binary)
    r.message = path + ": " + ext + " has no binary variant; wrote ASCII";
  Out_file out(path);
  if (!out.is_open()) {
    r.status = Status::io_error;
    r.message = path + ": cannot open for writing (" + std::strerror(errno) + ")";
    return;
  }
  try {
    if (ext == "off")
      write_off(out, raw);
    else if (ext == "obj")
      write_obj(out, raw);
    else if (ext == "ply")
      write_ply(out, raw, r.binary);
    else {
      write_stl(out, raw, r.binary);
      r.polygons = fan_triangle_count(raw);
    }
  } catch (const std::bad_alloc&) {
    out.close();
    r.status = Status::io_error;
    r.message = path + ": out of memory while writing";
    return;
  }
  if (!out.close()) {
    r.status = Status::io_error;
    r.message = path + ": write error (disk full?)";
  }
}

template <typename Point>
double coordinate(const Point& p, int d)
{
  return CGAL::to_double(d == 0 ? p.x() : (d == 1 ? p.y() : p.z()));
}

} // namespace io
} // namespace internal

/// \ingroup mrepair_io
/// reads the polygon soup of an OFF, OBJ, PLY or STL file (by extension).
/// \tparam Point constructible from three `double`s (e.g. `CGAL::Epick::Point_3`)
/// \tparam Polygon a resizable random-access container of integers, e.g. `std::vector<std::size_t>`
/// \param path the file
/// \param points, polygons outputs, replaced (not appended to)
/// \return `Io_result`: `ok`; `non_finite_input` or `invalid_index` with the data
///   loaded (see the file comment); or `io_error`, `parse_error`, `empty_input`,
///   `unsupported_format` with both outputs empty.
template <class Point, class Polygon>
Io_result read_polygon_soup(const std::string& path, std::vector<Point>& points,
                            std::vector<Polygon>& polygons)
{
  points.clear();
  polygons.clear();
  Io_result r;
  internal::io::Raw_soup raw;
  internal::io::read_raw(path, raw, r);
  if (r.points == 0) return r;
  try {
    using Index = typename Polygon::value_type;
    points.reserve(raw.num_points());
    for (std::size_t i = 0; i < raw.num_points(); ++i)
      points.emplace_back(raw.xyz[3 * i], raw.xyz[3 * i + 1], raw.xyz[3 * i + 2]);
    raw.xyz = std::vector<double>();
    polygons.resize(raw.num_polygons());
    for (std::size_t f = 0; f < raw.num_polygons(); ++f) {
      Polygon& poly = polygons[f];
      const std::size_t b = raw.starts[f], n = raw.starts[f + 1] - b;
      poly.resize(n);
      for (std::size_t k = 0; k < n; ++k) poly[k] = static_cast<Index>(raw.indices[b + k]);
    }
  } catch (const std::bad_alloc&) {
    points.clear();
    polygons.clear();
    r = Io_result();
    r.status = Status::io_error;
    r.message = path + ": out of memory";
  }
  return r;
}

/// \ingroup mrepair_io
/// writes a polygon soup to an OFF, OBJ, PLY or STL file (by extension).
/// \param binary binary PLY (little endian, double coordinates) or binary STL
///   (float32); ignored for OFF and OBJ, which are written as ASCII (the
///   message says so)
/// \return `Io_result`: `ok`; `invalid_index` (nothing written) when a polygon
///   refers to a point out of range, or for STL has fewer than 3 vertices;
///   `unsupported_format`; `io_error`. Non-finite points are written as
///   `nan`/`inf` and counted.
template <class Point, class Polygon>
Io_result write_polygon_soup(const std::string& path, const std::vector<Point>& points,
                             const std::vector<Polygon>& polygons, bool binary = false)
{
  Io_result r;
  internal::io::Raw_soup raw;
  try {
    raw.xyz.reserve(3 * points.size());
    for (const Point& p : points)
      for (int d = 0; d < 3; ++d) raw.xyz.push_back(internal::io::coordinate(p, d));
    std::size_t corners = 0;
    for (const Polygon& poly : polygons) corners += poly.size();
    raw.indices.reserve(corners);
    raw.starts.reserve(polygons.size() + 1);
    for (const Polygon& poly : polygons) {
      for (const auto& i : poly) {
        // negative values of a signed index type and huge unsigned ones are out of range
        std::int64_t v = static_cast<std::int64_t>(i);
        if (std::is_unsigned<std::decay_t<decltype(i)>>::value &&
            static_cast<std::uint64_t>(i) > static_cast<std::uint64_t>((std::numeric_limits<std::int64_t>::max)()))
          v = -1;
        raw.indices.push_back(v);
      }
      raw.starts.push_back(raw.indices.size());
    }
  } catch (const std::bad_alloc&) {
    r.status = Status::io_error;
    r.message = path + ": out of memory";
    return r;
  }
  internal::io::write_raw(path, raw, binary, r);
  return r;
}

/// \ingroup mrepair_io
/// returns `true` when `polygons` (indices into `num_points` points) form a
/// manifold, consistently oriented polygon mesh: the test of
/// `CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh`, done in
/// linear time on flat arrays (CGAL 5.5's takes seconds on a million faces).
/// Out-of-range indices make it `false`. `why`, when given, receives the reason.
/// \tparam PolygonRange range of random-access ranges of integer indices
template <class PolygonRange>
bool is_polygon_soup_a_polygon_mesh(const PolygonRange& polygons, std::size_t num_points,
                                    std::string* why = nullptr)
{
  std::vector<std::int64_t> indices;
  std::vector<std::size_t> starts{0};
  starts.reserve(polygons.size() + 1);
  for (const auto& poly : polygons) {
    for (const auto& i : poly) {
      // a negative signed index or one that does not fit stays out of range
      const std::int64_t v = static_cast<std::int64_t>(i);
      indices.push_back(v < 0 || static_cast<std::uint64_t>(i) >= num_points ? -1 : v);
    }
    starts.push_back(indices.size());
  }
  internal::io::Soup_topology topology;
  std::string reason;
  const bool ok = topology.compute(num_points, indices.data(), starts.data(), polygons.size(),
                                   reason);
  if (why) *why = reason;
  return ok;
}

/// \ingroup mrepair_io
/// reads a file (as `read_polygon_soup`) and builds `pmesh` from it when the
/// soup is a valid polygon mesh (the test of
/// `CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh`, done on flat
/// arrays, and a direct halfedge builder: much faster than the PMP pair).
/// Faces keep the file's order, vertices the file's order of points. Points
/// used by no polygon are not added (isolated vertices fail
/// `CGAL::is_valid_polygon_mesh`); the status stays `ok` and the message counts them.
/// `pmesh` is cleared first and stays empty on any failure.
/// \tparam PolygonMesh model of `MutableFaceGraph`
/// \param np optional: `vertex_point_map` (default `get(CGAL::vertex_point, pmesh)`)
/// \return `Io_result`; besides the soup statuses, `non_finite_input` and
///   `invalid_index` (mesh not built) and `non_manifold_input` when the soup
///   is not a manifold, consistently oriented polygon mesh (run `mrepair soup`).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Io_result read_polygon_mesh(const std::string& path, PolygonMesh& pmesh,
                            const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using VPM = typename CGAL::GetVertexPointMap<PolygonMesh, NamedParameters>::type;
  using Point = typename boost::property_traits<VPM>::value_type;
  VPM vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                             get_property_map(CGAL::vertex_point, pmesh));
  CGAL::clear(pmesh);
  Io_result r;
  internal::io::Raw_soup raw;
  internal::io::read_raw(path, raw, r);
  if (r.status == Status::non_finite_input || r.status == Status::invalid_index) {
    r.message += " (mesh not built; run `mrepair soup` to repair)";
    return r;
  }
  if (r.status != Status::ok) return r;
  try {
    // the same test as PMP::is_polygon_soup_a_polygon_mesh, on flat arrays
    internal::io::Soup_topology topology;
    std::string why;
    if (!topology.compute(raw.num_points(), raw.indices.data(), raw.starts.data(),
                          raw.num_polygons(), why)) {
      r.status = Status::non_manifold_input;
      r.message = path + ": not a manifold, consistently oriented polygon mesh (" + why +
                  "); run `mrepair soup` first";
      return r;
    }
    internal::io::build_mesh(topology, raw.num_points(), raw.indices.data(), raw.starts.data(),
                             raw.num_polygons(), pmesh, [&](auto v, std::size_t i) {
                               const double* q = &raw.xyz[3 * i];
                               put(vpm, v, Point(q[0], q[1], q[2]));
                             });
    const std::size_t isolated = r.points - static_cast<std::size_t>(vertices(pmesh).size());
    if (isolated)
      r.message += (r.message.empty() ? path + ": " : std::string("; ")) +
                   std::to_string(isolated) +
                   " point(s) used by no polygon were not added to the mesh";
  } catch (const std::bad_alloc&) {
    CGAL::clear(pmesh);
    r.status = Status::io_error;
    r.message = path + ": out of memory building the mesh";
  }
  return r;
}

/// \ingroup mrepair_io
/// writes `pmesh` to an OFF, OBJ, PLY or STL file (by extension); vertices are
/// numbered in the order of `vertices(pmesh)`, faces in the order of `faces(pmesh)`.
/// \tparam PolygonMesh model of `FaceListGraph` (`Surface_mesh`, `Polyhedron_3`, ...)
/// \param binary as for `write_polygon_soup`
/// \param np optional: `vertex_point_map` (default `get(CGAL::vertex_point, pmesh)`),
///   `vertex_index_map` (default: an initialized index map of `pmesh`)
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Io_result write_polygon_mesh(const std::string& path, const PolygonMesh& pmesh, bool binary = false,
                             const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using VPM = typename CGAL::GetVertexPointMap<PolygonMesh, NamedParameters>::const_type;
  VPM vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                             get_const_property_map(CGAL::vertex_point, pmesh));
  Io_result r;
  internal::io::Raw_soup raw;
  try {
    // the mesh's own indices may have gaps (Surface_mesh with removed
    // elements): renumber them consecutively in the order of vertices(pmesh)
    auto vim = CGAL::get_initialized_vertex_index_map(pmesh, np);
    std::size_t max_id = 0, nv = 0;
    for (auto v : vertices(pmesh)) {
      max_id = (std::max)(max_id, static_cast<std::size_t>(get(vim, v)));
      ++nv;
    }
    std::vector<std::int64_t> renum(nv ? max_id + 1 : 0, -1);
    raw.xyz.reserve(3 * nv);
    std::int64_t next = 0;
    for (auto v : vertices(pmesh)) {
      renum[static_cast<std::size_t>(get(vim, v))] = next++;
      const auto& p = get(vpm, v);
      for (int d = 0; d < 3; ++d) raw.xyz.push_back(internal::io::coordinate(p, d));
    }
    raw.starts.reserve(faces(pmesh).size() + 1);
    raw.indices.reserve(3 * faces(pmesh).size());
    for (auto f : faces(pmesh)) {
      for (auto v : CGAL::vertices_around_face(halfedge(f, pmesh), pmesh))
        raw.indices.push_back(renum[static_cast<std::size_t>(get(vim, v))]);
      raw.starts.push_back(raw.indices.size());
    }
  } catch (const std::bad_alloc&) {
    r.status = Status::io_error;
    r.message = path + ": out of memory";
    return r;
  }
  internal::io::write_raw(path, raw, binary, r);
  return r;
}

} // namespace mrepair

#endif // MREPAIR_IO_H
