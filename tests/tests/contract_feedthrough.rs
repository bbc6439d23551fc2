//! Honest output dependencies (issue 29): every kind declares, per output, the
//! inputs it depends on at a communication point (`Port::depends_on`, written
//! to an FMU's `ModelStructure`). A master builds its loop graph from them, so
//! a declared dependency that is not there shows a loop that is not there, and
//! a missing one hides a real loop. Checked on a started sample of every kind:
//! each input nudged in turn, the outputs read again without a step.

use slender_tests::samples::{inputs_at, samples, started};
use std::collections::BTreeSet;

/// (output, input) pairs whose outputs move when the input moves alone: by
/// more than round-off of the output's value, and by more than 1e-9 of the
/// output's largest sensitivity to any input (so a sum's round-off is not
/// taken for a dependency, and a weak coupling is).
fn observed(driver: &mut slender_units::Driver, at: &[f64]) -> BTreeSet<(usize, usize)> {
    let n_out = driver.description().outputs.len();
    let mut base = vec![0.0; n_out];
    let mut moved = vec![0.0; n_out];
    driver.set_inputs(at).unwrap();
    driver.outputs(&mut base).unwrap();
    // Per output and input: the largest change per unit of input.
    let mut sensitivity = vec![vec![0.0f64; at.len()]; n_out];
    // Small and large nudges both ways: an output that switches (a flag, a
    // contact) may move for some of them only.
    for i in 0..at.len() {
        for factor in [1e-2, -1e-2, 10.0, -10.0] {
            let mut nudged = at.to_vec();
            let nudge = factor * at[i].abs().max(1.0);
            nudged[i] += nudge;
            driver.set_inputs(&nudged).unwrap();
            driver.outputs(&mut moved).unwrap();
            for (o, (a, b)) in base.iter().zip(&moved).enumerate() {
                let change = if a.is_nan() != b.is_nan() {
                    f64::INFINITY
                } else if (a - b).abs() > 1e-14 * a.abs().max(b.abs()) {
                    (a - b).abs() / nudge.abs()
                } else {
                    0.0
                };
                sensitivity[o][i] = sensitivity[o][i].max(change);
            }
        }
    }
    driver.set_inputs(at).unwrap();
    let mut pairs = BTreeSet::new();
    for (o, row) in sensitivity.iter().enumerate() {
        let largest = row
            .iter()
            .filter(|s| s.is_finite())
            .fold(0.0f64, |m, s| m.max(*s));
        for (i, s) in row.iter().enumerate() {
            if *s > 0.0 && (s.is_infinite() || *s > 1e-9 * largest) {
                pairs.insert((o, i));
            }
        }
    }
    pairs
}

/// (output, input) pairs the kind declares.
fn declared(driver: &slender_units::Driver) -> BTreeSet<(usize, usize)> {
    let outputs = &driver.description().outputs;
    outputs
        .iter()
        .enumerate()
        .flat_map(|(o, p)| p.depends_on.iter().map(move |&i| (o, i)))
        .collect()
}

#[test]
fn every_kind_declares_the_output_dependencies_its_outputs_have() {
    let dir = tempfile::tempdir().unwrap();
    let mut wrong = Vec::new();
    for (kind, config) in samples(dir.path()) {
        let (mut driver, start, _) = started(&config, 3);
        let at = inputs_at(&start, 3);
        let seen = observed(&mut driver, &at);
        let said = declared(&driver);
        let description = driver.description().clone();
        let name = |(o, i): &(usize, usize)| {
            format!(
                "{} on {}",
                description.outputs[*o].name, description.inputs[*i].name
            )
        };
        for pair in seen.difference(&said) {
            wrong.push(format!("{kind}: {} undeclared", name(pair)));
        }
        for pair in said.difference(&seen) {
            wrong.push(format!("{kind}: {} declared, not there", name(pair)));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
