// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_WRITE_H
#define MREPAIR_INTERNAL_IO_WRITE_H

// Writers of a flat soup. Text formats print the shortest decimal that reads
// back to the same double (std::to_chars), so ASCII OFF/OBJ/PLY round-trip
// exactly; binary PLY stores doubles. STL stores float32 (the format has no
// double), fan-triangulates polygons and writes each facet's normal.
// Records are formatted in parallel pieces (std::to_chars into a reused
// buffer per piece) and written in order; binary PLY writes the coordinate
// array as its vertex records in one call.

#include <mrepair/internal/io/common.h>
#include <mrepair/internal/io/text_chunks.h>
#include <mrepair/internal/utility.h>

namespace mrepair {
namespace internal {
namespace io {

/// what the writers read: a `Raw_soup`, or (convert.h) the caller's point and
/// polygon vectors, written without an intermediate copy.
struct Raw_soup_view
{
  const Raw_soup& s;
  std::size_t num_points() const { return s.num_points(); }
  std::size_t num_polygons() const { return s.num_polygons(); }
  void point(std::size_t i, double* c) const
  {
    c[0] = s.xyz[3 * i];
    c[1] = s.xyz[3 * i + 1];
    c[2] = s.xyz[3 * i + 2];
  }
  std::size_t degree(std::size_t f) const { return s.starts[f + 1] - s.starts[f]; }
  std::int64_t index(std::size_t f, std::size_t k) const { return s.indices[s.starts[f] + k]; }
  /// the coordinates as one array of 3 doubles per point, when there is one
  const double* xyz() const { return s.xyz.data(); }
  static constexpr bool parallel = true;  ///< may be read from several threads
};

/// what the writers need to know of the whole soup before writing: found by
/// the one validating pass of `write_view` (dispatch.h).
struct Soup_stats
{
  std::size_t max_degree = 0;  ///< corners of the largest polygon
  std::size_t triangles = 0;   ///< triangles of the fan triangulation
};

/// a piece of output text or bytes, formatted in place with std::to_chars.
class Piece
{
  std::string s_;
  std::size_t n_ = 0;

public:
  void clear() { n_ = 0; }
  const char* data() const { return s_.data(); }
  std::size_t size() const { return n_; }
  /// room for `k` more bytes; returns where they go (commit with `advance`).
  char* room(std::size_t k)
  {
    if (s_.size() < n_ + k) s_.resize(std::max(2 * s_.size(), n_ + k + 4096));
    return &s_[n_];
  }
  void advance(char* q) { n_ = static_cast<std::size_t>(q - s_.data()); }
  static char* put_double(char* q, double v) { return std::to_chars(q, q + 32, v).ptr; }
  static char* put_uint(char* q, std::uint64_t v) { return std::to_chars(q, q + 24, v).ptr; }
  template <std::size_t N>
  static char* put(char* q, const char (&text)[N])
  {
    std::memcpy(q, text, N - 1);
    return q + (N - 1);
  }
  static char* put(char* q, const char* text, std::size_t n)
  {
    std::memcpy(q, text, n);
    return q + n;
  }
};

/// writes items [0, n), formatted by `format(i, piece)`, in pieces of `per_piece`
/// items formatted in parallel (in waves of a few pieces per thread) and written
/// in order.
template <typename Format>
void write_pieces(Out_file& out, std::size_t n, std::size_t per_piece, const Format& format,
                  bool parallel = true)
{
  per_piece = std::max<std::size_t>(per_piece, 1);
  const std::size_t pieces = (n + per_piece - 1) / per_piece;
  const std::size_t wave = 2 * io_threads();
  std::vector<Piece> buf(std::min(wave, pieces));
  for (std::size_t w0 = 0; w0 < pieces; w0 += wave) {
    const std::size_t m = std::min(wave, pieces - w0);
    auto format_piece = [&](std::size_t k) {
      Piece& piece = buf[k];
      piece.clear();
      const std::size_t b = (w0 + k) * per_piece, e = std::min(n, b + per_piece);
      for (std::size_t i = b; i < e; ++i) format(i, piece);
    };
    if (parallel)
      parallel_for_index(m, 1, format_piece);
    else
      for (std::size_t k = 0; k < m; ++k) format_piece(k);
    for (std::size_t k = 0; k < m; ++k) out.put_bytes(buf[k].data(), buf[k].size());
  }
}

/// items per piece for items of about `bytes_per_item` bytes.
inline std::size_t items_per_piece(std::size_t bytes_per_item)
{
  return std::max<std::size_t>(io_chunk_bytes() / std::max<std::size_t>(bytes_per_item, 1), 1);
}

/// "prefix x y z\n" for every point.
template <class View>
void write_point_lines(Out_file& out, const View& s, const char* prefix)
{
  const std::size_t pn = std::strlen(prefix);
  write_pieces(out, s.num_points(), items_per_piece(64), [&](std::size_t i, Piece& piece) {
    double c[3];
    s.point(i, c);
    char* q = piece.room(pn + 3 * 32);
    q = Piece::put(q, prefix, pn);
    q = Piece::put_double(q, c[0]);
    *q++ = ' ';
    q = Piece::put_double(q, c[1]);
    *q++ = ' ';
    q = Piece::put_double(q, c[2]);
    *q++ = '\n';
    piece.advance(q);
  }, View::parallel);
}

/// a line per polygon: "n i1 ... in" (`counted`) or "f i1+1 ... in+1" (OBJ).
template <class View>
void write_polygon_lines(Out_file& out, const View& s, bool counted)
{
  write_pieces(out, s.num_polygons(), items_per_piece(24), [&](std::size_t f, Piece& piece) {
    const std::size_t n = s.degree(f);
    char* q = piece.room(22 * (n + 1) + 2);
    if (counted)
      q = Piece::put_uint(q, n);
    else
      *q++ = 'f';
    const std::uint64_t add = counted ? 0 : 1;
    for (std::size_t k = 0; k < n; ++k) {
      *q++ = ' ';
      q = Piece::put_uint(q, static_cast<std::uint64_t>(s.index(f, k)) + add);
    }
    *q++ = '\n';
    piece.advance(q);
  }, View::parallel);
}

/// the body OFF and ASCII PLY share: a line "x y z" per point, then a line
/// "n i1 ... in" per polygon.
template <class View>
void write_points_and_counted_polygons(Out_file& out, const View& s)
{
  write_point_lines(out, s, "");
  write_polygon_lines(out, s, true);
}

template <class View>
void write_off(Out_file& out, const View& s)
{
  out.put("OFF\n").put_uint(s.num_points()).put(' ').put_uint(s.num_polygons()).put(" 0\n");
  write_points_and_counted_polygons(out, s);
}

template <class View>
void write_obj(Out_file& out, const View& s)
{
  out.put("# written by mrepair\n");
  write_point_lines(out, s, "v ");
  write_polygon_lines(out, s, false);
}

template <class View>
void write_ply(Out_file& out, const View& s, const Soup_stats& stats, bool binary)
{
  // uchar counts are what most readers expect; wider only when needed
  const bool wide_count = stats.max_degree > 255;
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
  if (host_is_little_endian() && s.xyz()) {
    // the vertex records are the coordinate array itself
    out.put_bytes(reinterpret_cast<const char*>(s.xyz()), 3 * s.num_points() * sizeof(double));
  } else {
    write_pieces(out, s.num_points(), items_per_piece(24), [&](std::size_t i, Piece& piece) {
      double c[3];
      s.point(i, c);
      char* q = piece.room(24);
      for (int d = 0; d < 3; ++d) store_le<double>(q + 8 * d, c[d]);
      piece.advance(q + 24);
    }, View::parallel);
  }
  write_pieces(out, s.num_polygons(), items_per_piece(16), [&](std::size_t f, Piece& piece) {
    const std::size_t n = s.degree(f);
    char* q = piece.room(4 + 4 * n);
    if (wide_count) {
      store_le<std::uint32_t>(q, static_cast<std::uint32_t>(n));
      q += 4;
    } else {
      *q++ = static_cast<char>(static_cast<unsigned char>(n));
    }
    for (std::size_t k = 0; k < n; ++k, q += 4)
      store_le<std::uint32_t>(q, static_cast<std::uint32_t>(s.index(f, k)));
    piece.advance(q);
  }, View::parallel);
}

/// unit normal of triangle (a,b,c), or zero when degenerate.
inline Vec3 unit_triangle_normal(const double* a, const double* b, const double* c)
{
  const Vec3 n = triangle_normal(load_vec3(a), load_vec3(b), load_vec3(c));
  const double l = norm(n);
  if (!(l > 0 && std::isfinite(l))) return Vec3{{0, 0, 0}};
  return {{n[0] / l, n[1] / l, n[2] / l}};
}

template <class View>
void write_stl(Out_file& out, const View& s, const Soup_stats& stats, bool binary)
{
  if (binary) {
    char header[80] = {};
    const char* text = "binary STL written by mrepair";  // must not start with "solid"
    std::memcpy(header, text, std::strlen(text));
    out.put_bytes(header, 80);
    char cnt[4];
    store_le<std::uint32_t>(cnt, static_cast<std::uint32_t>(stats.triangles));
    out.put_bytes(cnt, 4);
  } else {
    out.put("solid mrepair\n");
  }
  write_pieces(out, s.num_polygons(), items_per_piece(binary ? 50 : 250),
               [&](std::size_t f, Piece& piece) {
    const std::size_t n = s.degree(f);
    double corners[3][3];
    if (n >= 3) s.point(static_cast<std::size_t>(s.index(f, 0)), corners[0]);
    for (std::size_t k = 1; k + 1 < n; ++k) {
      s.point(static_cast<std::size_t>(s.index(f, k)), corners[1]);
      s.point(static_cast<std::size_t>(s.index(f, k + 1)), corners[2]);
      const double* tri[3] = {corners[0], corners[1], corners[2]};
      const Vec3 nrm = unit_triangle_normal(tri[0], tri[1], tri[2]);
      if (binary) {
        char* rec = piece.room(50);
        for (int d = 0; d < 3; ++d) store_le<float>(rec + 4 * d, static_cast<float>(nrm[d]));
        for (int v = 0; v < 3; ++v)
          for (int d = 0; d < 3; ++d)
            store_le<float>(rec + 12 + 12 * v + 4 * d, static_cast<float>(tri[v][d]));
        rec[48] = rec[49] = 0;
        piece.advance(rec + 50);
      } else {
        char* q = piece.room(12 * 32 + 80);
        q = Piece::put(q, " facet normal ");
        for (int d = 0; d < 3; ++d) {
          q = Piece::put_double(q, nrm[d]);
          *q++ = d < 2 ? ' ' : '\n';
        }
        q = Piece::put(q, "  outer loop\n");
        for (int v = 0; v < 3; ++v) {
          q = Piece::put(q, "   vertex ");
          for (int d = 0; d < 3; ++d) {
            q = Piece::put_double(q, tri[v][d]);
            *q++ = d < 2 ? ' ' : '\n';
          }
        }
        q = Piece::put(q, "  endloop\n endfacet\n");
        piece.advance(q);
      }
    }
  }, View::parallel);
  if (!binary) out.put("endsolid mrepair\n");
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_WRITE_H
