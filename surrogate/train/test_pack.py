"""pack.py: a training pack travels small and unpacks into the dataset the trainer reads.

    PLUMEKIT_EXE=build/plumekit /usr/bin/python3 -m pytest surrogate/train/test_pack.py

A hybrid dataset (--physics-input) of two small maps is made by plumekit, packed and unpacked: the
map channels and sources come back exactly, the physics channel and the targets to float16, the
source distance to 1e-5 m; the pack is smaller than the shards. A thesis-grid dataset and an
existing --out are refused (exit 2) and nothing is written.
"""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
PACK = os.path.join(HERE, "pack.py")
EXE = os.environ.get("PLUMEKIT_EXE", os.path.join(HERE, "..", "..", "build", "plumekit"))


def plumekit(*args):
    subprocess.run([EXE, *map(str, args)], check=True, capture_output=True)


def pack_py(*args):
    return subprocess.run([sys.executable, PACK, *map(str, args)], capture_output=True, text=True)


def du(path):
    return sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(path) for f in fs)


@pytest.fixture(scope="module")
def hybrid(tmp_path_factory):
    d = tmp_path_factory.mktemp("hybrid") / "hybrid"
    plumekit("dataset", "generate", "--maps", 2, "--sources", 3, "--feature-cell", 0.2,
             "--physics-input", "--simulator", "advection-diffusion", "--cell", 0.1,
             "--seed", 3, "--out", d)
    return d


def test_round_trip(hybrid, tmp_path):
    assert pack_py("pack", hybrid, "--out", tmp_path / "pack").returncode == 0
    assert du(tmp_path / "pack") < du(hybrid / "shards") / 2
    r = pack_py("unpack", tmp_path / "pack", "--out", tmp_path / "data")
    assert r.returncode == 0, r.stderr
    back = tmp_path / "data" / "hybrid"
    manifest = json.loads((back / "manifest.json").read_text())
    assert "float16" in manifest["packed"]
    names = manifest["contract"]["inputs"]["names"]
    assert names[4] == "physics_mean"
    for entry in manifest["shards"]:
        a, b = hybrid / "shards" / entry["name"], back / "shards" / entry["name"]
        x, y = np.load(a / "inputs.npy"), np.load(b / "inputs.npy")
        assert x.shape == y.shape and y.dtype == np.float32
        assert np.array_equal(x[:, :4], y[:, :4])
        phys = x[:, 4]
        assert phys.max() > 100
        np.testing.assert_allclose(y[:, 4], phys, rtol=1e-3, atol=1e-3 * phys.max())
        np.testing.assert_allclose(y[:, 5], x[:, 5], atol=1e-5)
        t, u = np.load(a / "targets.npy"), np.load(b / "targets.npy")
        np.testing.assert_allclose(u, t, rtol=1e-3, atol=1e-3 * t.max())
        assert np.array_equal(np.load(a / "sources.npy"), np.load(b / "sources.npy"))
        assert np.array_equal(np.load(a / "map_ids.npy"), np.load(b / "map_ids.npy"))
    assert sorted(os.listdir(back / "maps")) == sorted(os.listdir(hybrid / "maps"))


def test_refusals(hybrid, tmp_path):
    thesis = tmp_path / "thesis"
    plumekit("dataset", "generate", "--maps", 1, "--sources", 1, "--simulator",
             "advection-diffusion", "--cell", 0.1, "--out", thesis)
    # The second dataset is refused after the first was packed: nothing partial is left.
    r = pack_py("pack", hybrid, thesis, "--out", tmp_path / "p1")
    assert r.returncode == 2 and "physical-grid" in r.stderr
    assert not (tmp_path / "p1").exists() and not (tmp_path / "p1.partial").exists()
    (tmp_path / "taken").mkdir()
    (tmp_path / "taken" / "mine.txt").write_text("a user's file")
    for verb, src in (("pack", hybrid), ("unpack", tmp_path / "taken")):
        r = pack_py(verb, src, "--out", tmp_path / "taken")
        assert r.returncode == 2 and "exists" in r.stderr
    assert os.listdir(tmp_path / "taken") == ["mine.txt"]
