//! A UQ study's runs as CSV (read back to resume) and its expansions as
//! Markdown.

use super::{Run, UqReport};

/// The header of `runs.csv`: index, inputs, outputs, and when an unstable
/// run's growth set in (NaN for the others).
pub fn header(inputs: &[String], outputs: &[String]) -> String {
    format!(
        "index,{},{},unstable_from\n",
        inputs.join(","),
        outputs.join(",")
    )
}

/// One row of `runs.csv` (values in full precision, so a resumed study reads
/// back the same bits).
pub fn row(index: usize, run: &Run) -> String {
    let onset = run.unstable_from.unwrap_or(f64::NAN);
    let values: Vec<String> = (run.inputs.iter())
        .chain(&run.outputs)
        .chain([&onset])
        .map(|v| format!("{v:e}"))
        .collect();
    format!("{index},{}\n", values.join(","))
}

/// The runs of an earlier `runs.csv` by index (a missing index is an empty run
/// that will not match); rows that do not parse are left out.
pub fn read_runs(text: &str, inputs: usize, outputs: usize) -> Vec<Run> {
    let mut runs: Vec<Run> = Vec::new();
    for line in text.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != 2 + inputs + outputs {
            continue;
        }
        let (Ok(index), Ok(values)) = (
            fields[0].parse::<usize>(),
            fields[1..]
                .iter()
                .map(|f| f.parse::<f64>())
                .collect::<Result<Vec<f64>, _>>(),
        ) else {
            continue;
        };
        if runs.len() <= index {
            runs.resize(index + 1, Run::default());
        }
        let onset = values[inputs + outputs];
        runs[index] = Run {
            inputs: values[..inputs].to_vec(),
            outputs: values[inputs..inputs + outputs].to_vec(),
            unstable_from: onset.is_finite().then_some(onset),
        };
    }
    runs
}

/// A run's outcome in words for the progress line: its phi, or that its loop
/// went unstable and when, or that it failed (its reason is in the report).
pub fn outcome(run: &Run) -> String {
    let phi: Vec<String> = run.outputs.iter().map(|v| format!("{v:.4e}")).collect();
    match run.unstable_from {
        Some(t) => format!(
            "unstable from t = {t:.2} s (measured phi {})",
            phi.join(", ")
        ),
        None if run.stable() => phi.join(", "),
        None => "failed (left out; uq.md says why)".into(),
    }
}

/// The expansions as Markdown: the runs that went unstable or failed, then
/// per output the moments, indices with intervals and the dominant inputs
/// (unstable runs counted as failures of fidelity), then the same over the
/// stable runs alone.
pub fn to_markdown(report: &UqReport) -> String {
    let unstable = report.stability.as_ref().map_or(0, |s| s.unstable_runs);
    let mut out = format!(
        "UQ study of `{}`: {} runs of a {} ({unstable} unstable, {} failed and left out); sparse PCE per output, 95 % bootstrap intervals.\n",
        report.scene, report.samples, report.design, report.failed_runs
    );
    for f in report.failures.iter().take(5) {
        let at: Vec<String> = (report.inputs.iter().zip(&f.inputs))
            .map(|(name, x)| format!("{name} = {x:.4e}"))
            .collect();
        out += &format!(
            "- run {} ({}) failed: {}\n",
            f.index,
            at.join(", "),
            f.reason.replace('\n', " ")
        );
    }
    if report.failures.len() > 5 {
        out += &format!(
            "- and {} more (uq.json lists them all)\n",
            report.failures.len() - 5
        );
    }
    if let Some(s) = &report.stability {
        out += &stability_markdown(s);
    }
    for o in &report.outputs {
        out += &output_markdown(o, &report.inputs, "");
    }
    if !report.conditional.is_empty() {
        out += "\nOver the stable runs alone (conditional on stability): the moments a study that leaves the unstable runs out reports; its expansion still spans the inputs where the loop is unstable, extrapolated there.\n";
    }
    for o in &report.conditional {
        out += &output_markdown(o, &report.inputs, ", conditional on stability");
    }
    out
}

/// The stability section: how often the loop went unstable, which inputs
/// drive it, and when it set in.
fn stability_markdown(s: &super::stability::Stability) -> String {
    let mut out = format!(
        "\n## Stability\n\n{} of {} runs went unstable (an output's error past {} times its reference's peak, or a run stopped with a recorded signal grown past that many times its median window peak): probability of instability {:.3} (95 % interval [{:.3}, {:.3}]). The expansions count them at phi = {}; those over the stable runs alone follow.\n\n| input | KS distance | p-value | mean where unstable | mean where stable |\n|---|---|---|---|---|\n",
        s.unstable_runs,
        s.unstable_runs + s.stable_runs,
        s.growth,
        s.probability,
        s.interval.0,
        s.interval.1,
        s.counted_as
    );
    for d in &s.drivers {
        out += &format!(
            "| {} | {:.3} | {:.1e} | {:.4} | {:.4} |\n",
            d.input, d.distance, d.p_value, d.mean_unstable, d.mean_stable
        );
    }
    let onsets: Vec<String> = (s.onsets.iter().take(10))
        .map(|(k, t)| format!("run {k} from {t:.2} s"))
        .collect();
    out += &format!(
        "\nGrowth set in at: {}{}.\n",
        onsets.join(", "),
        if s.onsets.len() > 10 {
            " and more (runs.csv's `unstable_from` lists them all)"
        } else {
            ""
        }
    );
    out
}

/// One output's expansion: moments, indices, nested designs, distribution,
/// the dominant inputs and a caution on a poor fit.
fn output_markdown(o: &super::OutputResult, inputs: &[String], qualifier: &str) -> String {
    let mut out = format!(
        "\n## {}{qualifier}\n\nE = {:.4} (in [{:.4}, {:.4}]), sd = {:.4}; degree {}, {} terms, LOO error {:.2e}\n\n| input | first-order | total |\n|---|---|---|\n",
        o.name,
        o.mean,
        o.intervals.mean.0,
        o.intervals.mean.1,
        o.sd,
        o.degree,
        o.terms,
        o.loo_error
    );
    for (i, name) in inputs.iter().enumerate() {
        let (f, t) = (o.intervals.first_order[i], o.intervals.total[i]);
        out += &format!(
            "| {name} | {:.3} [{:.3}, {:.3}] | {:.3} [{:.3}, {:.3}] |\n",
            o.first_order[i], f.0, f.1, o.total[i], t.0, t.1
        );
    }
    let steps: Vec<String> = (o.convergence.iter())
        .map(|(n, m, sd)| format!("{n} runs: E = {m:.4}, sd = {sd:.4}"))
        .collect();
    out += &format!("\nNested designs: {}.\n", steps.join("; "));
    let [q05, q50, q95] = o.distribution.quantiles;
    out += &format!(
        "\nDistribution (the expansion on {} Sobol' points): median {q50:.4}, 90 % of outcomes in [{q05:.4}, {q95:.4}].\n",
        o.distribution.samples
    );
    let mut ranked: Vec<usize> = (0..inputs.len()).collect();
    ranked.sort_by(|&a, &b| o.total[b].total_cmp(&o.total[a]));
    let top: Vec<String> = (ranked.iter().take(3))
        .map(|&i| format!("{} ({:.2})", inputs[i], o.total[i]))
        .collect();
    out += &format!("\nMost influential (total index): {}.\n", top.join(", "));
    if let Some(caution) = poor_fit(o) {
        out += &format!("\n**Caution:** {caution}\n");
    }
    out
}

/// The largest leave-one-out error (relative to the output's variance) at
/// which an expansion's moments, indices and ranking are reported without a
/// caution: above it the expansion misses more than a tenth of the variance.
pub const LOO_TRUSTED: f64 = 0.1;

/// Why an output's expansion should not be trusted, when its leave-one-out
/// error is above [`LOO_TRUSTED`] (or not a number), with the design size to
/// try next: twice the design's (the error of a sparse expansion falls with
/// the design; how fast depends on the output).
pub fn poor_fit(o: &super::OutputResult) -> Option<String> {
    let size = o.convergence.last().map_or(0, |c| c.0);
    (o.loo_error.is_nan() || o.loo_error > LOO_TRUSTED).then(|| {
        format!(
            "`{}`: the expansion's leave-one-out error is {:.2} (above {LOO_TRUSTED}) on {size} runs: it explains the output poorly, so its moments, indices and ranking are not reliable; try --samples {} (twice the design; the scene's `samples` times a power of two keeps the runs made) and see whether the error falls, or study fewer inputs",
            o.name,
            o.loo_error,
            2 * size
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_read_back_as_written_unstable_or_not() {
        let runs = [
            Run {
                inputs: vec![0.1, 1.0 / 3.0],
                outputs: vec![1.25],
                unstable_from: None,
            },
            Run {
                inputs: vec![0.2, 0.7],
                outputs: vec![-1.5],
                unstable_from: Some(6.93),
            },
            Run {
                inputs: vec![0.3, 0.9],
                outputs: vec![f64::NAN],
                unstable_from: None,
            },
        ];
        let names = ["a".to_string(), "b".to_string()];
        let mut text = header(&names, &["phi".to_string()]);
        assert!(text.ends_with("phi,unstable_from\n"), "{text}");
        for (k, r) in runs.iter().enumerate() {
            text += &row(k, r);
        }
        let back = read_runs(&text, 2, 1);
        assert_eq!(back[..2], runs[..2]);
        assert!(back[2].outputs[0].is_nan() && !back[2].stable() && !back[2].unstable());
        assert_eq!(outcome(&runs[0]), "1.2500e0");
        assert!(outcome(&runs[1]).starts_with("unstable from t = 6.93 s"));
        assert!(outcome(&runs[2]).starts_with("failed"));
    }
}
