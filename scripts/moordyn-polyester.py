#!/usr/bin/env python3
"""MoorDyn side by side with the 3D line on seed 000's polyester line (not in
CI): the fairlead surging 3 m at 0.6 rad/s (faded in over 20 s), without a
current or, with --current, with polyester_line_3d.toml's current across the
line's plane (0.5 m/s along +y at the surface, none at the anchor, linear
between: MoorDyn's steady current grid, `Currents = 1`), the fairlead tension's mean, standard deviation, maximum and minimum over
40-120 s, and the cost per simulated second (median of 3 runs, MoorDyn driven
from Python every 0.1 s, or every --call seconds: its coupling step, of
which its own time step is a divisor). MoorDyn's line type maps slender's parameters: its
volume diameter from the weight in water (0.2091 m), its drag and added-mass
coefficients rescaled to the hydrodynamic diameter 0.264 m; axial damping at
80 % of critical (MoorDyn needs it; slender's line has none).

Usage: python -m venv /tmp/md && /tmp/md/bin/pip install moordyn &&
       /tmp/md/bin/python scripts/moordyn-polyester.py [--current] [--call STEP] SEGMENTS DT [SEGMENTS DT ...]"""

import math, os, statistics, sys, tempfile, time

import moordyn

LINE = """--------------------- MoorDyn Input File ------------------------------------
Seed 000 polyester line (slender scripts/moordyn-polyester.py)
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam     Mass/m     EA         BA/-zeta    EI     Cd     Ca     CdAx   CaAx
(name)     (m)      (kg/m)     (N)        (N-s/-)     (N-m^2) (-)   (-)    (-)    (-)
poly       0.2091   44.7       4.6598e8   -0.8        100    2.020  1.594  0.0    0.0
---------------------- POINTS --------------------------------
ID    Attachment  X        Y     Z         Mass   Volume  CdA    CA
(#)   (-)         (m)      (m)   (m)       (kg)   (m^3)   (m^2)  (-)
1     Fixed       0        0     -1200.11  0      0       0      0
2     Coupled     1529.11  0     0         0      0       0      0
---------------------- LINES --------------------------------------
ID    LineType   AttachA  AttachB  UnstrLen  NumSegs  Outputs
(#)   (name)     (#)      (#)      (m)       (-)      (-)
1     poly       1        2        1934.0    {segments}  -
---------------------- OPTIONS -----------------------------------------
{dt}     dtM       - time step to use in mooring integration (s)
1250.0   WtrDpth   - water depth (m)
1025     rhow      - water density (kg/m^3)
9.81     g         - gravity (m/s^2)
3.0e6    kBot      - bottom stiffness (Pa/m)
3.0e5    cBot      - bottom damping (Pa-s/m)
0.5      dtIC      - time interval for analyzing convergence during IC gen (s)
200      TmaxIC    - max time for ic gen (s)
{cd_scale}      CdScaleIC - factor by which to scale drag coefficients during dynamic relaxation (-)
0.0001   threshIC  - threshold for IC convergence (-)
{currents}
------------------------- need this line --------------------------------------
"""

# MoorDyn's steady current grid (read from current_profile.txt beside the
# input file): z (m), ux, uy, uz (m/s), linear between the rows.
CURRENT = """--------------------- MoorDyn steady currents File ----------------------------------
The current of slender's examples/polyester_line_3d.toml: along +y, 0.5 m/s at the surface, none at the anchor
z (m), ux (m/s), uy (m/s), uz (m/s)
-1250.0 0 0 0
-1200.0 0 0 0
0.0 0 0.5 0
"""


def fairlead(t):
    """Position and velocity of the fairlead at t (s)."""
    fade = 1.0 if t >= 20 else 0.5 * (1 - math.cos(math.pi * t / 20))
    rate = 0.0 if t >= 20 else 0.5 * math.pi / 20 * math.sin(math.pi * t / 20)
    s, c = math.sin(0.6 * t), math.cos(0.6 * t)
    return [1529.11 + fade * 3 * s, 0.0, 0.0], [rate * 3 * s + fade * 1.8 * c, 0.0, 0.0]


def run(segments, dt, current, call=0.1):
    folder = tempfile.mkdtemp()
    path = os.path.join(folder, "line.txt")
    currents = "1        Currents  - steady current grid from current_profile.txt" if current else ""
    with open(path, "w") as f:
        f.write(LINE.format(segments=segments, dt=dt, currents=currents, cd_scale=1.5 if current else 4.0))
    if current:
        with open(os.path.join(folder, "current_profile.txt"), "w") as f:
            f.write(CURRENT)
    system = moordyn.Create(path)
    moordyn.Init(system, *fairlead(0.0))
    tensions, t, wall = [], 0.0, time.perf_counter()
    calls = round(120.0 / call)
    for k in range(1, calls + 1):
        t1 = call * k
        force = moordyn.Step(system, *fairlead(t1), t, call)
        t = t1
        if t1 >= 40 - 1e-9:
            tensions.append(math.sqrt(sum(x * x for x in force)))
    wall = time.perf_counter() - wall
    moordyn.Close(system)
    stats = [statistics.fmean(tensions), statistics.pstdev(tensions), max(tensions), min(tensions)]
    return stats, wall / 120.0


def main():
    args = sys.argv[1:]
    current = "--current" in args
    call = 0.1
    if "--call" in args:
        i = args.index("--call")
        call = float(args[i + 1])
        del args[i : i + 2]
    args = [a for a in args if a != "--current"]
    for segments, dt in zip(args[::2], args[1::2]):
        runs = [run(int(segments), float(dt), current, call) for _ in range(3)]
        stats = runs[0][0]
        cost = statistics.median(c for _, c in runs)
        print(f"\nRESULT {segments} {dt} call {call} mean {stats[0]:.1f} sd {stats[1]:.1f} max {stats[2]:.1f} min {stats[3]:.1f} cost {cost:.3e}")


if __name__ == "__main__":
    main()
