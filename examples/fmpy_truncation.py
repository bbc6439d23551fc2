"""Active truncation in FMPy: slender's cable sections as FMUs, coupled by a small
Python master, compared with slender's own run of the same scene.

    cargo build --release            # the slender CLI and libslender_fmu.so
    .venv/bin/python examples/fmpy_truncation.py [--duration 20]

Exports the units `load` (characteristic top load), `p` (upper section, 80 % of
the depth) and `n` (lower section) of examples/truncation_substructured.toml, then
steps them in FMPy with iterative Gauss-Seidel: p takes the load and a guess of
the truncation-point velocity, n takes p's truncation force and answers with its
velocity; the guess is relaxed (factor 0.5, which suits a loop gain near -1) until
it changes by less than 1e-6 m/s, rolling both sections back with
fmi2GetFMUstate/fmi2SetFMUstate between iterations. Inputs ramp over each step
(fmi2SetRealInputDerivatives), as slender's units expect.
"""

import argparse
import csv
import os
import subprocess
import sys
import tempfile

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "examples", "truncation_substructured.toml")


class Unit:
    """One FMU instance with its variables by name."""

    def __init__(self, path, name):
        md = read_model_description(path)
        self.refs = {v.name: v.valueReference for v in md.modelVariables}
        self.starts = {v.name: float(v.start) for v in md.modelVariables if v.causality == "input"}
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=extract(path),
                             modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
        self.fmu.instantiate()
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        # Inputs at the start of the next step (the last accepted end values).
        self.accepted = dict(self.starts)

    def get(self, *names):
        return self.fmu.getReal([self.refs[n] for n in names])

    def step(self, t, h, end_values):
        """Steps with inputs ramping from the accepted values to `end_values`."""
        names = list(end_values)
        refs = [self.refs[n] for n in names]
        self.fmu.setReal(refs, [self.accepted[n] for n in names])
        slopes = [(end_values[n] - self.accepted[n]) / h for n in names]
        self.fmu.setRealInputDerivatives(refs, [1] * len(refs), slopes)
        self.fmu.doStep(t, h)

    def accept(self, end_values):
        self.accepted.update(end_values)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--duration", type=float, default=20.0, help="simulated time (s)")
    parser.add_argument("--slender", default=os.path.join(ROOT, "target", "release", "slender"))
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="fmpy-truncation-")
    for unit in ("load", "p", "n"):
        subprocess.run([args.slender, "fmu", "export", SCENE, "--unit", unit, "-o",
                        os.path.join(work, unit + ".fmu")], check=True)
    load, p, n = (Unit(os.path.join(work, u + ".fmu"), u) for u in ("load", "p", "n"))

    h, tolerance, relaxation = 0.01, 1e-6, 0.5
    steps = int(round(args.duration / h))
    velocity = list(n.get("top_velocity_x", "top_velocity_z"))
    rows, iterations = [], 0
    for k in range(steps):
        t = k * h
        load.step(t, h, {})
        fx, fz = load.get("force_x", "force_z")
        saved = [p.fmu.getFMUState(), n.fmu.getFMUState()]
        guess = list(velocity)
        for iteration in range(1, 101):
            p_in = {"top_force_x": fx, "top_force_z": fz,
                    "bottom_velocity_x": guess[0], "bottom_velocity_z": guess[1]}
            p.step(t, h, p_in)
            bx, bz = p.get("bottom_force_x", "bottom_force_z")
            n_in = {"top_force_x": bx, "top_force_z": bz}
            n.step(t, h, n_in)
            answer = n.get("top_velocity_x", "top_velocity_z")
            change = max(abs(a - g) for a, g in zip(answer, guess))
            if change < tolerance:
                break
            guess = [g + relaxation * (a - g) for a, g in zip(answer, guess)]
            p.fmu.setFMUState(saved[0])
            n.fmu.setFMUState(saved[1])
        else:
            sys.exit(f"t = {t:.2f} s: no convergence in 100 iterations")
        iterations += iteration
        for unit, s in zip((p, n), saved):
            unit.fmu.freeFMUState(s)
        p.accept(p_in)
        n.accept(n_in)
        velocity = list(answer)
        rows.append((t + h, *p.get("top_velocity_x", "top_velocity_z"), *n.get("bottom_force_x", "bottom_force_z")))

    # slender's own run of the scene (IQN-ILS, same tolerance) for comparison.
    native = os.path.join(work, "native")
    subprocess.run([args.slender, "run", SCENE, "--quiet", "--out", native], check=True,
                   stdout=subprocess.DEVNULL)
    with open(os.path.join(native, "timeseries.csv")) as f:
        reader = csv.reader(f)
        # The header gives each column's unit in brackets: "p.top_velocity_x [m/s]".
        header = [c.split(" [")[0] for c in next(reader)]
        reference = {round(float(r[0]), 6): dict(zip(header, r)) for r in reader}
    names = ["p.top_velocity_x", "p.top_velocity_z", "n.bottom_force_x", "n.bottom_force_z"]
    print(f"FMPy master: {steps} steps, {iterations / steps:.2f} iterations per step")
    for j, name in enumerate(names):
        ref = [float(reference[round(r[0], 6)][name]) for r in rows]
        scale = max(abs(v) for v in ref)
        worst = max(abs(r[j + 1] - v) for r, v in zip(rows, ref))
        print(f"{name:<18} largest difference from slender's run {worst:.3e} (scale {scale:.3e})")
    for unit in (load, p, n):
        unit.fmu.terminate()
        unit.fmu.freeInstance()


if __name__ == "__main__":
    main()
