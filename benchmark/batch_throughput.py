#!/usr/bin/env python3
# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""Throughput of repairing a dataset (issue 41): files per second of
`mrepair batch` with 1 and 2 jobs and of `mrepair.batch.repair_dataset` on a
Dask LocalCluster of 1 and 2 workers, over a folder of real meshes and a
folder of generated 250k-face scans; prints a Markdown table.

    PYTHONPATH=build/release/python /usr/bin/python3 benchmark/batch_throughput.py \\
        --cli build/release/tools/mrepair --generator build/release/tools/mrepair-generate \\
        --real ../shared/real-meshes --scans 8 --work /tmp/mrepair-batch-bench

Overhead per file = (wall time x parallel slots - the sum of the repairs'
own wall times from the manifest) / files: the slot time not spent inside a
`mrepair repair` child, i.e. the batch's bookkeeping (discovery, fork, report
parsing, fsync, rename), Dask's scheduling and idle slots at the end. The
repairs' own times include starting the process (`start` column: `mrepair
--help` wall time). The Dask cluster is started before the clock runs (its
start-up time is printed apart).
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path


def manifest(out):
    return [json.loads(l) for l in (Path(out) / "manifest.jsonl").read_text().splitlines() if l.strip()]


def run_cli(cli, src, out, jobs, extra):
    shutil.rmtree(out, ignore_errors=True)
    t0 = time.monotonic()
    subprocess.run([cli, "batch", str(src), str(out), "--jobs", str(jobs), "--quiet", *extra],
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.monotonic() - t0, manifest(out)


def run_dask(cli, src, out, workers, extra_timeout):
    from distributed import Client, LocalCluster

    from mrepair.batch import repair_dataset

    shutil.rmtree(out, ignore_errors=True)
    t0 = time.monotonic()
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, dashboard_address=":0")
    client = Client(cluster)
    start = time.monotonic() - t0
    threads = max(1, (os.cpu_count() or 1) // workers)
    try:
        t0 = time.monotonic()
        repair_dataset(src, out, client=client, cli=cli, timeout=extra_timeout, threads_per_job=threads)
        wall = time.monotonic() - t0
    finally:
        client.close()
        cluster.close()
    return wall, manifest(out), start


def process_start(cli, n=20):
    t = []
    for _ in range(n):
        t0 = time.monotonic()
        subprocess.run([cli, "--help"], stdout=subprocess.DEVNULL)
        t.append(time.monotonic() - t0)
    return statistics.median(t)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cli", required=True)
    p.add_argument("--generator", required=True)
    p.add_argument("--real", help="folder of real meshes (../shared/real-meshes)")
    p.add_argument("--scans", type=int, default=8, help="generated 250k-face scans (0: none)")
    p.add_argument("--faces", type=int, default=250000)
    p.add_argument("--work", default="/tmp/mrepair-batch-bench", help="scratch folder (inputs and outputs)")
    p.add_argument("--timeout", type=float, default=120, help="per-file limit of every run")
    p.add_argument("--no-dask", action="store_true")
    a = p.parse_args()
    cli = str(Path(a.cli).resolve())
    work = Path(a.work)
    sets = []
    if a.real:
        sets.append(("real meshes", Path(a.real)))
    if a.scans:
        scans = work / "scans"
        scans.mkdir(parents=True, exist_ok=True)
        for i in range(a.scans):
            f = scans / f"scan{i}.ply"
            if not f.exists():
                subprocess.run([a.generator, "scan", "--faces", str(a.faces), "--seed", str(100 + i), "--noise",
                                "0.1", "--output", str(f)], check=True, stdout=subprocess.DEVNULL)
        sets.append((f"{a.scans} scans of {a.faces // 1000}k faces", scans))
    start = process_start(cli)
    rows = []
    for name, src in sets:
        runs = [("batch --jobs 1", 1, lambda o: run_cli(cli, src, o, 1, ["--timeout", str(a.timeout)]) + (None,)),
                ("batch --jobs 2", 2, lambda o: run_cli(cli, src, o, 2, ["--timeout", str(a.timeout)]) + (None,))]
        if not a.no_dask:
            runs += [("Dask, 1 worker", 1, lambda o: run_dask(cli, src, o, 1, a.timeout)),
                     ("Dask, 2 workers", 2, lambda o: run_dask(cli, src, o, 2, a.timeout))]
        for label, slots, run in runs:
            out = work / "out" / label.replace(" ", "_").replace(",", "")
            wall, lines, cluster_start = run(out)
            n = len(lines)
            child = sum(l["seconds"] for l in lines)
            ok = sum(l["status"] in ("ok", "partial") for l in lines)
            rows.append((name, label, n, ok, wall, n / wall if wall else 0, child / max(n, 1),
                         (wall * slots - child) / max(n, 1), cluster_start))
            print(f"  {name}, {label}: {n} files in {wall:.2f} s", file=sys.stderr, flush=True)
    print(f"\nprocess start (`mrepair --help`, median of 20): {start * 1000:.1f} ms; "
          f"{os.cpu_count()} cores\n")
    print("| input | run | files (ok+partial) | wall s | files/s | repair s per file (mean) | overhead per file | cluster start |")
    print("|---|---|---|---|---|---|---|---|")
    for name, label, n, ok, wall, fps, mean, over, cs in rows:
        print(f"| {name} | {label} | {n} ({ok}) | {wall:.2f} | {fps:.2f} | {mean * 1000:.0f} ms | "
              f"{over * 1000:.0f} ms | {'' if cs is None else f'{cs:.1f} s'} |")


if __name__ == "__main__":
    main()
