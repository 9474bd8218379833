// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The worker of ensure_valid_mesh(): the degeneracy fixer (collapses, flips,
// removals that change no geometry where possible), the duplicate-face sort
// and the split of non-manifold vertices.
#ifndef MREPAIR_INTERNAL_ENSURE_VALID_MESH_FIXER_H
#define MREPAIR_INTERNAL_ENSURE_VALID_MESH_FIXER_H

#include <mrepair/cleaning_results.h>
#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/internal/inspect/parallel.h>
#include <mrepair/internal/utility.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Kernel/global_functions.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/Polygon_mesh_processing/repair.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace mrepair {

namespace internal {
namespace validity {

template <typename PM, typename VPM>
class Degeneracy_fixer
{
  using GT = boost::graph_traits<PM>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Point = typename boost::property_traits<VPM>::value_type;

  Local_operations<PM, VPM>& ops_;
  PM& pm_;
  VPM vpm_;
  std::set<face_descriptor> queue_;  // ordered by handle: safe to erase before a removal

public:
  Validity_result& r;

  Degeneracy_fixer(Local_operations<PM, VPM>& ops, Validity_result& result)
    : ops_(ops), pm_(ops.mesh()), vpm_(ops.vertex_point_map()), r(result)
  {}

  bool finite(face_descriptor f) const
  {
    for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_))
      if (!is_finite_point(vpm_, v)) return false;
    return true;
  }

  bool degenerate(face_descriptor f) const
  {
    if (!finite(f)) return false;  // exact predicates need finite input: left to the caller
    const halfedge_descriptor h = halfedge(f, pm_);
    const Point& a = get(vpm_, source(h, pm_));
    const Point& b = get(vpm_, target(h, pm_));
    const Point& c = get(vpm_, target(next(h, pm_), pm_));
    return a == b || b == c || a == c || CGAL::collinear(a, b, c);
  }

  // the degenerate faces, found in parallel (reads only: safe on any mesh)
  std::vector<face_descriptor> degenerate_faces() const
  {
    const std::vector<face_descriptor> fs(faces(pm_).begin(), faces(pm_).end());
    std::vector<unsigned char> bad(fs.size(), 0);
    parallel_for_index(fs.size(), 8192, [&](std::size_t i) { bad[i] = degenerate(fs[i]); });
    std::vector<face_descriptor> out;
    for (std::size_t i = 0; i < fs.size(); ++i)
      if (bad[i]) out.push_back(fs[i]);
    return out;
  }

  // Fixes what it can; the faces left are counted by the caller once the
  // duplicate faces are gone too (a pillow flattened by an earlier step is
  // degenerate, and goes as a duplicate pair).
  void run(std::size_t cap)
  {
    for (face_descriptor f : degenerate_faces()) queue_.insert(f);
    r.degenerate_faces_found = queue_.size();
    const std::size_t budget = cap ? cap : 10 * queue_.size() + 1000;
    std::set<face_descriptor> stuck;
    while (!queue_.empty() && r.operations < budget) {
      const face_descriptor f = *queue_.begin();
      queue_.erase(queue_.begin());
      if (!degenerate(f)) continue;
      ++r.operations;
      if (!fix(f)) stuck.insert(f);
    }
  }

private:
  double sqdist(vertex_descriptor u, vertex_descriptor v) const
  {
    return squared_norm(sub(point(vpm_, u), point(vpm_, v)));
  }

  void forget_faces_of_edge(halfedge_descriptor h)
  {
    if (!is_border(h, pm_)) queue_.erase(face(h, pm_));
    if (!is_border(opposite(h, pm_), pm_)) queue_.erase(face(opposite(h, pm_), pm_));
  }

  void requeue_around(vertex_descriptor v)
  {
    for (halfedge_descriptor k : CGAL::halfedges_around_target(halfedge(v, pm_), pm_))
      if (!is_border(k, pm_) && degenerate(face(k, pm_))) queue_.insert(face(k, pm_));
  }

  // Collapses the edge of `h` keeping position `p`; true when done.
  // `check`: 0 none, 1 no surviving face may become degenerate, 2 nor turn over.
  bool collapse(halfedge_descriptor h, const Point& p, int check)
  {
    const bool check_geometry = check > 0;
    // the link condition alone: a zero-length edge between two border
    // vertices joins what is one point already
    if (!ops_.satisfies_link_condition(h)) return false;
    const vertex_descriptor a = source(h, pm_), b = target(h, pm_);
    if (check_geometry) {
      // no surviving face may turn over or become degenerate
      for (vertex_descriptor v : {a, b})
        for (halfedge_descriptor k : CGAL::halfedges_around_target(halfedge(v, pm_), pm_)) {
          if (is_border(k, pm_)) continue;
          const face_descriptor f = face(k, pm_);
          if (f == face(h, pm_) || (!is_border(opposite(h, pm_), pm_) &&
                                    f == face(opposite(h, pm_), pm_)))
            continue;
          std::array<Point, 3> q;
          std::array<Point, 3> old;
          int i = 0;
          for (vertex_descriptor u : CGAL::vertices_around_face(halfedge(f, pm_), pm_)) {
            old[i] = get(vpm_, u);
            q[i] = (u == a || u == b) ? p : get(vpm_, u);
            ++i;
          }
          if (q[0] == q[1] || q[1] == q[2] || q[0] == q[2] || CGAL::collinear(q[0], q[1], q[2]))
            return false;
          if (check > 1 && !(dot(normal(old), normal(q)) > 0.)) return false;
        }
    }
    std::size_t removed = 0;
    if (!is_border(h, pm_)) ++removed;
    if (!is_border(opposite(h, pm_), pm_)) ++removed;
    forget_faces_of_edge(h);
    const vertex_descriptor kept = ops_.collapse_edge(h, p);
    r.faces_removed_degenerate += removed;
    requeue_around(kept);
    return true;
  }

  static Vec3 normal(const std::array<Point, 3>& q)
  {
    const Vec3 p0 = to_vec3(q[0]);
    return triangle_normal(p0, to_vec3(q[1]), to_vec3(q[2]));
  }

  bool fix(face_descriptor f)
  {
    // 1. a zero-length edge: collapse it, nothing moves
    for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, pm_), pm_))
      if (get(vpm_, source(h, pm_)) == get(vpm_, target(h, pm_))) {
        const Point p = get(vpm_, target(h, pm_));
        if (collapse(h, p, 0)) {
          ++r.zero_length_edges_collapsed;
          return true;
        }
      }
    // 2. a cap: the middle vertex c faces the longest edge ab
    halfedge_descriptor ab = halfedge(f, pm_);
    double best = -1.;
    for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, pm_), pm_)) {
      const double l = sqdist(source(h, pm_), target(h, pm_));
      if (l > best) { best = l; ab = h; }
    }
    const vertex_descriptor a = source(ab, pm_), b = target(ab, pm_),
                            c = target(next(ab, pm_), pm_);
    const halfedge_descriptor ba = opposite(ab, pm_);
    if (!is_border(ba, pm_)) {
      // the triangle across ab is split at c by the flip: no vertex moves
      if (ops_.flip_keeps_manifold(ab)) {
        const face_descriptor g = face(ba, pm_);
        ops_.flip_edge(ab);
        ++r.caps_flipped;
        for (face_descriptor x : {f, g})
          if (degenerate(x)) queue_.insert(x);
        return true;
      }
    } else if (!is_border_vertex(c, pm_)) {
      // a zero-area face on the border: removing it loses no surface, and c
      // (interior so far) joins the border without a pinch
      queue_.erase(f);
      ops_.remove_face(f);
      ++r.border_faces_removed;
      ++r.faces_removed_degenerate;
      return true;
    }
    // 3. move c onto the nearer end of ab (it lies on the segment)
    const halfedge_descriptor ca = prev(ab, pm_);  // c -> a
    const halfedge_descriptor bc = next(ab, pm_);  // b -> c
    const bool to_a = sqdist(c, a) <= sqdist(c, b);
    const halfedge_descriptor e = to_a ? ca : bc;
    const Point target_point = get(vpm_, to_a ? a : b);
    const halfedge_descriptor e2 = to_a ? bc : ca;
    const Point other_point = get(vpm_, to_a ? b : a);
    // first without turning a face over; then, as a last resort (the mesh
    // already folds there), without creating a degenerate face
    for (int check : {2, 1}) {
      if (collapse(e, target_point, check) || collapse(e2, other_point, check)) {
        ++r.cap_vertices_collapsed;
        return true;
      }
    }
    // 4. no collapse satisfies the link condition (a tiny closed mesh where
    // every vertex neighbours every other): remove the zero-area face when
    // none of its vertices is on a border yet, so that no vertex is pinched;
    // the mesh opens along a slit of zero width and loses no surface
    bool inside = true;
    for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_))
      if (is_border_vertex(v, pm_)) inside = false;
    if (inside) {
      queue_.erase(f);
      ops_.remove_face(f);
      ++r.border_faces_removed;
      ++r.faces_removed_degenerate;
      return true;
    }
    return false;
  }
};

// The faces whose sorted vertex indices `tri[i]` (each below `indices`) are
// the same, as consecutive pairs (i, j) in the order of a sort of all faces
// by (triple, face): triples increasing, `face_less` within one triple. Only
// the few faces that share a smallest index are sorted together: a counting
// sort by that index lists them (linear and parallel, where one sort of all
// 10M faces of a scan took 0.55 s of this step's 1.9 s).
template <typename I, typename FaceLess>
std::vector<std::pair<std::size_t, std::size_t>> same_vertex_triples(const std::vector<std::array<I, 3>>& tri,
                                                                    std::size_t indices,
                                                                    const FaceLess& face_less)
{
  using Pairs = std::vector<std::pair<std::size_t, std::size_t>>;
  std::vector<I> first, order;
  bucket_items(tri.size(), indices, static_cast<I>(-1), [&](std::size_t i) { return tri[i][0]; }, first,
               order);
  auto same = [&](I x, I y) { return tri[x][1] == tri[y][1] && tri[x][2] == tri[y][2]; };
  auto parts = chunked<Pairs>(indices, [&](std::size_t b, std::size_t e, Pairs& part) {
    std::vector<I> items;
    for (std::size_t v = b; v < e; ++v) {
      if (first[v + 1] - first[v] < 2) continue;
      items.assign(order.begin() + first[v], order.begin() + first[v + 1]);
      std::sort(items.begin(), items.end(), [&](I x, I y) {
        if (tri[x][1] != tri[y][1]) return tri[x][1] < tri[y][1];
        if (tri[x][2] != tri[y][2]) return tri[x][2] < tri[y][2];
        return face_less(x, y);
      });
      for (std::size_t k = 1; k < items.size(); ++k)
        if (same(items[k - 1], items[k])) part.emplace_back(items[k - 1], items[k]);
    }
  });
  Pairs pairs;
  for (const Pairs& part : parts) pairs.insert(pairs.end(), part.begin(), part.end());
  return pairs;
}

// the pairs of faces of `fs` with the same three vertices (see above)
template <typename PM>
std::vector<std::pair<std::size_t, std::size_t>> faces_with_same_vertices(
    PM& pm, const std::vector<typename boost::graph_traits<PM>::face_descriptor>& fs)
{
  using vertex_descriptor = typename boost::graph_traits<PM>::vertex_descriptor;
  auto index = get(CGAL::dynamic_vertex_property_t<std::size_t>(), pm);
  std::size_t nv = 0;
  for (vertex_descriptor v : vertices(pm)) put(index, v, nv++);
  auto pairs_of = [&](auto zero) {
    using I = decltype(zero);
    std::vector<std::array<I, 3>> tri(fs.size());
    // reads of the index map: in parallel where it is an array
    parallel_for_mesh_elements<PM>(fs.size(), [&](std::size_t i) {
      std::array<I, 3> key{};
      int k = 0;
      for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(fs[i], pm), pm))
        if (k < 3) key[k++] = static_cast<I>(get(index, v));
      std::sort(key.begin(), key.end());
      tri[i] = key;
    });
    return same_vertex_triples(tri, nv, [&](std::size_t x, std::size_t y) { return fs[x] < fs[y]; });
  };
  // 4-byte indices while they fit (with -1 free for "no bucket"): half the memory
  const std::size_t limit = std::numeric_limits<std::uint32_t>::max();
  if (nv < limit && fs.size() < limit) return pairs_of(std::uint32_t(0));
  return pairs_of(std::size_t(0));
}

// Whether a vertex has more than one umbrella (fan of halfedges pointing to
// it): each halfedge lies in one umbrella of its target, so the umbrellas of
// `halfedge(v)` hold every halfedge exactly when there is none. Counted in
// parallel (PMP's search, which also finds them, is one sequential pass:
// 0.3 s at 10M faces, almost always to find nothing).
template <typename PM>
bool has_non_manifold_vertices(const PM& pm)
{
  using vertex_descriptor = typename boost::graph_traits<PM>::vertex_descriptor;
  const std::vector<vertex_descriptor> vs(vertices(pm).begin(), vertices(pm).end());
  auto counts = chunked<std::size_t>(vs.size(), [&](std::size_t b, std::size_t e, std::size_t& n) {
    for (std::size_t i = b; i < e; ++i)
      if (halfedge(vs[i], pm) != boost::graph_traits<PM>::null_halfedge())
        n += CGAL::halfedges_around_target(halfedge(vs[i], pm), pm).size();
  });
  std::size_t in_umbrellas = 0;
  for (std::size_t n : counts) in_umbrellas += n;
  return in_umbrellas != static_cast<std::size_t>(num_halfedges(pm));
}

}  // namespace validity
}  // namespace internal

namespace internal {
// the body of ensure_valid_mesh(), editing through `ops` (the pipeline's,
// whose counts are its face accounting); `check_structure` false when the
// caller checked the halfedge structure itself and only its own steps edited
// the mesh since (clean_scan_mesh: 50 ms of a 1M-face job)
template <typename PolygonMesh, typename VPM, typename NamedParameters>
Validity_result ensure_valid_mesh_with(Local_operations<PolygonMesh, VPM>& ops, const NamedParameters& np,
                                       bool check_structure)
{
  using GT = boost::graph_traits<PolygonMesh>;
  using face_descriptor = typename GT::face_descriptor;
  PolygonMesh& pmesh = ops.mesh();
  const std::size_t cap = internal::get_or(np, internal_np::max_validity_operations, std::size_t(0));
  Validity_result r;
  if (internal::face_count(pmesh) == 0) return r;
  // One pass over the faces, in parallel: every face must be a triangle, and
  // the pillows (two faces sharing all three edges, a detached double-sided
  // fin) are listed: an earlier step may have flattened one, and no local
  // edit fixes a degenerate pillow face, but the pair is a duplicate and goes
  // whole. Linear: each face looks across its three edges.
  std::vector<face_descriptor> pillow_faces;
  {
    struct Face_scan
    {
      bool triangles = true;
      std::vector<face_descriptor> pillows;
    };
    if (std::string broken = check_structure ? internal::halfedge_structure_defect(pmesh) : std::string();
        !broken.empty()) {
      r.status = Status::invalid_mesh;
      r.message = "ensure_valid_mesh: the mesh's halfedge structure is broken: " + broken;
      return r;
    }
    const std::vector<face_descriptor> fs(faces(pmesh).begin(), faces(pmesh).end());
    auto scans = internal::chunked<Face_scan>(fs.size(), [&](std::size_t b, std::size_t e, Face_scan& s) {
      for (std::size_t i = b; i < e && s.triangles; ++i) {
        const face_descriptor f = fs[i];
        face_descriptor g = GT::null_face();
        bool pillow = true;
        std::size_t degree = 0;
        for (auto h : CGAL::halfedges_around_face(halfedge(f, pmesh), pmesh)) {
          if (++degree > 3) break;
          const auto o = opposite(h, pmesh);
          if (is_border(o, pmesh) || (g != GT::null_face() && face(o, pmesh) != g)) pillow = false;
          g = face(o, pmesh);
        }
        if (degree != 3) s.triangles = false;
        if (pillow && g != f) s.pillows.push_back(f);  // both faces are listed
      }
    });
    for (const Face_scan& s : scans) {
      if (!s.triangles) {
        r.status = Status::invalid_mesh;
        r.message = "ensure_valid_mesh needs a triangle mesh";
        return r;
      }
      pillow_faces.insert(pillow_faces.end(), s.pillows.begin(), s.pillows.end());
    }
  }
  ops.remove_components(pillow_faces);
  r.duplicate_faces_removed += pillow_faces.size();
  internal::validity::Degeneracy_fixer<PolygonMesh, VPM> fixer(ops, r);
  fixer.run(cap);

  // Duplicate faces: the same three vertices.
  {
    const std::vector<face_descriptor> fs(faces(pmesh).begin(), faces(pmesh).end());
    std::vector<std::pair<face_descriptor, face_descriptor>> pairs;
    for (const auto& p : internal::validity::faces_with_same_vertices(pmesh, fs))
      pairs.emplace_back(fs[p.first], fs[p.second]);
    std::set<face_descriptor> gone;
    for (const auto& pr : pairs) {
      if (gone.count(pr.first) || gone.count(pr.second)) continue;
      bool pillow = true;  // every edge of the first is shared with the second
      for (auto h : CGAL::halfedges_around_face(halfedge(pr.first, pmesh), pmesh))
        if (is_border(opposite(h, pmesh), pmesh) || face(opposite(h, pmesh), pmesh) != pr.second)
          pillow = false;
      if (pillow) {
        gone.insert(pr.first);
        gone.insert(pr.second);
        ops.remove_components({pr.first, pr.second});
        r.duplicate_faces_removed += 2;
      } else {
        std::vector<face_descriptor> doomed(1, pr.second);
        gone.insert(pr.second);
        // faces removed to avoid a pinch are listed in `doomed` afterwards
        r.duplicate_faces_removed += ops.remove_faces_without_pinches(doomed);
        for (face_descriptor f : doomed) gone.insert(f);
      }
    }
  }

  if (internal::validity::has_non_manifold_vertices(pmesh))
    r.non_manifold_vertices_split = ops.split_non_manifold_vertices();

  // faces left: those no local edit could fix and those the cap cut off
  // (none when none was found: removals and vertex splits move no point)
  r.degenerate_faces_left = r.degenerate_faces_found == 0 ? 0 : fixer.degenerate_faces().size();

  if (r.degenerate_faces_left > 0) {
    r.status = Status::partial;
    r.message = std::to_string(r.degenerate_faces_left) +
                " exactly degenerate faces left (no collapse, flip or removal keeps the mesh valid)";
  }
  return r;
}

// the same on a mesh of its own, with its own local operations
template <typename PolygonMesh, typename NamedParameters>
Validity_result ensure_valid_mesh(PolygonMesh& pmesh, const NamedParameters& np, bool check_structure)
{
  auto vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, pmesh));
  internal::Local_operations<PolygonMesh, decltype(vpm)> ops(pmesh, vpm);
  return ensure_valid_mesh_with(ops, np, check_structure);
}
} // namespace internal

}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_ENSURE_VALID_MESH_FIXER_H
