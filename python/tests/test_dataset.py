"""Datasets through the Python module: the thesis's 64 x 64 grid as single arrays, a physical grid
as one set of arrays per map, both exactly the bytes the shards hold, and a damaged shard refused
by name."""
import json
from pathlib import Path

import numpy as np
import pytest

import plumekit


def generate(cli, out, *flags):
    # Advection-diffusion: seconds for a few maps, the same files as the filament model's.
    cli("dataset", "generate", "--maps", 2, "--sources", 3, "--seed", 4, "--threads", 1,
        "--simulator", "advection-diffusion", "--out", out, *flags)
    return Path(out)


def shard_arrays(folder, shard):
    d = Path(folder) / "shards" / shard
    return {name: np.load(d / f"{name}.npy") for name in ("inputs", "targets", "sources")}


def test_a_thesis_grid_dataset_is_one_set_of_arrays(cli, tmp_path):
    folder = generate(cli, tmp_path / "thesis")
    data = plumekit.read_dataset(folder)
    assert data["inputs"].shape == (6, 3, 64, 64) and data["targets"].shape == (6, 2, 64, 64)
    assert list(data["map_ids"]) == [0, 0, 0, 1, 1, 1]
    assert "maps" not in data
    first = shard_arrays(folder, "shard-00000")
    assert np.array_equal(data["inputs"][:3], first["inputs"])
    assert np.array_equal(data["targets"][:3], first["targets"])


def test_a_physical_grid_dataset_is_one_set_of_arrays_per_map(cli, tmp_path):
    folder = generate(cli, tmp_path / "physical", "--feature-cell", 0.2)
    data = plumekit.read_dataset(folder)
    assert data["feature_cell"] == pytest.approx(0.2)
    assert "inputs" not in data
    manifest = json.loads((folder / "manifest.json").read_text())
    assert [m["map_id"] for m in data["maps"]] == [s["map_index"] for s in manifest["shards"]]
    for m in data["maps"]:
        arena = plumekit.read_map(folder / m["map"])
        ny, nx = round(arena.height / 0.2), round(arena.width / 0.2)
        assert m["inputs"].shape == (3, 5, ny, nx)  # region, distance, wind u and v, source
        assert m["targets"].shape == (3, 2, ny, nx)
        assert m["sources"].shape == (3, 2)
        assert np.abs(m["inputs"][:, 2:4]).max() > 0.05  # the wind is there
        stored = shard_arrays(folder, f"shard-{m['map_id']:05d}")
        for name in ("inputs", "targets", "sources"):
            assert np.array_equal(m[name], stored[name]), name


def test_a_damaged_shard_is_refused_by_its_file(cli, tmp_path):
    folder = generate(cli, tmp_path / "damaged", "--feature-cell", 0.2)
    target = folder / "shards" / "shard-00001" / "targets.npy"
    raw = bytearray(target.read_bytes())
    raw[-1] ^= 0x01
    target.write_bytes(bytes(raw))
    with pytest.raises(Exception, match="targets.npy"):
        plumekit.read_dataset(folder)


def test_a_hybrid_dataset_has_the_physics_channel_before_the_source(cli, tmp_path):
    folder = generate(cli, tmp_path / "hybrid", "--feature-cell", 0.2, "--physics-input")
    data = plumekit.read_dataset(folder)
    for m in data["maps"]:
        assert m["inputs"].shape[1] == 6  # region, distance, wind u and v, physics, source
        stored = shard_arrays(folder, f"shard-{m['map_id']:05d}")
        assert np.array_equal(m["inputs"], stored["inputs"])
        # The simulator is advection-diffusion: the physics channel is its plume, up to the decay
        # (the channel's is the world's, 1/28 s; the simulator's here none), so never above it.
        assert m["inputs"][:, 4].max() > 100
        assert np.all(m["inputs"][:, 4] <= m["targets"][:, 0] * (1 + 1e-5) + 1e-3)
