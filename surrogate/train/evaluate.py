"""Scores a plumekit-cnn/1 model on held-out maps and on the test maps' ground truth.

    /usr/bin/python3 surrogate/train/evaluate.py --model data/models/plume-unet.pkcnn \
        --data TRAINING_DATASET --test TEST_MAP_TRUTH --out data/models/plume-unet-eval

--data: the training dataset; only the validation maps named in the model's header
(training.val_maps) are scored, so the figures are for maps the model never saw. --test: the
dataset of the nine test maps (`plumekit dataset generate --map-dir data/test-maps --seed 0`). Either may
be left out.

Several datasets (scripts/train-model-v2.sh: --data FAMILIES BUILDINGS --test TEST_BUILDINGS
TEST_MAPS): --data must name the model's training datasets (header training.datasets) in the same
order, and each one's own validation maps are scored; held_out then pools them all and
held_out.datasets holds each one's figures (by folder name). Each --test dataset is scored as one
alone would be, in test_sets (by folder name; pictures in OUT/NAME/), and all together in
test_pooled (all samples, and the mean over all maps of each map's mean RMSE / peak). With one
--data and one --test the result is as it always was (held_out, test_maps).

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

v2 models (header features.cell_size) on v2 datasets (each map on its own grid): every sample is
fed as the model's contract says (channel 4 as 1 / max(distance, min_distance), zero padding up to
a multiple of features.multiple on the high side), the output is cropped back to the map's cells,
and every figure is over map cells only (rmse pools the squared errors of all map cells of all
samples). The dataset's feature_cell must be the model's cell_size. --test then takes any v2
dataset (its maps are named from maps/*.json), and the pictures keep each map's aspect.

Hybrid models and datasets (issue 46: the physics_mean channel, `plumekit dataset generate
--physics-input`): each model is fed the channels its header names, scaled as it says (a plain
model reads a hybrid dataset without the physics channel; a hybrid model refuses a dataset without
it). Beside the model, each v2 test set with the physics channel gets `physics`: that channel (the
physics plume of each source) times the one least-squares factor that fits the set best (the
factor and the mean's figures). --floor names, for each --test in order, another realization of
it (the same maps and sources, another --seed): `floor` scores that realization's targets as the
prediction, the two-realization floor. Both appear as rows of evaluation.md.

--json prints the result on stdout (the human lines go to stderr); --out may then be left out.
Per-sample figures (`per_sample`: shard, row, map, rmse of the mean over map cells, peak of the true
mean) are in the result for v2 models, and for v1 with --per-sample.
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
from model_file import is_v2, output_scales, read_model  # noqa: E402
from shards import (PHYSICS, channel_names, feature_cell, map_file, open_dataset,  # noqa: E402
                    padded_size, v2_input)

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


# --- v2: each map on its own grid, padded for the network, scored on the map's cells ---

class V2Set:
    """Samples of a v2 dataset as lists (shapes differ from map to map): x, y (float32, [c, ny, nx]),
    map ids, sources and (shard name, row). `keep`: the dataset's channels the model reads, in its
    order (a plain model on a hybrid dataset leaves the physics channel out); `physics`: where the
    dataset's physics channel is (None without one)."""

    def __init__(self, directory, header, keep_maps=None):
        manifest, shards = open_dataset(directory)
        cell, want = feature_cell(directory, manifest), float(header["features"]["cell_size"])
        names = channel_names(manifest, cell)
        if cell <= 0 or any(s.inputs.shape[1] != len(names) for s in shards):
            raise ValueError(f"{directory}: not a v2 dataset (5 or 6 channels and a "
                             "feature_cell), which the v2 model needs")
        if abs(cell - want) > 1e-9 * want:
            raise ValueError(f"{directory}: feature cell {cell:g} m, the model's cell_size is {want:g} m")
        wanted = [c["name"] for c in header["features"]["channels"]]
        missing = [n for n in wanted if n not in names]
        if missing:
            raise ValueError(f"{directory}: the model reads {', '.join(missing)}, which the dataset "
                             "lacks (make it with `plumekit dataset generate --physics-input`)")
        self.keep = [names.index(n) for n in wanted]
        self.physics = names.index(PHYSICS) if PHYSICS in names else None
        self.directory, self.manifest = directory, manifest
        self.x, self.y, self.ids, self.sources, self.where = [], [], [], [], []
        for s in shards:
            for row in range(len(s.map_ids)):
                if keep_maps is not None and int(s.map_ids[row]) not in keep_maps:
                    continue
                self.x.append(np.asarray(s.inputs[row], dtype=np.float32))
                self.y.append(np.asarray(s.targets[row], dtype=np.float32))
                self.ids.append(int(s.map_ids[row]))
                self.sources.append([float(v) for v in s.sources[row]])
                self.where.append((os.path.basename(s.directory), row))
        if not self.x:
            raise ValueError(f"{directory}: no samples to score")
        self.ids = np.array(self.ids)

    def subset(self, sel):
        return [self.x[i] for i in sel], [self.y[i] for i in sel]


def predict_v2(model, header, scales, xs, keep=None, batch=32):
    """Predictions [2, ny, nx] in dataset units for each v2 sample [c, ny, nx]: its channels `keep`
    (V2Set.keep), padded and scaled as the model's features say, batched by padded shape, cropped
    back."""
    features = header["features"]
    multiple = int(features["multiple"])
    channels = features["channels"]
    source = channels[-1]
    min_distance = float(source.get("min_distance", float(features["cell_size"]) / 2))
    divide = {k: float(c["scale"]) for k, c in enumerate(channels) if c["name"] == PHYSICS}
    groups = {}
    for i, x in enumerate(xs):
        groups.setdefault((padded_size(x.shape[1], multiple), padded_size(x.shape[2], multiple)), []).append(i)
    out = [None] * len(xs)
    with torch.no_grad():
        for (rows, cols), members in groups.items():
            for k in range(0, len(members), batch):
                part = members[k:k + batch]
                inp = np.concatenate([v2_input(xs[i][None], min_distance, rows, cols, keep, divide)
                                      for i in part])
                p = model(torch.from_numpy(inp)).numpy() * scales[None, :, None, None]
                for j, i in enumerate(part):
                    out[i] = p[j, :, :xs[i].shape[1], :xs[i].shape[2]]
    return out


def scores_v2(preds, truths):
    """scores() over samples of differing shapes, each sample's map cells only: rmse pools every
    cell of every sample; sse is each sample's sum, averaged."""
    peaks = [float(t[0].max()) for t in truths]
    peak = float(np.mean(peaks))
    cells = sum(t[0].size for t in truths)
    out = {"samples": len(truths), "average_peak_mean": peak}
    for c, name in enumerate(CHANNELS):
        sq = [float(np.sum((p[c].astype(np.float64) - t[c]) ** 2)) for p, t in zip(preds, truths)]
        norm = sum(float(np.sum(t[c].astype(np.float64) ** 2)) for t in truths)
        rmse = float(np.sqrt(sum(sq) / cells))
        out[name] = {"rmse": rmse, "rmse_rel_peak": rmse / peak if peak > 0 else None,
                     "sse": float(np.mean(sq)),
                     "rel_l2": float(np.sqrt(sum(sq) / norm)) if norm > 0 else None,
                     "zero_rmse_rel_peak": float(np.sqrt(norm / cells)) / peak if peak > 0 else None}
    return out


def baselines(test, header, floor_dir=None):
    """What the model is weighed against on one scored set (issue 46): `physics`, the dataset's
    physics channel (the advection-diffusion plume of each source) times the one factor that fits
    the set best in least squares (its mean figures and the factor); `floor`, with floor_dir (the
    same maps and sources, another filament seed), that realization's targets as the prediction:
    what two realizations of the world differ by."""
    out = {}
    if test.physics is not None:
        phys = [x[test.physics].astype(np.float64) for x in test.x]
        num = sum(float(np.sum(p * y[0])) for p, y in zip(phys, test.y))
        den = sum(float(np.sum(p * p)) for p in phys)
        factor = num / den if den > 0 else 0.0
        preds = [np.stack([factor * p, np.zeros_like(p)]) for p in phys]
        s = scores_v2(preds, test.y)
        out["physics"] = {"samples": s["samples"], "average_peak_mean": s["average_peak_mean"],
                          "factor": factor, "mean": s["mean"]}
    if floor_dir:
        floor = V2Set(floor_dir, header)
        same = (np.array_equal(floor.ids, test.ids) and floor.sources == test.sources
                and all(a.shape == b.shape for a, b in zip(floor.y, test.y)))
        if not same:
            raise ValueError(f"--floor {floor_dir}: not the maps and sources of {test.directory}")
        out["floor"] = dict(scores_v2(floor.y, test.y), dataset=os.path.basename(
            os.path.normpath(floor_dir)))
    return out


def per_sample(preds, truths, ids, where):
    """Each sample's RMSE of the mean over its map cells, and its peak true mean."""
    return [{"shard": w[0], "row": int(w[1]), "map": int(m),
             "rmse_mean": float(np.sqrt(np.mean((p[0].astype(np.float64) - t[0]) ** 2))),
             "peak_mean": float(t[0].max())}
            for p, t, m, w in zip(preds, truths, ids, where)]


def picture_v2(path, xs, truths, preds, sources, size, picks):
    """picture() for one v2 map of size (W, H) m: square cells, about 240 pixels on the long side."""
    ny, nx = truths[0].shape[1:]
    px = max(1, 240 // max(nx, ny))
    rows = []
    for k in picks:
        t, p = truths[k][0], preds[k][0]
        vmax = float(max(t.max(), p.max()))
        labels = xs[k][0]
        gap = np.full((ny * px, 6, 3), 255, np.uint8)
        args = (labels, vmax, sources[k], px, px, size)
        rows.append(np.concatenate([panel(t, *args), gap, panel(p, *args), gap,
                                    panel(np.abs(p - t), *args)], axis=1))
        rows.append(np.full((6, rows[-1].shape[1], 3), 255, np.uint8))
    write_png(path, np.concatenate(rows[:-1], axis=0))


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


def panel(field, labels, vmax, source, sx=5, sy=2, size=(10.0, 4.0)):
    """One 64x64 field as an image of (64*sy) x (64*sx) pixels (10 x 4 m: cells 5:2), y up (any
    field of a map of `size` metres, with cells sx x sy pixels)."""
    rgb = colour(field / vmax if vmax > 0 else field * 0)
    rgb[labels == 0] = (150, 150, 150)  # inside obstacles
    rows, cols = field.shape
    c, r = int(source[0] / size[0] * cols), int(source[1] / size[1] * rows)
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
        m, d = s["mean"], s.get("std")
        std = f"{d['rmse']:.2f} | {100 * d['rel_l2']:.1f} %" if d else "– | –"
        lines.append(f"| {name} | {s['samples']} | {s['average_peak_mean']:.1f} | {m['rmse']:.2f} | "
                     f"{100 * m['rmse_rel_peak']:.2f} % | {100 * m['zero_rmse_rel_peak']:.2f} % | "
                     f"{100 * m['rel_l2']:.1f} % | {m['sse']:.4g} | {std} |")

    def set_rows(name, t):
        row(name, t["all"])
        if "physics" in t:
            row(f"{name}: physics plume × {t['physics']['factor']:.3g}", t["physics"])
        if "floor" in t:
            row(f"{name}: two realizations ({t['floor']['dataset']})", t["floor"])
    if "held_out" in result:
        row("held-out maps", result["held_out"])
        for name, s in result["held_out"].get("datasets", {}).items():
            row(f"held-out maps of {name}", s)
    if "test_maps" in result:
        v2 = result.get("features") == "v2"
        set_rows("**test maps**" if v2 else "**nine test maps**", result["test_maps"])
        for name, s in result["test_maps"]["per_map"].items():
            row(name, s)
        lines.append("")
        lines.append(f"Mean over the {'' if v2 else 'nine '}maps of each map's mean RMSE / peak: "
                     f"{100 * result['test_maps']['mean_of_map_rel_rmse']:.2f} %")
    if "test_sets" in result:
        for name, t in result["test_sets"].items():
            set_rows(f"**{name}**", t)
            for map_name, s in t["per_map"].items():
                row(map_name, s)
        row("**all test sets**", result["test_pooled"]["all"])
        lines.append("")
        lines.append("Mean over the maps of each map's mean RMSE / peak:")
        lines.append("")
        for name, t in result["test_sets"].items():
            lines.append(f"- {name}: {100 * t['mean_of_map_rel_rmse']:.2f} %")
        lines.append(f"- all test sets: {100 * result['test_pooled']['mean_of_map_rel_rmse']:.2f} %")
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--model", required=True)
    ap.add_argument("--data", nargs="+", metavar="DIR",
                    help="the training dataset(s) (their validation maps are scored)")
    ap.add_argument("--test", nargs="+", metavar="DIR",
                    help="ground-truth dataset(s): the test maps' (several: each scored and pooled)")
    ap.add_argument("--floor", nargs="+", metavar="DIR",
                    help="v2: for each --test dataset, in order, another realization of it (the\n"
                         "same maps and sources, another --seed): the two-realization floor")
    ap.add_argument("--out", help="folder for evaluation.json, evaluation.md and the pictures")
    ap.add_argument("--json", action="store_true", help="print the result as JSON on stdout")
    ap.add_argument("--per-sample", action="store_true",
                    help="per-sample figures in the result (always for v2 models)")
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    args = ap.parse_args(argv)
    if not args.out and not args.json:
        ap.error("give --out, --json or both")
    torch.set_num_threads(max(1, args.threads))
    try:
        model, header = read_model(args.model)
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"evaluate.py: {e}")
    scales = output_scales(header["outputs"])
    if args.out:
        os.makedirs(args.out, exist_ok=True)
    if is_v2(header):
        return main_v2(args, model, header, scales)
    if args.floor:
        sys.exit("evaluate.py: --floor is for physical-grid (v2) models and datasets")
    result = {"model": os.path.basename(args.model), "training": header.get("training", {})}
    say = (lambda *a: print(*a, file=sys.stderr)) if args.json else print

    def held_out(directory, val_maps):
        x, y, _ = load_rows(directory, set(val_maps))
        pred = predict(model, scales, x)
        entry = dict(scores(pred, y), maps=val_maps)
        if args.per_sample:
            entry["per_sample"] = per_sample(pred, y, *_where(directory, set(val_maps)))
        return entry, pred, y

    def test_set(directory, picture_dir):
        x, y, ids = load_rows(directory)
        pred = predict(model, scales, x)

        manifest_dir = os.path.join(directory, "maps")
        per_map = {}
        for m in sorted(set(int(i) for i in ids)):
            with open(os.path.join(manifest_dir, "map-%05d.json" % m)) as f:
                name = json.load(f).get("name", "map-%05d" % m)
            sel = np.flatnonzero(ids == m)
            per_map[name] = scores(pred[sel], y[sel])
            sources = [tuple(v) for v in _sources(directory, m)]
            if picture_dir:
                picture(os.path.join(picture_dir, f"{name}.png"), x[sel], y[sel], pred[sel],
                        [sources[i] for i in range(len(sel))], picks=[0, 1, 2][:len(sel)])
            say("%-22s mean RMSE %.2f = %.2f %% of its average peak %.1f" % (
                name, per_map[name]["mean"]["rmse"], 100 * per_map[name]["mean"]["rmse_rel_peak"],
                per_map[name]["average_peak_mean"]))
        entry = {
            "all": scores(pred, y), "per_map": per_map,
            "mean_of_map_rel_rmse": float(np.mean(
                [s["mean"]["rmse_rel_peak"] for s in per_map.values()]))}
        if args.per_sample:
            entry["per_sample"] = per_sample(pred, y, *_where(directory, None))
        return entry, pred, y

    pool = lambda preds, truths: scores(np.concatenate(preds), np.concatenate(truths))  # noqa: E731
    if args.data:
        score_held_out(args, header, result, say, held_out, pool, "held-out maps: mean RMSE %.3f "
                       "(%.2f %% of peak)")
    if args.test:
        score_tests(args, result, say, test_set, pool, "nine test maps")
    finish(args, result)


def folder_names(directories):
    """Each directory's folder name, made unique with -2, -3, ... where two share one."""
    names = []
    for d in directories:
        base = os.path.basename(os.path.abspath(d))
        name, k = base, 1
        while name in names:
            k += 1
            name = f"{base}-{k}"
        names.append(name)
    return names


def held_out_maps(args, header):
    """[(directory, validation map ids)] for --data: each dataset's validation maps as the model's
    header records them (train.py's split): training.val_maps for a model of one dataset,
    training.datasets[k].val_maps for one of several, whose folder names --data must give in the
    same order. A dataset without validation maps (one of a single map) is left out."""
    training = header.get("training", {})
    if "datasets" not in training:
        val_maps = training.get("val_maps")
        if not val_maps:
            sys.exit(f"evaluate.py: {args.model}: header has no training.val_maps")
        if len(args.data) > 1:
            sys.exit(f"evaluate.py: {args.model} was trained on one dataset "
                     f"({training.get('dataset')}), --data gives {len(args.data)}")
        return [(args.data[0], val_maps)]
    recorded = training["datasets"]
    names = [os.path.basename(str(r.get("dataset", "")).rstrip("/\\")) for r in recorded]
    given = [os.path.basename(os.path.abspath(d)) for d in args.data]
    if given != names:
        sys.exit(f"evaluate.py: {args.model} was trained on {len(names)} datasets, "
                 f"{', '.join(names)} in that order; --data gives {', '.join(given)}: the validation "
                 "maps are each dataset's own, so give the same datasets in the same order")
    out = [(d, r["val_maps"]) for d, r in zip(args.data, recorded) if r.get("val_maps")]
    if not out:
        sys.exit(f"evaluate.py: {args.model}: header has no training.datasets[].val_maps")
    return out


def score_held_out(args, header, result, say, one, pool, line):
    """result["held_out"]: one(directory, val_maps) -> (figures, predictions, truths) per dataset;
    with several datasets the figures pool them all, and `datasets` holds each one's (by folder
    name)."""
    sets = held_out_maps(args, header)
    if len(args.data) == 1:
        result["held_out"] = one(*sets[0])[0]
        held = result["held_out"]
    else:
        names = dict(zip(args.data, folder_names(args.data)))
        per, preds, truths = {}, [], []
        for directory, val_maps in sets:
            per[names[directory]], p, t = one(directory, val_maps)
            preds.append(p)
            truths.append(t)
        held = result["held_out"] = dict(pool(preds, truths), datasets=per)
        for name, s in per.items():
            say("held-out maps of %s: mean RMSE %.3f (%.2f %% of the average peak)" % (
                name, s["mean"]["rmse"], 100 * s["mean"]["rmse_rel_peak"]))
    say(line % (held["mean"]["rmse"], 100 * held["mean"]["rmse_rel_peak"]))


def score_tests(args, result, say, one, pool, label):
    """result["test_maps"] for one --test dataset; for several, result["test_sets"] (each one's
    figures by folder name, its pictures in OUT/NAME/) and result["test_pooled"] (all their
    samples together, and the mean over all their maps of each map's mean RMSE / peak).
    one(directory, picture folder or None) -> (figures, predictions, truths)."""
    line = "%s: mean RMSE %.3f = %.2f %% of the average peak"
    if len(args.test) == 1:
        result["test_maps"] = one(args.test[0], args.out)[0]
        say(line % (label, result["test_maps"]["all"]["mean"]["rmse"],
                    100 * result["test_maps"]["all"]["mean"]["rmse_rel_peak"]))
        return
    names = folder_names(args.test)
    sets, preds, truths = {}, [], []
    for name, directory in zip(names, args.test):
        pictures = os.path.join(args.out, name) if args.out else None
        if pictures:
            os.makedirs(pictures, exist_ok=True)
        sets[name], p, t = one(directory, pictures)
        preds.append(p)
        truths.append(t)
        say(line % (name, sets[name]["all"]["mean"]["rmse"],
                    100 * sets[name]["all"]["mean"]["rmse_rel_peak"]))
    result["test_sets"] = sets
    result["test_pooled"] = {
        "sets": names, "all": pool(preds, truths),
        "mean_of_map_rel_rmse": float(np.mean([s["mean"]["rmse_rel_peak"] for t in sets.values()
                                               for s in t["per_map"].values()]))}
    say(line % ("all test sets", result["test_pooled"]["all"]["mean"]["rmse"],
                100 * result["test_pooled"]["all"]["mean"]["rmse_rel_peak"]))


def finish(args, result):
    if args.out:
        with open(os.path.join(args.out, "evaluation.json"), "w") as f:
            json.dump(result, f, indent=1)
        with open(os.path.join(args.out, "evaluation.md"), "w") as f:
            f.write(markdown(result))
    if args.json:
        json.dump(result, sys.stdout, indent=1)
        print()


def _where(directory, keep_maps):
    """map ids and (shard name, row) of the samples load_rows() returns, in its order."""
    _, shards = open_dataset(directory)
    ids, where = [], []
    for s in shards:
        for row, m in enumerate(s.map_ids):
            if keep_maps is None or int(m) in keep_maps:
                ids.append(int(m))
                where.append((os.path.basename(s.directory), row))
    return ids, where


def main_v2(args, model, header, scales):
    """main() for a v2 model: the same sets and figures, over each sample's map cells."""
    result = {"model": os.path.basename(args.model), "features": "v2",
              "cell_size": header["features"]["cell_size"], "training": header.get("training", {})}
    say = (lambda *a: print(*a, file=sys.stderr)) if args.json else print

    def held_out(directory, val_maps):
        held = V2Set(directory, header, set(val_maps))
        pred = predict_v2(model, header, scales, held.x, held.keep)
        entry = dict(scores_v2(pred, held.y), maps=val_maps,
                     per_sample=per_sample(pred, held.y, held.ids, held.where))
        return entry, pred, held.y

    def test_set(directory, picture_dir):
        test = V2Set(directory, header)
        pred = predict_v2(model, header, scales, test.x, test.keep)
        per_map = {}
        for m in sorted(set(int(i) for i in test.ids)):
            path = map_file(directory, test.manifest, m)
            with open(path) as f:
                spec = json.load(f)
            name = spec.get("name", "map-%05d" % m)
            sel = np.flatnonzero(test.ids == m)
            xs, ys = test.subset(sel)
            ps = [pred[i] for i in sel]
            per_map[name] = scores_v2(ps, ys)
            if picture_dir:
                origin = (spec.get("frame") or {}).get("origin", [0.0, 0.0])
                sources = [(test.sources[i][0] - origin[0], test.sources[i][1] - origin[1])
                           for i in sel]
                picture_v2(os.path.join(picture_dir, f"{name}.png"), xs, ys, ps, sources,
                           spec["size"], picks=[0, 1, 2][:len(sel)])
            say("%-22s mean RMSE %.2f = %.2f %% of its average peak %.1f" % (
                name, per_map[name]["mean"]["rmse"], 100 * per_map[name]["mean"]["rmse_rel_peak"],
                per_map[name]["average_peak_mean"]))
        entry = {
            "all": scores_v2(pred, test.y), "per_map": per_map,
            "mean_of_map_rel_rmse": float(np.mean(
                [s["mean"]["rmse_rel_peak"] for s in per_map.values()])),
            "per_sample": per_sample(pred, test.y, test.ids, test.where)}
        entry.update(baselines(test, header, floors.get(directory)))
        return entry, pred, test.y

    if args.floor and len(args.floor) != len(args.test or []):
        sys.exit(f"evaluate.py: --floor gives {len(args.floor)} datasets, --test "
                 f"{len(args.test or [])}: one for each test set, in the same order")
    floors = dict(zip(args.test or [], args.floor or []))

    pool = lambda preds, truths: scores_v2(sum(preds, []), sum(truths, []))  # noqa: E731
    try:
        if args.data:
            score_held_out(args, header, result, say, held_out, pool,
                           "held-out maps: mean RMSE %.3f (%.2f %% of the average peak)")
        if args.test:
            score_tests(args, result, say, test_set, pool, "test maps")
    except (OSError, ValueError) as e:
        sys.exit(f"evaluate.py: {e}")
    finish(args, result)


def _sources(directory, map_index):
    """The sources of one map's shard, in sample order."""
    return np.load(os.path.join(directory, "shards", "shard-%05d" % map_index, "sources.npy"))


if __name__ == "__main__":
    main()
