// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_READ_OBJ_H
#define MREPAIR_INTERNAL_IO_READ_OBJ_H

// Wavefront OBJ reader: `v x y z [w] [r g b]` and `f a b c ...` with corners
// `i`, `i/t`, `i//n`, `i/t/n` (and `i/`, `i//` as some exporters write them).
// Indices are 1-based; a negative index is relative to the vertices read so
// far (-1 = last), per the OBJ spec. Index 0 and indices before the first
// vertex become negative (invalid) indices. A `\` as the last non-blank
// character of a line (outside a comment) joins the next line to it, for any
// record. Every other record (vt, vn, g, o, s, usemtl, mtllib, l, p, ...) is
// ignored. Files without continuations are parsed in parallel chunks of lines
// (text_chunks.h): a chunk first counts its `v` records, so that relative
// indices resolve as in one pass; the first error in file order is reported.

#include <mrepair/internal/io/common.h>
#include <mrepair/internal/io/text_chunks.h>

namespace mrepair {
namespace internal {
namespace io {

/// the end of the physical line starting at `p`: its '\n' or `end`.
inline const char* obj_line_end(const char* p, const char* end)
{
  const void* nl = p < end ? std::memchr(p, '\n', static_cast<std::size_t>(end - p)) : nullptr;
  return nl ? static_cast<const char*>(nl) : end;
}

/// the `\` that continues the line [b, e) on the next line, or nullptr: the
/// last non-blank character, when no comment starts before it.
inline const char* obj_continuation(const char* b, const char* e)
{
  while (e > b && is_blank(e[-1])) --e;
  if (e == b || e[-1] != '\\') return nullptr;
  const char* mark = e - 1;
  if (std::memchr(b, '#', static_cast<std::size_t>(mark - b))) return nullptr;
  return mark;
}

/// true when the record [b, e) is a vertex (`v`) record.
inline bool is_obj_vertex(const char* b, const char* e)
{
  while (b < e && is_blank(*b)) ++b;
  return e - b >= 2 && b[0] == 'v' && is_space(b[1]);
}

/// parses one logical record [b, e) (no newline inside) that starts on `line`;
/// `vertex_base` vertices precede those of `soup` (chunked parsing).
inline bool read_obj_record(const char* b, const char* e, std::size_t line,
                            const std::string& path, Raw_soup& soup, Error& err,
                            std::int64_t vertex_base = 0)
{
  Text_cursor c(b, e);
  c.line = line;
  auto fail = [&](const std::string& why) {
    return err.set(Status::parse_error, path + ":" + std::to_string(line) + ": " + why);
  };
  c.skip_blank();
  if (c.at_eol()) return true;
  std::string_view kw = c.read_token();
  if (kw == "v") {
    double v[3];
    for (int d = 0; d < 3; ++d) {
      c.skip_blank();
      if (!c.parse_double(v[d])) return fail("vertex: expected a coordinate, got " + c.shown_token());
    }
    soup.add_point(v[0], v[1], v[2], line);
  } else if (kw == "f" || kw == "fo") {
    const std::int64_t nv = vertex_base + static_cast<std::int64_t>(soup.num_points());
    while (!c.at_eol()) {
      std::int64_t i;
      if (!c.parse_int(i, '/')) return fail("face: expected a vertex index, got " + c.shown_token());
      // skip "/t", "//n", "/t/n", "/", "//": only the vertex index matters here
      while (c.p < c.end && !is_space(*c.p)) ++c.p;
      // 1-based; negative relative to the vertices read so far; 0 is invalid
      std::int64_t r = i > 0 ? i - 1 : (i < 0 ? nv + i : -1);
      soup.add_index(r);
    }
    soup.end_polygon(line);
  }
  return true;
}

/// the chunked parse of a file without line continuations.
inline bool read_obj_in_chunks(const File_buffer& buf, const std::string& path, Raw_soup& soup,
                               Error& err)
{
  std::vector<Text_chunk> chunks = split_text(buf.begin(), buf.end(), 1, '#');
  std::vector<std::int64_t> vertex_base(chunks.size() + 1, 0);
  parallel_for_index(chunks.size(), 1, [&](std::size_t k) {
    for (const char* s = chunks[k].b; s < chunks[k].e;) {
      const char* t = line_end(s, chunks[k].e);
      vertex_base[k + 1] += is_obj_vertex(s, t);
      s = t + 1;
    }
  });
  for (std::size_t k = 0; k < chunks.size(); ++k) vertex_base[k + 1] += vertex_base[k];
  std::vector<Error> errors(chunks.size());
  const std::size_t records = chunks.empty() ? 0 : chunks.back().first_record + chunks.back().records;
  const std::size_t vertices = static_cast<std::size_t>(vertex_base.back());
  soup.reserve(vertices, records - vertices, 3 * (records - vertices));
  const bool ok = parse_chunks(chunks.size(), soup, [&](std::size_t k, Raw_soup& part) {
    const std::size_t nv = static_cast<std::size_t>(vertex_base[k + 1] - vertex_base[k]);
    const std::size_t nf = chunks[k].records > nv ? chunks[k].records - nv : 0;
    part.reserve(nv, nf, 3 * nf);
    return for_each_record(chunks[k], '#', [&](std::size_t, const char* b, const char* e,
                                               std::size_t line) {
      return read_obj_record(b, e, line, path, part, errors[k], vertex_base[k]);
    });
  });
  if (ok) return true;
  for (Error& e : errors)
    if (!e.ok()) {
      err = std::move(e);
      break;
    }
  return false;
}

inline bool read_obj(const File_buffer& buf, const std::string& path, Raw_soup& soup, Error& err)
{
  soup.has_lines = true;
  if (!std::memchr(buf.begin(), '\\', buf.size)) return read_obj_in_chunks(buf, path, soup, err);
  std::string joined;  // a record continued over several lines
  const char* p = buf.begin();
  const char* const end = buf.end();
  std::size_t line = 1;
  while (p < end) {
    const std::size_t first_line = line;
    const char* e = obj_line_end(p, end);
    const char* mark = obj_continuation(p, e);
    if (!mark) {
      if (!read_obj_record(p, e, first_line, path, soup, err)) return false;
    } else {
      // the continued lines, each `\` (and the blanks after it) replaced by a space
      joined.assign(p, mark);
      while (mark && e < end) {
        p = e + 1;
        ++line;
        e = obj_line_end(p, end);
        mark = obj_continuation(p, e);
        joined.push_back(' ');
        joined.append(p, mark ? mark : e);
      }
      if (!read_obj_record(joined.data(), joined.data() + joined.size(), first_line, path, soup,
                           err))
        return false;
    }
    p = e < end ? e + 1 : end;
    ++line;
  }
  return true;
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_READ_OBJ_H
