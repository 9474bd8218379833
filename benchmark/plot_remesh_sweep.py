#!/usr/bin/env python3
# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""Plots the harness task remesh-adaptive-sweep: Hausdorff distance against
faces, one PNG per JSON file (one mesh), every variant on one plot, and prints
the table of the sweep in Markdown.

    mrepair-bench remesh-adaptive-sweep MESH --json sweep.json
    python3 benchmark/plot_remesh_sweep.py sweep.json [more.json ...] --out doc/images \
        [--name armadillo ...] [--table table.md] [--cgal-from cgal6.json ...]

Besides each mesh's table it prints, per mrepair variant and tolerance,
mrepair's Hausdorff distance over CGAL's curve interpolated (log-log) at
mrepair's face count (below 1: better; "beyond" where the count lies outside
CGAL's range, then the nearest end's slope is used). --cgal-from takes CGAL's
variant from another run of the same mesh (one file per JSON, in order): a
harness built on 5.5 has no CGAL column, and mrepair's figures are the same on
both releases, so a 5.5 run can be set beside a stored 6.x one.

Needs matplotlib (Debian: python3-matplotlib) for the PNGs; --no-plot prints
the table only.
"""
import argparse
import json
import os
import re
import sys

COLUMNS = [
    ("tolerance_rel", "tolerance / diag", "{:g}"),
    ("faces", "faces", "{:,.0f}"),
    ("hausdorff_rel", "Hausdorff / diag", "{:.5f}"),
    ("hausdorff_output_to_input_rel", "out->in", "{:.5f}"),
    ("hausdorff_input_to_output_rel", "in->out", "{:.5f}"),
    ("mean_distance_rel", "mean dist / diag", "{:.2e}"),
    ("min_angle_deg", "min angle", "{:.1f}"),
    ("share_angles_below_30", "< 30 deg", "{:.2%}"),
    ("seconds", "time [s]", "{:.2f}"),
]


def runs_of(variant):
    """the per-tolerance sections t1, t2, ... of a variant: list of dicts"""
    sections = {}
    for key, value in variant.get("values", {}).items():
        m = re.match(r"result\.t(\d+)\.(.+)$", key)
        if not m:
            continue
        sections.setdefault(int(m.group(1)), {})[m.group(2)] = value
    out = []
    for i in sorted(sections):
        row = {}
        for k, v in sections[i].items():
            try:
                row[k] = float(v)
            except ValueError:
                row[k] = v
        out.append(row)
    return out


def table(data, name):
    lines = [f"**{name}** ({data.get('input', '')}, CGAL {data.get('cgal', '?')})", ""]
    head = ["variant"] + [c[1] for c in COLUMNS]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "---|" * len(head))
    for v in data["variants"]:
        runs = runs_of(v)
        if not runs:
            lines.append(f"| {v['name']} | " + " | ".join([v.get("status", "")] + [""] * (len(COLUMNS) - 1)) + " |")
            continue
        for r in runs:
            cells = [v["name"]]
            for key, _, fmt in COLUMNS:
                val = r.get(key)
                if key == "seconds" and "face_count_seconds" in r:
                    val = r["face_count_seconds"]
                cells.append(fmt.format(val) if isinstance(val, float) else ("" if val is None else str(val)))
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def curve_ratios(data, name):
    """mrepair's Hausdorff over CGAL's curve at mrepair's face count"""
    import math
    cgal = next((v for v in data["variants"] if v["name"].startswith("CGAL")), None)
    pts = sorted((r["faces"], r["hausdorff_rel"]) for r in runs_of(cgal or {})
                 if isinstance(r.get("faces"), float) and isinstance(r.get("hausdorff_rel"), float))
    if len(pts) < 2:
        return ""

    def at(faces):
        x = math.log(faces)
        xs = [math.log(f) for f, _ in pts]
        ys = [math.log(h) for _, h in pts]
        i = 0
        while i + 2 < len(xs) and x > xs[i + 1]:
            i += 1
        t = (x - xs[i]) / (xs[i + 1] - xs[i])
        return math.exp(ys[i] + t * (ys[i + 1] - ys[i])), not (xs[0] <= x <= xs[-1])

    lines = [f"**{name}**: mrepair's Hausdorff / CGAL's curve at the same face count", ""]
    variants = [v for v in data["variants"] if v["name"].startswith("mrepair") and runs_of(v)]
    tols = [r.get("tolerance_rel") for r in runs_of(variants[0])] if variants else []
    lines.append("| variant | " + " | ".join(f"{t:g}" for t in tols) + " |")
    lines.append("|" + "---|" * (len(tols) + 1))
    for v in variants:
        cells = []
        for r in runs_of(v):
            if not isinstance(r.get("faces"), float) or not isinstance(r.get("hausdorff_rel"), float):
                cells.append("")
                continue
            h, beyond = at(r["faces"])
            cells.append(f"{r['hausdorff_rel'] / h:.2f}" + (" (beyond)" if beyond else ""))
        lines.append(f"| {v['name']} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def plot(data, name, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = {
        "mrepair::adaptive_remesh": dict(marker="o", color="tab:blue"),
        "CGAL Adaptive_sizing_field": dict(marker="s", color="tab:red"),
        "mrepair::remesh_to_face_count": dict(marker="^", color="tab:green", linestyle="--"),
    }
    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=110)
    for v in data["variants"]:
        runs = [r for r in runs_of(v) if isinstance(r.get("faces"), float)]
        if not runs:
            continue
        runs.sort(key=lambda r: r["faces"])
        label = v["name"]
        if label == "mrepair::remesh_to_face_count":
            label += " (at CGAL's counts)" if "CGAL" in str(runs[0].get("target_from", "CGAL")) else ""
        ax.plot([r["faces"] for r in runs], [r["hausdorff_rel"] for r in runs], label=label,
                **styles.get(v["name"], {}))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("faces")
    ax.set_ylabel("Hausdorff distance / bounding-box diagonal")
    ax.set_title(f"{name}: adaptive remeshing, tolerance 0.0005-0.008 x diag (CGAL {data.get('cgal', '?')})",
                 fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out_dir, f"remesh_sweep_{name}.png")
    fig.savefig(path)
    plt.close(fig)
    return path


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("json", nargs="+")
    p.add_argument("--out", default="doc/images")
    p.add_argument("--name", action="append", help="mesh name per JSON file (default: input file stem)")
    p.add_argument("--table", help="also write the Markdown tables here")
    p.add_argument("--no-plot", action="store_true")
    p.add_argument("--cgal-from", action="append", help="take CGAL's variant from this run (per JSON file)")
    a = p.parse_args()
    tables = []
    for i, path in enumerate(a.json):
        with open(path) as f:
            data = json.load(f)
        if a.cgal_from and i < len(a.cgal_from):
            with open(a.cgal_from[i]) as f:
                other = json.load(f)
            theirs = [v for v in other["variants"] if v["name"].startswith("CGAL")]
            data["variants"] = [v for v in data["variants"] if not v["name"].startswith("CGAL")] + theirs
            data["mrepair_built_with_cgal"] = data.get("cgal", "?")
            data["cgal"] = other.get("cgal", "?")
        name = a.name[i] if a.name and i < len(a.name) else os.path.splitext(os.path.basename(data["input"]))[0]
        tables.append(table(data, name))
        tables.append(curve_ratios(data, name))
        if not a.no_plot:
            os.makedirs(a.out, exist_ok=True)
            print(f"wrote {plot(data, name, a.out)}", file=sys.stderr)
    text = "\n".join(tables)
    print(text)
    if a.table:
        with open(a.table, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
