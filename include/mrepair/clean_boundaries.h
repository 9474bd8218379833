// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_CLEAN_BOUNDARIES_H
#define MREPAIR_CLEAN_BOUNDARIES_H

#include <mrepair/internal/clean_scan_mesh/mesh_ops.h>
#include <mrepair/internal/clean_scan_mesh/safety.h>
#include <mrepair/internal/coordinate_range.h>
#include <mrepair/parameters.h>
#include <mrepair/remove_small_components.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Named_function_parameters.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

/// \file clean_boundaries.h
/// RameshCleaner 3.3: removal of bad boundary vertices inside a confidence
/// region around the boundaries, removal of the small components this leaves,
/// and restricted Laplacian smoothing of the boundary 1-ring.

MREPAIR_ADD_NAMED_PARAMETER(boundary_dihedral_angle)       // degrees (120)
MREPAIR_ADD_NAMED_PARAMETER(confidence_rings)              // n of the n-ring region (4)
MREPAIR_ADD_NAMED_PARAMETER(max_boundary_rounds)           // removal rounds (30)
MREPAIR_ADD_NAMED_PARAMETER(boundary_component_faces)      // components removed in the region (40)
MREPAIR_ADD_NAMED_PARAMETER(boundary_smoothing_iterations) // (10)
MREPAIR_ADD_NAMED_PARAMETER(boundary_smoothing_step)       // (0.02)
MREPAIR_ADD_NAMED_PARAMETER(jagged_loop_turning)           // loops whose jaggedness exceeds this x 2 pi are eroded (1)
MREPAIR_ADD_NAMED_PARAMETER(boundary_erosion_share)        // share of a loop's region faces removable (0.5)

namespace mrepair {

/// \ingroup mrepair_clean
/// what `clean_boundaries()` did.
struct Boundary_cleaning_result
{
  Status status = Status::ok;
  std::size_t boundary_vertices = 0;     ///< boundary vertices found at the start
  std::size_t region_vertices = 0;       ///< vertices of the confidence region
  std::size_t rounds = 0;                ///< removal rounds run
  std::size_t bad_vertices_removed = 0;  ///< bad boundary vertices whose faces were removed
  std::size_t bad_vertices_left = 0;     ///< bad boundary vertices left when the round cap hit
  std::size_t faces_removed = 0;         ///< faces removed with bad vertices (pinch fixes included)
  std::size_t pinch_faces_removed = 0;   ///< of which: smaller fans removed at would-be pinched vertices
  std::size_t components_removed = 0;    ///< small components removed in the region
  std::size_t component_faces_removed = 0;
  std::size_t vertices_smoothed = 0;
  std::size_t loops = 0;                 ///< boundary loops found at the start
  std::size_t jagged_loops = 0;          ///< of which jagged: eroded along their length
  std::size_t tooth_vertices = 0;        ///< vertices of local teeth on the other loops: eroded there
  std::size_t loops_at_budget = 0;       ///< loops whose erosion stopped at `boundary_erosion_share`

  void to_report(Report& r) const
  {
    r.add("status", status);
    r.add("boundary_vertices", boundary_vertices);
    r.add("region_vertices", region_vertices);
    r.add("rounds", rounds);
    r.add("bad_vertices_removed", bad_vertices_removed);
    r.add("bad_vertices_left", bad_vertices_left);
    r.add("faces_removed", faces_removed);
    r.add("pinch_faces_removed", pinch_faces_removed);
    r.add("components_removed", components_removed);
    r.add("component_faces_removed", component_faces_removed);
    r.add("vertices_smoothed", vertices_smoothed);
    r.add("loops", loops);
    r.add("jagged_loops", jagged_loops);
    r.add("tooth_vertices", tooth_vertices);
    r.add("loops_at_budget", loops_at_budget);
  }
};

namespace internal {
namespace clean_pipeline {

// Why a boundary vertex is bad (RameshCleaner 3.3): a) its valence is 2,
// b) an incident edge has a dihedral angle above `max_angle` (a border face
// folded back), c) it has more than two incident boundary edges.
enum class Bad_boundary { no, valence_two, folded, pinched };

template <typename PM, typename VPM>
Bad_boundary bad_boundary_vertex(typename boost::graph_traits<PM>::vertex_descriptor v,
                                 const PM& pm, const VPM& vpm, double max_angle)
{
  std::size_t valence = 0, border_edges = 0;
  bool sharp = false;
  for (auto h : CGAL::halfedges_around_target(halfedge(v, pm), pm)) {
    ++valence;
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

// Collects each boundary vertex once (order of the halfedge scan).
template <typename PM, typename VMark>
void collect_boundary_vertices(const PM& pm, VMark& seen,
                               std::vector<typename boost::graph_traits<PM>::vertex_descriptor>& out)
{
  out.clear();
  for (auto h : halfedges(pm))
    if (is_border(h, pm)) {
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
template <typename PM, typename VPM, typename Smoothable, typename Observer = No_edit_observer>
std::size_t smooth_boundary_ring(PM& pm, const VPM& vpm, std::size_t iterations, double step,
                                 const Smoothable& smoothable, Observer* observer = nullptr)
{
  using vertex_descriptor = typename boost::graph_traits<PM>::vertex_descriptor;
  if (iterations == 0 || step == 0.) return 0;
  auto idx = get(CGAL::dynamic_vertex_property_t<int>(), pm);
  auto seen = get(CGAL::dynamic_vertex_property_t<bool>(), pm);
  for (vertex_descriptor v : vertices(pm)) {
    put(idx, v, -1);
    put(seen, v, false);
  }
  std::vector<vertex_descriptor> set;
  collect_boundary_vertices(pm, seen, set);
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
  if (observer) observer->before(set);
  for (std::size_t i = 0; i < set.size(); ++i) set_point(vpm, set[i], pos[i]);
  if (observer) observer->after(set);
  return set.size();
}

}  // namespace clean_pipeline
}  // namespace internal

/// \ingroup mrepair_clean
/// cleans and smooths the boundaries of `pmesh` (RameshCleaner 3.3).
///
/// \code
/// R <- n-ring of the boundary vertices (the confidence region)
/// C <- boundary vertices
/// E <- vertices of jagged loops and of local teeth (the safety policy)
/// repeat at most max_boundary_rounds times:
///   B <- bad vertices of C inside R   (valence 2 and in E, or an incident
///                                      dihedral angle > boundary_dihedral_angle,
///                                      or more than 2 incident boundary edges)
///   if B is empty: stop
///   remove the faces of B, within each loop's budget; where a vertex would
///   be pinched (two fans), also remove its smaller fans;
///   C <- surviving vertices of removed faces (they join E)
/// remove the pieces with < boundary_component_faces faces the erosion split off
/// smooth the boundary 1-ring of E with the restricted uniform Laplacian
/// \endcode
/// The mesh stays a valid manifold mesh after every removal.
///
/// Safety policy (doc/guarantees.md): a loop is jagged when the turning it
/// undoes within a vertex or two exceeds `jagged_loop_turning` x 2 pi (a scan
/// border that zigzags); a tooth is a window of 5 border vertices whose
/// undone turning exceeds half that (a dangling ear). Straight and convex
/// borders, and the corners of sheets, are neither: they keep their shape.
/// Each loop loses at most `boundary_erosion_share` of the faces of its
/// confidence region, and components smaller than 4 x
/// `boundary_component_faces` are never removed here (the job of
/// `remove_small_components()`).
///
/// \tparam PolygonMesh model of `MutableFaceGraph` (triangles expected)
/// \param np optional:
///   - `vertex_point_map` (default: internal point map)
///   - `boundary_dihedral_angle` (double, degrees, default 120): dihedral angle
///     (between face normals) above which an incident edge makes a boundary vertex bad
///   - `confidence_rings` (std::size_t, default 4): n of the n-ring region
///   - `max_boundary_rounds` (std::size_t, default 30)
///   - `boundary_component_faces` (std::size_t, default 40): components with
///     fewer faces touching a boundary are removed afterwards (0: none)
///   - `boundary_smoothing_iterations` (std::size_t, default 10)
///   - `boundary_smoothing_step` (double, default 0.02)
///   - `jagged_loop_turning` (double, default 1): see the safety policy above
///   - `boundary_erosion_share` (double in [0, 1], default 0.5)
///   - `visitor`: phase "clean_boundaries"; `stop_requested()` polled between rounds
/// \return `Boundary_cleaning_result`: status `ok`, `partial` (round cap hit
///   with bad vertices left), `non_finite_input` (a region vertex has a
///   non-finite coordinate, or the coordinates span more than 1e100; mesh
///   untouched), `invalid_parameter`, `cancelled`
template <typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Boundary_cleaning_result clean_boundaries(
    PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values())
{
  using GT = boost::graph_traits<PolygonMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  namespace SC = internal::clean_pipeline;

  internal::Visitor_handle<NamedParameters> visitor(np);
  internal::Phase_scope<internal::Visitor_handle<NamedParameters>> phase(visitor,
                                                                         "clean_boundaries");
  auto vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, pmesh));
  const double max_angle = internal::get_or(np, internal_np::boundary_dihedral_angle, 120.);
  const std::size_t rings = internal::get_or(np, internal_np::confidence_rings, std::size_t(4));
  const std::size_t max_rounds =
      internal::get_or(np, internal_np::max_boundary_rounds, std::size_t(30));
  const std::size_t comp_faces =
      internal::get_or(np, internal_np::boundary_component_faces, std::size_t(40));
  const std::size_t smooth_it =
      internal::get_or(np, internal_np::boundary_smoothing_iterations, std::size_t(10));
  const double step = internal::get_or(np, internal_np::boundary_smoothing_step, 0.02);
  const double jag_turning = internal::get_or(np, internal_np::jagged_loop_turning, 1.);
  const double share = internal::get_or(np, internal_np::boundary_erosion_share, 0.5);

  auto observer = SC::edit_observer(np);
  Boundary_cleaning_result r;
  if (!(max_angle >= 0. && max_angle <= 180.) || !(step >= 0. && step <= 1.) ||
      !(share >= 0. && share <= 1.) || !(jag_turning >= 0.)) {
    r.status = Status::invalid_parameter;
    return r;
  }
  if (internal::coordinates_too_large(pmesh, vpm)) {
    r.status = Status::non_finite_input;
    return r;
  }

  // Boundary loops: each boundary vertex gets its loop's index (a manifold
  // vertex lies on one loop at most). Only the vertices of jagged loops and
  // of local teeth (an ear, a folded border face, on a loop straight
  // elsewhere) may be eroded; a vertex the erosion uncovers inherits that
  // right from the vertex whose faces went.
  auto seen = get(CGAL::dynamic_vertex_property_t<bool>(), pmesh);
  auto loop_of = get(CGAL::dynamic_vertex_property_t<int>(), pmesh);
  auto erodible = get(CGAL::dynamic_vertex_property_t<bool>(), pmesh);
  for (vertex_descriptor v : vertices(pmesh)) {
    put(seen, v, false);
    put(loop_of, v, -1);
    put(erodible, v, false);
  }
  std::vector<vertex_descriptor> boundary;
  SC::collect_boundary_vertices(pmesh, seen, boundary);
  r.boundary_vertices = boundary.size();
  if (boundary.empty()) return r;
  for (vertex_descriptor v : boundary)
    if (!SC::is_finite_point(vpm, v)) {
      r.status = Status::non_finite_input;
      return r;
    }
  std::vector<char> jagged;
  {
    constexpr double two_pi = 2. * 3.14159265358979323846;
    std::vector<std::pair<vertex_descriptor, double>> turns;
    for (auto h : halfedges(pmesh)) {
      if (!is_border(h, pmesh) || get(loop_of, target(h, pmesh)) >= 0) continue;
      const int l = int(jagged.size());
      SC::loop_turns(h, pmesh, vpm, turns);
      for (const auto& t : turns) put(loop_of, t.first, l);
      const bool whole = SC::loop_jaggedness(turns) > jag_turning * two_pi;
      jagged.push_back(whole);
      if (whole)
        for (const auto& t : turns) put(erodible, t.first, true);
      else
        SC::mark_local_teeth(turns, std::size_t(2), jag_turning * two_pi / 2.,
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
  auto region = get(CGAL::dynamic_vertex_property_t<int>(), pmesh);
  for (vertex_descriptor v : vertices(pmesh)) put(region, v, -1);
  std::vector<vertex_descriptor> region_list;
  {
    std::vector<vertex_descriptor> layer = boundary, next_layer;
    for (vertex_descriptor v : layer) put(region, v, get(loop_of, v));
    region_list = layer;
    for (std::size_t d = 0; d < rings && !layer.empty(); ++d) {
      next_layer.clear();
      for (vertex_descriptor v : layer)
        for (vertex_descriptor w : CGAL::vertices_around_target(halfedge(v, pmesh), pmesh))
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
    if (!SC::is_finite_point(vpm, v)) {
      r.status = Status::non_finite_input;
      return r;
    }
  auto fmark = get(CGAL::dynamic_face_property_t<char>(), pmesh);
  for (face_descriptor f : faces(pmesh)) put(fmark, f, char(0));
  std::vector<std::size_t> budget(jagged.size(), 0), spent(jagged.size(), 0);
  {
    std::vector<face_descriptor> counted;
    for (vertex_descriptor v : region_list)
      for (auto h : CGAL::halfedges_around_target(halfedge(v, pmesh), pmesh))
        if (!is_border(h, pmesh) && !get(fmark, face(h, pmesh))) {
          put(fmark, face(h, pmesh), char(1));
          counted.push_back(face(h, pmesh));
          ++budget[std::size_t(get(region, v))];
        }
    for (face_descriptor f : counted) put(fmark, f, char(0));
    for (std::size_t& b : budget) b = static_cast<std::size_t>(share * double(b));
  }
  // Components too small to survive an erosion whole are never touched by
  // the removal of small components below: it only removes pieces the
  // erosion split off larger components.
  auto protect = get(CGAL::dynamic_face_property_t<bool>(), pmesh);
  for (face_descriptor f : faces(pmesh)) put(protect, f, false);
  if (comp_faces > 1) {
    std::vector<face_descriptor> seeds, small;
    std::vector<std::size_t> offsets;
    for (auto h : halfedges(pmesh))
      if (is_border(h, pmesh)) seeds.push_back(face(opposite(h, pmesh), pmesh));
    SC::find_small_components(pmesh, seeds, 4 * comp_faces, small, offsets);
    for (face_descriptor f : small) put(protect, f, true);
  }

  // Iterative removal of bad boundary vertices of jagged loops inside the region.
  std::vector<vertex_descriptor> candidates = boundary, bad, survivors;
  std::vector<face_descriptor> doomed;
  std::vector<char> at_budget(jagged.size(), 0);
  while (!candidates.empty()) {
    if (visitor.stop_requested()) {
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
      const SC::Bad_boundary why = SC::bad_boundary_vertex(v, pmesh, vpm, max_angle);
      if (why == SC::Bad_boundary::folded || why == SC::Bad_boundary::pinched ||
          (why == SC::Bad_boundary::valence_two && get(erodible, v)))
        bad.push_back(v);
    }
    for (vertex_descriptor v : candidates) put(seen, v, false);
    if (bad.empty()) break;
    if (r.rounds == max_rounds) {
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
      for (auto h : CGAL::halfedges_around_target(halfedge(v, pmesh), pmesh))
        if (!is_border(h, pmesh) && !get(fmark, face(h, pmesh))) ++n;
      if (spent[l] + n > budget[l]) {
        at_budget[l] = 1;
        continue;
      }
      spent[l] += n;
      ++accepted;
      for (auto h : CGAL::halfedges_around_target(halfedge(v, pmesh), pmesh)) {
        if (is_border(h, pmesh)) continue;
        if (!get(fmark, face(h, pmesh))) {
          put(fmark, face(h, pmesh), char(1));
          doomed.push_back(face(h, pmesh));
        }
        // the vertices this uncovers join the loop, and may be eroded in turn
        if (get(loop_of, source(h, pmesh)) < 0) put(loop_of, source(h, pmesh), int(l));
        put(erodible, source(h, pmesh), true);
      }
    }
    for (face_descriptor f : doomed) put(fmark, f, char(0));
    if (accepted == 0) break;
    ++r.rounds;
    survivors.clear();
    std::size_t extra = 0;
    r.faces_removed +=
        SC::remove_faces_without_pinches(pmesh, doomed, fmark, extra, &survivors, observer);
    r.pinch_faces_removed += extra;
    r.bad_vertices_removed += accepted;
    candidates.swap(survivors);
    visitor.progress(double(r.rounds) / double(max_rounds + 1));
  }
  for (char b : at_budget) r.loops_at_budget += std::size_t(b);

  // Small pieces the erosion split off, next to the boundaries (every
  // component with a boundary has a boundary face, so seeding from those
  // finds them all); protected components and the largest one stay.
  if (comp_faces > 1 && r.faces_removed > 0) {
    std::vector<face_descriptor> seeds;
    for (auto h : halfedges(pmesh))
      if (is_border(h, pmesh) && !get(protect, face(opposite(h, pmesh), pmesh)))
        seeds.push_back(face(opposite(h, pmesh), pmesh));
    Small_components_result c =
        SC::remove_small_components_seeded(pmesh, vpm, seeds, comp_faces, 1., observer, &protect);
    r.components_removed = c.components_removed;
    r.component_faces_removed = c.faces_removed;
  }

  // Only jagged loops and teeth are smoothed: clean borders keep their shape.
  r.vertices_smoothed = SC::smooth_boundary_ring(
      pmesh, vpm, smooth_it, step,
      [&](vertex_descriptor v) { return get(erodible, v); },
      observer);
  visitor.progress(1.);
  return r;
}

}  // namespace mrepair

#endif  // MREPAIR_CLEAN_BOUNDARIES_H
