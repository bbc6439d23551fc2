//! A UQ study's runs as CSV (read back to resume) and its expansions as
//! Markdown.

use super::{Run, UqReport};

/// The header of `runs.csv`: index, inputs, outputs.
pub fn header(inputs: &[String], outputs: &[String]) -> String {
    format!("index,{},{}\n", inputs.join(","), outputs.join(","))
}

/// One row of `runs.csv` (values in full precision, so a resumed study reads
/// back the same bits).
pub fn row(index: usize, run: &Run) -> String {
    let values: Vec<String> = run
        .0
        .iter()
        .chain(&run.1)
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
        if fields.len() != 1 + inputs + outputs {
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
            runs.resize(index + 1, (Vec::new(), Vec::new()));
        }
        runs[index] = (values[..inputs].to_vec(), values[inputs..].to_vec());
    }
    runs
}

/// The expansions as Markdown: moments, indices with intervals, the dominant inputs.
pub fn to_markdown(report: &UqReport) -> String {
    let mut out = format!(
        "UQ study of `{}`: {} runs of a {} ({} failed, left out); sparse PCE per output, 95 % bootstrap intervals.\n",
        report.scene, report.samples, report.design, report.failed_runs
    );
    for (k, why) in report.failures.iter().take(5) {
        out += &format!("- run {k} failed: {}\n", why.replace('\n', " "));
    }
    if report.failures.len() > 5 {
        out += &format!(
            "- and {} more (uq.json lists them all)\n",
            report.failures.len() - 5
        );
    }
    for o in &report.outputs {
        out += &format!(
            "\n## {}\n\nE = {:.4} (in [{:.4}, {:.4}]), sd = {:.4}; degree {}, {} terms, LOO error {:.2e}\n\n| input | first-order | total |\n|---|---|---|\n",
            o.name,
            o.mean,
            o.intervals.mean.0,
            o.intervals.mean.1,
            o.sd,
            o.degree,
            o.terms,
            o.loo_error
        );
        for (i, name) in report.inputs.iter().enumerate() {
            let (f, t) = (o.intervals.first_order[i], o.intervals.total[i]);
            out += &format!(
                "| {name} | {:.3} [{:.3}, {:.3}] | {:.3} [{:.3}, {:.3}] |\n",
                o.first_order[i], f.0, f.1, o.total[i], t.0, t.1
            );
        }
        let steps: Vec<String> = o
            .convergence
            .iter()
            .map(|(n, m, sd)| format!("{n} runs: E = {m:.4}, sd = {sd:.4}"))
            .collect();
        out += &format!("\nNested designs: {}.\n", steps.join("; "));
        let [q05, q50, q95] = o.distribution.quantiles;
        out += &format!(
            "\nDistribution (the expansion on {} Sobol' points): median {q50:.4}, 90 % of outcomes in [{q05:.4}, {q95:.4}].\n",
            o.distribution.samples
        );
        let mut ranked: Vec<usize> = (0..report.inputs.len()).collect();
        ranked.sort_by(|&a, &b| o.total[b].total_cmp(&o.total[a]));
        let top: Vec<String> = ranked
            .iter()
            .take(3)
            .map(|&i| format!("{} ({:.2})", report.inputs[i], o.total[i]))
            .collect();
        out += &format!("\nMost influential (total index): {}.\n", top.join(", "));
        if let Some(caution) = poor_fit(o) {
            out += &format!("\n**Caution:** {caution}\n");
        }
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
