"""Writes a small random dataset in the plumekit-dataset/1 layout (manifest.json, shards/NAME/*.npy)
for the training smoke test: plausible features, a blob of "gas" downwind of the source.

    /usr/bin/python3 surrogate/train/synthetic_dataset.py OUT_DIR [--maps 3] [--per-map 4]

--feature-cell C (> 0) writes a v2 dataset instead (the layout of `plumekit dataset generate
--feature-cell C`): maps of different sizes (--sizes WxH,..., else drawn from 2.5-6 m a side), each
on its own grid of round(W / C) x round(H / C) cells, 5 input channels (region, signed distance,
wind u, wind v, Euclidean source distance), the map files maps/map-NNNNN.json (plumekit-map/2,
inlets on the left wall at 0.5-1.5 m/s, an outlet on the right; every third map also has a second
inlet on the bottom wall) and feature_cell in manifest.json's generator and parameters.json (where
`plumekit dataset generate` puts it).
"""
import argparse
import json
import os

import numpy as np


def plume_targets(xx, yy, sx, sy, region):
    """Mean and std of a made-up plume blowing along +x from (sx, sy), 0 in obstacles."""
    plume = 1000 * np.exp(-((yy - sy) ** 2) / (0.05 + 0.05 * np.maximum(xx - sx, 0)))
    plume *= (xx >= sx) * (region > 0)
    return [plume, 0.3 * plume]


def write_shard(out, m, inputs, targets, sources):
    """Map m's shard files; returns the shard's name."""
    name = "shard-%05d" % m
    d = os.path.join(out, "shards", name)
    os.makedirs(d, exist_ok=True)
    np.save(os.path.join(d, "inputs.npy"), inputs)
    np.save(os.path.join(d, "targets.npy"), targets)
    np.save(os.path.join(d, "sources.npy"), sources)
    np.save(os.path.join(d, "map_ids.npy"), np.full(len(inputs), m, np.int32))
    return name


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("out")
    ap.add_argument("--maps", type=int, default=3)
    ap.add_argument("--per-map", type=int, default=4)
    ap.add_argument("--grid", type=int, default=64)
    ap.add_argument("--seed", type=int, default=3)
    ap.add_argument("--feature-cell", type=float, default=0.0, help="v2 dataset with this cell (m)")
    ap.add_argument("--sizes", help="v2: map sizes W x H in metres, e.g. 3x2,4.4x3")
    args = ap.parse_args()
    if args.feature_cell > 0:
        return write_v2(args)
    rng = np.random.default_rng(args.seed)
    g, width, height = args.grid, 10.0, 4.0
    yy, xx = np.meshgrid((np.arange(g) + 0.5) * height / g, (np.arange(g) + 0.5) * width / g,
                         indexing="ij")
    shards = []
    for m in range(args.maps):
        n = args.per_map
        region = np.ones((g, g), np.float32)
        x0, y0 = rng.uniform(2, 7), rng.uniform(0.5, 2.5)
        inside = (xx > x0) & (xx < x0 + 1) & (yy > y0) & (yy < y0 + 1)
        region[inside] = 0
        region[:, 0], region[:, -1], region[0, :], region[-1, :] = 3, 4, 2, 2
        sdf = np.minimum.reduce([xx - x0, x0 + 1 - xx, yy - y0, y0 + 1 - yy])
        sdf = np.where(inside, sdf, np.hypot(np.maximum(0, np.maximum(x0 - xx, xx - x0 - 1)),
                                             np.maximum(0, np.maximum(y0 - yy, yy - y0 - 1))))
        inputs = np.zeros((n, 3, g, g), np.float32)
        targets = np.zeros((n, 2, g, g), np.float32)
        sources = np.zeros((n, 2), np.float32)
        for i in range(n):
            sx, sy = rng.uniform(0.5, 2.0), rng.uniform(0.5, 3.5)
            d = np.hypot(xx - sx, yy - sy)
            inputs[i] = [region, sdf, d]
            targets[i] = plume_targets(xx, yy, sx, sy, region)
            sources[i] = [sx, sy]
        name = write_shard(args.out, m, inputs, targets, sources)
        shards.append({"name": name, "map_index": m, "samples": n})
    with open(os.path.join(args.out, "manifest.json"), "w") as f:
        json.dump({"format": "plumekit-dataset/1", "synthetic": True, "shards": shards}, f, indent=1)



def cells(length, cell):
    """max(1, round(length / cell)), halves rounded away from zero (as C++'s std::round)."""
    return max(1, int(np.floor(length / cell + 0.5)))


def write_v2(args):
    rng = np.random.default_rng(args.seed)
    sizes = ([tuple(float(v) for v in wh.split("x")) for wh in args.sizes.split(",")] if args.sizes
             else [(round(rng.uniform(2.5, 6), 1), round(rng.uniform(2.5, 6), 1))
                   for _ in range(args.maps)])
    generator = {"seed": args.seed, "maps": len(sizes), "synthetic": True,
                 "feature_cell": args.feature_cell}
    os.makedirs(os.path.join(args.out, "maps"), exist_ok=True)
    shards = []
    for m, (width, height) in enumerate(sizes):
        nx, ny = cells(width, args.feature_cell), cells(height, args.feature_cell)
        yy, xx = np.meshgrid((np.arange(ny) + 0.5) * height / ny, (np.arange(nx) + 0.5) * width / nx,
                             indexing="ij")
        bw, bh = 0.3 * width, 0.3 * height  # one block in the middle third
        x0, y0 = rng.uniform(0.35, 0.45) * width, rng.uniform(0.2, 0.5) * height
        inside = (xx > x0) & (xx < x0 + bw) & (yy > y0) & (yy < y0 + bh)
        region = np.ones((ny, nx), np.float32)
        region[inside] = 0
        region[0, :], region[-1, :] = 2, 2
        region[:, 0], region[:, -1] = 3, 4
        outside = np.hypot(np.maximum(0, np.maximum(x0 - xx, xx - x0 - bw)),
                           np.maximum(0, np.maximum(y0 - yy, yy - y0 - bh)))
        into = np.minimum.reduce([xx - x0, x0 + bw - xx, yy - y0, y0 + bh - yy])
        sdf = np.where(inside, -into, np.minimum(outside, np.minimum(yy, height - yy)))
        speed = round(float(rng.uniform(0.5, 1.5)), 3)
        openings = [{"kind": "inlet", "from": [0.0, 0.0], "to": [0.0, height], "speed": speed,
                     "profile": "uniform"},
                    {"kind": "outlet", "from": [width, 0.0], "to": [width, height]}]
        if m % 3 == 2:
            openings.append({"kind": "inlet", "from": [0.5 * width, 0.0], "to": [0.6 * width, 0.0],
                             "speed": 2.0 * speed, "profile": "uniform"})
        wind_u = np.where(inside, 0, speed).astype(np.float32)
        wind_v = np.where(inside, 0, 0.1 * speed * np.sin(np.pi * xx / width)).astype(np.float32)
        n = args.per_map
        inputs = np.zeros((n, 5, ny, nx), np.float32)
        targets = np.zeros((n, 2, ny, nx), np.float32)
        sources = np.zeros((n, 2), np.float32)
        for i in range(n):
            sx, sy = rng.uniform(0.1, 0.3) * width, rng.uniform(0.2, 0.8) * height
            d = np.hypot(xx - sx, yy - sy)
            inputs[i] = [region, sdf, wind_u, wind_v, d]
            targets[i] = plume_targets(xx, yy, sx, sy, region)
            sources[i] = [sx, sy]
        name = write_shard(args.out, m, inputs, targets, sources)
        map_path = "maps/map-%05d.json" % m
        with open(os.path.join(args.out, map_path), "w") as f:
            json.dump({"format": "plumekit-map/2", "name": "synthetic-%d" % m, "size": [width, height],
                       "openings": openings,
                       "obstacles": [[[x0, y0], [x0 + bw, y0], [x0 + bw, y0 + bh], [x0, y0 + bh]]]},
                      f, indent=1)
        shards.append({"name": name, "map_index": m, "map": map_path, "samples": n})
    with open(os.path.join(args.out, "parameters.json"), "w") as f:
        json.dump(generator, f, indent=1)
    with open(os.path.join(args.out, "manifest.json"), "w") as f:
        json.dump({"format": "plumekit-dataset/1", "synthetic": True, "generator": generator,
                   "shards": shards}, f, indent=1)


if __name__ == "__main__":
    main()
