#!/usr/bin/python3
"""The tables and box plots of seed 004's 3-D systems from scripts/tunnel-benchmark.sh.

    scripts/tunnel_table.py OUT [PNG_DIR]

Fig. 11.3: for the 3-D STE in conditions A-D (OUT/ste-3d/A..D) and condition D with the thesis's
likelihood alone (OUT/ste-3d/D-thesis-likelihood): the runs, the share declared within 0.5 m, the
medians of the error and of its x, y and z parts, the 90th percentile of the z error, the samples,
the distance and the compute per step. Figs. 17.4 and 17.8: for the surge-spiral and the 2-D
surge-cast in set-ups A-H (OUT/trackers/A..H/{surge-spiral,surge-cast-2d}): the share that found
the source (its 20 cm box while in the plume) and their median time, the share that came within
0.5 m of it and their median time to get there. With PNG_DIR, also PNG_DIR/tunnel-ste-3d.png
(errors per axis per condition) and PNG_DIR/tunnel-trackers.png (time to within 0.5 m per set-up); a PNG there that this script did not draw is refused (exit 2). Exit 2 when
a folder is missing or malformed.
"""
import statistics
import sys
from pathlib import Path

from evaluation_runs import draw_boxplots, read_runs

CONDITIONS = ["A", "B", "C", "D"]  # Table 8.1
SETUPS = {"A": (0.2, "low", 0.7), "B": (0.2, "low", 0.9), "C": (0.2, "high", 0.7),
          "D": (0.2, "high", 0.9), "E": (0.9, "low", 0.7), "F": (0.9, "low", 0.9),
          "G": (0.9, "high", 0.7), "H": (0.9, "high", 0.9)}  # Table 17.1
TRACKERS = ["surge-spiral", "surge-cast-2d"]
SOFTWARE = "plumekit scripts/tunnel_table.py"


def fail(message):
    print(f"tunnel_table.py: {message}", file=sys.stderr)
    sys.exit(2)


def load(folder):
    try:
        rows = [{k: (v if k in ("method", "stopped_by") else float(v)) for k, v in r.items()}
                for r in read_runs(folder)]
    except (OSError, KeyError, ValueError) as e:
        fail(f"{folder}: {e}")
    if not rows:
        fail(f"{folder}: no runs")
    return rows


def col(rows, key):
    return [r[key] for r in rows]


def median(values):
    return statistics.median(values) if values else float("nan")


def p90(values):
    s = sorted(values)
    return s[min(len(s) - 1, round(0.9 * (len(s) - 1)))]


def whole(value):
    return "-" if value != value else f"{value:.0f}"  # NaN: no run


def share(flags):
    return f"{100 * sum(flags) / len(flags):.0f} %"


def draw(path, title, labels, panels):
    if not draw_boxplots(path, SOFTWARE, title, labels, panels):
        fail(f"{path} exists and was not drawn by this script; not overwriting it")


def main(argv):
    if len(argv) not in (2, 3):
        fail("usage: tunnel_table.py OUT [PNG_DIR]")
    out = Path(argv[1])
    ste = {c: load(out / "ste-3d" / c) for c in CONDITIONS + ["D-thesis-likelihood"]}
    print("| condition | runs | within 0.5 m | error m | x m | y m | z m | z, 90th pct. m | "
          "samples | distance m | step ms |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for c, rows in ste.items():
        name = "D, σ_M alone" if c == "D-thesis-likelihood" else c
        print(f"| {name} | {len(rows)} | {share([e <= 0.5 for e in col(rows, 'error_m')])} | "
              f"{median(col(rows, 'error_m')):.2f} | {median(col(rows, 'error_x')):.2f} | "
              f"{median(col(rows, 'error_y')):.2f} | {median(col(rows, 'error_z')):.2f} | "
              f"{p90(col(rows, 'error_z')):.2f} | {median(col(rows, 'samples')):.0f} | "
              f"{median(col(rows, 'distance_m')):.1f} | "
              f"{1000 * median(col(rows, 'median_step_s')):.1f} |")
    trackers = {(s, m): load(out / "trackers" / s / m) for s in SETUPS for m in TRACKERS}
    print("\n| set-up | wind m/s | release | threshold | surge-spiral: found | time found s | "
          "within 0.5 m | time to 0.5 m s | surge-cast 2-D: found | time found s | within 0.5 m | "
          "time to 0.5 m s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for s, (wind, release, threshold) in SETUPS.items():
        cells = []
        for m in TRACKERS:
            rows = trackers[(s, m)]
            found = [r["stopped_by"] == "found" for r in rows]
            time_found = [r["mission_s"] for r in rows if r["stopped_by"] == "found"]
            near = [r["time_within_0_5m_s"] for r in rows if r["time_within_0_5m_s"] >= 0]
            cells += [share(found), whole(median(time_found)),
                      share([r["time_within_0_5m_s"] >= 0 for r in rows]), whole(median(near))]
        print(f"| {s} | {wind} | {release} | {threshold} | " + " | ".join(cells) + " |")
    if len(argv) == 3:
        png = Path(argv[2])
        png.mkdir(parents=True, exist_ok=True)
        draw(png / "tunnel-ste-3d.png", "3-D STE in the 10 x 4 x 2 m tunnel, conditions A-D "
             "(Fig. 11.3)", CONDITIONS,
             [(f"{axis} error (m)", [col(ste[c], f"error_{axis}") for c in CONDITIONS],
               0.2 if axis == "z" else None) for axis in "xyz"])
        labels = list(SETUPS)
        draw(png / "tunnel-trackers.png", "Time to within 0.5 m of the source, 20 x 4 x 2 m "
             "tunnel, set-ups A-H (Figs. 17.4, 17.8; runs that got there)", labels,
             [(f"{m} (s)", [[t for t in col(trackers[(s, m)], "time_within_0_5m_s") if t >= 0]
                            for s in SETUPS], None) for m in TRACKERS])


if __name__ == "__main__":
    main(sys.argv)
