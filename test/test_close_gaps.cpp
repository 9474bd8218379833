// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Tests of close_gaps() and Gap_closing_sequence (issue 4).
#include <mrepair/close_gaps.h>
#include <mrepair/compare_to_reference.h>
#include <mrepair/io.h>

#include "fixtures.h"

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/helpers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <tuple>
#include <vector>

// A namespace of its own: this file is compiled in one translation unit with
// other test files (a unity build, CMakeLists.txt).
namespace {
namespace close_gaps_tests {

using namespace mrepair_test;
namespace MP = mrepair::parameters;
namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

// nx x ny grid of triangles over [x0, x0+w] x [0, h], appended to `s`.
void add_patch(Soup& s, double x0, double w, std::size_t nx, double h, std::size_t ny)
{
  std::size_t base = s.points.size();
  for (std::size_t j = 0; j <= ny; ++j)
    for (std::size_t i = 0; i <= nx; ++i)
      s.points.emplace_back(x0 + w * double(i) / nx, h * double(j) / ny, 0.);
  auto id = [&](std::size_t i, std::size_t j) { return base + j * (nx + 1) + i; };
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      s.polygons.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.polygons.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

// 20 x 10 grid over [0,2] x [0,1] cut along y = 0.5 between x = 0.5 and 1.5:
// the 9 inner vertices of the cut are duplicated and the copies used by the
// faces above are lifted by `opening` in y. 400 faces, 240 vertices.
Soup slit_plane(double opening)
{
  Soup s;
  const std::size_t nx = 20, ny = 10;
  for (std::size_t j = 0; j <= ny; ++j)
    for (std::size_t i = 0; i <= nx; ++i) s.points.emplace_back(0.1 * i, 0.1 * j, 0.);
  std::vector<std::size_t> copy(nx + 1, 0);
  for (std::size_t i = 6; i <= 14; ++i) {
    copy[i] = s.points.size();
    s.points.emplace_back(0.1 * i, 0.5 + opening, 0.);
  }
  auto id = [&](std::size_t i, std::size_t j, bool upper) {
    if (upper && j == 5 && i >= 6 && i <= 14) return copy[i];
    return j * (nx + 1) + i;
  };
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      bool up = j >= 5;  // faces of rows 5.. are above the cut
      s.polygons.push_back({id(i, j, up), id(i + 1, j, up), id(i + 1, j + 1, up)});
      s.polygons.push_back({id(i, j, up), id(i + 1, j + 1, up), id(i, j + 1, up)});
    }
  return s;
}

template <class Mesh>
std::size_t border_edges(const Mesh& m)
{
  return mrepair::internal::count_boundary(m).first;
}
template <class Mesh>
std::size_t border_loops(const Mesh& m)
{
  return mrepair::internal::count_boundary(m).second;
}
template <class Mesh>
std::size_t components(const Mesh& m)
{
  auto fcc = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  return PMP::connected_components(m, fcc);
}
template <class Mesh>
Point point(const Mesh& m, typename boost::graph_traits<Mesh>::vertex_descriptor v)
{
  auto p = get(CGAL::vertex_point, m, v);
  return Point(p.x(), p.y(), p.z());
}
// border halfedges with both ends in the vertical band x0 <= x <= x1 and not horizontal.
template <class Mesh>
std::size_t seam_border_edges(const Mesh& m, double x0, double x1)
{
  std::size_t n = 0;
  for (auto h : halfedges(m)) {
    if (!is_border(h, m)) continue;
    Point a = point(m, source(h, m)), b = point(m, target(h, m));
    if (a.x() >= x0 && a.x() <= x1 && b.x() >= x0 && b.x() <= x1 && std::abs(a.y() - b.y()) > 1e-9) ++n;
  }
  return n;
}
// the mesh as a sorted list of faces, each face its three points rotated to start at the smallest.
template <class Mesh>
std::vector<std::array<std::tuple<double, double, double>, 3>> signature(const Mesh& m)
{
  std::vector<std::array<std::tuple<double, double, double>, 3>> out;
  for (auto f : faces(m)) {
    std::array<std::tuple<double, double, double>, 3> t;
    int i = 0;
    for (auto v : CGAL::vertices_around_face(halfedge(f, m), m)) {
      Point p = point(m, v);
      t[i++] = std::make_tuple(p.x(), p.y(), p.z());
    }
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}
template <class Mesh>
std::vector<std::tuple<double, double, double>> vertex_signature(const Mesh& m)
{
  std::vector<std::tuple<double, double, double>> out;
  for (auto v : vertices(m)) {
    Point p = point(m, v);
    out.push_back(std::make_tuple(p.x(), p.y(), p.z()));
  }
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace

template <class C>
class Close_gaps : public ::testing::Test
{
};
TYPED_TEST_SUITE(Close_gaps, Mesh_configs);

TYPED_TEST(Close_gaps, two_patches_with_one_percent_gap_become_one)
{
  using Mesh = typename TypeParam::Mesh;
  BOOST_CONCEPT_ASSERT((CGAL::concepts::MutableFaceGraph<Mesh>));
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);
  add_patch(s, 1.01, 1.0, 10, 1.0, 10);
  Mesh m = to_mesh<Mesh>(s);
  ASSERT_EQ(border_edges(m), 80u);
  ASSERT_EQ(components(m), 2u);

  mrepair::Gap_closing_result r = mrepair::close_gaps(m, 0.02);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(r.boundary_edges_before, 80u);
  EXPECT_EQ(r.boundary_loops_before, 2u);
  // 11 seam vertices on each side merge pairwise; the 20 seam edges glue.
  EXPECT_EQ(r.vertex_vertex, 11u);
  EXPECT_EQ(r.vertex_edge, 0u);
  EXPECT_EQ(r.boundary_edges_after, 60u);
  EXPECT_EQ(r.boundary_loops_after, 1u);
  EXPECT_EQ(border_edges(m), 60u);
  EXPECT_EQ(components(m), 1u);
  EXPECT_EQ(face_count(m), 400u);
  EXPECT_EQ(vertices(m).size(), 231u);
  EXPECT_EQ(seam_border_edges(m, 0.95, 1.06), 0u);
  EXPECT_LE(r.max_displacement, 0.02);
  EXPECT_NEAR(r.max_displacement, 0.005, 1e-9);  // λ = 0.5: both sides meet in the middle
  EXPECT_EQ(r.pinched_vertices, 0u);
}

// gap_bridge_first (what repair() uses): the crack of the test above is
// joined by a strip of quads between its facing border edges, so its 18
// inner vertices keep their input positions (a contraction moved each by
// 0.005: lost by compare_to_reference). Only the two rungs the strip leaves
// on the border, at the sheet's corners, are collapsed by contractions.
TYPED_TEST(Close_gaps, bridge_first_joins_a_crack_with_a_strip)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);
  add_patch(s, 1.01, 1.0, 10, 1.0, 10);
  Mesh m = to_mesh<Mesh>(s);
  const auto before = vertex_signature(m);

  mrepair::Gap_closing_result r = mrepair::close_gaps(m, 0.02, MP::gap_bridge_first(true));
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(r.seam_edges_zipped, 10u);
  EXPECT_EQ(r.seam_faces, 20u);
  EXPECT_EQ(r.operations, 2u);
  EXPECT_EQ(r.boundary_edges_before, 80u);
  EXPECT_EQ(r.boundary_edges_after, 60u);
  EXPECT_EQ(r.boundary_loops_after, 1u);
  EXPECT_EQ(components(m), 1u);
  EXPECT_EQ(face_count(m), 418u);
  EXPECT_EQ(seam_border_edges(m, 0.95, 1.06), 0u);
  const auto after = vertex_signature(m);
  ASSERT_EQ(after.size(), 240u);
  std::vector<std::tuple<double, double, double>> kept;
  std::set_intersection(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(kept));
  EXPECT_EQ(kept.size(), 238u);  // all but the two corner merges
  // without it, the 11 pairs merge halfway (the test above)
  Mesh plain = to_mesh<Mesh>(s);
  EXPECT_EQ(mrepair::close_gaps(plain, 0.02).seam_edges_zipped, 0u);
}

TYPED_TEST(Close_gaps, t_junction_seam_closes_without_t_junctions)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);   // 11 vertices on the seam
  add_patch(s, 1.01, 1.0, 10, 1.0, 20);  // 21 vertices on the seam
  Mesh m = to_mesh<Mesh>(s);
  ASSERT_EQ(border_edges(m), 100u);  // 40 left + 60 right

  mrepair::Gap_closing_result r = mrepair::close_gaps(m, 0.02);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  // 11 matching pairs merge; the 10 right vertices between them split left edges.
  EXPECT_EQ(r.vertex_vertex, 11u);
  EXPECT_EQ(r.vertex_edge, 10u);
  EXPECT_EQ(border_edges(m), 70u);  // 30 left + 40 right
  EXPECT_EQ(border_loops(m), 1u);
  EXPECT_EQ(components(m), 1u);
  EXPECT_EQ(face_count(m), 200u + 400u + 10u);
  EXPECT_EQ(vertices(m).size(), 121u + 231u - 11u);
  EXPECT_EQ(seam_border_edges(m, 0.95, 1.06), 0u);
}

// gap_keep_input_points (what repair() uses) on a crack along a crease: a
// sheet in z = 0 (11 vertices on its edge x = 1) and an upright one in
// x = 1.004 whose lowest row, 0.004 up, has 21. Without the parameter the 10
// vertex-edge contractions move each T-junction vertex halfway to its edge,
// 0.003 off the surface. With it each leaves its vertex in place and bends
// the edge to it. The 11 corner pairs lose their points either way: merged
// at either end, the other end's point is 0.004 off the faces (a crease),
// so they stay at the λ point.
TYPED_TEST(Close_gaps, keep_input_points_bends_edges_to_t_junction_vertices)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);  // z = 0, 11 vertices on x = 1
  // the upright sheet: x = 1.004, z in [0.004, 1], 21 vertices on its seam row
  const std::size_t base = s.points.size();
  for (std::size_t j = 0; j <= 10; ++j)
    for (std::size_t i = 0; i <= 20; ++i) s.points.emplace_back(1.004, 0.05 * double(i), 0.004 + 0.0996 * double(j));
  auto id = [&](std::size_t i, std::size_t j) { return base + j * 21 + i; };
  for (std::size_t j = 0; j < 10; ++j)
    for (std::size_t i = 0; i < 20; ++i) {
      s.polygons.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});  // facing -x: one
      s.polygons.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});  // orientation with z = 0
    }
  const std::vector<Point> input = s.points;
  auto lost_after = [&](bool keep, mrepair::Gap_closing_result& r) {
    Mesh m = to_mesh<Mesh>(s);
    r = mrepair::close_gaps(m, 0.02, MP::gap_keep_input_points(keep));
    EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
    EXPECT_EQ(border_loops(m), 1u);
    return mrepair::compare_to_reference(input, m).vertices_lost;
  };
  mrepair::Gap_closing_result plain, kept;
  const std::size_t lost_plain = lost_after(false, plain);
  const std::size_t lost_kept = lost_after(true, kept);
  ASSERT_EQ(plain.status, mrepair::Status::ok);
  ASSERT_EQ(kept.status, mrepair::Status::ok);
  EXPECT_EQ(kept.vertex_vertex, plain.vertex_vertex);
  EXPECT_EQ(kept.vertex_edge, plain.vertex_edge);
  EXPECT_EQ(kept.vertex_edge, 10u);
  EXPECT_EQ(lost_plain, 32u);  // 22 corners, 10 T-junction vertices
  EXPECT_EQ(lost_kept, 22u);
  EXPECT_EQ(kept.alternative_placements, 10u);
}

TYPED_TEST(Close_gaps, crack_in_a_plane_closes)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(slit_plane(0.005));
  ASSERT_EQ(border_edges(m), 80u);  // 60 outer + 2 x 10 along the slit
  ASSERT_EQ(border_loops(m), 2u);

  mrepair::Gap_closing_result r = mrepair::close_gaps(m, 0.01);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(r.operations, 9u);
  EXPECT_EQ(border_edges(m), 60u);
  EXPECT_EQ(border_loops(m), 1u);
  EXPECT_EQ(face_count(m), 400u);
  EXPECT_EQ(vertices(m).size(), 231u);
}

TYPED_TEST(Close_gaps, slot_wider_than_tolerance_stays_open)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);
  add_patch(s, 1.01, 1.0, 10, 1.0, 10);  // gap 0.01: closes
  add_patch(s, 2.06, 1.0, 10, 1.0, 10);  // slot 0.05: stays
  Mesh m = to_mesh<Mesh>(s);
  ASSERT_EQ(border_edges(m), 120u);

  mrepair::Gap_closing_result r = mrepair::close_gaps(m, 0.02);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(r.operations, 11u);
  EXPECT_EQ(border_edges(m), 100u);
  EXPECT_EQ(border_loops(m), 2u);
  EXPECT_EQ(components(m), 2u);
  EXPECT_EQ(seam_border_edges(m, 0.95, 1.06), 0u);
  EXPECT_EQ(seam_border_edges(m, 2.0, 2.1), 20u);  // both sides of the slot
}

TYPED_TEST(Close_gaps, relative_tolerance)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);
  add_patch(s, 1.01, 1.0, 10, 1.0, 10);  // gap 0.01; diagonal sqrt(2.01^2 + 1) = 2.245
  Mesh m = to_mesh<Mesh>(s);
  const double diag = std::sqrt(2.01 * 2.01 + 1.0);
  auto r = mrepair::close_gaps(m, 0.004, MP::gap_relative_tolerance(true));  // 0.00898 < 0.01
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_NEAR(r.tolerance, 0.004 * diag, 1e-12);
  EXPECT_EQ(r.operations, 0u);
  EXPECT_EQ(border_edges(m), 80u);
  r = mrepair::close_gaps(m, 0.006, MP::gap_relative_tolerance(true));  // 0.0135 > 0.01
  EXPECT_EQ(r.operations, 11u);
  EXPECT_EQ(border_edges(m), 60u);
}

TYPED_TEST(Close_gaps, forward_backward_restores_the_input)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);
  add_patch(s, 1.01, 1.0, 10, 1.0, 20);
  add_patch(s, 2.025, 1.0, 10, 1.0, 7);
  Mesh m = to_mesh<Mesh>(s);
  const auto faces0 = signature(m);
  const auto verts0 = vertex_signature(m);
  const std::size_t nf0 = face_count(m), nv0 = vertices(m).size();
  std::vector<std::pair<typename boost::graph_traits<Mesh>::vertex_descriptor, Point>> by_descriptor;
  for (auto v : vertices(m)) by_descriptor.emplace_back(v, point(m, v));

  mrepair::Gap_closing_sequence<Mesh> seq(m, 0.02);
  ASSERT_EQ(seq.status(), mrepair::Status::ok);
  EXPECT_EQ(seq.position(), 0u);
  EXPECT_EQ(seq.current_distance(), 0.0);
  // the 0.01 gap first, then the 0.015 one
  std::size_t a = seq.forward_to_distance(0.012);
  EXPECT_EQ(a, 21u);
  EXPECT_LE(seq.current_distance(), 0.012);
  EXPECT_EQ(border_loops(m), 2u);
  std::size_t b = seq.forward_to_distance(0.02);
  EXPECT_GT(b, 0u);
  EXPECT_EQ(border_loops(m), 1u);
  EXPECT_EQ(seq.size(), a + b);
  EXPECT_EQ(seq.position(), a + b);
  const auto faces1 = signature(m);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));

  // back to the first gap only, then all the way
  EXPECT_EQ(seq.backward_to_distance(0.012), b);
  EXPECT_EQ(seq.position(), a);
  EXPECT_EQ(border_loops(m), 2u);
  EXPECT_EQ(seq.backward(1000), a);
  EXPECT_EQ(seq.position(), 0u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(face_count(m), nf0);
  EXPECT_EQ(vertices(m).size(), nv0);
  EXPECT_EQ(signature(m), faces0);
  EXPECT_EQ(vertex_signature(m), verts0);
  if (std::is_same<Mesh, Surface_mesh>::value) {
    // Surface_mesh: the very same vertex indices with bit-identical positions
    for (auto& vp : by_descriptor) {
      Point p = point(m, vp.first);
      EXPECT_TRUE(p.x() == vp.second.x() && p.y() == vp.second.y() && p.z() == vp.second.z());
    }
  }
  // replay forward: the same result
  EXPECT_EQ(seq.forward(1000000), a + b);
  EXPECT_EQ(signature(m), faces1);
  EXPECT_EQ(seq.backward(a + b), a + b);
  EXPECT_EQ(signature(m), faces0);
}

TYPED_TEST(Close_gaps, valid_after_every_step)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);
  add_patch(s, 1.01, 1.0, 10, 1.0, 20);
  Mesh m = to_mesh<Mesh>(slit_plane(0.005));
  Mesh m2 = to_mesh<Mesh>(s);
  for (Mesh* mesh : {&m, &m2}) {
    mrepair::Gap_closing_sequence<Mesh> seq(*mesh, 0.02);
    std::size_t n = 0;
    while (seq.forward(1) == 1) {
      ++n;
      ASSERT_TRUE(mrepair_test::valid_polygon_mesh(*mesh)) << "after forward step " << n;
    }
    EXPECT_GT(n, 0u);
    while (seq.backward(1) == 1) ASSERT_TRUE(mrepair_test::valid_polygon_mesh(*mesh)) << "backward at " << seq.position();
    EXPECT_EQ(seq.position(), 0u);
  }
}

TYPED_TEST(Close_gaps, region_restriction)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);
  add_patch(s, 1.01, 1.0, 10, 1.0, 10);
  add_patch(s, 2.02, 1.0, 10, 1.0, 10);
  Mesh m = to_mesh<Mesh>(s);
  // select the faces of the two right patches only
  auto sel = get(CGAL::dynamic_face_property_t<bool>(), m);
  for (auto f : faces(m)) {
    double x = 0;
    for (auto v : CGAL::vertices_around_face(halfedge(f, m), m)) x += point(m, v).x() / 3;
    put(sel, f, x > 1.005);
  }
  auto r = mrepair::close_gaps(m, 0.02, MP::gap_face_selection(sel));
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(r.operations, 11u);
  EXPECT_EQ(border_loops(m), 2u);
  EXPECT_EQ(seam_border_edges(m, 0.95, 1.06), 20u);  // the unselected seam stays open
  EXPECT_EQ(seam_border_edges(m, 1.96, 2.07), 0u);

  // the same with a vertex selection: only x < 1.5 (the left seam)
  Mesh m2 = to_mesh<Mesh>(s);
  auto vsel = get(CGAL::dynamic_vertex_property_t<bool>(), m2);
  for (auto v : vertices(m2)) put(vsel, v, point(m2, v).x() < 1.5);
  auto r2 = mrepair::close_gaps(m2, 0.02, MP::gap_vertex_selection(vsel));
  EXPECT_EQ(r2.operations, 11u);
  EXPECT_EQ(seam_border_edges(m2, 0.95, 1.06), 0u);
  EXPECT_EQ(seam_border_edges(m2, 1.96, 2.07), 20u);
}

TYPED_TEST(Close_gaps, bad_input)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh empty;
  EXPECT_EQ(mrepair::close_gaps(empty, 0.1).status, mrepair::Status::empty_input);

  Soup s;
  add_patch(s, 0.0, 1.0, 4, 1.0, 4);
  add_patch(s, 1.01, 1.0, 4, 1.0, 4);
  s.points[3] = Point(std::numeric_limits<double>::quiet_NaN(), 0., 0.);
  Mesh m = to_mesh<Mesh>(s);
  const auto before = face_count(m);
  auto r = mrepair::close_gaps(m, 0.02);
  EXPECT_EQ(r.status, mrepair::Status::non_finite_input);
  EXPECT_EQ(face_count(m), before);
  EXPECT_EQ(r.operations, 0u);

  Mesh m2 = to_mesh<Mesh>(grid(3, 3));
  EXPECT_EQ(mrepair::close_gaps(m2, -1.0).status, mrepair::Status::invalid_parameter);
  EXPECT_EQ(mrepair::close_gaps(m2, 0.1, MP::gap_lambda(2.0)).status,
            mrepair::Status::invalid_parameter);
  // a closed mesh: nothing to do
  Mesh sphere = to_mesh<Mesh>(icosphere(2));
  auto rs = mrepair::close_gaps(sphere, 0.1);
  EXPECT_EQ(rs.status, mrepair::Status::ok);
  EXPECT_EQ(rs.operations, 0u);
  EXPECT_EQ(face_count(sphere), 320u);
}

TYPED_TEST(Close_gaps, report_and_cancel)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 300);
  add_patch(s, 1.01, 1.0, 10, 1.0, 300);
  Mesh m = to_mesh<Mesh>(s);
  struct Stopper : mrepair::Default_visitor
  {
    bool stop_requested() { return true; }
  } stop;
  auto r = mrepair::close_gaps(m, 0.02, CGAL::parameters::visitor(std::ref(stop)));
  EXPECT_EQ(r.status, mrepair::Status::cancelled);
  EXPECT_EQ(r.operations, 0u);  // polled before the first contraction (then every 256)
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  mrepair::Report rep;
  r.to_report(rep);
  EXPECT_NE(rep.to_json().find("\"vertex_vertex\""), std::string::npos);
}

// ---- automatic tolerance and CAD-like seams (issue 18) ----------------------

namespace {

// a lens: an icosphere of radius 1 flattened to half-thickness `t` along z (a
// thin part with a sharp rim, like a turbine blade's trailing edge), as two
// patches with their own vertices: the faces above z = 0 and the others; the
// lower patch is shifted by `shift` in x, so that the rim seam has a crack.
Soup split_lens(double t, double shift, int levels = 3)
{
  Soup sphere = icosphere(levels, 1.0);
  Soup s;
  std::vector<std::size_t> copy[2];
  copy[0].assign(sphere.points.size(), std::size_t(-1));
  copy[1].assign(sphere.points.size(), std::size_t(-1));
  for (const Polygon& f : sphere.polygons) {
    double cz = 0;
    for (std::size_t v : f) cz += sphere.points[v].z();
    const int side = cz > 0 ? 0 : 1;
    Polygon g;
    for (std::size_t v : f) {
      if (copy[side][v] == std::size_t(-1)) {
        copy[side][v] = s.points.size();
        const Point& p = sphere.points[v];
        s.points.emplace_back(p.x() + (side ? shift : 0.), p.y(), t * p.z());
      }
      g.push_back(copy[side][v]);
    }
    s.polygons.push_back(g);
  }
  return s;
}

// faces whose normal points towards the lens centre (a flip on a convex part).
template <class Mesh>
std::size_t inward_faces(const Mesh& m)
{
  std::size_t n = 0;
  for (auto f : faces(m)) {
    std::vector<Point> p;
    for (auto v : CGAL::vertices_around_face(halfedge(f, m), m)) p.push_back(point(m, v));
    const K::Vector_3 nrm = CGAL::cross_product(p[1] - p[0], p[2] - p[0]);
    const K::Vector_3 c = ((p[0] - CGAL::ORIGIN) + (p[1] - CGAL::ORIGIN) + (p[2] - CGAL::ORIGIN)) / 3.;
    if (nrm * c < 0) ++n;
  }
  return n;
}

// two 10 x 10 patches of [0,1]^2 and [1+gap, 2+gap] x [0,1] with a square hole
// of 2 x 2 cells (rim 8 edges of 0.1) cut out of the first.
Soup two_patches_and_a_hole(double gap, std::size_t right_rows = 10)
{
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);
  std::vector<Polygon> kept;
  for (std::size_t k = 0; k < s.polygons.size(); ++k) {
    const std::size_t cell = k / 2, i = cell % 10, j = cell / 10;
    if (i >= 4 && i <= 5 && j >= 4 && j <= 5) continue;
    kept.push_back(s.polygons[k]);
  }
  s.polygons = kept;
  // drop the hole's centre, left without faces
  const std::size_t centre = 5 * 11 + 5;
  s.points.erase(s.points.begin() + centre);
  for (Polygon& f : s.polygons)
    for (std::size_t& v : f)
      if (v > centre) --v;
  add_patch(s, 1.0 + gap, 1.0, 10, 1.0, right_rows);
  return s;
}

} // namespace

TYPED_TEST(Close_gaps, automatic_tolerance_closes_seams_not_a_hole)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(two_patches_and_a_hole(0.01));
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
  ASSERT_EQ(border_loops(m), 3u);

  const mrepair::Gap_tolerance_estimate e = mrepair::estimate_gap_tolerance(m);
  EXPECT_EQ(e.status, mrepair::Status::ok);
  // the seam pairs are 0.01 apart; the hole's rim is 0.1 from itself at least
  EXPECT_GE(e.tolerance, 0.01);
  EXPECT_LT(e.tolerance, 0.05);
  EXPECT_EQ(e.candidates, 22u);  // 11 vertices on each side of the seam

  mrepair::Gap_closing_result r = mrepair::close_gaps(m, mrepair::automatic_gap_tolerance);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_TRUE(r.tolerance_estimated);
  EXPECT_DOUBLE_EQ(r.tolerance, e.tolerance);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(seam_border_edges(m, 0.95, 1.06), 0u);
  EXPECT_EQ(border_loops(m), 2u);  // the outline and the hole
  EXPECT_EQ(r.boundary_edges_after, 60u + 8u);
  EXPECT_LE(r.max_displacement, r.tolerance);
  EXPECT_GT(r.max_displacement, 0.);
}

TYPED_TEST(Close_gaps, automatic_tolerance_t_junction_seam)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(two_patches_and_a_hole(0.01, 20));  // 11 against 21 seam vertices
  mrepair::Gap_closing_result r = mrepair::close_gaps(m, mrepair::automatic_gap_tolerance);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(r.vertex_edge, 10u);  // the 10 right vertices between the matches split left edges
  EXPECT_EQ(seam_border_edges(m, 0.95, 1.06), 0u);
  EXPECT_EQ(border_loops(m), 2u);
}

TYPED_TEST(Close_gaps, automatic_tolerance_of_closed_and_holed_meshes_is_zero)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh sphere = to_mesh<Mesh>(icosphere(2));
  EXPECT_EQ(mrepair::estimate_gap_tolerance(sphere).tolerance, 0.);
  Soup s = two_patches_and_a_hole(0.01);
  s.polygons.resize(s.polygons.size() - 200);  // the first patch alone: an outline and a hole
  s.points.resize(s.points.size() - 121);
  Mesh m = to_mesh<Mesh>(s);
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
  const auto sig = signature(m);
  const mrepair::Gap_tolerance_estimate e = mrepair::estimate_gap_tolerance(m);
  EXPECT_EQ(e.tolerance, 0.);
  EXPECT_EQ(e.candidates, 0u);
  auto r = mrepair::close_gaps(m, mrepair::automatic_gap_tolerance);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.operations, 0u);
  EXPECT_EQ(signature(m), sig);
}

// Regression (CGAL's nm_vertices_pinched.off, geometry-central's
// triple_vierbein.obj through `mrepair repair`): two slits of a plate, one
// row of thin faces apart. Every rim vertex facing the other slit has a
// partner nearer than its edges, so the knee rule alone chose 1.5 x that
// distance and zipped the row away (10-15% of the faces of those meshes).
// A real model's narrow strip is no exporter's seam: the tolerance stays
// within 1% of the boundary's diagonal and nothing moves.
TYPED_TEST(Close_gaps, automatic_tolerance_leaves_a_narrow_strip_between_holes)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  add_patch(s, 0.0, 2.0, 20, 2.0, 20);  // cells of 0.1 over [0,2]^2
  std::vector<Polygon> kept;
  for (std::size_t k = 0; k < s.polygons.size(); ++k) {
    const std::size_t cell = k / 2, i = cell % 20, j = cell / 20;
    if (i >= 3 && i <= 16 && (j == 8 || j == 10)) continue;  // the two slits
    kept.push_back(s.polygons[k]);
  }
  s.polygons = kept;
  for (std::size_t i = 3; i <= 17; ++i) s.points[10 * 21 + i] = Point(0.1 * double(i), 0.95, 0.);
  Mesh m = to_mesh<Mesh>(s);
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
  ASSERT_EQ(border_loops(m), 3u);
  const auto sig = signature(m);
  const mrepair::Gap_tolerance_estimate e = mrepair::estimate_gap_tolerance(m);
  EXPECT_GE(e.candidates, 16u);                 // both rims of the strip: enough for a knee
  EXPECT_LE(e.tolerance, 0.01 * std::sqrt(8.));  // the boundary's diagonal
  EXPECT_LT(e.tolerance, 0.05);                  // the strip is 0.05 wide
  auto r = mrepair::close_gaps(m, mrepair::automatic_gap_tolerance);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.operations, 0u);
  EXPECT_EQ(signature(m), sig);
  EXPECT_EQ(border_loops(m), 3u);
}

// A flattened open tube: 40 points around an ellipse 2 wide and 0.02 thick,
// 20 rings along y. Each open end's upper and lower sides are 0.02 apart,
// nearer than the end's edges (0.16): the near pairs of a thin open end
// (a blade's end cap), which once set the tolerance that zipped the blade's
// ends. Both sides' faces lie on the same side of the end, so no pair faces
// the other: no tolerance, nothing moves.
TYPED_TEST(Close_gaps, automatic_tolerance_ignores_the_thin_open_ends_of_a_flat_tube)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  const std::size_t around = 40, rings = 20;
  const double pi = 3.14159265358979323846;
  for (std::size_t j = 0; j <= rings; ++j)
    for (std::size_t k = 0; k < around; ++k) {
      const double a = 2 * pi * double(k) / double(around);
      s.points.emplace_back(std::cos(a), 0.1 * double(j), 0.01 * std::sin(a));
    }
  auto id = [&](std::size_t j, std::size_t k) { return j * around + k % around; };
  for (std::size_t j = 0; j < rings; ++j)
    for (std::size_t k = 0; k < around; ++k) {
      s.polygons.push_back({id(j, k), id(j, k + 1), id(j + 1, k + 1)});
      s.polygons.push_back({id(j, k), id(j + 1, k + 1), id(j + 1, k)});
    }
  Mesh m = to_mesh<Mesh>(s);
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
  ASSERT_EQ(border_loops(m), 2u);
  const auto sig = signature(m);
  const mrepair::Gap_tolerance_estimate e = mrepair::estimate_gap_tolerance(m);
  EXPECT_GE(e.not_facing, 60u);  // nearly every end vertex has the other side within 0.02
  EXPECT_LT(e.candidates, 16u);
  EXPECT_EQ(e.tolerance, 0.);
  auto r = mrepair::close_gaps(m, mrepair::automatic_gap_tolerance);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.operations, 0u);
  EXPECT_EQ(border_edges(m), 2 * around);
  EXPECT_EQ(signature(m), sig);
}

TYPED_TEST(Close_gaps, gaps_wider_than_the_tolerance_stay_open)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(two_patches_and_a_hole(0.03));
  const auto sig = signature(m);
  auto r = mrepair::close_gaps(m, 0.02);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.operations, 0u);
  EXPECT_EQ(border_loops(m), 3u);
  EXPECT_EQ(signature(m), sig);
}

TYPED_TEST(Close_gaps, blade_like_thin_part_closes_without_flips)
{
  using Mesh = typename TypeParam::Mesh;
  // half-thickness 0.03 against a rim crack of 0.004: near the rim the two
  // sides are nearer to each other than the tolerance
  Mesh m = to_mesh<Mesh>(split_lens(0.03, 0.004));
  ASSERT_EQ(border_loops(m), 2u);
  ASSERT_EQ(inward_faces(m), 0u);
  for (int automatic = 0; automatic < 2; ++automatic) {
    Mesh c = m;
    auto r = automatic ? mrepair::close_gaps(c, mrepair::automatic_gap_tolerance)
                       : mrepair::close_gaps(c, 0.02);
    EXPECT_EQ(r.status, mrepair::Status::ok);
    EXPECT_TRUE(mrepair_test::valid_polygon_mesh(c));
    EXPECT_EQ(border_edges(c), 0u) << "automatic " << automatic;
    EXPECT_TRUE(CGAL::is_closed(c));
    EXPECT_EQ(inward_faces(c), 0u);
    EXPECT_EQ(r.pinched_vertices, 0u);
    EXPECT_LE(r.max_displacement, r.tolerance);
  }
}

#ifdef MREPAIR_CLI
// The command line: close-gaps on an OFF file; bad input exits non-zero.
TEST(Close_gaps_cli, closes_a_file_and_refuses_bad_input)
{
  Soup s;
  add_patch(s, 0.0, 1.0, 10, 1.0, 10);
  add_patch(s, 1.01, 1.0, 10, 1.0, 20);
  const std::string dir = ::testing::TempDir();
  const std::string in = dir + "close_gaps_in.off", out = dir + "close_gaps_out.off",
                    rep = dir + "close_gaps_report.json";
  {
    std::ofstream f(in);
    f.precision(17);
    f << "OFF\n" << s.points.size() << " " << s.polygons.size() << " 0\n";
    for (const Point& p : s.points) f << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const Polygon& q : s.polygons) f << "3 " << q[0] << " " << q[1] << " " << q[2] << "\n";
  }
  std::string cmd = std::string(MREPAIR_CLI) + " close-gaps " + in + " " + out +
                    " --tolerance 0.02 --quiet --report " + rep + " > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  Surface_mesh m;
  ASSERT_EQ(mrepair::read_polygon_mesh(out, m).status, mrepair::Status::ok);
  EXPECT_EQ(border_edges(m), 70u);
  EXPECT_EQ(face_count(m), 610u);
  std::ifstream r(rep);
  std::string json((std::istreambuf_iterator<char>(r)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"vertex_edge\": 10"), std::string::npos) << json;

  std::string missing = std::string(MREPAIR_CLI) + " close-gaps " + dir + "no_such.off " + out +
                        " --tolerance 0.02 --quiet 2> /dev/null";
  EXPECT_NE(std::system(missing.c_str()), 0);
  std::string no_tol = std::string(MREPAIR_CLI) + " close-gaps " + in + " " + out + " 2> /dev/null";
  EXPECT_NE(std::system(no_tol.c_str()), 0);
}
#endif

// A narrow slit left open is bridged with Liepa's triangles, nothing moved.
// A bridge that would pass through a clean stretch of the surface (here a
// thin closed box standing in the slit, touching neither side) is taken
// back and the slit stays open; without the box the same slit is bridged.
TYPED_TEST(Close_gaps, bridge_through_a_clean_surface_is_taken_back)
{
  using Mesh = typename TypeParam::Mesh;
  const double w = 0.004;  // the slit's width
  // a strip over [0,1] x [-0.2,0.2] with a slit from x = 0.2 to 0.8 along y = 0
  Soup strip;
  const double ys[6] = {-0.2, -0.1, -w / 2, w / 2, 0.1, 0.2};
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i <= 10; ++i) strip.points.emplace_back(0.1 * i, ys[j], 0.);
  auto id = [](int i, int j) { return std::size_t(j * 11 + i); };
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 10; ++i) {
      if (j == 2 && i >= 2 && i < 8) continue;  // the slit
      strip.polygons.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      strip.polygons.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  Soup box = translated(cube(1.), 0., 0., 0.);
  for (auto& p : box.points) p = Point(0.4 + 0.2 * p.x(), -w / 4 + 0.5 * w * p.y(), -0.1 + 0.2 * p.z());
  for (bool with_box : {false, true}) {
    Mesh m = to_mesh<Mesh>(with_box ? merged(strip, box) : strip);
    const std::size_t faces_before = face_count(m);
    auto vpm = get(CGAL::vertex_point, m);
    mrepair::internal::Visitor_handle<CGAL::parameters::Default_named_parameters> quiet(
        CGAL::parameters::default_values());
    mrepair::Gap_closing_result r;
    mrepair::internal::bridge_narrow_loops(m, vpm, 0.02, 100, quiet, r);
    EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
    if (with_box) {
      EXPECT_EQ(r.loops_bridged, 0u);
      EXPECT_EQ(r.bridges_rejected_intersecting, 1u);
      EXPECT_EQ(face_count(m), faces_before);
      EXPECT_FALSE(PMP::does_self_intersect(m));
    } else {
      EXPECT_EQ(r.loops_bridged, 1u);
      EXPECT_EQ(r.bridges_rejected_intersecting, 0u);
      EXPECT_EQ(face_count(m), faces_before + r.bridge_faces);
      EXPECT_GT(r.bridge_faces, 10u);
    }
  }
}

} // namespace close_gaps_tests
} // namespace
