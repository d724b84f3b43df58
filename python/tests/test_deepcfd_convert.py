"""Bring your own DeepCFD model (issue 19): a UNetEx-style network with weight norm, saved by
PyTorch, converted by surrogate/train/convert_deepcfd.py, predicts in plumekit's engine what it
predicts in PyTorch, as a mean-only model with the inverse source channel; `localize` runs with it.
The checkpoint is made here: no third-party weights are committed."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import torch
import torch.nn as nn
import torch.nn.functional as F
from torch.nn.utils import weight_norm

import plumekit

ROOT = Path(__file__).resolve().parents[2]
CONVERTER = ROOT / "surrogate" / "train" / "convert_deepcfd.py"


def layer(cin, cout, kernel, convolution, activation, batch_norm):
    """DeepCFD's create_layer: a weight-normalised convolution, then ReLU, then batch norm."""
    parts = [weight_norm(convolution(cin, cout, kernel, padding=kernel // 2))]
    if activation:
        parts.append(nn.ReLU())
    if batch_norm:
        parts.append(nn.BatchNorm2d(cout))
    return nn.Sequential(*parts)


class UNetEx(nn.Module):
    """The wiring and the key names of DeepCFD's Models/UNetEx.py (Ribeiro et al. 2020)."""

    def __init__(self, in_channels, out_channels, kernel, filters, layers, batch_norm=False):
        super().__init__()
        blocks, prev = [], in_channels
        for f in filters:
            blocks.append(nn.Sequential(*[layer(prev if j == 0 else f, f, kernel, nn.Conv2d, True,
                                                batch_norm) for j in range(layers)]))
            prev = f
        self.encoder = nn.Sequential(*blocks)
        decoders = []
        for _ in range(out_channels):
            levels = []
            for b, f in enumerate(filters):
                last = filters[b - 1] if b > 0 else 1
                final = b == 0
                levels.insert(0, nn.Sequential(*[
                    layer(2 * f if j == 0 else f, last if j == layers - 1 else f, kernel,
                          nn.ConvTranspose2d, not (final and j == layers - 1),
                          batch_norm and not (final and j == layers - 1))
                    for j in range(layers)]))
            decoders.append(nn.Sequential(*levels))  # the deepest level first
        self.decoders = nn.Sequential(*decoders)

    def forward(self, x):
        skips, indices = [], []
        for block in self.encoder:
            x = block(x)
            skips.append(x)
            x, ind = F.max_pool2d(x, 2, 2, return_indices=True)
            indices.append(ind)
        outputs = []
        for decoder in self.decoders:
            y = x
            for k, block in enumerate(decoder):
                b = len(skips) - 1 - k
                y = F.max_unpool2d(y, indices[b], 2, 2, output_size=skips[b].shape[-2:])
                y = block(torch.cat([skips[b], y], dim=1))
            outputs.append(y)
        return torch.cat(outputs, dim=1)


def convert(*args):
    return subprocess.run([sys.executable, str(CONVERTER), *map(str, args)], capture_output=True,
                          text=True)


@pytest.fixture
def checkpoint(tmp_path):
    torch.manual_seed(3)
    net = UNetEx(3, 1, 3, [4, 8], 2)
    with torch.no_grad():
        # weight_norm starts with g = |v|, w = v: other lengths make the folding count.
        for name, g in net.named_parameters():
            if name.endswith("weight_g"):
                g.mul_(0.5 + torch.rand_like(g))
        net.decoders[0][-1][-1][0].bias.fill_(0.5)  # a positive output: the clamp hides nothing
    path = tmp_path / "deepcfd.pt"
    torch.save({"epoch": 7, "state_dict": net.state_dict()}, path)
    return net, path


def test_engine_matches_pytorch_with_weight_norm_folded(tmp_path, checkpoint, data):
    net, path = checkpoint
    out = tmp_path / "deepcfd.pkcnn"
    r = convert(path, out, "--arena", "10,4", "--source-form", "inverse", "--min-distance", 0.05)
    assert r.returncode == 0, r.stderr
    assert "weight norm folded" in r.stdout
    block = plumekit.read_map(data / "test-maps" / "test-1-block.json")
    model = plumekit.Surrogate(block, cnn=out)
    for source in [(7.5, 2.0), (2.2, 0.6)]:
        x = model.features(source)
        d = np.hypot(*np.meshgrid((np.arange(64) + 0.5) * 10 / 64 - source[0],
                                  (np.arange(64) + 0.5) * 4 / 64 - source[1], indexing="xy"))
        np.testing.assert_allclose(x[2], 1 / np.maximum(d, 0.05), rtol=1e-5)
        with torch.no_grad():
            y = net(torch.from_numpy(x[None])).numpy()[0, 0]
        y = np.where(x[0] == 0, 0.0, np.maximum(y, 0.0))  # plumekit's clamp and obstacle cells
        p = model.predict(source)
        assert p["std"] is None
        # Within 1e-4 of the peak, but where a max-pool window is a near-tie on the map's flat
        # features (margins of 1e-8 here; docs/design/surrogate.md, "Golden files"): float32 engines
        # summing in different orders may pick another cell, which moves one value locally. A
        # wrong conversion (weight norm not folded, levels swapped) errs everywhere.
        err = np.abs(p["mean"] - y) / np.abs(y).max()
        assert np.mean(err <= 1e-4) >= 0.99
        assert err.max() <= 1e-2
        assert np.abs(y).max() > 0.1


def test_localize_runs_with_a_mean_only_model(tmp_path, checkpoint, data, cli):
    _, path = checkpoint
    out = tmp_path / "deepcfd.pkcnn"
    assert convert(path, out, "--arena", "10,4").returncode == 0
    run = cli("localize", data / "test-maps" / "test-1-block.json", "--source", "7.5,2",
              "--start", "2,2", "--cnn", out, "--max-samples", 3)
    assert run["samples"] == 3 and run["stopped_by"] == "max_samples"


def test_predict_writes_the_mean_alone(tmp_path, checkpoint, data, cli):
    _, path = checkpoint
    out = tmp_path / "deepcfd.pkcnn"
    assert convert(path, out, "--arena", "10,4").returncode == 0
    pictures = tmp_path / "predict"
    run = cli("predict", data / "test-maps" / "test-1-block.json", "--source", "7.5,2", "--cnn",
              out, "--out", pictures)
    assert run["peak_std"] is None and run["peak_mean"] > 0.1
    assert (pictures / "mean.npy").exists() and (pictures / "plume.png").exists()
    assert not (pictures / "std.npy").exists()


def test_maps_outside_the_training_ranges_are_warned_about(tmp_path, checkpoint, data, cli):
    _, path = checkpoint
    block = data / "test-maps" / "test-1-block.json"  # inlet on the left at 1 m/s
    inside, outside = tmp_path / "inside.pkcnn", tmp_path / "outside.pkcnn"
    assert convert(path, inside, "--arena", "10,4", "--trained-on",
                   '{"map_width_m": [10, 10], "inlet_walls": ["left"]}').returncode == 0
    assert convert(path, outside, "--arena", "10,4", "--trained-on",
                   '{"inlet_speed_m_s": [2, 3]}').returncode == 0
    assert plumekit.Surrogate(plumekit.read_map(block), cnn=inside).warnings == []
    warnings = plumekit.Surrogate(plumekit.read_map(block), cnn=outside).warnings
    assert len(warnings) == 1 and "blows at 1 m/s" in warnings[0]
    run = cli("predict", block, "--source", "7.5,2", "--cnn", outside, "--out", tmp_path / "p")
    assert run["warnings"] == warnings
    r = convert(path, tmp_path / "bad.pkcnn", "--arena", "10,4", "--trained-on",
                '{"inlet_walls": ["ceiling"]}')
    assert r.returncode == 2 and "inlet_walls" in r.stderr


def test_converter_refuses_what_it_cannot_convert(tmp_path, checkpoint):
    _, path = checkpoint
    bn = tmp_path / "bn.pt"
    torch.save(UNetEx(3, 1, 3, [4, 8], 2, batch_norm=True).state_dict(), bn)
    r = convert(bn, tmp_path / "bn.pkcnn", "--arena", "10,4")
    assert r.returncode == 2 and "batch normalisation" in r.stderr
    assert not (tmp_path / "bn.pkcnn").exists()
    junk = tmp_path / "junk.pt"
    junk.write_bytes(b"not a checkpoint")
    r = convert(junk, tmp_path / "junk.pkcnn", "--arena", "10,4")
    assert r.returncode == 2 and "torch.load" in r.stderr
    mine = tmp_path / "mine.pkcnn"
    mine.write_text("keep")
    r = convert(path, mine, "--arena", "10,4")
    assert r.returncode == 2 and mine.read_text() == "keep"
    r = convert(path, tmp_path / "two.pkcnn", "--arena", "10,4", "--outputs", "mean,std")
    assert r.returncode == 2 and "1 outputs" in r.stderr
