// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The options of `mrepair repair` and their checks, shared by `repair`
// (cmd_repair.cpp) and `batch` (cmd_batch.cpp), which validates them once up
// front with this same code and hands them to each `repair` child unchanged.
// No CGAL here: the batch's translation unit stays light.
#ifndef MREPAIR_TOOLS_REPAIR_OPTIONS_H
#define MREPAIR_TOOLS_REPAIR_OPTIONS_H

#include "cli.h"

#include <mrepair/input_classification.h>

#include <optional>
#include <string>
#include <vector>

namespace mrepair {
namespace cli {

/// the options of `mrepair repair` (the common ones, `--report` etc., apart).
inline const std::vector<Option>& repair_options()
{
  static const std::vector<Option> o = {
      {"profile", true, "auto|scan|cad: which cleaning steps apply (auto: decided from the mesh)"},
      {"close-gaps", true,
       "close boundary gaps narrower than T (model units; 0: off; default: a tolerance derived from "
       "the input on CAD exports and print models, none on scans)"},
      {"merge-epsilon", true, "merge soup points closer than E before stitching (0)"},
      {"spike-angle", true, "dihedral angle (degrees) of a spiked vertex (relax_spikes default)"},
      {"max-hole", true, "holes with fewer boundary vertices are filled (100 scan, 500 cad)"},
      {"min-component", true, "components with fewer faces are removed (400)"},
      {"iterations", true, "cleaning iteration cap (5)"},
      {"no-self-intersections", false, "do not count self-intersections in the inspection of the output"},
      {"input-self-intersections", false,
       "count self-intersections in the inspection of the input too (off: 1.9 s of a 6.8 s job at 1M faces)"},
      {"keep-shells-separate", false, "do not merge overlapping closed shells into their union"},
      {"no-resolve-intersections", false, "leave crossings as the cleaning left them (no solid repair)"},
      {"binary", false, "write a binary file (PLY, STL; default: the input's encoding for its own format, binary for another)"},
      {"ascii", false, "write an ASCII file"}};
  return o;
}

/// the values of the options of `repair` that take one, as the library gets
/// them: an empty optional is an absent parameter (the library's default).
struct Repair_option_values
{
  std::optional<double> gap, merge, spike;
  std::optional<std::size_t> max_hole, min_component, iterations;
  std::optional<Input_profile> profile;
};

/// reads and checks the options of `repair` in `a`; throws `Usage_error`.
inline Repair_option_values parse_repair_options(const Arguments& a)
{
  Repair_option_values v;
  v.gap = a.optional_double("close-gaps");
  v.merge = a.optional_double("merge-epsilon");
  v.spike = a.optional_double("spike-angle");
  if (v.gap.value_or(0.) < 0. || v.merge.value_or(0.) < 0.)
    throw Usage_error("--close-gaps and --merge-epsilon must be >= 0");
  v.max_hole = a.optional_count("max-hole", 1);
  v.min_component = a.optional_count("min-component", 1);
  v.iterations = a.optional_count("iterations", 0);
  if (a.has("profile")) {
    Input_profile p;
    if (!parse_input_profile(a.get("profile"), p))
      throw Usage_error("--profile must be auto, scan or cad");
    v.profile = p;
  }
  return v;
}

/// the options of `repair` given in `a`, as arguments again (`--name [VALUE]`),
/// in the order of `repair_options()`.
inline std::vector<std::string> repair_arguments(const Arguments& a)
{
  std::vector<std::string> out;
  for (const Option& o : repair_options()) {
    if (!a.has(o.name)) continue;
    out.push_back("--" + o.name);
    if (o.takes_value) out.push_back(a.get(o.name));
  }
  return out;
}

} // namespace cli
} // namespace mrepair

#endif // MREPAIR_TOOLS_REPAIR_OPTIONS_H
