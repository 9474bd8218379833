// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Inspection: hand-built soups and meshes with hand-counted defects, on the
// soup path and on both mesh types; a CGAL cross-check on a real mesh.
#include <mrepair/compare_to_reference.h>
#include <mrepair/inspect.h>
#include <mrepair/internal/studio/overlay.h>
#include <mrepair/locate_defects.h>
#include <mrepair/relax_spikes.h>
#include <mrepair/internal/spatial_grid.h>
#include <mrepair/internal/triangle_intersection.h>

#include "fixtures.h"

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>

// A namespace of its own: this file is compiled in one translation unit with
// other test files (a unity build, CMakeLists.txt).
namespace {
namespace inspect_tests {

using namespace mrepair_test;
namespace MP = mrepair::parameters;
using mrepair::Inspection_report;
using mrepair::Status;

namespace {

using Counts = std::map<std::string, std::size_t>;

// Compares the named counters of a report (as printed in its "defects" or
// "input" section) with hand counts.
void expect_counts(const Inspection_report& r, const Counts& expected, const std::string& where)
{
  mrepair::Report rep;
  r.to_report(rep);
  for (const auto& kv : expected) {
    std::string v = rep.get("defects." + kv.first);
    if (v.empty()) v = rep.get("input." + kv.first);
    EXPECT_EQ(v, std::to_string(kv.second)) << where << ": " << kv.first;
  }
}

Soup without_polygons(Soup s, std::set<std::size_t> drop)
{
  Soup out;
  out.points = s.points;
  for (std::size_t i = 0; i < s.polygons.size(); ++i)
    if (!drop.count(i)) out.polygons.push_back(s.polygons[i]);
  return out;
}

// drops the points no polygon uses (indices remapped).
Soup compacted(const Soup& s)
{
  std::vector<std::size_t> id(s.points.size(), std::size_t(-1));
  Soup out;
  for (const Polygon& p : s.polygons)
    for (std::size_t i : p)
      if (id[i] == std::size_t(-1)) id[i] = 0;
  for (std::size_t i = 0; i < s.points.size(); ++i)
    if (id[i] == 0) {
      id[i] = out.points.size();
      out.points.push_back(s.points[i]);
    }
  for (Polygon p : s.polygons) {
    for (auto& i : p) i = id[i];
    out.polygons.push_back(p);
  }
  return out;
}

std::size_t grid_index(std::size_t nx, std::size_t i, std::size_t j) { return j * (nx + 1) + i; }

// index of the first triangle of cell (i, j) of `grid(nx, ny)`; the second is +1.
std::size_t cell_triangle(std::size_t nx, std::size_t i, std::size_t j) { return 2 * (j * nx + i); }

template <class Mesh>
void set_point(Mesh& m, std::size_t index, const Point& p)
{
  auto vpm = get(CGAL::vertex_point, m);
  std::size_t i = 0;
  for (auto v : vertices(m))
    if (i++ == index) put(vpm, v, typename boost::property_traits<decltype(vpm)>::value_type(p.x(), p.y(), p.z()));
}

// locate_defects(): its report is the inspection's (`r`), and every list has
// as many instances as the report counts; the overlay draws them all.
void expect_located(const mrepair::Defect_locations& d, const Inspection_report& r,
                    const mrepair::internal::Indexed_faces& faces, const std::string& where)
{
  mrepair::Report a, b;
  d.report.to_report(a);
  r.to_report(b);
  EXPECT_EQ(a.to_json(), b.to_json()) << where;
  EXPECT_EQ(d.boundary_loops.size(), r.boundary_loops) << where;
  std::size_t boundary_edges = 0;
  for (std::size_t i = 0; i < d.boundary_loops.size(); ++i) boundary_edges += d.loop_edges(i);
  // every boundary edge is on one loop (a soup non-manifold edge is not a boundary edge)
  EXPECT_EQ(boundary_edges, r.boundary_edges) << where;
  EXPECT_EQ(d.small_holes.size(), r.small_holes) << where;
  for (std::size_t i : d.small_holes) EXPECT_LT(d.loop_edges(i), r.max_hole_vertices) << where;
  EXPECT_EQ(d.non_manifold_edges.size(), r.non_manifold_edges) << where;
  EXPECT_EQ(d.non_manifold_vertices.size(), r.non_manifold_vertices) << where;
  EXPECT_EQ(d.spiked_vertices.size(), r.spiked_vertices) << where;
  EXPECT_EQ(d.near_degenerate_faces.size(), r.near_degenerate_faces) << where;
  EXPECT_EQ(d.small_components.size(), r.small_components) << where;
  for (const auto& c : d.small_components) EXPECT_LT(c.size(), r.min_component_faces) << where;
  EXPECT_EQ(d.self_intersecting_pairs.size(), r.self_intersections_counted ? r.self_intersecting_pairs : 0u)
      << where;
  std::size_t touching = 0;
  for (unsigned char t : d.self_intersecting_pairs_touching) touching += t;
  EXPECT_EQ(touching, r.self_intersections_counted ? r.self_intersecting_pairs_touching : 0u) << where;
  EXPECT_EQ(d.t_junction_vertices.size(), r.t_junctions) << where;
  EXPECT_EQ(d.t_junction_edges.size(), r.t_junctions) << where;
  const mrepair::internal::Defect_overlay o = mrepair::internal::make_defect_overlay(faces, d, 1000000);
  ASSERT_EQ(o.kinds.size(), 9u);
  EXPECT_EQ(o.kinds[0].segments.size(), 6 * r.boundary_edges) << where;
  EXPECT_EQ(o.kinds[2].segments.size(), 6 * r.non_manifold_edges) << where;
  EXPECT_EQ(o.kinds[3].points.size(), 3 * r.non_manifold_vertices) << where;
  EXPECT_EQ(o.kinds[4].points.size(), 3 * r.spiked_vertices) << where;
  EXPECT_EQ(o.kinds[8].points.size(), 3 * r.t_junctions) << where;
  for (const auto& k : o.kinds) {
    EXPECT_EQ(k.drawn, k.count) << where << ": " << k.key;
    EXPECT_EQ(k.has_first, k.count > 0) << where << ": " << k.key;
  }
}

template <class Mesh>
void expect_located_on_mesh(const Mesh& m, const std::string& where)
{
  expect_located(mrepair::locate_defects(m), mrepair::inspect(m), mrepair::internal::indexed_faces_of_mesh(m), where);
}

void expect_located_on_soup(const Soup& s, const std::string& where)
{
  expect_located(mrepair::locate_defects(s.points, s.polygons), mrepair::inspect_polygon_soup(s.points, s.polygons),
                 mrepair::internal::indexed_faces_of_soup(s.points, s.polygons), where);
}

// Runs the soup inspection and, when the soup is a polygon mesh, the mesh
// inspection too, and checks the same counts on both; and that
// locate_defects() lists as many defects as they count.
template <class Mesh>
void expect_both(const Soup& s, const Counts& expected, const std::string& where)
{
  Inspection_report rs = mrepair::inspect_polygon_soup(s.points, s.polygons);
  expect_counts(rs, expected, where + " (soup)");
  expect_located_on_soup(s, where + " (soup)");
  Mesh m = to_mesh<Mesh>(s);
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
  Inspection_report rm = mrepair::inspect(m);
  expect_counts(rm, expected, where + " (mesh)");
  expect_located_on_mesh(m, where + " (mesh)");
}

} // namespace

// ---------------------------------------------------------------------------
// Soup-only defects (a halfedge mesh cannot hold them)

TEST(Inspect_soup, fin_is_one_non_manifold_edge)
{
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0), Point(0.5, -1, 0), Point(0.5, 0, 1)};
  s.polygons = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  Inspection_report r = mrepair::inspect_polygon_soup(s.points, s.polygons);
  EXPECT_EQ(r.status, Status::ok);
  expect_counts(r, {{"non_manifold_edges", 1}, {"inconsistent_orientation_edges", 0},
                    {"non_manifold_vertices", 0}, {"boundary_edges", 6}, {"boundary_loops", 1},
                    {"small_holes", 1}, {"connected_components", 1}, {"edges", 7},
                    {"spiked_vertices", 0}, {"duplicate_faces", 0}, {"degenerate_faces", 0}},
                "fin");
  EXPECT_TRUE(std::isnan(r.max_dihedral_angle)); // no edge with exactly two faces
  EXPECT_FALSE(r.closed);
  expect_located_on_soup(s, "fin");
  const mrepair::Defect_locations d = mrepair::locate_defects(s.points, s.polygons);
  ASSERT_EQ(d.non_manifold_edges.size(), 1u);
  EXPECT_EQ(d.non_manifold_edges[0], (std::array<std::size_t, 2>{{0, 1}}));
  // the boundary graph: six edges, 0 and 1 with three each: one loop, listed
  // as an open walk from 0 to 1 (then walk_end)
  ASSERT_EQ(d.boundary_loops.size(), 1u);
  EXPECT_EQ(d.loop_edges(0), 6u);
  ASSERT_EQ(d.boundary_loops[0].size(), 8u);
  EXPECT_EQ(d.boundary_loops[0].back(), mrepair::Defect_locations::walk_end);
  EXPECT_EQ(std::min(d.boundary_loops[0].front(), d.boundary_loops[0][6]), 0u);
  EXPECT_EQ(std::max(d.boundary_loops[0].front(), d.boundary_loops[0][6]), 1u);
}

TEST(Inspect_soup, bowtie_and_crack_vertices)
{
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(-1, 0, 0), Point(-1, -1, 0)};
  s.polygons = {{0, 1, 2}, {0, 3, 4}};
  Inspection_report r = mrepair::inspect_polygon_soup(s.points, s.polygons);
  expect_counts(r, {{"non_manifold_vertices", 1}, {"non_manifold_edges", 0}, {"boundary_edges", 6},
                    {"boundary_loops", 1}, {"connected_components", 2}},
                "bowtie");
  // a T-junction crack with shared corners: l1 and l2 join two fans each
  Soup c;
  c.points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0),
              Point(2, 0, 0), Point(2, 1, 0), Point(1, 0.5, 0)};
  c.polygons = {{0, 1, 2}, {0, 2, 3}, {1, 4, 6}, {6, 4, 5}, {6, 5, 2}};
  r = mrepair::inspect_polygon_soup(c.points, c.polygons);
  expect_counts(r, {{"non_manifold_vertices", 2}, {"t_junctions", 1}, {"boundary_edges", 9},
                    {"connected_components", 2}, {"duplicate_points", 0}},
                "crack");
}

TEST(Inspect_soup, flipped_face_gives_three_inconsistent_edges)
{
  Soup s = grid(3, 3);
  Polygon& p = s.polygons[cell_triangle(3, 1, 1)]; // interior triangle, 3 neighbours
  std::swap(p[1], p[2]);
  Inspection_report r = mrepair::inspect_polygon_soup(s.points, s.polygons);
  expect_counts(r, {{"inconsistent_orientation_edges", 3}, {"non_manifold_edges", 0},
                    {"non_manifold_vertices", 0}, {"boundary_edges", 12}, {"boundary_loops", 1},
                    {"connected_components", 1}, {"spiked_vertices", 0}, {"duplicate_faces", 0}},
                "flipped");
  // the fold is measured with one normal reversed: the flat grid stays flat
  EXPECT_NEAR(r.max_dihedral_angle, 0.0, 1e-9);
  EXPECT_NEAR(r.area, 9.0, 1e-12);
}

TEST(Inspect_soup, duplicate_faces_both_orientations)
{
  Soup s = grid(1, 1); // (0,1,3), (0,3,2)
  s.polygons.push_back({1, 3, 0}); // same as (0,1,3), rotated
  s.polygons.push_back({0, 2, 3}); // (0,3,2) reversed
  Inspection_report r = mrepair::inspect_polygon_soup(s.points, s.polygons);
  // edge {0,3} has four faces; {0,1} and {1,3} are used twice 0->1 / 1->3;
  // {0,2}, {2,3} have both directions; no boundary remains
  expect_counts(r, {{"duplicate_faces", 2}, {"duplicate_faces_opposite", 1},
                    {"non_manifold_edges", 1}, {"inconsistent_orientation_edges", 2},
                    {"boundary_edges", 0}, {"non_manifold_vertices", 0},
                    {"connected_components", 1}},
                "duplicates");
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(std::isnan(r.volume)); // not a 2-manifold: no volume
}

TEST(Inspect_soup, degenerate_repeated_and_invalid_polygons)
{
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0),
              Point(0, 0, 1), Point(1, 0, 1), Point(0, 1, 1)};
  s.polygons = {{0, 1, 2}, {3, 4, 5}, {3, 3, 4}, {0, 1, 2, 1}, {3, 4, 99}, {3, 4}};
  Inspection_report r = mrepair::inspect_polygon_soup(s.points, s.polygons);
  EXPECT_EQ(r.status, Status::invalid_index);
  expect_counts(r, {{"invalid_polygons", 2}, {"faces", 4}, {"degenerate_faces", 3},
                    {"repeated_index_faces", 2}, {"isolated_vertices", 0},
                    {"connected_components", 2}, {"duplicate_faces", 0}},
                "degenerate");
  // signed indices: a negative one is invalid
  std::vector<std::vector<int>> signed_polys = {{0, 1, -1}, {3, 4, 5}};
  r = mrepair::inspect_polygon_soup(s.points, signed_polys);
  EXPECT_EQ(r.invalid_polygons, 1u);
  EXPECT_EQ(r.faces, 1u);
  EXPECT_EQ(r.isolated_vertices, 3u);
}

// Bad input reaches locate_defects() as it reaches the inspection: invalid
// polygons are skipped, non-finite points and empty soups give a status, and
// the lists still follow the report's counts.
TEST(Inspect_soup, locate_defects_on_bad_input)
{
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0),
              Point(0, 0, 1), Point(1, 0, 1), Point(0, 1, 1)};
  s.polygons = {{0, 1, 2}, {3, 4, 5}, {3, 3, 4}, {0, 1, 2, 1}, {3, 4, 99}, {3, 4}};
  expect_located_on_soup(s, "invalid polygons");
  EXPECT_EQ(mrepair::locate_defects(s.points, s.polygons).report.status, Status::invalid_index);

  std::vector<std::vector<int>> signed_polys = {{0, 1, -1}, {3, 4, 5}};
  const mrepair::Defect_locations d = mrepair::locate_defects(s.points, signed_polys);
  EXPECT_EQ(d.report.invalid_polygons, 1u);
  EXPECT_EQ(d.boundary_loops.size(), d.report.boundary_loops);

  Soup nan = grid(4, 4);
  nan.points[7] = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  expect_located_on_soup(nan, "non-finite point");
  EXPECT_EQ(mrepair::locate_defects(nan.points, nan.polygons).report.status, Status::non_finite_input);

  Soup empty;
  expect_located_on_soup(empty, "empty soup");
  EXPECT_TRUE(mrepair::locate_defects(empty.points, empty.polygons).boundary_loops.empty());
}

TEST(Inspect_soup, duplicate_points_and_empty_input)
{
  Soup s = grid(2, 1);
  s.points.push_back(s.points[0]);  // 2 copies at point 0
  s.points.push_back(s.points[0]);
  s.points.push_back(Point(-0.0, 0, 0)); // -0 is the same location as +0
  s.points.push_back(s.points[4]);
  Inspection_report r = mrepair::inspect_polygon_soup(s.points, s.polygons);
  expect_counts(r, {{"duplicate_points", 4}, {"isolated_vertices", 4}}, "duplicate points");

  std::vector<Point> no_points;
  std::vector<Polygon> no_polys;
  EXPECT_EQ(mrepair::inspect_polygon_soup(no_points, no_polys).status, Status::empty_input);
  EXPECT_EQ(mrepair::inspect_polygon_soup(s.points, no_polys).status, Status::empty_input);
  EXPECT_EQ(mrepair::inspect_polygon_soup(s.points, no_polys).isolated_vertices, s.points.size());
}

TEST(Inspect_soup, bad_parameters)
{
  Soup s = grid(1, 1);
  EXPECT_EQ(mrepair::inspect_polygon_soup(s.points, s.polygons, MP::spike_angle(-5.0)).status,
            Status::invalid_parameter);
  EXPECT_EQ(mrepair::inspect_polygon_soup(s.points, s.polygons, MP::t_junction_tolerance(
                                                                    std::numeric_limits<double>::quiet_NaN()))
                .status,
            Status::invalid_parameter);
}

TEST(Inspect_soup, quads_use_newell_area)
{
  Soup s = grid(2, 3, 0.5, true);
  Inspection_report r = mrepair::inspect_polygon_soup(s.points, s.polygons);
  expect_counts(r, {{"faces", 6}, {"triangles", 0}, {"edges", 17}, {"boundary_edges", 10},
                    {"degenerate_faces", 0}},
                "quads");
  EXPECT_NEAR(r.area, 1.5, 1e-12);
  EXPECT_TRUE(std::isnan(r.min_angle)); // angles are measured on triangles only
  Soup c = cube(2.0, true);
  r = mrepair::inspect_polygon_soup(c.points, c.polygons);
  EXPECT_TRUE(r.closed);
  EXPECT_NEAR(r.volume, 8.0, 1e-12);
  EXPECT_NEAR(r.max_dihedral_angle, 90.0, 1e-9);
  EXPECT_EQ(r.spiked_vertices, 0u);
  EXPECT_EQ(mrepair::inspect_polygon_soup(c.points, c.polygons, MP::spike_angle(80.0)).spiked_vertices, 8u);
}

// ---------------------------------------------------------------------------
// Typed over Surface_mesh and Polyhedron_3: mesh path and soup path agree

template <class C>
class Inspect : public ::testing::Test
{};
TYPED_TEST_SUITE(Inspect, Mesh_configs);

TYPED_TEST(Inspect, clean_grid)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(4, 4);
  expect_both<Mesh>(s, {{"vertices", 25}, {"faces", 32}, {"edges", 56}, {"boundary_edges", 16},
                        {"boundary_loops", 1}, {"small_holes", 1}, {"connected_components", 1},
                        {"small_components", 1}, {"non_manifold_vertices", 0}, {"duplicate_points", 0},
                        {"near_degenerate_faces", 0}, {"collapsible_edges", 0}, {"spiked_vertices", 0},
                        {"t_junctions", 0}, {"degenerate_faces", 0}, {"isolated_vertices", 0}},
                    "grid");
  Mesh m = to_mesh<Mesh>(s);
  Inspection_report r = mrepair::inspect(m);
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_TRUE(r.self_intersections_counted);
  EXPECT_EQ(r.self_intersecting_pairs, 0u);
  EXPECT_NEAR(r.min_angle, 45.0, 1e-9);
  EXPECT_NEAR(r.small_angle_share, 0.0, 0.0);
  EXPECT_NEAR(r.area, 16.0, 1e-12);
  // 9 interior vertices, all of valence 6 in this triangulation
  EXPECT_NEAR(r.mean_valence_deviation, 0.0, 1e-12);
  EXPECT_NEAR(r.edge_length_mean, (40.0 + 16.0 * std::sqrt(2.0)) / 56.0, 1e-12);
  EXPECT_FALSE(r.closed);
  EXPECT_TRUE(std::isnan(r.volume));
  EXPECT_TRUE(r.is_clean() == false); // the outer border is a small hole by the default threshold
  EXPECT_EQ(mrepair::inspect(m, MP::max_hole_vertices(16, MP::min_component_faces(32))).small_holes, 0u);
  EXPECT_EQ(mrepair::inspect(m, MP::max_hole_vertices(17, MP::min_component_faces(33))).small_components, 1u);
}

TYPED_TEST(Inspect, grid_with_one_face_hole)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = without_polygons(grid(4, 4), {cell_triangle(4, 1, 1)});
  expect_both<Mesh>(s, {{"faces", 31}, {"boundary_edges", 19}, {"boundary_loops", 2},
                        {"small_holes", 2}, {"connected_components", 1}, {"small_components", 1}},
                    "one-face hole");
  Mesh m = to_mesh<Mesh>(s);
  Inspection_report r = mrepair::inspect(m, MP::max_hole_vertices(10, MP::min_component_faces(10)));
  EXPECT_EQ(r.small_holes, 1u);
  EXPECT_EQ(r.small_components, 0u);
}

TYPED_TEST(Inspect, grid_with_three_by_three_hole)
{
  using Mesh = typename TypeParam::Mesh;
  std::set<std::size_t> hole;
  for (std::size_t i = 2; i <= 4; ++i)
    for (std::size_t j = 2; j <= 4; ++j) {
      hole.insert(cell_triangle(7, i, j));
      hole.insert(cell_triangle(7, i, j) + 1);
    }
  Soup with_points = without_polygons(grid(7, 7), hole);
  // the 4 grid points inside the hole are no longer used
  EXPECT_EQ(mrepair::inspect_polygon_soup(with_points.points, with_points.polygons).isolated_vertices, 4u);
  Soup s = compacted(with_points);
  expect_both<Mesh>(s, {{"faces", 80}, {"boundary_edges", 40}, {"boundary_loops", 2},
                        {"small_holes", 2}, {"connected_components", 1}},
                    "3x3 hole");
  Mesh m = to_mesh<Mesh>(s);
  EXPECT_EQ(mrepair::inspect(m, MP::max_hole_vertices(13)).small_holes, 1u); // the 12-edge loop
  EXPECT_EQ(mrepair::inspect(m, MP::max_hole_vertices(12)).small_holes, 0u);
  EXPECT_EQ(mrepair::inspect(m, MP::max_hole_vertices(29)).small_holes, 2u); // and the 28-edge one
}

TYPED_TEST(Inspect, two_components_one_tiny)
{
  using Mesh = typename TypeParam::Mesh;
  Soup tiny;
  tiny.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)};
  tiny.polygons = {{0, 1, 2}};
  Soup s = merged(grid(5, 5), translated(tiny, 10, 10, 0));
  expect_both<Mesh>(s, {{"connected_components", 2}, {"small_components", 2}, {"boundary_loops", 2}},
                    "two components");
  Mesh m = to_mesh<Mesh>(s);
  EXPECT_EQ(mrepair::inspect(m, MP::min_component_faces(10)).small_components, 1u);
  EXPECT_EQ(mrepair::inspect(m, MP::min_component_faces(1)).small_components, 0u);
}

TYPED_TEST(Inspect, spike_raised_five_edge_lengths)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(6, 6);
  const std::size_t apex = grid_index(6, 3, 3);
  s.points[apex] = Point(3, 3, 5);
  // dihedral angles of this tall spike (the grid's diagonals make them uneven):
  // 87.80 deg on 2 edges, 81.95 on 2, 78.69 on 4, 44.44 on 4 (hand computed)
  // Height criterion (as relax_spikes): the apex is 5 above the plane of its
  // link, whose 6 edges have mean length (4 + 2 sqrt 2) / 6 = 1.138; 5 / 1.138
  // = 4.39 > 2. The 6 ring vertices (every dihedral > 15 deg) stay far below:
  // 0.394 / 2.452 = 0.16 (4 of them) and 0.539 / 2.504 = 0.22 (2).
  Mesh m = to_mesh<Mesh>(s);
  Inspection_report r = mrepair::inspect(m);
  EXPECT_NEAR(r.max_dihedral_angle, 87.80, 0.01);
  EXPECT_EQ(r.spiked_vertices, 1u);  // the apex, by height only (every dihedral < 100 deg)
  EXPECT_EQ(mrepair::inspect(m, MP::spike_height_factor(0.0)).spiked_vertices, 0u);
  EXPECT_EQ(mrepair::inspect(m, MP::spike_height_factor(4.5)).spiked_vertices, 0u);
  EXPECT_EQ(mrepair::inspect(m, MP::spike_height_factor(4.3)).spiked_vertices, 1u);
  EXPECT_EQ(mrepair::inspect(m, MP::spike_angle(85.0)).spiked_vertices, 3u);  // apex + 2
  EXPECT_EQ(mrepair::inspect(m, MP::spike_angle(80.0)).spiked_vertices, 7u);  // apex + 6 ring
  EXPECT_EQ(mrepair::inspect(m, MP::spike_angle(40.0)).spiked_vertices, 7u);
  EXPECT_EQ(mrepair::inspect(m, MP::spike_angle(88.0)).spiked_vertices, 1u);  // apex by height
  EXPECT_EQ(mrepair::inspect(m, MP::spike_angle(88.0, MP::spike_height_factor(0.0))).spiked_vertices, 0u);
  EXPECT_EQ(mrepair::inspect_polygon_soup(s.points, s.polygons, MP::spike_angle(80.0)).spiked_vertices, 7u);
  EXPECT_EQ(mrepair::inspect_polygon_soup(s.points, s.polygons).spiked_vertices, 1u);
  // The same definition as relax_spikes(): it finds the same single vertex.
  Mesh relaxed = m;
  const mrepair::Spike_relaxation_result sr = mrepair::relax_spikes(relaxed);
  EXPECT_EQ(sr.spiked_vertices_before, 1u);
  EXPECT_EQ(sr.spiked_by_height_before, 1u);
  EXPECT_EQ(mrepair::inspect(relaxed).spiked_vertices, sr.spiked_vertices_after);
  EXPECT_EQ(r.self_intersecting_pairs, 0u);
  // located: the apex; with 80 degrees the apex and its ring
  EXPECT_EQ(mrepair::locate_defects(m).spiked_vertices, std::vector<std::size_t>{apex});
  EXPECT_EQ(mrepair::locate_defects(s.points, s.polygons).spiked_vertices, std::vector<std::size_t>{apex});
  const mrepair::Defect_locations d80 = mrepair::locate_defects(m, MP::spike_angle(80.0));
  EXPECT_EQ(d80.spiked_vertices.size(), 7u);
  EXPECT_TRUE(std::is_sorted(d80.spiked_vertices.begin(), d80.spiked_vertices.end()));
  expect_located_on_mesh(m, "spike");
}

TYPED_TEST(Inspect, sliver_faces)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(4, 4);
  const std::size_t v = grid_index(4, 2, 2);
  // zero edge: |v w| = 0.05 < 0.1 x mean: both triangles on it
  s.points[v] = Point(2.95, 2, 0);
  expect_both<Mesh>(s, {{"near_degenerate_faces", 2}, {"collapsible_edges", 1}, {"degenerate_faces", 0}},
                    "zero edge");
  // skinny edge: |v w| = 0.2 is above 0.1 x mean (~0.11) but below 0.25 x local
  // mean (~0.28); its opposite angle is 6.3 deg in one triangle, 11.3 in the other
  s.points[v] = Point(2.8, 2, 0);
  expect_both<Mesh>(s, {{"near_degenerate_faces", 1}, {"collapsible_edges", 1}}, "skinny edge");
  Mesh m = to_mesh<Mesh>(s);
  EXPECT_EQ(mrepair::inspect(m, MP::skinny_angle(12.0)).near_degenerate_faces, 2u);
  EXPECT_EQ(mrepair::inspect(m, MP::skinny_angle(5.0)).near_degenerate_faces, 0u);
  EXPECT_EQ(mrepair::inspect(m, MP::skinny_angle(5.0)).collapsible_edges, 0u);
  EXPECT_EQ(mrepair::inspect(m, MP::zero_edge_factor(0.2)).near_degenerate_faces, 2u);
}

TYPED_TEST(Inspect, collinear_face)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(2, 1);
  s.points[1] = Point(0.5, 0.5, 0); // on the diagonal (0,0)-(1,1): triangle (0,1,4) is flat
  expect_both<Mesh>(s, {{"degenerate_faces", 1}, {"repeated_index_faces", 0}}, "collinear");
  Mesh m = to_mesh<Mesh>(s);
  Inspection_report r = mrepair::inspect(m);
  EXPECT_NEAR(r.min_angle, 0.0, 1e-12);
  // CGAL reports the flat face as (f, f), not counted; the moved vertex also
  // touches edge (0,4) of triangle (0,4,3), which both triangles on it
  // intersect: 2 pairs
  EXPECT_EQ(r.self_intersecting_pairs, 2u);
}

TYPED_TEST(Inspect, closed_icosphere)
{
  using Mesh = typename TypeParam::Mesh;
  const double radius = 2.0;
  Soup s = icosphere(3, radius); // 1280 faces, 642 vertices
  expect_both<Mesh>(s, {{"faces", 1280}, {"vertices", 642}, {"edges", 1920}, {"boundary_edges", 0},
                        {"boundary_loops", 0}, {"small_holes", 0}, {"connected_components", 1},
                        {"small_components", 0}, {"spiked_vertices", 0}, {"near_degenerate_faces", 0},
                        {"non_manifold_vertices", 0}},
                    "icosphere");
  Mesh m = to_mesh<Mesh>(s);
  Inspection_report r = mrepair::inspect(m);
  EXPECT_TRUE(r.closed);
  const double exact = 4.0 / 3.0 * CGAL_PI * radius * radius * radius;
  EXPECT_NEAR(r.volume, exact, 0.02 * exact); // inscribed polyhedron: slightly smaller
  EXPECT_LT(r.volume, exact);
  EXPECT_NEAR(r.area, 4 * CGAL_PI * radius * radius, 0.02 * 4 * CGAL_PI * radius * radius);
  EXPECT_EQ(r.self_intersecting_pairs, 0u);
  EXPECT_NEAR(r.mean_valence_deviation, 12.0 / 642.0, 1e-12); // the 12 valence-5 vertices
  EXPECT_LT(r.max_dihedral_angle, 20.0);
  EXPECT_TRUE(r.is_clean());
  // no defect: every list empty
  const mrepair::Defect_locations d = mrepair::locate_defects(m);
  EXPECT_EQ(d.report.status, Status::ok);
  EXPECT_TRUE(d.boundary_loops.empty() && d.small_holes.empty() && d.non_manifold_edges.empty() &&
              d.non_manifold_vertices.empty() && d.spiked_vertices.empty() && d.near_degenerate_faces.empty() &&
              d.small_components.empty() && d.self_intersecting_pairs.empty() && d.t_junction_vertices.empty());
  const mrepair::internal::Defect_overlay o =
      mrepair::internal::make_defect_overlay(mrepair::internal::indexed_faces_of_mesh(m), d, 100);
  for (const auto& k : o.kinds)
    EXPECT_TRUE(k.count == 0 && k.points.empty() && k.segments.empty() && k.triangles.empty() && !k.has_first);
  // the preview: the mesh itself within the budget, else at most the budget
  const mrepair::internal::Mesh_preview full = mrepair::internal::make_preview(mrepair::internal::indexed_faces_of_mesh(m), 1280);
  EXPECT_FALSE(full.decimated);
  EXPECT_EQ(full.indices.size(), 3 * 1280u);
  EXPECT_EQ(full.positions.size(), 3 * 642u);
  const mrepair::internal::Mesh_preview small = mrepair::internal::make_preview(mrepair::internal::indexed_faces_of_mesh(m), 300);
  EXPECT_TRUE(small.decimated);
  EXPECT_EQ(small.faces, 1280u);
  EXPECT_LE(small.indices.size(), 3 * 300u);
  EXPECT_GE(small.indices.size(), 3 * 30u);
}

TYPED_TEST(Inspect, pillow_is_a_duplicate_of_opposite_orientation)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)};
  s.polygons = {{0, 1, 2}, {0, 2, 1}};
  expect_both<Mesh>(s, {{"duplicate_faces", 1}, {"duplicate_faces_opposite", 1}, {"boundary_edges", 0},
                        {"inconsistent_orientation_edges", 0}, {"spiked_vertices", 3}},
                    "pillow");
  Mesh m = to_mesh<Mesh>(s);
  Inspection_report r = mrepair::inspect(m);
  EXPECT_TRUE(r.closed);
  EXPECT_NEAR(r.volume, 0.0, 1e-15);
  EXPECT_NEAR(r.max_dihedral_angle, 180.0, 1e-9);
  // the two faces overlap across their shared edges: one pair, as CGAL says
  EXPECT_EQ(r.self_intersecting_pairs, 1u);
}

// Self-intersections of a crumpled sphere (random radii): the same pairs as
// PMP::self_intersections, without its (f, f) pairs of degenerate faces.
TYPED_TEST(Inspect, self_intersections_agree_with_cgal)
{
  using Mesh = typename TypeParam::Mesh;
  namespace PMP = CGAL::Polygon_mesh_processing;
  Soup s = icosphere(3, 1.0);
  std::uint32_t seed = 12345;
  for (auto& p : s.points) {
    seed = seed * 1664525u + 1013904223u;
    const double f = 0.6 + 0.8 * double(seed >> 8) / double(1u << 24);
    p = Point(p.x() * f, p.y() * f, p.z() * f);
  }
  s.points[7] = s.points[8]; // and one degenerate (collapsed edge) region
  Mesh m = to_mesh<Mesh>(s);
  std::vector<std::pair<typename boost::graph_traits<Mesh>::face_descriptor,
                        typename boost::graph_traits<Mesh>::face_descriptor>> pairs;
  PMP::self_intersections(m, std::back_inserter(pairs));
  std::size_t distinct = 0, degenerate = 0;
  for (const auto& p : pairs) (p.first != p.second ? distinct : degenerate)++;
  ASSERT_GT(distinct, 50u); // 72 with this seed
  Inspection_report r = mrepair::inspect(m);
  EXPECT_EQ(r.self_intersecting_pairs, distinct);
  EXPECT_EQ(r.degenerate_faces, degenerate);
  EXPECT_EQ(mrepair::inspect_polygon_soup(s.points, s.polygons).self_intersecting_pairs, distinct);
}

TYPED_TEST(Inspect, non_finite_and_isolated_vertices)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s = grid(2, 2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  s.points[grid_index(2, 1, 1)] = Point(nan, 0, 0); // the centre, in 6 triangles
  s.points.push_back(Point(5, 5, 5));              // isolated
  Inspection_report r = mrepair::inspect_polygon_soup(s.points, s.polygons);
  EXPECT_EQ(r.status, Status::non_finite_input);
  expect_counts(r, {{"non_finite_vertices", 1}, {"isolated_vertices", 1}, {"boundary_edges", 8},
                    {"connected_components", 1}, {"degenerate_faces", 0}},
                "nan soup");
  EXPECT_NEAR(r.area, 1.0, 1e-12); // the two triangles away from the centre

  Soup g = grid(2, 2);
  Mesh m = to_mesh<Mesh>(g);
  auto v = add_vertex(m);
  put(get(CGAL::vertex_point, m), v, Point(5, 5, 5));
  set_point(m, grid_index(2, 1, 1), Point(nan, 0, 0));
  r = mrepair::inspect(m);
  EXPECT_EQ(r.status, Status::non_finite_input);
  expect_counts(r, {{"non_finite_vertices", 1}, {"isolated_vertices", 1}, {"boundary_edges", 8}},
                "nan mesh");
  EXPECT_FALSE(r.self_intersections_counted);
  EXPECT_NEAR(r.area, 1.0, 1e-12);
}

TYPED_TEST(Inspect, self_intersections)
{
  using Mesh = typename TypeParam::Mesh;
  // a triangle pierced by another
  Soup s;
  s.points = {Point(0, 0, 0), Point(2, 0, 0), Point(0, 2, 0),
              Point(0.2, 0.5, -1), Point(0.8, 0.5, -1), Point(0.5, 0.5, 1)};
  s.polygons = {{0, 1, 2}, {3, 4, 5}};
  Mesh m = to_mesh<Mesh>(s);
  Inspection_report r = mrepair::inspect(m);
  EXPECT_TRUE(r.self_intersections_counted);
  EXPECT_EQ(r.self_intersecting_pairs, 1u);
  EXPECT_FALSE(mrepair::inspect(m, MP::count_self_intersections(false)).self_intersections_counted);
  Inspection_report rs = mrepair::inspect_polygon_soup(s.points, s.polygons);
  EXPECT_TRUE(rs.self_intersections_counted);
  EXPECT_EQ(rs.self_intersecting_pairs, 1u);
  EXPECT_FALSE(mrepair::inspect_polygon_soup(s.points, s.polygons, MP::count_self_intersections(false))
                   .self_intersections_counted);

  // a tetrahedron whose apex pokes through the bottom face of another: its
  // three side faces each cross that face
  Soup t;
  t.points = {Point(0, 0, 0), Point(2, 0, 0), Point(0, 2, 0), Point(0, 0, 2),
              Point(0.3, 0.3, -1), Point(0.9, 0.3, -1), Point(0.6, 0.9, -1), Point(0.5, 0.5, 0.5)};
  t.polygons = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {4, 6, 5}, {4, 5, 7}, {4, 7, 6}, {5, 6, 7}};
  Mesh m2 = to_mesh<Mesh>(t);
  r = mrepair::inspect(m2);
  EXPECT_EQ(r.self_intersecting_pairs, 3u);
  EXPECT_EQ(r.connected_components, 2u);
  EXPECT_TRUE(r.closed);
  EXPECT_NEAR(r.volume, 8.0 / 6.0 + 0.6 * 0.6 * 1.5 / 6.0, 1e-12);
}

// Faces that meet only at coincident vertices of their own (a non-manifold
// vertex split into copies, as the soup stage and the gap closing leave it;
// unmerged duplicate points) intersect for PMP::self_intersections; the
// report says how many of its pairs are only such touching. Each copy taken
// as one shared vertex (or two as a shared edge) decides it.
TYPED_TEST(Inspect, pairs_touching_at_coincident_vertices)
{
  using Mesh = typename TypeParam::Mesh;
  namespace PMP = CGAL::Polygon_mesh_processing;
  // one intersecting pair, as PMP counts it, of which `touching` only touch
  auto expect_one_pair = [](const Soup& s, std::size_t touching, const char* what) {
    const Mesh m = to_mesh<Mesh>(s);
    std::vector<std::pair<typename boost::graph_traits<Mesh>::face_descriptor,
                          typename boost::graph_traits<Mesh>::face_descriptor>> pairs;
    PMP::self_intersections(m, std::back_inserter(pairs));
    EXPECT_EQ(pairs.size(), 1u) << what;
    const Inspection_report r = mrepair::inspect(m);
    EXPECT_EQ(r.self_intersecting_pairs, 1u) << what;
    EXPECT_EQ(r.self_intersecting_pairs_touching, touching) << what;
    EXPECT_EQ(mrepair::inspect_polygon_soup(s.points, s.polygons).self_intersecting_pairs_touching, touching)
        << what;
  };
  // a bowtie split at its centre: two copies of (0, 0, 0)
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 0, 0), Point(-1, 0, 0), Point(-1, -1, 0)};
  s.polygons = {{0, 1, 2}, {3, 4, 5}};
  expect_one_pair(s, 1, "split bowtie");
  // the same copies, but the second face folds back through the first
  s.points[4] = Point(0.6, 0.2, -1);
  s.points[5] = Point(0.6, 0.2, 1);
  expect_one_pair(s, 0, "folded through");
  // two triangles on copies of one edge: on either side of it, touching; on
  // the same side (overlapping), crossing
  Soup e;
  e.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0), Point(1, 0, 0), Point(0, 0, 0), Point(0.5, -1, 0.2)};
  e.polygons = {{0, 1, 2}, {3, 4, 5}};
  expect_one_pair(e, 1, "edge copies apart");
  e.points[5] = Point(0.5, 0.5, 0);
  expect_one_pair(e, 0, "edge copies overlapping");
  // a fan about vertex 0 that turns back onto its first edge: its last face
  // shares vertex 0 with the first and has a copy of the first edge's other
  // end (as where a solid touches itself along an edge): touching along it
  Soup f;
  f.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0.3), Point(1, 0, 0), Point(-1, 0, 0.2)};
  f.polygons = {{0, 1, 2}, {0, 2, 4}, {0, 4, 3}};
  expect_one_pair(f, 1, "vertex shared, edge end a copy");
}

TYPED_TEST(Inspect, t_junction_between_patches)
{
  using Mesh = typename TypeParam::Mesh;
  // left square; right square whose left side is split at (1, 0.5)
  Soup s;
  s.points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0),
              Point(1, 0, 0), Point(2, 0, 0), Point(2, 1, 0), Point(1, 1, 0), Point(1, 0.5, 0)};
  s.polygons = {{0, 1, 2}, {0, 2, 3}, {4, 5, 8}, {8, 5, 6}, {8, 6, 7}};
  expect_both<Mesh>(s, {{"t_junctions", 1}, {"duplicate_points", 2}, {"boundary_edges", 9},
                        {"boundary_loops", 2}, {"connected_components", 2}, {"non_manifold_vertices", 0}},
                    "T-junction");
  Mesh m = to_mesh<Mesh>(s);
  for (const mrepair::Defect_locations& d : {mrepair::locate_defects(s.points, s.polygons), mrepair::locate_defects(m)}) {
    ASSERT_EQ(d.t_junction_vertices.size(), 1u);
    EXPECT_EQ(d.t_junction_vertices[0], 8u);
    EXPECT_EQ(d.t_junction_edges[0], (std::array<std::size_t, 2>{{1, 2}}));
  }
  // a tolerance smaller than the gap misses a vertex moved 0.01 off the edge
  set_point(m, 8, Point(1.01, 0.5, 0));
  EXPECT_EQ(mrepair::inspect(m).t_junctions, 0u); // default 1e-4 x diagonal
  EXPECT_EQ(mrepair::inspect(m, MP::t_junction_tolerance(0.02)).t_junctions, 1u);
  // ... and a tolerance larger than the distance to an endpoint does not count it
  EXPECT_EQ(mrepair::inspect(m, MP::t_junction_tolerance(0.6)).t_junctions, 0u);
}

TYPED_TEST(Inspect, bowtie_mesh_vertex)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m;
  auto vpm = get(CGAL::vertex_point, m);
  using VD = typename boost::graph_traits<Mesh>::vertex_descriptor;
  std::vector<VD> v;
  for (Point p : {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(-1, 0, 0), Point(-1, -1, 0)}) {
    v.push_back(add_vertex(m));
    put(vpm, v.back(), p);
  }
  ASSERT_NE(CGAL::Euler::add_face(std::vector<VD>{v[0], v[1], v[2]}, m),
            boost::graph_traits<Mesh>::null_face());
  ASSERT_NE(CGAL::Euler::add_face(std::vector<VD>{v[0], v[3], v[4]}, m),
            boost::graph_traits<Mesh>::null_face());
  Inspection_report r = mrepair::inspect(m);
  expect_counts(r, {{"non_manifold_vertices", 1}, {"boundary_edges", 6}, {"connected_components", 2},
                    {"faces", 2}, {"vertices", 5}},
                "bowtie mesh");
  // border cycles as CGAL links them
  std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor> cycles;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(m, std::back_inserter(cycles));
  EXPECT_EQ(r.boundary_loops, cycles.size());
}

TYPED_TEST(Inspect, empty_mesh)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m;
  EXPECT_EQ(mrepair::inspect(m).status, Status::empty_input);
}

// On a real scan-like mesh with holes: soup and mesh agree, and the counts
// match CGAL's own functions.
TYPED_TEST(Inspect, agrees_with_cgal_on_elephant)
{
  using Mesh = typename TypeParam::Mesh;
  namespace PMP = CGAL::Polygon_mesh_processing;
  const std::string path = std::string(MREPAIR_CGAL_DATA_DIR) + "/elephant-with-holes.off";
  if (!std::ifstream(path)) GTEST_SKIP() << "no CGAL sample data";
  Mesh m;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(path, m));
  Inspection_report r = mrepair::inspect(m);
  std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor> cycles;
  PMP::extract_boundary_cycles(m, std::back_inserter(cycles));
  EXPECT_EQ(r.boundary_loops, cycles.size());
  std::size_t border = 0;
  for (auto h : halfedges(m)) border += is_border(h, m);
  EXPECT_EQ(r.boundary_edges, border);
  auto fcc = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  EXPECT_EQ(r.connected_components, PMP::connected_components(m, fcc));
  std::vector<std::pair<typename boost::graph_traits<Mesh>::face_descriptor,
                        typename boost::graph_traits<Mesh>::face_descriptor>> si;
  PMP::self_intersections(m, std::back_inserter(si));
  EXPECT_EQ(r.self_intersecting_pairs, si.size());
  expect_located_on_mesh(m, "elephant");
  // the located pairs are CGAL's
  {
    const mrepair::Defect_locations d = mrepair::locate_defects(m);
    std::map<typename boost::graph_traits<Mesh>::face_descriptor, std::size_t> fid;
    for (auto f : faces(m)) fid.emplace(f, fid.size());
    std::set<std::array<std::size_t, 2>> cgal, ours(d.self_intersecting_pairs.begin(), d.self_intersecting_pairs.end());
    for (const auto& p : si) {
      const std::size_t a = fid[p.first], b = fid[p.second];
      cgal.insert({{std::min(a, b), std::max(a, b)}});
    }
    EXPECT_EQ(ours, cgal);
  }
  std::set<std::array<double, 3>> distinct;
  for (auto v : vertices(m)) {
    auto p = get(CGAL::vertex_point, m, v);
    distinct.insert({p.x(), p.y(), p.z()});
  }
  EXPECT_EQ(r.duplicate_points, vertices(m).size() - distinct.size());

  // the soup of the same faces gives the same counts (self-intersections aside)
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, std::size_t> id;
  for (auto v : vertices(m)) {
    id[v] = pts.size();
    auto p = get(CGAL::vertex_point, m, v);
    pts.emplace_back(p.x(), p.y(), p.z());
  }
  for (auto f : faces(m)) {
    polys.emplace_back();
    for (auto v : CGAL::vertices_around_face(halfedge(f, m), m)) polys.back().push_back(id[v]);
  }
  Inspection_report rs = mrepair::inspect_polygon_soup(pts, polys);
  mrepair::Report a, b;
  r.to_report(a);
  rs.to_report(b);
  auto fa = a.flatten(), fb = b.flatten();
  ASSERT_EQ(fa.size(), fb.size());
  for (std::size_t i = 0; i < fa.size(); ++i) {
    if (fa[i].first == "kind" || fa[i].first == "defects.self_intersecting_pairs") continue;
    EXPECT_EQ(fa[i], fb[i]);
  }
}

// The double-precision certificates in front of the exact pair tests
// (internal/triangle_intersection.h) must never change an answer. Pairs from
// nearly coplanar fans (a subdivided flat face, the case they are for),
// folded fans, overlapping and crossing triangles, and random triangles in a
// small box: the pair test with the certificates gives what the exact
// predicates alone give, and the flat cases are decided by the certificates.
TEST(Inspect_issue_17, pair_certificates_agree_with_the_exact_predicates)
{
  namespace I = mrepair::internal;
  using P = I::Epick_point;
  using K = CGAL::Epick;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(-1, 1);
  auto exact = [](const int fk[3], const P f[3], const int gk[3], const P g[3]) {
    int shared = 0, fi[3] = {0, 0, 0}, gj[3] = {0, 0, 0};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (fk[i] == gk[j]) { fi[shared] = i; gj[shared] = j; ++shared; }
    if (shared == 0) return CGAL::do_intersect(K::Triangle_3(f[0], f[1], f[2]), K::Triangle_3(g[0], g[1], g[2]));
    if (shared == 1) {
      const int i = fi[0], j = gj[0];
      return CGAL::do_intersect(K::Triangle_3(f[0], f[1], f[2]), K::Segment_3(g[(j + 1) % 3], g[(j + 2) % 3])) ||
             CGAL::do_intersect(K::Triangle_3(g[0], g[1], g[2]), K::Segment_3(f[(i + 1) % 3], f[(i + 2) % 3]));
    }
    if (shared == 2) {
      const int c = 3 - fi[0] - fi[1], d = 3 - gj[0] - gj[1];
      return CGAL::coplanar(f[fi[0]], f[fi[1]], f[c], g[d]) &&
             CGAL::coplanar_orientation(f[fi[0]], f[fi[1]], f[c], g[d]) == CGAL::POSITIVE;
    }
    return true;
  };
  std::size_t pairs = 0, intersecting = 0, certified = 0, flat_pairs = 0, flat_certified = 0;
  auto check = [&](const std::vector<P>& pts, const std::vector<std::array<int, 3>>& tris, bool flat) {
    for (std::size_t a = 0; a < tris.size(); ++a)
      for (std::size_t b = a + 1; b < tris.size(); ++b) {
        const int* fk = tris[a].data();
        const int* gk = tris[b].data();
        const P f[3] = {pts[fk[0]], pts[fk[1]], pts[fk[2]]};
        const P g[3] = {pts[gk[0]], pts[gk[1]], pts[gk[2]]};
        if (CGAL::collinear(f[0], f[1], f[2]) || CGAL::collinear(g[0], g[1], g[2])) continue;
        const bool expected = exact(fk, f, gk, g);
        ASSERT_EQ(I::triangles_intersect(fk, f, gk, g), expected) << "pair " << a << " " << b;
        ++pairs;
        intersecting += expected;
        // which certificate applies, and whether it answered
        int shared = 0, fi[2] = {0, 0}, gj[2] = {0, 0};
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            if (fk[i] == gk[j] && shared < 2) { fi[shared] = i; gj[shared] = j; ++shared; }
        bool decided = false;
        if (shared == 0) decided = I::certify::apart_disjoint(f, g);
        else if (shared == 1) decided = I::certify::apart_beside_vertex(f, fi[0], g, gj[0]);
        else {
          const int c = 3 - fi[0] - fi[1];
          const int d = 3 - gj[0] - gj[1];
          decided = I::certify::apart_across_edge(f[fi[0]], f[fi[1]], f[c], g[d]);
        }
        if (decided) {
          EXPECT_FALSE(expected);
        }
        certified += decided;
        if (flat) {
          ++flat_pairs;
          flat_certified += decided;
        }
      }
  };
  for (int trial = 0; trial < 300; ++trial) {
    // a fan of 7 to 12 triangles around a centre, its ring in a tilted plane
    // given by rounded coordinates (as midpoint subdivision leaves them),
    // sometimes folded (one ring point pulled across) or lifted off the plane
    const int k = 7 + trial % 6;
    const double ax = unit(rng), ay = unit(rng), az = 1 + unit(rng);
    const int mode = trial % 4;  // 0 flat, 1 lifted by 1e-12, 2 folded, 3 spread out of the plane
    std::vector<P> pts{P(0.1 * unit(rng), 0.1 * unit(rng), 0.)};
    for (int i = 0; i < k; ++i) {
      double t = 2 * CGAL_PI * (i + 0.3 * unit(rng)) / k;
      if (mode == 2 && i == 2) t = 2 * CGAL_PI * 0.5 / k;  // folds back over its neighbour
      const double x = std::cos(t) * (1 + 0.3 * unit(rng)), y = std::sin(t) * (1 + 0.3 * unit(rng));
      double z = (ax * x + ay * y) / az;  // on the plane, rounded
      if (mode == 1) z += 1e-12 * unit(rng);
      if (mode == 3) z += 0.2 * unit(rng);
      pts.emplace_back(x, y, z);
    }
    // midpoints of the ring edges: nearly, not exactly, coplanar
    for (int i = 1; i <= k; ++i) {
      const P& p = pts[i];
      const P& q = pts[i % k + 1];
      pts.emplace_back((p.x() + q.x()) / 2, (p.y() + q.y()) / 2, (p.z() + q.z()) / 2);
    }
    std::vector<std::array<int, 3>> tris;
    for (int i = 1; i <= k; ++i) {
      const int m = k + i;  // midpoint of ring edge i
      tris.push_back({0, i, m});
      tris.push_back({0, m, i % k + 1});
    }
    // and a few loose triangles nearby (sharing nothing or a point)
    for (int r = 0; r < 4; ++r) {
      const int base = int(pts.size());
      for (int c = 0; c < 3; ++c) {
        const double x = 1.5 * unit(rng), y = 1.5 * unit(rng);
        double z = (ax * x + ay * y) / az;
        if (r % 2) z += 0.3 * unit(rng);
        pts.emplace_back(x, y, z);
      }
      tris.push_back({base, base + 1, base + 2});
    }
    check(pts, tris, mode == 0);
  }
  std::fprintf(stderr, "pairs %zu, intersecting %zu, decided by a certificate %zu (flat fans: %zu of %zu)\n", pairs,
               intersecting, certified, flat_certified, flat_pairs);
  EXPECT_GT(intersecting, 0u);  // folds and crossings are there
  EXPECT_GT(certified, pairs / 4);
  // on flat fans the certificates decide most pairs (else the exact predicates would)
  EXPECT_GT(flat_certified, flat_pairs / 2) << flat_certified << " of " << flat_pairs;
}

// Issue 17: the counter skips the pairs that share a vertex whose fan it
// certifies flat (one consistently oriented fan projecting one-to-one). A
// folded fan, two fans pinched at one vertex and a fan winding twice around
// its centre must not be certified, and the count stays the exact one.
TEST(Inspect_issue_17, flat_fan_certificates_keep_the_exact_count)
{
  namespace I = mrepair::internal;
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::mt19937 rng(1717);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::size_t n = 24;
  Soup s = grid(n, n);
  for (Point& p : s.points) p = Point(p.x() + 0.2 * u(rng), p.y() + 0.2 * u(rng), 0.3 * u(rng));
  // folds: interior vertices pulled in the plane across a neighbour
  std::vector<std::size_t> folded;
  for (std::size_t k = 0; k < 6; ++k) {
    const std::size_t v = (3 + 3 * k) * (n + 1) + 4 + 3 * k;
    const Point& p = s.points[v];
    s.points[v] = Point(p.x() + 1.6, p.y() + 0.1, p.z());
    folded.push_back(v);
  }
  // a fan of 12 triangles whose ring turns twice around its centre
  const std::size_t twice = s.points.size();
  s.points.emplace_back(40., 0., 0.);
  for (int i = 0; i < 12; ++i) {
    const double t = 4 * CGAL_PI * i / 12, r = 1 + 0.3 * (i % 2);
    s.points.emplace_back(40. + r * std::cos(t), r * std::sin(t), 0.05 * u(rng));
  }
  for (std::size_t i = 0; i < 12; ++i) s.polygons.push_back({twice, twice + 1 + i, twice + 1 + (i + 1) % 12});
  const Soup mesh_part = s;

  // a second sheet pinched at an interior grid vertex, lying across its fan
  const std::size_t pinch = 12 * (n + 1) + 12, base = s.points.size();
  const Point c = s.points[pinch];
  for (int i = 0; i < 3; ++i) {
    const double t = 0.3 + 0.8 * i;
    s.points.emplace_back(c.x() + std::cos(t), c.y() + std::sin(t), c.z() + 0.05);
  }
  s.polygons.push_back({pinch, base, base + 1});
  s.polygons.push_back({pinch, base + 1, base + 2});

  // which vertices are certified
  I::Surface_arrays a;
  std::size_t invalid = 0;
  ASSERT_TRUE(I::build_soup_arrays(s.points, s.polygons, a, invalid));
  I::certify_flat_stars(a);
  ASSERT_EQ(a.flat_star.size(), s.points.size());
  std::size_t flat = 0;
  for (unsigned char f : a.flat_star) flat += f;
  EXPECT_GT(flat, s.points.size() / 2);  // the certificate answers on most of a rough surface
  for (std::size_t v : folded) EXPECT_EQ(a.flat_star[v], 0) << "folded vertex " << v;
  EXPECT_EQ(a.flat_star[twice], 0);
  EXPECT_EQ(a.flat_star[pinch], 0);

  // the counts: the soup's against every pair tested exactly, the mesh's
  // against CGAL
  std::size_t expected = 0;
  for (std::size_t f = 0; f < s.polygons.size(); ++f)
    for (std::size_t g = f + 1; g < s.polygons.size(); ++g) {
      std::size_t fk[3], gk[3];
      I::Epick_point fp[3], gp[3];
      for (int i = 0; i < 3; ++i) {
        fk[i] = s.polygons[f][i];
        gk[i] = s.polygons[g][i];
        fp[i] = s.points[fk[i]];
        gp[i] = s.points[gk[i]];
      }
      expected += I::triangles_intersect(fk, fp, gk, gp);
    }
  const mrepair::Inspection_report rs = mrepair::inspect_polygon_soup(s.points, s.polygons);
  ASSERT_TRUE(rs.self_intersections_counted);
  EXPECT_GT(expected, 0u);
  EXPECT_EQ(rs.self_intersecting_pairs, expected);

  const Surface_mesh m = to_mesh<Surface_mesh>(mesh_part);
  std::vector<std::pair<Surface_mesh::Face_index, Surface_mesh::Face_index>> cgal_pairs;
  PMP::self_intersections(m, std::back_inserter(cgal_pairs));
  const mrepair::Inspection_report rm = mrepair::inspect(m);
  ASSERT_TRUE(rm.self_intersections_counted);
  EXPECT_GT(cgal_pairs.size(), 0u);
  EXPECT_EQ(rm.self_intersecting_pairs, cgal_pairs.size());
}

// Issue 17: the fan of a vertex is put together from its corners' own edges
// (a vertex-corner table, no walk over the edges' corner lists). One
// consistently oriented fan of triangles, closed or open, is certified; a
// flipped face, a third face on an edge, a quad, two fans at the vertex and
// a face with a repeated index are not. The table the inspection passes in
// gives the certificates the counter builds for itself.
TEST(Inspect_issue_17, fan_certificates_need_one_consistent_fan_of_triangles)
{
  namespace I = mrepair::internal;
  auto hexagon = [] {
    Soup s;
    s.points.emplace_back(0., 0., 0.);
    for (int i = 0; i < 6; ++i)
      s.points.emplace_back(std::cos(CGAL_PI * i / 3), std::sin(CGAL_PI * i / 3), 0.01 * (i % 2));
    for (std::size_t i = 0; i < 6; ++i) s.polygons.push_back({0, 1 + i, 1 + (i + 1) % 6});
    return s;
  };
  auto certified = [](const Soup& s) {
    I::Surface_arrays a;
    std::size_t invalid = 0;
    EXPECT_TRUE(I::build_soup_arrays(s.points, s.polygons, a, invalid));
    I::certify_flat_stars(a);
    std::vector<unsigned char> own = a.flat_star;
    std::vector<I::Inspect_index> first, corners;
    I::bucket_items(a.corner_v.size(), a.num_vertices, I::inspect_npos,
                    [&](std::size_t c) { return a.corner_v[c]; }, first, corners);
    I::certify_flat_stars(a, first, corners);
    EXPECT_EQ(own, a.flat_star);
    return a.flat_star;
  };

  const Soup closed = hexagon();
  std::vector<unsigned char> f = certified(closed);
  EXPECT_EQ(f[0], 1);  // closed fan
  for (std::size_t v = 1; v <= 6; ++v) EXPECT_EQ(f[v], 1) << v;  // open fans of two faces

  Soup open = hexagon();
  open.polygons.erase(open.polygons.begin() + 2);
  EXPECT_EQ(certified(open)[0], 1);

  Soup flipped = hexagon();
  std::swap(flipped.polygons[3][1], flipped.polygons[3][2]);
  EXPECT_EQ(certified(flipped)[0], 0);

  Soup fin = hexagon();
  fin.points.emplace_back(0.5, 0., 1.);
  fin.polygons.push_back({0, 1, 7});
  f = certified(fin);
  EXPECT_EQ(f[0], 0);
  EXPECT_EQ(f[1], 0);

  Soup quad = hexagon();
  quad.polygons.erase(quad.polygons.begin(), quad.polygons.begin() + 2);
  quad.polygons.push_back({0, 1, 2, 3});
  EXPECT_EQ(certified(quad)[0], 0);

  Soup bowtie = hexagon();
  bowtie.polygons.erase(bowtie.polygons.begin() + 3);
  bowtie.polygons.erase(bowtie.polygons.begin());
  EXPECT_EQ(certified(bowtie)[0], 0);  // two open fans: rims 2-3-4 and 5-6-1

  Soup repeated = hexagon();
  repeated.polygons.push_back({0, 0, 4});
  EXPECT_EQ(certified(repeated)[0], 0);
}

// The counter's outward rounding of box sides steps like std::nextafter.
TEST(Inspect_issue_17, box_sides_step_like_nextafter)
{
  namespace I = mrepair::internal;
  std::vector<float> values = {0.f, -0.f, 1.f, -1.f, 1e-45f, -1e-45f, FLT_MIN, -FLT_MIN, FLT_MAX, -FLT_MAX,
                               HUGE_VALF, -HUGE_VALF, 3.14159f, -2.5e-30f, 7.5e30f};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 10000; ++i) values.push_back(static_cast<float>(u(rng) * std::pow(10., int(rng() % 70) - 35)));
  for (float x : values)
    for (bool up : {false, true}) {
      const float a = I::float_step(x, up), b = std::nextafter(x, up ? HUGE_VALF : -HUGE_VALF);
      EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << x << (up ? " up" : " down");
    }
}

// Issue 17: bucket_items sorts many items in two parallel passes (ranges of
// buckets, then buckets); the order is the one of a single stable pass:
// buckets in order, items increasing in each, skipped items left out, empty
// and crowded buckets alike.
TEST(Inspect_issue_17, bucket_items_in_two_passes_keeps_the_stable_order)
{
  namespace I = mrepair::internal;
  using T = I::Inspect_index;
  const std::size_t n = (std::size_t(1) << 20) + 12345, buckets = 300007;
  std::mt19937 rng(42);
  std::vector<T> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t x = rng();
    key[i] = x % 17 == 0 ? I::inspect_npos                        // skipped
             : x % 13 == 0 ? T(buckets - 1)                        // a crowded last bucket
             : T((x >> 8) % (buckets / 2) * 2);                    // odd buckets stay empty
  }
  std::vector<T> first, order;
  I::bucket_items(n, buckets, I::inspect_npos, [&](std::size_t i) { return key[i]; }, first, order);
  std::vector<std::vector<T>> expected(buckets);
  for (std::size_t i = 0; i < n; ++i)
    if (key[i] != I::inspect_npos) expected[key[i]].push_back(T(i));
  ASSERT_EQ(first.size(), buckets + 1);
  std::size_t total = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    ASSERT_EQ(first[b], total) << b;
    ASSERT_TRUE(std::equal(expected[b].begin(), expected[b].end(), order.begin() + first[b])) << b;
    total += expected[b].size();
  }
  EXPECT_EQ(first[buckets], total);
  EXPECT_EQ(order.size(), total);
  EXPECT_GT(expected[buckets - 1].size(), 50000u);
}

// ---- the spatial grid (internal/spatial_grid.h) ------------------------------

// points within the cell size of p are among the 27 cells around p's, which
// are visited in (dx, dy, dz) order with the ids of a cell ascending; a
// brute-force count of the same cells gives the same sequence.
TEST(Spatial_grid, near_query_visits_the_27_cells_in_order)
{
  namespace I = mrepair::internal;
  std::mt19937 rng(39);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<I::Vec3> P(3000);
  for (auto& p : P) p = I::Vec3{{u(rng), u(rng), 0.25 * u(rng)}};
  for (std::size_t i = 0; i < 200; ++i) P.push_back(P[i * 7]);  // coincident points
  const double r = 0.05;
  std::vector<std::uint32_t> ids;
  for (std::uint32_t i = P.size(); i-- > 0;)
    if (i % 5 != 0) ids.push_back(i);  // in no order, some left out
  const I::Spatial_grid<std::uint32_t> grid(r, ids, [&](std::uint32_t i) -> const I::Vec3& { return P[i]; });
  ASSERT_EQ(grid.entries().size(), ids.size());
  for (std::size_t k = 1; k < grid.entries().size(); ++k) {
    const auto &a = grid.entries()[k - 1], &b = grid.entries()[k];
    ASSERT_TRUE(a.c < b.c || (a.c == b.c && a.id < b.id));
  }
  std::vector<std::uint32_t> sorted_ids = ids;
  std::sort(sorted_ids.begin(), sorted_ids.end());
  std::size_t neighbours = 0;
  for (std::uint32_t q = 0; q < P.size(); q += 3) {
    const I::Grid_cell c = grid.cell_of(P[q]);
    std::vector<std::uint32_t> got, expected;
    grid.for_each_near(P[q], [&](std::uint32_t i) { got.push_back(i); });
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          for (std::uint32_t i : sorted_ids)
            if (grid.cell_of(P[i]) == I::Grid_cell{{c[0] + dx, c[1] + dy, c[2] + dz}}) expected.push_back(i);
    ASSERT_EQ(got, expected) << q;
    for (std::uint32_t i : sorted_ids)
      if (I::squared_norm(I::sub(P[i], P[q])) <= r * r) {
        ++neighbours;
        ASSERT_NE(std::find(got.begin(), got.end(), i), got.end()) << q << " " << i;
      }
  }
  EXPECT_GT(neighbours, 1000u);  // 1627: the check is not vacuous
}

// cells whose keys collide are told apart: a table of one key per cell and
// deliberately equal keys still finds each run.
TEST(Spatial_grid, cell_table_tells_colliding_keys_apart)
{
  namespace I = mrepair::internal;
  I::Cell_table t;
  t.reset(2);
  for (std::uint32_t v = 0; v < 100; ++v) t.insert(v % 3 == 0 ? 7 : 1000 + v, v);  // grows from 16 slots
  EXPECT_EQ(t.size(), 100u);
  for (std::uint32_t v = 0; v < 100; ++v)
    EXPECT_EQ(t.find(v % 3 == 0 ? 7 : 1000 + v, [v](std::uint32_t x) { return x == v; }), v);
  EXPECT_EQ(t.find(7, [](std::uint32_t x) { return x == 1; }), I::Cell_table::npos);
  EXPECT_EQ(t.find(5), I::Cell_table::npos);
  std::uint32_t& head = t.at(5);
  EXPECT_EQ(head, I::Cell_table::npos);
  head = 42;
  EXPECT_EQ(t.find(5), 42u);
  EXPECT_EQ(t.at(5), 42u);
  EXPECT_EQ(t.size(), 101u);
  // 21 bits an axis: cells 2^21 apart share a packed key, neighbours do not
  EXPECT_EQ(I::pack_cell(3, -1, 5), I::pack_cell(3 + (1 << 21), -1, 5));
  EXPECT_NE(I::pack_cell(3, -1, 5), I::pack_cell(3, 0, 5));
  EXPECT_NE(I::hash_cell({{3, -1, 5}}), I::hash_cell({{3, 0, 5}}));
}

// boxes entered in the cells they span: a box query returns each box whose
// cells meet the query's (each once per shared cell), as a scan over all does.
TEST(Spatial_grid, box_query_finds_the_boxes_sharing_a_cell)
{
  namespace I = mrepair::internal;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 10.0), s(0.0, 2.5);
  std::vector<I::Grid_box> boxes(400);
  for (auto& b : boxes) {
    const I::Vec3 p{{u(rng), u(rng), u(rng)}};
    b.add(p);
    b.add(I::Vec3{{p[0] + s(rng), p[1] + s(rng), p[2] + s(rng)}});
  }
  const double inverse_cell = 1.0;
  std::vector<I::Spatial_grid<std::uint32_t>::Entry> cells;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    I::Cell_range::of(boxes[i], inverse_cell).for_each([&](std::int64_t x, std::int64_t y, std::int64_t z) {
      cells.push_back({I::Grid_cell{{x, y, z}}, i});
    });
  const I::Spatial_grid<std::uint32_t> grid(cells);
  auto shared_cells = [&](const I::Cell_range& a, const I::Cell_range& b) {
    std::size_t n = 1;
    for (int d = 0; d < 3; ++d) {
      const std::int64_t lo = std::max(a.lo[d], b.lo[d]), hi = std::min(a.hi[d], b.hi[d]);
      n *= hi < lo ? 0 : std::size_t(hi - lo + 1);
    }
    return n;
  };
  for (std::size_t q = 0; q < 100; ++q) {
    I::Grid_box query;
    query.add(I::Vec3{{u(rng), u(rng), u(rng)}});
    query.add(I::Vec3{{u(rng), u(rng), u(rng)}});
    const I::Cell_range qc = I::Cell_range::of(query, inverse_cell);
    std::map<std::uint32_t, std::size_t> got;
    grid.for_each_in(qc, [&](std::uint32_t i) { ++got[i]; });
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
      const std::size_t n = shared_cells(qc, I::Cell_range::of(boxes[i], inverse_cell));
      EXPECT_EQ(got.count(i) ? got[i] : 0u, n) << q << " " << i;
      if (boxes[i].meets(query)) {
        EXPECT_GT(n, 0u);  // a meeting box shares a cell
      }
    }
  }
}

// ---------------------------------------------------------------------------
// compare_to_reference (issue 50, item 4): which input vertices an output still
// holds, on hand-made cases, typed over Surface_mesh and Polyhedron_3.

template <class C>
class Compare_to_reference : public ::testing::Test
{};
TYPED_TEST_SUITE(Compare_to_reference, Mesh_configs);

TYPED_TEST(Compare_to_reference, identical_output_keeps_every_vertex)
{
  using Mesh = typename TypeParam::Mesh;
  const Soup s = icosphere(2);
  const Mesh m = to_mesh<Mesh>(s);
  const mrepair::Reference_comparison r = mrepair::compare_to_reference(s.points, m);
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_EQ(r.vertices, s.points.size());
  EXPECT_EQ(r.vertices_lost, 0u);
  EXPECT_LE(r.max_distance, 1e-12);
  EXPECT_TRUE(r.inside_tested);
  EXPECT_NEAR(r.diagonal, 2 * std::sqrt(3.), 1e-9);
  EXPECT_NEAR(r.tolerance, 1e-6 * r.diagonal, 1e-15);
}

TYPED_TEST(Compare_to_reference, a_removed_part_is_lost_and_a_part_inside_is_not)
{
  using Mesh = typename TypeParam::Mesh;
  // output: a 4-unit cube; reference: that cube, a small cube inside it, a
  // small cube outside it
  const Soup big = cube(4.0);
  const Soup inner = translated(cube(1.0), 1.5, 1.5, 1.5);
  const Soup outer = translated(cube(1.0), 10, 0, 0);
  const Soup reference = merged(merged(big, inner), outer);
  const Mesh m = to_mesh<Mesh>(big);
  const mrepair::Reference_comparison r = mrepair::compare_to_reference(reference.points, m);
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_EQ(r.vertices, 24u);
  EXPECT_EQ(r.vertices_inside, 8u);  // the inner cube: absorbed, not lost
  EXPECT_EQ(r.vertices_lost, 8u);    // the outer cube: deleted
  ASSERT_EQ(r.lost.size(), 8u);
  for (std::size_t k = 0; k < 8; ++k) EXPECT_EQ(r.lost[k], 16 + k);
  // farthest: the outer cube's far corners, (11, 1, 1) and (11, 0, 0) from the face x = 4
  EXPECT_NEAR(r.max_distance, 7., 1e-9);
  EXPECT_NEAR(r.max_distance_relative, 7. / r.diagonal, 1e-12);
  // the soup overload reads the same output
  const mrepair::Reference_comparison q =
      mrepair::compare_to_reference(reference.points, big.points, big.polygons);
  EXPECT_EQ(q.vertices_lost, 8u);
  EXPECT_EQ(q.vertices_inside, 8u);
}

TYPED_TEST(Compare_to_reference, an_open_output_encloses_nothing)
{
  using Mesh = typename TypeParam::Mesh;
  // the cube without its top: the points inside are lost, the vertices on it kept
  const Soup open = cube(4.0);
  Soup top_removed;
  top_removed.points = open.points;
  for (const Polygon& p : open.polygons) {
    bool top = true;
    for (std::size_t i : p) top = top && open.points[i].z() == 4.0;
    if (!top) top_removed.polygons.push_back(p);
  }
  ASSERT_EQ(top_removed.polygons.size(), 10u);
  const Soup inner = translated(cube(1.0), 1.5, 1.5, 1.5);
  const Soup reference = merged(top_removed, inner);
  const Mesh m = to_mesh<Mesh>(top_removed);
  const mrepair::Reference_comparison r = mrepair::compare_to_reference(reference.points, m);
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_FALSE(r.inside_tested);
  EXPECT_EQ(r.vertices_inside, 0u);
  EXPECT_EQ(r.vertices_lost, 8u);
  // a closed part beside the open one is tested for inside, the open one not
  const Soup with_closed = merged(top_removed, translated(cube(1.0), 10, 0, 0));
  const Soup reference2 = merged(reference, translated(cube(0.25), 10.25, 0.25, 0.25));
  const Mesh m2 = to_mesh<Mesh>(with_closed);
  const mrepair::Reference_comparison r2 = mrepair::compare_to_reference(reference2.points, m2);
  EXPECT_TRUE(r2.inside_tested);
  EXPECT_EQ(r2.vertices_inside, 8u);  // inside the closed unit cube at x = 10
  EXPECT_EQ(r2.vertices_lost, 8u);    // inside the open box: lost
}

TYPED_TEST(Compare_to_reference, overlapping_shells_count_as_their_union_and_cavities_as_empty)
{
  using Mesh = typename TypeParam::Mesh;
  // two cubes that overlap (crossings left, as a repair may leave them): a
  // point in both is inside (a parity test would call it outside)
  const Soup two = merged(cube(2.0), translated(cube(2.0), 1, 1, 1));
  const std::vector<Point> in_both = {Point(1.5, 1.5, 1.5), Point(1.2, 1.7, 1.9)};
  const std::vector<Point> in_one = {Point(0.5, 0.5, 0.5), Point(2.5, 2.5, 2.5)};
  const std::vector<Point> outside = {Point(2.5, 0.5, 0.5), Point(-1, 1, 1)};
  const Mesh m = to_mesh<Mesh>(two);
  for (const auto& set : {in_both, in_one}) {
    const mrepair::Reference_comparison r = mrepair::compare_to_reference(set, m);
    EXPECT_EQ(r.vertices_lost, 0u);
    EXPECT_EQ(r.vertices_inside, 2u);
  }
  EXPECT_EQ(mrepair::compare_to_reference(outside, m).vertices_lost, 2u);
  // a cavity: the inner cube turned inward; a point in it is outside the solid
  Soup inner = translated(cube(1.0), 1.5, 1.5, 1.5);
  for (Polygon& p : inner.polygons) std::reverse(p.begin(), p.end());
  const Mesh hollow = to_mesh<Mesh>(merged(cube(4.0), inner));
  const std::vector<Point> probes = {Point(2, 2, 2), Point(0.5, 3, 1)};  // in the cavity, in the wall
  const mrepair::Reference_comparison r = mrepair::compare_to_reference(probes, hollow);
  EXPECT_EQ(r.lost, std::vector<std::size_t>{0});
  EXPECT_EQ(r.vertices_inside, 1u);
  // on axis-aligned faces, through edges and corners: the rays avoid them
  std::vector<Point> grid_points;
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j) grid_points.emplace_back(0.5 * i, 0.5 * j, 0.5);
  const Mesh box = to_mesh<Mesh>(translated(cube(4.0), 0, 0, 0));
  const mrepair::Reference_comparison g = mrepair::compare_to_reference(grid_points, box);
  EXPECT_EQ(g.vertices_lost, 0u);  // on the walls (distance 0) or inside
}

TYPED_TEST(Compare_to_reference, tolerance_is_respected)
{
  using Mesh = typename TypeParam::Mesh;
  const Soup g = grid(4, 4);  // a sheet: only the distance counts
  const Mesh m = to_mesh<Mesh>(g);
  // one vertex lifted by 0.01, one by 0.1, one pushed below by 0.05
  std::vector<Point> reference = g.points;
  reference[6] = Point(reference[6].x(), reference[6].y(), 0.01);
  reference[12] = Point(reference[12].x(), reference[12].y(), 0.1);
  reference[18] = Point(reference[18].x(), reference[18].y(), -0.05);
  const double diagonal = std::sqrt(32. + 0.15 * 0.15);
  // default: 1e-6 x diagonal, all three lost
  mrepair::Reference_comparison r = mrepair::compare_to_reference(reference, m);
  EXPECT_NEAR(r.diagonal, diagonal, 1e-12);
  EXPECT_EQ(r.vertices_lost, 3u);
  EXPECT_NEAR(r.max_distance, 0.1, 1e-12);
  // 0.06 keeps the first and the last
  r = mrepair::compare_to_reference(reference, m, MP::reference_tolerance(0.06));
  EXPECT_EQ(r.vertices_lost, 1u);
  EXPECT_EQ(r.lost, std::vector<std::size_t>{12});
  r = mrepair::compare_to_reference(reference, m, MP::reference_tolerance(std::optional<double>(0.2)));
  EXPECT_EQ(r.vertices_lost, 0u);
  // an empty optional is the default
  r = mrepair::compare_to_reference(reference, m, MP::reference_tolerance(std::optional<double>()));
  EXPECT_EQ(r.vertices_lost, 3u);
  // the sequential run gives the same figures
  const mrepair::Reference_comparison seq = mrepair::compare_to_reference<CGAL::Sequential_tag>(reference, m);
  EXPECT_EQ(seq.lost, std::vector<std::size_t>({6, 12, 18}));
  EXPECT_EQ(seq.max_distance, r.max_distance);
}

TYPED_TEST(Compare_to_reference, bad_input_gets_a_status)
{
  using Mesh = typename TypeParam::Mesh;
  const Soup c = cube(1.0);
  const Mesh m = to_mesh<Mesh>(c);
  EXPECT_EQ(mrepair::compare_to_reference(std::vector<Point>(), m).status, Status::empty_input);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Point> with_nan = c.points;
  with_nan.emplace_back(nan, 0, 0);
  mrepair::Reference_comparison r = mrepair::compare_to_reference(with_nan, m);
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_EQ(r.vertices, 8u);
  EXPECT_EQ(r.vertices_skipped, 1u);
  EXPECT_EQ(r.vertices_lost, 0u);
  EXPECT_EQ(mrepair::compare_to_reference(std::vector<Point>(1, Point(nan, nan, nan)), m).status,
            Status::empty_input);
  EXPECT_EQ(mrepair::compare_to_reference(c.points, m, MP::reference_tolerance(-1.)).status,
            Status::invalid_parameter);
  EXPECT_EQ(mrepair::compare_to_reference(c.points, m, MP::reference_tolerance(nan)).status,
            Status::invalid_parameter);
  // an output without faces loses everything
  r = mrepair::compare_to_reference(c.points, Mesh());
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_EQ(r.vertices_lost, 8u);
  EXPECT_TRUE(std::isinf(r.max_distance));
  // a quad mesh is not a triangle mesh; its soup is read as fans
  const Soup quads = cube(1.0, true);
  const Mesh q = to_mesh<Mesh>(quads);
  EXPECT_EQ(mrepair::compare_to_reference(c.points, q).status, Status::invalid_mesh);
  r = mrepair::compare_to_reference(c.points, quads.points, quads.polygons);
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_EQ(r.vertices_lost, 0u);
  EXPECT_TRUE(r.inside_tested);
  // an out-of-range index
  Soup broken = c;
  broken.polygons[0][0] = 99;
  EXPECT_EQ(mrepair::compare_to_reference(c.points, broken.points, broken.polygons).status,
            Status::invalid_index);
  // a non-finite output point
  Soup nan_out = c;
  nan_out.points[0] = Point(nan, 0, 0);
  EXPECT_EQ(mrepair::compare_to_reference(c.points, nan_out.points, nan_out.polygons).status,
            Status::non_finite_input);
}

} // namespace inspect_tests
} // namespace
