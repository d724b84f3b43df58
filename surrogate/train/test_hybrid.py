"""Issue 46's designs in training and evaluation, on hybrid datasets plumekit makes.

    PLUMEKIT_EXE=build/plumekit /usr/bin/python3 -m pytest surrogate/train/test_hybrid.py

A hybrid dataset (--physics-input) of two small maps trains each design a step (tiny networks):
the headers say which channels each reads and the residual's plus_input; evaluate.py feeds each
what it reads (a plain model a hybrid dataset without its physics channel), refuses a hybrid model
on a dataset without the channel, and scores the baselines: the physics plume best-scaled (on a
dataset whose targets are exactly twice the physics channel: factor 2, error 0) and the
two-realization floor (a dataset against itself: error 0; another seed: a positive error).
"""
import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
EXE = os.environ.get("PLUMEKIT_EXE", os.path.join(HERE, "..", "..", "build", "plumekit"))
TINY = ["--filters", "4,4,4,4", "--kernel", "3", "--convs", "1", "--threads", "1"]


def plumekit(*args):
    subprocess.run([EXE, *map(str, args)], check=True, capture_output=True)


def py(script, *args):
    return subprocess.run([sys.executable, os.path.join(HERE, script), *map(str, args)],
                          capture_output=True, text=True)


def evaluate(model, *tests, floor=()):
    args = ["--model", model, "--test", *tests, "--json", "--threads", 1]
    if floor:
        args += ["--floor", *floor]
    r = py("evaluate.py", *args)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    root = tmp_path_factory.mktemp("hybrid")
    common = ["--feature-cell", 0.4, "--cell", 0.1, "--simulator", "advection-diffusion"]
    plumekit("dataset", "generate", "--maps", 2, "--sources", 3, "--seed", 3, "--physics-input",
             *common, "--out", root / "hybrid")
    plumekit("dataset", "generate", "--maps", 2, "--sources", 3, "--seed", 3, *common,
             "--out", root / "five")
    # Targets exactly twice the physics channel: the best-scaled physics is then exact.
    shutil.copytree(root / "hybrid", root / "twice")
    for shard in (root / "twice" / "shards").iterdir():
        x, t = np.load(shard / "inputs.npy"), np.load(shard / "targets.npy")
        t[:, 0] = 2 * x[:, 4]
        np.save(shard / "targets.npy", t)
    models = {}
    for design, flags in (("plain", ["--inputs", "plain"]), ("hybrid", []),
                          ("residual", ["--residual"])):
        models[design] = root / f"{design}.pkcnn"
        r = py("train.py", "--data", root / "hybrid", "--work", root / design, "--out",
               models[design], "--max-steps", 1, "--batch", 2, *TINY, *flags)
        assert r.returncode == 0, r.stderr
    return root, models


def header(path):
    sys.path.insert(0, HERE)
    from model_file import read_model
    return read_model(path)[1]


def test_headers_say_the_design(data):
    _, models = data
    names = {d: [c["name"] for c in header(m)["features"]["channels"]] for d, m in models.items()}
    assert names["plain"] == ["region", "signed_distance", "wind_u", "wind_v", "source_distance"]
    assert names["hybrid"] == names["residual"] == names["plain"][:4] + ["physics_mean",
                                                                         "source_distance"]
    for design, m in models.items():
        h = header(m)
        assert h["training"]["inputs"] == names[design]
        assert h["training"]["residual"] == (design == "residual")
        assert h["outputs"][0].get("plus_input") == ("physics_mean" if design == "residual" else None)
        if design != "plain":
            phys = h["features"]["channels"][4]
            assert phys["scale"] == h["outputs"][0]["scale"] and phys["decay_rate"] == 1 / 28


def test_evaluate_feeds_each_design_and_scores_the_baselines(data):
    root, models = data
    for design, m in models.items():
        r = evaluate(m, root / "twice", root / "hybrid", floor=(root / "twice", root / "hybrid"))
        twice, same = r["test_sets"]["twice"], r["test_sets"]["hybrid"]
        assert np.isfinite(twice["all"]["mean"]["rel_l2"]), design
        assert twice["physics"]["factor"] == pytest.approx(2.0, rel=1e-6)
        assert twice["physics"]["mean"]["rel_l2"] == pytest.approx(0.0, abs=1e-6)
        assert same["floor"]["mean"]["rel_l2"] == 0.0 and same["floor"]["std"]["rmse"] == 0.0
    # A plain model reads a five-channel dataset as well; a hybrid one cannot.
    r = evaluate(models["plain"], root / "five")
    assert "physics" not in r["test_maps"]
    r = py("evaluate.py", "--model", models["hybrid"], "--test", root / "five", "--json")
    assert r.returncode != 0 and "physics_mean" in r.stderr
    # --floor must be another realization of the same maps and sources, one per --test.
    r = py("evaluate.py", "--model", models["plain"], "--test", root / "hybrid", "--floor",
           root / "five", root / "five", "--json")
    assert r.returncode != 0 and "--floor" in r.stderr


def test_the_floor_of_another_seed_is_positive(data, tmp_path):
    root, models = data
    other = tmp_path / "other"
    plumekit("dataset", "generate", "--map-dir", root / "hybrid" / "maps", "--feature-cell", 0.4,
             "--cell", 0.1, "--physics-input", "--seed", 9, "--out", other)
    first = tmp_path / "first"
    plumekit("dataset", "generate", "--map-dir", root / "hybrid" / "maps", "--feature-cell", 0.4,
             "--cell", 0.1, "--physics-input", "--seed", 8, "--out", first)
    r = evaluate(models["hybrid"], first, floor=(other,))
    floor = r["test_maps"]["floor"]["mean"]
    assert 0.0 < floor["rel_l2"] < 1.0
    md = py("evaluate.py", "--model", models["hybrid"], "--test", first, "--floor", other,
            "--out", tmp_path / "eval")
    assert md.returncode == 0, md.stderr
    text = (tmp_path / "eval" / "evaluation.md").read_text()
    assert "two realizations (other)" in text and "physics plume ×" in text
