"""The Python reader (python/slender) against the files the CLI writes:
run by tests/tests/python_reader.rs with SLENDER_BINARY set and the package
installed in the test venv. Prints one line per check; exits non-zero on the
first failure."""

import json
import math
import sys
import tempfile
from pathlib import Path

import slender

root = Path(sys.argv[1])
work = Path(tempfile.mkdtemp(prefix="reader-"))

# A run: the frame is timeseries.csv, indexed by time, with summary.json's units.
b1 = slender.run(root / "examples/b1_two_masses.toml", out=work / "b1")
assert b1.status == "completed", b1.summary
with open(work / "b1" / "timeseries.csv") as f:
    header = f.readline().strip().split(",")
    # Each column says its unit in brackets; the frame's columns are the names.
    assert header[:2] == ["time [s]", "left.displacement [m]"], header
    names = [c.split(" [")[0] for c in header]
    rows = [dict(zip(names, line.strip().split(","))) for line in f]
frame = b1.timeseries
assert list(frame.columns) == names[1:], frame.columns
assert len(frame) == len(rows) == 101, len(frame)
assert frame.index.name == "time" and frame.index[-1] == 1.0
for row, (t, values) in zip(rows, frame.iterrows()):
    assert float(row["time"]) == t
    assert all(float(row[c]) == values[c] for c in frame.columns)
assert b1.units["left.displacement"] == "m" and b1.units["left.velocity"] == "m/s"
assert frame.attrs["units"] == b1.units
# B1's analytic solution, u1 = (cos 2 pi t + cos 6 pi t) / 2, to the scheme's error.
exact = [(math.cos(2 * math.pi * t) + math.cos(6 * math.pi * t)) / 2 for t in frame.index]
worst = max(abs(a - b) for a, b in zip(frame["left.displacement"], exact))
assert worst < 0.05, worst
print(f"run: {len(frame)} rows x {len(frame.columns)} signals, units {b1.units['left.velocity']}, B1 within {worst:.2e} m")

# --set and --duration reach the command.
short = slender.run(root / "examples/b1_two_masses.toml", out=work / "short", duration=0.5,
                    set={"master.scheme": "iterative_jacobi"})
assert short.timeseries.index[-1] == 0.5 and short.summary["overrides"] == ['master.scheme="iterative_jacobi"'], short.summary
print("run: --duration and --set passed through")

# Statistics over a window without the build-up, as pandas and scipy compute
# them from the recorded CSV.
from scipy import stats
sea = slender.run(root / "examples/sea_state.toml", duration=300.0,
                  set={"output.statistics": {"from": 20.0}})
wave = sea.timeseries.loc[sea.timeseries.index >= 20.0, "wave.value"]
row = sea.statistics.loc["wave.value"]
assert row["samples"] == len(wave), (row, len(wave))
for name, value in [("mean", wave.mean()), ("std_dev", wave.std(ddof=0)),
                    ("skewness", stats.skew(wave)), ("kurtosis", stats.kurtosis(wave, fisher=False)),
                    ("min", wave.min()), ("max", wave.max())]:
    assert abs(row[name] - value) <= 1e-9 * max(1.0, abs(value)), (name, row[name], value)
assert slender.run(root / "examples/b1_two_masses.toml", duration=0.1).statistics.empty
print(f"run: statistics as pandas and scipy compute them (sd {row['std_dev']:.4f} m)")

# A study: one row per run, as study.csv.
rows = slender.study(root / "examples/b3_force_displacement.toml", vary={"step": [0.001, 0.002, 0.005]},
                     out=work / "study")
assert list(rows["value"]) == [0.001, 0.002, 0.005], rows
assert rows["epsilon_motion"].iloc[0] == 0.0 and (rows["epsilon_motion"].iloc[1:] > 0).all()
assert (rows["cost_per_simulated_second"] > 0).all()
print(f"study: {len(rows)} rows, epsilon {list(rows['epsilon_motion'])}")

# A failed run is a row with its reason, not an exception.
rows = slender.study(root / "examples/b3_force_displacement.toml", vary={"step": [0.001, 0.06]},
                     out=work / "failing")
assert "(the scene as changed by --vary step=0.06)" in rows["error"].iloc[1], rows["error"]
print("study: a failed run is a row with its error")

# A fidelity study.
table = slender.fidelity(root / "examples/structure_hanging_pipe.toml", {"middle": ["nonlinear", "linear"]},
                         out=work / "fidelity", duration=2.0)
assert len(table) == 3 and bool(table["reference"].iloc[0]) and table["combination"].iloc[0] == "monolithic=nonlinear", table
print(f"fidelity: {len(table)} rows")

# Bad input raises with the command's message.
try:
    slender.run(root / "examples/no_such_scene.toml", out=work / "missing")
except slender.SlenderError as e:
    assert e.code == 2 and "no_such_scene" in str(e), e
    print("bad input: SlenderError, exit 2")
else:
    raise AssertionError("a missing scene did not raise")

# Numbers are numbers: an empty cell (the reference's start_change) is NaN,
# true/false columns are booleans (issue 49 #9: they came back as strings).
assert table["start_change"].dtype.kind == "f" and table["cost_spread"].dtype.kind == "f", table.dtypes
assert table["reference"].dtype == bool and table["pareto"].dtype == bool, table.dtypes
assert rows["start_change"].dtype.kind == "f" and rows["value"].dtype.kind == "f", rows.dtypes
print("tables: numeric columns as numbers, flags as booleans")

# A torn timeseries.csv, a missing one and a run that never finished raise,
# saying which (a cut last row was read as a number; a missing file as empty).
import shutil
torn = work / "torn"
shutil.copytree(work / "b1", torn)
text = (torn / "timeseries.csv").read_text()
(torn / "timeseries.csv").write_text(text[:-7])


def refused(folder, error, *says):
    """read_run(folder) raises `error` whose message has every one of `says`."""
    try:
        slender.read_run(folder)
    except error as e:
        assert all(s in str(e) for s in says), e
    else:
        raise AssertionError(f"{folder} was read")


refused(torn, ValueError, "torn")
short_csv = work / "short_csv"
shutil.copytree(work / "b1", short_csv)
lines = (short_csv / "timeseries.csv").read_text().splitlines(keepends=True)
(short_csv / "timeseries.csv").write_text("".join(lines[:-3]))
refused(short_csv, ValueError, "ends at t")
(short_csv / "timeseries.csv").unlink()
refused(short_csv, FileNotFoundError, "missing")
unfinished = work / "unfinished"
unfinished.mkdir()
(unfinished / "timeseries.csv.partial").write_text("time [s]\n0\n")
refused(unfinished, FileNotFoundError, "did not finish", "timeseries.csv.partial")
print("reader: torn, short, missing and unfinished results raise")

# Without `out` the temporary folder is removed once read.
import glob
import os
before = set(glob.glob(os.path.join(tempfile.gettempdir(), "slender-run-*")))
quick = slender.run(root / "examples/b1_two_masses.toml", duration=0.1)
after = set(glob.glob(os.path.join(tempfile.gettempdir(), "slender-run-*")))
assert quick.folder is None and after <= before and len(quick.timeseries) > 0, (quick.folder, after - before)
print("reader: temporary folders removed")

# An uncertainty study from Python.
report, runs = slender.uq(root / "examples/truncation_uq.toml", samples=4, duration=2.0, jobs=2,
                          out=work / "uq")
assert len(runs) == 4 and "inputs" in report and "design" in report, (len(runs), sorted(report))
print(f"uq: {len(runs)} runs, uq.json keys {sorted(report)[:4]}")
