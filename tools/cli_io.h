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

#include "cli.h"

#include <mrepair/internal/studio/payload.h>
#include <mrepair/io.h>
#include <mrepair/locate_defects.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/triangulate_polygons.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

// where the build puts the HTML report template (tools/CMakeLists.txt), and
// where `make install` puts it; both "" in a relocatable build (MREPAIR_RELOCATABLE,
// the pip package), which finds it beside the program only
#ifndef MREPAIR_STUDIO_BUILD_DIR
#define MREPAIR_STUDIO_BUILD_DIR ""
#endif
#ifndef MREPAIR_STUDIO_INSTALL_DIR
#define MREPAIR_STUDIO_INSTALL_DIR ""
#endif

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

/// whether to write `output` in binary: as `--binary` or `--ascii` say when
/// given, else keeping the encoding of the file read as `input`
/// (`keeps_encoding_binary`: binary in, binary out for the same format;
/// binary where the output's format has it across formats).
inline bool write_binary(const Arguments& a, const Io_result& input, const std::string& output)
{
  if (a.has("binary")) return true;
  if (a.has("ascii")) return false;
  return keeps_encoding_binary(input, output);
}

/// triangulates the faces with more than three sides (CAD exports carry quads
/// and n-gons; cleaning and remeshing need triangles) and adds section
/// "triangulation" to `report` when there were any. Fails with a one-line
/// `error` when CGAL cannot triangulate a face (the mesh stays valid).
/// Every caller passes a mesh this program built (the reader or the soup
/// stage), whose halfedge structure is valid by construction: a mesh of
/// triangles only is left to the algorithm's own input check instead of
/// having its structure checked here too (a parallel pass over 6M halfedges
/// at 1M faces).
template <class PolygonMesh>
bool triangulate_polygons(PolygonMesh& mesh, Report& report, std::string& error)
{
  if (CGAL::is_triangle_mesh(mesh)) return true;
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

// ---- the HTML report (doc/studio.md) ------------------------------------------------

/// <prefix>/share/mrepair/studio for this program at <prefix>/bin/mrepair: where
/// `cmake --install` and pip put the web assets beside it, wherever the prefix
/// (a venv, a moved install) now is. "" when /proc/self/exe cannot be read.
inline std::string studio_dir_beside_program()
{
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec || exe.empty()) return "";
  return (exe.parent_path().parent_path() / "share" / "mrepair" / "studio").string();
}

/// the HTML report template: $MREPAIR_STUDIO_ASSETS, the folder beside the
/// program, the build's studio folder, the configured install folder. "" and a
/// message saying how to get it when none has it.
inline std::string studio_template(std::string& error)
{
  std::string tried;
  const std::string path = internal::find_studio_template(
      {studio_dir_beside_program(), MREPAIR_STUDIO_BUILD_DIR, MREPAIR_STUDIO_INSTALL_DIR}, tried);
  if (path.empty())
    error = std::string("--html: no report template (") + internal::studio_template_name + ") in " +
            (tried.empty() ? "any folder" : tried) +
            "; build it with `cmake --build BUILD --target mrepair-studio-assets` (needs Node.js and npm, "
            "option MREPAIR_BUILD_STUDIO) or set MREPAIR_STUDIO_ASSETS to a folder that holds it";
  return path;
}

/// one mesh of the HTML report: its preview ("meshes") and its defect
/// overlay ("defects") as JSON, from `locations` found on it
struct Studio_view
{
  std::string mesh_json = "null", overlay_json = "null";
};

inline Studio_view studio_view(const internal::Indexed_faces& faces, const Defect_locations& locations,
                               std::size_t face_budget, std::size_t max_elements)
{
  Studio_view v;
  v.overlay_json = internal::overlay_json(internal::make_defect_overlay(faces, locations, max_elements));
  v.mesh_json = internal::preview_json(internal::make_preview(faces, face_budget));
  return v;
}

/// warns when a located count differs from the count of the report (they
/// come from the same code; a difference means different thresholds)
inline void check_located_counts(const Inspection_report& located, const Inspection_report& reported,
                                 const char* which)
{
  const std::size_t a[] = {located.boundary_loops, located.small_holes, located.non_manifold_edges,
                           located.non_manifold_vertices, located.spiked_vertices, located.near_degenerate_faces,
                           located.small_components, located.self_intersecting_pairs, located.t_junctions};
  const std::size_t b[] = {reported.boundary_loops, reported.small_holes, reported.non_manifold_edges,
                           reported.non_manifold_vertices, reported.spiked_vertices, reported.near_degenerate_faces,
                           reported.small_components, reported.self_intersecting_pairs, reported.t_junctions};
  for (std::size_t i = 0; i < 9; ++i)
    if (a[i] != b[i]) {
      std::cerr << "mrepair: warning: --html: the " << which << " defects drawn differ from the report's count of "
                << internal::overlay_kind_table()[i].key << " (" << a[i] << " vs " << b[i] << ")\n";
    }
}

/// writes the HTML report `out_path` from `template_path` (doc/studio.md):
/// the payload JSON in place of the placeholder line. "" or an error message.
inline std::string write_studio_report(const std::string& template_path, const std::string& out_path,
                                       const std::string& title, const Studio_view& before,
                                       const Studio_view& after, const Report& report, const Report& settings)
{
  std::string payload = "{\"version\": 1, \"title\": " + internal::json_string(title) +
                        ",\n\"meshes\": {\"before\": " + before.mesh_json + ",\n\"after\": " + after.mesh_json +
                        "},\n\"defects\": {\"before\": " + before.overlay_json + ",\n\"after\": " +
                        after.overlay_json + "},\n\"report\": " + report.to_json() +
                        ",\n\"settings\": " + settings.to_json() + "}";
  return internal::write_studio_html(template_path, out_path, internal::script_safe_json(payload));
}

} // namespace cli
} // namespace mrepair

#endif // MREPAIR_TOOLS_CLI_IO_H
