// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Byte decoding shared by the fuzz targets, the corpus generator and the
// regression test (test/test_fuzz_regressions.cpp). Standard library only, so
// that the corpus generator compiles in seconds.
//
// Encoded soup (every read past the end yields 0, so any byte string decodes):
//   byte            number of points n = byte % 33
//   n x 3 coords    one code byte each:
//                     0..159   grid value (c % 16) * 0.5 - 4        (duplicates, coplanarity)
//                     160..191 grid value ((c - 160) % 16) * 0.5 - 4 + 1e-7 (near duplicates)
//                     192..223 special value special_values()[c - 192]  (NaN, inf, 1e300, ...)
//                     224..255 raw double: the next 8 bytes, little endian
//   byte            number of polygons m = byte % 65
//   m polygons      size code byte s = byte & 15: s < 8: 3 corners, 8/9: 4, 10: 5, 11: 6,
//                   12: 8, 13: 0, 14: 1, 15: 2; then one byte per corner:
//                     0..247   index (byte % n), or byte when n == 0
//                     248..255 an out-of-range index: n, n + 1, n + 100, 2^32 - 1,
//                              2^32, SIZE_MAX, SIZE_MAX - 1, 2^63
#ifndef MREPAIR_FUZZ_DECODE_H
#define MREPAIR_FUZZ_DECODE_H

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace mrepair_fuzz {

/// reads bytes front to back; past the end it returns zeros.
class Byte_reader
{
public:
  Byte_reader(const std::uint8_t* data, std::size_t size) : p_(data), n_(size) {}
  std::uint8_t byte() { return i_ < n_ ? p_[i_++] : 0; }
  double raw_double()
  {
    std::uint64_t bits = 0;
    for (int k = 0; k < 8; ++k) bits |= static_cast<std::uint64_t>(byte()) << (8 * k);
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }
  std::size_t remaining() const { return i_ < n_ ? n_ - i_ : 0; }
  const std::uint8_t* rest() const { return p_ + (i_ < n_ ? i_ : n_); }

private:
  const std::uint8_t* p_;
  std::size_t n_;
  std::size_t i_ = 0;
};

inline const std::array<double, 32>& special_values()
{
  static const std::array<double, 32> v = {
      std::numeric_limits<double>::quiet_NaN(),
      std::numeric_limits<double>::infinity(),
      -std::numeric_limits<double>::infinity(),
      1e300, -1e300, 1e-300, -1e-300,
      (std::numeric_limits<double>::max)(), -(std::numeric_limits<double>::max)(),
      std::numeric_limits<double>::denorm_min(), (std::numeric_limits<double>::min)(),
      1e8, -1e8, 1e-8, 0.1, -0.0, 1.0 / 3.0, 1e15, 1e154, 1e-154, 2.0, 1.0 + 1e-15,
      4.0 + 1e-12, -4.0 - 1e-12, 1e-30, 3e-7, 7.25, -7.25, 1e20, 65504.0, 16777217.0,
      -std::numeric_limits<double>::quiet_NaN()};
  return v;
}

inline double decode_coordinate(Byte_reader& in)
{
  const std::uint8_t c = in.byte();
  if (c < 160) return (c % 16) * 0.5 - 4.0;
  if (c < 192) return ((c - 160) % 16) * 0.5 - 4.0 + 1e-7;
  if (c < 224) return special_values()[c - 192];
  return in.raw_double();
}

inline std::size_t polygon_size_of_code(std::uint8_t code)
{
  const unsigned s = code & 15u;
  if (s < 8) return 3;
  static const std::size_t rest[8] = {4, 4, 5, 6, 8, 0, 1, 2};
  return rest[s - 8];
}

inline std::size_t decode_index(std::uint8_t b, std::size_t n)
{
  if (b < 248) return n ? b % n : b;
  switch (b - 248) {
    case 0: return n;
    case 1: return n + 1;
    case 2: return n + 100;
    case 3: return 0xffffffffu;
    case 4: return static_cast<std::size_t>(1) << 32;
    case 5: return (std::numeric_limits<std::size_t>::max)();
    case 6: return (std::numeric_limits<std::size_t>::max)() - 1;
    default: return static_cast<std::size_t>(1) << 63;
  }
}

using Polygon = std::vector<std::size_t>;

/// decodes a soup; `Point` is constructible from three doubles.
template <class Point>
void decode_soup(Byte_reader& in, std::vector<Point>& points, std::vector<Polygon>& polygons)
{
  points.clear();
  polygons.clear();
  const std::size_t n = in.byte() % 33;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = decode_coordinate(in);
    const double y = decode_coordinate(in);
    const double z = decode_coordinate(in);
    points.emplace_back(x, y, z);
  }
  const std::size_t m = in.byte() % 65;
  for (std::size_t f = 0; f < m; ++f) {
    Polygon poly(polygon_size_of_code(in.byte()));
    for (std::size_t& i : poly) i = decode_index(in.byte(), n);
    polygons.push_back(std::move(poly));
  }
}

// ---- encoding, for the seed corpus -----------------------------------------

/// appends the encoding of a soup (coordinates as raw doubles, polygon sizes
/// 0..6 and 8, indices < 248) to `out`; the inverse of `decode_soup`.
inline void encode_soup(const std::vector<std::array<double, 3>>& points,
                        const std::vector<Polygon>& polygons, std::vector<std::uint8_t>& out)
{
  out.push_back(static_cast<std::uint8_t>(points.size()));
  for (const auto& p : points)
    for (double d : p) {
      // grid values have a one-byte code; everything else is written raw
      const double g = (d + 4.0) * 2.0;
      if (g >= 0 && g < 16 && static_cast<int>(g) * 0.5 - 4.0 == d && !(d == 0 && std::signbit(d))) {
        out.push_back(static_cast<std::uint8_t>(g));
      } else {
        out.push_back(224);
        std::uint64_t bits;
        std::memcpy(&bits, &d, sizeof d);
        for (int k = 0; k < 8; ++k) out.push_back(static_cast<std::uint8_t>(bits >> (8 * k)));
      }
    }
  out.push_back(static_cast<std::uint8_t>(polygons.size()));
  for (const Polygon& poly : polygons) {
    static const std::uint8_t code[9] = {13, 14, 15, 0, 8, 10, 11, 0, 12};
    out.push_back(code[poly.size()]);
    for (std::size_t i : poly)
      out.push_back(static_cast<std::uint8_t>(i < points.size() ? i : 248 + (i - points.size() > 1 ? 5 : i - points.size())));
  }
}

/// a named encoded soup of the seed corpus.
struct Seed
{
  std::string name;
  std::vector<std::array<double, 3>> points;
  std::vector<Polygon> polygons;
};

/// small soups with the defects the algorithms handle: a closed cube, an open
/// grid, a bowtie vertex, a fin (edge with three faces), duplicated and flipped
/// faces, a NaN point, out-of-range indices, a quad cube, a crack, a Moebius
/// strip, degenerate faces.
inline std::vector<Seed> seed_soups()
{
  std::vector<Seed> s;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto cube_points = [] {
    std::vector<std::array<double, 3>> p;
    for (int k = 0; k < 8; ++k) p.push_back({double(k & 1), double((k >> 1) & 1), double((k >> 2) & 1)});
    return p;
  };
  const std::size_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                               {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  {
    Seed c{"cube", cube_points(), {}};
    for (auto& f : q) {
      c.polygons.push_back({f[0], f[1], f[2]});
      c.polygons.push_back({f[0], f[2], f[3]});
    }
    s.push_back(c);
    Seed quads{"cube_quads", cube_points(), {}};
    for (auto& f : q) quads.polygons.push_back({f[0], f[1], f[2], f[3]});
    s.push_back(quads);
    Seed dup = c;  // duplicated and flipped faces
    dup.name = "cube_duplicates";
    dup.polygons.push_back(c.polygons[0]);
    dup.polygons.push_back({c.polygons[3][2], c.polygons[3][1], c.polygons[3][0]});
    s.push_back(dup);
    Seed holed = c;  // two faces missing: a hole
    holed.name = "cube_hole";
    holed.polygons.resize(10);
    s.push_back(holed);
    Seed bad = c;  // NaN point, out-of-range index, degenerate polygons
    bad.name = "cube_nan_bad_index";
    bad.points.push_back({nan, 0.5, 0.5});
    bad.polygons.push_back({0, 1, 8});
    bad.polygons.push_back({0, 1, 9});
    bad.polygons.push_back({2, 2, 3});
    bad.polygons.push_back({0, 1});
    bad.polygons.push_back({});
    s.push_back(bad);
  }
  {
    Seed g{"grid", {}, {}};  // open 3x3 grid, 4x4 points
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) g.points.push_back({double(i), double(j), 0.0});
    for (std::size_t j = 0; j < 3; ++j)
      for (std::size_t i = 0; i < 3; ++i) {
        std::size_t a = 4 * j + i, b = a + 1, c = a + 5, d = a + 4;
        g.polygons.push_back({a, b, c});
        g.polygons.push_back({a, c, d});
      }
    s.push_back(g);
    Seed crack = g;  // the right column re-made from its own points: a crack to close
    crack.name = "grid_crack";
    for (int j = 0; j < 4; ++j) crack.points.push_back({2.0 + 1e-3, double(j), 0.0});
    for (auto& p : crack.polygons)
      for (auto& i : p)
        if (i % 4 == 2 && (&p - &crack.polygons[0]) % 6 >= 4) i = 16 + i / 4;
    s.push_back(crack);
    Seed bumpy = g;  // a spike and a fold
    bumpy.name = "grid_spike";
    bumpy.points[5][2] = 3.0;
    bumpy.points[10][2] = -0.5;
    s.push_back(bumpy);
  }
  {
    Seed b{"bowtie", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}};
    s.push_back(b);
    Seed fin{"fin", {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}},
             {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}};
    s.push_back(fin);
    Seed mob{"moebius", {}, {}};
    const int k = 6;
    for (int i = 0; i < k; ++i) {
      const double t = 6.283185307179586 * i / k, w = 0.3;
      const double c = std::cos(t / 2) * w, z = std::sin(t / 2) * w;
      mob.points.push_back({(1 + c) * std::cos(t), (1 + c) * std::sin(t), z});
      mob.points.push_back({(1 - c) * std::cos(t), (1 - c) * std::sin(t), -z});
    }
    for (std::size_t i = 0; i < k; ++i) {
      std::size_t a = 2 * i, b = 2 * i + 1, c = (2 * i + 2) % (2 * k), d = (2 * i + 3) % (2 * k);
      if (i == k - 1) std::swap(c, d);  // the half twist
      mob.polygons.push_back({a, c, b});
      mob.polygons.push_back({b, c, d});
    }
    s.push_back(mob);
    Seed tet{"tetra_huge", {{0, 0, 0}, {1e300, 0, 0}, {0, 1e-300, 0}, {0, 0, 1}},
             {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}};
    s.push_back(tet);
    Seed col{"collinear", {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}}};
    s.push_back(col);
  }
  {  // issue 36: small soups that hung or crashed `repair`
    Seed pentagon{"polygonfaces",  // trimesh's polygonfaces.obj
                  {{-500, 0, 500}, {500, 0, 500}, {500, 0, -500}, {-500, 0, -500}, {0, 500, -500}},
                  {{0, 1, 2, 3, 4}}};
    s.push_back(pentagon);
    Seed octagon{"octagon_wide", {}, {{0, 1, 2, 3, 4, 5, 6, 7}}};  // non-planar, 1e-9 .. 1e9
    for (int i = 0; i < 8; ++i)
      octagon.points.push_back({std::pow(10.0, i - 4) * (i % 2 ? 1 : -1), std::pow(10.0, 9 - 2 * i % 19),
                                i % 3 == 0 ? 1e-9 : 0.0});
    s.push_back(octagon);
    Seed repeats{"repeated_corners",
                 {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}},
                 {{0, 1, 2, 1, 3, 0}, {1, 4, 5, 2, 3, 2, 1, 0}}};
    s.push_back(repeats);
  }
  return s;
}

} // namespace mrepair_fuzz

#endif // MREPAIR_FUZZ_DECODE_H
