// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_READ_OFF_H
#define MREPAIR_INTERNAL_IO_READ_OFF_H

// OFF reader (ASCII). Header keyword `[ST][C][N][4][n]OFF` (optional), then
// `nv nf [ne]`, nv vertex lines, nf face lines `n i0 .. i(n-1) [color]`.
// Vertex and face records are read line by line: after the coordinates
// (x y z, or x y z w for 4OFF, or `dim` values for nOFF) the rest of the
// line (normals, colors, texture coordinates) is skipped, and the rest of a
// face line after its indices (face colors) too. Comments start with '#'.
// The body is parsed in parallel chunks of lines when every record is on one
// line (text_chunks.h); otherwise, or on any error, line by line.

#include <mrepair/internal/io/common.h>
#include <mrepair/internal/io/text_chunks.h>

namespace mrepair {
namespace internal {
namespace io {

/// parses the `nv` vertex and `nf` face records of an OFF body [b, e) that
/// starts on line `line`, one record per line, in parallel chunks; false when
/// a record is not on one line or anything is wrong (nothing is kept then).
inline bool read_off_body_in_chunks(const char* b, const char* e, std::size_t line,
                                    std::uint64_t nv, std::uint64_t nf, std::int64_t dim,
                                    bool homogeneous, Raw_soup& soup)
{
  std::vector<Text_chunk> chunks = split_text(b, e, line, '#');
  const std::uint64_t records = chunks.empty() ? 0 : chunks.back().first_record + chunks.back().records;
  if (records < nv + nf || nv + nf < nv) return false;
  soup.reserve(nv, nf, 3 * nf);
  return parse_chunks(chunks.size(), soup, [&](std::size_t k, Raw_soup& part) {
    const Text_chunk& ch = chunks[k];
    if (ch.first_record >= nv + nf) return true;
    const std::uint64_t last = std::min<std::uint64_t>(ch.first_record + ch.records, nv + nf);
    const std::uint64_t in_v = ch.first_record < nv ? std::min<std::uint64_t>(last, nv) - ch.first_record : 0;
    part.reserve(in_v, last - ch.first_record - in_v, 3 * (last - ch.first_record - in_v));
    bool bad = false;
    for_each_record(ch, '#', [&](std::uint64_t r, const char* lb, const char* le, std::size_t ln) {
      if (r >= nv + nf) return false;  // past the faces: the rest is ignored
      bad = true;  // until the record is read
      Text_cursor c(lb, le);
      if (r < nv) {
        double v[4] = {0, 0, 0, 1};
        for (std::int64_t d = 0; d < dim; ++d) {
          double x;
          c.skip_blank();
          if (!c.parse_double(x)) return false;
          if (d < 3)
            v[d] = x;
          else if (homogeneous && d == dim - 1)
            v[3] = x;
        }
        if (homogeneous) {
          v[0] /= v[3];
          v[1] /= v[3];
          v[2] /= v[3];
        }
        part.add_point(v[0], v[1], v[2], ln);
        bad = false;
        return true;
      }
      std::int64_t n, idx;
      c.skip_blank();
      if (!c.parse_int(n) || n < 0) return false;
      for (std::int64_t i = 0; i < n; ++i) {
        c.skip_blank();
        if (!c.parse_int(idx)) return false;
        part.add_index(idx);
      }
      part.end_polygon(ln);
      bad = false;
      return true;
    });
    return !bad;
  });
}

inline bool read_off(const File_buffer& buf, const std::string& path, Raw_soup& soup, Error& err,
                     bool& binary)
{
  binary = false;
  Text_cursor c(buf.begin(), buf.end());
  auto fail = [&](Status s, const std::string& why) {
    return err.set(s, path + ":" + std::to_string(c.line) + ": " + why);
  };
  c.skip_ws();
  if (c.at_end()) return err.set(Status::empty_input, path + ": empty file");

  // header keyword: optional prefixes ST, C, N, 4, n before "OFF"
  bool homogeneous = false, ndim = false;
  std::string_view kw = c.peek_token();
  if (kw.size() >= 3 && kw.substr(kw.size() - 3) == "OFF") {
    std::string_view prefix = kw.substr(0, kw.size() - 3);
    if (prefix.size() >= 2 && prefix.substr(0, 2) == "ST") prefix.remove_prefix(2);
    for (char ch : prefix) {
      if (ch == '4')
        homogeneous = true;
      else if (ch == 'n')
        ndim = true;
      else if (ch != 'C' && ch != 'N')
        return fail(Status::parse_error, "unknown OFF header keyword '" + std::string(kw) + "'");
    }
    c.read_token();
    c.skip_blank();
    if (c.peek_token() == "BINARY")
      return fail(Status::unsupported_format, "binary OFF is not supported");
  } else {
    std::int64_t probe;
    Text_cursor t = c;
    if (!t.parse_int(probe))
      return fail(Status::parse_error, "not an OFF file: starts with " + c.shown_token());
  }
  std::int64_t dim = 3;
  if (ndim) {
    if (!c.next_int(dim)) return fail(Status::parse_error, "expected the dimension of nOFF, got " + c.shown_token());
    if (homogeneous) ++dim;
    if (dim < 3 || dim > 64)
      return fail(Status::unsupported_format, "nOFF dimension " + std::to_string(dim) + " is not 3D");
  } else if (homogeneous) {
    dim = 4;
  }

  std::int64_t nv = 0, nf = 0;
  c.skip_ws();
  if (c.at_end()) return fail(Status::parse_error, "file ends before the vertex and face counts");
  if (!c.parse_int(nv) || nv < 0)
    return fail(Status::parse_error, "expected the vertex count, got " + c.shown_token());
  if (!c.next_int(nf) || nf < 0)
    return fail(Status::parse_error, "expected the face count, got " + c.shown_token());
  c.skip_line();  // edge count and anything else on the counts line

  soup.has_lines = true;
  if (read_off_body_in_chunks(c.p, c.end, c.line, static_cast<std::uint64_t>(nv),
                              static_cast<std::uint64_t>(nf), dim, homogeneous, soup))
    return true;
  soup = Raw_soup();
  soup.has_lines = true;
  std::size_t rest = static_cast<std::size_t>(c.end - c.p);
  // a vertex takes at least 6 bytes ("0 0 0\n"), a triangle at least 8
  soup.reserve(capped(static_cast<std::uint64_t>(nv), rest, 6),
               capped(static_cast<std::uint64_t>(nf), rest, 8),
               3 * capped(static_cast<std::uint64_t>(nf), rest, 8));

  for (std::int64_t i = 0; i < nv; ++i) {
    double v[4] = {0, 0, 0, 1};
    for (std::int64_t d = 0; d < dim; ++d) {
      c.skip_ws();
      if (c.at_end())
        return fail(Status::parse_error, "file ends after " + std::to_string(i) + " of " +
                                             std::to_string(nv) + " vertices");
      double x;
      if (!c.parse_double(x))
        return fail(Status::parse_error, "vertex " + std::to_string(i) + ": expected a number, got " +
                                             c.shown_token());
      if (d < 3)
        v[d] = x;
      else if (homogeneous && d == dim - 1)
        v[3] = x;
    }
    if (homogeneous) {
      v[0] /= v[3];
      v[1] /= v[3];
      v[2] /= v[3];
    }
    soup.add_point(v[0], v[1], v[2], c.line);
    c.skip_line();  // per-vertex normals, colors, texture coordinates
  }

  for (std::int64_t f = 0; f < nf; ++f) {
    c.skip_ws();
    if (c.at_end())
      return fail(Status::parse_error,
                  "file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    std::int64_t n;
    if (!c.parse_int(n))
      return fail(Status::parse_error, "face " + std::to_string(f) +
                                           ": expected the vertex count, got " + c.shown_token());
    if (n < 0 || n > static_cast<std::int64_t>(c.end - c.p))
      return fail(Status::parse_error, "face " + std::to_string(f) + ": bad vertex count " +
                                           std::to_string(n));
    std::size_t line = c.line;
    for (std::int64_t k = 0; k < n; ++k) {
      std::int64_t idx;
      c.skip_blank();
      if (!c.parse_int(idx)) {
        if (c.at_eol())
          return fail(Status::parse_error, "face " + std::to_string(f) + ": " + std::to_string(n) +
                                               " vertices announced, " + std::to_string(k) +
                                               " found");
        return fail(Status::parse_error, "face " + std::to_string(f) +
                                             ": expected a vertex index, got " + c.shown_token());
      }
      soup.add_index(idx);
    }
    soup.end_polygon(line);
    c.skip_line();  // face colors
  }
  return true;
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_READ_OFF_H
