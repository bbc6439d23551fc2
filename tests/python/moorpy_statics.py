"""MoorPy's view of a moored body's statics that `slender statics` wrote.

Usage: moorpy_statics.py SCENE_FACTS.json STATICS.json OFFSETS.csv

SCENE_FACTS.json gives the system as the scene has it (depth, water density,
gravity, the line's length, mass per length, diameter and EA, the fairleads in
the body's frame and the anchors). MoorPy's quasi-static lines (no seabed
friction, cb = 0) hang from a body held at slender's equilibrium offset; its
mooring loads and coupled stiffness there, and its loads and tensions along
slender's surge, sway and yaw offset curves, are compared with slender's.
Prints JSON: the largest relative differences.
"""

import csv
import json
import sys

import moorpy as mp
import numpy as np


def system(facts, r6):
    ms = mp.System(depth=facts["depth"], rho=facts["rho"], g=facts["g"])
    ms.setLineType(
        dnommm=1000 * facts["diameter"],
        name="main",
        d_vol=facts["diameter"],
        mass=facts["mass_per_length"],
        EA=facts["axial_stiffness"],
    )
    body = ms.addBody(-1, np.array(r6, dtype=float))
    for fairlead, anchor in zip(facts["fairleads"], facts["anchors"]):
        a = ms.addPoint(1, np.array(anchor, dtype=float))
        f = ms.addPoint(1, np.array(fairlead, dtype=float))
        body.attachPoint(f.number, np.array(fairlead, dtype=float))
        ms.addLine(facts["length"], "main", nSegs=40, pointA=a.number, pointB=f.number, cb=0)
    ms.initialize()
    body.setPosition(np.array(r6, dtype=float))
    ms.solveEquilibrium()
    return ms, body


def loads_and_tensions(facts, r6):
    ms, body = system(facts, r6)
    loads = body.getForces(lines_only=True)
    tensions = [line.TB for line in ms.lineList]
    return np.array(loads), np.array(tensions), ms


def main():
    facts = json.load(open(sys.argv[1]))
    statics = json.load(open(sys.argv[2]))
    offset = np.array(statics["offset"], dtype=float)
    r6 = offset.copy()
    loads, tensions, ms = loads_and_tensions(facts, r6)
    stiffness = np.array(ms.getCoupledStiffnessA(lines_only=True))
    ours = np.array(statics["mooring_stiffness"])
    # Relative to each row's and column's scale: a translation row against
    # the largest translational entry, and so on.
    scale = np.abs(np.diag(ours))
    k_error = np.max(np.abs(stiffness - ours) / np.sqrt(np.outer(scale, scale)))
    our_tensions = [np.linalg.norm(line["force_N"]) for line in statics["lines"]]
    t_error = np.max(np.abs(tensions - np.array(our_tensions)) / np.array(our_tensions))
    curve_error = 0.0
    dof_index = {"surge": 0, "sway": 1, "yaw": 5}
    with open(sys.argv[3]) as f:
        rows = list(csv.DictReader(f))
    for row in rows[:: max(1, len(rows) // 12)]:
        dof = dof_index[row["dof"]]
        at = offset.copy()
        value = float(row["offset"])
        at[dof] += np.radians(value) if dof == 5 else value
        loads_at, tensions_at, _ = loads_and_tensions(facts, at)
        ours_t = np.array([float(row[k]) for k in row if k.endswith("_tension_N")])
        curve_error = max(curve_error, np.max(np.abs(tensions_at - ours_t) / ours_t))
        restoring = float(row["restoring"])
        reference = max(abs(loads_at[dof]), 1e-3 * scale[dof] * (1.0 if dof < 3 else 1.0))
        curve_error = max(curve_error, abs(-loads_at[dof] - restoring) / max(reference, 1.0))
    print(
        json.dumps(
            {
                "stiffness_error": float(k_error),
                "tension_error": float(t_error),
                "curve_error": float(curve_error),
                "moorpy_stiffness_diagonal": [float(x) for x in np.diag(stiffness)],
                "moorpy_tensions": [float(t) for t in tensions],
            }
        )
    )


if __name__ == "__main__":
    main()
