// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INSPECTION_REPORT_H
#define MREPAIR_INSPECTION_REPORT_H

#include <mrepair/report.h>
#include <mrepair/status.h>

#include <cstddef>
#include <limits>
#include <string>

/// \file inspection_report.h
/// The result of `mrepair::inspect()` and `mrepair::inspect_polygon_soup()`
/// (see `inspect.h`). Every count is defined precisely in `doc/defects.md`.

namespace mrepair {

/// \ingroup mrepair_inspect
/// defect counts and quality figures of a polygon soup or polygon mesh.
/// Angles are in degrees, lengths in model units. A figure that cannot be
/// computed (no triangle, not closed, ...) is NaN, printed as `null` in JSON.
struct Inspection_report
{
  /// `ok`; `empty_input` (no point or no usable face); `invalid_index` (soup
  /// polygons with an out-of-range/negative index or fewer than 3 vertices,
  /// counted in `invalid_polygons` and left out of every other figure);
  /// `non_finite_input` (NaN/inf coordinates: faces touching them are left
  /// out of the geometric figures, self-intersections are not computed);
  /// `invalid_parameter`. All figures are filled in every case but
  /// `invalid_parameter`.
  Status status = Status::ok;
  std::string message;
  bool from_mesh = false;  ///< filled by `inspect(mesh)` (else by the soup version)

  // ---- sizes ----------------------------------------------------------------
  std::size_t vertices = 0;          ///< points (soup) or vertices (mesh)
  std::size_t faces = 0;             ///< usable polygons / faces
  std::size_t edges = 0;             ///< distinct undirected edges of those faces
  std::size_t triangles = 0;         ///< faces with 3 vertices
  std::size_t invalid_polygons = 0;  ///< soup only: bad index or < 3 vertices

  // ---- defects ----------------------------------------------------------------
  std::size_t non_finite_vertices = 0;
  std::size_t isolated_vertices = 0;
  std::size_t duplicate_points = 0;               ///< points beyond the first at a location
  std::size_t degenerate_faces = 0;               ///< repeated index or collinear
  std::size_t repeated_index_faces = 0;           ///< part of `degenerate_faces`
  std::size_t duplicate_faces = 0;                ///< same vertex set as an earlier face
  std::size_t duplicate_faces_opposite = 0;       ///< part of it: reversed cyclic order
  std::size_t non_manifold_edges = 0;             ///< more than two incident faces
  std::size_t non_manifold_vertices = 0;          ///< incident faces form several fans
  std::size_t inconsistent_orientation_edges = 0; ///< two faces, same direction
  std::size_t boundary_edges = 0;
  std::size_t boundary_loops = 0;
  std::size_t small_holes = 0;                    ///< loops with < max_hole_vertices edges
  std::size_t connected_components = 0;
  std::size_t small_components = 0;              ///< < min_component_faces faces
  std::size_t near_degenerate_faces = 0;          ///< RameshCleaner 3.6, per face
  std::size_t collapsible_edges = 0;              ///< RameshCleaner 3.6, per edge
  std::size_t spiked_vertices = 0;
  double max_dihedral_angle = std::numeric_limits<double>::quiet_NaN();
  bool self_intersections_counted = false;
  std::size_t self_intersecting_pairs = 0;        ///< pairs of distinct faces
  /// of those, the pairs that only touch at coincident vertices of their own
  /// (the copies of a split non-manifold vertex, unmerged duplicate points)
  std::size_t self_intersecting_pairs_touching = 0;
  std::size_t t_junctions = 0;                    ///< boundary vertices on another boundary edge
  bool closed = false;

  // ---- quality figures ----------------------------------------------------------
  double min_angle = std::numeric_limits<double>::quiet_NaN();
  double small_angle_share = std::numeric_limits<double>::quiet_NaN(); ///< share of angles < small_angle
  double mean_valence_deviation = std::numeric_limits<double>::quiet_NaN();
  double edge_length_mean = std::numeric_limits<double>::quiet_NaN();
  double edge_length_stddev = std::numeric_limits<double>::quiet_NaN();
  double area = 0;
  double volume = std::numeric_limits<double>::quiet_NaN();  ///< closed, oriented only

  // ---- thresholds used (after defaults were resolved) -----------------------------
  double spike_angle = 0;
  double spike_height_factor = 0;
  double zero_edge_factor = 0;
  double skinny_edge_factor = 0;
  double skinny_angle = 0;
  double small_angle = 0;
  std::size_t max_hole_vertices = 0;
  std::size_t min_component_faces = 0;
  double t_junction_tolerance = 0;

  /// `true` when no defect is counted (quality figures are not defects).
  bool is_clean() const
  {
    return invalid_polygons == 0 && non_finite_vertices == 0 && isolated_vertices == 0 &&
           duplicate_points == 0 && degenerate_faces == 0 && duplicate_faces == 0 &&
           non_manifold_edges == 0 && non_manifold_vertices == 0 &&
           inconsistent_orientation_edges == 0 && small_holes == 0 && small_components == 0 &&
           near_degenerate_faces == 0 && spiked_vertices == 0 && self_intersecting_pairs == 0 &&
           t_junctions == 0;
  }

  /// writes the figures that say whether a soup is a clean mesh (the
  /// `before` and `after` sections of `mrepair soup`), flat.
  void to_summary_report(Report& r) const
  {
    r.add("vertices", vertices);
    r.add("faces", faces);
    r.add("invalid_polygons", invalid_polygons);
    r.add("non_finite_vertices", non_finite_vertices);
    r.add("duplicate_points", duplicate_points);
    r.add("degenerate_faces", degenerate_faces);
    r.add("duplicate_faces", duplicate_faces);
    r.add("non_manifold_edges", non_manifold_edges);
    r.add("non_manifold_vertices", non_manifold_vertices);
    r.add("inconsistent_orientation_edges", inconsistent_orientation_edges);
    r.add("boundary_edges", boundary_edges);
    r.add("connected_components", connected_components);
  }

  /// writes sections `input`, `defects`, `quality`, `thresholds`.
  void to_report(Report& r) const
  {
    r.add("status", status);
    if (!message.empty()) r.add("message", message);
    r.add("kind", from_mesh ? "mesh" : "soup");
    Report& in = r.section("input");
    in.add("vertices", vertices);
    in.add("faces", faces);
    in.add("edges", edges);
    in.add("triangles", triangles);
    Report& d = r.section("defects");
    d.add("invalid_polygons", invalid_polygons);
    d.add("non_finite_vertices", non_finite_vertices);
    d.add("isolated_vertices", isolated_vertices);
    d.add("duplicate_points", duplicate_points);
    d.add("degenerate_faces", degenerate_faces);
    d.add("repeated_index_faces", repeated_index_faces);
    d.add("duplicate_faces", duplicate_faces);
    d.add("duplicate_faces_opposite", duplicate_faces_opposite);
    d.add("non_manifold_edges", non_manifold_edges);
    d.add("non_manifold_vertices", non_manifold_vertices);
    d.add("inconsistent_orientation_edges", inconsistent_orientation_edges);
    d.add("boundary_edges", boundary_edges);
    d.add("boundary_loops", boundary_loops);
    d.add("small_holes", small_holes);
    d.add("connected_components", connected_components);
    d.add("small_components", small_components);
    d.add("near_degenerate_faces", near_degenerate_faces);
    d.add("collapsible_edges", collapsible_edges);
    d.add("spiked_vertices", spiked_vertices);
    if (self_intersections_counted) {
      d.add("self_intersecting_pairs", self_intersecting_pairs);
      d.add("self_intersecting_pairs_touching", self_intersecting_pairs_touching);
    } else {
      d.add("self_intersecting_pairs", "not computed");
      d.add("self_intersecting_pairs_touching", "not computed");
    }
    // no pair crosses: those left only touch at coincident vertices
    d.add("intersection_free", !self_intersections_counted ? "not computed"
                               : self_intersecting_pairs == self_intersecting_pairs_touching ? "yes"
                                                                                            : "no");
    d.add("t_junctions", t_junctions);
    d.add("closed", closed);
    Report& q = r.section("quality");
    q.add("min_angle", min_angle);
    q.add("small_angle_share", small_angle_share);
    q.add("max_dihedral_angle", max_dihedral_angle);
    q.add("mean_valence_deviation", mean_valence_deviation);
    q.add("edge_length_mean", edge_length_mean);
    q.add("edge_length_stddev", edge_length_stddev);
    q.add("area", area);
    q.add("volume", volume);
    Report& t = r.section("thresholds");
    t.add("spike_angle", spike_angle);
    t.add("spike_height_factor", spike_height_factor);
    t.add("zero_edge_factor", zero_edge_factor);
    t.add("skinny_edge_factor", skinny_edge_factor);
    t.add("skinny_angle", skinny_angle);
    t.add("small_angle", small_angle);
    t.add("max_hole_vertices", max_hole_vertices);
    t.add("min_component_faces", min_component_faces);
    t.add("t_junction_tolerance", t_junction_tolerance);
  }
};

} // namespace mrepair

#endif // MREPAIR_INSPECTION_REPORT_H
