"""Reading an `evaluate --out` folder's runs, shared by the issue 20 table and plot scripts."""
import csv
from pathlib import Path

# The seeds' success radius (seed 001: a localization within 1.5 m succeeds).
SEEDS_SUCCESS_M = 1.5


def read_runs(folder):
    """The rows of FOLDER/runs.csv, as dicts of strings."""
    with open(Path(folder) / "runs.csv", newline="") as f:
        return list(csv.DictReader(f))


def share_within(errors, radius=SEEDS_SUCCESS_M):
    """The share of ERRORS (metres) at most RADIUS."""
    return sum(e <= radius for e in errors) / len(errors)


def drawn_by(path, software):
    """Whether PATH is a PNG whose "Software" text is SOFTWARE: a picture that script drew, which
    it may draw again (any other file is never overwritten)."""
    from PIL import Image
    try:
        with Image.open(path) as im:
            return im.format == "PNG" and im.info.get("Software") == software
    except (OSError, ValueError):
        return False


def draw_boxplots(path, software, title, labels, panels, rotation=0):
    """Box plots side by side into PATH (marked with SOFTWARE), one panel per (NAME, GROUPS,
    REFERENCE) of PANELS: a box per group, labelled by LABELS, whiskers at 1.5 IQR, and a dashed
    line at REFERENCE unless it is None. Returns False, drawing nothing, when PATH exists and is
    not this software's picture."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    if Path(path).exists() and not drawn_by(path, software):
        return False
    fig, axes = plt.subplots(1, len(panels), figsize=(4.8 * len(panels), 4.5), squeeze=False)
    for ax, (name, groups, reference) in zip(axes[0], panels):
        ax.boxplot(groups, labels=labels, flierprops={"markersize": 2})
        ax.set_title(name)
        ax.tick_params(axis="x", rotation=rotation)
        ax.grid(axis="y", alpha=0.3)
        if reference is not None:
            ax.axhline(reference, color="tab:green", linestyle="--", linewidth=1)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=100, metadata={"Software": software})
    plt.close(fig)
    return True
