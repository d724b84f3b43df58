#!/usr/bin/python3
"""Source term estimation driven from Python with the readings of a robot log.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/localize_from_a_robot_log.py [LOG.csv]

A log is a CSV of stops: x, y (m, the map's frame) and reading (the mean gas reading over the
stop). Each reading goes into a plumekit Mission, which returns the posterior and says where the
robot should sample next (on a real robot: send that goal, drive, read, repeat). The shipped log
was recorded by a simulated robot on test map 1 (`data/robot-log.csv`, see its first line), so the
true source is known here: the map's first source.
"""
import csv
import sys
from pathlib import Path

import plumekit

log = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).parent / "data" / "robot-log.csv")
arena = plumekit.read_map(Path(plumekit.data_dir()) / "test-maps" / "test-1-block.json")
# Wind and plume model, built once; the log's stops were 5 s each, read only while standing.
scenario = plumekit.Scenario(arena, plume_model="physics", protocol="thesis")
mission = scenario.mission(seed=1)

with open(log) as f:
    stops = [row for row in csv.DictReader(line for line in f if not line.startswith("#"))]
for k, stop in enumerate(stops, 1):
    here = (float(stop["x"]), float(stop["y"]))
    posterior = mission.add(here, float(stop["reading"]))
    ex, ey = posterior["estimate"]
    note = f"stopped ({mission.stopped_by})" if mission.stopped else \
        "next: ({:.2f}, {:.2f})".format(*mission.next(here)["goal"])
    print(f"{k:2d}  at ({here[0]:5.2f}, {here[1]:5.2f}) read {float(stop['reading']):7.1f}  "
          f"estimate ({ex:5.2f}, {ey:5.2f})  entropy {posterior['entropy']:.2f}  {note}")
    if mission.stopped:
        break
ex, ey = mission.posterior["estimate"]
tx, ty = arena.sources[0]
error = ((ex - tx) ** 2 + (ey - ty) ** 2) ** 0.5
print(f"source at ({ex:.2f}, {ey:.2f}) after {mission.samples} samples; "
      f"{error:.2f} m from the true source")
