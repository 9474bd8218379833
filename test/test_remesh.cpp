// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Tests of isotropic_remesh / adaptive_remesh / remesh_to_face_count (issue 7).
#include <mrepair/adaptive_remesh.h>
#include <mrepair/internal/adaptive_remesh/reference_surface.h>

#include "fixtures.h"

#include <mrepair/internal/cgal_compat.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/boost/graph/IO/OFF.h>

#include <fstream>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

// A namespace of its own: this file is compiled in one translation unit with
// other test files (a unity build, CMakeLists.txt).
namespace {
namespace remesh_tests {

using namespace mrepair_test;
namespace MP = mrepair::parameters;

template <class C>
class Remesh : public ::testing::Test
{};
TYPED_TEST_SUITE(Remesh, Mesh_configs);

namespace {

template <class Mesh>
void expect_valid(const Mesh& m)
{
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(CGAL::is_triangle_mesh(m));
}

// Polyhedron_3 and Surface_mesh both have `point(v)` through the vertex point map.
template <class Mesh>
Point pt(const Mesh& m, typename boost::graph_traits<Mesh>::vertex_descriptor v)
{
  return get(CGAL::vertex_point, m, v);
}

template <class Mesh>
double mean_edge_length(const Mesh& m)
{
  double s = 0;
  std::size_t n = 0;
  for (auto e : edges(m)) {
    auto h = halfedge(e, m);
    s += std::sqrt(CGAL::squared_distance(pt(m, source(h, m)), pt(m, target(h, m))));
    ++n;
  }
  return n ? s / n : 0;
}

template <class Mesh>
double dihedral_cos(const Mesh& m, typename boost::graph_traits<Mesh>::halfedge_descriptor h)
{
  auto n = [&](typename boost::graph_traits<Mesh>::halfedge_descriptor g) {
    Point a = pt(m, source(g, m)), b = pt(m, target(g, m)), c = pt(m, target(next(g, m), m));
    return CGAL::cross_product(b - a, c - a);
  };
  auto n1 = n(h), n2 = n(opposite(h, m));
  return n1 * n2 / std::sqrt(n1.squared_length() * n2.squared_length());
}

// max distance from the output's vertices, edge midpoints and face centroids to `ref`
template <class Mesh>
double one_sided_distance(const Mesh& out, const Mesh& ref)
{
  using Prim = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
  using Tree = mrepair::internal::Aabb_tree<K, Prim>;
  Tree tree(faces(ref).first, faces(ref).second, ref);
  tree.accelerate_distance_queries();
  double d = 0;
  for (auto f : faces(out)) {
    auto h = halfedge(f, out);
    Point a = pt(out, source(h, out)), b = pt(out, target(h, out)),
          c = pt(out, target(next(h, out), out));
    for (const Point& q : {a, CGAL::midpoint(a, b), CGAL::centroid(a, b, c)})
      d = std::max(d, std::sqrt(tree.squared_distance(q)));
  }
  return d;
}

} // namespace

namespace {

// torus of radii R (of the centre circle) and r (of the tube), nu x nv quads
// split in triangles, outward.
Soup torus(double R, double r, std::size_t nu, std::size_t nv)
{
  Soup s;
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t j = 0; j < nv; ++j) {
      const double u = 2 * CGAL_PI * double(i) / double(nu), v = 2 * CGAL_PI * double(j) / double(nv);
      s.points.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                            r * std::sin(v));
    }
  auto id = [&](std::size_t i, std::size_t j) { return (i % nu) * nv + (j % nv); };
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t j = 0; j < nv; ++j) {
      s.polygons.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.polygons.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

// a flat 4 x 4 square whose border has `per_side` edges a side, filled
// with Liepa's triangulation (CGAL's triangulate_hole_polyline)
Soup liepa_square(int per_side)
{
  Soup s;
  const double step = 4. / per_side;
  for (int i = 0; i < per_side; ++i) s.points.emplace_back(step * i, 0, 0);
  for (int i = 0; i < per_side; ++i) s.points.emplace_back(4, step * i, 0);
  for (int i = 0; i < per_side; ++i) s.points.emplace_back(4 - step * i, 4, 0);
  for (int i = 0; i < per_side; ++i) s.points.emplace_back(0, 4 - step * i, 0);
  std::vector<CGAL::Triple<int, int, int>> triangles;
  CGAL::Polygon_mesh_processing::triangulate_hole_polyline(s.points, std::back_inserter(triangles));
  for (const auto& t : triangles)
    s.polygons.push_back({std::size_t(t.first), std::size_t(t.second), std::size_t(t.third)});
  return s;
}

template <class Mesh>
double min_angle_deg(const Mesh& m)
{
  double best = 180;
  for (auto f : faces(m)) {
    auto h = halfedge(f, m);
    Point p[3] = {pt(m, source(h, m)), pt(m, target(h, m)), pt(m, target(next(h, m), m))};
    for (int i = 0; i < 3; ++i) {
      K::Vector_3 u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
      double c = u * v / std::sqrt(u.squared_length() * v.squared_length());
      best = std::min(best, std::acos(std::max(-1., std::min(1., c))) * 180. / CGAL_PI);
    }
  }
  return best;
}

// fandisk has no self-intersection, narrow strips between feature lines and
// a 19.4 degree wedge between two lines at a corner: remeshing, coarse or
// fine, uniform or adaptive, must not fold a face through another, and the
// final min-angle pass keeps the smallest angle above CGAL 5.5's 18.5 degrees
// (mean input length 0.0207, 3 iterations).
template <class Mesh>
std::size_t component_count(const Mesh& m)
{
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;
  std::set<face_descriptor> seen;
  std::size_t n = 0;
  for (face_descriptor f : faces(m)) {
    if (!seen.insert(f).second) continue;
    ++n;
    std::vector<face_descriptor> stack{f};
    while (!stack.empty()) {
      face_descriptor g = stack.back();
      stack.pop_back();
      for (auto h : CGAL::halfedges_around_face(halfedge(g, m), m)) {
        auto o = opposite(h, m);
        if (!is_border(o, m) && seen.insert(face(o, m)).second) stack.push_back(face(o, m));
      }
    }
  }
  return n;
}

} // namespace

// Remeshing changes the sampling, never the shape's topology: a torus (no
// feature, every dihedral angle under 23 degrees) refined to a third of its
// edge length stays one closed surface of genus 1 (V - E + F = 0), and every
// vertex stays on the input, within the input's chord error of the true torus.
// collect_garbage(false) leaves the collapses' removed elements in a
// Surface_mesh (as CGAL's remeshing does; the CLI writes around them): the
// same mesh otherwise, which collect_garbage() then makes element for
// element the one the default call returns; with threads and without.
TEST(Remesh_garbage, left_uncollected_the_mesh_is_the_same_once_collected)
{
  for (bool threads : {false, true}) {
    Surface_mesh collected = to_mesh<Surface_mesh>(icosphere(4));
    Surface_mesh left = collected;
    const double L = 2.5 * mean_edge_length(collected);  // coarser: many collapses
    auto remesh = [&](Surface_mesh& m, bool gc) {
      auto np = MP::collect_garbage(gc, MP::number_of_iterations(3));
      return threads ? mrepair::isotropic_remesh<CGAL::Parallel_if_available_tag>(m, L, np)
                     : mrepair::isotropic_remesh(m, L, np);
    };
    const mrepair::Remeshing_result a = remesh(collected, true), b = remesh(left, false);
    ASSERT_EQ(a.status, mrepair::Status::ok);
    ASSERT_EQ(b.status, mrepair::Status::ok);
    EXPECT_FALSE(collected.has_garbage());
    EXPECT_TRUE(left.has_garbage());
    expect_valid(left);
    EXPECT_EQ(a.faces_after, b.faces_after);
    EXPECT_EQ(b.faces_after, faces(left).size());
    EXPECT_EQ(a.collapses, b.collapses);
    EXPECT_GT(b.collapses, 100u);
    left.collect_garbage();
    ASSERT_EQ(left.number_of_vertices(), collected.number_of_vertices());
    ASSERT_EQ(left.number_of_faces(), collected.number_of_faces());
    for (auto v : vertices(left)) ASSERT_EQ(left.point(v), collected.point(v));
    for (auto f : faces(left)) {
      auto h = left.halfedge(f), g = collected.halfedge(f);
      for (int k = 0; k < 3; ++k, h = left.next(h), g = collected.next(g)) ASSERT_EQ(left.target(h), collected.target(g));
    }
  }
}

TYPED_TEST(Remesh, torus_keeps_its_genus_and_stays_on_the_surface)
{
  using Mesh = typename TypeParam::Mesh;
  const double R = 2, r = 0.7;
  Mesh m = to_mesh<Mesh>(torus(R, r, 32, 16));  // edges 0.25 to 0.53
  ASSERT_EQ(vertices(m).size() + faces(m).size(), edges(m).size());
  const std::size_t f0 = face_count(m);
  auto res = mrepair::isotropic_remesh(m, 0.15, CGAL::parameters::number_of_iterations(3));
  ASSERT_EQ(res.status, mrepair::Status::ok) << res.message;
  expect_valid(m);
  EXPECT_TRUE(CGAL::is_closed(m));
  EXPECT_EQ(res.feature_edges, 0u);
  EXPECT_GT(face_count(m), 4 * f0);
  EXPECT_EQ(res.faces_after, face_count(m));
  const long long chi = static_cast<long long>(vertices(m).size()) -
                        static_cast<long long>(edges(m).size()) +
                        static_cast<long long>(faces(m).size());
  EXPECT_EQ(chi, 0) << "genus changed";
  EXPECT_EQ(component_count(m), 1u);
  // chord error of the input: 2.7 (1 - cos(pi/32)) + 0.7 (1 - cos(pi/16)) < 0.027
  double worst = 0;
  for (auto v : vertices(m)) {
    const Point p = pt(m, v);
    const double d = std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r;
    worst = (std::max)(worst, std::abs(d));
  }
  EXPECT_LT(worst, 0.03);
  EXPECT_NEAR(mean_edge_length(m), 0.15, 0.02);
}

// A unit cube keeps its 12 sharp edges as 12 polylines between its 8 corners.
TYPED_TEST(Remesh, cube_keeps_edges_and_corners)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(cube(1.0));
  auto r = mrepair::isotropic_remesh(m, 0.1);
  ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
  expect_valid(m);
  EXPECT_EQ(r.feature_edges, 12u);
  EXPECT_EQ(r.corners, 8u);
  EXPECT_GT(face_count(m), 300u);  // 6 faces of area 1 at L = 0.1: ~460 faces
  std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, int> sharp;
  double sharp_length = 0;
  for (auto e : edges(m)) {
    auto h = halfedge(e, m);
    if (dihedral_cos(m, h) > 0.5) continue;  // sharp: normals more than 60 deg apart
    ++sharp[source(h, m)];
    ++sharp[target(h, m)];
    Point a = pt(m, source(h, m)), b = pt(m, target(h, m));
    sharp_length += std::sqrt(CGAL::squared_distance(a, b));
    // on a cube edge: at least two coordinates of both ends in {0, 1}
    int on = 0;
    for (int i = 0; i < 3; ++i)
      on += (a[i] == 0 || a[i] == 1) && a[i] == b[i];
    EXPECT_GE(on, 2);
  }
  int corners = 0, inner = 0;
  for (auto& kv : sharp) {
    if (kv.second == 3) {
      ++corners;
      Point p = pt(m, kv.first);
      for (int i = 0; i < 3; ++i) EXPECT_TRUE(p[i] == 0 || p[i] == 1);
    } else {
      EXPECT_EQ(kv.second, 2);
      ++inner;
    }
  }
  EXPECT_EQ(corners, 8);
  EXPECT_NEAR(sharp_length, 12.0, 1e-9);
  // 8 corners x 3 = 24 line ends = 12 polylines; every polyline got split
  EXPECT_GE(inner, 12 * 5);
  for (auto v : vertices(m)) {  // still on the cube surface
    Point p = pt(m, v);
    bool on_face = false;
    for (int i = 0; i < 3; ++i) {
      EXPECT_GE(p[i], -1e-12);
      EXPECT_LE(p[i], 1 + 1e-12);
      on_face = on_face || std::abs(p[i]) < 1e-9 || std::abs(p[i] - 1) < 1e-9;
    }
    EXPECT_TRUE(on_face);
  }
}

// A 1x1 plane with its boundary keeps its square outline.
TYPED_TEST(Remesh, plane_keeps_outline)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(10, 10, 0.1));
  auto r = mrepair::isotropic_remesh(m, 0.045);
  ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
  expect_valid(m);
  EXPECT_EQ(r.corners, 4u);
  std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor> border;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(m, std::back_inserter(border));
  EXPECT_EQ(border.size(), 1u);
  double outline = 0;
  int square_corners = 0;
  for (auto h : halfedges(m)) {
    if (!is_border(h, m)) continue;
    Point a = pt(m, source(h, m)), b = pt(m, target(h, m));
    outline += std::sqrt(CGAL::squared_distance(a, b));
    EXPECT_TRUE((a.x() == b.x() && (a.x() == 0 || a.x() == 1)) ||
                (a.y() == b.y() && (a.y() == 0 || a.y() == 1)));
    if ((a.x() == 0 || a.x() == 1) && (a.y() == 0 || a.y() == 1)) ++square_corners;
  }
  EXPECT_NEAR(outline, 4.0, 1e-9);
  EXPECT_EQ(square_corners, 4);
  for (auto v : vertices(m)) EXPECT_EQ(pt(m, v).z(), 0.0);
  EXPECT_GT(face_count(m), 200u * 2);  // 200 input faces, L halved-ish
}

// Found through the hole filler: one coarse flat patch (a square of 32
// border edges, two triangles across it) remeshed to a quarter of its border
// edges. The relaxation moves every vertex at once; undoing a move that
// folded a face could fold a neighbour that was checked against the undone
// position, and the output crossed itself after one iteration.
TYPED_TEST(Remesh, dense_flat_patch_does_not_fold)
{
  using Mesh = typename TypeParam::Mesh;
  const Soup s = liepa_square(8);
  ASSERT_EQ(s.polygons.size(), 30u);
  for (bool protect : {false, true}) {
    Mesh m = to_mesh<Mesh>(s);
    auto r = mrepair::isotropic_remesh(
        m, 0.125, CGAL::parameters::protect_constraints(protect).number_of_iterations(1));
    ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
    expect_valid(m);
    EXPECT_GT(face_count(m), 2000u);
    EXPECT_FALSE(CGAL::Polygon_mesh_processing::does_self_intersect(m)) << "protect " << protect;
  }
}

// A protected border 4 and 8 times coarser than the target can never be
// split: the faces beside it kept a long side, every split of that side
// halved their height, and after 10 iterations a square of border edges 4 L
// had 3,320 degenerate faces out of 6,580. The mesh now grades away from
// the long edges instead.
TYPED_TEST(Remesh, protected_coarse_border_does_not_degenerate)
{
  using Mesh = typename TypeParam::Mesh;
  for (int per_side : {4, 8}) {
    Mesh m = to_mesh<Mesh>(liepa_square(per_side));
    auto r = mrepair::isotropic_remesh(
        m, 0.125, CGAL::parameters::protect_constraints(true).number_of_iterations(10));
    ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
    expect_valid(m);
    EXPECT_GT(face_count(m), 1500u) << per_side;
    EXPECT_LT(face_count(m), 4000u) << per_side;
    std::size_t degenerate = 0;
    for (auto f : faces(m))
      degenerate += CGAL::Polygon_mesh_processing::is_degenerate_triangle_face(f, m) ? 1 : 0;
    EXPECT_EQ(degenerate, 0u) << per_side;
    EXPECT_FALSE(CGAL::Polygon_mesh_processing::does_self_intersect(m)) << per_side;
    EXPECT_GT(min_angle_deg(m), 3.) << per_side;
    std::size_t border = 0;
    for (auto h : halfedges(m)) border += is_border(h, m) ? 1 : 0;
    EXPECT_EQ(border, std::size_t(4 * per_side)) << "the protected border stays as it was";
  }
}

// A sphere reaches the requested edge length within 10% on average.
TYPED_TEST(Remesh, sphere_reaches_target_length)
{
  using Mesh = typename TypeParam::Mesh;
  for (double L : {0.05, 0.12, 0.3}) {
    Mesh m = to_mesh<Mesh>(icosphere(3));
    auto r = mrepair::isotropic_remesh(m, L);
    ASSERT_EQ(r.status, mrepair::Status::ok);
    expect_valid(m);
    EXPECT_NEAR(mean_edge_length(m), L, 0.1 * L) << "L = " << L;
    EXPECT_EQ(r.feature_edges, 0u);
    for (auto v : vertices(m))
      EXPECT_NEAR(std::sqrt((pt(m, v) - CGAL::ORIGIN).squared_length()), 1.0, 0.02);
  }
}

// Remeshing a part leaves the rest bit-identical (same faces, same coordinates).
TYPED_TEST(Remesh, part_leaves_rest_identical)
{
  using Mesh = typename TypeParam::Mesh;
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;
  Mesh m = to_mesh<Mesh>(icosphere(3));
  using Tri = std::array<std::array<double, 3>, 3>;
  auto key = [&](face_descriptor f) {
    Tri t;
    int k = 0;
    for (auto v : vertices_around_face(halfedge(f, m), m)) {
      Point p = pt(m, v);
      t[k++] = {p.x(), p.y(), p.z()};
    }
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // keep orientation
    return t;
  };
  std::vector<face_descriptor> part;
  std::multiset<Tri> rest;
  for (face_descriptor f : faces(m)) {
    Point c = pt(m, target(halfedge(f, m), m));
    if (c.z() > 0.3)
      part.push_back(f);
    else
      rest.insert(key(f));
  }
  const std::size_t part_before = part.size();
  auto r = mrepair::isotropic_remesh(part, m, 0.05);
  ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
  expect_valid(m);
  std::multiset<Tri> after;
  for (face_descriptor f : faces(m)) after.insert(key(f));
  for (const Tri& t : rest) EXPECT_EQ(after.count(t), rest.count(t));
  EXPECT_GT(face_count(m) - rest.size(), 2 * part_before);  // the part got finer
  for (auto v : vertices(m))
    EXPECT_NEAR(std::sqrt((pt(m, v) - CGAL::ORIGIN).squared_length()), 1.0, 0.02);
}

// area of a triangle mesh
template <typename Mesh>
double mesh_area(const Mesh& m)
{
  double a = 0;
  for (auto f : faces(m)) {
    auto h = halfedge(f, m);
    a += std::sqrt(CGAL::squared_area(pt(m, source(h, m)), pt(m, target(h, m)), pt(m, target(next(h, m), m))));
  }
  return a;
}

// Adaptive: a smaller error than uniform with as many faces on a shape of varying curvature.
TYPED_TEST(Remesh, adaptive_beats_uniform_on_ellipsoid)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = icosphere(5);
  for (Point& p : s.points) p = Point(3 * p.x(), p.y(), 0.5 * p.z());
  const Mesh input = to_mesh<Mesh>(s);
  Mesh a = input;
  auto ra = mrepair::adaptive_remesh(a, 0.002);
  ASSERT_EQ(ra.status, mrepair::Status::ok) << ra.message;
  expect_valid(a);
  EXPECT_LT(ra.min_target, ra.max_target);
  const double ha = one_sided_distance(a, input);
  // uniform with the edge length of equilateral triangles at the same count
  Mesh u = input;
  const double L = std::sqrt(4. * mesh_area(input) / (std::sqrt(3.) * double(face_count(a))));
  auto ru = mrepair::isotropic_remesh(u, L);
  ASSERT_EQ(ru.status, mrepair::Status::ok) << ru.message;
  expect_valid(u);
  const double hu = one_sided_distance(u, input);
  EXPECT_LT(ha, hu) << "adaptive " << face_count(a) << " faces, " << ha << "; uniform "
                    << face_count(u) << " faces, " << hu;
  // the error control keeps the sampled deviation near the tolerance
  EXPECT_LT(ha, 2 * 0.002);
}

// Issue 52: the relaxation after the last error-control round moved faces
// over the tolerance again, and a Hausdorff distance is its worst face: on
// this ellipsoid (lengths up to 0.05 x diagonal, as in the harness's sweep)
// the mesh-to-input distance was 1.26 x the tolerance at 0.0003 x diagonal
// and 1.32 x at 0.0008 (the 1M scan: 1.5 x). The faces still over it after
// the last iteration are split at the input surface, and the min-angle pass
// after that keeps the smallest angle.
TYPED_TEST(Remesh, adaptive_faces_end_within_the_tolerance)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = icosphere(5);
  for (Point& p : s.points) p = Point(3 * p.x(), p.y(), 0.5 * p.z());
  const Mesh input = to_mesh<Mesh>(s);
  const double diag = 2. * std::sqrt(9. + 1. + 0.25);
  for (double relative : {0.0003, 0.0008}) {
    Mesh a = input;
    const double tolerance = relative * diag;
    auto r = mrepair::adaptive_remesh(a, tolerance, mrepair::parameters::remesh_max_edge_length(0.05 * diag));
    ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
    expect_valid(a);
    EXPECT_LT(one_sided_distance(a, input), 1.02 * tolerance) << relative << " x diagonal";
    EXPECT_GT(min_angle_deg(a), 29.) << relative << " x diagonal";
  }
}

// remesh_to_face_count: within 2% of the count, adaptive (a smaller error
// than uniform remeshing at about the same count) and its tolerance reported
TYPED_TEST(Remesh, face_count_within_two_percent)
{
  using Mesh = typename TypeParam::Mesh;
  for (std::size_t n : {500u, 4000u}) {
    Mesh m = to_mesh<Mesh>(icosphere(3));
    auto r = mrepair::remesh_to_face_count(m, n);
    ASSERT_EQ(r.status, mrepair::Status::ok);
    expect_valid(m);
    EXPECT_NEAR(double(face_count(m)), double(n), 0.02 * n);
    EXPECT_EQ(r.target_faces, n);
  }
  Soup s = icosphere(5);
  for (Point& p : s.points) p = Point(3 * p.x(), p.y(), 0.5 * p.z());
  const Mesh input = to_mesh<Mesh>(s);
  for (std::size_t n : {1500u, 6000u}) {
    Mesh m = input;
    auto r = mrepair::remesh_to_face_count(m, n);
    ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
    expect_valid(m);
    EXPECT_NEAR(double(face_count(m)), double(n), 0.02 * n);
    EXPECT_GT(r.tolerance, 0.);
    Mesh u = input;
    const double L = std::sqrt(4. * mesh_area(input) / (std::sqrt(3.) * double(face_count(m))));
    ASSERT_EQ(mrepair::isotropic_remesh(u, L).status, mrepair::Status::ok);
    EXPECT_LT(one_sided_distance(m, input), one_sided_distance(u, input))
        << n << " faces: adaptive " << face_count(m) << ", uniform " << face_count(u);
  }
}

// A stray vertex 1e19 away (fuzz finding 4) makes a sliver far thinner than
// the target length: splits and collapses traded it back and forth for
// minutes. The operation budget (100 per input and target face) stops it.
TYPED_TEST(Remesh, face_count_on_a_far_sliver_keeps_to_its_budget)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  s.points = {{1.3, 0, 0},     {0.7, 0, 0},   {-9.9151249396188815e18, 3.5000001, 2},
              {-4, -4, -3},    {-3.5, -4, -3.5}, {-3, -2.5, -4}, {-3, -2, -2.5},
              {-4, -2.5, -2},  {-1.5, -4, -2}, {1.3, 0, 0},   {-3, -2.5, -4}};
  s.polygons = {{2, 3, 0}, {3, 5, 0}, {4, 10, 9}, {0, 5, 6}, {7, 6, 5}, {7, 8, 6}, {1, 8, 7}};
  Mesh m = to_mesh<Mesh>(s);
  auto r = mrepair::remesh_to_face_count(m, 100, CGAL::parameters::number_of_iterations(3));
  EXPECT_TRUE(r.status == mrepair::Status::ok || r.status == mrepair::Status::partial)
      << mrepair::to_string(r.status);
  EXPECT_LE(r.splits + r.collapses, 100u * (7 + 100));
  if (r.status == mrepair::Status::partial) {
    EXPECT_FALSE(r.message.empty());
  }
  expect_valid(m);
  EXPECT_EQ(r.faces_after, face_count(m));
}

// Issue 52: a count that needs edges longer than the user's
// remesh_max_edge_length (with a minimum given, so that the tolerance found
// cannot lift the field over it) cannot be reached: the field sits at the
// maximum everywhere. The call used to run its 8 scaling rounds for nothing
// and say `ok`; it now stops and says why, with a valid mesh.
TYPED_TEST(Remesh, face_count_below_what_the_maximum_length_allows_says_so)
{
  using Mesh = typename TypeParam::Mesh;
  namespace MP = mrepair::parameters;
  Mesh m = to_mesh<Mesh>(icosphere(4));  // unit sphere: ~320 faces at edge length 0.3
  auto r = mrepair::remesh_to_face_count(m, 100, MP::remesh_max_edge_length(0.3, MP::remesh_min_edge_length(0.01)));
  EXPECT_EQ(r.status, mrepair::Status::partial) << r.message;
  EXPECT_NE(r.message.find("longer than remesh_max_edge_length"), std::string::npos) << r.message;
  expect_valid(m);
  EXPECT_EQ(r.faces_after, face_count(m));
  EXPECT_GT(face_count(m), 200u);
  // within reach, the same bound does not get in the way
  Mesh w = to_mesh<Mesh>(icosphere(4));
  auto ok = mrepair::remesh_to_face_count(w, 1000, MP::remesh_max_edge_length(0.3, MP::remesh_min_edge_length(0.01)));
  EXPECT_EQ(ok.status, mrepair::Status::ok) << ok.message;
  EXPECT_NEAR(double(face_count(w)), 1000., 20.);
}

// A user edge map marks features; protect_constraints keeps them unsplit.
TYPED_TEST(Remesh, user_edge_map_and_protection)
{
  using Mesh = typename TypeParam::Mesh;
  using edge_descriptor = typename boost::graph_traits<Mesh>::edge_descriptor;
  Mesh m = to_mesh<Mesh>(cube(1.0));
  auto ecm = get(CGAL::dynamic_edge_property_t<bool>(), m);
  for (edge_descriptor e : edges(m)) put(ecm, e, dihedral_cos(m, halfedge(e, m)) < 0.5);
  auto r = mrepair::isotropic_remesh(
      m, 0.3, CGAL::parameters::edge_is_constrained_map(ecm).protect_constraints(true));
  ASSERT_EQ(r.status, mrepair::Status::ok);
  expect_valid(m);
  EXPECT_EQ(r.feature_edges, 12u);
  std::size_t marked = 0;
  for (edge_descriptor e : edges(m)) marked += get(ecm, e);
  EXPECT_EQ(marked, 12u);  // protected: not split
  Mesh m2 = to_mesh<Mesh>(cube(1.0));
  auto ecm2 = get(CGAL::dynamic_edge_property_t<bool>(), m2);
  for (edge_descriptor e : edges(m2)) put(ecm2, e, dihedral_cos(m2, halfedge(e, m2)) < 0.5);
  r = mrepair::isotropic_remesh(m2, 0.3, CGAL::parameters::edge_is_constrained_map(ecm2));
  std::size_t marked2 = 0;
  for (edge_descriptor e : edges(m2)) marked2 += get(ecm2, e);
  EXPECT_EQ(marked2, 12u * 4);  // each unit edge split into 4 edges of 0.25 (< 4/3 * 0.3)
}

TYPED_TEST(Remesh, bad_input)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh empty;
  EXPECT_EQ(mrepair::isotropic_remesh(empty, 0.1).status, mrepair::Status::empty_input);
  EXPECT_EQ(mrepair::adaptive_remesh(empty, 0.1).status, mrepair::Status::empty_input);
  Mesh m = to_mesh<Mesh>(icosphere(1));
  EXPECT_EQ(mrepair::isotropic_remesh(m, -1.0).status, mrepair::Status::invalid_parameter);
  EXPECT_EQ(mrepair::isotropic_remesh(m, std::nan("")).status,
            mrepair::Status::invalid_parameter);
  auto v = *vertices(m).first;
  put(CGAL::get(CGAL::vertex_point, m), v,
      Point(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  auto r = mrepair::isotropic_remesh(m, 0.1);
  EXPECT_EQ(r.status, mrepair::Status::non_finite_input);
  EXPECT_EQ(face_count(m), 80u);  // untouched
  expect_valid(m);
  Mesh q = to_mesh<Mesh>(grid(2, 2, 1.0, true));  // quads
  EXPECT_EQ(mrepair::isotropic_remesh(q, 0.1).status, mrepair::Status::invalid_mesh);
  EXPECT_EQ(face_count(q), 4u);
}

struct Stopper : mrepair::Default_visitor
{
  int phases = 0;
  void start_phase(const char*) { ++phases; }
  bool stop_requested() { return phases > 3; }
};

TYPED_TEST(Remesh, cancel_leaves_valid_mesh)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(icosphere(3));
  Stopper s;
  auto r = mrepair::isotropic_remesh(m, 0.05, CGAL::parameters::visitor(std::ref(s)));
  EXPECT_EQ(r.status, mrepair::Status::cancelled);
  expect_valid(m);
}

TYPED_TEST(Remesh, parallel_tag_and_real_mesh)
{
  using Mesh = typename TypeParam::Mesh;
  std::ifstream in(std::string(MREPAIR_CGAL_DATA_DIR) + "/fandisk.off");
  Mesh m;
  if (!in || !CGAL::IO::read_OFF(in, m)) GTEST_SKIP() << "fandisk.off not available";
  auto r = mrepair::isotropic_remesh<CGAL::Parallel_if_available_tag>(m, 0.01,
                                                                     CGAL::parameters::number_of_iterations(3));
  ASSERT_EQ(r.status, mrepair::Status::ok);
  expect_valid(m);
  EXPECT_GT(r.feature_edges, 100u);
}

// With threads the remesher's whole-mesh scans (the candidates of the
// splits, collapses, flips and cleanup, the vertices to relax) run in
// parallel and its flips come from a heap of the edges that passed the
// valence test or that a flip touched: the result must be the sequential
// one, point for point and face for face. Surface_mesh only: on Polyhedron_3
// the remesher runs sequentially with either tag. A torus of 25,600 faces
// (38,400 edges: past the size where the scans use threads), its points
// jittered so that every pass has work, remeshed to 0.6 and 1.5 times its
// mean edge length and adaptively.
TEST(Remesh_threads, parallel_passes_give_the_sequential_mesh)
{
  using Mesh = CGAL::Surface_mesh<Point>;
  Soup s = torus(2.0, 0.7, 160, 80);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  for (Point& p : s.points) p = Point(p.x() + jitter(rng), p.y() + jitter(rng), p.z() + jitter(rng));
  Mesh input;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(s.points, s.polygons, input);
  ASSERT_EQ(num_faces(input), 25600u);
  const double mean = mean_edge_length(input);
  auto same = [](const Mesh& a, const Mesh& b) {
    if (num_vertices(a) != num_vertices(b) || num_faces(a) != num_faces(b)) return false;
    for (auto v : vertices(a))
      if (a.point(v) != b.point(v)) return false;
    for (auto f : faces(a)) {
      auto ha = halfedge(f, a), hb = halfedge(f, b);
      for (int k = 0; k < 3; ++k, ha = next(ha, a), hb = next(hb, b))
        if (std::size_t(target(ha, a)) != std::size_t(target(hb, b))) return false;
    }
    return true;
  };
  for (double factor : {0.6, 1.5}) {
    Mesh seq = input, par = input;
    auto rs = mrepair::isotropic_remesh<CGAL::Sequential_tag>(seq, factor * mean,
                                                              CGAL::parameters::number_of_iterations(3));
    auto rp = mrepair::isotropic_remesh<CGAL::Parallel_if_available_tag>(par, factor * mean,
                                                                        CGAL::parameters::number_of_iterations(3));
    ASSERT_EQ(rs.status, mrepair::Status::ok);
    ASSERT_EQ(rp.status, mrepair::Status::ok);
    EXPECT_GT(rs.flips, 0u) << factor;
    EXPECT_GT(rs.splits + rs.collapses, 1000u) << factor;
    EXPECT_EQ(rs.flips, rp.flips) << factor;
    EXPECT_EQ(rs.splits, rp.splits) << factor;
    EXPECT_EQ(rs.collapses, rp.collapses) << factor;
    EXPECT_TRUE(same(seq, par)) << "factor " << factor;
    expect_valid(par);
  }
  Mesh seq = input, par = input;
  auto rs = mrepair::adaptive_remesh<CGAL::Sequential_tag>(seq, 0.002);
  auto rp = mrepair::adaptive_remesh<CGAL::Parallel_if_available_tag>(par, 0.002);
  ASSERT_EQ(rs.status, mrepair::Status::ok) << rs.message;
  ASSERT_EQ(rp.status, mrepair::Status::ok) << rp.message;
  EXPECT_TRUE(same(seq, par)) << "adaptive";
  expect_valid(par);
}

TYPED_TEST(Remesh, fandisk_no_self_intersections_and_min_angle)
{
  using Mesh = typename TypeParam::Mesh;
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::ifstream in(std::string(MREPAIR_CGAL_DATA_DIR) + "/fandisk.off");
  Mesh input;
  if (!in || !CGAL::IO::read_OFF(in, input)) GTEST_SKIP() << "fandisk.off not available";
  ASSERT_FALSE(PMP::does_self_intersect(input));
  for (double L : {0.0207, 0.05, 0.1}) {
    Mesh m = input;
    auto r = mrepair::isotropic_remesh(m, L, CGAL::parameters::number_of_iterations(3));
    ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
    expect_valid(m);
    EXPECT_GT(r.feature_edges, 100u);
    EXPECT_FALSE(PMP::does_self_intersect(m)) << "L = " << L;
    if (L < 0.03) {
      EXPECT_GT(min_angle_deg(m), 18.5);
    }
  }
  Mesh a = input;
  auto ra = mrepair::adaptive_remesh(a, 0.002);
  ASSERT_EQ(ra.status, mrepair::Status::ok) << ra.message;
  expect_valid(a);
  EXPECT_FALSE(PMP::does_self_intersect(a));
}

// Coarsening armadillo (L = 1.5 x its mean edge length, 10 iterations) folded
// faces through their neighbours at thin parts (7 intersecting pairs) before
// collapses and flips refused to create folds. Surface_mesh only: the
// Polyhedron_3 run adds ~15 s and exercises no other code.
TEST(Remesh_armadillo, coarse_remeshing_keeps_no_self_intersections)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::ifstream in(std::string(MREPAIR_CGAL_DATA_DIR) + "/armadillo.off");
  Surface_mesh m;
  if (!in || !CGAL::IO::read_OFF(in, m)) GTEST_SKIP() << "armadillo.off not available";
  ASSERT_FALSE(PMP::does_self_intersect<CGAL::Parallel_if_available_tag>(m));
  const double L = 1.5 * mean_edge_length(m);
  auto r = mrepair::isotropic_remesh(m, L, CGAL::parameters::number_of_iterations(10));
  ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
  expect_valid(m);
  EXPECT_LT(face_count(m), 30000u);  // 52000 input faces, coarsened
  EXPECT_FALSE(PMP::does_self_intersect<CGAL::Parallel_if_available_tag>(m));
}

// armadillo from CGAL's data (false when it is not there) and its bounding-box diagonal
bool read_armadillo(Surface_mesh& m, double& diag)
{
  std::ifstream in(std::string(MREPAIR_CGAL_DATA_DIR) + "/armadillo.off");
  if (!in || !CGAL::IO::read_OFF(in, m)) return false;
  CGAL::Bbox_3 box;
  for (const Point& p : m.points()) box += p.bbox();
  diag = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                   CGAL::square(box.zmax() - box.zmin()));
  return true;
}

// Issue 52: adaptive remeshing of armadillo at the coarse end of the sweep
// (lengths in [tolerance, 0.05 x diagonal]). Before, the final min-angle pass
// moved vertices so that their faces swung off the input: the mesh's largest
// deviation was 2.2 x the tolerance at 0.004 x diagonal, at faces that were
// all within it at the last error control (1.27 x at 0.008). The pass now
// keeps its moves within the tolerance: 1.37 x and 1.14 x. The other way
// (input to mesh) was 1.85 x and 1.32 x, not controlled; since stop 67 the
// faces nearest to input points farther than the tolerance are split toward
// them after the last iteration: 1.15 x and 1.08 x, held to 1.3 x and 1.2 x.
// Surface_mesh only (the remesher is the same code on both types; the typed
// tests cover Polyhedron_3).
TEST(Remesh_armadillo, adaptive_min_angle_pass_stays_within_the_tolerance)
{
  Surface_mesh input;
  double diag = 0;
  if (!read_armadillo(input, diag)) GTEST_SKIP() << "armadillo.off not available";
  for (const auto& [relative, bound, back] :
       {std::tuple<double, double, double>{0.004, 1.6, 1.3}, {0.008, 1.25, 1.2}}) {
    Surface_mesh m = input;
    const double tolerance = relative * diag;
    auto r = mrepair::adaptive_remesh<CGAL::Parallel_if_available_tag>(
        m, tolerance,
        mrepair::parameters::remesh_max_edge_length(0.05 * diag,
                                                    mrepair::parameters::remesh_min_edge_length(tolerance)));
    ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
    expect_valid(m);
    EXPECT_LT(face_count(m), 12000u);  // 52000 input faces
    EXPECT_LT(one_sided_distance(m, input), bound * tolerance) << "mesh to input at " << relative;
    EXPECT_LT(one_sided_distance(input, m), back * tolerance) << "input to mesh at " << relative;
  }
}

// Issue 52: remesh_to_face_count on armadillo at CGAL 6's count for 0.001 x
// diagonal (19,984 faces, 10 iterations, lengths up to 0.05 x diagonal).
// The mode used to refine only outliers at 3 x its tolerance: 0.0075 x
// diagonal at that count, twice CGAL 6's 0.0037. It now runs the adaptive
// mode's error control at a tolerance a pilot corrected for the shape:
// 0.0029 both ways. Held to CGAL 6's 0.0037 each way.
TEST(Remesh_armadillo, face_count_mode_is_as_accurate_as_the_adaptive_mode)
{
  Surface_mesh input;
  double diag = 0;
  if (!read_armadillo(input, diag)) GTEST_SKIP() << "armadillo.off not available";
  Surface_mesh m = input;
  const std::size_t target = 19984;
  auto r = mrepair::remesh_to_face_count<CGAL::Parallel_if_available_tag>(
      m, target,
      mrepair::parameters::remesh_max_edge_length(0.05 * diag, mrepair::parameters::number_of_iterations(10)));
  ASSERT_EQ(r.status, mrepair::Status::ok) << r.message;
  expect_valid(m);
  EXPECT_NEAR(double(face_count(m)), double(target), 0.02 * target);
  EXPECT_LT(one_sided_distance(m, input), 0.0037 * diag) << "mesh to input";
  EXPECT_LT(one_sided_distance(input, m), 0.0037 * diag) << "input to mesh";
}

// `ref` made of the triangles of `s`, every point off the lines, one sizing
void build_reference(mrepair::internal::remesh::Reference_surface& ref, const Soup& s, double sizing)
{
  for (const Point& p : s.points) ref.points.push_back(mrepair::internal::to_vec3(p));
  for (const Polygon& f : s.polygons) ref.triangles.push_back({int(f[0]), int(f[1]), int(f[2])});
  ref.on_line.assign(ref.points.size(), 0);
  ref.sizing.assign(ref.points.size(), sizing);
  ref.build();
}

// the distance from `q` to the nearest of all triangles of `ref` (brute force)
double distance_by_every_triangle(const mrepair::internal::remesh::Reference_surface& ref,
                                  const mrepair::internal::Vec3& q)
{
  namespace I = mrepair::internal;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : ref.triangles) {
    double u, v, w;
    const I::Vec3 p = mrepair::internal::remesh::Reference_surface::closest_on_triangle(
        q, ref.points[t[0]], ref.points[t[1]], ref.points[t[2]], u, v, w);
    best = std::min(best, I::squared_norm(I::sub(p, q)));
  }
  return std::sqrt(best);
}

// Issue 17: the reference surface builds its triangle tree on the first
// projection that needs it (no hint, or the local descent landing farther
// than asked), from several threads at once in the parallel relaxation.
// Both paths give the closest point of the input.
TEST(Remesh_issue_17, reference_tree_built_on_first_use_gives_the_closest_point)
{
  namespace R = mrepair::internal::remesh;
  namespace I = mrepair::internal;
  using I::Vec3;
  const Soup s = icosphere(3, 1.0);
  R::Reference_surface ref;
  build_reference(ref, s, 0.1);
  ASSERT_TRUE(ref.has_surface());
  auto nearest = [&](const Vec3& q) { return distance_by_every_triangle(ref, q); };
  const std::size_t n = 4000;
  std::vector<Vec3> q(n), by_tree(n), by_descent(n);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (Vec3& x : q) x = Vec3{{u(rng), u(rng), u(rng)}};
  // concurrent first uses of the tree: no hint, and a descent from a far
  // triangle with a tiny accepted distance
  mrepair::internal::parallel_for_index(n, 16, [&](std::size_t i) {
    double size = 0;
    int hint = -1;
    by_tree[i] = ref.project_surface(q[i], size, hint, 1.0);
    EXPECT_GE(hint, 0);
    EXPECT_NEAR(size, 0.1, 1e-12);
    int far_hint = int(i % ref.triangles.size());
    by_descent[i] = ref.project_surface(q[i], size, far_hint, 1e-9);
  });
  for (std::size_t i = 0; i < n; ++i) {
    const double d = nearest(q[i]);
    EXPECT_NEAR(I::distance(by_tree[i], q[i]), d, 1e-9) << i;
    EXPECT_NEAR(I::distance(by_descent[i], q[i]), d, 1e-9) << i;
  }
}

// Issue 49: the uniform remesher's projection walks from its hint across the
// input's edges (and through a corner's star) instead of evaluating whole
// vertex stars. From a
// hint one or two triangles away, on a bumpy closed surface and on an open
// one (its boundary edges have no triangle across), it must land on the
// closest point of the whole input for points near the surface, as vertices
// are after a relaxation step.
TEST(Remesh_issue_49, projection_walk_finds_the_closest_point_near_the_surface)
{
  namespace R = mrepair::internal::remesh;
  namespace I = mrepair::internal;
  using I::Vec3;
  for (const bool open : {false, true}) {
    const Soup s = icosphere(4, 1.0);
    R::Reference_surface ref;
    std::mt19937 rng(49);
    std::uniform_real_distribution<double> bump(-0.01, 0.01);
    for (const Point& p : s.points) {
      const Vec3 x = I::to_vec3(p);
      ref.points.push_back(I::mul(x, 1. + bump(rng)));
    }
    for (const Polygon& f : s.polygons) {
      const std::array<int, 3> t{int(f[0]), int(f[1]), int(f[2])};
      // the open case keeps the faces above z = -0.3: a boundary loop below
      if (open && ref.points[t[0]][2] + ref.points[t[1]][2] + ref.points[t[2]][2] < -0.9) continue;
      ref.triangles.push_back(t);
    }
    ref.on_line.assign(ref.points.size(), 0);
    ref.sizing.assign(ref.points.size(), 0.05);
    ref.build();
    ref.set_walk_edges(true);
    ASSERT_TRUE(ref.has_surface());
    std::uniform_real_distribution<double> unit(0., 1.), offset(-0.02, 0.02);
    std::uniform_int_distribution<int> pick(0, int(ref.triangles.size()) - 1);
    std::size_t walked_far = 0;
    for (int i = 0; i < 3000; ++i) {
      // a point of a random triangle, moved by ~ a third of an edge (0.075 here)
      const int t0 = pick(rng);
      const auto& t = ref.triangles[t0];
      double a = unit(rng), b = unit(rng);
      if (a + b > 1) { a = 1 - a; b = 1 - b; }
      Vec3 q = I::add(I::add(I::mul(ref.points[t[0]], 1 - a - b), I::mul(ref.points[t[1]], a)),
                      I::mul(ref.points[t[2]], b));
      q = I::add(q, Vec3{{offset(rng), offset(rng), offset(rng)}});
      const double best = distance_by_every_triangle(ref, q);
      // the hint: a triangle across an edge of t0 (or t0 on the boundary)
      const int start = ref.neighbour[t0][i % 3] >= 0 ? ref.neighbour[t0][i % 3] : t0;
      int hint = start;
      double size = 0;
      // a tiny accepted distance would send every query to the tree: accept all
      const Vec3 c = ref.project_surface(q, size, hint, 10.);
      EXPECT_NEAR(I::distance(c, q), best, 1e-12) << (open ? "open " : "closed ") << i;
      EXPECT_NEAR(size, 0.05, 1e-12);
      if (hint != start) ++walked_far;
    }
    EXPECT_GT(walked_far, 0u);  // the walk moved off its hint
  }
}

// Issue 52: on a fine input the error control's samples of a coarse face lie
// many input edges from the hint, beyond the local search's steps; the point
// where it stopped overstated the deviation, and the adaptive mode refined a
// 1M-face scan 10 x beyond CGAL 6's count at 0.18 x the tolerance. A search
// that runs out of steps asks the tree: from a hint a quarter of the sphere
// away, both searches give the closest point of the whole input.
TEST(Remesh_issue_52, projection_far_from_its_hint_gives_the_closest_point)
{
  namespace R = mrepair::internal::remesh;
  namespace I = mrepair::internal;
  using I::Vec3;
  const Soup s = icosphere(5, 1.0);  // 20,480 triangles, edges ~0.04
  for (const bool walk : {false, true}) {
    R::Reference_surface ref;
    build_reference(ref, s, 0.1);
    ref.set_walk_edges(walk);
    std::mt19937 rng(52);
    std::normal_distribution<double> g(0., 1.);
    for (int i = 0; i < 200; ++i) {
      Vec3 d{{g(rng), g(rng), g(rng)}};
      d = I::mul(d, 1. / I::norm(d));
      const Vec3 q = I::mul(d, 1.05);
      // the hint: the triangle nearest to a point a quarter turn away
      const Vec3 side = I::norm(I::cross(d, Vec3{{0, 0, 1}})) > 0.1 ? I::cross(d, Vec3{{0, 0, 1}})
                                                                     : I::cross(d, Vec3{{1, 0, 0}});
      const Vec3 far_point = I::mul(side, 1. / I::norm(side));
      int hint = -1;
      double size = 0;
      ref.project_surface_tree(far_point, size, hint);
      const Vec3 c = ref.project_surface(q, size, hint, 10.);  // any distance accepted
      EXPECT_NEAR(I::distance(c, q), distance_by_every_triangle(ref, q), 1e-12)
          << (walk ? "walk " : "descent ") << i;
    }
  }
}

} // namespace remesh_tests
} // namespace
