// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Body of the soup fuzz target (fuzz_soup.cpp), shared with the regression test.
//   byte 0: options: bits 0-1 merge_epsilon (0, 1e-9, 1e-3, 0.6); bits 2-3
//           snap_epsilon (0, 1e-6, 1e-2, 0.75); bit 4 keep_two_sided; bit 5
//           orient_outward off; bit 6 also build a Polyhedron_3; bit 7 no
//           self-intersection count in the inspection. Soups of up to
//           max_repair_polygons polygons also go through the whole job
//           (`repair_polygon_soup`, issue 36: small soups that hung it),
//           with the option set of bits 0-1.
//   rest:   an encoded soup (fuzz_decode.h)
#ifndef MREPAIR_FUZZ_SOUP_H
#define MREPAIR_FUZZ_SOUP_H

#include "fuzz_check.h"

#include <mrepair/inspect.h>
#include <mrepair/io.h>
#include <mrepair/repair.h>
#include <mrepair/stitch_soup.h>

#include <optional>
#include <string>
#include <vector>

namespace mrepair_fuzz {

namespace MP = mrepair::parameters;

inline std::string check_soup_result(const mrepair::Soup_repair_result& r, std::size_t faces_out,
                                     const std::string& what)
{
  using mrepair::Status;
  if (r.status != Status::ok && r.status != Status::partial && r.status != Status::empty_input)
    return what + ": unexpected status " + mrepair::to_string(r.status);
  if (r.status == Status::empty_input) return {};
  if (r.faces_in != r.faces_out + r.faces_removed()) return what + ": faces_in != faces_out + faces_removed()";
  if (r.faces_out != faces_out) return what + ": faces_out differs from the output";
  return {};
}

template <class Mesh, class NP>
std::string soup_to_mesh(const std::vector<Point>& pts, const std::vector<Polygon>& polys, const NP& np,
                         const std::string& what)
{
  Mesh m;
  const mrepair::Soup_repair_result r = mrepair::polygon_soup_to_manifold_mesh(pts, polys, m, np);
  if (std::string e = check_soup_result(r, static_cast<std::size_t>(faces(m).size()), what); !e.empty())
    return e;
  return check_mesh(m, what, true);
}

// the whole job on a small soup: a valid mesh, a clear status, and a face
// accounting that reconciles when the job ran to its end.
constexpr std::size_t max_repair_polygons = 16;

// The four option sets small soups are repaired with (here and in
// test_small_soups.cpp): the defaults of `mrepair repair`, a scan, a given gap
// tolerance and merge distance, CAD without the automatic tolerance and
// with no component too small.
// `count_self_intersections` as given. An option left empty is absent: the
// library's default.
inline auto small_soup_repair_options(unsigned k, bool count_self_intersections = true)
{
  namespace MP = mrepair::parameters;
  std::optional<mrepair::Input_profile> profile;
  std::optional<double> gap, merge;
  std::optional<std::size_t> min_component;
  bool automatic_gap = true;
  switch (k % 4) {
    case 1: profile = mrepair::Input_profile::scan; break;
    case 2:
      gap = 0.3;
      merge = 1e-6;
      break;
    case 3:
      profile = mrepair::Input_profile::cad;
      automatic_gap = false;
      min_component = 1;
      break;
    default: break;
  }
  return MP::input_profile(
      profile, MP::gap_tolerance(
                   gap, MP::merge_epsilon(
                            merge, MP::automatic_gap_tolerance(
                                       automatic_gap, MP::min_component_faces(
                                                          min_component, MP::count_self_intersections(
                                                                             count_self_intersections))))));
}

template <class Mesh>
std::string repair_soup(std::vector<Point> pts, std::vector<Polygon> polys, std::uint8_t opt,
                        const std::string& what)
{
  using mrepair::Status;
  Mesh m;
  const mrepair::Repair_result r =
      mrepair::repair_polygon_soup(pts, polys, m, small_soup_repair_options(opt & 3, (opt & 128) == 0));
  if (std::string e = check_mesh(m, what, true, false); !e.empty()) return e;
  if (r.status == Status::empty_input) return faces(m).empty() ? std::string() : what + ": empty_input with faces";
  if (!r.failed_stage.empty()) {
    if (r.message.empty()) return what + ": stage " + r.failed_stage + " failed without a message";
    return {};
  }
  if (!mrepair::succeeded(r.status)) return what + ": unexpected status " + mrepair::to_string(r.status);
  if (!r.faces_reconcile()) return what + ": the face accounting does not reconcile";
  return {};
}

inline std::string run_soup(const std::uint8_t* data, std::size_t size)
{
  using mrepair::Status;
  Byte_reader in(data, size);
  const std::uint8_t opt = in.byte();
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  decode_soup(in, pts, polys);

  const mrepair::Inspection_report ir =
      mrepair::inspect_polygon_soup(pts, polys, MP::count_self_intersections((opt & 128) == 0));
  if (ir.status != Status::ok && ir.status != Status::empty_input && ir.status != Status::invalid_index &&
      ir.status != Status::non_finite_input)
    return std::string("inspect_polygon_soup: unexpected status ") + mrepair::to_string(ir.status);

  static const double merge[4] = {0, 1e-9, 1e-3, 0.6};
  static const double snap[4] = {0, 1e-6, 1e-2, 0.75};
  const auto np = MP::merge_epsilon(merge[opt & 3],
                  MP::snap_epsilon(snap[(opt >> 2) & 3],
                  MP::keep_two_sided((opt & 16) != 0,
                  MP::orient_outward((opt & 32) == 0))));
  if (std::string e = soup_to_mesh<Surface_mesh>(pts, polys, np, "polygon_soup_to_manifold_mesh"); !e.empty())
    return e;
  if (opt & 64)
    if (std::string e = soup_to_mesh<Polyhedron>(pts, polys, np, "polygon_soup_to_manifold_mesh (Polyhedron_3)");
        !e.empty())
      return e;

  if (polys.size() <= max_repair_polygons) {
    if (std::string e = repair_soup<Surface_mesh>(pts, polys, opt, "repair_polygon_soup"); !e.empty()) return e;
    if (opt & 64)
      if (std::string e = repair_soup<Polyhedron>(pts, polys, opt, "repair_polygon_soup (Polyhedron_3)"); !e.empty())
        return e;
  }

  // the in-place soup version: a valid polygon mesh soup of finite points
  std::vector<Point> p2 = pts;
  std::vector<Polygon> q2 = polys;
  const mrepair::Soup_repair_result r2 = mrepair::repair_polygon_soup_to_manifold(p2, q2, np);
  if (std::string e = check_soup_result(r2, q2.size(), "repair_polygon_soup_to_manifold"); !e.empty()) return e;
  if (mrepair::succeeded(r2.status)) {
    for (const Point& p : p2)
      if (!finite(p)) return "repair_polygon_soup_to_manifold: non-finite point in the output";
    std::string why;
    if (!q2.empty() && !mrepair::is_polygon_soup_a_polygon_mesh(q2, p2.size(), &why))
      return "repair_polygon_soup_to_manifold: output is not a polygon mesh (" + why + ")";
  }
  return {};
}

} // namespace mrepair_fuzz

#endif // MREPAIR_FUZZ_SOUP_H
