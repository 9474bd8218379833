// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Tests of polygon_soup_to_manifold_mesh and the soup stages (issue 3).
#include "fixtures.h"

#include <mrepair/stitch_soup.h>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

// A namespace of its own: this file is compiled in one translation unit with
// other test files (a unity build, CMakeLists.txt).
namespace {
namespace stitch_soup_tests {

namespace PMP = CGAL::Polygon_mesh_processing;
namespace MP = mrepair::parameters;
using namespace mrepair_test;

namespace {

// Signed volumes (x6) of the connected components of `m`, sorted.
template <class Mesh>
std::vector<double> component_volumes(const Mesh& m)
{
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;
  auto fcc = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  for (face_descriptor f : faces(m)) put(fcc, f, 0);
  std::size_t n = PMP::connected_components(m, fcc);
  std::vector<double> vol(n, 0.0);
  for (face_descriptor f : faces(m)) {
    auto h = halfedge(f, m);
    const auto& a = get(CGAL::vertex_point, m, source(h, m));
    const auto& b = get(CGAL::vertex_point, m, target(h, m));
    const auto& c = get(CGAL::vertex_point, m, target(next(h, m), m));
    vol[get(fcc, f)] += CGAL::determinant(a - CGAL::ORIGIN, b - CGAL::ORIGIN, c - CGAL::ORIGIN);
  }
  std::sort(vol.begin(), vol.end());
  return vol;
}

// Face counts of the connected components, sorted.
template <class Mesh>
std::vector<std::size_t> component_sizes(const Mesh& m)
{
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;
  auto fcc = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  for (face_descriptor f : faces(m)) put(fcc, f, 0);
  std::size_t n = PMP::connected_components(m, fcc);
  std::vector<std::size_t> sz(n, 0);
  for (face_descriptor f : faces(m)) ++sz[get(fcc, f)];
  std::sort(sz.begin(), sz.end());
  return sz;
}

// Checks every promise on an output: valid, triangles, no degenerate face, no
// non-manifold vertex, exported soup is a polygon mesh (no non-manifold edge,
// consistent orientation), face accounting, boundary count.
template <class Mesh>
void check_output(const Mesh& m, const mrepair::Soup_repair_result& r)
{
  using halfedge_descriptor = typename boost::graph_traits<Mesh>::halfedge_descriptor;
  using vertex_descriptor = typename boost::graph_traits<Mesh>::vertex_descriptor;
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(face_count(m), r.faces_out);
  EXPECT_EQ(static_cast<std::size_t>(vertices(m).size()), r.vertices_out);
  EXPECT_EQ(r.faces_in, r.faces_out + r.faces_removed());
  if (faces(m).size() == 0) return;
  EXPECT_TRUE(CGAL::is_triangle_mesh(m));
  std::vector<halfedge_descriptor> nm;
  PMP::non_manifold_vertices(m, std::back_inserter(nm));
  EXPECT_EQ(nm.size(), 0u);
  for (auto f : faces(m)) EXPECT_FALSE(PMP::is_degenerate_triangle_face(f, m));
  std::map<vertex_descriptor, std::size_t> id;
  for (vertex_descriptor v : vertices(m)) id.emplace(v, id.size());
  std::vector<std::vector<std::size_t>> polys;
  for (auto f : faces(m)) {
    std::vector<std::size_t> p;
    for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, m), m)) p.push_back(id[target(h, m)]);
    polys.push_back(p);
  }
  EXPECT_TRUE(PMP::is_polygon_soup_a_polygon_mesh(polys));
  std::size_t border = 0;
  for (halfedge_descriptor h : halfedges(m)) border += is_border(h, m);
  EXPECT_EQ(border, r.boundary_edges);
}

template <class Mesh, class NP = CGAL::parameters::Default_named_parameters>
mrepair::Soup_repair_result repair(const Soup& s, Mesh& m, const NP& np = CGAL::parameters::default_values())
{
  mrepair::Soup_repair_result r = mrepair::polygon_soup_to_manifold_mesh(s.points, s.polygons, m, np);
  check_output(m, r);
  return r;
}

// six triangles on the edge (0,0,0)-(0,0,1), wings every 60 degrees,
// running up (u->v) at 0, 120, 240 and down at 60, 180, 300 degrees.
Soup six_fin()
{
  Soup s;
  s.points = {Point(0, 0, 0), Point(0, 0, 1)};
  const double pi = 3.14159265358979323846;
  for (int k = 0; k < 6; ++k) {
    s.points.emplace_back(std::cos(k * pi / 3), std::sin(k * pi / 3), 0.5);
    if (k % 2 == 0)
      s.polygons.push_back({0, 1, std::size_t(2 + k)});
    else
      s.polygons.push_back({1, 0, std::size_t(2 + k)});
  }
  return s;
}

// a twisted strip of n quads (2n triangles) closed into a Moebius band.
Soup moebius(int n = 12)
{
  Soup s;
  const double pi = 3.14159265358979323846, R = 3, w = 0.5;
  for (int i = 0; i < n; ++i) {
    double t = 2 * pi * i / n, phi = t / 2;
    double rx = std::cos(phi) * std::cos(t), ry = std::cos(phi) * std::sin(t), rz = std::sin(phi);
    double cx = R * std::cos(t), cy = R * std::sin(t);
    s.points.emplace_back(cx + w * rx, cy + w * ry, w * rz);  // top i = 2i
    s.points.emplace_back(cx - w * rx, cy - w * ry, -w * rz); // bottom i = 2i + 1
  }
  for (int i = 0; i < n; ++i) {
    std::size_t top = 2 * i, bot = 2 * i + 1, top1 = 2 * (i + 1), bot1 = 2 * (i + 1) + 1;
    if (i + 1 == n) {  // half twist: top meets bottom
      top1 = 1;
      bot1 = 0;
    }
    s.polygons.push_back({bot, bot1, top1});
    s.polygons.push_back({bot, top1, top});
  }
  return s;
}

Soup& append(Soup& a, const Soup& b)
{
  std::size_t off = a.points.size();
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (Polygon p : b.polygons) {
    for (auto& i : p) i += off;
    a.polygons.push_back(p);
  }
  return a;
}

// cube whose six faces are separate quads with their own corners, each corner
// moved by up to `noise` per coordinate; quad 0 reversed when asked.
Soup cracked_cube(double noise, bool reverse_one)
{
  Soup c = cube(1.0, true), s;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-noise, noise);
  for (std::size_t q = 0; q < c.polygons.size(); ++q) {
    Polygon p;
    for (std::size_t i : c.polygons[q]) {
      const Point& x = c.points[i];
      s.points.emplace_back(x.x() + d(rng), x.y() + d(rng), x.z() + d(rng));
      p.push_back(s.points.size() - 1);
    }
    if (reverse_one && q == 0) std::reverse(p.begin(), p.end());
    s.polygons.push_back(p);
  }
  return s;
}

// two tetrahedra glued on the face (0,1,2), each written with its own copy of
// it (trimesh's joined_tetrahedra.obj): the copy is a wall inside the solid.
Soup joined_tetrahedra()
{
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0.3, 0.3, 1), Point(0.3, 0.3, -1)};
  s.polygons = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 1, 2}, {0, 4, 1}, {1, 4, 2}, {2, 4, 0}};
  return s;
}

// the closed tetrahedron of joined_tetrahedra() above the plane z = 0.
Soup tetrahedron()
{
  Soup s = joined_tetrahedra();
  s.polygons.resize(4);
  return s;
}

// true when `m` has a vertex at exactly `p`.
template <class Mesh>
bool has_point(const Mesh& m, const Point& p)
{
  for (auto v : vertices(m))
    if (get(CGAL::vertex_point, m, v) == p) return true;
  return false;
}

template <class C>
class Stitch_soup : public ::testing::Test
{
};
TYPED_TEST_SUITE(Stitch_soup, Mesh_configs);

} // namespace

TYPED_TEST(Stitch_soup, ManifoldInputIsKept)
{
  using Mesh = typename TypeParam::Mesh;
  BOOST_CONCEPT_ASSERT((CGAL::concepts::MutableFaceGraph<Mesh>));
  Mesh m;
  auto r = repair(icosphere(2), m);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.faces_in, 320u);
  EXPECT_EQ(r.faces_out, 320u);
  EXPECT_EQ(r.vertices_out, 162u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.closed_components, 1u);
  EXPECT_EQ(r.faces_reoriented, 0u);
  EXPECT_EQ(r.vertices_duplicated, 0u);
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_GT(component_volumes(m)[0], 0);
}

TYPED_TEST(Stitch_soup, ThreeFacesOnOneEdgeKeepThePlaneTogether)
{
  using Mesh = typename TypeParam::Mesh;
  for (int fin_dir = 0; fin_dir < 2; ++fin_dir) {
    Soup s;
    // u, v, plane wings w1 (+y) and w2 (-y), fin wing w3 (+z)
    s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, -1, 0), Point(0.5, 0, 1)};
    s.polygons = {{0, 1, 2}, {1, 0, 3}};
    s.polygons.push_back(fin_dir ? Polygon{1, 0, 4} : Polygon{0, 1, 4});
    Mesh m;
    auto r = repair(s, m);
    EXPECT_EQ(r.status, mrepair::Status::ok);
    EXPECT_EQ(r.faces_out, 3u);
    EXPECT_EQ(r.complex_edges, 1u);
    EXPECT_EQ(r.vertices_duplicated, 2u);  // u and v once each for the fin
    EXPECT_EQ(r.complex_vertices, 2u);
    EXPECT_EQ(r.vertices_out, 7u);
    EXPECT_EQ(r.boundary_edges, 7u);  // 4 around the plane, 3 around the fin
    EXPECT_EQ(r.faces_reoriented, 0u);
    EXPECT_EQ(component_sizes(m), (std::vector<std::size_t>{1, 2}));
  }
}

TYPED_TEST(Stitch_soup, TwoCubesSharingAnEdgeStaySeparateSolids)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = cube();
  append(s, translated(cube(), 1, 1, 0));  // shares the edge x = y = 1
  Mesh m;
  auto r = repair(s, m);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.points_merged, 2u);
  EXPECT_EQ(r.complex_edges, 1u);  // 4 faces on it
  EXPECT_EQ(r.faces_out, 24u);
  EXPECT_EQ(r.vertices_duplicated, 2u);
  EXPECT_EQ(r.vertices_out, 16u);
  EXPECT_EQ(r.components, 2u);
  EXPECT_EQ(r.closed_components, 2u);
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_EQ(r.faces_reoriented, 0u);
  EXPECT_EQ(component_sizes(m), (std::vector<std::size_t>{12, 12}));
  auto vol = component_volumes(m);
  EXPECT_NEAR(vol[0], 6.0, 1e-9);  // 6 x unit volume
  EXPECT_NEAR(vol[1], 6.0, 1e-9);
}

TYPED_TEST(Stitch_soup, SixFacesOnOneEdgePairByWedges)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m;
  auto r = repair(six_fin(), m);
  EXPECT_EQ(r.complex_edges, 1u);
  EXPECT_EQ(r.faces_out, 6u);
  EXPECT_EQ(r.components, 3u);  // wedges 60-120, 180-240, 300-0 degrees
  EXPECT_EQ(component_sizes(m), (std::vector<std::size_t>{2, 2, 2}));
  EXPECT_EQ(r.vertices_duplicated, 4u);
  EXPECT_EQ(r.vertices_out, 12u);
  EXPECT_EQ(r.boundary_edges, 12u);
  EXPECT_EQ(r.faces_reoriented, 0u);
}

TYPED_TEST(Stitch_soup, FourFinWithMixedOrientationsIsCutNotLost)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = six_fin();
  s.polygons.resize(4);
  std::swap(s.polygons[1][0], s.polygons[1][1]);  // now three faces run up, one down
  Mesh m;
  auto r = repair(s, m);
  EXPECT_EQ(r.faces_out, 4u);
  EXPECT_EQ(r.complex_edges, 1u);
}

TYPED_TEST(Stitch_soup, BowtieVertexIsDuplicated)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0), Point(-1, 0, 0),
              Point(-1, -1, 0), Point(0, -1, 0)};
  // two fans of two triangles each around vertex 0
  s.polygons = {{0, 1, 2}, {0, 2, 3}, {0, 4, 5}, {0, 5, 6}};
  Mesh m;
  auto r = repair(s, m);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.complex_edges, 0u);
  EXPECT_EQ(r.complex_vertices, 1u);
  EXPECT_EQ(r.vertices_duplicated, 1u);
  EXPECT_EQ(r.vertices_out, 8u);
  EXPECT_EQ(r.components, 2u);
  EXPECT_EQ(r.faces_out, 4u);
}

TYPED_TEST(Stitch_soup, MoebiusBandIsCutOnce)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m;
  auto r = repair(moebius(12), m);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.faces_out, 24u);
  EXPECT_EQ(r.edges_cut_nonorientable, 1u);
  EXPECT_EQ(r.vertices_duplicated, 2u);  // both ends of the cut rung
  EXPECT_EQ(r.vertices_out, 26u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.boundary_edges, 26u);  // 24 border edges + the two sides of the cut
}

TYPED_TEST(Stitch_soup, DuplicatesInBothOrientations)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = icosphere(1);  // 80 faces
  for (int i = 0; i < 10; ++i) s.polygons.push_back(s.polygons[i]);
  for (int i = 10; i < 20; ++i) {
    Polygon p = s.polygons[i];
    std::reverse(p.begin(), p.end());
    s.polygons.push_back(p);
  }
  Mesh m;
  auto r = repair(s, m);
  EXPECT_EQ(r.faces_in, 100u);
  EXPECT_EQ(r.removed_duplicate, 20u);
  EXPECT_EQ(r.faces_out, 80u);
  EXPECT_EQ(r.closed_components, 1u);
  EXPECT_EQ(r.faces_reoriented, 0u);

  Mesh m2;
  auto r2 = repair(s, m2, MP::keep_two_sided(true));
  EXPECT_EQ(r2.removed_duplicate, 10u);
  EXPECT_EQ(r2.faces_out, 90u);
}

TYPED_TEST(Stitch_soup, TwoSidedSheet)
{
  using Mesh = typename TypeParam::Mesh;
  // a hexagonal fan (every interior edge meets the centre) given with both orientations
  Soup s;
  s.points.emplace_back(0, 0, 0);
  for (int k = 0; k < 6; ++k) s.points.emplace_back(std::cos(k * 1.0471975511965976), std::sin(k * 1.0471975511965976), 0);
  for (std::size_t k = 0; k < 6; ++k) s.polygons.push_back({0, 1 + k, 1 + (k + 1) % 6});
  for (std::size_t k = 0; k < 6; ++k) s.polygons.push_back({1 + (k + 1) % 6, 1 + k, 0});
  Mesh one;
  auto r = repair(s, one);
  EXPECT_EQ(r.removed_duplicate, 6u);
  EXPECT_EQ(r.faces_out, 6u);
  EXPECT_EQ(r.boundary_edges, 6u);

  Mesh two;
  auto r2 = repair(s, two, MP::keep_two_sided(true));
  EXPECT_EQ(r2.removed_duplicate, 0u);
  EXPECT_EQ(r2.faces_out, 12u);
  EXPECT_EQ(r2.components, 1u);  // front and back glued along the border
  EXPECT_EQ(r2.closed_components, 1u);
  EXPECT_EQ(r2.boundary_edges, 0u);
  EXPECT_EQ(r2.complex_edges, 6u);        // the spokes: two front, two back faces
  EXPECT_EQ(r2.vertices_duplicated, 1u);  // the centre: front fan, back fan
  EXPECT_EQ(r2.vertices_out, 8u);

  // a grid sheet: its interior edges between two border vertices would be
  // double edges of the closed sheet, so the sheet is cut there; nothing is lost
  Soup g = grid(3, 3);
  const std::size_t n = g.polygons.size();
  for (std::size_t i = 0; i < n; ++i) {
    Polygon p = g.polygons[i];
    std::reverse(p.begin(), p.end());
    g.polygons.push_back(p);
  }
  Mesh three;
  auto r3 = repair(g, three, MP::keep_two_sided(true));
  EXPECT_EQ(r3.faces_out, 2 * n);
}

TYPED_TEST(Stitch_soup, MixedOrientationBecomesOutward)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = icosphere(2);
  std::mt19937 rng(42);
  std::size_t flipped = 0;
  for (Polygon& p : s.polygons)
    if (rng() % 3 == 0) {
      std::reverse(p.begin(), p.end());
      ++flipped;
    }
  ASSERT_GT(flipped, 50u);
  Mesh m;
  auto r = repair(s, m);
  EXPECT_EQ(r.faces_out, 320u);
  EXPECT_EQ(r.closed_components, 1u);
  EXPECT_EQ(r.faces_reoriented, flipped);
  EXPECT_GT(component_volumes(m)[0], 0);

  // all reversed: the outward rule flips the whole sphere
  Soup inv = icosphere(2);
  for (Polygon& p : inv.polygons) std::reverse(p.begin(), p.end());
  Mesh m2;
  auto r2 = repair(inv, m2);
  EXPECT_EQ(r2.components_flipped, 1u);
  EXPECT_EQ(r2.faces_reoriented, 320u);
  EXPECT_GT(component_volumes(m2)[0], 0);
  Mesh m3;
  auto r3 = repair(inv, m3, MP::orient_outward(false));
  EXPECT_EQ(r3.faces_reoriented, 0u);
  EXPECT_LT(component_volumes(m3)[0], 0);
}

TYPED_TEST(Stitch_soup, NestedShellsKeepTheirInputOrientation)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = icosphere(2, 2.0);        // outer
  append(s, icosphere(2, 1.0));      // inner, given outward: an overlap, not a cavity
  append(s, translated(icosphere(1, 0.5), 10, 0, 0));  // apart, reversed below
  for (std::size_t i = 640; i < s.polygons.size(); ++i) std::reverse(s.polygons[i].begin(), s.polygons[i].end());
  Mesh m;
  auto r = repair(s, m);
  EXPECT_EQ(r.components, 3u);
  EXPECT_EQ(r.closed_components, 3u);
  EXPECT_EQ(r.components_flipped, 1u);  // only the far sphere: it is inside nothing
  EXPECT_EQ(r.faces_reoriented, 80u);
  auto vol = component_volumes(m);
  EXPECT_GT(vol[0], 0);
  EXPECT_GT(vol[1], 0);
  EXPECT_GT(vol[2], 0);
}

TYPED_TEST(Stitch_soup, NestedCubesOverlapOrCavityAsGiven)
{
  using Mesh = typename TypeParam::Mesh;
  for (int cavity = 0; cavity < 2; ++cavity) {
    Soup s = cube(3.0);
    Soup inner = translated(cube(1.0), 1, 1, 1);
    if (cavity)
      for (Polygon& p : inner.polygons) std::reverse(p.begin(), p.end());
    append(s, inner);
    Mesh m;
    auto r = repair(s, m);
    EXPECT_EQ(r.faces_out, 24u);
    EXPECT_EQ(r.closed_components, 2u);
    EXPECT_EQ(r.components_flipped, 0u);
    EXPECT_EQ(r.faces_reoriented, 0u);
    auto vol = component_volumes(m);  // x6
    if (cavity) {
      EXPECT_NEAR(vol[0], -6.0, 1e-9);
      EXPECT_NEAR(PMP::volume(m), 26.0, 1e-9);
    } else {
      EXPECT_NEAR(vol[0], 6.0, 1e-9);
      EXPECT_NEAR(PMP::volume(m), 28.0, 1e-9);
    }
    EXPECT_NEAR(vol[1], 6.0 * 27, 1e-9);

    // an inward outer shell is turned outward; the inner one keeps its own orientation
    Soup inv = s;
    for (std::size_t i = 0; i < 12; ++i) std::reverse(inv.polygons[i].begin(), inv.polygons[i].end());
    Mesh m2;
    auto r2 = repair(inv, m2);
    EXPECT_EQ(r2.components_flipped, 1u);
    EXPECT_EQ(r2.faces_reoriented, 12u);
    EXPECT_NEAR(PMP::volume(m2), cavity ? 26.0 : 28.0, 1e-9);
  }
}

TYPED_TEST(Stitch_soup, JoinedTetrahedraLoseTheirInternalWall)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m;
  auto r = repair(joined_tetrahedra(), m);
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.faces_in, 8u);
  EXPECT_EQ(r.removed_internal_walls, 2u);
  EXPECT_EQ(r.removed_duplicate, 0u);
  EXPECT_EQ(r.faces_out, 6u);
  EXPECT_EQ(face_count(m), 6u);
  EXPECT_TRUE(CGAL::is_triangle_mesh(m));
  EXPECT_TRUE(CGAL::is_closed(m));
  EXPECT_EQ(r.complex_edges, 0u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.closed_components, 1u);
  EXPECT_EQ(r.vertices_out, 5u);
  EXPECT_TRUE(has_point(m, Point(0.3, 0.3, 1)));
  EXPECT_TRUE(has_point(m, Point(0.3, 0.3, -1)));
  EXPECT_NEAR(PMP::volume(m), 1.0 / 3.0, 1e-12);  // base 1/2, heights 1 + 1

  // keep_two_sided keeps both copies: two closed tetrahedra, nothing removed
  Mesh two;
  auto r2 = repair(joined_tetrahedra(), two, MP::keep_two_sided(true));
  EXPECT_EQ(r2.removed_internal_walls, 0u);
  EXPECT_EQ(r2.removed_duplicate, 0u);
  EXPECT_EQ(r2.faces_out, 8u);
  EXPECT_EQ(r2.closed_components, 2u);

  // the same in place
  Soup s = joined_tetrahedra();
  auto rc = mrepair::clean_polygon_soup(s.points, s.polygons);
  EXPECT_EQ(rc.removed_internal_walls, 2u);
  EXPECT_EQ(s.polygons.size(), 6u);
  EXPECT_EQ(rc.faces_in, rc.faces_out + rc.faces_removed());
}

TYPED_TEST(Stitch_soup, TwoCubesSharingAFaceBecomeOneBox)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = cube();
  append(s, translated(cube(), 1, 0, 0));  // the wall x = 1: two triangles, each twice
  Mesh m;
  auto r = repair(s, m);
  EXPECT_EQ(r.removed_internal_walls, 4u);
  EXPECT_EQ(r.removed_duplicate, 0u);
  EXPECT_EQ(r.faces_out, 20u);
  EXPECT_EQ(r.complex_edges, 0u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.closed_components, 1u);
  EXPECT_TRUE(CGAL::is_closed(m));
  EXPECT_NEAR(PMP::volume(m), 2.0, 1e-12);
}

TYPED_TEST(Stitch_soup, DoubledFacesOnOneShellKeepOneCopy)
{
  using Mesh = typename TypeParam::Mesh;
  for (int reverse = 0; reverse < 2; ++reverse) {
    Soup s = tetrahedron();
    Polygon copy = s.polygons[1];
    if (reverse) std::reverse(copy.begin(), copy.end());
    s.polygons.push_back(copy);  // its edges have three faces: no wall
    Mesh m;
    auto r = repair(s, m);
    EXPECT_EQ(r.removed_internal_walls, 0u);
    EXPECT_EQ(r.removed_duplicate, 1u);
    EXPECT_EQ(r.faces_out, 4u);
    EXPECT_EQ(r.closed_components, 1u);
    EXPECT_TRUE(CGAL::is_closed(m));
    EXPECT_GT(PMP::volume(m), 0);
  }
  {
    // a face and its three neighbours doubled: the middle face's edges have
    // four faces (two copies of a neighbour each), the patch's border three
    Soup s = icosphere(2);
    const Polygon f = s.polygons[0];
    std::vector<Polygon> twice = {f};
    for (const Polygon& g : s.polygons) {
      int shared = 0;
      for (std::size_t v : g) shared += std::count(f.begin(), f.end(), v);
      if (shared == 2) twice.push_back(g);
    }
    ASSERT_EQ(twice.size(), 4u);
    for (const Polygon& g : twice) s.polygons.push_back(g);
    Mesh m;
    auto r = repair(s, m);
    EXPECT_EQ(r.removed_internal_walls, 0u);
    EXPECT_EQ(r.removed_duplicate, 4u);
    EXPECT_EQ(r.faces_out, 320u);
    EXPECT_EQ(r.boundary_edges, 0u);
  }
  {
    // a whole shell given twice: every edge has four faces, but no body is walled off
    Soup s = icosphere(1);
    const std::size_t n = s.polygons.size();
    for (std::size_t i = 0; i < n; ++i) s.polygons.push_back(s.polygons[i]);
    Mesh m;
    auto r = repair(s, m);
    EXPECT_EQ(r.removed_internal_walls, 0u);
    EXPECT_EQ(r.removed_duplicate, n);
    EXPECT_EQ(r.faces_out, n);
    EXPECT_EQ(r.closed_components, 1u);
  }
}

TYPED_TEST(Stitch_soup, CrackedCubeClosesWithEpsilon)
{
  using Mesh = typename TypeParam::Mesh;
  {
    Mesh m;
    auto r = repair(cracked_cube(1e-4, false), m);
    EXPECT_EQ(r.polygons_triangulated, 6u);
    EXPECT_EQ(r.faces_out, 12u);
    EXPECT_EQ(r.components, 6u);
    EXPECT_EQ(r.vertices_out, 24u);
    EXPECT_EQ(r.boundary_edges, 24u);
  }
  {
    Mesh m;
    auto r = repair(cracked_cube(1e-4, true), m, MP::merge_epsilon(1e-3));
    EXPECT_EQ(r.points_merged, 16u);
    EXPECT_EQ(r.faces_out, 12u);
    EXPECT_EQ(r.vertices_out, 8u);
    EXPECT_EQ(r.components, 1u);
    EXPECT_EQ(r.closed_components, 1u);
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_EQ(r.faces_reoriented, 2u);
    EXPECT_GT(component_volumes(m)[0], 0);
  }
  {
    Mesh m;
    auto r = repair(cracked_cube(1e-4, true), m, MP::snap_epsilon(1e-3));
    EXPECT_EQ(r.edges_stitched, 12u);
    EXPECT_EQ(r.faces_out, 12u);
    EXPECT_EQ(r.vertices_out, 8u);
    EXPECT_EQ(r.components, 1u);
    EXPECT_EQ(r.closed_components, 1u);
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_EQ(r.components_flipped, 1u);  // the reversed quad, the smaller side
    EXPECT_EQ(r.faces_reoriented, 2u);
    EXPECT_GT(component_volumes(m)[0], 0);
  }
}

TYPED_TEST(Stitch_soup, StitchingNeverMakesComplexEdges)
{
  using Mesh = typename TypeParam::Mesh;
  // three separate triangles whose long edges lie within epsilon: at most one pair glues
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0),         //
              Point(1, 0, 1e-5), Point(0, 0, 1e-5), Point(0.5, -1, 0),  //
              Point(0, 1e-5, 0), Point(1, 1e-5, 0), Point(0.5, 0, 1)};
  s.polygons = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
  Mesh m;
  auto r = repair(s, m, MP::snap_epsilon(1e-3));
  EXPECT_EQ(r.faces_out, 3u);
  EXPECT_EQ(r.edges_stitched, 1u);
  EXPECT_EQ(r.components, 2u);
}

TYPED_TEST(Stitch_soup, BadInputIsReportedNotFatal)
{
  using Mesh = typename TypeParam::Mesh;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Point> pts = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(nan, 0, 0), Point(1, 1, 0)};
  std::vector<std::vector<int>> polys = {{0, 1, 2}, {1, 3, 2}, {1, 4, 99}, {-1, 1, 4}, {1, 4, 2}};
  Mesh m;
  auto r = mrepair::polygon_soup_to_manifold_mesh(pts, polys, m);
  check_output(m, r);
  EXPECT_EQ(r.status, mrepair::Status::partial);
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(r.non_finite_points, 1u);
  EXPECT_EQ(r.removed_non_finite, 1u);
  EXPECT_EQ(r.removed_invalid_index, 2u);
  EXPECT_EQ(r.faces_out, 2u);
  EXPECT_EQ(r.faces_in, 5u);

  Mesh e;
  std::vector<Point> no_pts;
  std::vector<std::vector<std::size_t>> no_polys;
  auto re = mrepair::polygon_soup_to_manifold_mesh(no_pts, no_polys, e);
  EXPECT_EQ(re.status, mrepair::Status::empty_input);
  EXPECT_EQ(face_count(e), 0u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(e));

  Mesh e2;
  auto re2 = mrepair::polygon_soup_to_manifold_mesh(pts, no_polys, e2);
  EXPECT_EQ(re2.status, mrepair::Status::empty_input);

  Mesh keep = to_mesh<Mesh>(cube());
  auto rp = mrepair::polygon_soup_to_manifold_mesh(pts, polys, keep, MP::merge_epsilon(-1.0));
  EXPECT_EQ(rp.status, mrepair::Status::invalid_parameter);
  EXPECT_EQ(face_count(keep), 12u);  // untouched
}

TYPED_TEST(Stitch_soup, DegeneratePolygonsAndNgons)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  // 0..4: an L-shaped (non-convex) hexagon minus one corner: pentagon in z = 0
  s.points = {Point(0, 0, 0), Point(2, 0, 0), Point(2, 1, 0), Point(1, 1, 0), Point(1, 2, 0), Point(0, 2, 0),
              Point(5, 0, 0), Point(6, 0, 0), Point(7, 0, 0), Point(0, 0, 0)};
  s.polygons = {{0, 1, 2, 3, 4, 5},  // L shape, area 3: 4 triangles
                {6, 7, 8},           // collinear
                {6, 6, 7},           // repeated index
                {6, 7},              // too few
                {9, 1, 2},           // point 9 equals point 0: the L's first ear again
                {0, 1, 1, 2}};       // consecutive repeat: triangle 0 1 2 once more
  Mesh m;
  auto r = repair(s, m);
  EXPECT_EQ(r.polygons_triangulated, 1u);
  EXPECT_EQ(r.removed_collinear, 1u);
  EXPECT_EQ(r.removed_degenerate_index, 2u);
  EXPECT_EQ(r.removed_duplicate, 2u);
  EXPECT_EQ(r.points_merged, 1u);
  EXPECT_EQ(r.points_unreferenced, 3u);
  EXPECT_EQ(r.faces_in, 4u + 1 + 1 + 1 + 1 + 1);
  EXPECT_EQ(r.faces_out, 4u);
  // the L is covered exactly once: total area 3, one component, 6 boundary edges
  double area = 0;
  for (auto f : faces(m)) area += CGAL::to_double(PMP::face_area(f, m));
  EXPECT_NEAR(area, 3.0, 1e-12);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.boundary_edges, 6u);
}

TYPED_TEST(Stitch_soup, CancelLeavesMeshUntouched)
{
  using Mesh = typename TypeParam::Mesh;
  struct Stop : mrepair::Default_visitor
  {
    int phases = 0;
    void start_phase(const char*) { ++phases; }
    bool stop_requested() { return true; }
  } stop;
  Mesh m = to_mesh<Mesh>(cube());
  Soup s = icosphere(1);
  auto r = mrepair::polygon_soup_to_manifold_mesh(s.points, s.polygons, m, CGAL::parameters::visitor(std::ref(stop)));
  EXPECT_EQ(r.status, mrepair::Status::cancelled);
  EXPECT_EQ(face_count(m), 12u);
  EXPECT_GE(stop.phases, 1);
}

TEST(Stitch_soup_stages, InPlaceSoupStages)
{
  Soup s = cracked_cube(1e-4, true);
  std::vector<Point> pts = s.points;
  std::vector<std::vector<std::size_t>> polys = s.polygons;
  auto r = mrepair::clean_polygon_soup(pts, polys, MP::merge_epsilon(1e-3));
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(pts.size(), 8u);
  EXPECT_EQ(polys.size(), 12u);
  EXPECT_FALSE(PMP::is_polygon_soup_a_polygon_mesh(polys));  // quad 0 still reversed

  std::vector<Point> pts2 = s.points;
  std::vector<std::array<std::size_t, 3>> tris;
  pts2 = pts;
  for (auto& p : polys) tris.push_back({p[0], p[1], p[2]});
  auto r2 = mrepair::repair_polygon_soup_to_manifold(pts2, tris);
  EXPECT_EQ(r2.status, mrepair::Status::ok);
  EXPECT_EQ(tris.size(), 12u);
  EXPECT_EQ(pts2.size(), 8u);
  EXPECT_EQ(r2.faces_reoriented, 2u);
  EXPECT_TRUE(PMP::is_polygon_soup_a_polygon_mesh(tris));
}

TYPED_TEST(Stitch_soup, RealMeshSplitIntoUnindexedTriangles)
{
  using Mesh = typename TypeParam::Mesh;
  std::string path = std::string(MREPAIR_CGAL_DATA_DIR) + "/elephant.off";
  std::ifstream in(path);
  if (!in) GTEST_SKIP() << "no " << path;
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  ASSERT_TRUE(CGAL::IO::read_polygon_soup(path, pts, polys));
  Soup s;
  std::mt19937 rng(3);
  std::size_t flipped = 0;
  for (const Polygon& p : polys) {
    Polygon q;
    for (std::size_t i : p) {
      s.points.push_back(pts[i]);
      q.push_back(s.points.size() - 1);
    }
    if (rng() % 5 == 0) {
      std::reverse(q.begin(), q.end());
      ++flipped;
    }
    s.polygons.push_back(q);
  }
  Mesh m;
  auto r = repair(s, m);
  EXPECT_EQ(r.faces_out, polys.size());
  EXPECT_EQ(r.faces_reoriented, flipped);
  EXPECT_EQ(r.closed_components, 1u);
}

#ifdef MREPAIR_GENERATOR
namespace {
// the integer after "key": in a manifest (flat JSON numbers only)
long manifest_count(const std::string& json, const std::string& key)
{
  std::size_t at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return -1;
  return std::strtol(json.c_str() + at + key.size() + 3, nullptr, 10);
}
} // namespace

TYPED_TEST(Stitch_soup, GeneratedCadSoup)
{
  using Mesh = typename TypeParam::Mesh;
  const std::string dir = ::testing::TempDir();
  const std::string stl = dir + "/mrepair_soup_cad.stl", json = dir + "/mrepair_soup_cad.json";
  if (!std::ifstream(MREPAIR_GENERATOR)) GTEST_SKIP() << "mrepair-generate not built";
  const std::string cmd = std::string(MREPAIR_GENERATOR) + " cad --faces 20000 --seed 5 --output " + stl +
                          " --manifest " + json + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream in(json);
  std::string manifest((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  ASSERT_TRUE(CGAL::IO::read_polygon_soup(stl, pts, polys));
  const double diag = 4.16893271714;  // the generator's part has a fixed size
  Mesh m;
  auto r = repair(Soup{pts, polys}, m, MP::snap_epsilon(1e-3 * diag));
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(long(r.removed_duplicate), manifest_count(manifest, "duplicate_face"));
  EXPECT_EQ(long(r.removed_collinear), manifest_count(manifest, "degenerate_face.collinear"));
  EXPECT_EQ(long(r.removed_degenerate_index), manifest_count(manifest, "degenerate_face.repeated_index"));
  EXPECT_EQ(long(r.faces_reoriented), manifest_count(manifest, "flipped_face"));
  EXPECT_GE(long(r.complex_edges), manifest_count(manifest, "fin"));
  EXPECT_GT(r.edges_stitched, 0u);
}
#endif

#ifdef MREPAIR_CLI
TEST(Stitch_soup_cli, CrackedCubeFileBecomesClosed)
{
  if (!std::ifstream(MREPAIR_CLI)) GTEST_SKIP() << "mrepair not built";
  const std::string dir = ::testing::TempDir();
  const std::string in = dir + "/mrepair_soup_cli_in.off", out = dir + "/mrepair_soup_cli_out.off",
                    report = dir + "/mrepair_soup_cli.json";
  Soup s = cracked_cube(1e-4, true);
  {
    std::ofstream f(in);
    f.precision(17);
    f << "OFF\n" << s.points.size() << " " << s.polygons.size() << " 0\n";
    for (const Point& p : s.points) f << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const Polygon& p : s.polygons) f << "4 " << p[0] << " " << p[1] << " " << p[2] << " " << p[3] << "\n";
  }
  std::string cmd = std::string(MREPAIR_CLI) + " soup " + in + " " + out + " --epsilon 1e-3 --quiet --report " +
                    report + " > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  Surface_mesh m;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(out, m));
  EXPECT_EQ(face_count(m), 12u);
  EXPECT_TRUE(CGAL::is_closed(m));
  std::ifstream r(report);
  std::string json((std::istreambuf_iterator<char>(r)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"edges_stitched\": 12"), std::string::npos);

  std::string bad = std::string(MREPAIR_CLI) + " soup " + dir + "/no_such_file.off " + out + " 2> /dev/null";
  EXPECT_NE(std::system(bad.c_str()), 0);
}
#endif

} // namespace stitch_soup_tests
} // namespace
