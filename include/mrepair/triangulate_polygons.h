// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_TRIANGULATE_POLYGONS_H
#define MREPAIR_TRIANGULATE_POLYGONS_H

/// \file triangulate_polygons.h
/// The first step of every call that needs triangles (gap closing, cleaning,
/// remeshing, the whole repair): CAD exports carry quads and n-gons.

#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/polygon_triangulation.h>
#include <mrepair/internal/utility.h>

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <cstddef>
#include <string>
#include <vector>

namespace mrepair {

/// \ingroup mrepair_core
/// what `triangulate_polygons()` did.
struct Triangulation_result
{
  Status status = Status::ok;  ///< `ok`, or `invalid_mesh` when a face could not be triangulated
  std::string message;         ///< why the status is not `ok`
  std::size_t polygons = 0;    ///< faces with more than three sides
  std::size_t faces_before = 0;
  std::size_t faces_after = 0;
  bool complete = true;        ///< every polygon was triangulated

  /// writes the counters (the commands add this section only when `polygons > 0`).
  void to_report(Report& r) const
  {
    r.add("polygons", polygons);
    r.add("faces_before", faces_before);
    r.add("faces_after", faces_after);
    r.add("complete", complete);
  }
};

/// \ingroup mrepair_core
/// triangulates the faces of `pmesh` with more than three sides by ear
/// clipping, one `CGAL::Euler::split_face` per cut (see
/// internal/polygon_triangulation.h: CGAL 5.5's `triangulate_faces` left an
/// invalid structure on a non-planar pentagon); a triangle mesh is left untouched.
/// A cut never joins a vertex to itself nor doubles an existing edge: a face
/// that cannot be finished that way keeps its last polygon (status
/// `invalid_mesh`, `complete` false), and the mesh stays valid either way.
/// \tparam PolygonMesh model of `MutableFaceGraph`
/// \return `Triangulation_result`; status `invalid_mesh` when the mesh's
///   halfedge structure is broken (nothing is changed) or a face could not be
///   triangulated
template <typename PolygonMesh>
Triangulation_result triangulate_polygons(PolygonMesh& pmesh)
{
  using GT = boost::graph_traits<PolygonMesh>;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  Triangulation_result t;
  t.faces_before = t.faces_after = internal::face_count(pmesh);
  if (std::string why = internal::halfedge_structure_defect(pmesh); !why.empty()) {
    t.status = Status::invalid_mesh;
    t.complete = false;
    t.message = "triangulate_polygons: the mesh's halfedge structure is broken: " + why;
    return t;
  }
  std::vector<face_descriptor> polygons;
  for (face_descriptor f : faces(pmesh))
    if (next(next(next(halfedge(f, pmesh), pmesh), pmesh), pmesh) != halfedge(f, pmesh)) polygons.push_back(f);
  t.polygons = polygons.size();
  if (polygons.empty()) return t;
  const auto vpm = get(CGAL::vertex_point, pmesh);
  std::vector<halfedge_descriptor> in;  // per corner: the halfedge of the face left that ends there
  std::vector<vertex_descriptor> corner_vertex;
  std::vector<internal::Vec3> corner_point;
  std::size_t unfinished = 0;
  for (face_descriptor f : polygons) {
    in.clear();
    corner_vertex.clear();
    corner_point.clear();
    for (halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, pmesh), pmesh)) {
      in.push_back(h);
      corner_vertex.push_back(target(h, pmesh));
      corner_point.push_back(internal::to_vec3(get(vpm, target(h, pmesh))));
    }
    const std::size_t cuts = in.size() - 3;
    std::size_t made = 0;
    const bool done = internal::clip_ears(
        corner_point, corner_vertex,
        [&](std::size_t a, std::size_t c) {
          return corner_vertex[a] != corner_vertex[c] &&
                 !halfedge(corner_vertex[a], corner_vertex[c], pmesh).second;
        },
        [&](std::size_t a, std::size_t, std::size_t c) {
          if (made++ == cuts) return;  // the last triangle is the face left
          // the new halfedge c -> a follows b -> c (the triangle); a -> c is the face left
          const halfedge_descriptor ca = CGAL::Euler::split_face(in[c], in[a], pmesh);
          in[c] = opposite(ca, pmesh);
        });
    if (!done) ++unfinished;
  }
  t.faces_after = internal::face_count(pmesh);
  if (unfinished > 0) {
    t.complete = false;
    t.status = Status::invalid_mesh;
    t.message = std::to_string(unfinished) + " of the " + std::to_string(t.polygons) +
                " polygons with more than three sides could not be triangulated without doubling an edge";
  }
  return t;
}

} // namespace mrepair

#endif // MREPAIR_TRIANGULATE_POLYGONS_H
