"""A physical-grid (v2) model through the Python module: any map size, the wind as input, the same
numbers as `plumekit predict` and as PyTorch on the module's own features."""
import sys
from pathlib import Path

import numpy as np
import pytest
import torch

import plumekit

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "surrogate" / "train"))
from model import PlumeUNet  # noqa: E402
from model_file import v2_features, write_model  # noqa: E402


@pytest.fixture(scope="module")
def v2_model(tmp_path_factory):
    torch.manual_seed(3)
    net = PlumeUNet(in_channels=5, filters=(4, 8), kernel=3, convs=1)
    path = tmp_path_factory.mktemp("v2") / "v2.pkcnn"
    write_model(path, net, features=v2_features(0.2, 4))
    return path, net.eval()


def test_v2_model_runs_on_a_floor_with_its_wind(v2_model, data, tmp_path, cli):
    path, net = v2_model
    floor = plumekit.read_map(data / "floors" / "tb3_world.json")
    s = plumekit.Surrogate(floor, cnn=path)
    src = (-1.5, -1.5)
    p = s.predict(src)
    # 19.2 x 19.2 m at 0.2 m: 96 x 96 cells, already a multiple of 4.
    assert p["mean"].shape == (96, 96) and p["std"].shape == (96, 96)
    x = s.features(src)
    assert x.shape == (5, 96, 96)
    assert np.abs(x[2:4]).max() > 0.1  # the wind is in the input
    with torch.no_grad():
        y = net(torch.from_numpy(x[None])).numpy()[0]
    free = x[0] != 0
    expect = np.where(free, np.maximum(y[0], 0), 0)
    assert np.allclose(p["mean"], expect, rtol=1e-4, atol=1e-4 * np.abs(y[0]).max())
    out = cli("predict", data / "floors" / "tb3_world.json", "--cnn", path, "--source", "-1.5,-1.5",
              "--out", tmp_path / "p")
    assert out["grid"] == [96, 96]
    assert np.array_equal(np.load(tmp_path / "p" / "mean.npy"), p["mean"])


def test_v2_model_pads_a_map_that_is_not_a_multiple(v2_model, data):
    path, _ = v2_model
    block = plumekit.read_map(data / "test-maps" / "test-1-block.json")
    s = plumekit.Surrogate(block, cnn=path)
    src = block.sources[0]
    # 10 x 4 m at 0.2 m: 50 x 20 cells, padded to 52 x 20 for a multiple of 4.
    assert s.predict(src)["mean"].shape == (20, 50)
    x = s.features(src)
    assert x.shape == (5, 20, 52)
    assert not x[:, :, 50:].any()
