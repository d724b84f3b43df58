#!/usr/bin/python3
"""The open-field maps of seed 004's STE-versus-ALT benchmark (ch. 16, Fig. 16.5; ch. 5.1's arena).

    scripts/levy_maps.py OUT SPEED START [COUNT] [SEED] [LENGTH]

writes COUNT (default 10) maps OUT/levy-NN.json: a LENGTH x 4 m arena (default 10: ch. 5.1's; the
local framework's benchmark of ch. 12 uses 20) with a uniform inlet of SPEED m/s
on the left and an outlet on the right, one source 1 m from the upwind wall at a random y in
[0.5, 3.5], and the starts of START: "plume", one start 8 m downwind on the source's line (inside
the plume, ch. 16 (a)); or "crosswind", five starts at x = 9 m and random y in [0.3, 3.7] (ch. 16
(b)), used in turn by the runs. The same SEED (default 1) gives the same sources for both starts.
Each map is marked "generated_by": "plumekit scripts/levy_maps.py". Exit 2, writing nothing, on
bad arguments or an OUT that holds any other file (one without that mark included).
"""
import json
import os
import random
import sys


def fail(message):
    print(f"levy_maps.py: {message}", file=sys.stderr)
    sys.exit(2)


MARK = "plumekit scripts/levy_maps.py"


def ours(path):
    """Whether PATH is a map this script wrote (its mark)."""
    try:
        with open(path) as f:
            return json.load(f).get("generated_by") == MARK
    except (OSError, ValueError, AttributeError):
        return False


def main(argv):
    if len(argv) not in (4, 5, 6, 7):
        fail("usage: levy_maps.py OUT SPEED START [COUNT] [SEED] [LENGTH]")
    out, speed_text, start = argv[1], argv[2], argv[3]
    try:
        speed = float(speed_text)
        count = int(argv[4]) if len(argv) > 4 else 10
        seed = int(argv[5]) if len(argv) > 5 else 1
        length = float(argv[6]) if len(argv) > 6 else 10.0
    except ValueError:
        fail("SPEED and LENGTH must be numbers, COUNT and SEED whole numbers")
    if not 10.0 <= length <= 100.0:
        fail("LENGTH in [10, 100] m")
    if not (0.0 < speed <= 10.0) or count < 1 or start not in ("plume", "crosswind"):
        fail("SPEED in (0, 10] m/s, COUNT at least 1, START plume or crosswind")
    names = [f"levy-{k:02d}.json" for k in range(count)]
    if os.path.exists(out):
        if not os.path.isdir(out) or any(n not in names or not ours(os.path.join(out, n))
                                         for n in os.listdir(out)):
            fail(f"{out} exists and holds files this script did not write")
    sources = random.Random(seed)
    starts = random.Random(seed + 1000)
    os.makedirs(out, exist_ok=True)
    for k, name in enumerate(names):
        y = round(sources.uniform(0.5, 3.5), 3)
        if start == "plume":
            points = [[9.0, y]]
        else:
            points = [[9.0, round(starts.uniform(0.3, 3.7), 3)] for _ in range(5)]
        m = {
            "format": "plumekit-map/2",
            "name": f"levy-{k:02d}",
            "generated_by": MARK,
            "size": [length, 4.0],
            "openings": [
                {"kind": "inlet", "from": [0.0, 0.0], "to": [0.0, 4.0], "speed": speed,
                 "profile": "uniform"},
                {"kind": "outlet", "from": [length, 0.0], "to": [length, 4.0]},
            ],
            "obstacles": [],
            "sources": [[1.0, y]],
            "starts": points,
        }
        with open(os.path.join(out, name), "w") as f:
            json.dump(m, f, indent=2)
            f.write("\n")


if __name__ == "__main__":
    main(sys.argv)
