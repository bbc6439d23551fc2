//! The chord unit against the cantilever with tension, in both models and
//! orientations.

use super::*;
use crate::contract::Driver;

fn chord(model: ChordModel, moving: MovingEnd, tension: f64) -> Driver<Chord> {
    let params = ChordParams {
        model,
        moving,
        start: [0.0, 0.0],
        end: [6.0, 8.0],
        weight: 0.0,
        weight_at: [3.0, 4.0],
        loaded_end_displacement: [0.0; 3],
        flexural_rigidity: 1e4,
        mass_per_length: 10.0,
        damping_per_length: 40.0,
        tension,
        axial_stiffness: None,
        axial_mass: None,
        elements: 20,
        alpha: 0.0,
        order: 16,
        band: ten_hz(),
    };
    Driver::new(Chord::new(params).unwrap())
}

/// Tip deflection (m) of a cantilever of length 10 m, EI 1e4 N m^2 under
/// axial tension `t` and a transverse tip force `p`: p / T (L - tanh(kL) / k),
/// k = sqrt(T / EI); p L^3 / (3 EI) without tension.
fn cantilever(p: f64, t: f64) -> f64 {
    let (l, ei) = (10.0f64, 1e4);
    if t == 0.0 {
        return p * l.powi(3) / (3.0 * ei);
    }
    let k = (t / ei).sqrt();
    p / t * (l - (k * l).tanh() / k)
}

/// Ramps a transverse force on the loaded end up over 5 s and holds it, the
/// moving end held where it started; the end displacement after 40 s.
fn settled(unit: &mut Driver<Chord>, force: [f64; 2], tension: f64) -> [f64; 7] {
    // The loaded end carries the tension along the chord (outwards).
    let e = [0.6, 0.8];
    let outward = if unit.unit().loaded_at_end() {
        1.0
    } else {
        -1.0
    };
    let pull = [outward * tension * e[0], outward * tension * e[1]];
    let mover = if outward > 0.0 {
        [0.0, 0.0]
    } else {
        [6.0, 8.0]
    };
    let at = |s: f64| {
        [
            mover[0],
            mover[1],
            0.0,
            pull[0] + s * force[0],
            pull[1] + s * force[1],
            0.0,
        ]
    };
    unit.set_inputs(&at(0.0)).unwrap();
    unit.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(0.01).unwrap();
    for k in 0..4000 {
        let t = 0.01 * f64::from(k + 1);
        unit.set_inputs(&at((t / 5.0).min(1.0))).unwrap();
        unit.do_step(Time::from_secs(0.01 * f64::from(k)).unwrap(), h)
            .unwrap();
    }
    let mut out = [0.0; 7];
    unit.outputs(&mut out).unwrap();
    out
}

#[test]
fn a_loaded_end_deflects_as_a_cantilever_with_tension_in_both_models_and_orientations() {
    // A force across the chord, n = (-0.8, 0.6), of 100 N.
    let p = 100.0;
    let force = [-0.8 * p, 0.6 * p];
    for model in [ChordModel::Beam, ChordModel::Span] {
        for moving in [MovingEnd::Start, MovingEnd::End] {
            for tension in [0.0, 2e3] {
                let mut unit = chord(model, moving, tension);
                let out = settled(&mut unit, force, tension);
                let across = -0.8 * out[3] + 0.6 * out[4];
                let along = 0.6 * out[3] + 0.8 * out[4];
                let expect = cantilever(p, tension);
                assert!(
                    (across - expect).abs() < 1e-3 * expect,
                    "{model:?} {moving:?} T = {tension}: {across} against {expect}"
                );
                assert!(along.abs() < 1e-12, "the chord is rigid: {along}");
                // The moving end carries the force and its moment p L less
                // the tension's at the deflected end, T y(L).
                let lever = p * 10.0 - tension * expect;
                let moment = if moving == MovingEnd::Start {
                    lever
                } else {
                    -lever
                };
                assert!(
                    (out[2] - moment).abs() < 1e-3 * p * 10.0,
                    "{model:?} {moving:?} T = {tension}: moment {} against {moment}",
                    out[2]
                );
            }
        }
    }
}

#[test]
fn with_an_axial_stiffness_the_loaded_end_moves_along_the_chord_by_the_force_over_it() {
    // The same cantilever, pulled 500 N further along its chord at the
    // loaded end, with EA / L = 1e5 N/m: 5 mm along the chord, outward from
    // the moving end, and the transverse answer unchanged.
    for moving in [MovingEnd::Start, MovingEnd::End] {
        let mut params = chord(ChordModel::Beam, moving, 0.0).unit().params.clone();
        params.axial_stiffness = Some(1e5);
        let mut unit = Driver::new(Chord::new(params).unwrap());
        // The chord's direction e = (0.6, 0.8), pointing away from the moving end.
        let outward = if moving == MovingEnd::Start {
            1.0
        } else {
            -1.0
        };
        let pull = [0.6 * 500.0 * outward, 0.8 * 500.0 * outward];
        let out = settled(&mut unit, pull, 0.0);
        let along = 0.6 * out[3] + 0.8 * out[4];
        assert!(
            (along - outward * 5e-3).abs() < 1e-12,
            "{moving:?}: {along}"
        );
        let across = -0.8 * out[3] + 0.6 * out[4];
        assert!(across.abs() < 1e-9, "{moving:?}: {across}");
    }
}

/// The chord of `chord` with EA / L = 1e5 N/m and 100 kg at its loaded end
/// (omega = 31.6 rad/s), Newmark's `alpha`, pulled 500 N further along its
/// chord from the first step on, its moving end held; the loaded end's
/// displacement along the chord (m) and the moving end's axial force's change
/// (N) over `steps` steps of `h` (s).
fn pulled_mass(alpha: f64, steps: usize, h: f64) -> Vec<(f64, f64)> {
    let mut params = chord(ChordModel::Beam, MovingEnd::Start, 0.0)
        .unit()
        .params
        .clone();
    params.axial_stiffness = Some(1e5);
    params.axial_mass = Some(100.0);
    params.alpha = alpha;
    let mut unit = Driver::new(Chord::new(params).unwrap());
    unit.set_inputs(&[0.0; 6]).unwrap();
    unit.initialize(Time::ZERO).unwrap();
    unit.set_inputs(&[0.0, 0.0, 0.0, 300.0, 400.0, 0.0])
        .unwrap();
    let step = Time::from_secs(h).unwrap();
    let mut out = [0.0; 7];
    (0..steps)
        .map(|k| {
            unit.do_step(Time::from_secs(h * k as f64).unwrap(), step)
                .unwrap();
            unit.outputs(&mut out).unwrap();
            (0.6 * out[3] + 0.8 * out[4], 0.6 * out[0] + 0.8 * out[1])
        })
        .collect()
}

#[test]
fn an_axial_mass_oscillates_on_the_stretch_as_a_mass_on_a_spring() {
    // 500 N on 1e5 N/m from rest: u = 5 mm (1 - cos w t), w = sqrt(1e3); the
    // spring pulls the moving end by k u. Trapezoidal rule, w h = 0.032.
    let w = 1e3f64.sqrt();
    let run = pulled_mass(0.0, 2000, 1e-3);
    let mut worst = 0.0f64;
    for (k, (along, force)) in run.iter().enumerate() {
        let t = 1e-3 * (k + 1) as f64;
        // The force ramps in over the first step (its centre at h / 2).
        let exact = 5e-3 * (1.0 - (w * (t - 5e-4)).cos());
        worst = worst.max((along - exact).abs() / 5e-3);
        assert!((force - 1e5 * along).abs() < 1e-6, "t = {t}: {force}");
    }
    assert!(
        worst < 2e-2,
        "largest error {worst:.3e} of the static stretch"
    );
    // Undamped: after 2 s (10 periods) it still swings over the full range.
    let late = &run[1700..];
    let top = late.iter().map(|r| r.0).fold(f64::MIN, f64::max);
    assert!(top > 9.9e-3, "{top}");
}

#[test]
fn numerical_damping_settles_the_axial_mass_on_the_static_stretch() {
    // At w h = 1.6 Newmark's alpha = 0.3 damps the swing within 20 s; the
    // trapezoidal rule (alpha = 0) keeps it.
    let run = pulled_mass(0.3, 400, 0.05);
    let (along, force) = run[run.len() - 1];
    assert!((along - 5e-3).abs() < 1e-6, "{along}");
    assert!((force - 500.0).abs() < 1e-2, "{force}");
    let undamped = pulled_mass(0.0, 400, 0.05);
    let swing = undamped[380..].iter().map(|r| (r.0 - 5e-3).abs());
    assert!(swing.fold(0.0, f64::max) > 1e-3);
}

#[test]
fn a_mass_without_a_stiffness_is_refused() {
    let mut params = chord(ChordModel::Beam, MovingEnd::Start, 0.0)
        .unit()
        .params
        .clone();
    params.axial_mass = Some(100.0);
    let e = Chord::new(params).err().expect("refused").to_string();
    assert!(
        e.contains("axial_mass") && e.contains("axial_stiffness"),
        "{e}"
    );
}
