// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Invariants checked after every public call on seeded random soups and meshes
// with injected defects (doc/guarantees.md lists them), and the limits: a
// cancel request or a time budget stops every long call with a valid mesh.
// Typed over Surface_mesh and Polyhedron_3.
//
// The number of random cases per mesh type is MREPAIR_INVARIANT_CASES
// (environment, default 500; the asan test preset sets 300).
#include "fixtures.h"

#include <mrepair/adaptive_remesh.h>
#include <mrepair/clean_boundaries.h>
#include <mrepair/clean_scan_mesh.h>
#include <mrepair/input_profile.h>
#include <mrepair/close_gaps.h>
#include <mrepair/fill_small_holes.h>
#include <mrepair/resolve_intersections.h>
#include <mrepair/inspect.h>
#include <mrepair/relax_spikes.h>
#include <mrepair/repair.h>
#include <mrepair/remove_small_components.h>
#include <mrepair/repair_near_degenerate_faces.h>
#include <mrepair/stitch_soup.h>
#include <mrepair/visitors.h>

#include <mrepair/internal/cgal_compat.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/boost/graph/IO/OFF.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace mrepair_test;
namespace MP = mrepair::parameters;
using mrepair::Status;

namespace {

using Rng = std::mt19937_64;
const double nan_value = std::numeric_limits<double>::quiet_NaN();

double uniform(Rng& rng, double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
std::size_t pick(Rng& rng, std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); }
bool chance(Rng& rng, double p) { return uniform(rng, 0, 1) < p; }

std::size_t case_count()
{
  if (const char* s = std::getenv("MREPAIR_INVARIANT_CASES")) {
    long n = std::atol(s);
    if (n > 0) return static_cast<std::size_t>(n);
  }
  return 500;
}

// ---- random soups with injected defects ------------------------------------

struct Random_case
{
  Soup soup;
  double step = 1;           // typical edge length of the base shape
  std::string defects;       // what was injected (printed on failure)
  bool nan_in_mesh = false;  // put a NaN into the mesh after stitching
  bool injected = false;     // a defect other than noise was injected
};

Soup base_shape(Rng& rng, double& step, std::string& what)
{
  switch (pick(rng, 5)) {
    case 0: {
      std::size_t nx = 2 + pick(rng, 7), ny = 2 + pick(rng, 7);
      step = uniform(rng, 0.1, 2.0);
      what = "grid" + std::to_string(nx) + "x" + std::to_string(ny);
      return grid(nx, ny, step, chance(rng, 0.2));
    }
    case 1: {
      int levels = 1 + int(pick(rng, 2));
      double r = uniform(rng, 0.5, 5.0);
      step = r * (levels == 1 ? 0.6 : 0.3);
      what = "sphere" + std::to_string(levels);
      return icosphere(levels, r);
    }
    case 2: {
      step = uniform(rng, 0.5, 3.0);
      what = "cube";
      return cube(step, chance(rng, 0.3));
    }
    case 3: {  // a wavy height field: dihedral angles vary
      std::size_t n = 3 + pick(rng, 6);
      step = 1;
      Soup s = grid(n, n, step);
      const double a = uniform(rng, 0, 1.5);
      for (Point& p : s.points) p = Point(p.x(), p.y(), a * std::sin(p.x()) * std::cos(p.y()));
      what = "wave" + std::to_string(n);
      return s;
    }
    default: {  // two spheres, one inside the other (nesting) or apart
      Soup a = icosphere(1, 2.0), b = icosphere(1, chance(rng, 0.5) ? 0.7 : 1.0);
      const double dx = chance(rng, 0.5) ? 0.0 : 3.5;
      const std::size_t off = a.points.size();
      for (const Point& p : b.points) a.points.emplace_back(p.x() + dx, p.y(), p.z());
      for (Polygon q : b.polygons) {
        for (auto& i : q) i += off;
        a.polygons.push_back(q);
      }
      step = 1.0;
      what = "two_spheres";
      return a;
    }
  }
}

Random_case make_case(std::uint64_t seed)
{
  Rng rng(seed);
  Random_case c;
  Soup& s = c.soup;
  s = base_shape(rng, c.step, c.defects);
  const double h = c.step;
  auto add = [&](const std::string& d) { c.defects += " " + d; };
  if (chance(rng, 0.7)) {  // noise
    const double a = uniform(rng, 0, 0.2) * h;
    for (Point& p : s.points)
      p = Point(p.x() + uniform(rng, -a, a), p.y() + uniform(rng, -a, a), p.z() + uniform(rng, -a, a));
    add("noise");
  }
  const std::size_t n_defects = pick(rng, 5);
  c.injected = n_defects > 0;
  for (std::size_t k = 0; k < n_defects && !s.polygons.empty(); ++k) {
    const std::size_t np = s.points.size();
    switch (pick(rng, 13)) {
      case 0:  // NaN point (used)
        s.points[pick(rng, np)] = Point(nan_value, 0, 0);
        add("nan");
        break;
      case 1:  // out-of-range index
        s.polygons.push_back({pick(rng, np), np + pick(rng, 5), pick(rng, np)});
        add("bad_index");
        break;
      case 2:  // duplicate polygon
        s.polygons.push_back(s.polygons[pick(rng, s.polygons.size())]);
        add("duplicate");
        break;
      case 3: {  // flipped polygon
        Polygon& q = s.polygons[pick(rng, s.polygons.size())];
        std::reverse(q.begin(), q.end());
        add("flip");
        break;
      }
      case 4: {  // hole: drop a few polygons around a vertex
        const std::size_t v = s.polygons[pick(rng, s.polygons.size())][0];
        std::vector<Polygon> kept;
        for (const Polygon& q : s.polygons)
          if (std::find(q.begin(), q.end(), v) == q.end() || chance(rng, 0.2)) kept.push_back(q);
        s.polygons.swap(kept);
        add("hole");
        break;
      }
      case 5: {  // spike
        const std::size_t v = pick(rng, np);
        const Point& p = s.points[v];
        if (std::isfinite(p.x())) s.points[v] = Point(p.x(), p.y(), p.z() + uniform(rng, 2, 10) * h);
        add("spike");
        break;
      }
      case 6: {  // sliver / needle: a vertex moved next to a neighbour or onto an edge
        const Polygon& q = s.polygons[pick(rng, s.polygons.size())];
        const Point& a = s.points[q[0]];
        const Point& b = s.points[q[1]];
        const double t = chance(rng, 0.5) ? uniform(rng, 0, 1e-3) : 0.5;
        if (q.size() >= 3)
          s.points[q[2]] = Point(a.x() + t * (b.x() - a.x()), a.y() + t * (b.y() - a.y()),
                                 a.z() + t * (b.z() - a.z()) + uniform(rng, -1e-4, 1e-4) * h);
        add("sliver");
        break;
      }
      case 7: {  // gap / crack: the polygons on one side get their own copies of the points, offset
        const double cut = uniform(rng, -1, 1) * h;
        const double gap = chance(rng, 0.5) ? 0.0 : uniform(rng, 0, 0.05) * h;
        std::vector<std::size_t> copy(np, std::size_t(-1));
        for (Polygon& q : s.polygons) {
          bool side = true;
          for (std::size_t i : q)
            if (i >= np || !(s.points[i].x() > cut)) side = false;
          if (!side) continue;
          for (std::size_t& i : q) {
            if (copy[i] == std::size_t(-1)) {
              const Point& p = s.points[i];
              copy[i] = s.points.size();
              s.points.emplace_back(p.x() + gap, p.y(), p.z());
            }
            i = copy[i];
          }
        }
        add("gap");
        break;
      }
      case 8: {  // island: a small fan far away
        const std::size_t base = s.points.size();
        const double ox = uniform(rng, 5, 10) * h;
        const std::size_t m = 1 + pick(rng, 4);
        s.points.emplace_back(ox, 0, 0);
        for (std::size_t i = 0; i <= m; ++i)
          s.points.emplace_back(ox + h * std::cos(i * 0.8), h * std::sin(i * 0.8), 0);
        for (std::size_t i = 0; i < m; ++i) s.polygons.push_back({base, base + 1 + i, base + 2 + i});
        add("island");
        break;
      }
      case 9: {  // non-manifold edge: a fin on an edge
        const Polygon& q = s.polygons[pick(rng, s.polygons.size())];
        const std::size_t a = q[0], b = q[1];
        if (a < np && b < np) {
          const Point p = s.points[a];  // a copy: emplace_back reallocates
          s.points.emplace_back(p.x() + 0.3 * h, p.y() - 0.2 * h, p.z() + h);
          s.polygons.push_back({a, b, s.points.size() - 1});
          if (chance(rng, 0.5)) s.polygons.push_back({b, a, s.points.size() - 1});
        }
        add("fin");
        break;
      }
      case 10: {  // degenerate polygons: repeated index, collinear points
        const std::size_t a = pick(rng, np), b = pick(rng, np);
        s.polygons.push_back({a, a, b});
        const Point p = s.points[a];  // a copy: emplace_back reallocates
        s.points.emplace_back(p.x() + h, p.y(), p.z());
        s.points.emplace_back(p.x() + 2 * h, p.y(), p.z());
        s.polygons.push_back({a, s.points.size() - 2, s.points.size() - 1});
        add("degenerate");
        break;
      }
      case 11: {  // bowtie: two faces sharing only a vertex
        const std::size_t a = pick(rng, np);
        const Point p = s.points[a];  // a copy: emplace_back reallocates
        s.points.emplace_back(p.x(), p.y() + h, p.z() + h);
        s.points.emplace_back(p.x() + h, p.y(), p.z() + h);
        s.polygons.push_back({a, s.points.size() - 2, s.points.size() - 1});
        add("bowtie");
        break;
      }
      default:  // the mesh gets a NaN after stitching (error paths of the mesh calls)
        c.nan_in_mesh = true;
        add("nan_in_mesh");
        break;
    }
  }
  return c;
}

// ---- snapshots and checks ---------------------------------------------------

std::array<std::uint64_t, 3> bits(const Point& p)
{
  std::array<std::uint64_t, 3> b;
  const double c[3] = {p.x(), p.y(), p.z()};
  std::memcpy(b.data(), c, sizeof c);
  return b;
}

// The mesh as vertex positions (bit patterns, in iteration order) and faces as
// index lists: equal snapshots mean the mesh is untouched.
struct Snapshot
{
  std::vector<std::array<std::uint64_t, 3>> points;
  std::vector<std::vector<std::size_t>> faces;
  bool operator==(const Snapshot& o) const { return points == o.points && faces == o.faces; }
};

template <class Mesh>
Snapshot snapshot(const Mesh& m)
{
  Snapshot s;
  std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, std::size_t> id;
  for (auto v : vertices(m)) {
    id.emplace(v, s.points.size());
    s.points.push_back(bits(get(CGAL::vertex_point, m, v)));
  }
  for (auto f : faces(m)) {
    std::vector<std::size_t> q;
    for (auto h : CGAL::halfedges_around_face(halfedge(f, m), m)) q.push_back(id[target(h, m)]);
    s.faces.push_back(q);
  }
  return s;
}

struct Geometry
{
  std::set<std::array<std::uint64_t, 3>> points;  // finite input points, bit patterns
  CGAL::Bbox_3 box;                                // of the finite points
  double diag = 0;
  std::size_t non_finite = 0;
};

template <class Mesh>
Geometry geometry(const Mesh& m)
{
  Geometry g;
  for (auto v : vertices(m)) {
    const Point& p = get(CGAL::vertex_point, m, v);
    if (std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())) {
      g.points.insert(bits(p));
      g.box += p.bbox();
    } else {
      ++g.non_finite;
    }
  }
  if (!g.points.empty())
    g.diag = std::sqrt(CGAL::square(g.box.xmax() - g.box.xmin()) +
                       CGAL::square(g.box.ymax() - g.box.ymin()) +
                       CGAL::square(g.box.zmax() - g.box.zmin()));
  return g;
}

bool inside(const CGAL::Bbox_3& b, const Point& p, double slack)
{
  return p.x() >= b.xmin() - slack && p.x() <= b.xmax() + slack && p.y() >= b.ymin() - slack &&
         p.y() <= b.ymax() + slack && p.z() >= b.zmin() - slack && p.z() <= b.zmax() + slack;
}

// Validity, triangles, no new non-finite coordinate.
template <class Mesh>
::testing::AssertionResult valid_output(const Mesh& m, const Geometry& in)
{
  if (!mrepair_test::valid_polygon_mesh(m)) return ::testing::AssertionFailure() << "invalid polygon mesh";
  if (faces(m).size() > 0 && !CGAL::is_triangle_mesh(m))
    return ::testing::AssertionFailure() << "not a triangle mesh";
  std::size_t nf = 0;
  for (auto v : vertices(m)) {
    const Point& p = get(CGAL::vertex_point, m, v);
    if (!(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()))) ++nf;
  }
  if (nf > in.non_finite)
    return ::testing::AssertionFailure() << nf << " non-finite vertices, input had " << in.non_finite;
  return ::testing::AssertionSuccess();
}

// Every finite output point is a finite input point, bit for bit (nothing moved).
template <class Mesh>
std::size_t points_not_in_input(const Mesh& m, const Geometry& in)
{
  std::size_t n = 0;
  for (auto v : vertices(m)) {
    const Point& p = get(CGAL::vertex_point, m, v);
    if (std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()) && !in.points.count(bits(p)))
      ++n;
  }
  return n;
}

template <class Mesh>
std::size_t points_outside(const Mesh& m, const Geometry& in)
{
  std::size_t n = 0;
  const double slack = 1e-9 * std::max(in.diag, 1.0);
  for (auto v : vertices(m)) {
    const Point& p = get(CGAL::vertex_point, m, v);
    if (std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()) && !inside(in.box, p, slack))
      ++n;
  }
  return n;
}

// Largest distance from an output vertex to its nearest input vertex: a lower
// bound of how far any surviving vertex moved (exact per-vertex tracking is
// not available on Polyhedron_3, whose ids the algorithms reinitialise).
template <class Mesh>
double max_distance_to_input_vertex(const Mesh& m, const Mesh& input)
{
  std::vector<Point> pts;
  for (auto v : vertices(input)) pts.push_back(get(CGAL::vertex_point, input, v));
  double worst = 0;
  for (auto v : vertices(m)) {
    const Point& p = get(CGAL::vertex_point, m, v);
    double best = std::numeric_limits<double>::infinity();
    for (const Point& q : pts)
      if (std::isfinite(q.x())) best = std::min(best, CGAL::squared_distance(p, q));
    worst = std::max(worst, best);
  }
  return std::sqrt(worst);
}

// Largest distance from an output vertex to the input surface.
template <class Mesh>
double max_distance_to_surface(const Mesh& m, const Mesh& input)
{
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
  using Tree = mrepair::internal::Aabb_tree<K, Primitive>;
  Tree tree(faces(input).first, faces(input).second, input);
  tree.accelerate_distance_queries();
  double worst = 0;
  for (auto v : vertices(m))
    worst = std::max(worst, tree.squared_distance(get(CGAL::vertex_point, m, v)));
  return std::sqrt(worst);
}

template <class Mesh>
std::size_t nfaces(const Mesh& m) { return static_cast<std::size_t>(faces(m).size()); }

bool allowed_error(Status s)
{
  return s == Status::empty_input || s == Status::non_finite_input || s == Status::invalid_mesh ||
         s == Status::invalid_parameter || s == Status::non_manifold_input;
}

// Tallies over all cases, printed at the end (and checked: the cases must
// reach every path they are meant to).
struct Tally
{
  std::map<std::string, std::map<std::string, std::size_t>> by_call;  // call -> status -> count
  void add(const std::string& call, Status s) { ++by_call[call][mrepair::to_string(s)]; }
  std::size_t count(const std::string& call, const std::string& status) const
  {
    auto it = by_call.find(call);
    if (it == by_call.end()) return 0;
    auto jt = it->second.find(status);
    return jt == it->second.end() ? 0 : jt->second;
  }
  std::string text() const
  {
    std::ostringstream os;
    for (auto& c : by_call) {
      os << "  " << c.first << ":";
      for (auto& s : c.second) os << " " << s.first << "=" << s.second;
      os << "\n";
    }
    return os.str();
  }
};

template <class C>
class Invariants : public ::testing::Test
{};
TYPED_TEST_SUITE(Invariants, Mesh_configs);

// Runs one mesh call on a copy of `base` and checks the common invariants:
// valid triangle mesh, no new non-finite point, the input untouched on an
// error status. `call` returns the status and may add its own checks.
template <class Mesh, class Call>
Status run_mesh_call(const char* name, const Mesh& base, const Geometry& in, Tally& tally,
                     const std::string& context, Call call)
{
  Mesh m(base);
  const Snapshot before = snapshot(m);
  const Status s = call(m);
  tally.add(name, s);
  EXPECT_TRUE(mrepair::succeeded(s) || allowed_error(s)) << name << ": " << mrepair::to_string(s) << context;
  EXPECT_TRUE(valid_output(m, in)) << name << context;
  if (allowed_error(s)) { EXPECT_TRUE(snapshot(m) == before) << name << " changed the mesh on " << mrepair::to_string(s) << context; }
  return s;
}

TYPED_TEST(Invariants, RandomSoupsThroughEveryCall)
{
  using Mesh = typename TypeParam::Mesh;
  const std::size_t n_cases = case_count();
  Tally tally;
  std::size_t meshes = 0;
  const char* only = std::getenv("MREPAIR_INVARIANT_ONLY");  // reproduce one case
  for (std::size_t ci = 0; ci < n_cases; ++ci) {
    if (only && std::to_string(ci) != only) continue;
    const std::uint64_t seed = 0x5eed0000ull + ci;
    Random_case rc = make_case(seed);
    const Soup& soup = rc.soup;
    std::ostringstream ctx_os;
    ctx_os << " [case " << ci << ", seed " << seed << ":" << rc.defects << "]";
    const std::string ctx = ctx_os.str();
    Rng rng(seed ^ 0xabcdefull);

    // -- inspect_polygon_soup: const input; every polygon is counted once
    {
      mrepair::Inspection_report ir = mrepair::inspect_polygon_soup(soup.points, soup.polygons,
                                                                    MP::count_self_intersections(chance(rng, 0.3)));
      tally.add("inspect_polygon_soup", ir.status);
      EXPECT_TRUE(ir.status == Status::ok || ir.status == Status::invalid_index ||
                  ir.status == Status::non_finite_input)
          << mrepair::to_string(ir.status) << ctx;
      EXPECT_EQ(ir.faces + ir.invalid_polygons, soup.polygons.size()) << ctx;
    }

    // -- stitch_soup (polygon_soup_to_manifold_mesh)
    Mesh mesh;
    {
      Geometry soup_geo;
      for (const Point& p : soup.points) {
        if (std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())) {
          soup_geo.points.insert(bits(p));
          soup_geo.box += p.bbox();
        }
      }
      const double merge = chance(rng, 0.3) ? uniform(rng, 0, 0.01) * rc.step : 0.0;
      const double snap = chance(rng, 0.5) ? uniform(rng, 0, 0.1) * rc.step : 0.0;
      const bool bad_parameter = chance(rng, 0.03);
      // a sentinel: the output must be untouched on invalid_parameter
      Mesh out = to_mesh<Mesh>(cube(7.0));
      const Snapshot sentinel = snapshot(out);
      mrepair::Soup_repair_result r = mrepair::polygon_soup_to_manifold_mesh(
          soup.points, soup.polygons, out,
          MP::merge_epsilon(merge, MP::snap_epsilon(bad_parameter ? -1.0 : snap,
                                                    MP::keep_two_sided(chance(rng, 0.2)))));
      tally.add("polygon_soup_to_manifold_mesh", r.status);
      if (bad_parameter) {
        EXPECT_EQ(r.status, Status::invalid_parameter) << ctx;
        EXPECT_TRUE(snapshot(out) == sentinel) << ctx;
        continue;
      }
      EXPECT_TRUE(r.status == Status::ok || r.status == Status::partial || r.status == Status::empty_input)
          << mrepair::to_string(r.status) << ctx;
      EXPECT_EQ(r.faces_in, r.faces_out + r.faces_removed()) << ctx;
      EXPECT_EQ(nfaces(out), r.faces_out) << ctx;
      Geometry none;
      EXPECT_TRUE(valid_output(out, none)) << ctx;
      EXPECT_EQ(points_not_in_input(out, soup_geo), 0u) << "stitch moved a point" << ctx;
      // no face lost without a reason: nothing is removed from a clean soup
      if (!rc.injected) { EXPECT_EQ(r.faces_removed(), 0u) << ctx; }
      mesh = out;
    }
    if (nfaces(mesh) == 0) continue;
    ++meshes;
    if (rc.nan_in_mesh) {
      auto v = *std::next(vertices(mesh).begin(), static_cast<std::ptrdiff_t>(pick(rng, vertices(mesh).size())));
      put(CGAL::vertex_point, mesh, v, Point(0, nan_value, 0));
    }
    const Geometry in = geometry(mesh);
    const bool finite = in.non_finite == 0;
    const double h = rc.step;

    // -- inspect: const, status
    {
      mrepair::Inspection_report ir = mrepair::inspect(mesh, MP::count_self_intersections(chance(rng, 0.3)));
      tally.add("inspect", ir.status);
      EXPECT_EQ(ir.status, finite ? Status::ok : Status::non_finite_input) << ctx;
      EXPECT_EQ(ir.faces, nfaces(mesh)) << ctx;
    }

    // -- close_gaps: vertices move by at most the tolerance
    {
      const double tol = uniform(rng, 0, 0.3) * h;
      run_mesh_call("close_gaps", mesh, in, tally, ctx, [&](Mesh& m) {
        mrepair::Gap_closing_result r = mrepair::close_gaps(m, tol);
        if (!finite) { EXPECT_EQ(r.status, Status::non_finite_input) << ctx; }
        if (mrepair::succeeded(r.status)) {
          EXPECT_LE(r.max_displacement, tol) << ctx;
          EXPECT_LE(max_distance_to_input_vertex(m, mesh), tol * (1 + 1e-12)) << ctx;
        }
        return r.status;
      });
    }

    // -- repair_near_degenerate_faces: counts, vertices stay in the input's box
    {
      const bool bad = chance(rng, 0.03);
      run_mesh_call("repair_near_degenerate_faces", mesh, in, tally, ctx, [&](Mesh& m) {
        const std::size_t f0 = nfaces(m);
        mrepair::Near_degenerate_faces_result r = mrepair::repair_near_degenerate_faces(
            m, MP::max_normal_deviation(bad ? -5.0 : 45.0));
        if (bad && finite) { EXPECT_EQ(r.status, Status::invalid_parameter) << ctx; }
        if (!bad && !finite) { EXPECT_EQ(r.status, Status::non_finite_input) << ctx; }
        if (mrepair::succeeded(r.status)) {
          EXPECT_EQ(r.faces_before, f0) << ctx;
          EXPECT_EQ(r.faces_after, nfaces(m)) << ctx;
          // an interior collapse removes two faces, a boundary one one, a flip none
          EXPECT_LE(f0 - nfaces(m), 2 * r.edges_collapsed) << ctx;
          EXPECT_GE(f0 - nfaces(m), r.edges_collapsed) << ctx;
          EXPECT_EQ(points_outside(m, in), 0u) << ctx;
        }
        return r.status;
      });
    }

    // -- relax_spikes: connectivity kept, vertices stay in the input's box
    {
      run_mesh_call("relax_spikes", mesh, in, tally, ctx, [&](Mesh& m) {
        mrepair::Spike_relaxation_result r = mrepair::relax_spikes(m);
        if (!finite) { EXPECT_EQ(r.status, Status::non_finite_input) << ctx; }
        if (mrepair::succeeded(r.status)) {
          EXPECT_EQ(nfaces(m), nfaces(mesh)) << ctx;
          EXPECT_EQ(vertices(m).size(), vertices(mesh).size()) << ctx;
          EXPECT_EQ(points_outside(m, in), 0u) << ctx;
        }
        return r.status;
      });
    }

    // -- remove_unrelaxable_spikes: removes faces only, counted; nothing moves
    {
      run_mesh_call("remove_unrelaxable_spikes", mesh, in, tally, ctx, [&](Mesh& m) {
        const std::size_t f0 = nfaces(m);
        mrepair::Spike_removal_result r = mrepair::remove_unrelaxable_spikes(m);
        if (!finite) { EXPECT_EQ(r.status, Status::non_finite_input) << ctx; }
        if (mrepair::succeeded(r.status)) {
          EXPECT_EQ(f0 - r.faces_removed - r.dangling_faces_removed, nfaces(m)) << ctx;
          EXPECT_EQ(points_not_in_input(m, in), 0u) << ctx;
        }
        return r.status;
      });
    }

    // -- remove_small_components: removes whole small components, counted
    {
      const std::size_t threshold = chance(rng, 0.03) ? 0 : 1 + pick(rng, 60);
      run_mesh_call("remove_small_components", mesh, in, tally, ctx, [&](Mesh& m) {
        const std::size_t f0 = nfaces(m);
        mrepair::Small_components_result r =
            mrepair::remove_small_components(m, MP::min_component_faces(threshold));
        if (threshold == 0) { EXPECT_EQ(r.status, Status::invalid_parameter) << ctx; }
        if (mrepair::succeeded(r.status)) {
          EXPECT_EQ(f0 - r.faces_removed, nfaces(m)) << ctx;
          EXPECT_GT(nfaces(m), 0u) << ctx;
          EXPECT_EQ(points_not_in_input(m, in), 0u) << ctx;
        }
        return r.status;
      });
    }

    // -- clean_boundaries: removals counted, vertices stay in the input's box
    {
      run_mesh_call("clean_boundaries", mesh, in, tally, ctx, [&](Mesh& m) {
        const std::size_t f0 = nfaces(m);
        mrepair::Boundary_cleaning_result r = mrepair::clean_boundaries(m);
        if (mrepair::succeeded(r.status)) {
          EXPECT_EQ(f0 - r.faces_removed - r.component_faces_removed, nfaces(m)) << ctx;
          EXPECT_EQ(points_outside(m, in), 0u) << ctx;
        }
        return r.status;
      });
    }

    // -- fill_small_holes: old vertices stay, new ones in the box, faces counted
    {
      const std::size_t max_hole = 3 + pick(rng, 40);
      const bool fair = chance(rng, 0.2);
      run_mesh_call("fill_small_holes", mesh, in, tally, ctx, [&](Mesh& m) {
        const std::size_t f0 = nfaces(m);
        mrepair::Hole_filling_result r = mrepair::fill_small_holes(
            m, MP::max_hole_vertices(max_hole, MP::fair_hole_patches(fair)));
        if (mrepair::succeeded(r.status)) {
          EXPECT_EQ(f0 - r.enlargement_faces_removed + r.faces_added, nfaces(m)) << ctx;
          EXPECT_LE(points_not_in_input(m, in), r.vertices_added) << ctx;
          // on Liepa's patch, inside the loop's box; fairing may leave it
          if (!fair) { EXPECT_EQ(points_outside(m, in), 0u) << ctx; }
        }
        return r.status;
      });
    }

    // -- resolve_intersections (issue 37): faces counted, intersection_free
    // only without crossing pairs left, vertices stay in the input's box
    // (patches lie on Liepa's patch, union vertices on the input's faces)
    {
      const bool merge = chance(rng, 0.7);
      run_mesh_call("resolve_intersections", mesh, in, tally, ctx, [&](Mesh& m) {
        const std::size_t f0 = nfaces(m);
        mrepair::Intersection_repair_result r =
            mrepair::resolve_intersections(m, MP::merge_overlapping_shells(merge));
        if (!finite) { EXPECT_EQ(r.status, Status::non_finite_input) << ctx; }
        if (mrepair::succeeded(r.status)) {
          EXPECT_EQ(f0 - r.local_faces_removed + r.local_faces_added - r.union_faces_removed + r.union_faces_added -
                        r.solid_faces_removed + r.solid_faces_added + r.cap_faces_added,
                    nfaces(m)) << ctx;
          EXPECT_EQ(r.intersection_free, r.crossing_pairs_after == 0) << ctx;
          EXPECT_EQ(r.status == Status::ok, r.crossing_pairs_after == 0) << ctx;
          EXPECT_EQ(points_outside(m, in), 0u) << ctx;
          if (!merge) { EXPECT_EQ(r.shells_merged, 0u) << ctx; }
        }
        return r.status;
      });
    }

    // -- clean_scan_mesh: counts match the mesh, vertices stay in the input's box
    {
      run_mesh_call("clean_scan_mesh", mesh, in, tally, ctx, [&](Mesh& m) {
        const std::size_t f0 = nfaces(m);
        const Mesh base_copy = m;
        // the random meshes are small: auto reads them as cad, so half the
        // cases force the scan profile to reach every step
        const mrepair::Input_profile profile =
            chance(rng, 0.5) ? mrepair::Input_profile::scan : mrepair::Input_profile::automatic;
        mrepair::Scan_cleaning_result r = mrepair::clean_scan_mesh(
            m, MP::min_component_faces(
                   1 + pick(rng, 50),
                   MP::max_hole_vertices(3 + pick(rng, 40), MP::input_profile(profile))));
        EXPECT_EQ(r.faces_before, f0) << ctx;
        if (mrepair::succeeded(r.status)) {
          EXPECT_EQ(r.faces_after, nfaces(m)) << ctx;
          EXPECT_TRUE(r.faces_reconcile()) << ctx;
          // Degenerate faces no local edit can remove (a zero-area face
          // whose every fix would fold a neighbour) are counted, with
          // status partial; the tally shows how often.
          if (r.validity.degenerate_faces_left > 0) {
            EXPECT_EQ(r.status, Status::partial) << ctx;
            tally.add("clean_scan_mesh_degenerate_left", Status::partial);
            if (std::getenv("MREPAIR_INVARIANT_DUMP")) {
              std::ofstream out("/tmp/invariant_case_" + std::to_string(ci) + ".off");
              out.precision(17);
              CGAL::IO::write_OFF(out, base_copy);
            }
          }
          EXPECT_EQ(r.non_finite_vertices_removed, in.non_finite) << ctx;
          EXPECT_EQ(points_outside(m, in), 0u) << ctx;
        }
        return r.status;
      });
    }

    // -- adaptive / isotropic remeshing: back-projected onto the input surface
    {
      const bool adaptive = chance(rng, 0.5);
      const double value = adaptive ? uniform(rng, 0.02, 0.1) * h : uniform(rng, 0.5, 1.5) * h;
      run_mesh_call(adaptive ? "adaptive_remesh" : "isotropic_remesh", mesh, in, tally, ctx, [&](Mesh& m) {
        mrepair::Remeshing_result r =
            adaptive ? mrepair::adaptive_remesh(m, value, CGAL::parameters::number_of_iterations(3))
                     : mrepair::isotropic_remesh(m, value, CGAL::parameters::number_of_iterations(3));
        if (!finite) { EXPECT_EQ(r.status, Status::non_finite_input) << ctx; }
        if (mrepair::succeeded(r.status)) {
          EXPECT_EQ(r.faces_after, nfaces(m)) << ctx;
          // Back-projection puts every relaxed vertex on the input; the
          // cleanup of bad triangles after the last projection may move a
          // vertex by a collapse, by less than the largest target length
          // (doc/guarantees.md, known gap).
          const double d = max_distance_to_surface(m, mesh);
          const double L = adaptive ? r.max_target : r.target_edge_length;
          EXPECT_LE(d, L) << (adaptive ? "adaptive" : "isotropic") << ctx;
          if (d > 1e-6 * in.diag) tally.add("remesh_vertex_off_the_input_surface", r.status);
        }
        return r.status;
      });
    }
  }
  std::cout << n_cases << " cases, " << meshes << " meshes through every mesh call\n" << tally.text();
  if (only) return;
  // the cases reach the paths they are meant to
  EXPECT_GT(meshes, n_cases / 2);
  EXPECT_GT(tally.count("polygon_soup_to_manifold_mesh", "partial"), 0u);
  EXPECT_GT(tally.count("close_gaps", "non_finite_input"), 0u);
  EXPECT_GT(tally.count("remove_small_components", "invalid_parameter"), 0u);
}

// ---- limits: cancellation and time budgets ----------------------------------

struct Counting_cancel : mrepair::Default_visitor
{
  std::size_t polls = 0;
  bool stop_requested()
  {
    ++polls;
    return true;
  }
};

// A scan-like mesh with every defect kind the long calls work on: a noisy
// sphere with gaps, spikes, holes and islands (about 5k faces).
template <class Mesh>
Mesh defective_mesh()
{
  Soup s = icosphere(4, 10.0);
  Rng rng(42);
  for (Point& p : s.points) p = Point(p.x() + uniform(rng, -0.05, 0.05), p.y(), p.z());
  for (std::size_t k = 0; k < 30; ++k) {  // spikes
    Point& p = s.points[pick(rng, s.points.size())];
    p = Point(p.x() * 1.3, p.y() * 1.3, p.z() * 1.3);
  }
  std::vector<Polygon> kept;
  for (const Polygon& q : s.polygons)
    if (!chance(rng, 0.02)) kept.push_back(q);  // holes
  s.polygons.swap(kept);
  // a crack: the faces with x > 0 get their own points, shifted a little
  std::vector<std::size_t> copy(s.points.size(), std::size_t(-1));
  const std::size_t np = s.points.size();
  for (Polygon& q : s.polygons) {
    bool right = true;
    for (std::size_t i : q) right = right && s.points[i].x() > 0;
    if (!right) continue;
    for (std::size_t& i : q) {
      if (copy[i] == std::size_t(-1)) {
        copy[i] = s.points.size();
        s.points.emplace_back(s.points[i].x() + 0.01, s.points[i].y(), s.points[i].z());
      }
      i = copy[i];
    }
  }
  (void)np;
  Mesh m;
  mrepair::polygon_soup_to_manifold_mesh(s.points, s.polygons, m);
  return m;
}

template <class C>
class Limits : public ::testing::Test
{};
TYPED_TEST_SUITE(Limits, Mesh_configs);

// Runs `call(mesh, visitor_np)` with an immediate cancel and with a budget of
// zero seconds and expects `cancelled` and a valid mesh each time.
template <class Mesh, class Call>
void expect_cancels(const char* name, const Mesh& base, Call call)
{
  Geometry none;
  none.non_finite = 0;
  {
    Mesh m(base);
    Counting_cancel v;
    Status s = call(m, CGAL::parameters::visitor(std::ref(v)));
    EXPECT_EQ(s, Status::cancelled) << name << " (immediate cancel)";
    EXPECT_GE(v.polls, 1u) << name;
    EXPECT_TRUE(valid_output(m, none)) << name;
  }
  {
    Mesh m(base);
    mrepair::Time_budget_visitor<> budget(0.0);
    Status s = call(m, CGAL::parameters::visitor(std::ref(budget)));
    EXPECT_EQ(s, Status::cancelled) << name << " (zero budget)";
    EXPECT_TRUE(budget.expired()) << name;
    EXPECT_TRUE(valid_output(m, none)) << name;
  }
}

TYPED_TEST(Limits, EveryLongCallStopsOnCancelAndBudget)
{
  using Mesh = typename TypeParam::Mesh;
  const Mesh base = defective_mesh<Mesh>();
  ASSERT_GT(nfaces(base), 4000u);
  const Soup soup = icosphere(3, 1.0);

  {  // stitch_soup: the output mesh is untouched when cancelled
    Counting_cancel v;
    Mesh out = to_mesh<Mesh>(cube());
    const Snapshot before = snapshot(out);
    auto r = mrepair::polygon_soup_to_manifold_mesh(soup.points, soup.polygons, out,
                                                    CGAL::parameters::visitor(std::ref(v)));
    EXPECT_EQ(r.status, Status::cancelled);
    EXPECT_TRUE(snapshot(out) == before);
    mrepair::Time_budget_visitor<> budget(0.0);
    r = mrepair::polygon_soup_to_manifold_mesh(soup.points, soup.polygons, out,
                                               CGAL::parameters::visitor(std::ref(budget)));
    EXPECT_EQ(r.status, Status::cancelled);
    EXPECT_TRUE(snapshot(out) == before);
  }
  expect_cancels("close_gaps", base, [](Mesh& m, const auto& np) { return mrepair::close_gaps(m, 0.05, np).status; });
  expect_cancels("clean_scan_mesh", base, [](Mesh& m, const auto& np) { return mrepair::clean_scan_mesh(m, np).status; });
  expect_cancels("adaptive_remesh", base, [](Mesh& m, const auto& np) { return mrepair::adaptive_remesh(m, 0.05, np).status; });
  expect_cancels("isotropic_remesh", base, [](Mesh& m, const auto& np) { return mrepair::isotropic_remesh(m, 0.5, np).status; });
  expect_cancels("fill_small_holes", base, [](Mesh& m, const auto& np) { return mrepair::fill_small_holes(m, np).status; });
  expect_cancels("relax_spikes", base, [](Mesh& m, const auto& np) { return mrepair::relax_spikes(m, np).status; });
  expect_cancels("repair_near_degenerate_faces", base,
                 [](Mesh& m, const auto& np) { return mrepair::repair_near_degenerate_faces(m, np).status; });
  expect_cancels("clean_boundaries", base, [](Mesh& m, const auto& np) { return mrepair::clean_boundaries(m, np).status; });
  expect_cancels("remove_small_components", base,
                 [](Mesh& m, const auto& np) { return mrepair::remove_small_components(m, np).status; });
}

// A budget that runs out in the middle of a call: the call stops within a
// poll interval, cancelled, with a valid mesh that kept its work so far.
TYPED_TEST(Limits, TinyBudgetStopsMidway)
{
  using Mesh = typename TypeParam::Mesh;
  const Mesh base = defective_mesh<Mesh>();
  Geometry none;
  auto check = [&](const char* name, auto call) {
    Mesh m(base);
    mrepair::Time_budget_visitor<> budget(1e-4);
    Status s = call(m, CGAL::parameters::visitor(std::ref(budget)));
    EXPECT_EQ(s, Status::cancelled) << name;
    EXPECT_TRUE(valid_output(m, none)) << name;
    EXPECT_LT(budget.elapsed(), 30.0) << name;
  };
  check("clean_scan_mesh", [](Mesh& m, const auto& np) { return mrepair::clean_scan_mesh(m, np).status; });
  check("adaptive_remesh", [](Mesh& m, const auto& np) { return mrepair::adaptive_remesh(m, 0.02, np).status; });
  check("isotropic_remesh", [](Mesh& m, const auto& np) { return mrepair::isotropic_remesh(m, 0.3, np).status; });
}

// The whole job takes triangles as fixed arrays (what the command-line
// program reads an all-triangle file into) and gives the same mesh, vertex
// for vertex and face for face, as with polygon vectors.
TEST(RepairJob, TriangleArraysGiveTheSameMeshAsPolygonVectors)
{
  using Mesh = CGAL::Surface_mesh<Point>;
  Soup s = icosphere(3, 1.0);
  const std::size_t nf = s.polygons.size();
  s.polygons.push_back(s.polygons[5]);                                  // a duplicate
  s.polygons.push_back({s.polygons[7][0], s.polygons[7][0], s.polygons[7][1]});  // repeated index
  s.polygons.erase(s.polygons.begin() + 100, s.polygons.begin() + 103);  // a hole
  s.points[s.polygons[200][0]] = Point(0, 0, 3);                         // a spike
  const Soup piece = translated(icosphere(0, 0.05), 3, 0, 0);             // a small component
  s = merged(s, piece);
  ASSERT_GT(s.polygons.size(), nf);
  std::vector<Point> p1 = s.points, p2 = s.points;
  std::vector<Polygon> polygons = s.polygons;
  std::vector<std::array<std::size_t, 3>> triangles;
  for (const Polygon& f : s.polygons) triangles.push_back({f[0], f[1], f[2]});
  Mesh m1, m2;
  const mrepair::Repair_result a = mrepair::repair_polygon_soup(p1, polygons, m1);
  const mrepair::Repair_result b = mrepair::repair_polygon_soup(p2, triangles, m2);
  EXPECT_EQ(a.status, b.status) << a.message << " / " << b.message;
  EXPECT_EQ(a.before.faces, b.before.faces);
  EXPECT_EQ(a.before.duplicate_faces, b.before.duplicate_faces);
  EXPECT_GE(a.before.duplicate_faces, 1u);
  EXPECT_EQ(a.faces_in, b.faces_in);
  EXPECT_EQ(a.faces_out, b.faces_out);
  EXPECT_EQ(a.after.faces, b.after.faces);
  EXPECT_TRUE(a.faces_reconcile());
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m1));
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m2));
  ASSERT_EQ(num_vertices(m1), num_vertices(m2));
  ASSERT_EQ(num_faces(m1), num_faces(m2));
  EXPECT_EQ(a.after.boundary_loops, 0u);  // the hole is filled
  for (auto v : vertices(m1)) EXPECT_EQ(m1.point(v), m2.point(v)) << v;
  for (auto f : faces(m1)) {
    std::vector<std::size_t> x, y;
    for (auto v : CGAL::vertices_around_face(halfedge(f, m1), m1)) x.push_back(v);
    for (auto v : CGAL::vertices_around_face(halfedge(f, m2), m2)) y.push_back(v);
    EXPECT_EQ(x, y) << f;
  }
}

// Issue 17: up to `concurrent_inspection_polygons` polygons the inspection of
// the input runs beside the soup stage. The job is the same either way: the
// same mesh, the same report (timings aside), the stages reported in the
// same order, "before" first.
TEST(RepairJob, InputInspectionBesideTheSoupStageChangesNothing)
{
  using Mesh = CGAL::Surface_mesh<Point>;
  Soup s = icosphere(4, 1.0);
  s.polygons.push_back(s.polygons[11]);                                  // a duplicate
  s.polygons.erase(s.polygons.begin() + 300, s.polygons.begin() + 304);  // a hole
  s.points[s.polygons[900][1]] = Point(0, 0, 2.5);                       // a spike
  s = merged(s, translated(icosphere(1, 0.05), 3, 0, 0));                // a small component
  s = merged(s, translated(grid(6, 6, 0.1), -3, 0, 0));                  // an open sheet
  auto run = [&](std::size_t beside, std::vector<std::string>& stages, Mesh& m) {
    std::vector<Point> points = s.points;
    std::vector<Polygon> polygons = s.polygons;
    namespace MP = mrepair::parameters;
    mrepair::Repair_result r = mrepair::repair_polygon_soup(
        points, polygons, m,
        MP::concurrent_inspection_polygons(
            beside, MP::after_stage([&](const char* stage, const mrepair::Repair_result&) {
              stages.push_back(stage);
            })));
    EXPECT_TRUE(points.empty() && polygons.empty());  // freed once the mesh is built
    std::string json, line;
    std::istringstream lines(r.sections.to_json());
    while (std::getline(lines, line))
      if (line.find("\"seconds\"") == std::string::npos) json += line + "\n";
    return std::make_pair(r, json);
  };
  std::vector<std::string> one_by_one, side_by_side;
  Mesh m1, m2;
  const auto a = run(0, one_by_one, m1);
  const auto b = run(std::size_t(-1), side_by_side, m2);
  EXPECT_EQ(a.first.status, b.first.status) << a.first.message << " / " << b.first.message;
  EXPECT_GE(a.first.before.duplicate_faces, 1u);
  EXPECT_GE(a.first.before.boundary_loops, 2u);
  EXPECT_EQ(a.second, b.second);
  EXPECT_EQ(a.second.find("\"before\""), b.second.find("\"before\""));
  EXPECT_LT(a.second.find("\"before\""), a.second.find("\"soup_to_manifold\""));
  ASSERT_GE(one_by_one.size(), 2u);
  EXPECT_EQ(one_by_one, side_by_side);
  EXPECT_EQ(one_by_one[0], "before");
  EXPECT_EQ(one_by_one[1], "soup_to_manifold");
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m1));
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m2));
  ASSERT_EQ(num_vertices(m1), num_vertices(m2));
  ASSERT_EQ(num_faces(m1), num_faces(m2));
  for (auto v : vertices(m1)) EXPECT_EQ(m1.point(v), m2.point(v)) << v;
  for (auto f : faces(m1)) {
    std::vector<std::size_t> x, y;
    for (auto v : CGAL::vertices_around_face(halfedge(f, m1), m1)) x.push_back(v);
    for (auto v : CGAL::vertices_around_face(halfedge(f, m2), m2)) y.push_back(v);
    EXPECT_EQ(x, y) << f;
  }
}

// Issue 17: `output_final` tells a caller of `after_stage` that the mesh will
// not change any more (mrepair repair writes it from that callback): set
// once the cleaning succeeded and the solid repair ran (issue 37: its
// "resolve_intersections" callback, or "clean" when that step is off), never
// when the cleaning failed or was cancelled.
TEST(RepairJob, OutputIsFinalOnlyAfterASuccessfulCleaning)
{
  using Mesh = CGAL::Surface_mesh<Point>;
  Soup s = icosphere(3, 1.0);
  s.polygons.erase(s.polygons.begin() + 40, s.polygons.begin() + 43);  // a hole to fill
  struct Stop_in_cleaning : mrepair::Default_visitor
  {
    bool cancel = false, in_cleaning = false;
    void start_phase(const char* name)
    {
      if (std::string(name) == "fill_small_holes") in_cleaning = true;
    }
    bool stop_requested() const { return cancel && in_cleaning; }
  };
  for (bool cancel : {false, true}) {
    std::vector<Point> points = s.points;
    std::vector<Polygon> polygons = s.polygons;
    Stop_in_cleaning visitor;
    visitor.cancel = cancel;
    std::vector<std::pair<std::string, bool>> seen;
    Mesh m;
    const mrepair::Repair_result r = mrepair::repair_polygon_soup(
        points, polygons, m,
        mrepair::parameters::after_stage([&](const char* stage, const mrepair::Repair_result& so_far) {
          seen.emplace_back(stage, so_far.output_final);
        }).visitor(std::ref(visitor)));
    ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
    ASSERT_FALSE(seen.empty());
    for (const auto& x : seen) {
      if (x.first != "resolve_intersections" && x.first != "after") {
        EXPECT_FALSE(x.second) << x.first;
      }
    }
    if (cancel) {
      EXPECT_EQ(r.failed_stage, "clean");
      EXPECT_EQ(r.status, mrepair::Status::cancelled);
      EXPECT_FALSE(r.output_final);
      EXPECT_EQ(seen.back(), std::make_pair(std::string("clean"), false));
    } else {
      EXPECT_TRUE(r.failed_stage.empty()) << r.message;
      EXPECT_TRUE(r.output_final);
      ASSERT_GE(seen.size(), 2u);
      EXPECT_EQ(seen[seen.size() - 3], std::make_pair(std::string("clean"), false));
      EXPECT_EQ(seen[seen.size() - 2], std::make_pair(std::string("resolve_intersections"), true));
      EXPECT_EQ(seen.back(), std::make_pair(std::string("after"), true));
    }
  }
  // without the solid repair, the mesh is final at the cleaning
  std::vector<Point> points = s.points;
  std::vector<Polygon> polygons = s.polygons;
  std::vector<std::pair<std::string, bool>> seen;
  namespace MP = mrepair::parameters;
  Mesh m;
  const mrepair::Repair_result r = mrepair::repair_polygon_soup(
      points, polygons, m,
      MP::resolve_intersections(false, MP::after_stage([&](const char* stage, const mrepair::Repair_result& so_far) {
                                  seen.emplace_back(stage, so_far.output_final);
                                })));
  EXPECT_TRUE(r.output_final);
  ASSERT_GE(seen.size(), 2u);
  EXPECT_EQ(seen[seen.size() - 2], std::make_pair(std::string("clean"), true));
}

// Issue 49: on one shell the output inspection runs before the solid repair,
// and its count of crossing pairs decides whether the repair has anything
// to do. The reported output inspection is always that of the output: the
// same as inspecting the repaired mesh afresh, whether the solid repair was
// skipped (a sphere with a hole and a spike), ran and changed nothing, or
// changed the mesh (a box whose top is pushed through its bottom).
TEST(RepairJob, OneShellWithoutCrossingNeedsNoSolidRepairAndTheReportStaysTheOutputs)
{
  using Mesh = CGAL::Surface_mesh<Point>;
  auto without_seconds = [](const mrepair::Inspection_report& i) {
    mrepair::Report report;
    i.to_report(report.section("after"));
    std::string json, line;
    std::istringstream lines(report.to_json());
    while (std::getline(lines, line))
      if (line.find("\"seconds\"") == std::string::npos) json += line + "\n";
    return json;
  };
  Soup sphere = icosphere(3, 1.0);
  sphere.polygons.erase(sphere.polygons.begin() + 300, sphere.polygons.begin() + 303);  // a hole
  Soup box = cube(1.0);
  // the top's back edge below the bottom: the top crosses the bottom
  for (Point& p : box.points)
    if (p.z() == 1 && p.y() == 1) p = Point(p.x(), 0.5, -0.5);
  for (int which = 0; which < 2; ++which) {
    SCOPED_TRACE(which == 0 ? "sphere with a hole" : "box pushed through itself");
    const Soup& s = which == 0 ? sphere : box;
    std::vector<Point> points = s.points;
    std::vector<Polygon> polygons = s.polygons;
    Mesh m;
    const mrepair::Repair_result r = mrepair::repair_polygon_soup(points, polygons, m);
    ASSERT_TRUE(mrepair_test::valid_polygon_mesh(m));
    ASSERT_TRUE(r.intersections_resolved) << r.message;
    const mrepair::Intersection_repair_result& ir = r.intersections;
    const bool skipped = ir.message.find("nothing to resolve") != std::string::npos;
    if (which == 0) {
      EXPECT_TRUE(skipped) << ir.message;
      EXPECT_EQ(ir.status, mrepair::Status::ok);
      EXPECT_TRUE(ir.intersection_free);
      EXPECT_TRUE(r.after.closed);
    } else {
      EXPECT_FALSE(skipped);
      EXPECT_GT(ir.crossing_pairs_before, 0u);
    }
    ASSERT_TRUE(r.after.self_intersections_counted);
    namespace MP = mrepair::parameters;
    const mrepair::Inspection_report fresh =
        mrepair::inspect(m, MP::max_hole_vertices(
                                r.after.max_hole_vertices,
                                MP::min_component_faces(r.after.min_component_faces,
                                                        MP::spike_angle(r.after.spike_angle))));
    EXPECT_EQ(without_seconds(r.after), without_seconds(fresh));
    EXPECT_EQ(r.after.self_intersecting_pairs - r.after.self_intersecting_pairs_touching,
              ir.crossing_pairs_after);
  }
}

TEST(TimeBudgetVisitor, ForwardsHooksAndHonoursTheInnerStop)
{
  struct Recorder : mrepair::Default_visitor
  {
    std::vector<std::string> phases;
    bool stop = false;
    double last = -1;
    void start_phase(const char* n) { phases.push_back(n); }
    void progress(double f) { last = f; }
    bool stop_requested() { return stop; }
  } rec;
  mrepair::Time_budget_visitor<std::reference_wrapper<Recorder>> v(3600.0, std::ref(rec));
  v.start_phase("a");
  v.progress(0.5);
  EXPECT_EQ(rec.phases, std::vector<std::string>{"a"});
  EXPECT_EQ(rec.last, 0.5);
  EXPECT_FALSE(v.stop_requested());
  rec.stop = true;
  EXPECT_TRUE(v.stop_requested());
  EXPECT_FALSE(v.expired());  // the inner visitor stopped, not the budget
  rec.stop = false;
  v.restart(0.0);
  EXPECT_TRUE(v.stop_requested());
  EXPECT_TRUE(v.expired());
  v.restart(3600.0);
  EXPECT_FALSE(v.stop_requested());
}

}  // namespace
