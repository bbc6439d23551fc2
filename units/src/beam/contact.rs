//! The beam's contact with its surface: forces and tangents at the contact
//! integration points, gaps for the energy-conserving law, Lagrangian updates.

use super::{Beam, ContactValues};
use crate::contact::Law;
use crate::numerics::banded::SymmetricBand;

impl Beam {
    /// Keeps the contact evaluated at the state just accepted (time `t`): its
    /// force for the next step and the reactions, its summary for the outputs,
    /// and the gaps.
    pub(super) fn accept_contact(&mut self, values: &ContactValues, t: f64) {
        self.state.contact_force.copy_from_slice(&values.force);
        self.state.contact = [
            values.energy,
            values.start,
            values.end,
            values.length,
            values.max_penetration,
        ];
        self.record_gaps(t);
    }

    /// Contact forces (and, when `tangent` is given, adds the tangent scaled by
    /// `k_scale` for stiffness and `c_scale` for damping) at deflections `q`,
    /// velocities `v`, time t. `penalty` overrides the law's penalty (statics).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn contact_at(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        lambda: &[f64],
        penalty: Option<f64>,
        mut tangent: Option<(&mut SymmetricBand, f64, f64)>,
        out: &mut ContactValues,
    ) {
        out.force.clear();
        out.force.resize(q.len(), 0.0);
        out.energy = 0.0;
        out.start = 0.0;
        out.end = 0.0;
        out.length = 0.0;
        out.max_penetration = 0.0;
        let Some(contact) = &self.params.contact else {
            return;
        };
        let law = with_penalty(&contact.method, penalty);
        let mut first = true;
        for (i, p) in self.points.iter().enumerate() {
            let Some((f, f_rate)) = contact.surface.at(p.x, t) else {
                continue;
            };
            let base = 2 * p.element;
            let y: f64 = (0..4).map(|j| p.shape[j] * q[base + j]).sum();
            let yv: f64 = (0..4).map(|j| p.shape[j] * v[base + j]).sum();
            let d = y - f;
            let (xi, g, k) = law.evaluate(d, lambda[i]);
            let mut force = g;
            let mut damping = 0.0;
            if contact.damping > 0.0 && d <= contact.gap_band {
                force += contact.damping * (yv - f_rate);
                damping = contact.damping;
            }
            out.energy += p.weight * xi;
            if d <= 0.0 {
                if first {
                    out.start = p.x;
                    first = false;
                }
                out.end = p.x;
                out.length += p.weight;
                out.max_penetration = out.max_penetration.max(-d);
            }
            for j in 0..4 {
                out.force[base + j] += p.weight * force * p.shape[j];
            }
            if let Some((m, k_scale, c_scale)) = tangent.as_mut() {
                let s = p.weight * (*k_scale * k + *c_scale * damping);
                if s != 0.0 {
                    for r in 0..4 {
                        for col in 0..=r {
                            m.add(base + r, base + col, s * p.shape[r] * p.shape[col]);
                        }
                    }
                }
            }
        }
    }

    pub(super) fn record_gaps(&mut self, t: f64) {
        if let Some(contact) = &self.params.contact {
            for (i, p) in self.points.iter().enumerate() {
                let y: f64 = (0..4)
                    .map(|j| p.shape[j] * self.state.q[2 * p.element + j])
                    .sum();
                self.state.gap[i] = contact
                    .surface
                    .at(p.x, t)
                    .map_or(f64::INFINITY, |(f, _)| y - f);
            }
        }
    }

    pub(super) fn update_lambda(&mut self, law: &Law, t: f64) {
        let Some(contact) = &self.params.contact else {
            return;
        };
        if law.lambda_update().is_none() {
            return;
        }
        for (i, p) in self.points.iter().enumerate() {
            if let Some((f, _)) = contact.surface.at(p.x, t) {
                let y: f64 = (0..4)
                    .map(|j| p.shape[j] * self.state.q[2 * p.element + j])
                    .sum();
                self.state.lambda[i] = law.updated_lambda(y - f, self.state.lambda[i]);
            }
        }
    }
}

pub(super) fn penalty_of(law: &Law) -> f64 {
    match *law {
        Law::Penalty { penalty }
        | Law::EnergyConserving { penalty }
        | Law::AugmentedLagrangian { penalty, .. }
        | Law::AugmentedBarrier { penalty, .. } => penalty,
    }
}

pub(super) fn with_penalty(law: &Law, p: Option<f64>) -> Law {
    let mut l = law.clone();
    if let Some(p) = p {
        match &mut l {
            Law::Penalty { penalty }
            | Law::EnergyConserving { penalty }
            | Law::AugmentedLagrangian { penalty, .. }
            | Law::AugmentedBarrier { penalty, .. } => *penalty = p,
        }
    }
    l
}
