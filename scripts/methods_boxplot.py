#!/usr/bin/python3
"""Box plots of several `evaluate` folders side by side (issue 20's comparison).

    scripts/methods_boxplot.py OUT.png TITLE DIR...    # each DIR an `evaluate --out` folder

Four panels over the same runs: localization error (m), samples (stops), distance travelled (m)
and mission time (s), one box per folder, labelled by its method. Whiskers at 1.5 IQR; the
dashed 0.5 m and dotted 1.5 m lines mark plumekit's and the seeds' success radii.

OUT.png must be new or a picture this script drew (its PNG "Software" text says so): any other
file is refused (exit 2), never overwritten.
"""
import json
import sys
from pathlib import Path

import matplotlib

from evaluation_runs import SEEDS_SUCCESS_M, drawn_by, read_runs

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


SOFTWARE = "plumekit scripts/methods_boxplot.py"


def load(folder):
    summary = json.loads((Path(folder) / "summary.json").read_text())
    return summary.get("method", "ste"), read_runs(folder)


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    out, title, folders = argv[0], argv[1], argv[2:]
    if Path(out).exists() and not drawn_by(out, SOFTWARE):
        print(f"methods_boxplot.py: {out} exists and was not drawn by this script; "
              "not overwriting it", file=sys.stderr)
        sys.exit(2)
    data = [load(f) for f in folders]
    labels = [m for m, _ in data]
    fig, axes = plt.subplots(1, 4, figsize=(19, 4.5))
    for ax, (column, name) in zip(axes, [("error_m", "error (m)"), ("samples", "samples"),
                                         ("distance_m", "distance (m)"),
                                         ("mission_s", "mission time (s)")]):
        values = [[float(r[column]) for r in rows] for _, rows in data]
        ax.boxplot(values, labels=labels, showfliers=True, flierprops={"markersize": 2})
        ax.set_title(name)
        ax.tick_params(axis="x", rotation=45)
        ax.grid(axis="y", alpha=0.3)
        if column == "error_m":
            ax.axhline(0.5, color="tab:green", linestyle="--", linewidth=1)
            ax.axhline(SEEDS_SUCCESS_M, color="tab:orange", linestyle=":", linewidth=1)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110, metadata={"Software": SOFTWARE})


if __name__ == "__main__":
    main(sys.argv[1:])
