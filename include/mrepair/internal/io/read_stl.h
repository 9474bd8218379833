// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_READ_STL_H
#define MREPAIR_INTERNAL_IO_READ_STL_H

// STL reader, ASCII and binary. STL stores each facet's corners by value, so
// corners with exactly equal coordinates (+0 == -0) are merged into one point
// while reading, through an open-addressing hash table; NaN corners are never
// merged. A file is binary when its size is 84 + 50 n, n being the count in
// bytes 80..83, even if its header starts with "solid" (many exporters write
// that); otherwise it is ASCII when it starts with "solid", else binary.

#include <mrepair/internal/io/common.h>

namespace mrepair {
namespace internal {
namespace io {

/// maps exact coordinates to point indices of a `Raw_soup`, in order of first
/// appearance. Slots hold the coordinates themselves, so that a lookup costs
/// one cache miss; `prefetch` lets a reader overlap the misses of a batch.
class Point_merger
{
  struct Slot
  {
    double x, y, z;
    std::uint32_t tag;    // 32 hash bits
    std::uint32_t index;  // point index + 1; 0 = empty
  };
  Big_vector<Slot> slots_;
  std::size_t mask_ = 0;
  std::size_t used_ = 0;
  Raw_soup& soup_;

  static std::uint64_t mix(std::uint64_t x)
  {
    x ^= x >> 30;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 27;
    x *= 0x94D049BB133111EBull;
    x ^= x >> 31;
    return x;
  }
  static std::uint64_t bits(double v)
  {
    v += 0.0;  // -0 becomes +0 so that both hash alike
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
  }
  void grow()
  {
    Big_vector<Slot> old;
    old.swap(slots_);
    slots_.assign(2 * old.size(), Slot{0, 0, 0, 0, 0});
    mask_ = slots_.size() - 1;
    for (const Slot& s : old)
      if (s.index) {
        std::size_t h = hash(s.x, s.y, s.z) & mask_;
        while (slots_[h].index) h = (h + 1) & mask_;
        slots_[h] = s;
      }
  }

public:
  static std::size_t hash(double x, double y, double z)
  {
    return static_cast<std::size_t>(mix(mix(mix(bits(x)) ^ bits(y)) ^ bits(z)));
  }

  explicit Point_merger(Raw_soup& soup, std::size_t expected_points) : soup_(soup)
  {
    std::size_t cap = 1024;
    while (cap < 2 * expected_points) cap *= 2;
    slots_.assign(cap, Slot{0, 0, 0, 0, 0});
    mask_ = cap - 1;
  }
  void prefetch(std::size_t h) const
  {
#if defined(__GNUC__)
    __builtin_prefetch(&slots_[h & mask_]);
#else
    (void)h;
#endif
  }
  /// the index of point (x,y,z) of hash `h`, added to the soup when new.
  std::int64_t index_hashed(double x, double y, double z, std::size_t h, std::size_t line = 0)
  {
    if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
      soup_.add_point(x, y, z, line);
      return static_cast<std::int64_t>(soup_.num_points() - 1);
    }
    if (2 * (used_ + 1) > slots_.size()) {
      grow();
    }
    const std::uint32_t tag = static_cast<std::uint32_t>(h >> 32);
    h &= mask_;
    for (;; h = (h + 1) & mask_) {
      const Slot& s = slots_[h];
      if (!s.index) break;
      if (s.tag == tag && s.x == x && s.y == y && s.z == z) return s.index - 1;
    }
    soup_.add_point(x, y, z, line);
    slots_[h] = Slot{x, y, z, tag, static_cast<std::uint32_t>(soup_.num_points())};
    ++used_;
    return static_cast<std::int64_t>(soup_.num_points() - 1);
  }
  std::int64_t index(double x, double y, double z, std::size_t line = 0)
  {
    return index_hashed(x, y, z, hash(x, y, z), line);
  }
};

inline bool read_stl_binary(const File_buffer& buf, const std::string& path, Raw_soup& soup,
                            Error& err)
{
  std::uint32_t n = load<std::uint32_t>(buf.begin() + 80, !host_is_little_endian());
  std::uint64_t available = (buf.size - 84) / 50;
  if (n > available)
    return err.set(Status::parse_error,
                   path + ": binary STL announces " + std::to_string(n) + " triangles, file holds " +
                       std::to_string(available));
  if (n > (std::numeric_limits<std::uint32_t>::max)() / 3 - 1)
    return err.set(Status::unsupported_format, path + ": too many triangles");
  soup.reserve(n / 2 + 3, n, 3 * std::size_t(n));
  Point_merger merge(soup, n / 2 + 3);
  const bool swap = !host_is_little_endian();
  const char* p = buf.begin() + 84;
  // batches of triangles: hash and prefetch all corners, then resolve them,
  // so that the table's cache misses overlap
  constexpr std::uint32_t batch = 8;
  double c[batch * 9];
  std::size_t h[batch * 3];
  for (std::uint32_t t0 = 0; t0 < n; t0 += batch) {
    const std::uint32_t m = std::min(batch, n - t0);
    for (std::uint32_t t = 0; t < m; ++t, p += 50)
      for (int k = 0; k < 9; ++k) c[9 * t + k] = load<float>(p + 12 + 4 * k, swap);
    for (std::uint32_t i = 0; i < 3 * m; ++i) {
      h[i] = Point_merger::hash(c[3 * i], c[3 * i + 1], c[3 * i + 2]);
      merge.prefetch(h[i]);
    }
    for (std::uint32_t t = 0; t < m; ++t) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t i = 3 * t + k;
        soup.add_index(merge.index_hashed(c[3 * i], c[3 * i + 1], c[3 * i + 2], h[i]));
      }
      soup.end_polygon();
    }
  }
  return true;
}

inline bool read_stl_ascii(const File_buffer& buf, const std::string& path, Raw_soup& soup,
                           Error& err)
{
  Text_cursor c(buf.begin(), buf.end(), '\0');
  auto fail = [&](const std::string& why) {
    return err.set(Status::parse_error, path + ":" + std::to_string(c.line) + ": " + why);
  };
  soup.has_lines = true;
  // an ASCII facet takes at least ~120 bytes
  std::size_t expected = capped(std::uint64_t(-1), buf.size, 120);
  soup.reserve(expected / 2, expected, 3 * expected);
  Point_merger merge(soup, expected / 2);
  bool in_facet = false, in_solid = false;
  std::size_t facet_line = 0, corners = 0;
  for (;;) {
    c.skip_ws();
    if (c.at_end()) break;
    std::string_view kw = c.read_token();
    if (kw == "solid") {
      if (in_solid) return fail("'solid' inside a solid");
      in_solid = true;
      c.skip_line();  // the name
    } else if (kw == "endsolid") {
      if (in_facet) return fail("'endsolid' inside a facet");
      in_solid = false;
      c.skip_line();
    } else if (kw == "facet") {
      if (!in_solid) return fail("'facet' outside a solid");
      if (in_facet) return fail("'facet' inside a facet");
      in_facet = true;
      facet_line = c.line;
      corners = 0;
      c.skip_line();  // the normal: recomputed from the corners when needed
    } else if (kw == "outer" || kw == "endloop") {
      if (!in_facet) return fail("'" + std::string(kw) + "' outside a facet");
      c.skip_line();
    } else if (kw == "vertex") {
      if (!in_facet) return fail("'vertex' outside a facet");
      double v[3];
      for (int d = 0; d < 3; ++d) {
        c.skip_blank();
        if (!c.parse_double(v[d])) return fail("vertex: expected a coordinate, got " + c.shown_token());
      }
      soup.add_index(merge.index(v[0], v[1], v[2], c.line));
      ++corners;
    } else if (kw == "endfacet") {
      if (!in_facet) return fail("'endfacet' outside a facet");
      in_facet = false;
      soup.end_polygon(facet_line);
    } else {
      std::string s(kw.substr(0, 24));
      return fail("unexpected '" + s + "' in ASCII STL");
    }
  }
  if (in_facet) return fail("file ends inside a facet");
  (void)corners;
  return true;
}

inline bool read_stl(const File_buffer& buf, const std::string& path, Raw_soup& soup, Error& err,
                     bool& binary)
{
  if (buf.size == 0) return err.set(Status::empty_input, path + ": empty file");
  const char* b = buf.begin();
  std::size_t i = 0;
  while (i < buf.size && is_space(b[i])) ++i;
  bool starts_solid = buf.size - i >= 5 && std::memcmp(b + i, "solid", 5) == 0 &&
                      (buf.size - i == 5 || is_space(b[i + 5]));
  bool size_matches = false;
  if (buf.size >= 84) {
    std::uint32_t n = load<std::uint32_t>(b + 80, !host_is_little_endian());
    size_matches = buf.size == 84 + 50 * std::uint64_t(n);
  }
  binary = size_matches || !starts_solid;
  if (!binary && buf.size >= 84 &&
      std::memchr(b, '\0', std::min<std::size_t>(buf.size, 1024)) != nullptr) {
    // "solid" header but binary content whose size disagrees with its count
    std::uint32_t n = load<std::uint32_t>(b + 80, !host_is_little_endian());
    return err.set(Status::parse_error,
                   path + ": binary STL (header starts with 'solid') announces " +
                       std::to_string(n) + " triangles, file holds " +
                       std::to_string((buf.size - 84) / 50) + " (truncated?)");
  }
  if (binary) {
    if (buf.size < 84)
      return err.set(Status::parse_error, path + ": binary STL shorter than its 84-byte header");
    return read_stl_binary(buf, path, soup, err);
  }
  return read_stl_ascii(buf, path, soup, err);
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_READ_STL_H
