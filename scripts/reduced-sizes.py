#!/usr/bin/env python3
"""Where a `reduced` section pays (issue 48 item 6; a benchmark, not in CI).

The mooring line (examples/structure_mooring.toml) at several meshes, its
lower section at each fidelity, the twin beside it, one run at a time with
the fidelities alternated in each round. Prints per mesh and fidelity the
lower section's own step time (`counters.units[line_lower].step_time_s` in
summary.json: its steps, Jacobians and corrections), the ratio of the full
section's median to the fidelity's with its range over the rounds, and the
top force's epsilon against the twin.

    cargo build --release
    python3 scripts/reduced-sizes.py [--rounds 3] [--elements 80,160,320,500,1000]
"""

import argparse
import json
import statistics
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SLENDER = ROOT / "target" / "release" / "slender"
SCENE = ROOT / "examples" / "structure_mooring.toml"
FULL = '"nonlinear"'
FIDELITIES = [
    FULL,
    '"linear"',
    '{kind="reduced",modes=6}',
    '{kind="reduced",modes=6,training=2.0}',
    '{kind="reduced",modes=2,training=2.0}',
    '{kind="reduced",modes=2,training=2.0,tolerance=1e-2}',
]


def run(elements, fidelity, out):
    """The lower section's step time (s) and the top force's epsilon."""
    subprocess.run(
        [SLENDER, "run", SCENE, "--quiet", "--out", out,
         "--set", f"structure.model.segments[0].elements={elements}",
         "--set", f"structure.sections[0].fidelity={fidelity}",
         "--set", "output.plots=[]"],
        check=True, capture_output=True)
    summary = json.loads((Path(out) / "summary.json").read_text())
    units = {u["name"]: u for u in summary["counters"]["units"]}
    top = next(i for i in summary["indicators"] if i["name"] == "top_force")
    return units["line_lower"]["step_time_s"], top["relative_error"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--elements", default="80,160,320,500,1000")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as out:
        for elements in map(int, args.elements.split(",")):
            times = {f: [] for f in FIDELITIES}
            epsilon = {}
            for _ in range(args.rounds):
                for f in FIDELITIES:
                    t, e = run(elements, f, out)
                    times[f].append(t)
                    epsilon[f] = e
            base = statistics.median(times[FULL])
            for f in FIDELITIES:
                ratios = [base / t for t in times[f]]
                print(f"{elements:5d} {f:55s} {statistics.median(times[f]):.3f} s "
                      f"{base / statistics.median(times[f]):.2f}x "
                      f"({min(ratios):.2f}-{max(ratios):.2f}) epsilon {epsilon[f]:.1e}")


if __name__ == "__main__":
    main()
