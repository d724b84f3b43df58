"""Writer of plumekit-cnn/1 model files (the format is specified in ../README.md).

Layout, all integers little-endian:
  magic "PLUMECNN" (8 bytes) | version u32 = 1 | header length u32 | header JSON (UTF-8)
  | zero padding to a multiple of 16 | tensors, float32 LE | SHA-256 of every byte before it (32).
The C++ reader is surrogate/model_file.cpp.
"""
import hashlib
import json
import os
import struct

import numpy as np

MAGIC = b"PLUMECNN"
VERSION = 1
FORMAT = "plumekit-cnn/1"

# The feature contract of plumekit's datasets (dataset/ builds these channels).
DEFAULT_FEATURES = {
    "grid": [64, 64],
    "arena": [10.0, 4.0],
    "cells": "cell-centred: row r at y = (r + 0.5) * arena[1] / grid[0], column c at "
             "x = (c + 0.5) * arena[0] / grid[1]; row 0 at y = 0",
    "channels": [
        {"name": "region", "unit": "label",
         "labels": {"obstacle": 0, "free": 1, "wall": 2, "inlet": 3, "outlet": 4}},
        {"name": "signed_distance", "unit": "m", "sign": "negative inside obstacles"},
        {"name": "source_distance", "unit": "m", "form": "euclidean"},
    ],
}

def physics_channel(scale, options):
    """A hybrid model's physics_mean channel (issue 46): the advection-diffusion plume of the source
    with `options` (the dataset's generator.physics_mean: diffusivity, decay_rate, release_rate),
    fed divided by `scale`."""
    return {"name": "physics_mean", "unit": "concentration / scale", "scale": float(scale),
            "diffusivity": float(options["diffusivity"]), "decay_rate": float(options["decay_rate"]),
            "release_rate": float(options["release_rate"])}


def v2_features(cell_size, multiple, physics=None):
    """The v2 feature contract (physical grid, any map size; no grid/arena keys): 5 channels, the
    source channel in inverse form with min_distance half a cell; with `physics` (a
    physics_channel()), 6: that channel before the source distance."""
    features = {
        "cell_size": float(cell_size),
        "multiple": int(multiple),
        "cells": "nominal cell size cell_size: a map W x H m gets round(W/cell_size) x "
                 "round(H/cell_size) cells over the whole map (at least 1 each way), cell-centred, "
                 "row 0 at y = 0; the input is padded with zeros in every channel up to the next "
                 "multiple of `multiple`, on the high side (extra columns at the right, extra rows "
                 "at the top)",
        "channels": [
            dict(DEFAULT_FEATURES["channels"][0]),
            dict(DEFAULT_FEATURES["channels"][1]),
            {"name": "wind_u", "unit": "m/s"},
            {"name": "wind_v", "unit": "m/s"},
            {"name": "source_distance", "unit": "1/m", "form": "inverse",
             "min_distance": float(cell_size) / 2},
        ],
    }
    if physics is not None:
        features["channels"].insert(4, physics)
    return features


def residual_of(header):
    """(input channel, factor) a residual model adds to its scaled mean (outputs[mean].plus_input;
    the factor is that channel's scale over the mean's), or (None, 1.0)."""
    channels = header.get("features", {}).get("channels", [])
    names = [c["name"] for c in channels]
    for o in header.get("outputs", []):
        if o.get("name") == "mean" and o.get("plus_input"):
            c = names.index(o["plus_input"])
            return c, float(channels[c]["scale"]) / float(o["scale"])
    return None, 1.0


def is_v2(header):
    """A v2 model: its features give a cell size (a physical grid) instead of a grid and arena."""
    return "cell_size" in header.get("features", {})


DEFAULT_OUTPUTS = [
    {"name": "mean", "unit": "concentration (dataset units)", "scale": 1.0},
    {"name": "std", "unit": "concentration (dataset units)", "scale": 1.0},
]


def provenance_path(path, cwd=None):
    """How a provenance field names a file or folder: relative to the current folder when it lies
    inside it, else only its final name. Never absolute: a model file must not carry the layout of
    the machine that made it."""
    full = os.path.abspath(path)
    here = os.path.abspath(cwd or os.getcwd())
    if os.path.commonpath([full, here]) == here and full != here:
        return os.path.relpath(full, here)
    return os.path.basename(full.rstrip(os.sep)) or "."


def absolute_paths(value, where="training"):
    """The keys of `value` (a provenance dict) whose string is an absolute path."""
    if isinstance(value, dict):
        return [k for key, v in value.items() for k in absolute_paths(v, f"{where}.{key}")]
    if isinstance(value, list):
        return [k for i, v in enumerate(value) for k in absolute_paths(v, f"{where}[{i}]")]
    return [where] if isinstance(value, str) and os.path.isabs(value) else []


def header_for(model, features=None, outputs=None, training=None, trained_on=None):
    features = features or DEFAULT_FEATURES
    outputs = outputs or DEFAULT_OUTPUTS
    layers = []
    count = 0
    for name, op, conv, relu in model.layer_table():
        w = list(conv.weight.shape)
        cin, cout = (w[1], w[0]) if op == "conv2d" else (w[0], w[1])
        layers.append({"name": name, "op": op, "in": cin, "out": cout, "kernel": model.kernel,
                       "padding": model.padding, "relu": relu, "weight_shape": w,
                       "bias_shape": [cout]})
        count += conv.weight.numel() + conv.bias.numel()
    header = {
        "format": FORMAT,
        "architecture": {
            "type": "deepcfd-unet",
            "in_channels": model.in_channels,
            "out_channels": model.out_channels,
            "filters": list(model.filters),
            "kernel": model.kernel,
            "padding": model.padding,
            "convs_per_block": model.convs,
        },
        "layers": layers,
        "parameter_count": count,
        "data_bytes": 4 * count,
        "features": features,
        "outputs": outputs,
    }
    if training is not None:
        bad = absolute_paths(training)
        if bad:
            raise ValueError(f"provenance holds absolute paths ({', '.join(bad)}): "
                             "name them with provenance_path()")
        header["training"] = training
    if trained_on is not None:  # the ranges plumekit warns outside (docs/design/surrogate.md)
        header["trained_on"] = trained_on
    return header


def model_bytes(model, features=None, outputs=None, training=None, trained_on=None):
    header = header_for(model, features, outputs, training, trained_on)
    text = json.dumps(header, indent=1).encode("utf-8")
    head = MAGIC + struct.pack("<II", VERSION, len(text)) + text
    head += b"\0" * (-len(head) % 16)
    chunks = []
    for _, _, conv, _ in model.layer_table():
        for t in (conv.weight, conv.bias):
            chunks.append(t.detach().cpu().contiguous().numpy().astype("<f4").tobytes())
    body = head + b"".join(chunks)
    assert len(body) - len(head) == header["data_bytes"]
    return body + hashlib.sha256(body).digest()


def write_model(path, model, features=None, outputs=None, training=None, trained_on=None):
    """Writes atomically: a temporary file renamed over `path` once complete."""
    data = model_bytes(model, features, outputs, training, trained_on)
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)
    return len(data)


def output_scales(outputs=None):
    return np.array([o["scale"] for o in (outputs or DEFAULT_OUTPUTS)], dtype=np.float32)


def read_model(path):
    """(PlumeUNet in eval mode, header dict) from a plumekit-cnn/1 file; ValueError naming the file
    and the fault when it is malformed. The network outputs target / scale: multiply by
    output_scales(header["outputs"]) for dataset units."""
    import torch

    from model import PlumeUNet
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 16 + 32 or data[:8] != MAGIC:
        raise ValueError(f"{path}: not a plumekit-cnn file (magic or size)")
    version, length = struct.unpack("<II", data[8:16])
    if version != VERSION:
        raise ValueError(f"{path}: version {version}, this reader knows {VERSION}")
    if hashlib.sha256(data[:-32]).digest() != data[-32:]:
        raise ValueError(f"{path}: SHA-256 mismatch (truncated or corrupt)")
    header = json.loads(data[16:16 + length].decode("utf-8"))
    arch = header["architecture"]
    model = PlumeUNet(arch["in_channels"], arch["out_channels"], arch["filters"], arch["kernel"],
                      arch["convs_per_block"], *residual_of(header))
    offset = 16 + length
    offset += -offset % 16
    values = np.frombuffer(data, dtype="<f4", count=header["data_bytes"] // 4, offset=offset)
    at = 0
    with torch.no_grad():
        for _, _, conv, _ in model.layer_table():
            for t in (conv.weight, conv.bias):
                t.copy_(torch.from_numpy(values[at:at + t.numel()].copy()).reshape(t.shape))
                at += t.numel()
    if at != values.size:
        raise ValueError(f"{path}: {values.size} weights in the file, the architecture has {at}")
    return model.eval(), header
