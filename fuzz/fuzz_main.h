// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The libFuzzer side of a target: a violated invariant is printed and aborts,
// so that libFuzzer saves the input as a crash.
#ifndef MREPAIR_FUZZ_MAIN_H
#define MREPAIR_FUZZ_MAIN_H

#include <cstdio>
#include <cstdlib>
#include <string>

namespace mrepair_fuzz {
inline void report_violation(const std::string& e)
{
  if (e.empty()) return;
  std::fprintf(stderr, "mrepair fuzz invariant violated: %s\n", e.c_str());
  std::abort();
}
} // namespace mrepair_fuzz

#endif // MREPAIR_FUZZ_MAIN_H
