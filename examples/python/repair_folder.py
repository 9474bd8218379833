#!/usr/bin/env python3
# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""Repairs every mesh (OFF, OBJ, PLY, STL) of a folder with mrepair.repair,
writes each result next to the others in an output folder, and writes a CSV
with the defect counts of every mesh before and after.

    python3 repair_folder.py INPUT_FOLDER OUTPUT_FOLDER [--csv defects.csv] [--profile auto]

Shows a progress bar: tqdm's when it is installed, else a line per phase.
"""

import argparse
import csv
import sys
from pathlib import Path

import mrepair

EXTENSIONS = {".off", ".obj", ".ply", ".stl"}
# the defect counts of the report's "before" and "after" sections that go to the CSV
DEFECTS = [
    "non_finite_vertices", "isolated_vertices", "duplicate_points", "degenerate_faces",
    "duplicate_faces", "non_manifold_edges", "non_manifold_vertices",
    "inconsistent_orientation_edges", "boundary_loops", "small_holes", "connected_components",
    "small_components", "near_degenerate_faces", "spiked_vertices", "self_intersecting_pairs",
    "t_junctions",
]


class LineProgress:
    """the fallback without tqdm: one line per phase on stderr."""

    def __init__(self, name):
        self.name = name
        self.phase = None

    def __call__(self, phase, fraction):
        if phase != self.phase:
            self.phase = phase
            print(f"  {self.name}: {phase}", file=sys.stderr, flush=True)

    def close(self):
        pass


def progress_for(name):
    """a progress callable and its closer: a tqdm bar, or lines."""
    try:
        from tqdm import tqdm
    except ImportError:
        line = LineProgress(name)
        return line, line.close
    bar = tqdm(total=100, desc=name, leave=False, unit="%")
    return mrepair.progress_bar(bar), bar.close


def repair_folder(input_dir, output_dir, csv_path, profile="auto"):
    """repairs every mesh of `input_dir` into `output_dir`; returns the CSV rows."""
    output_dir.mkdir(parents=True, exist_ok=True)
    paths = sorted(p for p in input_dir.iterdir() if p.suffix.lower() in EXTENSIONS)
    fields = ["mesh", "status", "faces_before", "faces_after"]
    fields += [f"{d}_{when}" for d in DEFECTS for when in ("before", "after")]
    rows = []
    for path in paths:
        row = {"mesh": path.name}
        progress, close = progress_for(path.name)
        try:
            V, F = mrepair.read(path)
            V2, F2, report = mrepair.repair(V, F, profile=profile, progress=progress)
            mrepair.write(output_dir / path.name, V2, F2, binary=path.suffix.lower() in {".ply", ".stl"})
            row["status"] = report["clean"]["status"]
            row["faces_before"] = report["before"]["input"]["faces"]
            row["faces_after"] = report["after"]["input"]["faces"]
            for when in ("before", "after"):
                for d in DEFECTS:
                    row[f"{d}_{when}"] = report[when]["defects"][d]
        except (ValueError, OSError) as error:  # a file mrepair cannot read or repair
            row["status"] = f"failed: {error}"
        finally:
            close()
        rows.append(row)
        print(f"{path.name}: {row['status']}", file=sys.stderr)
    with open(csv_path, "w", newline="") as out:
        writer = csv.DictWriter(out, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input", type=Path, help="folder of meshes")
    parser.add_argument("output", type=Path, help="folder for the repaired meshes")
    parser.add_argument("--csv", type=Path, default=None, help="CSV file (default OUTPUT/defects.csv)")
    parser.add_argument("--profile", default="auto", choices=["auto", "scan", "cad"])
    args = parser.parse_args()
    csv_path = args.csv or args.output / "defects.csv"
    rows = repair_folder(args.input, args.output, csv_path, args.profile)
    print(f"{len(rows)} meshes; defect counts in {csv_path}")
    return 0 if all(not r["status"].startswith("failed") for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
