#!/usr/bin/env python3
"""Convergence of the 3D polyester line (examples/polyester_line_3d.toml) in
elements and step: the fairlead tension's mean, standard deviation, maximum and
minimum over 40-120 s (the build-up left out) against a converged run, and each
setting's cost per simulated second (one sample; the cheapest setting within
0.5 % is timed again with `slender bench --repeats 5`).

Usage: scripts/line3d-convergence.py [--slender target/release/slender] [--coarse] [--duration S]
`--coarse` scans the cheapest settings instead (3-6 elements, 0.4-1.0 s
steps: the MoorDyn comparison's); `--duration` runs every setting and the
converged run that long (default the scene's 120 s; the statistics always
from 40 s on).
Writes results/line3d-convergence/table.csv and prints the table."""

import argparse, csv, json, os, statistics, subprocess, sys

SCENE = "examples/polyester_line_3d.toml"
OUT = "results/line3d-convergence"


def run(slender, elements, step, duration=None):
    name = f"e{elements}_h{step}"
    out = os.path.join(OUT, name)
    cmd = [slender, "run", SCENE, "--out", out,
           "--set", f"units.line.parameters.elements={elements}",
           "--set", f"simulation.step={step}"]
    if duration is not None:
        cmd += ["--set", f"simulation.duration={duration}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "timeseries.csv")) as f:
        rows = list(csv.reader(f))
    head = rows[0]
    t = head.index("time [s]")
    k = head.index("line.end_tension [N]")
    values = [float(r[k]) for r in rows[1:] if float(r[t]) >= 40.0]
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    stats = [statistics.fmean(values), statistics.pstdev(values), max(values), min(values)]
    return stats, summary


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--slender", default="target/release/slender")
    parser.add_argument("--coarse", action="store_true")
    parser.add_argument("--duration", type=float)
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    reference, _ = run(args.slender, 640, 0.0125, args.duration)
    table = []
    meshes, steps = [20, 40, 80, 160, 320], [0.2, 0.1, 0.05, 0.025]
    if args.coarse:
        meshes, steps = [3, 4, 5, 6], [0.4, 0.6, 0.8, 1.0]
    for elements in meshes:
        for step in steps:
            stats, summary = run(args.slender, elements, step, args.duration)
            errors = [abs(s / r - 1.0) for s, r in zip(stats, reference)]
            cost = summary["cost_per_simulated_second"]
            table.append((elements, step, *errors, max(errors), cost))
            print(f"{elements:4d} {step:6.4f} " + " ".join(f"{e:.2e}" for e in errors) + f"  worst {max(errors):.2e}  cost {cost}")
            sys.stdout.flush()
    with open(os.path.join(OUT, "table.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["elements", "step", "mean", "sd", "max", "min", "worst", "cost_s_per_sim_s"])
        w.writerows(table)
    print("reference (640 elements, 0.0125 s): mean, sd, max, min =", reference)


if __name__ == "__main__":
    main()
