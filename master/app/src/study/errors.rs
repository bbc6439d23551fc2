//! A study run's error against its reference run, and which components were
//! judged against their indicator's largest (issue 27: the study says so, as
//! a run does).

use super::{Judged, Outcome};
use crate::indicators::{interpolate, round_off_components};

/// One column per component of an indicator, over a run's recorded times.
type Columns = Vec<Vec<f64>>;

/// The run's columns of indicator `j` and the reference run's, interpolated
/// at the run's recorded times; None when either recorded nothing.
fn aligned(j: &Judged, run: &Outcome, reference: &Outcome) -> Option<(Columns, Columns)> {
    let columns = |o: &Outcome| {
        o.columns
            .iter()
            .find(|(name, _)| *name == j.name)
            .map(|(_, cols)| cols.clone())
    };
    let (cols, ref_cols) = (columns(run)?, columns(reference)?);
    if reference.time.is_empty() || cols.len() != ref_cols.len() {
        return None;
    }
    let resampled = ref_cols
        .iter()
        .map(|r| {
            (run.time.iter())
                .map(|&t| interpolate(&reference.time, r, t))
                .collect()
        })
        .collect();
    Some((cols, resampled))
}

/// epsilon of indicator `j` under its norm: the run's signals against the
/// reference run's of the same indicator name, interpolated at the run's
/// recorded times (NaN when the reference recorded nothing).
pub(super) fn relative_error(j: &Judged, run: &Outcome, reference: &Outcome) -> f64 {
    let Some((cols, resampled)) = aligned(j, run, reference) else {
        return f64::NAN;
    };
    let x: Vec<&[f64]> = cols.iter().map(Vec::as_slice).collect();
    let r: Vec<&[f64]> = resampled.iter().map(Vec::as_slice).collect();
    crate::indicators::measure(&j.name, j.norm, &run.time, &x, &r).relative_error
}

/// `indicator: signal` of each RMS component of the run judged against its
/// indicator's largest: from the run's own indicators where the reference is
/// in the run, else from the reference run's columns (none for the
/// reference run against itself).
pub(super) fn floored(
    judged: &[Judged],
    run: &Outcome,
    (reference, is_reference): (&Outcome, bool),
) -> Vec<String> {
    let mut out = Vec::new();
    for j in judged
        .iter()
        .filter(|j| j.norm == slender_scene::spec::Norm::Rms)
    {
        let signals: Vec<String> = if j.in_run {
            (run.own.iter().find(|i| i.name == j.name))
                .map(|i| i.floored.clone())
                .unwrap_or_default()
        } else if is_reference {
            Vec::new()
        } else {
            let Some((_, resampled)) = aligned(j, run, reference) else {
                continue;
            };
            let r: Vec<&[f64]> = resampled.iter().map(Vec::as_slice).collect();
            round_off_components(&run.time, &r)
                .into_iter()
                .filter_map(|k| j.signals.get(k).cloned())
                .collect()
        };
        out.extend(signals.into_iter().map(|s| format!("{}: {s}", j.name)));
    }
    out
}
