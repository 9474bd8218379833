// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Gap_closing_sequence as the command line uses it (issue 18): sequence files
// (save, read, replay, corrupt files), stepping to a distance, backward and
// forward, region selection; and `mrepair close-gaps` with those options.
#include "fixtures.h"

#include <mrepair/close_gaps.h>
#include <mrepair/gap_closing_sequence.h>
#include <mrepair/io.h>

#include <CGAL/boost/graph/iterator.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

// A namespace of its own: this file is compiled in one translation unit with
// other test files (a unity build, CMakeLists.txt).
namespace {
namespace gap_sequence_tests {

using namespace mrepair_test;
namespace MP = mrepair::parameters;

namespace {

// nx x ny triangulated grid over [x0, x0+1] x [0,1] (z = 0)
void add_patch(Soup& s, double x0, std::size_t nx, std::size_t ny)
{
  const std::size_t base = s.points.size();
  for (std::size_t j = 0; j <= ny; ++j)
    for (std::size_t i = 0; i <= nx; ++i) s.points.emplace_back(x0 + double(i) / nx, double(j) / ny, 0);
  auto id = [&](std::size_t i, std::size_t j) { return base + j * (nx + 1) + i; };
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      s.polygons.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.polygons.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

// three patches with two gaps, of width 0.01 (at x = 1) and 0.015 (at x = 2.01);
// the middle patch is twice as fine along y (T-junctions on the first seam)
Soup two_gaps(double second = 2.025)
{
  Soup s;
  add_patch(s, 0.0, 10, 10);
  add_patch(s, 1.01, 10, 20);
  add_patch(s, second, 10, 20);
  return s;
}

const double tolerance = 0.02;

// the mesh as sorted vertex positions and sorted faces (position triples in
// cyclic order from the smallest): what "exactly the same mesh" means
template <class Mesh>
std::pair<std::vector<std::array<double, 3>>, std::vector<std::array<double, 9>>> shape(const Mesh& m)
{
  auto vpm = get(CGAL::vertex_point, m);
  auto p3 = [&](typename boost::graph_traits<Mesh>::vertex_descriptor v) {
    const auto& p = get(vpm, v);
    return std::array<double, 3>{{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
  };
  std::vector<std::array<double, 3>> vs;
  for (auto v : vertices(m)) vs.push_back(p3(v));
  std::sort(vs.begin(), vs.end());
  std::vector<std::array<double, 9>> fs;
  for (auto f : faces(m)) {
    std::vector<std::array<double, 3>> c;
    for (auto v : CGAL::vertices_around_face(halfedge(f, m), m)) c.push_back(p3(v));
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    std::array<double, 9> t{};
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d) t[3 * i + d] = c[i][d];
    fs.push_back(t);
  }
  std::sort(fs.begin(), fs.end());
  return {vs, fs};
}

template <class Mesh>
std::size_t border_edges(const Mesh& m)
{
  return mrepair::internal::count_boundary(m).first;
}

// border edges with both ends in x0 < x < x1 (one seam)
template <class Mesh>
std::size_t seam_border_edges(const Mesh& m, double x0, double x1)
{
  auto vpm = get(CGAL::vertex_point, m);
  std::size_t n = 0;
  for (auto h : halfedges(m)) {
    if (!is_border(h, m)) continue;
    double a = CGAL::to_double(get(vpm, source(h, m)).x()), b = CGAL::to_double(get(vpm, target(h, m)).x());
    if (a > x0 && a < x1 && b > x0 && b < x1) ++n;
  }
  return n;
}

template <class Mesh>
std::string saved(const mrepair::Gap_closing_sequence<Mesh>& seq)
{
  std::ostringstream out;
  EXPECT_EQ(seq.save(out), mrepair::Status::ok);
  return out.str();
}

mrepair::Status read_file(const std::string& text, mrepair::Gap_sequence_file& f, std::string& error)
{
  std::istringstream in(text);
  return f.read(in, error);
}

} // namespace

template <class C>
class Gap_sequence : public ::testing::Test
{};
TYPED_TEST_SUITE(Gap_sequence, Mesh_configs);

// save, read back, replay on a fresh copy of the input: the same mesh, the same file
TYPED_TEST(Gap_sequence, save_and_replay_give_the_same_mesh)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m1 = to_mesh<Mesh>(two_gaps()), m2 = m1;
  mrepair::Gap_closing_sequence<Mesh> s1(m1, tolerance, MP::gap_fingerprint_input(true));
  ASSERT_EQ(s1.status(), mrepair::Status::ok);
  s1.forward_to_distance(tolerance);
  ASSERT_GT(s1.size(), 10u);
  const std::string text = saved(s1);
  EXPECT_EQ(text.compare(0, 23, "mrepair-gap-sequence 1\n"), 0);

  mrepair::Gap_sequence_file f;
  std::string error;
  ASSERT_EQ(read_file(text, f, error), mrepair::Status::ok) << error;
  EXPECT_EQ(f.contractions.size(), s1.size());
  mrepair::Gap_closing_sequence<Mesh> s2(m2, f.tolerance,
                                         MP::gap_lambda(f.lambda, MP::gap_snap_distance(f.snap,
                                                                  MP::gap_fingerprint_input(true))));
  ASSERT_EQ(s2.replay(f, error), mrepair::Status::ok) << error;
  EXPECT_EQ(s2.position(), s1.size());
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m2));
  EXPECT_EQ(shape(m1), shape(m2));
  EXPECT_EQ(saved(s2), text);

  // without the fingerprint there is nothing to save
  Mesh m3 = to_mesh<Mesh>(two_gaps());
  mrepair::Gap_closing_sequence<Mesh> s3(m3, tolerance);
  s3.forward(3);
  std::ostringstream out;
  EXPECT_EQ(s3.save(out), mrepair::Status::invalid_parameter);
}

// forward to a distance, full closure then back to it, and K steps forward: one mesh
TYPED_TEST(Gap_sequence, to_distance_equals_stepping_forward)
{
  using Mesh = typename TypeParam::Mesh;
  const Mesh input = to_mesh<Mesh>(two_gaps());
  Mesh full = input;
  mrepair::Gap_closing_sequence<Mesh> sf(full, tolerance);
  sf.forward_to_distance(tolerance);
  ASSERT_GT(sf.size(), 4u);
  // a distance in the middle of the sequence, between two levels
  const std::size_t half = sf.count_within(sf.distance_at(sf.size() / 2));
  const double d = sf.distance_at(half);
  ASSERT_LT(half, sf.size());

  Mesh m1 = input;
  mrepair::Gap_closing_sequence<Mesh> s1(m1, tolerance);
  s1.forward_to_distance(d);
  EXPECT_EQ(s1.position(), half);
  sf.backward_to_distance(d);
  EXPECT_EQ(sf.position(), half);
  Mesh m3 = input;
  mrepair::Gap_closing_sequence<Mesh> s3(m3, tolerance);
  EXPECT_EQ(s3.forward(half), half);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m1));
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(full));
  EXPECT_EQ(shape(m1), shape(full));
  EXPECT_EQ(shape(m1), shape(m3));
  EXPECT_LE(s1.current_distance(), d);
  EXPECT_LT(border_edges(m1), border_edges(input));
}

// all the way back gives the input, all the way forward again the closure
TYPED_TEST(Gap_sequence, backward_then_forward_restores_the_mesh)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(two_gaps());
  const auto input = shape(m);
  mrepair::Gap_closing_sequence<Mesh> s(m, tolerance);
  s.forward_to_distance(tolerance);
  const auto closed = shape(m);
  const std::size_t n = s.size();
  ASSERT_GT(n, 0u);
  EXPECT_NE(closed, input);
  EXPECT_EQ(s.backward(n), n);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(shape(m), input);
  EXPECT_EQ(s.forward(n), n);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(shape(m), closed);
  EXPECT_EQ(s.size(), n);  // replayed, nothing new recorded
  s.go_to(n / 3);
  s.go_to(n);
  EXPECT_EQ(shape(m), closed);
}

// truncated, altered, foreign or mismatched files are refused with a message; the mesh stays the input
TYPED_TEST(Gap_sequence, corrupt_or_foreign_sequence_is_rejected)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m1 = to_mesh<Mesh>(two_gaps());
  mrepair::Gap_closing_sequence<Mesh> s1(m1, tolerance, MP::gap_fingerprint_input(true));
  s1.forward_to_distance(tolerance);
  const std::string text = saved(s1);
  mrepair::Gap_sequence_file f;
  std::string error;
  // truncations: anywhere, including just before the last newline
  for (std::size_t cut : {std::size_t(0), std::size_t(10), text.size() / 2, text.size() - 30, text.size() - 1}) {
    EXPECT_EQ(read_file(text.substr(0, cut), f, error), mrepair::Status::parse_error) << cut;
    EXPECT_FALSE(error.empty());
  }
  // one digit altered in a contraction: the checksum catches it
  std::string altered = text;
  std::size_t c = altered.find("\nc ") + 5;
  altered[c] = altered[c] == '1' ? '2' : '1';
  EXPECT_EQ(read_file(altered, f, error), mrepair::Status::parse_error);
  EXPECT_NE(error.find("checksum"), std::string::npos) << error;
  // a count beyond the file, another version, another format, trailing data
  std::string big = text;
  big.replace(big.find("contractions ") + 13, 0, "99999");
  EXPECT_EQ(read_file(big, f, error), mrepair::Status::parse_error);
  std::string v2 = text;
  v2[21] = '2';
  EXPECT_EQ(read_file(v2, f, error), mrepair::Status::parse_error);
  EXPECT_NE(error.find("version"), std::string::npos) << error;
  EXPECT_EQ(read_file("OFF\n3 1 0\n", f, error), mrepair::Status::parse_error);
  EXPECT_EQ(read_file(text + "x\n", f, error), mrepair::Status::parse_error);

  // a good file on another mesh (the last patch 0.001 further): refused, mesh untouched
  ASSERT_EQ(read_file(text, f, error), mrepair::Status::ok) << error;
  Mesh m2 = to_mesh<Mesh>(two_gaps(2.026));
  const auto before = shape(m2);
  mrepair::Gap_closing_sequence<Mesh> s2(m2, f.tolerance, MP::gap_fingerprint_input(true));
  EXPECT_EQ(s2.replay(f, error), mrepair::Status::invalid_parameter);
  EXPECT_NE(error.find("another mesh"), std::string::npos) << error;
  EXPECT_EQ(shape(m2), before);
  // the same mesh with another region: refused
  Mesh m3 = to_mesh<Mesh>(two_gaps());
  auto sel = get(CGAL::dynamic_vertex_property_t<bool>(), m3);
  for (auto v : vertices(m3)) put(sel, v, get(CGAL::vertex_point, m3, v).x() < 1.5);
  mrepair::Gap_closing_sequence<Mesh> s3(m3, f.tolerance,
                                         MP::gap_vertex_selection(sel, MP::gap_fingerprint_input(true)));
  EXPECT_EQ(s3.replay(f, error), mrepair::Status::invalid_parameter);
  EXPECT_NE(error.find("region"), std::string::npos) << error;
  EXPECT_EQ(s3.position(), 0u);
}

// a region around the first gap closes it and leaves the second one open
TYPED_TEST(Gap_sequence, region_keeps_gaps_outside_open)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(two_gaps());
  const std::size_t first = seam_border_edges(m, 0.95, 1.06), second = seam_border_edges(m, 1.96, 2.07);
  ASSERT_EQ(first, 30u);
  ASSERT_EQ(second, 40u);
  auto sel = get(CGAL::dynamic_vertex_property_t<bool>(), m);
  for (auto v : vertices(m)) put(sel, v, get(CGAL::vertex_point, m, v).x() < 1.5);
  const auto before = shape(m);
  mrepair::Gap_closing_result r = mrepair::close_gaps(m, tolerance, MP::gap_vertex_selection(sel));
  ASSERT_EQ(r.status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(seam_border_edges(m, 0.95, 1.06), 0u);
  EXPECT_EQ(seam_border_edges(m, 1.96, 2.07), second);
  // nothing outside the region moved: every vertex right of x = 1.5 is where it was
  {
    std::vector<std::array<double, 3>> outside;
    for (const auto& p : before.first)
      if (p[0] > 1.5) outside.push_back(p);
    const auto after = shape(m);
    ASSERT_FALSE(outside.empty());
    EXPECT_TRUE(std::includes(after.first.begin(), after.first.end(), outside.begin(), outside.end()));
  }

  // the same with faces: those with a vertex right of x = 1.5 only
  Mesh f = to_mesh<Mesh>(two_gaps());
  auto fsel = get(CGAL::dynamic_face_property_t<bool>(), f);
  for (auto fd : faces(f)) {
    bool right = false;
    for (auto v : CGAL::vertices_around_face(halfedge(fd, f), f)) right = right || get(CGAL::vertex_point, f, v).x() > 1.5;
    put(fsel, fd, right);
  }
  r = mrepair::close_gaps(f, tolerance, MP::gap_face_selection(fsel));
  ASSERT_EQ(r.status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(f));
  EXPECT_EQ(seam_border_edges(f, 0.95, 1.06), first);
  EXPECT_EQ(seam_border_edges(f, 1.96, 2.07), 0u);
}

#ifdef MREPAIR_CLI
namespace {

std::string slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// the meshes of two files as shapes (the order of faces may differ after stepping back)
std::pair<std::vector<std::array<double, 3>>, std::vector<std::array<double, 9>>> file_shape(const std::string& path)
{
  Surface_mesh m;
  EXPECT_EQ(mrepair::read_polygon_mesh(path, m).status, mrepair::Status::ok) << path;
  return shape(m);
}

int run(const std::string& args)
{
  std::string cmd = std::string(MREPAIR_CLI) + " close-gaps " + args + " --quiet > /dev/null 2>&1";
  int s = std::system(cmd.c_str());
  return WIFEXITED(s) ? WEXITSTATUS(s) : -1;
}

std::string write_input(const std::string& name, const Soup& s)
{
  const std::string path = ::testing::TempDir() + name;
  std::ofstream f(path);
  f.precision(17);
  f << "OFF\n" << s.points.size() << " " << s.polygons.size() << " 0\n";
  for (const Point& p : s.points) f << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const Polygon& q : s.polygons) f << "3 " << q[0] << " " << q[1] << " " << q[2] << "\n";
  return path;
}

} // namespace

// --save-sequence / --load-sequence / --to-distance / --steps / --profile-table
TEST(Gap_sequence_cli, save_load_distance_steps_and_profile)
{
  if (!std::ifstream(MREPAIR_CLI)) GTEST_SKIP() << "mrepair not built";
  const std::string dir = ::testing::TempDir();
  const std::string in = write_input("gapseq_in.off", two_gaps());
  const std::string seq = dir + "gapseq.seq", out1 = dir + "gapseq_1.off", out2 = dir + "gapseq_2.off",
                    out3 = dir + "gapseq_3.off", out4 = dir + "gapseq_4.off", csv = dir + "gapseq.csv";
  ASSERT_EQ(run(in + " " + out1 + " --tolerance 0.02 --save-sequence " + seq + " --profile-table " + csv), 0);
  ASSERT_EQ(run(in + " " + out2 + " --load-sequence " + seq), 0);
  EXPECT_EQ(file_shape(out1), file_shape(out2));
  Surface_mesh m;
  ASSERT_EQ(mrepair::read_polygon_mesh(out1, m).status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));

  // the profile: a header, the input row first, boundary edges never growing
  std::istringstream table(slurp(csv));
  std::string line;
  std::getline(table, line);
  EXPECT_EQ(line, "distance,contractions,boundary_edges,boundary_loops,boundary_length");
  std::vector<std::pair<double, std::size_t>> rows;  // (distance, contractions)
  std::size_t last_edges = 0;
  while (std::getline(table, line)) {
    double d = 0, len = 0;
    std::size_t k = 0, e = 0, l = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%zu,%zu,%zu,%lf", &d, &k, &e, &l, &len), 5) << line;
    if (rows.empty()) {
      EXPECT_EQ(k, 0u);
      EXPECT_EQ(e, 160u);
    } else {
      EXPECT_LE(e, last_edges);
    }
    last_edges = e;
    rows.push_back({d, k});
  }
  ASSERT_GE(rows.size(), 3u);

  // a middle row: --to-distance D (from a replay or a fresh run) equals --steps K
  const auto mid = rows[rows.size() / 2];
  char dist[64];
  std::snprintf(dist, sizeof dist, "%.17g", mid.first);
  ASSERT_EQ(run(in + " " + out3 + " --tolerance 0.02 --steps " + std::to_string(mid.second)), 0);
  ASSERT_EQ(run(in + " " + out4 + " --load-sequence " + seq + " --to-distance " + dist), 0);
  EXPECT_EQ(file_shape(out3), file_shape(out4));
  ASSERT_EQ(run(in + " " + out4 + " --tolerance 0.02 --to-distance " + dist), 0);
  EXPECT_EQ(file_shape(out3), file_shape(out4));
}

// bad sequence files, bad options and another input are errors, not crashes
TEST(Gap_sequence_cli, bad_sequences_and_options_are_refused)
{
  if (!std::ifstream(MREPAIR_CLI)) GTEST_SKIP() << "mrepair not built";
  const std::string dir = ::testing::TempDir();
  const std::string in = write_input("gapseq_bad_in.off", two_gaps());
  const std::string other = write_input("gapseq_bad_other.off", two_gaps(2.026));
  const std::string seq = dir + "gapseq_bad.seq", bad = dir + "gapseq_bad_cut.seq", out = dir + "gapseq_bad.off";
  ASSERT_EQ(run(in + " " + out + " --tolerance 0.02 --save-sequence " + seq), 0);
  const std::string text = slurp(seq);
  { std::ofstream(bad, std::ios::binary) << text.substr(0, text.size() / 2); }
  EXPECT_EQ(run(in + " " + out + " --load-sequence " + bad), 1);
  { std::ofstream(bad, std::ios::binary) << "garbage\n"; }
  EXPECT_EQ(run(in + " " + out + " --load-sequence " + bad), 1);
  EXPECT_EQ(run(in + " " + out + " --load-sequence " + dir + "no_such.seq"), 1);
  EXPECT_EQ(run(other + " " + out + " --load-sequence " + seq), 1);
  EXPECT_EQ(run(in + " " + out + " --load-sequence " + seq + " --box 0,0,-1,1.5,1,1"), 1);  // another region
  EXPECT_EQ(run(in + " " + out + " --load-sequence " + seq + " --tolerance 0.02"), 2);
  EXPECT_EQ(run(in + " " + out + " --tolerance 0.02 --steps 3 --to-distance 0.01"), 2);
  EXPECT_EQ(run(in + " " + out + " --tolerance 0.02 --to-distance 0.5"), 2);
  EXPECT_EQ(run(in + " " + out + " --tolerance 0.02 --steps -1"), 2);
  EXPECT_EQ(run(in + " " + out + " --tolerance 0.02 --box 0,0,0,1"), 2);
  EXPECT_EQ(run(in + " " + out + " --tolerance 0.02 --box 1,0,0,0,1,1"), 2);
  const std::string faces = dir + "gapseq_faces.txt";
  { std::ofstream(faces) << "0 1 2\n999999\n"; }
  EXPECT_EQ(run(in + " " + out + " --tolerance 0.02 --faces " + faces), 1);
  { std::ofstream(faces) << "0 1 x\n"; }
  EXPECT_EQ(run(in + " " + out + " --tolerance 0.02 --faces " + faces), 1);
  EXPECT_EQ(run(in + " " + out + " --tolerance 0.02 --faces " + dir + "no_such_faces.txt"), 1);
}

// --box and --faces close the gaps of the region only
TEST(Gap_sequence_cli, region_options_keep_gaps_outside_open)
{
  if (!std::ifstream(MREPAIR_CLI)) GTEST_SKIP() << "mrepair not built";
  const std::string dir = ::testing::TempDir();
  const Soup s = two_gaps();
  const std::string in = write_input("gapseq_region_in.off", s), out = dir + "gapseq_region.off";
  ASSERT_EQ(run(in + " " + out + " --tolerance 0.02 --box -1,-1,-1,1.5,2,1"), 0);
  Surface_mesh m;
  ASSERT_EQ(mrepair::read_polygon_mesh(out, m).status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(seam_border_edges(m, 0.95, 1.06), 0u);
  EXPECT_EQ(seam_border_edges(m, 1.96, 2.07), 40u);

  // the faces of the third patch and of the middle one's last column
  const std::string faces = dir + "gapseq_region_faces.txt";
  {
    std::ofstream f(faces);
    f << "# faces right of x = 1.5\n";
    for (std::size_t i = 0; i < s.polygons.size(); ++i)
      if (s.points[s.polygons[i][0]].x() > 1.5) f << i << "\n";
  }
  ASSERT_EQ(run(in + " " + out + " --tolerance 0.02 --faces " + faces), 0);
  Surface_mesh m2;
  ASSERT_EQ(mrepair::read_polygon_mesh(out, m2).status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m2));
  EXPECT_EQ(seam_border_edges(m2, 0.95, 1.06), 30u);
  EXPECT_EQ(seam_border_edges(m2, 1.96, 2.07), 0u);
}
#endif

} // namespace gap_sequence_tests
} // namespace
