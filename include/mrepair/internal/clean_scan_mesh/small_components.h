// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Worker of remove_small_components() (RameshCleaner 3.2), also run by
// clean_boundaries() on the pieces its erosion splits off.
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SMALL_COMPONENTS_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SMALL_COMPONENTS_H

#include <mrepair/cleaning_results.h>
#include <mrepair/definitions.h>
#include <mrepair/internal/clean_scan_mesh/safety.h>
#include <mrepair/internal/local_operations.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace mrepair {
namespace internal {
namespace clean_pipeline {

/// Finds the face-connected components with fewer than `threshold` faces
/// among those that contain a face of `seeds`. Each component is grown by a
/// queue from a seed; growth stops as soon as it reaches `threshold` faces or
/// touches a face already known to lie in a large component, and then all the
/// faces it collected are labelled large, so every face is enqueued at most
/// once over the whole call (linear time whatever the threshold).
///
/// `small` receives the faces of the small components, `offsets` the start of
/// each component in `small` (plus a final end offset).
template <typename PM, typename FaceRange>
void find_small_components(const PM& pm, const FaceRange& seeds, std::size_t threshold,
                           std::vector<typename boost::graph_traits<PM>::face_descriptor>& small,
                           std::vector<std::size_t>& offsets)
{
  using GT = boost::graph_traits<PM>;
  using face_descriptor = typename GT::face_descriptor;
  small.clear();
  offsets.assign(1, 0);
  if (threshold <= 1) return;  // no component has fewer than 1 face
  // 0 unvisited, 1 growing, 2 in a large component, 3 in a small one
  auto label = get(CGAL::dynamic_face_property_t<char>(), pm);  // value-initialised: all 0
  std::vector<face_descriptor> comp;
  for (face_descriptor seed : seeds) {
    if (get(label, seed) != 0) continue;
    comp.clear();
    comp.push_back(seed);
    put(label, seed, char(1));
    bool large = comp.size() >= threshold;
    for (std::size_t head = 0; head < comp.size() && !large; ++head) {
      for (auto h : CGAL::halfedges_around_face(halfedge(comp[head], pm), pm)) {
        auto o = opposite(h, pm);
        if (is_border(o, pm)) continue;
        face_descriptor n = face(o, pm);
        char l = get(label, n);
        if (l == 2) { large = true; break; }
        if (l == 0) {
          put(label, n, char(1));
          comp.push_back(n);
          if (comp.size() >= threshold) { large = true; break; }
        }
      }
    }
    const char final_label = large ? char(2) : char(3);
    for (face_descriptor f : comp) put(label, f, final_label);
    if (!large) {
      small.insert(small.end(), comp.begin(), comp.end());
      offsets.push_back(small.size());
    }
  }
}

/// Open components with fewer faces than this are the debris the cad profile
/// may remove (three facets, at most, hang together without closing a volume).
constexpr std::size_t open_debris_faces = 4;

/// true when no border loop of the open component made of the faces
/// [first, last) (of total area `area`) is a hole by the hole filler's rule
/// (doc/guarantees.md, "Hole or border"): a cap under `max_hole_area_share`
/// of the component's area would close it into a volume. Three faces of a
/// tetrahedron enclose one; a lone triangle, a quad or a strip do not.
template <typename PM, typename VPM, typename FaceIterator>
bool encloses_nothing(const PM& pm, const VPM& vpm, FaceIterator first, FaceIterator last, double area)
{
  using halfedge_descriptor = typename boost::graph_traits<PM>::halfedge_descriptor;
  std::vector<halfedge_descriptor> walked;
  for (FaceIterator f = first; f != last; ++f)
    for (auto h : CGAL::halfedges_around_face(halfedge(*f, pm), pm)) {
      const halfedge_descriptor b = opposite(h, pm);
      if (!is_border(b, pm) || std::find(walked.begin(), walked.end(), b) != walked.end()) continue;
      std::size_t steps = 0;  // a few faces: a loop of at most 3 x 3 edges
      for (auto g : CGAL::halfedges_around_face(b, pm)) {
        walked.push_back(g);
        if (++steps > 64) return false;  // not a few faces after all: keep it
      }
      const double cap = loop_cap_area(b, pm, vpm);
      if (cap > 0. && cap < defaults::max_hole_area_share * area) return false;
    }
  return true;
}

/// Removes the small components that contain a face of `seeds` (see
/// `find_small_components()`). A component is small when it has fewer than
/// `threshold` faces and, relative to the largest component (most faces),
/// fewer than `relative` times its faces and less than `relative` times its
/// area. The largest component is never removed, so a non-empty mesh is never
/// emptied and a model made of several comparable parts keeps them all.
/// With `protect` (a face property of bool), components with a protected face
/// stay too.
template <typename PM, typename VPM, typename FaceRange, typename Protect = std::nullptr_t>
Small_components_result remove_small_components_seeded(Local_operations<PM, VPM>& ops,
                                                       const FaceRange& seeds,
                                                       std::size_t threshold, double relative,
                                                       const Protect* protect = nullptr,
                                                       bool open_debris_only = false)
{
  using face_descriptor = typename boost::graph_traits<PM>::face_descriptor;
  PM& pm = ops.mesh();
  const VPM& vpm = ops.vertex_point_map();
  Small_components_result r;
  std::vector<face_descriptor> small;
  std::vector<std::size_t> offsets;
  find_small_components(pm, seeds, threshold, small, offsets);
  const std::size_t n_comp = offsets.size() - 1;
  if (n_comp == 0) return r;
  // Sizes of every component, to compare the candidates with the largest.
  auto id = get(CGAL::dynamic_face_property_t<std::size_t>(), pm);
  std::vector<std::size_t> faces_of;
  std::vector<double> area_of;
  label_components(pm, vpm, id, faces_of, area_of);
  std::size_t largest = 0;
  for (std::size_t c = 1; c < faces_of.size(); ++c)
    if (faces_of[c] > faces_of[largest] ||
        (faces_of[c] == faces_of[largest] && area_of[c] > area_of[largest]))
      largest = c;
  // Debris mode (print models): only open bits of a few faces next to a
  // closed largest component go (a stray facet by a solid).
  std::vector<char> open(open_debris_only ? faces_of.size() : 0, 0);
  if (open_debris_only) {
    for (auto h : halfedges(pm))
      if (is_border(h, pm)) open[get(id, face(opposite(h, pm), pm))] = 1;
    if (open[largest]) return r;
  }
  for (std::size_t c = 0; c < n_comp; ++c) {
    const std::size_t label = get(id, small[offsets[c]]);
    const std::size_t nf = offsets[c + 1] - offsets[c];
    if (label == largest) {
      r.kept_largest = true;
      continue;
    }
    // debris (issue 50): open, a few stray facets (under 4 faces), and
    // enclosing nothing (no border loop the hole filler would close). A part
    // that is closed, or can be closed, stays however small.
    const bool removable =
        open_debris_only
            ? open[label] && nf < open_debris_faces &&
                  encloses_nothing(pm, vpm, small.begin() + offsets[c], small.begin() + offsets[c + 1],
                                   area_of[label])
            : double(nf) < relative * double(faces_of[largest]) &&
                  area_of[label] < relative * area_of[largest];
    if (!removable) {
      ++r.components_kept_relative;
      continue;
    }
    if constexpr (!std::is_same<Protect, std::nullptr_t>::value) {
      bool is_protected = false;
      for (std::size_t i = offsets[c]; i < offsets[c + 1] && !is_protected; ++i)
        is_protected = get(*protect, small[i]);
      if (is_protected) continue;
    }
    // Components are vertex-disjoint in a valid mesh: removing one whole never
    // pinches another.
    const std::size_t vertices_gone = ops.counts().vertices_removed;
    ops.remove_components(std::vector<face_descriptor>(small.begin() + offsets[c],
                                                       small.begin() + offsets[c + 1]));
    r.vertices_removed += ops.counts().vertices_removed - vertices_gone;
    ++r.components_removed;
    r.faces_removed += nf;
  }
  return r;
}

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_SMALL_COMPONENTS_H
