// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The worker behind `isotropic_remesh` / `adaptive_remesh`: Botsch-Kobbelt
// local operations driven by a per-vertex sizing field (Dunyach et al. 2013).
//
//   classify edges: 0 free, LINE (feature or boundary), FROZEN (outside the
//                   part, its border, protected); vertices: free, line, frozen
//   for it in 1..iterations:
//     split   edges longer than 4/3 L(e) at their midpoint (repeat until none)
//     collapse edges shorter than 4/5 L(e): link condition, no edge longer than
//             4/3 L, no flipped normal, features only along themselves
//     flip    free edges when the valence deviation (6 inside, 4 on boundary)
//             decreases and no face flips or degenerates
//     relax   free vertices to the area*size weighted face barycentre, in the
//             tangent plane; line vertices to the weighted edge midpoints
//     project onto the input (line vertices onto the input lines), reading the
//             sizing field at the projection
//     cleanup faces under 20 degrees: angle-improving flip or needle collapse
//   last iteration: vertices of faces under 30 degrees try positions towards
//             their neighbours (lines along the line), projected, keeping the
//             one that raises the smallest angle of their star
//   collapses and flips never create a fold (two adjacent faces with normals
//   more than 120 degrees apart that were not folded before): folds at thin
//   parts were the self-intersections of coarse remeshing
#ifndef MREPAIR_INTERNAL_ADAPTIVE_REMESH_REMESHER_H
#define MREPAIR_INTERNAL_ADAPTIVE_REMESH_REMESHER_H

#include <mrepair/internal/adaptive_remesh/reference_surface.h>
#include <mrepair/internal/vertex_order.h>
#include <mrepair/internal/utility.h>
#include <mrepair/status.h>

#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <type_traits>
#include <vector>

namespace mrepair {
namespace internal {
namespace remesh {

enum : char { LINE = 1, FROZEN = 2, FEATURE = 4, HELD = 8 };  // HELD: unsplit during one split phase
enum : char { V_FREE = 0, V_LINE = 1, V_FROZEN = 2 };

template <typename VD>
struct Is_sm_index : std::false_type {};
template <>
struct Is_sm_index<CGAL::SM_Vertex_index> : std::true_type {};

struct Counters
{
  std::size_t splits = 0, collapses = 0, flips = 0, relaxed = 0, iterations = 0;
};

template <typename TriangleMesh, typename VertexPointMap, bool Parallel>
class Remesher
{
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Point = typename boost::property_traits<VertexPointMap>::value_type;

  template <typename T>
  using VMap = typename boost::property_map<TriangleMesh, CGAL::dynamic_vertex_property_t<T>>::type;
  template <typename T>
  using EMap = typename boost::property_map<TriangleMesh, CGAL::dynamic_edge_property_t<T>>::type;
  template <typename T>
  using HMap = typename boost::property_map<TriangleMesh, CGAL::dynamic_halfedge_property_t<T>>::type;
  template <typename T>
  using FMap = typename boost::property_map<TriangleMesh, CGAL::dynamic_face_property_t<T>>::type;

  // Parallel passes only where property maps are flat arrays (Surface_mesh);
  // Polyhedron_3's dynamic maps are hash maps, unsafe to read concurrently.
  static constexpr bool parallel_ = Parallel && Is_sm_index<vertex_descriptor>::value;

  TriangleMesh& tm_;
  VertexPointMap vpm_;
  VMap<Vec3> pos_;
  VMap<double> size_;
  VMap<char> kind_;
  VMap<char> bnd_;
  VMap<int> deg_;
  VMap<int> ref_;
  VMap<int> thint_;  // last reference triangle a vertex projected to (-1: none)
  VMap<int> shint_;  // last reference segment
  EMap<char> flag_;
  HMap<unsigned> dead_;
  unsigned stamp_ = 0;

  Reference_surface ref;
  bool uniform_ = true;
  double L_ = 1;
  double guard_ = 0;  // > 0: the min-angle pass keeps the faces it moves within this distance
  double collapse_cos_ = 0.2;  // collapse rejected when a face normal turns more than ~78 deg
  bool relax_lines_ = true;
  double bad_angle_ = 20.;  // degrees: faces below it get the cleanup pass
  std::size_t op_budget_ = 0;  // splits + collapses allowed in all; 0: no limit

public:
  Counters counters;
  std::size_t feature_edges = 0, corners = 0;

  Remesher(TriangleMesh& tm, VertexPointMap vpm)
    : tm_(tm), vpm_(vpm),
      pos_(get(CGAL::dynamic_vertex_property_t<Vec3>(), tm)),
      size_(get(CGAL::dynamic_vertex_property_t<double>(), tm)),
      kind_(get(CGAL::dynamic_vertex_property_t<char>(), tm)),
      bnd_(get(CGAL::dynamic_vertex_property_t<char>(), tm)),
      deg_(get(CGAL::dynamic_vertex_property_t<int>(), tm)),
      ref_(get(CGAL::dynamic_vertex_property_t<int>(), tm)),
      thint_(get(CGAL::dynamic_vertex_property_t<int>(), tm)),
      shint_(get(CGAL::dynamic_vertex_property_t<int>(), tm)),
      flag_(get(CGAL::dynamic_edge_property_t<char>(), tm)),
      dead_(get(CGAL::dynamic_halfedge_property_t<unsigned>(), tm))
  {}

  const Reference_surface& reference() const { return ref; }
  Reference_surface& reference() { return ref; }
  void set_relax_lines(bool b) { relax_lines_ = b; }
  /// the final min-angle pass keeps a move only when the vertex's faces stay
  /// within `tolerance` of the input, or within their deviation before
  /// (adaptive mode; 0: no check, as in the uniform and face-count modes)
  void guard_min_angle_pass(double tolerance) { guard_ = tolerance; }
  /// caps the splits plus collapses of all runs; `run` returns `partial` once spent
  void set_operation_budget(std::size_t n) { op_budget_ = n; }
  bool budget_spent() const
  {
    return op_budget_ != 0 && counters.splits + counters.collapses >= op_budget_;
  }

  /// classifies edges and vertices and builds the reference surface.
  /// `in_part(f)`: f belongs to the remeshed part; `is_feature(e)`: user or
  /// dihedral feature; `is_fixed(v)`: user-constrained vertex.
  template <typename InPart, typename IsFeature, typename IsFixed>
  void setup(InPart in_part, IsFeature is_feature, IsFixed is_fixed, bool protect,
             double cos_turn)
  {
    std::vector<vertex_descriptor> vs;
    vertices_where(vs, [](vertex_descriptor) { return true; });
    for_each_index(vs.size(), [&](std::size_t i) {
      const vertex_descriptor v = vs[i];
      put(pos_, v, to_vec3(get(vpm_, v)));
      put(size_, v, L_);
      put(kind_, v, char(V_FREE));
      put(bnd_, v, char(0));
      put(deg_, v, 0);
      put(ref_, v, -1);
      put(thint_, v, -1);
      put(shint_, v, -1);
    });
    // Surface_mesh's dynamic maps start at their value type's default (0)
    if constexpr (!Is_sm_index<vertex_descriptor>::value)
      for (halfedge_descriptor h : halfedges(tm_)) put(dead_, h, 0u);
    // Each edge's flag (the feature test, two face normals, is most of the
    // setup: over the edges at once with threads), then, in order, what the
    // flags say of the vertices: line/frozen edge counts, kept in deg_ for now.
    std::vector<edge_descriptor> es;
    edges_where(es, [](edge_descriptor) { return true; });
    for_each_index(es.size(), [&](std::size_t i) {
      const edge_descriptor e = es[i];
      halfedge_descriptor h = halfedge(e, tm_), o = opposite(h, tm_);
      face_descriptor f1 = face(h, tm_), f2 = face(o, tm_);
      bool n1 = f1 == GT::null_face(), n2 = f2 == GT::null_face();
      bool in1 = !n1 && in_part(f1), in2 = !n2 && in_part(f2);
      char fl = 0;
      if (!in1 && !in2)
        fl = FROZEN;
      else if ((!n1 && !in1) || (!n2 && !in2))
        fl = FROZEN;
      else if (n1 || n2)
        fl = protect ? FROZEN : LINE;
      else if (is_feature(e))
        fl = char(FEATURE | (protect ? FROZEN : LINE));
      put(flag_, e, fl);
    });
    for (edge_descriptor e : es) {
      const char fl = get(flag_, e);
      halfedge_descriptor h = halfedge(e, tm_), o = opposite(h, tm_);
      const bool n1 = is_border(h, tm_), n2 = is_border(o, tm_);
      vertex_descriptor a = source(h, tm_), b = target(h, tm_);
      if (n1 || n2) { put(bnd_, a, char(1)); put(bnd_, b, char(1)); }
      if (fl & FEATURE) ++feature_edges;
      if (fl & FROZEN) {
        // only vertices of the part matter; outside vertices are never touched
        put(kind_, a, char(V_FROZEN));
        put(kind_, b, char(V_FROZEN));
      } else if (fl & LINE) {
        put(deg_, a, get(deg_, a) + 1);
        put(deg_, b, get(deg_, b) + 1);
      }
    }
    for (vertex_descriptor v : vertices(tm_)) {
      if (get(kind_, v) == V_FROZEN || is_fixed(v) || halfedge(v, tm_) == GT::null_halfedge()) {
        put(kind_, v, char(V_FROZEN));
        continue;
      }
      int c = get(deg_, v);
      if (c == 2 && !sharp_turn(v, cos_turn))
        put(kind_, v, char(V_LINE));
      else if (c != 0) {
        put(kind_, v, char(V_FROZEN));
        ++corners;
      }
    }
    // reference surface: the faces of the part
    if constexpr (parallel_)
      reference_triangles_in_parallel(in_part);
    else
      reference_triangles(in_part);
    for (edge_descriptor e : edges(tm_)) {
      char fl = get(flag_, e);
      if (!(fl & LINE)) continue;
      halfedge_descriptor h = halfedge(e, tm_);
      put(shint_, source(h, tm_), static_cast<int>(ref.segments.size()));
      put(shint_, target(h, tm_), static_cast<int>(ref.segments.size()));
      ref.segments.push_back({get(ref_, source(h, tm_)), get(ref_, target(h, tm_))});
    }
    ref.build();
  }

  // The reference surface's points and triangles from the faces of the part:
  // points numbered in the order the faces first reach them, each vertex's
  // triangle hint its last face.
  template <typename InPart>
  void reference_triangles(InPart in_part)
  {
    for (face_descriptor f : faces(tm_)) {
      if (!in_part(f)) continue;
      std::array<int, 3> t;
      int k = 0;
      for (vertex_descriptor v : vertices_around_face(halfedge(f, tm_), tm_)) {
        int r = get(ref_, v);
        if (r < 0) {
          r = static_cast<int>(ref.points.size());
          ref.points.push_back(get(pos_, v));
          ref.on_line.push_back(get(kind_, v) != V_FREE || get(bnd_, v));
          put(ref_, v, r);
        }
        if (k < 3) t[k] = r;
        ++k;
        put(thint_, v, static_cast<int>(ref.triangles.size()));
      }
      ref.triangles.push_back(t);
    }
  }

  // The same numbering on a Surface_mesh with threads (the sequential loop
  // was half the setup at 1M faces): each vertex finds the first corner of
  // the part's faces at it (face position, then its place in the face) and
  // its last face from its own fan; the points are then the vertices in the
  // order of their first corners. Triangle meshes only (checked on entry).
  template <typename InPart>
  void reference_triangles_in_parallel(InPart in_part)
  {
    using size_type = typename TriangleMesh::size_type;
    std::vector<face_descriptor> fs;
    faces_where(fs, [&](face_descriptor f) { return in_part(f); });
    std::vector<int> position(tm_.number_of_faces() + tm_.number_of_removed_faces(), -1);
    for_each_index(fs.size(), [&](std::size_t i) { position[static_cast<size_type>(fs[i])] = static_cast<int>(i); });
    std::vector<vertex_descriptor> vs;
    vertices_where(vs, [](vertex_descriptor) { return true; });
    sort_by_halfedge(tm_, vs, relax_buffers_.order);
    constexpr std::size_t none = static_cast<std::size_t>(-1);
    std::vector<std::size_t> first(vs.size(), none);
    for_each_index(vs.size(), [&](std::size_t j) {
      const vertex_descriptor v = vs[j];
      int last = -1;
      for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
        const face_descriptor f = face(g, tm_);
        if (f == GT::null_face()) continue;
        const int p = position[static_cast<size_type>(f)];
        if (p < 0) continue;
        const halfedge_descriptor h0 = halfedge(f, tm_);
        const std::size_t k = g == h0 ? 0 : (g == next(h0, tm_) ? 1 : 2);
        first[j] = std::min(first[j], 3 * static_cast<std::size_t>(p) + k);
        last = std::max(last, p);
      }
      if (last >= 0) put(thint_, v, last);
    });
    // the vertices by first corner (each corner is the first of one vertex at most)
    std::vector<int> at_corner(3 * fs.size(), -1);
    for_each_index(vs.size(), [&](std::size_t j) {
      if (first[j] != none) at_corner[first[j]] = static_cast<int>(j);
    });
    std::vector<int> order;
    order.reserve(vs.size());
    for (int j : at_corner)
      if (j >= 0) order.push_back(j);
    free_memory(at_corner, first);
    ref.points.resize(order.size());
    ref.on_line.resize(order.size());
    for_each_index(order.size(), [&](std::size_t r) {
      const vertex_descriptor v = vs[static_cast<std::size_t>(order[r])];
      ref.points[r] = get(pos_, v);
      ref.on_line[r] = get(kind_, v) != V_FREE || get(bnd_, v);
      put(ref_, v, static_cast<int>(r));
    });
    ref.triangles.resize(fs.size());
    for_each_index(fs.size(), [&](std::size_t i) {
      const halfedge_descriptor h0 = halfedge(fs[i], tm_);
      const halfedge_descriptor h1 = next(h0, tm_);
      ref.triangles[i] = {get(ref_, target(h0, tm_)), get(ref_, target(h1, tm_)),
                          get(ref_, target(next(h1, tm_), tm_))};
    });
  }

  // a line vertex where its line turns by more than the feature angle is a corner
  bool sharp_turn(vertex_descriptor v, double cos_turn) const
  {
    Vec3 d[2]{};
    int k = 0;
    const Vec3 pv = get(pos_, v);
    for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
      if (!(get(flag_, edge(g, tm_)) & LINE) || k == 2) continue;
      d[k++] = pv - get(pos_, source(g, tm_));
    }
    if (k != 2) return true;
    // d[0] points into v, -d[1] out of it: turning angle between them
    double l = norm(d[0]) * norm(d[1]);
    return !(l > 0) || -dot(d[0], d[1]) < cos_turn * l;
  }

  void set_uniform(double L)
  {
    uniform_ = true;
    ref.set_walk_edges(true);
    L_ = L;
    ref.sizing.assign(ref.points.size(), L);
    for (vertex_descriptor v : vertices(tm_)) put(size_, v, L);
  }

  void set_adaptive(double eps, double lmin, double lmax, double gamma)
  {
    uniform_ = false;
    ref.set_walk_edges(false);
    ref.compute_adaptive_sizing(eps, lmin, lmax, gamma);
    for (vertex_descriptor v : vertices(tm_)) {
      int r = get(ref_, v);
      put(size_, v, r >= 0 ? ref.sizing[r] : lmax);
    }
  }

  /// multiplies the sizing field (the reference's and the vertices') by `f`,
  /// clamped to [lmin, lmax]; returns how many points of the reference
  /// changed (0: the whole field is held at a bound)
  std::size_t scale_sizing(double f, double lmin, double lmax)
  {
    std::size_t changed = 0;
    for (double& L : ref.sizing) {
      const double scaled = std::clamp(L * f, lmin, lmax);
      changed += scaled != L;
      L = scaled;
    }
    for (vertex_descriptor v : vertices(tm_)) put(size_, v, std::clamp(get(size_, v) * f, lmin, lmax));
    return changed;
  }

  /// the min-angle optimisation of the last iteration, for runs made with
  /// `last_run` false
  void finish(bool project, double min_deg = 30.) { optimize_bad_vertices(min_deg, project, 4); }

  /// the smallest angle of the mesh, in degrees
  double min_angle_deg() const
  {
    double worst = -1;
    for (face_descriptor f : faces(tm_)) {
      const halfedge_descriptor h = halfedge(f, tm_);
      worst = std::max(worst, min_angle_cos(get(pos_, source(h, tm_)), get(pos_, target(h, tm_)),
                                            get(pos_, target(next(h, tm_), tm_))));
    }
    return std::acos(std::clamp(worst, -1., 1.)) * 180. / CGAL_PI;
  }

  // ---------------------------------------------------------------- helpers
  // The passes below edit the mesh one element at a time, but each starts
  // with a scan of the whole mesh for the few elements it works on (a few
  // hundred of 1.5M edges on a mesh near its target length): on Surface_mesh
  // with threads that scan runs over the index slots in chunks, in parallel,
  // and gives the list the loop over edges(tm_) / faces(tm_) gives, in its order.
  template <typename Desc, typename Range, typename Keep>
  void collect(const Range& range, std::size_t slots, std::vector<Desc>& out, const Keep& keep) const
  {
    out.clear();
    if constexpr (parallel_) {
      if (slots > 20000) {
        auto parts = chunked_over_slots<Desc, std::vector<Desc>>(
            tm_, slots, [&](Desc d, std::vector<Desc>& part) {
              if (!tm_.is_removed(d) && keep(d)) part.push_back(d);
            });
        for (const std::vector<Desc>& part : parts) out.insert(out.end(), part.begin(), part.end());
        return;
      }
    }
    for (Desc d : range)
      if (keep(d)) out.push_back(d);
  }
  template <typename Keep>
  void edges_where(std::vector<edge_descriptor>& out, const Keep& keep) const
  {
    std::size_t slots = 0;
    if constexpr (parallel_) slots = tm_.number_of_edges() + tm_.number_of_removed_edges();
    collect(edges(tm_), slots, out, keep);
  }
  template <typename Keep>
  void faces_where(std::vector<face_descriptor>& out, const Keep& keep) const
  {
    std::size_t slots = 0;
    if constexpr (parallel_) slots = tm_.number_of_faces() + tm_.number_of_removed_faces();
    collect(faces(tm_), slots, out, keep);
  }
  template <typename Keep>
  void vertices_where(std::vector<vertex_descriptor>& out, const Keep& keep) const
  {
    std::size_t slots = 0;
    if constexpr (parallel_) slots = tm_.number_of_vertices() + tm_.number_of_removed_vertices();
    collect(vertices(tm_), slots, out, keep);
  }

  double tsize(vertex_descriptor a, vertex_descriptor b) const
  {
    return uniform_ ? L_ : std::min(get(size_, a), get(size_, b));
  }
  double sqlength(halfedge_descriptor h) const
  {
    return squared_norm(get(pos_, target(h, tm_)) - get(pos_, source(h, tm_)));
  }

  // ------------------------------------------------------------------ split
  void split(halfedge_descriptor h)
  {
    vertex_descriptor a = source(h, tm_), b = target(h, tm_);
    char fl = get(flag_, edge(h, tm_));
    Vec3 m = 0.5 * (get(pos_, a) + get(pos_, b));
    double s = 0.5 * (get(size_, a) + get(size_, b));
    bool border = CGAL::is_border_edge(h, tm_);
    halfedge_descriptor hnew = CGAL::Euler::split_edge(h, tm_);  // a -> v, then h: v -> b
    vertex_descriptor v = target(hnew, tm_);
    put(pos_, v, m);
    put(size_, v, s);
    put(kind_, v, char((fl & LINE) ? V_LINE : V_FREE));
    put(bnd_, v, char(border ? 1 : 0));
    put(ref_, v, -1);
    put(deg_, v, 0);
    put(thint_, v, get(thint_, a));
    put(shint_, v, get(shint_, a) >= 0 ? get(shint_, a) : get(shint_, b));
    put(flag_, edge(hnew, tm_), fl);
    put(dead_, hnew, 0u);
    put(dead_, opposite(hnew, tm_), 0u);
    if (!is_border(hnew, tm_)) {
      halfedge_descriptor d = CGAL::Euler::split_face(hnew, next(h, tm_), tm_);
      put(flag_, edge(d, tm_), char(0));
      put(dead_, d, 0u);
      put(dead_, opposite(d, tm_), 0u);
    }
    halfedge_descriptor o = opposite(h, tm_);
    if (!is_border(o, tm_)) {
      halfedge_descriptor d =
          CGAL::Euler::split_face(o, next(opposite(hnew, tm_), tm_), tm_);
      put(flag_, edge(d, tm_), char(0));
      put(dead_, d, 0u);
      put(dead_, opposite(d, tm_), 0u);
    }
    ++counters.splits;
  }

  // A frozen edge longer than 4/3 L can never be split, so the face beside
  // it always keeps a long side: splitting that side puts the new vertex
  // halfway down to the frozen edge, and every later pass halves the height
  // again until the faces along the frozen edge are degenerate (a protected
  // border of edges 4 L folded into thousands of zero-area faces). Such a
  // split is refused when the new face on the frozen edge would be thinner
  // than the old one and than `frozen_split_min_deg`: the faces beside a long
  // frozen edge stay large and the mesh grades away from it.
  static constexpr double frozen_split_min_deg = 20.;

  bool split_thins_a_frozen_side(halfedge_descriptor h) const
  {
    static const double cthr = std::cos(frozen_split_min_deg * CGAL_PI / 180.);
    const vertex_descriptor a = source(h, tm_), b = target(h, tm_);
    const Vec3 pa = get(pos_, a), pb = get(pos_, b), m = 0.5 * (pa + pb);
    for (halfedge_descriptor g : {h, opposite(h, tm_)}) {
      if (is_border(g, tm_)) continue;
      // face (s, t, c) of g; after the split: (s, m, c) and (m, t, c)
      const vertex_descriptor s = source(g, tm_), t = target(g, tm_), c = target(next(g, tm_), tm_);
      const Vec3 ps = get(pos_, s), pt = get(pos_, t), pc = get(pos_, c);
      const double old_cos = min_angle_cos(ps, pt, pc);
      const halfedge_descriptor sides[2] = {prev(g, tm_), next(g, tm_)};  // (c, s), (t, c)
      for (int i = 0; i < 2; ++i) {
        const halfedge_descriptor side = sides[i];
        if (!(get(flag_, edge(side, tm_)) & (FROZEN | HELD))) continue;
        const double hi = 4. / 3. * tsize(source(side, tm_), target(side, tm_));
        if (sqlength(side) <= hi * hi) continue;
        const double new_cos = i == 0 ? min_angle_cos(ps, m, pc) : min_angle_cos(m, pt, pc);
        if (new_cos > cthr && new_cos > old_cos) return true;
      }
    }
    return false;
  }

  void split_long_edges()
  {
    std::vector<edge_descriptor> cand;
    std::size_t held = 0;
    for (int pass = 0; pass < 10; ++pass) {  // bounded: frozen long edges keep splitting their neighbours
      edges_where(cand, [&](edge_descriptor e) {
        if (get(flag_, e) & FROZEN) return false;
        halfedge_descriptor h = halfedge(e, tm_);
        double hi = 4. / 3. * tsize(source(h, tm_), target(h, tm_));
        return sqlength(h) > hi * hi;
      });
      if (cand.empty()) break;
      // splits leave the other candidates' end points unchanged
      std::size_t done = 0;
      for (edge_descriptor e : cand) {
        const halfedge_descriptor h = halfedge(e, tm_);
        if (budget_spent()) return;
        if (split_thins_a_frozen_side(h)) {
          put(flag_, edge(h, tm_), char(get(flag_, edge(h, tm_)) | HELD));
          ++held;
          continue;
        }
        put(flag_, edge(h, tm_), char(get(flag_, edge(h, tm_)) & ~HELD));
        split(h);
        ++done;
      }
      if (done == 0) break;
    }
    if (held != 0)
      for (edge_descriptor e : edges(tm_)) put(flag_, e, char(get(flag_, e) & ~HELD));
  }

  // --------------------------------------------------------------- collapse
  // may source(h) be removed into target(h)?
  bool may_remove(halfedge_descriptor h) const
  {
    vertex_descriptor v0 = source(h, tm_);
    char k = get(kind_, v0);
    if (k == V_FREE) return true;
    if (k != V_LINE) return false;
    if (!(get(flag_, edge(h, tm_)) & LINE)) return false;
    // sliding along a line: never merge two line edges of a triangle
    if (!is_border(h, tm_) && (get(flag_, edge(next(h, tm_), tm_)) & (LINE | FROZEN)) &&
        (get(flag_, edge(prev(h, tm_), tm_)) & (LINE | FROZEN)))
      return false;
    halfedge_descriptor o = opposite(h, tm_);
    if (!is_border(o, tm_) && (get(flag_, edge(next(o, tm_), tm_)) & (LINE | FROZEN)) &&
        (get(flag_, edge(prev(o, tm_), tm_)) & (LINE | FROZEN)))
      return false;
    return true;
  }

  // a pair of faces meeting at an angle sharper than this (normals more than
  // 120 degrees apart) is a fold; operations must not create new ones
  static bool folds(const Vec3& na, const Vec3& nb)
  {
    double d = dot(na, nb);
    return d < 0 && d * d > 0.25 * squared_norm(na) * squared_norm(nb);
  }

  Vec3 face_normal(halfedge_descriptor g) const
  {
    return triangle_normal(get(pos_, source(g, tm_)), get(pos_, target(g, tm_)),
                           get(pos_, target(next(g, tm_), tm_)));
  }

  struct Star_face
  {
    vertex_descriptor w, x;  // the face (w, centre, x)
    Vec3 before{}, after{};
  };

  bool geometry_ok(halfedge_descriptor h) const
  {
    vertex_descriptor v0 = source(h, tm_), v1 = target(h, tm_);
    const Vec3 p0 = get(pos_, v0), p1 = get(pos_, v1);
    // the star of v1 after the collapse, to find folds between its faces
    Star_face star[64];
    int ns = 0;
    for (halfedge_descriptor g : halfedges_around_target(v0, tm_)) {
      vertex_descriptor w = source(g, tm_);
      if (w == v1) continue;
      double hi = 4. / 3. * tsize(v1, w);
      if (squared_norm(get(pos_, w) - p1) > hi * hi) return false;
      if (is_border(g, tm_)) continue;
      vertex_descriptor x = target(next(g, tm_), tm_);  // face (w, v0, x)
      if (x == v1) continue;
      const Vec3 pw = get(pos_, w), px = get(pos_, x);
      Vec3 n0 = triangle_normal(pw, p0, px), n1 = triangle_normal(pw, p1, px);
      double l0 = squared_norm(n0), l1 = squared_norm(n1);
      if (!(l1 > 1e-24 * l0) || l1 == 0) return false;
      double d = dot(n0, n1);
      if (d <= 0 || d * d < collapse_cos_ * collapse_cos_ * l0 * l1) return false;
      // the unchanged face across (x, w)
      halfedge_descriptor out = opposite(prev(g, tm_), tm_);
      if (!is_border(out, tm_)) {
        Vec3 no = face_normal(out);
        if (folds(n1, no) && !folds(n0, no)) return false;
      }
      if (ns == 64) return false;  // a huge star: not worth the risk
      star[ns++] = {w, x, n0, n1};
    }
    for (halfedge_descriptor g : halfedges_around_target(v1, tm_)) {
      if (is_border(g, tm_)) continue;
      vertex_descriptor w = source(g, tm_), x = target(next(g, tm_), tm_);
      if (w == v0 || x == v0) continue;  // removed with the collapse
      if (ns == 64) return false;
      Vec3 n = face_normal(g);
      star[ns++] = {w, x, n, n};
    }
    for (int i = 0; i < ns; ++i)
      for (int j = 0; j < ns; ++j)
        if (star[i].x == star[j].w && i != j && folds(star[i].after, star[j].after) &&
            !folds(star[i].before, star[j].before))
          return false;
    return true;
  }

  void mark_dead_around(vertex_descriptor v, unsigned value)
  {
    for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
      put(dead_, g, value);
      put(dead_, opposite(g, tm_), value);
    }
  }

  bool collapse(halfedge_descriptor h)
  {
    vertex_descriptor v0 = source(h, tm_), v1 = target(h, tm_);
    // survivor's attributes
    Vec3 p1 = get(pos_, v1);
    double s1 = get(size_, v1);
    char k1 = get(kind_, v1), b1 = get(bnd_, v1);
    int r1 = get(ref_, v1), t1 = get(thint_, v1), g1 = get(shint_, v1);
    // the edges merged by the collapse: their flags are or-ed
    vertex_descriptor wl = GT::null_vertex(), wr = GT::null_vertex();
    char fl = 0, fr = 0;
    if (!is_border(h, tm_)) {
      wl = target(next(h, tm_), tm_);
      fl = get(flag_, edge(next(h, tm_), tm_)) | get(flag_, edge(prev(h, tm_), tm_));
    }
    halfedge_descriptor o = opposite(h, tm_);
    if (!is_border(o, tm_)) {
      wr = target(next(o, tm_), tm_);
      fr = get(flag_, edge(next(o, tm_), tm_)) | get(flag_, edge(prev(o, tm_), tm_));
    }
    mark_dead_around(v0, stamp_);
    mark_dead_around(v1, stamp_);
    vertex_descriptor k = CGAL::Euler::collapse_edge(edge(h, tm_), tm_);
    put(pos_, k, p1);
    put(size_, k, s1);
    put(kind_, k, k1);
    put(bnd_, k, b1);
    put(ref_, k, r1);
    put(thint_, k, t1);
    put(shint_, k, g1);
    if (wl != GT::null_vertex()) {
      auto he = halfedge(k, wl, tm_);
      if (he.second) put(flag_, edge(he.first, tm_), fl);
    }
    if (wr != GT::null_vertex()) {
      auto he = halfedge(k, wr, tm_);
      if (he.second) put(flag_, edge(he.first, tm_), fr);
    }
    mark_dead_around(k, 0u);
    ++counters.collapses;
    return true;
  }

  bool try_collapse(halfedge_descriptor h)
  {
    if (budget_spent()) return false;
    edge_descriptor e = edge(h, tm_);
    if (get(flag_, e) & FROZEN) return false;
    halfedge_descriptor cands[2] = {h, opposite(h, tm_)};
    // prefer removing the free end so that lines keep their vertices
    if (get(kind_, source(h, tm_)) > get(kind_, target(h, tm_))) std::swap(cands[0], cands[1]);
    for (halfedge_descriptor c : cands) {
      if (!may_remove(c)) continue;
      if (!geometry_ok(c)) continue;
      if (!CGAL::Euler::does_satisfy_link_condition(e, tm_)) return false;
      return collapse(c);
    }
    return false;
  }

  void collapse_short_edges()
  {
    ++stamp_;
    std::vector<edge_descriptor> cand;
    edges_where(cand, [&](edge_descriptor e) {
      if (get(flag_, e) & FROZEN) return false;
      halfedge_descriptor h = halfedge(e, tm_);
      double lo = 4. / 5. * tsize(source(h, tm_), target(h, tm_));
      return sqlength(h) < lo * lo;
    });
    for (edge_descriptor e : cand) {
      if (budget_spent()) return;
      const halfedge_descriptor h = halfedge(e, tm_);
      if (get(dead_, h) == stamp_) continue;  // removed or changed by an earlier collapse
      double lo = 4. / 5. * tsize(source(h, tm_), target(h, tm_));
      if (sqlength(h) >= lo * lo) continue;
      try_collapse(h);
    }
  }

  // ------------------------------------------------------------------- flip
  // would flipping h fold one of the new faces against an outer neighbour?
  bool flip_folds(halfedge_descriptor h) const
  {
    halfedge_descriptor o = opposite(h, tm_);
    const Vec3 pa = get(pos_, source(h, tm_)), pb = get(pos_, target(h, tm_)),
               pc = get(pos_, target(next(h, tm_), tm_)), pd = get(pos_, target(next(o, tm_), tm_));
    const Vec3 m1 = triangle_normal(pa, pb, pc), m2 = triangle_normal(pb, pa, pd);  // (a,b,c), (b,a,d)
    const Vec3 n1 = triangle_normal(pa, pd, pc), n2 = triangle_normal(pb, pc, pd);  // (a,d,c), (b,c,d)
    // outer edges: (b,c), (c,a) of the face of h; (a,d), (d,b) of the face of o
    halfedge_descriptor outer[4] = {next(h, tm_), prev(h, tm_), next(o, tm_), prev(o, tm_)};
    const Vec3* before[4] = {&m1, &m1, &m2, &m2};
    const Vec3* after[4] = {&n2, &n1, &n1, &n2};
    for (int i = 0; i < 4; ++i) {
      halfedge_descriptor g = opposite(outer[i], tm_);
      if (is_border(g, tm_)) continue;
      Vec3 no = face_normal(g);
      if (folds(*after[i], no) && !folds(*before[i], no)) return true;
    }
    return false;
  }

  // the valence test of flipping edge a-b (opposite corners c, d) with the
  // degrees in deg_: the deviation from 6 (4 on the border) must go down and
  // a, b keep a valid valence
  bool flip_lowers_valence_deviation(vertex_descriptor a, vertex_descriptor b, vertex_descriptor c,
                                     vertex_descriptor d) const
  {
    int da = get(deg_, a), db = get(deg_, b), dc = get(deg_, c), dd = get(deg_, d);
    int ta = get(bnd_, a) ? 4 : 6, tb = get(bnd_, b) ? 4 : 6, tc = get(bnd_, c) ? 4 : 6,
        td = get(bnd_, d) ? 4 : 6;
    int before = std::abs(da - ta) + std::abs(db - tb) + std::abs(dc - tc) + std::abs(dd - td);
    int after = std::abs(da - 1 - ta) + std::abs(db - 1 - tb) + std::abs(dc + 1 - tc) +
                std::abs(dd + 1 - td);
    if (after >= before) return false;
    return !(da - 1 < (get(bnd_, a) ? 2 : 3) || db - 1 < (get(bnd_, b) ? 2 : 3));
  }

  void flip_edges()
  {
    std::vector<vertex_descriptor> vs;
    vertices_where(vs, [](vertex_descriptor) { return true; });
    if constexpr (parallel_) sort_by_halfedge(tm_, vs, relax_buffers_.order);
    for_each_index(vs.size(), [&](std::size_t i) { put(deg_, vs[i], static_cast<int>(degree(vs[i], tm_))); });
    std::vector<edge_descriptor> cand;
    edges_where(cand, [&](edge_descriptor e) { return get(flag_, e) == 0; });
    auto corners = [&](halfedge_descriptor h) {
      return std::array<vertex_descriptor, 4>{source(h, tm_), target(h, tm_), target(next(h, tm_), tm_),
                                              target(next(opposite(h, tm_), tm_), tm_)};
    };
    // A flip changes the degrees of its four corners and the faces of its
    // edge only: an edge none of whose four corners took part in a flip since
    // the scan passes the valence test now exactly when it passed it then.
    // So with threads the test runs on all candidates at once, and instead of
    // the loop over all of them, the edges that passed, and those that a flip
    // touched (its corners' edges and the edges facing them) later in the
    // order, are taken in the order of the loop (edge index): the same flips.
    if constexpr (parallel_) {
      std::vector<char> passed(cand.size());
      for_each_index(cand.size(), [&](std::size_t i) {
        const auto q = corners(halfedge(cand[i], tm_));
        passed[i] = q[2] != q[3] && flip_lowers_valence_deviation(q[0], q[1], q[2], q[3]);
      });
      std::vector<std::size_t> queue;  // a min-heap of edge indices
      for (std::size_t i = 0; i < cand.size(); ++i)
        if (passed[i]) queue.push_back(std::size_t(cand[i]));
      const std::greater<std::size_t> later;
      std::make_heap(queue.begin(), queue.end(), later);
      std::size_t last = std::size_t(-1);
      while (!queue.empty()) {
        std::pop_heap(queue.begin(), queue.end(), later);
        const std::size_t i = queue.back();
        queue.pop_back();
        if (i == last) continue;  // queued twice
        last = i;
        const edge_descriptor e(static_cast<typename TriangleMesh::size_type>(i));
        const auto q = corners(halfedge(e, tm_));
        if (!try_flip(halfedge(e, tm_), q)) continue;
        for (vertex_descriptor v : q)
          for (halfedge_descriptor g : halfedges_around_target(v, tm_))
            for (halfedge_descriptor x : {g, prev(g, tm_)}) {
              const edge_descriptor t = edge(x, tm_);
              if (std::size_t(t) > i && get(flag_, t) == 0 && !(is_border(x, tm_) && x != g)) {
                queue.push_back(std::size_t(t));
                std::push_heap(queue.begin(), queue.end(), later);
              }
            }
      }
    } else {
      for (edge_descriptor e : cand) {
        const halfedge_descriptor h = halfedge(e, tm_);
        try_flip(h, corners(h));
      }
    }
  }

  // flips h = a-b (opposite corners c, d) when that lowers the valence
  // deviation and no face flips, degenerates or folds
  bool try_flip(halfedge_descriptor h, const std::array<vertex_descriptor, 4>& q)
  {
    const vertex_descriptor a = q[0], b = q[1], c = q[2], d = q[3];
    if (c == d) return false;
    if (!flip_lowers_valence_deviation(a, b, c, d)) return false;
    const int da = get(deg_, a), db = get(deg_, b), dc = get(deg_, c), dd = get(deg_, d);
    const Vec3 pa = get(pos_, a), pb = get(pos_, b), pc = get(pos_, c), pd = get(pos_, d);
    Vec3 m1 = triangle_normal(pa, pb, pc), m2 = triangle_normal(pb, pa, pd);  // (a,b,c), (b,a,d)
    Vec3 n1 = triangle_normal(pa, pd, pc), n2 = triangle_normal(pb, pc, pd);  // (a,d,c), (b,c,d)
    Vec3 m = m1 + m2;
    double l1 = squared_norm(n1), l2 = squared_norm(n2), lm = squared_norm(m1) + squared_norm(m2);
    if (!(l1 > 1e-12 * lm) || !(l2 > 1e-12 * lm)) return false;
    if (dot(n1, m) <= 0 || dot(n2, m) <= 0 || dot(n1, n2) <= 0) return false;
    if (flip_folds(h)) return false;
    if (halfedge(c, d, tm_).second) return false;
    CGAL::Euler::flip_edge(h, tm_);
    put(deg_, a, da - 1);
    put(deg_, b, db - 1);
    put(deg_, c, dc + 1);
    put(deg_, d, dd + 1);
    ++counters.flips;
    return true;
  }

  // --------------------------------------------------- bad-triangle cleanup
  // Near frozen vertices and feature lines relaxation cannot even out the
  // triangles, so faces with an angle under `min_deg` get an angle-improving
  // flip of their longest edge, or else the collapse of their shortest edge.
  static double min_angle_cos(const Vec3& a, const Vec3& b, const Vec3& c)
  {
    // largest cosine of the three angles (= cosine of the smallest angle)
    auto cosine = [](const Vec3& u, const Vec3& v) {
      double l = std::sqrt(squared_norm(u) * squared_norm(v));
      return l > 0 ? dot(u, v) / l : 1.;
    };
    return std::max({cosine(b - a, c - a), cosine(a - b, c - b), cosine(a - c, b - c)});
  }

  // min-angle cosine after flipping h, or 2 when the flip is not allowed
  double flip_gain(halfedge_descriptor h) const
  {
    if (is_border(h, tm_) || is_border(opposite(h, tm_), tm_)) return 2.;
    if (!flip_improves(h)) return 2.;
    halfedge_descriptor o = opposite(h, tm_);
    const Vec3 pa = get(pos_, source(h, tm_)), pb = get(pos_, target(h, tm_)),
               pc = get(pos_, target(next(h, tm_), tm_)), pd = get(pos_, target(next(o, tm_), tm_));
    return std::max(min_angle_cos(pa, pd, pc), min_angle_cos(pb, pc, pd));
  }

  bool flip_improves(halfedge_descriptor h) const
  {
    if (get(flag_, edge(h, tm_)) != 0) return false;
    halfedge_descriptor o = opposite(h, tm_);
    vertex_descriptor a = source(h, tm_), b = target(h, tm_);
    vertex_descriptor c = target(next(h, tm_), tm_), d = target(next(o, tm_), tm_);
    if (c == d) return false;
    if (degree(a, tm_) <= 3 || degree(b, tm_) <= 3) return false;
    const Vec3 pa = get(pos_, a), pb = get(pos_, b), pc = get(pos_, c), pd = get(pos_, d);
    double before = std::max(min_angle_cos(pa, pb, pc), min_angle_cos(pb, pa, pd));
    double after = std::max(min_angle_cos(pa, pd, pc), min_angle_cos(pb, pc, pd));
    if (!(after < before)) return false;
    Vec3 m = triangle_normal(pa, pb, pc) + triangle_normal(pb, pa, pd);
    Vec3 n1 = triangle_normal(pa, pd, pc), n2 = triangle_normal(pb, pc, pd);
    // the flipped pair must stay nearly coplanar with the old one (no ridge created)
    double lm = norm(m);
    if (!(lm > 0) || dot(n1, m) <= 0.7 * norm(n1) * lm || dot(n2, m) <= 0.7 * norm(n2) * lm)
      return false;
    if (flip_folds(h)) return false;
    return !halfedge(c, d, tm_).second;
  }

  // has the face of h an angle whose cosine is above `cthr`?
  bool face_angle_below(halfedge_descriptor h, double cthr) const
  {
    return min_angle_cos(get(pos_, source(h, tm_)), get(pos_, target(h, tm_)),
                         get(pos_, target(next(h, tm_), tm_))) > cthr;
  }

  void fix_bad_triangles(double min_deg)
  {
    const double cthr = std::cos(min_deg * CGAL_PI / 180.);
    std::vector<face_descriptor> bad_faces;
    faces_where(bad_faces, [&](face_descriptor f) { return face_angle_below(halfedge(f, tm_), cthr); });
    if (bad_faces.empty()) return;
    // halfedges, taken now: the flips below move the halfedge of a face
    std::vector<halfedge_descriptor> bad(bad_faces.size());
    for (std::size_t i = 0; i < bad.size(); ++i) bad[i] = halfedge(bad_faces[i], tm_);
    ++stamp_;
    for (halfedge_descriptor h : bad) {
      if (get(dead_, h) == stamp_ || is_border(h, tm_)) continue;
      halfedge_descriptor e3[3] = {h, next(h, tm_), prev(h, tm_)};
      const Vec3 p[3] = {get(pos_, source(h, tm_)), get(pos_, target(h, tm_)),
                         get(pos_, target(next(h, tm_), tm_))};
      if (!(min_angle_cos(p[0], p[1], p[2]) > cthr)) continue;  // fixed meanwhile
      int longest = 0, shortest = 0;
      double l[3];
      for (int i = 0; i < 3; ++i) {
        l[i] = squared_norm(p[(i + 1) % 3] - p[i]);
        if (l[i] > l[longest]) longest = i;
        if (l[i] < l[shortest]) shortest = i;
      }
      // the best angle-improving flip among the three edges
      int bi = -1;
      double bc = 2.;
      for (int i = 0; i < 3; ++i) {
        double c = flip_gain(e3[i]);
        if (c < bc) { bc = c; bi = i; }
      }
      if (bi >= 0) {
        CGAL::Euler::flip_edge(e3[bi], tm_);
        ++counters.flips;
        continue;
      }
      // a needle: remove its shortest edge when that is allowed
      if (l[shortest] < 0.25 * l[longest] && try_collapse(e3[shortest])) continue;
      // a short edge between two lines: slide one of its ends along its own line
      if (l[shortest] < 0.5 * l[longest]) {
        halfedge_descriptor hs = e3[shortest];
        for (vertex_descriptor v : {source(hs, tm_), target(hs, tm_)}) {
          if (get(kind_, v) != V_LINE) continue;
          halfedge_descriptor best = GT::null_halfedge();
          double bl = std::numeric_limits<double>::infinity();
          for (halfedge_descriptor g : halfedges_around_source(v, tm_)) {
            if (!(get(flag_, edge(g, tm_)) & LINE)) continue;
            double lg = sqlength(g);
            if (lg < bl) { bl = lg; best = g; }
          }
          if (best != GT::null_halfedge() && bl < 0.8 * 0.8 * l[longest] && may_remove(best) &&
              geometry_ok(best) && CGAL::Euler::does_satisfy_link_condition(edge(best, tm_), tm_)) {
            collapse(best);
            break;
          }
        }
      }
    }
  }

  // ------------------------------------------- min-angle vertex optimisation
  // Relaxation evens out areas, not angles; next to feature lines (narrow
  // strips, wedges between lines) its fixed point can keep a thin triangle.
  // The vertices of the worst faces try a few positions towards their
  // neighbours (line vertices only along their line), projected back onto
  // the input, and keep the one that raises the smallest angle of their star
  // without turning any face more than ~45 degrees.

  // cosine of the smallest angle of the star of v with v at p (2: rejected)
  double star_min_cos(vertex_descriptor v, const Vec3& p) const
  {
    double worst = -1;
    const Vec3 pv = get(pos_, v);
    for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
      if (is_border(g, tm_)) continue;
      const Vec3 pa = get(pos_, source(g, tm_)), pb = get(pos_, target(next(g, tm_), tm_));
      Vec3 n0 = cross(pv - pa, pb - pv), n1 = cross(p - pa, pb - p);
      double d = dot(n0, n1);
      if (!(d > 0) || d * d < 0.5 * squared_norm(n0) * squared_norm(n1)) return 2.;
      worst = std::max(worst, min_angle_cos(pa, p, pb));
    }
    return worst;
  }

  void optimize_bad_vertices(double min_deg, bool project, int rounds)
  {
    const double cthr = std::cos(min_deg * CGAL_PI / 180.);
    const double sliver_cos = std::cos(10. * CGAL_PI / 180.);
    const bool lines = ref.has_lines(), surf = ref.has_surface();
    std::vector<vertex_descriptor> vs, moved;
    auto add_vertices = [&](halfedge_descriptor h) {
      for (vertex_descriptor v : {source(h, tm_), target(h, tm_), target(next(h, tm_), tm_)})
        if (get(kind_, v) == V_FREE || (relax_lines_ && get(kind_, v) == V_LINE)) vs.push_back(v);
    };
    auto add_if_bad = [&](halfedge_descriptor h) {
      if (face_angle_below(h, cthr)) add_vertices(h);
    };
    // one scan of the mesh; later rounds revisit the bad faces around moved vertices
    {
      std::vector<face_descriptor> bad;
      faces_where(bad, [&](face_descriptor f) { return face_angle_below(halfedge(f, tm_), cthr); });
      for (face_descriptor f : bad) add_vertices(halfedge(f, tm_));
    }
    for (int round = 0; round < rounds && !vs.empty(); ++round) {
      std::sort(vs.begin(), vs.end());
      vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
      moved.clear();
      for (vertex_descriptor v : vs) {
        const bool line = get(kind_, v) == V_LINE;
        const Vec3 pv = get(pos_, v);
        double best = star_min_cos(v, pv), best_size = get(size_, v);
        Vec3 bp = pv;
        int th = get(thint_, v), sh = get(shint_, v), bth = th, bsh = sh;
        for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
          if (line && !(get(flag_, edge(g, tm_)) & LINE)) continue;
          const Vec3 d = get(pos_, source(g, tm_)) - pv;
          for (double t : {0.04, 0.08, 0.15, 0.25, 0.35}) {
            Vec3 c = pv + t * d;
            // never query the projection trees with NaN (exact predicates abort on it)
            if (!is_finite(c)) continue;
            double s = get(size_, v);
            int h1 = th, h2 = sh;
            if (project) {
              if (!line && surf)
                c = ref.project_surface(c, s, h1, get(size_, v));
              else if (line && lines)
                c = ref.project_line(c, s, h2);
            }
            if (!is_finite(c)) continue;
            double q = star_min_cos(v, c);
            if (q < best - 1e-9) { best = q; bp = c; best_size = s; bth = h1; bsh = h2; }
          }
        }
        if (bp == pv) continue;
        // With a guard (adaptive mode): a move that widens an angle can swing
        // the vertex's faces off the input (on armadillo at 0.004 x diagonal
        // this pass made the largest deviation, 2.2 x the tolerance, where
        // every face had been within it): kept only when its faces stay
        // within the guard, or within their deviation before, unless it
        // removes an angle under 10 degrees (a sliver costs more).
        const bool guarded = guard_ > 0 && surf && project && !(star_min_cos(v, pv) > sliver_cos);
        const double before = guarded ? star_deviation(v) : 0.;
        put(pos_, v, bp);
        put(thint_, v, bth);
        if (guarded) {
          const double after = star_deviation(v);
          if (after > std::max(guard_, before)) {
            put(pos_, v, pv);
            put(thint_, v, th);
            continue;
          }
        }
        if (!uniform_) put(size_, v, best_size);
        put(shint_, v, bsh);
        moved.push_back(v);
      }
      vs.clear();
      for (vertex_descriptor v : moved)
        for (halfedge_descriptor g : halfedges_around_target(v, tm_))
          if (!is_border(g, tm_)) add_if_bad(g);
    }
  }

  // ------------------------------------------------------- relax + project
  template <typename F>
  void for_each_index(std::size_t n, const F& f)
  {
    if (parallel_ && n > 2000)
      parallel_for_index(n, 512, f);
    else
      for (std::size_t i = 0; i < n; ++i) f(i);
  }

  Vec3 vertex_normal(vertex_descriptor v) const
  {
    Vec3 n{};
    const Vec3 pv = get(pos_, v);
    for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
      if (is_border(g, tm_)) continue;
      n += cross(pv - get(pos_, source(g, tm_)), get(pos_, target(next(g, tm_), tm_)) - pv);
    }
    return n;
  }

  struct Relax_buffers
  {
    std::vector<vertex_descriptor> vs;
    std::vector<Vec3> np, normal, old;
    std::vector<double> ns;
    std::vector<char> bad, undone;
    std::vector<vertex_descriptor> order;  // scratch of sort_by_halfedge, for every vertex pass
  };

  Relax_buffers relax_buffers_;

  void relax_and_project(bool project)
  {
    // the buffers live across iterations: at 1M faces, fresh ones cost
    // their page faults (~40 MB) every iteration
    auto& vs = relax_buffers_.vs;
    vs.clear();
    vertices_where(vs, [&](vertex_descriptor v) {
      return get(kind_, v) == V_FREE || (relax_lines_ && get(kind_, v) == V_LINE);
    });
    // in the order of their halfedges (internal/vertex_order.h): each move is
    // computed from the positions before the round, so the order changes no
    // result, only the time
    if constexpr (parallel_) sort_by_halfedge(tm_, vs, relax_buffers_.order);
    auto& np = relax_buffers_.np;
    auto& normal = relax_buffers_.normal;
    auto& old = relax_buffers_.old;
    auto& ns = relax_buffers_.ns;
    np.resize(vs.size());
    normal.resize(vs.size());
    old.resize(vs.size());
    ns.resize(vs.size());
    const bool lines = ref.has_lines(), surf = ref.has_surface();
    for_each_index(vs.size(), [&](std::size_t i) {
      vertex_descriptor v = vs[i];
      const Vec3 pv = get(pos_, v);
      old[i] = pv;
      Vec3 c{};
      double sw = 0;
      Vec3 n{};
      if (get(kind_, v) == V_FREE) {
        const double sv = uniform_ ? 1. : get(size_, v);
        for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
          if (is_border(g, tm_)) continue;
          vertex_descriptor a = source(g, tm_), b = target(next(g, tm_), tm_);
          const Vec3 pa = get(pos_, a), pb = get(pos_, b);
          Vec3 cr = cross(pv - pa, pb - pv);
          n += cr;
          double w = norm(cr);
          if (!uniform_) w *= (get(size_, a) + get(size_, b) + sv) / 3.;
          c += w * (pa + pb + pv);
          sw += 3. * w;
        }
        if (sw > 0) {
          c *= 1. / sw;
          double nl = norm(n);
          if (nl > 0) {
            n *= 1. / nl;
            c += n * dot(n, pv - c);
          }
        } else
          c = pv;
      } else {
        for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
          if (!(get(flag_, edge(g, tm_)) & LINE)) continue;
          vertex_descriptor a = source(g, tm_);
          const Vec3 pa = get(pos_, a);
          double w = norm(pa - pv);
          if (!uniform_) w *= 0.5 * (get(size_, a) + get(size_, v));
          c += w * 0.5 * (pa + pv);
          sw += w;
        }
        c = sw > 0 ? c * (1. / sw) : pv;
        n = vertex_normal(v);
      }
      normal[i] = n;
      double s = get(size_, v);
      // never query the projection trees with NaN (exact predicates abort on it)
      if (!is_finite(c)) c = pv;
      if (project && is_finite(c)) {
        if (get(kind_, v) == V_FREE && surf) {
          int hint = get(thint_, v);
          c = ref.project_surface(c, s, hint, get(size_, v));
          put(thint_, v, hint);  // own slot only: safe in parallel
        } else if (get(kind_, v) == V_LINE && lines) {
          int hint = get(shint_, v);
          c = ref.project_line(c, s, hint);
          put(shint_, v, hint);
        }
      }
      np[i] = c;
      ns[i] = s;
    });
    // apply (each vertex writes only its own slot)
    for_each_index(vs.size(), [&](std::size_t i) {
      put(pos_, vs[i], np[i]);
      if (!uniform_) put(size_, vs[i], ns[i]);
    });
    // undo moves that fold a face over (checked against the normal before).
    // The moves were made all at once, so undoing one can fold a face of a
    // neighbour that was checked against the undone position: check the
    // kept moves again until none folds (each round only undoes more, and
    // with every move undone the mesh is the one before).
    auto& bad = relax_buffers_.bad;
    auto& undone = relax_buffers_.undone;
    bad.assign(vs.size(), 0);
    undone.assign(vs.size(), 0);
    auto check = [&](std::size_t i) {
      if (undone[i]) return;
      vertex_descriptor v = vs[i];
      const Vec3 pv = get(pos_, v);
      for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
        if (is_border(g, tm_)) continue;
        Vec3 fn = cross(pv - get(pos_, source(g, tm_)), get(pos_, target(next(g, tm_), tm_)) - pv);
        if (dot(fn, normal[i]) <= 0) { bad[i] = 1; break; }
      }
    };
    for (;;) {
      for_each_index(vs.size(), check);
      bool more = false;
      for (std::size_t i = 0; i < vs.size(); ++i)
        if (bad[i] && !undone[i]) {
          put(pos_, vs[i], old[i]);
          undone[i] = 1;
          more = true;
        }
      if (!more) break;
    }
    for (std::size_t i = 0; i < vs.size(); ++i)
      if (!undone[i]) ++counters.relaxed;
  }

  // ------------------------------------------------------- error control
  // The sizing field predicts the deviation from the curvature; where the
  // estimate is off (a peak smoothed away, a flat-faceted input, a thin part)
  // the faces deviate more. Their samples (centroid, edge midpoints, as the
  // Hausdorff distance is measured) are projected onto the input, and where
  // one lies farther than `limit` the sizing around the face is lowered so
  // that the deviation, quadratic in the edge length, comes down to `goal`.

  /// largest distance of the samples of the face of `h` to the input surface
  double face_deviation(halfedge_descriptor h) const
  {
    const vertex_descriptor v3[3] = {source(h, tm_), target(h, tm_), target(next(h, tm_), tm_)};
    const Vec3 p[3] = {get(pos_, v3[0]), get(pos_, v3[1]), get(pos_, v3[2])};
    int hint = -1;
    for (vertex_descriptor v : v3)
      if (hint < 0 && get(kind_, v) == V_FREE) hint = get(thint_, v);
    for (vertex_descriptor v : v3)
      if (hint < 0) hint = get(thint_, v);
    const double reach =
        std::sqrt(std::max({squared_norm(p[1] - p[0]), squared_norm(p[2] - p[1]), squared_norm(p[0] - p[2])}));
    const Vec3 samples[4] = {(1. / 3.) * (p[0] + p[1] + p[2]), 0.5 * (p[0] + p[1]),
                             0.5 * (p[1] + p[2]), 0.5 * (p[2] + p[0])};
    double worst = 0;
    for (const Vec3& q : samples) {
      if (!is_finite(q)) continue;
      double s = 0;
      int h1 = hint;
      const Vec3 c = ref.project_surface(q, s, h1, reach);
      worst = std::max(worst, squared_norm(c - q));
    }
    return std::sqrt(worst);
  }

  /// the largest deviation from the input of the faces around `v`
  double star_deviation(vertex_descriptor v) const
  {
    double d = 0;
    for (halfedge_descriptor g : halfedges_around_target(v, tm_))
      if (!is_border(g, tm_)) d = std::max(d, face_deviation(g));
    return d;
  }

  /// lowers the sizing around faces deviating more than `limit` (see above);
  /// returns the number of such faces.
  std::size_t refine_deviating_faces(double limit, double goal, double lmin)
  {
    if (!ref.has_surface()) return 0;
    std::vector<halfedge_descriptor> fs;
    for (face_descriptor f : faces(tm_)) fs.push_back(halfedge(f, tm_));
    std::vector<double> dev(fs.size(), 0.);
    for_each_index(fs.size(), [&](std::size_t i) { dev[i] = face_deviation(fs[i]); });
    std::size_t bad = 0;
    for (std::size_t i = 0; i < fs.size(); ++i) {
      if (!(dev[i] > limit)) continue;
      ++bad;
      const halfedge_descriptor h = fs[i];
      const vertex_descriptor v3[3] = {source(h, tm_), target(h, tm_), target(next(h, tm_), tm_)};
      const Vec3 p[3] = {get(pos_, v3[0]), get(pos_, v3[1]), get(pos_, v3[2])};
      const double longest = std::sqrt(
          std::max({squared_norm(p[1] - p[0]), squared_norm(p[2] - p[1]), squared_norm(p[0] - p[2])}));
      const double L = std::max(lmin, longest * std::sqrt(goal / dev[i]));
      const Vec3 c = (1. / 3.) * (p[0] + p[1] + p[2]);
      for (vertex_descriptor v : v3) {
        if (get(size_, v) > L) put(size_, v, L);
        ref.lower_sizing_near(c, longest, get(thint_, v), L);
      }
    }
    return bad;
  }

  // The relaxation after the last error-control round moves faces over the
  // tolerance again (1M scan at 0.0005 x diagonal: 254 faces over it after
  // the last round, the worst at 1.5 x), and a Hausdorff distance is its
  // worst face. So the faces still over `limit` once the iterations are done
  // get their longest edge split at the input surface, worst first, with no
  // relaxation after that could undo it; a split that would fold a face, or
  // make an angle smaller than both `min_deg` and the smallest angle of the
  // faces it splits, is not made.

  /// the input-surface point of the midpoint of `h` for a vertex of kind
  /// `line` (the midpoint itself without a reference or when not finite)
  Vec3 projected_midpoint(halfedge_descriptor h, bool line, double& size, int& hint) const
  {
    const vertex_descriptor a = source(h, tm_), b = target(h, tm_);
    const Vec3 m = 0.5 * (get(pos_, a) + get(pos_, b));
    size = 0.5 * (get(size_, a) + get(size_, b));
    hint = line ? (get(shint_, a) >= 0 ? get(shint_, a) : get(shint_, b)) : get(thint_, a);
    if (!is_finite(m)) return m;
    Vec3 c = m;
    if (line && ref.has_lines())
      c = ref.project_line(m, size, hint);
    else if (!line && ref.has_surface())
      c = ref.project_surface(m, size, hint, std::sqrt(sqlength(h)));
    return is_finite(c) ? c : m;
  }

  /// may `h` be split with its new vertex at `c` (see above)?
  bool split_keeps_faces(halfedge_descriptor h, const Vec3& c, double min_cos) const
  {
    for (halfedge_descriptor g : {h, opposite(h, tm_)}) {
      if (is_border(g, tm_)) continue;
      const Vec3 ps = get(pos_, source(g, tm_)), pt = get(pos_, target(g, tm_)),
                 pa = get(pos_, target(next(g, tm_), tm_));
      const Vec3 n = triangle_normal(ps, pt, pa);
      if (dot(triangle_normal(ps, c, pa), n) <= 0 || dot(triangle_normal(c, pt, pa), n) <= 0) return false;
      const double limit = std::max(min_cos, min_angle_cos(ps, pt, pa));
      if (min_angle_cos(ps, c, pa) > limit || min_angle_cos(c, pt, pa) > limit) return false;
    }
    return true;
  }

  /// splits the longest edge of the faces deviating more than `limit`, in
  /// rounds (see above); at most `max_splits` splits. Returns the splits made.
  std::size_t split_deviating_faces(double limit, std::size_t max_splits, double min_deg, int rounds = 3)
  {
    if (!ref.has_surface()) return 0;
    const double min_cos = std::cos(min_deg * CGAL_PI / 180.);
    std::size_t made = 0;
    std::vector<halfedge_descriptor> fs, cand;
    std::vector<double> dev;
    std::vector<std::size_t> order;
    std::vector<vertex_descriptor> added;
    for (int round = 0; round < rounds && made < max_splits; ++round) {
      fs.clear();
      for (face_descriptor f : faces(tm_)) fs.push_back(halfedge(f, tm_));
      dev.assign(fs.size(), 0.);
      for_each_index(fs.size(), [&](std::size_t i) { dev[i] = face_deviation(fs[i]); });
      order.clear();
      for (std::size_t i = 0; i < fs.size(); ++i)
        if (dev[i] > limit) order.push_back(i);
      if (order.empty()) break;
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return dev[a] > dev[b]; });
      // the longest edge that may be split, one per face; an edge once
      cand.clear();
      ++stamp_;
      for (std::size_t i : order) {
        halfedge_descriptor best = GT::null_halfedge();
        double bl = -1;
        for (halfedge_descriptor g : CGAL::halfedges_around_face(fs[i], tm_)) {
          if (get(flag_, edge(g, tm_)) & FROZEN) continue;
          const double l = sqlength(g);
          if (l > bl) { bl = l; best = g; }
        }
        if (best == GT::null_halfedge() || get(dead_, best) == stamp_) continue;
        put(dead_, best, stamp_);
        put(dead_, opposite(best, tm_), stamp_);
        cand.push_back(best);
      }
      // a bounded count is spread over the rounds: the worst faces may need a second split
      const std::size_t round_end = made + std::max<std::size_t>(1, (max_splits - made) / std::size_t(rounds - round));
      added.clear();
      for (halfedge_descriptor h : cand) {
        if (made >= round_end || budget_spent()) break;
        const bool line = (get(flag_, edge(h, tm_)) & LINE) != 0;
        double size = 0;
        int hint = -1;
        const Vec3 c = projected_midpoint(h, line, size, hint);
        if (!split_keeps_faces(h, c, min_cos)) continue;
        const halfedge_descriptor o = opposite(h, tm_);
        split(h);
        // split() puts the new vertex at the midpoint: it is the target of prev(h)'s source side
        const vertex_descriptor v = source(h, tm_);
        put(pos_, v, c);
        put(size_, v, size);
        if (line) put(shint_, v, hint); else put(thint_, v, hint);
        put(dead_, h, stamp_);
        put(dead_, o, stamp_);
        added.push_back(v);
        ++made;
      }
      if (added.empty()) break;
      flip_around(added);
    }
    return made;
  }

  /// the edges opposite each of `vs` flipped where that raises the smallest
  /// angle of their faces (one flip per vertex: its star changes)
  void flip_around(const std::vector<vertex_descriptor>& vs)
  {
    for (vertex_descriptor v : vs)
      for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
        if (is_border(g, tm_)) continue;
        const halfedge_descriptor e = next(g, tm_);  // the edge opposite v
        if (is_border(opposite(e, tm_), tm_) || !flip_improves(e)) continue;
        CGAL::Euler::flip_edge(e, tm_);
        ++counters.flips;
        break;
      }
  }

  // The other direction of the Hausdorff distance: input points the mesh
  // passes far from (a thin part cut short, the tip of a finger), which no
  // face sample sees. After the last iteration the face nearest to each input
  // point farther than `limit` from the mesh has its longest edge split with
  // the new vertex at that point (it lies on the input), farthest point
  // first, one split per face and round, under the rules of
  // split_deviating_faces; line edges and points on lines are left to the
  // lines. Later rounds measure only the points that were far.

  /// splits toward input points farther than `limit` from the mesh (see
  /// above); at most `max_splits`. Returns the splits made.
  std::size_t split_toward_far_input_points(double limit, std::size_t max_splits, double min_deg, int rounds = 3)
  {
    using EK = CGAL::Epick;
    using Triangles = std::vector<EK::Triangle_3>;
    using Tree = Aabb_tree<EK, Aabb_triangle_primitive<EK, typename Triangles::const_iterator>>;
    if (!ref.has_surface() || ref.points.empty()) return 0;
    const double min_cos = std::cos(min_deg * CGAL_PI / 180.);
    auto kp = [](const Vec3& p) { return EK::Point_3(p[0], p[1], p[2]); };
    std::vector<int> far;  // the input points still measured
    for (std::size_t i = 0; i < ref.points.size(); ++i)
      if (!ref.on_line[i] && is_finite(ref.points[i])) far.push_back(int(i));
    std::size_t made = 0;
    std::vector<halfedge_descriptor> fh;
    Triangles tris;
    std::vector<double> dist;
    std::vector<int> nearest;
    std::vector<vertex_descriptor> added;
    for (int round = 0; round < rounds && made < max_splits && !far.empty(); ++round) {
      fh.clear();
      tris.clear();
      for (face_descriptor f : faces(tm_)) {
        const halfedge_descriptor h = halfedge(f, tm_);
        EK::Triangle_3 t(kp(get(pos_, source(h, tm_))), kp(get(pos_, target(h, tm_))),
                         kp(get(pos_, target(next(h, tm_), tm_))));
        if (t.is_degenerate()) continue;
        fh.push_back(h);
        tris.push_back(t);
      }
      if (tris.empty()) break;
      Tree tree(tris.cbegin(), tris.cend());
      tree.accelerate_distance_queries();
      dist.assign(far.size(), 0.);
      nearest.assign(far.size(), -1);
      for_each_index(far.size(), [&](std::size_t k) {
        const auto pp = tree.closest_point_and_primitive(kp(ref.points[far[k]]));
        dist[k] = std::sqrt(CGAL::to_double(CGAL::squared_distance(pp.first, kp(ref.points[far[k]]))));
        nearest[k] = int(pp.second - tris.cbegin());
      });
      std::vector<std::size_t> order;
      for (std::size_t k = 0; k < far.size(); ++k)
        if (dist[k] > limit) order.push_back(k);
      if (order.empty()) break;
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return dist[a] > dist[b]; });
      ++stamp_;
      added.clear();
      for (std::size_t k : order) {
        if (made >= max_splits || budget_spent()) break;
        const halfedge_descriptor f = fh[nearest[k]];
        // one split per face and round: its halfedges carry the stamp once split
        halfedge_descriptor best = GT::null_halfedge();
        double bl = -1;
        bool touched = false;
        for (halfedge_descriptor g : CGAL::halfedges_around_face(f, tm_)) {
          touched = touched || get(dead_, g) == stamp_;
          if (get(flag_, edge(g, tm_)) & (FROZEN | LINE)) continue;
          const double l = sqlength(g);
          if (l > bl) { bl = l; best = g; }
        }
        if (touched || best == GT::null_halfedge()) continue;
        const Vec3 c = ref.points[far[k]];
        if (!split_keeps_faces(best, c, min_cos)) continue;
        const vertex_descriptor a = source(best, tm_), b = target(best, tm_);
        const double size = 0.5 * (get(size_, a) + get(size_, b));
        const int hint = get(thint_, a);
        split(best);
        const vertex_descriptor v = source(best, tm_);
        put(pos_, v, c);
        put(size_, v, size);
        put(thint_, v, hint);
        for (halfedge_descriptor g : halfedges_around_target(v, tm_)) {
          put(dead_, g, stamp_);
          put(dead_, opposite(g, tm_), stamp_);
          if (!is_border(g, tm_))
            for (halfedge_descriptor e : CGAL::halfedges_around_face(g, tm_)) put(dead_, e, stamp_);
        }
        added.push_back(v);
        ++made;
      }
      if (added.empty()) break;
      flip_around(added);
      // the next round measures the far points again, as many as the splits
      // left could use (a bounded count measures every point the first time)
      const std::size_t keep = max_splits - made >= order.size() / 8 ? order.size()
                                                                      : 8 * (max_splits - made) + 1024;
      std::vector<int> still;
      for (std::size_t k = 0; k < std::min(keep, order.size()); ++k) still.push_back(far[order[k]]);
      far.swap(still);
    }
    return made;
  }

  /// runs `iterations` rounds; `stop()` is polled between phases. Returns
  /// `partial` when the operation budget ran out (the mesh stays valid but
  /// has not reached its target), `cancelled` on a stop request.
  template <typename Visitor>
  Status run(int iterations, bool project, Visitor& vis, bool last_run = true)
  {
    for (int it = 0; it < iterations; ++it) {
      if (vis.stop_requested()) return Status::cancelled;
      vis.start_phase("split");
      split_long_edges();
      vis.end_phase("split");
#ifdef MREPAIR_REMESH_DEBUG
      debug_report(it, "split");
#endif
      if (vis.stop_requested()) return Status::cancelled;
      vis.start_phase("collapse");
      collapse_short_edges();
      vis.end_phase("collapse");
#ifdef MREPAIR_REMESH_DEBUG
      debug_report(it, "collapse");
#endif
      if (vis.stop_requested()) return Status::cancelled;
      if (budget_spent()) {
        // the last relaxation puts the vertices back on the input surface
        relax_and_project(project);
        return Status::partial;
      }
      vis.start_phase("flip");
      flip_edges();
      vis.end_phase("flip");
#ifdef MREPAIR_REMESH_DEBUG
      debug_report(it, "flip");
#endif
      if (vis.stop_requested()) return Status::cancelled;
      vis.start_phase("relax");
      relax_and_project(project);
      vis.end_phase("relax");
#ifdef MREPAIR_REMESH_DEBUG
      debug_report(it, "relax");
#endif
      vis.start_phase("cleanup");
      fix_bad_triangles(bad_angle_);
      // the cleanup's flips and collapses come after the last relaxation
      if (last_run && it + 1 == iterations) optimize_bad_vertices(30., project, 4);
      vis.end_phase("cleanup");
#ifdef MREPAIR_REMESH_DEBUG
      debug_report(it, "cleanup");
#endif
      ++counters.iterations;
      vis.progress(double(it + 1) / double(iterations));
    }
    return Status::ok;
  }

#ifdef MREPAIR_REMESH_DEBUG
  void debug_report(int it, const char* phase) const
  {
    double worst = -1; std::size_t nf = 0, bad = 0;
    for (face_descriptor f : faces(tm_)) {
      halfedge_descriptor h = halfedge(f, tm_);
      double c = min_angle_cos(get(pos_, source(h, tm_)), get(pos_, target(h, tm_)), get(pos_, target(next(h, tm_), tm_)));
      worst = std::max(worst, c); ++nf; if (c > std::cos(5 * CGAL_PI / 180)) ++bad;
    }
    std::fprintf(stderr, "it %d %-8s faces %zu min %.3f deg, <5deg %zu\n", it, phase, nf, std::acos(std::min(1., worst)) * 180 / CGAL_PI, bad);
  }
#endif
  /// writes positions back to the vertex point map (only where they changed).
  void write_back()
  {
    for (vertex_descriptor v : vertices(tm_)) {
      const Vec3 q = get(pos_, v);
      const Point& p = get(vpm_, v);
      if (to_vec3(p) != q) put(vpm_, v, Point(q[0], q[1], q[2]));
    }
  }

  /// true for edges that are features (user or detected) in the output.
  bool is_feature(edge_descriptor e) const { return (get(flag_, e) & FEATURE) != 0; }

  double mean_sizing() const
  {
    double s = 0;
    std::size_t n = 0;
    for (vertex_descriptor v : vertices(tm_))
      if (get(kind_, v) != V_FROZEN || get(ref_, v) >= 0) { s += get(size_, v); ++n; }
    return n ? s / n : 0.;
  }
};

} // namespace remesh
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_ADAPTIVE_REMESH_REMESHER_H
