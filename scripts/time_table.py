#!/usr/bin/env python3
"""The mission-time table of results/ste-time (issue 47): one row per evaluation OUT/SET-VARIANT,
its success within 0.5 m with the 95 % interval, median samples, median mission time and its
ratio to the same set's `today` row, median time to 1 m, mission over the optimum and GSL-Bench's
success (1 m within 300 s).

    time_table.py OUT > table.md
"""
import json
import sys
from pathlib import Path

SETS = [("test", "nine test maps"), ("buildings", "20 random buildings"), ("real", "real floors")]


def row(summary, today):
    o = summary["overall"]
    lo, hi = o["success_0_5m_ci95"]
    ratio = o["median_mission_s"] / today if today else float("nan")
    t1 = o.get("median_time_to_1m_s")
    return (f"{100 * o['success_0_5m']:.1f} % ({100 * lo:.0f}-{100 * hi:.0f}) | "
            f"{o['median_samples']:g} | {o['median_mission_s']:.0f} s | {ratio:.2f} | "
            f"{'-' if t1 is None else f'{t1:.0f} s'} | {o['median_mission_over_optimum']:.1f} | "
            f"{100 * o['gsl_bench_success']:.0f} %")


def main(argv):
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    out = Path(argv[0])
    print("| set | variant | runs | within 0.5 m (95 % CI) | median samples | median mission | "
          "÷ today | median time to 1 m | mission ÷ optimum | GSL-Bench 1 m in 300 s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for key, name in SETS:
        parts = sorted(out.glob(f"{key}-*/summary.json"))
        today_file = out / f"{key}-today" / "summary.json"
        today = (json.loads(today_file.read_text())["overall"]["median_mission_s"]
                 if today_file.exists() else None)
        order = {"today": 0, "today-physics": 1}
        for p in sorted(parts, key=lambda p: (order.get(p.parent.name[len(key) + 1:], 2),
                                              p.parent.name)):
            s = json.loads(p.read_text())
            variant = p.parent.name[len(key) + 1:]
            print(f"| {name} | {variant} | {s['overall']['runs']} | {row(s, today)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
