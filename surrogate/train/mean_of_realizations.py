#!/usr/bin/env python3
"""Ground truth closer to the world's mean: the average of several realizations of one dataset.

    /usr/bin/python3 surrogate/train/mean_of_realizations.py OUT DATASET DATASET...

Each DATASET holds the same maps and sources (`plumekit dataset generate --map-dir` with other
`--seed`s: the seed only draws the filaments then). A single realization's mean is noisy: two of
them differ by about 19 % (relative L2) on the nine test maps at 0.2 m, so scoring a model against
one realization charges it with that noise (a perfect model would score about 19 % / sqrt(2)).
OUT is the first dataset with its targets replaced by the average over the N realizations, of
the mean channel and of the std channel alike; its inputs are the first's (the inputs do not
depend on the seed, which is checked), its checksums recomputed, and its manifest's
"realizations" key names the datasets averaged. plumekit's own reader reads it.

Refused (exit 2, nothing written): an existing OUT; fewer than two datasets; datasets whose
shards, maps, sources or inputs differ.
"""
import hashlib
import json
import os
import shutil
import sys

import numpy as np


class RealizationError(Exception):
    pass


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def manifest_of(d):
    with open(os.path.join(d, "manifest.json")) as f:
        return json.load(f)


def check_same(first, other, m0, m1):
    names0 = [(s["name"], s["samples"]) for s in m0["shards"]]
    if names0 != [(s["name"], s["samples"]) for s in m1["shards"]]:
        raise RealizationError(f"{other}: its shards are not {first}'s")
    for s in m0["shards"]:
        for f in ("inputs.npy", "sources.npy"):
            if s["sha256"][f] != next(t for t in m1["shards"] if t["name"] == s["name"])["sha256"][f]:
                raise RealizationError(f"{other}: {s['name']}/{f} differs from {first}'s: not "
                                       "the same maps and sources")


def average(out, datasets):
    if os.path.exists(out):
        raise RealizationError(f"{out}: exists; name a new folder")
    if len(datasets) < 2:
        raise RealizationError("give at least two datasets to average")
    manifests = [manifest_of(d) for d in datasets]
    for d, m in zip(datasets[1:], manifests[1:]):
        check_same(datasets[0], d, manifests[0], m)
    tmp = out + ".partial"
    shutil.rmtree(tmp, ignore_errors=True)
    try:
        shutil.copytree(datasets[0], tmp)
        manifest = manifests[0]
        for s in manifest["shards"]:
            targets = [np.load(os.path.join(d, "shards", s["name"], "targets.npy")).astype(np.float64)
                       for d in datasets]
            mean = (sum(targets) / len(targets)).astype(np.float32)
            shard = os.path.join(tmp, "shards", s["name"])
            np.save(os.path.join(shard, "targets.npy"), mean)
            s["sha256"]["targets.npy"] = sha256(os.path.join(shard, "targets.npy"))
            with open(os.path.join(shard, "checksums.json"), "w") as f:
                json.dump(s["sha256"], f, indent=2)
                f.write("\n")
        manifest["realizations"] = {
            "count": len(datasets),
            "datasets": [os.path.basename(os.path.normpath(d)) for d in datasets],
            "targets": "the average of the datasets' targets (mean and std channels alike)"}
        with open(os.path.join(tmp, "manifest.json"), "w") as f:
            json.dump(manifest, f, indent=2)
            f.write("\n")
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    os.rename(tmp, out)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) < 1 or argv[0] in ("-h", "--help"):
        print(__doc__, file=sys.stderr)
        return 0 if argv else 2
    try:
        average(argv[0], argv[1:])
    except (RealizationError, OSError, KeyError, ValueError, StopIteration) as e:
        print(f"mean_of_realizations.py: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
