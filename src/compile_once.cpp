// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The parts of the header-only library that cost the compiler most and take
// no template parameter, defined once for the project's own programs, tests
// and Python module (CMake option MREPAIR_COMPILE_ONCE): they include the
// headers with MREPAIR_SEPARATE_ARRANGEMENT defined, which then only declare
// them. A user's program can do the same: define MREPAIR_SEPARATE_ARRANGEMENT
// everywhere and compile this file (or its two lines) once.
//
// The winding-number arrangement (exact constructions, three projected
// constrained Delaunay triangulations): ~60 CPU-s of GCC 12 at -O3 in every
// translation unit that reaches resolve_intersections.h.
#ifndef MREPAIR_SEPARATE_ARRANGEMENT
#define MREPAIR_SEPARATE_ARRANGEMENT
#endif
#define MREPAIR_ARRANGEMENT_DEFINITION
#include <mrepair/internal/resolve_intersections/arrangement.h>
