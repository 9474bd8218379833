// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Worker of clean_boundaries() (RameshCleaner 3.3) and the safety policy of
// boundary erosion (doc/guarantees.md).
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_BOUNDARIES_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_BOUNDARIES_H

#include <mrepair/cleaning_results.h>
#include <mrepair/definitions.h>
#include <mrepair/parameters.h>
#include <mrepair/internal/clean_scan_mesh/mesh_ops.h>
#include <mrepair/internal/clean_scan_mesh/safety.h>
#include <mrepair/internal/clean_scan_mesh/small_components.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/internal/utility.h>
#include <mrepair/status.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {
namespace clean_pipeline {

// Why a boundary vertex is bad (RameshCleaner 3.3): a) its valence is 2,
// b) an incident edge has a dihedral angle above `max_angle` (a border face
// folded back) or an incident face has no area (its fold is undefined: it is
// treated as folded), c) it has more than two incident boundary edges.
enum class Bad_boundary { no, valence_two, folded, pinched };

template <typename PM, typename VPM>
Bad_boundary bad_boundary_vertex(typename boost::graph_traits<PM>::vertex_descriptor v,
                                 const PM& pm, const VPM& vpm, double max_angle)
{
  std::size_t valence = 0, border_edges = 0;
  bool sharp = false;
  for (auto h : CGAL::halfedges_around_target(halfedge(v, pm), pm)) {
    ++valence;
    if (!sharp && !is_border(h, pm) && is_zero(face_normal(h, pm, vpm))) sharp = true;
    if (is_border_edge(h, pm))
      ++border_edges;
    else if (!sharp && dihedral_angle_deg(h, pm, vpm) > max_angle)
      sharp = true;
  }
  if (border_edges == 0) return Bad_boundary::no;
  if (border_edges > 2) return Bad_boundary::pinched;
  if (sharp) return Bad_boundary::folded;
  return valence == 2 ? Bad_boundary::valence_two : Bad_boundary::no;
}

// Collects each boundary vertex once (order of the halfedge scan), from the
// border halfedges `border` (border_halfedges()).
template <typename PM, typename VMark>
void collect_boundary_vertices(const PM& pm,
                               const std::vector<typename boost::graph_traits<PM>::halfedge_descriptor>& border,
                               VMark& seen, std::vector<typename boost::graph_traits<PM>::vertex_descriptor>& out)
{
  out.clear();
  for (auto h : border) {
    auto v = target(h, pm);
    if (!get(seen, v)) {
      put(seen, v, true);
      out.push_back(v);
    }
  }
  for (auto v : out) put(seen, v, false);
}

/// Restricted uniform Laplacian (RameshCleaner eq. 1) on the boundary
/// vertices and their 1-ring: boundary vertices average only their neighbours
/// across boundary edges (no shrinkage into the surface), others their whole
/// 1-ring. Jacobi steps of `step` x L(v). Returns the number of vertices moved.
/// Only the boundary vertices `smoothable(v)` accepts move, with their rings.
template <typename PM, typename VPM, typename Smoothable>
std::size_t smooth_boundary_ring(Local_operations<PM, VPM>& ops, std::size_t iterations,
                                 double step, const Smoothable& smoothable)
{
  using vertex_descriptor = typename boost::graph_traits<PM>::vertex_descriptor;
  PM& pm = ops.mesh();
  const VPM& vpm = ops.vertex_point_map();
  if (iterations == 0 || step == 0.) return 0;
  auto idx = get(CGAL::dynamic_vertex_property_t<int>(), pm);
  // new dynamic maps hold value-initialised entries (false) on every mesh type
  auto seen = get(CGAL::dynamic_vertex_property_t<bool>(), pm);
  for (vertex_descriptor v : vertices(pm)) put(idx, v, -1);
  std::vector<vertex_descriptor> set;
  {
    std::vector<typename boost::graph_traits<PM>::halfedge_descriptor> border;
    border_halfedges(pm, border);
    collect_boundary_vertices(pm, border, seen, set);
  }
  set.erase(std::remove_if(set.begin(), set.end(),
                           [&](vertex_descriptor v) { return !smoothable(v); }),
            set.end());
  const std::size_t nb = set.size();
  if (nb == 0) return 0;
  for (std::size_t i = 0; i < nb; ++i) put(idx, set[i], int(i));
  for (std::size_t i = 0; i < nb; ++i)
    for (vertex_descriptor w : CGAL::vertices_around_target(halfedge(set[i], pm), pm))
      if (get(idx, w) < 0) {
        put(idx, w, int(set.size()));
        set.push_back(w);
      }
  // Neighbour lists (CSR) as indices into `pos`; vertices outside the set
  // are appended as fixed entries.
  std::vector<Vec3> pos;
  pos.reserve(set.size() * 2);
  for (vertex_descriptor v : set) pos.push_back(point(vpm, v));
  std::vector<std::size_t> offs(set.size() + 1, 0);
  std::vector<int> nbr;
  nbr.reserve(set.size() * 6);
  std::vector<vertex_descriptor> fixed;
  for (std::size_t i = 0; i < set.size(); ++i) {
    vertex_descriptor v = set[i];
    const bool boundary = i < nb;
    for (auto h : CGAL::halfedges_around_target(halfedge(v, pm), pm)) {
      if (boundary && !is_border_edge(h, pm)) continue;
      vertex_descriptor w = source(h, pm);
      int j = get(idx, w);
      if (j < 0) {
        j = int(pos.size());
        put(idx, w, j);
        pos.push_back(point(vpm, w));
        fixed.push_back(w);
      }
      nbr.push_back(j);
    }
    offs[i + 1] = nbr.size();
  }
  std::vector<Vec3> next(set.size());
  for (std::size_t it = 0; it < iterations; ++it) {
    for (std::size_t i = 0; i < set.size(); ++i) {
      const std::size_t k = offs[i + 1] - offs[i];
      if (k == 0) { next[i] = pos[i]; continue; }
      Vec3 c{0, 0, 0};
      for (std::size_t a = offs[i]; a < offs[i + 1]; ++a) c = add(c, pos[nbr[a]]);
      c = mul(c, 1. / double(k));
      next[i] = add(pos[i], mul(sub(c, pos[i]), step));
    }
    std::copy(next.begin(), next.end(), pos.begin());
  }
  pos.resize(set.size());  // the fixed neighbours stay
  ops.move_vertices(set, pos);
  return set.size();
}

/// Counts the faces next to the confidence region `region_list` (BFS order),
/// each once, for the loop `region` gives its first vertex in that order.
/// On a Surface_mesh with a large region (unless `parallel` is false) in
/// parallel, without `fmark`: a face goes to its vertex of lowest rank in the
/// list (10M faces, 1.3M region vertices: 0.27 s one after the other, 0.16 s
/// so). Else one after the other, marking counted faces in `fmark` (all 0,
/// left as it was).
template <typename PM, typename RegionMap, typename FaceMark>
void count_region_faces(PM& pm, const std::vector<typename boost::graph_traits<PM>::vertex_descriptor>& region_list,
                        const RegionMap& region, FaceMark& fmark, std::vector<std::size_t>& count,
                        bool parallel = true)
{
  using face_descriptor = typename boost::graph_traits<PM>::face_descriptor;
  if constexpr (Is_surface_mesh<PM>::value) {
    if (parallel && region_list.size() > 20000) {
      // 0 outside the region, else the position in the list plus one (new
      // dynamic maps hold value-initialised entries)
      auto rank = get(CGAL::dynamic_vertex_property_t<std::size_t>(), pm);
      parallel_for_index(region_list.size(), 8192, [&](std::size_t i) { put(rank, region_list[i], i + 1); });
      // vertices in index order, not the list's: the list goes loop by loop
      // and ring by ring, a cache miss at each vertex; the index order
      // follows the mesh's layout
      using Vertex_index = typename PM::Vertex_index;
      const std::size_t slots = pm.number_of_vertices() + pm.number_of_removed_vertices();
      auto parts = chunked_over_slots<Vertex_index, std::vector<int>>(
          pm, slots, [&](Vertex_index v, std::vector<int>& loops) {
        const std::size_t own = get(rank, v);
        if (own == 0) return;
        for (auto h : CGAL::halfedges_around_target(halfedge(v, pm), pm)) {
          if (is_border(h, pm)) continue;
          bool first = true;
          for (auto w : CGAL::vertices_around_face(h, pm)) {
            const std::size_t r = get(rank, w);
            if (r != 0 && r < own) first = false;
          }
          if (first) loops.push_back(get(region, v));
        }
      });
      for (const std::vector<int>& loops : parts)
        for (int l : loops) ++count[std::size_t(l)];
      return;
    }
  }
  std::vector<face_descriptor> counted;
  for (auto v : region_list)
    for (auto h : CGAL::halfedges_around_target(halfedge(v, pm), pm))
      if (!is_border(h, pm) && !get(fmark, face(h, pm))) {
        put(fmark, face(h, pm), char(1));
        counted.push_back(face(h, pm));
        ++count[std::size_t(get(region, v))];
      }
  for (face_descriptor f : counted) put(fmark, f, char(0));
}

/// the settings of `clean_boundaries()`, read and checked by it.
struct Boundary_settings
{
  double max_angle = defaults::boundary_dihedral_angle;  // degrees
  std::size_t rings = defaults::confidence_rings;
  std::size_t max_rounds = defaults::max_boundary_rounds;
  std::size_t component_faces = defaults::boundary_component_faces;
  std::size_t smoothing_iterations = defaults::boundary_smoothing_iterations;
  double smoothing_step = defaults::boundary_smoothing_step;
  double jagged_loop_turning = defaults::jagged_loop_turning;
  double erosion_share = defaults::boundary_erosion_share;
};

// Reads the settings of `clean_boundaries()` from `np` (the public call's or
// the pipeline's, which forwards its own); false when one is out of range.
template <typename NamedParameters>
bool read_boundary_settings(const NamedParameters& np, Boundary_settings& s)
{
  s.max_angle = get_or(np, internal_np::boundary_dihedral_angle, s.max_angle);
  s.rings = get_or(np, internal_np::confidence_rings, s.rings);
  s.max_rounds = get_or(np, internal_np::max_boundary_rounds, s.max_rounds);
  s.component_faces = get_or(np, internal_np::boundary_component_faces, s.component_faces);
  s.smoothing_iterations =
      get_or(np, internal_np::boundary_smoothing_iterations, s.smoothing_iterations);
  s.smoothing_step = get_or(np, internal_np::boundary_smoothing_step, s.smoothing_step);
  s.jagged_loop_turning = get_or(np, internal_np::jagged_loop_turning, s.jagged_loop_turning);
  s.erosion_share = get_or(np, internal_np::boundary_erosion_share, s.erosion_share);
  return s.max_angle >= 0. && s.max_angle <= 180. && s.smoothing_step >= 0. &&
         s.smoothing_step <= 1. && s.erosion_share >= 0. && s.erosion_share <= 1. &&
         s.jagged_loop_turning >= 0.;
}

/// the worker of `clean_boundaries()`: every edit goes through `ops`.
template <typename PM, typename VPM, typename Visitor>
Boundary_cleaning_result clean_boundaries_with(Local_operations<PM, VPM>& ops,
                                               const Boundary_settings& s, Visitor& vis)
{
  using GT = boost::graph_traits<PM>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  PM& pm = ops.mesh();
  const VPM& vpm = ops.vertex_point_map();
  Boundary_cleaning_result r;

  // Boundary loops: each boundary vertex gets its loop's index (a manifold
  // vertex lies on one loop at most). Only the vertices of jagged loops and
  // of local teeth (an ear, a folded border face, on a loop straight
  // elsewhere) may be eroded; a vertex the erosion uncovers inherits that
  // right from the vertex whose faces went.
  // new dynamic maps hold value-initialised entries (false) on every mesh type
  auto seen = get(CGAL::dynamic_vertex_property_t<bool>(), pm);
  auto loop_of = get(CGAL::dynamic_vertex_property_t<int>(), pm);
  auto erodible = get(CGAL::dynamic_vertex_property_t<bool>(), pm);
  for (vertex_descriptor v : vertices(pm)) put(loop_of, v, -1);
  // the border halfedges, read by three passes below before the first edit
  std::vector<typename GT::halfedge_descriptor> border;
  border_halfedges(pm, border);
  std::vector<vertex_descriptor> boundary;
  collect_boundary_vertices(pm, border, seen, boundary);
  r.boundary_vertices = boundary.size();
  if (boundary.empty()) return r;
  for (vertex_descriptor v : boundary)
    if (!is_finite_point(vpm, v)) {
      r.status = Status::non_finite_input;
      return r;
    }
  std::vector<char> jagged;
  {
    std::vector<std::pair<vertex_descriptor, double>> turns;
    for (auto h : border) {
      if (get(loop_of, target(h, pm)) >= 0) continue;
      const int l = int(jagged.size());
      loop_turns(h, pm, vpm, turns);
      for (const auto& t : turns) put(loop_of, t.first, l);
      const bool whole = loop_jaggedness(turns) > s.jagged_loop_turning * two_pi;
      jagged.push_back(whole);
      if (whole)
        for (const auto& t : turns) put(erodible, t.first, true);
      else
        mark_local_teeth(turns, std::size_t(2), s.jagged_loop_turning * two_pi / 2.,
                             [&](vertex_descriptor v) { put(erodible, v, true); });
    }
  }
  r.loops = jagged.size();
  for (char j : jagged) r.jagged_loops += std::size_t(j);
  for (vertex_descriptor v : boundary) r.tooth_vertices += std::size_t(get(erodible, v) && !jagged[std::size_t(get(loop_of, v))]);

  // The confidence region (BFS to depth `rings`), each vertex labelled with
  // the loop that reached it first, and each loop's region faces: a loop
  // loses at most `share` of them, so no component ever loses more than that
  // share of its faces to the erosion.
  auto region = get(CGAL::dynamic_vertex_property_t<int>(), pm);
  for (vertex_descriptor v : vertices(pm)) put(region, v, -1);
  std::vector<vertex_descriptor> region_list;
  {
    std::vector<vertex_descriptor> layer = boundary, next_layer;
    for (vertex_descriptor v : layer) put(region, v, get(loop_of, v));
    region_list = layer;
    for (std::size_t d = 0; d < s.rings && !layer.empty(); ++d) {
      next_layer.clear();
      for (vertex_descriptor v : layer)
        for (vertex_descriptor w : CGAL::vertices_around_target(halfedge(v, pm), pm))
          if (get(region, w) < 0) {
            put(region, w, get(region, v));
            next_layer.push_back(w);
          }
      region_list.insert(region_list.end(), next_layer.begin(), next_layer.end());
      layer.swap(next_layer);
    }
  }
  r.region_vertices = region_list.size();
  // Geometry is read on the region and its 1-ring only: check it is finite
  // there before the first angle is computed.
  for (vertex_descriptor v : region_list)
    if (!is_finite_point(vpm, v)) {
      r.status = Status::non_finite_input;
      return r;
    }
  auto fmark = get(CGAL::dynamic_face_property_t<char>(), pm);  // all 0
  std::vector<std::size_t> budget(jagged.size(), 0), spent(jagged.size(), 0);
  count_region_faces(pm, region_list, region, fmark, budget);
  for (std::size_t& b : budget) b = static_cast<std::size_t>(s.erosion_share * double(b));
  // Components too small to survive an erosion whole are never touched by
  // the removal of small components below: it only removes pieces the
  // erosion split off larger components.
  auto protect = get(CGAL::dynamic_face_property_t<bool>(), pm);  // all false
  if (s.component_faces > 1) {
    std::vector<face_descriptor> seeds, small;
    std::vector<std::size_t> offsets;
    for (auto h : border) seeds.push_back(face(opposite(h, pm), pm));
    find_small_components(pm, seeds, 4 * s.component_faces, small, offsets);
    for (face_descriptor f : small) put(protect, f, true);
  }

  // Iterative removal of bad boundary vertices of jagged loops inside the region.
  std::vector<vertex_descriptor> candidates = boundary, bad, survivors;
  std::vector<face_descriptor> doomed;
  std::vector<char> at_budget(jagged.size(), 0);
  while (!candidates.empty()) {
    if (vis.stop_requested()) {
      r.status = Status::cancelled;
      return r;
    }
    bad.clear();
    for (vertex_descriptor v : candidates) {
      if (get(seen, v)) continue;  // listed twice
      put(seen, v, true);
      const int l = get(loop_of, v);
      if (get(region, v) < 0 || l < 0) continue;
      // A valence-2 vertex is also the corner of a clean sheet: it goes only
      // on a jagged loop or a tooth. A fold or a pinch is a defect anywhere.
      const Bad_boundary why = bad_boundary_vertex(v, pm, vpm, s.max_angle);
      if (why == Bad_boundary::folded || why == Bad_boundary::pinched ||
          (why == Bad_boundary::valence_two && get(erodible, v)))
        bad.push_back(v);
    }
    for (vertex_descriptor v : candidates) put(seen, v, false);
    if (bad.empty()) break;
    if (r.rounds == s.max_rounds) {
      r.bad_vertices_left = bad.size();
      r.status = Status::partial;
      break;
    }
    // Each bad vertex's faces are charged to its loop; a vertex whose faces
    // would overrun the loop's budget stays.
    doomed.clear();
    std::size_t accepted = 0;
    for (vertex_descriptor v : bad) {
      const std::size_t l = std::size_t(get(loop_of, v));
      std::size_t n = 0;
      for (auto h : CGAL::halfedges_around_target(halfedge(v, pm), pm))
        if (!is_border(h, pm) && !get(fmark, face(h, pm))) ++n;
      if (spent[l] + n > budget[l]) {
        at_budget[l] = 1;
        continue;
      }
      spent[l] += n;
      ++accepted;
      for (auto h : CGAL::halfedges_around_target(halfedge(v, pm), pm)) {
        if (is_border(h, pm)) continue;
        if (!get(fmark, face(h, pm))) {
          put(fmark, face(h, pm), char(1));
          doomed.push_back(face(h, pm));
        }
        // the vertices this uncovers join the loop, and may be eroded in turn
        if (get(loop_of, source(h, pm)) < 0) put(loop_of, source(h, pm), int(l));
        put(erodible, source(h, pm), true);
      }
    }
    for (face_descriptor f : doomed) put(fmark, f, char(0));
    if (accepted == 0) break;
    ++r.rounds;
    survivors.clear();
    const std::size_t pinch_before = ops.counts().pinch_faces_removed;
    r.faces_removed += ops.remove_faces_without_pinches(doomed, &survivors);
    r.pinch_faces_removed += ops.counts().pinch_faces_removed - pinch_before;
    r.bad_vertices_removed += accepted;
    candidates.swap(survivors);
    vis.progress(double(r.rounds) / double(s.max_rounds + 1));
  }
  for (char b : at_budget) r.loops_at_budget += std::size_t(b);

  // Small pieces the erosion split off, next to the boundaries (every
  // component with a boundary has a boundary face, so seeding from those
  // finds them all); protected components and the largest one stay.
  if (s.component_faces > 1 && r.faces_removed > 0) {
    std::vector<face_descriptor> seeds;
    border_halfedges(pm, border);  // after the erosion
    for (auto h : border)
      if (!get(protect, face(opposite(h, pm), pm))) seeds.push_back(face(opposite(h, pm), pm));
    Small_components_result c =
        remove_small_components_seeded(ops, seeds, s.component_faces, 1., &protect);
    r.components_removed = c.components_removed;
    r.component_faces_removed = c.faces_removed;
  }

  // Only jagged loops and teeth are smoothed: clean borders keep their shape.
  r.vertices_smoothed = smooth_boundary_ring(
      ops, s.smoothing_iterations, s.smoothing_step,
      [&](vertex_descriptor v) { return get(erodible, v); });
  vis.progress(1.);
  return r;
}

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_BOUNDARIES_H
