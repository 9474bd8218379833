// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_IO_RESULT_H
#define MREPAIR_IO_RESULT_H

/// \file io_result.h
/// The outcome of reading or writing a file (see `io.h` for what each status
/// keeps).

#include <mrepair/report.h>
#include <mrepair/status.h>

#include <cstddef>
#include <string>

namespace mrepair {

/// \ingroup mrepair_io
/// outcome of reading or writing a file.
struct Io_result
{
  Status status = Status::ok;   ///< see the file comment of io.h for what each status keeps
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

} // namespace mrepair

#endif // MREPAIR_IO_RESULT_H
