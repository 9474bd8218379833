// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The check that a patch filling a border loop (a hole filler's cap, a gap
// closer's bridge) touches the surface only along its loop: a cap that passes through the rest of the model (the bottom of a
// teapot through its body, a slit's fill over faces that already overlap)
// would add the self-intersections the repair is meant to remove, so such a
// fill is taken back like a failed triangulation.
//
// A patch that only continues a crossing the surface already had
// (overlapping parts of a CAD assembly, a missing face where two parts
// interpenetrate: each stretch of faces it meets already crosses the model)
// is kept: taking it back would leave a hole and remove no intersection.
//
// One pass over the mesh per round of fills collects, for each loop to be
// filled, the faces whose box meets the loop's box; a patch is tested against
// those, against the patches accepted since, and against itself. A patch that
// leaves its loop's box (fairing can bulge) is tested against every face.
#ifndef MREPAIR_INTERNAL_PATCH_GUARD_H
#define MREPAIR_INTERNAL_PATCH_GUARD_H

#include <mrepair/internal/spatial_grid.h>
#include <mrepair/internal/triangle_intersection.h>
#include <mrepair/internal/utility.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <atomic>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

namespace mrepair {
namespace internal {

template <typename PM, typename VPM>
class Patch_intersection_guard
{
  using GT = boost::graph_traits<PM>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;

  using Box = Grid_box;

  // a face read once: its vertices (the keys of what two faces share), its
  // corners as exact-predicate points, its box; `finite` false (a non-finite
  // or collinear corner, not a triangle) skips it
  struct Tri
  {
    vertex_descriptor v[3];
    Epick_point p[3];
    Box box;
    bool finite = true;
  };

  PM& pm_;
  VPM vpm_;
  std::vector<Box> loop_boxes_;                      // per prepared loop (empty: not guarded)
  std::vector<std::vector<face_descriptor>> near_;   // faces meeting each loop's box
  std::vector<std::pair<Box, std::vector<face_descriptor>>> accepted_;

  Box face_box(face_descriptor f) const
  {
    Box b;
    for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_))
      b.add(point(vpm_, v));
    return b;
  }

  Tri read(face_descriptor f) const
  {
    Tri t;
    int k = 0;
    for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_)) {
      if (k == 3) { t.finite = false; break; }  // not a triangle: never tested
      const Vec3 q = point(vpm_, v);
      t.finite = t.finite && is_finite(q);
      t.v[k] = v;
      t.p[k] = Epick_point(q[0], q[1], q[2]);
      t.box.add(q);
      ++k;
    }
    if (k != 3) t.finite = false;
    // like the inspection, a degenerate triangle takes no part in pairs (the
    // exact predicates need a proper triangle; the validity step removes it)
    if (t.finite && CGAL::collinear(t.p[0], t.p[1], t.p[2])) t.finite = false;
    return t;
  }

  static bool meet(const Tri& a, const Tri& b)
  {
    return a.finite && b.finite && a.box.meets(b.box) && triangles_intersect(a.v, a.p, b.v, b.p);
  }

public:
  Patch_intersection_guard(PM& pm, VPM vpm) : pm_(pm), vpm_(vpm) {}

  /// collects the faces near each loop of `loops` whose `guarded(i)` holds
  /// (the loops that will be filled), with boxes grown by `margin` times
  /// their extent. Forgets the patches accepted before.
  template <typename Guarded>
  void prepare(const std::vector<halfedge_descriptor>& loops, const Guarded& guarded, double margin)
  {
    accepted_.clear();
    loop_boxes_.assign(loops.size(), Box());
    near_.assign(loops.size(), {});
    std::vector<double> extents;
    for (std::size_t i = 0; i < loops.size(); ++i) {
      if (!guarded(i)) continue;
      Box b;
      for (halfedge_descriptor g : CGAL::halfedges_around_face(loops[i], pm_))
        b.add(point(vpm_, target(g, pm_)));
      if (b.empty()) continue;
      const double grow = margin * b.extent() + 1e-12 * (1. + b.extent());
      for (int d = 0; d < 3; ++d) { b.lo[d] -= grow; b.hi[d] += grow; }
      loop_boxes_[i] = b;
      extents.push_back(b.extent());
    }
    if (extents.empty()) return;
    // a coarse grid over the loop boxes, cells of their median extent; a box
    // spanning too many cells is matched against every face instead
    std::nth_element(extents.begin(), extents.begin() + extents.size() / 2, extents.end());
    const double inverse_cell = 1. / std::max(extents[extents.size() / 2], 1e-300);
    std::vector<typename Spatial_grid<std::uint32_t>::Entry> cells;
    std::vector<std::uint32_t> big;
    for (std::size_t i = 0; i < loops.size(); ++i) {
      const Box& b = loop_boxes_[i];
      if (b.empty()) continue;
      const Cell_range c = Cell_range::of(b, inverse_cell);
      if (!(c.count <= 512)) { big.push_back(std::uint32_t(i)); continue; }
      c.for_each([&](std::int64_t x, std::int64_t y, std::int64_t z) {
        cells.push_back({Grid_cell{{x, y, z}}, std::uint32_t(i)});
      });
    }
    const bool gridded = !cells.empty();
    const Spatial_grid<std::uint32_t> grid(std::move(cells));
    // The faces are matched in blocks, in parallel where the mesh allows it
    // (reads only), and appended block by block: the lists do not depend on
    // the threads. Loop boxes that overlap much of a large model would make
    // the lists quadratic: past a budget of entries they are dropped and
    // every patch is tested against all faces instead (slower, bounded memory).
    std::vector<face_descriptor> all(faces(pm_).begin(), faces(pm_).end());
    const std::size_t budget = 8 * all.size() + (std::size_t(1) << 20);
    const std::size_t block = 1 << 14, blocks = (all.size() + block - 1) / block;
    std::vector<std::vector<std::pair<std::uint32_t, face_descriptor>>> found(blocks);
    std::atomic<std::size_t> entries{0};
    auto match = [&](std::size_t b) {
      std::vector<std::uint32_t> seen;
      auto& out = found[b];
      for (std::size_t k = b * block; k < std::min(all.size(), (b + 1) * block); ++k) {
        if (entries.load(std::memory_order_relaxed) > budget) return;
        const face_descriptor f = all[k];
        const Box fb = face_box(f);
        if (fb.empty() || !std::isfinite(fb.lo[0] + fb.hi[0] + fb.lo[1] + fb.hi[1] + fb.lo[2] + fb.hi[2]))
          continue;
        const std::size_t before = out.size();
        for (std::uint32_t i : big)
          if (loop_boxes_[i].meets(fb)) out.emplace_back(i, f);
        const Cell_range c = Cell_range::of(fb, inverse_cell);
        if (!(c.count <= 64)) {  // a face far larger than the loops: every loop box
          for (std::size_t i = 0; i < loop_boxes_.size(); ++i)
            if (!loop_boxes_[i].empty() && loop_boxes_[i].meets(fb) &&
                std::find(big.begin(), big.end(), std::uint32_t(i)) == big.end())
              out.emplace_back(std::uint32_t(i), f);
        } else if (gridded) {
          seen.clear();
          grid.for_each_in(c, [&](std::uint32_t i) {
            if (loop_boxes_[i].meets(fb) && std::find(seen.begin(), seen.end(), i) == seen.end()) {
              seen.push_back(i);
              out.emplace_back(i, f);
            }
          });
        }
        // most faces add nothing: no shared write for them (the atomic add
        // on every face was a fifth of the scan, the threads contending)
        if (out.size() != before) entries.fetch_add(out.size() - before, std::memory_order_relaxed);
      }
    };
    // only reads: safe on Surface_mesh's arrays, kept sequential elsewhere
    // like the library's other loops over mesh elements
    if (Is_surface_mesh<PM>::value)
      parallel_for_index(blocks, 1, match);
    else
      for (std::size_t b = 0; b < blocks; ++b) match(b);
    if (entries.load() > budget) {
      loop_boxes_.assign(loops.size(), Box());
      near_.assign(loops.size(), {});
      return;
    }
    for (const auto& out : found)
      for (const auto& e : out) near_[e.first].push_back(e.second);
  }

  /// whether the faces of `patch`, filling prepared loop `i`, meet the
  /// rest of the surface or each other other than along what they share.
  /// Faces in `tolerated` (when given) may be met; with `test_itself`
  /// false, so may the patch's own faces.
  bool patch_intersects(std::size_t i, const std::vector<face_descriptor>& patch,
                        const std::set<face_descriptor>* tolerated = nullptr, bool test_itself = true)
  {
    std::vector<Tri> tris;
    tris.reserve(patch.size());
    Box pb;
    for (face_descriptor f : patch) {
      tris.push_back(read(f));
      pb.add(tris.back().box);
    }
    // the patch against itself: faces sorted by their lowest x, swept
    std::vector<std::size_t> order(tris.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return tris[a].box.lo[0] < tris[b].box.lo[0]; });
    for (std::size_t a = 0; test_itself && a < order.size(); ++a)
      for (std::size_t b = a + 1; b < order.size(); ++b) {
        if (tris[order[b]].box.lo[0] > tris[order[a]].box.hi[0]) break;
        if (meet(tris[order[a]], tris[order[b]])) return true;
      }
    const std::set<face_descriptor> own(patch.begin(), patch.end());
    std::vector<face_descriptor> candidates;
    const bool inside = i < loop_boxes_.size() && !loop_boxes_[i].empty() &&
                        loop_boxes_[i].contains(pb);
    if (inside) {
      candidates = near_[i];
      for (const auto& a : accepted_)
        if (a.first.meets(pb)) candidates.insert(candidates.end(), a.second.begin(), a.second.end());
    } else {
      for (face_descriptor g : faces(pm_))
        if (!own.count(g)) candidates.push_back(g);
    }
    // the faces the patch meets
    std::vector<face_descriptor> met;
    std::vector<Tri> met_tris;
    for (face_descriptor g : candidates) {
      if (own.count(g) || (tolerated && tolerated->count(g)) || !pb.meets(face_box(g))) continue;
      const Tri t = read(g);
      for (const Tri& p : tris) {
        if (meet(p, t)) {
          met.push_back(g);
          met_tris.push_back(t);
          break;
        }
      }
    }
    if (met.empty()) return false;
    // A stretch of surface that already crosses the model (overlapping parts
    // of a CAD assembly, a part through another) is where the missing faces
    // crossed it too: a patch that only continues such a crossing is kept.
    // The faces the patch meets are grouped by shared edges; every group
    // must hold a face that crosses the surface outside the patch, else the
    // patch cuts through a clean stretch and makes a new crossing.
    std::map<face_descriptor, std::size_t> index_of;
    for (std::size_t k = 0; k < met.size(); ++k) index_of.emplace(met[k], k);
    Union_find<std::size_t> groups(met.size());
    for (std::size_t k = 0; k < met.size(); ++k)
      for (halfedge_descriptor g : CGAL::halfedges_around_face(halfedge(met[k], pm_), pm_)) {
        const halfedge_descriptor o = opposite(g, pm_);
        if (is_border(o, pm_)) continue;
        const auto it = index_of.find(face(o, pm_));
        if (it != index_of.end()) groups.unite(k, it->second);
      }
    std::vector<char> group_crosses(met.size(), 0);
    for (std::size_t k = 0; k < met.size(); ++k) {
      const std::size_t root = groups.find(k);
      if (!group_crosses[root] && crosses_surface(met_tris[k], met[k], candidates, own))
        group_crosses[root] = 1;
    }
    for (std::size_t k = 0; k < met.size(); ++k)
      if (!group_crosses[groups.find(k)]) return true;
    return false;
  }

  // whether `t` (face `g`) meets a face of `candidates` outside the patch
  bool crosses_surface(const Tri& t, face_descriptor g, const std::vector<face_descriptor>& candidates,
                       const std::set<face_descriptor>& own)
  {
    for (face_descriptor h : candidates) {
      if (h == g || own.count(h) || !t.box.meets(face_box(h))) continue;
      if (meet(t, read(h))) return true;
    }
    return false;
  }

  /// records a patch kept in the mesh, so that later patches are tested against it.
  void accept(const std::vector<face_descriptor>& patch)
  {
    Box b;
    for (face_descriptor f : patch) b.add(face_box(f));
    accepted_.emplace_back(b, patch);
  }
};

}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_PATCH_GUARD_H
