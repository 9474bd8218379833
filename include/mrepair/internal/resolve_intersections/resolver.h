// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Worker of resolve_intersections(): the local repair of shells that cross
// themselves, then the union of closed shells that overlap (doc/solids.md).
#ifndef MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_RESOLVER_H
#define MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_RESOLVER_H

#include <mrepair/definitions.h>
#include <mrepair/internal/clean_scan_mesh/hole_filler.h>
#include <mrepair/internal/compare_to_reference/worker.h>
#include <mrepair/internal/local_operations.h>
#include <mrepair/internal/resolve_intersections/arrangement.h>
#include <mrepair/internal/resolve_intersections/crossings.h>
#include <mrepair/internal/resolve_intersections/shells.h>
#include <mrepair/internal/triangle_intersection.h>
#include <mrepair/internal/utility.h>
#include <mrepair/status.h>

#include <CGAL/Bbox_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/utility.h>

#include <boost/iterator/function_output_iterator.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {
namespace solid {

struct Resolver_settings
{
  bool merge_shells = true;          // union of overlapping closed shells
  bool solidify = true;              // closed shells that cross: one solid by winding numbers
  std::size_t arrangement_passes = 3;  // arrangements of the rounded result that still crosses
  std::size_t local_rounds = 3;      // rounds of the local repair (each a ring wider)
  bool refine_patches = true;        // the local repair's patches remeshed (not on CAD)
  std::size_t max_patch_vertices = 2000;  // longer loops of the local repair stay open
  std::size_t max_nesting_shells = 5000;  // above: no test for shells nested in others
  std::size_t max_cap_vertices = 500;    // longer border loops keep an open shell out of the solid
  // a border point of an open part outside the solids it crosses still
  // counts as stuck into them within this share of its loop's size (see
  // cap_parts_stuck_into_solids)
  double rim_outside_share = 0.1;
  // the same for an open part that crosses nothing and rests on a solid
  // (cap_parts_resting_on_solids): a dome whose rim follows a curved body
  // at up to a fifth of the rim's size (the doorman's buttons: 0.1-11%)
  double rim_resting_share = 0.2;
  std::size_t sheet_cap_rounds = 4;
};

// Counters of the worker; the public result copies them.
struct Resolver_counts
{
  std::size_t crossing_before = 0, touching_before = 0;
  std::size_t crossing_after = 0, touching_after = 0;
  std::size_t local_rounds = 0;
  std::size_t local_faces_removed = 0, local_faces_added = 0;
  std::size_t local_holes_left_open = 0;  // after the last round
  std::size_t local_rounds_taken_back = 0;
  std::size_t shells_merged = 0;       // shells that went into a union (the union's result counts once each)
  std::size_t solids_from_unions = 0;  // unions written back
  std::size_t nested_shells_merged = 0;  // outward shells inside another outward shell, absorbed
  std::size_t union_faces_removed = 0, union_faces_added = 0;
  std::size_t unions_failed = 0;
  std::size_t shells_solidified = 0;   // closed shells replaced by the winding-number solid
  std::size_t solid_faces_removed = 0, solid_faces_added = 0;
  std::size_t open_parts_capped = 0, cap_faces_added = 0;  // parts resting on a solid
  std::size_t sheets_cut = 0;          // open shells cut where they enter the solid
  std::size_t arrangement_faces = 0;   // of the last arrangement
  std::size_t arrangement_passes = 0;
  std::string solidify_note;           // why the solidification left the shells as they were
  std::vector<std::pair<std::string, std::size_t>> left_by_reason;  // crossing pairs left
  std::vector<std::string> unions;  // per union: the shells' faces (nested ones marked) -> the result's
};

template <typename PolygonMesh, typename VertexPointMap>
class Intersection_resolver
{
  using PM = PolygonMesh;
  using GT = boost::graph_traits<PM>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Pair = std::pair<face_descriptor, face_descriptor>;
  using Component_map = typename boost::property_map<PM, CGAL::dynamic_face_property_t<std::size_t>>::type;

  PM& pm_;
  VertexPointMap vpm_;
  Resolver_settings settings_;
  bool rounding_left_crossings_ = false;  // the solid was kept with crossings rounding made
  bool sheets_taken_ = false;             // the last solidification cut open sheets

public:
  Resolver_counts counts;

  Intersection_resolver(PM& pm, VertexPointMap vpm, const Resolver_settings& settings)
    : pm_(pm), vpm_(vpm), settings_(settings)
  {}

  // Runs both phases; `scan` holds the crossing pairs of the mesh as given.
  template <typename Visitor>
  Status run(Crossing_scan<PM> scan, Visitor& visitor)
  {
    counts.crossing_before = scan.crossing.size();
    counts.touching_before = scan.touching;
    // closed shells that cross (themselves or each other): one solid
    if (settings_.solidify && settings_.merge_shells && !scan.crossing.empty()) {
      if (visitor.stop_requested()) return Status::cancelled;
      // the mesh as given, while a solid that rounding left crossing (see
      // solidify_closed_shells) is weighed against the repair without it
      PM given;
      const Resolver_counts counts_given = counts;
      CGAL::copy_face_graph(pm_, given, CGAL::parameters::vertex_point_map(vpm_));
      // with the open sheets that cross the solid cut at it; without them
      // when that fails
      bool solid = solidify_closed_shells(scan, true);
      if (!solid && sheets_taken_) solid = solidify_closed_shells(scan, false);
      if (solid) {
        const Status with_solid = finish(scan_crossings(pm_, vpm_), visitor);
        // a solid without crossings of its own stays (what is left crosses
        // open shells, which the repair without it would cut into)
        if (!rounding_left_crossings_ || counts.crossing_after == 0 || with_solid == Status::cancelled)
          return with_solid;
        const Resolver_counts counts_solid = counts;
        PM solid_result;
        CGAL::copy_face_graph(pm_, solid_result, CGAL::parameters::vertex_point_map(vpm_));
        replace_mesh_with(given);
        counts = counts_given;
        const Status without = finish(scan_crossings(pm_, vpm_), visitor);
        if (counts.crossing_after < counts_solid.crossing_after) {
          counts.solidify_note = counts_solid.solidify_note + "; the repair without the solid left fewer";
          return without;
        }
        replace_mesh_with(solid_result);
        counts = counts_solid;
        return with_solid;
      }
    }
    return finish(std::move(scan), visitor);
  }

private:
  // the local repair, then the union; the counts of what is left
  template <typename Visitor>
  Status finish(Crossing_scan<PM> scan, Visitor& visitor)
  {
    // after the solid: the parts that rest on it (the solid's shells may
    // have been open before it)
    if (settings_.solidify && settings_.merge_shells) {
      if (visitor.stop_requested()) return Status::cancelled;
      cap_parts_resting_on_solids(scan);
    }
    // the local repair leaves `scan` current; a union needs a new one
    if (!scan.crossing.empty()) {
      if (visitor.stop_requested()) return Status::cancelled;
      repair_locally(scan, visitor);
    }
    // one shell and no crossing: nothing to unite (most scans stop here)
    if (settings_.merge_shells && scan.status == Status::ok && (scan.components > 1 || !scan.crossing.empty())) {
      if (visitor.stop_requested()) return Status::cancelled;
      if (merge_overlapping_shells(scan)) scan = scan_crossings(pm_, vpm_);
    }
    if (scan.status != Status::ok) return scan.status;
    counts.crossing_after = scan.crossing.size();
    counts.touching_after = scan.touching;
    explain_left(scan);
    return scan.crossing.empty() ? Status::ok : Status::partial;
  }

  // `pm_` becomes a copy of `other` (a user's property maps, the point map
  // among them, stay attached to a Surface_mesh)
  void replace_mesh_with(const PM& other)
  {
    if constexpr (Is_surface_mesh<PM>::value) pm_.clear_without_removing_property_maps();
    else CGAL::clear(pm_);
    CGAL::copy_face_graph(other, pm_, CGAL::parameters::default_values(), CGAL::parameters::vertex_point_map(vpm_));
  }

  // the shell of every face, and which shells cross themselves
  std::vector<Shell<PM>> shells_of(Component_map& component) const
  {
    return label_shells(pm_, vpm_, component);
  }

  // The caps that close open shell `shell` for the arrangement, as the hole
  // filler would close it were its holes not beside a crossing: each border
  // loop's Liepa triangulation (CGAL's triangulate_hole_polyline), oriented
  // as the faces around it. `no_cap` when a loop is longer than
  // max_cap_vertices or cannot be triangulated; `large_caps` when a cap
  // would be a sheet's border by the filler's rule (over
  // max_hole_area_share of the shell's area: a terrain, a bowl, an open
  // part), which is capped only where its border lies inside a solid.
  enum Capping { no_cap, small_caps, large_caps };
  Capping caps_closing(const Shell<PM>& shell, std::vector<std::array<vertex_descriptor, 3>>& cap) const
  {
    using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
    double shell_area = 0.;
    std::vector<halfedge_descriptor> borders;
    for (face_descriptor f : shell.faces) {
      const halfedge_descriptor h = halfedge(f, pm_);
      shell_area += 0.5 * norm(triangle_normal(point(vpm_, source(h, pm_)), point(vpm_, target(h, pm_)),
                                               point(vpm_, target(next(h, pm_), pm_))));
      for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_))
        if (is_border(opposite(g, pm_), pm_)) borders.push_back(opposite(g, pm_));
    }
    if (!(shell_area > 0.) || !std::isfinite(shell_area)) return no_cap;
    std::set<halfedge_descriptor> walked;
    bool large = false;
    for (halfedge_descriptor h : borders) {
      if (walked.count(h)) continue;
      // the loop in the direction of its border halfedges: a triangle that
      // follows it is oriented as the faces across the border
      std::vector<vertex_descriptor> loop;
      std::vector<Epick::Point_3> points;
      for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_)) {
        walked.insert(g);
        if (loop.size() == settings_.max_cap_vertices) return no_cap;
        loop.push_back(target(g, pm_));
        const Vec3 p = point(vpm_, target(g, pm_));
        points.emplace_back(p[0], p[1], p[2]);
      }
      std::vector<CGAL::Triple<int, int, int>> triangles;
      CGAL::Polygon_mesh_processing::triangulate_hole_polyline(points, std::back_inserter(triangles));
      if (loop.size() < 3 || triangles.size() + 2 != loop.size()) return no_cap;
      std::vector<std::array<std::size_t, 3>> local;
      double cap_area = 0.;
      for (const auto& t : triangles) {
        local.push_back({{std::size_t(t.first), std::size_t(t.second), std::size_t(t.third)}});
        cap_area += 0.5 * norm(triangle_normal(point(vpm_, loop[t.first]), point(vpm_, loop[t.second]),
                                               point(vpm_, loop[t.third])));
      }
      if (!(cap_area <= defaults::max_hole_area_share * shell_area)) large = true;
      // the cap runs along the border halfedges (loop[i] -> loop[i + 1]);
      // the faces across them run the other way
      std::set<std::pair<std::size_t, std::size_t>> directed;
      bool reversed = false;
      for (const auto& t : local)
        for (int k = 0; k < 3; ++k) directed.emplace(t[k], t[(k + 1) % 3]);
      for (std::size_t i = 0; i < loop.size(); ++i)
        if (directed.count({(i + 1) % loop.size(), i})) reversed = true;
      for (const auto& t : local)
        cap.push_back(reversed ? std::array<vertex_descriptor, 3>{{loop[t[0]], loop[t[2]], loop[t[1]]}}
                               : std::array<vertex_descriptor, 3>{{loop[t[0]], loop[t[1]], loop[t[2]]}});
    }
    if (cap.empty()) return no_cap;
    // the shell and its caps must make one polygon mesh: a cap edge that is
    // already an edge of the shell would have three faces meet there, and
    // the soup of all chosen shells would be refused as a whole
    std::map<vertex_descriptor, std::size_t> local;
    auto id = [&](vertex_descriptor v) { return local.emplace(v, local.size()).first->second; };
    std::vector<std::array<std::size_t, 3>> closed;
    for (face_descriptor f : shell.faces) {
      const halfedge_descriptor h = halfedge(f, pm_);
      closed.push_back({{id(source(h, pm_)), id(target(h, pm_)), id(target(next(h, pm_), pm_))}});
    }
    for (const auto& t : cap) closed.push_back({{id(t[0]), id(t[1]), id(t[2])}});
    if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(closed)) return no_cap;
    return large ? large_caps : small_caps;
  }

  // The open shells not considered yet (no crossing of their own:
  // `solid_shell` -1) that a cap of `caps` crosses: (capped shell, crossed
  // shell) pairs. Triangles that meet only in what they share (a corner at
  // the same point: a lid's rim on its pot's rim) do not count
  // (triangles_intersect, the inspection's test, with points as keys).
  std::vector<std::pair<std::size_t, std::size_t>> shells_crossing_caps(
      const std::vector<Shell<PM>>& shells, const std::vector<signed char>& solid_shell,
      const std::map<std::size_t, std::vector<std::array<vertex_descriptor, 3>>>& caps) const
  {
    using Corners = std::array<Epick_point, 3>;
    std::vector<std::pair<std::size_t, std::size_t>> found;
    auto corners = [&](vertex_descriptor a, vertex_descriptor b, vertex_descriptor c) {
      Corners t;
      const vertex_descriptor v[3] = {a, b, c};
      for (int k = 0; k < 3; ++k) {
        const Vec3 p = point(vpm_, v[k]);
        t[k] = Epick_point(p[0], p[1], p[2]);
      }
      return t;
    };
    auto box_of = [](const Corners& t) { return t[0].bbox() + t[1].bbox() + t[2].bbox(); };
    auto flat = [](const Corners& t) { return CGAL::collinear(t[0], t[1], t[2]); };  // no triangle to test
    for (const auto& cap : caps) {
      std::vector<Corners> triangles;
      CGAL::Bbox_3 box;
      for (const auto& t : cap.second) {
        triangles.push_back(corners(t[0], t[1], t[2]));
        box += box_of(triangles.back());
      }
      for (std::size_t d = 0; d < shells.size(); ++d) {
        if (solid_shell[d] >= 0 || shells[d].closed || !CGAL::do_overlap(box, shells[d].box)) continue;
        bool crosses = false;
        for (std::size_t i = 0; i < shells[d].faces.size() && !crosses; ++i) {
          const halfedge_descriptor h = halfedge(shells[d].faces[i], pm_);
          const Corners g = corners(source(h, pm_), target(h, pm_), target(next(h, pm_), pm_));
          const CGAL::Bbox_3 gb = box_of(g);
          if (!CGAL::do_overlap(gb, box) || flat(g)) continue;
          for (const Corners& t : triangles)
            if (!flat(t) && CGAL::do_overlap(gb, box_of(t)) && triangles_intersect(g.data(), g.data(), t.data(), t.data())) {
              crosses = true;
              break;
            }
        }
        if (crosses) found.emplace_back(cap.first, d);
      }
    }
    return found;
  }

  // The open shells of `sheet_caps` whose every border point lies inside
  // the closed shells that take part in a crossing (non-zero winding number
  // of those shells, exact ray casts: compare_to_reference's test) get their
  // caps (moved to `caps`) and count as solids. A border point outside them
  // by at most `outside_share` of its loop's bounding-box diagonal counts
  // as inside: a part modelled sitting on a curved body has its rim on the
  // smooth surface, a little off the body's facets (the doorman's buttons:
  // 0.8-5% of their loop outside, where the parts that merely cross another
  // open part lie 29-220% of theirs away). The test runs again with the
  // parts capped so far among the solids (a button on a capped part), for
  // at most sheet_cap_rounds rounds.
  void cap_parts_stuck_into_solids(const std::vector<Shell<PM>>& shells, std::vector<signed char>& solid_shell,
                                   std::map<std::size_t, std::vector<std::array<vertex_descriptor, 3>>>& sheet_caps,
                                   std::map<std::size_t, std::vector<std::array<vertex_descriptor, 3>>>& caps,
                                   double outside_share) const
  {
    for (std::size_t round = 0; round < settings_.sheet_cap_rounds && !sheet_caps.empty(); ++round)
      if (!cap_parts_stuck_into(shells, solid_shell, sheet_caps, caps, outside_share)) break;
  }

  // One round of cap_parts_stuck_into_solids(): the solids are the closed
  // shells and the capped ones; false when no part was capped.
  bool cap_parts_stuck_into(const std::vector<Shell<PM>>& shells, std::vector<signed char>& solid_shell,
                            std::map<std::size_t, std::vector<std::array<vertex_descriptor, 3>>>& sheet_caps,
                            std::map<std::size_t, std::vector<std::array<vertex_descriptor, 3>>>& caps,
                            double outside_share) const
  {
    using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Work_mesh = CGAL::Surface_mesh<Epick::Point_3>;
    using Work_vpm = typename boost::property_map<Work_mesh, CGAL::vertex_point_t>::const_type;
    using Tree = typename CGAL::Side_of_triangle_mesh<Work_mesh, Epick, Work_vpm>::AABB_tree;
    std::vector<Epick::Point_3> points;
    std::vector<std::array<std::size_t, 3>> triangles;
    std::map<vertex_descriptor, std::size_t> index;
    auto corner = [&](vertex_descriptor v) {
      auto it = index.find(v);
      if (it == index.end()) {
        const Vec3 p = point(vpm_, v);
        it = index.emplace(v, points.size()).first;
        points.emplace_back(p[0], p[1], p[2]);
      }
      return it->second;
    };
    for (std::size_t c = 0; c < shells.size(); ++c) {
      const auto capped = caps.find(c);
      if (solid_shell[c] != 1 || (!shells[c].closed && capped == caps.end())) continue;
      for (face_descriptor f : shells[c].faces) {
        std::array<std::size_t, 3> t;
        int k = 0;
        for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_)) {
          if (k < 3) t[k] = corner(v);
          ++k;
        }
        if (k != 3) return false;
        triangles.push_back(t);
      }
      if (capped != caps.end())
        for (const auto& t : capped->second) triangles.push_back({{corner(t[0]), corner(t[1]), corner(t[2])}});
    }
    if (triangles.empty() || !CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(triangles)) return false;
    Work_mesh solids;
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, triangles, solids);
    const Work_vpm wvpm = get(CGAL::vertex_point, solids);
    std::vector<typename boost::graph_traits<Work_mesh>::face_descriptor> fs(faces(solids).begin(),
                                                                              faces(solids).end());
    Tree tree(fs.begin(), fs.end(), solids, wvpm);
    tree.build();
    const CGAL::Bbox_3 b = tree.bbox();
    const double reach = 4. * std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                                        CGAL::square(b.zmax() - b.zmin())) + 1.;
    bool capped_any = false;
    for (auto sc_it = sheet_caps.begin(); sc_it != sheet_caps.end();) {
      auto& sc = *sc_it;
      // the border loops: the corners of each loop's cap triangles
      std::map<vertex_descriptor, std::size_t> loop_of;
      Union_find<std::size_t> loops(3 * sc.second.size());
      for (std::size_t t = 0; t < sc.second.size(); ++t)
        for (int k = 0; k < 3; ++k) {
          const auto it = loop_of.emplace(sc.second[t][k], 3 * t + k).first;
          loops.unite(it->second, 3 * t);
        }
      std::map<std::size_t, CGAL::Bbox_3> loop_box;
      for (const auto& vl : loop_of) {
        const Vec3 p = point(vpm_, vl.first);
        loop_box[loops.find(vl.second)] += CGAL::Bbox_3(p[0], p[1], p[2], p[0], p[1], p[2]);
      }
      bool inside = true;
      for (const auto& vl : loop_of) {
        const Vec3 p = point(vpm_, vl.first);
        const Epick::Point_3 q(p[0], p[1], p[2]);
        // near the solids' surface counts whichever side it is on; tested
        // first, because a point on that surface (a lid whose rim sits on
        // the rim of its pot) has no ray without a degenerate hit
        const CGAL::Bbox_3& box = loop_box[loops.find(vl.second)];
        const double loop_size = std::sqrt(CGAL::square(box.xmax() - box.xmin()) +
                                           CGAL::square(box.ymax() - box.ymin()) +
                                           CGAL::square(box.zmax() - box.zmin()));
        const double allowed = outside_share * loop_size;
        if (tree.squared_distance(q) <= allowed * allowed) continue;
        int winding = 0;
        if (!winding_number(tree, solids, wvpm, q, reach, winding) || winding == 0) {
          inside = false;
          break;
        }
      }
      if (!inside) {
        ++sc_it;
        continue;
      }
      solid_shell[sc.first] = !shell_is_flat(pm_, vpm_, shells[sc.first]);
      caps.emplace(sc.first, std::move(sc.second));
      sc_it = sheet_caps.erase(sc_it);
      capped_any = true;
    }
    return capped_any;
  }

  // ------------------------------------------------------ resting parts
  // Open parts that rest on a solid without crossing anything (a button
  // modelled as an open dome on a coat, its rim a little off the coat's
  // facets: the doorman's buttons lie 0.1-11% of their rim's size away). The
  // hole filler left their loops open as a sheet's border; their rims lie
  // inside or near the closed shells (cap_parts_stuck_into_solids' test), so
  // they are parts, and their loops get Liepa's caps in place: the part
  // becomes closed. A cap in a crossing the mesh did not have is taken back
  // (its part stays open). `scan` is kept current.
  bool cap_parts_resting_on_solids(Crossing_scan<PM>& scan)
  {
    // one part, or no border: nothing to cap (most meshes; the shells'
    // labelling below costs more than these two looks)
    if (scan.components < 2) return false;
    bool any_border = false;
    for (halfedge_descriptor h : halfedges(pm_))
      if (is_border(h, pm_)) {
        any_border = true;
        break;
      }
    if (!any_border) return false;
    Component_map component = get(CGAL::dynamic_face_property_t<std::size_t>(), pm_);
    const std::vector<Shell<PM>> shells = shells_of(component);
    if (shells.size() < 2) return false;
    std::vector<signed char> solid_shell(shells.size(), 0);
    CGAL::Bbox_3 solids_box;
    bool any_solid = false, any_open = false;
    for (std::size_t c = 0; c < shells.size(); ++c) {
      if (!shells[c].closed) any_open = true;
      else if (!shell_is_flat(pm_, vpm_, shells[c])) {
        solid_shell[c] = 1;
        solids_box += shells[c].box;
        any_solid = true;
      }
    }
    if (!any_solid || !any_open) return false;
    // the parts in a crossing are the solidification's
    std::vector<unsigned char> crossing(shells.size(), 0);
    for (const Pair& p : scan.crossing) crossing[get(component, p.first)] = crossing[get(component, p.second)] = 1;
    std::map<std::size_t, std::vector<std::array<vertex_descriptor, 3>>> open_caps, caps;
    for (std::size_t c = 0; c < shells.size(); ++c) {
      if (shells[c].closed || crossing[c]) continue;
      const CGAL::Bbox_3& b = shells[c].box;
      const double grow = settings_.rim_resting_share *
                          std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                                    CGAL::square(b.zmax() - b.zmin()));
      const CGAL::Bbox_3 reach(b.xmin() - grow, b.ymin() - grow, b.zmin() - grow, b.xmax() + grow,
                               b.ymax() + grow, b.zmax() + grow);
      if (!CGAL::do_overlap(reach, solids_box) || shell_is_flat(pm_, vpm_, shells[c])) continue;
      std::vector<std::array<vertex_descriptor, 3>> cap;
      if (caps_closing(shells[c], cap) != no_cap) open_caps.emplace(c, std::move(cap));
    }
    if (open_caps.empty()) return false;
    cap_parts_stuck_into_solids(shells, solid_shell, open_caps, caps, settings_.rim_resting_share);
    if (caps.empty()) return false;
    // Liepa's triangulation of each loop, in the mesh; the faces of each part
    std::map<std::size_t, std::vector<face_descriptor>> added;
    std::map<face_descriptor, std::size_t> part_of;
    for (const auto& cap : caps) {
      std::vector<halfedge_descriptor> loops;
      std::set<halfedge_descriptor> walked;
      for (face_descriptor f : shells[cap.first].faces)
        for (halfedge_descriptor g : CGAL::halfedges_around_face(halfedge(f, pm_), pm_)) {
          const halfedge_descriptor o = opposite(g, pm_);
          if (!is_border(o, pm_) || walked.count(o)) continue;
          loops.push_back(o);
          for (halfedge_descriptor w : CGAL::halfedges_around_face(o, pm_)) walked.insert(w);
        }
      std::vector<face_descriptor>& mine = added[cap.first];
      bool whole = true;
      for (halfedge_descriptor h : loops) whole = whole && triangulate_hole_checked(pm_, h, vpm_, true, mine);
      if (!whole) {
        for (face_descriptor f : mine) CGAL::Euler::remove_face(halfedge(f, pm_), pm_);
        added.erase(cap.first);
        continue;
      }
      for (face_descriptor f : mine) part_of.emplace(f, cap.first);
    }
    // A cap in a crossing goes again, with its part's other caps (the
    // pairs without a cap are the mesh's own: their faces did not change).
    // Each round takes back a part or ends; after the third all go.
    for (int round = 0; !added.empty(); ++round) {
      Crossing_scan<PM> after = scan_crossings(pm_, vpm_);
      std::set<std::size_t> back;
      if (after.status == Status::ok)
        for (const Pair& p : after.crossing)
          for (face_descriptor f : {p.first, p.second}) {
            const auto it = part_of.find(f);
            if (it != part_of.end()) back.insert(it->second);
          }
      if (after.status == Status::ok && back.empty()) {
        scan = std::move(after);
        break;
      }
      if (after.status != Status::ok || round == 2)
        for (const auto& a : added) back.insert(a.first);
      for (std::size_t c : back) {
        for (face_descriptor f : added[c]) {
          part_of.erase(f);
          CGAL::Euler::remove_face(halfedge(f, pm_), pm_);
        }
        added.erase(c);
      }
    }
    for (const auto& a : added) {
      ++counts.open_parts_capped;
      counts.cap_faces_added += a.second.size();
    }
    return !added.empty();
  }

  // ---------------------------------------------------------- solidify
  // The closed shells that take part in a crossing become the boundary of
  // the cells their arrangement gives a winding number >= 1 (arrangement.h).
  // The result is rounded to doubles; while it crosses or has a degenerate
  // face, the arrangement runs again on it (at most arrangement_passes). A
  // result that is not a valid closed triangle mesh without crossing leaves
  // the shells as they were (`solidify_note` says why).
  bool solidify_closed_shells(const Crossing_scan<PM>& scan, bool with_sheets)
  {
    sheets_taken_ = false;
    using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Work_mesh = CGAL::Surface_mesh<Epick::Point_3>;
    Component_map component = get(CGAL::dynamic_face_property_t<std::size_t>(), pm_);
    std::vector<Shell<PM>> shells = shells_of(component);
    std::vector<unsigned char> chosen(shells.size(), 0);
    // closed, or closed by the caps the hole filler would give it (an open
    // shell's holes beside a crossing stay open in the cleaning, whose
    // filler refuses a patch that crosses the surface: the arrangement
    // resolves those crossings), and not flat (a flat shell bounds no cell:
    // shell_is_flat)
    std::vector<signed char> solid_shell(shells.size(), -1);
    std::map<std::size_t, std::vector<std::array<vertex_descriptor, 3>>> caps;
    std::map<std::size_t, std::vector<std::array<vertex_descriptor, 3>>> sheet_caps;
    // Only open shells that cross another shell are capped: one that only
    // crosses itself (a fold beside a hole) keeps the local repair, which
    // removes the fold; the arrangement would keep the fold's flap as a
    // sliver of solid of its own.
    std::vector<unsigned char> crosses_another(shells.size(), 0);
    for (const Pair& p : scan.crossing) {
      const std::size_t a = get(component, p.first), b = get(component, p.second);
      if (a != b) crosses_another[a] = crosses_another[b] = 1;
    }
    auto bounds_a_solid = [&](std::size_t c) {
      if (solid_shell[c] < 0) {
        bool closed = shells[c].closed;
        if (!closed && crosses_another[c]) {
          std::vector<std::array<vertex_descriptor, 3>> cap;
          const Capping capping = caps_closing(shells[c], cap);
          closed = capping == small_caps;
          if (capping == small_caps) caps.emplace(c, std::move(cap));
          if (capping == large_caps) sheet_caps.emplace(c, std::move(cap));
        }
        solid_shell[c] = closed && !shell_is_flat(pm_, vpm_, shells[c]);
      }
      return solid_shell[c] == 1;
    };
    for (const Pair& p : scan.crossing) {
      bounds_a_solid(get(component, p.first));
      bounds_a_solid(get(component, p.second));
    }
    // A cap can cross a shell that nothing crossed before: the flat cap of a
    // pot's opening crosses the lid that sits in it (the Utah teapot: the
    // lid only touches the pot's rim). Such an open shell is a candidate too,
    // paired with the capped shell.
    const std::vector<std::pair<std::size_t, std::size_t>> cap_crossings = shells_crossing_caps(shells, solid_shell, caps);
    for (const auto& cd : cap_crossings) {
      crosses_another[cd.second] = 1;
      bounds_a_solid(cd.second);
    }
    // An open part stuck into a body (a dome, a button, a leg of a model
    // whose parts were modelled as open surfaces): its border lies inside
    // the body, so its cap does too and the union does not show it.
    if (!sheet_caps.empty())
      cap_parts_stuck_into_solids(shells, solid_shell, sheet_caps, caps, settings_.rim_outside_share);
    // Open shells that cross a solid and bound nothing (a ribbon, a strap,
    // a fin modelled as a sheet): the arrangement cuts them where they enter
    // it and keeps what lies outside, attached at the solid's surface; what
    // lies inside is absorbed, as a part inside a solid is. Sheets stay
    // sheets.
    std::vector<unsigned char> sheet(shells.size(), 0);
    bool any = false;
    for (const Pair& p : scan.crossing) {
      const std::size_t a = get(component, p.first), b = get(component, p.second);
      const bool sa = bounds_a_solid(a), sb = bounds_a_solid(b);
      if (sa && sb) chosen[a] = chosen[b] = 1, any = true;
      else if (with_sheets && a != b && (sa || sb)) {
        const std::size_t open = sa ? b : a;
        if (shells[open].closed) continue;  // a flat closed shell bounds nothing either: left
        chosen[sa ? a : b] = sheet[open] = 1;
        any = true;
      }
    }
    for (const auto& cd : cap_crossings)
      if (bounds_a_solid(cd.first) && bounds_a_solid(cd.second)) chosen[cd.first] = chosen[cd.second] = 1, any = true;
    if (!any) return false;
    for (std::size_t c = 0; c < shells.size(); ++c) sheet[c] = sheet[c] && !chosen[c];
    // the chosen shells as a soup, and their crossing pairs by soup index
    Triangle_soup soup;
    std::vector<face_descriptor> doomed;
    std::map<face_descriptor, std::size_t> index_of;
    {
      std::map<vertex_descriptor, std::size_t> vertex_index;
      for (std::size_t c = 0; c < shells.size(); ++c) {
        if (!chosen[c] && !sheet[c]) continue;
        for (face_descriptor f : shells[c].faces) {
          std::array<std::size_t, 3> t;
          int k = 0;
          for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_)) {
            auto it = vertex_index.emplace(v, soup.points.size());
            if (it.second) soup.points.push_back(point(vpm_, v));
            if (k < 3) t[k] = it.first->second;
            ++k;
          }
          if (k != 3) return false;
          index_of.emplace(f, soup.triangles.size());
          soup.triangles.push_back(t);
          soup.sheet.push_back(sheet[c]);
          doomed.push_back(f);
        }
        if (sheet[c]) {
          ++counts.sheets_cut;
          sheets_taken_ = true;
          continue;
        }
        auto cap = caps.find(c);
        if (cap != caps.end())
          for (const auto& t : cap->second) {
            soup.triangles.push_back({{vertex_index.at(t[0]), vertex_index.at(t[1]), vertex_index.at(t[2])}});
            soup.sheet.push_back(0);
          }
        ++counts.shells_solidified;
      }
    }
    if (!sheets_taken_) soup.sheet.clear();
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    bool capped = false;
    for (std::size_t c = 0; c < shells.size(); ++c) capped = capped || (chosen[c] && caps.count(c));
    if (capped) {
      // the caps cross what the shells' faces cross, and more: the pairs of
      // the capped soup, counted on it (faces in soup order)
      Work_mesh capped_mesh;
      std::vector<Epick::Point_3> points;
      for (const auto& p : soup.points) points.emplace_back(p[0], p[1], p[2]);
      if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(soup.triangles)) {
        counts.shells_solidified = counts.sheets_cut = 0;
        counts.solidify_note = "caps_not_closing: the capped shells are not a polygon mesh";
        return false;
      }
      CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, soup.triangles, capped_mesh);
      auto capped_scan = scan_crossings(capped_mesh, get(CGAL::vertex_point, capped_mesh));
      if (capped_scan.status != Status::ok || capped_scan.crossing.empty()) {
        counts.shells_solidified = counts.sheets_cut = 0;
        return false;
      }
      for (const auto& p : capped_scan.crossing)
        pairs.emplace_back(std::size_t(p.first.idx()), std::size_t(p.second.idx()));
    } else {
      for (const Pair& p : scan.crossing) {
        auto a = index_of.find(p.first), b = index_of.find(p.second);
        if (a != index_of.end() && b != index_of.end()) pairs.emplace_back(a->second, b->second);
      }
    }
    const std::size_t max_faces = 4 * soup.triangles.size() + 500000;
    // The best rounded solid so far: valid, closed, no flat face, and the
    // fewest crossing pairs. Rounding the exact solid to doubles can make a
    // few crossings where two of its sheets pass closer than the rounding
    // (8 pairs on a 56-body printer gantry, against 8,850 in its shells);
    // when passes on the rounded result do not clear them either, a solid
    // with fewer crossings than its shells had is still kept, and the local
    // repair that follows takes what is left.
    const std::size_t crossing_in = pairs.size();
    Work_mesh solid, best;
    Triangle_soup sheets_outside;  // of the first pass (the next ones arrange the solid alone)
    std::size_t best_left = crossing_in;
    bool done = false;
    for (std::size_t pass = 0; pass < settings_.arrangement_passes && !done; ++pass) {
      ++counts.arrangement_passes;
      Arrangement_outcome o = arrange_winding_number_solid(soup, pairs, max_faces);
      counts.arrangement_faces = o.pieces;
      if (pass == 0) sheets_outside = std::move(o.sheets);
      if (!o.ok) {
        counts.solidify_note = o.reason;
        break;
      }
      // the copies where the solid touches itself stay apart; points that
      // rounding made equal or collinear are flat faces: the next pass
      std::vector<Epick::Point_3> points;
      for (const auto& p : o.solid.points) points.emplace_back(p[0], p[1], p[2]);
      if (o.solid.triangles.empty()) {
        counts.solidify_note = "arrangement_empty: no cell of nonzero winding number";
        break;
      }
      std::vector<std::array<std::size_t, 3>> triangles = std::move(o.solid.triangles);
      if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(triangles)) {
        // Where bodies of an assembly touch at a corner, or along an edge
        // whose faces the arrangement did not pair, the kept faces meet in
        // more than one fan: each fan gets a copy of the corner or edge
        // (orient_polygon_soup; faces already consistent keep their
        // orientation).
        CGAL::Polygon_mesh_processing::orient_polygon_soup(points, triangles);
        if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(triangles)) {
          counts.solidify_note = "arrangement_not_closed: the kept faces are not a polygon mesh";
          break;
        }
      }
      solid.clear();
      CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, triangles, solid);
      if (!CGAL::is_valid_polygon_mesh(solid) || !CGAL::is_closed(solid) || !CGAL::is_triangle_mesh(solid)) {
        counts.solidify_note = "arrangement_not_closed: the kept faces do not close";
        break;
      }
      auto next = scan_crossings(solid, get(CGAL::vertex_point, solid));
      if (next.status != Status::ok) {
        counts.solidify_note = "arrangement_failed: the crossing test could not run";
        break;
      }
      if (next.skipped == 0 && next.crossing.size() < best_left) {
        best = solid;
        best_left = next.crossing.size();
      }
      if (next.crossing.empty() && next.skipped == 0) {
        done = true;
        break;
      }
      // rounding made crossings or flat faces: arrange the rounded result
      soup = Triangle_soup();
      for (auto v : vertices(solid)) {
        const auto& p = solid.point(v);
        soup.points.push_back({{p.x(), p.y(), p.z()}});
      }
      for (auto f : faces(solid)) {
        std::array<std::size_t, 3> t;
        int k = 0;
        for (auto v : CGAL::vertices_around_face(halfedge(f, solid), solid)) t[k++] = std::size_t(v.idx());
        soup.triangles.push_back(t);
      }
      pairs.clear();
      for (const auto& p : next.crossing) pairs.emplace_back(std::size_t(p.first.idx()), std::size_t(p.second.idx()));
      counts.solidify_note = "rounding_left_crossings: " + std::to_string(next.crossing.size()) + " pairs, " +
                             std::to_string(next.skipped) + " flat faces";
    }
    if (!done && best_left < crossing_in) {
      // kept with the crossings rounding left (the note says how many)
      solid = std::move(best);
      counts.solidify_note = "rounding_left_crossings: " + std::to_string(best_left) +
                             " pairs kept for the local repair (" + std::to_string(crossing_in) +
                             " in the shells)";
      rounding_left_crossings_ = true;
      done = true;
    }
    if (!done) {
      counts.shells_solidified = counts.sheets_cut = 0;
      return false;
    }
    // the sheets' pieces outside the solid: a mesh of their own (where a
    // sheet crossed itself its pieces meet in more than two: split there)
    Work_mesh sheets_mesh;
    if (sheets_taken_ && !sheets_outside.triangles.empty()) {
      std::vector<Epick::Point_3> points;
      for (const auto& p : sheets_outside.points) points.emplace_back(p[0], p[1], p[2]);
      std::vector<std::array<std::size_t, 3>> triangles;
      for (const auto& t : sheets_outside.triangles)  // rounding can flatten a sliver
        if (!CGAL::collinear(points[t[0]], points[t[1]], points[t[2]])) triangles.push_back(t);
      if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(triangles))
        CGAL::Polygon_mesh_processing::orient_polygon_soup(points, triangles);
      if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(triangles)) {
        counts.shells_solidified = counts.sheets_cut = 0;
        counts.solidify_note = "sheets_not_a_mesh: the sheets' pieces outside the solid";
        return false;
      }
      CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, triangles, sheets_mesh);
      if (!CGAL::is_valid_polygon_mesh(sheets_mesh)) {
        counts.shells_solidified = counts.sheets_cut = 0;
        counts.solidify_note = "sheets_not_a_mesh: the sheets' pieces outside the solid";
        return false;
      }
    }
    if (best_left == 0) counts.solidify_note.clear();
    {
      Local_operations<PM, VertexPointMap> ops(pm_, vpm_);
      counts.solid_faces_removed += ops.remove_components(doomed);
    }
    counts.solid_faces_added += internal::face_count(solid);
    CGAL::copy_face_graph(solid, pm_, CGAL::parameters::default_values(), CGAL::parameters::vertex_point_map(vpm_));
    if (!CGAL::is_empty(sheets_mesh)) {
      counts.solid_faces_added += internal::face_count(sheets_mesh);
      CGAL::copy_face_graph(sheets_mesh, pm_, CGAL::parameters::default_values(),
                            CGAL::parameters::vertex_point_map(vpm_));
    }
    return true;
  }

  // --------------------------------------------------------------- local
  // A shell that crosses itself (MeshFix's removal and refill, kept local):
  // round r removes the faces of its crossing pairs and r rings around them
  // (no vertex left pinched), and fills the loops this opens with the hole
  // filler (Liepa's patch, refined, taken back when it would cross the
  // surface; an aborted fill is enlarged by a ring, twice at most). The
  // next round looks at the crossings left. A round that leaves more border
  // loops or another number of components than it found, no fewer
  // crossings, more sharply folded vertices where it worked, or that removes
  // more than a third of the shells it touches, is taken back (the mesh as
  // copied before it) and ends the repair: a crossing is better than a hole,
  // a spike or a piece cut off by the repair. Pieces the removal would cut
  // off (a strip between two crossing zones, a pushed-through cap) are
  // removed with the region, so that the fill covers them.
  template <typename Visitor>
  bool repair_locally(Crossing_scan<PM>& scan, Visitor& visitor)
  {
    Component_map component = get(CGAL::dynamic_face_property_t<std::size_t>(), pm_);
    auto self_pairs = [&](const Crossing_scan<PM>& s) {
      std::vector<face_descriptor> fs;
      for (const Pair& p : s.crossing)
        if (get(component, p.first) == get(component, p.second)) {
          fs.push_back(p.first);
          fs.push_back(p.second);
        }
      return fs;
    };
    std::vector<Shell<PM>> found = shells_of(component);
    std::size_t shells = found.size(), loops = border_loop_count();
    std::vector<face_descriptor> doomed = self_pairs(scan);
    bool edited = false;
    for (std::size_t round = 0; round < settings_.local_rounds && !doomed.empty(); ++round) {
      if (visitor.stop_requested()) break;
      ++counts.local_rounds;
      // the copy to go back to, with where the faces of the crossing pairs
      // went: after a take-back the scan's pairs are renamed, not recounted
      std::set<face_descriptor> paired;
      for (const Pair& p : scan.crossing) {
        paired.insert(p.first);
        paired.insert(p.second);
      }
      std::map<face_descriptor, face_descriptor> to_backup;
      PM backup;
      CGAL::copy_face_graph(pm_, backup,
                            CGAL::parameters::vertex_point_map(vpm_).face_to_face_output_iterator(
                                boost::make_function_output_iterator([&](const Pair& p) {
                                  if (paired.count(p.first)) to_backup.emplace(p.first, p.second);
                                })));
      grow_by_rings(doomed, round);
      absorb_islands(doomed);
      // the faces of the shells the round touches: it may replace a third of
      // them at most (a small shell folded through itself is no local defect)
      std::size_t touched_faces = 0;
      {
        std::set<std::size_t> touched;
        for (face_descriptor f : doomed) touched.insert(get(component, f));
        for (std::size_t c : touched) touched_faces += found[c].faces.size();
      }
      // where the round works: the region's box, grown by its extent (the
      // filler's enlargements reach a ring or two beyond the region)
      const CGAL::Bbox_3 area = grown_box(doomed);
      const std::size_t sharp = sharp_vertices_in(area);
      std::size_t removed = 0, added = 0, open = 0, taken = 0;
      {
        Local_operations<PM, VertexPointMap> ops(pm_, vpm_);
        std::vector<vertex_descriptor> survivors;
        taken = ops.remove_faces_without_pinches(doomed, &survivors);
        clean_pipeline::Hole_filling_settings patch;
        patch.max_vertices = settings_.max_patch_vertices;
        patch.refine = settings_.refine_patches;
        patch.area_share = 0.;  // the round's own holes: no sheet border among them
        clean_pipeline::Small_hole_filler<PM, VertexPointMap> filler(ops, patch);
        std::vector<halfedge_descriptor> hs, new_loops;
        for (vertex_descriptor v : survivors)
          for (halfedge_descriptor h : CGAL::halfedges_around_target(v, pm_))
            if (is_border(h, pm_)) hs.push_back(h);
        filler.loops_of(hs, new_loops);
        filler.run_on(std::move(new_loops), 2, visitor);
        open = filler.result.open_holes.size();
        taken += filler.result.enlargement_faces_removed;
        removed = ops.counts().faces_removed;
        added = ops.counts().faces_added;
      }
      std::vector<Shell<PM>> found1 = shells_of(component);
      const std::size_t shells1 = found1.size(), loops1 = border_loop_count();
      // the cheap tests first: a round they refuse costs no crossing scan
      bool keep = shells1 == shells && loops1 <= loops && 3 * taken <= touched_faces &&
                  sharp_vertices_in(area) <= sharp;
      Crossing_scan<PM> next;
      if (keep) {
        next = scan_crossings(pm_, vpm_);
        keep = next.status == Status::ok && next.crossing.size() < scan.crossing.size();
      }
      if (!keep) {
        // a user's property maps (the point map among them) stay attached
        if constexpr (Is_surface_mesh<PM>::value) pm_.clear_without_removing_property_maps();
        else CGAL::clear(pm_);
        std::set<face_descriptor> paired_back;
        for (const auto& x : to_backup) paired_back.insert(x.second);
        std::map<face_descriptor, face_descriptor> from_backup;
        CGAL::copy_face_graph(backup, pm_,
                              CGAL::parameters::face_to_face_output_iterator(
                                  boost::make_function_output_iterator([&](const Pair& p) {
                                    if (paired_back.count(p.first)) from_backup.emplace(p.first, p.second);
                                  })),
                              CGAL::parameters::vertex_point_map(vpm_));
        ++counts.local_rounds_taken_back;
        for (Pair& p : scan.crossing) {
          p.first = from_backup.at(to_backup.at(p.first));
          p.second = from_backup.at(to_backup.at(p.second));
        }
        // A wider region around the same crossings fared no better where
        // it was tried (the 1M blade CAD soup: a patch whose whole seam
        // crosses its neighbours is cut off by every ring, 3 rounds 12 s):
        // the first refusal ends the repair.
        break;
      }
      counts.local_faces_removed += removed;
      counts.local_faces_added += added;
      counts.local_holes_left_open = open;
      edited = true;
      scan = std::move(next);
      found = std::move(found1);
      shells = shells1;
      loops = loops1;
      doomed = self_pairs(scan);
    }
    return edited;
  }

  CGAL::Bbox_3 grown_box(const std::vector<face_descriptor>& fs) const
  {
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (face_descriptor f : fs)
      for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_)) {
        const Vec3 p = point(vpm_, v);
        for (int d = 0; d < 3; ++d) {
          lo[d] = std::min(lo[d], p[d]);
          hi[d] = std::max(hi[d], p[d]);
        }
      }
    for (int d = 0; d < 3; ++d) {
      const double e = hi[d] - lo[d];
      lo[d] -= e;
      hi[d] += e;
    }
    return CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  }

  // The vertices in `box` with an edge folded beyond the spike angle (the
  // dihedral criterion of inspect's spiked vertices). A round may not add
  // such folds where it worked: a Liepa patch over a jagged sliver seam can
  // (the 200k blade CAD soup: 33 more spiked vertices for 73 crossings gone).
  std::size_t sharp_vertices_in(const CGAL::Bbox_3& box) const
  {
    std::size_t n = 0;
    for (vertex_descriptor v : vertices(pm_)) {
      const Vec3 p = point(vpm_, v);
      if (p[0] < box.xmin() || p[0] > box.xmax() || p[1] < box.ymin() || p[1] > box.ymax() ||
          p[2] < box.zmin() || p[2] > box.zmax())
        continue;
      const halfedge_descriptor h0 = halfedge(v, pm_);
      if (h0 == GT::null_halfedge()) continue;
      for (halfedge_descriptor h : CGAL::halfedges_around_target(h0, pm_))
        if (clean_pipeline::dihedral_angle_deg(h, pm_, vpm_) > defaults::spike_angle) {
          ++n;
          break;
        }
    }
    return n;
  }

  std::size_t border_loop_count() const
  {
    std::vector<halfedge_descriptor> border;
    border_halfedges(pm_, border);
    std::set<halfedge_descriptor> seen;
    std::size_t n = 0;
    for (halfedge_descriptor h : border) {
      if (seen.count(h)) continue;
      ++n;
      for (halfedge_descriptor g : CGAL::halfedges_around_face(h, pm_)) seen.insert(g);
    }
    return n;
  }

  // Adds to `fs` the pieces its removal would cut off: the faces reached
  // from its edge neighbours without crossing `fs`, when a search stops
  // before `limit` faces (the largest island it may absorb). A search that
  // reaches the limit marks what it saw as mainland, so that later searches
  // stop there: the work is about limit x (islands + 1) plus the region.
  void absorb_islands(std::vector<face_descriptor>& fs) const
  {
    std::set<face_descriptor> region(fs.begin(), fs.end()), mainland;
    const std::size_t limit = std::max<std::size_t>(64, fs.size());
    std::vector<face_descriptor> seeds, piece, stack;
    for (face_descriptor f : fs)
      for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, pm_), pm_)) {
        const halfedge_descriptor o = opposite(h, pm_);
        if (!is_border(o, pm_) && !region.count(face(o, pm_))) seeds.push_back(face(o, pm_));
      }
    for (face_descriptor seed : seeds) {
      if (region.count(seed) || mainland.count(seed)) continue;
      std::set<face_descriptor> seen{seed};
      stack.assign(1, seed);
      bool reached_mainland = false;
      while (!stack.empty() && !reached_mainland) {
        const face_descriptor f = stack.back();
        stack.pop_back();
        for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, pm_), pm_)) {
          const halfedge_descriptor o = opposite(h, pm_);
          if (is_border(o, pm_)) continue;
          const face_descriptor g = face(o, pm_);
          if (region.count(g) || seen.count(g)) continue;
          if (mainland.count(g) || seen.size() >= limit) {
            reached_mainland = true;
            break;
          }
          seen.insert(g);
          stack.push_back(g);
        }
      }
      if (reached_mainland) mainland.insert(seen.begin(), seen.end());
      else {
        region.insert(seen.begin(), seen.end());
        fs.insert(fs.end(), seen.begin(), seen.end());
      }
    }
  }

  // `fs` and the faces around its vertices, `rings` times over
  void grow_by_rings(std::vector<face_descriptor>& fs, std::size_t rings) const
  {
    std::set<face_descriptor> in(fs.begin(), fs.end());
    std::vector<face_descriptor> frontier(in.begin(), in.end());
    for (std::size_t r = 0; r < rings; ++r) {
      std::set<vertex_descriptor> vs;
      for (face_descriptor f : frontier)
        for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm_), pm_)) vs.insert(v);
      frontier.clear();
      for (vertex_descriptor v : vs)
        for (halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, pm_), pm_))
          if (!is_border(h, pm_) && in.insert(face(h, pm_)).second) frontier.push_back(face(h, pm_));
    }
    fs.assign(in.begin(), in.end());
  }

  // --------------------------------------------------------------- union
  // Closed, outward shells that cross one another, or lie one inside the
  // other, become their union (CGAL's exact corefinement, one shell at a
  // time, largest first). An inward shell is a cavity and an open shell
  // bounds nothing: neither takes part. A union that CGAL refuses (it would
  // be non-manifold, an operand crosses itself) or that would still cross
  // leaves its shells as they were.
  bool merge_overlapping_shells(const Crossing_scan<PM>& scan)
  {
    Component_map component = get(CGAL::dynamic_face_property_t<std::size_t>(), pm_);
    std::vector<Shell<PM>> shells = shells_of(component);
    const std::size_t S = shells.size();
    if (S < 2) return false;
    std::vector<unsigned char> self_crossing(S, 0);
    std::vector<std::size_t> parent(S);
    std::iota(parent.begin(), parent.end(), std::size_t(0));
    auto find = [&](std::size_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    auto solid = [&](std::size_t c) { return shells[c].closed && shells[c].volume > 0.; };
    std::vector<std::pair<std::size_t, std::size_t>> touching_shells;
    for (const Pair& p : scan.crossing) {
      const std::size_t a = get(component, p.first), b = get(component, p.second);
      if (a == b) self_crossing[a] = 1;
      else touching_shells.emplace_back(a, b);
    }
    bool any = false;
    for (const auto& ab : touching_shells)
      if (solid(ab.first) && solid(ab.second) && !self_crossing[ab.first] && !self_crossing[ab.second]) {
        parent[find(ab.first)] = find(ab.second);
        any = true;
      }
    // shells inside another, outward both: the inner one adds nothing to
    // the solid (a cavity is inward and stays)
    std::vector<unsigned char> nested(S, 0);
    if (S <= settings_.max_nesting_shells) any = find_nested(shells, self_crossing, parent, nested) || any;
    if (!any) return false;
    std::vector<std::vector<std::size_t>> clusters(S);
    for (std::size_t c = 0; c < S; ++c) clusters[find(c)].push_back(c);
    bool changed = false;
    std::vector<face_descriptor> doomed;
    std::vector<PM> results;
    for (auto& members : clusters) {
      if (members.size() < 2) continue;
      std::sort(members.begin(), members.end(),
                [&](std::size_t x, std::size_t y) { return shells[x].volume > shells[y].volume; });
      PM acc;
      copy_faces_out(pm_, vpm_, shells[members[0]].faces, acc);
      std::vector<std::size_t> merged(1, members[0]);
      for (std::size_t i = 1; i < members.size(); ++i) {
        PM operand, out;
        copy_faces_out(pm_, vpm_, shells[members[i]].faces, operand);
        bool ok = false;
        try {
          ok = CGAL::Polygon_mesh_processing::corefine_and_compute_union(
              acc, operand, out, CGAL::parameters::throw_on_self_intersection(true));
        } catch (...) {
          ok = false;
        }
        ok = ok && CGAL::is_valid_polygon_mesh(out) && CGAL::is_closed(out) && CGAL::is_triangle_mesh(out);
        // CGAL numbers what the corefinement creates in an order of heap
        // addresses, and those vary with the thread timing of the stages
        // before (see copy_in_canonical_order): the union goes on, and into
        // the mesh, in an order of its geometry alone, so that the output is
        // the same file on every run. A refused union may have refined `acc`.
        if (ok || (CGAL::is_valid_polygon_mesh(acc) && CGAL::is_triangle_mesh(acc))) {
          PM canonical;
          copy_in_canonical_order(ok ? out : acc, canonical);
          acc = std::move(canonical);
        }
        if (!ok) {
          ++counts.unions_failed;
          continue;
        }
        merged.push_back(members[i]);
      }
      if (merged.size() < 2) continue;
      // rounding the intersection points to doubles can leave a crossing
      if (!scan_crossings(acc, get(CGAL::vertex_point, acc)).crossing.empty()) {
        ++counts.unions_failed;
        continue;
      }
      std::string what = std::to_string(merged.size()) + " shells of";
      for (std::size_t c : merged) {
        doomed.insert(doomed.end(), shells[c].faces.begin(), shells[c].faces.end());
        counts.nested_shells_merged += nested[c];
        what += " " + std::to_string(shells[c].faces.size()) + (nested[c] ? " (nested)" : "");
      }
      counts.unions.push_back(what + " faces -> " + std::to_string(internal::face_count(acc)) + " faces");
      counts.shells_merged += merged.size();
      ++counts.solids_from_unions;
      results.push_back(std::move(acc));
      changed = true;
    }
    if (!changed) return false;
    {
      Local_operations<PM, VertexPointMap> ops(pm_, vpm_);
      counts.union_faces_removed += ops.remove_components(doomed);
    }
    for (const PM& r : results) {
      counts.union_faces_added += internal::face_count(r);
      CGAL::copy_face_graph(r, pm_, CGAL::parameters::default_values(), CGAL::parameters::vertex_point_map(vpm_));
    }
    return true;
  }

  // Unites each closed outward shell that no crossing touches with the
  // closed outward shell that contains it (box first, then CGAL's exact
  // side-of-mesh test on one of its vertices); `nested` marks the inner ones.
  bool find_nested(const std::vector<Shell<PM>>& shells, const std::vector<unsigned char>& self_crossing,
                   std::vector<std::size_t>& parent, std::vector<unsigned char>& nested)
  {
    const std::size_t S = shells.size();
    auto solid = [&](std::size_t c) {
      return shells[c].closed && shells[c].volume > 0. && !self_crossing[c];
    };
    auto inside_box = [](const CGAL::Bbox_3& a, const CGAL::Bbox_3& b) {
      return b.xmin() <= a.xmin() && a.xmax() <= b.xmax() && b.ymin() <= a.ymin() && a.ymax() <= b.ymax() &&
             b.zmin() <= a.zmin() && a.zmax() <= b.zmax();
    };
    using Point = typename boost::property_traits<VertexPointMap>::value_type;
    using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
    using Side = CGAL::Side_of_triangle_mesh<PM, Kernel>;
    // each container copied out once, with its tree
    struct Container
    {
      PM mesh;
      std::unique_ptr<Side> side;
    };
    std::map<std::size_t, Container> containers;
    bool any = false;
    for (std::size_t c = 0; c < S; ++c) {
      if (!solid(c) || parent[c] != c) continue;  // already in a union: handled there
      // the smallest container wins, so a shell inside two goes with the inner
      std::size_t best = S;
      for (std::size_t d = 0; d < S; ++d) {
        if (d == c || !solid(d) || !inside_box(shells[c].box, shells[d].box)) continue;
        if (shells[d].volume <= shells[c].volume) continue;
        Container& k = containers[d];
        if (!k.side) {
          copy_faces_out(pm_, vpm_, shells[d].faces, k.mesh);
          k.side.reset(new Side(k.mesh));
        }
        const Point q = get(vpm_, target(halfedge(shells[c].faces.front(), pm_), pm_));
        if ((*k.side)(q) != CGAL::ON_BOUNDED_SIDE) continue;
        if (best == S || shells[d].volume < shells[best].volume) best = d;
      }
      if (best == S) continue;
      nested[c] = 1;
      std::size_t r = best;
      while (parent[r] != r) r = parent[r];
      parent[c] = r;
      any = true;
    }
    return any;
  }

  // -------------------------------------------------------------- report
  void explain_left(const Crossing_scan<PM>& scan)
  {
    if (scan.crossing.empty()) return;
    Component_map component = get(CGAL::dynamic_face_property_t<std::size_t>(), pm_);
    std::vector<Shell<PM>> shells = shells_of(component);
    std::map<std::string, std::size_t> by;
    for (const Pair& p : scan.crossing) {
      const std::size_t a = get(component, p.first), b = get(component, p.second);
      std::string why;
      if (a == b) why = "shell_crosses_itself";
      else if (!shells[a].closed || !shells[b].closed) why = "open_shells_cross";
      else if (!(shells[a].volume > 0.) || !(shells[b].volume > 0.)) why = "inward_shell_crosses";
      else if (!settings_.merge_shells) why = "shells_kept_separate";
      else why = "union_failed";
      ++by[why];
    }
    counts.left_by_reason.assign(by.begin(), by.end());
  }
};

} // namespace solid
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_RESOLVE_INTERSECTIONS_RESOLVER_H
