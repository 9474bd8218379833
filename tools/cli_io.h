// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// File helpers shared by the `mrepair` commands: load and save a mesh or a
// soup, time it, record the Io_result in a "read" / "write" report section,
// and turn failures into one-line errors. Header-only, like cli.h.
//
//   mrepair::Report report;
//   std::string error;
//   Mesh mesh;
//   if (!cli::load_mesh(input, mesh, report, error)) return cli::fail(error);
//   ...
//   if (!cli::save_mesh(output, mesh, args.has("binary"), report, error)) return cli::fail(error);
#ifndef MREPAIR_TOOLS_CLI_IO_H
#define MREPAIR_TOOLS_CLI_IO_H

#include <mrepair/io.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/triangulate_polygons.h>

#include <chrono>
#include <string>
#include <vector>

namespace mrepair {
namespace cli {

namespace internal_io {
inline double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
inline void record(const Io_result& r, double seconds, const std::string& path, Report& section)
{
  section.add("path", path);
  r.to_report(section);
  section.add("seconds", seconds);
}
inline std::string one_line(const Io_result& r, const std::string& path)
{
  return r.message.empty() ? path + ": " + to_string(r.status) : r.message;
}
} // namespace internal_io

/// reads `path` into a polygon soup; adds section `section_name` ("read") to
/// `report`. With `accept_defects` (default), non-finite points and invalid
/// polygons are loaded and accepted (status in the report) so that a repair
/// command can fix them; otherwise they fail. On failure returns false with a
/// one-line `error`.
template <class Point, class Polygon>
bool load_soup(const std::string& path, std::vector<Point>& points, std::vector<Polygon>& polygons,
               Report& report, std::string& error, bool accept_defects = true,
               const std::string& section_name = "read")
{
  auto t0 = std::chrono::steady_clock::now();
  Io_result r = read_polygon_soup(path, points, polygons);
  internal_io::record(r, internal_io::seconds_since(t0), path, report.section(section_name));
  const bool defect = r.status == Status::non_finite_input || r.status == Status::invalid_index;
  if (r.status == Status::ok || (defect && accept_defects)) return true;
  error = internal_io::one_line(r, path);
  return false;
}

/// reads `path` into `mesh` (any MutableFaceGraph); adds section
/// `section_name` ("read") to `report`. Fails with a one-line `error` unless the
/// file holds a valid polygon mesh (non-manifold or defective soups: the
/// message says to run `mrepair soup` first).
template <class PolygonMesh>
bool load_mesh(const std::string& path, PolygonMesh& mesh, Report& report, std::string& error,
               const std::string& section_name = "read")
{
  auto t0 = std::chrono::steady_clock::now();
  Io_result r = read_polygon_mesh(path, mesh);
  Report& s = report.section(section_name);
  internal_io::record(r, internal_io::seconds_since(t0), path, s);
  if (r.status == Status::ok) {
    s.add("vertices", static_cast<std::size_t>(vertices(mesh).size()));
    s.add("faces", static_cast<std::size_t>(faces(mesh).size()));
    return true;
  }
  error = internal_io::one_line(r, path);
  return false;
}

/// writes `mesh` to `path` (format by extension; `binary` for PLY/STL); adds
/// section `section_name` ("write") to `report`. Fails with a one-line `error`.
template <class PolygonMesh>
bool save_mesh(const std::string& path, const PolygonMesh& mesh, bool binary, Report& report,
               std::string& error, const std::string& section_name = "write")
{
  auto t0 = std::chrono::steady_clock::now();
  Io_result r = write_polygon_mesh(path, mesh, binary);
  internal_io::record(r, internal_io::seconds_since(t0), path, report.section(section_name));
  if (r.status == Status::ok) return true;
  error = internal_io::one_line(r, path);
  return false;
}

/// triangulates the faces with more than three sides (CAD exports carry quads
/// and n-gons; cleaning and remeshing need triangles) and adds section
/// "triangulation" to `report` when there were any. Fails with a one-line
/// `error` when CGAL cannot triangulate a face (the mesh stays valid).
template <class PolygonMesh>
bool triangulate_polygons(PolygonMesh& mesh, Report& report, std::string& error)
{
  const Triangulation_result t = mrepair::triangulate_polygons(mesh);
  if (t.polygons > 0) t.to_report(report.section("triangulation"));
  if (t.status == Status::ok) return true;
  error = t.message;
  return false;
}

/// writes a polygon soup like `save_mesh`.
template <class Point, class Polygon>
bool save_soup(const std::string& path, const std::vector<Point>& points,
               const std::vector<Polygon>& polygons, bool binary, Report& report,
               std::string& error, const std::string& section_name = "write")
{
  auto t0 = std::chrono::steady_clock::now();
  Io_result r = write_polygon_soup(path, points, polygons, binary);
  internal_io::record(r, internal_io::seconds_since(t0), path, report.section(section_name));
  if (r.status == Status::ok) return true;
  error = internal_io::one_line(r, path);
  return false;
}

} // namespace cli
} // namespace mrepair

#endif // MREPAIR_TOOLS_CLI_IO_H
