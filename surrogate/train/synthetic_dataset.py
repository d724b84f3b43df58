"""Writes a small random dataset in the plumekit-dataset/1 layout (manifest.json, shards/NAME/*.npy)
for the training smoke test: plausible features, a blob of "gas" downwind of the source.

    /usr/bin/python3 surrogate/train/synthetic_dataset.py OUT_DIR [--maps 3] [--per-map 4]
"""
import argparse
import json
import os

import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("out")
    ap.add_argument("--maps", type=int, default=3)
    ap.add_argument("--per-map", type=int, default=4)
    ap.add_argument("--grid", type=int, default=64)
    ap.add_argument("--seed", type=int, default=3)
    args = ap.parse_args()
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
            plume = 1000 * np.exp(-((yy - sy) ** 2) / (0.05 + 0.05 * np.maximum(xx - sx, 0)))
            plume *= (xx >= sx) * (region > 0)
            targets[i] = [plume, 0.3 * plume]
            sources[i] = [sx, sy]
        name = "shard-%05d" % m
        d = os.path.join(args.out, "shards", name)
        os.makedirs(d, exist_ok=True)
        np.save(os.path.join(d, "inputs.npy"), inputs)
        np.save(os.path.join(d, "targets.npy"), targets)
        np.save(os.path.join(d, "sources.npy"), sources)
        np.save(os.path.join(d, "map_ids.npy"), np.full(n, m, np.int32))
        shards.append({"name": name, "map_index": m, "samples": n})
    with open(os.path.join(args.out, "manifest.json"), "w") as f:
        json.dump({"format": "plumekit-dataset/1", "synthetic": True, "shards": shards}, f, indent=1)


if __name__ == "__main__":
    main()
