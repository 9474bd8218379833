// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Tests of mrepair/io.h: exact round trips of every format on both mesh
// types, and every kind of bad file (written here into a temp directory).

#include <mrepair/io.h>

#include "fixtures.h"
#include "cli.h"
#include "cli_io.h"

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <unistd.h>

// A namespace of its own: this file is compiled in one translation unit with
// other test files (a unity build, CMakeLists.txt).
namespace {
namespace io_tests {

namespace {

using namespace mrepair_test;
using mrepair::Io_result;
using mrepair::Status;
namespace fs = std::filesystem;

/// a fresh directory per test program run, removed at exit.
const fs::path& temp_dir()
{
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("mrepair_test_io_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  static struct Cleanup
  {
    ~Cleanup() { std::error_code ec; fs::remove_all(dir, ec); }
  } cleanup;
  return dir;
}

std::string temp_file(const std::string& name) { return (temp_dir() / name).string(); }

/// writes `bytes` to a temp file `name` and returns its path.
std::string write_file(const std::string& name, const std::string& bytes)
{
  std::string path = temp_file(name);
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

std::string read_bytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

template <typename T>
void append_raw(std::string& s, T v, bool big_endian = false)
{
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

struct Read
{
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  Io_result r;
};

Read read(const std::string& path)
{
  Read x;
  x.r = mrepair::read_polygon_soup(path, x.points, x.polygons);
  EXPECT_EQ(x.r.points, x.points.size());
  EXPECT_EQ(x.r.polygons, x.polygons.size());
  return x;
}

/// status of a failure that must leave the outputs empty.
void expect_cleared(const Read& x, Status s)
{
  EXPECT_EQ(x.r.status, s) << x.r.message;
  EXPECT_TRUE(x.points.empty());
  EXPECT_TRUE(x.polygons.empty());
  EXPECT_FALSE(x.r.message.empty());
  EXPECT_EQ(x.r.message.find('\n'), std::string::npos) << "message must be one line";
}

// ---- round trips on both mesh types -----------------------------------------

struct Format
{
  const char* ext;
  bool binary;
};
const Format all_formats[] = {{"off", false}, {"obj", false}, {"ply", false},
                              {"ply", true},  {"stl", false}, {"stl", true}};

template <class C>
class Io_mesh : public ::testing::Test
{};
TYPED_TEST_SUITE(Io_mesh, Mesh_configs);

/// icosphere with float-representable coordinates (binary STL stores floats)
/// that are not short decimals, so that text output must be exact to pass.
/// rounds to float. Through a volatile: GCC 12.2 at -O2 drops the
/// double->float->double round trip of x and y when it SLP-vectorizes
/// `p = Point(float(p.x()), float(p.y()), float(p.z()))` (wrong code, seen here).
double to_float(double v)
{
  volatile float f = static_cast<float>(v);
  return f;
}

Soup float_sphere()
{
  Soup s = icosphere(2, 1.0);
  for (Point& p : s.points) p = Point(to_float(p.x()), to_float(p.y()), to_float(p.z()));
  for (const Point& p : s.points) EXPECT_EQ(static_cast<float>(p.y()), p.y());
  return s;
}

TYPED_TEST(Io_mesh, round_trip_every_format_exactly)
{
  using Mesh = typename TypeParam::Mesh;
  const Soup soup = float_sphere();
  const Mesh mesh = to_mesh<Mesh>(soup);
  for (const Format& f : all_formats) {
    SCOPED_TRACE(std::string(f.ext) + (f.binary ? " binary" : " ascii"));
    const std::string path = temp_file(std::string("rt_mesh.") + f.ext);
    Io_result w = mrepair::write_polygon_mesh(path, mesh, f.binary);
    ASSERT_EQ(w.status, Status::ok) << w.message;
    EXPECT_EQ(w.binary, f.binary);
    EXPECT_EQ(w.points, 162u);
    EXPECT_EQ(w.polygons, 320u);

    Mesh back;
    Io_result r = mrepair::read_polygon_mesh(path, back);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_EQ(r.format, f.ext);
    EXPECT_EQ(r.binary, f.binary);
    EXPECT_TRUE(mrepair_test::valid_polygon_mesh(back));
    EXPECT_EQ(vertices(back).size(), 162u);
    EXPECT_EQ(face_count(back), 320u);

    // faces as cyclic sequences of exact points, compared up to rotation
    auto face_set = [](const Mesh& m) {
      std::multiset<std::vector<std::array<double, 3>>> out;
      for (auto fd : faces(m)) {
        std::vector<std::array<double, 3>> ps;
        for (auto v : CGAL::vertices_around_face(halfedge(fd, m), m)) {
          const auto& p = get(CGAL::vertex_point, m, v);
          ps.push_back({p.x(), p.y(), p.z()});
        }
        std::rotate(ps.begin(), std::min_element(ps.begin(), ps.end()), ps.end());
        out.insert(ps);
      }
      return out;
    };
    EXPECT_TRUE(face_set(mesh) == face_set(back));
    if (std::string(f.ext) != "stl") {
      // indexed formats keep the vertex order too
      auto a = vertices(mesh).begin();
      for (auto v : vertices(back)) {
        EXPECT_EQ(get(CGAL::vertex_point, back, v), get(CGAL::vertex_point, mesh, *a));
        ++a;
      }
    }
  }
}

TYPED_TEST(Io_mesh, doubles_round_trip_exactly_in_text_and_binary_ply)
{
  using Mesh = typename TypeParam::Mesh;
  Soup soup = icosphere(1, 1.0);
  // coordinates that need all 17 significant digits, and tiny/huge exponents
  soup.points[0] = Point(0.1 + 0.2, -1e-300, 1.0 / 3.0);
  soup.points[1] = Point(123456789.12345678, 5e-324, -2.2250738585072014e-308);
  const Mesh mesh = to_mesh<Mesh>(soup);
  for (const Format& f : all_formats) {
    if (std::string(f.ext) == "stl") continue;  // float32 format
    SCOPED_TRACE(std::string(f.ext) + (f.binary ? " binary" : " ascii"));
    const std::string path = temp_file(std::string("rt_double.") + f.ext);
    ASSERT_EQ(mrepair::write_polygon_mesh(path, mesh, f.binary).status, Status::ok);
    Mesh back;
    ASSERT_EQ(mrepair::read_polygon_mesh(path, back).status, Status::ok);
    ASSERT_EQ(vertices(back).size(), soup.points.size());
    std::size_t i = 0;
    for (auto v : vertices(back)) {
      const Point& p = get(CGAL::vertex_point, back, v);
      EXPECT_EQ(p, soup.points[i]) << "point " << i;
      ++i;
    }
  }
}

TYPED_TEST(Io_mesh, quads_preserved_in_off_obj_ply)
{
  using Mesh = typename TypeParam::Mesh;
  const Mesh cube = to_mesh<Mesh>(mrepair_test::cube(2.0, true));
  for (const Format& f : all_formats) {
    SCOPED_TRACE(std::string(f.ext) + (f.binary ? " binary" : " ascii"));
    const std::string path = temp_file(std::string("quads.") + f.ext);
    ASSERT_EQ(mrepair::write_polygon_mesh(path, cube, f.binary).status, Status::ok);
    Mesh back;
    Io_result r = mrepair::read_polygon_mesh(path, back);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_EQ(vertices(back).size(), 8u);
    if (std::string(f.ext) == "stl") {
      EXPECT_EQ(face_count(back), 12u);  // fan-triangulated
      EXPECT_TRUE(CGAL::is_triangle_mesh(back));
    } else {
      EXPECT_EQ(face_count(back), 6u);
      for (auto fd : faces(back)) EXPECT_EQ(CGAL::degree(fd, back), 4u);
    }
    EXPECT_TRUE(CGAL::is_closed(back));
  }
}

TYPED_TEST(Io_mesh, read_mesh_refuses_bad_soups_and_leaves_mesh_empty)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(mrepair_test::cube());
  // three triangles on edge 0-1: a non-manifold edge
  std::string fin = write_file("fin.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n"
                                          "3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  Io_result r = mrepair::read_polygon_mesh(fin, m);
  EXPECT_EQ(r.status, Status::non_manifold_input);
  EXPECT_NE(r.message.find("mrepair soup"), std::string::npos) << r.message;
  EXPECT_EQ(vertices(m).size(), 0u);
  EXPECT_EQ(face_count(m), 0u);

  m = to_mesh<Mesh>(mrepair_test::cube());
  std::string nan = write_file("nan_mesh.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(mrepair::read_polygon_mesh(nan, m).status, Status::non_finite_input);
  EXPECT_EQ(vertices(m).size(), 0u);

  std::string bad = write_file("bad_mesh.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  EXPECT_EQ(mrepair::read_polygon_mesh(bad, m).status, Status::invalid_index);
  EXPECT_EQ(vertices(m).size(), 0u);

  EXPECT_EQ(mrepair::read_polygon_mesh(temp_file("missing.ply"), m).status, Status::io_error);
  EXPECT_EQ(vertices(m).size(), 0u);
}

TYPED_TEST(Io_mesh, writes_surface_mesh_with_removed_elements)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(2, 2));
  // remove one corner face (and its now isolated corner vertex): index gaps
  // in Surface_mesh until garbage collection
  auto f0 = *faces(m).begin();
  CGAL::Euler::remove_face(halfedge(f0, m), m);
  const std::string path = temp_file("removed.off");
  Io_result w = mrepair::write_polygon_mesh(path, m);
  ASSERT_EQ(w.status, Status::ok) << w.message;
  EXPECT_EQ(w.polygons, 7u);
  Mesh back;
  ASSERT_EQ(mrepair::read_polygon_mesh(path, back).status, Status::ok);
  EXPECT_EQ(face_count(back), 7u);
  EXPECT_EQ(vertices(back).size(), vertices(m).size());
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(back));
}

// A Surface_mesh without removed elements is written in place, a Polyhedron
// or a mesh with removed elements through a copy: the bytes are those of its
// soup written in face order, in every format, and so are the counts.
TYPED_TEST(Io_mesh, mesh_writes_the_bytes_of_its_soup)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = icosphere(2, 1.0);
  s.points[7] = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);  // counted, written as nan
  const Mesh m = to_mesh<Mesh>(s);
  // the mesh's own soup: its points in vertex order, its faces' vertices as
  // vertices_around_face lists them
  Soup own;
  std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, std::size_t> id;
  for (auto v : vertices(m)) {
    id[v] = own.points.size();
    own.points.push_back(get(CGAL::vertex_point, m, v));
  }
  for (auto f : faces(m)) {
    Polygon p;
    for (auto v : CGAL::vertices_around_face(halfedge(f, m), m)) p.push_back(id[v]);
    own.polygons.push_back(p);
  }
  for (const Format& f : all_formats) {
    SCOPED_TRACE(std::string(f.ext) + (f.binary ? " binary" : " ascii"));
    const std::string a = temp_file(std::string("mesh_view.") + f.ext),
                      b = temp_file(std::string("mesh_soup.") + f.ext);
    const Io_result wa = mrepair::write_polygon_mesh(a, m, f.binary);
    const Io_result wb = mrepair::write_polygon_soup(b, own.points, own.polygons, f.binary);
    ASSERT_EQ(wa.status, Status::ok) << wa.message;
    ASSERT_EQ(wb.status, Status::ok) << wb.message;
    EXPECT_EQ(wa.points, wb.points);
    EXPECT_EQ(wa.polygons, wb.polygons);
    EXPECT_EQ(wa.non_finite_points, 1u);
    EXPECT_EQ(wa.non_finite_points, wb.non_finite_points);
    EXPECT_EQ(read_bytes(a), read_bytes(b));
  }
}

// The one halfedge builder (internal/halfedge_builder.h) through the file
// reader's adapter: a quad and four triangles around an interior vertex, a
// point no polygon uses. Unused points get no vertex, a face's halfedge is
// its first corner's, a vertex's the last corner entering it, or on the
// border the border halfedge entering it.
TYPED_TEST(Io_mesh, halfedge_builder_wires_the_corners_in_order)
{
  using Mesh = typename TypeParam::Mesh;
  namespace IO = mrepair::internal::io;
  const std::vector<Point> P = {Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0), Point(0, 1, 0),
                                Point(1, 1, 0), Point(2, 1, 0), Point(1, 2, 0), Point(5, 5, 5)};
  const std::vector<std::vector<std::int64_t>> polygons = {{0, 1, 4, 3}, {1, 2, 5}, {1, 5, 4}, {3, 4, 6}, {4, 5, 6}};
  std::vector<std::int64_t> indices;
  std::vector<std::size_t> starts = {0};
  for (const auto& p : polygons) {
    indices.insert(indices.end(), p.begin(), p.end());
    starts.push_back(indices.size());
  }
  IO::Soup_topology t;
  std::string why;
  ASSERT_TRUE(t.compute(P.size(), indices.data(), starts.data(), polygons.size(), why)) << why;
  Mesh m;
  auto vpm = get(CGAL::vertex_point, m);
  IO::build_mesh(t, P.size(), indices.data(), starts.data(), polygons.size(), m,
                 [&](auto v, std::size_t i) { put(vpm, v, P[i]); });
  ASSERT_TRUE(CGAL::is_valid_polygon_mesh(m));
  EXPECT_EQ(vertices(m).size(), 7u);  // point 7 is not used
  EXPECT_EQ(faces(m).size(), 5u);
  EXPECT_EQ(edges(m).size(), 11u);
  auto index_of = [&](typename boost::graph_traits<Mesh>::vertex_descriptor v) {
    return std::size_t(std::find(P.begin(), P.end(), get(vpm, v)) - P.begin());
  };
  std::size_t f_index = 0;
  for (auto f : faces(m)) {
    const auto& p = polygons[f_index++];
    const auto h = halfedge(f, m);
    EXPECT_EQ(index_of(source(h, m)), std::size_t(p[0]));
    EXPECT_EQ(index_of(target(h, m)), std::size_t(p[1]));
    EXPECT_EQ(CGAL::halfedges_around_face(h, m).size(), p.size());
  }
  for (auto v : vertices(m)) {
    const auto h = halfedge(v, m);
    EXPECT_EQ(target(h, m), v);
    if (index_of(v) == 4) {  // interior: the last corner entering it, 6 -> 4
      EXPECT_FALSE(is_border(h, m));
      EXPECT_EQ(index_of(source(h, m)), 6u);
    } else {
      EXPECT_TRUE(is_border(h, m)) << index_of(v);
    }
  }
}

// ---- soups ---------------------------------------------------------------------

// The writers' validating pass runs in chunks: the counts are those of the
// whole soup and the message names the first bad polygon, whatever chunk
// holds it.
TEST(Io_soup, write_names_the_first_of_many_invalid_polygons)
{
  const Soup g = grid(150, 150);  // 45,000 triangles: several chunks
  ASSERT_GT(g.polygons.size(), 40000u);
  Soup s = g;
  for (std::size_t f : {std::size_t(20000), std::size_t(33333), std::size_t(44999)})
    s.polygons[f][2] = s.points.size() + f;
  const std::string path = temp_file("many_bad.off");
  const Io_result w = mrepair::write_polygon_soup(path, s.points, s.polygons);
  EXPECT_EQ(w.status, Status::invalid_index);
  EXPECT_EQ(w.invalid_polygons, 3u);
  EXPECT_NE(w.message.find("first is polygon 20000"), std::string::npos) << w.message;
  EXPECT_FALSE(fs::exists(path));
}

TEST(Io_soup, round_trip_soup_every_format)
{
  const Soup s = mrepair_test::cube(1.5, true);
  for (const Format& f : all_formats) {
    SCOPED_TRACE(std::string(f.ext) + (f.binary ? " binary" : " ascii"));
    const std::string path = temp_file(std::string("soup.") + f.ext);
    Io_result w = mrepair::write_polygon_soup(path, s.points, s.polygons, f.binary);
    ASSERT_EQ(w.status, Status::ok) << w.message;
    Read x = read(path);
    ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
    EXPECT_EQ(x.r.binary, f.binary);
    if (std::string(f.ext) == "stl") {
      EXPECT_EQ(x.polygons.size(), 12u);
      EXPECT_EQ(x.points.size(), 8u);  // corners merged
    } else {
      EXPECT_EQ(x.points, s.points);
      EXPECT_EQ(x.polygons, s.polygons);
    }
  }
}

TEST(Io_soup, binary_flag_ignored_for_text_only_formats)
{
  const Soup s = mrepair_test::cube();
  Io_result w = mrepair::write_polygon_soup(temp_file("t.obj"), s.points, s.polygons, true);
  EXPECT_EQ(w.status, Status::ok);
  EXPECT_FALSE(w.binary);
  EXPECT_NE(w.message.find("ASCII"), std::string::npos);
}

TEST(Io_soup, write_refuses_invalid_polygons)
{
  Soup s = mrepair_test::cube();
  s.polygons[3][1] = 8;  // one past the end
  const std::string path = temp_file("refused.off");
  Io_result w = mrepair::write_polygon_soup(path, s.points, s.polygons);
  EXPECT_EQ(w.status, Status::invalid_index);
  EXPECT_EQ(w.invalid_polygons, 1u);
  EXPECT_FALSE(fs::exists(path));

  Soup t = mrepair_test::cube();
  t.polygons.push_back({0, 1});  // STL cannot hold it, OFF can
  EXPECT_EQ(mrepair::write_polygon_soup(temp_file("two.stl"), t.points, t.polygons).status,
            Status::invalid_index);
  EXPECT_EQ(mrepair::write_polygon_soup(temp_file("two.off"), t.points, t.polygons).status,
            Status::ok);
  Read x = read(temp_file("two.off"));
  EXPECT_EQ(x.r.status, Status::invalid_index);
  EXPECT_EQ(x.r.invalid_polygons, 1u);
  EXPECT_EQ(x.polygons.back(), (Polygon{0, 1}));
}

TEST(Io_soup, write_errors)
{
  const Soup s = mrepair_test::cube();
  Io_result w = mrepair::write_polygon_soup(temp_file("no_such_dir/x.off"), s.points, s.polygons);
  EXPECT_EQ(w.status, Status::io_error);
  EXPECT_FALSE(w.message.empty());
  w = mrepair::write_polygon_soup(temp_file("x.vrml"), s.points, s.polygons);
  EXPECT_EQ(w.status, Status::unsupported_format);
}

TEST(Io_soup, writes_non_finite_points_and_reads_them_back)
{
  Soup s = mrepair_test::cube();
  s.points[2] = Point(std::nan(""), 0, HUGE_VAL);
  for (const char* ext : {"off", "obj", "ply"}) {
    const std::string path = temp_file(std::string("nonfinite.") + ext);
    Io_result w = mrepair::write_polygon_soup(path, s.points, s.polygons);
    ASSERT_EQ(w.status, Status::ok);
    EXPECT_EQ(w.non_finite_points, 1u);
    Read x = read(path);
    EXPECT_EQ(x.r.status, Status::non_finite_input) << ext;
    EXPECT_EQ(x.r.non_finite_points, 1u);
    ASSERT_EQ(x.points.size(), 8u);
    EXPECT_TRUE(std::isnan(x.points[2].x()));
    EXPECT_EQ(x.points[2].z(), HUGE_VAL);
  }
}

// ---- OFF variants and bad OFF files ---------------------------------------------

TEST(Io_off, variants_comments_and_extra_fields)
{
  // COFF with RGBA colors, comments, face colors, counts on the keyword line
  Read x = read(write_file("c.off", "COFF 4 2 0 # counts here\n"
                                    "# a comment line\n"
                                    "0 0 0 255 0 0 255\n"
                                    "1 0 0 0 255 0 255\n\n"
                                    "0 1 0 0 0 255 255  # trailing comment\n"
                                    "1 1 0 1 1 1 1\n"
                                    "3 0 1 2 255 0 0\n"
                                    "3 2 1 3\n"));
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.points, (std::vector<Point>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}));
  EXPECT_EQ(x.polygons, (std::vector<Polygon>{{0, 1, 2}, {2, 1, 3}}));

  // NOFF with normals, STCNOFF with texture + color + normal
  x = read(write_file("n.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n"));
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.points[1], Point(1, 0, 0));
  x = read(write_file("st.off",
                      "STCNOFF\n3 1 0\n0 0 0 .1 .2 .3 0 0 1 1 0 0\n1 0 0 0 1 0 0 1 1 1 1 1\n"
                      "0 1 0 1 1 1 1 1 1 1 1 1\n3 0 1 2\n"));
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.points[2], Point(0, 1, 0));

  // homogeneous 4OFF: divided by w
  x = read(write_file("h.off", "4OFF\n3 1 0\n2 4 6 2\n1 0 0 1\n0 4 0 4\n3 0 1 2\n"));
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.points[0], Point(1, 2, 3));
  EXPECT_EQ(x.points[2], Point(0, 1, 0));

  // no keyword at all, CRLF line ends, '+' signs and exponents
  x = read(write_file("nokw.off", "3 1 0\r\n+1e0 0 0\r\n0 1.5E+0 0\r\n0 0 -2.\r\n3 0 1 2\r\n"));
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.points[0], Point(1, 0, 0));
  EXPECT_EQ(x.points[1], Point(0, 1.5, 0));
  EXPECT_EQ(x.points[2], Point(0, 0, -2));
  EXPECT_EQ(x.r.format, "off");
}

TEST(Io_off, uppercase_extension)
{
  Read x = read(write_file("UPPER.OFF", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.r.format, "off");
}

TEST(Io_off, empty_and_missing_and_unsupported)
{
  for (const char* ext : {"off", "obj", "ply", "stl"}) {
    SCOPED_TRACE(ext);
    expect_cleared(read(write_file(std::string("empty.") + ext, "")), Status::empty_input);
    expect_cleared(read(write_file(std::string("blank.") + ext, "  \n\n")),
                   std::string(ext) == "off" || std::string(ext) == "obj" ? Status::empty_input
                                                                          : Status::parse_error);
    expect_cleared(read(temp_file(std::string("missing.") + ext)), Status::io_error);
  }
  expect_cleared(read(write_file("zero.off", "OFF\n0 0 0\n")), Status::empty_input);
  expect_cleared(read(write_file("points_only.off", "OFF\n1 0 0\n0 0 0\n")), Status::empty_input);
  expect_cleared(read(write_file("x.wrl", "#VRML\n")), Status::unsupported_format);
  expect_cleared(read(write_file("noext", "OFF\n")), Status::unsupported_format);
  fs::create_directories(temp_dir() / "dir.off");
  expect_cleared(read(temp_file("dir.off")), Status::io_error);
}

TEST(Io_off, truncated_files)
{
  Read x = read(write_file("tv.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n"));
  expect_cleared(x, Status::parse_error);
  EXPECT_NE(x.r.message.find("2 of 4 vertices"), std::string::npos) << x.r.message;
  EXPECT_EQ(x.r.message.find(temp_file("tv.off")), 0u) << "message names the file";

  x = read(write_file("tf.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  expect_cleared(x, Status::parse_error);
  EXPECT_NE(x.r.message.find("1 of 2 faces"), std::string::npos) << x.r.message;

  x = read(write_file("tfi.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n"));
  expect_cleared(x, Status::parse_error);
  EXPECT_NE(x.r.message.find(":6:"), std::string::npos) << x.r.message;

  x = read(write_file("thdr.off", "OFF\n3\n"));
  expect_cleared(x, Status::parse_error);
}

TEST(Io_off, garbage_tokens_name_the_line)
{
  Read x = read(write_file("g1.off", "OFF\n3 1 0\n0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n"));
  expect_cleared(x, Status::parse_error);
  EXPECT_NE(x.r.message.find(":4:"), std::string::npos) << x.r.message;
  EXPECT_NE(x.r.message.find("'abc'"), std::string::npos) << x.r.message;

  x = read(write_file("g2.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 x 2\n"));
  expect_cleared(x, Status::parse_error);
  EXPECT_NE(x.r.message.find(":6:"), std::string::npos) << x.r.message;

  expect_cleared(read(write_file("g3.off", "OFFX\n3 1 0\n")), Status::parse_error);
  expect_cleared(read(write_file("g4.off", "hello world\n")), Status::parse_error);
  expect_cleared(read(write_file("g5.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n")),
                 Status::parse_error);
  expect_cleared(read(write_file("g6.off", "OFF\n-3 1 0\n")), Status::parse_error);
  expect_cleared(read(write_file("g7.off", "OFF BINARY\n")), Status::unsupported_format);
  expect_cleared(read(write_file("g8.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n")),
                 Status::parse_error);
}

TEST(Io_off, absurd_counts_do_not_allocate)
{
  Read x = read(write_file("huge.off", "OFF\n1000000000000000000 1000000000000000000 0\n0 0 0\n"));
  expect_cleared(x, Status::parse_error);
  x = read(write_file("huge2.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n999999999999 0 1 2\n"));
  expect_cleared(x, Status::parse_error);
  // too large for int64: not a count
  expect_cleared(read(write_file("huge3.off", "OFF\n99999999999999999999999 1 0\n")),
                 Status::parse_error);
}

TEST(Io_off, non_finite_points_are_loaded_and_counted)
{
  Read x = read(write_file("nan.off", "OFF\n4 1 0\n0 0 0\nnan 0 0\n0 1 inf\n-INF 1e999 0\n3 0 1 2\n"));
  EXPECT_EQ(x.r.status, Status::non_finite_input);
  EXPECT_EQ(x.r.non_finite_points, 3u);
  EXPECT_EQ(x.r.invalid_polygons, 0u);
  ASSERT_EQ(x.points.size(), 4u);
  ASSERT_EQ(x.polygons.size(), 1u);
  EXPECT_TRUE(std::isnan(x.points[1].x()));
  EXPECT_EQ(x.points[2].z(), HUGE_VAL);
  EXPECT_EQ(x.points[3].x(), -HUGE_VAL);
  EXPECT_EQ(x.points[3].y(), HUGE_VAL);  // overflow reads as inf
  EXPECT_NE(x.r.message.find(":4:"), std::string::npos) << x.r.message;
}

TEST(Io_off, invalid_indices_are_kept_and_counted)
{
  Read x = read(write_file("idx.off", "OFF\n3 5 0\n0 0 0\n1 0 0\n0 1 0\n"
                                      "3 0 1 2\n3 0 1 5\n3 -1 1 2\n2 0 1\n0\n"));
  EXPECT_EQ(x.r.status, Status::invalid_index);
  EXPECT_EQ(x.r.invalid_polygons, 4u);
  ASSERT_EQ(x.polygons.size(), 5u);
  EXPECT_EQ(x.polygons[0], (Polygon{0, 1, 2}));
  EXPECT_EQ(x.polygons[1], (Polygon{0, 1, 5}));
  EXPECT_EQ(x.polygons[2][0], static_cast<std::size_t>(-1));  // wraps: >= points.size()
  EXPECT_EQ(x.polygons[3], (Polygon{0, 1}));
  EXPECT_TRUE(x.polygons[4].empty());
  EXPECT_NE(x.r.message.find(":7:"), std::string::npos) << "first bad polygon's line: " << x.r.message;

  // NaN and bad indices together: invalid_index, both counted
  x = read(write_file("both.off", "OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"));
  EXPECT_EQ(x.r.status, Status::invalid_index);
  EXPECT_EQ(x.r.non_finite_points, 1u);
  EXPECT_EQ(x.r.invalid_polygons, 1u);

  // a signed index type keeps negative indices negative
  std::vector<Point> pts;
  std::vector<std::vector<int>> polys;
  Io_result r = mrepair::read_polygon_soup(temp_file("idx.off"), pts, polys);
  EXPECT_EQ(r.status, Status::invalid_index);
  EXPECT_EQ(polys[2][0], -1);
}

// All triangles: fixed arrays holding what read_polygon_soup reads, statuses
// and counts included; one polygon of another size: the polygon vectors.
TEST(Io_soup, triangles_read_into_arrays_else_polygons)
{
  using Triangle = std::array<std::size_t, 3>;
  auto both = [](const std::string& path, bool expect_triangles) {
    std::vector<Point> p1, p2;
    std::vector<Polygon> polys, other;
    std::vector<Triangle> tris;
    bool all = !expect_triangles;
    const Io_result a = mrepair::read_polygon_soup(path, p1, polys);
    const Io_result b = mrepair::read_polygon_or_triangle_soup(path, p2, other, tris, all);
    EXPECT_EQ(all, expect_triangles) << path;
    EXPECT_EQ(a.status, b.status) << path;
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.polygons, b.polygons);
    EXPECT_EQ(a.non_finite_points, b.non_finite_points);
    EXPECT_EQ(a.invalid_polygons, b.invalid_polygons);
    EXPECT_EQ(a.message, b.message);
    ASSERT_EQ(p1.size(), p2.size());
    for (std::size_t i = 0; i < p1.size(); ++i)
      EXPECT_TRUE(p1[i] == p2[i] || std::isnan(p1[i].x())) << i;
    if (expect_triangles) {
      EXPECT_TRUE(other.empty());
      ASSERT_EQ(tris.size(), polys.size());
      for (std::size_t f = 0; f < tris.size(); ++f)
        EXPECT_EQ(Polygon(tris[f].begin(), tris[f].end()), polys[f]) << f;
    } else {
      EXPECT_TRUE(tris.empty());
      EXPECT_EQ(other, polys);
    }
  };
  both(write_file("tris.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 2 1 3\n"), true);
  // an out-of-range and a negative index, and a NaN point, stay as read
  both(write_file("tris_bad.off", "OFF\n3 3 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 7\n3 -1 1 2\n"),
       true);
  both(write_file("quad.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n4 0 1 3 2\n"), false);
  both(write_file("pair.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n2 0 1\n"), false);
  // nothing read: both empty, the same error
  both(write_file("empty.off", ""), false);
  std::vector<Point> p;
  std::vector<Polygon> polys;
  std::vector<Triangle> tris;
  bool all = true;
  const Io_result r = mrepair::read_polygon_or_triangle_soup(temp_file("missing.off"), p, polys, tris, all);
  EXPECT_EQ(r.status, Status::io_error);
  EXPECT_FALSE(all);
  EXPECT_TRUE(p.empty() && polys.empty() && tris.empty());
}

// ---- OBJ ----------------------------------------------------------------------

TEST(Io_obj, corner_forms_and_relative_indices)
{
  Read x = read(write_file("rel.obj", "# comment\nmtllib x.mtl\no thing\n"
                                      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1.0\n"
                                      "vt 0 0\nvn 0 0 1\ns off\nusemtl m\n"
                                      "f -4 -3 -2\n"
                                      "f 1/1/1 3//1 4/1\n"
                                      "v 2 0 0\n"
                                      "f -4 -1 -3 # -1 is the fifth vertex now\n"
                                      "l 1 2\n"
                                      "f 1 2 3 4\n"));
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.points.size(), 5u);
  EXPECT_EQ(x.polygons, (std::vector<Polygon>{{0, 1, 2}, {0, 2, 3}, {1, 4, 2}, {0, 1, 2, 3}}));
  EXPECT_FALSE(x.r.binary);
  EXPECT_EQ(x.r.format, "obj");
}

TEST(Io_obj, bad_indices_and_garbage)
{
  Read x = read(write_file("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                      "f 0 1 2\nf -4 1 2\nf 1 2 4\nf 1 2 3\n"));
  EXPECT_EQ(x.r.status, Status::invalid_index);
  EXPECT_EQ(x.r.invalid_polygons, 3u);
  ASSERT_EQ(x.polygons.size(), 4u);
  EXPECT_EQ(x.polygons[2], (Polygon{0, 1, 3}));  // forward reference past the end
  EXPECT_NE(x.r.message.find(":4:"), std::string::npos) << x.r.message;

  Read g = read(write_file("garbage.obj", "v 0 0 0\nv 1 zero 0\n"));
  expect_cleared(g, Status::parse_error);
  EXPECT_NE(g.r.message.find(":2:"), std::string::npos) << g.r.message;
  expect_cleared(read(write_file("short.obj", "v 0 0\nf 1 1 1\n")), Status::parse_error);
  expect_cleared(read(write_file("badf.obj", "v 0 0 0\nf 1 a 1\n")), Status::parse_error);
  expect_cleared(read(write_file("nofaces.obj", "v 0 0 0\nv 1 0 0\n")), Status::empty_input);
}

// ---- PLY ----------------------------------------------------------------------

/// a PLY with extra properties and elements, in the requested encoding:
/// 4 points (x float, nx float, red uchar, y double, z short... as the types
/// below), 2 faces (quad + triangle) with a trailing float list, one edge element.
std::string fancy_ply(const std::string& format, bool big_endian)
{
  std::string h = "ply\nformat " + format +
                  " 1.0\ncomment fancy\nobj_info test\n"
                  "element vertex 4\nproperty float x\nproperty float nx\nproperty uchar red\n"
                  "property double y\nproperty list uchar int junk\nproperty short z\n"
                  "element face 2\nproperty uchar flags\nproperty list uint16 uint vertex_index\n"
                  "property list uchar float texcoord\n"
                  "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
                  "end_header\n";
  const float xs[4] = {0.5f, 1.25f, -3.0f, 7.0f};
  const double ys[4] = {0.1, 0.2, 0.3, 1e10};
  const short zs[4] = {-1, 2, 300, 4};
  std::string b = h;
  if (format == "ascii") {
    b += "0.5 0 255 0.1 2 7 8 -1\n1.25 0 0 0.2 0 2\n-3 0 1 0.3 1 5 300\n7 1 2 1e10 0 4\n";
    b += "9 4 0 1 2 3 2 0.5 0.5\n0 3 1 3 2 0\n";
    b += "0 1\n";
    return b;
  }
  for (int i = 0; i < 4; ++i) {
    append_raw<float>(b, xs[i], big_endian);
    append_raw<float>(b, 0.f, big_endian);
    append_raw<unsigned char>(b, 255, big_endian);
    append_raw<double>(b, ys[i], big_endian);
    append_raw<unsigned char>(b, static_cast<unsigned char>(i % 3), big_endian);
    for (int k = 0; k < i % 3; ++k) append_raw<int>(b, 77, big_endian);
    append_raw<short>(b, zs[i], big_endian);
  }
  append_raw<unsigned char>(b, 9, big_endian);
  append_raw<std::uint16_t>(b, 4, big_endian);
  for (unsigned v : {0u, 1u, 2u, 3u}) append_raw<unsigned>(b, v, big_endian);
  append_raw<unsigned char>(b, 2, big_endian);
  append_raw<float>(b, .5f, big_endian);
  append_raw<float>(b, .5f, big_endian);
  append_raw<unsigned char>(b, 0, big_endian);
  append_raw<std::uint16_t>(b, 3, big_endian);
  for (unsigned v : {1u, 3u, 2u}) append_raw<unsigned>(b, v, big_endian);
  append_raw<unsigned char>(b, 0, big_endian);
  append_raw<int>(b, 0, big_endian);
  append_raw<int>(b, 1, big_endian);
  return b;
}

TEST(Io_ply, all_encodings_with_extra_properties_and_elements)
{
  struct Case
  {
    const char* format;
    bool big;
    bool binary;
  };
  for (Case c : {Case{"ascii", false, false}, Case{"binary_little_endian", false, true},
                 Case{"binary_big_endian", true, true}}) {
    SCOPED_TRACE(c.format);
    std::string bytes = fancy_ply(c.format, c.big);
    Read x = read(write_file(std::string("fancy_") + c.format + ".ply", bytes));
    ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
    EXPECT_EQ(x.r.binary, c.binary);
    EXPECT_EQ(x.points, (std::vector<Point>{{0.5, 0.1, -1}, {1.25, 0.2, 2}, {-3, 0.3, 300}, {7, 1e10, 4}}));
    EXPECT_EQ(x.polygons, (std::vector<Polygon>{{0, 1, 2, 3}, {1, 3, 2}}));

    if (c.binary) {
      // every truncation is a clean parse error, never a crash
      std::size_t header = bytes.find("end_header\n") + 11;
      for (std::size_t len = header; len < bytes.size(); ++len) {
        Read t = read(write_file("trunc.ply", bytes.substr(0, len)));
        EXPECT_EQ(t.r.status, Status::parse_error) << len;
        EXPECT_TRUE(t.points.empty());
      }
    }
  }
}

TEST(Io_ply, bad_headers_and_counts)
{
  expect_cleared(read(write_file("nomagic.ply", "plx\nformat ascii 1.0\nend_header\n")),
                 Status::parse_error);
  expect_cleared(read(write_file("noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n")),
                 Status::parse_error);
  expect_cleared(read(write_file("fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n")),
                 Status::unsupported_format);
  expect_cleared(read(write_file("noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                              "property float x\nproperty float y\nend_header\n0 0\n")),
                 Status::parse_error);
  expect_cleared(read(write_file("badtype.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                                "property float128 x\nend_header\n")),
                 Status::parse_error);
  // counts far beyond the file size
  const std::string hdr = "element vertex 1000000000000000\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1000000000000000\n"
                          "property list uchar int vertex_indices\nend_header\n";
  expect_cleared(read(write_file("huge_a.ply", "ply\nformat ascii 1.0\n" + hdr + "0 0 0\n")),
                 Status::parse_error);
  expect_cleared(read(write_file("huge_b.ply", "ply\nformat binary_little_endian 1.0\n" + hdr +
                                                   std::string(12, '\0'))),
                 Status::parse_error);
  // list count larger than the rest of the file
  std::string b = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                  "property float y\nproperty float z\nelement face 1\n"
                  "property list uint int vertex_indices\nend_header\n";
  for (int i = 0; i < 9; ++i) append_raw<float>(b, float(i));
  append_raw<unsigned>(b, 4000000000u);
  append_raw<int>(b, 0);
  expect_cleared(read(write_file("hugelist.ply", b)), Status::parse_error);
}

TEST(Io_ply, invalid_indices_and_non_finite)
{
  Read x = read(write_file("bad.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\n"
                                      "property double y\nproperty double z\nelement face 2\n"
                                      "property list uchar int vertex_indices\nend_header\n"
                                      "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n3 0 -2 2\n"));
  EXPECT_EQ(x.r.status, Status::invalid_index);
  EXPECT_EQ(x.r.invalid_polygons, 1u);
  EXPECT_EQ(x.r.non_finite_points, 1u);
  ASSERT_EQ(x.polygons.size(), 2u);
  EXPECT_NE(x.r.message.find(":14:"), std::string::npos) << x.r.message;
}

// ---- STL ----------------------------------------------------------------------

/// binary STL of the two triangles (0,0,0),(1,0,0),(0,1,0) and (1,0,0),(1,1,0),(0,1,0).
std::string two_triangle_stl(const std::string& header_text, std::uint32_t announced = 2)
{
  std::string b(80, ' ');
  std::memcpy(&b[0], header_text.data(), std::min<std::size_t>(80, header_text.size()));
  append_raw<std::uint32_t>(b, announced);
  const float tris[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
  for (auto& t : tris) {
    for (int d = 0; d < 3; ++d) append_raw<float>(b, d == 2 ? 1.f : 0.f);
    for (auto& p : t)
      for (float c : p) append_raw<float>(b, c);
    append_raw<std::uint16_t>(b, 0);
  }
  return b;
}

TEST(Io_stl, binary_with_solid_header_and_merged_corners)
{
  for (const char* header : {"solid fake ascii header", "binary"}) {
    SCOPED_TRACE(header);
    Read x = read(write_file("two.stl", two_triangle_stl(header)));
    ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
    EXPECT_TRUE(x.r.binary);
    EXPECT_EQ(x.points, (std::vector<Point>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}));
    EXPECT_EQ(x.polygons, (std::vector<Polygon>{{0, 1, 2}, {1, 3, 2}}));
  }
}

TEST(Io_stl, binary_truncated_or_shorter_than_announced)
{
  const std::string full = two_triangle_stl("binary");
  for (std::size_t len = 1; len < full.size(); ++len) {
    Read x = read(write_file("cut.stl", full.substr(0, len)));
    EXPECT_TRUE(x.r.status == Status::parse_error) << len << " " << x.r.message;
    EXPECT_TRUE(x.points.empty());
  }
  Read x = read(write_file("lying.stl", two_triangle_stl("binary", 1000)));
  expect_cleared(x, Status::parse_error);
  EXPECT_NE(x.r.message.find("1000"), std::string::npos) << x.r.message;
  // "solid" header and a size that disagrees with the count
  x = read(write_file("lying_solid.stl", two_triangle_stl("solid x", 3)));
  expect_cleared(x, Status::parse_error);
  // zero triangles
  expect_cleared(read(write_file("zero.stl", two_triangle_stl("binary", 0).substr(0, 84))),
                 Status::empty_input);
}

TEST(Io_stl, ascii_merging_nan_and_errors)
{
  const std::string facet1 = " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
                             "   vertex 0 1 0\n  endloop\n endfacet\n";
  const std::string facet2 = " facet normal 0 0 1\n  outer loop\n   vertex 1 0 0\n   vertex 1 1 0\n"
                             "   vertex -0 1 0\n  endloop\n endfacet\n";
  Read x = read(write_file("a.stl", "solid my part\n" + facet1 + facet2 + "endsolid my part\n"));
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_FALSE(x.r.binary);
  EXPECT_EQ(x.points.size(), 4u);  // -0 merged with 0
  EXPECT_EQ(x.polygons, (std::vector<Polygon>{{0, 1, 2}, {1, 3, 2}}));

  // two solids in one file
  x = read(write_file("two.stl", "solid a\n" + facet1 + "endsolid a\nsolid b\n" + facet2 +
                                     "endsolid\n"));
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.polygons.size(), 2u);

  // NaN corners are kept and never merged
  std::string nanfacet = " facet normal 0 0 1\n outer loop\n vertex nan 0 0\n vertex 1 0 0\n"
                         " vertex nan 0 0\n endloop\n endfacet\n";
  x = read(write_file("nan.stl", "solid\n" + nanfacet + "endsolid\n"));
  EXPECT_EQ(x.r.status, Status::non_finite_input);
  EXPECT_EQ(x.r.non_finite_points, 2u);
  EXPECT_EQ(x.points.size(), 3u);

  // truncated inside a facet, garbage, bad number
  Read t = read(write_file("t.stl", "solid a\n" + facet1.substr(0, 60)));
  expect_cleared(t, Status::parse_error);
  t = read(write_file("g.stl", "solid a\n" + facet1 + "hello\n"));
  expect_cleared(t, Status::parse_error);
  EXPECT_NE(t.r.message.find(":9:"), std::string::npos) << t.r.message;
  t = read(write_file("n.stl", "solid a\n facet normal 0 0 1\n outer loop\n vertex 0 x 0\n"));
  expect_cleared(t, Status::parse_error);
  EXPECT_NE(t.r.message.find(":4:"), std::string::npos) << t.r.message;
}

// ---- what real exporters write ------------------------------------------------

TEST(Io_obj, line_continuation_joins_any_record)
{
  const std::string text = "# exported with continuations\n"
                           "mtllib scene.mtl\n"
                           "o thing\n"
                           "v 0 0 0\n"
                           "v 1 0 \\\n"
                           "0\n"
                           "v 1 1 \\  \r\n"  // blanks after the backslash, CRLF
                           "  0\r\n"
                           "v 0 1 0\n"
                           "g a \\\n"
                           "  b\n"
                           "usemtl red\n"
                           "f 1 2 \\\n"
                           "3 4\n"
                           "# a comment ending in a backslash does not continue \\\n"
                           "f 1 2 3 # nor does a face whose comment ends in one \\\n"
                           "f 1 \\\n"
                           "\\\n"  // a line holding only a backslash continues too
                           "2 \\\n"
                           "3\n"
                           "v \\\n"
                           " 2 0 0\n"
                           "f -4 -1 \\\n"
                           "-3\n"
                           "f 1 2 3 \\";  // at the end of the file, without a newline
  Read x = read(write_file("continued.obj", text));
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.points, (std::vector<Point>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}}));
  EXPECT_EQ(x.polygons, (std::vector<Polygon>{
                            {0, 1, 2, 3}, {0, 1, 2}, {0, 1, 2}, {1, 4, 2}, {0, 1, 2}}));

  // errors name the first line of a continued record, and later lines keep
  // their numbers
  Read e = read(write_file("continued_bad.obj", "v 0 0 0\nf 1 \\\n2 x\n"));
  expect_cleared(e, Status::parse_error);
  EXPECT_NE(e.r.message.find(":2:"), std::string::npos) << e.r.message;
  e = read(write_file("continued_bad2.obj", "v 0 0 0\nv 1 \\\n0 \\\n0\nv 0 1 0\nf 1 2 y\n"));
  expect_cleared(e, Status::parse_error);
  EXPECT_NE(e.r.message.find(":6:"), std::string::npos) << e.r.message;
  // invalid polygons are located the same way
  Read b = read(write_file("continued_idx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\\\n\nf 1 2 \\\n9\n"));
  EXPECT_EQ(b.r.status, Status::invalid_index);
  EXPECT_NE(b.r.message.find(":6:"), std::string::npos) << b.r.message;
}

TEST(Io_obj, exporter_records_and_corner_forms)
{
  // what Blender, 3ds Max and MeshLab write: a header comment, mtllib,
  // objects and groups, smoothing groups, materials, vt/vn and every corner form
  Read x = read(write_file("exporter.obj",
                           "# Blender v2.93 OBJ File\nmtllib cube.mtl\no Cube\n"
                           "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\n"
                           "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 -1\nvn 0 -1 0.5\n"
                           "g side\nusemtl Material.001\ns 1\n"
                           "f 1/1/2 2/2/2 5/3/2\n"           // v/vt/vn
                           "f 2//2 3//2 5//2\n"              // v//vn
                           "f -3/-3/-1 -2/-2/-1 -1/-1/-1\n"  // relative v/vt/vn
                           "f -2//-1 -5//-1 -1//-1\n"        // relative v//vn
                           "g base\nusemtl Material.002\ns off\n"
                           "f 1/1 4/2 3/3 2/1\n"            // v/vt
                           "o Pentagon\nf 1// 2// 3// 4// 5//\n"  // trailing slashes
                           "f 1/ 2/ 3/\n"));
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.points.size(), 5u);
  EXPECT_EQ(x.polygons, (std::vector<Polygon>{{0, 1, 4},
                                              {1, 2, 4},
                                              {2, 3, 4},
                                              {3, 0, 4},
                                              {0, 3, 2, 1},
                                              {0, 1, 2, 3, 4},
                                              {0, 1, 2}}));
}

TYPED_TEST(Io_mesh, exporter_obj_files_read_as_meshes)
{
  using Mesh = typename TypeParam::Mesh;
  // the non-planar pentagon of issue 15, as a lone face
  const std::string pentagon =
      write_file("pentagon.obj", "o p\nv 0 0 0\nv 1 0 0.2\nv 1.3 1 0\nv 0.5 1.6 0.3\nv -0.3 1 0\n"
                                 "s off\nf 1// 2// 3// 4// 5//\n");
  Mesh m;
  Io_result r = mrepair::read_polygon_mesh(pentagon, m);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  ASSERT_EQ(face_count(m), 1u);
  EXPECT_EQ(CGAL::degree(*faces(m).begin(), m), 5u);

  // a closed pyramid written with continuations and relative v/vt/vn corners
  const std::string pyramid =
      write_file("pyramid.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nvt 0 0\nvn 0 0 1\n"
                                "usemtl m\nf -5/1/1 -2/1/1 \\\n -3/1/1 -4/1/1\n"
                                "f 1//1 2//1 5//1\nf 2//1 3//1 5//1\nf 3/1/1 4/1/1 \\\n5/1/1\n"
                                "f -2 \\\n -5 \\\n -1\n");
  Mesh p;
  r = mrepair::read_polygon_mesh(pyramid, p);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(p));
  EXPECT_TRUE(CGAL::is_closed(p));
  EXPECT_EQ(vertices(p).size(), 5u);
  EXPECT_EQ(face_count(p), 5u);
}

/// appends `v` as a PLY value of `type`: text (with a trailing space) when
/// `encoding` is 0 (ascii) or 3 (ascii with CRLF), else binary little (1) or big (2) endian.
void append_ply_value(std::string& s, const std::string& type, double v, int encoding)
{
  if (encoding == 0 || encoding == 3) {
    char tmp[64];
    const bool floating = type == "float" || type == "float32" || type == "double" ||
                          type == "float64";
    std::snprintf(tmp, sizeof tmp, floating ? "%.17g " : "%.0f ", v);
    s += tmp;
    return;
  }
  const bool big = encoding == 2;
  if (type == "char" || type == "int8") append_raw<std::int8_t>(s, static_cast<std::int8_t>(v), big);
  else if (type == "uchar" || type == "uint8") append_raw<std::uint8_t>(s, static_cast<std::uint8_t>(v), big);
  else if (type == "short" || type == "int16") append_raw<std::int16_t>(s, static_cast<std::int16_t>(v), big);
  else if (type == "ushort" || type == "uint16") append_raw<std::uint16_t>(s, static_cast<std::uint16_t>(v), big);
  else if (type == "int" || type == "int32") append_raw<std::int32_t>(s, static_cast<std::int32_t>(v), big);
  else if (type == "uint" || type == "uint32") append_raw<std::uint32_t>(s, static_cast<std::uint32_t>(v), big);
  else if (type == "float" || type == "float32") append_raw<float>(s, static_cast<float>(v), big);
  else if (type == "double" || type == "float64") append_raw<double>(s, v, big);
  else ADD_FAILURE() << "unknown PLY type " << type;
}

/// a PLY as exporters write it: vertices with normals and RGBA colors, faces
/// with a `flags` property before or after the index list (of the given count
/// and index types) and a texcoord list, an `edge` element, and a `material`
/// element before or after the rest. `encoding` as for `append_ply_value`.
struct Exporter_ply
{
  int encoding = 0;
  std::string count_type = "uchar";
  std::string index_type = "int";
  bool flags_after = false;
  bool material_first = false;
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<int>> faces;

  std::string bytes() const
  {
    static const char* const formats[] = {"ascii", "binary_little_endian", "binary_big_endian",
                                          "ascii"};
    const std::string nl = encoding == 3 ? "\r\n" : "\n";
    const bool text = encoding == 0 || encoding == 3;
    std::string h = "ply" + nl + "format " + formats[encoding] + " 1.0" + nl +
                    "comment exported by a test" + nl;
    const std::string material = "element material 1" + nl + "property uchar ambient_red" + nl +
                                 "property float shininess" + nl;
    if (material_first) h += material;
    h += "element vertex " + std::to_string(points.size()) + nl;
    for (const char* p : {"float x", "float y", "float z", "float nx", "float ny", "float nz",
                          "uchar red", "uchar green", "uchar blue", "uchar alpha"})
      h += std::string("property ") + p + nl;
    h += "element face " + std::to_string(faces.size()) + nl;
    if (!flags_after) h += "property int flags" + nl;
    h += "property list " + count_type + " " + index_type + " vertex_indices" + nl;
    if (flags_after) h += "property int flags" + nl;
    h += "property list uchar float texcoord" + nl;
    h += "element edge 2" + nl + "property int vertex1" + nl + "property int vertex2" + nl +
         "property uchar red" + nl;
    if (!material_first) h += material;
    h += "end_header" + nl;

    std::string b;
    auto end_record = [&] {
      if (text) b += nl;
    };
    auto add_material = [&] {
      append_ply_value(b, "uchar", 200, encoding);
      append_ply_value(b, "float", 0.5, encoding);
      end_record();
    };
    if (material_first) add_material();
    for (const auto& p : points) {
      for (double c : p) append_ply_value(b, "float", c, encoding);
      for (double n : {0.0, 0.0, 1.0}) append_ply_value(b, "float", n, encoding);
      for (double c : {10.0, 20.0, 30.0, 255.0}) append_ply_value(b, "uchar", c, encoding);
      end_record();
    }
    for (const auto& f : faces) {
      if (!flags_after) append_ply_value(b, "int", 7, encoding);
      append_ply_value(b, count_type, static_cast<double>(f.size()), encoding);
      for (int i : f) append_ply_value(b, index_type, i, encoding);
      if (flags_after) append_ply_value(b, "int", 7, encoding);
      append_ply_value(b, "uchar", 2, encoding);
      append_ply_value(b, "float", 0.25, encoding);
      append_ply_value(b, "float", 0.75, encoding);
      end_record();
    }
    for (int e = 0; e < 2; ++e) {
      append_ply_value(b, "int", e, encoding);
      append_ply_value(b, "int", e + 1, encoding);
      append_ply_value(b, "uchar", 0, encoding);
      end_record();
    }
    if (!material_first) add_material();
    return h + b;
  }
  /// line of data record `k` of a text file (0-based: vertices, then faces;
  /// a leading material record is accounted for).
  std::size_t data_line(std::size_t k) const
  {
    const std::string b = bytes();
    return static_cast<std::size_t>(
               std::count(b.begin(), b.begin() + b.find("end_header") + 10, '\n')) +
           2 + k + (material_first ? 1 : 0);
  }
};

/// a closed square pyramid, apex last.
Exporter_ply pyramid_ply()
{
  Exporter_ply e;
  e.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
  e.faces = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  return e;
}

const char* const ply_encodings[] = {"ascii", "binary_little_endian", "binary_big_endian",
                                     "ascii_crlf"};

TEST(Io_ply, every_count_and_index_type_with_exporter_properties)
{
  const std::vector<Point> points{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
  const std::vector<Polygon> polygons{{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  int combination = 0;
  for (int encoding = 0; encoding < 4; ++encoding)
    for (const char* count : {"uchar", "uint8", "char", "int8", "ushort", "uint16", "short",
                              "int16", "uint", "uint32", "int", "int32"})
      for (const char* index : {"char", "int8", "uchar", "uint8", "short", "int16", "ushort",
                                "uint16", "int", "int32", "uint", "uint32"}) {
        Exporter_ply e = pyramid_ply();
        e.encoding = encoding;
        e.count_type = count;
        e.index_type = index;
        e.flags_after = combination % 2 == 1;
        e.material_first = combination % 3 == 0;
        ++combination;
        SCOPED_TRACE(std::string(ply_encodings[encoding]) + " list " + count + " " + index +
                     (e.flags_after ? ", flags after" : ", flags before") +
                     (e.material_first ? ", material first" : ", material last"));
        Read x = read(write_file("types.ply", e.bytes()));
        ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
        EXPECT_EQ(x.r.binary, encoding == 1 || encoding == 2);
        EXPECT_EQ(x.points, points);
        EXPECT_EQ(x.polygons, polygons);
        EXPECT_EQ(x.r.polygons_skipped, 0u);
        EXPECT_TRUE(x.r.message.empty()) << x.r.message;
      }
}

TEST(Io_ply, faces_with_fewer_than_three_vertices_are_skipped_and_counted)
{
  for (int encoding = 0; encoding < 4; ++encoding) {
    SCOPED_TRACE(ply_encodings[encoding]);
    Exporter_ply e = pyramid_ply();
    e.encoding = encoding;
    e.count_type = encoding == 1 ? "ushort" : "uchar";
    e.index_type = encoding == 2 ? "uint" : "int";
    // counts 0, 1 and 2 between the real faces
    e.faces = {{0, 3, 2, 1}, {}, {0, 1, 4}, {2}, {1, 2, 4}, {2, 3}, {2, 3, 4}, {3, 0, 4}};
    const std::string path = write_file("short_faces.ply", e.bytes());
    Read x = read(path);
    ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
    EXPECT_EQ(x.r.polygons_skipped, 3u);
    EXPECT_EQ(x.r.invalid_polygons, 0u);
    EXPECT_EQ(x.points.size(), 5u);
    EXPECT_EQ(x.polygons, (std::vector<Polygon>{{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4},
                                                {3, 0, 4}}));
    EXPECT_EQ(x.r.message.find('\n'), std::string::npos);
    EXPECT_NE(x.r.message.find("3 face(s) with fewer than 3 vertices skipped (first is face 1)"),
              std::string::npos)
        << x.r.message;
    const bool text = encoding == 0 || encoding == 3;
    // ascii names the line of the first one (vertex records come first)
    const std::string where = text ? path + ":" + std::to_string(e.data_line(5 + 1)) + ": "
                                   : path + ": ";
    EXPECT_EQ(x.r.message.rfind(where, 0), 0u) << x.r.message << " (want " << where << ")";

    mrepair::Report rep;
    x.r.to_report(rep);
    EXPECT_EQ(rep.get("polygons_skipped"), "3");

    // the mesh is built from the remaining faces
    Surface_mesh m;
    Io_result r = mrepair::read_polygon_mesh(path, m);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_EQ(r.polygons_skipped, 3u);
    EXPECT_EQ(face_count(m), 5u);
    EXPECT_TRUE(CGAL::is_closed(m));
    EXPECT_NE(r.message.find("skipped"), std::string::npos) << r.message;

    // with an invalid index as well: that status wins, both are reported
    e.faces = {{0, 3, 2, 1}, {0, 1}, {0, 1, 9}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    Read y = read(write_file("short_and_bad.ply", e.bytes()));
    EXPECT_EQ(y.r.status, Status::invalid_index) << y.r.message;
    EXPECT_EQ(y.r.invalid_polygons, 1u);
    EXPECT_EQ(y.r.polygons_skipped, 1u);
    EXPECT_EQ(y.polygons.size(), 5u);
    EXPECT_NE(y.r.message.find("1 invalid polygon(s)"), std::string::npos) << y.r.message;
    EXPECT_NE(y.r.message.find("1 face(s) with fewer than 3 vertices skipped"), std::string::npos)
        << y.r.message;
    EXPECT_EQ(y.r.message.find('\n'), std::string::npos);
  }
}

TEST(Io_point_cloud, vertices_without_faces_give_one_clear_line)
{
  Exporter_ply cloud = pyramid_ply();
  cloud.faces.clear();
  Exporter_ply cloud_binary = cloud;
  cloud_binary.encoding = 1;
  Exporter_ply only_short = pyramid_ply();
  only_short.faces = {{0, 1}, {2}, {}};
  struct Case
  {
    const char* name;
    std::string bytes;
    std::size_t vertices;
  };
  const Case cases[] = {
      {"cloud.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", 3},
      {"cloud_noff.off", "NOFF\n2 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n", 2},
      {"cloud.obj", "# scanner output\nv 0 0 0\nv 1 0 0\nvn 0 0 1\nv 0 1 0\nv 0 0 1\np 1 2 3 4\n", 4},
      {"cloud_lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n", 2},
      {"cloud_one.obj", "v 0 0 0\n", 1},
      {"cloud.ply", cloud.bytes(), 5},
      {"cloud_binary.ply", cloud_binary.bytes(), 5},
      {"cloud_vertex_only.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                                "property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n", 2},
      {"cloud_short_faces.ply", only_short.bytes(), 5},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = write_file(c.name, c.bytes);
    const std::string want = path + ": no faces (a point cloud of " + std::to_string(c.vertices) +
                             (c.vertices == 1 ? " vertex" : " vertices");
    Read x = read(path);
    expect_cleared(x, Status::empty_input);
    EXPECT_EQ(x.r.message.rfind(want, 0), 0u) << x.r.message;
    EXPECT_NE(x.r.message.find("); mrepair repairs surface meshes"), std::string::npos)
        << x.r.message;

    Surface_mesh m;
    Io_result r = mrepair::read_polygon_mesh(path, m);
    EXPECT_EQ(r.status, Status::empty_input);
    EXPECT_EQ(r.message, x.r.message);
    EXPECT_EQ(vertices(m).size(), 0u);

    // what the commands print
    mrepair::Report rep;
    std::string error;
    EXPECT_FALSE(mrepair::cli::load_mesh(path, m, rep, error));
    EXPECT_EQ(error, x.r.message);
    std::vector<Point> pts;
    std::vector<Polygon> polys;
    EXPECT_FALSE(mrepair::cli::load_soup(path, pts, polys, rep, error));
    EXPECT_EQ(error, x.r.message);
  }
  // the PLY whose faces all have fewer than 3 vertices says so
  Read s = read(temp_file("cloud_short_faces.ply"));
  EXPECT_NE(s.r.message.find("3 face(s) with fewer than 3 vertices skipped"), std::string::npos)
      << s.r.message;

  // STL has no vertex outside a facet: an STL without facets is empty, not a cloud
  for (const std::string& stl : {std::string("solid empty\nendsolid empty\n"),
                                 two_triangle_stl("binary", 0).substr(0, 84)}) {
    Read t = read(write_file("no_facets.stl", stl));
    expect_cleared(t, Status::empty_input);
    EXPECT_EQ(t.r.message.find("point cloud"), std::string::npos) << t.r.message;
  }
}

// ---- no crash on arbitrary bytes ------------------------------------------------

TEST(Io_robustness, random_bytes_and_truncations_never_crash)
{
  std::mt19937 rng(42);
  const Soup s = icosphere(1);
  for (const Format& f : all_formats) {
    const std::string path = temp_file(std::string("valid.") + f.ext);
    ASSERT_EQ(mrepair::write_polygon_soup(path, s.points, s.polygons, f.binary).status, Status::ok);
    const std::string bytes = read_bytes(path);
    for (int trial = 0; trial < 200; ++trial) {
      std::string b = bytes.substr(0, rng() % (bytes.size() + 1));
      // flip a few bytes
      for (int k = 0; k < 3 && !b.empty(); ++k) b[rng() % b.size()] = static_cast<char>(rng());
      Read x = read(write_file(std::string("fuzz.") + f.ext, b));
      if (!x.points.empty()) {
        // data loaded: the counters agree with the data
        std::size_t bad = 0;
        for (const Polygon& p : x.polygons) {
          bool invalid = p.size() < 3;
          for (std::size_t i : p) invalid = invalid || i >= x.points.size();
          bad += invalid;
        }
        EXPECT_EQ(bad, x.r.invalid_polygons);
      } else {
        EXPECT_FALSE(mrepair::succeeded(x.r.status));
      }
    }
  }
}

// Every field with its own value, so that a field reported under another's
// key, or dropped, fails (a read leaves most counters 0, which would not).
TEST(Io_report, to_report_has_every_field)
{
  mrepair::Io_result x;
  x.status = mrepair::Status::invalid_index;
  x.message = "m.ply:7: index out of range";
  x.format = "ply";
  x.binary = true;
  x.points = 11;
  x.polygons = 12;
  x.non_finite_points = 13;
  x.invalid_polygons = 14;
  x.polygons_skipped = 15;
  mrepair::Report rep;
  x.to_report(rep);
  EXPECT_EQ(rep.get("status"), mrepair::to_string(x.status));
  EXPECT_EQ(rep.get("message"), x.message);
  EXPECT_EQ(rep.get("format"), "ply");
  EXPECT_EQ(rep.get("binary"), "true");
  EXPECT_EQ(rep.get("points"), "11");
  EXPECT_EQ(rep.get("polygons"), "12");
  EXPECT_EQ(rep.get("non_finite_points"), "13");
  EXPECT_EQ(rep.get("invalid_polygons"), "14");
  EXPECT_EQ(rep.get("polygons_skipped"), "15");
  // and what a read reports: the counts of the file
  Read r = read(write_file("r.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\nnan 0 0\n3 0 1 2\n3 0 1 9\n"));
  mrepair::Report read_rep;
  r.r.to_report(read_rep);
  EXPECT_EQ(read_rep.get("format"), "off");
  EXPECT_EQ(read_rep.get("points"), "4");
  EXPECT_EQ(read_rep.get("non_finite_points"), "1");
  EXPECT_EQ(read_rep.get("invalid_polygons"), "1");
}

// ---- the mesh builder agrees with CGAL ----------------------------------------

/// random sub-soups of a grid and a sphere: some faces dropped (holes, pinched
/// vertices), some flipped (orientation), some duplicated (fins), some with a
/// repeated vertex; the decision and the mesh must match CGAL's.
TYPED_TEST(Io_mesh, builder_agrees_with_cgal_on_random_soups)
{
  using Mesh = typename TypeParam::Mesh;
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::mt19937 rng(7);
  std::size_t built = 0, refused = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Soup s = trial % 2 ? grid(4, 3, 1.0, trial % 4 == 1) : icosphere(1);
    std::vector<Polygon> polys;
    const int mode = trial % 7;
    for (const Polygon& p : s.polygons) {
      unsigned r = rng() % 100;
      if (mode >= 1 && r < 15) continue;  // drop
      Polygon q = p;
      if (mode >= 3 && r >= 15 && r < 18) std::reverse(q.begin(), q.end());  // flip
      if (mode >= 4 && r >= 18 && r < 20) polys.push_back(q);               // duplicate
      if (mode >= 5 && r == 20 && q.size() == 4) q[2] = q[0];              // repeat a vertex
      polys.push_back(q);
    }
    if (polys.empty()) continue;
    const std::string path = temp_file("builder.off");
    ASSERT_EQ(mrepair::write_polygon_soup(path, s.points, polys).status, Status::ok);
    const bool cgal_ok = PMP::is_polygon_soup_a_polygon_mesh(polys);
    Mesh ours;
    Io_result r = mrepair::read_polygon_mesh(path, ours);
    ASSERT_EQ(r.status == Status::ok, cgal_ok) << "trial " << trial << ": " << r.message;
    if (!cgal_ok) {
      EXPECT_EQ(r.status, Status::non_manifold_input);
      EXPECT_EQ(vertices(ours).size(), 0u);
      ++refused;
      continue;
    }
    ++built;
    Mesh theirs;
    PMP::polygon_soup_to_polygon_mesh(s.points, polys, theirs);
    ASSERT_TRUE(mrepair_test::valid_polygon_mesh(ours)) << "trial " << trial;
    // CGAL keeps unused points as isolated vertices, we leave them out
    std::set<std::size_t> used;
    for (const Polygon& p : polys) used.insert(p.begin(), p.end());
    EXPECT_EQ(vertices(ours).size(), used.size());
    if (used.size() < s.points.size()) {
      EXPECT_NE(r.message.find("used by no polygon"), std::string::npos) << r.message;
    }
    EXPECT_EQ(edges(ours).size(), edges(theirs).size());
    ASSERT_EQ(face_count(ours), face_count(theirs));
    // same faces in the same order with the same cycles of points
    auto fo = faces(ours).begin();
    for (auto ft : faces(theirs)) {
      std::vector<Point> a, b;
      for (auto v : CGAL::vertices_around_face(halfedge(*fo, ours), ours))
        a.push_back(get(CGAL::vertex_point, ours, v));
      for (auto v : CGAL::vertices_around_face(halfedge(ft, theirs), theirs))
        b.push_back(get(CGAL::vertex_point, theirs, v));
      auto it = std::find(a.begin(), a.end(), b.front());
      ASSERT_NE(it, a.end());
      std::rotate(a.begin(), it, a.end());
      EXPECT_EQ(a, b);
      ++fo;
    }
    // the same border: count of border halfedges and of border cycles
    auto borders = [](const Mesh& m) {
      std::size_t n = 0, cycles = 0;
      std::set<typename boost::graph_traits<Mesh>::halfedge_descriptor> seen;
      for (auto h : halfedges(m))
        if (CGAL::is_border(h, m)) {
          ++n;
          if (seen.count(h)) continue;
          ++cycles;
          for (auto g : CGAL::halfedges_around_face(h, m)) seen.insert(g);
        }
      return std::make_pair(n, cycles);
    };
    EXPECT_EQ(borders(ours), borders(theirs)) << "trial " << trial;
    for (auto v : vertices(ours))
      if (CGAL::is_border(v, ours)) {
        EXPECT_TRUE(CGAL::is_border(halfedge(v, ours), ours)) << "border vertex points to a border halfedge";
      }
  }
  EXPECT_GT(built, 50u);
  EXPECT_GT(refused, 50u);
}

// The file reader's builder on an empty Surface_mesh sizes its arrays once
// and wires the halfedges in parallel; on other meshes it adds element by
// element. Both must give the same elements in the same order, and the
// 32-bit topology the reader uses below 4G corners the 64-bit one's arrays.
// The soup is large enough for the parallel passes (over 2^20 corners and
// 2^16 points), with holes and its faces in a shuffled order (as in files
// whose faces do not follow their vertices).
TEST(Io_builder, parallel_surface_mesh_build_and_narrow_topology_match_the_generic_ones)
{
  namespace IO = mrepair::internal::io;
  const std::size_t nx = 450, ny = 400;
  Soup s = grid(nx, ny);
  // holes of one cell, apart from each other (border edges and vertices, no
  // vertex with two fans), then the faces in a shuffled order
  std::vector<Polygon> kept;
  for (std::size_t f = 0; f < s.polygons.size(); ++f) {
    const std::size_t cell = f / 2, i = cell % nx, j = cell / nx;
    if (i % 10 != 5 || j % 10 != 5) kept.push_back(s.polygons[f]);
  }
  std::mt19937 rng(11);
  std::shuffle(kept.begin(), kept.end(), rng);
  std::vector<std::int64_t> indices;
  std::vector<std::size_t> starts = {0};
  for (const Polygon& p : kept) {
    indices.insert(indices.end(), p.begin(), p.end());
    starts.push_back(indices.size());
  }
  const std::size_t nf = starts.size() - 1;
  ASSERT_GT(indices.size(), std::size_t(1) << 20);
  std::string why;
  IO::Basic_soup_topology<std::uint32_t> narrow;
  IO::Soup_topology wide;
  ASSERT_TRUE(narrow.compute(s.points.size(), indices.data(), starts.data(), nf, why)) << why;
  ASSERT_TRUE(wide.compute(s.points.size(), indices.data(), starts.data(), nf, why)) << why;
  ASSERT_EQ(narrow.out_start.size(), wide.out_start.size());
  for (std::size_t v = 0; v < wide.out_start.size(); ++v) ASSERT_EQ(narrow.out_start[v], wide.out_start[v]);
  std::size_t borders = 0;
  for (std::size_t c = 0; c < indices.size(); ++c) {
    ASSERT_EQ(narrow.next[c], wide.next[c]);
    ASSERT_EQ(narrow.prev[c], wide.prev[c]);
    ASSERT_EQ(narrow.opposite_of(c), wide.opposite_of(c));
    ASSERT_EQ(narrow.out[c], wide.out[c]);
    borders += wide.opposite_of(c) == IO::Soup_topology::none;
  }
  EXPECT_GT(borders, 1000u);

  Surface_mesh sm;
  Polyhedron ph;
  auto sm_points = get(CGAL::vertex_point, sm);
  auto ph_points = get(CGAL::vertex_point, ph);
  IO::build_mesh(narrow, s.points.size(), indices.data(), starts.data(), nf, sm,
                 [&](auto v, std::size_t i) { put(sm_points, v, s.points[i]); });
  IO::build_mesh(wide, s.points.size(), indices.data(), starts.data(), nf, ph,
                 [&](auto v, std::size_t i) { put(ph_points, v, s.points[i]); });
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(sm));
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(ph));
  ASSERT_EQ(vertices(sm).size(), vertices(ph).size());
  ASSERT_EQ(edges(sm).size(), edges(ph).size());
  ASSERT_EQ(faces(sm).size(), faces(ph).size());
  // vertices: the same points, each pointing to the same halfedge (by its ends)
  auto pv = vertices(ph).begin();
  for (auto v : vertices(sm)) {
    ASSERT_EQ(get(sm_points, v), get(ph_points, *pv));
    const auto hs = halfedge(v, sm);
    const auto hp = halfedge(*pv, ph);
    ASSERT_EQ(get(sm_points, source(hs, sm)), get(ph_points, source(hp, ph)));
    ASSERT_EQ(CGAL::is_border(hs, sm), CGAL::is_border(hp, ph));
    ++pv;
  }
  // faces: the same cycles from the same first halfedge
  auto pf = faces(ph).begin();
  for (auto f : faces(sm)) {
    std::vector<Point> a, b;
    for (auto v : CGAL::vertices_around_face(halfedge(f, sm), sm)) a.push_back(get(sm_points, v));
    for (auto v : CGAL::vertices_around_face(halfedge(*pf, ph), ph)) b.push_back(get(ph_points, v));
    ASSERT_EQ(a, b);
    ++pf;
  }
  // edges in the same order, each halfedge with the same ends and face side
  auto pe = edges(ph).begin();
  for (auto e : edges(sm)) {
    const auto hs = halfedge(e, sm);
    const auto hp = halfedge(*pe, ph);
    ASSERT_EQ(get(sm_points, source(hs, sm)), get(ph_points, source(hp, ph)));
    ASSERT_EQ(get(sm_points, target(hs, sm)), get(ph_points, target(hp, ph)));
    ASSERT_EQ(CGAL::is_border(hs, sm), CGAL::is_border(hp, ph));
    ASSERT_EQ(get(sm_points, target(next(hs, sm), sm)), get(ph_points, target(next(hp, ph), ph)));
    ++pe;
  }
}

// A Surface_mesh with removed elements (collapses, as the remesher leaves
// them with collect_garbage(false)) is written in place, the removed slots
// skipped: the same bytes, in every format, as through the copy the writer
// makes for a user-given index map, and read back with the mesh's counts.
TEST(Io_write, mesh_with_removed_elements_is_written_as_its_copy)
{
  Surface_mesh m = to_mesh<Surface_mesh>(icosphere(3));
  for (int i = 0; i < 40; ++i) {
    auto e = *std::next(edges(m).begin(), 37 * i + 3);
    if (CGAL::Euler::does_satisfy_link_condition(e, m)) CGAL::Euler::collapse_edge(e, m);
  }
  ASSERT_TRUE(m.has_garbage());
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
  for (const char* ext : {"off", "obj", "ply", "stl"})
    for (bool binary : {false, true}) {
      const std::string in_place = temp_file(std::string("gaps_view.") + ext);
      const std::string copied = temp_file(std::string("gaps_copy.") + ext);
      ASSERT_EQ(mrepair::write_polygon_mesh(in_place, m, binary).status, Status::ok) << ext;
      ASSERT_EQ(mrepair::write_polygon_mesh(copied, m, binary,
                                            CGAL::parameters::vertex_index_map(get(CGAL::vertex_index, m)))
                    .status,
                Status::ok)
          << ext;
      EXPECT_EQ(read_bytes(in_place), read_bytes(copied)) << ext << (binary ? " binary" : " ascii");
      Surface_mesh back;
      ASSERT_EQ(mrepair::read_polygon_mesh(in_place, back).status, Status::ok) << ext;
      EXPECT_EQ(faces(back).size(), faces(m).size()) << ext;
      EXPECT_EQ(vertices(back).size(), vertices(m).size()) << ext;
    }
}

TYPED_TEST(Io_mesh, large_polygons)
{
  using Mesh = typename TypeParam::Mesh;
  // one 300-gon: PLY needs a wider list count than uchar
  Soup s;
  Polygon big;
  for (std::size_t i = 0; i < 300; ++i) {
    s.points.emplace_back(std::cos(i * 0.02), std::sin(i * 0.02), 0.);
    big.push_back(i);
  }
  s.polygons.push_back(big);
  for (const Format& f : all_formats) {
    SCOPED_TRACE(std::string(f.ext) + (f.binary ? " binary" : " ascii"));
    const std::string path = temp_file(std::string("big.") + f.ext);
    ASSERT_EQ(mrepair::write_polygon_soup(path, s.points, s.polygons, f.binary).status, Status::ok);
    Mesh m;
    Io_result r = mrepair::read_polygon_mesh(path, m);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_EQ(face_count(m), std::string(f.ext) == "stl" ? 298u : 1u);
    EXPECT_EQ(vertices(m).size(), 300u);
    EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  }
  // the same polygon with a vertex repeated far apart is not a mesh
  s.polygons[0][250] = 10;
  const std::string path = temp_file("big_repeat.off");
  ASSERT_EQ(mrepair::write_polygon_soup(path, s.points, s.polygons).status, Status::ok);
  Mesh m;
  Io_result r = mrepair::read_polygon_mesh(path, m);
  EXPECT_EQ(r.status, Status::non_manifold_input);
  EXPECT_NE(r.message.find("repeats a vertex"), std::string::npos) << r.message;
}

// ---- the allocator policy of `mrepair repair` (tools/cli.h) ----------------------

// glibc only, and not under a sanitizer (its allocator replaces glibc's;
// GCC names the sanitizers by macros, clang by __has_feature)
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define MREPAIR_TEST_OWN_ALLOCATOR 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define MREPAIR_TEST_OWN_ALLOCATOR 1
#endif
#if defined(__GLIBC__) && (__GLIBC__ > 2 || __GLIBC_MINOR__ >= 33) && !defined(MREPAIR_TEST_OWN_ALLOCATOR)
TEST(Cli_memory, large_blocks_come_from_the_heap_only_while_asked)
{
  // 64 MB: above any threshold glibc accepts, so mapped unless told otherwise
  const std::size_t big = std::size_t(64) << 20;
  auto mapped_bytes = [] { return mallinfo2().hblkhd; };
  auto allocate = [&] {
    std::unique_ptr<char[]> p(new char[big]);
    p[0] = p[big - 1] = 1;
    asm volatile("" : : "g"(p.get()) : "memory");  // keep the allocation
    return p;
  };
  mrepair::cli::serve_large_blocks_from_heap(true);
  {
    const std::size_t before = mapped_bytes();
    const auto p = allocate();
    EXPECT_LT(mapped_bytes(), before + big);
  }
  mrepair::cli::release_freed_memory_above(0);
  mrepair::cli::serve_large_blocks_from_heap(false);  // glibc's default again
  {
    const std::size_t before = mapped_bytes();
    const auto p = allocate();
    EXPECT_GE(mapped_bytes(), before + big);
  }
}
#endif
#undef MREPAIR_TEST_OWN_ALLOCATOR  // the other files of the unity build do not see it

// ---- the CLI helpers (tools/cli_io.h) -------------------------------------------

TYPED_TEST(Io_mesh, cli_helpers_report_and_fail_in_one_line)
{
  using Mesh = typename TypeParam::Mesh;
  const Mesh cube = to_mesh<Mesh>(mrepair_test::cube());
  mrepair::Report rep;
  std::string error;
  const std::string path = temp_file("cli.ply");
  ASSERT_TRUE(mrepair::cli::save_mesh(path, cube, true, rep, error)) << error;
  EXPECT_EQ(rep.get("write.status"), "ok");
  EXPECT_EQ(rep.get("write.binary"), "true");
  EXPECT_EQ(rep.get("write.polygons"), "12");

  Mesh m;
  ASSERT_TRUE(mrepair::cli::load_mesh(path, m, rep, error)) << error;
  EXPECT_EQ(face_count(m), 12u);
  EXPECT_EQ(rep.get("read.faces"), "12");
  EXPECT_EQ(rep.get("read.format"), "ply");
  EXPECT_FALSE(rep.get("read.seconds").empty());

  std::string fin = write_file("cli_fin.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n"
                                              "3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  mrepair::Report rep2;
  EXPECT_FALSE(mrepair::cli::load_mesh(fin, m, rep2, error));
  EXPECT_EQ(rep2.get("read.status"), "non_manifold_input");
  EXPECT_NE(error.find("mrepair soup"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);

  // soups with defects load by default, and fail on request
  std::string nan = write_file("cli_nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  mrepair::Report rep3;
  EXPECT_TRUE(mrepair::cli::load_soup(nan, pts, polys, rep3, error));
  EXPECT_EQ(rep3.get("read.status"), "non_finite_input");
  EXPECT_FALSE(mrepair::cli::load_soup(nan, pts, polys, rep3, error, false));
  EXPECT_NE(error.find(nan), std::string::npos) << error;

  EXPECT_FALSE(mrepair::cli::save_mesh(temp_file("nodir/x.off"), cube, false, rep3, error));
  EXPECT_EQ(rep3.get("write.status"), "io_error");
  EXPECT_FALSE(mrepair::cli::save_soup(temp_file("x.stl"), pts, std::vector<Polygon>{{0, 1}},
                                       false, rep3, error));
  EXPECT_EQ(rep3.get("write.status"), "invalid_index");
}

// ---- a real mesh, when CGAL's data is installed ---------------------------------

TEST(Io_real, armadillo_matches_cgal_counts)
{
  const std::string path = std::string(MREPAIR_CGAL_DATA_DIR) + "/armadillo.off";
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
  Read x = read(path);
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  EXPECT_EQ(x.points.size(), 26002u);
  EXPECT_EQ(x.polygons.size(), 52000u);
  Surface_mesh m;
  ASSERT_EQ(mrepair::read_polygon_mesh(path, m).status, Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(CGAL::is_closed(m));
}


// ---- issue 17: bulk binary reads, chunked text parsing, parallel writing ------

/// sets the size of the parallel text chunks for one scope.
struct Chunk_bytes
{
  std::size_t saved = mrepair::internal::io::io_chunk_bytes();
  explicit Chunk_bytes(std::size_t b) { mrepair::internal::io::io_chunk_bytes() = b; }
  ~Chunk_bytes() { mrepair::internal::io::io_chunk_bytes() = saved; }
};

/// chunk sizes that cut records everywhere: a byte, a few bytes, lines, the default.
const std::size_t chunk_sizes[] = {1, 7, 64, 1000, std::size_t(1) << 20};

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same_points(const std::vector<Point>& a, const std::vector<Point>& b)
{
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int d = 0; d < 3; ++d)
      ASSERT_TRUE(same_bits(a[i][d], b[i][d])) << "point " << i << " coordinate " << d << ": "
                                               << a[i][d] << " vs " << b[i][d];
}

/// a soup with awkward doubles (tiny, huge, signed zero, subnormal, many
/// digits), triangles, quads and pentagons; `floats` keeps it float-exact.
Soup awkward_soup(std::size_t n, bool floats, unsigned seed = 17)
{
  std::mt19937_64 rng(seed);
  const double special[] = {1e-300, -0.0, 1.5e10, 0.1, -123456.789012345678, 4.9e-324,
                            1.7976931348623157e308, 2.2250738585072014e-308, 1.0 / 3.0, 7.0};
  Soup s;
  for (std::size_t i = 0; i < n; ++i) {
    double c[3];
    for (double& v : c) {
      const std::uint64_t r = rng();
      if (r % 4 == 0) {
        v = special[(r >> 8) % 10];
      } else {
        std::uint64_t bits = rng();
        std::memcpy(&v, &bits, sizeof v);
        if (!std::isfinite(v)) v = std::ldexp(static_cast<double>(r >> 11), -40);
      }
      if (floats) {
        v = to_float(v);
        if (!std::isfinite(v) || v == 0) v = to_float(static_cast<double>(r % 1000) / 7.0 + 1);
      }
    }
    s.points.emplace_back(c[0], c[1], c[2]);
  }
  for (std::size_t f = 0; f + 5 < n; f += 2) {
    const std::size_t k = 3 + (f / 2) % 3;  // 3, 4 or 5 corners
    Polygon poly;
    for (std::size_t j = 0; j < k; ++j) poly.push_back((f + j * 7919) % n);
    s.polygons.push_back(poly);
  }
  return s;
}

TEST(Io_issue_17, round_trips_are_bit_identical_in_every_format_and_chunk_size)
{
  const Soup s = awkward_soup(3000, false);
  const Soup sf = awkward_soup(3000, true);
  for (std::size_t bytes : chunk_sizes) {
    Chunk_bytes chunk(bytes);
    for (const Format& f : all_formats) {
      SCOPED_TRACE(std::string(f.ext) + (f.binary ? " binary" : " ascii") + ", chunks of " +
                   std::to_string(bytes));
      const bool stl = std::string(f.ext) == "stl";
      const Soup& in = stl ? sf : s;
      const std::string path = temp_file(std::string("awkward.") + f.ext);
      Io_result w = mrepair::write_polygon_soup(path, in.points, in.polygons, f.binary);
      ASSERT_EQ(w.status, Status::ok) << w.message;
      Read x = read(path);
      ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
      EXPECT_EQ(x.r.binary, f.binary);
      if (!stl) {
        expect_same_points(x.points, in.points);
        EXPECT_EQ(x.polygons, in.polygons);
        continue;
      }
      // STL: fan triangles, corners by value: every triangle's corners match
      std::size_t t = 0;
      for (const Polygon& poly : in.polygons)
        for (std::size_t k = 1; k + 1 < poly.size(); ++k, ++t) {
          ASSERT_LT(t, x.polygons.size());
          const std::size_t want[3] = {poly[0], poly[k], poly[k + 1]};
          for (int c = 0; c < 3; ++c)
            ASSERT_EQ(x.points[x.polygons[t][c]], in.points[want[c]]) << "triangle " << t;
        }
      EXPECT_EQ(t, x.polygons.size());
      // the merge numbers points in order of first appearance, exactly once each
      std::set<std::array<double, 3>> distinct;
      for (const Point& p : x.points) distinct.insert({p.x(), p.y(), p.z()});
      EXPECT_EQ(distinct.size(), x.points.size());
    }
  }
}

TEST(Io_issue_17, writing_twice_gives_the_same_bytes_whatever_the_chunk_size)
{
  const Soup s = awkward_soup(2000, false);
  for (const Format& f : all_formats) {
    SCOPED_TRACE(std::string(f.ext) + (f.binary ? " binary" : " ascii"));
    std::string reference;
    for (std::size_t bytes : chunk_sizes) {
      Chunk_bytes chunk(bytes);
      const std::string path = temp_file(std::string("bytes.") + f.ext);
      ASSERT_EQ(mrepair::write_polygon_soup(path, s.points, s.polygons, f.binary).status, Status::ok);
      const std::string b = read_bytes(path);
      if (reference.empty())
        reference = b;
      else
        EXPECT_TRUE(b == reference) << "chunks of " << bytes;
    }
  }
}

/// the points and polygons of the decorated text files below.
const std::vector<std::array<double, 3>> decorated_points = {
    {1e-300, -0.0, 1.5e10}, {1, 0, 0}, {0.25, 1, -0.0}, {-1.5e-7, 2.5, 3}, {4, 5, 6}};
const std::vector<Polygon> decorated_polygons = {{0, 1, 2}, {1, 3, 2, 4}, {4, 3, 0}};

/// text of the decorated points; each coordinate written in a different style
std::string decorated_coordinate(std::size_t i, int d)
{
  static const char* text[5][3] = {{"1e-300", "-0", "1.5E+10"},
                                   {"1.0", "0", "+0.0"},
                                   {".25", "1e0", "-0.0e5"},
                                   {"-1.5e-7", "2.50", "3"},
                                   {"4", "5.", "6.000"}};
  return text[i][d];
}

void expect_decorated(const Read& x, const std::string& what)
{
  SCOPED_TRACE(what);
  ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
  ASSERT_EQ(x.points.size(), decorated_points.size());
  for (std::size_t i = 0; i < decorated_points.size(); ++i)
    for (int d = 0; d < 3; ++d)
      EXPECT_TRUE(same_bits(x.points[i][d], decorated_points[i][d])) << i << "," << d;
  EXPECT_EQ(x.polygons, decorated_polygons);
}

/// `copies` of the decorated soup in one body, with CRLF line ends,
/// comments (where the format has them), blank lines, tabs and trailing blanks.
std::string decorated_lines(const std::string& format, int copies, bool crlf)
{
  const std::string nl = crlf ? "\r\n" : "\n";
  const bool comments = format != "ply";
  std::string v, f;
  for (int c = 0; c < copies; ++c)
    for (std::size_t i = 0; i < decorated_points.size(); ++i) {
      if (format == "obj") v += i % 2 ? "v\t" : "v ";
      v += (i % 2 ? "\t" : "") + decorated_coordinate(i, 0) + (i % 3 ? " \t" : " ") +
           decorated_coordinate(i, 1) + " " + decorated_coordinate(i, 2);
      v += (i == 2 && comments ? "  # a comment" : "   ") + nl;
      if (i == 1) v += nl + (comments ? "# between vertices" + nl : std::string()) + " \t" + nl;
    }
  const std::size_t np = decorated_points.size();
  for (int c = 0; c < copies; ++c)
    for (std::size_t k = 0; k < decorated_polygons.size(); ++k) {
      const Polygon& poly = decorated_polygons[k];
      f += format == "obj" ? "f" : std::to_string(poly.size());
      for (std::size_t j = 0; j < poly.size(); ++j) {
        const std::size_t i = poly[j] + c * np;
        if (format != "obj") {
          f += (j % 2 ? "\t" : " ") + std::to_string(i);
        } else if (k == 1) {  // relative: -1 is the last vertex read so far
          f += " " + std::to_string(static_cast<long>(i) - static_cast<long>(copies * np));
        } else {
          f += " " + std::to_string(i + 1) + (j == 1 ? "//1" : "");
        }
      }
      f += (k == 2 ? " \t " : "") + nl;
      if (k == 0) f += nl;
    }
  return v + f;
}

Soup decorated_copies(int copies)
{
  Soup s;
  for (int c = 0; c < copies; ++c) {
    for (const auto& p : decorated_points) s.points.emplace_back(p[0], p[1], p[2]);
  }
  for (int c = 0; c < copies; ++c)
    for (Polygon poly : decorated_polygons) {
      for (std::size_t& i : poly) i += c * decorated_points.size();
      s.polygons.push_back(poly);
    }
  return s;
}

TEST(Io_issue_17, chunk_boundaries_in_crlf_comments_blank_lines_tabs_and_odd_numbers)
{
  const int copies = 40;
  const Soup want = decorated_copies(copies);
  const std::size_t np = want.points.size(), nf = want.polygons.size();
  for (bool crlf : {false, true}) {
    const std::string nl = crlf ? "\r\n" : "\n";
    const std::string off = "OFF" + nl + "# counts next" + nl + std::to_string(np) + " " +
                            std::to_string(nf) + " 0" + nl + decorated_lines("off", copies, crlf);
    const std::string obj = "# obj" + nl + decorated_lines("obj", copies, crlf);
    const std::string ply = "ply" + nl + "format ascii 1.0" + nl + "element vertex " +
                            std::to_string(np) + nl + "property double x" + nl +
                            "property double y" + nl + "property double z" + nl +
                            "element face " + std::to_string(nf) + nl +
                            "property list uchar int vertex_indices" + nl + "end_header" + nl +
                            decorated_lines("ply", copies, crlf);
    for (std::size_t bytes : chunk_sizes) {
      Chunk_bytes chunk(bytes);
      const std::string what = std::string(crlf ? "CRLF" : "LF") + ", chunks of " + std::to_string(bytes);
      for (const auto& file : {std::make_pair("deco.off", off), std::make_pair("deco.obj", obj),
                               std::make_pair("deco.ply", ply)}) {
        Read x = read(write_file(file.first, file.second));
        ASSERT_EQ(x.r.status, Status::ok) << what << " " << file.first << ": " << x.r.message;
        expect_same_points(x.points, want.points);
        EXPECT_EQ(x.polygons, want.polygons) << what << " " << file.first;
      }
    }
  }
  // one copy, checked against the values themselves
  Chunk_bytes chunk(5);
  expect_decorated(read(write_file("deco1.off", "OFF\n5 3 0\n" + decorated_lines("off", 1, true))),
                   "off");
  expect_decorated(read(write_file("deco1.obj", decorated_lines("obj", 1, false))), "obj");
}

TEST(Io_issue_17, records_over_several_lines_and_trailing_text_read_as_before)
{
  for (std::size_t bytes : chunk_sizes) {
    Chunk_bytes chunk(bytes);
    SCOPED_TRACE(bytes);
    // OFF: a vertex over two lines, a comment inside; text after the last face
    Read x = read(write_file("split.off", "OFF\n3 1\n0 0\n0\n1 0 0 # c\n0 1\n# c\n 0\n3 0 1 2\n"
                                          "trailing words are ignored\n"));
    ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
    EXPECT_EQ(x.points.size(), 3u);
    EXPECT_EQ(x.polygons, (std::vector<Polygon>{{0, 1, 2}}));
    // PLY ascii: one vertex's properties over two lines
    x = read(write_file("split.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                     "property float y\nproperty float z\nelement face 1\n"
                                     "property list uchar int vertex_indices\nend_header\n"
                                     "0 0\n0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
    EXPECT_EQ(x.points.size(), 3u);
    EXPECT_EQ(x.polygons, (std::vector<Polygon>{{0, 1, 2}}));
    // OBJ with a continuation (read line by line) and relative indices
    x = read(write_file("cont.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 \\\n -2 -1\n"));
    ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
    EXPECT_EQ(x.polygons, (std::vector<Polygon>{{0, 1, 2}}));
  }
}

TEST(Io_issue_17, errors_name_the_same_line_whatever_the_chunk_size)
{
  // many good lines, then one bad: the line number must survive the chunking
  std::string good_v, good_f;
  for (int i = 0; i < 300; ++i) good_v += std::to_string(i) + " 0 0\n";
  for (int i = 0; i + 2 < 300; ++i)
    good_f += "3 " + std::to_string(i) + " " + std::to_string(i + 1) + " " + std::to_string(i + 2) + "\n";
  const std::string off_bad = "OFF\n300 299 0\n" + good_v + good_f + "3 1 2 x\n";
  const std::string off_short = "OFF\n300 400 0\n" + good_v + good_f;
  std::string obj_bad;
  for (int i = 0; i < 300; ++i) obj_bad += "v " + std::to_string(i) + " 0 0\n";
  for (int i = 0; i < 100; ++i) obj_bad += "f -1 -2 -3\n";
  obj_bad += "f 1 2 zz\n";
  for (int i = 0; i < 100; ++i) obj_bad += "v 0 0 q\n";  // later errors: not reported
  std::string ply_bad = "ply\nformat ascii 1.0\nelement vertex 300\nproperty float x\n"
                        "property float y\nproperty float z\nelement face 299\n"
                        "property list uchar int vertex_indices\nend_header\n" +
                        good_v + good_f + "3 1 2 x\n";
  std::map<std::string, std::string> reference;
  for (std::size_t bytes : chunk_sizes) {
    Chunk_bytes chunk(bytes);
    SCOPED_TRACE(bytes);
    for (const auto& file : {std::make_pair("bad.off", off_bad), std::make_pair("short.off", off_short),
                             std::make_pair("bad2.obj", obj_bad), std::make_pair("bad.ply", ply_bad)}) {
      Read x = read(write_file(file.first, file.second));
      expect_cleared(x, Status::parse_error);
      if (reference.count(file.first))
        EXPECT_EQ(x.r.message, reference[file.first]);
      else
        reference[file.first] = x.r.message;
    }
  }
  EXPECT_NE(reference["bad.off"].find(":601:"), std::string::npos) << reference["bad.off"];
  EXPECT_NE(reference["bad2.obj"].find(":401:"), std::string::npos) << reference["bad2.obj"];
  EXPECT_NE(reference["short.off"].find("298 of 400 faces"), std::string::npos) << reference["short.off"];
  EXPECT_NE(reference["bad.ply"].find(":608:"), std::string::npos) << reference["bad.ply"];
}

TEST(Io_issue_17, invalid_data_found_in_any_chunk_is_kept_counted_and_located)
{
  std::string off = "OFF\n200 100 0\n";
  for (int i = 0; i < 200; ++i) off += (i == 150 ? std::string("nan 0 0") : std::to_string(i) + " 1 2") + "\n";
  for (int i = 0; i < 100; ++i) off += "3 " + std::to_string(i) + " " + std::to_string(i + 1) + " " +
                                       std::to_string(i == 70 ? 999 : i + 2) + "\n";
  std::string obj;
  for (int i = 0; i < 200; ++i) obj += "v " + std::to_string(i) + " 1 2\n";
  for (int i = 0; i < 100; ++i) obj += i == 80 ? "f 1 2 -300\n" : "f -1 -2 -3\n";
  for (std::size_t bytes : chunk_sizes) {
    Chunk_bytes chunk(bytes);
    SCOPED_TRACE(bytes);
    Read x = read(write_file("inv.off", off));
    EXPECT_EQ(x.r.status, Status::invalid_index);
    EXPECT_EQ(x.r.invalid_polygons, 1u);
    EXPECT_EQ(x.r.non_finite_points, 1u);
    EXPECT_NE(x.r.message.find(":273:"), std::string::npos) << x.r.message;
    EXPECT_EQ(x.points.size(), 200u);
    x = read(write_file("inv.obj", obj));
    EXPECT_EQ(x.r.status, Status::invalid_index);
    EXPECT_EQ(x.r.invalid_polygons, 1u);
    EXPECT_NE(x.r.message.find(":281:"), std::string::npos) << x.r.message;
    ASSERT_EQ(x.polygons.size(), 100u);
    EXPECT_EQ(x.polygons[99], (Polygon{199, 198, 197}));
    x = read(write_file("nan.off", "OFF\n3 1\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n"));
    EXPECT_EQ(x.r.status, Status::non_finite_input);
    EXPECT_NE(x.r.message.find(":4:"), std::string::npos) << x.r.message;
  }
}

/// a binary PLY of `s`, with a uchar flag before the list and a list of
/// texture coordinates after it in each face, counts of `count_type`
/// and indices of `index_type`; faces with fewer than 3 corners allowed.
std::string binary_ply(const Soup& s, bool big_endian, const std::string& count_type,
                       const std::string& index_type)
{
  std::string h = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex " + std::to_string(s.points.size()) +
                  "\nproperty float x\nproperty double y\nproperty float z\nproperty uchar red\n"
                  "element face " + std::to_string(s.polygons.size()) +
                  "\nproperty uchar flags\nproperty list " + count_type + " " + index_type +
                  " vertex_indices\nproperty list uchar float texcoord\nend_header\n";
  for (const Point& p : s.points) {
    append_raw(h, static_cast<float>(p.x()), big_endian);
    append_raw(h, p.y(), big_endian);
    append_raw(h, static_cast<float>(p.z()), big_endian);
    append_raw(h, std::uint8_t(7), big_endian);
  }
  for (const Polygon& poly : s.polygons) {
    append_raw(h, std::uint8_t(1), big_endian);
    if (count_type == "uchar") append_raw(h, static_cast<std::uint8_t>(poly.size()), big_endian);
    if (count_type == "ushort") append_raw(h, static_cast<std::uint16_t>(poly.size()), big_endian);
    if (count_type == "int") append_raw(h, static_cast<std::int32_t>(poly.size()), big_endian);
    for (std::size_t i : poly) {
      if (index_type == "int") append_raw(h, static_cast<std::int32_t>(i), big_endian);
      if (index_type == "uint") append_raw(h, static_cast<std::uint32_t>(i), big_endian);
      if (index_type == "ushort") append_raw(h, static_cast<std::uint16_t>(i), big_endian);
    }
    append_raw(h, std::uint8_t(2), big_endian);
    append_raw(h, 0.5f, big_endian);
    append_raw(h, 0.25f, big_endian);
  }
  return h;
}

TEST(Io_issue_17, binary_ply_general_layouts_over_many_blocks)
{
  Soup s = awkward_soup(40000, true);  // > 16384 faces per block: several blocks
  for (Point& p : s.points) p = Point(p.x(), to_float(p.y() / 3), p.z());
  Soup with_short = s;
  with_short.polygons.insert(with_short.polygons.begin() + 17000, Polygon{1, 2});
  with_short.polygons.insert(with_short.polygons.begin() + 5, Polygon{});
  for (bool be : {false, true})
    for (const char* count : {"uchar", "ushort", "int"})
      for (const char* index : {"int", "uint"}) {
        SCOPED_TRACE(std::string(be ? "big" : "little") + " " + count + " " + index);
        Read x = read(write_file("general.ply", binary_ply(with_short, be, count, index)));
        ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
        EXPECT_TRUE(x.r.binary);
        EXPECT_EQ(x.r.polygons_skipped, 2u);
        EXPECT_NE(x.r.message.find("first is face 5"), std::string::npos) << x.r.message;
        expect_same_points(x.points, s.points);
        EXPECT_EQ(x.polygons, s.polygons);
      }
  // truncated in the middle of a face list, in a later block
  std::string b = binary_ply(s, false, "uchar", "int");
  Read x = read(write_file("trunc.ply", b.substr(0, b.size() - 100)));
  expect_cleared(x, Status::parse_error);
  EXPECT_NE(x.r.message.find("ends in element face"), std::string::npos) << x.r.message;
}

TEST(Io_issue_17, large_files_cross_the_default_chunk_size)
{
  // a few MB of text: several default-sized chunks and waves
  const Soup s = awkward_soup(120000, false, 5);
  for (const Format& f : all_formats) {
    if (std::string(f.ext) == "stl") continue;
    SCOPED_TRACE(std::string(f.ext) + (f.binary ? " binary" : " ascii"));
    const std::string path = temp_file(std::string("large.") + f.ext);
    ASSERT_EQ(mrepair::write_polygon_soup(path, s.points, s.polygons, f.binary).status, Status::ok);
    if (!f.binary) {
      EXPECT_GT(fs::file_size(path), 3 * mrepair::internal::io::io_chunk_bytes());
    }
    Read x = read(path);
    ASSERT_EQ(x.r.status, Status::ok) << x.r.message;
    expect_same_points(x.points, s.points);
    EXPECT_EQ(x.polygons, s.polygons);
  }
}

TEST(Io_issue_18, mesh_check_names_the_first_defect_whatever_the_blocks)
{
  // a grid large enough for the parallel blocks of the soup-to-mesh check
  // (over 16,384 polygons and vertices); one triangle flipped near the start
  // and one near the end: the refusal names the first, as a sequential scan
  // would, and the second alone names a vertex of a later block
  const Soup g = grid(140, 140, 1.0, false);
  ASSERT_GT(g.polygons.size(), 2u * 16384u);
  ASSERT_GT(g.points.size(), 16384u);
  auto refusal = [&](std::vector<std::size_t> flipped) {
    Soup s = g;
    for (std::size_t f : flipped) std::reverse(s.polygons[f].begin(), s.polygons[f].end());
    const std::string path = temp_file("flipped.off");
    EXPECT_EQ(mrepair::write_polygon_soup(path, s.points, s.polygons).status, Status::ok);
    Surface_mesh m;
    const Io_result r = mrepair::read_polygon_mesh(path, m);
    EXPECT_EQ(r.status, Status::non_manifold_input);
    EXPECT_EQ(faces(m).size(), 0u);
    return r.message;
  };
  const std::size_t late = g.polygons.size() - 100;
  const std::string first = refusal({100}), second = refusal({late});
  EXPECT_NE(first.find("used twice in the same direction"), std::string::npos) << first;
  EXPECT_NE(first, second);
  EXPECT_EQ(refusal({100, late}), first);
  EXPECT_EQ(refusal({late, 100}), first);
  // the vertex named by the late flip lies past the first block of vertices
  const std::size_t at = second.find("edge (");
  ASSERT_NE(at, std::string::npos) << second;
  EXPECT_GE(std::stoul(second.substr(at + 6)), 16384u) << second;
}

} // namespace

} // namespace io_tests
} // namespace
