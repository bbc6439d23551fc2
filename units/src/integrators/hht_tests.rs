//! HHT-alpha's local error estimate against the true local error of one step
//! of a single-DOF oscillator started on its exact solution.

use super::hht::{HhtAlpha, Matrices, NewtonSettings, SecondOrderSystem, StepLoads, TangentScales};
use crate::numerics::banded::SymmetricBand;

/// m a + k q = 0 with m = 1 kg, k = omega^2.
struct Spring {
    mass: SymmetricBand,
    stiffness: SymmetricBand,
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
}

impl SecondOrderSystem for Spring {
    fn label(&self) -> &str {
        "spring"
    }
    fn matrices(&self) -> Matrices<'_> {
        Matrices {
            mass: &self.mass,
            damping: None,
            stiffness: Some(&self.stiffness),
            varies: false,
        }
    }
    super::hht::motion_fields!();
    fn is_linear(&self) -> bool {
        true
    }
    fn nonlinear_force(
        &mut self,
        _q: &[f64],
        _v: &[f64],
        _t: f64,
        _tangent: Option<(&mut SymmetricBand, TangentScales)>,
        force: &mut Vec<f64>,
    ) {
        force.clear();
    }
}

const OMEGA: f64 = 2.0;

/// The exact motion q = cos(omega t): (q, v, a).
fn exact(t: f64) -> [f64; 3] {
    let (s, c) = (OMEGA * t).sin_cos();
    [c, -OMEGA * s, -OMEGA * OMEGA * c]
}

/// One step of `h` from the exact state at `t0`: the estimate and the true
/// displacement error.
fn one_step(alpha: f64, t0: f64, h: f64) -> (f64, f64) {
    let mut mass = SymmetricBand::zeros(1, 0);
    mass.add(0, 0, 1.0);
    let mut stiffness = SymmetricBand::zeros(1, 0);
    stiffness.add(0, 0, OMEGA * OMEGA);
    let [q, v, a] = exact(t0);
    let mut spring = Spring {
        mass,
        stiffness,
        q: vec![q],
        v: vec![v],
        a: vec![a],
    };
    let mut hht = HhtAlpha::new(alpha, 1, 0);
    let loads = StepLoads {
        t0,
        t1: t0 + h,
        h,
        f0: &[0.0],
        f1: &[0.0],
        g0: None,
        held: &[],
    };
    let newton = NewtonSettings {
        tolerance: 1e-14,
        max_iterations: 5,
    };
    hht.step(&mut spring, &loads, newton)
        .expect("a linear step");
    let estimate = hht.local_error(|_| true);
    (estimate, (spring.q[0] - exact(t0 + h)[0]).abs())
}

#[test]
fn the_estimate_is_the_true_local_error_to_leading_order() {
    // alpha = 0 (average acceleration): the error is (beta - 1/6) h^3 q''';
    // the estimate's ratio to it tends to one as the step shrinks. With
    // alpha > 0 the forces weighted between the step's ends add a term of
    // their own that the estimate leaves out: the ratio tends to a constant
    // near one instead (1.09 at alpha = 0.05).
    for (alpha, limit, within) in [(0.0, 1.0, 0.01), (0.05, 1.09, 0.01)] {
        let mut ratios = Vec::new();
        for h in [0.1, 0.05, 0.025, 0.0125, 0.003, 0.001] {
            let (estimate, error) = one_step(alpha, 0.3, h);
            ratios.push(estimate / error);
        }
        eprintln!("alpha {alpha}: estimate / true error {ratios:?}");
        let last = ratios[ratios.len() - 1];
        assert!((last - limit).abs() < within, "alpha {alpha}: {ratios:?}");
    }
}

#[test]
fn the_estimate_falls_as_the_cube_of_the_step() {
    let (coarse, _) = one_step(0.0, 0.3, 0.02);
    let (fine, _) = one_step(0.0, 0.3, 0.01);
    let order = (coarse / fine).log2();
    assert!((order - 3.0).abs() < 0.05, "order {order}");
}

#[test]
fn no_step_no_estimate() {
    assert_eq!(HhtAlpha::new(0.0, 1, 0).local_error(|_| true), 0.0);
}
