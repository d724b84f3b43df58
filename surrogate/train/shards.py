"""Reads plumekit-dataset/1 directories (dataset/README.md) memory-mapped, and splits them by map.

DIR/manifest.json lists `shards` (each with `name`, else `map_index`); DIR/shards/NAME/ holds
inputs.npy float32 [n,3,64,64], targets.npy float32 [n,2,64,64], sources.npy float32 [n,2] and
map_ids.npy int [n]. Arrays stay on disk (numpy mmap_mode='r'); a batch copies only its rows.

The C++ reader (dataset/dataset_reader.hpp) is the format's reference: `python3 shards.py DIR INDEX`
prints what this reader loads for one sample in the fields of `plumekit dataset show --json`, and
tests/surrogate/train_smoke_test.cpp checks that the two agree.
"""
import hashlib
import json
import os
import sys

import numpy as np


class Shard:
    def __init__(self, directory):
        self.directory = directory
        load = lambda name: np.load(os.path.join(directory, name), mmap_mode="r")  # noqa: E731
        self.inputs = load("inputs.npy")
        self.targets = load("targets.npy")
        self.sources = load("sources.npy")
        self.map_ids = np.asarray(load("map_ids.npy")).astype(np.int64)
        n = self.inputs.shape[0]
        if (self.inputs.ndim != 4 or self.inputs.shape[1] != 3 or self.targets.shape[0] != n
                or self.targets.shape[1] != 2 or self.targets.shape[2:] != self.inputs.shape[2:]
                or self.map_ids.shape != (n,)):
            raise ValueError(f"{directory}: inconsistent shard shapes {self.inputs.shape}, "
                             f"{self.targets.shape}, {self.map_ids.shape}")


def open_dataset(directory):
    with open(os.path.join(directory, "manifest.json")) as f:
        manifest = json.load(f)
    shards = []
    for s in manifest["shards"]:
        name = s.get("name") or "shard-%05d" % s["map_index"]
        shards.append(Shard(os.path.join(directory, "shards", name)))
    if not shards:
        raise ValueError(f"{directory}: manifest lists no shards")
    return manifest, shards


def split_by_map(shards, val_fraction, seed):
    """Rows (shard, row) of training and validation, and the validation map ids; no map is in
    both."""
    maps = sorted({int(m) for s in shards for m in np.unique(s.map_ids)})
    rng = np.random.default_rng(seed)
    order = rng.permutation(len(maps))
    n_val = max(1, int(round(val_fraction * len(maps)))) if len(maps) > 1 else 0
    val_maps = {maps[i] for i in order[:n_val]}
    train, val = [], []
    for si, s in enumerate(shards):
        for row, m in enumerate(s.map_ids):
            (val if int(m) in val_maps else train).append((si, row))
    return train, val, sorted(val_maps)


def batch(shards, rows):
    """Stacks the rows (shard, row) into float32 arrays x [b,3,H,W], y [b,2,H,W]."""
    x = np.stack([shards[s].inputs[r] for s, r in rows]).astype(np.float32)
    y = np.stack([shards[s].targets[r] for s, r in rows]).astype(np.float32)
    return x, y


def sample(directory, index):
    """Sample `index` over the whole dataset (shards in manifest order), in the fields of
    `plumekit dataset show --json`: shard, row, map_index, source and the SHA-256 of the sample's
    float32 inputs and targets as stored."""
    manifest, shards = open_dataset(directory)
    start = 0
    for entry, shard in zip(manifest["shards"], shards):
        n = shard.inputs.shape[0]
        if index < start + n:
            row = index - start
            raw = lambda a: np.ascontiguousarray(a[row], dtype="<f4").tobytes()  # noqa: E731
            return {"shard": os.path.basename(shard.directory), "row": row,
                    "map_index": int(shard.map_ids[row]),
                    "source": [float(v) for v in shard.sources[row]],
                    "inputs_sha256": hashlib.sha256(raw(shard.inputs)).hexdigest(),
                    "targets_sha256": hashlib.sha256(raw(shard.targets)).hexdigest()}
        start += n
    raise IndexError(f"{directory}: sample {index} of {start}")


if __name__ == "__main__":
    print(json.dumps(sample(sys.argv[1], int(sys.argv[2]))))
