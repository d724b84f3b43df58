#!/usr/bin/python3
"""The wind of a ROS map, drawn with matplotlib.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/wind_of_a_ros_map.py [OUT.png]

Imports the shipped office map (a ROS map_server YAML + PGM) with a door on its left wall and a
window on its right one, solves its steady wind, and draws the speed with streamlines.
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt
import numpy as np

import plumekit

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/python/office-wind.png")
office = plumekit.import_ros(
    Path(plumekit.data_dir()) / "ros" / "office.yaml",
    inlets=["0,1.8,0,3.4,0.5"],  # a door, 0.5 m/s in
    outlets=["11.25,1.0,11.25,4.2"],  # a window
)
wind = plumekit.flow(office, cell=0.1)
print(f"{office.name}: {office.width:.2f} x {office.height:.2f} m, {wind.nx} x {wind.ny} cells, "
      f"solved in {wind.summary['seconds']:.2f} s")

speed = np.hypot(wind.u, wind.v)  # wind.u and wind.v are views of the solver's arrays
x0, x1, y0, y1 = wind.extent
x = np.linspace(x0 + wind.cell[0] / 2, x1 - wind.cell[0] / 2, wind.nx)
y = np.linspace(y0 + wind.cell[1] / 2, y1 - wind.cell[1] / 2, wind.ny)

fig, ax = plt.subplots(figsize=(8, 8 * office.height / office.width + 0.8))
image = ax.imshow(np.ma.masked_where(wind.solid == 1, speed), origin="lower",
                  extent=wind.extent, cmap="viridis")
ax.streamplot(x, y, wind.u, wind.v, color="white", density=1.2, linewidth=0.6, arrowsize=0.7)
ax.set(title=f"wind of {office.name} (plumekit)", xlabel="x [m]", ylabel="y [m]")
fig.colorbar(image, ax=ax, label="speed [m/s]", shrink=0.8)
out.parent.mkdir(parents=True, exist_ok=True)
fig.savefig(out, dpi=100, bbox_inches="tight")
print(f"wrote {out}")
