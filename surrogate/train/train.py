"""Trains the plume U-Net on a plumekit dataset and writes a plumekit-cnn/1 model file.

    /usr/bin/python3 surrogate/train/train.py --data DATASET_DIR --work WORK_DIR --out MODEL.pkcnn

Loss: mean squared error over all pixels of both output channels (mean and std) of the scaled
targets, target / s, with one scale s for both channels: the largest mean concentration in the
training split (`--target-scale` overrides). The thesis trained on raw values (0 to over 3000); the
division keeps AdamW's lr 1e-3 in a sensible range and changes nothing else, since the model file's
output scale is s and the engine multiplies by it, so predictions come out in dataset units.

Split: by map id, --val-fraction of the maps (default 10 %) for validation, never seen in training.

Several datasets (--data DIR DIR ...; scripts/train-model-v2.sh trains on its families and its
buildings) train as one: they must be of one kind (all v1 on one grid, or all v2 with one feature
cell; else the run stops naming the dataset that differs). Map ids name maps within a dataset, so
dataset k's map m is the map (k, m), and each dataset's maps are split on their own by the same
rule (shards.split_datasets: dataset 0 as it would split alone, dataset k > 0 from the seed and k),
so every dataset of two maps or more has validation maps. The target scale is the largest training
mean over all datasets, trained_on spans the training maps of all (none when one has no map
files), and the header's `training` lists each dataset (`datasets`: its provenance path, format,
sample counts and validation maps, which evaluate.py scores) with the `val_fraction`. The
checkpoint records the datasets (each folder's name, sample and map count, in order): resuming
with other ones is refused. One dataset trains, logs and writes exactly as before.
Optimiser: AdamW, lr 1e-3, weight decay 5e-3 (the thesis's settings). Batches of 32 by default.
Every epoch: WORK/log.csv gains a line (epoch, step, train loss, val loss, val RMSE of the mean in
dataset units, seconds); WORK/checkpoint.pt is rewritten (model, optimiser, epoch, RNG, best), and
WORK/best.pt when validation improved. Rerunning the same command resumes from the checkpoint.
Training stops after --epochs, after --patience epochs without a better validation loss, after
--max-steps optimiser steps, or once --max-minutes of wall time have passed in this invocation (the
checkpoint is then written mid-epoch, and the same command with a larger limit carries on).
WORK/checkpoint.pt is also rewritten every --checkpoint-minutes inside an epoch, so a killed run
loses at most that much work. --lr-schedule cosine decays the learning rate from --lr to 1 % of it
over --epochs (by step), for runs whose length is fixed in advance; the thesis kept it constant.
The best finished epoch's model (or, if none finished, the current weights) is written to --out,
with a golden input/output pair (OUT_input.npy, OUT_output.npy: validation samples and PyTorch's
prediction in dataset units; see golden_pair() for which samples).
Runs unchanged on CUDA when a GPU is present.

Data-parallel on several GPUs (or CPU processes) under torchrun:

    torchrun --standalone --nproc_per_node 4 surrogate/train/train.py --data ... --work ... --out ...

Each process takes every WORLD_SIZE-th sample of each batch (--batch stays the whole batch, so the
batches, the epochs and the learning rate are those of one process), DistributedDataParallel
averages the gradients (NCCL on GPUs, gloo on CPUs), and rank 0 alone writes the log, the
checkpoints and the model. The result is one process's, up to the order of float sums.

v2 datasets (manifest generator.dataset.feature_cell > 0: 5 input channels on each map's own
physical grid, shapes differing from map to map) train a 5-input network the same way, except:
channel 4 (Euclidean source distance, m) is fed as 1 / max(distance, cell / 2); every sample is
zero-padded (all channels) on the high side up to a multiple of 2 ** len(filters) (16); samples are
bucketed by padded shape, so each batch has one shape, and a batch holds at most --batch x 64 x 64
cells (--batch-cells), at least one sample; the loss is the MSE of target / s over the map's cells
only (the padding is masked out). The log gains val_rmse_over_peak (validation RMSE of the mean
over the average of each sample's peak mean) as its last column. The model file's header carries
the v2 `features` (cell_size, multiple, 5 channels) and, for v1 and v2 alike, `trained_on` from
the training maps' files (when the dataset has them). The golden pair is padded inputs of one
padded shape, [k,5,H,W], and the network's scaled output over the whole padded grid.

Hybrid datasets (issue 46, `plumekit dataset generate --physics-input`: 6 channels, physics_mean,
the physics plume of the source, before the source distance) train one of three designs on the
same data: the hybrid (all six channels; the default, `--inputs all`), the plain network
(`--inputs plain`: the physics channel left out, the v2 model's five inputs) and the residual
(`--residual`: six inputs, the mean predicted as the physics plume plus the network's correction).
The physics channel is fed divided by the target scale s, so with the residual the scaled mean is
net + physics / s. The header's physics_mean channel carries that scale and the dataset's physics
options (generator.physics_mean), the residual's mean output "plus_input": "physics_mean", and
training.inputs and training.residual say the design; a checkpoint resumes only with its design.
"""
import argparse
import csv
import hashlib
import math
import os
import sys
import time

import numpy as np
import torch
import torch.distributed as dist

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from model import PlumeUNet, parameter_count, pick_device, pool_margin  # noqa: E402
from model_file import (DEFAULT_FEATURES, DEFAULT_OUTPUTS, provenance_path, read_model,  # noqa: E402
                        write_model)
from model_file import is_v2, physics_channel, v2_features  # noqa: E402
from shards import (PHYSICS, batch, channel_names, feature_cell, map_summaries,  # noqa: E402
                    open_dataset, padded_size, ranges, split_datasets, v2_input)


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--data", required=True, nargs="+", metavar="DIR",
                    help="dataset directory (manifest.json, shards/), or several of one kind")
    ap.add_argument("--work", required=True, help="checkpoints and log.csv")
    ap.add_argument("--out", required=True, help="model file to write")
    ap.add_argument("--epochs", type=int, default=1000)
    ap.add_argument("--max-steps", type=int, default=0, help="stop after this many steps (0: no limit)")
    ap.add_argument("--max-minutes", type=float, default=0.0,
                    help="stop after this much wall time in this invocation (0: no limit)")
    ap.add_argument("--checkpoint-minutes", type=float, default=5.0,
                    help="also checkpoint inside an epoch this often")
    ap.add_argument("--lr-schedule", choices=["constant", "cosine"], default="constant",
                    help="cosine: from --lr down to 1%% of it over --epochs")
    ap.add_argument("--batch", type=int, default=32)
    ap.add_argument("--lr", type=float, default=1e-3)
    ap.add_argument("--weight-decay", type=float, default=5e-3)
    ap.add_argument("--val-fraction", type=float, default=0.1)
    ap.add_argument("--patience", type=int, default=20, help="epochs without improvement")
    ap.add_argument("--target-scale", type=float, default=0.0, help="0: max training mean")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 1,
                    help="CPU threads (Debian's torch defaults to 1)")
    ap.add_argument("--init", metavar="MODEL",
                    help="start from this plumekit-cnn file's weights and target scale (fine-tuning;\n"
                         "ignored when resuming). Its validation loss is scored first, so the result\n"
                         "is never worse on the validation maps than the start")
    ap.add_argument("--golden", type=int, default=2, help="samples in the golden pair")
    ap.add_argument("--inputs", choices=["all", "plain"], default="all",
                    help="all: every channel of the dataset; plain: leave out a hybrid dataset's\n"
                         "physics_mean channel (the plain design on the same data)")
    ap.add_argument("--residual", action="store_true",
                    help="predict the mean as the physics plume plus a correction (needs a\n"
                         "dataset made with --physics-input, and --inputs all)")
    ap.add_argument("--preload", choices=["auto", "yes", "no"], default="auto",
                    help="copy the whole dataset into the device's memory once instead of reading\n"
                         "each batch from the memory maps (auto: on CUDA only; the batches and\n"
                         "the results are the same, only faster)")
    # Hidden: the architecture (tests train tiny networks) and the v2 batch size in cells.
    ap.add_argument("--filters", default="8,16,32,32", help=argparse.SUPPRESS)
    ap.add_argument("--kernel", type=int, default=5, help=argparse.SUPPRESS)
    ap.add_argument("--convs", type=int, default=3, help=argparse.SUPPRESS)
    ap.add_argument("--batch-cells", type=int, default=0, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    args.filters = tuple(int(f) for f in str(args.filters).split(","))
    return args


class Batches:
    """Batches of rows (shard, row) as device tensors: read from the memory maps per batch, or,
    with preload, gathered from one copy of every shard held in the device's memory (a GPU's
    memory holds a thesis-scale dataset several times over, and the per-batch reads would
    otherwise starve it)."""

    def __init__(self, shards, device, preload):
        self.shards, self.device = shards, device
        self.x = self.y = None
        if preload:
            self.offsets = np.cumsum([0] + [len(s.map_ids) for s in shards])
            self.x = torch.cat([torch.from_numpy(np.ascontiguousarray(s.inputs)) for s in shards]).to(device)
            self.y = torch.cat([torch.from_numpy(np.ascontiguousarray(s.targets)) for s in shards]).to(device)

    def __call__(self, rows):
        if self.x is None:
            x, y = batch(self.shards, rows)
            return torch.from_numpy(x).to(self.device), torch.from_numpy(y).to(self.device)
        index = torch.as_tensor([int(self.offsets[s]) + int(r) for s, r in rows], device=self.device)
        return self.x[index], self.y[index]


def available_memory():
    """Bytes of memory available (MemAvailable), or 0 when unknown."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def masked_squares(p, y, mask):
    """(p - y)^2 on the map's cells, 0 on the padding (whatever p and y hold there, NaN included)."""
    d = torch.where(mask, p - y, torch.zeros((), dtype=p.dtype, device=p.device))
    return d * d


class V2Batches:
    """v2 samples (each map on its own grid) as padded device tensors, bucketed by padded shape.

    A sample of shard s, [5, ny, nx], becomes the network input v2_input() makes, [5, H, W] with H, W
    the next multiples of `multiple`; its targets are zero-padded alike, and a mask [1, H, W] is
    True on the map's ny x nx cells. One batch holds samples of one padded shape only, at most
    max(1, cells // (H * W)) of them. With preload every shard is padded once and kept in the
    device's memory; otherwise each batch reads its rows from the memory maps."""

    def __init__(self, shards, device, preload, cell, multiple, cells, keep=None, divide=None):
        self.shards, self.device = shards, device
        self.keep, self.divide = keep, divide  # the channels fed, and those divided (Design)
        self.min_distance = cell / 2
        self.raw = [tuple(int(v) for v in s.inputs.shape[2:]) for s in shards]
        self.shapes = [(padded_size(r, multiple), padded_size(c, multiple)) for r, c in self.raw]
        self.cap = {hw: max(1, cells // (hw[0] * hw[1])) for hw in self.shapes}
        self.x = self.y = None
        if preload:
            self.x = [torch.from_numpy(self._inputs(si, slice(None))).to(device)
                      for si in range(len(shards))]
            self.y = [torch.from_numpy(self._targets(si, slice(None))).to(device)
                      for si in range(len(shards))]

    @staticmethod
    def bytes_needed(shards, multiple):
        return sum(4 * s.inputs.shape[0] * (s.inputs.shape[1] + s.targets.shape[1])
                   * padded_size(s.inputs.shape[2], multiple) * padded_size(s.inputs.shape[3], multiple)
                   for s in shards)

    def _inputs(self, si, rows):
        return v2_input(self.shards[si].inputs[rows], self.min_distance, *self.shapes[si],
                        keep=self.keep, divide=self.divide)

    def _targets(self, si, rows):
        t = np.asarray(self.shards[si].targets[rows], dtype=np.float32)
        out = np.zeros(t.shape[:2] + self.shapes[si], np.float32)
        out[:, :, :t.shape[2], :t.shape[3]] = t
        return out

    def shape(self, row):
        return self.shapes[row[0]]

    def numpy_inputs(self, rows):
        """The padded network inputs of rows (one padded shape), as a numpy array."""
        return np.concatenate([self._inputs(s, [r]) for s, r in rows])

    def __call__(self, rows):
        """x [b,5,H,W], y [b,2,H,W] (dataset units, zero padding) and mask [b,1,H,W] of rows, which
        share one padded shape."""
        h, w = self.shape(rows[0])
        if any(self.shape(r) != (h, w) for r in rows):
            raise ValueError("a v2 batch mixes padded shapes")
        if self.x is None:
            x = torch.from_numpy(self.numpy_inputs(rows)).to(self.device)
            y = torch.from_numpy(np.concatenate([self._targets(s, [r]) for s, r in rows])).to(self.device)
        else:
            x = torch.stack([self.x[s][r] for s, r in rows])
            y = torch.stack([self.y[s][r] for s, r in rows])
        mask = torch.zeros((len(rows), 1, h, w), dtype=torch.bool)
        for i, (s, _) in enumerate(rows):
            ny, nx = self.raw[s]
            mask[i, :, :ny, :nx] = True
        return x, y, mask.to(self.device)

    def batches(self, rows):
        """Lists of rows, one padded shape each: walking `rows` in order, a shape's batch is given
        out when it holds its cap of samples; then the unfilled ones, in the order their shapes
        first appeared. Each batch's rows are sorted (shard, row). The count depends only on how
        many rows each shape has, so every epoch has the same number of steps."""
        out, open_ = [], {}
        for row in rows:
            hw = self.shape(row)
            pending = open_.setdefault(hw, [])
            pending.append(row)
            if len(pending) == self.cap[hw]:
                out.append(sorted(pending))
                open_[hw] = []
        out.extend(sorted(p) for p in open_.values() if p)
        return out

    def loss(self, model, rows, mine, weight, world, scale):
        """This rank's part of the batch's loss: squared error of the scaled targets summed over
        its rows' map cells (both channels), over the whole batch's map cells x 2."""
        x, y, mask = self(mine)
        total = 2 * sum(self.raw[s][0] * self.raw[s][1] for s, _ in rows)
        return masked_squares(model(x), y / scale, mask).sum() * (weight * world / total)


def evaluate_v2(model, batches, rows, scale):
    """(loss on scaled targets over map cells, RMSE of the mean channel over map cells in dataset
    units, that RMSE over the average of each sample's peak mean)."""
    model.eval()
    sq, sq_mean, cells, peaks = 0.0, 0.0, 0, []
    with torch.no_grad():
        for group in batches.batches(rows):
            x, y, mask = batches(group)
            e = masked_squares(model(x), y / scale, mask)
            sq += e.sum().item()
            sq_mean += e[:, 0].sum().item()
            cells += int(mask.sum().item())
            peaks += torch.where(mask[:, 0], y[:, 0], torch.full_like(y[:, 0], -math.inf)).amax(
                dim=(1, 2)).tolist()
    if not cells:
        return 0.0, 0.0, 0.0
    rmse = math.sqrt(sq_mean / cells) * scale
    peak = float(np.mean(peaks))  # y is in dataset units
    return sq / (2 * cells), rmse, rmse / peak if peak > 0 else 0.0


class Team:
    """This process's place among torchrun's: rank, world size and device; one process when
    WORLD_SIZE is unset or 1 (the collective calls are then plain no-ops)."""

    def __init__(self):
        self.world = int(os.environ.get("WORLD_SIZE", "1"))
        self.rank = int(os.environ.get("RANK", "0"))
        if self.world <= 1:
            self.world, self.rank, self.device = 1, 0, pick_device()
            return
        local = int(os.environ.get("LOCAL_RANK", "0"))
        if torch.cuda.is_available():
            torch.cuda.set_device(local)
            self.device, backend = torch.device("cuda", local), "nccl"
        else:
            self.device, backend = torch.device("cpu"), "gloo"
        dist.init_process_group(backend)

    @property
    def lead(self):
        return self.rank == 0

    def wrap(self, model):
        """The model to train: DistributedDataParallel over the team, or the model itself."""
        if self.world == 1:
            return model
        ids = [self.device.index] if self.device.type == "cuda" else None
        return torch.nn.parallel.DistributedDataParallel(model, device_ids=ids)

    def share(self, values):
        """Rank 0's floats on every rank: one decision (validation, time limit) for all."""
        if self.world == 1:
            return values
        t = torch.tensor(values, dtype=torch.float64, device=self.device)
        dist.broadcast(t, 0)
        return t.tolist()

    def mean(self, value):
        if self.world == 1:
            return value
        t = torch.tensor([value], dtype=torch.float64, device=self.device)
        dist.all_reduce(t)
        return t.item() / self.world

    def my_rows(self, rows):
        """This rank's share of a batch: every world-th row, or the first row when a short last
        batch leaves none (its loss then counts zero: every rank must run backward)."""
        mine = rows[self.rank::self.world]
        return (mine, 1.0) if mine else (rows[:1], 0.0)

    def close(self):
        if self.world > 1:
            dist.destroy_process_group()


def evaluate(model, batches, rows, scale, batch_size):
    """(loss on scaled targets, RMSE of the mean channel in dataset units)."""
    model.eval()
    total, sq_mean, count = 0.0, 0.0, 0
    with torch.no_grad():
        for i in range(0, len(rows), batch_size):
            x, y = batches(rows[i:i + batch_size])
            y = y / scale
            p = model(x)
            total += torch.mean((p - y) ** 2).item() * len(x)
            sq_mean += torch.mean(((p[:, 0] - y[:, 0]) * scale) ** 2).item() * len(x)
            count += len(x)
    return total / max(count, 1), (sq_mean / max(count, 1)) ** 0.5


def learning_rate(args, step, steps_per_epoch):
    if args.lr_schedule == "constant":
        return args.lr
    total = max(1, args.epochs * steps_per_epoch)
    t = min(1.0, step / total)
    return args.lr * (0.01 + 0.99 * 0.5 * (1.0 + math.cos(math.pi * t)))


def golden_pair(model, shards, rows, count, tries=64):
    """Inputs and float32 outputs of the `count` samples, among the first `tries`, whose max-pool
    decisions have the widest margins (model.pool_margin). A 2x2 max-pool whose two largest inputs
    differ by less than float32 rounding picks its argmax by summation order, and max-unpool then
    moves a decoder value to another pixel, so two correct float32 engines can disagree there by
    ~1e-3 or more. On smooth plumes every sample has some such window (margins ~1e-8..1e-6), so this
    only picks the least exposed ones; the margins are printed."""
    x, _ = batch(shards, rows[:tries])
    margins = pool_margin(model, x)
    best = np.argsort(-margins)[:count]
    with torch.no_grad():
        y = model(torch.from_numpy(x[best])).numpy()
    print("golden pair: samples (shard, row) %s, pool margins %s" % (
        [tuple(int(v) for v in rows[i]) for i in best], ", ".join("%.2g" % margins[i] for i in best)))
    return x[best], y


def golden_pair_v2(model, batches, rows, count, tries=64):
    """golden_pair() for v2: the candidates are the first `tries` rows of rows[0]'s padded shape, so
    the pair is one array [k,5,H,W] of padded network inputs; margins leave out exact ties (the
    zero padding is full of them, and every engine breaks them alike)."""
    hw = batches.shape(rows[0])
    rows = [r for r in rows if batches.shape(r) == hw][:tries]
    x = batches.numpy_inputs(rows)
    margins = pool_margin(model, x, ignore_exact_ties=True)
    best = np.argsort(-margins)[:count]
    with torch.no_grad():
        y = model(torch.from_numpy(x[best])).numpy()
    print("golden pair: samples (shard, row) %s, padded %dx%d, pool margins %s (exact ties of "
          "identical computations, as in the padding, left out)" % (
        [tuple(int(v) for v in rows[i]) for i in best], hw[0], hw[1],
        ", ".join("%.2g" % margins[i] for i in best)))
    return x[best], y


def open_datasets(dirs):
    """Opens the --data datasets, which must be of one kind: all v1 (3 channels) on one grid, or
    all v2 (5 channels, or 6 with the physics) with one feature cell and the same channels.
    Returns their manifests, all their shards in order, the dataset index of each shard, whether
    they are v2, the v2 feature cell (0 for v1) and the channel names."""
    manifests, shards, dataset_of, kinds, names_of = [], [], [], [], []
    seen = [os.path.realpath(d) for d in dirs]
    for k, d in enumerate(dirs):
        if seen.index(seen[k]) != k:  # its maps would be in both splits, as (j, m) and (k, m)
            sys.exit(f"train.py: --data gives {d} twice")
        manifest, own = open_dataset(d)
        channels = {int(s.inputs.shape[1]) for s in own}
        cell = feature_cell(d, manifest)
        v2 = cell > 0 or channels == {5}
        names = channel_names(manifest, cell)
        if channels != {len(names)}:
            sys.exit(f"train.py: {d}: input channels {sorted(channels)}, its manifest names "
                     f"{len(names)} ({', '.join(names)})")
        if v2 and cell <= 0:
            sys.exit(f"train.py: {d}: 5-channel inputs but no generator.dataset.feature_cell "
                     "in manifest.json")
        grids = sorted({tuple(int(v) for v in s.inputs.shape[2:]) for s in own})
        kinds.append((v2, cell, grids))
        if k and not same_kind(kinds[0], kinds[k]):
            sys.exit(f"train.py: {d} is a {kind_name(kinds[k])} dataset, but {dirs[0]} is a "
                     f"{kind_name(kinds[0])} one: the --data datasets must be of one kind (all v1 "
                     "on one grid, or all v2 with one feature cell)")
        if k and names != names_of[0]:
            sys.exit(f"train.py: {d} has the input channels {', '.join(names)}, {dirs[0]} "
                     f"{', '.join(names_of[0])}: the --data datasets must have the same ones")
        names_of.append(names)
        manifests.append(manifest)
        shards += own
        dataset_of += [k] * len(own)
    return manifests, shards, dataset_of, kinds[0][0], kinds[0][1], names_of[0]


def same_kind(a, b):
    (v2_a, cell_a, grids_a), (v2_b, cell_b, grids_b) = a, b
    if v2_a != v2_b:
        return False
    return abs(cell_a - cell_b) <= 1e-9 * cell_a if v2_a else grids_a == grids_b


def kind_name(kind):
    v2, cell, grids = kind
    return (f"v2 (feature cell {cell:g} m)" if v2
            else "v1 (grid %s)" % ", ".join("%dx%d" % g for g in grids))


class Design:
    """What the network is fed and predicts: the dataset's channels kept (`keep`, their `names`),
    where the physics channel is among them (`physics`, or None), whether the mean is residual,
    and the physics options the header records."""

    def __init__(self, args, names, manifests):
        self.dataset_names = tuple(names)
        has_physics = PHYSICS in names
        if args.residual and not has_physics:
            sys.exit("train.py: --residual needs the physics channel: make the dataset with "
                     "`plumekit dataset generate --feature-cell 0.2 --physics-input`")
        if args.residual and args.inputs == "plain":
            sys.exit("train.py: --residual adds the physics channel, which --inputs plain leaves out")
        self.keep = [k for k, n in enumerate(names) if not (n == PHYSICS and args.inputs == "plain")]
        self.names = [names[k] for k in self.keep]
        self.physics = self.names.index(PHYSICS) if PHYSICS in self.names else None
        self.residual = bool(args.residual)
        self.options = None
        if self.physics is not None:
            found = [m.get("generator", {}).get("physics_mean") for m in manifests]
            if any(f != found[0] for f in found) or not isinstance(found[0], dict):
                sys.exit("train.py: the --data datasets' generator.physics_mean differ or are "
                         "missing: every dataset's physics channel must be the same physics")
            self.options = found[0]

    @property
    def in_channels(self):
        return len(self.keep)

    def divide(self, scale):
        """Input channels divided by a number: the physics channel by the target scale."""
        return {} if self.physics is None else {self.physics: scale}

    def record(self):
        return {"inputs": self.names, "residual": self.residual}


def dataset_record(dirs, shards, dataset_of):
    """What a checkpoint records of its --data datasets, in order: each one's folder name, sample
    count and map count (not the path, so a moved work tree still resumes)."""
    out = []
    for k, d in enumerate(dirs):
        own = [s for s, o in zip(shards, dataset_of) if o == k]
        out.append({"name": os.path.basename(os.path.abspath(d)),
                    "samples": int(sum(len(s.map_ids) for s in own)),
                    "maps": len({int(m) for s in own for m in np.unique(s.map_ids)})})
    return out


def describe_record(record):
    if record is None:
        return "one dataset (the checkpoint does not say which)"
    return ", ".join(f"{r['name']} ({r['samples']} samples, {r['maps']} maps)" for r in record)


def trained_on_ranges(dirs, manifests, shards, dataset_of, val_maps_of, say):
    """The header's trained_on: what the training maps' files say (none without map files), over
    the training maps of every dataset."""
    summaries = []
    for k, d in enumerate(dirs):
        train_maps = sorted({int(m) for s, o in zip(shards, dataset_of) if o == k
                             for m in np.unique(s.map_ids)} - set(val_maps_of[k]))
        try:
            got = map_summaries(d, manifests[k], train_maps)
        except (OSError, ValueError, KeyError, TypeError) as e:
            sys.exit(f"train.py: {d}: a map file cannot be read for trained_on: {e!r}")
        if got is None:  # ranges over some of the datasets would claim too little
            if len(dirs) > 1:
                say(f"no trained_on in the header: {d} has no map files")
            summaries = None
            break
        summaries += got
    return ranges(summaries) if summaries is not None else None


def read_init(args, v2, cell):
    """The --init model and header (None, None without --init); its features must be the dataset's."""
    if not args.init:
        return None, None
    try:
        init_model, init_header = read_model(args.init)
    except (OSError, ValueError) as e:
        sys.exit(f"train.py: --init: {e}")
    if is_v2(init_header) != v2 or (
            v2 and abs(float(init_header["features"]["cell_size"]) - cell) > 1e-9 * cell):
        sys.exit(f"train.py: --init {args.init}: its features ("
                 f"{'cell ' + str(init_header['features'].get('cell_size')) if is_v2(init_header) else 'v1 grid'}"
                 f") are not this dataset's ({'cell ' + str(cell) if v2 else 'v1 grid'})")
    return init_model, init_header


def target_scale(args, init_header, shards, dataset_of, val_maps_of):
    """What the targets are divided by: --target-scale, else the start's, else the largest
    training mean."""
    scale = args.target_scale
    if scale <= 0 and init_header is not None:  # keep the start's units
        scale = float(init_header["outputs"][0]["scale"])
    if scale <= 0:  # the largest training mean, read shard by shard from the memory maps
        scale = 0.0
        for s, k in zip(shards, dataset_of):
            keep = ~np.isin(s.map_ids, val_maps_of[k])
            if keep.any():
                scale = max(scale, float(np.max(s.targets[np.flatnonzero(keep), 0])))
        scale = scale if scale > 0 else 1.0
    return scale


def open_batches(args, shards, device, v2, cell, multiple, design, scale, say):
    """The samples' batches, preloaded onto the device or read from the memory maps."""
    if v2:  # on the CPU too when the padded dataset takes at most a quarter of the free memory
        need = V2Batches.bytes_needed(shards, multiple)
        preload = args.preload == "yes" or (args.preload == "auto" and (
            device.type == "cuda" or need <= available_memory() // 4))
        batches = V2Batches(shards, device, preload, cell, multiple,
                            args.batch_cells or args.batch * 64 * 64, design.keep,
                            design.divide(scale))
        say(f"v2 dataset: cell {cell:g} m, {len(set(batches.shapes))} padded shapes "
            f"(multiple {multiple}), {'preloaded, %.0f MB' % (need / 2**20) if preload else 'memory-mapped'}")
    else:
        preload = args.preload == "yes" or (args.preload == "auto" and device.type == "cuda")
        batches = Batches(shards, device, preload)
    return batches


def network(args, design):
    """The untrained network of --filters, --kernel and --convs for `design`."""
    return PlumeUNet(design.in_channels, 2, args.filters, args.kernel, args.convs,
                     design.physics if design.residual else None)


def load(path, device):
    """torch.load of our own checkpoints, which hold the optimiser's state and the training state
    (newer PyTorch loads weights only unless told)."""
    try:
        return torch.load(path, map_location=device, weights_only=False)
    except TypeError:  # PyTorch before 1.13.1 has no weights_only
        return torch.load(path, map_location=device)


def new_model(args, design, device, init_model):
    """The network, seeded by --seed, with the --init model's weights when given."""
    torch.manual_seed(args.seed)
    model = network(args, design).to(device)
    if init_model is not None:
        try:
            model.load_state_dict(init_model.state_dict())
        except RuntimeError as e:  # another architecture than the one trained here
            sys.exit(f"train.py: --init {args.init}: {str(e).splitlines()[0]}")
    return model


def validate_start(args, team, model, state, validate, best_path, say):
    """Epoch 0 is the start itself: a fine-tuning that only hurts returns the start. Returns the
    start's log row."""
    val = team.share(list(validate(model)))
    val_loss, val_rmse = val[:2]
    state["best_val"] = val_loss
    if team.lead:
        torch.save({"model": model.state_dict(), "state": dict(state)}, best_path)
    say(f"start {args.init}: val {val_loss:.4g} (mean RMSE {val_rmse:.4g})", flush=True)
    return [0, 0, "", f"{val_loss:.6g}", f"{val_rmse:.6g}", "0"] + [f"{v:.6g}" for v in val[2:]]


def resume(ckpt_path, device, model, opt, several, data_record, design, say):
    """Loads the checkpoint's model, optimizer and random state; returns its training state."""
    ckpt = load(ckpt_path, device)
    # A checkpoint from before the designs (issue 46) fed every channel, without a residual.
    if ckpt.get("design", {"inputs": None, "residual": False}) not in (
            design.record(), {"inputs": None, "residual": design.residual}):
        sys.exit(f"train.py: {ckpt_path} was written for the design {ckpt.get('design')}; this "
                 f"run's is {design.record()} (--inputs, --residual). Resume with the same flags, "
                 "or train in another --work folder")
    # A checkpoint from before checkpoints recorded their datasets had one dataset.
    if ckpt.get("data", None if several else data_record) != data_record:
        sys.exit(f"train.py: {ckpt_path} was written for --data {describe_record(ckpt.get('data'))}; "
                 f"this run gives {describe_record(data_record)}. Resume with the same datasets "
                 "in the same order, or train in another --work folder")
    model.load_state_dict(ckpt["model"])
    opt.load_state_dict(ckpt["optimizer"])
    state = ckpt["state"]
    torch.set_rng_state(ckpt["torch_rng"].cpu())  # map_location moved it to the device
    for key, value in (("batch", 0), ("running", 0.0), ("seen", 0)):
        state.setdefault(key, value)
    say(f"resumed from {ckpt_path} at epoch {state['epoch']}, step {state['step']}")
    return state


def train_steps(args, team, model, opt, state, batches, train_rows, v2, scale, steps_per_epoch,
                started, last_save, save_checkpoint):
    """The current epoch's batches from state["batch"] on, until its end, --max-steps or
    --max-minutes. Returns (out of time, the last checkpoint's time)."""
    model.train()
    # Seeded by epoch, so a resumed run draws the same batches as an uninterrupted one.
    order = np.random.default_rng([args.seed, state["epoch"]]).permutation(len(train_rows))
    if v2:
        epoch_batches = batches.batches([train_rows[j] for j in order])
    while state["batch"] < steps_per_epoch:
        if args.max_steps and state["step"] >= args.max_steps:
            break
        if args.max_minutes and team.share(
                [time.time() - started > 60.0 * args.max_minutes])[0]:
            return True, last_save
        if v2:
            rows = epoch_batches[state["batch"]]
        else:
            i = state["batch"] * args.batch
            rows = sorted(train_rows[j] for j in order[i:i + args.batch])
        mine, weight = team.my_rows(rows)
        if not v2:
            x, y = batches(mine)
            y = y / scale
        for group in opt.param_groups:
            group["lr"] = learning_rate(args, state["step"], steps_per_epoch)
        if v2:
            loss = batches.loss(model, rows, mine, weight, team.world, scale)
        elif team.world == 1:
            loss = torch.mean((model(x) - y) ** 2)
        else:  # this rank's part of the whole batch's mean; DDP averages over ranks
            per_sample = torch.mean((model(x) - y) ** 2, dim=(1, 2, 3))
            loss = per_sample.sum() * (weight * team.world / len(rows))
        opt.zero_grad()
        loss.backward()
        opt.step()
        state["step"] += 1
        state["batch"] += 1
        state["running"] += team.mean(loss.item()) * len(rows)
        state["seen"] += len(rows)
        if time.time() - last_save > 60.0 * args.checkpoint_minutes:
            save_checkpoint()
            last_save = time.time()
    return False, last_save


def end_epoch(team, core, state, validate, log, log_file, t0, v2, best_path, say):
    """Validates after a finished epoch, logs it and keeps the model if it is the best so far."""
    state["epoch"] += 1
    val = team.share(list(validate(core)))
    val_loss, val_rmse = val[:2]
    train_loss = state["running"] / max(state["seen"], 1)
    state["batch"], state["running"], state["seen"] = 0, 0.0, 0
    log.writerow([state["epoch"], state["step"], f"{train_loss:.6g}", f"{val_loss:.6g}",
                  f"{val_rmse:.6g}", f"{time.time() - t0:.2f}"] + [f"{v:.6g}" for v in val[2:]])
    log_file.flush()
    say(f"epoch {state['epoch']} step {state['step']}: train {train_loss:.4g} "
          f"val {val_loss:.4g} (mean RMSE {val_rmse:.4g}"
          f"{', %.2f %% of the average peak' % (100 * val[2]) if v2 else ''})", flush=True)
    if val_loss < state["best_val"]:
        state["best_val"], state["stale"] = val_loss, 0
        if team.lead:
            torch.save({"model": core.state_dict(), "state": dict(state)}, best_path + ".tmp")
            os.replace(best_path + ".tmp", best_path)
    else:
        state["stale"] += 1


def training_record(args, dirs, manifests, dataset_of, train_rows, val_rows, val_maps_of, v2, cell,
                    best, design):
    """The model header's training section: the data, the run's settings and its best epoch."""
    if len(dirs) > 1:  # each dataset's own part, and its validation maps (evaluate.py reads them)
        counts = [[sum(1 for s, _ in rows if dataset_of[s] == k) for k in range(len(dirs))]
                  for rows in (train_rows, val_rows)]
        training = {"datasets": [{"dataset": provenance_path(d), "dataset_format": m.get("format"),
                                  "train_samples": counts[0][k], "val_samples": counts[1][k],
                                  "val_maps": val_maps_of[k]}
                                 for k, (d, m) in enumerate(zip(dirs, manifests))],
                    "train_samples": len(train_rows), "val_samples": len(val_rows),
                    "val_fraction": args.val_fraction}
    else:
        training = {"dataset": provenance_path(dirs[0]), "dataset_format": manifests[0].get("format"),
                    "train_samples": len(train_rows), "val_samples": len(val_rows),
                    "val_maps": val_maps_of[0]}
    training.update({"epochs": best["state"]["epoch"],
                     "steps": best["state"]["step"], "best_val_loss": best["state"]["best_val"],
                     "loss": "MSE of target/scale over both channels", "optimizer": "AdamW",
                     "lr": args.lr, "lr_schedule": args.lr_schedule, "weight_decay": args.weight_decay,
                     "batch": args.batch, "seed": args.seed})
    if v2:
        training.update(loss="MSE of target/scale over both channels, on map cells only (padding "
                        "masked)", batch_cells=args.batch_cells or args.batch * 64 * 64,
                        feature_cell=cell)
    if design.physics is not None or args.inputs != "all":
        training.update(design.record())
    if args.init:
        training["init"] = {"model": os.path.basename(args.init),
                            "sha256": hashlib.sha256(open(args.init, "rb").read()).hexdigest()}
    return training


def write_final(args, best_path, design, scale, v2, cell, multiple, shards, dataset_of,
                manifests, train_rows, val_rows, val_maps_of, trained_on):
    """Writes the best epoch's model to --out, with its golden input/output pair beside it."""
    dirs = args.data
    best = load(best_path, "cpu")
    final = network(args, design)
    final.load_state_dict(best["model"])
    final.eval()
    outputs = [dict(o, scale=scale) for o in DEFAULT_OUTPUTS]
    if design.residual:
        outputs[0]["plus_input"] = "physics_mean"
    if v2:
        physics = physics_channel(scale, design.options) if design.physics is not None else None
        features = v2_features(cell, multiple, physics)
    else:
        features = dict(DEFAULT_FEATURES, grid=list(shards[0].inputs.shape[2:]))
    training = training_record(args, dirs, manifests, dataset_of, train_rows, val_rows, val_maps_of,
                               v2, cell, best, design)
    size = write_model(args.out, final, features, outputs, training, trained_on)
    if v2:
        x, y = golden_pair_v2(final, V2Batches(shards, torch.device("cpu"), False, cell, multiple, 1,
                                               design.keep, design.divide(scale)),
                              val_rows + train_rows, args.golden)
    else:
        x, y = golden_pair(final, shards, val_rows + train_rows, args.golden)
    y = y * scale
    stem = os.path.splitext(args.out)[0]
    np.save(stem + "_input.npy", x)
    np.save(stem + "_output.npy", y.astype(np.float32))
    print(f"wrote {args.out} ({size} bytes) from epoch {best['state']['epoch']}")


def main(argv=None):
    args = parse_args(argv)
    torch.set_num_threads(max(1, args.threads))
    team = Team()
    device = team.device
    say = print if team.lead else (lambda *a, **k: None)
    os.makedirs(args.work, exist_ok=True)
    manifests, shards, dataset_of, v2, cell, names = open_datasets(args.data)
    dirs, several = args.data, len(args.data) > 1
    design = Design(args, names, manifests)
    multiple = 2 ** len(args.filters)
    # Map m of dataset k is the map (k, m); each dataset's maps are split on their own.
    train_rows, val_rows, val_maps_of = split_datasets(shards, dataset_of, args.val_fraction, args.seed)
    val_maps = val_maps_of[0]
    if not train_rows or not val_rows:
        sys.exit("train.py: need at least two maps (one for validation)")
    trained_on = trained_on_ranges(dirs, manifests, shards, dataset_of, val_maps_of, say)
    init_model, init_header = read_init(args, v2, cell)
    scale = target_scale(args, init_header, shards, dataset_of, val_maps_of)
    batches = open_batches(args, shards, device, v2, cell, multiple, design, scale, say)
    # Late bound: a resumed run validates with the checkpoint's scale.
    validate = ((lambda m: evaluate_v2(m, batches, val_rows, scale)) if v2  # noqa: E731
                else (lambda m: evaluate(m, batches, val_rows, scale, args.batch)))

    model = new_model(args, design, device, init_model)
    opt = torch.optim.AdamW(model.parameters(), lr=args.lr, weight_decay=args.weight_decay)
    # batch: the next batch of the current epoch; running, seen: that epoch's loss sums so far.
    state = {"epoch": 0, "step": 0, "best_val": float("inf"), "stale": 0, "scale": scale,
             "batch": 0, "running": 0.0, "seen": 0}
    ckpt_path = os.path.join(args.work, "checkpoint.pt")
    best_path = os.path.join(args.work, "best.pt")
    # Every rank sees the work folder as it was before rank 0 writes anything to it.
    resuming, fresh = os.path.exists(ckpt_path), not os.path.exists(best_path)
    if team.world > 1:
        dist.barrier()
    data_record = dataset_record(dirs, shards, dataset_of)
    if resuming:
        state = resume(ckpt_path, device, model, opt, several, data_record, design, say)
        if design.physics is not None and state["scale"] != scale:  # the inputs were divided by it
            sys.exit(f"train.py: {ckpt_path} trained with the target scale {state['scale']:.6g}, "
                     f"this run's is {scale:.6g} (--target-scale?): the physics channel is divided "
                     "by it, so resume with the same one")
        scale = state["scale"]
    start_row = None
    if init_model is not None and not resuming and fresh:
        start_row = validate_start(args, team, model, state, validate, best_path, say)
    shown_val_maps = ("; ".join(f"{r['name']} {v}" for r, v in zip(data_record, val_maps_of))
                      if several else val_maps)
    say(f"{parameter_count(model)} parameters on {device}"
        f"{f' x {team.world} processes' if team.world > 1 else ''}; {len(train_rows)} training and "
        f"{len(val_rows)} validation samples (validation maps {shown_val_maps}); target scale {scale:.6g}")
    core, model = model, team.wrap(model)  # core: the network itself, for saving and validation

    log_path = os.path.join(args.work, "log.csv") if team.lead else os.devnull
    new_log = not os.path.exists(log_path)
    with open(log_path, "a", newline="") as log_file:
        log = csv.writer(log_file)
        if new_log:
            log.writerow(["epoch", "step", "train_loss", "val_loss", "val_rmse_mean", "seconds"]
                         + (["val_rmse_over_peak"] if v2 else []))
        if start_row:
            log.writerow(start_row)
        def save_checkpoint():
            if not team.lead:
                return
            torch.save({"model": core.state_dict(), "optimizer": opt.state_dict(),
                        "state": state, "torch_rng": torch.get_rng_state(), "data": data_record,
                        "design": design.record()},
                       ckpt_path + ".tmp")
            os.replace(ckpt_path + ".tmp", ckpt_path)

        started = last_save = time.time()
        out_of_time = False
        if v2:
            steps_per_epoch = len(batches.batches(train_rows))
        else:
            steps_per_epoch = (len(train_rows) + args.batch - 1) // args.batch
        while state["epoch"] < args.epochs and state["stale"] < args.patience and not out_of_time:
            if args.max_steps and state["step"] >= args.max_steps:
                break
            t0 = time.time()
            out_of_time, last_save = train_steps(args, team, model, opt, state, batches, train_rows,
                                                 v2, scale, steps_per_epoch, started, last_save,
                                                 save_checkpoint)
            if state["batch"] < steps_per_epoch:  # stopped inside the epoch (time or steps)
                save_checkpoint()
                if team.lead and not os.path.exists(best_path):  # no finished epoch: keep these
                    val_loss = validate(core)[0]
                    torch.save({"model": core.state_dict(), "state": dict(state, best_val=val_loss)},
                               best_path)
                break
            end_epoch(team, core, state, validate, log, log_file, t0, v2, best_path, say)
            save_checkpoint()
            last_save = time.time()

    team.close()
    if not team.lead:
        return
    write_final(args, best_path, design, scale, v2, cell, multiple, shards, dataset_of,
                manifests, train_rows, val_rows, val_maps_of, trained_on)


if __name__ == "__main__":
    main()
