//! A sum of sines evaluated fast where it is long: a sea state's components
//! lie on one frequency grid, w_k = w_0 + k dw, so their phasors
//! exp(i w_k t) follow from two (exp(i w_0 t) and exp(i dw t)) by one complex
//! product each, instead of a sine and a cosine per component and time. A
//! 3-hour sea that does not repeat needs thousands of components (dw at most
//! 2 pi / 10 800 s), evaluated at every step of a vessel's motion: summed so,
//! the motion costs a small part of the line it moves.
//!
//! The recurrence's rounding grows with k by about one unit in the last
//! place per product (4e-13 relative after 4 000 components), below what
//! evaluating w_k t + phi directly loses at t = 10 800 s (an argument of 3e4
//! rad carries 4e-12 rad of rounding).

use super::sine::Sine;

/// The shortest run of steady sines on one grid that is summed by phasors
/// (shorter runs cost less summed directly).
const SHORTEST_GRID: usize = 16;

/// Sines on one frequency grid: w_k = first + k step, each term's
/// (amplitude cos phase, amplitude sin phase, w_k).
#[derive(Clone, Debug, PartialEq)]
struct Grid {
    first: f64,
    step: f64,
    terms: Vec<[f64; 3]>,
}

/// A sum of sines, split into grids summed by phasors and the others summed
/// one by one. Built once from the sines; `eval` allocates nothing.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SineSeries {
    grids: Vec<Grid>,
    others: Vec<Sine>,
    len: usize,
}

impl SineSeries {
    /// The series of `sines` (their order kept within each grid).
    pub fn new(sines: &[Sine]) -> SineSeries {
        let mut series = SineSeries {
            len: sines.len(),
            ..SineSeries::default()
        };
        let mut rest = sines;
        while !rest.is_empty() {
            let run = grid_run(rest);
            if run >= SHORTEST_GRID {
                series.grids.push(grid(&rest[..run]));
                rest = &rest[run..];
            } else {
                series.others.push(rest[0].clone());
                rest = &rest[1..];
            }
        }
        series
    }

    /// How many sines it sums.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether it sums none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The sum and its first two time derivatives at t (s).
    pub fn eval(&self, t: f64) -> [f64; 3] {
        let mut out = [0.0; 3];
        self.add_to(&mut out, t);
        out
    }

    /// Adds the sum and its two time derivatives at t (s) to `out`: the
    /// grids first, then the other sines one by one in their order (so a
    /// series without a grid adds exactly as a loop over its sines does).
    pub fn add_to(&self, out: &mut [f64; 3], t: f64) {
        for g in &self.grids {
            let (mut sin, mut cos) = (g.first * t).sin_cos();
            let (turn_sin, turn_cos) = (g.step * t).sin_cos();
            for &[a_cos, a_sin, w] in &g.terms {
                // a sin(w t + phi) and a cos(w t + phi).
                let value = sin * a_cos + cos * a_sin;
                let rate = cos * a_cos - sin * a_sin;
                out[0] += value;
                out[1] += w * rate;
                out[2] -= w * w * value;
                (sin, cos) = (
                    sin * turn_cos + cos * turn_sin,
                    cos * turn_cos - sin * turn_sin,
                );
            }
        }
        for s in &self.others {
            let v = s.eval(t);
            (0..3).for_each(|i| out[i] += v[i]);
        }
    }
}

/// The length of the run of steady sines at the head of `sines` whose
/// frequencies step evenly (to a few units in the last place of the
/// largest); 0 when the first sine decays.
fn grid_run(sines: &[Sine]) -> usize {
    let steady = sines.iter().take_while(|s| s.decay == 0.0).count();
    if steady < 2 {
        return steady;
    }
    let w = |k: usize| sines[k].angular_frequency;
    let step = w(1) - w(0);
    if step.is_nan() || step <= 0.0 {
        return 1;
    }
    // A loose pass finds the run; tight ones with the run's own mean step
    // cut it where a frequency is off the grid by more than rounding.
    let mut run = (0..steady)
        .take_while(|&k| (w(k) - w(0) - k as f64 * step).abs() <= 1e-6 * step)
        .count();
    while run > 2 {
        let step = (w(run - 1) - w(0)) / (run - 1) as f64;
        let tolerance = 8.0 * f64::EPSILON * w(run - 1).abs().max(w(0).abs());
        match (0..run).find(|&k| (w(k) - w(0) - k as f64 * step).abs() > tolerance) {
            Some(off) => run = off.max(1),
            None => break,
        }
    }
    run
}

/// The grid of a run `grid_run` found.
fn grid(run: &[Sine]) -> Grid {
    let first = run[0].angular_frequency;
    let step = (run[run.len() - 1].angular_frequency - first) / (run.len() - 1) as f64;
    let terms = run
        .iter()
        .map(|s| {
            let (sin, cos) = s.phase.sin_cos();
            [s.amplitude * cos, s.amplitude * sin, s.angular_frequency]
        })
        .collect();
    Grid { first, step, terms }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sea::spectrum::{Spectrum, SpectrumKind};

    /// The direct sum, sine by sine.
    fn direct(sines: &[Sine], t: f64) -> [f64; 3] {
        sines.iter().fold([0.0; 3], |acc, s| {
            let v = s.eval(t);
            [acc[0] + v[0], acc[1] + v[1], acc[2] + v[2]]
        })
    }

    fn sea(components: usize) -> Vec<Sine> {
        let text = format!(
            "kind = \"jonswap\"\nsignificant_height = 4.0\npeak_period = 10.0\ncomponents = {components}\nseed = 3"
        );
        let spectrum: Spectrum = toml::from_str(&text).unwrap();
        assert_eq!(spectrum.kind, SpectrumKind::Jonswap);
        spectrum.sines()
    }

    #[test]
    fn a_sea_summed_by_phasors_is_the_direct_sum_over_a_three_hour_storm() {
        let sines = sea(5000);
        let series = SineSeries::new(&sines);
        assert_eq!((series.grids.len(), series.others.len()), (1, 0));
        // The sum's scale: Hs / 4 for the value, times the frequencies' for
        // the rates.
        let scale = [1.0, 0.63, 0.4];
        let mut worst = [0.0f64; 3];
        for k in 0..400 {
            let t = 27.1 * k as f64;
            let (fast, slow) = (series.eval(t), direct(&sines, t));
            for i in 0..3 {
                worst[i] = worst[i].max((fast[i] - slow[i]).abs() / scale[i]);
            }
        }
        // Measured: 1.9e-12, 2.9e-12 and 8.0e-12, the direct sum's own
        // rounding at these times.
        assert!(worst.iter().all(|&w| w < 2e-11), "{worst:?}");
    }

    #[test]
    fn sines_off_the_grid_or_decaying_are_summed_one_by_one() {
        let mut sines = vec![Sine {
            amplitude: 2.0,
            angular_frequency: 0.3,
            phase: 0.1,
            decay: 0.0,
        }];
        sines.extend(sea(40));
        sines.push(Sine {
            amplitude: 0.5,
            angular_frequency: 1.7,
            phase: -0.4,
            decay: 0.05,
        });
        // A short run stays direct; a frequency moved off the grid by far
        // more than rounding cuts the grid there.
        sines.extend(sea(40).into_iter().take(10));
        let mut moved = sea(40);
        moved[20].angular_frequency *= 1.0 + 1e-9;
        sines.extend(moved);
        let series = SineSeries::new(&sines);
        assert_eq!(series.len(), sines.len());
        let grid_sizes: Vec<usize> = series.grids.iter().map(|g| g.terms.len()).collect();
        assert_eq!(grid_sizes, [40, 20, 19], "{grid_sizes:?}");
        for t in [0.0, 3.3, 700.0] {
            let (fast, slow) = (series.eval(t), direct(&sines, t));
            for i in 0..3 {
                assert!(
                    (fast[i] - slow[i]).abs() < 1e-12,
                    "{t} {i}: {fast:?} {slow:?}"
                );
            }
        }
        assert!(SineSeries::new(&[]).is_empty());
    }
}
