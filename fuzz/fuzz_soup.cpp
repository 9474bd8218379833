// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: inspect_polygon_soup and the soup-to-manifold calls of
// stitch_soup.h on decoded soups (see fuzz_soup.h).
#include "fuzz_main.h"
#include "fuzz_soup.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  mrepair_fuzz::report_violation(mrepair_fuzz::run_soup(data, size));
  return 0;
}
