// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Uniform, adaptive, feature-preserving and partial remeshing of one mesh.
// usage: example_adaptive_remesh [INPUT.off]   (default: a built-in cube-ish sample)
#include <mrepair/adaptive_remesh.h>
#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <mrepair/triangulate_polygons.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <cmath>
#include <iostream>
#include <vector>

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
using Polyhedron = CGAL::Polyhedron_3<K>;
namespace MP = mrepair::parameters;

int main(int argc, char** argv)
{
  Mesh input;
  if (argc > 1) {
    mrepair::Io_result io = mrepair::read_polygon_mesh(argv[1], input);
    if (!mrepair::succeeded(io.status) || !CGAL::is_triangle_mesh(input)) {
      std::cerr << argv[1] << ": cannot read a triangle mesh (" << mrepair::to_string(io.status)
                << ")\n";
      return 1;
    }
  } else {  // a unit cube: six planar faces, twelve sharp edges
    CGAL::make_hexahedron(K::Point_3(0, 0, 0), K::Point_3(1, 0, 0), K::Point_3(1, 1, 0),
                          K::Point_3(0, 1, 0), K::Point_3(0, 1, 1), K::Point_3(0, 0, 1),
                          K::Point_3(1, 0, 1), K::Point_3(1, 1, 1), input);
    mrepair::triangulate_polygons(input);
  }
  CGAL::Bbox_3 b = CGAL::Polygon_mesh_processing::bbox(input);
  const double diag = std::sqrt(CGAL::square(b.xmax() - b.xmin()) +
                                CGAL::square(b.ymax() - b.ymin()) + CGAL::square(b.zmax() - b.zmin()));
  auto print = [](const char* what, const mrepair::Remeshing_result& r) {
    std::cout << what << ": " << mrepair::to_string(r.status) << ", " << r.faces_before
              << " -> " << r.faces_after << " faces, " << r.feature_edges << " feature edges, "
              << r.corners << " corners" << std::endl;
  };

  // 1. uniform, edges of 3% of the diagonal, sharp edges above 44 degrees kept
  Mesh uniform = input;
  auto r1 = mrepair::isotropic_remesh(uniform, 0.03 * diag);
  print("uniform", r1);

  // 2. adaptive: tolerance 0.05% of the diagonal, in parallel when TBB is there
  Mesh adaptive = input;
  auto r2 = mrepair::adaptive_remesh<CGAL::Parallel_if_available_tag>(
      adaptive, 0.0005 * diag, MP::remesh_max_edge_length(0.05 * diag).number_of_iterations(8));
  print("adaptive", r2);

  // 3. features from the user's edge map only (here the border edges; none on a
  //    closed input), no angle detection, protected
  Mesh featured = input;
  auto ecm = get(CGAL::dynamic_edge_property_t<bool>(), featured);
  for (auto e : edges(featured)) put(ecm, e, CGAL::is_border_edge(halfedge(e, featured), featured));
  auto r3 = mrepair::isotropic_remesh(
      featured, 0.05 * diag, CGAL::parameters::edge_is_constrained_map(ecm).protect_constraints(true));
  print("user edge map (border edges), protected", r3);

  // 4. a part of the uniform result, twice finer: the faces whose first vertex lies in
  //    the lower half; the rest is untouched (the part's border is never split, so
  //    a target near the border's edge length suits best)
  Polyhedron poly;
  CGAL::copy_face_graph(uniform, poly);
  std::vector<boost::graph_traits<Polyhedron>::face_descriptor> part;
  const double zmid = 0.5 * (b.zmin() + b.zmax());
  for (auto f : faces(poly))
    if (f->halfedge()->vertex()->point().z() < zmid) part.push_back(f);
  auto r4 = mrepair::isotropic_remesh(part, poly, 0.02 * diag);
  print("part (Polyhedron_3)", r4);

  bool ok = mrepair::succeeded(r1.status) && mrepair::succeeded(r2.status) &&
            mrepair::succeeded(r3.status) && mrepair::succeeded(r4.status);
  if (ok) mrepair::write_polygon_mesh("adaptive_remesh_out.off", adaptive);
  return ok ? 0 : 1;
}
