// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Scan cleaning I: geometric statistics, near-degenerate faces, spike relaxation,
// unrelaxable spikes. Typed over Surface_mesh and Polyhedron_3.
#include "fixtures.h"

#include <mrepair/geometric_statistics.h>
#include <mrepair/relax_spikes.h>
#include <mrepair/repair_near_degenerate_faces.h>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>

#include <tbb/global_control.h>

#include <atomic>
#include <mutex>
#include <random>
#include <set>
#include <thread>
#include <type_traits>

// A namespace of its own: this file is compiled in one translation unit with
// other test files (a unity build, CMakeLists.txt).
namespace {
namespace scan_clean_tests {

using namespace mrepair_test;

namespace {

template <class Mesh>
using Stats = mrepair::Geometric_statistics<Mesh>;

// Compares locally maintained statistics with a fresh global computation.
template <class Mesh>
::testing::AssertionResult stats_equal_fresh(Mesh& m, const Stats<Mesh>& st)
{
  Stats<Mesh> fresh(m);
  fresh.compute_all();
  const double tol = 1e-12;
  for (auto f : faces(m)) {
    const auto& a = st.face_stats(f);
    const auto& b = fresh.face_stats(f);
    if (std::abs(a.area - b.area) > tol || std::abs(a.min_angle - b.min_angle) > tol)
      return ::testing::AssertionFailure() << "face area/min angle differ";
    for (int i = 0; i < 3; ++i)
      if (std::abs(a.normal[i] - b.normal[i]) > tol)
        return ::testing::AssertionFailure() << "face normal differs";
  }
  for (auto h : halfedges(m)) {
    const auto& a = st.halfedge_stats(h);
    const auto& b = fresh.halfedge_stats(h);
    if (std::abs(a.opposite_angle - b.opposite_angle) > tol)
      return ::testing::AssertionFailure() << "opposite angle differs";
    if (std::abs(a.length - b.length) > tol || std::abs(a.dihedral - b.dihedral) > tol)
      return ::testing::AssertionFailure() << "edge length/dihedral differ";
  }
  for (auto v : vertices(m)) {
    const auto& a = st.vertex_stats(v);
    const auto& b = fresh.vertex_stats(v);
    if (a.valence != b.valence) return ::testing::AssertionFailure() << "valence differs";
    if (std::abs(a.mean_edge_length - b.mean_edge_length) > tol ||
        std::abs(a.max_dihedral - b.max_dihedral) > tol)
      return ::testing::AssertionFailure() << "vertex mean length/max dihedral differ";
  }
  if (st.edge_count() != fresh.edge_count() || st.edge_count() != edges(m).size())
    return ::testing::AssertionFailure() << "edge count " << st.edge_count() << " vs "
                                         << fresh.edge_count();
  if (std::abs(st.global_mean_edge_length() - fresh.global_mean_edge_length()) >
      1e-9 * fresh.global_mean_edge_length())
    return ::testing::AssertionFailure() << "global mean " << st.global_mean_edge_length()
                                         << " vs " << fresh.global_mean_edge_length();
  return ::testing::AssertionSuccess();
}

// Every stored value of `a` and `b` bit for bit, and the global sum.
template <class Mesh, class StatsA, class StatsB>
::testing::AssertionResult stats_identical(const Mesh& m, const StatsA& a, const StatsB& b)
{
  for (auto f : faces(m)) {
    const auto& x = a.face_stats(f);
    const auto& y = b.face_stats(f);
    if (x.area != y.area || x.min_angle != y.min_angle || x.normal != y.normal)
      return ::testing::AssertionFailure() << "face statistics differ";
  }
  for (auto h : halfedges(m)) {
    const auto& x = a.halfedge_stats(h);
    const auto& y = b.halfedge_stats(h);
    if (x.opposite_angle != y.opposite_angle || x.length != y.length || x.dihedral != y.dihedral)
      return ::testing::AssertionFailure() << "halfedge statistics differ";
  }
  for (auto v : vertices(m)) {
    const auto& x = a.vertex_stats(v);
    const auto& y = b.vertex_stats(v);
    if (x.valence != y.valence || x.mean_edge_length != y.mean_edge_length ||
        x.max_dihedral != y.max_dihedral)
      return ::testing::AssertionFailure() << "vertex statistics differ";
  }
  if (a.edge_count() != b.edge_count() || a.edge_length_sum() != b.edge_length_sum())
    return ::testing::AssertionFailure() << "sum " << a.edge_length_sum() << " vs "
                                         << b.edge_length_sum();
  return ::testing::AssertionSuccess();
}

// The mesh's point map, recording which threads read it: shows whether
// `compute_all()` really ran on several threads.
std::atomic<unsigned> recording_run{0};

template <class Mesh>
struct Thread_recording_map
{
  using Base = typename boost::property_map<Mesh, CGAL::vertex_point_t>::const_type;
  using key_type = typename boost::property_traits<Base>::key_type;
  using value_type = typename boost::property_traits<Base>::value_type;
  using reference = value_type;
  using category = boost::readable_property_map_tag;

  struct Threads
  {
    std::mutex mutex;
    std::set<std::thread::id> ids;
  };

  Base base;
  std::shared_ptr<Threads> threads = std::make_shared<Threads>();
  unsigned run = ++recording_run;

  std::size_t thread_count() const
  {
    std::lock_guard<std::mutex> lock(threads->mutex);
    return threads->ids.size();
  }

  friend value_type get(const Thread_recording_map& m, key_type k)
  {
    thread_local unsigned recorded = 0;  // the last run this thread was recorded in
    if (recorded != m.run) {
      std::lock_guard<std::mutex> lock(m.threads->mutex);
      m.threads->ids.insert(std::this_thread::get_id());
      recorded = m.run;
    }
    return get(m.base, k);
  }
};

// Random flips, splits, collapses and moves, each followed by the local update.
template <class Mesh>
void random_edits(Mesh& m, unsigned seed, int steps)
{
  using GT = boost::graph_traits<Mesh>;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;
  using vertex_descriptor = typename GT::vertex_descriptor;
  auto vpm = get(CGAL::vertex_point, m);
  Stats<Mesh> st(m);
  st.compute_all();
  ASSERT_TRUE(stats_equal_fresh(m, st));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  int done[4] = {0, 0, 0, 0};
  for (int step = 0; step < steps; ++step) {
    std::vector<edge_descriptor> es(edges(m).begin(), edges(m).end());
    edge_descriptor e = es[rng() % es.size()];
    halfedge_descriptor h = halfedge(e, m);
    const int op = static_cast<int>(rng() % 4);
    if (op == 0) { // vertex move
      vertex_descriptor v = target(h, m);
      auto p = get(vpm, v);
      st.before_vertex_move(v);
      put(vpm, v, Point(p.x() + jitter(rng), p.y() + jitter(rng), p.z() + jitter(rng)));
      st.after_vertex_move(v);
    } else if (op == 1) { // flip
      if (is_border_edge(h, m)) continue;
      vertex_descriptor c = target(next(h, m), m), d = target(next(opposite(h, m), m), m);
      if (c == d || halfedge(c, d, m).second || degree(source(h, m), m) < 4 ||
          degree(target(h, m), m) < 4)
        continue;
      st.before_edge_flip(e);
      CGAL::Euler::flip_edge(h, m);
      st.after_edge_flip(e);
    } else if (op == 2) { // split + triangulate both sides
      auto ps = get(vpm, source(h, m)), pt = get(vpm, target(h, m));
      st.before_edge_split(e);
      halfedge_descriptor hn = CGAL::Euler::split_edge(h, m);
      vertex_descriptor v = target(hn, m);
      put(vpm, v, CGAL::midpoint(ps, pt));
      if (!is_border(hn, m)) CGAL::Euler::split_face(hn, next(h, m), m);
      halfedge_descriptor oh = opposite(h, m), ohn = opposite(hn, m);
      if (!is_border(oh, m)) CGAL::Euler::split_face(oh, next(ohn, m), m);
      st.after_edge_split(v);
    } else { // collapse
      if (faces(m).size() < 30 || !CGAL::Euler::does_satisfy_link_condition(e, m)) continue;
      auto mid = CGAL::midpoint(get(vpm, source(h, m)), get(vpm, target(h, m)));
      st.before_edge_collapse(e);
      vertex_descriptor v = CGAL::Euler::collapse_edge(e, m);
      put(vpm, v, mid);
      st.after_edge_collapse(v);
    }
    ++done[op];
    ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
    if (step % 25 == 0) {
      ASSERT_TRUE(stats_equal_fresh(m, st)) << "step " << step;
    }
  }
  ASSERT_TRUE(stats_equal_fresh(m, st));
  for (int i = 0; i < 4; ++i) EXPECT_GT(done[i], steps / 10) << "op " << i;
}

template <class Mesh>
typename boost::graph_traits<Mesh>::vertex_descriptor find_vertex(const Mesh& m, double x, double y,
                                                                  double z = 0)
{
  for (auto v : vertices(m)) {
    auto p = get(CGAL::vertex_point, m, v);
    if (std::abs(p.x() - x) < 1e-9 && std::abs(p.y() - y) < 1e-9 && std::abs(p.z() - z) < 1e-9)
      return v;
  }
  ADD_FAILURE() << "no vertex at " << x << " " << y << " " << z;
  return boost::graph_traits<Mesh>::null_vertex();
}

// Splits edge (a,b) at point p and triangulates both sides; returns the new vertex.
template <class Mesh>
typename boost::graph_traits<Mesh>::vertex_descriptor
insert_on_edge(Mesh& m, typename boost::graph_traits<Mesh>::vertex_descriptor a,
               typename boost::graph_traits<Mesh>::vertex_descriptor b, const Point& p)
{
  auto hb = halfedge(a, b, m);
  EXPECT_TRUE(hb.second);
  auto h = hb.first; // a -> b
  auto hn = CGAL::Euler::split_edge(h, m); // hn: a -> v, next(hn) == h
  auto v = target(hn, m);
  put(get(CGAL::vertex_point, m), v, p);
  if (!is_border(hn, m)) CGAL::Euler::split_face(hn, next(h, m), m);
  auto oh = opposite(h, m), ohn = opposite(hn, m);
  if (!is_border(oh, m)) CGAL::Euler::split_face(oh, next(ohn, m), m);
  return v;
}

// No vertex with two fans (two border halfedges around it).
template <class Mesh>
bool no_pinched_vertices(const Mesh& m)
{
  for (auto v : vertices(m)) {
    int b = 0;
    for (auto h : CGAL::halfedges_around_target(v, m)) b += is_border(h, m);
    if (b > 1) return false;
  }
  return true;
}

template <class Mesh>
std::size_t border_halfedge_count(const Mesh& m)
{
  std::size_t n = 0;
  for (auto h : halfedges(m)) n += is_border(h, m);
  return n;
}

template <class Mesh>
std::size_t component_count(const Mesh& m)
{
  auto fcc = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  return CGAL::Polygon_mesh_processing::connected_components(m, fcc);
}

// Builds a mesh from a soup, orienting it first.
template <class Mesh>
Mesh oriented_mesh(Soup s)
{
  CGAL::Polygon_mesh_processing::orient_polygon_soup(s.points, s.polygons);
  return to_mesh<Mesh>(s);
}

// Two parallel 6x6 grids at z = 0 and z = gap, each without the triangle
// (2,2)(3,2)(3,3), joined by a triangular tube through those holes: a micro tunnel.
inline Soup micro_tunnel_soup(double gap)
{
  Soup a = grid(6, 6), s;
  const std::size_t n = a.points.size();
  for (const Point& p : a.points) s.points.push_back(p);
  for (const Point& p : a.points) s.points.emplace_back(p.x(), p.y(), gap);
  const std::size_t i0 = 2 * 7 + 2, i1 = 2 * 7 + 3, i2 = 3 * 7 + 3;
  for (const Polygon& f : a.polygons) {
    if (f[0] == i0 && f[1] == i1 && f[2] == i2) continue;
    s.polygons.push_back(f);
    s.polygons.push_back({f[0] + n, f[2] + n, f[1] + n});
  }
  const std::size_t r[3] = {i0, i1, i2};
  for (int k = 0; k < 3; ++k) {
    std::size_t x = r[k], y = r[(k + 1) % 3];
    s.polygons.push_back({x, y, y + n});
    s.polygons.push_back({x, y + n, x + n});
  }
  return s;
}

struct Stop_visitor : mrepair::Default_visitor
{
  int polls = 0;
  bool stop_requested() { return ++polls > 0; }
};

template <class Mesh>
double max_abs_z(const Mesh& m)
{
  double z = 0;
  for (auto v : vertices(m)) z = (std::max)(z, std::abs(get(CGAL::vertex_point, m, v).z()));
  return z;
}

} // namespace

template <class C>
class Scan_clean : public ::testing::Test
{};
TYPED_TEST_SUITE(Scan_clean, Mesh_configs);

TYPED_TEST(Scan_clean, statistics_hand_values)
{
  using Mesh = typename TypeParam::Mesh;
  // two right triangles (0,0)(1,0)(1,1) and (0,0)(1,1)(0,1) folded by 90 degrees about the diagonal? no: flat
  Mesh m = to_mesh<Mesh>(grid(1, 1));
  Stats<Mesh> st(m);
  st.compute_all();
  const double pi = std::acos(-1.);
  for (auto f : faces(m)) {
    EXPECT_NEAR(st.area(f), 0.5, 1e-15);
    EXPECT_NEAR(st.min_angle(f), pi / 4, 1e-15);
    EXPECT_NEAR(st.normal(f)[2], 1.0, 1e-15);
  }
  for (auto e : edges(m)) EXPECT_NEAR(st.dihedral(e), 0., 1e-15);
  EXPECT_EQ(st.edge_count(), 5u);
  EXPECT_NEAR(st.global_mean_edge_length(), (4 + std::sqrt(2.)) / 5, 1e-15);
  // fold the square: lift corner (1,0) so that the two faces meet at 90 degrees
  Mesh c = to_mesh<Mesh>(cube());
  Stats<Mesh> sc(c);
  sc.compute_all();
  std::size_t right = 0, flat = 0;
  for (auto e : edges(c)) {
    if (std::abs(sc.dihedral(e) - pi / 2) < 1e-12) ++right;
    if (std::abs(sc.dihedral(e)) < 1e-12) ++flat;
  }
  EXPECT_EQ(right, 12u); // cube edges
  EXPECT_EQ(flat, 6u);   // face diagonals
  for (auto v : vertices(c)) EXPECT_NEAR(sc.max_dihedral(v), pi / 2, 1e-12);
}

// compute_all() runs its face, edge and vertex loops with TBB on a
// Surface_mesh above 20,000 elements (never on Polyhedron_3, whose dynamic
// maps are hash maps). Checked against references computed here, not against
// another run of the same code: the sum of the edge lengths equals an
// independent sum, each face area the half cross product; and the parallel
// runs, with 1, 2 and 4 threads allowed, store bit for bit what the
// sequential run stores (no race, no order dependence), on as many threads as
// the mesh type promises.
TYPED_TEST(Scan_clean, statistics_parallel_equals_sequential)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(icosphere(6)); // 81920 faces: above the parallel threshold
  Stats<Mesh> seq(m);
  seq.set_parallel(false);
  seq.compute_all();

  // independent references: long double sums over edges and faces, in the mesh's edge order
  auto vpm = get(CGAL::vertex_point, m);
  long double length_sum = 0;
  std::size_t n_edges = 0;
  for (auto e : edges(m)) {
    length_sum += std::sqrt(static_cast<long double>(
        CGAL::squared_distance(get(vpm, source(e, m)), get(vpm, target(e, m)))));
    ++n_edges;
  }
  ASSERT_EQ(n_edges, 122880u);
  EXPECT_EQ(seq.edge_count(), n_edges);
  // (a double sum of 122,880 terms is within 1e-11 of the exact one; a missing
  // or doubled edge would be off by 1e-5)
  EXPECT_NEAR(seq.edge_length_sum(), static_cast<double>(length_sum), 1e-10 * length_sum);
  EXPECT_NEAR(seq.global_mean_edge_length(), static_cast<double>(length_sum / n_edges),
              1e-10 * static_cast<double>(length_sum / n_edges));
  long double area_sum = 0;
  for (auto f : faces(m)) {
    auto h = halfedge(f, m);
    const Point a = get(vpm, source(h, m)), b = get(vpm, target(h, m)),
                c = get(vpm, target(next(h, m), m));
    const double area = 0.5 * std::sqrt(CGAL::cross_product(b - a, c - a).squared_length());
    EXPECT_NEAR(seq.area(f), area, 1e-12 * area);
    area_sum += area;
  }
  // an icosphere inscribed in the unit sphere: a little under 4 pi
  EXPECT_GT(area_sum, 4 * 3.14159265358979 * 0.999);
  EXPECT_LT(area_sum, 4 * 3.14159265358979);

  constexpr bool parallel_mesh = std::is_same<Mesh, Surface_mesh>::value;
  for (int threads : {1, 2, 4}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::size_t most_threads = 0;
    // a loaded machine may finish before a worker joins: retry a few times
    for (int attempt = 0; attempt < 20; ++attempt) {
      Thread_recording_map<Mesh> recording{get(CGAL::vertex_point, m)};
      mrepair::Geometric_statistics<Mesh, Thread_recording_map<Mesh>> par(m, recording);
      par.compute_all();
      ASSERT_TRUE(stats_identical(m, par, seq)) << threads << " threads";
      most_threads = (std::max)(most_threads, recording.thread_count());
      if (!parallel_mesh || threads == 1 || most_threads > 1) break;
    }
    if (!parallel_mesh || threads == 1) {
      EXPECT_EQ(most_threads, 1u) << threads << " threads allowed";
    } else if (std::thread::hardware_concurrency() > 1) {
      EXPECT_GT(most_threads, 1u) << threads << " threads allowed: compute_all ran sequentially";
    }
  }
}

TYPED_TEST(Scan_clean, statistics_local_updates_match_global)
{
  using Mesh = typename TypeParam::Mesh;
  {
    Mesh m = to_mesh<Mesh>(icosphere(3));
    random_edits(m, 7u, 600);
  }
  {
    Mesh m = to_mesh<Mesh>(grid(12, 12));
    random_edits(m, 11u, 600);
  }
}

namespace MP = mrepair::parameters;

TYPED_TEST(Scan_clean, needle_pair_is_collapsed)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(8, 8));
  // a vertex 0.01 from (4,4) on the edge (4,4)-(5,4): two needles with a zero edge
  insert_on_edge(m, find_vertex(m, 4, 4), find_vertex(m, 5, 4), Point(4.01, 4, 0));
  ASSERT_EQ(face_count(m), 130u);
  Stats<Mesh> st(m);
  st.compute_all();
  auto r = mrepair::repair_near_degenerate_faces(m, st);
  EXPECT_EQ(r.status, mrepair::Status::ok) << r.message;
  EXPECT_EQ(r.near_degenerate_faces_before, 2u);
  EXPECT_EQ(r.near_degenerate_faces_after, 0u);
  EXPECT_EQ(r.edges_collapsed, 1u);
  EXPECT_EQ(face_count(m), 128u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(stats_equal_fresh(m, st));
  mrepair::Report rep;
  r.to_report(rep);
  EXPECT_NE(rep.to_json().find("edges_collapsed"), std::string::npos);
}

TYPED_TEST(Scan_clean, sliver_fan_is_repaired)
{
  using Mesh = typename TypeParam::Mesh;
  // apexes v=(0,0) and q=(2,0); 21 points on x = 1, 0.05 apart: 40 slivers (2.9 degrees)
  Soup s;
  s.points.emplace_back(0, 0, 0);
  s.points.emplace_back(2, 0, 0);
  for (int i = 0; i <= 20; ++i) s.points.emplace_back(1, -0.5 + 0.05 * i, 0);
  for (std::size_t i = 0; i < 20; ++i) {
    s.polygons.push_back({0, 2 + i, 3 + i});
    s.polygons.push_back({1, 3 + i, 2 + i});
  }
  Mesh m = to_mesh<Mesh>(s);
  Stats<Mesh> st(m);
  st.compute_all();
  auto r = mrepair::repair_near_degenerate_faces(m, st);
  EXPECT_EQ(r.near_degenerate_faces_before, 40u);
  EXPECT_EQ(r.near_degenerate_faces_after, 0u) << r.message;
  EXPECT_EQ(r.status, mrepair::Status::ok);
  EXPECT_GT(r.edges_collapsed, 10u);
  EXPECT_EQ(face_count(m), 40u - 2 * r.edges_collapsed);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(stats_equal_fresh(m, st));
  // the boundary (diamond v, p0, q, p20) is unchanged: 4 border edges
  EXPECT_EQ(border_halfedge_count(m), 4u);
  for (auto f : faces(m)) EXPECT_GT(st.min_angle(f), mrepair::internal::to_radians(5));
}

TYPED_TEST(Scan_clean, needle_next_to_boundary_keeps_boundary)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(6, 6));
  // x = (3, 0.01) on edge (3,0)-(3,1); (3,0) is on the boundary
  insert_on_edge(m, find_vertex(m, 3, 0), find_vertex(m, 3, 1), Point(3, 0.01, 0));
  const std::size_t border_before = border_halfedge_count(m);
  auto r = mrepair::repair_near_degenerate_faces(m);
  EXPECT_EQ(r.status, mrepair::Status::ok) << r.message;
  EXPECT_EQ(r.edges_collapsed, 1u);
  EXPECT_EQ(face_count(m), 72u);
  EXPECT_EQ(border_halfedge_count(m), border_before);
  // collapsed onto the boundary vertex, which did not move
  find_vertex(m, 3, 0);
  for (auto v : vertices(m)) EXPECT_GT(std::abs(get(CGAL::vertex_point, m, v).y() - 0.01), 1e-6);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
}

TYPED_TEST(Scan_clean, cap_is_repaired)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(8, 8));
  // (4,4) moved to 0.1 from the middle of the short edge... build a cap: a vertex
  // almost on the edge (5,4)-(5,5) close to (5,4): angle ~ 170 degrees at it
  auto v = find_vertex(m, 4, 4);
  put(get(CGAL::vertex_point, m), v, Point(4.97, 4.12, 0));
  Stats<Mesh> st(m);
  st.compute_all();
  auto r = mrepair::repair_near_degenerate_faces(m, st);
  EXPECT_GE(r.near_degenerate_faces_before, 1u);
  EXPECT_EQ(r.near_degenerate_faces_after, 0u);
  EXPECT_GE(r.edges_collapsed + r.edges_flipped, 1u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(stats_equal_fresh(m, st));
  for (auto f : faces(m)) EXPECT_GT(st.normal(f)[2], 0.99); // nothing folded
}

TYPED_TEST(Scan_clean, flip_fallback_when_collapse_would_pinch_boundary)
{
  using Mesh = typename TypeParam::Mesh;
  // a 6x1 strip; the top vertex (3,1) pulled down to (3,0.05): the edge to (3,0)
  // is a zero edge joining two boundary vertices through the interior, so no
  // collapse is allowed. Its face (3,0),(4,1),T has a 133.5 degree angle at T
  // (a cap, min angle 1.5): flipping (3,0)-(4,1) to T-(4,0) raises the min angle to 2.9.
  Mesh m = to_mesh<Mesh>(grid(6, 1));
  auto t = find_vertex(m, 3, 1);
  put(get(CGAL::vertex_point, m), t, Point(3, 0.05, 0));
  Stats<Mesh> st(m);
  st.compute_all();
  auto r = mrepair::repair_near_degenerate_faces(m, st);
  EXPECT_EQ(r.status, mrepair::Status::partial);
  EXPECT_EQ(r.near_degenerate_faces_before, 2u);
  EXPECT_EQ(r.collapsible_edges_initial, 1u);
  EXPECT_EQ(r.edges_collapsed, 0u);
  EXPECT_EQ(r.edges_flipped, 1u);
  EXPECT_EQ(r.rejected_boundary, 1u);
  EXPECT_EQ(r.near_degenerate_faces_after, 2u); // the zero edge stays: both its ends are on the boundary
  EXPECT_TRUE(halfedge(t, find_vertex(m, 4, 0), m).second); // the flipped edge
  EXPECT_FALSE(halfedge(find_vertex(m, 3, 0), find_vertex(m, 4, 1), m).second);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(stats_equal_fresh(m, st));
  for (auto f : faces(m)) EXPECT_GT(st.normal(f)[2], 0.99);
}

TYPED_TEST(Scan_clean, spike_on_plane_relaxes_into_plane)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(10, 10));
  auto v = find_vertex(m, 5, 5);
  put(get(CGAL::vertex_point, m), v, Point(5, 5, 1.5));
  Stats<Mesh> st(m);
  st.compute_all();
  auto r = mrepair::relax_spikes(m, st, MP::spike_angle(60.0));
  EXPECT_EQ(r.status, mrepair::Status::ok) << r.message;
  EXPECT_GE(r.spiked_vertices_before, 1u);
  EXPECT_EQ(r.spiked_vertices_after, 0u);
  EXPECT_LT(max_abs_z(m), 1e-9);
  auto p = get(CGAL::vertex_point, m, v);
  EXPECT_NEAR(p.x(), 5, 1e-9);
  EXPECT_NEAR(p.y(), 5, 1e-9);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(stats_equal_fresh(m, st));
}

TYPED_TEST(Scan_clean, tall_narrow_spike_found_with_defaults)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(20, 20));
  auto v = find_vertex(m, 10, 10);
  put(get(CGAL::vertex_point, m), v, Point(10, 10, 6.0)); // 6 mean edge lengths up
  {
    Stats<Mesh> st(m);
    st.compute_all();
    double maxd = 0;
    for (auto e : edges(m)) maxd = (std::max)(maxd, st.dihedral(e));
    EXPECT_LT(maxd, mrepair::internal::to_radians(90)); // the dihedral test misses it
  }
  {
    Mesh c = m; // without the second criterion nothing is found
    auto r = mrepair::relax_spikes(c, MP::spike_height_factor(0.0));
    EXPECT_EQ(r.spiked_vertices_before, 0u);
  }
  auto r = mrepair::relax_spikes(m);
  EXPECT_EQ(r.status, mrepair::Status::ok) << r.message;
  EXPECT_EQ(r.spiked_vertices_before, 1u);
  EXPECT_EQ(r.spiked_by_height_before, 1u);
  EXPECT_EQ(r.spiked_vertices_after, 0u);
  EXPECT_LT(max_abs_z(m), 1e-9);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  // clean meshes: no spike with the defaults
  Mesh ico = to_mesh<Mesh>(icosphere(3));
  EXPECT_EQ(mrepair::relax_spikes(ico).spiked_vertices_before, 0u);
  Mesh cu = to_mesh<Mesh>(cube());
  EXPECT_EQ(mrepair::relax_spikes(cu).spiked_vertices_before, 0u);
}

// Issue 17: after each round the relaxation retests only the vertices of the
// working region next to a moved vertex; its counts must still be those of a
// fresh detection over the whole mesh, also when spikes are left.
TYPED_TEST(Scan_clean, relaxation_counts_match_a_fresh_detection)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(60, 60));
  auto vpm = get(CGAL::vertex_point, m);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> noise(-0.05, 0.05), tall(-4.0, 4.0);
  for (auto v : vertices(m)) {
    const Point p = get(vpm, v);
    put(vpm, v, Point(p.x(), p.y(), rng() % 5 == 0 ? tall(rng) : noise(rng)));
  }
  Stats<Mesh> st(m);
  st.compute_all();
  // one round leaves spikes; after it only part of W was tested again
  const auto r = mrepair::relax_spikes(m, st, MP::max_relax_iterations(1));
  EXPECT_GT(r.spiked_vertices_before, 200u);
  EXPECT_EQ(r.iterations, 1u);
  EXPECT_GT(r.spiked_vertices_after, 0u);
  Mesh copy = m;
  EXPECT_EQ(mrepair::relax_spikes(copy).spiked_vertices_before, r.spiked_vertices_after);
  EXPECT_EQ(r.spiked_in_region_after, r.spiked_vertices_after); // the region holds every spike
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(stats_equal_fresh(m, st));
}

TYPED_TEST(Scan_clean, foldover_is_unfolded)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(10, 10));
  auto v = find_vertex(m, 5, 5);
  put(get(CGAL::vertex_point, m), v, Point(6.4, 5.3, 0)); // beyond its neighbour (6,5)
  Stats<Mesh> st(m);
  st.compute_all();
  std::size_t flipped = 0;
  for (auto f : faces(m)) flipped += st.normal(f)[2] < 0;
  ASSERT_GE(flipped, 1u);
  auto r = mrepair::relax_spikes(m, st);
  EXPECT_EQ(r.status, mrepair::Status::ok) << r.message;
  EXPECT_GE(r.spiked_vertices_before, 1u);
  EXPECT_EQ(r.spiked_vertices_after, 0u);
  for (auto f : faces(m)) EXPECT_GT(st.normal(f)[2], 0.99);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(stats_equal_fresh(m, st));
}

TYPED_TEST(Scan_clean, micro_tunnel_is_removed)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = oriented_mesh<Mesh>(micro_tunnel_soup(0.2));
  ASSERT_EQ(face_count(m), 148u);
  ASSERT_EQ(component_count(m), 1u);
  Stats<Mesh> st(m);
  st.compute_all();
  auto np = MP::spike_angle(80.0);
  auto rr = mrepair::relax_spikes(m, st, np);
  EXPECT_EQ(rr.status, mrepair::Status::partial); // a tube does not relax
  EXPECT_GE(rr.spiked_in_region_after, 4u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(stats_equal_fresh(m, st));
  auto r = mrepair::remove_unrelaxable_spikes(m, st, np);
  EXPECT_EQ(r.status, mrepair::Status::ok) << r.message;
  EXPECT_EQ(r.spiked_vertices_after, 0u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(no_pinched_vertices(m));
  EXPECT_TRUE(stats_equal_fresh(m, st));
  EXPECT_EQ(component_count(m), 2u); // the two sheets, no tube
  EXPECT_EQ(r.boundary_loops, 2u);   // one hole in each sheet
  // the 6 rim vertices go with the 6 tube faces and 12 faces of each sheet
  // (5 faces left around each of the 3 rim vertices of a sheet, 3 shared)
  EXPECT_EQ(r.vertices_removed, 6u);
  EXPECT_EQ(r.faces_removed, 30u);
  EXPECT_EQ(face_count(m), 118u);
}

// The spike tracker (spikes_impl.h) finds again, from the statistics'
// journal, exactly the set a whole-mesh pass finds, in the same order, after
// relaxation, removal of unrelaxable spikes (faces and vertices go), moves
// and near-degenerate repair (collapses and flips), all through one
// Local_operations. On Polyhedron_3 every call is a whole-mesh pass.
TYPED_TEST(Scan_clean, spike_tracker_matches_whole_mesh_passes)
{
  using Mesh = typename TypeParam::Mesh;
  namespace SCI = mrepair::internal::clean_pipeline;
  Mesh m = to_mesh<Mesh>(grid(40, 40));
  auto vpm = get(CGAL::vertex_point, m);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.3, 0.3);
  std::size_t k = 0;
  for (auto v : vertices(m)) {
    const Point p = get(vpm, v);
    double z = noise(rng);
    if (++k % 97 == 0) z += 4.0;  // tall spikes, some next to the border
    put(vpm, v, Point(p.x() + 0.2 * noise(rng), p.y(), z));
  }
  Stats<Mesh> st(m);
  st.compute_all();
  mrepair::internal::Local_operations<Mesh, decltype(vpm)> ops(m, vpm);
  ops.keep_current(&st);
  SCI::Spike_settings s;
  std::string message;
  ASSERT_TRUE(SCI::read_spike_settings(MP::spike_angle(60.0), s, message)) << message;
  SCI::Spike_tracker<Mesh, decltype(vpm)> tracker(st);
  auto same = [&](const char* when) {
    std::size_t by_height_tracked = 0, by_height_whole = 0;
    const auto tracked = tracker.collect(s, &by_height_tracked);
    const auto whole = SCI::collect_spiked(st, s, &by_height_whole);
    EXPECT_TRUE(tracked == whole) << when << ": " << tracked.size() << " vs " << whole.size();
    EXPECT_EQ(by_height_tracked, by_height_whole) << when;
    return whole.size();
  };
  EXPECT_GT(same("first pass"), 10u);
  mrepair::Default_visitor vis;
  const auto relaxed = SCI::relax_spikes_with(ops, st, s, vis, &tracker);
  EXPECT_GT(relaxed.vertices_relaxed, 0u);
  same("after relaxation");
  // the noise itself is spiked at 60 degrees: stricter settings re-prime
  SCI::Spike_settings strict = s;
  strict.spike_angle = s.spike_angle / 2;
  std::swap(s, strict);
  same("other settings");
  std::swap(s, strict);
  same("settings back");
  const auto removed = SCI::remove_unrelaxable_spikes_with(ops, st, s, vis, &tracker);
  same("after removal");
  std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor> vs(vertices(m).begin(),
                                                                         vertices(m).end());
  for (int i = 0; i < 150; ++i) {
    const auto v = vs[rng() % vs.size()];
    const Point p = get(vpm, v);
    ops.move_vertices({v}, {{{p.x(), p.y(), p.z() + 10 * noise(rng)}}});
  }
  same("after moves");
  SCI::Near_degenerate_settings nd;
  ASSERT_TRUE(SCI::read_near_degenerate_settings(MP::default_values(), st.edge_count(), nd, message));
  const auto fixed = SCI::repair_near_degenerate_faces_with(ops, st, nd, vis);
  same("after near-degenerate repair");
  const auto again = SCI::relax_spikes_with(ops, st, s, vis, &tracker);
  same("after a second relaxation");
  EXPECT_GT(removed.faces_removed + fixed.edges_collapsed + fixed.edges_flipped +
                again.vertices_relaxed,
            0u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  EXPECT_TRUE(stats_equal_fresh(m, st));
}

TYPED_TEST(Scan_clean, bad_input)
{
  using Mesh = typename TypeParam::Mesh;
  {
    Mesh m = to_mesh<Mesh>(grid(3, 3));
    put(get(CGAL::vertex_point, m), *vertices(m).begin(),
        Point(std::numeric_limits<double>::quiet_NaN(), 0, 0));
    EXPECT_EQ(mrepair::repair_near_degenerate_faces(m).status, mrepair::Status::non_finite_input);
    EXPECT_EQ(mrepair::relax_spikes(m).status, mrepair::Status::non_finite_input);
    EXPECT_EQ(mrepair::remove_unrelaxable_spikes(m).status, mrepair::Status::non_finite_input);
    EXPECT_EQ(face_count(m), 18u);
  }
  {
    Mesh m;
    EXPECT_EQ(mrepair::repair_near_degenerate_faces(m).status, mrepair::Status::empty_input);
    EXPECT_EQ(mrepair::relax_spikes(m).status, mrepair::Status::empty_input);
    EXPECT_EQ(mrepair::remove_unrelaxable_spikes(m).status, mrepair::Status::empty_input);
  }
  {
    Mesh m = to_mesh<Mesh>(grid(3, 3, 1.0, true));
    EXPECT_EQ(mrepair::repair_near_degenerate_faces(m).status, mrepair::Status::invalid_mesh);
  }
  {
    Mesh m = to_mesh<Mesh>(grid(3, 3));
    EXPECT_EQ(mrepair::repair_near_degenerate_faces(m, MP::skinny_angle(-1.0)).status,
              mrepair::Status::invalid_parameter);
    EXPECT_EQ(mrepair::relax_spikes(m, MP::spike_angle(200.0)).status,
              mrepair::Status::invalid_parameter);
  }
}

// Nothing flagged: the step skips its worker and second count, but reports
// the same as a full run, and a stop request is still honoured.
TYPED_TEST(Scan_clean, near_degenerate_with_nothing_to_do)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(8, 8));
  auto r = mrepair::repair_near_degenerate_faces(m);
  EXPECT_EQ(r.status, mrepair::Status::ok) << r.message;
  EXPECT_EQ(r.near_degenerate_faces_before, 0u);
  EXPECT_EQ(r.near_degenerate_faces_after, 0u);
  EXPECT_EQ(r.faces_before, 128u);
  EXPECT_EQ(r.faces_after, 128u);
  Stop_visitor sv;
  r = mrepair::repair_near_degenerate_faces(m, CGAL::parameters::visitor(std::ref(sv)));
  EXPECT_EQ(r.status, mrepair::Status::cancelled);
  EXPECT_GT(sv.polls, 0);
  EXPECT_EQ(face_count(m), 128u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
}

// Flagged but nothing editable (a lone needle: every collapse would delete
// the model, every edge is a border): the count after is the count before,
// and a fresh run finds the same.
TYPED_TEST(Scan_clean, near_degenerate_without_an_edit_keeps_its_count)
{
  using Mesh = typename TypeParam::Mesh;
  Soup s;
  s.points.emplace_back(0, 0, 0);
  s.points.emplace_back(1, 0, 0);
  s.points.emplace_back(1, 0.01, 0);  // a zero edge: 0.01 < 0.1 * the mean length
  s.polygons.push_back({0, 1, 2});
  Mesh m = to_mesh<Mesh>(s);
  auto r = mrepair::repair_near_degenerate_faces(m);
  EXPECT_EQ(r.near_degenerate_faces_before, 1u);
  EXPECT_EQ(r.edges_collapsed + r.edges_flipped, 0u);
  EXPECT_EQ(r.near_degenerate_faces_after, 1u);
  EXPECT_EQ(r.status, mrepair::Status::partial);
  EXPECT_EQ(face_count(m), 1u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  auto again = mrepair::repair_near_degenerate_faces(m);
  EXPECT_EQ(again.near_degenerate_faces_before, r.near_degenerate_faces_after);
}

TYPED_TEST(Scan_clean, cancellation)
{
  using Mesh = typename TypeParam::Mesh;
  Mesh m = to_mesh<Mesh>(grid(8, 8));
  insert_on_edge(m, find_vertex(m, 4, 4), find_vertex(m, 5, 4), Point(4.01, 4, 0));
  Stop_visitor sv;
  auto r = mrepair::repair_near_degenerate_faces(m, CGAL::parameters::visitor(std::ref(sv)));
  EXPECT_EQ(r.status, mrepair::Status::cancelled);
  EXPECT_EQ(r.edges_collapsed, 0u);
  EXPECT_GT(sv.polls, 0);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
  auto v = find_vertex(m, 5, 5);
  put(get(CGAL::vertex_point, m), v, Point(5, 5, 3));
  auto rr = mrepair::relax_spikes(m, CGAL::parameters::visitor(std::ref(sv)));
  EXPECT_EQ(rr.status, mrepair::Status::cancelled);
  EXPECT_EQ(rr.vertices_relaxed, 0u);
  EXPECT_TRUE(mrepair_test::valid_polygon_mesh(m));
}

} // namespace scan_clean_tests
} // namespace
