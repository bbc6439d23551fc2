//! A study run's indicator against its group's (or another scene's)
//! reference run: its error, and the components judged against their
//! indicator's largest (issue 27: the study says so, as a run does).

use super::{Judged, Outcome};
use crate::indicators::{Indicator, interpolate};

/// Indicator `j` of `run` against `reference`: the run's signals against the
/// reference run's of the same indicator name, interpolated at the run's
/// recorded times (epsilon NaN when either recorded nothing).
fn against_reference(j: &Judged, run: &Outcome, reference: &Outcome) -> Indicator {
    let nothing = Indicator {
        name: j.name.clone(),
        fidelity: f64::NAN,
        relative_error: f64::NAN,
        floored: Vec::new(),
    };
    let columns = |o: &Outcome| {
        o.columns
            .iter()
            .find(|(name, _)| *name == j.name)
            .map(|(_, cols)| cols.clone())
    };
    let (Some(cols), Some(ref_cols)) = (columns(run), columns(reference)) else {
        return nothing;
    };
    if reference.time.is_empty() || cols.len() != ref_cols.len() {
        return nothing;
    }
    let resampled: Vec<Vec<f64>> = ref_cols
        .iter()
        .map(|r| {
            (run.time.iter())
                .map(|&t| interpolate(&reference.time, r, t))
                .collect()
        })
        .collect();
    let x: Vec<&[f64]> = cols.iter().map(Vec::as_slice).collect();
    let r: Vec<&[f64]> = resampled.iter().map(Vec::as_slice).collect();
    let (time, x) = crate::indicators::window(&run.time, &x, j.from);
    let (_, r) = crate::indicators::window(&run.time, &r, j.from);
    crate::indicators::measure((&j.name, &j.signals), j.norm, time, &x, &r)
}

/// epsilon of indicator `j` in `run`, and the signals judged against its
/// largest component: from the run's own indicator where the reference is in
/// the run, else against the reference run (0 for the reference run against
/// itself; NaN for a run that recorded nothing).
pub(super) fn judged(
    j: &Judged,
    run: &Outcome,
    (reference, is_reference): (&Outcome, bool),
) -> (f64, Vec<String>) {
    if run.error.is_some() && run.time.is_empty() {
        (f64::NAN, Vec::new())
    } else if j.in_run {
        (run.own.iter().find(|i| i.name == j.name)).map_or((f64::NAN, Vec::new()), |i| {
            (i.relative_error, i.floored.clone())
        })
    } else if is_reference {
        (0.0, Vec::new())
    } else {
        let i = against_reference(j, run, reference);
        (i.relative_error, i.floored)
    }
}
