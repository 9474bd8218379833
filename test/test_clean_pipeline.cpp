// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Scan cleaning II (issue 6): small components, boundary cleaning, small
// holes with aborted fills, and the whole RameshCleaner pipeline.
#include "fixtures.h"

#include <mrepair/clean_boundaries.h>
#include <mrepair/clean_scan_mesh.h>
#include <mrepair/fill_small_holes.h>
#include <mrepair/geometric_statistics.h>
#include <mrepair/io.h>
#include <mrepair/remove_small_components.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>

// A namespace of its own: this file is compiled in one translation unit with
// other test files (a unity build, CMakeLists.txt).
namespace {
namespace clean_pipeline_tests {

namespace {

using namespace mrepair_test;
namespace MP = mrepair::parameters;
namespace PMP = CGAL::Polygon_mesh_processing;

// Removes the triangles of grid cells [i0, i0+w) x [j0, j0+h) of `grid(nx, .)`.
Soup punched(Soup s, std::size_t nx, std::size_t i0, std::size_t j0, std::size_t w, std::size_t h)
{
  std::vector<Polygon> keep;
  for (std::size_t k = 0; k < s.polygons.size(); ++k) {
    std::size_t cell = k / 2, i = cell % nx, j = cell / nx;
    if (i >= i0 && i < i0 + w && j >= j0 && j < j0 + h) continue;
    keep.push_back(s.polygons[k]);
  }
  s.polygons.swap(keep);
  return s;
}

// Drops points no polygon uses (soup-to-mesh would keep them as isolated vertices).
Soup compacted(const Soup& s)
{
  std::vector<std::size_t> map(s.points.size(), std::size_t(-1));
  Soup out;
  for (const Polygon& p : s.polygons) {
    Polygon q;
    for (std::size_t i : p) {
      if (map[i] == std::size_t(-1)) {
        map[i] = out.points.size();
        out.points.push_back(s.points[i]);
      }
      q.push_back(map[i]);
    }
    out.polygons.push_back(q);
  }
  return out;
}

// A 30 x 30 grid with edges 0.5 and a side x side square hole at (10, 10):
// a loop of 4 side vertices; the outline is a loop of 120.
template <class Mesh>
Mesh grid_with_square_hole(std::size_t side)
{
  return to_mesh<Mesh>(compacted(punched(grid(30, 30, 0.5), 30, 10, 10, side, side)));
}

template <class Mesh>
std::size_t border_loops(const Mesh& m, std::vector<std::size_t>* sizes = nullptr)
{
  std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor> loops;
  PMP::extract_boundary_cycles(m, std::back_inserter(loops));
  if (sizes)
    for (auto h : loops) {
      std::size_t n = 0;
      for (auto g : CGAL::halfedges_around_face(h, m)) { (void)g; ++n; }
      sizes->push_back(n);
    }
  return loops.size();
}

template <class Mesh>
std::size_t components(const Mesh& m)
{
  auto fcc = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  return PMP::connected_components(m, fcc);
}

template <class Mesh>
std::size_t isolated_vertices(const Mesh& m)
{
  std::size_t n = 0;
  for (auto v : vertices(m))
    if (halfedge(v, m) == boost::graph_traits<Mesh>::null_halfedge()) ++n;
  return n;
}

template <class Mesh>
bool all_finite(const Mesh& m)
{
  for (auto v : vertices(m)) {
    auto p = get(CGAL::vertex_point, m, v);
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) return false;
  }
  return true;
}

template <class Mesh>
typename boost::graph_traits<Mesh>::vertex_descriptor vertex_at(const Mesh& m, double x, double y)
{
  for (auto v : vertices(m)) {
    auto p = get(CGAL::vertex_point, m, v);
    if (p.x() == x && p.y() == y) return v;
  }
  return boost::graph_traits<Mesh>::null_vertex();
}

template <class C>
class Clean_pipeline : public ::testing::Test
{};
TYPED_TEST_SUITE(Clean_pipeline, Mesh_configs);

// ---- 3.2 small components ---------------------------------------------------

TYPED_TEST(Clean_pipeline, components_just_below_and_above_the_limit_issue_6)
{
  using Mesh = typename TypeParam::Mesh;
  BOOST_CONCEPT_ASSERT((CGAL::concepts::MutableFaceGraph<Mesh>));
  // 800-face grid, a 38-face strip (19 x 1) and a 40-face strip (20 x 1).
  Soup s = merged(merged(grid(20, 20), translated(grid(19, 1), 0, 30, 0)),
                  translated(grid(20, 1), 0, 40, 0));
  Mesh m = to_mesh<Mesh>(compacted(s));
  ASSERT_EQ(face_count(m), 878u);
  // Relative to the largest (800 faces, area 400) the strips are small under 10%.
  auto r = mrepair::remove_small_components(m, MP::min_component_faces(std::size_t(40), MP::relative_component_size(0.1)));
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.components_removed, 1u);
  EXPECT_EQ(r.faces_removed, 38u);
  EXPECT_EQ(r.vertices_removed, 40u);
  EXPECT_FALSE(r.kept_largest);
  EXPECT_EQ(face_count(m), 840u);
  EXPECT_EQ(components(m), 2u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));

  // Limit 41: the 40-face strip is small now.
  auto r2 = mrepair::remove_small_components(m, MP::min_component_faces(std::size_t(41), MP::relative_component_size(0.1)));
  EXPECT_EQ(r2.components_removed, 1u);
  EXPECT_EQ(face_count(m), 800u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
}

// The default relative size (1% of the largest component's faces and area)
// keeps parts of a model: two strips of 5% stay although under 400 faces.
TYPED_TEST(Clean_pipeline, components_relative_to_the_largest_stay)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = merged(merged(grid(20, 20), translated(grid(19, 1), 0, 30, 0)),
                  translated(grid(20, 1), 0, 40, 0));
  Mesh m = to_mesh<Mesh>(compacted(s));
  auto r = mrepair::remove_small_components(m);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.components_removed, 0u);
  EXPECT_EQ(r.components_kept_relative, 2u);
  EXPECT_EQ(face_count(m), 878u);
  // A 2-face speck next to the 800-face grid (0.25%) goes.
  Mesh d = to_mesh<Mesh>(compacted(merged(grid(20, 20), translated(grid(1, 1), 30, 0, 0))));
  auto rd = mrepair::remove_small_components(d);
  EXPECT_EQ(rd.components_removed, 1u);
  EXPECT_EQ(face_count(d), 800u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(d));
}

TYPED_TEST(Clean_pipeline, components_never_empties_the_mesh)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(merged(grid(3, 3), translated(grid(1, 1), 10, 0, 0)));
  // default 400 faces: both are small; relative to the largest, under 50%
  // of it only the 2-face one is.
  auto r = mrepair::remove_small_components(m, MP::relative_component_size(0.5));
  EXPECT_EQ(r.components_removed, 1u);
  EXPECT_EQ(r.faces_removed, 2u);
  EXPECT_TRUE(r.kept_largest);
  EXPECT_EQ(face_count(m), 18u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));

  // With every size relative to it small, the largest still stays.
  auto r1 = mrepair::remove_small_components(m, MP::relative_component_size(1.0));
  EXPECT_EQ(face_count(m), 18u);
  EXPECT_TRUE(r1.kept_largest);

  auto r0 = mrepair::remove_small_components(m, MP::min_component_faces(0));
  EXPECT_EQ(r0.status, mrepair::Status::invalid_parameter);
}

// ---- 3.3 boundary cleaning --------------------------------------------------

TYPED_TEST(Clean_pipeline, jagged_boundary_and_flipped_border_face)
{
  using Mesh = typename TypeParam::Mesh;
  // grid(30, 30): vertex (i, j) has index j * 31 + i. Its corners (30, 0)
  // and (0, 30) lie in one triangle each (valence 2).
  Soup s = grid(30, 30);
  auto id = [](std::size_t i, std::size_t j) { return j * 31 + i; };
  // A dangling ear on the border edge (5,0)-(6,0), in the plane: its apex has valence 2.
  s.points.emplace_back(5.5, -1.0, 0.0);
  s.polygons.push_back({id(6, 0), id(5, 0), s.points.size() - 1});
  // A border face folded back over the grid on edge (10,0)-(11,0): dihedral ~180 degrees.
  s.points.emplace_back(10.5, 0.8, 0.01);
  s.polygons.push_back({id(11, 0), id(10, 0), s.points.size() - 1});
  Mesh m = to_mesh<Mesh>(compacted(s));
  ASSERT_EQ(face_count(m), 1802u);

  auto r = mrepair::clean_boundaries(m);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  // The outline is straight but for the ear and the fold: not a jagged loop,
  // and the grid's valence-2 corners stay (a sheet's corners). The ear is a
  // tooth (turns of 63, -127 and 63 degrees: its apex and both base
  // vertices); the fold is not (seen from its own flipped normal it turns
  // one way), but both its base vertices have an incident edge above 120
  // degrees. Round 1 removes the ear apex and the two fold base vertices:
  // the ear, the fold, and the 5 grid triangles around (10,0) and (11,0).
  EXPECT_EQ(r.loops, 1u);
  EXPECT_EQ(r.jagged_loops, 0u);
  EXPECT_EQ(r.tooth_vertices, 3u);
  EXPECT_EQ(r.bad_vertices_removed, 3u);
  EXPECT_EQ(r.faces_removed, 7u);
  EXPECT_EQ(r.pinch_faces_removed, 0u);
  EXPECT_EQ(r.rounds, 1u);
  EXPECT_EQ(face_count(m), 1795u);
  EXPECT_NE(vertex_at(m, 30, 0), boost::graph_traits<Mesh>::null_vertex());
  EXPECT_NE(vertex_at(m, 0, 30), boost::graph_traits<Mesh>::null_vertex());
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  // Smoothing moved the boundary ring a little, never out of the plane.
  double max_shift = 0.;
  for (auto v : vertices(m)) {
    auto p = get(CGAL::vertex_point, m, v);
    EXPECT_NEAR(p.z(), 0., 1e-12);
    max_shift = (std::max)(max_shift, std::abs(p.x() - std::round(p.x())));
    max_shift = (std::max)(max_shift, std::abs(p.y() - std::round(p.y())));
  }
  EXPECT_GT(max_shift, 0.);
  EXPECT_LT(max_shift, 0.3);
  EXPECT_EQ(border_loops(m), 1u);
}

TYPED_TEST(Clean_pipeline, dangling_face_on_a_hole_border_then_fill)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = punched(grid(30, 30), 30, 10, 10, 4, 4);  // hole of 16 boundary vertices
  auto id = [](std::size_t i, std::size_t j) { return j * 31 + i; };
  s.points.emplace_back(11.5, 10.7, 0.0);  // ear pointing into the hole
  s.polygons.push_back({id(11, 10), id(12, 10), s.points.size() - 1});
  Mesh m = to_mesh<Mesh>(compacted(s));
  ASSERT_EQ(face_count(m), 1800u - 32u + 1u);

  auto r = mrepair::clean_boundaries(m);
  EXPECT_EQ(r.bad_vertices_removed, 1u);  // the ear apex; the outer corners stay
  EXPECT_EQ(r.faces_removed, 1u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  std::vector<std::size_t> sizes;
  EXPECT_EQ(border_loops(m, &sizes), 2u);

  auto h = mrepair::fill_small_holes(m);  // outer loop: 118 vertices, not small
  EXPECT_EQ(h.status, mrepair::Status::ok);
  EXPECT_EQ(h.holes_found, 1u);
  EXPECT_EQ(h.holes_filled, 1u);
  EXPECT_EQ(h.holes_too_large, 1u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(border_loops(m), 1u);
}

TYPED_TEST(Clean_pipeline, island_near_a_boundary_is_removed)
{
  using Mesh = typename TypeParam::Mesh;
  // A 6 x 6 hole, with a 3 x 2 island (12 faces) floating in it. Boundary
  // cleaning never removes a whole original component (it could be a part
  // of the model); the small-component step, relative to the largest, does.
  Soup s = merged(punched(grid(30, 30), 30, 10, 10, 6, 6), translated(grid(3, 2, 1.0), 11.5, 11.5, 0));
  Mesh m = to_mesh<Mesh>(compacted(s));
  ASSERT_EQ(components(m), 2u);
  auto r = mrepair::clean_boundaries(m);
  EXPECT_TRUE(mrepair::succeeded(r.status));
  EXPECT_EQ(components(m), 2u);
  EXPECT_EQ(r.components_removed, 0u);
  auto c = mrepair::remove_small_components(m);
  EXPECT_EQ(c.components_removed, 1u);
  EXPECT_EQ(c.faces_removed, 12u);
  EXPECT_EQ(components(m), 1u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(isolated_vertices(m), 0u);
}

TYPED_TEST(Clean_pipeline, removal_never_leaves_a_pinched_vertex)
{
  using Mesh = typename TypeParam::Mesh;
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;
  // Around interior vertex (5, 5) of grid(10, 10) the fan is, in order:
  // [(5,5),(6,5),(6,6)], [(5,5),(6,6),(5,6)], [(5,5),(5,6),(4,5)],
  // [(5,5),(4,5),(4,4)], [(5,5),(4,4),(5,4)], [(5,5),(5,4),(6,5)].
  // Removing the 1st and 5th would leave two holes touching at (5, 5): the
  // smaller remaining fan (the 6th face alone) is removed too.
  Mesh m = to_mesh<Mesh>(grid(10, 10));
  auto vpm = get(CGAL::vertex_point, m);
  auto is = [&](face_descriptor f, std::initializer_list<std::array<int, 2>> corners) {
    std::size_t hit = 0;
    for (auto v : CGAL::vertices_around_face(halfedge(f, m), m))
      for (auto c : corners)
        if (get(vpm, v).x() == c[0] && get(vpm, v).y() == c[1]) ++hit;
    return hit == 3;
  };
  std::vector<face_descriptor> doomed;
  face_descriptor sixth = boost::graph_traits<Mesh>::null_face();
  for (face_descriptor f : faces(m)) {
    if (is(f, {{5, 5}, {6, 5}, {6, 6}}) || is(f, {{5, 5}, {4, 4}, {5, 4}})) doomed.push_back(f);
    if (is(f, {{5, 5}, {5, 4}, {6, 5}})) sixth = f;
  }
  ASSERT_EQ(doomed.size(), 2u);
  ASSERT_NE(sixth, boost::graph_traits<Mesh>::null_face());
  mrepair::internal::Local_operations<Mesh, decltype(vpm)> ops(m, vpm);
  std::size_t removed = ops.remove_faces_without_pinches(doomed);
  EXPECT_EQ(removed, 3u);
  EXPECT_EQ(ops.counts().pinch_faces_removed, 1u);
  EXPECT_EQ(ops.counts().pinches_resolved, 1u);
  EXPECT_EQ(ops.counts().faces_removed, 3u);
  EXPECT_EQ(face_count(m), 197u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(border_loops(m), 2u);
}

// ---- 3.4 / 3.5 small holes ----------------------------------------------------

TYPED_TEST(Clean_pipeline, small_hole_patch_matches_the_surrounding_density)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = grid_with_square_hole<Mesh>(6);  // 24-vertex loop, edges 0.5
  const std::size_t f0 = face_count(m);
  auto r = mrepair::fill_small_holes(m, MP::max_hole_vertices(100));
  EXPECT_EQ(r.holes_filled, 1u);
  EXPECT_EQ(r.holes_too_large, 1u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  // The missing 72 triangles come back at about the same density.
  const std::size_t added = face_count(m) - f0;
  EXPECT_GT(added, 40u);
  EXPECT_LT(added, 120u);
  EXPECT_GT(r.vertices_added, 10u);
  // Patch edges: every edge inside the hole's square is near 0.5 long.
  double sum = 0, mx = 0;
  std::size_t n = 0;
  for (auto e : edges(m)) {
    auto p = get(CGAL::vertex_point, m, source(e, m)), q = get(CGAL::vertex_point, m, target(e, m));
    auto in = [](const Point& x) {
      return x.x() > 5.01 && x.x() < 7.99 && x.y() > 5.01 && x.y() < 7.99;
    };
    if (!in(p) && !in(q)) continue;
    double l = std::sqrt(CGAL::squared_distance(p, q));
    sum += l;
    mx = (std::max)(mx, l);
    ++n;
    EXPECT_NEAR(p.z(), 0., 1e-9);
  }
  ASSERT_GT(n, 0u);
  EXPECT_NEAR(sum / n, 0.5, 0.15);
  EXPECT_LT(mx, 0.5 * 4. / 3. + 0.05);

  // Denser patches with a density factor below 1.
  Mesh m2 = grid_with_square_hole<Mesh>(6);
  auto r2 = mrepair::fill_small_holes(m2, MP::hole_density_factor(0.5));
  EXPECT_EQ(r2.holes_filled, 1u);
  EXPECT_GT(face_count(m2) - f0, 2 * added);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m2));
}

TYPED_TEST(Clean_pipeline, large_hole_is_left_open)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = punched(grid(30, 30), 30, 5, 5, 12, 12);  // 48-vertex loop
  Mesh m = to_mesh<Mesh>(compacted(s));
  const std::size_t f0 = face_count(m);
  auto r = mrepair::fill_small_holes(m, MP::max_hole_vertices(48));  // fewer than 48 only
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.holes_found, 0u);
  EXPECT_EQ(r.holes_too_large, 2u);
  EXPECT_EQ(face_count(m), f0);
  auto r2 = mrepair::fill_small_holes(m, MP::max_hole_vertices(49));
  EXPECT_EQ(r2.holes_filled, 1u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
}

TYPED_TEST(Clean_pipeline, aborted_fill_of_a_slit_is_enlarged_and_filled)
{
  using Mesh = typename TypeParam::Mesh;
  // A slit along y = 15 from x = 10 to x = 14: the faces below the line use
  // copies of vertices (11..13, 15). Its 8-vertex loop is collinear, so every
  // triangulation is degenerate: the fill aborts, the loop's 1-ring is
  // removed and the larger hole is filled.
  Soup s = grid(30, 30);
  auto id = [](std::size_t i, std::size_t j) { return j * 31 + i; };
  std::map<std::size_t, std::size_t> copy;
  for (std::size_t i = 11; i <= 13; ++i) {
    copy[id(i, 15)] = s.points.size();
    s.points.push_back(s.points[id(i, 15)]);
  }
  for (std::size_t k = 0; k < s.polygons.size(); ++k) {
    std::size_t j = (k / 2) / 30;
    if (j != 14) continue;  // cells just below the line
    for (std::size_t& v : s.polygons[k])
      if (copy.count(v)) v = copy[v];
  }
  Mesh m = to_mesh<Mesh>(compacted(s));
  std::vector<std::size_t> sizes;
  ASSERT_EQ(border_loops(m, &sizes), 2u);
  auto r = mrepair::fill_small_holes(m);
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_GE(r.aborted_fills, 1u);
  EXPECT_GE(r.enlargements, 1u);
  EXPECT_GT(r.enlargement_faces_removed, 0u);
  EXPECT_EQ(r.holes_filled, 1u);
  EXPECT_TRUE(r.open_holes.empty());
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_EQ(border_loops(m), 1u);

  // With no enlargement allowed the hole is reported open, with its reason.
  Mesh m2 = to_mesh<Mesh>(compacted(s));
  auto r2 = mrepair::fill_small_holes(m2, MP::max_hole_enlargements(0));
  EXPECT_EQ(r2.status, mrepair::Status::partial);
  ASSERT_EQ(r2.open_holes.size(), 1u);
  EXPECT_EQ(r2.open_holes[0].reason, "triangulation_failed");
  EXPECT_EQ(r2.open_holes[0].vertices, 8u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m2));
}

// ---- 3.5 fills that would create a complex edge ----------------------------

// true when two distinct edges join the same two vertices (a halfedge mesh
// cannot hold a complex edge; a fill that ignored an existing edge would
// leave such a pair instead).
template <class Mesh>
bool has_multi_edge(const Mesh& m)
{
  for (auto v : vertices(m)) {
    if (halfedge(v, m) == boost::graph_traits<Mesh>::null_halfedge()) continue;
    std::set<typename boost::graph_traits<Mesh>::vertex_descriptor> seen;
    for (auto h : CGAL::halfedges_around_target(halfedge(v, m), m))
      if (!seen.insert(source(h, m)).second) return true;
  }
  return false;
}

template <class Mesh>
void expect_clean_disk(const Mesh& m, std::size_t outer_loop, const char* what)
{
  SCOPED_TRACE(what);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_FALSE(has_multi_edge(m));
  std::vector<std::size_t> sizes;
  EXPECT_EQ(border_loops(m, &sizes), 1u);
  if (sizes.size() == 1) {
    EXPECT_EQ(sizes[0], outer_loop);
  }
  // a disk: V - E + F = 1
  EXPECT_EQ(vertices(m).size() + face_count(m), edges(m).size() + 1);
}

// The first round of fills runs as a batch whose patches are remeshed in
// parallel (hole_filler.h, fill_batch): the result must not depend on the
// number of threads (the same faces on the same points, in the same order).
TYPED_TEST(Clean_pipeline, batch_fill_does_not_depend_on_the_threads)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(60, 60, 0.5);
  // 16 rectangular holes of 2 to 4 cells a side on a wavy sheet
  std::vector<Polygon> keep;
  for (std::size_t k = 0; k < s.polygons.size(); ++k) {
    const std::size_t cell = k / 2, i = cell % 60, j = cell / 60;
    const bool hole = i % 14 >= 5 && i % 14 < 7 + (j / 14) % 3 && j % 14 >= 5 && j % 14 < 7 + (i / 14) % 3 &&
                      i < 56 && j < 56;
    if (!hole) keep.push_back(s.polygons[k]);
  }
  s.polygons.swap(keep);
  for (Point& p : s.points) p = Point(p.x(), p.y(), 0.8 * std::sin(0.4 * p.x()) * std::cos(0.3 * p.y()));
  const Mesh m0 = to_mesh<Mesh>(compacted(s));
  auto fill_with = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    Mesh m = m0;
    const auto r = mrepair::fill_small_holes(m, MP::max_hole_vertices(40));
    EXPECT_EQ(r.status, mrepair::Status::ok);
    EXPECT_EQ(r.holes_filled, 16u);
    EXPECT_GT(r.vertices_added, 0u);  // refined patches, not Liepa's alone
    EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
    std::vector<std::array<double, 9>> triangles;
    for (auto f : faces(m)) {
      std::array<double, 9> t{};
      int k = 0;
      for (auto v : CGAL::vertices_around_face(halfedge(f, m), m)) {
        const Point p = get(CGAL::vertex_point, m, v);
        t[k++] = p.x();
        t[k++] = p.y();
        t[k++] = p.z();
      }
      triangles.push_back(t);
    }
    return triangles;
  };
  const auto one = fill_with(1), all = fill_with(8);
  EXPECT_GT(one.size(), face_count(m0));
  EXPECT_TRUE(one == all);
}

TYPED_TEST(Clean_pipeline, fill_avoids_an_existing_chord_of_its_loop)
{
  using Mesh = typename TypeParam::Mesh;
  // A 6x6 grid without the 3x3 cells (1..3, 1..3) except the "tongue" cell
  // (2,3), which hangs into the hole from its top edge. The 14-vertex loop
  // (1,1) (2,1) (3,1) (4,1) (4,2) (4,3) (4,4) (3,4) (3,3) (2,3) (2,4) (1,4)
  // (1,3) (1,2) runs round the tongue, so two pairs of non-adjacent loop
  // vertices are already joined by interior edges: the tongue's diagonal
  // (2,3)-(3,4) and its base (2,4)-(3,4). A fan from (3,4) would duplicate
  // both; the fill must avoid them.
  Soup s = grid(6, 6);
  std::vector<Polygon> keep;
  for (std::size_t k = 0; k < s.polygons.size(); ++k) {
    const std::size_t cell = k / 2, i = cell % 6, j = cell / 6;
    if (i >= 1 && i <= 3 && j >= 1 && j <= 3 && !(i == 2 && j == 3)) continue;
    keep.push_back(s.polygons[k]);
  }
  s.polygons.swap(keep);
  s = compacted(s);  // (2,2) and (3,2) are gone
  const Mesh m0 = to_mesh<Mesh>(s);
  ASSERT_EQ(face_count(m0), 72u - 16u);
  ASSERT_EQ(vertices(m0).size(), 49u - 2u);
  const auto a = vertex_at(m0, 2, 3), b = vertex_at(m0, 3, 4), c = vertex_at(m0, 2, 4);
  ASSERT_TRUE(halfedge(a, b, m0).second);
  ASSERT_TRUE(halfedge(c, b, m0).second);
  std::vector<std::size_t> sizes;
  ASSERT_EQ(border_loops(m0, &sizes), 2u);
  std::sort(sizes.begin(), sizes.end());
  ASSERT_EQ(sizes, (std::vector<std::size_t>{14, 24}));

  // Unrefined: a triangulation of a 14-gon has exactly 12 triangles.
  Mesh m = m0;
  auto r = mrepair::fill_small_holes(m, MP::max_hole_vertices(20, MP::refine_hole_patches(false)));
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.holes_found, 1u);
  EXPECT_EQ(r.holes_too_large, 1u);  // the grid's border, 24 vertices
  EXPECT_EQ(r.holes_filled, 1u);
  EXPECT_EQ(r.aborted_fills, 0u);
  EXPECT_EQ(r.faces_added, 12u);
  EXPECT_EQ(face_count(m), 56u + 12u);
  EXPECT_EQ(vertices(m).size(), 47u);
  EXPECT_EQ(edges(m).size(), 47u + 68u - 1u);
  expect_clean_disk(m, 24, "unrefined");
  // the chords still have exactly their two old faces each
  EXPECT_FALSE(is_border_edge(halfedge(a, b, m).first, m));
  EXPECT_FALSE(is_border_edge(halfedge(c, b, m).first, m));

  // Refined to the loop's density: still no duplicated edge.
  Mesh m2 = m0;
  auto r2 = mrepair::fill_small_holes(m2, MP::max_hole_vertices(20));
  EXPECT_EQ(r2.status, mrepair::Status::ok);
  EXPECT_EQ(r2.holes_filled, 1u);
  EXPECT_EQ(r2.aborted_fills, 0u);
  expect_clean_disk(m2, 24, "refined");
}

// Builds a 12x12 grid whose cells (4..7, 4..7) are replaced by a gadget: the
// 16-vertex square loop round them is zipped (by angle round an inner point)
// to the triangle p (6,5), q (7,6), s (6,7), and a "tongue" triangle
// (p, q, r) with r (6,6) on the segment p-s sits inside it. The hole left is
// the loop p, r, q, s: a triangle (r, q, s) plus a zero-width slit between
// the tongue's edge p-r and the zip face's edge s-p. Its only two
// triangulations use the diagonal p-q, the tongue's base, already an
// interior edge (a complex edge), or the diagonal r-s, whose triangle
// (p, r, s) is degenerate (collinear).
Soup complex_edge_gadget()
{
  Soup s = grid(12, 12);
  std::vector<Polygon> keep;
  for (std::size_t k = 0; k < s.polygons.size(); ++k) {
    const std::size_t cell = k / 2, i = cell % 12, j = cell / 12;
    if (i >= 4 && i < 8 && j >= 4 && j < 8) continue;
    keep.push_back(s.polygons[k]);
  }
  s.polygons.swap(keep);
  auto gid = [](std::size_t i, std::size_t j) { return j * 13 + i; };
  std::vector<std::size_t> outer;  // counter-clockwise from (4,4)
  for (std::size_t i = 4; i < 8; ++i) outer.push_back(gid(i, 4));
  for (std::size_t j = 4; j < 8; ++j) outer.push_back(gid(8, j));
  for (std::size_t i = 8; i > 4; --i) outer.push_back(gid(i, 8));
  for (std::size_t j = 8; j > 4; --j) outer.push_back(gid(4, j));
  auto add = [&](double x, double y) {
    s.points.emplace_back(x, y, 0.);
    return s.points.size() - 1;
  };
  const std::size_t p = add(6, 5), q = add(7, 6), sv = add(6, 7), r = add(6, 6);
  s.polygons.push_back({p, q, r});
  const std::vector<std::size_t> inner = {p, q, sv};  // counter-clockwise
  const double cx = 19.0 / 3.0, cy = 6.0;           // inside (p, q, s)
  auto angle = [&](std::size_t v) {
    double a = std::atan2(s.points[v].y() - cy, s.points[v].x() - cx);
    return a < 0 ? a + 2 * CGAL_PI : a;
  };
  auto start = [&](const std::vector<std::size_t>& L) {
    std::size_t k = 0;
    for (std::size_t i = 1; i < L.size(); ++i)
      if (angle(L[i]) < angle(L[k])) k = i;
    std::vector<std::size_t> out(L.begin() + k, L.end());
    out.insert(out.end(), L.begin(), L.begin() + k);
    return out;
  };
  auto unwrapped = [&](const std::vector<std::size_t>& L) {
    std::vector<double> a;
    for (std::size_t i = 0; i <= L.size(); ++i) {
      double x = angle(L[i % L.size()]);
      while (!a.empty() && x < a.back()) x += 2 * CGAL_PI;
      a.push_back(x);
    }
    return a;
  };
  const std::vector<std::size_t> O = start(outer), I = start(inner);
  const std::vector<double> ao = unwrapped(O), ai = unwrapped(I);
  std::size_t i = 0, j = 0;
  while (i < O.size() || j < I.size()) {
    if (j == I.size() || (i < O.size() && ao[i + 1] <= ai[j + 1])) {
      s.polygons.push_back({O[i], O[(i + 1) % O.size()], I[j % I.size()]});
      ++i;
    } else {
      s.polygons.push_back({I[(j + 1) % I.size()], I[j], O[i % O.size()]});
      ++j;
    }
  }
  return compacted(s);  // the 9 grid vertices inside the square are gone
}

TYPED_TEST(Clean_pipeline, fill_that_would_create_a_complex_edge_is_enlarged)
{
  using Mesh = typename TypeParam::Mesh;
  const Mesh m0 = to_mesh<Mesh>(complex_edge_gadget());
  // 288 grid triangles - 32 + 16 + 3 zip triangles + the tongue
  ASSERT_EQ(face_count(m0), 276u);
  ASSERT_EQ(vertices(m0).size(), 169u - 9u + 4u);
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m0));
  ASSERT_TRUE(halfedge(vertex_at(m0, 6, 5), vertex_at(m0, 7, 6), m0).second);  // p-q
  std::vector<std::size_t> sizes;
  ASSERT_EQ(border_loops(m0, &sizes), 2u);
  std::sort(sizes.begin(), sizes.end());
  ASSERT_EQ(sizes, (std::vector<std::size_t>{4, 48}));

  // No enlargement allowed: left open, with the reason; the mesh is untouched.
  Mesh m1 = m0;
  auto r1 = mrepair::fill_small_holes(
      m1, MP::max_hole_vertices(40, MP::max_hole_enlargements(std::size_t(0))));
  EXPECT_EQ(r1.status, mrepair::Status::partial);
  EXPECT_EQ(r1.holes_found, 1u);
  EXPECT_EQ(r1.aborted_fills, 1u);
  EXPECT_EQ(r1.holes_filled, 0u);
  ASSERT_EQ(r1.open_holes.size(), 1u);
  EXPECT_EQ(r1.open_holes[0].vertices, 4u);
  EXPECT_EQ(r1.open_holes[0].reason, "triangulation_failed");
  EXPECT_EQ(face_count(m1), 276u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m1));
  EXPECT_FALSE(has_multi_edge(m1));

  // One enlargement: every zip face and the tongue touch p, q or s (20
  // faces); r, p, q, s are left without faces and go; the 16-vertex square
  // loop is filled by 14 triangles (unrefined).
  Mesh m = m0;
  auto r = mrepair::fill_small_holes(
      m, MP::max_hole_vertices(40, MP::refine_hole_patches(false)));
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(r.aborted_fills, 1u);
  EXPECT_EQ(r.enlargements, 1u);
  EXPECT_EQ(r.enlargement_faces_removed, 20u);
  EXPECT_EQ(r.holes_filled, 1u);
  EXPECT_TRUE(r.open_holes.empty());
  EXPECT_EQ(r.faces_added, 14u);
  EXPECT_EQ(face_count(m), 276u - 20u + 14u);
  EXPECT_EQ(vertices(m).size(), 160u);
  expect_clean_disk(m, 48, "unrefined");

  // Refined, and through the whole pipeline.
  Mesh m2 = m0;
  auto r2 = mrepair::fill_small_holes(m2, MP::max_hole_vertices(40));
  EXPECT_EQ(r2.status, mrepair::Status::ok);
  EXPECT_EQ(r2.holes_filled, 1u);
  EXPECT_GT(face_count(m2), 270u);
  expect_clean_disk(m2, 48, "refined");
  Mesh m3 = m0;
  auto r3 = mrepair::clean_scan_mesh(
      m3, MP::max_hole_vertices(40, MP::input_profile(mrepair::Input_profile::scan)));
  EXPECT_TRUE(mrepair::succeeded(r3.status)) << mrepair::to_string(r3.status);
  EXPECT_TRUE(r3.holes.open_holes.empty());
  EXPECT_EQ(border_loops(m3), 1u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m3));
  EXPECT_FALSE(has_multi_edge(m3));
}

// The fast soup check of the CLI agrees with PMP::is_polygon_soup_a_polygon_mesh.
TEST(Clean_pipeline_soup_check, agrees_with_cgal)
{
  using mrepair::is_polygon_soup_a_polygon_mesh;
  auto both = [](const Soup& s) {
    bool a = is_polygon_soup_a_polygon_mesh(s.polygons, s.points.size());
    bool b = PMP::is_polygon_soup_a_polygon_mesh(s.polygons);
    EXPECT_EQ(a, b);
    return a;
  };
  EXPECT_TRUE(both(grid(4, 3)));
  EXPECT_TRUE(both(grid(2, 2, 1.0, true)));
  EXPECT_TRUE(both(icosphere(1)));
  EXPECT_TRUE(both(punched(grid(6, 6), 6, 2, 2, 2, 2)));
  Soup flipped = grid(3, 3);
  std::swap(flipped.polygons[4][0], flipped.polygons[4][1]);
  EXPECT_FALSE(both(flipped));
  Soup fin = grid(2, 1);
  fin.points.emplace_back(0.5, 0.5, 1.0);
  fin.polygons.push_back({0, 4, fin.points.size() - 1});  // third face on edge 0-4
  EXPECT_FALSE(both(fin));
  // Bowtie: two triangles sharing only vertex 0.
  Soup bow;
  bow.points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(-1, 0, 0), Point(-1, -1, 0)};
  bow.polygons = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_FALSE(both(bow));
  Soup repeated = grid(1, 1);
  repeated.polygons[0] = {0, 1, 0, 3};
  EXPECT_FALSE(is_polygon_soup_a_polygon_mesh(repeated.polygons, repeated.points.size()));
  Soup out_of_range = grid(1, 1);
  out_of_range.polygons[0][0] = 99;
  EXPECT_FALSE(is_polygon_soup_a_polygon_mesh(out_of_range.polygons, out_of_range.points.size()));
}

// ---- statistics kept current through the edit observer ----------------------


// Locally maintained statistics equal a fresh global computation.
template <class Mesh>
::testing::AssertionResult stats_equal_fresh(Mesh& m, const mrepair::Geometric_statistics<Mesh>& st)
{
  mrepair::Geometric_statistics<Mesh> fresh(m);
  fresh.compute_all();
  const double tol = 1e-12;
  for (auto f : faces(m)) {
    const auto &a = st.face_stats(f), &b = fresh.face_stats(f);
    if (std::abs(a.area - b.area) > tol || std::abs(a.min_angle - b.min_angle) > tol)
      return ::testing::AssertionFailure() << "face area/min angle differ";
  }
  for (auto h : halfedges(m)) {
    const auto &a = st.halfedge_stats(h), &b = fresh.halfedge_stats(h);
    if (std::abs(a.opposite_angle - b.opposite_angle) > tol || std::abs(a.length - b.length) > tol ||
        std::abs(a.dihedral - b.dihedral) > tol)
      return ::testing::AssertionFailure() << "halfedge/edge statistics differ";
  }
  for (auto v : vertices(m)) {
    const auto &a = st.vertex_stats(v), &b = fresh.vertex_stats(v);
    if (a.valence != b.valence || std::abs(a.mean_edge_length - b.mean_edge_length) > tol ||
        std::abs(a.max_dihedral - b.max_dihedral) > tol)
      return ::testing::AssertionFailure() << "vertex statistics differ";
  }
  if (st.edge_count() != fresh.edge_count() ||
      std::abs(st.global_mean_edge_length() - fresh.global_mean_edge_length()) >
          1e-9 * fresh.global_mean_edge_length())
    return ::testing::AssertionFailure() << "global mean/edge count differ";
  return ::testing::AssertionSuccess();
}

TYPED_TEST(Clean_pipeline, steps_keep_statistics_current_through_the_local_operations)
{
  using Mesh = typename TypeParam::Mesh;
  // Jagged border, a dangling ear into a hole, an island, an aborted (slit) fill.
  Soup s = punched(grid(30, 30), 30, 3, 3, 4, 4);
  auto id = [](std::size_t i, std::size_t j) { return j * 31 + i; };
  s.points.emplace_back(4.5, 3.7, 0.0);
  s.polygons.push_back({id(4, 3), id(5, 3), s.points.size() - 1});
  s.points.emplace_back(10.5, 0.8, 0.01);
  s.polygons.push_back({id(11, 0), id(10, 0), s.points.size() - 1});
  std::map<std::size_t, std::size_t> copy;
  for (std::size_t i = 16; i <= 18; ++i) {
    copy[id(i, 20)] = s.points.size();
    s.points.push_back(s.points[id(i, 20)]);
  }
  for (Polygon& p : s.polygons) {
    bool below = false;
    for (std::size_t v : p) below = below || (v < 31 * 31 && s.points[v].y() < 19.5 && s.points[v].y() > 18.5);
    if (below)
      for (std::size_t& v : p)
        if (copy.count(v)) v = copy[v];
  }
  s = merged(s, translated(grid(2, 1), 40, 40, 0));
  Mesh m = to_mesh<Mesh>(compacted(s));
  // The steps' workers, run as the pipeline runs them: every edit goes
  // through one Local_operations holding the statistics.
  namespace SC = mrepair::internal::clean_pipeline;
  auto vpm = get(CGAL::vertex_point, m);
  mrepair::Geometric_statistics<Mesh> st(m);
  st.compute_all();
  mrepair::internal::Local_operations<Mesh, decltype(vpm)> ops(m, vpm);
  ops.keep_current(&st);
  mrepair::Default_visitor vis;
  const std::size_t f0 = face_count(m);
  auto b = SC::clean_boundaries_with(ops, SC::Boundary_settings(), vis);
  EXPECT_GT(b.faces_removed, 0u);
  EXPECT_EQ(ops.counts().faces_removed, b.faces_removed + b.component_faces_removed);
  EXPECT_TRUE(stats_equal_fresh(m, st));
  auto c = SC::remove_small_components_seeded(ops, faces(m), 100, 1.);
  EXPECT_EQ(c.components_removed, 1u);  // the island
  EXPECT_TRUE(stats_equal_fresh(m, st));
  SC::Small_hole_filler<Mesh, decltype(vpm)> filler(ops, SC::Hole_filling_settings());
  filler.run(vis);
  const auto& h = filler.result;
  EXPECT_GE(h.holes_filled, 2u);
  EXPECT_GE(h.enlargements, 1u);
  EXPECT_TRUE(stats_equal_fresh(m, st));
  // a removal that no later insertion recycles (a Surface_mesh reuses the
  // slots of removed faces for new ones, as the patches did)
  std::vector<typename boost::graph_traits<Mesh>::face_descriptor> one{*faces(m).begin()};
  EXPECT_GE(ops.remove_faces_without_pinches(one), 1u);
  EXPECT_TRUE(stats_equal_fresh(m, st));
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  // the counts of the operations reconcile with the mesh
  EXPECT_EQ(f0 + ops.counts().faces_added, face_count(m) + ops.counts().faces_removed);
  // the constant-time element counts the operations use agree with the
  // ranges, removed (not yet collected) elements left out
  EXPECT_EQ(mrepair::internal::face_count(m),
            static_cast<std::size_t>(std::distance(faces(m).begin(), faces(m).end())));
  EXPECT_EQ(mrepair::internal::vertex_count(m),
            static_cast<std::size_t>(std::distance(vertices(m).begin(), vertices(m).end())));
  if constexpr (mrepair::internal::Is_surface_mesh<Mesh>::value) {
    EXPECT_GT(m.number_of_removed_faces(), 0u);
  }
}

// ---- section 4: the pipeline --------------------------------------------------

// An icosphere with punched holes, a small floating component, a NaN vertex
// and an isolated vertex.
template <class Mesh>
Mesh dirty_sphere()
{
  Soup s = icosphere(4, 10.0);  // 5120 faces
  // Punch holes: drop the faces around a few vertices (1-ring, 5 faces each).
  std::set<std::size_t> centers = {0, 2, 4, 6, 8};  // icosahedron corners, far apart
  std::vector<Polygon> keep;
  for (const Polygon& p : s.polygons) {
    bool hit = false;
    for (std::size_t v : p) hit = hit || centers.count(v);
    if (!hit) keep.push_back(p);
  }
  s.polygons.swap(keep);
  s = compacted(s);
  // A NaN vertex in a small fan inside the sphere.
  Soup fan = grid(2, 2, 0.3);
  fan.points[4] = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  s = merged(s, translated(fan, 1, 1, 1));
  s = merged(s, translated(grid(2, 1, 0.5), -2, -2, 0));  // a 4-face component
  Mesh m = to_mesh<Mesh>(compacted(s));
  auto v = add_vertex(m);  // isolated
  put(get(CGAL::vertex_point, m), v, Point(0, 0, 0));
  return m;
}

TYPED_TEST(Clean_pipeline, pipeline_on_a_dirty_sphere)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = dirty_sphere<Mesh>();
  ASSERT_EQ(isolated_vertices(m), 1u);
  auto r = mrepair::clean_scan_mesh(m);
  EXPECT_TRUE(mrepair::succeeded(r.status)) << mrepair::to_string(r.status) << " " << r.message;
  // The added vertex, and the fan's corners 0 and 8, whose faces all use
  // the NaN centre (finite vertices left without a face count as isolated).
  EXPECT_EQ(r.isolated_vertices_removed, 3u);
  EXPECT_EQ(r.non_finite_vertices_removed, 1u);
  // 6 of the 8 faces of grid(2, 2) use its centre (vertex 4).
  EXPECT_EQ(r.faces_removed_with_non_finite, 6u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(all_finite(m));
  EXPECT_EQ(isolated_vertices(m), 0u);
  EXPECT_EQ(components(m), 1u);
  EXPECT_EQ(border_loops(m), 0u);  // every hole was small
  EXPECT_GE(r.holes.holes_filled, 5u);
  EXPECT_GE(r.iterations, 1u);
  mrepair::Report rep;
  r.to_report(rep);
  EXPECT_NE(rep.to_json().find("fill_small_holes"), std::string::npos);
}

// The pipeline reserves room for its fills up front (3% of the faces + 1024)
// so that the statistics' maps are not reallocated; fills that need more grow
// the mesh and those maps as before.
TYPED_TEST(Clean_pipeline, fills_beyond_the_reserved_room)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = grid_with_square_hole<Mesh>(8);  // 32-vertex loop
  const std::size_t f0 = face_count(m);
  // 1,672 faces: too small for the automatic scan profile.
  auto r = mrepair::clean_scan_mesh(
      m, MP::hole_density_factor(0.25, MP::input_profile(mrepair::Input_profile::scan)));
  EXPECT_EQ(r.status, mrepair::Status::ok) << r.message;
  EXPECT_GE(r.holes.holes_filled, 1u);
  // the case must outgrow the reserved room; that no result changes is tested in
  // test_keeps_model.cpp (Keeps_model_reserve.reserved_room_changes_no_result)
  ASSERT_GT(r.holes.faces_added, f0 / 32 + 1024) << "the case must outgrow the reserved room";
  EXPECT_EQ(border_loops(m), 1u);  // the grid's outline only
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(all_finite(m));

  // A dense patch (about 8,500 faces for a 24-vertex loop): its short edges
  // are collapsed in sorted batches (a rescan per collapse took 17 s here).
  Mesh d = grid_with_square_hole<Mesh>(6);
  const std::size_t d0 = face_count(d);
  auto h = mrepair::fill_small_holes(d, MP::hole_density_factor(0.1));
  EXPECT_EQ(h.holes_filled, 1u);
  EXPECT_GT(face_count(d), d0 + 5000);
  EXPECT_EQ(border_loops(d), 1u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(d));
}

TYPED_TEST(Clean_pipeline, pipeline_steps_can_be_disabled)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = dirty_sphere<Mesh>();
  const std::size_t f0 = face_count(m);
  // Only preprocessing: holes and the small component stay.
  auto r = mrepair::clean_scan_mesh(
      m, MP::clean_steps(unsigned(mrepair::clean_step_remove_degenerate_vertices)));
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_EQ(face_count(m), f0 - 6);
  // The sphere, the strip and the two corner triangles left of the NaN fan.
  EXPECT_EQ(components(m), 4u);
  EXPECT_EQ(border_loops(m), 8u);  // 5 holes, the strip, 2 triangles
  EXPECT_FALSE(r.steps[5].enabled);
  EXPECT_EQ(r.steps[5].runs, 0u);

  // With NaN and the preprocessing disabled: refused, untouched.
  Mesh m2 = dirty_sphere<Mesh>();
  const std::size_t f2 = face_count(m2);
  auto r2 = mrepair::clean_scan_mesh(
      m2, MP::clean_steps(unsigned(mrepair::clean_step_all & ~mrepair::clean_step_remove_degenerate_vertices)));
  EXPECT_EQ(r2.status, mrepair::Status::non_finite_input);
  EXPECT_EQ(face_count(m2), f2);
}

TYPED_TEST(Clean_pipeline, empty_and_non_triangle_input)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh empty;
  auto r = mrepair::clean_scan_mesh(empty);
  EXPECT_EQ(r.status, mrepair::Status::empty_input);
  EXPECT_EQ(mrepair::fill_small_holes(empty).holes_found, 0u);
  EXPECT_EQ(mrepair::clean_boundaries(empty).status, mrepair::Status::ok);
  EXPECT_EQ(mrepair::remove_small_components(empty).components_removed, 0u);

  Mesh quads = to_mesh<Mesh>(grid(3, 3, 1.0, true));
  auto rq = mrepair::clean_scan_mesh(quads);
  EXPECT_EQ(rq.status, mrepair::Status::invalid_mesh);
  EXPECT_EQ(face_count(quads), 9u);

  Mesh m = to_mesh<Mesh>(grid(4, 4));
  EXPECT_EQ(mrepair::clean_scan_mesh(m, MP::max_hole_vertices(0)).status,
            mrepair::Status::invalid_parameter);
}

TYPED_TEST(Clean_pipeline, nan_vertex_on_a_boundary)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(10, 10);
  s.points[5] = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);  // (5, 0)
  Mesh m = to_mesh<Mesh>(compacted(s));
  auto b = mrepair::clean_boundaries(m);
  EXPECT_EQ(b.status, mrepair::Status::non_finite_input);
  EXPECT_EQ(face_count(m), 200u);
  // (max_hole_vertices 10: the sheet's own border must not be "filled")
  auto r = mrepair::clean_scan_mesh(m, MP::min_component_faces(10, MP::max_hole_vertices(10)));
  EXPECT_TRUE(mrepair::succeeded(r.status));
  EXPECT_EQ(r.faces_removed_with_non_finite, 3u);
  EXPECT_TRUE(all_finite(m));
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
}

// Finite coordinates near DBL_MAX overflow in averages and cross products
// (fuzz finding 7: a relaxed spike neighbour went to -inf): every geometry
// call refuses them, mesh untouched, and a NaN vertex does not count.
TYPED_TEST(Clean_pipeline, huge_coordinates_are_refused_untouched)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(10, 10);
  s.points[60] = Point(5, -std::numeric_limits<double>::max(), 0);
  s.points[5] = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  const Mesh m0 = to_mesh<Mesh>(compacted(s));
  auto same = [&](const Mesh& m) {
    std::vector<Point> a, b;
    for (auto v : vertices(m0)) a.push_back(get(CGAL::vertex_point, m0, v));
    for (auto v : vertices(m)) b.push_back(get(CGAL::vertex_point, m, v));
    if (a.size() != b.size() || face_count(m) != face_count(m0)) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!(a[i].x() == b[i].x() || (std::isnan(a[i].x()) && std::isnan(b[i].x()))) ||
          a[i].y() != b[i].y() || a[i].z() != b[i].z())
        return false;
    return true;
  };
  const auto huge = mrepair::Status::non_finite_input;
  { Mesh m = m0; EXPECT_EQ(mrepair::clean_scan_mesh(m).status, huge); EXPECT_TRUE(same(m)); }
  { Mesh m = m0; EXPECT_EQ(mrepair::clean_boundaries(m).status, huge); EXPECT_TRUE(same(m)); }
  { Mesh m = m0; EXPECT_EQ(mrepair::fill_small_holes(m).status, huge); EXPECT_TRUE(same(m)); }
  // a NaN vertex alone is not "too large": the pipeline removes it
  Soup t = grid(10, 10);
  t.points[60] = Point(5, 1e90, 0);
  t.points[5] = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  Mesh m = to_mesh<Mesh>(compacted(t));
  auto r = mrepair::clean_scan_mesh(m, MP::min_component_faces(10, MP::max_hole_vertices(10)));
  EXPECT_TRUE(mrepair::succeeded(r.status)) << mrepair::to_string(r.status);
  EXPECT_TRUE(all_finite(m));
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
}

// The team generator's scan (mrepair-generate scan), when it is built: after
// the pipeline no small component, small hole, isolated or non-finite vertex.
TYPED_TEST(Clean_pipeline, generated_scan)
{
  using Mesh = typename TypeParam::Mesh;
#ifdef MREPAIR_GENERATOR
  const std::string gen = MREPAIR_GENERATOR;
  if (!std::ifstream(gen).good()) GTEST_SKIP() << "mrepair-generate not built: " << gen;
  const std::string out = ::testing::TempDir() + "mrepair_clean_scan_20k.off";
  const std::string cmd = gen + " scan --faces 20000 --seed 7 --ascii --output " + out +
                          " --manifest " + out + ".json > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  // mrepair's reader: CGAL's rejects the generator's NaN coordinates.
  mrepair::Io_result io = mrepair::read_polygon_soup(out, pts, polys);
  ASSERT_TRUE(io.status == mrepair::Status::ok || io.status == mrepair::Status::non_finite_input)
      << io.message;
  ASSERT_TRUE(PMP::is_polygon_soup_a_polygon_mesh(polys));
  Mesh m;
  PMP::polygon_soup_to_polygon_mesh(pts, polys, m);
  const std::size_t f0 = face_count(m);
  auto r = mrepair::clean_scan_mesh(m, MP::min_component_faces(100, MP::max_hole_vertices(60)));
  EXPECT_TRUE(mrepair::succeeded(r.status)) << mrepair::to_string(r.status) << " " << r.message;
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(all_finite(m));
  EXPECT_EQ(isolated_vertices(m), 0u);
  EXPECT_GE(r.isolated_vertices_removed + r.non_finite_vertices_removed, 1u);
  // Components: the sphere only (islands below 100 faces are gone).
  EXPECT_EQ(components(m), 1u);
  std::vector<std::size_t> sizes;
  border_loops(m, &sizes);
  for (std::size_t n : sizes) EXPECT_GE(n, 60u);
  EXPECT_GT(r.holes.holes_filled, 0u);
  // Conservative: the face count stays within a few percent.
  EXPECT_NEAR(double(face_count(m)), double(f0), 0.05 * double(f0));
#else
  GTEST_SKIP() << "MREPAIR_GENERATOR not defined";
#endif
}

// CAD exports carry quads and n-gons: every command that needs triangles
// triangulates them (and says so in its report) instead of refusing the file.
TEST(Cli, polygon_meshes_are_triangulated)
{
#ifdef MREPAIR_CLI
  if (!std::ifstream(MREPAIR_CLI)) GTEST_SKIP() << "mrepair not built";
  const std::string dir = ::testing::TempDir();
  const std::string in = dir + "mrepair_cli_quads.off", report = dir + "mrepair_cli_quads.json";
  {
    // a cube of quads with one face a hexagon (two of its edges split)
    std::ofstream f(in);
    f << "OFF\n10 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
         "0.5 0 0\n0.5 1 0\n"
         "6 0 3 9 2 1 8\n4 4 5 6 7\n5 0 8 1 5 4\n4 1 2 6 5\n5 2 9 3 7 6\n4 3 0 4 7\n";
  }
  for (const char* command : {"repair", "clean", "close-gaps", "remesh"}) {
    const std::string out = dir + "mrepair_cli_quads_" + command + ".off";
    std::string extra = std::string(command) == "close-gaps" ? " --tolerance 0.01"
                        : std::string(command) == "remesh"   ? " --edge-length 0.5"
                                                             : "";
    std::string cmd = std::string(MREPAIR_CLI) + " " + command + " " + in + " " + out + extra +
                      " --quiet --report " + report + " > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    Surface_mesh m;
    ASSERT_EQ(mrepair::read_polygon_mesh(out, m).status, mrepair::Status::ok) << command;
    EXPECT_TRUE(CGAL::is_triangle_mesh(m)) << command;
    EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m)) << command;
    EXPECT_TRUE(CGAL::is_closed(m)) << command;
    if (std::string(command) != "remesh") {
      EXPECT_EQ(face_count(m), 16u) << command;
    }
    std::ifstream r(report);
    std::string json((std::istreambuf_iterator<char>(r)), std::istreambuf_iterator<char>());
    EXPECT_NE(json.find("\"triangulation\""), std::string::npos) << command;
  }
#else
  GTEST_SKIP() << "MREPAIR_CLI not defined";
#endif
}

// Issue 17: `mrepair repair` writes its output beside the inspection of the
// output (a task started once the cleaning succeeded). One thread runs the
// task at the join instead: the file and the report are the same.
TEST(Cli, repair_writes_the_same_file_on_one_thread_and_beside_the_inspection)
{
#ifdef MREPAIR_CLI
  if (!std::ifstream(MREPAIR_CLI)) GTEST_SKIP() << "mrepair not built";
  const std::string dir = ::testing::TempDir(), in = std::string(MREPAIR_SAMPLE_DIR) + "/sample_scan.off";
  auto run = [&](const char* threads) {
    const std::string out = dir + "mrepair_cli_beside_" + threads + ".off",
                      report = dir + "mrepair_cli_beside_" + threads + ".json";
    std::remove(out.c_str());
    const std::string cmd = std::string("MREPAIR_THREADS=") + threads + " " + MREPAIR_CLI + " repair " + in +
                            " " + out + " --quiet --report " + report + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::ifstream f(out), r(report);
    std::string file((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>()),
        json((std::istreambuf_iterator<char>(r)), std::istreambuf_iterator<char>());
    EXPECT_NE(json.find("\"output\""), std::string::npos) << threads;
    return file;
  };
  const std::string one = run("1"), two = run("2");
  ASSERT_FALSE(one.empty());
  EXPECT_EQ(one, two);
  Surface_mesh m;
  ASSERT_EQ(mrepair::read_polygon_mesh(dir + "mrepair_cli_beside_2.off", m).status, mrepair::Status::ok);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
#else
  GTEST_SKIP() << "MREPAIR_CLI not defined";
#endif
}

}  // namespace

// Issue 17: clean_boundaries charges each face next to its confidence region
// to the loop of the face's first region vertex in BFS order. On a large
// Surface_mesh the faces are counted in parallel, by the vertex of lowest
// rank: the same counts as the sequential pass, with removed vertices in the
// index range and a list in no index order.
TEST(Clean_issue_17, parallel_region_face_counts_match_the_sequential_pass)
{
  namespace CP = mrepair::internal::clean_pipeline;
  Surface_mesh m = to_mesh<Surface_mesh>(grid(180, 180, 0.1));
  // a few holes: removed faces and vertices stay in the index range
  std::vector<Surface_mesh::Face_index> doomed;
  for (auto f : faces(m))
    if (std::size_t(f) % 997 == 0) doomed.push_back(f);
  for (auto f : doomed) CGAL::Euler::remove_face(halfedge(f, m), m);
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
  // a list of 24,000 vertices in a scrambled order, labelled with 37 loops
  std::vector<Surface_mesh::Vertex_index> list;
  for (auto v : vertices(m))
    if (std::size_t(v) % 4 != 3) list.push_back(v);
  list.resize(24000);
  std::mt19937 rng(5);
  std::shuffle(list.begin(), list.end(), rng);
  auto region = get(CGAL::dynamic_vertex_property_t<int>(), m);
  for (std::size_t i = 0; i < list.size(); ++i) put(region, list[i], int((i * 7919) % 37));
  auto fmark = get(CGAL::dynamic_face_property_t<char>(), m);
  std::vector<std::size_t> parallel(37, 0), sequential(37, 0);
  CP::count_region_faces(m, list, region, fmark, parallel, true);
  CP::count_region_faces(m, list, region, fmark, sequential, false);
  EXPECT_EQ(parallel, sequential);
  std::size_t total = 0;
  for (std::size_t c : sequential) total += c;
  EXPECT_GT(total, std::size_t(40000));
  for (auto f : faces(m)) ASSERT_EQ(get(fmark, f), 0);  // left as it was
}

// Issue 17: on a large Surface_mesh the components are labelled by a parallel
// union-find. Same numbering (order of each component's first face), counts
// and areas as a sequential search, with removed faces in the index range.
TEST(Clean_issue_17, parallel_component_labels_match_the_sequential_search)
{
  namespace CP = mrepair::internal::clean_pipeline;
  namespace PMP = CGAL::Polygon_mesh_processing;
  // a 200 x 200 grid (80,000 faces) and 300 small grids beside it, merged so
  // that the islands' faces come first, between and after the big one's
  Soup s = grid(3, 2, 0.1);
  for (int k = 1; k < 150; ++k) s = merged(s, translated(grid(1 + k % 4, 2, 0.1), 0.5 * k, -5., 0.));
  s = merged(s, grid(200, 200, 0.05));
  for (int k = 0; k < 150; ++k) s = merged(s, translated(grid(2, 1 + k % 3, 0.1), 0.5 * k, -9., 0.));
  Surface_mesh m = to_mesh<Surface_mesh>(s);
  // remove a band of faces across the big grid (cuts it in two) and a few
  // islands' faces: removed slots stay in the index range
  std::vector<Surface_mesh::Face_index> doomed;
  for (auto f : faces(m)) {
    double x = 0, y = 0;
    for (auto v : vertices_around_face(halfedge(f, m), m)) {
      x += m.point(v).x() / 3;
      y += m.point(v).y() / 3;
    }
    const Point c(x, y, 0.);
    if (c.y() > 4.9 && c.y() < 5.05 && c.x() < 10.) doomed.push_back(f);
    if (c.y() < -8.95 && c.y() > -9. && int(c.x()) % 7 == 0) doomed.push_back(f);
  }
  for (auto f : doomed) CGAL::Euler::remove_face(halfedge(f, m), m);
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
  ASSERT_GE(m.num_faces(), std::size_t(65536));  // the parallel path

  auto id = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  std::vector<std::size_t> faces_of;
  std::vector<double> area_of;
  const std::size_t n = CP::label_components(m, m.points(), id, faces_of, area_of);
  EXPECT_EQ(n, faces_of.size());

  // the sequential reference: a search from each unlabelled face, in face order
  std::map<Surface_mesh::Face_index, std::size_t> expected;
  std::vector<std::size_t> count;
  std::vector<double> area;
  for (auto seed : faces(m)) {
    if (expected.count(seed)) continue;
    const std::size_t c = count.size();
    count.push_back(0);
    area.push_back(0.);
    std::vector<Surface_mesh::Face_index> stack{seed};
    expected[seed] = c;
    while (!stack.empty()) {
      const auto f = stack.back();
      stack.pop_back();
      ++count[c];
      area[c] += PMP::face_area(f, m);
      for (auto h : CGAL::halfedges_around_face(halfedge(f, m), m)) {
        const auto o = opposite(h, m);
        if (is_border(o, m) || expected.count(face(o, m))) continue;
        expected[face(o, m)] = c;
        stack.push_back(face(o, m));
      }
    }
  }
  ASSERT_EQ(faces_of.size(), count.size());
  EXPECT_GT(count.size(), 300u);
  for (std::size_t c = 0; c < count.size(); ++c) {
    EXPECT_EQ(faces_of[c], count[c]) << c;
    EXPECT_NEAR(area_of[c], area[c], 1e-9 * (1. + area[c])) << c;
  }
  for (auto f : faces(m)) EXPECT_EQ(get(id, f), expected[f]);
}

// ---- totals over the iterations ------------------------------------------------------------------

namespace totals_check {

// Gives every listed field of `x` a distinct value from `seed` (booleans
// alternate, the status is `partial` for odd seeds).
template <typename Result>
void fill(Result& x, std::size_t seed)
{
  std::size_t k = seed;
  Result::for_each_field([&](const char*, auto member, auto) {
    using T = std::decay_t<decltype(x.*member)>;
    ++k;
    if constexpr (std::is_same<T, bool>::value)
      x.*member = (k % 2) == 1;
    else if constexpr (std::is_same<T, mrepair::Status>::value)
      x.*member = seed % 2 ? mrepair::Status::partial : mrepair::Status::ok;
    else
      x.*member = static_cast<T>(k * 7 + 1);
  });
}

// Checks `add_totals(a, b)` field by field against what the list says: sums
// add, `last` takes b's value, `any` is an or. Returns the number of fields.
template <typename Result>
std::size_t expect_totals_follow_the_list()
{
  Result a, b;
  fill(a, 10);
  fill(b, 31);
  const Result a0 = a;
  mrepair::internal::add_totals(a, b);
  std::size_t fields = 0;
  Result::for_each_field([&](const char* name, auto member, auto how) {
    using How = decltype(how);
    ++fields;
    if constexpr (std::is_same<How, mrepair::totals::sum>::value)
      EXPECT_EQ(a.*member, a0.*member + b.*member) << name;
    else if constexpr (std::is_same<How, mrepair::totals::any>::value)
      EXPECT_EQ(a.*member, a0.*member || b.*member) << name;
    else
      EXPECT_EQ(a.*member, b.*member) << name;
  });
  return fields;
}

}  // namespace totals_check

TEST(Clean_totals, add_totals_follows_each_field_list)
{
  using namespace totals_check;
  EXPECT_GE(expect_totals_follow_the_list<mrepair::Spike_relaxation_result>(), 5u);
  EXPECT_GE(expect_totals_follow_the_list<mrepair::Spike_removal_result>(), 5u);
  EXPECT_GE(expect_totals_follow_the_list<mrepair::Near_degenerate_faces_result>(), 5u);
  EXPECT_GE(expect_totals_follow_the_list<mrepair::Small_components_result>(), 4u);
  EXPECT_GE(expect_totals_follow_the_list<mrepair::Boundary_cleaning_result>(), 5u);
  EXPECT_GE(expect_totals_follow_the_list<mrepair::Hole_filling_result>(), 5u);
}

// The fields outside the lists: the largest component kept in any run, and
// the holes left open by the last run.
TEST(Clean_totals, add_totals_keeps_the_fields_outside_the_lists)
{
  mrepair::Small_components_result total, kept, none;
  kept.kept_largest = true;
  mrepair::internal::add_totals(total, kept);
  mrepair::internal::add_totals(total, none);
  EXPECT_TRUE(total.kept_largest);
  mrepair::Report r;
  total.to_report(r);
  EXPECT_EQ(r.get("kept_largest_small_component"), "true");

  mrepair::Hole_filling_result holes, first, last;
  first.open_holes.resize(3);
  last.open_holes.resize(1);
  mrepair::internal::add_totals(holes, first);
  mrepair::internal::add_totals(holes, last);
  EXPECT_EQ(holes.open_holes.size(), 1u);
}

} // namespace clean_pipeline_tests
} // namespace
