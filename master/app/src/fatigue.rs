//! Fatigue damage of a line by rainflow counting and Miner's rule (issue 50):
//! a recorded tension (and bending moment) becomes a stress or a tension
//! ratio, its ranges are counted (`crate::rainflow`) and each range's cycles
//! are divided by the cycles the curve allows at it. The curves and their
//! sources:
//! - DNV-OS-E301 (2013, Ch.2 Sec.2, the fatigue limit state) T-N curves, n = a_D s^-m with s
//!   the stress range (MPa) on the nominal area: studless chain a_D = 6.0e10,
//!   m = 3.0; studlink chain 1.2e11, 3.0; six-strand rope 3.4e14, 4.0;
//!   spiral-strand rope 1.7e17, 4.8;
//! - API RP 2SK (3rd ed., 2005, the fatigue analysis) T-N curves, N R^M = K with R the
//!   tension range over the reference breaking strength: common studless
//!   chain M = 3.0, K = 316; common studlink chain 3.0, 1000; six- or
//!   multi-strand rope M = 4.09, log10 K = 3.20 - 2.79 Lm; spiral-strand rope
//!   5.05, 3.25 - 3.43 Lm; Lm the mean load over the breaking strength;
//! - DNV-RP-C203 (2016, Tables 2-1 and 2-2) two-slope S-N curves,
//!   log N = log a - m log s, the first slope above 10^7 cycles in air and
//!   10^6 in seawater with cathodic protection: in air B1 (m 4.0, log a
//!   15.117; 5, 17.146), C (3, 12.592; 5, 16.320), D (3, 12.164; 5, 15.606),
//!   E (3, 12.010; 5, 15.350), F (3, 11.855; 5, 15.091), F1 (3, 11.699; 5,
//!   14.832); in seawater with cathodic protection B1 (4.0, 14.917), C (3,
//!   12.192), D (3, 11.764), E (3, 11.610), F (3, 11.455), F1 (3, 11.299),
//!   each with the same second slope as in air; with DNV-RP-C203's
//!   thickness effect (2.4.3: the range times (t / t_ref)^k for t above
//!   t_ref = 25 mm, k from Tables 2-1 and 2-2: B1 0, C 0.05, D and E 0.20,
//!   F and F1 0.25) and mean stress effect (2.5: the compressive part of a
//!   cycle's range times 0.6 in base material, 0.8 in post-weld heat
//!   treated welds) where the scene asks for them.

use crate::rainflow::{self, Cycle};
use serde::Serialize;
use slender_scene::spec::{FatigueCurve, FatigueSpec};

/// Seconds in a year of 365.25 days.
const YEAR_S: f64 = 365.25 * 86_400.0;

/// The damage of one `[[output.fatigue]]` entry over its window.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Damage {
    /// The window's length (s).
    pub window_s: f64,
    /// The cycles counted (half cycles as halves).
    pub cycles: f64,
    /// The largest range counted (MPa for a stress curve, a fraction of the
    /// breaking strength for API RP 2SK's).
    pub largest_range: f64,
    /// Miner's sum over the window.
    pub damage: f64,
    /// The damage in a year of this sea state.
    pub damage_per_year: f64,
    /// 1 / damage per year (years; infinite for no damage).
    pub life_years: f64,
}

/// Cycles to failure at range `s` for `curve` (s in MPa, or the tension
/// ratio for API RP 2SK's curves, `mean_ratio` their Lm).
pub fn cycles_to_failure(curve: FatigueCurve, s: f64, mean_ratio: f64) -> f64 {
    use FatigueCurve::*;
    let single = |log_a: f64, m: f64| 10f64.powf(log_a - m * s.log10());
    // DNV-RP-C203: slope m1 above the knee's stress (at 10^knee cycles), 5 below.
    let two = |m1: f64, log_a1: f64, log_a2: f64, knee: f64| {
        if s >= 10f64.powf((log_a1 - knee) / m1) {
            single(log_a1, m1)
        } else {
            single(log_a2, 5.0)
        }
    };
    match curve {
        DnvStudlessChain => single(6.0e10f64.log10(), 3.0),
        DnvStudlinkChain => single(1.2e11f64.log10(), 3.0),
        DnvSixStrandRope => single(3.4e14f64.log10(), 4.0),
        DnvSpiralStrandRope => single(1.7e17f64.log10(), 4.8),
        ApiStudlessChain => single(316f64.log10(), 3.0),
        ApiStudlinkChain => single(1000f64.log10(), 3.0),
        ApiSixStrandRope => single(3.20 - 2.79 * mean_ratio, 4.09),
        ApiSpiralStrandRope => single(3.25 - 3.43 * mean_ratio, 5.05),
        DnvC203B1Air => two(4.0, 15.117, 17.146, 7.0),
        DnvC203CAir => two(3.0, 12.592, 16.320, 7.0),
        DnvC203DAir => two(3.0, 12.164, 15.606, 7.0),
        DnvC203EAir => two(3.0, 12.010, 15.350, 7.0),
        DnvC203FAir => two(3.0, 11.855, 15.091, 7.0),
        DnvC203F1Air => two(3.0, 11.699, 14.832, 7.0),
        DnvC203B1SeawaterCp => two(4.0, 14.917, 17.146, 6.0),
        DnvC203CSeawaterCp => two(3.0, 12.192, 16.320, 6.0),
        DnvC203DSeawaterCp => two(3.0, 11.764, 15.606, 6.0),
        DnvC203ESeawaterCp => two(3.0, 11.610, 15.350, 6.0),
        DnvC203FSeawaterCp => two(3.0, 11.455, 15.091, 6.0),
        DnvC203F1SeawaterCp => two(3.0, 11.299, 14.832, 6.0),
    }
}

/// DNV-RP-C203's thickness exponent k of `curve` (Tables 2-1 and 2-2, the
/// same in air and in seawater); 0 for the chain and rope curves.
pub fn thickness_exponent(curve: FatigueCurve) -> f64 {
    use FatigueCurve::*;
    match curve {
        DnvC203CAir | DnvC203CSeawaterCp => 0.05,
        DnvC203DAir | DnvC203DSeawaterCp | DnvC203EAir | DnvC203ESeawaterCp => 0.20,
        DnvC203FAir | DnvC203FSeawaterCp | DnvC203F1Air | DnvC203F1SeawaterCp => 0.25,
        _ => 0.0,
    }
}

/// The factor DNV-RP-C203's thickness effect puts on every range:
/// (max(t, t_ref) / t_ref)^k, 1 without a thickness.
fn thickness_factor(spec: &FatigueSpec) -> f64 {
    let Some(t) = spec.thickness else {
        return 1.0;
    };
    let reference = spec.reference_thickness.unwrap_or(0.025);
    let k = (spec.thickness_exponent).unwrap_or_else(|| thickness_exponent(spec.curve));
    (t.max(reference) / reference).powf(k)
}

/// The range `cycle` enters the curve with: its compressive part reduced by
/// the mean stress effect, then raised by the thickness effect (`thickness`
/// is the latter's factor).
fn effective_range(spec: &FatigueSpec, cycle: &Cycle, thickness: f64) -> f64 {
    let range = match spec.mean_stress {
        Some(effect) => {
            let (top, bottom) = (
                cycle.mean + cycle.range / 2.0,
                cycle.mean - cycle.range / 2.0,
            );
            let tensile = top.max(0.0) - bottom.max(0.0);
            tensile + effect.compressive_factor() * (cycle.range - tensile)
        }
        None => cycle.range,
    };
    range * thickness
}

/// The nominal area (m2) of `spec`: given, or a chain's two bars.
fn nominal_area(spec: &FatigueSpec) -> f64 {
    spec.area.unwrap_or_else(|| {
        let d = spec.chain_diameter.unwrap_or(f64::NAN);
        2.0 * std::f64::consts::PI * d * d / 4.0
    })
}

/// Miner's damage of `spec` from the tension (N) and moment (N m) samples of
/// a window `window_s` seconds long; the worse of the section's two sides
/// when a moment is given.
pub fn damage(
    spec: &FatigueSpec,
    tension: &[f64],
    moment: Option<&[f64]>,
    window_s: f64,
) -> Damage {
    let scf = spec.scf.unwrap_or(1.0);
    let sides: Vec<Vec<f64>> = if let Some(b) = spec.breaking_load {
        vec![tension.iter().map(|t| scf * t / b).collect()]
    } else {
        let area = nominal_area(spec);
        let stress = |side: f64| -> Vec<f64> {
            (tension.iter().enumerate())
                .map(|(k, t)| {
                    let bending = match (moment, spec.section_modulus) {
                        (Some(m), Some(z)) => side * m[k] / z,
                        _ => 0.0,
                    };
                    scf * (t / area + bending) / 1e6
                })
                .collect()
        };
        if moment.is_some() {
            vec![stress(1.0), stress(-1.0)]
        } else {
            vec![stress(0.0)]
        }
    };
    let mean_ratio = match spec.breaking_load {
        Some(b) => tension.iter().sum::<f64>() / tension.len().max(1) as f64 / b,
        None => 0.0,
    };
    let thickness = thickness_factor(spec);
    let of_side = |history: &Vec<f64>| -> Damage {
        let cycles = rainflow::count(history);
        let damage: f64 = (cycles.iter())
            .map(|c| (c.count, effective_range(spec, c, thickness)))
            .filter(|(_, range)| *range > 0.0)
            .map(|(count, range)| count / cycles_to_failure(spec.curve, range, mean_ratio))
            .sum();
        let per_year = damage * YEAR_S / window_s;
        Damage {
            window_s,
            cycles: cycles.iter().map(|c| c.count).sum(),
            largest_range: cycles.iter().map(|c| c.range).fold(0.0, f64::max),
            damage,
            damage_per_year: per_year,
            life_years: 1.0 / per_year,
        }
    };
    (sides.iter().map(of_side))
        .max_by(|a, b| a.damage.total_cmp(&b.damage))
        .unwrap_or_else(|| of_side(&Vec::new()))
}

#[cfg(test)]
mod tests;
