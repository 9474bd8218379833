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
/// Speed (issue 17): files are mapped, not copied; binary PLY records are
/// decoded in bulk (float/double x, y, z without a per-value type switch; face
/// lists in two passes, the second in parallel); the bodies of ASCII OFF, PLY
/// and OBJ files are parsed in parallel chunks of lines with `std::from_chars`
/// when each record is on one line (OBJ: when no line is continued), else
/// line by line as before, with the same results and messages; writers format
/// pieces in parallel with `std::to_chars` and write them in order. With TBB
/// (`CGAL_LINKED_WITH_TBB`) the parallel steps use the current task arena.
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

#include <mrepair/internal/io/convert.h>
#include <mrepair/internal/io/dispatch.h>
#include <mrepair/io_result.h>
#include <mrepair/report.h>
#include <mrepair/status.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <string>
#include <vector>

namespace mrepair {

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
  internal::io::raw_to_soup(path, raw, points, polygons, r);
  return r;
}

/// \ingroup mrepair_io
/// reads a file as `read_polygon_soup` does, into `triangles` when every
/// polygon of the file is a triangle (`polygons` left empty), else into
/// `polygons` (`triangles` left empty). A triangle as a fixed array is no heap
/// block of its own: on a 10M-face scan, 10 million allocations and 320 MB
/// less than `std::vector` polygons, for the reader and for every pass over the soup.
/// \tparam Triangle e.g. `std::array<std::size_t, 3>`
/// \param all_triangles set to which of the two was filled
template <class Point, class Polygon, class Triangle>
Io_result read_polygon_or_triangle_soup(const std::string& path, std::vector<Point>& points,
                                        std::vector<Polygon>& polygons,
                                        std::vector<Triangle>& triangles, bool& all_triangles)
{
  points.clear();
  polygons.clear();
  triangles.clear();
  all_triangles = false;
  Io_result r;
  internal::io::Raw_soup raw;
  internal::io::read_raw(path, raw, r);
  if (r.points == 0) return r;
  all_triangles = internal::io::all_polygons_have(raw, 3);
  if (all_triangles)
    internal::io::raw_to_soup(path, raw, points, triangles, r);
  else
    internal::io::raw_to_soup(path, raw, points, polygons, r);
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
  internal::io::write_view(path, internal::io::Vectors_view<Point, Polygon>{points, polygons},
                           binary, r);
  return r;
}

/// \ingroup mrepair_io
/// the encoding that keeps the file's own when a mesh read as `input` (the
/// result of a reader: its `format` and `binary`) is written to `output_path`:
/// the input's encoding when the output has the input's format, else binary
/// where the output's format has a binary variant (PLY, STL). The `binary`
/// argument of `write_polygon_mesh` and `write_polygon_soup`.
inline bool keeps_encoding_binary(const Io_result& input, const std::string& output_path)
{
  const std::string format = internal::io::extension(output_path);
  if (!input.format.empty() && format == input.format) return input.binary;
  return internal::io::has_binary_variant(internal::io::file_format(format));
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
  std::string reason;
  const bool ok = internal::io::is_soup_a_mesh(polygons, num_points, reason);
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
  internal::io::raw_to_mesh(path, raw, pmesh, vpm, r);
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
  if constexpr (internal::Is_surface_mesh<PolygonMesh>::value) {
    // written in place, removed elements skipped (a user-given vertex index
    // map is read through the copy alone)
    if (CGAL::parameters::is_default_parameter<NamedParameters, CGAL::internal_np::vertex_index_t>::value) {
      using View = internal::io::Surface_mesh_view<typename PolygonMesh::Point, VPM>;
      internal::io::fill_or_report_oom(path, r, [&] {
        internal::io::write_view(path, View::with_gaps(pmesh, vpm), binary, r);
      });
      return r;
    }
  }
  internal::io::Raw_soup raw;
  if (internal::io::mesh_to_raw(path, pmesh, vpm, np, raw, r))
    internal::io::write_raw(path, raw, binary, r);
  return r;
}

} // namespace mrepair

#endif // MREPAIR_IO_H
