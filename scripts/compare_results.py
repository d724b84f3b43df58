#!/usr/bin/python3
"""Compare a committed results folder with a fresh run of the same command (results/README.md).

    scripts/compare_results.py COMMITTED NEW

Every file under COMMITTED is looked for under NEW. What is not the experiment's result is left
out: timings, which differ from run to run (the files in TIMING_FILES, the CSV columns and JSON
keys in TIMING_FIELDS, the Markdown table columns in TIMING_COLUMNS), and map_dir, the folder the
maps were read from, which for generated maps lies under the output folder. CSV files are
compared row by row, JSON files as data, Markdown tables cell by cell, .plumekit-output.json by
the files it lists, everything else (pictures, maps) byte for byte. Numbers within ROUNDING of
each other (relative) are reported apart, as last-digit rounding, not as differences.

Prints one line per file that differs or agrees only to rounding, then a count; exits 1 if any
file differs, 0 if all agree (to rounding at worst), 2 on bad arguments.
"""
import csv
import json
import sys
from pathlib import Path

# Measured CPU or wall time; every other *_s field is simulated time (mission_s, ...) or a setting.
TIMING_FIELDS = {"compute_s", "median_step_s", "median_step_compute_s", "wall_s", "wind_s",
                 "table_build_s"}
TIMING_FILES = {"timings.csv", "timings.json", "wall.txt"}
TIMING_COLUMNS = {"step ms"}
PATH_FIELDS = {"map_dir"}
ROUNDING = 1e-9
ROUNDED = "agrees to rounding (numbers within 1e-9 relative, last digits)"
# plumekit's list of the files it wrote, with their sizes and hashes: the files themselves are
# compared, so only which files it lists is.
MANIFEST = ".plumekit-output.json"


def close(a, b):
    """Whether two values are equal, or numbers within ROUNDING (relative) of each other."""
    if a == b:
        return True
    try:
        x, y = float(a), float(b)
    except (TypeError, ValueError):
        return False
    return abs(x - y) <= ROUNDING * max(abs(x), abs(y))


def without_timings(value):
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items()
                if k not in TIMING_FIELDS and k not in PATH_FIELDS}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def csv_rows(path):
    with open(path, newline="") as f:
        return [{k: v for k, v in row.items() if k not in TIMING_FIELDS}
                for row in csv.DictReader(f)]


def data(path):
    return without_timings(json.loads(path.read_text()))


def manifest(path):
    m = json.loads(path.read_text())
    names = [f["path"] if isinstance(f, dict) else f for f in m.get("files", [])]
    return {**m, "files": sorted(n for n in names if Path(n).name not in TIMING_FILES)}


def json_differences(a, b, where):
    """Where two JSON values differ: key paths, a key only on one side marked - (gone) or +,
    numbers that agree to rounding marked ~."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = [f"-{where}/{k}" for k in a if k not in b]
        out += [f"+{where}/{k}" for k in b if k not in a]
        for k in a:
            if k in b:
                out += json_differences(a[k], b[k], f"{where}/{k}")
        return out
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [d for i, (x, y) in enumerate(zip(a, b))
                for d in json_differences(x, y, f"{where}/{i}")]
    if a == b:
        return []
    return [("~" if close(a, b) else "") + (where or "/")]


def markdown_rows(path):
    """The lines of a Markdown file, the cells of its tables' timing columns left out."""
    rows, dropped = [], set()
    for line in path.read_text().splitlines():
        if not line.startswith("|"):
            rows.append(line)
            dropped = set()
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not dropped and any(c in TIMING_COLUMNS for c in cells):
            dropped = {i for i, c in enumerate(cells) if c in TIMING_COLUMNS}
        rows.append([c for i, c in enumerate(cells) if i not in dropped])
    return rows


def first_difference(old, new):
    """A short description of where two files differ, or None when they agree."""
    if old.suffix == ".csv":
        a, b = csv_rows(old), csv_rows(new)
        if len(a) != len(b):
            return f"{len(a)} rows, now {len(b)}"
        rounding, rows, cols = False, [], []
        for i, (x, y) in enumerate(zip(a, b)):
            if x != y:
                changed = [k for k in x if not close(x.get(k), y.get(k))]
                if changed or x.keys() != y.keys():
                    rows.append(i + 1)
                    cols += [k for k in changed or ["columns"] if k not in cols]
                else:
                    rounding = True
        if rows:
            return (f"{len(rows)} of {len(a)} rows differ (rows {', '.join(map(str, rows[:8]))}"
                    f"{' ...' if len(rows) > 8 else ''}) in {', '.join(cols[:6])}")
        return ROUNDED if rounding else None
    if old.suffix == ".json":
        read = manifest if old.name == MANIFEST else data
        paths = json_differences(read(old), read(new), "")
        real = [p for p in paths if not p.startswith("~")]
        if not real:
            return ROUNDED if paths else None
        return "differs at " + ", ".join(real[:6]) + \
            (f" and {len(real) - 6} more" if len(real) > 6 else "")
    if old.suffix == ".md":
        a, b = markdown_rows(old), markdown_rows(new)
        if a == b:
            return None
        line = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
        return f"line {line + 1} differs"
    return None if old.read_bytes() == new.read_bytes() else "bytes differ"


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    committed, fresh = Path(argv[1]), Path(argv[2])
    if not committed.is_dir() or not fresh.is_dir():
        print("compare_results.py: both arguments must be folders", file=sys.stderr)
        return 2
    checked, differing, rounded = 0, 0, 0
    for old in sorted(p for p in committed.rglob("*") if p.is_file()):
        rel = old.relative_to(committed)
        if old.name in TIMING_FILES or old.name == "README.md" or old.name == "make.sh":
            continue
        new = fresh / rel
        checked += 1
        problem = "missing" if not new.is_file() else first_difference(old, new)
        if problem:
            rounded += problem == ROUNDED
            differing += problem != ROUNDED
            print(f"{rel}: {problem}")
    print(f"{checked - differing - rounded} of {checked} files agree (timings left out), "
          f"{rounded} to rounding only, {differing} differ")
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
