# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""`mrepair.batch` (issue 41) on a Dask LocalCluster of 2 workers, over the
folder `mrepair batch` is tested on: the same outputs, the same manifest keys
and statuses, the same resume rule; a scheduler given by its address.
Run by the CTest test `python_batch` (MREPAIR_CLI, MREPAIR_GENERATOR)."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

distributed = pytest.importorskip("distributed")  # Debian: python3-distributed (scripts/install_deps.sh)

from mrepair import batch as mbatch  # noqa: E402

CLI = os.environ.get("MREPAIR_CLI")
GEN = os.environ.get("MREPAIR_GENERATOR")
pytestmark = pytest.mark.skipif(not (CLI and GEN and Path(CLI).exists() and Path(GEN).exists()),
                                reason="MREPAIR_CLI and MREPAIR_GENERATOR not set")
TIMEOUT = 1.5  # the 1M-face scan takes about 9 s here (8.8 s), a small file 0.05 s


def generate(path, mode, faces, seed, *extra):
    path.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run([GEN, mode, "--faces", str(faces), "--seed", str(seed), "--output", str(path), *extra],
                   check=True, stdout=subprocess.DEVNULL)


def lines(path):
    return [json.loads(l) for l in Path(path).read_text().splitlines() if l.strip()]


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    root = tmp_path_factory.mktemp("dask") / "in"
    generate(root / "scan1.ply", "scan", 2000, 1)
    generate(root / "sub" / "scan2.off", "scan", 3000, 2, "--ascii")
    generate(root / "sub" / "deeper" / "part1.stl", "cad", 2000, 3)
    generate(root / "part2.obj", "cad", 3000, 4)
    text = (root / "sub" / "scan2.off").read_text()
    (root / "broken.off").write_text(text[: len(text) // 2])
    generate(root / "huge.ply", "scan", 1_000_000, 7)
    return root


@pytest.fixture(scope="module")
def cli_run(dataset, tmp_path_factory):
    out = tmp_path_factory.mktemp("dask_cli") / "out"
    subprocess.run([CLI, "batch", dataset, out, "--jobs", "2", "--timeout", str(TIMEOUT), "--quiet"],
                   capture_output=True)
    return out


@pytest.fixture(scope="module")
def cluster():
    from distributed import LocalCluster

    c = LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=":0")
    yield c
    c.close()


def test_same_outputs_and_manifest_as_the_program(dataset, cli_run, cluster, tmp_path):
    out = tmp_path / "out"
    # the scheduler by its address, as on an existing cluster
    s = mbatch.repair_dataset(dataset, out, client=cluster.scheduler_address, timeout=TIMEOUT, cli=CLI)
    assert s["files"] == 6 and s["repaired_now"] == 6 and s["skipped_as_done"] == 0
    ours, theirs = lines(out / "manifest.jsonl"), lines(cli_run / "manifest.jsonl")
    assert sorted(l["path"] for l in ours) == sorted(l["path"] for l in theirs)
    by_path = {l["path"]: l for l in theirs}
    for l in ours:
        t = by_path[l["path"]]
        assert list(l) == list(t) == list(mbatch.MANIFEST_KEYS)
        assert l["status"] == t["status"], l["path"]
        for k in ("faces_in", "faces_out", "defects_before", "defects_after", "face_accounting", "exit_code"):
            assert l[k] == t[k], (l["path"], k)
        if l["status"] in ("ok", "partial"):
            assert (out / l["path"]).read_bytes() == (cli_run / l["path"]).read_bytes(), l["path"]
        else:
            assert not (out / l["path"]).exists()
    assert {l["path"]: l["status"] for l in ours}["huge.ply"] == "timeout"
    assert {l["path"]: l["status"] for l in ours}["broken.off"] == "unreadable"
    assert s["statuses"]["timeout"] == 1 and s["statuses"]["unreadable"] == 1

    # resume: done files are skipped, the timeout is tried again; a file
    # whose line is gone is repaired again, its output replaced
    kept = [l for l in ours if l["path"] != "sub/scan2.off"]
    (out / "manifest.jsonl").write_text("".join(json.dumps(l) + "\n" for l in kept))
    s = mbatch.repair_dataset(dataset, out, client=cluster.scheduler_address, timeout=TIMEOUT, cli=CLI)
    assert s["skipped_as_done"] == 4
    assert sorted(r["path"] for r in s["records"]) == ["huge.ply", "sub/scan2.off"]
    assert lines(out / "manifest.jsonl")[: len(kept)] == kept


def test_local_cluster_and_a_file_list(dataset, cli_run, tmp_path):
    """client=None: a LocalCluster of its own; paths as a list of files."""
    files = [dataset / "scan1.ply", dataset / "sub" / "deeper" / "part1.stl"]
    out = tmp_path / "out"
    s = mbatch.repair_dataset(files, out, workers=2, cli=CLI)
    assert sorted(r["path"] for r in s["records"]) == ["scan1.ply", "sub/deeper/part1.stl"]
    for r in s["records"]:
        assert r["status"] in ("ok", "partial")
        assert (out / r["path"]).read_bytes() == (cli_run / r["path"]).read_bytes()


def test_bad_options_fail_at_once(dataset, tmp_path):
    with pytest.raises(ValueError, match="profile"):
        mbatch.repair_dataset(dataset, tmp_path / "out", cli=CLI, profile="bogus")
    with pytest.raises(ValueError, match="unknown option"):
        mbatch.repair_dataset(dataset, tmp_path / "out", cli=CLI, no_such_option=True)


def test_module_from_the_shell(dataset, cluster, tmp_path):
    out = tmp_path / "out"
    env = dict(os.environ, MREPAIR_CLI=CLI)
    r = subprocess.run([sys.executable, "-m", "mrepair.batch", dataset / "sub", out, "--scheduler",
                        cluster.scheduler_address, "--profile", "scan", "--quiet"],
                       capture_output=True, text=True, env=env)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("batch: 2 files")
    assert sorted(l["path"] for l in lines(out / "manifest.jsonl")) == ["deeper/part1.stl", "scan2.off"]


def test_finds_the_program_installed_beside_the_interpreter(tmp_path, monkeypatch):
    """no MREPAIR_CLI, nothing on PATH: the ``mrepair`` pip put in the environment's
    bin/ (an inactive venv), before the build tree's."""
    import sysconfig

    scripts = tmp_path / "venv" / "bin"
    scripts.mkdir(parents=True)
    installed = scripts / "mrepair"
    installed.write_bytes(Path(CLI).read_bytes())
    installed.chmod(0o755)
    real_get_path = sysconfig.get_path
    monkeypatch.setattr(sysconfig, "get_path",
                        lambda name, *a, **k: str(scripts) if name == "scripts" else real_get_path(name, *a, **k))
    monkeypatch.delenv("MREPAIR_CLI", raising=False)
    monkeypatch.setenv("PATH", str(tmp_path / "empty"))
    assert mbatch.find_cli() == str(installed.resolve())
    # one given by name still comes first
    assert mbatch.find_cli(CLI) == str(Path(CLI).resolve())
