//! Explicit central differences (velocity Verlet) for any [`SecondOrderSystem`]:
//! seed 002 compares it with implicit integration for real-time hybrid tests.
//!
//! From q_n, v_n, a_n:
//! `v_half = v_n + h/2 a_n`, `q_{n+1} = q_n + h v_half`,
//! `M a_{n+1} = f_{n+1} - K q_{n+1} - C v_half - g(q_{n+1}, v_half)`,
//! `v_{n+1} = v_half + h/2 a_{n+1}`.
//! Second order, no solve but with M (factorised once; one back-substitution per
//! step, trivial for a lumped mass), and stable only below the critical step
//! `2 / omega_max` ([`CentralDifference::critical_step`]); damping and the
//! nonlinear force see the half-step velocity.

use super::hht::{Matrices, SecondOrderSystem};
use crate::contract::UnitError;
use crate::numerics::banded::BandLdlt;
use crate::numerics::lanczos::largest_eigenvalue;

/// The integrator: the factorised mass (with identity rows at prescribed DOFs) and
/// the step's buffers.
#[derive(Default)]
pub struct CentralDifference {
    mass: Option<BandLdlt>,
    held: Vec<usize>,
    q: Vec<f64>,
    v_half: Vec<f64>,
    rhs: Vec<f64>,
    force: Vec<f64>,
}

impl CentralDifference {
    /// An integrator; the mass is factorised at the first step.
    pub fn new() -> CentralDifference {
        CentralDifference::default()
    }

    fn factorise(&mut self, m: &Matrices<'_>, held: &[(usize, [f64; 3])]) -> Result<(), UnitError> {
        let dofs: Vec<usize> = held.iter().map(|(d, _)| *d).collect();
        if self.mass.is_some() && self.held == dofs {
            return Ok(());
        }
        let mut mass = m.mass.clone();
        for &d in &dofs {
            mass.set_identity_row(d);
        }
        self.mass = Some(BandLdlt::new(&mass).ok_or_else(|| {
            UnitError::Numerical(
                "central differences: the mass matrix is not positive definite".into(),
            )
        })?);
        self.held = dofs;
        Ok(())
    }

    /// One step of `h` seconds to `t1` under the external load `f1` at the step's
    /// end; `held` gives the prescribed DOFs' (q, v, a) at `t1`.
    pub fn step<S: SecondOrderSystem + ?Sized>(
        &mut self,
        system: &mut S,
        t1: f64,
        h: f64,
        f1: &[f64],
        held: &[(usize, [f64; 3])],
    ) -> Result<(), UnitError> {
        self.factorise(&system.matrices(), held)?;
        let [q0, v0, a0] = system.motion();
        let n = q0.len();
        self.q.resize(n, 0.0);
        self.v_half.resize(n, 0.0);
        self.rhs.resize(n, 0.0);
        for i in 0..n {
            self.v_half[i] = v0[i] + 0.5 * h * a0[i];
            self.q[i] = q0[i] + h * self.v_half[i];
        }
        for &(d, [q, v, _]) in held {
            self.q[d] = q;
            self.v_half[d] = v;
        }
        // M a1 = f1 - K q1 - C v_half - g(q1, v_half).
        self.rhs.copy_from_slice(f1);
        let m = system.matrices();
        if let Some(k) = m.stiffness {
            k.mul_add(-1.0, &self.q, &mut self.rhs);
        }
        if let Some(c) = m.damping {
            c.mul_add(-1.0, &self.v_half, &mut self.rhs);
        }
        if !system.is_linear() {
            let (q, v) = (&self.q, &self.v_half);
            system.nonlinear_force(q, v, t1, None, &mut self.force);
            for (r, g) in self.rhs.iter_mut().zip(&self.force) {
                *r -= g;
            }
        }
        for &(d, [_, _, a]) in held {
            self.rhs[d] = a;
        }
        let mass = self.mass.as_ref().ok_or_else(|| {
            UnitError::Numerical("central differences: the mass was not factorised".into())
        })?;
        mass.solve_in_place(&mut self.rhs);
        // rhs now holds a1; v1 = v_half + h/2 a1.
        for i in 0..n {
            self.v_half[i] += 0.5 * h * self.rhs[i];
        }
        for &(d, [_, v, _]) in held {
            self.v_half[d] = v;
        }
        if !self.v_half.iter().chain(&self.q).sum::<f64>().is_finite() {
            return Err(UnitError::Numerical(format!(
                "{}: central differences became non-finite at t = {t1} s (is h = {h} s below the critical step?)",
                system.label()
            )));
        }
        system.set_motion(&self.q, &self.v_half, &self.rhs);
        Ok(())
    }

    /// The critical step `2 / omega_max` (s) of the linear part, omega_max^2 the
    /// largest eigenvalue of K x = lambda M x by Lanczos (at most `max_steps`
    /// steps) and taken at its upper bound, so the step errs on the safe side.
    pub fn critical_step(m: &Matrices<'_>, max_steps: usize) -> Result<f64, UnitError> {
        let stiffness = m.stiffness.ok_or_else(|| {
            UnitError::Numerical("critical step: no stiffness matrix given".into())
        })?;
        let top = largest_eigenvalue(stiffness, m.mass, 1e-10, max_steps).ok_or_else(|| {
            UnitError::Numerical(
                "critical step: the mass matrix is not positive definite or M^-1 K is not finite"
                    .into(),
            )
        })?;
        if top.estimate.is_nan() || top.estimate <= 0.0 {
            return Err(UnitError::Numerical(
                "critical step: M^-1 K has no positive eigenvalue".into(),
            ));
        }
        if top.upper_bound - top.estimate > 1e-6 * top.estimate {
            return Err(UnitError::Numerical(format!(
                "critical step: Lanczos did not settle in {} steps (omega_max^2 between {:.6e} and {:.6e})",
                top.steps, top.estimate, top.upper_bound
            )));
        }
        Ok(2.0 / top.upper_bound.sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrators::hht::{TangentScales, motion_fields};
    use crate::numerics::banded::SymmetricBand;

    /// A chain of `n` unit masses on springs `k` (fixed at one end).
    struct Chain {
        m: SymmetricBand,
        k: SymmetricBand,
        q: Vec<f64>,
        v: Vec<f64>,
        a: Vec<f64>,
    }

    impl Chain {
        fn new(n: usize, k: f64) -> Chain {
            let mut m = SymmetricBand::zeros(n, 1);
            let mut stiffness = SymmetricBand::zeros(n, 1);
            for i in 0..n {
                m.add(i, i, 1.0);
                stiffness.add(i, i, if i + 1 < n { 2.0 * k } else { k });
                if i > 0 {
                    stiffness.add(i, i - 1, -k);
                }
            }
            Chain {
                m,
                k: stiffness,
                q: vec![0.0; n],
                v: vec![0.0; n],
                a: vec![0.0; n],
            }
        }
    }

    impl SecondOrderSystem for Chain {
        fn label(&self) -> &str {
            "chain"
        }
        fn matrices(&self) -> Matrices<'_> {
            Matrices {
                mass: &self.m,
                damping: None,
                stiffness: Some(&self.k),
                varies: false,
            }
        }
        motion_fields!();
        fn is_linear(&self) -> bool {
            true
        }
        fn nonlinear_force(
            &mut self,
            _: &[f64],
            _: &[f64],
            _: f64,
            _: Option<(&mut SymmetricBand, TangentScales)>,
            _: &mut Vec<f64>,
        ) {
        }
    }

    /// q(t) of one mass from q = 1 at rest, and the largest energy error.
    fn oscillate(omega: f64, h: f64, t_end: f64) -> (f64, f64) {
        let mut s = Chain::new(1, omega * omega);
        s.q[0] = 1.0;
        s.a[0] = -omega * omega;
        let mut cd = CentralDifference::new();
        let steps = (t_end / h).round() as usize;
        let mut worst = 0.0_f64;
        for k in 0..steps {
            cd.step(&mut s, (k + 1) as f64 * h, h, &[0.0], &[]).unwrap();
            let energy = 0.5 * s.v[0] * s.v[0] + 0.5 * omega * omega * s.q[0] * s.q[0];
            worst = worst.max((energy / (0.5 * omega * omega) - 1.0).abs());
        }
        (s.q[0] - (omega * t_end).cos(), worst)
    }

    #[test]
    fn a_free_oscillation_is_second_order_and_its_energy_stays_bounded() {
        let omega = 2.0 * std::f64::consts::PI;
        let (e1, _) = oscillate(omega, 0.01, 0.3);
        let (e2, _) = oscillate(omega, 0.005, 0.3);
        let order = (e1 / e2).abs().log2();
        assert!((order - 2.0).abs() < 0.1, "order {order}");
        // 1000 periods at half the critical step: the energy oscillates, bounded.
        let (_, drift) = oscillate(omega, 0.5 * 2.0 / omega, 1000.0);
        assert!(drift < 0.2, "energy error {drift}");
    }

    #[test]
    fn beyond_the_critical_step_it_blows_up_and_says_so() {
        let omega = 2.0 * std::f64::consts::PI;
        let h = 1.01 * 2.0 / omega;
        let mut s = Chain::new(1, omega * omega);
        s.q[0] = 1.0;
        s.a[0] = -omega * omega;
        let mut cd = CentralDifference::new();
        let mut k = 0;
        let error = loop {
            k += 1;
            if let Err(e) = cd.step(&mut s, k as f64 * h, h, &[0.0], &[]) {
                break e;
            }
            assert!(k < 1_000_000, "no blow-up");
        };
        assert!(error.to_string().contains("critical step"), "{error}");
    }

    #[test]
    fn the_critical_step_of_a_chain_is_two_over_its_highest_frequency() {
        let (n, k) = (20, 4.0e4);
        let chain = Chain::new(n, k);
        // A fixed-free chain of unit masses: omega_j = 2 sqrt(k) sin((2j-1) pi / (2(2n+1))).
        let j = n as f64;
        let omega_max = 2.0
            * k.sqrt()
            * ((2.0 * j - 1.0) * std::f64::consts::PI / (2.0 * (2.0 * j + 1.0))).sin();
        let h = CentralDifference::critical_step(&chain.matrices(), 200).unwrap();
        let exact = 2.0 / omega_max;
        assert!(((h - exact) / exact).abs() < 1e-4, "{h} vs {exact}");
    }
}
