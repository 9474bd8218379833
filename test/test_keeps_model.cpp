// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Issue 15: the repair keeps the user's model. One test per failure class seen
// on real meshes from other projects' test suites (three separate triangles,
// two icosahedra, open patches, a flat sheet, a non-planar pentagon, a
// zero-area face next to a needle, a Moebius strip), the input-kind decision,
// the hole-or-border rule, the final validity step and the face accounting.
#include "fixtures.h"

#include <mrepair/clean_boundaries.h>
#include <mrepair/compare_to_reference.h>
#include <mrepair/clean_scan_mesh.h>
#include <mrepair/ensure_valid_mesh.h>
#include <mrepair/fill_small_holes.h>
#include <mrepair/input_profile.h>
#include <mrepair/io.h>
#include <mrepair/remove_small_components.h>
#include <mrepair/repair.h>
#include <mrepair/stitch_soup.h>

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <mrepair/triangulate_polygons.h>
#include <CGAL/centroid.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace mrepair_test;
namespace MP = mrepair::parameters;
using mrepair::Input_profile;
using mrepair::Status;

Soup triangle(double x)
{
  Soup s;
  s.points = {Point(x, 0, 0), Point(x + 1, 0, 0), Point(x, 1, 0.2)};
  s.polygons = {{0, 1, 2}};
  return s;
}

// A Moebius strip of n x 2 quads split in triangles: non-orientable, so the
// soup-to-manifold step must cut it; one boundary loop.
Soup moebius(std::size_t n)
{
  Soup s;
  const double pi = 3.14159265358979323846;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = 2 * pi * double(i) / double(n);
    for (int j = 0; j < 3; ++j) {
      const double v = -0.3 + 0.3 * j;
      s.points.emplace_back((1 + v * std::cos(u / 2)) * std::cos(u),
                            (1 + v * std::cos(u / 2)) * std::sin(u), v * std::sin(u / 2));
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < 2; ++j) {
      const std::size_t i1 = (i + 1) % n;
      // the last column meets the first one flipped (v -> -v)
      const std::size_t a = 3 * i + j, b = 3 * i + j + 1;
      const std::size_t c = i1 == 0 ? 3 * i1 + (2 - j - 1) : 3 * i1 + j + 1;
      const std::size_t d = i1 == 0 ? 3 * i1 + (2 - j) : 3 * i1 + j;
      s.polygons.push_back({a, d, c});
      s.polygons.push_back({a, c, b});
    }
  return s;
}

// Runs the cleaning pipeline as `mrepair repair` does and checks what every
// output must satisfy: valid triangle mesh, no exactly degenerate face, a face
// accounting that reconciles.
template <class Mesh>
mrepair::Scan_cleaning_result clean_and_check(Mesh& m, Input_profile p = Input_profile::automatic)
{
  const std::size_t f0 = face_count(m);
  mrepair::Scan_cleaning_result r = mrepair::clean_scan_mesh(m, MP::input_profile(p));
  EXPECT_TRUE(mrepair::succeeded(r.status)) << mrepair::to_string(r.status) << " " << r.message;
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(CGAL::is_triangle_mesh(m));
  EXPECT_EQ(r.faces_before, f0);
  EXPECT_EQ(r.faces_after, face_count(m));
  EXPECT_TRUE(r.faces_reconcile()) << "in " << r.faces_before << " out " << r.faces_after
                                   << " removed " << r.faces_removed() << " added "
                                   << r.faces_added();
  EXPECT_EQ(r.validity.degenerate_faces_left, 0u);
  for (auto f : faces(m)) {
    auto h = halfedge(f, m);
    EXPECT_FALSE(CGAL::collinear(get(CGAL::vertex_point, m, source(h, m)),
                                 get(CGAL::vertex_point, m, target(h, m)),
                                 get(CGAL::vertex_point, m, target(next(h, m), m))));
  }
  return r;
}

template <class Mesh>
std::size_t border_edges(const Mesh& m)
{
  std::size_t n = 0;
  for (auto h : halfedges(m))
    if (is_border(h, m)) ++n;
  return n;
}

// the number of face-connected components of `m`
template <class Mesh>
std::size_t part_count(const Mesh& m)
{
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;
  std::set<face_descriptor> seen;
  std::size_t parts = 0;
  for (face_descriptor seed : faces(m)) {
    if (!seen.insert(seed).second) continue;
    ++parts;
    std::vector<face_descriptor> stack{seed};
    while (!stack.empty()) {
      const face_descriptor f = stack.back();
      stack.pop_back();
      for (auto h : CGAL::halfedges_around_face(halfedge(f, m), m))
        if (!is_border(opposite(h, m), m) && seen.insert(face(opposite(h, m), m)).second)
          stack.push_back(face(opposite(h, m), m));
    }
  }
  return parts;
}

template <class C>
class Keeps_model : public ::testing::Test
{};
TYPED_TEST_SUITE(Keeps_model, Mesh_configs);

TYPED_TEST(Keeps_model, three_separate_triangles)
{
  using Mesh = typename TypeParam::Mesh;
  for (Input_profile p : {Input_profile::automatic, Input_profile::scan}) {
    Mesh m = to_mesh<Mesh>(merged(merged(triangle(0), triangle(3)), triangle(6)));
    mrepair::Scan_cleaning_result r = clean_and_check(m, p);
    EXPECT_EQ(face_count(m), 3u) << mrepair::to_string(p);
    EXPECT_EQ(border_edges(m), 9u) << "a lone triangle is a sheet, not a hole to cap";
    if (p == Input_profile::automatic) { EXPECT_EQ(r.profile.profile, Input_profile::cad); }
  }
}

TYPED_TEST(Keeps_model, two_icosahedra)
{
  using Mesh = typename TypeParam::Mesh;
  for (Input_profile p : {Input_profile::automatic, Input_profile::scan}) {
    Mesh m = to_mesh<Mesh>(merged(icosphere(0), translated(icosphere(0), 3, 0, 0)));
    clean_and_check(m, p);
    EXPECT_EQ(face_count(m), 40u) << mrepair::to_string(p);
  }
  // the step alone, at the paper's threshold: equal parts are not small
  Mesh m = to_mesh<Mesh>(merged(icosphere(0), translated(icosphere(0), 3, 0, 0)));
  mrepair::Small_components_result c = mrepair::remove_small_components(m);
  EXPECT_EQ(c.components_removed, 0u);
  EXPECT_EQ(face_count(m), 40u);
}

TYPED_TEST(Keeps_model, largest_component_is_never_removed_and_islands_still_go)
{
  using Mesh = typename TypeParam::Mesh;
  // a dense part and a tiny island: the island is small both ways
  Mesh m = to_mesh<Mesh>(merged(icosphere(4, 10.0), translated(icosphere(0, 0.1), 30, 0, 0)));
  mrepair::Small_components_result c = mrepair::remove_small_components(m);
  EXPECT_EQ(c.components_removed, 1u);
  EXPECT_EQ(c.faces_removed, 20u);
  EXPECT_EQ(face_count(m), 5120u);
  // everything small by the absolute count: the largest stays, and a part a
  // quarter its size is not small next to it
  Mesh k = to_mesh<Mesh>(merged(icosphere(1), translated(icosphere(0, 0.1), 3, 0, 0)));
  c = mrepair::remove_small_components(k);
  EXPECT_TRUE(c.kept_largest);
  EXPECT_EQ(c.components_kept_relative, 1u);
  EXPECT_EQ(face_count(k), 100u);
}

TYPED_TEST(Keeps_model, several_open_patches_keep_their_borders)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(6, 6, 0.5);
  for (int k = 1; k < 4; ++k) s = merged(s, translated(grid(6, 6, 0.5), 4.0 * k, 0.3 * k, 0));
  for (Input_profile p : {Input_profile::automatic, Input_profile::scan}) {
    Mesh m = to_mesh<Mesh>(s);
    const std::size_t b0 = border_edges(m);
    clean_and_check(m, p);
    EXPECT_EQ(face_count(m), s.polygons.size()) << mrepair::to_string(p);
    EXPECT_EQ(border_edges(m), b0) << mrepair::to_string(p);
  }
}

TYPED_TEST(Keeps_model, flat_grid_sheet_is_neither_eroded_nor_capped)
{
  using Mesh = typename TypeParam::Mesh;
  const Soup s = grid(12, 12);
  Mesh m = to_mesh<Mesh>(s);
  // boundary cleaning alone: a straight border is clean, nothing moves
  mrepair::Boundary_cleaning_result b = mrepair::clean_boundaries(m);
  EXPECT_EQ(b.status, Status::ok);
  EXPECT_EQ(b.loops, 1u);
  EXPECT_EQ(b.jagged_loops, 0u);
  EXPECT_EQ(b.faces_removed + b.component_faces_removed, 0u);
  EXPECT_EQ(b.vertices_smoothed, 0u);
  for (auto v : vertices(m)) {
    const Point p = get(CGAL::vertex_point, m, v);
    EXPECT_EQ(p.z(), 0.);
    EXPECT_EQ(p.x(), std::round(p.x()));
    EXPECT_EQ(p.y(), std::round(p.y()));
  }
  // hole filling alone: the outer loop is a border, even under the vertex limit
  mrepair::Hole_filling_result h = mrepair::fill_small_holes(m, MP::max_hole_vertices(1000));
  EXPECT_EQ(h.holes_filled, 0u);
  EXPECT_EQ(h.sheet_borders, 1u);
  for (Input_profile p : {Input_profile::automatic, Input_profile::scan, Input_profile::cad}) {
    Mesh g = to_mesh<Mesh>(s);
    clean_and_check(g, p);
    EXPECT_EQ(face_count(g), s.polygons.size()) << mrepair::to_string(p);
    EXPECT_EQ(border_edges(g), 48u) << mrepair::to_string(p);
  }
}

TYPED_TEST(Keeps_model, sheet_with_a_hole_gets_the_hole_filled_only)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(12, 12);
  std::vector<Polygon> kept;
  for (std::size_t k = 0; k < s.polygons.size(); ++k) {
    const std::size_t cell = k / 2, i = cell % 12, j = cell / 12;
    if (i >= 5 && i < 7 && j >= 5 && j < 7) continue;  // a 2 x 2 hole in the middle
    kept.push_back(s.polygons[k]);
  }
  s.polygons = kept;
  Mesh m = to_mesh<Mesh>(s);
  mrepair::Hole_filling_result h = mrepair::fill_small_holes(m, MP::max_hole_vertices(1000));
  EXPECT_EQ(h.holes_filled, 1u);
  EXPECT_EQ(h.sheet_borders, 1u);
  EXPECT_EQ(border_edges(m), 48u);
}

TYPED_TEST(Keeps_model, jagged_border_is_eroded_within_its_budget)
{
  using Mesh = typename TypeParam::Mesh;
  // a grid whose border row carries ears: every other border cell keeps only
  // one triangle, so the loop zigzags
  Soup s = grid(20, 20);
  std::vector<Polygon> kept;
  for (std::size_t k = 0; k < s.polygons.size(); ++k) {
    const std::size_t cell = k / 2, i = cell % 20, j = cell / 20;
    if (j == 0 && i % 2 == 0 && k % 2 == 0) continue;
    kept.push_back(s.polygons[k]);
  }
  s.polygons = kept;
  Mesh m = to_mesh<Mesh>(s);
  const std::size_t f0 = face_count(m);
  mrepair::Boundary_cleaning_result b = mrepair::clean_boundaries(m);
  EXPECT_EQ(b.jagged_loops, 1u);
  EXPECT_GT(b.faces_removed, 0u);
  EXPECT_EQ(f0 - face_count(m), b.faces_removed + b.component_faces_removed);
  // never more than the loop's share of its region (plus pinch fans)
  EXPECT_LE(b.faces_removed - b.pinch_faces_removed, f0 / 2);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  // a tiny jagged component is never deleted by the erosion
  Soup tiny;
  tiny.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 0.1, 0), Point(0.5, 1, 0)};
  tiny.polygons = {{0, 2, 3}, {2, 1, 3}};
  Mesh t = to_mesh<Mesh>(tiny);
  mrepair::clean_boundaries(t, MP::jagged_loop_turning(0.0));
  EXPECT_GT(face_count(t), 0u);
}

// The loop measures of the boundary policy, on turn sequences (degrees).
TEST(Keeps_model_measures, jaggedness_counts_only_turns_undone_nearby)
{
  using Turns = std::vector<std::pair<int, double>>;
  const double deg = 3.14159265358979323846 / 180.;
  auto loop = [&](std::initializer_list<double> t, std::size_t repeat = 1) {
    Turns out;
    for (std::size_t k = 0; k < repeat; ++k)
      for (double a : t) out.emplace_back(int(out.size()), a * deg);
    return out;
  };
  namespace SC = mrepair::internal::clean_pipeline;
  // a square, and a convex polygon: one way, no jaggedness
  EXPECT_NEAR(SC::loop_jaggedness(loop({90, 0, 0, 90, 0, 0, 90, 0, 0, 90, 0, 0})), 0., 1e-12);
  EXPECT_NEAR(SC::loop_jaggedness(loop({10}, 36)), 0., 1e-12);
  // a slow change of sign (a cut Moebius strip): +8 on one half, -9 on the
  // other: far under 2 pi, though its total turning exceeds its net by 2 pi
  Turns moebius = loop({8}, 40);
  for (double a : {-90., 0., -90.})
    moebius.emplace_back(int(moebius.size()), a * deg);
  for (int k = 0; k < 40; ++k) moebius.emplace_back(int(moebius.size()), -9. * deg);
  EXPECT_LT(SC::loop_jaggedness(moebius), 60. * deg);
  // one ear on a straight border: twice its undone turn (2 x 126 degrees)
  Turns ear = loop({0, 0, 0, 63, -127, 63, 0, 0, 0, 90, 90, 90});
  EXPECT_NEAR(SC::loop_jaggedness(ear), 252. * deg, 1. * deg);
  // a zigzag of +-30 degrees at every vertex: 30 per vertex
  EXPECT_NEAR(SC::loop_jaggedness(loop({30, -30}, 50)), 3000. * deg, 1e-9);
  // teeth: the ear's three vertices, never a corner
  std::vector<int> teeth;
  SC::mark_local_teeth(ear, 2, 180. * deg, [&](int v) { teeth.push_back(v); });
  EXPECT_EQ(teeth, (std::vector<int>{3, 4, 5}));
  teeth.clear();
  SC::mark_local_teeth(loop({90, 0, 90, 0, 90, 0, 90, 0}), 2, 180. * deg,
                       [&](int v) { teeth.push_back(v); });
  EXPECT_TRUE(teeth.empty());
}

TYPED_TEST(Keeps_model, non_planar_pentagon_terminates)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0.3), Point(1.3, 1, 0), Point(0.5, 1.6, 0.4),
              Point(-0.3, 1, 0)};
  s.polygons = {{0, 1, 2, 3, 4}};
  Mesh m = to_mesh<Mesh>(s);
  ASSERT_EQ(mrepair::triangulate_polygons(m).status, mrepair::Status::ok);
  for (Input_profile p : {Input_profile::automatic, Input_profile::scan}) {
    Mesh g = m;
    clean_and_check(g, p);
    EXPECT_EQ(face_count(g), 3u) << mrepair::to_string(p);
  }
}

TYPED_TEST(Keeps_model, zero_area_face_next_to_a_needle)
{
  using Mesh = typename TypeParam::Mesh;
  // c1 lies on the segment c0 c2: the face (c2, c0, c1) has zero area; the
  // face across its long edge is a needle towards T
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0), Point(1, 1e-3, 0),
              Point(1, -1, 0)};
  s.polygons = {{0, 2, 3}, {2, 0, 1}, {1, 0, 4}, {2, 1, 4}};
  for (Input_profile p : {Input_profile::automatic, Input_profile::scan, Input_profile::cad}) {
    Mesh m = to_mesh<Mesh>(s);
    mrepair::Scan_cleaning_result r = clean_and_check(m, p);
    EXPECT_GE(r.validity.degenerate_faces_found + r.steps[6].changes, 1u) << mrepair::to_string(p);
    EXPECT_GE(face_count(m), 3u) << mrepair::to_string(p);
  }
  // the validity step alone flips the cap's long edge: no vertex moves
  Mesh m = to_mesh<Mesh>(s);
  mrepair::Validity_result v = mrepair::ensure_valid_mesh(m);
  EXPECT_EQ(v.status, Status::ok);
  EXPECT_EQ(v.degenerate_faces_found, 1u);
  EXPECT_EQ(v.caps_flipped, 1u);
  EXPECT_EQ(face_count(m), 4u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
}

TYPED_TEST(Keeps_model, zero_length_edge_is_collapsed_without_moving_anything)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(3, 3);
  // point 5 = (1, 1) gets a twin at the same place, joined by a face pair
  s.points[6] = s.points[5];  // (2, 1) moved onto (1, 1): faces through 5-6 collapse
  Mesh m = to_mesh<Mesh>(s);
  mrepair::Validity_result v = mrepair::ensure_valid_mesh(m);
  EXPECT_EQ(v.degenerate_faces_left, 0u);
  EXPECT_GE(v.zero_length_edges_collapsed, 1u);
  EXPECT_EQ(face_count(m), 18u - v.faces_removed());
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
}

// Found by the random invariants (case 117): a detached two-face pillow
// (a double-sided fin) that an earlier step flattened. Neither face can be
// fixed by a local edit, but the pair is a duplicate and goes; it must not
// be counted as a degenerate face left.
TYPED_TEST(Keeps_model, flattened_pillow_goes_as_a_duplicate_pair)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = cube(1.0);
  const std::size_t a = s.points.size();
  s.points.emplace_back(3, 0, 0);
  s.points.emplace_back(4, 0, 0);
  s.points.emplace_back(5, 0, 0);  // collinear: both faces are degenerate
  s.polygons.push_back({a, a + 1, a + 2});
  s.polygons.push_back({a + 2, a + 1, a});
  Mesh m = to_mesh<Mesh>(s);
  ASSERT_EQ(face_count(m), 14u);
  mrepair::Validity_result v = mrepair::ensure_valid_mesh(m);
  EXPECT_EQ(v.status, Status::ok) << v.message;
  EXPECT_EQ(v.degenerate_faces_left, 0u);
  EXPECT_EQ(v.duplicate_faces_removed, 2u);
  EXPECT_EQ(face_count(m), 12u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
}

// Issue 17: ensure_valid_mesh finds duplicate faces by bucketing them on
// their smallest vertex index instead of sorting all of them. Over 2^20
// triples (the parallel bucketing), with many repeats and a face order that
// is not the item order, the pairs are those of the global sort, in its order.
TEST(Keeps_model_validity, duplicate_triples_pair_as_the_global_sort_pairs_them)
{
  using Triple = std::array<std::uint32_t, 3>;
  const std::size_t n = (std::size_t(1) << 20) + 4321, indices = 70000;
  std::mt19937 rng(17);
  std::vector<Triple> tri(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && rng() % 50 == 0) {
      tri[i] = tri[rng() % i];  // a repeat of an earlier face
    } else {
      const std::uint32_t a = rng() % indices, b = rng() % 8, c = rng() % 8;
      tri[i] = {a, std::min<std::uint32_t>(a + b, indices - 1), std::min<std::uint32_t>(a + b + c, indices - 1)};
    }
  }
  // faces compare in the reverse of the item order
  auto face_less = [](std::size_t x, std::size_t y) { return x > y; };
  const auto pairs = mrepair::internal::validity::same_vertex_triples(tri, indices, face_less);

  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  std::sort(all.begin(), all.end(), [&](std::size_t x, std::size_t y) {
    return tri[x] != tri[y] ? tri[x] < tri[y] : face_less(x, y);
  });
  std::vector<std::pair<std::size_t, std::size_t>> expected;
  for (std::size_t k = 1; k < n; ++k)
    if (tri[all[k]] == tri[all[k - 1]]) expected.emplace_back(all[k - 1], all[k]);
  ASSERT_GT(expected.size(), std::size_t(20000));
  EXPECT_EQ(pairs, expected);
}

TYPED_TEST(Keeps_model, moebius_strip_stays_an_open_strip)
{
  using Mesh = typename TypeParam::Mesh;
  const Soup s = moebius(40);
  Mesh m;
  mrepair::Soup_repair_result sr = mrepair::polygon_soup_to_manifold_mesh(s.points, s.polygons, m);
  ASSERT_TRUE(mrepair::succeeded(sr.status));
  ASSERT_EQ(face_count(m), s.polygons.size());
  const std::size_t b0 = border_edges(m);
  for (Input_profile p : {Input_profile::automatic, Input_profile::scan}) {
    Mesh g = m;
    clean_and_check(g, p);
    EXPECT_EQ(face_count(g), s.polygons.size()) << mrepair::to_string(p);
    EXPECT_EQ(border_edges(g), b0) << mrepair::to_string(p);
  }
}

TYPED_TEST(Keeps_model, solid_with_small_holes_comes_out_closed)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = icosphere(2);
  // three holes of one face each
  s.polygons.erase(s.polygons.begin() + 200);
  s.polygons.erase(s.polygons.begin() + 100);
  s.polygons.erase(s.polygons.begin() + 10);
  Mesh m = to_mesh<Mesh>(s);
  mrepair::Scan_cleaning_result r = clean_and_check(m);
  EXPECT_EQ(r.profile.profile, Input_profile::cad);
  EXPECT_TRUE(CGAL::is_closed(m));
  EXPECT_GE(face_count(m), s.polygons.size());
}

// Found on real meshes (CGAL's boeing.off, model-repair's teapot.obj, CGAL's
// pinched.off): the cap of a hole passed through another part of the model
// and added self-intersections. A cap through a clean face is taken back and
// the hole stays open, counted with its reason.
TYPED_TEST(Keeps_model, cap_through_a_clean_surface_is_taken_back)
{
  using Mesh = typename TypeParam::Mesh;
  Soup sphere = icosphere(2);
  const Polygon hole = sphere.polygons[10];
  sphere.polygons.erase(sphere.polygons.begin() + 10);
  // a small closed cube through the middle of the missing face, touching
  // nothing else: the face's cap would cut through it
  Point c = CGAL::centroid(sphere.points[hole[0]], sphere.points[hole[1]], sphere.points[hole[2]]);
  const double half = 0.02;
  Soup s = merged(sphere, translated(cube(2 * half), c.x() - half, c.y() - half, c.z() - half));
  Mesh m = to_mesh<Mesh>(s);
  ASSERT_FALSE(CGAL::Polygon_mesh_processing::does_self_intersect(m));
  mrepair::Scan_cleaning_result r = clean_and_check(m);
  EXPECT_EQ(r.holes.fills_rejected_intersecting, 1u);
  ASSERT_EQ(r.holes.open_holes.size(), 1u);
  EXPECT_EQ(r.holes.open_holes[0].reason, "patch_intersects_surface");
  EXPECT_EQ(r.holes.open_holes[0].vertices, 3u);
  EXPECT_FALSE(CGAL::Polygon_mesh_processing::does_self_intersect(m));
  EXPECT_EQ(face_count(m), s.polygons.size());  // nothing added, nothing lost
}

// admesh's conveyor: a missing face where two parts of a CAD assembly
// already interpenetrate. Its cap only continues the crossing the faces
// around it have, so it is kept and the model comes out closed.
TYPED_TEST(Keeps_model, cap_continuing_an_existing_crossing_is_kept)
{
  using Mesh = typename TypeParam::Mesh;
  const Soup a = icosphere(2), b = translated(icosphere(2), 1.0, 0.05, 0.02);
  const Point cb(1.0, 0.05, 0.02);
  // a face of the first sphere that straddles the second one's surface
  std::size_t straddling = a.polygons.size();
  for (std::size_t i = 0; i < a.polygons.size() && straddling == a.polygons.size(); ++i) {
    int inside = 0;
    for (std::size_t v : a.polygons[i]) inside += CGAL::squared_distance(a.points[v], cb) < 1.0;
    if (inside == 1 || inside == 2) straddling = i;
  }
  ASSERT_LT(straddling, a.polygons.size());
  Soup holed = a;
  holed.polygons.erase(holed.polygons.begin() + std::ptrdiff_t(straddling));
  Mesh m = to_mesh<Mesh>(merged(holed, b));
  mrepair::Scan_cleaning_result r = clean_and_check(m, Input_profile::cad);
  EXPECT_EQ(r.holes.fills_rejected_intersecting, 0u);
  EXPECT_TRUE(r.holes.open_holes.empty());
  EXPECT_TRUE(CGAL::is_closed(m));
  EXPECT_EQ(face_count(m), a.polygons.size() + b.polygons.size());
}

TYPED_TEST(Keeps_model, stray_facet_next_to_a_solid_is_removed_and_counted)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(merged(cube(20.0), translated(triangle(0), -3, -3, -3)));
  mrepair::Scan_cleaning_result r = clean_and_check(m);
  EXPECT_EQ(face_count(m), 12u);
  EXPECT_TRUE(CGAL::is_closed(m));
  EXPECT_EQ(r.steps[4].faces_removed, 1u);
  // a sheet next to nothing closed stays: its parts are the model
  Mesh k = to_mesh<Mesh>(merged(grid(4, 4, 5.0), translated(triangle(0), -3, -3, -3)));
  clean_and_check(k);
  EXPECT_EQ(face_count(k), 33u);
}

// Issue 50, item 3: no part is deleted for being small in a CAD or print
// model. The doorman's case (757 parts, 1,882 faces lost to the small
// component step): a body with many small closed parts and small open
// patches of a few faces each; every face stays.
TYPED_TEST(Keeps_model, cad_profile_keeps_every_small_part)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = icosphere(3, 10.0);  // 1,280 faces
  for (int i = 0; i < 40; ++i) {
    const double x = 12.0 + 0.5 * (i % 10), y = 0.5 * (i / 10);
    s = merged(s, translated(cube(0.1), x, y, 0));              // closed, 12 faces
    s = merged(s, translated(icosphere(0, 0.05), x, y, 3));     // closed, 20 faces
    s = merged(s, translated(grid(2, 2, 0.02), x, y, 6));       // open, 8 faces
    s = merged(s, translated(grid(4, 1, 0.02), x, y, 9));       // open strip, 8 faces
  }
  const std::size_t faces_in = s.polygons.size();
  Mesh m = to_mesh<Mesh>(s);
  const mrepair::Scan_cleaning_result r = clean_and_check(m, Input_profile::cad);
  EXPECT_EQ(r.components.faces_removed, 0u);
  EXPECT_EQ(face_count(m), faces_in);
  EXPECT_EQ(part_count(m), 161u);
}

// Only open debris of a few faces that encloses nothing goes: a lone triangle
// and a quad by a solid; three faces of a tetrahedron enclose a volume (the
// hole filler closes them) and a strip of four faces is a part.
TYPED_TEST(Keeps_model, cad_profile_removes_only_open_debris_of_a_few_faces)
{
  using Mesh = typename TypeParam::Mesh;
  Soup fan;
  fan.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1)};
  fan.polygons = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  Soup s = cube(20.0);
  s = merged(s, translated(triangle(0), -10, 0, 0));     // removed
  s = merged(s, translated(grid(1, 1), -10, 5, 0));      // removed: 2 faces
  s = merged(s, translated(fan, -10, 10, 0));            // kept and closed: 3 + 1 faces
  s = merged(s, translated(grid(4, 1), -10, 15, 0));     // kept: 4 faces, a sheet
  Mesh m = to_mesh<Mesh>(s);
  const mrepair::Scan_cleaning_result r = clean_and_check(m, Input_profile::cad);
  EXPECT_EQ(r.components.faces_removed, 3u);
  EXPECT_EQ(r.components.components_removed, 2u);
  EXPECT_EQ(r.holes.holes_filled, 1u);
  // nothing else goes (the filler may refine the patches it adds)
  EXPECT_GE(face_count(m), 12u + 4u + 4u);
  EXPECT_EQ(part_count(m), 3u);
}

// `mrepair::repair_polygon_soup` of `s` into `m`, which must succeed and be a
// valid closed mesh; the input's points compared with it.
template <class Mesh>
mrepair::Reference_comparison repair_to_closed_mesh(const Soup& s, Mesh& m)
{
  std::vector<Point> points = s.points;
  std::vector<Polygon> polygons = s.polygons;
  const mrepair::Repair_result r = mrepair::repair_polygon_soup(points, polygons, m);
  EXPECT_TRUE(mrepair::succeeded(r.status)) << r.message;
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(CGAL::is_closed(m));
  return mrepair::compare_to_reference(s.points, m);
}

// A part inside another is absorbed by the union: its points end inside the
// output, none is lost (compare_to_reference); a small part beside it stays.
TYPED_TEST(Keeps_model, part_inside_another_is_absorbed_and_nothing_is_lost)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = cube(4.0);
  s = merged(s, translated(cube(1.0), 1.5, 1.5, 1.5));       // inside: absorbed
  s = merged(s, translated(icosphere(1, 0.3), 2, 2, 3.2));   // inside too
  s = merged(s, translated(cube(0.1), 10, 0, 0));            // beside: a part
  Mesh m;
  const mrepair::Reference_comparison c = repair_to_closed_mesh(s, m);
  EXPECT_EQ(c.status, Status::ok);
  EXPECT_EQ(c.vertices, s.points.size());
  EXPECT_EQ(c.vertices_lost, 0u);
  EXPECT_GE(c.vertices_inside, 8u);
  EXPECT_LE(c.max_distance, 1.5 + 1e-9);
}

// Two cubes that share an edge, each written with its own copies of the
// edge's ends and with that edge split at its middle twice, once on each of
// its two faces (four coincident points there; CGAL's stitching test
// nm_cubes.off has this shape). Merging every coincident point would make
// the edge non-manifold, so the soup stage keeps copies, and each cube is
// left with a zero-area border loop along the edge; there are too few seams
// for a gap tolerance. The repair still stitches coincident border points
// (within 1e-6 x the diagonal): both cubes close and touch along the edge.
TYPED_TEST(Keeps_model, cubes_on_one_split_edge_are_stitched_closed)
{
  using Mesh = typename TypeParam::Mesh;
  // the cube [x0,x0+1] x [y0,y0+1] x [0,1]; its vertical edge at (ex, ey)
  // split at z = 0.5 by one point on each of the two faces along it
  auto cube_with_split_edge = [](double x0, double y0, double ex, double ey) {
    Soup c;
    auto add = [&](double x, double y, double z) {
      c.points.emplace_back(x, y, z);
      return c.points.size() - 1;
    };
    std::size_t v[8];
    for (int k = 0; k < 8; ++k) v[k] = add(x0 + (k & 1), y0 + ((k >> 1) & 1), (k >> 2) & 1);
    const std::size_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (auto& f : q) {
      std::vector<std::size_t> poly;
      for (int i = 0; i < 4; ++i) {
        const std::size_t a = v[f[i]], b = v[f[(i + 1) % 4]];
        poly.push_back(a);
        const Point& pa = c.points[a];
        const Point& pb = c.points[b];
        if (pa.x() == ex && pa.y() == ey && pb.x() == ex && pb.y() == ey) poly.push_back(add(ex, ey, 0.5));
      }
      // a fan from the split point (a fan from a corner would have a flat triangle)
      if (poly.size() == 5)
        for (std::size_t k = 0; k < 5; ++k)
          if (c.points[poly[k]].z() == 0.5) {
            std::rotate(poly.begin(), poly.begin() + static_cast<std::ptrdiff_t>(k), poly.end());
            break;
          }
      for (std::size_t i = 1; i + 1 < poly.size(); ++i) c.polygons.push_back({poly[0], poly[i], poly[i + 1]});
    }
    return c;
  };
  Soup s = merged(cube_with_split_edge(0, 0, 1, 1), cube_with_split_edge(1, 1, 1, 1));
  ASSERT_EQ(s.polygons.size(), 28u);
  Mesh m;
  const mrepair::Reference_comparison c = repair_to_closed_mesh(s, m);
  EXPECT_EQ(face_count(m), 28u);
  EXPECT_NEAR(CGAL::Polygon_mesh_processing::volume(m), 2.0, 1e-12);
  EXPECT_EQ(c.vertices_lost, 0u);
  EXPECT_LE(c.max_distance, 1e-12);
}

// A sheet written twice, once in each orientation, each copy with its own
// points (CGAL's non_manifold.off; non_manifold2.off has the second copy in
// two pieces): the file reads as a valid mesh of two coincident layers that
// cross each other everywhere. The repeated copy goes, so nothing crosses and
// no point is lost; a part that repeats only some faces of another stays.
TYPED_TEST(Keeps_model, sheet_written_twice_keeps_one_copy)
{
  using Mesh = typename TypeParam::Mesh;
  const Soup sheet = grid(6, 4);
  // faces [b, e) of `s` with their own copies of their points, reversed
  auto reversed_piece = [](const Soup& s, std::size_t b, std::size_t e) {
    Soup piece;
    std::map<std::size_t, std::size_t> index;
    for (std::size_t f = b; f < e; ++f) {
      Polygon poly;
      for (std::size_t v : s.polygons[f]) {
        auto it = index.emplace(v, piece.points.size()).first;
        if (it->second == piece.points.size()) piece.points.push_back(s.points[v]);
        poly.push_back(it->second);
      }
      std::reverse(poly.begin(), poly.end());
      piece.polygons.push_back(poly);
    }
    return piece;
  };
  const std::size_t n = sheet.polygons.size();
  const Soup one_twin = merged(sheet, reversed_piece(sheet, 0, n));
  const Soup two_pieces = merged(merged(sheet, reversed_piece(sheet, 0, n / 2)), reversed_piece(sheet, n / 2, n));
  for (const Soup* s : {&one_twin, &two_pieces}) {
    std::vector<Point> points = s->points;
    std::vector<Polygon> polygons = s->polygons;
    Mesh m;
    const mrepair::Repair_result r = mrepair::repair_polygon_soup(points, polygons, m);
    ASSERT_TRUE(mrepair::succeeded(r.status)) << r.message;
    EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
    EXPECT_EQ(face_count(m), n);
    EXPECT_FALSE(CGAL::Polygon_mesh_processing::does_self_intersect(m));
    EXPECT_EQ(mrepair::compare_to_reference(s->points, m).vertices_lost, 0u);
  }
  // half the sheet repeated on a sheet of its own beside the full one: the
  // half repeats the full sheet's faces and goes; the full one stays
  const Soup half = merged(sheet, reversed_piece(sheet, 0, n / 2));
  std::vector<Point> points = half.points;
  std::vector<Polygon> polygons = half.polygons;
  Mesh m;
  ASSERT_TRUE(mrepair::succeeded(mrepair::repair_polygon_soup(points, polygons, m).status));
  EXPECT_EQ(face_count(m), n);
  EXPECT_EQ(mrepair::compare_to_reference(half.points, m).vertices_lost, 0u);
}

TYPED_TEST(Keeps_model, input_kind_is_decided_and_can_be_forced)
{
  using Mesh = typename TypeParam::Mesh;
  // a noisy dense sphere reads as a scan
  Soup s = icosphere(4, 10.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.02, 0.02);
  for (Point& p : s.points) p = Point(p.x() + noise(rng), p.y() + noise(rng), p.z() + noise(rng));
  Mesh scan = to_mesh<Mesh>(s);
  mrepair::Input_classification c = mrepair::classify_input(scan);
  EXPECT_EQ(c.profile, Input_profile::scan) << c.reason;
  EXPECT_FALSE(c.chosen_by_user);
  // a tessellated part: flat faces, mixed edge lengths
  Mesh part = to_mesh<Mesh>(merged(grid(60, 40, 0.5), translated(cube(3.0), 0, 0, 1)));
  c = mrepair::classify_input(part);
  EXPECT_EQ(c.profile, Input_profile::cad) << c.reason;
  c = mrepair::classify_input(part, MP::input_profile(Input_profile::scan));
  EXPECT_EQ(c.profile, Input_profile::scan);
  EXPECT_TRUE(c.chosen_by_user);
  // the pipeline runs the profile's steps and says so
  Mesh g = scan;
  mrepair::Scan_cleaning_result r = clean_and_check(g);
  EXPECT_EQ(r.profile.profile, Input_profile::scan);
  EXPECT_TRUE(r.steps[1].enabled);
  Mesh h = scan;
  r = clean_and_check(h, Input_profile::cad);
  EXPECT_FALSE(r.steps[1].enabled);
  EXPECT_TRUE(r.steps[5].enabled);
  EXPECT_TRUE(r.steps[8].enabled);
}

// The whole command on the pentagon OBJ that hung, and the face accounting
// of its report.
namespace {

// the faces of `m` as sorted triples of points (rotated to start at the
// smallest): equal for two meshes with the same faces, whatever the indices.
template <class Mesh>
std::vector<std::array<std::array<double, 3>, 3>> face_signature(const Mesh& m)
{
  std::vector<std::array<std::array<double, 3>, 3>> out;
  for (auto f : faces(m)) {
    std::array<std::array<double, 3>, 3> t{};
    int i = 0;
    for (auto v : CGAL::vertices_around_face(halfedge(f, m), m)) {
      const Point p = get(CGAL::vertex_point, m, v);
      if (i < 3) t[i] = {p.x(), p.y(), p.z()};
      ++i;
    }
    EXPECT_EQ(i, 3);
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace

// On Surface_mesh the pipeline reserves room for its hole fills before the
// statistics' property maps exist, so that fills do not reallocate them; fills
// that need more grow every array (maps included) while the steps hold them.
// Neither may change a result: a mesh whose capacity already holds every fill
// and one without any spare capacity, whose fills outgrow the reserved room,
// come out identical, face for face and figure for figure.
TEST(Keeps_model_reserve, reserved_room_changes_no_result)
{
  // a 60 x 60 sheet with three 16 x 16 holes (64-vertex loops): 5,664 faces,
  // about 1,500 faces of fills
  Soup g = grid(60, 60), s;
  s.points = g.points;
  auto in_hole = [&](const Polygon& q) {
    bool all = true;
    for (std::size_t i : q) {
      const Point& p = g.points[i];
      const bool x = (p.x() >= 3 && p.x() <= 19) || (p.x() >= 22 && p.x() <= 38) ||
                     (p.x() >= 41 && p.x() <= 57);
      all = all && x && p.y() >= 22 && p.y() <= 38;
    }
    return all;
  };
  for (const Polygon& q : g.polygons)
    if (!in_hole(q)) s.polygons.push_back(q);
  // the points inside the holes stay isolated in the soup: drop them
  Surface_mesh built = to_mesh<Surface_mesh>(s);
  std::vector<Surface_mesh::Vertex_index> isolated;
  for (auto v : vertices(built))
    if (built.is_isolated(v)) isolated.push_back(v);
  for (auto v : isolated) remove_vertex(v, built);
  built.collect_garbage();
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(built));
  const std::size_t f0 = face_count(built);
  ASSERT_EQ(f0, 7200u - 3 * 512u);

  Surface_mesh tight(built);  // a copy: no spare capacity
  Surface_mesh roomy(built);
  roomy.reserve(roomy.number_of_vertices() + 20000, roomy.number_of_edges() + 60000,
                roomy.number_of_faces() + 40000);
  mrepair::Scan_cleaning_result rt = mrepair::clean_scan_mesh(tight, MP::input_profile(Input_profile::scan));
  mrepair::Scan_cleaning_result rr = mrepair::clean_scan_mesh(roomy, MP::input_profile(Input_profile::scan));
  ASSERT_EQ(rt.status, Status::ok) << rt.message;
  EXPECT_EQ(rt.holes.holes_filled, 3u);
  // what makes the case: the fills outgrow the room reserved up front
  // (clean_scan_mesh.h: 1/32 of the faces + 1024), so the arrays grow mid-run
  ASSERT_GT(rt.holes.faces_added, f0 / 32 + 1024);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(tight));
  EXPECT_EQ(border_edges(tight), 240u);  // the sheet's outline only
  EXPECT_EQ(rt.faces_after, face_count(tight));
  EXPECT_TRUE(rt.faces_reconcile());

  rt.seconds = rr.seconds = 0;  // the only figures allowed to differ
  for (auto* r : {&rt, &rr})
    for (auto& step : r->steps) step.seconds = 0;
  EXPECT_EQ(mrepair::make_report(rt).to_json(), mrepair::make_report(rr).to_json());
  EXPECT_EQ(vertices(tight).size(), vertices(roomy).size());
  EXPECT_TRUE(face_signature(tight) == face_signature(roomy));
}

TEST(Keeps_model_cli, pentagon_obj_terminates_and_accounts_for_every_face)
{
#ifdef MREPAIR_CLI
  if (!std::ifstream(MREPAIR_CLI)) GTEST_SKIP() << "mrepair not built";
  const std::string dir = ::testing::TempDir();
  const std::string in = dir + "mrepair_pentagon.obj", out = dir + "mrepair_pentagon_out.off",
                    report = dir + "mrepair_pentagon.json";
  {
    std::ofstream f(in);
    f << "v 0 0 0\nv 1 0 0.3\nv 1.3 1 0\nv 0.5 1.6 0.4\nv -0.3 1 0\nf 1// 2// 3// 4// 5//\n";
  }
  const std::string cmd = "timeout 60 " + std::string(MREPAIR_CLI) + " repair " + in + " " + out +
                          " --quiet --report " + report + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  Surface_mesh m;
  ASSERT_EQ(mrepair::read_polygon_mesh(out, m).status, Status::ok);
  EXPECT_EQ(face_count(m), 3u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  std::ifstream r(report);
  const std::string json((std::istreambuf_iterator<char>(r)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"reconciles\": true"), std::string::npos) << json;
  EXPECT_NE(json.find("\"profile\": \"cad\""), std::string::npos) << json;
#else
  GTEST_SKIP() << "MREPAIR_CLI not defined";
#endif
}

}  // namespace

// Issue 37: the solid repair's cases (typed, each output checked with CGAL's
// does_self_intersect).
#include "solids_cases.h"
