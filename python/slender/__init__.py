"""Run slender scenes and read their results as pandas data frames.

Over the ``slender`` command line and the files it writes, so a result read
here is the result the command wrote::

    import slender
    run = slender.run("examples/b1_two_masses.toml", out="results/b1")
    run.timeseries["left.displacement"]     # a Series indexed by time (s)
    run.units["left.displacement"]          # "m"
    run.summary["status"]                   # "completed"
    run.statistics                          # with [output] statistics: a row per signal
    run.extremes, run.spectra, run.fatigue  # most probable maxima, Welch spectra, damage
    run.envelopes                           # min, max, mean along each unit (by arc)
    rows = slender.study("examples/b3_force_displacement.toml",
                         vary={"step": [0.001, 0.002, 0.005]})

The binary is ``$SLENDER_BINARY``, else the one installed with this package
(the ``slender`` wheel puts it in the environment's scripts folder, beside
the interpreter), else ``slender`` on the ``PATH``, else
``target/release/slender`` in the current folder or one above it. Without
``out``, a command writes into a temporary folder that is removed once read
(``Run.folder`` is then ``None``).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sysconfig
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
    "uq",
    "read_run",
    "read_study",
    "read_fidelity",
    "read_uq",
    "cases",
    "read_cases",
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

    #: Where the results are (``None``: a temporary folder, read and removed).
    folder: Optional[Path]
    #: The recorded signals, one column each, indexed by time (s).
    timeseries: pd.DataFrame
    #: summary.json as a dictionary (status, error, counters, indicators...).
    summary: dict
    #: The unit of measure of each column ("" for a dimensionless one).
    units: dict = field(default_factory=dict)
    #: With ``statistics.spectra``: spectra.csv, each signal's power spectral
    #: density (its unit squared per Hz) indexed by frequency (Hz).
    spectra: pd.DataFrame = field(default_factory=pd.DataFrame)
    #: With ``[output] envelopes``: envelopes.csv, a row per unit, field and
    #: point along it (unit, field, unit_of_measure, arc, min, max, mean).
    envelopes: pd.DataFrame = field(default_factory=pd.DataFrame)

    @property
    def status(self) -> str:
        """``completed``, ``failed`` or ``interrupted``."""
        return self.summary.get("status", "")

    @property
    def statistics(self) -> pd.DataFrame:
        """Each recorded signal's statistics over the window the scene's
        ``[output] statistics = { from = S }`` asks for: one row per signal
        (mean, std_dev, skewness, kurtosis, min, max,
        zero_up_crossing_period, samples); empty when the scene asks for none.
        """
        return _rows(self.summary.get("statistics", {}), "signal")

    @property
    def extremes(self) -> pd.DataFrame:
        """Each signal's most probable maximum over the duration
        ``statistics.extremes`` asks for: one row per signal (duration_s,
        peaks, largest_seen, rayleigh_mpm, the Weibull fit's weibull_shape,
        weibull_scale, weibull_r_squared, weibull_mpm, and the peaks-over-
        threshold fit's gpd_threshold, gpd_exceedances, gpd_shape, gpd_scale,
        gpd_ks_distance, gpd_mpm; NaN without a fit); empty when the scene
        asks for none."""
        rows = {}
        for signal, row in self.summary.get("extremes", {}).items():
            weibull = row.get("weibull") or {}
            gpd = row.get("gpd") or {}
            rows[signal] = {k: v for k, v in row.items() if k not in ("weibull", "gpd")}
            rows[signal].update({f"weibull_{k}": weibull.get(k, float("nan"))
                                 for k in ("shape", "scale", "r_squared", "mpm")})
            rows[signal].update({f"gpd_{k}": gpd.get(k, float("nan"))
                                 for k in ("threshold", "exceedances", "shape", "scale",
                                           "ks_distance", "mpm")})
        return _rows(rows, "signal")

    @property
    def spectral_moments(self) -> pd.DataFrame:
        """Each spectrum's m0, peak_period_s, zero_crossing_period_s,
        resolution_hz and segments: one row per signal."""
        return _rows(self.summary.get("spectra", {}), "signal")

    @property
    def fatigue(self) -> pd.DataFrame:
        """Each ``[[output.fatigue]]`` entry's window_s, cycles,
        largest_range, damage, damage_per_year and life_years: one row per
        entry; empty when the scene asks for none."""
        return _rows(self.summary.get("fatigue", {}), "name")


def _rows(rows: dict, index: str) -> pd.DataFrame:
    """A summary.json mapping of names to records as a data frame of floats."""
    frame = pd.DataFrame.from_dict(rows, orient="index", dtype=float)
    frame.index.name = index
    return frame


def binary() -> str:
    """The ``slender`` binary this package runs (see the module's help)."""
    given = os.environ.get("SLENDER_BINARY")
    if given:
        return given
    installed = Path(sysconfig.get_path("scripts")) / "slender"
    if installed.is_file():
        return str(installed)
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
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + " }"
    return repr(value)


def _folder(out: Optional[PathLike], name: str) -> Path:
    return Path(out) if out is not None else Path(tempfile.mkdtemp(prefix=f"slender-{name}-"))


def _read_then_tidy(folder: Path, out: Optional[PathLike], read):
    """``read(folder)``; a temporary folder (no ``out``) is removed after."""
    try:
        return read(folder)
    finally:
        if out is None:
            shutil.rmtree(folder, ignore_errors=True)


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
    result = _read_then_tidy(folder, out, read_run)
    if out is None:
        result.folder = None
    return result


def _name_and_unit(column: str) -> tuple:
    """A timeseries.csv header column, ``"left.displacement [m]"``, as its
    signal name and unit (``""`` when it gives none)."""
    if column.endswith("]") and " [" in column:
        name, unit = column[:-1].rsplit(" [", 1)
        return name, unit
    return column, ""


def _summary(folder: Path) -> dict:
    """summary.json, or an error that says why there is none."""
    path = folder / "summary.json"
    if path.exists():
        return json.loads(path.read_text())
    partial = sorted(p.name for p in folder.glob("*.partial"))
    if partial:
        raise FileNotFoundError(f"{folder}: the run did not finish (only {', '.join(partial)}; no summary.json)")
    raise FileNotFoundError(f"{folder}: no summary.json: not a slender run's results folder")


def _series(folder: Path, summary: dict) -> pd.DataFrame:
    """timeseries.csv, refused when torn (cut mid-row, or ending before the
    time the summary says the run reached) or missing where signals were
    recorded."""
    path = folder / "timeseries.csv"
    if not path.exists():
        if summary.get("units"):
            raise FileNotFoundError(f"{path}: missing, though the run recorded {len(summary['units'])} signals")
        return pd.DataFrame()
    text = path.read_text()
    if text and not text.endswith("\n"):
        raise ValueError(f"{path}: torn (its last row is cut off); run the scene again")
    frame = pd.read_csv(path, float_precision="round_trip")
    end = summary.get("start_s", 0.0) + summary.get("simulated_s", 0.0)
    if summary.get("status") == "completed" and len(frame) and abs(frame.iloc[-1, 0] - end) > 1e-9 * max(1.0, abs(end)):
        raise ValueError(f"{path}: torn (it ends at t = {frame.iloc[-1, 0]} s, the run at {end} s)")
    return frame


def read_run(folder: PathLike) -> Run:
    """A run's folder: timeseries.csv (indexed by time, its columns the signals'
    names; the units its header gives in brackets), summary.json and the
    columns' units. A torn or missing file raises (``ValueError``,
    ``FileNotFoundError``) saying which."""
    folder = Path(folder)
    summary = _summary(folder)
    frame = _series(folder, summary)
    units = dict(summary.get("units", {}))
    if not frame.empty:
        named = [_name_and_unit(c) for c in frame.columns]
        units.update({n: u for n, u in named[1:]})
        frame.columns = [n for n, _ in named]
        frame = frame.set_index("time")
    frame.attrs["units"] = units
    spectra = pd.DataFrame()
    if (folder / "spectra.csv").exists():
        spectra = pd.read_csv(folder / "spectra.csv", float_precision="round_trip")
        spectra.columns = [_name_and_unit(c)[0] for c in spectra.columns]
        spectra = spectra.set_index("frequency")
    envelopes = pd.DataFrame()
    if (folder / "envelopes.csv").exists():
        envelopes = pd.read_csv(folder / "envelopes.csv", float_precision="round_trip")
        envelopes = envelopes.rename(columns={"arc [m]": "arc"})
    return Run(folder=folder, timeseries=frame, summary=summary, units=units, spectra=spectra,
               envelopes=envelopes)


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
    return _read_then_tidy(folder, out, read_study)


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
    return _read_then_tidy(folder, out, read_fidelity)


def uq(scene: PathLike, samples: Optional[int] = None, out: Optional[PathLike] = None,
       duration: Optional[float] = None, jobs: Optional[int] = None,
       set: Optional[Mapping[str, object]] = None) -> tuple:
    """An uncertainty study (``slender uq``) of the scene's ``[uncertainty]``:
    (uq.json as a dictionary, runs.csv as a data frame), as :func:`read_uq`."""
    folder = _folder(out, "uq")
    args = ["uq", str(scene), "--out", str(folder), *_settings(set)]
    if samples is not None:
        args += ["--samples", str(int(samples))]
    if duration is not None:
        args += ["--duration", repr(float(duration))]
    if jobs is not None:
        args += ["--jobs", str(int(jobs))]
    _call(args, accept_failed_runs=True)
    return _read_then_tidy(folder, out, read_uq)


def _table(path: Path, text_columns: Sequence[str]) -> pd.DataFrame:
    """A study's CSV: its text columns as written, ``true``/``false`` columns as
    booleans, every other one a number (an empty cell NaN)."""
    frame = pd.read_csv(path, keep_default_na=False, na_values=["NaN", "nan"], float_precision="round_trip",
                        dtype=str)
    for column in frame.columns:
        values = frame[column]
        if column in text_columns:
            continue
        if values.isin(["true", "false"]).all() and len(values):
            frame[column] = values == "true"
        else:
            numbers = pd.to_numeric(values.replace("", "nan"), errors="coerce")
            # A column of words stays words.
            if numbers.notna().sum() >= (values.replace("", pd.NA).notna()).sum():
                frame[column] = numbers
    return frame


def read_study(folder: PathLike) -> pd.DataFrame:
    """study.csv of a study's folder."""
    return _table(Path(folder) / "study.csv", ["group", "setting", "settings", "error", "warnings"])


def read_fidelity(folder: PathLike) -> pd.DataFrame:
    """fidelity.csv of a fidelity study's folder."""
    return _table(Path(folder) / "fidelity.csv", ["combination", "error", "warnings"])


def read_uq(folder: PathLike) -> tuple:
    """A UQ study's folder: (uq.json as a dictionary, runs.csv as a data frame)."""
    folder = Path(folder)
    report = json.loads((folder / "uq.json").read_text())
    return report, pd.read_csv(folder / "runs.csv", float_precision="round_trip")


def cases(scene: PathLike, seas: Iterable[Sequence[float]], headings: Iterable[object] = (),
          seeds: int = 1, out: Optional[PathLike] = None, duration: Optional[float] = None,
          jobs: Optional[int] = None, set: Optional[Mapping[str, object]] = None) -> tuple:
    """A load-case matrix (``slender cases``): ``seas`` as (Hs, Tp,
    probability) triples, ``headings`` as degrees or (degrees, probability)
    pairs; (cases.json as a dictionary, cases.csv as a data frame), as
    :func:`read_cases`. Failed cases are rows marked ``failed``."""
    folder = _folder(out, "cases")
    args = ["cases", str(scene), "--out", str(folder), "--seeds", str(int(seeds)), *_settings(set)]
    for hs, tp, p in seas:
        args += ["--sea", f"{float(hs)!r},{float(tp)!r},{float(p)!r}"]
    for h in headings:
        args += ["--heading", ",".join(repr(float(v)) for v in (h if isinstance(h, (tuple, list)) else [h]))]
    if duration is not None:
        args += ["--duration", repr(float(duration))]
    if jobs is not None:
        args += ["--jobs", str(int(jobs))]
    _call(args, accept_failed_runs=True)
    return _read_then_tidy(folder, out, read_cases)


def read_cases(folder: PathLike) -> tuple:
    """A load-case matrix's folder: (cases.json as a dictionary: its groups,
    design values and fatigue lives; cases.csv as a data frame, a row per
    case indexed by its number)."""
    folder = Path(folder)
    report = json.loads((folder / "cases.json").read_text())
    table = pd.read_csv(folder / "cases.csv", float_precision="round_trip").set_index("case")
    return report, table
