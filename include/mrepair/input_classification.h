// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INPUT_CLASSIFICATION_H
#define MREPAIR_INPUT_CLASSIFICATION_H

#include <mrepair/report.h>

#include <cstddef>
#include <string>

/// \file input_classification.h
/// The input profiles and what `classify_input()` (input_profile.h) measured.

namespace mrepair {

/// \ingroup mrepair_clean
/// what kind of input a repair treats.
enum class Input_profile {
  automatic,  ///< decided by `classify_input()`
  scan,       ///< dense scan: every RameshCleaner step
  cad         ///< CAD export, print model, small patch: keep the geometry, fix validity, fill holes
};

inline const char* to_string(Input_profile p)
{
  switch (p) {
    case Input_profile::automatic: return "auto";
    case Input_profile::scan: return "scan";
    case Input_profile::cad: return "cad";
  }
  return "unknown";
}

/// parses "auto", "scan" or "cad"; false when unknown.
inline bool parse_input_profile(const std::string& s, Input_profile& out)
{
  if (s == "auto" || s == "automatic") out = Input_profile::automatic;
  else if (s == "scan") out = Input_profile::scan;
  else if (s == "cad") out = Input_profile::cad;
  else return false;
  return true;
}

/// \ingroup mrepair_clean
/// the decision of `classify_input()` and the measures behind it.
struct Input_classification
{
  Input_profile profile = Input_profile::cad;
  bool chosen_by_user = false;      ///< the caller fixed the profile; no measure decided
  std::string reason;               ///< one line a user can read
  std::size_t faces = 0;
  double edge_length_cv = 0;        ///< standard deviation / mean of the edge lengths
  double coplanar_edge_share = 0;   ///< interior edges whose faces are coplanar (< 0.01 degree)
  double skinny_face_share = 0;     ///< triangles with an angle under 5 degrees

  void to_report(Report& r) const
  {
    r.add("profile", to_string(profile));
    r.add("chosen_by", chosen_by_user ? "user" : "auto");
    r.add("reason", reason);
    r.add("faces", faces);
    r.add("edge_length_cv", edge_length_cv);
    r.add("coplanar_edge_share", coplanar_edge_share);
    r.add("skinny_face_share", skinny_face_share);
  }
};

}  // namespace mrepair

#endif  // MREPAIR_INPUT_CLASSIFICATION_H
