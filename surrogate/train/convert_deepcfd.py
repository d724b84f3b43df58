#!/usr/bin/python3
"""Converts a PyTorch DeepCFD `UNetEx`-style network into a plumekit model file (plumekit-cnn/1).

    /usr/bin/python3 surrogate/train/convert_deepcfd.py CHECKPOINT OUT.pkcnn --arena 10,4
        [--grid 64,64] [--source-form inverse|euclidean] [--min-distance M]
        [--outputs mean|mean,std] [--scale S] [--unit UNIT] [--trained-on JSON]

CHECKPOINT is what torch.save wrote: a state dict, a dict holding one under "state_dict",
"model_state_dict" or "model", or a whole module. Its keys are DeepCFD's (Ribeiro et al. 2020,
Models/UNetEx.py): encoder block b, layer j at `encoder.b.j.0.*`; decoder o (one per output
channel, deepest level first) at `decoders.o.k.j.0.*`, where k = 0 is the deepest level. A layer
may be weight-normalised (`weight_g`, `weight_v`, PyTorch's weight_norm over dimension 0): the
converter folds it, w = g v / |v|. Batch normalisation is refused (exit 2): the engine has none, and
DeepCFD puts it after the ReLU, where it does not commute with the max-pool. The filters, kernel,
layers per block and input and output channels are read from the tensors' shapes.

The features the network was trained on are the converter's to state (plumekit builds them from
each map): a grid of --grid cells over an arena of --arena metres, the channels region, signed
distance and the source channel, in metres (euclidean) or 1/m (inverse: 1 / max(d, --min-distance),
the thesis's code), and the outputs, "mean" (a mean-only model: the likelihood then uses sigma_M
alone) and optionally "std", each times --scale in --unit. Exit 2, writing nothing, on a checkpoint
that is not such a network or on bad arguments.
"""
import argparse
import json
import os
import re
import sys

import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from model import PlumeUNet  # noqa: E402
from model_file import DEFAULT_FEATURES, provenance_path, write_model  # noqa: E402

KEY = re.compile(r"^(encoder)\.(\d+)\.(\d+)\.0\.(weight|weight_g|weight_v|bias)$|"
                 r"^(decoders)\.(\d+)\.(\d+)\.(\d+)\.0\.(weight|weight_g|weight_v|bias)$")
BATCH_NORM = ("running_mean", "running_var", "num_batches_tracked")


class ConversionError(Exception):
    pass


def state_dict_of(checkpoint):
    """The state dict inside whatever torch.save wrote."""
    if isinstance(checkpoint, torch.nn.Module):
        return checkpoint.state_dict()
    if isinstance(checkpoint, dict):
        for key in ("state_dict", "model_state_dict", "model"):
            inner = checkpoint.get(key)
            if isinstance(inner, dict):
                return inner
            if isinstance(inner, torch.nn.Module):
                return inner.state_dict()
        return checkpoint
    raise ConversionError(f"holds a {type(checkpoint).__name__}, not a state dict or a module")


def fold(parts, name):
    """A layer's weight: as stored, or w = g v / |v| (norm over all dimensions but the first)."""
    if "weight" in parts:
        return parts["weight"]
    if "weight_g" not in parts or "weight_v" not in parts:
        raise ConversionError(f"{name}: neither a weight nor both weight_g and weight_v")
    v, g = parts["weight_v"].double(), parts["weight_g"].double()
    norm = v.flatten(1).norm(dim=1).reshape([-1] + [1] * (v.dim() - 1))
    if not torch.all(norm > 0):
        raise ConversionError(f"{name}: a weight-norm direction of length 0")
    return (g * v / norm).float()


def layers_of(state):
    """{("encoder", b, j) or ("decoder", o, b, j): {"weight": ..., "bias": ...}}, b the level
    (0 the finest) for both."""
    bn = [k for k in state if k.endswith(BATCH_NORM)]
    if bn:
        raise ConversionError(f"batch normalisation ({bn[0]}): plumekit's engine has none and "
                              "DeepCFD's, after the ReLU, cannot be folded through the max-pool; "
                              "train with batch_norm=False")
    raw = {}
    for key, tensor in state.items():
        m = KEY.match(key)
        if not m:
            raise ConversionError(f"unexpected key {key} (not a DeepCFD UNetEx convolution)")
        if m.group(1):
            where = ("encoder", int(m.group(2)), int(m.group(3)))
            part = m.group(4)
        else:
            where = ("decoders", int(m.group(6)), int(m.group(7)), int(m.group(8)))
            part = m.group(9)
        raw.setdefault(where, {})[part] = tensor.detach().cpu()
    levels = 1 + max((w[1] for w in raw if w[0] == "encoder"), default=-1)
    out = {}
    for where, parts in raw.items():
        name = ".".join(map(str, where))
        if "bias" not in parts:
            raise ConversionError(f"{name}: no bias")
        layer = {"weight": fold(parts, name), "bias": parts["bias"].float()}
        if where[0] == "encoder":
            out[where] = layer
        else:  # DeepCFD lists a decoder's levels deepest first
            out[("decoder", where[1], levels - 1 - where[2], where[3])] = layer
    return out, levels


def build(state):
    """A PlumeUNet holding the checkpoint's weights (its shapes checked layer by layer)."""
    layers, levels = layers_of(state)
    if levels == 0:
        raise ConversionError("no encoder layers")
    convs = 1 + max(k[2] for k in layers if k[0] == "encoder")
    first = layers[("encoder", 0, 0)]["weight"]
    kernel, in_channels = first.shape[-1], first.shape[1]
    if first.dim() != 4 or first.shape[-2] != kernel or kernel % 2 == 0:
        raise ConversionError(f"encoder.0.0: weight {list(first.shape)}: not a square, odd kernel")
    filters = [layers[("encoder", b, 0)]["weight"].shape[0] for b in range(levels)]
    outputs = 1 + max((k[1] for k in layers if k[0] == "decoder"), default=-1)
    if outputs == 0:
        raise ConversionError("no decoders")
    model = PlumeUNet(in_channels, outputs, filters, kernel, convs)
    expected = {}
    for b, block in enumerate(model.encoder):
        for j, conv in enumerate(block):
            expected[("encoder", b, j)] = conv
    for o, decoder in enumerate(model.decoders):
        for b, block in enumerate(decoder):
            for j, conv in enumerate(block):
                expected[("decoder", o, b, j)] = conv
    if set(expected) != set(layers):
        missing = sorted(set(expected) - set(layers))
        extra = sorted(set(layers) - set(expected))
        raise ConversionError(f"not a UNetEx of {levels} levels x {convs} layers, {outputs} "
                              f"outputs: missing {missing[:3]}, unexpected {extra[:3]}")
    with torch.no_grad():
        for where, conv in expected.items():
            w, b = layers[where]["weight"], layers[where]["bias"]
            if w.shape != conv.weight.shape or b.shape != conv.bias.shape:
                raise ConversionError(f"{'.'.join(map(str, where))}: weight {list(w.shape)}, "
                                      f"expected {list(conv.weight.shape)}")
            conv.weight.copy_(w)
            conv.bias.copy_(b)
    return model


RANGES = ("map_width_m", "map_height_m", "inlet_speed_m_s", "openings")
WALLS = ("left", "right", "bottom", "top")


def check_trained_on(value):
    """The ranges plumekit's reader accepts: [lo, hi] per key of RANGES, inlet_walls of WALLS."""
    if not isinstance(value, dict):
        raise ConversionError("--trained-on must be a JSON object")
    for key, v in value.items():
        if key in RANGES:
            if not (isinstance(v, list) and len(v) == 2 and
                    all(isinstance(x, (int, float)) and abs(x) < float("inf") for x in v) and
                    v[0] <= v[1]):
                raise ConversionError(f"--trained-on: {key} must be [lo, hi], lo <= hi")
        elif key == "inlet_walls":
            if not (isinstance(v, list) and all(w in WALLS for w in v)):
                raise ConversionError(f"--trained-on: inlet_walls must list walls of {WALLS}")
        else:
            raise ConversionError(f"--trained-on: unknown key {key!r} (known: "
                                  f"{', '.join(RANGES + ('inlet_walls',))})")


def pair(text, kind, name):
    try:
        a, b = (kind(v) for v in text.split(","))
    except ValueError:
        raise ConversionError(f"{name} must be two numbers A,B, got {text!r}")
    if not (a > 0 and b > 0):
        raise ConversionError(f"{name} must be positive, got {text!r}")
    return a, b


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("checkpoint")
    parser.add_argument("out")
    parser.add_argument("--arena", required=True, help="W,H in metres the grid covers")
    parser.add_argument("--grid", default="64,64", help="ROWS,COLS (plumekit builds 64,64)")
    parser.add_argument("--source-form", choices=("euclidean", "inverse"), default="inverse")
    parser.add_argument("--min-distance", type=float, help="inverse form: the floor, m "
                        "(default half the smaller cell side)")
    parser.add_argument("--outputs", default=None, help="names of the output channels in order: "
                        "mean, or mean,std (default: by their count)")
    parser.add_argument("--scale", type=float, default=1.0, help="output times this = value")
    parser.add_argument("--unit", default="concentration (dataset units)")
    parser.add_argument("--trained-on", help="JSON: what the network was trained on, e.g. "
                        "'{\"map_width_m\": [10, 10], \"inlet_speed_m_s\": [1, 1], "
                        "\"inlet_walls\": [\"left\"]}'; plumekit warns on maps outside it")
    args = parser.parse_args(argv[1:])
    try:
        if os.path.exists(args.out):
            raise ConversionError(f"{args.out} exists; plumekit does not overwrite it")
        width, height = pair(args.arena, float, "--arena")
        rows, cols = pair(args.grid, int, "--grid")
        if args.min_distance is not None and not (args.min_distance > 0):
            raise ConversionError("--min-distance must be positive")
        if not (args.scale == args.scale and abs(args.scale) < float("inf")):
            raise ConversionError("--scale must be a finite number")
        try:
            checkpoint = torch.load(args.checkpoint, map_location="cpu")
        except Exception as e:  # torch raises many kinds for a file that is not a checkpoint
            raise ConversionError(f"cannot be read by torch.load ({type(e).__name__}: {e})")
        state = state_dict_of(checkpoint)
        weight_norm = any(k.endswith("weight_g") for k in state)
        model = build(state)
        names = (args.outputs.split(",") if args.outputs
                 else ["mean", "std"][:model.out_channels])
        if len(names) != model.out_channels or names[0] != "mean" or \
                (len(names) == 2 and names[1] != "std"):
            raise ConversionError(f"the network has {model.out_channels} outputs; name them "
                                  "mean (and std)")
        if model.in_channels != 3:
            raise ConversionError(f"the network takes {model.in_channels} input channels; "
                                  "plumekit builds 3 (region, signed distance, source)")
        features = {k: v for k, v in DEFAULT_FEATURES.items()}
        features["grid"] = [rows, cols]
        features["arena"] = [width, height]
        channels = [dict(c) for c in DEFAULT_FEATURES["channels"]]
        channels[2] = {"name": "source_distance", "form": args.source_form,
                       "unit": "1/m" if args.source_form == "inverse" else "m"}
        if args.source_form == "inverse" and args.min_distance is not None:
            channels[2]["min_distance"] = args.min_distance
        features["channels"] = channels
        outputs = [{"name": n, "unit": args.unit, "scale": args.scale} for n in names]
        training = {"converted_from": provenance_path(args.checkpoint),
                    "converter": "surrogate/train/convert_deepcfd.py",
                    "weight_norm_folded": weight_norm}
        trained_on = None
        if args.trained_on:
            try:
                trained_on = json.loads(args.trained_on)
            except ValueError as e:
                raise ConversionError(f"--trained-on is not JSON ({e})")
            check_trained_on(trained_on)
        write_model(args.out, model, features, outputs, training, trained_on)
    except ConversionError as e:
        print(f"convert_deepcfd.py: {args.checkpoint}: {e}", file=sys.stderr)
        return 2
    print(f"wrote {args.out}: {model.in_channels} inputs, {model.out_channels} output(s) "
          f"({', '.join(names)}), filters {list(model.filters)}, kernel {model.kernel}, "
          f"{model.convs} layers per block, source channel {args.source_form}"
          + (", weight norm folded" if weight_norm else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
