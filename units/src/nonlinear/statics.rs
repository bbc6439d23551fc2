//! Static equilibrium of a nonlinear section: Newton on the tangent stiffness with
//! load continuation (loads and prescribed end displacements ramped together,
//! increments halved on failure), from the stress-free shape or from the
//! inextensible catenary through the ends.

use super::NonlinearSection;
use super::element::Formulation;
use super::params::StartShape;
use super::start_shape::{Catenary, GroundedCatenary, Shape};
use crate::contract::{Inputs, UnitError};
use crate::numerics::banded::{BandLdlt, SymmetricBand};

/// Newton iterations per load level.
const MAX_ITERATIONS: u32 = 60;
/// Halvings of the load increment before giving up.
const MAX_HALVINGS: u32 = 12;
/// Load levels of one continuation, at most.
const MAX_LEVELS: u32 = 20_000;
/// Correction relative to max(1, |q|) at which Newton has converged.
const TOLERANCE: f64 = 1e-10;

impl NonlinearSection {
    /// The equilibrium under the loads and end positions at the current time,
    /// at rest. From the chosen start shape first; where that fails, from the
    /// other kind of start (the stress-free shape's continuation fails where
    /// the ends move far, e.g. a laid pipe lifted to its hang-off; a shape's
    /// full-load Newton where the shape is far off), so a structure starts
    /// from the defaults; not from a catenary on a stinger, which it would
    /// hang through. The error names the load level each reached.
    pub(super) fn solve_static(&mut self, inputs: Inputs<'_>) -> Result<(), UnitError> {
        let n = self.model.dofs();
        let t = self.state.t;
        let mut load = vec![0.0; n];
        // The end elements' load moments follow the iterate (`newton`).
        self.applied_load(inputs, (t, 1.0), &mut load);
        let targets: Vec<(usize, f64)> = self
            .held()
            .map(|r| (r.dof, r.motion(inputs, (t, 0.0), (0.0, 1.0), [0.0; 3])[0]))
            .collect();
        let chosen = self.params.start_shape;
        // A catenary hangs below a stinger's rollers: no fallback to it there
        // (it would find the pipe under them).
        let fallback = match chosen {
            StartShape::Reference if self.params.stinger.is_some() => None,
            StartShape::Reference => Some(StartShape::Catenary),
            StartShape::Catenary | StartShape::Points => Some(StartShape::Reference),
        };
        let mut q = vec![0.0; n];
        let mut failures = Vec::new();
        for shape in std::iter::once(chosen).chain(fallback) {
            match self.solve_from(shape, &load, &targets, &mut q) {
                Ok(total) => {
                    self.state.q.copy_from_slice(&q);
                    self.state.v.fill(0.0);
                    self.state.newton_iterations = total;
                    return Ok(());
                }
                Err(reason) => failures.push(format!("from the {} shape, {reason}", shape.name())),
            }
        }
        Err(UnitError::Numerical(format!(
            "nonlinear section: the static solve failed at t = {t} s {}",
            failures.join("; then ")
        )))
    }

    /// The equilibrium from `shape` into `q`: a shape guess at full load, or
    /// the stress-free shape with the loads and end displacements ramped
    /// (`load_steps` increments, halved on failure up to 12 times in a row
    /// and doubled back after each success, at most `MAX_LEVELS` levels).
    /// Returns the Newton iterations; the error names the level reached.
    fn solve_from(
        &self,
        shape: StartShape,
        load: &[f64],
        targets: &[(usize, f64)],
        q: &mut [f64],
    ) -> Result<u32, String> {
        let n = self.model.dofs();
        q.fill(0.0);
        match shape {
            StartShape::Reference => {}
            StartShape::Catenary => self.catenary_guess(targets, q),
            StartShape::Points => self.points_guess(q),
        }
        let direct = shape != StartShape::Reference;
        let start: Vec<f64> = targets.iter().map(|&(d, _)| q[d]).collect();
        let initial = 1.0 / f64::from(self.params.load_steps);
        let (mut level, mut increment, mut halvings) = (0.0, initial, 0);
        let mut trial = q.to_vec();
        let mut work = NewtonWork::new(n);
        let mut total = 0;
        for _ in 0..MAX_LEVELS {
            let next = if direct {
                1.0
            } else {
                (level + increment).min(1.0)
            };
            trial.copy_from_slice(q);
            for (k, &(d, target)) in targets.iter().enumerate() {
                trial[d] = start[k] + next * (target - start[k]);
            }
            match self.newton(&mut trial, next, load, targets, &mut work) {
                Ok(iterations) => {
                    total += iterations;
                    q.copy_from_slice(&trial);
                    level = next;
                    if level >= 1.0 {
                        return Ok(total);
                    }
                    halvings = 0;
                    increment = (2.0 * increment).min(initial);
                }
                Err(_) if halvings < MAX_HALVINGS && !direct => {
                    halvings += 1;
                    increment *= 0.5;
                }
                Err(reason) => {
                    return Err(format!(
                        "after reaching load level {level:.4} of 1 (trying {next:.4}): {reason}"
                    ));
                }
            }
        }
        Err(format!(
            "reached load level {level:.4} of 1 in {MAX_LEVELS} load levels"
        ))
    }

    /// Newton at load level `level`; held DOFs stay at their values in `q`.
    fn newton(
        &self,
        q: &mut [f64],
        level: f64,
        load: &[f64],
        held: &[(usize, f64)],
        w: &mut NewtonWork,
    ) -> Result<u32, String> {
        for iteration in 1..=MAX_ITERATIONS {
            w.residual.fill(0.0);
            w.tangent.fill_zero();
            self.model
                .add_internal_force(q, 1.0, Some((&mut w.tangent, 1.0)), &mut w.residual);
            self.environment.add_force(
                &self.model,
                (q, &w.zeros, self.state.t),
                &self.state.lambda,
                1.0,
                false,
                Some((&mut w.tangent, 1.0, 0.0)),
                &mut w.residual,
            );
            for (r, f) in w.residual.iter_mut().zip(load) {
                *r = -(*r - level * f);
            }
            self.add_end_load_moments((q, self.state.t), level, &mut w.residual);
            for &(d, _) in held {
                w.tangent.set_identity_row(d);
                w.residual[d] = 0.0;
            }
            let shifted = w.factorise_regularised().map_err(|()| {
                format!(
                    "the tangent stiffness is not positive definite even shifted (iteration {iteration}: a free body, a buckled or slack part)"
                )
            })?;
            if let Some(f) = &w.factor {
                f.solve_in_place(&mut w.residual);
            }
            let step = w.residual.iter().fold(0.0f64, |m, r| m.max(r.abs()));
            if !step.is_finite() {
                return Err(format!("non-finite correction at iteration {iteration}"));
            }
            // A correction that moves a node by more than the shortest element or
            // turns it by more than 0.5 rad is scaled down (a damped step).
            let limit = self.model.correction_limit(&w.residual);
            for (qi, dq) in q.iter_mut().zip(&w.residual) {
                *qi += limit * dq;
            }
            let size = q.iter().fold(1.0f64, |m, v| m.max(v.abs()));
            // A shifted step is a damped one: only a plain Newton step may converge.
            if !shifted && limit == 1.0 && step < TOLERANCE * size {
                return Ok(iteration);
            }
        }
        Err(format!(
            "Newton did not converge in {MAX_ITERATIONS} iterations"
        ))
    }

    /// The inextensible catenary through the ends at their target positions (a
    /// straight line when the chord is as long as the section), as
    /// displacements; where it would hang below a flat seabed and one end
    /// lies on it, the catenary laid on the seabed from that end.
    fn catenary_guess(&self, targets: &[(usize, f64)], q: &mut [f64]) {
        let nodes = self.model.reference.len();
        let at = |node: usize| {
            let r = self.model.reference[node];
            let mut p = r;
            for &(d, v) in targets {
                if d / 3 == node && d % 3 < 2 {
                    p[d % 3] = r[d % 3] + v;
                }
            }
            p
        };
        let (a, b) = (at(0), at(nodes - 1));
        let length = *self.model.arc.last().unwrap_or(&0.0);
        // Stretched by about its weight over EA, so every element starts in tension
        // (a slack chain without bending stiffness has no positive tangent).
        let stretch = self.params.segments.iter().fold(1e-4f64, |m, s| {
            m.max(s.submerged_weight.abs() * length / s.axial_stiffness)
        });
        let stretched = length * (1.0 + stretch);
        let free = Catenary::through(a, b, stretched);
        // A catenary that would hang below a flat seabed lies on it from its
        // lower end instead and touches down tangentially.
        let grounded = self.flat_seabed().and_then(|height| {
            let tolerance = 1e-2 * (a[1].max(b[1]) - height).abs();
            let below = free.lowest() < height - tolerance;
            below
                .then(|| GroundedCatenary::through(a, b, stretched, (height, tolerance)))
                .flatten()
        });
        let shape: &dyn Shape = match &grounded {
            Some(g) => g,
            None => &free,
        };
        for j in 0..nodes {
            let (p, angle) = shape.at(self.model.arc[j] * (1.0 + stretch));
            let r = self.model.reference[j];
            q[3 * j] = p[0] - r[0];
            q[3 * j + 1] = p[1] - r[1];
            let e = j.min(self.model.elements.len() - 1);
            let el = &self.model.elements[e];
            let rotation = angle - el.sin0.atan2(el.cos0);
            q[3 * j + 2] = match self.model.formulation {
                Formulation::Corotational => rotation,
                Formulation::Seed002 => rotation.sin().atan2(rotation.cos()),
            };
        }
    }
}

impl NonlinearSection {
    /// The height (m) of a flat seabed, if the section has one.
    fn flat_seabed(&self) -> Option<f64> {
        match self.params.contact.as_ref()?.surface.shape {
            crate::contact::surface::Shape::Flat { height } => Some(height),
            _ => None,
        }
    }
}

impl NonlinearSection {
    /// The nodes spread over the polyline `start_points` in proportion to their
    /// arc length, each rotated to the direction between its neighbours.
    fn points_guess(&self, q: &mut [f64]) {
        let points = &self.params.start_points;
        let mut cumulative = vec![0.0];
        for w in points.windows(2) {
            let l = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
            cumulative.push(cumulative.last().unwrap_or(&0.0) + l);
        }
        let total = *cumulative.last().unwrap_or(&1.0);
        let length = *self.model.arc.last().unwrap_or(&1.0);
        let on_polyline = |s: f64| {
            let target = s / length * total;
            let i = cumulative
                .partition_point(|&c| c <= target)
                .clamp(1, points.len() - 1);
            let f = (target - cumulative[i - 1]) / (cumulative[i] - cumulative[i - 1]);
            let (a, b) = (points[i - 1], points[i]);
            [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]
        };
        let nodes = self.model.reference.len();
        let guess: Vec<[f64; 2]> = self.model.arc.iter().map(|&s| on_polyline(s)).collect();
        for j in 0..nodes {
            let (a, b) = (guess[j.saturating_sub(1)], guess[(j + 1).min(nodes - 1)]);
            let angle = (b[1] - a[1]).atan2(b[0] - a[0]);
            let r = self.model.reference[j];
            let el = &self.model.elements[j.min(nodes - 2)];
            let rotation = angle - el.sin0.atan2(el.cos0);
            q[3 * j] = guess[j][0] - r[0];
            q[3 * j + 1] = guess[j][1] - r[1];
            q[3 * j + 2] = rotation.sin().atan2(rotation.cos());
        }
    }
}

/// Buffers of the static Newton iterations.
struct NewtonWork {
    residual: Vec<f64>,
    zeros: Vec<f64>,
    tangent: SymmetricBand,
    shifted: SymmetricBand,
    factor: Option<BandLdlt>,
}

impl NewtonWork {
    fn new(n: usize) -> NewtonWork {
        NewtonWork {
            residual: vec![0.0; n],
            zeros: vec![0.0; n],
            tangent: SymmetricBand::zeros(n, super::model::BAND),
            shifted: SymmetricBand::zeros(n, super::model::BAND),
            factor: None,
        }
    }

    /// Factorises the tangent; where it is not positive definite (a mechanism held
    /// only by the load it is about to carry, e.g. a string at zero tension),
    /// factorises `K + mu diag(K)` instead with mu = 1e-8, 1e-7, ... 1e2
    /// (Levenberg-Marquardt). Returns whether it shifted; `Err` when no shift helps.
    fn factorise_regularised(&mut self) -> Result<bool, ()> {
        if self.refactorise(false) {
            return Ok(false);
        }
        let mut mu = 1e-8;
        while mu <= 1e2 {
            self.shifted.copy_from(&self.tangent);
            for i in 0..self.tangent.size() {
                let d = self.tangent.get(i, i).abs().max(1e-12);
                self.shifted.add(i, i, mu * d);
            }
            if self.refactorise(true) {
                return Ok(true);
            }
            mu *= 10.0;
        }
        Err(())
    }

    fn refactorise(&mut self, shifted: bool) -> bool {
        let a = if shifted {
            &self.shifted
        } else {
            &self.tangent
        };
        match self.factor.as_mut() {
            Some(f) => f.refactorise(a),
            None => {
                self.factor = BandLdlt::new(a);
                self.factor.is_some()
            }
        }
    }
}
