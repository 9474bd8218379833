// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_TEXT_CHUNKS_H
#define MREPAIR_INTERNAL_IO_TEXT_CHUNKS_H

// Parallel parsing of the body of a text file whose records are lines:
//
//   split the body into chunks of about `io_chunk_bytes()` at line boundaries
//   in parallel: count each chunk's newlines and record lines (lines holding
//                more than blanks and a comment)
//   prefix sums: each chunk's first line number and first record number
//   in waves of a few chunks per thread:
//     in parallel: each chunk parses its record lines into its own Raw_soup
//     append the chunk soups to the result in order (in parallel, by offsets)
//
// The waves keep the chunk soups small and reused, so that the pages they
// touch stay few and warm (see common.h on the cost of fresh pages).
//
// A chunk parser that meets anything unusual (a record over several lines, a
// bad token) reports failure; the readers then run their sequential parser
// from the start, which gives the exact message. The parallel path therefore
// only ever produces what the sequential one would.

#include <mrepair/internal/io/common.h>
#include <mrepair/internal/utility.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_arena.h>
#endif

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <vector>

namespace mrepair {
namespace internal {
namespace io {

/// the size of the pieces that text parsing and formatting work on in
/// parallel (bytes of text); tests make it small to exercise many chunks.
/// Small enough that the per-chunk buffers of a wave stay few fresh pages.
inline std::size_t& io_chunk_bytes()
{
  static std::size_t bytes = std::size_t(256) << 10;
  return bytes;
}

/// a piece of text made of whole lines.
struct Text_chunk
{
  const char* b = nullptr;
  const char* e = nullptr;
  std::size_t first_line = 0;    // line number of `b`
  std::size_t newlines = 0;
  std::size_t records = 0;       // lines with content
  std::size_t first_record = 0;  // number of record lines before `b`
};

/// the end of the line starting at `p`: its '\n' or `end`.
inline const char* line_end(const char* p, const char* end)
{
  // mesh lines are short: a plain loop first, memchr for long lines
  for (const char* stop = end - p > 96 ? p + 96 : end; p < stop; ++p)
    if (*p == '\n') return p;
  const void* nl = p < end ? std::memchr(p, '\n', static_cast<std::size_t>(end - p)) : nullptr;
  return nl ? static_cast<const char*>(nl) : end;
}

/// true when the line [p, e) holds more than blanks and a comment.
inline bool is_record_line(const char* p, const char* e, char comment)
{
  while (p < e && is_blank(*p)) ++p;
  return p < e && !(comment != '\0' && *p == comment);
}

/// splits [b, e) (starting on line `first_line`) at line boundaries and counts
/// the newlines and record lines of each chunk (in parallel).
inline std::vector<Text_chunk> split_text(const char* b, const char* e, std::size_t first_line,
                                          char comment)
{
  const std::size_t size = static_cast<std::size_t>(e - b);
  const std::size_t step = std::max<std::size_t>(io_chunk_bytes(), 1);
  std::vector<Text_chunk> chunks;
  chunks.reserve(size / step + 2);
  const char* p = b;
  while (p < e) {
    const char* q = static_cast<std::size_t>(e - p) > step ? p + step : e;
    if (q < e) {
      q = line_end(q - 1, e);  // the line holding the last byte ends the chunk
      if (q < e) ++q;
    }
    Text_chunk c;
    c.b = p;
    c.e = q;
    chunks.push_back(c);
    p = q;
  }
  parallel_for_index(chunks.size(), 1, [&](std::size_t k) {
    Text_chunk& c = chunks[k];
    for (const char* s = c.b; s < c.e;) {
      const char* t = line_end(s, c.e);
      if (is_record_line(s, t, comment)) ++c.records;
      if (t < c.e) ++c.newlines;
      s = t + 1;
    }
  });
  std::size_t line = first_line, record = 0;
  for (Text_chunk& c : chunks) {
    c.first_line = line;
    c.first_record = record;
    line += c.newlines;
    record += c.records;
  }
  return chunks;
}

/// calls `f(record, line_begin, line_end, line_number)` for each record line of
/// `c`, in order, until `f` returns false; returns false then.
template <typename F>
bool for_each_record(const Text_chunk& c, char comment, const F& f)
{
  std::size_t line = c.first_line, record = c.first_record;
  for (const char* s = c.b; s < c.e; ++line) {
    const char* t = line_end(s, c.e);
    if (is_record_line(s, t, comment)) {
      if (!f(record, s, t, line)) return false;
      ++record;
    }
    s = t + 1;
  }
  return true;
}

/// appends the chunk soups `parts` (in order) to `out`, whose polygon indices
/// they already use.
inline void concatenate(const Raw_soup* parts, std::size_t n, Raw_soup& out)
{
  std::vector<std::size_t> xyz0(n + 1), idx0(n + 1), poly0(n + 1);
  xyz0[0] = out.xyz.size();
  idx0[0] = out.indices.size();
  poly0[0] = out.num_polygons();
  for (std::size_t k = 0; k < n; ++k) {
    xyz0[k + 1] = xyz0[k] + parts[k].xyz.size();
    idx0[k + 1] = idx0[k] + parts[k].indices.size();
    poly0[k + 1] = poly0[k] + parts[k].num_polygons();
    if (out.first_non_finite_line == 0) out.first_non_finite_line = parts[k].first_non_finite_line;
  }
  out.xyz.resize(xyz0[n]);
  out.indices.resize(idx0[n]);
  out.starts.resize(poly0[n] + 1);
  if (out.has_lines) out.polygon_line.resize(poly0[n]);
  parallel_for_index(n, 1, [&](std::size_t k) {
    const Raw_soup& p = parts[k];
    std::copy(p.xyz.begin(), p.xyz.end(), out.xyz.begin() + static_cast<std::ptrdiff_t>(xyz0[k]));
    std::copy(p.indices.begin(), p.indices.end(),
              out.indices.begin() + static_cast<std::ptrdiff_t>(idx0[k]));
    for (std::size_t f = 0; f < p.num_polygons(); ++f)
      out.starts[poly0[k] + f + 1] = idx0[k] + p.starts[f + 1];
    if (out.has_lines)
      std::copy(p.polygon_line.begin(), p.polygon_line.end(),
                out.polygon_line.begin() + static_cast<std::ptrdiff_t>(poly0[k]));
  });
}

/// the number of threads parallel loops may use.
inline std::size_t io_threads()
{
#ifdef CGAL_LINKED_WITH_TBB
  return static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency()));
#else
  return 1;
#endif
}

/// runs `parse(k, part)` for every chunk k (in parallel, in waves of a few
/// chunks per thread), `part` being an emptied soup, and appends the parts to
/// `out` in chunk order. Stops after the first wave where a `parse` returned
/// false and returns false then (every chunk before that wave succeeded).
template <typename Parse>
bool parse_chunks(std::size_t num_chunks, Raw_soup& out, const Parse& parse)
{
  const std::size_t wave = 4 * io_threads();  // parts reused from wave to wave
  std::vector<Raw_soup> parts(std::min(wave, num_chunks));
  std::vector<char> ok(parts.size());
  for (std::size_t w0 = 0; w0 < num_chunks; w0 += wave) {
    const std::size_t n = std::min(wave, num_chunks - w0);
    parallel_for_index(n, 1, [&](std::size_t k) {
      Raw_soup& p = parts[k];
      p.xyz.clear();
      p.indices.clear();
      p.starts.resize(1);
      p.polygon_line.clear();
      p.first_non_finite_line = 0;
      p.has_lines = out.has_lines;
      ok[k] = parse(w0 + k, p);
    });
    if (std::find(ok.begin(), ok.begin() + static_cast<std::ptrdiff_t>(n), 0) !=
        ok.begin() + static_cast<std::ptrdiff_t>(n))
      return false;
    concatenate(parts.data(), n, out);
  }
  return true;
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_TEXT_CHUNKS_H
