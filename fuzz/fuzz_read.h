// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Body of the file-reader fuzz target (fuzz_read.cpp), shared with the regression test.
//   byte 0: bits 0-1 format (off, obj, ply, stl); bit 2 also read into a
//           Polyhedron_3; bit 3 round trip written binary (PLY)
//   rest:   the file's bytes
#ifndef MREPAIR_FUZZ_READ_H
#define MREPAIR_FUZZ_READ_H

#include "fuzz_check.h"

#include <mrepair/io.h>

#include <fstream>
#include <string>
#include <vector>

namespace mrepair_fuzz {

inline bool outputs_cleared(mrepair::Status s)
{
  using mrepair::Status;
  return s == Status::io_error || s == Status::parse_error || s == Status::empty_input ||
         s == Status::unsupported_format;
}

/// checks what read_polygon_soup returned against its documentation.
inline std::string check_read_soup(const mrepair::Io_result& r, const std::vector<Point>& pts,
                                   const std::vector<Polygon>& polys)
{
  using mrepair::Status;
  const std::string st = mrepair::to_string(r.status);
  if (outputs_cleared(r.status)) {
    if (!pts.empty() || !polys.empty()) return "read_polygon_soup: " + st + " but outputs not empty";
    if (r.message.empty()) return "read_polygon_soup: " + st + " without a message";
    return {};
  }
  if (r.status != Status::ok && r.status != Status::non_finite_input && r.status != Status::invalid_index)
    return "read_polygon_soup: unexpected status " + st;
  if (r.points != pts.size() || r.polygons != polys.size())
    return "read_polygon_soup: counts differ from the outputs";
  if (pts.empty() || polys.empty()) return "read_polygon_soup: " + st + " with an empty soup";
  std::size_t non_finite = 0, invalid = 0;
  for (const Point& p : pts) non_finite += !finite(p);
  for (const Polygon& poly : polys) {
    bool bad = poly.size() < 3;
    for (std::size_t i : poly) bad = bad || i >= pts.size();
    invalid += bad;
  }
  if (non_finite != r.non_finite_points) return "read_polygon_soup: non_finite_points miscounted";
  if (invalid != r.invalid_polygons) return "read_polygon_soup: invalid_polygons miscounted";
  const Status expected = invalid ? Status::invalid_index
                          : non_finite ? Status::non_finite_input : Status::ok;
  if (r.status != expected) return "read_polygon_soup: status " + st + " disagrees with the data";
  return {};
}

template <class Mesh>
std::string check_read_mesh(const std::string& path, const mrepair::Io_result& soup_r,
                            const std::vector<Polygon>& polys)
{
  using mrepair::Status;
  Mesh m;
  const mrepair::Io_result r = mrepair::read_polygon_mesh(path, m);
  const std::string st = mrepair::to_string(r.status);
  if (std::string e = check_mesh(m, "read_polygon_mesh", false); !e.empty()) return e;
  if (r.status == Status::ok) {
    if (soup_r.status != Status::ok) return "read_polygon_mesh: ok where read_polygon_soup was not";
    if (faces(m).size() != polys.size()) return "read_polygon_mesh: face count differs from the soup";
    return {};
  }
  if (!faces(m).empty() || !vertices(m).empty()) return "read_polygon_mesh: " + st + " but mesh not empty";
  if (r.status == Status::non_manifold_input && soup_r.status != Status::ok)
    return "read_polygon_mesh: non_manifold_input for a soup that read as " +
           std::string(mrepair::to_string(soup_r.status));
  if (r.status != Status::non_manifold_input && r.status != soup_r.status)
    return "read_polygon_mesh: status " + st + " differs from read_polygon_soup's";
  return {};
}

/// writes the soup and reads it back: the same points and polygons (OFF, OBJ, PLY).
inline std::string check_round_trip(const std::string& path, bool binary,
                                    const std::vector<Point>& pts, const std::vector<Polygon>& polys)
{
  const mrepair::Io_result w = mrepair::write_polygon_soup(path, pts, polys, binary);
  if (w.status != mrepair::Status::ok) return "write_polygon_soup: " + std::string(mrepair::to_string(w.status)) + ": " + w.message;
  std::vector<Point> p2;
  std::vector<Polygon> q2;
  const mrepair::Io_result r = mrepair::read_polygon_soup(path, p2, q2);
  if (r.status != mrepair::Status::ok) return "round trip: read back as " + std::string(mrepair::to_string(r.status)) + ": " + r.message;
  if (p2 != pts) return "round trip: points differ";
  if (q2 != polys) return "round trip: polygons differ";
  return {};
}

/// `dir` is a writable directory for the two temporary files.
inline std::string run_read(const std::uint8_t* data, std::size_t size, const std::string& dir)
{
  if (size == 0) return {};
  static const char* const ext[4] = {"off", "obj", "ply", "stl"};
  const std::uint8_t sel = data[0];
  const std::string format = ext[sel & 3];
  const std::string path = dir + "/fuzz_input." + format;
  {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  const mrepair::Io_result r = mrepair::read_polygon_soup(path, pts, polys);
  if (std::string e = check_read_soup(r, pts, polys); !e.empty()) return e;
  if (std::string e = check_read_mesh<Surface_mesh>(path, r, polys); !e.empty()) return e;
  if (sel & 4)
    if (std::string e = check_read_mesh<Polyhedron>(path, r, polys); !e.empty()) return e + " (Polyhedron_3)";
  // STL writes triangles and merges corners on reading: no exact round trip
  if (r.status == mrepair::Status::ok && format != "stl")
    return check_round_trip(dir + "/fuzz_round_trip." + format, (sel & 8) != 0, pts, polys);
  return {};
}

} // namespace mrepair_fuzz

#endif // MREPAIR_FUZZ_READ_H
