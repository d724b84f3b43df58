#!/usr/bin/env python3
"""The plume-model comparison of issue 46 as a Markdown table and a JSON summary.

    /usr/bin/python3 scripts/designs_table.py EVAL_DIR OUT_DIR

EVAL_DIR holds evaluate.py --json results (results/surrogate-designs/make.sh writes them):
  DESIGN-BUDGET.json   a model on the three averaged test sets (the mean of four realizations);
                       its `physics` entries give the physics plume's row (from the hybrid model's
                       file, whose sets hold the physics channel);
  floor.json           a model on single realizations with --floor: the two-realization row.
A model scored on some of the sets only (the thesis's 64 x 64 models, v1*.json: not on the
buildings) gets "-" in the others (null in the JSON).
Each row gives, per test set, the relative L2 error of the mean and its RMSE over the average peak
mean; OUT_DIR gets table.md and summary.json (the same numbers).
"""
import json
import os
import sys


def figures(entry):
    m = entry["mean"]
    return {"rel_l2": m["rel_l2"], "rmse_rel_peak": m["rmse_rel_peak"]}


def rows(eval_dir):
    out = []
    names = sorted(f[:-5] for f in os.listdir(eval_dir) if f.endswith(".json") and f != "floor.json")
    sets = None
    for name in names:
        with open(os.path.join(eval_dir, name + ".json")) as f:
            r = json.load(f)
        if len(r["test_sets"]) > len(sets or []):  # the columns: the most sets any model has
            sets = list(r["test_sets"])
        out.append((name, {k: figures(v["all"]) for k, v in r["test_sets"].items()}))
        if name.startswith("hybrid") and "physics" in next(iter(r["test_sets"].values())):
            physics = {k: dict(figures(v["physics"]), factor=v["physics"]["factor"])
                       for k, v in r["test_sets"].items()}
    out.append(("physics plume, best-scaled", physics))
    floor_file = os.path.join(eval_dir, "floor.json")
    if os.path.exists(floor_file):
        with open(floor_file) as f:
            r = json.load(f)
        floor = [figures(v["floor"]) for v in r["test_sets"].values()]
        out.append(("two realizations (floor)", dict(zip(sets, floor))))
    return sets, out


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    sets, table = rows(argv[0])
    lines = ["| model | " + " | ".join(f"{s}: rel. L2 / RMSE of peak" for s in sets) + " |",
             "|---|" + "---|" * len(sets)]
    table = [(name, {s: per.get(s) for s in sets}) for name, per in table]
    for name, per in table:
        lines.append(f"| {name} | " + " | ".join(
            f"{100 * per[s]['rel_l2']:.1f} % / {100 * per[s]['rmse_rel_peak']:.2f} %"
            if per[s] else "-" for s in sets) + " |")
    os.makedirs(argv[1], exist_ok=True)
    with open(os.path.join(argv[1], "table.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(argv[1], "summary.json"), "w") as f:
        json.dump({name: per for name, per in table}, f, indent=1)
        f.write("\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
