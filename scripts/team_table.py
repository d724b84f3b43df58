#!/usr/bin/python3
"""The tables and box plots of seed 004 ch. 13's team benchmark from scripts/team-benchmark.sh.

    scripts/team_table.py OUT [PNG_DIR]

For each setting (conditions A-D in the open field, the test maps) and each configuration
(strategy x robots): the runs; the share declared within 0.5 m; the median error; and the
medians of the thesis's metrics: samples (iterations) and distance summed over the robots, and
the mission time until the first declaration; and the median decision step over all the runs'
robots (timings.csv). Prints a markdown table. With PNG_DIR, also draws PNG_DIR/teams-SETTING.png
per setting: box plots of samples, distance, mission time and error per configuration. A PNG there
that this script did not draw is refused (exit 2), never overwritten. Exit 2 when a folder is
missing or malformed.
"""
import csv
import statistics
import sys
from pathlib import Path

from evaluation_runs import draw_boxplots, read_runs

SETTINGS = [("A", "A (0.2 m/s, 5 %)"), ("B", "B (0.2 m/s, 10 %)"), ("C", "C (0.9 m/s, 5 %)"),
            ("D", "D (0.9 m/s, 10 %)"), ("test-maps", "nine test maps")]
CONFIGS = [("individualist", 1), ("individualist", 2), ("individualist", 3),
           ("cooperative", 2), ("cooperative", 3), ("collaborative", 2), ("collaborative", 3)]
SOFTWARE = "plumekit scripts/team_table.py"


def fail(message):
    print(f"team_table.py: {message}", file=sys.stderr)
    sys.exit(2)


def label(strategy, robots):
    return "1 robot" if robots == 1 else f"{strategy} {robots}"


def load(folder):
    """The runs' metrics, and each run's decision steps' median (timings.csv)."""
    try:
        runs = read_runs(folder)
        metrics = {key: [float(r[key]) for r in runs]
                   for key in ("error_m", "samples", "distance_m", "mission_s")}
        with open(Path(folder) / "timings.csv", newline="") as f:
            steps = [float(r["median_step_s"]) for r in csv.DictReader(f)]
    except (OSError, KeyError, ValueError) as e:
        fail(f"{folder}: {e}")
    if not runs:
        fail(f"{folder}: no runs")
    metrics["entropy"] = [r["stopped_by"] == "entropy" for r in runs]
    metrics["step_s"] = steps
    return metrics


def boxplot(path, title, data):
    labels = [label(s, n) for (s, n), _ in data]
    panels = [(name, [m[key] for _, m in data], 0.5 if key == "error_m" else None)
              for key, name in [("samples", "samples, summed"),
                                ("distance_m", "distance (m), summed"),
                                ("mission_s", "mission time (s)"), ("error_m", "error (m)")]]
    if not draw_boxplots(path, SOFTWARE, title, labels, panels, rotation=45):
        fail(f"{path} exists and was not drawn by this script; not overwriting it")


def main(argv):
    if len(argv) not in (2, 3):
        fail("usage: team_table.py OUT [PNG_DIR]")
    out = Path(argv[1])
    png_dir = Path(argv[2]) if len(argv) == 3 else None
    print("| setting | team | runs | within 0.5 m | error m | samples | distance m | "
          "mission s | step ms |")
    print("|---|---|---|---|---|---|---|---|---|")
    for setting, name in SETTINGS:
        if not all((out / setting / f"{s}-{n}" / "runs.csv").is_file() for s, n in CONFIGS):
            print(f"team_table.py: {out / setting}: not every configuration has run; left out",
                  file=sys.stderr)
            continue
        data = [((s, n), load(out / setting / f"{s}-{n}")) for s, n in CONFIGS]
        for (s, n), m in data:
            ok = sum(e <= 0.5 for e in m["error_m"]) / len(m["error_m"])
            print(f"| {name} | {label(s, n)} | {len(m['error_m'])} | {100 * ok:.0f} % | "
                  f"{statistics.median(m['error_m']):.2f} | "
                  f"{statistics.median(m['samples']):.0f} | "
                  f"{statistics.median(m['distance_m']):.1f} | "
                  f"{statistics.median(m['mission_s']):.0f} | "
                  f"{1000 * statistics.median(m['step_s']):.1f} |")
        if png_dir is not None:
            png_dir.mkdir(parents=True, exist_ok=True)
            boxplot(png_dir / f"teams-{setting}.png", f"Robot teams, {name}", data)


if __name__ == "__main__":
    main(sys.argv)
