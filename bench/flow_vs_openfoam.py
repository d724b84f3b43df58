#!/usr/bin/python3
"""plumekit's steady flow solver against OpenFOAM's simpleFoam on the same map and mesh.

For each cell size: has an OpenFOAM case written and simpleFoam run (laminar), times `plumekit
flow` on the same map, cell size and viscosity, and prints the wall-time ratio and the difference
of the two velocity fields over the fluid cells. The case comes from plumekit's own OpenFOAM
engine (`plumekit flow --engine openfoam --keep-case`, default: the mesh is plumekit's grid, so
maps with any number of openings work, and --ranks N runs simpleFoam over N MPI ranks), or from
bench/openfoam/foam_case.py (--foam-case python: blockMesh + topoSet + subsetMesh, map/1 only).

    /usr/bin/python3 bench/flow_vs_openfoam.py [--map data/maps/cluttered-1.json]
        [--cells 0.05,0.025] [--nu 0.01] [--plumekit build/plumekit] [--keep DIR]
        [--repeats N] [--foam-tol 1e-6] [--foam-case engine|python] [--ranks N]
        [--foam-convection SCHEME (python case only)] [--json]

Needs Debian's openfoam and python3-numpy (bench/openfoam/install.sh); run with /usr/bin/python3.
With --foam-case python, if the plumekit binary is missing or fails, the OpenFOAM half is still
reported. See bench/openfoam/README.md.
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(HERE, "openfoam"))
import foam_case  # noqa: E402

# The targets for plumekit (this script only measures; it reports them for reference).
TARGET_SPEEDUP = 20.0
TARGET_REL_L2 = 0.05


LAST_CPU = [0.0]  # CPU seconds of the last plumekit run


def run_plumekit(exe, map_path, cell, nu, out, extra=()):
    """One `plumekit flow` run (`extra`: more flags). Returns wall seconds, the wind.json
    summary and u, v arrays, or raises RuntimeError with the reason."""
    if os.path.exists(out):
        shutil.rmtree(out)
    cmd = [exe, "flow", map_path, "--out", out, "--cell", repr(cell), "--nu", repr(nu),
           "--turbulence", "none", "--json", *extra]
    t0 = time.perf_counter()
    c0 = foam_case._child_cpu()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    LAST_CPU[0] = foam_case._child_cpu() - c0
    if r.returncode != 0:
        msg = (r.stderr.strip() or r.stdout.strip()).splitlines()[-5:]
        raise RuntimeError(f"`{' '.join(cmd)}` exited {r.returncode}: " + " | ".join(msg))
    try:
        with open(os.path.join(out, "wind.json")) as f:
            wind = json.load(f)
        u = np.load(os.path.join(out, "u.npy")).astype(np.float64)
        v = np.load(os.path.join(out, "v.npy")).astype(np.float64)
    except (OSError, ValueError) as e:
        raise RuntimeError(f"plumekit flow ran but its output in {out} is unreadable: {e}")
    return wall, wind, u, v


def compare(u_pk, v_pk, u_of, v_of, fluid):
    """Relative L2 of the velocity difference over the fluid cells, and the largest
    component-wise absolute difference there."""
    du = (u_pk - u_of)[fluid]
    dv = (v_pk - v_of)[fluid]
    ref = np.sqrt((u_of[fluid] ** 2 + v_of[fluid] ** 2).sum())
    rel = float(np.sqrt((du ** 2 + dv ** 2).sum()) / ref)
    return rel, float(max(np.abs(du).max(), np.abs(dv).max()))


def foam_python(args, m, cell, root, log):
    """The OpenFOAM half with foam_case.py's case (blockMesh + topoSet + subsetMesh; map/1 only).
    Returns the row so far, OpenFOAM's u and v, and the fluid mask."""
    case = os.path.join(root, f"cell-{cell:g}", "openfoam")
    foam_case.write_case(m, cell, args.nu, case,
                         {"p_tol": args.foam_tol, "U_tol": args.foam_tol,
                          "convection": args.foam_convection})
    mesh_times = foam_case.mesh_case(case)  # not timed in the comparison
    meta = foam_case.case_meta(case)
    nx, ny = meta["nx"], meta["ny"]
    log(f"[{cell:g} m] {nx} x {ny} cells, {meta['n_fluid']} fluid; meshed in "
        f"{sum(mesh_times.values()):.1f} s")
    row = {"cell": cell, "nx": nx, "ny": ny, "n_fluid": meta["n_fluid"],
           "cell_order": meta["cell_order"], "foam_tol": args.foam_tol,
           "foam_convection": args.foam_convection, "foam_case": "python", "foam_ranks": 1}
    runs = []
    for k in range(args.repeats):
        r = foam_case.run_solver(case)
        runs.append(r)
        log(f"[{cell:g} m] simpleFoam run {k + 1}/{args.repeats}: {r['seconds']:.2f} s "
            f"(cpu {r['cpu_seconds']:.2f} s), "
            f"{r['iterations']} iterations, converged={r['converged']}")
    foam_rows(row, runs)
    of = foam_case.read_result(case)
    fluid = ~np.load(os.path.join(case, "removed.npy"))
    for k in ("u", "v", "p"):
        np.save(os.path.join(case, f"{k}.npy"), of[k].astype(np.float32))
    return row, of["u"], of["v"], fluid


def foam_rows(row, runs):
    row["simpleFoam_seconds"] = statistics.median(r["seconds"] for r in runs)
    row["simpleFoam_seconds_all"] = [r["seconds"] for r in runs]
    row["simpleFoam_cpu_seconds"] = statistics.median(r["cpu_seconds"] for r in runs)
    row["simpleFoam_iterations"] = runs[-1]["iterations"]
    row["simpleFoam_converged"] = all(r["converged"] for r in runs)
    row["simpleFoam_final_residuals"] = runs[-1]["final_residuals"]


def read_label_list(path):
    """An ASCII OpenFOAM labelList (the engine's constant/plumekit_cells)."""
    with open(path) as f:
        text = f.read()
    body = text[text.index("(", text.index("}")) + 1:text.rindex(")")]
    return np.array(body.split(), dtype=np.int64)


def foam_engine(args, map_path, cell, root, log):
    """The OpenFOAM half with plumekit's own engine (`plumekit flow --engine openfoam`): the
    case is meshed from plumekit's grid, so any map with any openings works. simpleFoam's time
    is the engine's solver time (decomposePar and reconstructPar included when --ranks > 1)."""
    if args.foam_convection != foam_case.DEFAULTS["convection"]:
        raise SystemExit("--foam-convection needs --foam-case python (the engine uses "
                         "linearUpwind)")
    exe = args.plumekit
    out = os.path.join(root, f"cell-{cell:g}", "openfoam-out")
    case = os.path.join(root, f"cell-{cell:g}", "openfoam")
    runs = []
    for k in range(args.repeats):
        for d in (out, case):
            shutil.rmtree(d, ignore_errors=True)
        extra = ["--engine", "openfoam", "--foam-tol", repr(args.foam_tol), "--ranks",
                 str(args.ranks), "--keep-case", case]
        wall, wind, u, v = run_plumekit(exe, map_path, cell, args.nu, out, extra)
        of = wind["openfoam"]
        runs.append({"seconds": of["seconds_breakdown"]["solver"], "cpu_seconds": LAST_CPU[0],
                     "iterations": of["iterations"], "converged": wind["converged"],
                     "final_residuals": wind["final_residuals"], "wall": wall})
        log(f"[{cell:g} m] simpleFoam (engine, {args.ranks} rank(s)) run {k + 1}/{args.repeats}: "
            f"{runs[-1]['seconds']:.2f} s solver, {wall:.2f} s whole command "
            f"(cpu {LAST_CPU[0]:.2f} s), {of['iterations']} iterations")
    nx, ny = wind["grid"]["nx"], wind["grid"]["ny"]
    fluid = np.zeros(nx * ny, dtype=bool)
    fluid[read_label_list(os.path.join(case, "constant", "plumekit_cells"))] = True
    fluid = fluid.reshape(ny, nx)
    log(f"[{cell:g} m] {nx} x {ny} cells, {int(fluid.sum())} fluid")
    row = {"cell": cell, "nx": nx, "ny": ny, "n_fluid": int(fluid.sum()),
           "foam_tol": args.foam_tol, "foam_convection": foam_case.DEFAULTS["convection"],
           "foam_case": "engine", "foam_ranks": args.ranks,
           "engine_command_seconds": statistics.median(r["wall"] for r in runs)}
    foam_rows(row, runs)
    return row, u, v, fluid


def bench_cell(args, m, map_path, cell, root, log):
    if args.foam_case == "python":
        row, of_u, of_v, fluid = foam_python(args, m, cell, root, log)
    else:
        row, of_u, of_v, fluid = foam_engine(args, map_path, cell, root, log)
    nx, ny = row["nx"], row["ny"]
    of = {"u": of_u, "v": of_v}
    row["plumekit_error"] = None
    exe = args.plumekit
    if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
        row["plumekit_error"] = f"plumekit binary not found or not executable: {exe}"
    else:
        try:
            walls, solver, cpu = [], [], []
            for k in range(args.repeats):
                out = os.path.join(root, f"cell-{cell:g}", "plumekit")
                wall, wind, u, v = run_plumekit(exe, map_path, cell, args.nu, out)
                walls.append(wall)
                cpu.append(LAST_CPU[0])
                solver.append(float(wind.get("seconds", float("nan"))))
                log(f"[{cell:g} m] plumekit run {k + 1}/{args.repeats}: {wall:.3f} s wall "
                    f"(cpu {cpu[-1]:.3f} s), "
                    f"{solver[-1]:.3f} s solver, {wind.get('iterations')} iterations")
            if u.shape != (ny, nx) or v.shape != (ny, nx):
                raise RuntimeError(f"plumekit grid {u.shape} differs from ({ny}, {nx})")
            row["plumekit_seconds"] = statistics.median(walls)
            row["plumekit_seconds_all"] = walls
            row["plumekit_cpu_seconds"] = statistics.median(cpu)
            row["plumekit_solver_seconds"] = statistics.median(solver)
            row["plumekit_iterations"] = wind.get("iterations")
            # Recorded so that a result says which scheme and tolerance plumekit used.
            for key in ("convection", "tolerance", "converged"):
                row[f"plumekit_{key}"] = wind.get(key)
            row["ratio"] = row["simpleFoam_seconds"] / row["plumekit_seconds"]
            row["ratio_solver"] = row["simpleFoam_seconds"] / row["plumekit_solver_seconds"]
            row["rel_l2"], row["max_abs_diff"] = compare(u, v, of["u"], of["v"], fluid)
            # Obstacle cells should agree too: plumekit writes 0 there, as do we.
            row["solid_mismatch"] = int(((u != 0) | (v != 0))[~fluid].sum())
        except RuntimeError as e:
            row["plumekit_error"] = str(e)
    if row["plumekit_error"]:
        log(f"[{cell:g} m] plumekit: {row['plumekit_error']}")
    return row


def print_table(rows, map_path, nu):
    how = f"{rows[0]['foam_case']} case, {rows[0]['foam_ranks']} rank(s)" if rows else ""
    print(f"\nplumekit flow vs. OpenFOAM simpleFoam (laminar, {how}) on {map_path}, nu = {nu:g}")
    head = ("cell m", "nx x ny", "simpleFoam s", "iters", "plumekit s", "(solver s)",
            "ratio", "rel L2 |U|", "max |dU|")
    lines = [head]
    for r in rows:
        pk = r.get("plumekit_seconds") is not None
        lines.append((
            f"{r['cell']:g}", f"{r['nx']} x {r['ny']}", f"{r['simpleFoam_seconds']:.2f}",
            f"{r['simpleFoam_iterations']}" + ("" if r["simpleFoam_converged"] else "!"),
            f"{r['plumekit_seconds']:.3f}" if pk else "n/a",
            f"{r['plumekit_solver_seconds']:.3f}" if pk else "n/a",
            f"{r['ratio']:.1f}x" if pk else "n/a",
            f"{100 * r['rel_l2']:.2f} %" if pk else "n/a",
            f"{r['max_abs_diff']:.3g} m/s" if pk else "n/a"))
    w = [max(len(l[i]) for l in lines) for i in range(len(head))]
    for k, l in enumerate(lines):
        print("  ".join(s.rjust(w[i]) for i, s in enumerate(l)))
        if k == 0:
            print("  ".join("-" * x for x in w))
    print(f"load average at the end: {' '.join(f'{x:.2f}' for x in os.getloadavg())} "
          f"on {os.cpu_count()} CPUs (other work on the machine inflates wall times)")
    print(f"times are medians of wall-clock runs; ratio = simpleFoam s / plumekit s "
          f"(targets: >= {TARGET_SPEEDUP:g}x, rel L2 <= {100 * TARGET_REL_L2:g} %)")
    if any(not r["simpleFoam_converged"] for r in rows):
        print("! simpleFoam stopped at its iteration limit without meeting residualControl")
    for r in rows:
        if r.get("plumekit_seconds") is not None:
            print(f"plumekit at {r['cell']:g} m: {r['plumekit_iterations']} iterations, "
                  f"convection {r.get('plumekit_convection')}, tolerance "
                  f"{r.get('plumekit_tolerance')}, converged {r.get('plumekit_converged')}, "
                  f"nonzero velocity in {r['solid_mismatch']} obstacle cells")
        if r["plumekit_error"]:
            print(f"plumekit at {r['cell']:g} m: {r['plumekit_error']}")


def main():
    ap = argparse.ArgumentParser(
        description="Time plumekit flow against OpenFOAM simpleFoam on one map.")
    ap.add_argument("--map", default=os.path.join(REPO, "data", "maps", "cluttered-1.json"))
    ap.add_argument("--cells", default="0.05,0.025", help="comma-separated cell sizes in m")
    ap.add_argument("--nu", type=float, default=0.01, help="kinematic viscosity, m^2/s")
    ap.add_argument("--plumekit", default="build/plumekit", help="path to the plumekit program")
    ap.add_argument("--keep", help="folder for the cases and outputs (default: a temporary "
                    "folder, removed at the end)")
    ap.add_argument("--repeats", type=int, default=1, help="timed runs per solver and cell size")
    ap.add_argument("--foam-tol", type=float, default=foam_case.DEFAULTS["p_tol"],
                    help="simpleFoam residualControl for p and U (initial residuals)")
    ap.add_argument("--foam-convection", default=foam_case.DEFAULTS["convection"],
                    help="simpleFoam's div(phi,U) scheme (default: %(default)s)")
    ap.add_argument("--foam-case", choices=("engine", "python"), default="engine",
                    help="who writes and runs the OpenFOAM case: plumekit's own engine "
                    "(`plumekit flow --engine openfoam`: any map, any openings; default) or "
                    "bench/openfoam/foam_case.py (map/1 only)")
    ap.add_argument("--ranks", type=int, default=1,
                    help="MPI ranks for simpleFoam (--foam-case engine only)")
    ap.add_argument("--json", action="store_true", help="print a JSON result on stdout instead "
                    "of the table")
    args = ap.parse_args()
    if args.repeats < 1:
        ap.error("--repeats must be at least 1")
    cells = [float(c) for c in args.cells.split(",") if c.strip()]
    map_path = os.path.abspath(args.map)
    args.plumekit = os.path.abspath(args.plumekit)

    def log(msg):
        print(msg, file=sys.stderr if args.json else sys.stdout, flush=True)

    if shutil.which("simpleFoam") is None:
        sys.exit("simpleFoam not found: run bench/openfoam/install.sh (Debian's openfoam)")
    if args.foam_case == "python" and args.ranks != 1:
        ap.error("--ranks needs --foam-case engine")
    m = foam_case.load_map(map_path) if args.foam_case == "python" else None
    root = os.path.abspath(args.keep) if args.keep else tempfile.mkdtemp(prefix="plumekit-of-")
    os.makedirs(root, exist_ok=True)
    rows = []
    try:
        for cell in cells:
            rows.append(bench_cell(args, m, map_path, cell, root, log))
    finally:
        if not args.keep:
            shutil.rmtree(root, ignore_errors=True)

    if args.json:
        json.dump({"map": map_path, "loadavg_end": os.getloadavg(), "nu": args.nu, "repeats": args.repeats,
                   "plumekit": args.plumekit, "openfoam": "v1912 (Debian)",
                   "targets": {"speedup": TARGET_SPEEDUP, "rel_l2": TARGET_REL_L2},
                   "results": rows}, sys.stdout, indent=1)
        print()
    else:
        print_table(rows, map_path, args.nu)


if __name__ == "__main__":
    main()
