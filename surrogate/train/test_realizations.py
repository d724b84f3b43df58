"""mean_of_realizations.py: the average of realizations of one dataset, which plumekit still reads.

    PLUMEKIT_EXE=build/plumekit /usr/bin/python3 -m pytest surrogate/train/test_realizations.py

Three realizations of two small maps (given maps, three seeds) are averaged: the targets are the
mean of the three, the inputs the first's, `plumekit dataset show` reads the result (its
checksums hold). Datasets of other maps and an existing OUT are refused (exit 2).
"""
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "mean_of_realizations.py")
EXE = os.environ.get("PLUMEKIT_EXE", os.path.join(HERE, "..", "..", "build", "plumekit"))


def plumekit(*args):
    return subprocess.run([EXE, *map(str, args)], check=True, capture_output=True, text=True)


def average(*args):
    return subprocess.run([sys.executable, SCRIPT, *map(str, args)], capture_output=True, text=True)


def test_average_of_three(tmp_path):
    first = tmp_path / "r1"
    plumekit("dataset", "generate", "--maps", 2, "--sources", 2, "--feature-cell", 0.4,
             "--cell", 0.1, "--seed", 1, "--out", first)
    runs = [first]
    for seed in (2, 3):
        runs.append(tmp_path / f"r{seed}")
        plumekit("dataset", "generate", "--map-dir", first / "maps", "--feature-cell", 0.4,
                 "--cell", 0.1, "--seed", seed, "--out", runs[-1])
    r = average(tmp_path / "mean", *runs)
    assert r.returncode == 0, r.stderr
    manifest = json.loads((tmp_path / "mean" / "manifest.json").read_text())
    assert manifest["realizations"]["count"] == 3
    for s in manifest["shards"]:
        t = [np.load(d / "shards" / s["name"] / "targets.npy").astype(np.float64) for d in runs]
        assert not np.array_equal(t[0], t[1])  # another seed, another realization
        got = np.load(tmp_path / "mean" / "shards" / s["name"] / "targets.npy")
        np.testing.assert_allclose(got, (t[0] + t[1] + t[2]) / 3, rtol=1e-6, atol=1e-4)
        assert np.array_equal(np.load(tmp_path / "mean" / "shards" / s["name"] / "inputs.npy"),
                              np.load(first / "shards" / s["name"] / "inputs.npy"))
    shown = json.loads(plumekit("dataset", "show", tmp_path / "mean", "--index", 3, "--out",
                                tmp_path / "show.png", "--json").stdout)
    assert shown["ok"]


def test_refusals(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    for d, seed in ((a, 1), (b, 2)):  # random maps of other seeds: other maps
        plumekit("dataset", "generate", "--maps", 1, "--sources", 1, "--feature-cell", 0.4,
                 "--cell", 0.1, "--seed", seed, "--out", d)
    r = average(tmp_path / "out", a, b)
    assert r.returncode == 2 and "differs" in r.stderr
    assert not (tmp_path / "out").exists() and not (tmp_path / "out.partial").exists()
    assert average(tmp_path / "out", a).returncode == 2
    assert average(a, a, a).returncode == 2  # exists
    assert "realizations" not in json.loads((a / "manifest.json").read_text())
