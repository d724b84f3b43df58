#!/usr/bin/python3
"""The table and box plots of seed 004 ch. 12's local framework from scripts/local-benchmark.sh.

    scripts/local_table.py OUT [PNG_DIR]

For each sample budget B_0 (OUT/budget-B), the global framework (OUT/global) and, when there,
B_0 = 7 at low wind (OUT/low-wind): the runs, the
share declared within 0.5 m and 1 m, the medians of the error, of its x (along the wind) and y
parts, of the samples and of the travelled distance; then the global-over-local distance ratio
at B_0 = 7 (the thesis: about 3). With PNG_DIR, also PNG_DIR/local-budget.png (Fig. 12.4: error
and samples per B_0) and PNG_DIR/local-vs-global.png (Fig. 12.7: distance); a PNG there that this
script did not draw is refused (exit 2). Exit 2 when a folder is missing or malformed.
"""
import statistics
import sys
from pathlib import Path

from evaluation_runs import draw_boxplots, read_runs

BUDGETS = [1, 3, 5, 7, 9, 15, 25, 50]
SOFTWARE = "plumekit scripts/local_table.py"


def fail(message):
    print(f"local_table.py: {message}", file=sys.stderr)
    sys.exit(2)


def load(folder):
    try:
        runs = read_runs(folder)
        rows = [{"error": float(r["error_m"]),
                 "x": abs(float(r["estimate_x"]) - float(r["source_x"])),
                 "y": abs(float(r["estimate_y"]) - float(r["source_y"])),
                 "samples": float(r["samples"]), "distance": float(r["distance_m"]),
                 "declared": r["stopped_by"] == "entropy"} for r in runs]
    except (OSError, KeyError, ValueError) as e:
        fail(f"{folder}: {e}")
    if not rows:
        fail(f"{folder}: no runs")
    return {k: [r[k] for r in rows] for k in rows[0]}


def draw(path, title, labels, panels):
    if not draw_boxplots(path, SOFTWARE, title, labels, panels):
        fail(f"{path} exists and was not drawn by this script; not overwriting it")


def main(argv):
    if len(argv) not in (2, 3):
        fail("usage: local_table.py OUT [PNG_DIR]")
    out = Path(argv[1])
    data = {b: load(out / f"budget-{b}") for b in BUDGETS}
    data["global"] = load(out / "global")
    if (out / "low-wind").is_dir():  # condition A, B_0 = 7 (Fig. 12.5)
        data["low-wind"] = load(out / "low-wind")
    print("| framework | runs | declared | within 0.5 m | within 1 m | error m | x error m | "
          "y error m | samples | distance m |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for key, m in data.items():
        name = {"global": "global (map, positions)",
                "low-wind": "local, B_0 = 7, low wind (condition A)"}.get(key, f"local, B_0 = {key}")
        n = len(m["error"])
        print(f"| {name} | {n} | {100 * sum(m['declared']) / n:.0f} % | "
              f"{100 * sum(e <= 0.5 for e in m['error']) / n:.0f} % | "
              f"{100 * sum(e <= 1.0 for e in m['error']) / n:.0f} % | "
              f"{statistics.median(m['error']):.2f} | {statistics.median(m['x']):.2f} | "
              f"{statistics.median(m['y']):.2f} | {statistics.median(m['samples']):.0f} | "
              f"{statistics.median(m['distance']):.1f} |")
    ratio = statistics.median(data["global"]["distance"]) / statistics.median(data[7]["distance"])
    print(f"\nmedian distance, global / local (B_0 = 7): {ratio:.2f} (the thesis: about 3)")
    if len(argv) == 3:
        png = Path(argv[2])
        png.mkdir(parents=True, exist_ok=True)
        labels = [str(b) for b in BUDGETS]
        draw(png / "local-budget.png", "Local framework, condition C: sample budget B_0 "
             "(Fig. 12.4)", labels,
             [("error (m)", [data[b]["error"] for b in BUDGETS], 0.5),
              ("x error (m)", [data[b]["x"] for b in BUDGETS], None),
              ("samples", [data[b]["samples"] for b in BUDGETS], None)])
        draw(png / "local-vs-global.png", "Local against global framework, condition C "
             "(Fig. 12.7)", ["local, B_0 = 7", "global"],
             [("distance (m)", [data[7]["distance"], data["global"]["distance"]], None),
              ("error (m)", [data[7]["error"], data["global"]["error"]], 0.5)])


if __name__ == "__main__":
    main(sys.argv)
