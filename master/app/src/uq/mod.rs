//! `slender uq`: a scene's uncertain inputs (`[uncertainty]`) sampled by a
//! maximin Latin hypercube (nested: a larger design doubles the first, keeping
//! its runs), each point a co-simulation run in parallel and appended to
//! `runs.csv` as it finishes (a study that stops resumes where it stopped), then
//! a sparse polynomial chaos per output indicator's fidelity phi with its mean,
//! standard deviation and first-order and total Sobol' indices (95 % bootstrap
//! intervals).

pub mod plot;
pub mod report;
pub mod stability;

use crate::run::{RunOptions, run_scene};
use crate::study::setting::Setting;
use serde::Serialize;
use slender_scene::Scene;
use slender_scene::spec::{DesignKind, UncertaintySpec};
use slender_uq::basis::Family;
use slender_uq::bootstrap::{Intervals, intervals};
use slender_uq::design::{double, latin_hypercube, sobol};
use slender_uq::distribution::{Distribution, distribution};
use slender_uq::pce::{Settings, fit};
use std::path::Path;
use std::sync::Mutex;

/// What a study runs.
#[derive(Clone, Debug)]
pub struct UqPlan {
    /// Design size (default: the scene's `samples`); the scene's `samples`
    /// times a power of two keeps a smaller study's runs.
    pub samples: Option<usize>,
    /// Runs at once.
    pub jobs: usize,
    /// Simulated time of each run (s); the scene's when `None`.
    pub duration: Option<f64>,
    /// Run only shard K of N (1-based): the points whose index is K - 1 modulo
    /// N, and no expansion (`merge` makes it from every shard's runs).
    pub shard: Option<(usize, usize)>,
    /// The most runs the design may have (`--max-runs`).
    pub max_runs: usize,
    /// Scene keys set over the file first (`KEY=VALUE`, `--set`).
    pub overrides: Vec<String>,
}

/// One output's expansion.
#[derive(Clone, Debug, Serialize)]
pub struct OutputResult {
    /// The output's name.
    pub name: String,
    /// Its mean from the expansion.
    pub mean: f64,
    /// Its standard deviation from the expansion.
    pub sd: f64,
    /// First-order Sobol' index of each input.
    pub first_order: Vec<f64>,
    /// Total Sobol' index of each input.
    pub total: Vec<f64>,
    /// Bootstrap intervals of the mean, sd and indices.
    pub intervals: Intervals,
    /// Total degree of the expansion.
    pub degree: usize,
    /// Its number of terms.
    pub terms: usize,
    /// Its leave-one-out error (relative).
    pub loo_error: f64,
    /// (design size, mean, sd) of the expansion fitted on each nested design
    /// (the first `samples` points, then twice as many, ...), the whole last.
    pub convergence: Vec<(usize, f64, f64)>,
    /// The output's distribution from the expansion (16 384 Sobol' points).
    pub distribution: Distribution,
}

/// A study's result.
#[derive(Clone, Debug, Serialize)]
pub struct UqReport {
    /// The scene file.
    pub scene: String,
    /// Design points run.
    pub samples: usize,
    /// How the points were placed, in words.
    pub design: String,
    /// The inputs' names.
    pub inputs: Vec<String>,
    /// How many runs failed for another reason than an unstable loop (left
    /// out of every expansion).
    pub failed_runs: usize,
    /// Each failed run: where and why.
    pub failures: Vec<Failure>,
    /// The runs whose loop went unstable and the inputs that drive it;
    /// `None` when every run was stable.
    pub stability: Option<stability::Stability>,
    /// One result per output, unstable runs counted at
    /// `uncertainty.unstable_fidelity` (the study's answer).
    pub outputs: Vec<OutputResult>,
    /// One result per output over the stable runs only (conditional on
    /// stability); empty when every run was stable.
    pub conditional: Vec<OutputResult>,
}

/// A run that failed for another reason than an unstable loop.
#[derive(Clone, Debug, Serialize)]
pub struct Failure {
    /// Its design index.
    pub index: usize,
    /// Its inputs' values.
    pub inputs: Vec<f64>,
    /// Why it failed.
    pub reason: String,
}

/// One design point's run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Run {
    /// The inputs' values (empty: not run).
    pub inputs: Vec<f64>,
    /// The outputs' phi as measured (NaN when the run failed before it
    /// could be measured).
    pub outputs: Vec<f64>,
    /// When its loop's growth set in (s), if it went unstable.
    pub unstable_from: Option<f64>,
}

impl Run {
    /// Whether the loop went unstable.
    pub fn unstable(&self) -> bool {
        self.unstable_from.is_some()
    }

    /// Whether it ran on a stable loop and every output was measured.
    pub fn stable(&self) -> bool {
        !self.unstable() && self.outputs.iter().all(|v| v.is_finite())
    }

    /// Output `k` as an expansion counts it: the measured phi of a stable
    /// run, `unstable` for an unstable one, `None` for one that failed.
    pub fn counted(&self, k: usize, unstable: f64) -> Option<f64> {
        if self.unstable() {
            Some(unstable)
        } else {
            self.stable().then(|| self.outputs[k])
        }
    }
}

/// A study's scene checked before its first run: the table it varies, its
/// `[uncertainty]` and each input's setting.
pub struct CheckedInputs {
    draft: slender_scene::Draft,
    spec: UncertaintySpec,
    settings: Vec<Setting>,
}

/// Checks the scene's `[uncertainty]` table and that each input's key applies
/// to the scene: a key that does not apply (a unit that is not there) is bad
/// input, probed with its input's median.
pub fn check_inputs(path: &Path, plan: &UqPlan) -> Result<CheckedInputs, crate::AppError> {
    let draft = crate::study::draft_of(path, &plan.overrides)?;
    let scene = crate::study::scene_of(&draft, plan.duration)?;
    let spec = scene
        .spec
        .uncertainty
        .clone()
        .ok_or("a UQ study needs an `[uncertainty]` table in the scene")?;
    let settings = check(&scene, &spec)?;
    for (input, setting) in spec.inputs.iter().zip(&settings) {
        let mut probe = draft.clone();
        let median = toml::Value::Float(input.distribution.from_unit(0.5));
        let origin = format!("the median of `{}`", input.name);
        probe
            .edit(origin, |t| setting.apply(t, &median))
            .and_then(|()| crate::study::scene_of(&probe, plan.duration).map(|_| ()))
            .map_err(|e| format!("`uncertainty.inputs` `{}` ({}): {e}", input.name, input.key))?;
    }
    Ok(CheckedInputs {
        draft,
        spec,
        settings,
    })
}

/// Runs the study, reusing the rows of `runs` (the earlier runs of the same
/// design, or every shard's) and calling `done` with each new run's index as it
/// finishes, and its progress (`[k/N, about T left]` of the new runs). The
/// report is None for a shard.
pub fn run_uq(
    path: &Path,
    plan: &UqPlan,
    earlier: &[Run],
    done: impl Fn(usize, &Run, &str) + Sync,
) -> Result<(Option<UqReport>, Vec<Run>), crate::AppError> {
    run_checked(path, plan, &check_inputs(path, plan)?, earlier, done)
}

/// [`run_uq`] on inputs [`check_inputs`] has already checked.
pub fn run_checked(
    path: &Path,
    plan: &UqPlan,
    inputs: &CheckedInputs,
    earlier: &[Run],
    done: impl Fn(usize, &Run, &str) + Sync,
) -> Result<(Option<UqReport>, Vec<Run>), crate::AppError> {
    let CheckedInputs {
        draft,
        spec,
        settings,
    } = inputs;
    let samples = plan.samples.unwrap_or(spec.samples);
    if samples > plan.max_runs {
        return Err(crate::too_many_runs("the design", samples, plan.max_runs).into());
    }
    let points = points_of(spec, samples)?;
    let order: Vec<usize> = match plan.shard {
        Some((k, n)) if k >= 1 && k <= n => (k - 1..points.len()).step_by(n).collect(),
        Some((k, n)) => return Err(format!("--shard {k}/{n}: expected K in 1..=N").into()),
        None => (0..points.len()).collect(),
    };
    let fresh = Mutex::new(());
    let tasks: Vec<usize> = (0..order.len()).collect();
    // An earlier run of the same point is kept; a failed one is tried again.
    let kept = |k: usize| {
        let same = |r: &&Run| r.inputs == points[k] && (r.stable() || r.unstable());
        earlier.get(k).filter(same)
    };
    let counter =
        crate::progress::Progress::new(order.iter().filter(|&&k| kept(k).is_none()).count());
    let outcomes = crate::parallel::run_all(&order, &tasks, plan.jobs, |&k| {
        if let Some(run) = kept(k) {
            return (run.clone(), None);
        }
        let outcome = run_one(draft, settings, &points[k], plan.duration, spec);
        let ((outputs, unstable_from), why) = match outcome {
            Ok(measured) => (measured, None),
            Err(reason) => {
                let failure = Failure {
                    index: k,
                    inputs: points[k].clone(),
                    reason,
                };
                ((vec![f64::NAN; spec.outputs.len()], None), Some(failure))
            }
        };
        let run = Run {
            inputs: points[k].clone(),
            outputs,
            unstable_from,
        };
        // One writer at a time: the caller appends the row to its file.
        let _turn = fresh.lock().unwrap_or_else(|e| e.into_inner());
        done(k, &run, &counter.tick(true));
        (run, why)
    });
    let failures: Vec<Failure> = outcomes.iter().filter_map(|o| o.1.clone()).collect();
    let runs: Vec<Run> = outcomes.into_iter().map(|o| o.0).collect();
    crate::interrupt::stop_if_requested(&runs, |r| r.stable() || r.unstable())?;
    if plan.shard.is_some() {
        let shard: Vec<Run> = order.iter().zip(runs).map(|(_, r)| r).collect();
        return Ok((None, shard_rows(&order, shard)));
    }
    let mut report = expand(path, spec, &runs)?;
    report.failures = failures;
    Ok((Some(report), runs))
}

/// The design's points of `samples` runs, in the inputs' own values.
fn points_of(spec: &UncertaintySpec, samples: usize) -> Result<Vec<Vec<f64>>, String> {
    let design = design_of(spec, samples)?;
    Ok(design
        .iter()
        .map(|u| {
            spec.inputs
                .iter()
                .zip(u)
                .map(|(i, &u)| i.distribution.from_unit(u))
                .collect()
        })
        .collect())
}

/// A shard's runs at their design indices (the others empty).
fn shard_rows(order: &[usize], runs: Vec<Run>) -> Vec<Run> {
    let mut all = vec![Run::default(); order.last().map_or(0, |k| k + 1)];
    for (&k, run) in order.iter().zip(runs) {
        all[k] = run;
    }
    all
}

/// How many times the scene's first design (`uncertainty.samples` points)
/// doubles to `samples` points; `None` when no whole number of doublings does.
fn doublings(spec: &UncertaintySpec, samples: usize) -> Option<usize> {
    let mut n = spec.samples.max(1);
    let mut doublings = 0;
    while n < samples {
        n = n.saturating_mul(2);
        doublings += 1;
    }
    (n == samples).then_some(doublings)
}

/// Whether the design of `samples` points nests the smaller designs (its first
/// `uncertainty.samples` points, twice as many, ... are designs themselves):
/// every Sobol' design, and a Latin hypercube the scene's first one doubles to.
fn nests(spec: &UncertaintySpec, samples: usize) -> bool {
    spec.design == DesignKind::Sobol || doublings(spec, samples).is_some()
}

/// The design of `samples` points (at least 4): the first design doubled as
/// often as it takes (a Latin hypercube splits its strata; a Sobol' sequence
/// goes on); any other size of Latin hypercube is one of its own, which keeps
/// no earlier design's runs.
fn design_of(spec: &UncertaintySpec, samples: usize) -> Result<Vec<Vec<f64>>, String> {
    if samples < 4 {
        return Err(format!("--samples {samples}: expected at least 4 runs"));
    }
    let dims = spec.inputs.len();
    if spec.design == DesignKind::Sobol {
        return sobol(samples, dims, spec.seed).map_err(|e| format!("--samples {samples}: {e}"));
    }
    let Some(doublings) = doublings(spec, samples) else {
        return latin_hypercube(samples, dims, 20, spec.seed).map_err(|e| e.to_string());
    };
    let mut design =
        latin_hypercube(spec.samples, dims, 20, spec.seed).map_err(|e| e.to_string())?;
    for k in 0..doublings {
        design =
            double(&design, spec.seed.wrapping_add(1 + k as u64)).map_err(|e| e.to_string())?;
    }
    Ok(design)
}

/// Each input's key as a study setting; the error names what does not fit.
fn check(scene: &Scene, spec: &UncertaintySpec) -> Result<Vec<Setting>, String> {
    if spec.inputs.is_empty() || spec.outputs.is_empty() || spec.samples < 4 {
        return Err("`uncertainty`: expected inputs, outputs and samples >= 4".into());
    }
    for name in &spec.outputs {
        if !scene.spec.output.indicators.iter().any(|i| &i.name == name) {
            return Err(format!(
                "`uncertainty.outputs`: `{name}` is not an indicator of the scene ([[output.indicators]])"
            ));
        }
    }
    spec.inputs
        .iter()
        .map(|i| {
            i.distribution
                .validate()
                .map_err(|e| format!("`uncertainty.inputs` `{}`: {e}", i.name))?;
            i.key
                .parse::<Setting>()
                .map_err(|e| format!("`uncertainty.inputs` `{}`: {e}", i.name))
        })
        .collect()
}

/// One run's outputs' phi as measured and, when its loop went unstable
/// (grown past `unstable_growth`: [`stability::divergence`], whether the
/// run stopped or not), when the growth set in (s); the
/// error says why it cannot run or failed for another reason.
fn run_one(
    draft: &slender_scene::Draft,
    settings: &[Setting],
    point: &[f64],
    duration: Option<f64>,
    spec: &UncertaintySpec,
) -> Result<(Vec<f64>, Option<f64>), String> {
    let mut draft = draft.clone();
    let at: Vec<String> = (settings.iter().zip(point))
        .map(|(s, x)| format!("{s}={x}"))
        .collect();
    draft
        .edit(format!("the design point {}", at.join(" ")), |table| {
            (settings.iter().zip(point))
                .try_for_each(|(s, &x)| s.apply(table, &toml::Value::Float(x)))
        })
        .map_err(|e| e.to_string())?;
    let scene = crate::study::scene_of(&draft, duration).map_err(|e| e.to_string())?;
    let options = RunOptions {
        output_dir: None,
        progress: false,
        realtime: false,
    };
    let r = run_scene(&scene, &options).map_err(|e| e.to_string())?;
    let stopped = r.summary.error.is_some();
    let unstable_from = stability::divergence(&scene, &r.recorder, (&spec.outputs, stopped))
        .filter(|d| d.ratio >= spec.unstable_growth)
        .map(|d| d.onset);
    if let (Some(e), None) = (r.summary.error, unstable_from) {
        return Err(e);
    }
    let phi = (spec.outputs.iter())
        .map(|name| {
            (r.summary.indicators.iter())
                .find(|i| &i.name == name)
                .map_or(f64::NAN, |i| i.fidelity)
        })
        .collect();
    Ok((phi, unstable_from))
}

/// The runs' inputs as the families' standard variables.
fn standard(spec: &UncertaintySpec, runs: &[&Run]) -> Vec<Vec<f64>> {
    runs.iter()
        .map(|r| {
            spec.inputs
                .iter()
                .zip(&r.inputs)
                .map(|(i, &x)| i.distribution.to_standard(x))
                .collect()
        })
        .collect()
}

/// Which value of an output an expansion fits for a run (`None`: left out).
type Counted<'a> = &'a dyn Fn(&Run, usize) -> Option<f64>;

/// The runs an expansion of output `k` fits and their values.
fn fitted<'a>(runs: &'a [Run], k: usize, value: Counted) -> (Vec<&'a Run>, Vec<f64>) {
    (runs.iter())
        .filter_map(|r| value(r, k).map(|y| (r, y)))
        .unzip()
}

/// Mean and sd of output `k` from each nested design smaller than the whole:
/// the first `samples` runs, twice as many, ... (like seed 000's Fig. 9; the
/// caller adds the whole design's, already fitted).
fn convergence(
    spec: &UncertaintySpec,
    families: &[Family],
    (runs, value): (&[Run], Counted),
    k: usize,
) -> Result<Vec<(usize, f64, f64)>, String> {
    let mut out = Vec::new();
    if !nests(spec, runs.len()) {
        return Ok(out);
    }
    let mut size = spec.samples;
    while size < runs.len() {
        let (ok, y) = fitted(&runs[..size], k, value);
        let pce = fit(families, &standard(spec, &ok), &y, Settings::default())
            .map_err(|e| format!("{} on {size} runs: {e}", spec.outputs[k]))?;
        out.push((size, pce.mean(), pce.variance().sqrt()));
        size *= 2;
    }
    Ok(out)
}

/// The expansion of each output over the runs `value` counts.
fn expansions(
    spec: &UncertaintySpec,
    runs: &[Run],
    value: Counted,
) -> Result<Vec<OutputResult>, String> {
    let families: Vec<_> = (spec.inputs.iter())
        .map(|i| i.distribution.family())
        .collect();
    let marginals: Vec<_> = spec.inputs.iter().map(|i| i.distribution.clone()).collect();
    let mut outputs = Vec::new();
    for (k, name) in spec.outputs.iter().enumerate() {
        let (ok, y) = fitted(runs, k, value);
        let xi = standard(spec, &ok);
        let pce =
            fit(&families, &xi, &y, Settings::default()).map_err(|e| format!("{name}: {e}"))?;
        let ci =
            intervals(&pce, (&xi, &y), 200, 0.95, spec.seed).map_err(|e| format!("{name}: {e}"))?;
        let spread = distribution(&pce, &marginals, 1 << 14, 40, spec.seed)
            .map_err(|e| format!("{name}: {e}"))?;
        let dims = families.len();
        outputs.push(OutputResult {
            name: name.clone(),
            mean: pce.mean(),
            sd: pce.variance().sqrt(),
            first_order: (0..dims).map(|i| pce.first_order(i)).collect(),
            total: (0..dims).map(|i| pce.total(i)).collect(),
            intervals: ci,
            degree: pce.degree,
            terms: pce.coefficients.len(),
            loo_error: pce.loo_error,
            convergence: convergence(spec, &families, (runs, value), k)?
                .into_iter()
                .chain([(runs.len(), pce.mean(), pce.variance().sqrt())])
                .collect(),
            distribution: spread,
        });
    }
    Ok(outputs)
}

/// The study's expansions: unstable runs counted at the scene's
/// `unstable_fidelity` and, when there are any, the stable runs alone.
fn expand(path: &Path, spec: &UncertaintySpec, runs: &[Run]) -> Result<UqReport, String> {
    let names: Vec<String> = spec.inputs.iter().map(|i| i.name.clone()).collect();
    let floor = spec.unstable_fidelity;
    let stability = stability::assess(&names, runs, spec.unstable_growth, floor);
    let outputs = expansions(spec, runs, &|r, k| r.counted(k, floor))?;
    let conditional = match stability {
        Some(_) => expansions(spec, runs, &|r, k| r.stable().then(|| r.outputs[k]))?,
        None => Vec::new(),
    };
    Ok(UqReport {
        scene: path.display().to_string(),
        samples: runs.len(),
        design: match (spec.design, nests(spec, runs.len())) {
            (DesignKind::Lhs, true) => "maximin Latin hypercube".into(),
            (DesignKind::Lhs, false) => format!(
                "maximin Latin hypercube of its own ({} is not uncertainty.samples = {} times a power of two, so it nests no smaller design)",
                runs.len(),
                spec.samples
            ),
            (DesignKind::Sobol, _) => "Owen-scrambled Sobol' sequence".into(),
        },
        inputs: names,
        failed_runs: runs.iter().filter(|r| !r.stable() && !r.unstable()).count(),
        failures: Vec::new(),
        stability,
        outputs,
        conditional,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(design: &str) -> UncertaintySpec {
        toml::from_str(&format!(
            r#"samples = 8
design = "{design}"
outputs = ["phi1"]
inputs = [
  {{ name = "a", key = "units.x.parameters.a", distribution = {{ kind = "uniform", low = 0.0, high = 1.0 }} }},
  {{ name = "b", key = "units.x.parameters.b", distribution = {{ kind = "uniform", low = 0.0, high = 1.0 }} }},
]"#
        ))
        .unwrap()
    }

    #[test]
    fn both_designs_grow_keeping_their_points_and_take_any_size() {
        for kind in ["lhs", "sobol"] {
            let s = spec(kind);
            let small = design_of(&s, 8).unwrap();
            let large = design_of(&s, 32).unwrap();
            assert_eq!(&large[..8], &small[..], "{kind}");
            slender_uq::design::check_lhs(&large).unwrap();
            assert!(design_of(&s, 3).unwrap_err().contains("at least 4"));
        }
        // Off the doubling ladder: a Latin hypercube of its own size (every
        // stratum once), or the Sobol' sequence's first points.
        let lhs = design_of(&spec("lhs"), 24).unwrap();
        assert_eq!(lhs.len(), 24);
        slender_uq::design::check_lhs(&lhs).unwrap();
        assert!(!nests(&spec("lhs"), 24) && nests(&spec("lhs"), 64));
        let sobol = design_of(&spec("sobol"), 24).unwrap();
        assert_eq!(&sobol[..8], &design_of(&spec("sobol"), 8).unwrap()[..]);
        assert_ne!(design_of(&spec("lhs"), 8), design_of(&spec("sobol"), 8));
        let bad = toml::from_str::<UncertaintySpec>(
            "samples = 8\ndesign = \"halton\"\noutputs = []\ninputs = []",
        );
        assert!(bad.unwrap_err().to_string().contains("lhs"));
    }
}
