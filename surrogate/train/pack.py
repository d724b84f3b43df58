#!/usr/bin/env python3
"""Packs plumekit datasets small enough to travel to a GPU machine, and unpacks them there.

    /usr/bin/python3 surrogate/train/pack.py pack DATASET... --out PACK
    python3 surrogate/train/pack.py unpack PACK --out DIR      # on the GPU machine

A GPU machine takes a few tens of MiB (docs/design/surrogate.md, "Training on a GPU"), while a
dataset's shards repeat each map's own channels (region, signed distance, wind) for every source
and store every plane as float32. A pack keeps, per shard, the map's channels once (float32),
the per-source planes (the physics channel when present, the target mean and std) as float16,
and the sources; the source-distance channel is recomputed from the sources on unpacking (the
same cell centres as GridShape::centre, from the float32 sources: within 1e-5 m of the stored
channel, which the dataset measured from the double-precision source). numpy's savez_compressed squeezes the zeros.

Unpacking writes each dataset back in the plumekit-dataset/1 layout the trainer reads
(manifest.json, maps/, shards/NAME/{inputs,targets,sources,map_ids}.npy), with the manifest's
"packed" key saying the planes went through float16: the manifest's checksums are the originals',
so plumekit's C++ reader refuses an unpacked dataset (it is for training only). Packing checks
that the map's channels are the same in every sample and that the recomputed source distances
equal the stored ones; it refuses a dataset that is not on a physical grid, and an existing --out.
"""
import argparse
import json
import os
import shutil
import sys

import numpy as np

MAP_CHANNELS = ("region", "signed_distance", "wind_u", "wind_v")


class PackError(Exception):
    pass


def channel_names(manifest):
    names = manifest.get("contract", {}).get("inputs", {}).get("names")
    if not names:
        raise PackError("manifest.json has no contract.inputs.names (made before issue 46): "
                        "generate the dataset again with this plumekit")
    if list(names[:4]) != list(MAP_CHANNELS) or names[-1] != "source_distance":
        raise PackError(f"channels {names}: only physical-grid datasets (--feature-cell) are packed")
    return names


def source_distance(sources, ny, nx, width, height):
    """[n, ny, nx] float32: what surrogate::source_feature computes, in float64 then cast."""
    x = (np.arange(nx) + 0.5) * (width / nx)
    y = (np.arange(ny) + 0.5) * (height / ny)
    dx = x[None, None, :] - sources[:, 0, None, None].astype(np.float64)
    dy = y[None, :, None] - sources[:, 1, None, None].astype(np.float64)
    return np.sqrt(dx * dx + dy * dy).astype(np.float32)


def map_size(dataset, entry):
    with open(os.path.join(dataset, entry["map"])) as f:
        size = json.load(f)["size"]
    return float(size[0]), float(size[1])


def pack_shard(dataset, entry, names, out_dir):
    d = os.path.join(dataset, "shards", entry["name"])
    x = np.load(os.path.join(d, "inputs.npy"))
    t = np.load(os.path.join(d, "targets.npy"))
    s = np.load(os.path.join(d, "sources.npy"))
    per_map = x[0, :4]
    if not np.array_equal(x[:, :4], np.broadcast_to(per_map, x[:, :4].shape)):
        raise PackError(f"{d}: the map's channels differ between samples")
    width, height = map_size(dataset, entry)
    dist = source_distance(s, x.shape[2], x.shape[3], width, height)
    # The dataset measured from the double-precision source; sources.npy holds it as float32.
    if not np.allclose(dist, x[:, -1], rtol=1e-5, atol=1e-5):
        raise PackError(f"{d}: the source distance is not the recomputed one "
                        f"(max difference {np.abs(dist - x[:, -1]).max()})")
    planes = {"map_channels": per_map, "sources": s,
              "mean": t[:, 0].astype(np.float16), "std": t[:, 1].astype(np.float16)}
    if "physics_mean" in names:
        planes["physics_mean"] = x[:, names.index("physics_mean")].astype(np.float16)
    np.savez_compressed(os.path.join(out_dir, entry["name"] + ".npz"), **planes)


def write_whole(out, fill):
    """fill(folder) into OUT.partial, renamed to OUT once complete: a refusal or a crash leaves
    nothing partial, and an existing OUT is never touched."""
    if os.path.exists(out):
        raise PackError(f"--out {out}: exists; name a new folder")
    tmp = out + ".partial"
    shutil.rmtree(tmp, ignore_errors=True)
    try:
        fill(tmp)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    os.rename(tmp, out)


def pack(datasets, out):
    write_whole(out, lambda tmp: pack_into(datasets, tmp))


def pack_into(datasets, tmp):
    for dataset in datasets:
        with open(os.path.join(dataset, "manifest.json")) as f:
            manifest = json.load(f)
        names = channel_names(manifest)
        name = os.path.basename(os.path.normpath(dataset))
        target = os.path.join(tmp, name)
        os.makedirs(os.path.join(target, "shards"))
        shutil.copytree(os.path.join(dataset, "maps"), os.path.join(target, "maps"))
        shutil.copy(os.path.join(dataset, "manifest.json"), target)
        for entry in manifest["shards"]:
            pack_shard(dataset, entry, names, os.path.join(target, "shards"))
        print(f"packed {dataset}: {len(manifest['shards'])} shards", file=sys.stderr)


def unpack_shard(packed, entry, names, dataset):
    p = np.load(os.path.join(packed, "shards", entry["name"] + ".npz"))
    n = entry["samples"]
    per_map = p["map_channels"]
    ny, nx = per_map.shape[1:]
    width, height = map_size(packed, entry)
    x = np.empty((n, len(names), ny, nx), dtype=np.float32)
    x[:, :4] = per_map
    if "physics_mean" in names:
        x[:, names.index("physics_mean")] = p["physics_mean"].astype(np.float32)
    x[:, -1] = source_distance(p["sources"], ny, nx, width, height)
    t = np.stack([p["mean"].astype(np.float32), p["std"].astype(np.float32)], axis=1)
    d = os.path.join(dataset, "shards", entry["name"])
    os.makedirs(d)
    np.save(os.path.join(d, "inputs.npy"), x)
    np.save(os.path.join(d, "targets.npy"), t)
    np.save(os.path.join(d, "sources.npy"), p["sources"])
    np.save(os.path.join(d, "map_ids.npy"), np.full(n, entry["map_index"], dtype=np.int32))


def unpack(pack_dir, out):
    write_whole(out, lambda tmp: unpack_into(pack_dir, tmp))


def unpack_into(pack_dir, out):
    for name in sorted(os.listdir(pack_dir)):
        packed = os.path.join(pack_dir, name)
        with open(os.path.join(packed, "manifest.json")) as f:
            manifest = json.load(f)
        names = channel_names(manifest)
        dataset = os.path.join(out, name)
        shutil.copytree(os.path.join(packed, "maps"), os.path.join(dataset, "maps"))
        for entry in manifest["shards"]:
            unpack_shard(packed, entry, names, dataset)
        manifest["packed"] = ("unpacked by surrogate/train/pack.py: the per-source planes went "
                              "through float16; the checksums are the original shards'")
        with open(os.path.join(dataset, "manifest.json"), "w") as f:
            json.dump(manifest, f, indent=2)
        print(f"unpacked {name}: {len(manifest['shards'])} shards", file=sys.stderr)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="verb", required=True)
    p = sub.add_parser("pack", help="datasets -> a pack")
    p.add_argument("datasets", nargs="+")
    p.add_argument("--out", required=True)
    u = sub.add_parser("unpack", help="a pack -> datasets the trainer reads")
    u.add_argument("pack")
    u.add_argument("--out", required=True)
    args = ap.parse_args(argv)
    try:
        if args.verb == "pack":
            pack(args.datasets, args.out)
        else:
            unpack(args.pack, args.out)
    except (PackError, OSError, KeyError, ValueError) as e:
        print(f"pack.py: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
