// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_TRIANGULATE_POLYGONS_H
#define MREPAIR_TRIANGULATE_POLYGONS_H

/// \file triangulate_polygons.h
/// The first step of every call that needs triangles (gap closing, cleaning,
/// remeshing, the whole repair): CAD exports carry quads and n-gons.

#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/internal/utility.h>

#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/boost/graph/helpers.h>

#include <cstddef>
#include <string>

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
  bool complete = true;        ///< CGAL triangulated every polygon

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
/// triangulates the faces of `pmesh` with more than three sides
/// (`CGAL::Polygon_mesh_processing::triangulate_faces`); a triangle mesh is left untouched.
/// \tparam PolygonMesh model of `MutableFaceGraph`
/// \return `Triangulation_result`; status `invalid_mesh` when CGAL could not
///   triangulate a face (the mesh stays valid, with that face as it was)
template <typename PolygonMesh>
Triangulation_result triangulate_polygons(PolygonMesh& pmesh)
{
  Triangulation_result t;
  for (auto f : faces(pmesh))
    if (CGAL::halfedges_around_face(halfedge(f, pmesh), pmesh).size() != 3) ++t.polygons;
  t.faces_before = t.faces_after = internal::face_count(pmesh);
  if (t.polygons == 0) return t;
  t.complete = CGAL::Polygon_mesh_processing::triangulate_faces(pmesh);
  t.faces_after = internal::face_count(pmesh);
  if (!t.complete || !CGAL::is_triangle_mesh(pmesh)) {
    t.status = Status::invalid_mesh;
    t.message = "some of the " + std::to_string(t.polygons) +
                " polygons with more than three sides could not be triangulated";
  }
  return t;
}

} // namespace mrepair

#endif // MREPAIR_TRIANGULATE_POLYGONS_H
