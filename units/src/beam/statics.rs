//! Static equilibrium of the beam with contact, by Newton with penalty
//! continuation.

use super::contact::{penalty_of, with_penalty};
use super::{Beam, ContactValues};
use crate::contract::{Inputs, UnitError};
use crate::numerics::banded::BandLdlt;

impl Beam {
    /// Static equilibrium K q + F_contact(q) = F at the current time, by Newton with
    /// penalty continuation (p0 psi^(n-1)) and lambda updates every iteration.
    pub fn solve_static(&mut self, inputs: Inputs<'_>) -> Result<u32, UnitError> {
        let t = self.state.t;
        self.apply_kinematics(inputs, t, 0.0);
        let n = self.state.q.len();
        let mut values = ContactValues::default();
        let target = self.params.contact.as_ref().map(|c| penalty_of(&c.method));
        let mut penalty = match (self.params.static_penalty_start, target) {
            (Some(p0), Some(p)) => Some(p0.min(p)),
            (_, p) => p,
        };
        let mut load = vec![0.0; n];
        self.external_load(inputs, t, 0.0, &mut load);
        let zeros = vec![0.0; n];
        let cap = 20 * self.params.newton_max_iterations;
        let mut history = Vec::new();
        for iteration in 1..=cap {
            let mut jac = self.k.clone();
            let q = self.state.q.clone();
            let lambda = self.state.lambda.clone();
            self.contact_at(
                &q,
                &zeros,
                t,
                &lambda,
                penalty,
                Some((&mut jac, 1.0, 0.0)),
                &mut values,
            );
            let mut r = vec![0.0; n];
            self.k.mul_add(1.0, &q, &mut r);
            for i in 0..n {
                r[i] += values.force[i] - load[i];
            }
            self.state.reaction.copy_from_slice(&r);
            for dof in self.held_dofs().collect::<Vec<_>>() {
                jac.set_identity_row(dof);
                r[dof] = 0.0;
            }
            let factor = BandLdlt::new(&jac).ok_or_else(|| {
                UnitError::Numerical(
                    "no static equilibrium: the boundary conditions leave the beam free to move (a rigid-body mode) and no contact holds it".into(),
                )
            })?;
            for v in r.iter_mut() {
                *v = -*v;
            }
            factor.solve_in_place(&mut r);
            let step = r.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            history.push(step);
            for (q, dq) in self.state.q.iter_mut().zip(&r) {
                *q += dq;
            }
            let size = self.state.q.iter().fold(1.0f64, |a, v| a.max(v.abs()));
            if let Some(c) = &self.params.contact {
                let law = with_penalty(&c.method, penalty);
                self.update_lambda(&law, t);
            }
            let at_target = penalty == target;
            if step < self.params.newton_tolerance * size && at_target {
                self.state.newton_iterations = iteration;
                self.finish_static(t, penalty);
                return Ok(iteration);
            }
            if let (Some(p), Some(goal)) = (penalty, target) {
                penalty = Some((p * self.params.static_penalty_growth).min(goal));
            }
        }
        Err(UnitError::Numerical(format!(
            "static solve: Newton did not converge in {cap} iterations; corrections: {}",
            history
                .iter()
                .rev()
                .take(8)
                .rev()
                .map(|v| format!("{v:.3e}"))
                .collect::<Vec<_>>()
                .join(", ")
        )))
    }

    fn finish_static(&mut self, t: f64, penalty: Option<f64>) {
        let n = self.state.q.len();
        let mut values = ContactValues::default();
        let (q, lambda) = (self.state.q.clone(), self.state.lambda.clone());
        self.contact_at(&q, &vec![0.0; n], t, &lambda, penalty, None, &mut values);
        self.accept_contact(&values, t);
        self.state.v.fill(0.0);
        self.state.a.fill(0.0);
    }
}
