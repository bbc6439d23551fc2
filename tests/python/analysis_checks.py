"""A run's analysis (issue 50) against the field's Python references: the
Welch spectra against scipy.signal.welch, the fatigue damage against the
`rainflow` package (ASTM E1049) with DNV-OS-E301's studless chain curve, the
statistics against pandas, all on the recorded CSV of
examples/oc3_hywind_jonswap.toml.

Usage: analysis_checks.py REPO_ROOT (SLENDER_BINARY names the CLI)."""

import math
import sys
import tempfile
from pathlib import Path

import numpy as np
import rainflow
from scipy import signal

import slender

root = Path(sys.argv[1])
work = Path(tempfile.mkdtemp(prefix="slender-analysis-"))
run = slender.run(root / "examples/oc3_hywind_jonswap.toml", out=work / "oc3")
assert run.status == "completed", run.summary
window = run.timeseries.loc[run.timeseries.index >= 60.0]
dt = float(np.diff(window.index.values).mean())

# Spectra: the same estimate as scipy's Welch with its defaults (Hann,
# half-overlapping segments, the mean removed, one-sided density).
assert not run.spectra.empty
worst = 0.0
for name in ["spar.x", "spar.pitch", "line1_upper.end_tension"]:
    f, p = signal.welch(window[name].values, fs=1.0 / dt, nperseg=round(60.0 / dt))
    assert np.allclose(run.spectra.index.values, f, rtol=1e-12, atol=1e-12), name
    ours = run.spectra[name].values
    worst = max(worst, float(np.max(np.abs(ours - p)) / np.max(p)))
assert worst < 1e-9, worst
moments = run.spectral_moments.loc["spar.x"]
assert abs(moments["peak_period_s"] - 10.0) < 1e-9, moments
print(f"spectra: scipy.signal.welch to {worst:.1e} of the peak density")

# Fatigue: rainflow's cycles, ranges as stress on two chain bars of 62.5 mm,
# Miner's sum with a_D = 6.0e10, m = 3.
tension = window["line1_upper.end_tension"].values
area = 2.0 * math.pi * 0.0625**2 / 4.0
damage = sum(count * (rng / area / 1e6) ** 3 / 6.0e10
             for rng, count in rainflow.count_cycles(tension) if rng > 0)
row = run.fatigue.loc["line1_fairlead"]
assert abs(row["damage"] / damage - 1.0) < 1e-9, (row["damage"], damage)
cycles = sum(c for _, c in rainflow.count_cycles(tension))
assert row["cycles"] == cycles, (row["cycles"], cycles)
print(f"fatigue: damage {row['damage']:.4e} = rainflow's {damage:.4e}, {cycles} cycles")

# Extremes: Rayleigh's most probable maximum from the window's mean and sd.
ext = run.extremes.loc["spar.x"]
x = window["spar.x"]
assert ext["largest_seen"] == x.max()
assert ext["rayleigh_mpm"] > x.mean() + 3.0 * x.std(ddof=0), ext
assert 0.5 < ext["weibull_shape"] < 4.0 and 0.0 < ext["weibull_r_squared"] <= 1.0, ext
# Peaks over threshold: the peaks between up-crossings of the mean, counted
# above mean + 1.4 sd, are the GPD fit's exceedances.
values, mean = x.values, x.mean()
ups = [k for k in range(1, len(values)) if values[k - 1] < mean <= values[k]]
peaks = [values[a:b].max() for a, b in zip(ups, ups[1:])]
threshold = mean + 1.4 * x.std(ddof=0)
above = sum(p > threshold for p in peaks)
assert len(peaks) == ext["peaks"], (len(peaks), ext)
if above >= 10:
    assert abs(ext["gpd_threshold"] - threshold) < 1e-9 * abs(threshold), (ext, threshold)
    assert ext["gpd_exceedances"] == above, ext
    assert ext["gpd_mpm"] > threshold and -0.5 < ext["gpd_shape"] < 0.5, ext
else:
    # Fewer than ten peaks over the threshold: no fit, NaN in the frame.
    assert math.isnan(ext["gpd_mpm"]) and math.isnan(ext["gpd_shape"]), ext
print(f"extremes: spar.x MPM {ext['rayleigh_mpm']:.3f} m (Rayleigh), {ext['weibull_mpm']:.3f} m (Weibull); "
      f"{above} of {len(peaks)} peaks over mean + 1.4 sd, GPD MPM {ext['gpd_mpm']:.3f} m")

# A load-case matrix through the reader: the fatigue over the scatter is the
# table's damages weighed by the sea states' probabilities.
report, table = slender.cases(root / "examples/oc3_hywind_jonswap.toml", seas=[(4, 9, 0.7), (6, 10, 0.3)],
                              seeds=2, duration=120.0, out=work / "cases")
assert list(table.index) == [0, 1, 2, 3] and (table["status"] == "completed").all(), table
means = table.groupby("significant_height")["line1_fairlead/damage_per_year"].mean()
total = 0.7 * means[4.0] + 0.3 * means[6.0]
life = report["fatigue"][0]
assert abs(life["damage_per_year"] / total - 1.0) < 1e-12, (life, total)
print(f"cases: damage per year over the scatter {life['damage_per_year']:.4e} = the table's weighed mean")

# Envelopes: the frame of envelopes.csv holds the summary's extremes.
riser = slender.run(root / "examples/structure_riser.toml", duration=20.0, set={"output.envelopes": {}},
                    out=work / "riser")
frame = riser.envelopes
top = frame[(frame["unit"] == "riser_top") & (frame["field"] == "tension")]
said = next(e for e in riser.summary["envelopes"] if e["unit"] == "riser_top" and e["field"] == "tension")
assert top["max"].max() == said["max"] and top.loc[top["max"].idxmax(), "arc"] == said["max_arc_m"], (top, said)
print(f"envelopes: {len(frame)} rows; riser_top's largest tension {said['max']:.4e} N at {said['max_arc_m']:.1f} m")
