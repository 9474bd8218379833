// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Writes the seed corpus of the fuzz targets: OUT/read (tiny OFF, OBJ, PLY
// ascii/binary, STL ascii/binary files), OUT/soup and OUT/mesh (encoded soups
// of fuzz_decode.h's seed_soups()). Standard library only.
//   usage: mrepair-fuzz-corpus OUT_DIR
#include "fuzz_decode.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace mrepair_fuzz;

namespace {

using Bytes = std::vector<std::uint8_t>;

void save(const fs::path& dir, const std::string& name, const Bytes& b)
{
  std::ofstream f(dir / name, std::ios::binary);
  f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

Bytes with_prefix(std::uint8_t sel, const std::string& s)
{
  Bytes b{sel};
  b.insert(b.end(), s.begin(), s.end());
  return b;
}

std::string num(double d)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", d);
  return buf;
}

template <class T>
void put(std::string& s, T v, bool big_endian)
{
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  s.append(b, sizeof(T));
}

std::vector<std::array<std::size_t, 3>> fan(const Seed& s)
{
  std::vector<std::array<std::size_t, 3>> t;
  for (const auto& p : s.polygons)
    for (std::size_t k = 2; k < p.size(); ++k) t.push_back({p[0], p[k - 1], p[k]});
  return t;
}

std::array<double, 3> corner(const Seed& s, std::size_t i)
{
  return i < s.points.size() ? s.points[i] : std::array<double, 3>{0, 0, 0};
}

std::string off(const Seed& s)
{
  std::string o = "OFF\n# seed " + s.name + "\n" + std::to_string(s.points.size()) + " " +
                  std::to_string(s.polygons.size()) + " 0\n";
  for (auto& p : s.points) o += num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + "\n";
  for (auto& f : s.polygons) {
    o += std::to_string(f.size());
    for (auto i : f) o += " " + std::to_string(i);
    o += "\n";
  }
  return o;
}

std::string obj(const Seed& s, bool slashes)
{
  std::string o = "# seed " + s.name + "\n";
  for (auto& p : s.points) o += "v " + num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + "\n";
  if (slashes) o += "vt 0 0\nvn 0 0 1\n";
  for (auto& f : s.polygons) {
    o += "f";
    for (auto i : f) o += " " + std::to_string(i + 1) + (slashes ? "/1/1" : "");
    o += "\n";
  }
  return o;
}

std::string ply(const Seed& s, int mode)  // 0 ascii, 1 binary LE doubles, 2 binary BE floats
{
  static const char* fmt[3] = {"ascii", "binary_little_endian", "binary_big_endian"};
  const char* real = mode == 2 ? "float" : "double";
  std::string o = std::string("ply\nformat ") + fmt[mode] + " 1.0\ncomment seed " + s.name + "\nelement vertex " +
                  std::to_string(s.points.size()) + "\nproperty " + real + " x\nproperty " + real +
                  " y\nproperty " + real + " z\nelement face " + std::to_string(s.polygons.size()) +
                  "\nproperty list uchar int vertex_indices\nend_header\n";
  for (auto& p : s.points) {
    if (mode == 0) o += num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + "\n";
    for (int d = 0; d < 3 && mode; ++d)
      mode == 1 ? put<double>(o, p[d], false) : put<float>(o, float(p[d]), true);
  }
  for (auto& f : s.polygons) {
    if (mode == 0) {
      o += std::to_string(f.size());
      for (auto i : f) o += " " + std::to_string(i);
      o += "\n";
    } else {
      o += char(f.size());
      for (auto i : f) put<std::int32_t>(o, std::int32_t(i), mode == 2);
    }
  }
  return o;
}

std::string stl(const Seed& s, bool binary)
{
  const auto t = fan(s);
  std::string o;
  if (binary) {
    o.assign(80, ' ');
    o.replace(0, 5 + s.name.size(), "seed " + s.name);
    put<std::uint32_t>(o, std::uint32_t(t.size()), false);
    for (auto& tri : t) {
      for (int d = 0; d < 3; ++d) put<float>(o, 0.f, false);
      for (auto i : tri)
        for (int d = 0; d < 3; ++d) put<float>(o, float(corner(s, i)[d]), false);
      put<std::uint16_t>(o, 0, false);
    }
    return o;
  }
  o = "solid " + s.name + "\n";
  for (auto& tri : t) {
    o += " facet normal 0 0 0\n  outer loop\n";
    for (auto i : tri) {
      auto p = corner(s, i);
      o += "   vertex " + num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + "\n";
    }
    o += "  endloop\n endfacet\n";
  }
  return o + "endsolid " + s.name + "\n";
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 2) {
    std::cerr << "usage: mrepair-fuzz-corpus OUT_DIR\n";
    return 2;
  }
  const fs::path out = argv[1];
  for (const char* t : {"read", "soup", "mesh"}) fs::create_directories(out / t);
  std::size_t counts[3] = {0, 0, 0};
  for (const Seed& s : seed_soups()) {
    // read: byte 0 = format (0 off, 1 obj, 2 ply, 3 stl) | 4 (Polyhedron too) | 8 (binary round trip)
    save(out / "read", s.name + ".off", with_prefix(0, off(s)));
    save(out / "read", s.name + ".obj", with_prefix(1 | 4, obj(s, false)));
    save(out / "read", s.name + "_vtn.obj", with_prefix(1, obj(s, true)));
    save(out / "read", s.name + "_ascii.ply", with_prefix(2, ply(s, 0)));
    save(out / "read", s.name + "_le.ply", with_prefix(2 | 8, ply(s, 1)));
    save(out / "read", s.name + "_be.ply", with_prefix(2 | 4, ply(s, 2)));
    save(out / "read", s.name + "_ascii.stl", with_prefix(3, stl(s, false)));
    save(out / "read", s.name + "_binary.stl", with_prefix(3 | 4, stl(s, true)));
    counts[0] += 8;
    Bytes soup;
    encode_soup(s.points, s.polygons, soup);
    // soup: byte 0 = options (merge/snap epsilon, two-sided, outward, Polyhedron, no SI count)
    for (std::uint8_t opt : {0x00, 0x05, 0x1a, 0x6f, 0xa0}) {
      Bytes b{opt};
      b.insert(b.end(), soup.begin(), soup.end());
      save(out / "soup", s.name + "_" + std::to_string(opt), b);
      ++counts[1];
    }
    // mesh: op, p1, p2; op 8..15 poison a vertex with NaN
    for (std::uint8_t op = 0; op < 16; ++op) {
      if (op >= 8 && op != 8 && op != 10 && op != 11) continue;
      Bytes b{op, 96, 3};
      b.insert(b.end(), soup.begin(), soup.end());
      save(out / "mesh", s.name + "_op" + std::to_string(op), b);
      ++counts[2];
    }
  }
  // readers: odd variants of the formats
  const std::pair<const char*, Bytes> extra[] = {
      {"coff.off", with_prefix(0, "COFF\n3 1 3\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2\n")},
      {"noff.off", with_prefix(0, "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2 1 0 0\n")},
      {"nan_neg.off", with_prefix(0, "OFF\n4 2 0\nnan 0 0\n1 0 0\n0 1 inf\n0 0 1\n3 0 1 2\n3 0 1 -1\n")},
      {"negative.obj", with_prefix(1, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nf 1 2 0\n")},
      {"extra_props.ply", with_prefix(2, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                         "property float z\nproperty uchar red\nelement face 1\nproperty list uchar uint "
                                         "vertex_indices\nproperty int flags\nend_header\n0 0 0 1\n1 0 0 2\n0 1 0 3\n3 0 1 2 7\n")},
      {"empty.off", with_prefix(0, "")},
      {"truncated.ply", with_prefix(2, "ply\nformat binary_little_endian 1.0\nelement vertex 1000000\nproperty double x\n")},
      {"huge_count.off", with_prefix(0, "OFF\n99999999999 99999999999 0\n0 0 0\n")},
      {"solid_binary.stl", with_prefix(3, std::string("solid but binary") + std::string(64, '\0') + std::string("\x02\0\0\0", 4))},
  };
  for (const auto& [name, b] : extra) {
    save(out / "read", name, b);
    ++counts[0];
  }
  std::cout << "corpus in " << out.string() << ": read " << counts[0] << ", soup " << counts[1] << ", mesh "
            << counts[2] << " files\n";
  return 0;
}
