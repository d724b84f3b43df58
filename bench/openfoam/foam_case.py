#!/usr/bin/python3
"""Build, mesh, run and read back an OpenFOAM simpleFoam case for a plumekit map.

The mesh is plumekit's own staircase grid: blockMesh meshes the whole arena rectangle with the
cells plumekit uses (nx = round(W/cell), ny = round(H/cell), one cell thick in z, `empty` front and
back), topoSet selects the cells whose centres lie inside or on an obstacle polygon (plumekit's
rasterization rule, reproduced below), and subsetMesh removes them, turning the exposed faces
into the no-slip wall patch `obstacles`.

Steps (each is a function; `main` runs them all as a small CLI):
    write_case   map JSON + cell size -> case dir (system/, constant/, plumekit_case.json)
    mesh_case    blockMesh, topoSet, subsetMesh, writeCellCentres -> cell index map, 0/U, 0/p
    run_solver   simpleFoam, serial, timed                        -> seconds, iterations
    read_result  latest time's U and p                            -> (ny, nx) arrays, 0 in solids

Python 3 + numpy only (Debian: /usr/bin/python3 with python3-numpy).
OpenFOAM: Debian's `openfoam` package (v1912) puts the programs on PATH in /usr/bin; they need
WM_PROJECT_DIR=/usr/share/openfoam in the environment, which `foam_env()` sets.
"""

import argparse
import json
import math
import os
import re
import resource
import shutil
import subprocess
import sys
import time

import numpy as np

WM_PROJECT_DIR = "/usr/share/openfoam"

# ----------------------------------------------------------------------------------------------
# Map and rasterization (mirrors map/map.cpp and map/rasterize.cpp of plumekit)
# ----------------------------------------------------------------------------------------------

SIDES = ("left", "right", "bottom", "top")


def load_map(path):
    """Reads a plumekit-map/1 file and fills in the documented defaults (whole-wall spans,
    uniform profile). Validation proper is plumekit's job (`plumekit map validate`); this only
    checks what the case writer relies on."""
    with open(path) as f:
        m = json.load(f)
    if m.get("format") != "plumekit-map/1":
        raise ValueError(f"{path}: format is not plumekit-map/1")
    W, H = (float(v) for v in m["size"])
    for key in ("inlet", "outlet"):
        o = m[key]
        if o["side"] not in SIDES:
            raise ValueError(f"{path}: {key}.side must be one of {SIDES}")
        length = H if o["side"] in ("left", "right") else W
        o["from"] = float(o.get("from", 0.0))
        o["to"] = float(o.get("to", length))
    m["inlet"]["speed"] = float(m["inlet"]["speed"])
    m["inlet"]["profile"] = m["inlet"].get("profile", "uniform")
    if m["inlet"]["profile"] not in ("uniform", "parabolic"):
        raise ValueError(f"{path}: inlet.profile must be uniform or parabolic")
    m["obstacles"] = [[(float(x), float(y)) for x, y in poly] for poly in m.get("obstacles", [])]
    m["size"] = (W, H)
    return m


def grid_shape(W, H, cell):
    """plumekit's GridShape::with_cell: n = max(1, lround(extent / cell)), cell = extent / n.
    lround rounds halves away from zero, unlike Python's round()."""
    nx = max(1, int(math.floor(W / cell + 0.5)))
    ny = max(1, int(math.floor(H / cell + 0.5)))
    return nx, ny, W / nx, H / ny


def _orientation_sign(a, b, c):
    # Same tolerance as plumekit's geometry.cpp: 1e-12 * scale^2 on the cross product.
    scale = max(abs(a[0]), abs(a[1]), abs(b[0]), abs(b[1]), abs(c[0]), abs(c[1]), 1.0)
    tol = 1e-12 * scale * scale
    o = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    return 1 if o > tol else (-1 if o < -tol else 0)


def _within_box(p, a, b):
    tol = 1e-12 * max(abs(a[0]), abs(a[1]), abs(b[0]), abs(b[1]), 1.0)
    return (min(a[0], b[0]) - tol <= p[0] <= max(a[0], b[0]) + tol
            and min(a[1], b[1]) - tol <= p[1] <= max(a[1], b[1]) + tol)


def covers(poly, p):
    """True when p is inside the polygon or on its boundary (either orientation).
    Explicit on-segment test first, then crossing number with a half-open rule in y."""
    inside = False
    n = len(poly)
    j = n - 1
    for i in range(n):
        a, b = poly[j], poly[i]
        if _orientation_sign(a, b, p) == 0 and _within_box(p, a, b):
            return True
        if (a[1] > p[1]) != (b[1] > p[1]):
            x_at = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1])
            if p[0] < x_at:
                inside = not inside
        j = i
    return inside


def solid_mask(m, nx, ny, dx, dy):
    """(ny, nx) bool, row 0 at y = 0: True where the cell centre is inside/on an obstacle."""
    solid = np.zeros((ny, nx), dtype=bool)
    for poly in m["obstacles"]:
        xs = [p[0] for p in poly]
        ys = [p[1] for p in poly]
        # Only cells whose centres fall in the bounding box can be solid (same bounds as plumekit).
        i0 = max(0, int(math.floor(min(xs) / dx - 0.5)))
        i1 = min(nx - 1, int(math.ceil(max(xs) / dx - 0.5)))
        j0 = max(0, int(math.floor(min(ys) / dy - 0.5)))
        j1 = min(ny - 1, int(math.ceil(max(ys) / dy - 0.5)))
        for j in range(j0, j1 + 1):
            cy = (j + 0.5) * dy
            for i in range(i0, i1 + 1):
                if not solid[j, i] and covers(poly, ((i + 0.5) * dx, cy)):
                    solid[j, i] = True
    return solid


def wall_labels(m, side, n, d):
    """Patch name of each of the n boundary faces along one wall, by plumekit's label rule:
    inlet/outlet when the face centre's position along the wall lies in the opening's span
    (inclusive), plain wall otherwise."""
    out = []
    for k in range(n):
        s = (k + 0.5) * d
        name = "walls"
        for key in ("inlet", "outlet"):
            o = m[key]
            if o["side"] == side and o["from"] <= s <= o["to"]:
                name = key
                break
        out.append(name)
    return out


def enclosed_fluid(solid, labels):
    """Fluid cells not connected (4-neighbour) to any inlet or outlet face. OpenFOAM cannot
    solve a closed pocket with no pressure reference; the exact velocity there is zero, so the
    case treats those cells as solid too."""
    ny, nx = solid.shape
    seen = np.zeros_like(solid)
    stack = []
    for (side, names) in labels.items():
        for k, name in enumerate(names):
            if name == "walls":
                continue
            j, i = {"left": (k, 0), "right": (k, nx - 1), "bottom": (0, k), "top": (ny - 1, k)}[side]
            if not solid[j, i] and not seen[j, i]:
                seen[j, i] = True
                stack.append((j, i))
    while stack:
        j, i = stack.pop()
        for dj, di in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            a, b = j + dj, i + di
            if 0 <= a < ny and 0 <= b < nx and not solid[a, b] and not seen[a, b]:
                seen[a, b] = True
                stack.append((a, b))
    return ~solid & ~seen


def solid_boxes(solid, dx, dy):
    """Covers the solid cells with few axis-aligned boxes for topoSet's boxToCell (which selects
    by cell centre): row runs, merged downwards while the same run repeats. Boxes are inset by a
    quarter cell from the run's outer centres so no neighbouring centre can fall inside."""
    ny, nx = solid.shape
    open_runs = {}  # (i0, i1) -> first row j
    boxes = []

    def close(i0, i1, ja, jb):
        lo = ((i0 + 0.25) * dx, (ja + 0.25) * dy)
        hi = ((i1 + 0.75) * dx, (jb + 0.75) * dy)
        boxes.append((lo, hi))

    for j in range(ny + 1):
        runs = set()
        if j < ny:
            row = solid[j]
            i = 0
            while i < nx:
                if row[i]:
                    k = i
                    while k + 1 < nx and row[k + 1]:
                        k += 1
                    runs.add((i, k))
                    i = k + 1
                else:
                    i += 1
        for r in list(open_runs):
            if r not in runs:
                close(r[0], r[1], open_runs.pop(r), j - 1)
        for r in runs:
            open_runs.setdefault(r, j)
    return boxes


# ----------------------------------------------------------------------------------------------
# Writing the case
# ----------------------------------------------------------------------------------------------

HEADER = """/*--------------------------------*- C++ -*----------------------------------*\\
  Written by plumekit bench/openfoam/foam_case.py for OpenFOAM v1912
\\*---------------------------------------------------------------------------*/
FoamFile
{{
    version     2.0;
    format      ascii;
    class       {cls};
    location    "{loc}";
    object      {obj};
}}
"""

# Settings shared by every run; the README explains the choices. The convergence test is
# simpleFoam's residualControl on the *initial* residuals of each SIMPLE iteration.
DEFAULTS = {
    "p_tol": 1e-6,       # residualControl for p
    "U_tol": 1e-6,       # residualControl for U (all components)
    "max_iter": 20000,   # safety stop; a run that hits it is reported as not converged
    "convection": "bounded Gauss linearUpwind grad(U)",
    "relax_U": 0.9,      # SIMPLEC: under-relax U only, p unrelaxed
    "relax_p": 1.0,
}


def _write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def _fmt(x):
    return repr(float(x))


def _vec(v):
    return "(" + " ".join(_fmt(c) for c in v) + ")"


def write_case(m, cell, nu, case, settings=None):
    """Writes the mesh and solver dictionaries. Fields (0/U, 0/p) are written by mesh_case,
    after subsetMesh, because the parabolic inlet needs the final face centres."""
    s = dict(DEFAULTS)
    s.update(settings or {})
    W, H = m["size"]
    nx, ny, dx, dy = grid_shape(W, H, cell)
    dz = min(dx, dy)  # one cell in z; its thickness does not matter for an `empty` direction

    if os.path.exists(case):
        shutil.rmtree(case)
    os.makedirs(case)

    labels = {"left": wall_labels(m, "left", ny, dy), "right": wall_labels(m, "right", ny, dy),
              "bottom": wall_labels(m, "bottom", nx, dx), "top": wall_labels(m, "top", nx, dx)}
    solid = solid_mask(m, nx, ny, dx, dy)
    pockets = enclosed_fluid(solid, labels)
    removed = solid | pockets
    if not (~removed).any():
        raise ValueError("no fluid cell is connected to the inlet or outlet")
    if not any(n == "inlet" for v in labels.values() for n in v) or \
       not any(n == "outlet" for v in labels.values() for n in v):
        raise ValueError("the inlet or outlet span covers no boundary face at this cell size")

    n_blocks = _write_block_mesh(case, labels, nx, ny, dx, dy, dz)
    n_boxes = _write_topo_set(case, removed, dx, dy, dz)
    _write_control_and_schemes(case, s)
    _write_fv_solution(case, s)

    # v1912 (openfoam.com) reads constant/turbulenceProperties; momentumTransport is the name
    # used by openfoam.org v8+, and is not read here.
    _write(f"{case}/constant/turbulenceProperties",
           HEADER.format(cls="dictionary", loc="constant", obj="turbulenceProperties") +
           "\nsimulationType  laminar;\n")
    _write(f"{case}/constant/transportProperties",
           HEADER.format(cls="dictionary", loc="constant", obj="transportProperties") +
           f"\ntransportModel  Newtonian;\nnu              {_fmt(nu)};\n")

    meta = {
        "map_name": m.get("name", ""),
        "size": [W, H], "cell": cell, "nx": nx, "ny": ny, "dx": dx, "dy": dy, "dz": dz, "nu": nu,
        "inlet": m["inlet"], "outlet": m["outlet"],
        "n_solid": int(solid.sum()), "n_pocket": int(pockets.sum()),
        "n_fluid": int((~removed).sum()), "n_blocks": n_blocks, "n_boxes": n_boxes,
        "settings": s,
    }
    np.save(f"{case}/removed.npy", removed)
    with open(f"{case}/plumekit_case.json", "w") as f:
        json.dump(meta, f, indent=1)
    return meta


def _write_block_mesh(case, labels, nx, ny, dx, dy, dz):
    """Writes system/blockMeshDict: the arena rectangle in blocks whose wall faces each lie on one
    patch. Returns the number of blocks."""
    # Block breakpoints: every place along a wall where the patch label changes, so that each
    # block face lies on one patch. x breaks come from the bottom/top walls, y from left/right.
    def breaks(a, b, n):
        cuts = {0, n}
        for names in (a, b):
            for k in range(1, n):
                if names[k] != names[k - 1]:
                    cuts.add(k)
        return sorted(cuts)

    xb = breaks(labels["bottom"], labels["top"], nx)
    yb = breaks(labels["left"], labels["right"], ny)
    NX, NY = len(xb), len(yb)

    def vid(a, b, c):  # vertex index of breakpoint (a, b) at z level c
        return c * NX * NY + b * NX + a

    verts = []
    for c in (0, 1):
        for b in range(NY):
            for a in range(NX):
                # Breakpoint coordinates as plumekit computes them: index * (extent / n).
                verts.append((xb[a] * dx, yb[b] * dy, c * dz))

    blocks, patches = [], {"inlet": [], "outlet": [], "walls": [], "frontAndBack": []}
    for b in range(NY - 1):
        for a in range(NX - 1):
            v = [vid(a, b, 0), vid(a + 1, b, 0), vid(a + 1, b + 1, 0), vid(a, b + 1, 0)]
            w = [vid(a, b, 1), vid(a + 1, b, 1), vid(a + 1, b + 1, 1), vid(a, b + 1, 1)]
            blocks.append(f"    hex ({' '.join(map(str, v + w))}) "
                          f"({xb[a + 1] - xb[a]} {yb[b + 1] - yb[b]} 1) simpleGrading (1 1 1)")
            patches["frontAndBack"].append((v[0], v[3], v[2], v[1]))
            patches["frontAndBack"].append((w[0], w[1], w[2], w[3]))
            if a == 0:
                patches[labels["left"][yb[b]]].append((v[0], w[0], w[3], v[3]))
            if a == NX - 2:
                patches[labels["right"][yb[b]]].append((v[2], w[2], w[1], v[1]))
            if b == 0:
                patches[labels["bottom"][xb[a]]].append((v[1], w[1], w[0], v[0]))
            if b == NY - 2:
                patches[labels["top"][xb[a]]].append((v[3], w[3], w[2], v[2]))

    def face_list(fs):
        return "\n".join(f"            ({' '.join(map(str, f))})" for f in fs)

    types = {"inlet": "patch", "outlet": "patch", "walls": "wall", "frontAndBack": "empty"}
    bnd = []
    for name in ("inlet", "outlet", "walls", "frontAndBack"):
        bnd.append(f"    {name}\n    {{\n        type {types[name]};\n        faces\n        (\n"
                   f"{face_list(patches[name])}\n        );\n    }}")
    # Empty for now; subsetMesh moves the faces it exposes here.
    bnd.append("    obstacles\n    {\n        type wall;\n        faces ();\n    }")

    _write(f"{case}/system/blockMeshDict",
           HEADER.format(cls="dictionary", loc="system", obj="blockMeshDict") +
           "convertToMeters 1;\n\nvertices\n(\n" +
           "\n".join("    " + _vec(p) for p in verts) + "\n);\n\nblocks\n(\n" +
           "\n".join(blocks) + "\n);\n\nedges ();\n\nboundary\n(\n" + "\n".join(bnd) +
           "\n);\n\nmergePatchPairs ();\n")
    return len(blocks)


def _write_topo_set(case, removed, dx, dy, dz):
    """Writes system/topoSetDict, which selects the cells subsetMesh removes. Returns the number
    of boxes it takes."""
    # topoSet: `solid` = the obstacle cells (boxes around their centres); `fluid` = the rest,
    # which subsetMesh keeps.
    boxes = solid_boxes(removed, dx, dy)
    box_text = "\n".join(f"            {_vec((*lo, -1.0))} {_vec((*hi, 2.0 * dz + 1.0))}"
                         for lo, hi in boxes)
    _write(f"{case}/system/topoSetDict",
           HEADER.format(cls="dictionary", loc="system", obj="topoSetDict") + f"""
actions
(
    {{
        name    solid;
        type    cellSet;
        action  new;
        source  boxToCell;
        boxes
        (
{box_text}
        );
    }}
    {{
        name    fluid;
        type    cellSet;
        action  new;
        source  cellToCell;
        sets    (solid);
    }}
    {{
        name    fluid;
        type    cellSet;
        action  invert;
    }}
);
""")
    return len(boxes)


def _write_control_and_schemes(case, s):
    """Writes system/controlDict and system/fvSchemes from the settings `s`."""
    _write(f"{case}/system/controlDict",
           HEADER.format(cls="dictionary", loc="system", obj="controlDict") + f"""
application     simpleFoam;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         {int(s["max_iter"])};
deltaT          1;
// Write only at the end: simpleFoam writes the converged state when residualControl is met.
writeControl    timeStep;
writeInterval   {int(s["max_iter"])};
purgeWrite      0;
writeFormat     ascii;
writePrecision  12;
writeCompression off;
timeFormat      general;
timePrecision   8;
runTimeModifiable false;
""")

    _write(f"{case}/system/fvSchemes",
           HEADER.format(cls="dictionary", loc="system", obj="fvSchemes") + f"""
ddtSchemes      {{ default steadyState; }}
gradSchemes     {{ default Gauss linear; }}
divSchemes
{{
    default         none;
    div(phi,U)      {s["convection"]};
    div((nuEff*dev2(T(grad(U))))) Gauss linear;
}}
laplacianSchemes {{ default Gauss linear corrected; }}
interpolationSchemes {{ default linear; }}
snGradSchemes   {{ default corrected; }}
""")


def _write_fv_solution(case, s):
    """Writes system/fvSolution: the linear solvers, SIMPLEC and its relaxation, from `s`."""
    _write(f"{case}/system/fvSolution",
           HEADER.format(cls="dictionary", loc="system", obj="fvSolution") + f"""
solvers
{{
    p
    {{
        solver          GAMG;
        smoother        GaussSeidel;
        tolerance       1e-12;
        relTol          0.05;
    }}
    U
    {{
        solver          smoothSolver;
        smoother        symGaussSeidel;
        tolerance       1e-12;
        relTol          0.1;
    }}
}}

SIMPLE
{{
    consistent      yes;   // SIMPLEC
    nNonOrthogonalCorrectors 0;
    residualControl
    {{
        p               {s["p_tol"]:g};
        U               {s["U_tol"]:g};
    }}
}}

relaxationFactors
{{
    fields      {{ p {s["relax_p"]:g}; }}
    equations   {{ U {s["relax_U"]:g}; }}
}}
""")


# ----------------------------------------------------------------------------------------------
# Running OpenFOAM
# ----------------------------------------------------------------------------------------------

def foam_env():
    # Debian's programs live in /usr/bin and need no `source .../etc/bashrc`; without
    # WM_PROJECT_DIR they stop with "Could not find mandatory etc entry 'controlDict'".
    env = dict(os.environ)
    env["WM_PROJECT_DIR"] = WM_PROJECT_DIR
    return env


LAST_CPU = [0.0]  # CPU seconds (user + sys) of the last foam_run, for a loaded machine


def _child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def foam_run(case, args, log_name):
    """Runs one OpenFOAM program in the case, log to case/log.NAME; raises with the log's tail
    on failure. Returns the wall-clock seconds."""
    if shutil.which(args[0]) is None:
        raise RuntimeError(f"{args[0]} not found on PATH: run bench/openfoam/install.sh")
    log = os.path.join(case, f"log.{log_name}")
    env = foam_env()
    env["PWD"] = os.path.abspath(case)  # else OpenFOAM warns that PWD is not the cwd
    t0 = time.perf_counter()
    c0 = _child_cpu()
    with open(log, "w") as f:
        r = subprocess.run(args + ["-case", os.path.abspath(case)], stdout=f,
                           stderr=subprocess.STDOUT, env=env, cwd=case)
    dt = time.perf_counter() - t0
    LAST_CPU[0] = _child_cpu() - c0
    if r.returncode != 0:
        with open(log) as f:
            tail = "".join(f.readlines()[-30:])
        raise RuntimeError(f"{' '.join(args)} failed (exit {r.returncode}), see {log}:\n{tail}")
    return dt


def _balanced(text, i):
    """Index one past the ')' matching the '(' at text[i]."""
    depth = 0
    for k in range(i, len(text)):
        ch = text[k]
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth == 0:
                return k + 1
    raise ValueError("unbalanced parentheses")


def _parse_value(text, i, width):
    """Parses `uniform X;` or `nonuniform List<T> N (...)` starting at text[i]."""
    mo = re.compile(r"\s*(uniform|nonuniform)\s+").match(text, i)
    if mo is None:
        raise ValueError("expected uniform/nonuniform at " + text[i:i + 40])
    j = mo.end()
    if mo.group(1) == "uniform":
        if text[j] == "(":
            k = _balanced(text, j)
            return np.array(text[j + 1:k - 1].split(), dtype=float).reshape(1, width)
        return np.array([float(text[j:text.index(";", j)])]).reshape(1, 1)
    mo = re.compile(r"(?:List<\w+>)?\s*(\d+)\s*").match(text, j)  # empty list: `nonuniform 0()`
    n = int(mo.group(1))
    j = mo.end()
    k = _balanced(text, j)
    body = text[j + 1:k - 1].replace("(", " ").replace(")", " ")
    arr = np.array(body.split(), dtype=float)
    return arr.reshape(n, width)


def read_field(path, width):
    """internalField and each patch's `value` of an ASCII OpenFOAM field file."""
    with open(path) as f:
        text = f.read()
    i = text.index("internalField") + len("internalField")
    internal = _parse_value(text, i, width)
    patches = {}
    bf = text.index("boundaryField")
    for mo in re.finditer(r"\n\s{4}(\w+)\s*\n\s{4}\{", text[bf:]):
        start = bf + mo.end()
        end = text.index("\n    }", start)
        block = text[start:end]
        v = block.find("value")
        if v >= 0:
            patches[mo.group(1)] = _parse_value(block, v + len("value"), width)
    return internal, patches


def patch_names_of(case):
    """Patch names listed in constant/polyMesh/boundary."""
    with open(f"{case}/constant/polyMesh/boundary") as f:
        text = f.read()
    body = text[text.index("(", text.index("FoamFile") + 8):]
    return re.findall(r"^\s*(\w+)\s*\n\s*\{", body, re.M)


def case_meta(case):
    """The case summary written by write_case and completed by mesh_case."""
    with open(f"{case}/plumekit_case.json") as f:
        return json.load(f)


def mesh_case(case):
    """Meshes the case and writes 0/U and 0/p. Returns {program: seconds}. Also verifies (and
    records in cells.npy) which (row, column) of plumekit's grid each OpenFOAM cell is, from
    the cell centres OpenFOAM itself reports, rather than assuming an ordering."""
    with open(f"{case}/plumekit_case.json") as f:
        meta = json.load(f)
    nx, ny, dx, dy = meta["nx"], meta["ny"], meta["dx"], meta["dy"]
    removed = np.load(f"{case}/removed.npy")
    times = {"blockMesh": foam_run(case, ["blockMesh"], "blockMesh")}
    if removed.any():
        times["topoSet"] = foam_run(case, ["topoSet"], "topoSet")
        # -overwrite: the subset mesh replaces constant/polyMesh; exposed faces -> `obstacles`.
        times["subsetMesh"] = foam_run(case, ["subsetMesh", "fluid", "-patch", "obstacles",
                                              "-overwrite"], "subsetMesh")
    # Cell and face centres as OpenFOAM computes them (field C, boundary values = face centres).
    os.makedirs(f"{case}/0", exist_ok=True)
    times["writeCellCentres"] = foam_run(case, ["postProcess", "-func", "writeCellCentres",
                                                "-time", "0"], "writeCellCentres")
    C, Cb = read_field(f"{case}/0/C", 3)
    for name in ("C", "Cx", "Cy", "Cz", "V"):
        if os.path.exists(f"{case}/0/{name}"):
            os.remove(f"{case}/0/{name}")

    # Map each OpenFOAM cell to plumekit's (j, i) and check it is exactly that cell's centre.
    i = np.floor(C[:, 0] / dx).astype(int)
    j = np.floor(C[:, 1] / dy).astype(int)
    ok = (i >= 0) & (i < nx) & (j >= 0) & (j < ny)
    if not ok.all():
        raise RuntimeError("OpenFOAM cell centre outside the arena")
    err = max(np.abs(C[:, 0] - (i + 0.5) * dx).max(), np.abs(C[:, 1] - (j + 0.5) * dy).max())
    if err > 1e-9 * max(meta["size"]):
        raise RuntimeError(f"OpenFOAM cell centres off plumekit's grid by {err:g} m")
    flat = j * nx + i
    if len(np.unique(flat)) != len(flat):
        raise RuntimeError("two OpenFOAM cells map to one plumekit cell")
    expect = np.flatnonzero(~removed.ravel())  # row-major fluid cells
    if not np.array_equal(np.sort(flat), expect):
        raise RuntimeError("OpenFOAM's fluid cells differ from the rasterized fluid cells")
    # With one block, blockMesh numbers cells row-major (x fastest) and subsetMesh keeps the
    # surviving cells in their old order, so `flat` equals `expect` itself; with several blocks
    # (openings that are not whole walls) the order is block by block. Either way we map by
    # centre; this records which one held.
    meta["cell_order"] = "row-major minus removed" if np.array_equal(flat, expect) else "other"
    meta["centre_max_error"] = float(err)
    np.save(f"{case}/cells.npy", flat)

    # Fields. The inlet profile uses OpenFOAM's own inlet face centres (parabolic: peak `speed`
    # at the middle of the span, zero at its ends), directed into the domain.
    inl = meta["inlet"]
    side = inl["side"]
    normal = {"left": (1, 0), "right": (-1, 0), "bottom": (0, 1), "top": (0, -1)}[side]
    fc = Cb["inlet"]
    s = fc[:, 1] if side in ("left", "right") else fc[:, 0]
    if inl["profile"] == "parabolic":
        eta = (s - inl["from"]) / (inl["to"] - inl["from"])
        speed = inl["speed"] * 4.0 * eta * (1.0 - eta)
    else:
        speed = np.full(len(s), inl["speed"])
    rows = "\n".join(f"({_fmt(normal[0] * v)} {_fmt(normal[1] * v)} 0)" for v in speed)
    inlet_value = f"nonuniform List<vector>\n{len(speed)}\n(\n{rows}\n)"
    patch_names = ["inlet", "outlet", "walls", "obstacles"]
    have = set(patch_names_of(case))
    U_bc = {"inlet": f"type fixedValue; value {inlet_value};",
            "outlet": "type zeroGradient;",
            "walls": "type noSlip;", "obstacles": "type noSlip;"}
    p_bc = {"inlet": "type zeroGradient;", "outlet": "type fixedValue; value uniform 0;",
            "walls": "type zeroGradient;", "obstacles": "type zeroGradient;"}

    def field(cls, obj, dims, internal, bcs):
        body = "".join(f"    {n}\n    {{\n        {bcs[n]}\n    }}\n"
                       for n in patch_names if n in have)
        body += "    frontAndBack\n    {\n        type empty;\n    }\n"
        return (HEADER.format(cls=cls, loc="0", obj=obj) +
                f"\ndimensions {dims};\n\ninternalField {internal};\n\nboundaryField\n{{\n"
                f"{body}}}\n")

    _write(f"{case}/0/U", field("volVectorField", "U", "[0 1 -1 0 0 0 0]", "uniform (0 0 0)", U_bc))
    _write(f"{case}/0/p", field("volScalarField", "p", "[0 2 -2 0 0 0 0]", "uniform 0", p_bc))
    with open(f"{case}/plumekit_case.json", "w") as f:
        json.dump(meta, f, indent=1)
    return times


def clean_results(case):
    """Removes time directories other than 0, so that the case can be run again."""
    for d in os.listdir(case):
        if d != "0" and re.fullmatch(r"[0-9.eE+-]+", d) and os.path.isdir(f"{case}/{d}"):
            shutil.rmtree(f"{case}/{d}")


def run_solver(case, log_name="simpleFoam"):
    """Runs simpleFoam serially. Returns wall seconds, iterations, converged flag, final
    initial residuals (from the log)."""
    clean_results(case)
    seconds = foam_run(case, ["simpleFoam"], log_name)
    with open(os.path.join(case, f"log.{log_name}")) as f:
        log = f.read()
    iters = [int(x) for x in re.findall(r"^Time = (\d+)", log, re.M)]
    conv = re.search(r"SIMPLE solution converged in (\d+) iterations", log)
    res = {}
    for field in ("Ux", "Uy", "p"):
        found = re.findall(rf"Solving for {field}, Initial residual = ([0-9.eE+-]+)", log)
        if found:
            res[field] = float(found[-1])
    return {"seconds": seconds, "cpu_seconds": LAST_CPU[0], "iterations": iters[-1] if iters else 0,
            "converged": conv is not None, "final_residuals": res}


def latest_time(case):
    times = [d for d in os.listdir(case)
             if os.path.isdir(f"{case}/{d}") and re.fullmatch(r"[0-9.eE+-]+", d) and d != "0"]
    if not times:
        raise RuntimeError(f"{case}: no result time directory")
    return max(times, key=float)


def read_result(case):
    """Latest U and p as (ny, nx) float64 arrays (row 0 at y = 0), zero in removed cells."""
    with open(f"{case}/plumekit_case.json") as f:
        meta = json.load(f)
    nx, ny = meta["nx"], meta["ny"]
    flat = np.load(f"{case}/cells.npy")
    t = latest_time(case)
    U, _ = read_field(f"{case}/{t}/U", 3)
    p, _ = read_field(f"{case}/{t}/p", 1)
    out = {}
    for name, col in (("u", U[:, 0]), ("v", U[:, 1]), ("p", p[:, 0])):
        a = np.zeros(nx * ny)
        a[flat] = col
        out[name] = a.reshape(ny, nx)
    out["time"] = t
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("map")
    ap.add_argument("--cell", type=float, default=0.05)
    ap.add_argument("--nu", type=float, default=0.01)
    ap.add_argument("--case", required=True, help="case directory (replaced)")
    ap.add_argument("--p-tol", type=float, default=DEFAULTS["p_tol"])
    ap.add_argument("--U-tol", type=float, default=DEFAULTS["U_tol"])
    ap.add_argument("--convection", default=DEFAULTS["convection"])
    ap.add_argument("--max-iter", type=int, default=DEFAULTS["max_iter"])
    ap.add_argument("--no-run", action="store_true", help="write and mesh only")
    ap.add_argument("--save", help="write u, v, p .npy files (float32) to this folder")
    a = ap.parse_args()
    m = load_map(a.map)
    meta = write_case(m, a.cell, a.nu, a.case, {"p_tol": a.p_tol, "U_tol": a.U_tol,
                                                "convection": a.convection,
                                                "max_iter": a.max_iter})
    print(f"{meta['nx']} x {meta['ny']} cells, {meta['n_fluid']} fluid, {meta['n_blocks']} blocks")
    print("mesh:", mesh_case(a.case))
    if a.no_run:
        return
    r = run_solver(a.case)
    print(json.dumps(r))
    if a.save:
        res = read_result(a.case)
        os.makedirs(a.save, exist_ok=True)
        for k in ("u", "v", "p"):
            np.save(f"{a.save}/{k}.npy", res[k].astype(np.float32))


if __name__ == "__main__":
    main()
