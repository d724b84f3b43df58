"""Reads plumekit-dataset/1 directories (docs/design/dataset.md) memory-mapped, and splits them by map.

DIR/manifest.json lists `shards` (each with `name`, else `map_index`); DIR/shards/NAME/ holds
inputs.npy float32 [n,3,64,64], targets.npy float32 [n,2,64,64], sources.npy float32 [n,2] and
map_ids.npy int [n]. Arrays stay on disk (numpy mmap_mode='r'); a batch copies only its rows.

v2 datasets (`plumekit dataset generate --feature-cell C`; feature_cell() finds C in the manifest)
hold 5 input channels (region, signed distance, wind u, wind v, Euclidean source distance) on each
map's own physical grid, round(W / C) x round(H / C) cells, so the shapes differ from shard to
shard (one shard, one map). v2_input() turns a v2 sample into what a v2 network reads: channel 4
as 1 / max(distance, C / 2), zero-padded on the high side up to a multiple of 2 ** levels.
Hybrid datasets (issue 46, `--physics-input`) hold a sixth, physics_mean (the physics plume of the
source, concentration units), before the source distance; channel_names() reads the names from
the manifest's contract.inputs.names, and v2_input() can leave channels out and scale one.
map_ranges() reads the maps' files for a model header's `trained_on`.

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
        if (self.inputs.ndim != 4 or self.inputs.shape[1] not in (3, 5, 6) or self.targets.shape[0] != n
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
    train, val, val_maps = split_datasets(shards, [0] * len(shards), val_fraction, seed)
    return train, val, val_maps[0]


def split_datasets(shards, dataset_of, val_fraction, seed):
    """split_by_map() over several datasets, whose shards are `shards` (all datasets' shards, in
    order) with shard i from dataset dataset_of[i]. Map m of dataset k is the map (k, m): map ids of
    different datasets never name the same map. Each dataset's maps are split on their own by the
    same rule (round(val_fraction x its maps), at least one, none of a dataset with one map), drawn
    from numpy's default_rng(seed) for dataset 0 (so a lone dataset, and the first of several,
    splits as it would alone) and default_rng([seed, k]) for dataset k > 0. Rows (shard, row) of
    training and validation, and each dataset's sorted validation map ids (a list per dataset)."""
    count = max(dataset_of) + 1 if dataset_of else 0
    val_maps = []
    for k in range(count):
        maps = sorted({int(m) for s, d in zip(shards, dataset_of) if d == k
                       for m in np.unique(s.map_ids)})
        rng = np.random.default_rng(seed if k == 0 else [seed, k])
        order = rng.permutation(len(maps))
        n_val = max(1, int(round(val_fraction * len(maps)))) if len(maps) > 1 else 0
        val_maps.append({maps[i] for i in order[:n_val]})
    train, val = [], []
    for si, s in enumerate(shards):
        held = val_maps[dataset_of[si]]
        for row, m in enumerate(s.map_ids):
            (val if int(m) in held else train).append((si, row))
    return train, val, [sorted(v) for v in val_maps]


def batch(shards, rows):
    """Stacks the rows (shard, row) into float32 arrays x [b,3,H,W], y [b,2,H,W]."""
    x = np.stack([shards[s].inputs[r] for s, r in rows]).astype(np.float32)
    y = np.stack([shards[s].targets[r] for s, r in rows]).astype(np.float32)
    return x, y


def feature_cell(directory, manifest=None):
    """The v2 feature cell size in metres, or 0 for a v1 dataset (the key absent or 0). Looked up in
    manifest.json's generator (generator.dataset.feature_cell or generator.feature_cell), then
    parameters.json (the same two places), then manifest.json's contract.grid.cell."""
    if manifest is None:
        with open(os.path.join(directory, "manifest.json")) as f:
            manifest = json.load(f)
    candidates = [manifest.get("generator")]
    params = os.path.join(directory, "parameters.json")
    if os.path.exists(params):
        with open(params) as f:
            candidates.append(json.load(f))
    for c in candidates:
        if not isinstance(c, dict):
            continue
        for where in (c.get("dataset"), c):
            if isinstance(where, dict) and isinstance(where.get("feature_cell"), (int, float)):
                if where["feature_cell"] > 0:
                    return float(where["feature_cell"])
    grid = (manifest.get("contract") or {}).get("grid") or {}
    if isinstance(grid.get("cell"), (int, float)) and grid["cell"] > 0:
        return float(grid["cell"])
    return 0.0


V1_CHANNELS = ("region", "signed_distance", "source_distance")
V2_CHANNELS = ("region", "signed_distance", "wind_u", "wind_v", "source_distance")
PHYSICS = "physics_mean"


def channel_names(manifest, cell):
    """The dataset's input channel names in order: the manifest's contract.inputs.names (written
    since issue 46), else the v1 or v2 ones by the feature cell."""
    names = ((manifest.get("contract") or {}).get("inputs") or {}).get("names")
    if names:
        return tuple(names)
    return V2_CHANNELS if cell > 0 else V1_CHANNELS


def padded_size(n, multiple):
    return -(-int(n) // multiple) * multiple


def v2_input(x, min_distance, rows, cols, keep=None, divide=None):
    """Network input of v2 samples x [b,C,ny,nx] (dataset units): the channels `keep` (indices,
    default all; the source distance last), channel k of them divided by divide[k] (a dict, e.g.
    the physics channel by its scale), the last (metres) as 1 / max(distance, min_distance), then
    every channel zero-padded to [b,len(keep),rows,cols] (extra rows at the top, y > H; extra
    columns at the right)."""
    x = np.asarray(x, dtype=np.float32)
    if keep is not None and list(keep) != list(range(x.shape[1])):
        x = x[:, list(keep)]
    out = np.zeros(x.shape[:2] + (rows, cols), np.float32)
    out[:, :, :x.shape[2], :x.shape[3]] = x
    for k, by in (divide or {}).items():
        out[:, k] /= np.float32(by)
    d = out[:, -1, :x.shape[2], :x.shape[3]]
    out[:, -1, :x.shape[2], :x.shape[3]] = 1.0 / np.maximum(d, np.float32(min_distance))
    return out


def map_file(directory, manifest, map_index):
    """Path of map `map_index`'s file: the manifest's shard entry's `map`, else maps/map-NNNNN.json."""
    for s in manifest.get("shards", []):
        if s.get("map_index") == map_index and s.get("map"):
            return os.path.join(directory, s["map"])
    return os.path.join(directory, "maps", "map-%05d.json" % map_index)


def _opening_wall(opening, width, height, origin, tol=1e-6):
    """left/right/bottom/top for a plumekit-map/2 opening on an arena wall (as core's
    Map::wall_of), None for one on an obstacle's edge (a window or vent)."""
    (x0, y0), (x1, y1) = opening["from"], opening["to"]
    x0, x1, y0, y1 = x0 - origin[0], x1 - origin[0], y0 - origin[1], y1 - origin[1]
    if abs(x0 - x1) <= tol:
        return "left" if abs(x0) <= tol else "right" if abs(x0 - width) <= tol else None
    return "bottom" if abs(y0) <= tol else "top" if abs(y0 - height) <= tol else None


def map_summary(path):
    """width, height, inlets [(speed, wall or None)], opening count of a plumekit-map/1 or /2 file."""
    with open(path) as f:
        m = json.load(f)
    width, height = (float(v) for v in m["size"])
    if "openings" in m:  # plumekit-map/2
        origin = (m.get("frame") or {}).get("origin", [0.0, 0.0])
        inlets = [(float(o["speed"]), _opening_wall(o, width, height, origin))
                  for o in m["openings"] if o.get("kind") == "inlet"]
        count = len(m["openings"])
    else:  # plumekit-map/1: one inlet and one outlet, each on a wall
        inlets = [(float(m["inlet"]["speed"]), m["inlet"]["side"])]
        count = 2
    return {"width": width, "height": height, "inlets": inlets, "openings": count}


def map_summaries(directory, manifest, map_ids):
    """map_summary() of each of the maps map_ids (sorted, each once), or None when one has no map
    file (the synthetic smoke datasets hold none)."""
    maps = []
    for m in sorted(set(int(i) for i in map_ids)):
        path = map_file(directory, manifest, m)
        if not os.path.exists(path):
            return None
        maps.append(map_summary(path))
    return maps


def ranges(maps):
    """map_ranges() of map summaries (of one dataset or several), or None for none."""
    if not maps:
        return None
    span = lambda v: [min(v), max(v)]  # noqa: E731
    speeds = [s for m in maps for s, _ in m["inlets"]]
    out = {"map_width_m": span([m["width"] for m in maps]),
           "map_height_m": span([m["height"] for m in maps])}
    if speeds:
        out["inlet_speed_m_s"] = span(speeds)
    out["openings"] = span([m["openings"] for m in maps])
    walls = sorted({w or "interior" for m in maps for _, w in m["inlets"]})
    if walls:
        out["inlet_walls"] = walls
    return out


def map_ranges(directory, manifest, map_ids):
    """A model header's `trained_on` (docs/design/surrogate.md) over the maps map_ids: map_width_m,
    map_height_m, inlet_speed_m_s, openings as [lo, hi], inlet_walls (sorted; an inlet not on an
    arena wall, a window on an obstacle's edge, counts as "interior"). None when the dataset holds no map files (the synthetic smoke datasets)."""
    maps = map_summaries(directory, manifest, map_ids)
    return None if maps is None else ranges(maps)


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
