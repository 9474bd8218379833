// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_READ_OBJ_H
#define MREPAIR_INTERNAL_IO_READ_OBJ_H

// Wavefront OBJ reader: `v x y z [w] [r g b]` and `f a b c ...` with corners
// `i`, `i/t`, `i//n`, `i/t/n`. Indices are 1-based; a negative index is
// relative to the vertices read so far (-1 = last), per the OBJ spec. Index 0
// and indices before the first vertex become negative (invalid) indices.
// Every other record (vt, vn, g, o, s, usemtl, mtllib, l, p, ...) is ignored.

#include <mrepair/internal/io/common.h>

namespace mrepair {
namespace internal {
namespace io {

inline bool read_obj(const File_buffer& buf, const std::string& path, Raw_soup& soup, Error& err)
{
  Text_cursor c(buf.begin(), buf.end());
  auto fail = [&](const std::string& why) {
    return err.set(Status::parse_error, path + ":" + std::to_string(c.line) + ": " + why);
  };
  soup.has_lines = true;
  // rough sizes: a vertex line takes >= 8 bytes, a face line >= 8
  soup.reserve(0, 0, 0);
  while (c.p < c.end) {
    c.skip_blank();
    if (c.at_eol()) {
      c.skip_line();
      continue;
    }
    std::string_view kw = c.read_token();
    if (kw == "v") {
      double v[3];
      for (int d = 0; d < 3; ++d) {
        c.skip_blank();
        if (!c.parse_double(v[d]))
          return fail("vertex: expected a coordinate, got " + c.shown_token());
      }
      soup.add_point(v[0], v[1], v[2], c.line);
    } else if (kw == "f" || kw == "fo") {
      const std::int64_t nv = static_cast<std::int64_t>(soup.num_points());
      std::size_t line = c.line;
      while (!c.at_eol()) {
        std::int64_t i;
        if (!c.parse_int(i, '/')) return fail("face: expected a vertex index, got " + c.shown_token());
        // skip "/t", "//n", "/t/n": only the vertex index matters here
        while (c.p < c.end && !is_space(*c.p)) ++c.p;
        // 1-based; negative relative to the vertices read so far; 0 is invalid
        std::int64_t r = i > 0 ? i - 1 : (i < 0 ? nv + i : -1);
        soup.add_index(r);
      }
      soup.end_polygon(line);
    }
    c.skip_line();
  }
  return true;
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_READ_OBJ_H
