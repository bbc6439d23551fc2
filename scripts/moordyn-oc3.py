#!/usr/bin/env python3
"""The OC3-Hywind mooring driven by a prescribed body motion, slender and
MoorDyn side by side (issue 47's prescribed-motion benchmark; not in CI).

1. The motion: slender runs examples/oc3_hywind_jonswap.toml with its lines
   whole (`nonlinear`, 50 elements) for 300 s and records the spar's six
   degrees of freedom every 0.2 s.
2. slender, prescribed: the same scene without waves, the body following that
   record as its `motion_table` (a natural cubic spline), the lines stepped
   after it (Gauss-Seidel, body first: the motion does not depend on them).
3. MoorDyn 2 (PyPI): the same three lines between fixed anchors and coupled
   fairlead points, which follow the same spline (scipy's natural cubic
   spline, the fairleads placed by the z-y'-x'' rotation slender uses, their
   velocities by central differences), driven from Python every 0.2 s.
No waves act on the lines in either code (MoorDyn would need its wave grid):
the motion carries the sea. Each code is judged against its own converged run
(the fairlead tension's mean, standard deviation and maximum over 30-300 s of
each line), the two converged runs against each other, and the cost per
simulated second is the median of 3 runs, one at a time.

MoorDyn's line type: diameter 0.09 m (its weight in water 698 N/m as
slender's), Cd 1.6, Ca 1.0, CdAx 0.1, CaAx 0 (the OC3 lines), the same axial
damping in both (MoorDyn needs some; the example's line has none), MoorDyn's
seabed (3e6 Pa/m and 3e5 Pa s/m on the diameter: 2.7e5 N/m and 2.7e4 N s/m
per metre of line in slender's terms) without friction in both.

Usage (from the repository's root, after `cargo build --release`):
  python -m venv /tmp/md && /tmp/md/bin/pip install moordyn numpy scipy
  /tmp/md/bin/python scripts/moordyn-oc3.py slender ELEMENTS STEP [ELEMENTS STEP ...]
  /tmp/md/bin/python scripts/moordyn-oc3.py moordyn SEGMENTS DT [SEGMENTS DT ...]
(MoorDyn prints its progress; `| tr '\\r' '\\n' | grep RESULT` keeps the results;
REPEATS=1 in the environment times MoorDyn once.)"""

import csv, math, os, re, statistics, subprocess, sys, tempfile, time

import numpy as np
from scipy.interpolate import CubicSpline

SLENDER = os.path.join("target", "release", "slender")
EXAMPLE = os.path.join("examples", "oc3_hywind_jonswap.toml")
WORK = os.path.join(tempfile.gettempdir(), "slender-moordyn-oc3")
DURATION, START, SAMPLE = 300.0, 30.0, 0.2
DOFS = ["x", "y", "z", "roll", "pitch", "yaw"]
FAIRLEADS = [(5.2, 0.0, -70.0), (-2.6, 4.503332, -70.0), (-2.6, -4.503332, -70.0)]
ANCHORS = [(853.87, 0.0, -320.0), (-426.935, 739.473113, -320.0), (-426.935, -739.473113, -320.0)]
WHOLE = '[{ name = "upper" }]'
# Axial damping BA (N s), the same in both codes: MoorDyn's explicit scheme
# needs some, and given as a fraction of a segment's critical damping (its
# usual -0.8) it would change with the segments (the sd of the tension moved
# 8 % between 80 and 160 segments); this is -0.13 at 20 segments, small
# enough that the damping itself does not bound the explicit step at 160.
AXIAL_DAMPING = 1.0e6


def read_csv(path):
    """The columns of a slender time series by their names without units."""
    with open(path) as f:
        rows = list(csv.reader(f))
    names = [re.sub(r" \[.*\]$", "", n) for n in rows[0]]
    return {n: np.array([float(r[i]) for r in rows[1:]]) for i, n in enumerate(names)}


def example_text():
    with open(EXAMPLE) as f:
        text = f.read()
    return re.sub(r"sections = \[.*\]", "sections = " + WHOLE, text)


def recorded_motion():
    """The spar's motion in the example's sea: time and six columns."""
    path = os.path.join(WORK, "motion", "timeseries.csv")
    if not os.path.exists(path):
        scene = os.path.join(WORK, "motion.toml")
        with open(scene, "w") as f:
            f.write(example_text())
        signals = "[" + ", ".join(f'"spar.{d}"' for d in DOFS) + "]"
        subprocess.run([SLENDER, "run", scene, "--duration", str(DURATION),
                        "--set", f"output.signals={signals}", "--set", "output.plots=[]",
                        "--set", "output.fatigue=[]",
                        "--out", os.path.join(WORK, "motion")], check=True, capture_output=True)
    columns = read_csv(path)
    return columns["time"], [columns["spar." + d] for d in DOFS]


def prescribed_scene(elements, step):
    """The example without waves, its body following the recorded motion."""
    time_, dofs = recorded_motion()
    text = example_text()
    text = re.sub(r"\n\[mooring\.waves\]\n(.*\n)*?\n", "\n", text)
    text = re.sub(r"\nforce_rao = .*\n", "\n", text)
    names = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    table = ", ".join(f"{n} = {list(map(float, d - d[0]))}" for n, d in zip(names, dofs))
    text = text.replace('name = "spar"\n', f'name = "spar"\nmotion_table = {{ time = {list(map(float, time_))}, {table} }}\n')
    text = re.sub(r"\n\[output\]\n(.*\n)*", "\n", text)
    text = re.sub(r"\n\[master\]\n(.*\n)*?\n", "\n", text)
    tensions = ", ".join(f'"line{i}_upper.end_tension"' for i in (1, 2, 3))
    text += f"""
[master]
scheme = "gauss_seidel"
order = ["spar", "line1_upper", "line2_upper", "line3_upper"]

[output]
signals = [{tensions}]
"""
    text = re.sub(r"\nstep = .*\n", f"\nstep = {step}\n", text, count=1)
    text = re.sub(r"\nduration = .*\n", f"\nduration = {DURATION}\n", text, count=1)
    text = re.sub(r"\nelements = .*\n", f"\nelements = {elements}\naxial_damping = {AXIAL_DAMPING}\n", text, count=1)
    # MoorDyn's seabed per unit area (Pa/m, Pa s/m) times the diameter: per
    # unit length, as slender's.
    seabed = f"seabed = {{ depth = 320.0, stiffness = {3.0e6 * 0.09}, damping = {3.0e5 * 0.09} }}"
    text = re.sub(r"\nseabed = .*\n", f"\n{seabed}\n", text, count=1)
    path = os.path.join(WORK, f"prescribed-{elements}-{step}.toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def statistics_of(series):
    """Mean, standard deviation and maximum."""
    return [statistics.fmean(series), statistics.pstdev(series), max(series)]


def run_slender(elements, step):
    scene = prescribed_scene(elements, step)
    out = os.path.join(WORK, f"slender-{elements}-{step}")
    subprocess.run([SLENDER, "run", scene, "--out", out], check=True, capture_output=True)
    columns = read_csv(os.path.join(out, "timeseries.csv"))
    keep = columns["time"] >= START - 1e-9
    stats = [statistics_of(list(columns[f"line{i}_upper.end_tension"][keep])) for i in (1, 2, 3)]
    bench = subprocess.run([SLENDER, "bench", scene, "--repeats", "3"], check=True,
                           capture_output=True, text=True).stdout
    cost = float(re.search(r"cost\s+([0-9.e+-]+) s per simulated second", bench).group(1))
    return stats, cost


MOORDYN = """--------------------- MoorDyn Input File ------------------------------------
OC3-Hywind mooring, fairleads following a prescribed motion (slender scripts/moordyn-oc3.py)
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam     Mass/m     EA         BA/-zeta    EI     Cd     Ca     CdAx   CaAx
(name)     (m)      (kg/m)     (N)        (N-s/-)     (N-m^2) (-)   (-)    (-)    (-)
chain      0.09     77.7066    3.84243e8  {damping}   0      1.6    1.0    0.1    0.0
---------------------- POINTS --------------------------------
ID    Attachment  X        Y     Z         Mass   Volume  CdA    CA
(#)   (-)         (m)      (m)   (m)       (kg)   (m^3)   (m^2)  (-)
{points}
---------------------- LINES --------------------------------------
ID    LineType   AttachA  AttachB  UnstrLen  NumSegs  Outputs
(#)   (name)     (#)      (#)      (m)       (-)      (-)
{lines}
---------------------- OPTIONS -----------------------------------------
{dt}     dtM       - time step to use in mooring integration (s)
320.0    WtrDpth   - water depth (m)
1025     WtrDnsty  - water density (kg/m^3)
9.80665  g         - gravity (m/s^2)
3.0e6    kBot      - bottom stiffness (Pa/m)
3.0e5    cBot      - bottom damping (Pa-s/m)
1.0      dtIC      - time interval for analyzing convergence during IC gen (s)
200      TmaxIC    - max time for ic gen (s)
4.0      CdScaleIC - factor by which to scale drag coefficients during dynamic relaxation (-)
0.0001   threshIC  - threshold for IC convergence (-)
------------------------- need this line --------------------------------------
"""


def rotation(roll, pitch, yaw):
    """z-y'-x'': Rz(yaw) Ry(pitch) Rx(roll), as nalgebra's from_euler_angles."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch),
                              math.sin(pitch), math.cos(yaw), math.sin(yaw))
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def fairlead_motion():
    """The fairleads' positions (9 values) at t (s) and their velocities."""
    time_, dofs = recorded_motion()
    splines = [CubicSpline(time_, d, bc_type="natural") for d in dofs]

    def positions(t):
        x, y, z, roll, pitch, yaw = (float(s(t)) for s in splines)
        r = rotation(roll, pitch, yaw)
        return np.concatenate([np.array([x, y, z]) + r @ np.array(p) for p in FAIRLEADS])

    def at(t):
        d = 1e-4
        return list(positions(t)), list((positions(t + d) - positions(t - d)) / (2 * d))

    return at


def run_moordyn(segments, dt):
    import moordyn

    at = fairlead_motion()
    folder = tempfile.mkdtemp(dir=WORK)
    x0 = at(0.0)[0]
    points = [f"{i + 1}     Fixed     {a[0]}  {a[1]}  {a[2]}  0 0 0 0" for i, a in enumerate(ANCHORS)]
    points += [f"{i + 4}     Coupled   {x0[3 * i]}  {x0[3 * i + 1]}  {x0[3 * i + 2]}  0 0 0 0" for i in range(3)]
    lines = [f"{i + 1}     chain      {i + 1}    {i + 4}    902.2    {segments}    -" for i in range(3)]
    path = os.path.join(folder, "oc3.txt")
    with open(path, "w") as f:
        f.write(MOORDYN.format(points="\n".join(points), lines="\n".join(lines), dt=dt,
                               damping=AXIAL_DAMPING))
    system = moordyn.Create(path)
    moordyn.SetVerbosity(system, moordyn.LEVEL_ERR)  # no progress lines while timed
    moordyn.Init(system, *at(0.0))
    tensions, t, steps = [[], [], []], 0.0, round(DURATION / SAMPLE)
    # The motion made before the clock starts: only MoorDyn is timed.
    motion = [at(SAMPLE * k) for k in range(steps + 1)]
    wall = time.perf_counter()
    for k in range(1, steps + 1):
        t1 = SAMPLE * k
        force = moordyn.Step(system, *motion[k], t, SAMPLE)
        t = t1
        if t1 >= START - 1e-9:
            for i in range(3):
                tensions[i].append(math.sqrt(sum(v * v for v in force[3 * i:3 * i + 3])))
    wall = time.perf_counter() - wall
    moordyn.Close(system)
    return [statistics_of(s) for s in tensions], wall / DURATION


def main():
    os.makedirs(WORK, exist_ok=True)
    code, args = sys.argv[1], sys.argv[2:]
    for a, b in zip(args[::2], args[1::2]):
        if code == "slender":
            stats, cost = run_slender(int(a), float(b))
        else:
            repeats = int(os.environ.get("REPEATS", "3"))
            runs = [run_moordyn(int(a), float(b)) for _ in range(repeats)]
            stats, cost = runs[0][0], statistics.median(c for _, c in runs)
        text = " | ".join(f"mean {s[0]:.1f} sd {s[1]:.1f} max {s[2]:.1f}" for s in stats)
        print(f"RESULT {code} {a} {b} cost {cost:.3e} | {text}", flush=True)


if __name__ == "__main__":
    main()
