# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""Repairing a whole dataset on a Dask cluster: ``mrepair batch`` spread over machines.

    from mrepair.batch import repair_dataset
    summary = repair_dataset("meshes/", "repaired/")                    # a LocalCluster
    summary = repair_dataset("meshes/", "repaired/", client="tcp://head:8786", profile="cad")

or from the shell::

    python3 -m mrepair.batch meshes/ repaired/ --scheduler tcp://head:8786 --timeout 600

Every file is one Dask task, and each task runs ``mrepair batch IN OUT --file
REL --manifest -``: the ``mrepair`` program repairs that one file in a child
process of its own (the same ``mrepair repair`` a single run gives, with the
same time and memory limits and the same statuses) and prints its manifest
line, which this module appends to the manifest. A file that crashes, hangs
or runs out of memory therefore fails alone and never takes a Dask worker
down; the outputs, the manifest format and the resume rule are those of
``mrepair batch`` by construction.

Workers need the ``mrepair`` program (the one this driver found, when the
same path exists there, else ``MREPAIR_CLI``, else on ``PATH``, else the one
``pip install`` put in the worker interpreter's environment) and the input and
output folders at the same paths (a shared file system). A worker with this
package installed needs nothing else; one without it needs only the program:
the task is sent by value.
"""

import argparse
import fcntl
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["MANIFEST_KEYS", "STATUSES", "find_cli", "find_meshes", "read_manifest", "repair_dataset", "main"]

MESH_EXTENSIONS = (".off", ".obj", ".ply", ".stl")
#: every manifest line has these keys, in this order (``mrepair batch`` writes them)
MANIFEST_KEYS = ("path", "status", "message", "seconds", "cpu_seconds", "peak_memory_mb", "exit_code",
                 "signal", "faces_in", "faces_out", "defects_before", "defects_after", "face_accounting")
#: status -> (done: a resumed run skips it, output: an output file was written)
STATUSES = {
    "ok": (True, True),
    "partial": (True, True),
    "failed": (True, False),
    "unreadable": (True, False),
    "write_error": (False, False),
    "timeout": (False, False),
    "out_of_memory": (False, False),
    "crashed": (False, False),
}


def _installed_cli():
    """the ``mrepair`` program ``pip install`` put beside this interpreter (the
    environment's bin/, also when that is not on PATH: an inactive venv), or None."""
    import site
    import sysconfig

    for d in (sysconfig.get_path("scripts"), os.path.join(sys.prefix, "bin"),
              os.path.join(site.getuserbase(), "bin")):
        exe = os.path.join(d, "mrepair")
        if os.path.isfile(exe) and os.access(exe, os.X_OK):
            return exe
    return None


def find_cli(cli=None):
    """the ``mrepair`` program: ``cli`` when given, else ``$MREPAIR_CLI``, else
    ``mrepair`` on ``PATH``, else the one installed with this package (the
    environment's ``bin/``), else the one built beside this package (the build
    tree's ``tools/mrepair``)."""
    candidates = [cli, os.environ.get("MREPAIR_CLI"), shutil.which("mrepair"), _installed_cli()]
    here = Path(__file__).resolve().parent
    candidates += [here.parent.parent / "tools" / "mrepair", here / "mrepair"]
    for c in candidates:
        if c and Path(c).is_file() and os.access(str(c), os.X_OK):
            return str(Path(c).resolve())
    raise FileNotFoundError("cannot find the mrepair program: `pip install .` installs it; "
                            "else set MREPAIR_CLI or put it on PATH")


def _is_mesh(name):
    return name.lower().endswith(MESH_EXTENSIONS) and ".mrepair-partial" not in name


def find_meshes(paths, out_dir=None):
    """``(root, [relative paths])``: every mesh file under a folder (recursively,
    sorted; the output folder left out), or the files of a list relative to
    the folder that holds them all."""
    if isinstance(paths, (str, os.PathLike)):
        root = Path(paths)
        if not root.is_dir():
            raise NotADirectoryError(f"'{root}' is not a folder")
        skip = Path(out_dir).resolve() if out_dir is not None else None
        rels = []
        for d, dirs, names in os.walk(root):
            dirs[:] = [x for x in dirs if skip is None or (Path(d) / x).resolve() != skip]
            rels += [(Path(d) / n).relative_to(root).as_posix() for n in names
                     if _is_mesh(n) and os.path.isfile(os.path.join(d, n))]
        return root, sorted(rels)
    files = [Path(p).absolute() for p in paths]
    if not files:
        return Path("."), []
    root = Path(os.path.commonpath([str(f.parent) for f in files]))
    return root, sorted({f.relative_to(root).as_posix() for f in files})


def read_manifest(path):
    """``{path: the last record of that file}`` from a manifest (lines that
    cannot be read, such as one cut short by a lost machine, are skipped)."""
    last = {}
    try:
        with open(path, encoding="utf-8") as f:
            for line in f:
                try:
                    r = json.loads(line)
                except ValueError:
                    continue
                if isinstance(r, dict) and isinstance(r.get("path"), str):
                    last[r["path"]] = r
    except FileNotFoundError:
        pass
    return last


def _is_done(record, out_dir):
    done, output = STATUSES.get(record.get("status"), (False, False))
    return done and (not output or (Path(out_dir) / record["path"]).exists())


def _option_arguments(options):
    """repair options as Python keywords -> ``mrepair repair`` arguments:
    ``profile="cad"`` -> ``--profile cad``, ``binary=True`` -> ``--binary``."""
    args = []
    for key, value in options.items():
        if value is None or value is False:
            continue
        args.append("--" + key.replace("_", "-"))
        if value is not True:
            args.append(str(value))
    return args


def _limit_arguments(timeout, memory, threads_per_job):
    args = []
    if timeout:
        args += ["--timeout", str(timeout)]
    if memory:
        args += ["--memory", str(int(memory))]
    if threads_per_job:
        args += ["--threads-per-job", str(int(threads_per_job))]
    return args


def _repair_file(cli, root, out_dir, rel, args):
    """one Dask task: ``mrepair batch ROOT OUT --file REL --manifest -`` -> its manifest line (a dict)."""
    # the driver's program when this machine has it at the same path, else this machine's own
    exe = cli if os.path.isfile(cli) else (os.environ.get("MREPAIR_CLI") or shutil.which("mrepair")
                                           or _installed_cli() or cli)
    command = [exe, "batch", str(root), str(out_dir), "--file", rel, "--manifest", "-", "--jobs", "1", "--quiet", *args]
    try:
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        stdout, stderr, code = done.stdout, done.stderr, done.returncode
    except OSError as e:
        stdout, stderr, code = "", str(e), None
    for line in reversed(stdout.splitlines()):
        try:
            record = json.loads(line)
        except ValueError:
            continue
        if isinstance(record, dict) and record.get("path") == rel:
            return record
    # the batch process itself failed (it was killed, or the program is missing)
    record = dict.fromkeys(MANIFEST_KEYS)
    message = (stderr.strip().splitlines() or ["no manifest line"])[-1]
    record.update(path=rel, status="crashed", message=f"mrepair batch on this file: {message}",
                  seconds=0.0, cpu_seconds=0.0, peak_memory_mb=0,
                  exit_code=code if code is not None and code >= 0 else None,
                  signal=f"signal {-code}" if code is not None and code < 0 else None)
    return record


def _check_options(cli, args):
    """the repair options checked once, by the program's own parser (a typo
    fails at once, not on every file)."""
    with tempfile.TemporaryDirectory() as d:
        empty, out = Path(d) / "in", Path(d) / "out"
        empty.mkdir()
        r = subprocess.run([cli, "batch", str(empty), str(out), "--quiet", *args],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            raise ValueError(r.stderr.strip() or f"mrepair batch exit code {r.returncode}")


def _open_client(client, workers, threads_per_job):
    """(client, what to close at the end, threads per job): a LocalCluster
    when `client` is None, a connection when it is an address."""
    from distributed import Client, LocalCluster

    if client is None:
        n = workers or os.cpu_count() or 1
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, dashboard_address=":0")
        if threads_per_job is None and not os.environ.get("MREPAIR_THREADS"):
            threads_per_job = max(1, (os.cpu_count() or 1) // n)
        c = Client(cluster)
        return c, [c, cluster], threads_per_job
    if isinstance(client, str):
        c = Client(client)
        return c, [c], threads_per_job
    return client, [], threads_per_job


def _send_by_value():
    """pickle this module's functions by value: workers need the program, not this package."""
    try:
        import cloudpickle

        cloudpickle.register_pickle_by_value(sys.modules[__name__])
    except (ImportError, AttributeError, ValueError):
        pass


def repair_dataset(paths, out_dir, client=None, *, manifest=None, workers=None, timeout=None, memory=None,
                   threads_per_job=None, cli=None, progress=None, **options):
    """repairs every mesh of ``paths`` (a folder, recursively, or a list of
    files) into ``out_dir`` with the same relative paths, one Dask task per
    file, and appends one line per file to the manifest (``out_dir /
    "manifest.jsonl"`` by default), the format of ``mrepair batch``. Files
    whose last line says done (and whose output exists) are skipped, so a
    second call resumes an interrupted one.

    ``client``: a ``distributed.Client``, a scheduler address
    (``"tcp://host:8786"``), or None for a ``LocalCluster`` of ``workers``
    processes (default: the number of cores), closed at the end.
    ``timeout`` (seconds) and ``memory`` (MB of address space) limit each
    file, as ``mrepair batch --timeout/--memory`` do; ``threads_per_job`` sets
    each repair's threads. ``options`` are ``mrepair repair``'s, as keywords
    (``profile="cad"``, ``close_gaps=0.01``, ``binary=True``,
    ``no_resolve_intersections=True``). ``progress(done, total, record)`` is
    called as each file finishes.

    Returns a dict: ``files``, ``skipped_as_done``, ``repaired_now``,
    ``statuses`` (counts over every file, by its latest status), ``seconds``,
    ``records`` (the manifest lines of this call) and ``manifest``.
    """
    cli = find_cli(cli)
    out_dir = Path(out_dir)
    root, rels = find_meshes(paths, out_dir)
    if root.resolve() == out_dir.resolve():
        raise ValueError("out_dir must differ from the input folder (the outputs would replace the inputs)")
    out_dir.mkdir(parents=True, exist_ok=True)
    manifest = Path(manifest) if manifest is not None else out_dir / "manifest.jsonl"
    repair_args = _option_arguments(options)
    _check_options(cli, repair_args + _limit_arguments(timeout, memory, threads_per_job))

    t0 = time.monotonic()
    with open(manifest, "a", encoding="utf-8") as mf:
        try:
            fcntl.flock(mf, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            raise RuntimeError(f"the manifest '{manifest}' is in use by another batch") from None
        # the temporary outputs of a run that was killed (no other run of this manifest is going on)
        for d, _, names in os.walk(out_dir):
            for n in names:
                if ".mrepair-partial" in n and n.lower().endswith(MESH_EXTENSIONS):
                    try:
                        os.remove(os.path.join(d, n))
                    except OSError:
                        pass
        last = read_manifest(manifest)
        latest = {}
        todo = []
        for rel in rels:
            if rel in last and _is_done(last[rel], out_dir):
                latest[rel] = last[rel]["status"]
            else:
                todo.append(rel)
        skipped = len(rels) - len(todo)
        # largest first, as `mrepair batch` does: the long repairs start early
        todo.sort(key=lambda r: -(root / r).stat().st_size if (root / r).exists() else 0)
        records = []
        if todo:
            dask_client, owned, threads = _open_client(client, workers, threads_per_job)
            try:
                _send_by_value()
                args = repair_args + _limit_arguments(timeout, memory, threads)
                from distributed import as_completed

                futures = dask_client.map(_repair_file, [cli] * len(todo), [str(root.absolute())] * len(todo),
                                          [str(out_dir.absolute())] * len(todo), todo, [args] * len(todo),
                                          pure=False)
                for future in as_completed(futures):
                    record = future.result()
                    mf.write(json.dumps(record) + "\n")
                    mf.flush()
                    os.fdatasync(mf.fileno())
                    latest[record["path"]] = record["status"]
                    records.append(record)
                    if progress is not None:
                        progress(len(records), len(todo), record)
            finally:
                for x in owned:
                    x.close()
    statuses = dict.fromkeys(STATUSES, 0)
    for s in latest.values():
        statuses[s] = statuses.get(s, 0) + 1
    return {"files": len(rels), "skipped_as_done": skipped, "repaired_now": len(records), "statuses": statuses,
            "seconds": time.monotonic() - t0, "records": records, "manifest": str(manifest)}


def main(argv=None):
    p = argparse.ArgumentParser(prog="python3 -m mrepair.batch",
                                description="mrepair batch on a Dask cluster: repairs every mesh under IN into OUT")
    p.add_argument("input", metavar="IN", help="folder of meshes (OFF/OBJ/PLY/STL, recursively)")
    p.add_argument("output", metavar="OUT", help="output folder (same relative paths)")
    p.add_argument("--scheduler", help="address of a Dask scheduler (tcp://host:8786); default: a LocalCluster")
    p.add_argument("--workers", type=int, help="workers of the LocalCluster (default: the number of cores)")
    p.add_argument("--manifest", help="manifest file (default: OUT/manifest.jsonl)")
    p.add_argument("--timeout", type=float, help="seconds one file may take (default: no limit)")
    p.add_argument("--memory", type=int, help="MB of address space one repair may use (default: no limit)")
    p.add_argument("--threads-per-job", type=int, help="threads of each repair")
    p.add_argument("--cli", help="the mrepair program (default: $MREPAIR_CLI, PATH, the one installed with this package)")
    p.add_argument("--quiet", action="store_true", help="print no progress")
    args, rest = p.parse_known_args(argv)
    # the rest are `mrepair repair` options, passed on as they are (checked by the program)
    options, i = {}, 0
    while i < len(rest):
        a = rest[i]
        if not a.startswith("--"):
            p.error(f"unexpected argument '{a}'")
        name, eq, value = a[2:].partition("=")
        if not eq and i + 1 < len(rest) and not rest[i + 1].startswith("--"):
            value, i = rest[i + 1], i + 1
        options[name.replace("-", "_")] = value if (eq or value) else True
        i += 1

    start = time.monotonic()
    last_print = [start]

    def show(done, total, record):
        now = time.monotonic()
        if args.quiet or (now - last_print[0] < 10 and done < total):
            return
        last_print[0] = now
        rate = done / max(now - start, 1e-9)
        print(f"mrepair.batch: {done}/{total} files, {rate:.2f} files/s, ETA {(total - done) / rate:.0f} s",
              file=sys.stderr, flush=True)

    try:
        s = repair_dataset(args.input, args.output, client=args.scheduler, manifest=args.manifest,
                           workers=args.workers, timeout=args.timeout, memory=args.memory,
                           threads_per_job=args.threads_per_job, cli=args.cli, progress=show, **options)
    except (ValueError, RuntimeError, FileNotFoundError, NotADirectoryError) as e:
        print(f"mrepair.batch: {e}", file=sys.stderr)
        return 2
    st = s["statuses"]
    bad = sum(n for k, n in st.items() if k not in ("ok", "partial"))
    print(f"batch: {s['files']} files, {st['ok']} ok, {st['partial']} partial, {bad} not repaired"
          + (f" ({s['skipped_as_done']} done before)" if s["skipped_as_done"] else "")
          + f"; {s['repaired_now']} repaired in {s['seconds']:.1f} s")
    for r in sorted(s["records"], key=lambda r: r["path"]):
        if r["status"] not in ("ok", "partial"):
            print(f"  {r['path']}: {r['status']}: {r['message']}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
