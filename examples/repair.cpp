// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The whole repair job of `mrepair repair` from C++: a polygon soup in, a
// valid manifold triangle mesh out, the user's model kept, and a face
// accounting that says where every face went.
// usage: example_repair [INPUT [OUTPUT [OPTION=VALUE ...]]]
//   OPTION: profile=auto|scan|cad, close_gaps=T (0: off), max_hole=N,
//           min_component=N, keep_shells_separate=1
// Without INPUT: the bundled CAD sample (examples/data/sample_cad.off).
// An option not given is left out, so the library's default applies: this is
// how the command line and the Python module pass theirs.
#include <mrepair/io.h>
#include <mrepair/repair.h>

#include "example_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

using K = CGAL::Epick;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace MP = mrepair::parameters;

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : MREPAIR_SAMPLE_DIR "/sample_cad.off";
  // the options a user most often changes, absent unless given
  std::optional<mrepair::Input_profile> profile;
  std::optional<double> gap;
  std::optional<std::size_t> max_hole, min_component;
  bool keep_shells_separate = false;
  for (int i = 3; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::size_t eq = arg.find('=');
    const std::string key = arg.substr(0, eq), value = eq == std::string::npos ? "" : arg.substr(eq + 1);
    mrepair::Input_profile p;
    if (key == "profile" && mrepair::parse_input_profile(value, p))
      profile = p;
    else if (key == "close_gaps")
      gap = std::atof(value.c_str());
    else if (key == "max_hole")
      max_hole = std::size_t(std::atol(value.c_str()));
    else if (key == "min_component")
      min_component = std::size_t(std::atol(value.c_str()));
    else if (key == "keep_shells_separate")
      keep_shells_separate = value != "0";
    else {
      std::cerr << "unknown option " << arg << "\n";
      return 2;
    }
  }

  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  const mrepair::Io_result in = mrepair::read_polygon_soup(input, points, polygons);
  if (in.status != mrepair::Status::ok && in.status != mrepair::Status::non_finite_input) {
    std::cerr << "cannot read " << input << ": " << in.message << "\n";
    return 1;
  }

  // close_gaps=0 turns the gap closing off; without it a CAD export or print
  // model gets a tolerance derived from the input
  Mesh mesh;
  const mrepair::Repair_result r = mrepair::repair_polygon_soup(
      points, polygons, mesh,
      MP::input_profile(
          profile, MP::gap_tolerance(
                       gap, MP::automatic_gap_tolerance(
                                !gap, MP::max_hole_vertices(
                                          max_hole, MP::min_component_faces(
                                                        min_component, MP::merge_overlapping_shells(
                                                                           !keep_shells_separate)))))));
  std::cout << "status " << mrepair::to_string(r.status) << ", profile "
            << mrepair::to_string(r.clean.profile.profile) << " (" << r.clean.profile.reason << ")\n";
  if (!r.failed_stage.empty()) {
    std::cerr << r.message << "\n";  // the mesh is valid, but the job stopped at that stage
    return 1;
  }
  std::cout << "before: " << r.before.faces << " faces, " << r.before.boundary_loops
            << " boundary loops, " << r.before.non_manifold_edges << " non-manifold edges\n"
            << "after:  " << r.after.faces << " faces, " << r.after.boundary_loops
            << " boundary loops, " << r.after.non_manifold_edges << " non-manifold edges, "
            << (r.after.self_intersecting_pairs == r.after.self_intersecting_pairs_touching
                    ? "intersection-free"
                    : "crossing pairs left")
            << "\n";
  // every face in is out, or removed or added for a named reason
  std::cout << "faces: " << r.faces_in << " in, " << r.faces_out << " out\n";
  for (const auto& x : r.faces_removed)
    if (x.second) std::cout << "  removed " << x.second << " (" << x.first << ")\n";
  for (const auto& x : r.faces_added)
    if (x.second) std::cout << "  added   " << x.second << " (" << x.first << ")\n";
  std::cout << "  reconciles: " << (r.faces_reconcile() ? "yes" : "no") << "\n";

  if (argc > 2 && !write_mesh(argv[2], mesh)) return 1;
  return mrepair::succeeded(r.status) && r.faces_reconcile() ? 0 : 1;
}
