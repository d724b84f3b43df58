#!/usr/bin/python3
"""Validates the OpenFOAM half of the benchmark on a case with a known answer.

An empty 10 x 4 m channel with a parabolic inlet (peak 1.5 m/s, mean 1 m/s) at nu = 0.01 m^2/s is
fully developed plane Poiseuille flow from the start, so the steady solution must keep
u = 1.5 * 4 * eta * (1 - eta), v = 0 (eta = y / H) everywhere, up to discretisation error, with a
linear pressure drop dp/dx = -12 * nu * u_mean / H^2 (kinematic).

    /usr/bin/python3 bench/openfoam/check_poiseuille.py [--cells 0.05] [--keep DIR]

Exit status 1 when the profile error exceeds --max-error (relative to the peak speed).
"""

import argparse
import json
import os
import shutil
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import foam_case  # noqa: E402

CHANNEL = {
    "format": "plumekit-map/1",
    "name": "poiseuille-channel",
    "size": [10.0, 4.0],
    "inlet": {"side": "left", "from": 0.0, "to": 4.0, "speed": 1.5, "profile": "parabolic"},
    "outlet": {"side": "right", "from": 0.0, "to": 4.0},
    "obstacles": [],
}


def main():
    ap = argparse.ArgumentParser(description="simpleFoam vs. exact plane Poiseuille flow")
    ap.add_argument("--cells", default="0.05", help="comma-separated cell sizes in m")
    ap.add_argument("--nu", type=float, default=0.01)
    ap.add_argument("--keep", help="keep the cases in this folder")
    ap.add_argument("--max-error", type=float, default=0.01,
                    help="largest allowed max|u - exact| / peak (default 1%%)")
    a = ap.parse_args()

    root = a.keep or tempfile.mkdtemp(prefix="plumekit-poiseuille-")
    os.makedirs(root, exist_ok=True)
    map_path = os.path.join(root, "channel.json")
    with open(map_path, "w") as f:
        json.dump(CHANNEL, f, indent=1)
    m = foam_case.load_map(map_path)
    W, H = m["size"]
    peak = m["inlet"]["speed"]
    ok = True
    for cell in (float(c) for c in a.cells.split(",")):
        case = os.path.join(root, f"cell-{cell:g}")
        meta = foam_case.write_case(m, cell, a.nu, case)
        foam_case.mesh_case(case)
        run = foam_case.run_solver(case)
        res = foam_case.read_result(case)
        ny, nx, dy = meta["ny"], meta["nx"], meta["dy"]
        eta = (np.arange(ny) + 0.5) * dy / H
        exact = peak * 4.0 * eta * (1.0 - eta)
        err_u = np.abs(res["u"] - exact[:, None]).max() / peak
        err_v = np.abs(res["v"]).max() / peak
        # Relative L2 of velocity against the exact field, as the benchmark measures it.
        l2 = np.sqrt(((res["u"] - exact[:, None]) ** 2 + res["v"] ** 2).sum() /
                     (np.broadcast_to(exact[:, None], res["u"].shape) ** 2).sum())
        # Pressure gradient from a straight-line fit along the centre row, away from the ends.
        xc = (np.arange(nx) + 0.5) * meta["dx"]
        mid = (xc > 1.0) & (xc < W - 1.0)
        dpdx = np.polyfit(xc[mid], res["p"][ny // 2, mid], 1)[0]
        dpdx_exact = -12.0 * a.nu * (2.0 * peak / 3.0) / H ** 2
        good = err_u <= a.max_error and err_v <= a.max_error
        ok &= good and run["converged"]
        print(f"cell {cell:g} m ({nx} x {ny}): simpleFoam {run['seconds']:.2f} s, "
              f"{run['iterations']} iterations, converged={run['converged']}; "
              f"max|u-exact|/peak = {err_u:.2e}, max|v|/peak = {err_v:.2e}, "
              f"rel L2 = {l2:.2e}; dp/dx = {dpdx:.6f} (exact {dpdx_exact:.6f})"
              f"{'' if good else '  FAIL'}")
    if not a.keep:
        shutil.rmtree(root, ignore_errors=True)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
