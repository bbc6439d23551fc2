"""Run slender scenes and read their results as pandas data frames.

Over the ``slender`` command line and the files it writes, so a result read
here is the result the command wrote::

    import slender
    run = slender.run("examples/b1_two_masses.toml", out="results/b1")
    run.timeseries["left.displacement"]     # a Series indexed by time (s)
    run.units["left.displacement"]          # "m"
    run.summary["status"]                   # "completed"
    rows = slender.study("examples/b3_force_displacement.toml",
                         vary={"step": [0.001, 0.002, 0.005]})

The binary is ``$SLENDER_BINARY``, else ``slender`` on the ``PATH``, else
``target/release/slender`` in the current folder or one above it.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, Mapping, Optional, Sequence, Union

import pandas as pd

__all__ = [
    "SlenderError",
    "Run",
    "binary",
    "run",
    "study",
    "fidelity",
    "read_run",
    "read_study",
    "read_fidelity",
    "read_uq",
]

PathLike = Union[str, os.PathLike]


class SlenderError(RuntimeError):
    """A command that failed: its arguments, exit code and what it said."""

    def __init__(self, args: Sequence[str], code: int, stderr: str):
        self.command = list(args)
        self.code = code
        self.stderr = stderr
        super().__init__(f"slender {' '.join(args)} exited {code}: {stderr.strip()}")


@dataclass
class Run:
    """A run's results folder read back."""

    folder: Path
    #: The recorded signals, one column each, indexed by time (s).
    timeseries: pd.DataFrame
    #: summary.json as a dictionary (status, error, counters, indicators...).
    summary: dict
    #: The unit of measure of each column ("" for a dimensionless one).
    units: dict = field(default_factory=dict)

    @property
    def status(self) -> str:
        """``completed``, ``failed`` or ``interrupted``."""
        return self.summary.get("status", "")


def binary() -> str:
    """The ``slender`` binary this package runs (see the module's help)."""
    given = os.environ.get("SLENDER_BINARY")
    if given:
        return given
    found = shutil.which("slender")
    if found:
        return found
    here = Path.cwd().resolve()
    for folder in [here, *here.parents]:
        candidate = folder / "target" / "release" / "slender"
        if candidate.is_file():
            return str(candidate)
    raise SlenderError([], -1, "no slender binary: set SLENDER_BINARY, put slender on the PATH or build it (cargo build --release)")


def _call(args: Sequence[str], accept_failed_runs: bool = False) -> subprocess.CompletedProcess:
    """Runs ``slender args``; exit 1 (runs failed, rows written) passes when accepted."""
    done = subprocess.run([binary(), *args], capture_output=True, text=True)
    if done.returncode != 0 and not (accept_failed_runs and done.returncode == 1):
        raise SlenderError(args, done.returncode, done.stderr)
    return done


def _settings(set: Optional[Mapping[str, object]]) -> list:
    """``--set KEY=VALUE`` arguments; a value is written as TOML (str quoted)."""
    out = []
    for key, value in (set or {}).items():
        out += ["--set", f"{key}={_toml(value)}"]
    return out


def _toml(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return repr(value)


def _folder(out: Optional[PathLike], name: str) -> Path:
    return Path(out) if out is not None else Path(tempfile.mkdtemp(prefix=f"slender-{name}-"))


def run(scene: PathLike, out: Optional[PathLike] = None, duration: Optional[float] = None,
        set: Optional[Mapping[str, object]] = None) -> Run:
    """Runs ``scene`` (``slender run``) into ``out`` (a new temporary folder when
    none) and reads it back. A run that fails in the simulation is returned with
    ``status == "failed"`` and its results up to the failure; bad input raises
    :class:`SlenderError`."""
    folder = _folder(out, "run")
    args = ["run", str(scene), "--out", str(folder), *_settings(set)]
    if duration is not None:
        args += ["--duration", repr(float(duration))]
    _call(args, accept_failed_runs=True)
    return read_run(folder)


def _name_and_unit(column: str) -> tuple:
    """A timeseries.csv header column, ``"left.displacement [m]"``, as its
    signal name and unit (``""`` when it gives none)."""
    if column.endswith("]") and " [" in column:
        name, unit = column[:-1].rsplit(" [", 1)
        return name, unit
    return column, ""


def read_run(folder: PathLike) -> Run:
    """A run's folder: timeseries.csv (indexed by time, its columns the signals'
    names; the units its header gives in brackets), summary.json and the
    columns' units."""
    folder = Path(folder)
    summary = json.loads((folder / "summary.json").read_text())
    series = folder / "timeseries.csv"
    frame = pd.read_csv(series, float_precision="round_trip") if series.exists() else pd.DataFrame()
    units = dict(summary.get("units", {}))
    if not frame.empty:
        named = [_name_and_unit(c) for c in frame.columns]
        units.update({n: u for n, u in named[1:]})
        frame.columns = [n for n, _ in named]
        frame = frame.set_index("time")
    frame.attrs["units"] = units
    return Run(folder=folder, timeseries=frame, summary=summary, units=units)


def _vary(vary: Mapping[str, Iterable[object]]) -> list:
    args = []
    for key, values in vary.items():
        args += ["--vary", f"{key}=" + ",".join(str(v) for v in values)]
    return args


def study(scene: PathLike, vary: Mapping[str, Iterable[object]], grid: bool = False,
          out: Optional[PathLike] = None, duration: Optional[float] = None,
          repeats: int = 1, reference: Optional[PathLike] = None) -> pd.DataFrame:
    """A convergence and cost study (``slender study``): one row per run, as
    study.csv writes it (failed runs are rows with their ``error``)."""
    folder = _folder(out, "study")
    args = ["study", str(scene), "--out", str(folder), *_vary(vary), "--repeats", str(repeats)]
    if grid:
        args.append("--grid")
    if duration is not None:
        args += ["--duration", repr(float(duration))]
    if reference is not None:
        args += ["--reference", str(reference)]
    _call(args, accept_failed_runs=True)
    return read_study(folder)


def fidelity(scene: PathLike, sections: Mapping[str, Iterable[str]], grid: bool = False,
             out: Optional[PathLike] = None, duration: Optional[float] = None,
             quantities: Optional[Iterable[str]] = None, tolerance: Optional[float] = None) -> pd.DataFrame:
    """A fidelity study (``slender fidelity``): one row per combination, as
    fidelity.csv writes it."""
    folder = _folder(out, "fidelity")
    args = ["fidelity", str(scene), "--out", str(folder)]
    for section, choices in sections.items():
        args += ["--section", f"{section}=" + ",".join(choices)]
    if grid:
        args.append("--grid")
    if duration is not None:
        args += ["--duration", repr(float(duration))]
    if quantities is not None:
        args += ["--quantities", ",".join(quantities)]
    if tolerance is not None:
        args += ["--tolerance", repr(float(tolerance))]
    _call(args, accept_failed_runs=True)
    return read_fidelity(folder)


def read_study(folder: PathLike) -> pd.DataFrame:
    """study.csv of a study's folder."""
    return pd.read_csv(Path(folder) / "study.csv", keep_default_na=False, na_values=["NaN", "nan"], float_precision="round_trip")


def read_fidelity(folder: PathLike) -> pd.DataFrame:
    """fidelity.csv of a fidelity study's folder."""
    return pd.read_csv(Path(folder) / "fidelity.csv", keep_default_na=False, na_values=["NaN", "nan"], float_precision="round_trip")


def read_uq(folder: PathLike) -> tuple:
    """A UQ study's folder: (uq.json as a dictionary, runs.csv as a data frame)."""
    folder = Path(folder)
    report = json.loads((folder / "uq.json").read_text())
    return report, pd.read_csv(folder / "runs.csv", float_precision="round_trip")
