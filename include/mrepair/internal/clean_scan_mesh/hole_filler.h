// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Worker of fill_small_holes() (RameshCleaner 3.4, 3.5): Liepa's patch,
// refined and faired, inserted through the local operations; aborted fills
// enlarged by their 1-ring.
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_HOLE_FILLER_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_HOLE_FILLER_H

#include <mrepair/cleaning_results.h>
#include <mrepair/definitions.h>
#include <mrepair/internal/adaptive_remesh/driver.h>
#include <mrepair/internal/clean_scan_mesh/common.h>
#include <mrepair/internal/clean_scan_mesh/mesh_ops.h>
#include <mrepair/internal/clean_scan_mesh/safety.h>
#include <mrepair/internal/coordinate_range.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/internal/patch_guard.h>
#include <mrepair/parameters.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {
namespace clean_pipeline {

/// The settings of the hole filling.
struct Hole_filling_settings
{
  std::size_t max_vertices = defaults::max_hole_vertices;  // loops with fewer vertices are filled
  double density = defaults::hole_density_factor;           // patch edge length / border mean
  bool refine = true;                                       // remesh the patch (3.5)
  bool fair = false;                                        // ... and fair it
  std::size_t enlargements = defaults::max_hole_enlargements;  // of an aborted fill
  std::size_t delaunay_above = defaults::hole_delaunay_above;  // 3D Delaunay search space above
  double area_share = defaults::max_hole_area_share;  // a larger cap makes the loop a sheet's border
};

// Reads the settings of `fill_small_holes()` from `np` (the public call's or
// the pipeline's, which forwards its own). `cad`: the defaults of the cad
// profile: loops up to 500 vertices (long loops around flat cuts), Liepa's
// patch alone (no refinement to a density the part does not have, so no
// fairing) and no enlargement (it removes the user's faces). False when a
// setting is out of range.
template <typename NamedParameters>
bool read_hole_filling_settings(const NamedParameters& np, bool cad, Hole_filling_settings& s)
{
  s.max_vertices = get_or(np, internal_np::max_hole_vertices,
                          cad ? defaults::max_cad_hole_vertices : defaults::max_hole_vertices);
  s.density = get_or(np, internal_np::hole_density_factor, s.density);
  s.refine = get_or(np, internal_np::refine_hole_patches, !cad);
  s.fair = get_or(np, internal_np::fair_hole_patches, false) && !cad;
  s.enlargements = get_or(np, internal_np::max_hole_enlargements,
                          cad ? std::size_t(0) : defaults::max_hole_enlargements);
  s.delaunay_above = get_or(np, internal_np::hole_delaunay_above, s.delaunay_above);
  s.area_share = get_or(np, internal_np::max_hole_area_share, s.area_share);
  return s.max_vertices > 0 && s.density > 0. && std::isfinite(s.density) && s.area_share >= 0.;
}

/// Fills holes (3.4) and handles aborted fills (3.5) for one mesh.
template <typename PM, typename VPM>
class Small_hole_filler
{
  using GT = boost::graph_traits<PM>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;

  using Operations = Local_operations<PM, VPM>;
  using Patch_ops = Patch_operations<PM, VPM>;  // what a patch edit is given

  Operations& ops_;
  PM& pm_;
  VPM vpm_;
  std::size_t max_vertices_;
  double density_;
  bool refine_, fair_;
  std::size_t enlargements_;
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
  /// remeshing iterations of a patch
  static constexpr int refine_iterations = 3;

  // A patch remeshed off the mesh (remesh_patch): `triangles` index
  // `corner_of` (a loop vertex, or null for a new vertex at `positions`).
  struct Refined_patch
  {
    bool ok = false;
    std::vector<vertex_descriptor> corner_of;
    std::vector<Vec3> positions;
    std::vector<std::array<std::size_t, 3>> triangles;
  };

  Hole_filling_result result;

  Small_hole_filler(Operations& ops, const Hole_filling_settings& s)
    : ops_(ops), pm_(ops.mesh()), vpm_(ops.vertex_point_map()), max_vertices_(s.max_vertices),
      density_(s.density), refine_(s.refine), fair_(s.fair), enlargements_(s.enlargements),
      delaunay_above_(s.delaunay_above), area_share_(s.area_share), visited_(get(CGAL::dynamic_face_property_t<char>(), pm_)),
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

  // Mean edge length of the loop of `h`, or false when a loop vertex is not finite.
  bool loop_mean_length(halfedge_descriptor h, std::size_t n, double& mean) const
  {
    double lsum = 0.;
    for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_)) {
      if (!is_finite_point(vpm_, target(g, pm_))) return false;
      lsum += norm(sub(point(vpm_, target(g, pm_)), point(vpm_, source(g, pm_))));
    }
    mean = lsum / double(n);
    return true;
  }

  // Liepa's patch of the loop of `h` into `patch`: CGAL's implementation of
  // Liepa's weight; existing edges between loop vertices and degenerate
  // triangles are excluded, so an empty output is an aborted fill (3.5). The
  // DT3 search space only pays on longer loops.
  bool triangulate(halfedge_descriptor h, std::size_t n, std::vector<face_descriptor>& patch)
  {
    patch.reserve(2 * n);
    return triangulate_hole_checked(pm_, h, vpm_, n > delaunay_above_, patch);
  }

  // After the refinement: fairing, then the crossing test. A refined or
  // faired patch that crosses the surface gives way to Liepa's patch
  // (`coarse`), kept when it crosses nothing; false when the loop stays open.
  bool finish_fill(Patch_ops& patch_ops, std::vector<face_descriptor>& patch,
                   const std::vector<std::array<vertex_descriptor, 3>>& coarse,
                   std::vector<vertex_descriptor>& added, std::size_t index)
  {
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
      // the coarse patch back and keep it when it crosses nothing.
      if (!refined || !patch_ops.insert_triangles(coarse, patch) ||
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
  }

  // A loop filled in a batch (fill_batch).
  struct Batch_fill
  {
    Batch_fill(std::size_t loop_index, std::size_t loop_size, halfedge_descriptor border)
      : index(loop_index), n(loop_size), h(border)
    {}
    std::size_t index = 0, n = 0;
    halfedge_descriptor h;
    double length = 0.;  // target edge length of the refinement
    bool inserted = false;
    std::vector<vertex_descriptor> loop;
    std::vector<face_descriptor> patch;
    std::vector<std::array<vertex_descriptor, 3>> coarse;
    Refined_patch refined;
  };

  // Fills loops that passed the checks, in three passes with the result of
  // filling them one by one: Liepa's patches, in list order; their
  // remeshing, in parallel (each on its own copy, reading the mesh only);
  // then, in list order, each refined patch put in place of Liepa's, faired
  // and tested against the surface (finish_fill). The remeshing is most of a
  // fill's time; the other passes edit the mesh and stay sequential.
  void fill_batch(std::vector<Batch_fill>& batch, std::vector<halfedge_descriptor>& failed)
  {
    for (Batch_fill& b : batch) {
      double mean = 0.;
      if (!loop_mean_length(b.h, b.n, mean)) continue;
      b.length = density_ * mean;
      b.inserted = ops_.insert_patch(b.h, [&](Patch_ops& patch_ops, std::vector<vertex_descriptor>& loop,
                                              std::vector<vertex_descriptor>&) {
        if (!triangulate(b.h, b.n, b.patch)) return false;
        b.loop = loop;
        b.coarse = patch_ops.triangles_of(b.patch);
        return true;
      });
    }
    // reads only: the mesh's connectivity and points, each job its own copy
    parallel_for_index(batch.size(), 1, [&](std::size_t i) {
      Batch_fill& b = batch[i];
      if (refine_ && b.inserted && b.n > 3) b.refined = remesh_patch(b.patch, b.length);
    });
    for (Batch_fill& b : batch) {
      last_fill_intersected_ = false;
      bool filled = false;
      if (b.inserted)
        filled = ops_.edit_patch(b.loop, [&](Patch_ops& patch_ops, std::vector<vertex_descriptor>&,
                                             std::vector<vertex_descriptor>& added) {
          put_refined(patch_ops, b.patch, b.refined, added);
          return finish_fill(patch_ops, b.patch, b.coarse, added, b.index);
        });
      if (filled) ++result.holes_filled;
      else fill_failed(b.h, failed);
      b.refined = Refined_patch();  // frees the copy
    }
  }

  // Refines the patch to edge length `L` with the library's own remesher
  // (RameshCleaner 3.4: Liepa's patch, then isotropic remeshing of the
  // patch): the patch is copied into a small Surface_mesh whose border is the
  // loop, remeshed there with the border protected (the loop's edges and
  // vertices stay) and projected onto Liepa's patch; put_refined puts it in
  // place of the coarse patch through the local operations. The remesher
  // sees the patch only, so a fill costs O(patch) however large the mesh.
  // Reads the mesh only: patches are remeshed in parallel (fill_batch).
  Refined_patch remesh_patch(const std::vector<face_descriptor>& patch, double L) const
  {
    using Small = CGAL::Surface_mesh<CGAL::Epick::Point_3>;
    using Small_vertex = typename Small::Vertex_index;
    using Small_face = typename Small::Face_index;
    constexpr std::size_t none = std::size_t(-1);
    Refined_patch out;
    if (!(L > 0.)) return out;
    Small s;
    auto corner_index = s.add_property_map<Small_vertex, std::size_t>("v:mrepair_corner", none).first;
    std::vector<vertex_descriptor> corners;  // loop vertices, by corner index
    std::map<vertex_descriptor, Small_vertex> local;
    for (face_descriptor f : patch) {
      std::array<Small_vertex, 3> t;
      int k = 0;
      for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_)) {
        auto it = local.find(v);
        if (it == local.end()) {
          const Vec3 p = point(vpm_, v);
          const Small_vertex sv = s.add_vertex(Small::Point(p[0], p[1], p[2]));
          corner_index[sv] = corners.size();
          corners.push_back(v);
          it = local.emplace(v, sv).first;
        }
        if (k < 3) t[k] = it->second;
        ++k;
      }
      // a loop through one vertex twice: no disc to remesh, Liepa's patch stays
      if (k != 3 || s.add_face(t[0], t[1], t[2]) == Small::null_face()) return out;
    }
    Remesh_options options;
    options.iterations = refine_iterations;
    options.protect = true;        // the loop is the patch's border: it stays
    options.feature_angle = -1.;   // a coarse patch's creases are no features
    using No_constraint = CGAL::Static_boolean_property_map<typename Small::Edge_index, false>;
    using No_fixed = CGAL::Static_boolean_property_map<Small_vertex, false>;
    Visitor_handle<CGAL::parameters::Default_named_parameters> quiet(CGAL::parameters::default_values());
    const Remeshing_result r = remesh_driver<false>(
        s, static_cast<const std::vector<Small_face>*>(nullptr), Remesh_mode::uniform, L, options,
        s.points(), No_constraint(), No_fixed(), quiet, start_remeshing_result(s, Remesh_mode::uniform));
    if (!succeeded(r.status)) return out;
    // A remeshed patch with a degenerate face is dropped and Liepa's patch
    // stays. One that crosses itself is caught by the patch guard after the
    // insertion, which puts Liepa's patch back.
    for (Small_face f : s.faces())
      if (CGAL::Polygon_mesh_processing::is_degenerate_triangle_face(f, s)) return out;
    // `s` was compacted: corner indices moved with their vertices
    out.corner_of.assign(s.number_of_vertices(), GT::null_vertex());
    out.positions.resize(s.number_of_vertices());
    for (Small_vertex v : s.vertices()) {
      const std::size_t c = corner_index[v];
      if (c != none) out.corner_of[std::size_t(v)] = corners[c];
      const Small::Point& p = s.point(v);
      out.positions[std::size_t(v)] = Vec3{{p.x(), p.y(), p.z()}};
    }
    out.triangles.reserve(s.number_of_faces());
    for (Small_face f : s.faces()) {
      std::array<std::size_t, 3> t;
      int k = 0;
      for (Small_vertex v : CGAL::vertices_around_face(s.halfedge(f), s)) t[k++] = std::size_t(v);
      out.triangles.push_back(t);
    }
    out.ok = true;
    return out;
  }

  // Puts a remeshed patch in place of Liepa's; when it cannot go back (a new
  // inner edge would join two loop vertices joined elsewhere), Liepa's stays.
  void put_refined(Patch_ops& patch_ops, std::vector<face_descriptor>& patch, const Refined_patch& r,
                   std::vector<vertex_descriptor>& added)
  {
    if (!r.ok) return;
    std::vector<vertex_descriptor> created;
    if (patch_ops.replace_patch(patch, r.corner_of, r.positions, r.triangles, created)) added = created;
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

  // Fills every small hole of the mesh, with the settings' enlargements.
  template <typename Visitor>
  Status run(Visitor& visitor)
  {
    std::vector<halfedge_descriptor> all, loops;
    border_halfedges(pm_, all);
    loops_of(all, loops);
    return run_on(std::move(loops), enlargements_, visitor);
  }

  // The same on the given loops only, one border halfedge each (the holes an
  // edit just opened: the rest of the mesh's borders are not looked at).
  template <typename Visitor>
  Status run_on(std::vector<halfedge_descriptor> loops, std::size_t max_enlargements, Visitor& visitor)
  {
    prepare_guard(loops);
    std::vector<halfedge_descriptor> failed, next;
    std::vector<Batch_fill> batch;
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
      batch.emplace_back(index, n, h);
    }
    visitor.progress(0.2);
    fill_batch(batch, failed);
    visitor.progress(0.8);
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
      batch.clear();
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
        batch.emplace_back(index, n, h);
      }
      fill_batch(batch, failed);
    }
    return result.open_holes.empty() ? Status::ok : Status::partial;
  }
};

// fill_small_holes() on the whole mesh, with the settings of `np` and the
// defaults of the cad profile when `cad` (read_hole_filling_settings): the
// public call (`cad` false) and the holes the solid repair leaves (repair.h).
// `counts`, when given, receives what its local operations did (the job's
// face accounting).
template <typename PolygonMesh, typename NamedParameters, typename Visitor>
Hole_filling_result fill_small_holes_with(PolygonMesh& pmesh, const NamedParameters& np, bool cad,
                                          Visitor& visitor, Local_operation_counts* counts = nullptr)
{
  Hole_filling_result r;
  Hole_filling_settings settings;
  if (!read_hole_filling_settings(np, cad, settings)) {
    r.status = Status::invalid_parameter;
    return r;
  }
  auto vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, pmesh));
  std::string unused;  // the result has no message
  r.status = check_step_input(pmesh, vpm, true, unused);
  if (r.status != Status::ok) return r;
  Local_operations<PolygonMesh, decltype(vpm)> ops(pmesh, vpm);
  Small_hole_filler<PolygonMesh, decltype(vpm)> filler(ops, settings);
  filler.result.status = filler.run(visitor);
  if (counts) *counts = ops.counts();
  return filler.result;
}

// The same with the profile's defaults and no visitor of the caller's.
template <typename PolygonMesh, typename NamedParameters>
Hole_filling_result fill_small_holes_of_profile(PolygonMesh& pmesh, const NamedParameters& np, bool cad,
                                                Local_operation_counts* counts = nullptr)
{
  Default_visitor quiet;
  return fill_small_holes_with(pmesh, np, cad, quiet, counts);
}

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_HOLE_FILLER_H
