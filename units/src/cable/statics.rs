//! Static equilibrium of a cable hanging from a fixed bottom node under a top
//! force, its weight and the current drag, by Newton-Raphson with line search.

use super::current::CurrentProfile;
use super::drag::Drag;
use super::elements::{ElementProperties, element_state, internal_forces, stiffness};
use crate::contract::UnitError;
use crate::numerics::banded::{BandLdlt, SymmetricBand};

/// Distributed static loads.
#[derive(Clone, Debug)]
pub struct StaticLoads {
    /// Submerged weight per unit length (N/m), 0 when the effect is off.
    pub weight: f64,
    /// Current drag: density, diameter, normal and tangential coefficients,
    /// profile and water depth; `None` when drag or current is off.
    pub current: Option<(f64, f64, f64, f64, CurrentProfile, f64)>,
}

impl StaticLoads {
    /// The static drag of the current on a cable at positions `x` (N per node).
    pub fn drag(&self, p: &ElementProperties, x: &[[f64; 2]]) -> Option<Drag> {
        let (rho, d, cdn, cdt, profile, depth) = self.current.as_ref()?;
        let n = x.len() - 1;
        let mut dirs = Vec::with_capacity(n);
        let mut speeds = Vec::with_capacity(n);
        for e in 0..n {
            let (dir, _, _) = element_state(p, x[e], x[e + 1]);
            dirs.push(dir);
            speeds.push(profile.speed(0.5 * (x[e][1] + x[e + 1][1]), *depth));
        }
        Some(Drag::new(*rho, *d, *cdn, *cdt, p.length, dirs, speeds))
    }

    /// External nodal loads: weight and current drag (not the top force).
    pub fn nodal(&self, p: &ElementProperties, x: &[[f64; 2]], out: &mut [[f64; 2]]) {
        out.iter_mut().for_each(|f| *f = [0.0, 0.0]);
        let half = 0.5 * self.weight * p.length;
        for e in 0..x.len() - 1 {
            out[e][1] -= half;
            out[e + 1][1] -= half;
        }
        if let Some(drag) = self.drag(p, x) {
            let still = vec![[0.0; 2]; x.len()];
            drag.add_forces(&still, out);
        }
    }
}

/// A converged static state.
#[derive(Clone, Debug)]
pub struct StaticState {
    /// Node positions (m), bottom first.
    pub positions: Vec<[f64; 2]>,
    /// Element tensions (N).
    pub tensions: Vec<f64>,
    /// Newton iterations used.
    pub iterations: u32,
}

/// The free-DOF block (DOFs `from..`) of a banded matrix.
pub fn trailing_block(m: &SymmetricBand, from: usize) -> SymmetricBand {
    let n = m.size() - from;
    let w = m.half_bandwidth();
    let mut out = SymmetricBand::zeros(n, w);
    for i in 0..n {
        for k in 0..=w.min(i) {
            out.add(i, i - k, m.get(from + i, from + i - k));
        }
    }
    out
}

/// A straight first guess: from `bottom` along the top force, stretched by the
/// top tension.
pub fn straight_guess(
    p: &ElementProperties,
    bottom: [f64; 2],
    top_force: [f64; 2],
    elements: usize,
) -> Vec<[f64; 2]> {
    let f = (top_force[0].powi(2) + top_force[1].powi(2)).sqrt();
    let dir = if f > 0.0 {
        [top_force[0] / f, top_force[1] / f]
    } else {
        [0.0, 1.0]
    };
    let l = p.length * (1.0 + f / p.axial_stiffness);
    (0..=elements)
        .map(|j| {
            [
                bottom[0] + dir[0] * l * j as f64,
                bottom[1] + dir[1] * l * j as f64,
            ]
        })
        .collect()
}

/// The residual of the static equilibrium at given positions, with its buffers:
/// internal (bar tensions) plus external (weight, current drag, top force) nodal
/// forces of the free nodes.
struct Equilibrium<'a> {
    p: &'a ElementProperties,
    loads: &'a StaticLoads,
    top_force: [f64; 2],
    tensions: Vec<f64>,
    internal: Vec<[f64; 2]>,
    external: Vec<[f64; 2]>,
    residual: Vec<f64>,
}

impl Equilibrium<'_> {
    /// Fills the residual at `x`; returns its largest entry (N).
    fn evaluate(&mut self, x: &[[f64; 2]]) -> f64 {
        let (nodes, m) = (x.len(), x.len() - 1);
        internal_forces(self.p, x, &mut self.internal, &mut self.tensions);
        self.loads.nodal(self.p, x, &mut self.external);
        self.external[m][0] += self.top_force[0];
        self.external[m][1] += self.top_force[1];
        let mut worst: f64 = 0.0;
        for j in 1..nodes {
            for c in 0..2 {
                let v = self.internal[j][c] + self.external[j][c];
                self.residual[2 * (j - 1) + c] = v;
                worst = worst.max(v.abs());
            }
        }
        worst
    }

    /// Halves the Newton step while the residual grows (at most 12 times); the
    /// accepted positions go into `trial`. Returns the new residual norm, or
    /// `None` when no fraction of the step reduces it.
    fn line_search(
        &mut self,
        x: &[[f64; 2]],
        step: &[f64],
        norm: f64,
        trial: &mut [[f64; 2]],
    ) -> Option<f64> {
        let mut fraction = 1.0;
        for _ in 0..12 {
            for j in 1..x.len() {
                for c in 0..2 {
                    trial[j][c] = x[j][c] + fraction * step[2 * (j - 1) + c];
                }
            }
            let n = self.evaluate(trial);
            if n.is_finite() && n < norm {
                return Some(n);
            }
            fraction *= 0.5;
        }
        None
    }
}

/// Solves for the node positions with the bottom node fixed at `guess[0]` and
/// `top_force` (N) on the last node. Fails, with the residual history, when the
/// line goes slack or Newton does not converge in 100 iterations.
pub fn solve(
    p: &ElementProperties,
    loads: &StaticLoads,
    top_force: [f64; 2],
    mut x: Vec<[f64; 2]>,
    tolerance: f64,
) -> Result<StaticState, UnitError> {
    let nodes = x.len();
    let m = nodes - 1;
    let scale = (top_force[0].powi(2) + top_force[1].powi(2))
        .sqrt()
        .max(loads.weight * p.length * m as f64)
        .max(1.0);
    let mut eq = Equilibrium {
        p,
        loads,
        top_force,
        tensions: vec![0.0; m],
        internal: vec![[0.0; 2]; nodes],
        external: vec![[0.0; 2]; nodes],
        residual: vec![0.0; 2 * m],
    };
    let mut history = Vec::new();
    let mut norm = eq.evaluate(&x);
    // Round-off floor: positions of size |x| carry eps |x| of error, which the axial
    // stiffness EA / L0 turns into forces.
    let extent = x
        .iter()
        .fold(0.0f64, |a, p| a.max(p[0].abs()).max(p[1].abs()));
    let floor = 1e3 * f64::EPSILON * (p.axial_stiffness / p.length) * extent.max(p.length);
    let target = (tolerance * scale).max(floor);
    let mut trial = x.clone();
    for iteration in 0..100u32 {
        history.push(norm);
        if norm <= target {
            return Ok(StaticState {
                positions: x,
                tensions: eq.tensions,
                iterations: iteration,
            });
        }
        let k = trailing_block(&stiffness(p, &x, true), 2);
        let Some(factor) = BandLdlt::new(&k) else {
            return Err(UnitError::Numerical(format!(
                "static equilibrium: the line is slack or in compression at Newton iteration {iteration} (smallest tension {:.3e} N); the top force ({:.4e}, {:.4e}) N cannot hold it. Residual history (N): {}",
                eq.tensions.iter().copied().fold(f64::INFINITY, f64::min),
                top_force[0],
                top_force[1],
                format_history(&history)
            )));
        };
        let mut step = eq.residual.clone();
        factor.solve_in_place(&mut step);
        trial.clone_from(&x);
        let Some(n) = eq.line_search(&x, &step, norm, &mut trial) else {
            return Err(UnitError::Numerical(format!(
                "static equilibrium: Newton made no progress at iteration {iteration}. Residual history (N): {}",
                format_history(&history)
            )));
        };
        norm = n;
        x.clone_from(&trial);
    }
    Err(UnitError::Numerical(format!(
        "static equilibrium: no convergence in 100 Newton iterations. Residual history (N): {}",
        format_history(&history)
    )))
}

/// Refuses a static shape that goes below the seabed: the model has no seabed
/// contact, so such a "solution" means the top force cannot hold the line up.
pub fn check_above_seabed(
    state: &StaticState,
    seabed: f64,
    top_force: [f64; 2],
    length: f64,
) -> Result<(), UnitError> {
    let (j, lowest) = state
        .positions
        .iter()
        .enumerate()
        .map(|(j, p)| (j, p[1]))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, seabed));
    if lowest < seabed - 1e-6 * length {
        return Err(UnitError::Numerical(format!(
            "static equilibrium: node {j} lies at z = {lowest:.2} m, below the seabed (z = {seabed} m): the top force ({:.4e}, {:.4e}) N cannot hold the line up, and the cable model has no seabed contact",
            top_force[0], top_force[1]
        )));
    }
    Ok(())
}

fn format_history(h: &[f64]) -> String {
    h.iter()
        .map(|v| format!("{v:.3e}"))
        .collect::<Vec<_>>()
        .join(", ")
}
