// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_DISPATCH_H
#define MREPAIR_INTERNAL_IO_DISPATCH_H

// The file-level workers of io.h: the format chosen from the file extension
// (one table for reading and writing), the reader or writer of that format,
// and the checks of what was read or is to be written, summed up in an
// `Io_result`.

#include <mrepair/internal/io/common.h>
#include <mrepair/internal/io/read_obj.h>
#include <mrepair/internal/io/read_off.h>
#include <mrepair/internal/io/read_ply.h>
#include <mrepair/internal/io/read_stl.h>
#include <mrepair/internal/io/write.h>
#include <mrepair/internal/utility.h>
#include <mrepair/io_result.h>
#include <mrepair/status.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <string>
#include <vector>

namespace mrepair {
namespace internal {
namespace io {

enum class File_format { off, obj, ply, stl, unknown };

/// the format of a (lower-case) file extension.
inline File_format file_format(const std::string& ext)
{
  if (ext == "off") return File_format::off;
  if (ext == "obj") return File_format::obj;
  if (ext == "ply") return File_format::ply;
  if (ext == "stl") return File_format::stl;
  return File_format::unknown;
}

/// the format of `path` by its extension; `r.format` receives the extension,
/// and is cleared with `why` set to the refusal when the format is unknown.
inline File_format choose_format(const std::string& path, Io_result& r, std::string& why)
{
  r.format = extension(path);
  const File_format f = file_format(r.format);
  if (f == File_format::unknown) {
    why = path + ": unsupported file extension '" + r.format + "' (use .off, .obj, .ply or .stl)";
    r.format.clear();
  }
  return f;
}

/// formats with a binary variant (the others are always written as text).
inline bool has_binary_variant(File_format f) { return f == File_format::ply || f == File_format::stl; }

inline bool point_is_finite(const Raw_soup& raw, std::size_t i)
{
  const double* q = &raw.xyz[3 * i];
  return std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]);
}

inline bool index_in_range(std::int64_t i, std::int64_t num_points) { return i >= 0 && i < num_points; }

/// reads any supported file into `raw` and checks it; on io/parse/empty/format
/// failures `raw` is cleared and `r` tells why.
inline void read_raw(const std::string& path, Raw_soup& raw, Io_result& r)
{
  r = Io_result();
  Error err;
  bool ok = false;
  Ply_skipped_faces skipped;
  try {
    std::string why;
    const File_format format = choose_format(path, r, why);
    if (format == File_format::unknown) {
      err.set(Status::unsupported_format, why);
    } else {
      File_buffer buf;
      if (read_file(path, buf, err)) {
        bool binary = false;
        switch (format) {
          case File_format::off: ok = read_off(buf, path, raw, err, binary); break;
          case File_format::obj: ok = read_obj(buf, path, raw, err); break;
          case File_format::ply: ok = read_ply(buf, path, raw, err, binary, &skipped); break;
          default: ok = read_stl(buf, path, raw, err, binary); break;
        }
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
  for (std::size_t i = raw.num_points(); i-- > 0;)
    if (!point_is_finite(raw, i)) {
      ++r.non_finite_points;
      first_bad_point = i;
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
        if (!index_in_range(raw.indices[k], np)) {
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

/// writes the soup of `raw` (a `Raw_soup_view` or a view of the same shape)
/// to `path` in the format of its extension.
template <class View>
void write_view(const std::string& path, const View& raw, bool binary, Io_result& r)
{
  r = Io_result();
  std::string why;
  const File_format format = choose_format(path, r, why);
  r.points = raw.num_points();
  r.polygons = raw.num_polygons();
  if (format == File_format::unknown) {
    r.status = Status::unsupported_format;
    r.message = why;
    return;
  }
  const bool stl = format == File_format::stl;
  // refuse what the file could not represent faithfully
  const std::int64_t np = static_cast<std::int64_t>(raw.num_points());
  // one validating pass, in chunks (in parallel when the view may be read
  // from several threads): the same counts and the same first bad polygon
  struct Check
  {
    Soup_stats stats;
    std::size_t invalid = 0, first_bad = 0, non_finite = 0;
  };
  auto check_polygons = [&](std::size_t b, std::size_t e, Check& c) {
    for (std::size_t f = b; f < e; ++f) {
      const std::size_t n = raw.degree(f);
      c.stats.max_degree = std::max(c.stats.max_degree, n);
      if (n >= 3) c.stats.triangles += n - 2;
      bool bad = stl && n < 3;
      for (std::size_t k = 0; k < n && !bad; ++k) bad = !index_in_range(raw.index(f, k), np);
      if (bad && c.invalid++ == 0) c.first_bad = f;
    }
  };
  auto check_points = [&](std::size_t b, std::size_t e, Check& c) {
    for (std::size_t i = b; i < e; ++i) {
      double x[3];
      raw.point(i, x);
      if (!(std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]))) ++c.non_finite;
    }
  };
  auto in_chunks = [&](std::size_t n, const auto& check) {
    if (View::parallel) return chunked<Check>(n, check);
    std::vector<Check> whole(1);
    check(0, n, whole[0]);
    return whole;
  };
  Soup_stats stats;
  std::size_t first_bad = 0;
  for (const Check& c : in_chunks(raw.num_polygons(), check_polygons)) {
    stats.max_degree = std::max(stats.max_degree, c.stats.max_degree);
    stats.triangles += c.stats.triangles;
    if (c.invalid && r.invalid_polygons == 0) first_bad = c.first_bad;
    r.invalid_polygons += c.invalid;
  }
  for (const Check& c : in_chunks(raw.num_points(), check_points)) r.non_finite_points += c.non_finite;
  if (r.invalid_polygons) {
    r.status = Status::invalid_index;
    r.message = path + ": not written: " + std::to_string(r.invalid_polygons) +
                " polygon(s) with an out-of-range index" +
                (stl ? std::string(" or fewer than 3 vertices") : std::string()) +
                ", first is polygon " + std::to_string(first_bad);
    return;
  }
  if (stl && stats.triangles > (std::numeric_limits<std::uint32_t>::max)() && binary) {
    r.status = Status::unsupported_format;
    r.message = path + ": not written: too many triangles for binary STL";
    return;
  }
  r.binary = binary && has_binary_variant(format);
  if (binary && !r.binary)
    r.message = path + ": " + r.format + " has no binary variant; wrote ASCII";
  Out_file out(path);
  if (!out.is_open()) {
    r.status = Status::io_error;
    r.message = path + ": cannot open for writing (" + std::strerror(errno) + ")";
    return;
  }
  try {
    switch (format) {
      case File_format::off: write_off(out, raw); break;
      case File_format::obj: write_obj(out, raw); break;
      case File_format::ply: write_ply(out, raw, stats, r.binary); break;
      default:
        write_stl(out, raw, stats, r.binary);
        r.polygons = stats.triangles;
        break;
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

/// writes `raw` to `path` in the format of its extension.
inline void write_raw(const std::string& path, const Raw_soup& raw, bool binary, Io_result& r)
{
  write_view(path, Raw_soup_view{raw}, binary, r);
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_DISPATCH_H
