// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The one place where the cleaning steps edit a mesh.
//
// Every edit of the scan-cleaning steps (near-degenerate repair, spikes,
// boundaries, components, hole filling, the pipeline's preprocessing and the
// final validity step) is one of the operations below. Each operation
//  - keeps the attached geometric statistics current: it alone chooses the
//    vertex sets of `Geometric_statistics::before_local_edit` and
//    `after_local_edit`, so that no step can forget an edge or a face;
//  - checks, in builds with MREPAIR_CHECK_LOCAL_OPERATIONS (debug builds by
//    default), that the neighbourhood it leaves is a valid manifold piece;
//  - counts what it did (`Local_operation_counts`), so that face accounting
//    is the difference of two counts, not a tally each step keeps by hand.
//
// Statistics are optional: without them the operations are plain edits with
// the same checks and counts (ensure_valid_mesh, a step called on its own).
// The patch edits (take back, put back, replace a patch's faces) are reachable
// only through the `Patch_operations` that `insert_patch` and `edit_patch`
// hand their callback, where the statistics are updated for the whole patch.
#ifndef MREPAIR_INTERNAL_LOCAL_OPERATIONS_H
#define MREPAIR_INTERNAL_LOCAL_OPERATIONS_H

#include <mrepair/geometric_statistics.h>
#include <mrepair/internal/utility.h>

#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/exceptions.h>
#include <CGAL/version.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#if !defined(MREPAIR_CHECK_LOCAL_OPERATIONS) && !defined(NDEBUG)
#define MREPAIR_CHECK_LOCAL_OPERATIONS 1
#endif

namespace mrepair {
namespace internal {

/// what the local operations did, element by element.
struct Local_operation_counts
{
  std::size_t vertices_moved = 0;
  std::size_t edges_collapsed = 0;
  std::size_t edges_flipped = 0;
  std::size_t edges_split = 0;
  std::size_t faces_removed = 0;       ///< by every operation, pinch fans included
  std::size_t pinch_faces_removed = 0; ///< fans removed so that no vertex is pinched
  std::size_t pinches_resolved = 0;    ///< vertices whose smaller fans went
  std::size_t faces_added = 0;
  std::size_t vertices_removed = 0;    ///< isolated, or left without a face
  std::size_t vertices_added = 0;
  std::size_t patches_inserted = 0;
};

/// True when a halfedge around `v` is a border halfedge (on both Surface_mesh
/// and Polyhedron_3, whatever `halfedge(v)` is).
template <typename PM>
bool is_border_vertex(typename boost::graph_traits<PM>::vertex_descriptor v, const PM& pm)
{
  if (halfedge(v, pm) == boost::graph_traits<PM>::null_halfedge()) return false;
  for (auto h : CGAL::halfedges_around_target(halfedge(v, pm), pm))
    if (is_border(h, pm)) return true;
  return false;
}

/// CGAL's `triangulate_hole` (Liepa's weight; `use_delaunay` restricts the
/// search to a 3D Delaunay triangulation) of the border loop of `h`,
/// checked: the patch must be the loop's n - 2 triangles. On degenerate loops
/// (coincident corners, a pillow of two polygons) CGAL 5.5 reported a
/// triangle and a quadrilateral for a loop of five (its debug assertion
/// `Q.front() == Q.back()` fails), and the quadrilateral broke every step
/// after. Such a patch is removed again, the loop is a border once more and
/// `added` is empty: an aborted fill.
template <typename PM, typename VPM>
bool triangulate_hole_checked(PM& pm, typename boost::graph_traits<PM>::halfedge_descriptor h, const VPM& vpm,
                              bool use_delaunay,
                              std::vector<typename boost::graph_traits<PM>::face_descriptor>& added)
{
  using halfedge_descriptor = typename boost::graph_traits<PM>::halfedge_descriptor;
  const std::size_t n = CGAL::halfedges_around_face(h, pm).size();
  const std::size_t first = added.size();
  bool whole = true;
  try {  // with CGAL's assertions on (debug builds) the same loops throw
#if CGAL_VERSION_NR >= 1060000000
    // CGAL 6 first fills a near-planar loop by a 2D constrained Delaunay
    // triangulation in a fitted plane; mrepair keeps Liepa's minimum-weight
    // triangulation (the RameshCleaner's choice) for every loop, so that a
    // patch is the same on CGAL 5.5 and 6, and with an exact kernel too.
    CGAL::Polygon_mesh_processing::triangulate_hole(
        pm, h,
        CGAL::parameters::face_output_iterator(std::back_inserter(added))
            .vertex_point_map(vpm)
            .use_delaunay_triangulation(use_delaunay)
            .use_2d_constrained_delaunay_triangulation(false));
#else
    CGAL::Polygon_mesh_processing::triangulate_hole(
        pm, h, std::back_inserter(added),
        CGAL::parameters::vertex_point_map(vpm).use_delaunay_triangulation(use_delaunay));
#endif
  } catch (const CGAL::Failure_exception&) {
    whole = false;
  }
  whole = whole && added.size() - first + 2 == n;
  for (std::size_t i = first; i < added.size() && whole; ++i) {
    const halfedge_descriptor g = halfedge(added[i], pm);
    whole = next(next(next(g, pm), pm), pm) == g;
  }
  if (whole) return true;
  for (std::size_t i = first; i < added.size(); ++i) CGAL::Euler::remove_face(halfedge(added[i], pm), pm);
  added.resize(first);
  return false;
}

template <typename PM, typename VPM>
class Patch_operations;

template <typename PM, typename VPM>
class Local_operations
{
public:
  using GT = boost::graph_traits<PM>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Point = typename boost::property_traits<VPM>::value_type;
  using Statistics = Geometric_statistics<PM, VPM>;

  Local_operations(PM& pm, VPM vpm) : pm_(pm), vpm_(vpm) {}
  Local_operations(const Local_operations&) = delete;
  Local_operations& operator=(const Local_operations&) = delete;

  PM& mesh() const { return pm_; }
  const VPM& vertex_point_map() const { return vpm_; }

  /// the hook: from now on every operation keeps `s` current (null: none).
  void keep_current(Statistics* s) { stats_ = s; }
  Statistics* statistics() const { return stats_; }

  /// what the operations did so far (this object's edits only)
  const Local_operation_counts& counts() const { return counts_; }

  // ---- queries: the one copy of each validity test ---------------------------

  enum class Collapse_check { ok, would_pinch_border, fails_link_condition };

  /// whether the edge of `h` can collapse without breaking the manifold: an
  /// interior edge must not join two border vertices (that would pinch the
  /// border into a figure eight), and the link condition must hold.
  Collapse_check check_collapse(halfedge_descriptor h) const
  {
    if (!is_border_edge(h, pm_) && is_border_vertex(source(h, pm_), pm_) &&
        is_border_vertex(target(h, pm_), pm_))
      return Collapse_check::would_pinch_border;
    if (!CGAL::Euler::does_satisfy_link_condition(edge(h, pm_), pm_))
      return Collapse_check::fails_link_condition;
    return Collapse_check::ok;
  }
  bool collapse_keeps_manifold(halfedge_descriptor h) const
  {
    return check_collapse(h) == Collapse_check::ok;
  }

  /// the link condition alone (ensure_valid_mesh collapses zero-length edges
  /// between border vertices: the two vertices are one point already).
  bool satisfies_link_condition(halfedge_descriptor h) const
  {
    return CGAL::Euler::does_satisfy_link_condition(edge(h, pm_), pm_);
  }

  /// the edge of `h` can flip: an interior edge whose two opposite corners
  /// are distinct and not joined yet. With `min_valence`, neither end may
  /// drop to fewer than that many edges.
  bool flip_keeps_manifold(halfedge_descriptor h, std::size_t min_valence = 0) const
  {
    if (is_border_edge(h, pm_)) return false;
    const vertex_descriptor c = target(next(h, pm_), pm_);
    const vertex_descriptor d = target(next(opposite(h, pm_), pm_), pm_);
    if (c == d || halfedge(c, d, pm_).second) return false;
    if (min_valence > 0 && (degree(source(h, pm_), pm_) <= min_valence ||
                            degree(target(h, pm_), pm_) <= min_valence))
      return false;
    return true;
  }

  // ---- edits --------------------------------------------------------------------

  /// moves `vs[i]` to `ps[i]` for every i, with one statistics update.
  void move_vertices(const std::vector<vertex_descriptor>& vs, const std::vector<Vec3>& ps)
  {
    if (stats_) stats_->before_local_edit(vs);
    for (std::size_t i = 0; i < vs.size(); ++i) set_point(vpm_, vs[i], ps[i]);
    if (stats_) stats_->after_local_edit(vs);
    counts_.vertices_moved += vs.size();
  }

  /// moves each vertex of `vs` in turn to `position_of(v)`, which may read the
  /// vertices moved before it (Gauss-Seidel), with one statistics update.
  template <typename PositionOf>
  void move_vertices_in_order(const std::vector<vertex_descriptor>& vs, PositionOf&& position_of)
  {
    if (stats_) stats_->before_local_edit(vs);
    for (vertex_descriptor v : vs) set_point(vpm_, v, position_of(v));
    if (stats_) stats_->after_local_edit(vs);
    counts_.vertices_moved += vs.size();
  }

  /// collapses the edge of `h` (callers test `collapse_keeps_manifold` or the
  /// link condition first) and puts the surviving vertex at `p`; returns it.
  vertex_descriptor collapse_edge(halfedge_descriptor h, const Point& p)
  {
    const std::size_t faces_gone = std::size_t(!is_border(h, pm_)) +
                                   std::size_t(!is_border(opposite(h, pm_), pm_));
    const edge_descriptor e = edge(h, pm_);
    if (stats_) stats_->before_edge_collapse(e);
    const vertex_descriptor v = CGAL::Euler::collapse_edge(e, pm_);
    put(vpm_, v, p);
    if (stats_) stats_->after_edge_collapse(v);
    ++counts_.edges_collapsed;
    ++counts_.vertices_removed;
    counts_.faces_removed += faces_gone;
    check_around(v);
    return v;
  }
  vertex_descriptor collapse_edge(halfedge_descriptor h, const Vec3& p)
  {
    return collapse_edge(h, Point(p[0], p[1], p[2]));
  }

  /// flips the edge of `h` (callers test `flip_keeps_manifold` first).
  void flip_edge(halfedge_descriptor h)
  {
    const edge_descriptor e = edge(h, pm_);
    if (stats_) stats_->before_edge_flip(e);
    CGAL::Euler::flip_edge(h, pm_);
    if (stats_) stats_->after_edge_flip(e);
    ++counts_.edges_flipped;
    check_around(source(h, pm_));
    check_around(target(h, pm_));
  }

  /// removes one face whose removal pinches no vertex (the caller checked:
  /// e.g. a zero-area face on the border whose third vertex is interior).
  void remove_face(face_descriptor f)
  {
    std::array<vertex_descriptor, 3> vs;
    std::size_t n = 0;
    for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_))
      if (n < 3) vs[n++] = v;
    if (stats_) stats_->before_local_edit(vs);
    std::size_t kept = 0;
    std::array<vertex_descriptor, 3> survivors;
    for (std::size_t i = 0; i < n; ++i)
      if (has_other_face(vs[i], f)) survivors[kept++] = vs[i];
    CGAL::Euler::remove_face(halfedge(f, pm_), pm_);
    ++counts_.faces_removed;
    counts_.vertices_removed += n - kept;
    if (stats_) stats_->after_local_edit(std::vector<vertex_descriptor>(survivors.begin(), survivors.begin() + kept));
    for (std::size_t i = 0; i < kept; ++i) check_around(survivors[i]);
  }

  /// removes `to_remove` (duplicates allowed) so that no pinched vertex is
  /// left: a vertex whose kept faces would split into several fans keeps the
  /// largest fan, the others go too (counted in `pinch_faces_removed`), and
  /// their vertices are inspected in turn. Edges and vertices left without a
  /// face go with them. `survivors` receives the vertices of removed faces
  /// that keep a face (the new border), read before any removal so that no
  /// freed handle is touched (Polyhedron_3 frees them), and `removed_vertices`
  /// those that go with them. Returns the number of faces removed;
  /// `to_remove` holds them on return.
  std::size_t remove_faces_without_pinches(std::vector<face_descriptor>& to_remove,
                                           std::vector<vertex_descriptor>* survivors = nullptr,
                                           std::vector<vertex_descriptor>* removed_vertices = nullptr)
  {
    ensure_marks();
    std::vector<face_descriptor> uniq;
    uniq.reserve(to_remove.size());
    for (face_descriptor f : to_remove)
      if (get(fmark_, f) != 2) {
        put(fmark_, f, char(2));
        uniq.push_back(f);
      }
    to_remove.swap(uniq);
    const std::size_t asked = to_remove.size();

    std::vector<vertex_descriptor> work;
    for (face_descriptor f : to_remove)
      for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_)) work.push_back(v);
    std::vector<face_descriptor> ring;  // faces around a vertex, null = border
    std::vector<int> run_of;            // run index of each ring slot, -1 = gap
    std::vector<std::size_t> run_size;
    // Bounded: a vertex goes back on `work` only when a fan of its ring was
    // marked just then, and each face is marked (and pushed) once.
    while (!work.empty()) {
      const vertex_descriptor v = work.back();
      work.pop_back();
      ring.clear();
      for (halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, pm_), pm_))
        ring.push_back(is_border(h, pm_) ? GT::null_face() : face(h, pm_));
      const std::size_t n = ring.size();
      auto kept = [&](std::size_t i) { return ring[i] != GT::null_face() && get(fmark_, ring[i]) != 2; };
      std::size_t start = n;  // a gap slot to start the cyclic scan from
      for (std::size_t i = 0; i < n; ++i)
        if (!kept(i)) { start = i; break; }
      if (start == n) continue;  // every face kept: untouched
      run_of.assign(n, -1);
      run_size.clear();
      for (std::size_t k = 1; k <= n; ++k) {
        const std::size_t i = (start + k) % n;
        if (!kept(i)) continue;
        if (run_of[(i + n - 1) % n] < 0) run_size.push_back(0);
        run_of[i] = int(run_size.size()) - 1;
        ++run_size.back();
      }
      if (run_size.size() <= 1) continue;
      // a pinch: keep the largest fan, remove the others
      ++counts_.pinches_resolved;
      const std::size_t best = std::size_t(std::max_element(run_size.begin(), run_size.end()) - run_size.begin());
      // (a face met twice in one ring is marked and removed once)
      for (std::size_t i = 0; i < n; ++i)
        if (run_of[i] >= 0 && std::size_t(run_of[i]) != best && get(fmark_, ring[i]) != 2) {
          put(fmark_, ring[i], char(2));
          to_remove.push_back(ring[i]);
          for (vertex_descriptor w : CGAL::vertices_around_face(halfedge(ring[i], pm_), pm_))
            work.push_back(w);
        }
      work.push_back(v);  // re-check: now a single fan
    }

    // the vertices of the removed faces, and which of them keep a face
    std::vector<vertex_descriptor> touched, kept_vertices;
    for (face_descriptor f : to_remove)
      for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_)) touched.push_back(v);
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (vertex_descriptor v : touched) {
      bool keeps = false;
      for (halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, pm_), pm_))
        if (!is_border(h, pm_) && get(fmark_, face(h, pm_)) != 2) { keeps = true; break; }
      if (keeps) kept_vertices.push_back(v);
      else if (removed_vertices) removed_vertices->push_back(v);
    }
    if (stats_) stats_->before_local_edit(touched);
    // the mark goes back to zero first: slots recycled by later face creations
    // (Surface_mesh) or reused addresses (Polyhedron_3) carry no stale mark
    for (face_descriptor f : to_remove) put(fmark_, f, char(0));
    for (face_descriptor f : to_remove) CGAL::Euler::remove_face(halfedge(f, pm_), pm_);
    if (stats_) stats_->after_local_edit(kept_vertices);
    counts_.faces_removed += to_remove.size();
    counts_.pinch_faces_removed += to_remove.size() - asked;
    counts_.vertices_removed += touched.size() - kept_vertices.size();
    for (vertex_descriptor v : kept_vertices) check_around(v);
    if (survivors) survivors->insert(survivors->end(), kept_vertices.begin(), kept_vertices.end());
    return to_remove.size();
  }

  /// removes whole connected components given by all their faces: nothing
  /// around them survives, so no pinch can arise.
  std::size_t remove_components(const std::vector<face_descriptor>& component_faces)
  {
    std::vector<vertex_descriptor> touched;
    if (stats_) {
      for (face_descriptor f : component_faces)
        for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_)) touched.push_back(v);
      std::sort(touched.begin(), touched.end());
      touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
      stats_->before_local_edit(touched);
    }
    const std::size_t nv = internal::vertex_count(pm_);
    for (face_descriptor f : component_faces) CGAL::Euler::remove_face(halfedge(f, pm_), pm_);
    counts_.faces_removed += component_faces.size();
    counts_.vertices_removed += nv - internal::vertex_count(pm_);
    if (stats_) stats_->after_local_edit(std::vector<vertex_descriptor>());
    return component_faces.size();
  }

  /// removes a vertex without faces.
  void remove_isolated_vertex(vertex_descriptor v)
  {
    remove_vertex(v, pm_);
    ++counts_.vertices_removed;
  }

  /// splits every non-manifold vertex (two or more fans meeting at one
  /// point) into one vertex per fan at the same position, so that the mesh
  /// is a manifold again; returns the number of vertices added. Nothing
  /// moves; the statistics, when attached, do not see the new vertices (the
  /// callers split last, after every step that reads them).
  std::size_t split_non_manifold_vertices()
  {
    const std::size_t added = CGAL::Polygon_mesh_processing::duplicate_non_manifold_vertices(
        pm_, CGAL::parameters::vertex_point_map(vpm_));
    counts_.vertices_added += added;
    return added;
  }

  /// inserts a patch into the border loop of `h`: `build(patch_operations)`
  /// triangulates the loop and may refine, relax and fair the new faces,
  /// editing through the `Local_operations` it is given (no statistics: they
  /// are updated once for the whole patch here). `build` returns the new
  /// faces' vertices that are not on the loop, and leaves the mesh unchanged
  /// when it returns false. Returns what `build` returned.
  template <typename Build>
  bool insert_patch(halfedge_descriptor h, Build&& build)
  {
    std::vector<vertex_descriptor> loop;
    for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_)) loop.push_back(target(g, pm_));
    const bool done = patch_edit(loop, build);
    if (done) ++counts_.patches_inserted;
    return done;
  }

  /// edits a patch that `insert_patch` put into the loop `loop` (its
  /// vertices) and that has no vertex of its own yet (Liepa's patch), through
  /// the `Local_operations` given to `edit`, with the statistics updated once
  /// as `insert_patch` does. `edit(patch_ops, loop, added)` returns false when
  /// it took the patch back (the loop is a border again), true otherwise.
  template <typename Edit>
  bool edit_patch(std::vector<vertex_descriptor> loop, Edit&& edit)
  {
    const bool kept = patch_edit(loop, edit, true);
    if (!kept && counts_.patches_inserted > 0) --counts_.patches_inserted;
    return kept;
  }

protected:
  // ---- patch edits: only inside `insert_patch` / `edit_patch`, through the
  // `Patch_operations` they hand to their callback. They update no statistics
  // themselves: `patch_edit` updates them once for the whole patch.

  /// takes back the faces of a patch this object inserted into one border
  /// loop (the whole patch, nothing else): the loop is a border again.
  void remove_patch(const std::vector<face_descriptor>& patch)
  {
    for (face_descriptor f : patch) CGAL::Euler::remove_face(halfedge(f, pm_), pm_);
    counts_.faces_removed += patch.size();
  }

  /// adds `triangles` into the border loop they fill (the faces of a patch
  /// taken back with `remove_patch`, say), each next to those added before
  /// where it can be; `added` receives the new faces. False when some cannot
  /// be added (those that went in stay, in `added`).
  bool insert_triangles(const std::vector<std::array<vertex_descriptor, 3>>& triangles,
                        std::vector<face_descriptor>& added)
  {
    std::vector<std::array<vertex_descriptor, 3>> todo = triangles, later;
    auto next_to_border = [&](const std::array<vertex_descriptor, 3>& t) {
      for (int k = 0; k < 3; ++k)
        if (halfedge(t[k], t[(k + 1) % 3], pm_).second) return true;
      return false;
    };
    bool anywhere = false;  // a face on its own only when none goes next to the border
    // each pass adds a face or sets `anywhere`, two passes without one return
    while (!todo.empty()) {
      later.clear();
      for (const auto& t : todo) {
        face_descriptor f = GT::null_face();
        if ((anywhere || next_to_border(t)) && CGAL::Euler::can_add_face(t, pm_))
          f = CGAL::Euler::add_face(t, pm_);
        if (f == GT::null_face()) later.push_back(t);
        else { added.push_back(f); ++counts_.faces_added; }
      }
      if (later.size() == todo.size()) {
        if (anywhere) return false;
        anywhere = true;
      } else
        anywhere = false;
      todo.swap(later);
    }
    return true;
  }

  using Triangle = std::array<vertex_descriptor, 3>;

  /// the vertices of triangles `fs`, in face order (what `insert_triangles`
  /// takes to put them back after `remove_patch`).
  std::vector<Triangle> triangles_of(const std::vector<face_descriptor>& fs) const
  {
    std::vector<Triangle> ts;
    ts.reserve(fs.size());
    for (face_descriptor f : fs) {
      Triangle t;
      int k = 0;
      for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_))
        if (k < 3) t[k++] = v;
      ts.push_back(t);
    }
    return ts;
  }

  /// replaces `patch` (faces this object inserted into one border loop, with
  /// no vertex of their own) by `triangles`, indices into `corners`: a corner
  /// that is a vertex of the loop is given there, a new one is null there and
  /// is created at `positions[i]`. False, and the old patch back in place,
  /// when the new faces cannot go in (an inner edge would join two loop
  /// vertices already joined outside the patch). On success `patch` holds
  /// the new faces and `created` the new vertices.
  bool replace_patch(std::vector<face_descriptor>& patch, std::vector<vertex_descriptor> corners,
                     const std::vector<Vec3>& positions,
                     const std::vector<std::array<std::size_t, 3>>& triangles,
                     std::vector<vertex_descriptor>& created)
  {
    // an inner edge (two triangles) between two loop vertices must not exist
    // outside the old patch: the new face would go in on another border
    {
      std::set<face_descriptor> old_faces(patch.begin(), patch.end());
      std::map<std::pair<std::size_t, std::size_t>, int> uses;
      for (const auto& t : triangles)
        for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
      for (const auto& u : uses) {
        const vertex_descriptor a = corners[u.first.first], b = corners[u.first.second];
        if (u.second < 2 || a == GT::null_vertex() || b == GT::null_vertex()) continue;
        const auto h = halfedge(a, b, pm_);
        if (!h.second) continue;
        for (halfedge_descriptor g : {h.first, opposite(h.first, pm_)})
          if (is_border(g, pm_) || !old_faces.count(face(g, pm_))) return false;
      }
    }
    const std::vector<Triangle> old_triangles = triangles_of(patch);
    remove_patch(patch);
    patch.clear();
    created.clear();
    for (std::size_t i = 0; i < corners.size(); ++i)
      if (corners[i] == GT::null_vertex()) {
        corners[i] = add_vertex(pm_);
        set_point(vpm_, corners[i], positions[i]);
        created.push_back(corners[i]);
      }
    std::vector<Triangle> new_triangles(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) new_triangles[i][k] = corners[triangles[i][k]];
    if (!insert_triangles(new_triangles, patch)) {
      // the old patch went in before, so it goes in again
      remove_patch(patch);
      for (vertex_descriptor v : created)
        if (halfedge(v, pm_) == GT::null_halfedge()) remove_vertex(v, pm_);
      created.clear();
      patch.clear();
      insert_triangles(old_triangles, patch);
      return false;
    }
    counts_.vertices_added += created.size();
    return true;
  }

private:
  // The body of insert_patch and edit_patch: every edge that goes is between
  // loop vertices (the patch has none of its own before), every new one
  // touches the loop or the patch's new vertices.
  // `inserted_here`: faces that go were counted as added by insert_patch,
  // so a patch taken back cancels them (as within one insert_patch call)
  template <typename Build>
  bool patch_edit(std::vector<vertex_descriptor>& loop, Build& build, bool inserted_here = false)
  {
    if (stats_) stats_->before_local_edit(loop);
    Patch_operations<PM, VPM> patch_ops(pm_, vpm_);
    std::vector<vertex_descriptor> added;
    const std::size_t faces_before = internal::face_count(pm_);
    const std::size_t vertices_before = internal::vertex_count(pm_);
    const bool done = build(patch_ops, loop, added);
    const std::size_t faces_after = internal::face_count(pm_);
    const std::size_t vertices_after = internal::vertex_count(pm_);
    if (faces_after >= faces_before) counts_.faces_added += faces_after - faces_before;
    else if (inserted_here) counts_.faces_added -= std::min(counts_.faces_added, faces_before - faces_after);
    else counts_.faces_removed += faces_before - faces_after;
    if (vertices_after >= vertices_before) counts_.vertices_added += vertices_after - vertices_before;
    else counts_.vertices_removed += vertices_before - vertices_after;
    counts_.vertices_moved += patch_ops.counts().vertices_moved;
    // `loop` may have been updated by `build` (a collapse that kept a new vertex)
    std::vector<vertex_descriptor> after = loop;
    after.insert(after.end(), added.begin(), added.end());
    if (stats_) stats_->after_local_edit(after);
    for (vertex_descriptor v : after) check_around(v);
    return done;
  }

  using Face_mark = typename boost::property_map<PM, CGAL::dynamic_face_property_t<char>>::type;

  void ensure_marks()
  {
    // created on first use, all zero (Surface_mesh value-initialises new
    // entries; Polyhedron's map inserts char() on first get), zero between calls
    if (!has_marks_) {
      fmark_ = get(CGAL::dynamic_face_property_t<char>(), pm_);
      has_marks_ = true;
    }
  }

  bool has_other_face(vertex_descriptor v, face_descriptor f) const
  {
    for (halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, pm_), pm_))
      if (!is_border(h, pm_) && face(h, pm_) != f) return true;
    return false;
  }

  // The neighbourhood of `v` is consistent: halfedge links that close up,
  // and triangles. (Pinches and double edges are not tested: an input may
  // hold them before any operation ran.)
  void check_around(vertex_descriptor v) const
  {
#if MREPAIR_CHECK_LOCAL_OPERATIONS
    const halfedge_descriptor h0 = halfedge(v, pm_);
    if (h0 == GT::null_halfedge()) return;
    for (halfedge_descriptor h : CGAL::halfedges_around_target(h0, pm_)) {
      if (target(h, pm_) != v || opposite(opposite(h, pm_), pm_) != h ||
          prev(next(h, pm_), pm_) != h || next(prev(h, pm_), pm_) != h)
        throw std::logic_error("local operation left inconsistent halfedges");
      if (!is_border(h, pm_) && next(next(next(h, pm_), pm_), pm_) != h)
        throw std::logic_error("local operation left a face that is not a triangle");
    }
#else
    (void)v;
#endif
  }

  PM& pm_;
  VPM vpm_;
  Statistics* stats_ = nullptr;
  Local_operation_counts counts_;
  Face_mark fmark_;
  bool has_marks_ = false;
};

// What the callback of `insert_patch` and `edit_patch` edits the patch
// with: every operation, and those that take back, put back or replace the
// patch's faces (made only by `patch_edit`, so that those are reachable
// nowhere else).
template <typename PM, typename VPM>
class Patch_operations : public Local_operations<PM, VPM>
{
  using Base = Local_operations<PM, VPM>;
  friend class Local_operations<PM, VPM>;
  Patch_operations(PM& pm, VPM vpm) : Base(pm, vpm) {}

public:
  using Base::insert_triangles;
  using Base::remove_patch;
  using Base::replace_patch;
  using Base::triangles_of;
};

}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_LOCAL_OPERATIONS_H
