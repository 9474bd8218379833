// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: close_gaps, clean_scan_mesh and remeshing on meshes built
// from decoded soups (see fuzz_mesh.h).
#include "fuzz_main.h"
#include "fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  mrepair_fuzz::report_violation(mrepair_fuzz::run_mesh(data, size));
  return 0;
}
