// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INSPECT_H
#define MREPAIR_INSPECT_H

#include <mrepair/inspection_report.h>
#include <mrepair/internal/bounded_walks.h>
#include <mrepair/internal/inspect/analysis.h>
#include <mrepair/internal/inspect/finish.h>
#include <mrepair/internal/inspect/mesh_arrays.h>
#include <mrepair/internal/inspect/surface_arrays.h>
#include <mrepair/internal/clean_scan_mesh/spike_criterion.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/tags.h>

#include <cmath>
#include <string>
#include <vector>

/// \file inspect.h
/// Counts the defects mrepair repairs and a few quality figures, on a polygon
/// soup or on a polygon mesh. The definitions are in `doc/defects.md`.
///
/// Both functions flatten the input into index arrays, then run each count as
/// a loop over vertices, faces or edges (parallel with TBB), in linear time
/// except for the self-intersection test (a uniform grid of face boxes, then
/// CGAL's exact predicates with the semantics of `PMP::self_intersections`,
/// parallel) and the T-junction search (an AABB tree of boundary edges).

namespace mrepair {

namespace internal {

// Reads the thresholds of a pack over their defaults (Inspect_thresholds,
// from definitions.h); returns false (and a message) when one is out of range.
template <typename NamedParameters>
bool read_inspect_thresholds(const NamedParameters& np, Inspect_thresholds& t, std::string& msg)
{
  t.spike_angle = get_or<double>(np, internal_np::spike_angle, t.spike_angle);
  t.spike_height_factor = get_or<double>(np, internal_np::spike_height_factor, t.spike_height_factor);
  t.zero_edge_factor = get_or<double>(np, internal_np::zero_edge_factor, t.zero_edge_factor);
  t.skinny_edge_factor = get_or<double>(np, internal_np::skinny_edge_factor, t.skinny_edge_factor);
  t.skinny_angle = get_or<double>(np, internal_np::skinny_angle, t.skinny_angle);
  t.small_angle = get_or<double>(np, internal_np::inspect_small_angle, t.small_angle);
  t.max_hole_vertices = get_or<std::size_t>(np, internal_np::max_hole_vertices, t.max_hole_vertices);
  t.min_component_faces =
      get_or<std::size_t>(np, internal_np::min_component_faces, t.min_component_faces);
  t.t_junction_tolerance = get_or<double>(np, internal_np::t_junction_tolerance, t.t_junction_tolerance);
  auto bad = [&](const char* what) {
    msg = std::string("parameter out of range: ") + what;
    return false;
  };
  if (!(t.spike_angle >= 0 && t.spike_angle <= 180)) return bad("spike_angle (degrees, 0..180)");
  if (!std::isfinite(t.spike_height_factor)) return bad("spike_height_factor (finite)");
  if (!(t.zero_edge_factor >= 0) || !std::isfinite(t.zero_edge_factor)) return bad("zero_edge_factor");
  if (!(t.skinny_edge_factor >= 0) || !std::isfinite(t.skinny_edge_factor))
    return bad("skinny_edge_factor");
  if (!(t.skinny_angle >= 0 && t.skinny_angle <= 180)) return bad("skinny_angle (degrees, 0..180)");
  if (!(t.small_angle >= 0 && t.small_angle <= 180)) return bad("inspect_small_angle (degrees)");
  if (std::isnan(t.t_junction_tolerance) || std::isinf(t.t_junction_tolerance))
    return bad("t_junction_tolerance");
  return true;
}

// Both entry points: thresholds read and copied into the report, or the
// report says invalid_parameter.
template <typename NamedParameters>
bool start_inspection(const NamedParameters& np, Inspect_thresholds& t, Inspection_report& r)
{
  if (!read_inspect_thresholds(np, t, r.message)) {
    r.status = Status::invalid_parameter;
    return false;
  }
  copy_thresholds(t, r);
  return true;
}

// inspect_polygon_soup(), listing the defects into `sink` when it is not null
// (locate_defects.h).
template <typename PointRange, typename PolygonRange, typename NamedParameters>
Inspection_report inspect_soup(const PointRange& points, const PolygonRange& polygons,
                               const NamedParameters& np, Defect_locations* sink)
{
  Inspection_report r;
  r.from_mesh = false;
  Inspect_thresholds t;
  if (!start_inspection(np, t, r)) return r;
  Visitor_handle<NamedParameters> visitor(np);
  Surface_arrays a;
  {
    Phase_scope<decltype(visitor)> phase(visitor, "inspect: topology");
    if (!build_soup_arrays(points, polygons, a, r.invalid_polygons)) {
      r.status = Status::invalid_parameter;
      r.message = "soup too large (more than 2^32 - 1 points or corners)";
      return r;
    }
  }
  Phase_scope<decltype(visitor)> phase(visitor, "inspect: geometry");
  Surface_analysis analysis(a, t, r);
  analysis.set_sink(sink);
  analysis.run(nullptr);
  const bool count_si = get_or<bool>(np, internal_np::count_self_intersections, true);
  count_self_intersections(a, analysis, count_si, visitor, r);
  finish_status(r, analysis.non_finite_referenced);
  return r;
}

// inspect(), listing the defects into `sink` when it is not null.
template <typename PolygonMesh, typename NamedParameters>
Inspection_report inspect_mesh(const PolygonMesh& pmesh, const NamedParameters& np, Defect_locations* sink)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  Inspection_report r;
  r.from_mesh = true;
  Inspect_thresholds t;
  if (!start_inspection(np, t, r)) return r;
  const bool count_si = get_or<bool>(np, internal_np::count_self_intersections, true);
  auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                              get_const_property_map(CGAL::vertex_point, pmesh));
  Visitor_handle<NamedParameters> visitor(np);
  // every count below walks faces and vertices: a broken structure is
  // reported, not walked (bounded_walks.h)
  if (std::string broken = halfedge_structure_defect(pmesh); !broken.empty()) {
    r.status = Status::invalid_mesh;
    r.message = "inspect: the mesh's halfedge structure is broken: " + broken;
    return r;
  }
  Surface_arrays a;
  std::vector<std::size_t> loops;
  std::vector<std::vector<Inspect_index>> cycle_vertices;  // with a sink
  {
    Phase_scope<decltype(visitor)> phase(visitor, "inspect: topology");
    const Status built = build_mesh_arrays(pmesh, vpm, a, loops, sink ? &cycle_vertices : nullptr);
    if (built != Status::ok) {
      r.status = built;
      r.message = built == Status::invalid_mesh ? walk_bound_message("inspect: the border cycles")
                                                : "mesh too large (more than 2^32 - 1 elements)";
      return r;
    }
  }
  std::size_t non_finite_referenced = 0;
  {
    Phase_scope<decltype(visitor)> phase(visitor, "inspect: geometry");
    Surface_analysis analysis(a, t, r);
    analysis.set_sink(sink, &cycle_vertices);
    analysis.run(&loops);
    free_memory(cycle_vertices);
    non_finite_referenced = analysis.non_finite_referenced;
    free_memory(loops);
    count_self_intersections(a, analysis, count_si, visitor, r);
  }
  finish_status(r, non_finite_referenced);
  return r;
}

} // namespace internal

/// \ingroup mrepair_inspect
/// counts the defects of a polygon soup and its quality figures (see
/// `doc/defects.md`): validity of the polygons, non-finite, isolated and
/// duplicate points, degenerate and duplicate polygons, non-manifold edges
/// (more than two polygons) and vertices (several fans), edges used twice in
/// the same direction (inconsistent orientation), boundary edges and loops,
/// small holes, components, near-degenerate triangles, spiked vertices,
/// T-junctions, closedness, angles, valences, edge lengths, area and volume.
/// Self-intersecting pairs are counted as in `inspect()`, polygons sharing an
/// edge being those that share an undirected edge.
///
/// \tparam PointRange random-access range of points with `x()`, `y()`, `z()`
/// \tparam PolygonRange range of ranges of (signed or unsigned) integer indices
/// \param np optional, each as `mrepair::parameters::NAME(value)`:
///   - `spike_angle` (double, degrees, 100): dihedral angle above which an edge makes its ends spiked
///   - `spike_height_factor` (double, 2; 0 disables): an interior vertex farther than this many
///     mean link edge lengths from the plane of its link is spiked too (as in `relax_spikes()`)
///   - `zero_edge_factor` (double, 0.1): zero edge: length < factor x global mean edge length
///   - `skinny_edge_factor` (double, 0.25): skinny edge: length < factor x local mean edge length
///   - `skinny_angle` (double, degrees, 10): opposite angle below which a skinny edge counts
///   - `inspect_small_angle` (double, degrees, 30): `small_angle_share` counts angles below it
///   - `max_hole_vertices` (size_t, 100): a boundary loop with fewer edges is a small hole
///   - `min_component_faces` (size_t, 400): a component with fewer faces is small
///   - `t_junction_tolerance` (double, model units; default, or when negative: 1e-4 x bounding-box diagonal)
///   - `count_self_intersections` (bool, true): count self-intersecting pairs
///     (only when every polygon is a triangle with finite corners)
///   - `visitor` (`Default_visitor`): phases "inspect: topology", "inspect: geometry",
///     "inspect: self-intersections"
/// \return `Inspection_report`; `status` is `ok`, `empty_input`, `invalid_index`
///   (bad polygons left out and counted), `non_finite_input` or `invalid_parameter`.
template <typename PointRange, typename PolygonRange,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Inspection_report inspect_polygon_soup(const PointRange& points, const PolygonRange& polygons,
                                       const NamedParameters& np = CGAL::parameters::default_values())
{
  return internal::inspect_soup(points, polygons, np, nullptr);
}

/// \ingroup mrepair_inspect
/// counts the defects of a polygon mesh and its quality figures (see
/// `doc/defects.md`). Same counts as `inspect_polygon_soup()` on the mesh's
/// faces, except that boundary loops are the border halfedge cycles.
/// Self-intersecting pairs are the pairs `PMP::self_intersections()` reports,
/// without the pairs (f, f) it uses for degenerate faces (counted in
/// `degenerate_faces`), computed by mrepair's own parallel broad phase.
/// In a halfedge mesh non-manifold edges, inconsistent orientations and
/// same-orientation duplicate faces cannot occur: they are 0.
///
/// \tparam PolygonMesh model of `FaceListGraph` (`Surface_mesh`, `Polyhedron_3`, ...)
/// \param np optional: the parameters of `inspect_polygon_soup()` and
///   - `vertex_point_map` (default: the internal point map of `pmesh`)
///   - `count_self_intersections` (bool, true): count self-intersecting pairs
///     (needs a triangle mesh with finite coordinates, else not counted)
/// \pre `CGAL::is_valid_polygon_mesh(pmesh)`
/// \return `Inspection_report`; `status` is `ok`, `empty_input`, `non_finite_input`,
///   `invalid_parameter`, or `invalid_mesh` (a border cycle that does not close).
template <typename PolygonMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Inspection_report inspect(const PolygonMesh& pmesh,
                          const NamedParameters& np = CGAL::parameters::default_values())
{
  return internal::inspect_mesh(pmesh, np, nullptr);
}

} // namespace mrepair

#endif // MREPAIR_INSPECT_H
