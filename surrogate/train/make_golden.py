"""Writes the golden model files and input/output pairs that tests/surrogate checks the C++ engine
against. Run from the repository root:  /usr/bin/python3 surrogate/train/make_golden.py
Deterministic (fixed seeds, CPU); rewrites tests/data/surrogate/.
"""
import argparse
import os
import sys

import numpy as np
import torch
import torch.nn.functional as F

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from model import REAL_PARAMETERS, PlumeUNet, parameter_count, pool_margin  # noqa: E402
from model_file import DEFAULT_FEATURES, DEFAULT_OUTPUTS, v2_features, write_model  # noqa: E402

# The hybrid golden model's physics channel scale and output scales: all different, so a unit slip
# (the output's scale where the input's belongs) shows in the C++ test.
HYBRID_INPUT_SCALE = 250.0
HYBRID_OUTPUT_SCALES = (40.0, 20.0)


def features(rng, n, rows, cols, arena):
    """Plausible feature maps: labels 0..4 in patches (so max-pool meets ties), SDF, distance."""
    x = np.zeros((n, 3, rows, cols), dtype=np.float32)
    for i in range(n):
        coarse = rng.integers(0, 5, size=(rows // 4 + 1, cols // 4 + 1))
        x[i, 0] = np.kron(coarse, np.ones((4, 4)))[:rows, :cols]
        x[i, 1] = rng.uniform(-0.5, 2.0, size=(rows, cols))
        yy, xx = np.meshgrid((np.arange(rows) + 0.5) * arena[1] / rows,
                             (np.arange(cols) + 0.5) * arena[0] / cols, indexing="ij")
        sx, sy = rng.uniform(0, arena[0]), rng.uniform(0, arena[1])
        x[i, 2] = np.hypot(xx - sx, yy - sy)
    return x


def smooth_features(n, rows, cols, arena, seed):
    """An empty arena's features (free cells, walls on the edge, distance to the nearest wall, to
    a source): smooth fields, so thousands of max-pool windows are near-ties (margins ~1e-8)."""
    rng = np.random.default_rng(seed)
    x = np.zeros((n, 3, rows, cols), dtype=np.float32)
    yy, xx = np.meshgrid((np.arange(rows) + 0.5) * arena[1] / rows,
                         (np.arange(cols) + 0.5) * arena[0] / cols, indexing="ij")
    for i in range(n):
        x[i, 0] = 1.0
        x[i, 0, [0, -1], :] = 2.0
        x[i, 0, :, [0, -1]] = 2.0
        x[i, 1] = np.minimum(np.minimum(xx, arena[0] - xx), np.minimum(yy, arena[1] - yy))
        sx, sy = rng.uniform(0, arena[0]), rng.uniform(0, arena[1])
        x[i, 2] = np.hypot(xx - sx, yy - sy)
    return x


def pool_indices(model, x):
    """PyTorch's argmax of every 2x2 max-pool (the encoder of model.forward), levels concatenated,
    each [n, c, h/2, w/2] flat y*w+x in its input plane; float64 so core/npy reads it exactly."""
    out = []
    h = torch.from_numpy(x)
    with torch.no_grad():
        for block in model.encoder:
            for conv in block:
                h = F.relu(conv(h))
            h, ind = F.max_pool2d(h, 2, 2, return_indices=True)
            out.append(ind.numpy().reshape(-1))
    return np.concatenate(out).astype(np.float64)


def write_pair(out_dir, stem, model, x, outputs_meta):
    model.eval()
    with torch.no_grad():
        y = model(torch.from_numpy(x)).numpy()
    margin = float(pool_margin(model, x).min())
    scales = np.array([o["scale"] for o in outputs_meta], dtype=np.float32)
    y = y * scales[None, :, None, None]
    np.save(os.path.join(out_dir, stem + "_input.npy"), x)
    np.save(os.path.join(out_dir, stem + "_output.npy"), y.astype(np.float32))
    np.save(os.path.join(out_dir, stem + "_pool_indices.npy"), pool_indices(model, x))
    return y, margin


def golden(out_dir, stem, model, batch, features_meta, outputs_meta, seed):
    rows, cols = features_meta["grid"]
    rng = np.random.default_rng(seed)
    x = features(rng, batch, rows, cols, features_meta["arena"])
    model.eval()
    with torch.no_grad():
        y = model(torch.from_numpy(x)).numpy()
    # How exposed the pair is to max-pool near-ties (model.pool_margin); printed, for the record.
    margin = float(pool_margin(model, x).min())
    scales = np.array([o["scale"] for o in outputs_meta], dtype=np.float32)
    y = y * scales[None, :, None, None]
    size = write_model(os.path.join(out_dir, stem + ".pkcnn"), model, features_meta, outputs_meta,
                       training={"note": "random initialisation, seed %d; golden test model" % seed})
    np.save(os.path.join(out_dir, stem + "_input.npy"), x)
    np.save(os.path.join(out_dir, stem + "_output.npy"), y.astype(np.float32))
    np.save(os.path.join(out_dir, stem + "_pool_indices.npy"), pool_indices(model, x))
    print(f"{stem}: {parameter_count(model)} parameters, {size} bytes, input {x.shape}, "
          f"output max |y| {np.abs(y).max():.4g}, smallest max-pool margin {margin:.2g}")


def hybrid_features(cell_size, multiple):
    """A hybrid model's contract (issue 46): the v2 channels with physics_mean, the physics plume
    divided by its scale, with the plume's options, before the source distance."""
    f = v2_features(cell_size, multiple)
    f["channels"].insert(4, {"name": "physics_mean", "unit": "concentration / scale",
                             "scale": HYBRID_INPUT_SCALE, "diffusivity": 0.05,
                             "decay_rate": 1.0 / 28.0, "release_rate": 1000.0})
    return f


def hybrid_inputs(rng, n, rows, cols, cell):
    """Six plausible channels on a physical grid: labels in patches, SDF, a wind, a plume-like blob
    (0 on obstacle labels) in concentration / scale, and the inverse source distance."""
    x = np.zeros((n, 6, rows, cols), dtype=np.float32)
    yy, xx = np.meshgrid((np.arange(rows) + 0.5) * cell, (np.arange(cols) + 0.5) * cell,
                         indexing="ij")
    for i in range(n):
        coarse = rng.integers(0, 5, size=(rows // 4 + 1, cols // 4 + 1))
        x[i, 0] = np.kron(coarse, np.ones((4, 4)))[:rows, :cols]
        x[i, 1] = rng.uniform(-0.5, 2.0, size=(rows, cols))
        x[i, 2] = rng.uniform(0.0, 1.5, size=(rows, cols))
        x[i, 3] = rng.uniform(-0.5, 0.5, size=(rows, cols))
        sx, sy = rng.uniform(0, cols * cell), rng.uniform(0, rows * cell)
        d = np.hypot(xx - sx, yy - sy)
        plume = 0.2 * np.exp(-np.maximum(xx - sx, 0) / 4.0 - (yy - sy) ** 2 / 0.5 - d / 2.0)
        x[i, 4] = np.where(x[i, 0] == 0, 0.0, plume)
        x[i, 5] = 1.0 / np.maximum(d, cell / 2)
    return x


def golden_hybrid(out_dir, seed):
    """A residual model: the pair's output is the network's, each output times its scale, the
    mean plus HYBRID_INPUT_SCALE times the physics channel (float64 sum, then float32: what the
    engine's surrogate::residual_output does)."""
    torch.manual_seed(seed)
    model = PlumeUNet(in_channels=6, out_channels=2, filters=(4, 4, 4, 4), kernel=3, convs=2)
    feats = hybrid_features(0.2, 16)
    outs = [dict(DEFAULT_OUTPUTS[0], scale=HYBRID_OUTPUT_SCALES[0], plus_input="physics_mean"),
            dict(DEFAULT_OUTPUTS[1], scale=HYBRID_OUTPUT_SCALES[1])]
    x = hybrid_inputs(np.random.default_rng(seed), 2, 32, 48, 0.2)
    model.eval()
    with torch.no_grad():
        y = model(torch.from_numpy(x)).numpy()
    margin = float(pool_margin(model, x).min())
    y = y * np.array(HYBRID_OUTPUT_SCALES, dtype=np.float32)[None, :, None, None]
    net_mean = np.abs(y[:, 0]).max()
    y[:, 0] = (y[:, 0].astype(np.float64) + HYBRID_INPUT_SCALE * x[:, 4].astype(np.float64))
    note = "random initialisation, seed %d; golden test model" % seed
    size = write_model(os.path.join(out_dir, "hybrid.pkcnn"), model, feats, outs,
                       training={"note": note})
    np.save(os.path.join(out_dir, "hybrid_input.npy"), x)
    np.save(os.path.join(out_dir, "hybrid_output.npy"), y.astype(np.float32))
    print(f"hybrid: {parameter_count(model)} parameters, {size} bytes, input {x.shape}, "
          f"max |network mean| {net_mean:.4g}, max |mean| {np.abs(y[:, 0]).max():.4g}, "
          f"max |std| {np.abs(y[:, 1]).max():.4g}, smallest max-pool margin {margin:.2g}")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default_out = os.path.normpath(os.path.join(here, "..", "..", "tests", "data", "surrogate"))
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", default=default_out)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    torch.set_num_threads(1)

    # (a) the real architecture, randomly initialised.
    torch.manual_seed(5)
    real = PlumeUNet()
    count = parameter_count(real)
    if count != REAL_PARAMETERS:
        sys.exit(f'real architecture has {count} parameters, docs/design/surrogate.md, "Architecture" says {REAL_PARAMETERS}')
    golden(args.out, "real", real, 1, DEFAULT_FEATURES, DEFAULT_OUTPUTS, seed=11)
    # (a') the same model on smooth, plume-like features: near-ties everywhere. The engine is
    # compared with PyTorch on these with PyTorch's pool indices forced (tests/surrogate).
    x = smooth_features(2, 64, 64, DEFAULT_FEATURES["arena"], seed=17)
    _, margin = write_pair(args.out, "real_smooth", real, x, DEFAULT_OUTPUTS)
    print(f"real_smooth: input {x.shape}, smallest max-pool margin {margin:.2g}")

    # (b) odd channel counts, kernel 3, 2 convolutions a block, a grid that does not halve evenly
    # (max-pool floors, max-unpool pads back) and a non-unit output scale.
    torch.manual_seed(7)
    odd = PlumeUNet(in_channels=3, out_channels=2, filters=(3, 5, 7, 9), kernel=3, convs=2)
    feats = dict(DEFAULT_FEATURES, grid=[21, 30], arena=[7.5, 5.25])
    outs = [dict(DEFAULT_OUTPUTS[0], scale=2.5), dict(DEFAULT_OUTPUTS[1])]
    golden(args.out, "odd", odd, 3, feats, outs, seed=13)

    # (c) a hybrid residual model (issue 46): six channels on a physical grid, the mean adds the
    # physics channel back.
    golden_hybrid(args.out, seed=19)


if __name__ == "__main__":
    main()
