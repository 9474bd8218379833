// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Replays the inputs the fuzz targets found (test/data/fuzz/{read,soup,mesh}/)
// and the seed soups through the targets' own bodies (fuzz/fuzz_*.h), so that
// every fixed finding stays fixed in the ordinary (gcc, Release) build too.
#include "../fuzz/fuzz_mesh.h"
#include "../fuzz/fuzz_read.h"
#include "../fuzz/fuzz_soup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace mrepair_fuzz;

namespace {

using Bytes = std::vector<std::uint8_t>;

std::vector<fs::path> inputs(const std::string& target)
{
  std::vector<fs::path> files;
  const fs::path dir = fs::path(MREPAIR_TEST_DATA_DIR) / "fuzz" / target;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

Bytes load(const fs::path& p)
{
  std::ifstream f(p, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

Bytes seed_input(std::vector<std::uint8_t> prefix, const Seed& s)
{
  encode_soup(s.points, s.polygons, prefix);
  return prefix;
}

std::string scratch_dir()
{
  const fs::path d = fs::temp_directory_path() / ("mrepair_fuzz_regressions_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d.string();
}

} // namespace

TEST(FuzzDecode, DecodesTheDocumentedLayout)
{
  // 2 points: (grid 0 -> -4, grid 9 -> 0.5, special 192 -> NaN), (raw 1.5, grid 8 -> 0, 160 -> -4 + 1e-7);
  // 3 polygons: a triangle (0, 1, 2 % 2 = 0), a quad (code 8) with out-of-range 248 (= n) and
  // 253 (SIZE_MAX), an empty polygon (code 13)
  Bytes b{2, 0, 9, 192, 224, 0, 0, 0, 0, 0, 0, 0xf8, 0x3f, 8, 160, 3, 0, 0, 1, 2, 8, 1, 248, 253, 0, 13};
  Byte_reader in(b.data(), b.size());
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  decode_soup(in, pts, polys);
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(pts[0].x(), -4.0);
  EXPECT_EQ(pts[0].y(), 0.5);
  EXPECT_TRUE(std::isnan(pts[0].z()));
  EXPECT_EQ(pts[1].x(), 1.5);
  EXPECT_EQ(pts[1].y(), 0.0);
  EXPECT_EQ(pts[1].z(), -4.0 + 1e-7);
  ASSERT_EQ(polys.size(), 3u);
  EXPECT_EQ(polys[0], (Polygon{0, 1, 0}));
  EXPECT_EQ(polys[1], (Polygon{1, 2, (std::numeric_limits<std::size_t>::max)(), 0}));
  EXPECT_TRUE(polys[2].empty());
}

TEST(FuzzDecode, EncodeIsTheInverseOfDecode)
{
  for (const Seed& s : seed_soups()) {
    const Bytes b = seed_input({}, s);
    Byte_reader in(b.data(), b.size());
    std::vector<Point> pts;
    std::vector<Polygon> polys;
    decode_soup(in, pts, polys);
    ASSERT_EQ(pts.size(), s.points.size()) << s.name;
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (int d = 0; d < 3; ++d)
        EXPECT_TRUE(pts[i][d] == s.points[i][d] || (std::isnan(pts[i][d]) && std::isnan(s.points[i][d])))
            << s.name << " point " << i;
    std::vector<Polygon> expected = s.polygons;
    for (Polygon& p : expected)
      for (std::size_t& i : p)
        if (i >= s.points.size()) i = decode_index(static_cast<std::uint8_t>(248 + (i - s.points.size() > 1 ? 5 : i - s.points.size())), s.points.size());
    EXPECT_EQ(polys, expected) << s.name;
  }
}

TEST(FuzzChecks, CatchViolations)
{
  // the checks the targets rely on are not vacuous
  Surface_mesh m;
  auto a = m.add_vertex(Point(0, 0, 0)), b = m.add_vertex(Point(1, 0, 0)), c = m.add_vertex(Point(0, 1, 0));
  m.add_face(a, b, c);
  EXPECT_EQ(check_mesh(m, "t", true), "");
  const Snapshot<Surface_mesh> snap(m);
  EXPECT_TRUE(snap.same(m));
  m.point(b) = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  EXPECT_FALSE(snap.same(m));
  EXPECT_NE(check_mesh(m, "t", true), "");
  EXPECT_EQ(check_mesh(m, "t", true, false), "");
  m.add_vertex(Point(2, 2, 2));  // isolated vertex: invalid
  EXPECT_NE(check_mesh(m, "t", true, false), "");
}

TEST(FuzzRegressions, SeedSoups)
{
  for (const Seed& s : seed_soups()) {
    for (std::uint8_t opt : {0x00, 0x05, 0x1a, 0x6f, 0xa0}) {
      const Bytes b = seed_input({opt}, s);
      EXPECT_EQ(run_soup(b.data(), b.size()), "") << s.name << " opt " << int(opt);
    }
    for (std::uint8_t op = 0; op < 12; ++op) {
      const Bytes b = seed_input({op, 96, 3}, s);
      EXPECT_EQ(run_mesh(b.data(), b.size()), "") << s.name << " op " << int(op);
    }
  }
}

// The reader target's body on the seed soups written by the library in every
// format: test/data/fuzz/read/ holds no finding yet, so without these the
// replay below would check nothing.
TEST(FuzzRegressions, SeedFilesThroughTheReaders)
{
  const std::string dir = scratch_dir();
  const char* const ext[5] = {"off", "obj", "ply", "ply", "stl"};
  const std::uint8_t format[5] = {0, 1, 2, 2, 3};
  std::size_t replayed = 0;
  for (const Seed& s : seed_soups()) {
    std::vector<Point> points;
    for (const auto& p : s.points) points.emplace_back(p[0], p[1], p[2]);
    for (int f = 0; f < 5; ++f) {
      const bool binary = f == 3 || f == 4;
      const std::string path = dir + "/seed." + ext[f];
      // seeds with invalid polygons cannot be written: the writer refuses them
      if (mrepair::write_polygon_soup(path, points, s.polygons, binary).status != mrepair::Status::ok)
        continue;
      Bytes b = load(path);
      ASSERT_FALSE(b.empty()) << s.name << " " << ext[f];
      // also into a Polyhedron_3, and the PLY round trip in binary
      b.insert(b.begin(), static_cast<std::uint8_t>(format[f] | 4 | (binary ? 8 : 0)));
      EXPECT_EQ(run_read(b.data(), b.size(), dir), "") << s.name << " " << ext[f];
      ++replayed;
    }
  }
  EXPECT_GE(replayed, 5 * seed_soups().size() / 2);
  fs::remove_all(dir);
}

TEST(FuzzRegressions, ReadArtifacts)
{
  const std::string dir = scratch_dir();
  for (const fs::path& p : inputs("read")) {
    const Bytes b = load(p);
    EXPECT_EQ(run_read(b.data(), b.size(), dir), "") << p.filename();
  }
  fs::remove_all(dir);
}

// The committed findings are there: a renamed or missing folder would make
// the replay pass without running anything.
TEST(FuzzRegressions, SoupArtifacts)
{
  const std::vector<fs::path> files = inputs("soup");
  ASSERT_FALSE(files.empty()) << "no artifact in " << MREPAIR_TEST_DATA_DIR << "/fuzz/soup";
  for (const fs::path& p : files) {
    const Bytes b = load(p);
    ASSERT_FALSE(b.empty()) << p.filename();
    EXPECT_EQ(run_soup(b.data(), b.size()), "") << p.filename();
  }
}

TEST(FuzzRegressions, MeshArtifacts)
{
  const std::vector<fs::path> files = inputs("mesh");
  ASSERT_FALSE(files.empty()) << "no artifact in " << MREPAIR_TEST_DATA_DIR << "/fuzz/mesh";
  for (const fs::path& p : files) {
    const Bytes b = load(p);
    ASSERT_FALSE(b.empty()) << p.filename();
    EXPECT_EQ(run_mesh(b.data(), b.size()), "") << p.filename();
  }
}
