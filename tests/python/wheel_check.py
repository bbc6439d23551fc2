"""The `slender` wheel as a user without Rust gets it (issue 49): installed
into a fresh venv, run from a folder outside the repository with the venv
not on the PATH and no SLENDER_BINARY, so nothing but the wheel's own files
can answer. Checks that the reader finds the wheel's binary, runs a scene
and reads its results, and that the command exports an FMU with the FMU
library the wheel installed beside it.

Usage: (in the wheel's venv) wheel_check.py REPO_ROOT"""

import os
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

import slender

root = Path(sys.argv[1]).resolve()
installed = Path(sys.executable).parent / "slender"
assert "SLENDER_BINARY" not in os.environ
assert shutil.which("slender") is None, "the venv is on the PATH: the check would not show the lookup"
assert not Path.cwd().resolve().is_relative_to(root), "run outside the repository"
assert slender.binary() == str(installed), slender.binary()

version = subprocess.run([installed, "--version"], capture_output=True, text=True, check=True)
print(f"wheel: {version.stdout.strip()} at {installed}")

run = slender.run(root / "examples/b1_two_masses.toml")
assert run.status == "completed", run.summary
assert len(run.timeseries) > 100 and "left.displacement" in run.timeseries, run.timeseries.columns
assert run.units["left.displacement"] == "m"
print(f"run: {len(run.timeseries)} rows of {len(run.timeseries.columns)} signals, {run.status}")

work = Path(tempfile.mkdtemp(prefix="slender-wheel-"))
fmu = work / "left.fmu"
export = subprocess.run(
    [installed, "fmu", "export", root / "examples/b1_two_masses.toml", "--unit", "left", "--out", fmu],
    capture_output=True, text=True)
assert export.returncode == 0, export.stderr
with zipfile.ZipFile(fmu) as archive:
    libraries = [n for n in archive.namelist() if n.startswith("binaries/") and n.endswith(".so")]
assert libraries, "no library in the FMU"
info = subprocess.run([installed, "fmu", "info", fmu], capture_output=True, text=True)
assert info.returncode == 0 and "left" in info.stdout + info.stderr, info.stdout + info.stderr
print(f"fmu export: {fmu.name} with {libraries[0]}, loaded back by `slender fmu info`")
shutil.rmtree(work)
print("wheel checks passed")
