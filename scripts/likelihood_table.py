#!/usr/bin/env python3
"""The hybrid model's likelihood sweep (results/ste-hybrid/make.sh tuning) as a Markdown table.

    /usr/bin/python3 scripts/likelihood_table.py [--mission] TUNING_DIR > table.md
    /usr/bin/python3 scripts/likelihood_table.py --stop TUNING_DIR > stop-table.md

TUNING_DIR holds `evaluate` folders named SET-mSIGMA_M-kK (SET: families, buildings); one row per
(sigma_M, k): each set's success within 0.5 m, mean error and median samples (with --mission also
the median mission time), and both pooled. With --stop, folders SET-rRADIUS-pMASS instead (the
confidence stop rule, results/ste-time/make.sh stop-tuning), with the mission time.
"""
import json
import os
import re
import sys


def main(argv):
    stop = "--stop" in argv
    mission = "--mission" in argv or stop
    argv = [a for a in argv if a not in ("--mission", "--stop")]
    pattern = r"(families|buildings)-r([0-9.]+)-p([0-9.]+)" if stop else \
        r"(families|buildings)-m([0-9.]+)-k([0-9.]+)"
    heads = ("radius m", "mass") if stop else ("σ_M", "k")
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    found = {}
    for name in os.listdir(argv[0]):
        m = re.fullmatch(pattern, name)
        summary = os.path.join(argv[0], name, "summary.json")
        if m and os.path.exists(summary):
            with open(summary) as f:
                found.setdefault((float(m[2]), float(m[3])), {})[m[1]] = json.load(f)["overall"]
    what = "within 0.5 m / mean error / samples" + (" / mission" if mission else "")
    print(f"| {heads[0]} | {heads[1]} | families: {what} | buildings: same | pooled within 0.5 m |")
    print("|---|---|---|---|---|")
    order = (lambda kv: kv[0]) if stop else (lambda kv: (-kv[0][0], kv[0][1]))
    for (sm, k), sets in sorted(found.items(), key=order):
        cells, hits, runs = [], 0, 0
        for s in ("families", "buildings"):
            o = sets.get(s)
            if o is None:
                cells.append("-")
                continue
            n = o["runs"]
            hit = round(o["success_0_5m"] * n)
            hits, runs = hits + hit, runs + n
            cells.append(f"{hit}/{n} ({100 * o['success_0_5m']:.1f} %) / "
                         f"{o['mean_error_m']:.3f} m / {o['median_samples']:g}"
                         + (f" / {o['median_mission_s']:.0f} s" if mission else ""))
        pooled = f"{hits}/{runs} ({100 * hits / runs:.1f} %)" if runs else "-"
        print(f"| {sm:g} | {k:g} | {cells[0]} | {cells[1]} | {pooled} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
