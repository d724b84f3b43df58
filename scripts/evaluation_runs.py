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
