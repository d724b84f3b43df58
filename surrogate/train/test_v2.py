"""v2 surrogate training (surrogate/train): 5-channel inputs on each map's own physical grid.

    /usr/bin/python3 -m pytest surrogate/train/test_v2.py

A synthetic v2 dataset of 3 maps of different sizes (synthetic_dataset.py --feature-cell), a tiny
network (hidden --filters/--kernel/--convs), 3 steps on one thread; then the header, the padding
and its mask, the bucketing, the golden pair, read_model's round trip, resuming and evaluate.py.
Then two synthetic v2 datasets trained as one (--data A B): the split by map within each dataset,
the header's datasets, trained_on and target scale over both, the refusals (a v1 and a v2 dataset,
a dataset twice, resuming or evaluating with other datasets), and evaluate.py with two --test sets.
"""
import csv
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest
import torch

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from model import PlumeUNet  # noqa: E402
from model_file import read_model  # noqa: E402
from shards import (feature_cell, map_ranges, map_summary, open_dataset, padded_size,  # noqa: E402
                    ranges, split_by_map, split_datasets)
from train import V2Batches, evaluate_v2, masked_squares  # noqa: E402

CELL = 0.2
SIZES = [(3.0, 2.0), (4.4, 3.1), (2.6, 3.4)]  # 15x10, 22x16, 13x17 cells
TINY = ["--filters", "4,4,4,4", "--kernel", "3", "--convs", "1"]  # 16 = 2 ** 4: the real multiple
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))

torch.set_num_threads(1)


def run(*args, fail=False):
    r = subprocess.run([sys.executable, *map(str, args)], capture_output=True, text=True,
                       cwd=REPO)
    if fail:  # the run must be refused: its message
        assert r.returncode != 0, r.stdout + r.stderr
        return r.stderr
    assert r.returncode == 0, r.stdout + r.stderr
    return r.stdout


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    d = tmp_path_factory.mktemp("v2")
    data = d / "data"
    run(os.path.join(HERE, "synthetic_dataset.py"), data, "--feature-cell", CELL, "--per-map", 4,
        "--sizes", ",".join("%gx%g" % s for s in SIZES))
    train = [os.path.join(HERE, "train.py"), "--data", data, "--work", d / "work", "--out",
             d / "model.pkcnn", "--threads", "1", "--batch", "1", *TINY]
    run(*train, "--max-steps", 2)
    out = run(*train, "--max-steps", 3)  # resumes from the checkpoint
    return {"dir": d, "data": str(data), "model": str(d / "model.pkcnn"), "log": out}


def test_dataset_is_v2_with_each_map_on_its_own_grid(trained):
    manifest, shards = open_dataset(trained["data"])
    assert feature_cell(trained["data"], manifest) == CELL
    for s, (w, h) in zip(shards, SIZES):
        assert s.inputs.shape[1:] == (5, round(h / CELL), round(w / CELL))
        assert s.targets.shape[1:] == (2,) + s.inputs.shape[2:]
    assert len({s.inputs.shape[2:] for s in shards}) == 3


def test_feature_cell_is_found_where_a_generator_may_put_it(tmp_path):
    def cell(manifest, parameters=None):
        with open(tmp_path / "manifest.json", "w") as f:
            json.dump(manifest, f)
        if parameters is not None:
            with open(tmp_path / "parameters.json", "w") as f:
                json.dump(parameters, f)
        elif (tmp_path / "parameters.json").exists():
            os.remove(tmp_path / "parameters.json")
        return feature_cell(str(tmp_path))
    assert cell({"generator": {"feature_cell": 0.25}}) == 0.25  # plumekit dataset generate
    assert cell({"generator": {"dataset": {"feature_cell": 0.3}}}) == 0.3
    assert cell({"generator": {}}, {"dataset": {"feature_cell": 0.1}}) == 0.1
    assert cell({"generator": {}, "contract": {"grid": {"cell": 0.4, "nx": "..."}}}) == 0.4
    assert cell({"generator": {"feature_cell": 0}}) == 0.0  # v1
    assert cell({"generator": {}, "contract": {"grid": {"nx": 64, "ny": 64}}}) == 0.0


def test_header_states_the_v2_contract_and_the_training_ranges(trained):
    model, header = read_model(trained["model"])
    f = header["features"]
    assert f["cell_size"] == CELL and f["multiple"] == 16
    assert "grid" not in f and "arena" not in f and "multiple" in f["cells"]
    assert [c["name"] for c in f["channels"]] == ["region", "signed_distance", "wind_u", "wind_v",
                                                  "source_distance"]
    src = f["channels"][4]
    assert src["form"] == "inverse" and src["unit"] == "1/m" and src["min_distance"] == CELL / 2
    assert header["architecture"]["in_channels"] == 5 and model.in_channels == 5
    assert header["architecture"]["filters"] == [4, 4, 4, 4]
    # trained_on: over the training maps (not the validation one), read from the map files.
    val = set(header["training"]["val_maps"])
    assert len(val) == 1
    train_maps = [m for m in range(3) if m not in val]
    maps = [json.load(open(os.path.join(trained["data"], "maps", "map-%05d.json" % m)))
            for m in train_maps]
    t = header["trained_on"]
    assert t["map_width_m"] == [min(SIZES[m][0] for m in train_maps), max(SIZES[m][0] for m in train_maps)]
    assert t["map_height_m"] == [min(SIZES[m][1] for m in train_maps), max(SIZES[m][1] for m in train_maps)]
    speeds = [o["speed"] for m in maps for o in m["openings"] if o["kind"] == "inlet"]
    assert t["inlet_speed_m_s"] == [min(speeds), max(speeds)]
    counts = [len(m["openings"]) for m in maps]
    assert t["openings"] == [min(counts), max(counts)]
    # Map 2 has a second inlet on the bottom wall; every map one on the left.
    assert t["inlet_walls"] == (["bottom", "left"] if 2 in train_maps else ["left"])


def test_map_ranges_reads_framed_v2_maps_and_v1_maps(tmp_path):
    s = map_summary(os.path.join(REPO, "tests", "data", "maps-v2", "building.json"))
    assert (s["width"], s["height"], s["openings"]) == (6.0, 4.0, 4)
    assert sorted(s["inlets"]) == [(0.5, "bottom"), (1.0, "left")]
    s = map_summary(os.path.join(REPO, "data", "maps", "cluttered-1.json"))
    assert (s["width"], s["height"], s["openings"], s["inlets"]) == (10.0, 4.0, 2, [(1.0, "left")])
    # A window (an opening on an obstacle's edge) names no wall.
    (tmp_path / "maps").mkdir()
    with open(tmp_path / "maps" / "map-00000.json", "w") as f:
        json.dump({"format": "plumekit-map/2", "size": [6, 5], "openings": [
            {"kind": "inlet", "from": [0.2, 1], "to": [0.2, 2], "speed": 0.7},
            {"kind": "outlet", "from": [6, 1], "to": [6, 2]}]}, f)
    r = map_ranges(str(tmp_path), {"shards": []}, [0])
    assert r["inlet_speed_m_s"] == [0.7, 0.7] and r["inlet_walls"] == ["interior"]
    assert map_ranges(str(tmp_path), {"shards": []}, [1]) is None  # no map file: no ranges


def batches_of(data, cells=16 * 16 * 2):
    manifest, shards = open_dataset(data)
    return shards, V2Batches(shards, torch.device("cpu"), False, CELL, 16, cells)


def test_inputs_are_inverse_distance_and_zero_padded_with_a_mask(trained):
    shards, b = batches_of(trained["data"])
    for si, s in enumerate(shards):
        ny, nx = s.inputs.shape[2:]
        x, y, mask = b([(si, 0), (si, 1)])
        assert x.shape[2:] == (padded_size(ny, 16), padded_size(nx, 16))
        assert x.shape[2] % 16 == 0 and x.shape[3] % 16 == 0
        raw = np.asarray(s.inputs[:2])
        np.testing.assert_array_equal(x[:, :4, :ny, :nx].numpy(), raw[:, :4])
        np.testing.assert_allclose(x[:, 4, :ny, :nx].numpy(), 1 / np.maximum(raw[:, 4], CELL / 2),
                                   rtol=1e-6)
        assert x[:, 4, :ny, :nx].max() <= 1 / (CELL / 2) + 1e-4
        pad = ~mask.expand_as(x)
        assert torch.all(x[pad] == 0) and torch.all(y[~mask.expand_as(y)] == 0)
        assert int(mask.sum()) == 2 * ny * nx and bool(mask[:, :, :ny, :nx].all())


def test_loss_ignores_the_padding(trained):
    shards, b = batches_of(trained["data"])
    torch.manual_seed(0)
    model = PlumeUNet(5, 2, (4, 4, 4, 4), 3, 1)
    rows = [(1, 0), (1, 2)]  # 16 x 22 cells, padded to 16 x 32
    x, y, mask = b(rows)
    assert not bool(mask.all())
    loss = b.loss(model, rows, rows, 1.0, 1, 1000.0)
    # The same loss by hand, over the map cells only.
    p = model(x)
    ny, nx = shards[1].inputs.shape[2:]
    want = torch.mean((p[:, :, :ny, :nx] - y[:, :, :ny, :nx] / 1000.0) ** 2)
    assert torch.allclose(loss, want, rtol=1e-6)
    # Garbage (even NaN) in the padded targets or predictions changes nothing, gradients included.
    junk = y.clone()
    junk[~mask.expand_as(y)] = float("nan")
    junk[:, :, ny:, :] = 1e9
    junk[:, :, :ny, nx:] = float("nan")
    a = masked_squares(p, y / 1000.0, mask).sum()
    c = masked_squares(p, junk / 1000.0, mask).sum()
    assert a.item() == c.item()
    p2 = p.detach().clone().requires_grad_(True)
    masked_squares(p2, junk / 1000.0, mask).sum().backward()
    assert torch.isfinite(p2.grad).all() and torch.all(p2.grad[~mask.expand_as(p2)] == 0)


def test_every_batch_has_one_shape_and_a_cell_cap(trained):
    shards, b = batches_of(trained["data"], cells=16 * 32 * 2)
    rows = [(s, r) for s in range(len(shards)) for r in range(len(shards[s].map_ids))]
    counts = set()
    for seed in range(3):
        order = [rows[i] for i in np.random.default_rng(seed).permutation(len(rows))]
        got = b.batches(order)
        counts.add(len(got))
        assert sorted(r for g in got for r in g) == sorted(rows)  # each row once
        for g in got:
            shapes = {b.shape(r) for r in g}
            assert len(shapes) == 1
            (h, w), = shapes
            assert 1 <= len(g) <= max(1, 16 * 32 * 2 // (h * w)) and g == sorted(g)
    assert len(counts) == 1  # the same number of steps whatever the order
    assert b.cap == {(16, 16): 4, (16, 32): 2, (32, 16): 2}
    with pytest.raises(ValueError):
        b([(0, 0), (1, 0)])  # two padded shapes


def test_log_golden_pair_and_round_trip(trained):
    d = trained["dir"]
    assert "resumed from" in trained["log"]
    with open(d / "work" / "log.csv") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["epoch", "step", "train_loss", "val_loss", "val_rmse_mean", "seconds",
                       "val_rmse_over_peak"]
    assert len(rows) >= 2 and all(math.isfinite(float(v)) for v in rows[-1][3:])
    model, header = read_model(trained["model"])
    x = np.load(d / "model_input.npy")
    y = np.load(d / "model_output.npy")
    assert x.ndim == 4 and x.shape[1] == 5 and x.shape[2] % 16 == 0 and x.shape[3] % 16 == 0
    assert y.shape == (x.shape[0], 2) + x.shape[2:]
    scale = np.array([o["scale"] for o in header["outputs"]], np.float32)
    with torch.no_grad():
        p = model(torch.from_numpy(x)).numpy() * scale[None, :, None, None]
    np.testing.assert_allclose(p, y, rtol=1e-5, atol=1e-5 * np.abs(y).max())
    # The file's weights are best.pt's.
    best = torch.load(d / "work" / "best.pt")["model"]
    for k, v in model.state_dict().items():
        assert torch.equal(v, best[k])
    # The validation loss the trainer logged for the model's epoch is evaluate_v2's on the file.
    manifest, shards = open_dataset(trained["data"])
    _, val_rows, _ = split_by_map(shards, 0.1, 1)
    b = V2Batches(shards, torch.device("cpu"), True, CELL, 16, 64 * 64)
    loss, rmse, over_peak = evaluate_v2(model, b, val_rows, float(header["outputs"][0]["scale"]))
    assert loss == pytest.approx(header["training"]["best_val_loss"], rel=1e-5)
    assert 0 < over_peak < 10 and rmse > 0


def test_evaluate_scores_map_cells_and_prints_json(trained):
    out = run(os.path.join(HERE, "evaluate.py"), "--model", trained["model"], "--data",
              trained["data"], "--test", trained["data"], "--json", "--threads", "1")
    r = json.loads(out)
    assert r["features"] == "v2"
    held, every = r["held_out"], r["test_maps"]
    assert held["samples"] == 4 and every["all"]["samples"] == 12 and len(every["per_map"]) == 3
    per = every["per_sample"]
    assert len(per) == 12
    # The summary RMSE pools the per-sample squared errors over map cells.
    manifest, shards = open_dataset(trained["data"])
    cells = {os.path.basename(s.directory): s.inputs.shape[2] * s.inputs.shape[3] for s in shards}
    pooled = math.sqrt(sum(p["rmse_mean"] ** 2 * cells[p["shard"]] for p in per)
                       / sum(cells[p["shard"]] for p in per))
    assert every["all"]["mean"]["rmse"] == pytest.approx(pooled, rel=1e-9)
    peak = np.mean([p["peak_mean"] for p in per])
    assert every["all"]["mean"]["rmse_rel_peak"] == pytest.approx(pooled / peak, rel=1e-9)
    # The held-out RMSE is the trainer's last logged validation RMSE (the model's epoch).
    with open(trained["dir"] / "work" / "log.csv") as f:
        log = list(csv.DictReader(f))
    best = min(log, key=lambda row: float(row["val_loss"]))
    assert held["mean"]["rmse"] == pytest.approx(float(best["val_rmse_mean"]), rel=1e-4)
    assert held["mean"]["rmse_rel_peak"] == pytest.approx(float(best["val_rmse_over_peak"]), rel=1e-4)


def test_v1_datasets_train_as_before(tmp_path):
    """A v1 dataset (3 channels, 64 x 64) keeps v1's log columns and header (grid, arena)."""
    data = tmp_path / "data"
    run(os.path.join(HERE, "synthetic_dataset.py"), data, "--maps", 3, "--per-map", 2)
    run(os.path.join(HERE, "train.py"), "--data", data, "--work", tmp_path / "w", "--out",
        tmp_path / "m.pkcnn", "--threads", "1", "--batch", "2", "--max-steps", 2, *TINY)
    with open(tmp_path / "w" / "log.csv") as f:
        assert next(csv.reader(f)) == ["epoch", "step", "train_loss", "val_loss", "val_rmse_mean",
                                       "seconds"]
    _, header = read_model(str(tmp_path / "m.pkcnn"))
    assert header["features"]["grid"] == [64, 64] and "cell_size" not in header["features"]
    assert header["architecture"]["in_channels"] == 3
    assert "trained_on" not in header  # the synthetic v1 dataset has no map files
    assert np.load(tmp_path / "m_input.npy").shape[1:] == (3, 64, 64)


# --- several datasets (--data A B), as scripts/train-model-v2.sh trains families and buildings ---

SIZES_B = [(5.0, 2.4), (3.6, 4.2), (6.2, 3.0), (2.8, 2.2), (4.0, 5.6)]


@pytest.fixture(scope="module")
def two(tmp_path_factory):
    d = tmp_path_factory.mktemp("two")
    a, b = d / "fam", d / "bld"  # the folder names name the datasets
    run(os.path.join(HERE, "synthetic_dataset.py"), a, "--feature-cell", CELL, "--per-map", 2,
        "--sizes", ",".join("%gx%g" % s for s in SIZES + [(3.4, 2.8)]))
    run(os.path.join(HERE, "synthetic_dataset.py"), b, "--feature-cell", CELL, "--per-map", 2,
        "--seed", 4, "--sizes", ",".join("%gx%g" % s for s in SIZES_B))
    train = [os.path.join(HERE, "train.py"), "--data", a, b, "--work", d / "work", "--out",
             d / "model.pkcnn", "--threads", "1", "--batch", "1", "--epochs", 1, *TINY]
    out = run(*train)
    return {"dir": d, "data": [str(a), str(b)], "model": str(d / "model.pkcnn"), "log": out,
            "train": train}


def opened(dirs):
    shards, dataset_of = [], []
    for k, d in enumerate(dirs):
        own = open_dataset(d)[1]
        shards += own
        dataset_of += [k] * len(own)
    return shards, dataset_of


def test_several_datasets_split_each_one_s_maps_apart():
    # Map ids 0..3 in both datasets: map m of dataset k is the map (k, m).
    shards = [type("S", (), {"map_ids": np.full(3, m % 4)})() for m in range(8)]
    dataset_of = [0] * 4 + [1] * 4
    pooled = set()
    for seed in range(8):
        train, val, val_maps = split_datasets(shards, dataset_of, 0.3, seed)
        assert split_datasets(shards, dataset_of, 0.3, seed) == (train, val, val_maps)
        assert [len(v) for v in val_maps] == [1, 1]  # round(0.3 x 4): each dataset has its own
        assert sorted(train + val) == [(s, r) for s in range(8) for r in range(3)]
        maps = lambda rows: {(dataset_of[s], int(shards[s].map_ids[r])) for s, r in rows}  # noqa: E731
        assert not maps(train) & maps(val)  # no map in both splits
        assert maps(val) == {(k, m) for k in (0, 1) for m in val_maps[k]}
        # Dataset 0 splits as it would alone.
        assert val_maps[0] == split_by_map(shards[:4], 0.3, seed)[2]
        pooled.add(tuple(val_maps[0]) == tuple(val_maps[1]))
    assert False in pooled  # the same id is not held out in both datasets alike
    # A lone dataset: split_by_map as before (its first dataset's split).
    assert split_by_map(shards, 0.3, 5)[2] == split_datasets(shards, [0] * 8, 0.3, 5)[2][0]


def test_header_lists_both_datasets_with_their_validation_maps(two):
    _, header = read_model(two["model"])
    t = header["training"]
    assert "dataset" not in t and "val_maps" not in t and t["val_fraction"] == 0.1
    assert [os.path.basename(e["dataset"]) for e in t["datasets"]] == ["fam", "bld"]
    shards, dataset_of = opened(two["data"])
    train, val, val_maps = split_datasets(shards, dataset_of, 0.1, 1)
    assert [e["val_maps"] for e in t["datasets"]] == val_maps
    assert all(len(v) == 1 for v in val_maps)  # round(0.1 x 4 or 5) -> at least one each
    assert [e["train_samples"] for e in t["datasets"]] == [2 * 3, 2 * 4]
    assert [e["val_samples"] for e in t["datasets"]] == [2, 2]
    assert (t["train_samples"], t["val_samples"]) == (len(train), len(val)) == (14, 4)
    assert "validation maps fam %s; bld %s" % tuple(val_maps) in two["log"]
    # trained_on: the union over both datasets' training maps, read from their map files.
    maps = [map_summary(os.path.join(d, "maps", "map-%05d.json" % m))
            for k, d in enumerate(two["data"]) for m in range(len(SIZES) + 1 if k == 0 else 5)
            if m not in val_maps[k]]
    assert header["trained_on"] == ranges(maps)
    sizes = [s for k, sz in enumerate((SIZES + [(3.4, 2.8)], SIZES_B)) for m, s in enumerate(sz)
             if m not in val_maps[k]]
    assert header["trained_on"]["map_width_m"] == [min(w for w, _ in sizes), max(w for w, _ in sizes)]
    # The target scale: the largest training mean of both.
    want = max(float(np.max(s.targets[r, 0])) for s, k in zip(shards, dataset_of)
               for r in range(len(s.map_ids)) if int(s.map_ids[r]) not in val_maps[k])
    assert header["outputs"][0]["scale"] == pytest.approx(want, rel=1e-6)


def test_mixed_or_repeated_datasets_and_other_resumes_are_refused(two, tmp_path):
    v1 = tmp_path / "v1data"
    run(os.path.join(HERE, "synthetic_dataset.py"), v1, "--maps", 2, "--per-map", 1)
    common = ["--work", tmp_path / "w", "--out", tmp_path / "m.pkcnn", "--threads", "1", *TINY]
    err = run(os.path.join(HERE, "train.py"), "--data", two["data"][0], v1, *common, fail=True)
    assert "v1data is a v1 (grid 64x64) dataset" in err and "v2 (feature cell 0.2 m)" in err
    err = run(os.path.join(HERE, "train.py"), "--data", v1, two["data"][1], *common, fail=True)
    assert "bld is a v2 (feature cell 0.2 m) dataset, but" in err and "v1data" in err
    err = run(os.path.join(HERE, "train.py"), "--data", two["data"][0], two["data"][0], *common,
              fail=True)
    assert "gives" in err and "twice" in err
    # The checkpoint records its datasets: another order (or set) does not resume it.
    train = list(two["train"])
    i = train.index("--data")
    train[i + 1:i + 3] = train[i + 2:i + 3] + train[i + 1:i + 2]
    err = run(*train, fail=True)
    assert "was written for --data fam (8 samples, 4 maps), bld (10 samples, 5 maps)" in err
    assert "this run gives bld" in err
    err = run(*two["train"][:i + 2], *two["train"][i + 3:], fail=True)
    assert "this run gives fam (8 samples, 4 maps). Resume with the same datasets" in err


def test_evaluate_scores_each_dataset_and_pools_them(two):
    d = two["dir"]
    ev = [os.path.join(HERE, "evaluate.py"), "--model", two["model"], "--threads", "1"]
    out = run(*ev, "--data", *two["data"], "--test", *two["data"], "--json", "--out", d / "eval")
    r = json.loads(out)
    _, header = read_model(two["model"])
    held = r["held_out"]
    assert list(held["datasets"]) == ["fam", "bld"]
    for e, h in zip(header["training"]["datasets"], held["datasets"].values()):
        assert h["maps"] == e["val_maps"] and h["samples"] == e["val_samples"]
    assert held["samples"] == 4
    # The held-out figures are the trainer's validation figures over both datasets.
    with open(d / "work" / "log.csv") as f:
        log = list(csv.DictReader(f))
    assert len(log) == 1
    assert held["mean"]["rmse"] == pytest.approx(float(log[0]["val_rmse_mean"]), rel=1e-4)
    assert held["mean"]["rmse_rel_peak"] == pytest.approx(float(log[0]["val_rmse_over_peak"]), rel=1e-4)
    # Two --test sets: each alone, by folder name, and pooled.
    assert "test_maps" not in r and list(r["test_sets"]) == ["fam", "bld"]
    sets = r["test_sets"]
    assert [s["all"]["samples"] for s in sets.values()] == [8, 10]
    assert len(sets["fam"]["per_map"]) == 4 and len(sets["bld"]["per_map"]) == 5
    pooled = r["test_pooled"]
    assert pooled["sets"] == ["fam", "bld"] and pooled["all"]["samples"] == 18
    per = sets["fam"]["per_sample"] + sets["bld"]["per_sample"]
    cells = {}
    for k, name in enumerate(["fam", "bld"]):
        for s in open_dataset(two["data"][k])[1]:
            cells[name, os.path.basename(s.directory)] = s.inputs.shape[2] * s.inputs.shape[3]
    weights = [cells[name, p["shard"]] for name in ["fam", "bld"] for p in sets[name]["per_sample"]]
    want = math.sqrt(sum(p["rmse_mean"] ** 2 * w for p, w in zip(per, weights)) / sum(weights))
    assert pooled["all"]["mean"]["rmse"] == pytest.approx(want, rel=1e-9)
    alone = json.loads(run(*ev, "--test", two["data"][1], "--json"))["test_maps"]
    assert alone == sets["bld"]  # a set among several scores as it does alone
    md = open(d / "eval" / "evaluation.md").read()
    assert "| **fam** | 8 |" in md and "| **bld** | 10 |" in md and "| **all test sets** | 18 |" in md
    assert "held-out maps of bld" in md
    assert sorted(os.listdir(d / "eval" / "bld")) == ["synthetic-%d.png" % m for m in range(5)]
    # --data must be the model's datasets, in its order.
    err = run(*ev, "--data", *two["data"][::-1], "--json", fail=True)
    assert "trained on 2 datasets, fam, bld in that order; --data gives bld, fam" in err
