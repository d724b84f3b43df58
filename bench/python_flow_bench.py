#!/usr/bin/python3
"""What a Python `plumekit.flow` call costs over the library call it wraps.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_flow_bench.py [--repeats 15] [MAP...]

Per map, alternately: plumekit.flow(map) timed in Python (the map and options converted, the GIL
released, the summary built, the wind handed to Python), and the baseline, cfd::solve_wind on the
same map and options timed in C++ (plumekit._library_flow_seconds), in the same process. Prints the
medians and their ratio; the issue's target is within 5 %. Returning the wind's arrays copies nothing
(wind.u is a view), so that is not in either time.
"""
import argparse
import statistics
import time
from pathlib import Path

import plumekit

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("maps", nargs="*")
parser.add_argument("--repeats", type=int, default=15)
args = parser.parse_args()
data = Path(plumekit.data_dir())
maps = args.maps or [data / "maps" / "cluttered-1.json", data / "test-maps" / "test-8-baffles.json",
                     data / "floors" / "tb3_world.json"]

print(f"{'map':28s} {'library s':>10s} {'python s':>10s} {'ratio':>7s}")
for path in maps:
    m = plumekit.read_map(path)
    plumekit.flow(m)  # warm-up: the first call tunes malloc and loads what it loads
    lib, py = [], []
    for _ in range(args.repeats):
        lib.append(plumekit._library_flow_seconds(m))
        t0 = time.perf_counter()
        wind = plumekit.flow(m)
        py.append(time.perf_counter() - t0)
        _ = wind.u  # the numpy view: no copy
    a, b = statistics.median(lib), statistics.median(py)
    print(f"{Path(path).stem:28s} {a:10.4f} {b:10.4f} {b / a:7.3f}")
