#!/usr/bin/env python3
# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""Times mrepair.repair(V, F) from Python against the same call in C++
(mrepair-time-repair: repair_polygon_soup on the same soup, same build flags),
alternating the two RUNS times, and prints each time and the medians.

    python3 compare_repair.py MESH TIME_REPAIR_PROGRAM [RUNS]

The Python time includes what the binding adds: copying the arrays in,
the visitor polling Ctrl-C, and the arrays and the report dict out.
"""

import statistics
import subprocess
import sys
import time

import mrepair


def main():
    path, program = sys.argv[1], sys.argv[2]
    runs = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    V, F = mrepair.read(path)
    python, cpp = [], []
    for _ in range(runs):
        out = subprocess.run([program, path], capture_output=True, text=True, check=True)
        cpp.append(float(out.stdout.split()[0]))
        start = time.perf_counter()
        V2, F2, report = mrepair.repair(V, F)
        python.append(time.perf_counter() - start)
        print(f"C++ {cpp[-1]:.3f} s ({out.stdout.split()[2]} faces)   "
              f"Python {python[-1]:.3f} s ({len(F2)} faces)", flush=True)
    c, p = statistics.median(cpp), statistics.median(python)
    print(f"median: C++ {c:.3f} s, Python {p:.3f} s, Python / C++ = {p / c:.3f}")


if __name__ == "__main__":
    main()
