"""Scores a plumekit-cnn/1 model on held-out maps and on the test maps' ground truth.

    /usr/bin/python3 surrogate/train/evaluate.py --model data/models/plume-unet.pkcnn \
        --data TRAINING_DATASET --test TEST_MAP_TRUTH --out data/models/plume-unet-eval

--data: the training dataset; only the validation maps named in the model's header
(training.val_maps) are scored, so the figures are for maps the model never saw. --test: the
dataset of the nine test maps (`plumekit dataset generate --map-dir data/test-maps --seed 0`). Either may
be left out.

Figures, per channel (mean, std), in dataset units:
  rmse          per-pixel root mean squared error over every pixel of every sample
  rmse_rel_peak rmse / the average over samples of the sample's peak ground-truth mean
  sse           DeepCFD's figure: squared error summed over a sample's pixels, averaged over samples
  rel_l2        ||prediction - truth|| / ||truth|| over the whole set: the plumes cover a small part
                of the arena, so rmse_rel_peak is small even for a model that predicts nothing;
  zero_rmse_rel_peak  that baseline: the rmse_rel_peak of predicting zero everywhere
Writes OUT/evaluation.json (overall and per test map), OUT/evaluation.md (the same as tables) and
OUT/test-K-NAME.png: for three sources of each test map, ground truth, prediction and absolute
error of the mean (as the thesis's Fig. 14.5), one shared colour scale per row, obstacles in grey.
"""
import argparse
import json
import os
import struct
import sys
import zlib

import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from model_file import output_scales, read_model  # noqa: E402
from shards import open_dataset  # noqa: E402

CHANNELS = ("mean", "std")


def predict(model, scales, x, batch=32):
    out = []
    with torch.no_grad():
        for i in range(0, len(x), batch):
            out.append(model(torch.from_numpy(np.ascontiguousarray(x[i:i + batch]))).numpy())
    return np.concatenate(out) * scales[None, :, None, None]


def scores(pred, truth):
    """Figures of one set of samples (arrays [n, 2, H, W])."""
    err = (pred.astype(np.float64) - truth) ** 2
    peak = float(np.mean(truth[:, 0].reshape(len(truth), -1).max(axis=1)))
    out = {"samples": int(len(truth)), "average_peak_mean": peak}
    for c, name in enumerate(CHANNELS):
        rmse = float(np.sqrt(err[:, c].mean()))
        out[name] = {"rmse": rmse, "rmse_rel_peak": rmse / peak if peak > 0 else None,
                     "sse": float(err[:, c].reshape(len(truth), -1).sum(axis=1).mean()),
                     "rel_l2": float(np.sqrt(err[:, c].sum() / np.sum(truth[:, c].astype(np.float64) ** 2))),
                     "zero_rmse_rel_peak": float(np.sqrt(np.mean(truth[:, c].astype(np.float64) ** 2)))
                     / peak if peak > 0 else None}
    return out


def load_rows(directory, keep_maps=None):
    """inputs, targets, map_ids of every sample (of the maps in keep_maps, if given)."""
    _, shards = open_dataset(directory)
    xs, ys, ids = [], [], []
    for s in shards:
        rows = np.arange(len(s.map_ids))
        if keep_maps is not None:
            rows = rows[np.isin(s.map_ids, list(keep_maps))]
        if rows.size:
            xs.append(np.asarray(s.inputs[rows], dtype=np.float32))
            ys.append(np.asarray(s.targets[rows], dtype=np.float32))
            ids.append(np.asarray(s.map_ids[rows]))
    if not xs:
        raise ValueError(f"{directory}: no samples to score")
    return np.concatenate(xs), np.concatenate(ys), np.concatenate(ids)


# --- PNG pictures, written with zlib only (no plotting library is needed) ---

_ANCHORS = np.array([  # perceptually ordered dark blue -> teal -> yellow (viridis-like)
    [68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]], dtype=np.float64)


def colour(v):
    """Values in [0, 1] -> uint8 RGB."""
    t = np.clip(v, 0.0, 1.0) * (len(_ANCHORS) - 1)
    i = np.minimum(t.astype(int), len(_ANCHORS) - 2)
    f = (t - i)[..., None]
    return (_ANCHORS[i] * (1 - f) + _ANCHORS[i + 1] * f).astype(np.uint8)


def write_png(path, rgb):
    h, w, _ = rgb.shape
    raw = b"".join(b"\0" + rgb[r].tobytes() for r in range(h))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(png)
    os.replace(tmp, path)


def panel(field, labels, vmax, source, sx=5, sy=2):
    """One 64x64 field as an image of (64*sy) x (64*sx) pixels (10 x 4 m: cells 5:2), y up."""
    rgb = colour(field / vmax if vmax > 0 else field * 0)
    rgb[labels == 0] = (150, 150, 150)  # inside obstacles
    rows, cols = field.shape
    c, r = int(source[0] / 10.0 * cols), int(source[1] / 4.0 * rows)
    if 0 <= r < rows and 0 <= c < cols:
        rgb[max(r - 1, 0):r + 2, c] = (255, 0, 0)
        rgb[r, max(c - 1, 0):c + 2] = (255, 0, 0)
    big = np.repeat(np.repeat(rgb, sy, axis=0), sx, axis=1)
    return big[::-1]  # row 0 (y = 0) at the bottom


def picture(path, x, truth, pred, sources, picks):
    rows = []
    for k in picks:
        t, p = truth[k, 0], pred[k, 0]
        vmax = float(max(t.max(), p.max()))
        labels = x[k, 0]
        gap = np.full((64 * 2, 6, 3), 255, np.uint8)
        rows.append(np.concatenate([panel(t, labels, vmax, sources[k]), gap,
                                    panel(p, labels, vmax, sources[k]), gap,
                                    panel(np.abs(p - t), labels, vmax, sources[k])], axis=1))
        rows.append(np.full((6, rows[-1].shape[1], 3), 255, np.uint8))
    write_png(path, np.concatenate(rows[:-1], axis=0))


def markdown(result):
    lines = ["| set | samples | avg peak | mean RMSE | mean RMSE / peak | (predicting 0) | "
             "mean rel. L2 | mean SSE | std RMSE | std rel. L2 |",
             "|---|---|---|---|---|---|---|---|---|---|"]

    def row(name, s):
        m, d = s["mean"], s["std"]
        lines.append(f"| {name} | {s['samples']} | {s['average_peak_mean']:.1f} | {m['rmse']:.2f} | "
                     f"{100 * m['rmse_rel_peak']:.2f} % | {100 * m['zero_rmse_rel_peak']:.2f} % | "
                     f"{100 * m['rel_l2']:.1f} % | {m['sse']:.4g} | {d['rmse']:.2f} | "
                     f"{100 * d['rel_l2']:.1f} % |")
    if "held_out" in result:
        row("held-out maps", result["held_out"])
    if "test_maps" in result:
        row("**nine test maps**", result["test_maps"]["all"])
        for name, s in result["test_maps"]["per_map"].items():
            row(name, s)
        lines.append("")
        lines.append(f"Mean over the nine maps of each map's mean RMSE / peak: "
                     f"{100 * result['test_maps']['mean_of_map_rel_rmse']:.2f} %")
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--model", required=True)
    ap.add_argument("--data", help="the training dataset (its validation maps are scored)")
    ap.add_argument("--test", help="the test maps' ground-truth dataset")
    ap.add_argument("--out", required=True)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    args = ap.parse_args(argv)
    torch.set_num_threads(max(1, args.threads))
    try:
        model, header = read_model(args.model)
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"evaluate.py: {e}")
    scales = output_scales(header["outputs"])
    os.makedirs(args.out, exist_ok=True)
    result = {"model": os.path.basename(args.model), "training": header.get("training", {})}
    if args.data:
        val_maps = header.get("training", {}).get("val_maps")
        if not val_maps:
            sys.exit(f"evaluate.py: {args.model}: header has no training.val_maps")
        x, y, _ = load_rows(args.data, set(val_maps))
        result["held_out"] = dict(scores(predict(model, scales, x), y), maps=val_maps)
        print("held-out maps: mean RMSE %.3f (%.2f %% of peak)" % (
            result["held_out"]["mean"]["rmse"], 100 * result["held_out"]["mean"]["rmse_rel_peak"]))
    if args.test:
        x, y, ids = load_rows(args.test)
        pred = predict(model, scales, x)
        manifest_dir = os.path.join(args.test, "maps")
        per_map = {}
        for m in sorted(set(int(i) for i in ids)):
            with open(os.path.join(manifest_dir, "map-%05d.json" % m)) as f:
                name = json.load(f).get("name", "map-%05d" % m)
            sel = np.flatnonzero(ids == m)
            per_map[name] = scores(pred[sel], y[sel])
            sources = [tuple(v) for v in _sources(args.test, m)]
            picture(os.path.join(args.out, f"{name}.png"), x[sel], y[sel], pred[sel],
                    [sources[i] for i in range(len(sel))], picks=[0, 1, 2][:len(sel)])
            print("%-22s mean RMSE %.2f = %.2f %% of its average peak %.1f" % (
                name, per_map[name]["mean"]["rmse"], 100 * per_map[name]["mean"]["rmse_rel_peak"],
                per_map[name]["average_peak_mean"]))
        result["test_maps"] = {
            "all": scores(pred, y), "per_map": per_map,
            "mean_of_map_rel_rmse": float(np.mean(
                [s["mean"]["rmse_rel_peak"] for s in per_map.values()]))}
        print("nine test maps: mean RMSE %.3f = %.2f %% of the average peak" % (
            result["test_maps"]["all"]["mean"]["rmse"],
            100 * result["test_maps"]["all"]["mean"]["rmse_rel_peak"]))
    with open(os.path.join(args.out, "evaluation.json"), "w") as f:
        json.dump(result, f, indent=1)
    with open(os.path.join(args.out, "evaluation.md"), "w") as f:
        f.write(markdown(result))


def _sources(directory, map_index):
    """The sources of one map's shard, in sample order."""
    return np.load(os.path.join(directory, "shards", "shard-%05d" % map_index, "sources.npy"))


if __name__ == "__main__":
    main()
