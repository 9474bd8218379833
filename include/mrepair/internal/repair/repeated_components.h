// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Components that only repeat the faces of other components: a sheet written
// twice, once in each orientation, with its own copy of every point (CGAL's
// non_manifold.off). A mesh file like that reads as a valid mesh, so the soup
// stage, which would drop the second copy of each face, never sees it, and
// the two layers cross each other everywhere. Such a component holds no
// point of its own: removing it loses nothing.
#ifndef MREPAIR_INTERNAL_REPAIR_REPEATED_COMPONENTS_H
#define MREPAIR_INTERNAL_REPAIR_REPEATED_COMPONENTS_H

#include <mrepair/internal/utility.h>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <numeric>
#include <vector>

namespace mrepair {
namespace internal {

/// removes the connected components every face of which has a twin (the
/// same three positions, in either orientation) in another component that is
/// kept: smallest components first, so that of two copies the larger (or,
/// of equal ones, the first) stays. Returns the number of faces removed.
/// A triangle mesh; other faces make no twins. O(F log F).
template <class PolygonMesh, class VertexPointMap>
std::size_t remove_repeated_components(PolygonMesh& pm, const VertexPointMap& vpm)
{
  using GT = boost::graph_traits<PolygonMesh>;
  using face_descriptor = typename GT::face_descriptor;
  namespace PMP = CGAL::Polygon_mesh_processing;
  auto component = get(CGAL::dynamic_face_property_t<std::size_t>(), pm);
  const std::size_t nc = PMP::connected_components(pm, component);
  if (nc < 2) return 0;
  struct Face_key
  {
    std::array<Vec3, 3> corners;  // sorted
    std::size_t component;
  };
  std::vector<Face_key> keys;
  keys.reserve(face_count(pm));
  std::vector<std::size_t> size(nc, 0);
  for (face_descriptor f : faces(pm)) {
    const std::size_t c = get(component, f);
    ++size[c];
    Face_key k{{}, c};
    std::size_t n = 0;
    for (auto h : CGAL::halfedges_around_face(halfedge(f, pm), pm)) {
      if (n == 3) {
        n = 4;
        break;
      }
      k.corners[n++] = to_vec3(get(vpm, target(h, pm)));
    }
    if (n != 3) continue;
    std::sort(k.corners.begin(), k.corners.end());
    keys.push_back(k);
  }
  std::sort(keys.begin(), keys.end(), [](const Face_key& a, const Face_key& b) {
    return a.corners != b.corners ? a.corners < b.corners : a.component < b.component;
  });
  // the faces of each component, as runs of equal corners (groups)
  std::vector<std::size_t> group_start;  // group g: keys[group_start[g], group_start[g + 1])
  std::vector<std::vector<std::size_t>> groups_of(nc);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i == 0 || keys[i].corners != keys[i - 1].corners) group_start.push_back(i);
    groups_of[keys[i].component].push_back(group_start.size() - 1);
  }
  group_start.push_back(keys.size());
  std::vector<std::size_t> order(nc);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return size[a] != size[b] ? size[a] < size[b] : a > b;
  });
  std::vector<char> removed(nc, 0);
  std::vector<std::size_t> to_remove;
  std::size_t faces_removed = 0;
  for (std::size_t c : order) {
    // a face that is not a triangle has no key: the component stays
    if (groups_of[c].empty() || groups_of[c].size() != size[c]) continue;
    bool repeated = true;
    for (std::size_t g : groups_of[c]) {
      bool twin = false;
      for (std::size_t i = group_start[g]; i < group_start[g + 1] && !twin; ++i)
        twin = keys[i].component != c && !removed[keys[i].component];
      if (!twin) {
        repeated = false;
        break;
      }
    }
    if (!repeated) continue;
    removed[c] = 1;
    to_remove.push_back(c);
    faces_removed += size[c];
  }
  if (!to_remove.empty()) PMP::remove_connected_components(pm, to_remove, component);
  return faces_removed;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_REPAIR_REPEATED_COMPONENTS_H
