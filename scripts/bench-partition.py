#!/usr/bin/env python3
"""Partitioned structures against their monolithic run (issue 25).

Writes variants of the mooring line and S-lay examples into
target/bench-partition/ (no twin: the structure alone), then measures each
with `slender bench --repeats R --json`, one run at a time, the variants of
one structure interleaved round by round so that a slow spell of this shared
machine hits them alike. Prints one Markdown table per structure: cost per
simulated second (median over rounds of each round's median, and the spread
of the rounds), the ratio to the monolithic run of the same round, coupling
iterations per step and do_step calls per step.

Usage: scripts/bench-partition.py [--rounds 3] [--repeats 5] [--duration 20]
"""
import argparse
import json
import pathlib
import re
import statistics
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
SLENDER = ROOT / "target/release/slender"
OUT = ROOT / "target/bench-partition"

IQN = 'scheme = "iterative_gauss_seidel"\nmax_iterations = 100\ntolerances = {tol}\nacceleration = {{ kind = "iqn_ils", reuse_steps = 0 }}\n'
NEWTON = 'scheme = "iterative_jacobi"\nmax_iterations = 50\nthreads = {threads}\nextrapolation = "linear"\ntolerances = {tol}\nnewton = {{ derivatives = "units"{reuse} }}\n'


def variant(text, master, sections, duration):
    """The example with its [master], sections and duration replaced, no twin."""
    text = re.sub(r"\[master\]\n(?:[^\[\n][^\n]*\n)*", "[master]\n" + master + "\n", text, count=1)
    text = re.sub(r"duration = [0-9.]+", f"duration = {duration}", text, count=1)
    text = text.replace("reference = true\n", "")
    head, rest = text.split("[[structure.sections]]", 1)
    out = rest.split("[output]", 1)[1]
    out = re.sub(r"\n\[\[output\.indicators\]\](?:\n[^\[\n][^\n]*)*", "", "[output]" + out)
    out = re.sub(r"\n\[\[output\.plots\]\](?:\n[^\[\n][^\n]*)*", "", out)
    out = re.sub(r"signals = \[.*\]", "signals = []", out)
    return head + sections + "\n" + out


def structures(duration):
    mooring = (ROOT / "examples/structure_mooring.toml").read_text()
    slay = (ROOT / "examples/structure_slay.toml").read_text()
    m_tol = "{ velocity = 1e-6, force = 1.0, generic = 1e-6 }"
    s_tol = "{ velocity = 1e-7, force = 1e-2, generic = 1e-7 }"
    whole = '[[structure.sections]]\nname = "whole"\n'
    def sec(*cuts):
        names = ["s%d" % i for i in range(len(cuts) + 1)]
        text = ""
        for name, cut in zip(names, list(cuts) + [None]):
            text += f'[[structure.sections]]\nname = "{name}"\n'
            if cut is not None:
                text += f"to = {cut}\n"
        return text
    slay_cuts = re.findall(r"to = ([0-9.]+)", slay.split("[[structure.sections]]", 1)[1])
    yield "mooring line (80 elements, cut at node 65)", mooring, m_tol, whole, sec(1571.375)
    yield "mooring line (80 elements, cut at node 40)", mooring, m_tol, whole, sec(967.0)
    yield "S-lay (3 sections)", slay, s_tol, whole, sec(*slay_cuts)
    fine = mooring.replace("elements = 80", "elements = 640")
    yield "mooring line (640 elements, cut at node 320)", fine, m_tol, whole, sec(967.0)


def bench(path, repeats):
    out = subprocess.run([str(SLENDER), "bench", str(path), "--repeats", str(repeats), "--json"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--duration", type=float, default=20.0)
    p.add_argument("--only", default="", help="only the structures whose title contains this")
    a = p.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    for k, (title, text, tol, whole, cut) in enumerate(structures(a.duration)):
        if a.only and a.only not in title:
            continue
        runs = {
            "monolithic": variant(text, IQN.format(tol=tol), whole, a.duration),
            "IQN-ILS, Gauss-Seidel (before)": variant(text, IQN.format(tol=tol), cut, a.duration),
            "Newton, unit Jacobians, 1 thread": variant(text, NEWTON.format(tol=tol, threads=1, reuse=""), cut, a.duration),
            "Newton, unit Jacobians, 2 threads": variant(text, NEWTON.format(tol=tol, threads=2, reuse=""), cut, a.duration),
        }
        paths = {}
        for i, (name, scene) in enumerate(runs.items()):
            path = OUT / f"{k}_{i}.toml"
            path.write_text(scene)
            paths[name] = path
        costs = {n: [] for n in runs}
        ratios = {n: [] for n in runs}
        last = {}
        for _ in range(a.rounds):
            round_cost = {}
            for name, path in paths.items():
                r = bench(path, a.repeats)
                round_cost[name] = r["median_cost_per_simulated_second"]
                last[name] = r
            for name in runs:
                costs[name].append(round_cost[name])
                ratios[name].append(round_cost[name] / round_cost["monolithic"])
        print(f"\n### {title}, {a.duration} s simulated\n")
        print("| run | s per simulated s (median, spread of rounds) | ratio to monolithic (median, range) | iterations/step | do_step calls/step |")
        print("|---|---|---|---|---|")
        for name in runs:
            c = costs[name]
            r = ratios[name]
            info = last[name]
            steps = info["steps"]
            print(f"| {name} | {statistics.median(c):.3e} ({min(c):.2e}-{max(c):.2e}) | {statistics.median(r):.2f} ({min(r):.2f}-{max(r):.2f}) | {info['iterations'] / steps:.2f} | {info['do_step_calls'] / steps:.2f} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
