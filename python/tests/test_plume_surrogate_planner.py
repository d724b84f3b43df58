"""Plumes, the CNN surrogate and the planner, against the command line and simple physics."""
import numpy as np
import pytest

import plumekit


@pytest.fixture(scope="module")
def block(data):
    return plumekit.read_map(data / "test-maps" / "test-1-block.json")


@pytest.fixture(scope="module")
def wind(block):
    return plumekit.flow(block, cell=0.1)


def test_advection_diffusion_plume(block, wind):
    src = block.sources[0]
    p = plumekit.plume(wind, src, model="advection-diffusion", cell=0.1)
    mean = p["mean"]
    assert mean.shape == (40, 100) and (mean >= 0).all() and (p["std"] == 0).all()
    j, i = np.unravel_index(mean.argmax(), mean.shape)
    # The peak is at the source's cell, and the gas goes downwind (to larger x) more than upwind.
    assert abs((i + 0.5) * 0.1 - src[0]) <= 0.15 and abs((j + 0.5) * 0.1 - src[1]) <= 0.15
    assert mean[:, i + 10].sum() > 10 * mean[:, max(i - 10, 0)].sum()


def test_filament_plume_is_seeded(block, wind):
    a = plumekit.plume(wind, block.sources[0], seed=5, world="thesis")
    b = plumekit.plume(wind, block.sources[0], seed=5, world="thesis")
    c = plumekit.plume(wind, block.sources[0], seed=6, world="thesis")
    assert a["mean"].shape == (64, 64)
    assert np.array_equal(a["mean"], b["mean"]) and not np.array_equal(a["mean"], c["mean"])


def test_source_in_obstacle(block, wind):
    inside = tuple(np.mean(block.obstacles[0], axis=0))
    with pytest.raises(plumekit.InputError, match="plume.source"):
        plumekit.plume(wind, inside)


def test_surrogate_matches_cli(tmp_path, block, cli):
    src = block.sources[0]
    p = plumekit.predict(block, src)  # the default: the hybrid, on 0.2 m cells
    assert p["mean"].shape == (20, 50) and p["mean"].dtype == np.float32
    cli("predict", plumekit.data_dir() + "/test-maps/test-1-block.json",
        "--source", f"{src[0]!r},{src[1]!r}", "--out", tmp_path / "p")
    assert np.array_equal(np.load(tmp_path / "p" / "mean.npy"), p["mean"])
    net = plumekit.Surrogate(block, threads=2)
    assert np.array_equal(net.predict(src)["std"], p["std"])
    thesis = plumekit.predict(block, src, cnn="thesis")
    assert thesis["mean"].shape == (64, 64)
    named = plumekit.data_dir() + "/models/plume-unet.pkcnn"
    assert np.array_equal(plumekit.predict(block, src, cnn=named)["mean"], thesis["mean"])


def test_thesis_model_refuses_another_arena(data):
    floor = plumekit.read_map(data / "floors" / "tb3_world.json")
    with pytest.raises(plumekit.InputError, match="plume-unet.pkcnn.*cnn=\"hybrid\""):
        plumekit.Surrogate(floor, cnn="thesis")
    with pytest.raises(plumekit.InputError, match="no-such.pkcnn: no such model file"):
        plumekit.Surrogate(floor, cnn="no-such.pkcnn")


def test_plan_goes_round_the_block(block):
    start, goal = (0.5, 2.0), (9.5, 2.0)
    r = plumekit.plan(block, start, goal)
    assert r["path"][0] == start and r["path"][-1] == goal
    assert r["length"] >= 9.0
    planner = plumekit.Planner(block, margin=0.3)
    longer = planner.plan(start, goal)
    assert longer["length"] >= r["length"]
    inside = tuple(np.mean(block.obstacles[0], axis=0))
    with pytest.raises(plumekit.InputError):
        planner.plan(start, inside)
