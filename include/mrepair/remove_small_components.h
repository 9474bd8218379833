// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_REMOVE_SMALL_COMPONENTS_H
#define MREPAIR_REMOVE_SMALL_COMPONENTS_H

#include <mrepair/internal/clean_scan_mesh/mesh_ops.h>
#include <mrepair/internal/clean_scan_mesh/safety.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Named_function_parameters.h>

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <cstddef>
#include <vector>

/// \file remove_small_components.h
/// RameshCleaner 3.2: removal of small face-connected components by a
/// region growing that stops as soon as a component reaches the threshold, so
/// that large components cost little. "Small" is also relative to the
/// largest component, which is never removed.

MREPAIR_ADD_NAMED_PARAMETER(relative_component_size)  // share of the largest component (0.01)
MREPAIR_ADD_NAMED_PARAMETER(open_debris_only)         // bool: only open bits next to a closed largest component (false)

namespace mrepair {

/// \ingroup mrepair_clean
/// what `remove_small_components()` did.
struct Small_components_result
{
  Status status = Status::ok;
  std::size_t components_removed = 0;
  std::size_t faces_removed = 0;
  std::size_t vertices_removed = 0;
  /// the largest component was among the small candidates and was kept
  bool kept_largest = false;
  /// small by face count but not small next to the largest component: kept
  std::size_t components_kept_relative = 0;

  void to_report(Report& r) const
  {
    r.add("status", status);
    r.add("components_removed", components_removed);
    r.add("faces_removed", faces_removed);
    r.add("vertices_removed", vertices_removed);
    r.add("components_kept_relative", components_kept_relative);
    if (kept_largest) r.add("kept_largest_small_component", true);
  }
};

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
  auto label = get(CGAL::dynamic_face_property_t<char>(), pm);
  for (face_descriptor f : faces(pm)) put(label, f, char(0));
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

/// Removes the small components that contain a face of `seeds` (see
/// `find_small_components()`). A component is small when it has fewer than
/// `threshold` faces and, relative to the largest component (most faces),
/// fewer than `relative` times its faces and less than `relative` times its
/// area. The largest component is never removed, so a non-empty mesh is never
/// emptied and a model made of several comparable parts keeps them all.
/// With `protect` (a face property of bool), components with a protected face
/// stay too.
template <typename PM, typename VPM, typename FaceRange, typename Observer = No_edit_observer,
          typename Protect = std::nullptr_t>
Small_components_result remove_small_components_seeded(PM& pm, const VPM& vpm,
                                                       const FaceRange& seeds,
                                                       std::size_t threshold, double relative,
                                                       Observer* observer = nullptr,
                                                       const Protect* protect = nullptr,
                                                       bool open_debris_only = false)
{
  using face_descriptor = typename boost::graph_traits<PM>::face_descriptor;
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
  // Debris mode (print models): only open bits next to a closed largest
  // component go, whatever their face count (a stray facet by a solid).
  std::vector<char> open(open_debris_only ? faces_of.size() : 0, 0);
  if (open_debris_only) {
    for (auto h : halfedges(pm))
      if (is_border(h, pm)) open[get(id, face(opposite(h, pm), pm))] = 1;
    if (open[largest]) return r;
  }
  const std::size_t nv = static_cast<std::size_t>(vertices(pm).size());
  for (std::size_t c = 0; c < n_comp; ++c) {
    const std::size_t label = get(id, small[offsets[c]]);
    const std::size_t nf = offsets[c + 1] - offsets[c];
    if (label == largest) {
      r.kept_largest = true;
      continue;
    }
    // debris: open, and either a few stray facets (under 4 faces: no volume,
    // whatever their size) or small in area next to the solid
    const bool removable = open_debris_only
                           ? open[label] && (nf < 4 || area_of[label] < relative * area_of[largest])
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
    if (observer) {
      std::vector<typename boost::graph_traits<PM>::vertex_descriptor> vs;
      for (std::size_t i = offsets[c]; i < offsets[c + 1]; ++i)
        for (auto v : CGAL::vertices_around_face(halfedge(small[i], pm), pm)) vs.push_back(v);
      std::sort(vs.begin(), vs.end());
      vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
      observer->before(vs);  // nothing survives: no `after`
    }
    for (std::size_t i = offsets[c]; i < offsets[c + 1]; ++i)
      CGAL::Euler::remove_face(halfedge(small[i], pm), pm);
    ++r.components_removed;
    r.faces_removed += nf;
  }
  r.vertices_removed = nv - static_cast<std::size_t>(vertices(pm).size());
  return r;
}

}  // namespace clean_pipeline
}  // namespace internal

/// \ingroup mrepair_clean
/// removes the face-connected components of `pmesh` with fewer than
/// `min_component_faces` faces (RameshCleaner 3.2).
///
/// Components are found by queue-based region growing that stops as soon as a
/// component reaches the threshold (or meets a face known to be in a large
/// component), so the cost is linear in the mesh size whatever the threshold.
/// A component is removed only when it is also small next to the largest
/// component: fewer than `relative_component_size` times its faces and less
/// than that share of its area. The largest component is never removed (so a
/// non-empty mesh is never emptied, and two equal parts both stay).
///
/// \tparam PolygonMesh model of `MutableFaceGraph`
/// \param pmesh a valid polygon mesh
/// \param np optional:
///   - `min_component_faces` (std::size_t, default 400, the paper's tables):
///     components with fewer faces are removed
///   - `relative_component_size` (double in [0, 1], default 0.01): ... and
///     fewer faces and less area than this share of the largest component
///   - `open_debris_only` (bool, default false): remove only open components
///     next to a closed largest component, when they have fewer than 4 faces
///     or less than `relative_component_size` of its area (the stray facets
///     of a print model); the `cad` profile of `clean_scan_mesh()` uses this
///   - `vertex_point_map` (default: internal point map), for the areas
///   - `visitor` (default `Default_visitor`): phase "remove_small_components";
///     `stop_requested()` polled before any change
/// \return `Small_components_result`; `status` is `ok`, `cancelled` or
///   `invalid_parameter` (threshold 0, share outside [0, 1]); `pmesh` stays valid
template <typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Small_components_result remove_small_components(
    PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values())
{
  internal::Visitor_handle<NamedParameters> visitor(np);
  internal::Phase_scope<internal::Visitor_handle<NamedParameters>> phase(
      visitor, "remove_small_components");
  const std::size_t threshold =
      internal::get_or(np, internal_np::min_component_faces, std::size_t(400));
  const double relative = internal::get_or(np, internal_np::relative_component_size, 0.01);
  const bool debris = internal::get_or(np, internal_np::open_debris_only, false);
  auto vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_property_map(CGAL::vertex_point, pmesh));
  Small_components_result r;
  if (threshold == 0 || !(relative >= 0. && relative <= 1.)) {
    r.status = Status::invalid_parameter;
    return r;
  }
  if (visitor.stop_requested()) {
    r.status = Status::cancelled;
    return r;
  }
  r = internal::clean_pipeline::remove_small_components_seeded(
      pmesh, vpm, faces(pmesh), threshold, relative, internal::clean_pipeline::edit_observer(np),
      static_cast<const std::nullptr_t*>(nullptr), debris);
  visitor.progress(1.);
  return r;
}

}  // namespace mrepair

#endif  // MREPAIR_REMOVE_SMALL_COMPONENTS_H
