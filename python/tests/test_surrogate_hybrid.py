"""The shipped hybrid model (issue 46: the physics plume of the source among its inputs) through
the Python module: its features hold the physics plume, and the prediction is PyTorch's on them,
and `plumekit predict`'s."""
import sys
from pathlib import Path

import numpy as np
import torch

import plumekit

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "surrogate" / "train"))
from model_file import read_model  # noqa: E402


def test_hybrid_model_predicts_what_pytorch_does(data, tmp_path, cli):
    path = data / "models" / "plume-unet-v3.pkcnn"
    net, header = read_model(path)
    block = plumekit.read_map(data / "test-maps" / "test-1-block.json")
    s = plumekit.Surrogate(block, cnn=path)
    src = (2.0, 2.0)
    x = s.features(src)
    assert x.shape == (6, 32, 64)  # 20 x 50 cells of 0.2 m, padded to multiples of 16
    scale = header["features"]["channels"][4]["scale"]
    assert x[4].max() * scale > 500  # the physics plume, in concentration units over the scale
    assert np.all(x[4, 20:, :] == 0) and np.all(x[4, :, 50:] == 0)  # the padding
    with torch.no_grad():
        y = net(torch.from_numpy(x[None])).numpy()[0] * header["outputs"][0]["scale"]
    p = s.predict(src)
    free = x[0, :20, :50] != 0
    expect = np.where(free, np.maximum(y[0, :20, :50], 0), 0)
    assert np.allclose(p["mean"], expect, rtol=1e-4, atol=1e-4 * np.abs(y[0]).max())
    cli("predict", data / "test-maps" / "test-1-block.json", "--cnn", path, "--source", "2,2",
        "--out", tmp_path / "p")
    assert np.array_equal(np.load(tmp_path / "p" / "mean.npy"), p["mean"])
