// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Worker of fill_small_holes() (RameshCleaner 3.4, 3.5): Liepa's patch,
// refined and faired, inserted through the local operations; aborted fills
// enlarged by their 1-ring.
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_HOLE_FILLER_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_HOLE_FILLER_H

#include <mrepair/cleaning_results.h>
#include <mrepair/internal/clean_scan_mesh/mesh_ops.h>
#include <mrepair/internal/clean_scan_mesh/patch_guard.h>
#include <mrepair/internal/clean_scan_mesh/safety.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/status.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <set>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {
namespace clean_pipeline {

/// Fills holes (3.4) and handles aborted fills (3.5) for one mesh.
template <typename PM, typename VPM>
class Small_hole_filler
{
  using GT = boost::graph_traits<PM>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;

  using Operations = Local_operations<PM, VPM>;

  Operations& ops_;
  PM& pm_;
  VPM vpm_;
  std::size_t max_vertices_;
  double density_;
  bool refine_, fair_;
  std::size_t delaunay_above_;
  double area_share_;
  // scratch of the bounded component searches, all zero between searches
  typename boost::property_map<PM, CGAL::dynamic_face_property_t<char>>::type visited_;
  std::vector<face_descriptor> reached_;
  // fills that would pass through the surface are taken back (patch_guard.h)
  Patch_intersection_guard<PM, VPM> guard_;
  bool last_fill_intersected_ = false;
  std::set<halfedge_descriptor> intersected_;  // failed loops whose last patch was taken back

public:
  Hole_filling_result result;

  Small_hole_filler(Operations& ops, std::size_t max_vertices, double density, bool refine,
                    bool fair, std::size_t delaunay_above, double area_share)
    : ops_(ops), pm_(ops.mesh()), vpm_(ops.vertex_point_map()), max_vertices_(max_vertices),
      density_(density), refine_(refine), fair_(fair), delaunay_above_(delaunay_above),
      area_share_(area_share), visited_(get(CGAL::dynamic_face_property_t<char>(), pm_)),
      guard_(pm_, vpm_)
  {
    for (face_descriptor f : faces(pm_)) put(visited_, f, char(0));
  }

  // Grows the component of face `f0` until its faces reach `min_area` of
  // area or `min_faces` faces (each bound ignored when 0); true when they
  // do. The search stops there, so a small hole in a large mesh costs a few
  // rings, not the mesh.
  bool component_reaches(face_descriptor f0, double min_area, std::size_t min_faces)
  {
    reached_.assign(1, f0);
    put(visited_, f0, char(1));
    double area = 0.;
    bool enough = false;
    for (std::size_t head = 0; head < reached_.size() && !enough; ++head) {
      const face_descriptor f = reached_[head];
      const double a = 0.5 * norm(face_normal(halfedge(f, pm_), pm_, vpm_));
      if (std::isfinite(a)) area += a;
      enough = (min_area > 0. && area >= min_area) || (min_faces > 0 && head + 1 >= min_faces);
      for (halfedge_descriptor g : CGAL::halfedges_around_face(halfedge(f, pm_), pm_)) {
        halfedge_descriptor o = opposite(g, pm_);
        if (is_border(o, pm_) || get(visited_, face(o, pm_))) continue;
        put(visited_, face(o, pm_), char(1));
        reached_.push_back(face(o, pm_));
      }
    }
    for (face_descriptor f : reached_) put(visited_, f, char(0));
    return enough;
  }

  // The hole-or-border rule (doc/guarantees.md): a loop is a hole when the
  // cap that closes it is small next to the surface around it, under
  // `area_share_` of its component's area. The outer border of a sheet, a
  // patch or a lone triangle has a cap as large as the sheet itself, and
  // capping it would make a zero-volume double layer.
  bool is_sheet_border(halfedge_descriptor h)
  {
    if (area_share_ <= 0.) return false;
    const double cap = loop_cap_area(h, pm_, vpm_);
    if (!(cap > 0.)) return false;  // a flat zero-area loop: closing it adds nothing
    return !component_reaches(face(opposite(h, pm_), pm_), cap / area_share_, 0);
  }

  std::size_t loop_size(halfedge_descriptor h) const
  {
    std::size_t n = 0;
    for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_)) { (void)g; ++n; }
    return n;
  }

  // One representative border halfedge per border loop among `hs`
  // (deduplicated by walking each loop once).
  void loops_of(const std::vector<halfedge_descriptor>& hs, std::vector<halfedge_descriptor>& out)
  {
    std::set<halfedge_descriptor> done;
    for (halfedge_descriptor h : hs) {
      if (!is_border(h, pm_) || done.count(h)) continue;
      out.push_back(h);
      for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_)) done.insert(g);
    }
  }

  // Triangulates the loop of `h`, then refines and fairs the patch. Returns
  // false (mesh unchanged) when no valid triangulation exists.
  bool loop_is_finite(halfedge_descriptor h) const
  {
    for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_))
      if (!is_finite_point(vpm_, target(g, pm_))) return false;
    return true;
  }

  bool two_rings_are_finite(const std::vector<vertex_descriptor>& vs) const
  {
    for (vertex_descriptor v : vs)
      for (vertex_descriptor w : CGAL::vertices_around_target(halfedge(v, pm_), pm_)) {
        if (!is_finite_point(vpm_, w)) return false;
        for (vertex_descriptor x : CGAL::vertices_around_target(halfedge(w, pm_), pm_))
          if (!is_finite_point(vpm_, x)) return false;
      }
    return true;
  }

  // Inserts the patch of the loop of `h` through the local operations:
  // Liepa's triangulation, then refinement and fairing of the new faces,
  // with the statistics updated once for the whole patch.
  // `index`: the loop's place in the list the guard was prepared with.
  bool fill(halfedge_descriptor h, std::size_t n, std::size_t index)
  {
    last_fill_intersected_ = false;
    double lsum = 0.;
    for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_)) {
      if (!is_finite_point(vpm_, target(g, pm_))) return false;
      lsum += norm(sub(point(vpm_, target(g, pm_)), point(vpm_, source(g, pm_))));
    }
    return ops_.insert_patch(h, [&](Operations& patch_ops, std::vector<vertex_descriptor>& loop,
                                    std::vector<vertex_descriptor>& added) {
      std::vector<face_descriptor> patch;
      patch.reserve(2 * n);
      // CGAL's implementation of Liepa's weight; existing edges between loop
      // vertices and degenerate triangles are excluded, so an empty output is
      // an aborted fill (3.5). The DT3 search space only pays on longer loops.
      CGAL::Polygon_mesh_processing::triangulate_hole(
          pm_, h, std::back_inserter(patch),
          CGAL::parameters::vertex_point_map(vpm_).use_delaunay_triangulation(n > delaunay_above_));
      if (patch.empty()) return false;
      // Liepa's patch, kept to fall back on when the refined one crosses
      const std::vector<vertex_descriptor> loop_before = loop;
      const std::vector<std::array<vertex_descriptor, 3>> coarse = triangles_of(patch);
      if (refine_ && n > 3) refine(patch_ops, patch, density_ * lsum / double(n), added, loop);
      // Fairing reads the 2-ring of the patch vertices with exact predicates,
      // which fail on NaN: skip it next to a non-finite vertex.
      if (fair_ && !added.empty() && two_rings_are_finite(added))
        CGAL::Polygon_mesh_processing::fair(pm_, added, CGAL::parameters::vertex_point_map(vpm_));
      if (guard_.patch_intersects(index, patch)) {
        patch_ops.remove_patch(patch);
        const bool refined = !added.empty();
        added.clear();
        patch.clear();
        // A refinement or fairing can fold where Liepa's patch did not: put
        // the coarse patch back (its loop vertices as the refinement left
        // them) and keep it when it crosses nothing.
        if (!refined || !put_back(patch_ops, coarse, loop_before, loop, patch) ||
            guard_.patch_intersects(index, patch)) {
          if (!patch.empty()) patch_ops.remove_patch(patch);
          ++result.fills_rejected_intersecting;
          last_fill_intersected_ = true;
          return false;
        }
      }
      guard_.accept(patch);
      result.faces_added += patch.size();
      result.vertices_added += added.size();
      return true;
    });
  }

  std::vector<std::array<vertex_descriptor, 3>> triangles_of(const std::vector<face_descriptor>& fs) const
  {
    std::vector<std::array<vertex_descriptor, 3>> ts;
    for (face_descriptor f : fs) {
      std::array<vertex_descriptor, 3> t;
      int k = 0;
      for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_))
        if (k < 3) t[k++] = v;
      ts.push_back(t);
    }
    return ts;
  }

  // Re-inserts Liepa's triangles `coarse` into the loop; a loop vertex the
  // refinement replaced (loop_before[i] -> loop[i], same position) is mapped.
  bool put_back(Operations& patch_ops, std::vector<std::array<vertex_descriptor, 3>> coarse,
                const std::vector<vertex_descriptor>& loop_before,
                const std::vector<vertex_descriptor>& loop, std::vector<face_descriptor>& patch)
  {
    for (auto& t : coarse)
      for (vertex_descriptor& v : t) {
        const auto it = std::find(loop_before.begin(), loop_before.end(), v);
        if (it != loop_before.end()) v = loop[std::size_t(it - loop_before.begin())];
      }
    return patch_ops.insert_triangles(coarse, patch);
  }

  // Refines a patch to edge length `L` (Botsch-Kobbelt style, patch only):
  // split interior edges longer than 4/3 L, flip towards valence 6, relax new
  // vertices with the uniform Laplacian. The loop's edges and vertices stay.
  void refine(Operations& patch_ops, std::vector<face_descriptor>& patch, double L,
              std::vector<vertex_descriptor>& added, std::vector<vertex_descriptor>& loop)
  {
    if (!(L > 0.)) return;
    std::set<face_descriptor> in(patch.begin(), patch.end());
    auto interior = [&](halfedge_descriptor h) {
      return !is_border_edge(h, pm_) && in.count(face(h, pm_)) &&
             in.count(face(opposite(h, pm_), pm_));
    };
    auto sqlen = [&](halfedge_descriptor h) {
      Vec3 d = sub(point(vpm_, target(h, pm_)), point(vpm_, source(h, pm_)));
      return dot(d, d);
    };
    const double high2 = (4. / 3. * L) * (4. / 3. * L);
    const double low2 = (4. / 5. * L) * (4. / 5. * L);
    std::set<vertex_descriptor> added_set;
    std::vector<halfedge_descriptor> hs;
    // Flip and relax first, split last: the loop ends on a split pass that
    // found nothing, so every patch edge is at most 4/3 L on exit.
    for (int round = 0; round < 12; ++round) {
      // Flip interior edges towards valence 6 when it does not fold the patch.
      for (int pass = 0; pass < 2; ++pass) {
        hs.clear();
        for (face_descriptor f : patch)
          for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, pm_), pm_))
            if (interior(h) && h < opposite(h, pm_)) hs.push_back(h);
        for (halfedge_descriptor h : hs) try_flip(patch_ops, h);
      }
      // Relax the new vertices (uniform Laplacian, Jacobi).
      for (int it = 0; it < 3; ++it) {
        std::vector<Vec3> np(added.size());
        for (std::size_t i = 0; i < added.size(); ++i) {
          Vec3 c{0, 0, 0};
          int k = 0;
          for (vertex_descriptor w : CGAL::vertices_around_target(halfedge(added[i], pm_), pm_)) {
            c = add(c, point(vpm_, w));
            ++k;
          }
          np[i] = k ? mul(c, 1. / k) : point(vpm_, added[i]);
        }
        patch_ops.move_vertices(added, np);
      }
      // Split, longest first.
      hs.clear();
      for (face_descriptor f : patch)
        for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, pm_), pm_))
          if (interior(h) && h < opposite(h, pm_) && sqlen(h) > high2) hs.push_back(h);
      std::sort(hs.begin(), hs.end(), [&](halfedge_descriptor a, halfedge_descriptor b) {
        return sqlen(a) > sqlen(b);
      });
      std::size_t splits = 0;
      for (halfedge_descriptor h : hs) {
        if (sqlen(h) <= high2) continue;
        Vec3 m = mul(add(point(vpm_, source(h, pm_)), point(vpm_, target(h, pm_))), 0.5);
        std::vector<face_descriptor> cut;
        const vertex_descriptor vn = patch_ops.split_edge(h, m, &cut);
        added.push_back(vn);
        added_set.insert(vn);
        // both sides were patch triangles: every face beside the new edges is in the patch
        for (face_descriptor f : cut)
          if (in.insert(f).second) patch.push_back(f);
        ++splits;
      }
      // Collapse short edges at new vertices (the splits of fan-shaped
      // initial triangulations crowd vertices), shortest first.
      const std::size_t collapses =
          collapse_short_edges(patch_ops, patch, in, L, low2, added_set, loop, interior, sqlen);
      added.assign(added_set.begin(), added_set.end());
      if (splits == 0 && collapses == 0) break;
    }
  }

  // Collapses interior patch edges shorter than `low2` (squared) with a new
  // vertex at one end, shortest first, in batches: a batch lists the
  // candidates once and sorts them, so that a dense patch costs
  // O(n log n) per batch instead of a rescan of the patch per collapse
  // (a 24-vertex hole filled at density factor 0.1, about 8,500 faces, took
  // 17 s with rescans). Candidates are kept as vertex pairs and looked up
  // again: a collapse frees halfedges (on Polyhedron_3) and one vertex, whose
  // handle is only compared afterwards, never dereferenced.
  template <typename Interior, typename Sqlen>
  std::size_t collapse_short_edges(Operations& patch_ops, std::vector<face_descriptor>& patch,
                                   std::set<face_descriptor>& in, double L, double low2,
                                   std::set<vertex_descriptor>& added_set,
                                   std::vector<vertex_descriptor>& loop, const Interior& interior,
                                   const Sqlen& sqlen)
  {
    using Candidate = std::pair<double, std::pair<vertex_descriptor, vertex_descriptor>>;
    const std::size_t cap = 4 * patch.size();
    std::size_t total = 0;
    std::vector<Candidate> candidates;
    std::set<vertex_descriptor> gone;
    while (total < cap) {
      candidates.clear();
      for (face_descriptor f : patch)
        for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, pm_), pm_)) {
          const vertex_descriptor a = source(h, pm_), b = target(h, pm_);
          if (h < opposite(h, pm_) && interior(h) && sqlen(h) < low2 &&
              (added_set.count(a) || added_set.count(b)))
            candidates.push_back(Candidate(sqlen(h), std::make_pair(a, b)));
        }
      std::sort(candidates.begin(), candidates.end(),
                [](const Candidate& x, const Candidate& y) { return x.first < y.first; });
      gone.clear();
      std::size_t batch = 0;
      for (const Candidate& c : candidates) {
        if (total >= cap) break;
        const vertex_descriptor a = c.second.first, b = c.second.second;
        if (gone.count(a) || gone.count(b)) continue;
        const auto found = halfedge(a, b, pm_);
        if (!found.second) continue;
        const halfedge_descriptor h = found.first;
        if (!interior(h) || !(sqlen(h) < low2) || !(added_set.count(a) || added_set.count(b)) ||
            !can_collapse(patch_ops, h, L, added_set))
          continue;
        const vertex_descriptor kept = collapse(patch_ops, h, added_set, in, loop);
        gone.insert(kept == a ? b : a);
        ++batch;
        ++total;
      }
      if (batch == 0) break;
      patch.assign(in.begin(), in.end());
    }
    return total;
  }

  // Position of the vertex kept when `h`'s edge collapses: an original
  // vertex stays where it is, two new vertices meet at the midpoint.
  Vec3 collapse_point(halfedge_descriptor h, const std::set<vertex_descriptor>& added_set) const
  {
    vertex_descriptor a = source(h, pm_), b = target(h, pm_);
    if (!added_set.count(a)) return point(vpm_, a);
    if (!added_set.count(b)) return point(vpm_, b);
    return mul(add(point(vpm_, a), point(vpm_, b)), 0.5);
  }

  // Link condition, no edge longer than 4/3 L, no face turned over.
  bool can_collapse(const Operations& patch_ops, halfedge_descriptor h, double L,
                    const std::set<vertex_descriptor>& added_set)
  {
    if (!patch_ops.collapse_keeps_manifold(h)) return false;
    const Vec3 p = collapse_point(h, added_set);
    const double high2 = (4. / 3. * L) * (4. / 3. * L);
    vertex_descriptor a = source(h, pm_), b = target(h, pm_);
    for (vertex_descriptor v : {a, b})
      for (halfedge_descriptor k : CGAL::halfedges_around_target(v, pm_)) {
        vertex_descriptor w = source(k, pm_);
        if (w == a || w == b) continue;
        Vec3 d = sub(point(vpm_, w), p);
        if (dot(d, d) > high2) return false;
        if (is_border(k, pm_)) continue;
        // Face of k: (.., w, v): skip the two faces that vanish.
        face_descriptor f = face(k, pm_);
        if (f == face(h, pm_) || f == face(opposite(h, pm_), pm_)) continue;
        Vec3 q[3];
        int i = 0;
        Vec3 before = face_normal(k, pm_, vpm_);
        for (vertex_descriptor u : CGAL::vertices_around_face(k, pm_))
          q[i++] = (u == a || u == b) ? p : point(vpm_, u);
        Vec3 after = cross(sub(q[1], q[0]), sub(q[2], q[0]));
        if (dot(before, after) <= 0.) return false;
      }
    return true;
  }

  // `loop` lists the loop's vertices: when the collapse keeps the new vertex
  // (CGAL keeps target(halfedge(e))), it takes the original's place there.
  // Returns the vertex kept.
  vertex_descriptor collapse(Operations& patch_ops, halfedge_descriptor h,
                             std::set<vertex_descriptor>& added_set,
                             std::set<face_descriptor>& in, std::vector<vertex_descriptor>& loop)
  {
    const Vec3 p = collapse_point(h, added_set);
    const vertex_descriptor a = source(h, pm_), b = target(h, pm_);
    const bool keep_original = !added_set.count(a) || !added_set.count(b);
    const vertex_descriptor original = added_set.count(a) ? b : a;
    in.erase(face(h, pm_));
    in.erase(face(opposite(h, pm_), pm_));
    added_set.erase(source(h, pm_));
    added_set.erase(target(h, pm_));
    const vertex_descriptor v = patch_ops.collapse_edge(h, p);
    if (!keep_original)
      added_set.insert(v);  // two new vertices merged: still new
    else if (v != original)
      std::replace(loop.begin(), loop.end(), original, v);
    return v;
  }

  bool try_flip(Operations& patch_ops, halfedge_descriptor h)
  {
    if (!patch_ops.flip_keeps_manifold(h, 3)) return false;
    halfedge_descriptor o = opposite(h, pm_);
    vertex_descriptor a = target(h, pm_), b = target(o, pm_);
    vertex_descriptor c = target(next(h, pm_), pm_), d = target(next(o, pm_), pm_);
    auto val = [&](vertex_descriptor v) { return int(degree(v, pm_)); };
    const int va = val(a), vb = val(b), vc = val(c), vd = val(d);
    auto dev = [](int x) { return std::abs(x - 6); };
    int before = dev(va) + dev(vb) + dev(vc) + dev(vd);
    int after = dev(va - 1) + dev(vb - 1) + dev(vc + 1) + dev(vd + 1);
    if (after >= before) return false;
    // Geometry: both new triangles keep the orientation of the old pair.
    Vec3 pa = point(vpm_, a), pb = point(vpm_, b), pc = point(vpm_, c), pd = point(vpm_, d);
    Vec3 n_old = add(cross(sub(pa, pb), sub(pc, pb)), cross(sub(pb, pa), sub(pd, pa)));
    // h: b->a in face (b, a, c); o: a->b in face (a, b, d); the quad is
    // a-c-b-d and the flip makes (b, d, c) and (a, c, d).
    Vec3 n1 = cross(sub(pd, pb), sub(pc, pb)), n2 = cross(sub(pc, pa), sub(pd, pa));
    if (dot(n1, n_old) <= 0. || dot(n2, n_old) <= 0.) return false;
    // No needle: each new triangle keeps a fair share of the pair's area.
    if (norm(n1) <= 1e-2 * norm(n_old) || norm(n2) <= 1e-2 * norm(n_old)) return false;
    patch_ops.flip_edge(h);
    return true;
  }

  // Removes the faces around the loops of `holes` (their boundary's 1-ring),
  // resolving pinches; returns the border halfedges around the survivors.
  void enlarge(const std::vector<halfedge_descriptor>& holes,
               std::vector<halfedge_descriptor>& new_border)
  {
    std::vector<face_descriptor> doomed;
    for (halfedge_descriptor h : holes)
      for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_))
        for (halfedge_descriptor k : CGAL::halfedges_around_target(target(g, pm_), pm_))
          if (!is_border(k, pm_)) doomed.push_back(face(k, pm_));
    std::vector<vertex_descriptor> survivors;
    const std::size_t removed = ops_.remove_faces_without_pinches(doomed, &survivors);
    result.enlargement_faces_removed += removed;
    ++result.enlargements;
    std::vector<halfedge_descriptor> hs;
    for (vertex_descriptor v : survivors)
      for (halfedge_descriptor k : CGAL::halfedges_around_target(v, pm_))
        if (is_border(k, pm_)) hs.push_back(k);
    loops_of(hs, new_border);
  }

  // the guard reads the faces near the loops that may be filled
  void prepare_guard(const std::vector<halfedge_descriptor>& loops)
  {
    guard_.prepare(
        loops, [&](std::size_t i) { return loop_size(loops[i]) < max_vertices_; },
        fair_ ? 0.5 : 0.);  // fairing may bulge out of the loop's box; the rest stays inside
  }

  void fill_failed(halfedge_descriptor h, std::vector<halfedge_descriptor>& failed)
  {
    ++result.aborted_fills;
    failed.push_back(h);
    if (last_fill_intersected_) intersected_.insert(h);
  }

  template <typename Visitor>
  Status run(std::size_t max_enlargements, Visitor& visitor)
  {
    std::vector<halfedge_descriptor> all, loops;
    for (halfedge_descriptor h : halfedges(pm_))
      if (is_border(h, pm_)) all.push_back(h);
    loops_of(all, loops);
    prepare_guard(loops);
    std::vector<halfedge_descriptor> failed, next;
    std::size_t done = 0;
    for (std::size_t index = 0; index < loops.size(); ++index) {
      const halfedge_descriptor h = loops[index];
      if (visitor.stop_requested()) return Status::cancelled;
      std::size_t n = loop_size(h);
      if (n >= max_vertices_) { ++result.holes_too_large; continue; }
      if (!loop_is_finite(h)) {  // no fill and no enlargement around bad data
        ++result.holes_found;
        result.open_holes.push_back({n, "non_finite"});
        continue;
      }
      if (is_sheet_border(h)) { ++result.sheet_borders; continue; }
      ++result.holes_found;
      if (fill(h, n, index)) ++result.holes_filled;
      else fill_failed(h, failed);
      if ((++done & 63) == 0) visitor.progress(double(done) / double(loops.size()));
    }
    // 3.5: enlarge the aborted holes by their 1-ring and retry, a bounded
    // number of times. Enlarging all of them at once keeps every stored
    // halfedge valid (a loop's halfedges are only touched by its own round).
    for (std::size_t round = 0; !failed.empty(); ++round) {
      if (round == max_enlargements) {
        for (halfedge_descriptor h : failed)
          result.open_holes.push_back(
              {loop_size(h), intersected_.count(h) ? "patch_intersects_surface" : "triangulation_failed"});
        break;
      }
      if (visitor.stop_requested()) return Status::cancelled;
      // An enlargement removes the loop's 1-ring: only where the component
      // is at least ten times larger, so that no small part is eaten.
      {
        std::vector<halfedge_descriptor> kept;
        std::vector<face_descriptor> ring_faces;
        for (halfedge_descriptor h : failed) {
          ring_faces.clear();
          for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_))
            for (halfedge_descriptor k : CGAL::halfedges_around_target(g, pm_))
              if (!is_border(k, pm_) && !get(visited_, face(k, pm_))) {
                put(visited_, face(k, pm_), char(1));
                ring_faces.push_back(face(k, pm_));
              }
          for (face_descriptor f : ring_faces) put(visited_, f, char(0));
          const std::size_t ring = ring_faces.size();
          if (component_reaches(face(opposite(h, pm_), pm_), 0., 10 * ring)) kept.push_back(h);
          else result.open_holes.push_back({loop_size(h), "component_too_small"});
        }
        failed.swap(kept);
        if (failed.empty()) break;
      }
      loops.clear();
      enlarge(failed, loops);
      failed.clear();
      intersected_.clear();
      prepare_guard(loops);
      for (std::size_t index = 0; index < loops.size(); ++index) {
        const halfedge_descriptor h = loops[index];
        std::size_t n = loop_size(h);
        if (n >= max_vertices_ || is_sheet_border(h)) {
          result.open_holes.push_back({n, "grew_too_large"});
          continue;
        }
        if (!loop_is_finite(h)) {
          result.open_holes.push_back({n, "non_finite"});
          continue;
        }
        if (fill(h, n, index)) ++result.holes_filled;
        else fill_failed(h, failed);
      }
    }
    return result.open_holes.empty() ? Status::ok : Status::partial;
  }
};

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_HOLE_FILLER_H
