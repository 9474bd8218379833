// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_STATUS_H
#define MREPAIR_STATUS_H

/// \file status.h
/// The status every mrepair call returns in its result struct. Bad *data* is
/// reported here, never by a throw or a crash; `CGAL_precondition` is kept for
/// programming errors only.

namespace mrepair {

/// \ingroup mrepair_core
/// outcome of a public call.
enum class Status {
  ok = 0,              ///< the call did what it was asked
  partial,             ///< the call did some work and left some defects (see counters)
  empty_input,         ///< nothing to work on (no points, no faces, empty file)
  non_finite_input,    ///< a coordinate is NaN or infinite; input untouched
  invalid_index,       ///< a polygon refers to a negative or out-of-range vertex
  invalid_mesh,        ///< the mesh fails `CGAL::is_valid_polygon_mesh` or is not triangulated
  non_manifold_input,  ///< the call needs a manifold mesh and got none; input untouched
  io_error,            ///< a file could not be opened, read or written
  parse_error,         ///< a file is malformed or truncated
  unsupported_format,  ///< the file extension or variant is not supported
  invalid_parameter,   ///< a named parameter is out of its documented range
  cancelled            ///< the visitor asked to stop; the mesh is valid
};

/// returns a short lowercase name of `s`, stable for use in JSON reports.
inline const char* to_string(Status s)
{
  switch (s) {
    case Status::ok: return "ok";
    case Status::partial: return "partial";
    case Status::empty_input: return "empty_input";
    case Status::non_finite_input: return "non_finite_input";
    case Status::invalid_index: return "invalid_index";
    case Status::invalid_mesh: return "invalid_mesh";
    case Status::non_manifold_input: return "non_manifold_input";
    case Status::io_error: return "io_error";
    case Status::parse_error: return "parse_error";
    case Status::unsupported_format: return "unsupported_format";
    case Status::invalid_parameter: return "invalid_parameter";
    case Status::cancelled: return "cancelled";
  }
  return "unknown";
}

/// returns `true` when `s` means the call succeeded, possibly with defects left.
inline bool succeeded(Status s) { return s == Status::ok || s == Status::partial; }

} // namespace mrepair

#endif // MREPAIR_STATUS_H
