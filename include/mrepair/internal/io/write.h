// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_WRITE_H
#define MREPAIR_INTERNAL_IO_WRITE_H

// Writers of a flat soup. Text formats print the shortest decimal that reads
// back to the same double (std::to_chars), so ASCII OFF/OBJ/PLY round-trip
// exactly; binary PLY stores doubles. STL stores float32 (the format has no
// double), fan-triangulates polygons and writes each facet's normal.

#include <mrepair/internal/io/common.h>

namespace mrepair {
namespace internal {
namespace io {

/// the body OFF and ASCII PLY share: a line "x y z" per point, then a line
/// "n i1 ... in" per polygon.
inline void write_points_and_counted_polygons(Out_file& out, const Raw_soup& s)
{
  for (std::size_t i = 0; i < s.num_points(); ++i) {
    out.put_double(s.xyz[3 * i]).put(' ').put_double(s.xyz[3 * i + 1]).put(' ');
    out.put_double(s.xyz[3 * i + 2]).put('\n');
    out.maybe_flush();
  }
  for (std::size_t f = 0; f < s.num_polygons(); ++f) {
    out.put_uint(s.starts[f + 1] - s.starts[f]);
    for (std::size_t k = s.starts[f]; k < s.starts[f + 1]; ++k)
      out.put(' ').put_uint(static_cast<std::uint64_t>(s.indices[k]));
    out.put('\n');
    out.maybe_flush();
  }
}

inline void write_off(Out_file& out, const Raw_soup& s)
{
  out.put("OFF\n").put_uint(s.num_points()).put(' ').put_uint(s.num_polygons()).put(" 0\n");
  write_points_and_counted_polygons(out, s);
}

inline void write_obj(Out_file& out, const Raw_soup& s)
{
  out.put("# written by mrepair\n");
  for (std::size_t i = 0; i < s.num_points(); ++i) {
    out.put("v ").put_double(s.xyz[3 * i]).put(' ').put_double(s.xyz[3 * i + 1]).put(' ');
    out.put_double(s.xyz[3 * i + 2]).put('\n');
    out.maybe_flush();
  }
  for (std::size_t f = 0; f < s.num_polygons(); ++f) {
    out.put('f');
    for (std::size_t k = s.starts[f]; k < s.starts[f + 1]; ++k)
      out.put(' ').put_uint(static_cast<std::uint64_t>(s.indices[k]) + 1);
    out.put('\n');
    out.maybe_flush();
  }
}

inline void write_ply(Out_file& out, const Raw_soup& s, bool binary)
{
  std::size_t max_size = 0;
  for (std::size_t f = 0; f < s.num_polygons(); ++f)
    max_size = std::max(max_size, s.starts[f + 1] - s.starts[f]);
  // uchar counts are what most readers expect; wider only when needed
  const bool wide_count = max_size > 255;
  const bool wide_index = s.num_points() > static_cast<std::size_t>((std::numeric_limits<std::int32_t>::max)());
  out.put("ply\nformat ").put(binary ? "binary_little_endian" : "ascii").put(" 1.0\n");
  out.put("comment written by mrepair\n");
  out.put("element vertex ").put_uint(s.num_points()).put('\n');
  out.put("property double x\nproperty double y\nproperty double z\n");
  out.put("element face ").put_uint(s.num_polygons()).put('\n');
  out.put("property list ").put(wide_count ? "uint" : "uchar").put(' ');
  out.put(wide_index ? "uint" : "int").put(" vertex_indices\nend_header\n");
  if (!binary) {
    write_points_and_counted_polygons(out, s);
    return;
  }
  char tmp[24];
  for (std::size_t i = 0; i < s.num_points(); ++i) {
    for (int d = 0; d < 3; ++d) store_le<double>(tmp + 8 * d, s.xyz[3 * i + d]);
    out.put_bytes(tmp, 24);
  }
  for (std::size_t f = 0; f < s.num_polygons(); ++f) {
    std::size_t n = s.starts[f + 1] - s.starts[f];
    if (wide_count) {
      store_le<std::uint32_t>(tmp, static_cast<std::uint32_t>(n));
      out.put_bytes(tmp, 4);
    } else {
      tmp[0] = static_cast<char>(static_cast<unsigned char>(n));
      out.put_bytes(tmp, 1);
    }
    for (std::size_t k = s.starts[f]; k < s.starts[f + 1]; ++k) {
      store_le<std::uint32_t>(tmp, static_cast<std::uint32_t>(s.indices[k]));
      out.put_bytes(tmp, 4);
    }
  }
}

/// unit normal of triangle (a,b,c), or zero when degenerate.
inline void triangle_normal(const double* a, const double* b, const double* c, double* n)
{
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (l > 0 && std::isfinite(l)) {
    n[0] /= l;
    n[1] /= l;
    n[2] /= l;
  } else {
    n[0] = n[1] = n[2] = 0;
  }
}

/// number of triangles of the fan triangulation of `s`.
inline std::size_t fan_triangle_count(const Raw_soup& s)
{
  std::size_t t = 0;
  for (std::size_t f = 0; f < s.num_polygons(); ++f) {
    std::size_t n = s.starts[f + 1] - s.starts[f];
    if (n >= 3) t += n - 2;
  }
  return t;
}

inline void write_stl(Out_file& out, const Raw_soup& s, bool binary)
{
  auto point = [&](std::int64_t i) { return &s.xyz[3 * static_cast<std::size_t>(i)]; };
  if (binary) {
    char header[80] = {};
    const char* text = "binary STL written by mrepair";  // must not start with "solid"
    std::memcpy(header, text, std::strlen(text));
    out.put_bytes(header, 80);
    char cnt[4];
    store_le<std::uint32_t>(cnt, static_cast<std::uint32_t>(fan_triangle_count(s)));
    out.put_bytes(cnt, 4);
  } else {
    out.put("solid mrepair\n");
  }
  for (std::size_t f = 0; f < s.num_polygons(); ++f) {
    const std::size_t b = s.starts[f], n = s.starts[f + 1] - b;
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const double* tri[3] = {point(s.indices[b]), point(s.indices[b + k]), point(s.indices[b + k + 1])};
      double nrm[3];
      triangle_normal(tri[0], tri[1], tri[2], nrm);
      if (binary) {
        char rec[50] = {};
        for (int d = 0; d < 3; ++d) store_le<float>(rec + 4 * d, static_cast<float>(nrm[d]));
        for (int v = 0; v < 3; ++v)
          for (int d = 0; d < 3; ++d)
            store_le<float>(rec + 12 + 12 * v + 4 * d, static_cast<float>(tri[v][d]));
        out.put_bytes(rec, 50);
      } else {
        out.put(" facet normal ").put_double(nrm[0]).put(' ').put_double(nrm[1]).put(' ');
        out.put_double(nrm[2]).put("\n  outer loop\n");
        for (int v = 0; v < 3; ++v) {
          out.put("   vertex ").put_double(tri[v][0]).put(' ').put_double(tri[v][1]).put(' ');
          out.put_double(tri[v][2]).put('\n');
        }
        out.put("  endloop\n endfacet\n");
        out.maybe_flush();
      }
    }
  }
  if (!binary) out.put("endsolid mrepair\n");
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_WRITE_H
