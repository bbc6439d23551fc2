//! The 3D line's dynamics: a coupling step cut into internal steps, each an
//! HHT-alpha step with Newton; the ends' prescribed motion and loads; the
//! force at each step's end, which gives the ends' reactions, the next step's
//! start force and the energy ledger (work by the trapezoidal rule).

use super::Line3d;
use super::mechanics::BAND;
use super::mechanics::{DOF, node};
use super::params::{EndCondition, EndSpec};
use crate::contract::{Inputs, UnitError, require_finite_state};
use crate::integrators::hht::{
    Matrices, NewtonSettings, SecondOrderSystem, StepLoads, TangentScales, motion_fields,
};
use crate::numerics::banded::SymmetricBand;
use crate::signal::sine::faded_sum;

/// Step buffers, sized once.
#[derive(Default)]
pub(super) struct Work {
    f0: Vec<f64>,
    f1: Vec<f64>,
    g0: Vec<f64>,
    held: Vec<(usize, [f64; 3])>,
    /// A linear line's water force at the step's start and end (N), and its
    /// step's loads.
    water0: Vec<f64>,
    water1: Vec<f64>,
    linear_f0: Vec<f64>,
    linear_f1: Vec<f64>,
    /// The nodes' predicted positions at the step's end (m), where the
    /// waves' kinematics are taken.
    predicted: Vec<f64>,
}

/// The energy ledger (J).
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(super) struct Ledger {
    /// Kinetic, strain and potential energy at the start of the dynamics.
    pub initial: f64,
    /// Work done on the line since by its ends, the water (drag and wave
    /// inertia), seabed friction, the seabed's damper and the axial damper.
    pub work: [f64; 5],
    /// The powers (W) of the same at the current time.
    pub power: [f64; 5],
}

/// How many times an internal step is halved before Newton's failure is
/// reported (down to 1/64 of it).
const HALVINGS: u32 = 6;

/// Where each power goes in the ledger.
const ENDS: usize = 0;
const WATER: usize = 1;
pub(super) const FRICTION: usize = 2;
const SEABED_DAMPER: usize = 3;
const AXIAL_DAMPER: usize = 4;

/// Position, velocity and acceleration (m, m/s, m/s^2) of a fixed or moved
/// end at `t` (s from the start of the run), the sines faded in.
pub(super) fn end_motion(end: &EndSpec, t: f64) -> [[f64; 3]; 3] {
    let mut out = [[0.0; 3]; 3];
    for (axis, sines) in end.motion.iter().enumerate() {
        let [x, v, a] = faded_sum(end.position[axis], sines, end.fade_in, t);
        [out[0][axis], out[1][axis], out[2][axis]] = [x, v, a];
    }
    out
}

/// Position, velocity and acceleration at a step's end of a DOF moved to
/// velocity `v1` (m/s) over `h` (s) from its `start` motion, by Newmark with
/// HHT-alpha's `(alpha, beta, gamma)`: as the integrator moves every other
/// node, so a cut driven by the neighbour's velocity stays closed.
pub(super) fn follow_velocity(
    [q0, v0, a0]: [f64; 3],
    v1: f64,
    h: f64,
    (_, beta, gamma): (f64, f64, f64),
) -> [f64; 3] {
    let a1 = (v1 - v0) / (gamma * h) - (1.0 - gamma) / gamma * a0;
    let q1 = q0 + h * v0 + h * h * ((0.5 - beta) * a0 + beta * a1);
    [q1, v1, a1]
}

impl Line3d {
    /// Sets the start of the dynamics at the static shape `q`.
    pub(super) fn start_dynamics(&mut self, q: Vec<f64>, inputs: &Inputs<'_>, t0: f64) {
        let n = q.len();
        self.state.q = q;
        self.state.v = vec![0.0; n];
        self.state.a = vec![0.0; n];
        self.state.t = t0;
        self.state.newton_iterations = 0;
        self.state.released = [false; 2];
        for (k, end) in [&self.params.start, &self.params.end].iter().enumerate() {
            let node = if k == 0 { 0 } else { self.mechanics.nodes - 1 };
            let velocity = match (end.condition, self.first_input[k]) {
                (EndCondition::Velocity, Some(first)) => {
                    [0, 1, 2].map(|c| inputs.at(first + c, 1.0))
                }
                _ => end_motion(end, t0)[1],
            };
            if end.condition != EndCondition::Force {
                self.state.v[DOF * node..DOF * node + DOF].copy_from_slice(&velocity);
            }
        }
        let mut external = vec![0.0; n];
        self.end_loads(inputs, 1.0, &mut external);
        for (f, w) in external.iter_mut().zip(&self.weight) {
            *f += w;
        }
        let q = std::mem::take(&mut self.state.q);
        let v = std::mem::take(&mut self.state.v);
        let mut w = std::mem::take(&mut self.work);
        self.water(&q, &v, t0, &mut w.water1);
        let surroundings = self.evaluate_end(&q, &v, t0, (&external, &w.water1));
        self.work = w;
        self.state.q = q;
        self.state.v = v;
        self.update_linear_energy();
        self.state.ledger = Ledger {
            initial: self.energies().iter().sum(),
            ..Ledger::default()
        };
        self.evaluate_end_powers(surroundings);
    }

    /// One coupling step from `t` of length `h` (s); returns Newton's iterations.
    pub(super) fn step_coupling(
        &mut self,
        t: f64,
        h: f64,
        inputs: &Inputs<'_>,
    ) -> Result<u32, UnitError> {
        let max = self.params.max_step;
        let count = if max > 0.0 {
            (h / max - 1e-9).ceil().max(1.0) as usize
        } else {
            1
        };
        let mut iterations = 0;
        self.jacobian.ready = false;
        self.jacobian.h = h;
        let released = [self.params.start.released(t), self.params.end.released(t)];
        if released != self.state.released {
            // The held set changed: the Newton matrices are formed anew.
            self.state.released = released;
            self.hht.forget_matrices();
        }
        let mut whole = count == 1;
        // A repeated step (`Unit::warm_repeat`) starts Newton from the last
        // attempt moved by its derivatives.
        if let (true, Some(guess)) = (whole, self.jacobian.warm.guess(t, inputs.end())) {
            self.hht.guess_next(guess);
        }
        for k in 0..count {
            let (s0, s1) = (k as f64 / count as f64, (k + 1) as f64 / count as f64);
            let (taken, steps) = self.halving_step(t, h, inputs, [s0, s1], 0)?;
            iterations += taken;
            whole &= steps == 1;
        }
        self.jacobian.ready = whole;
        if whole {
            let mut warm = std::mem::take(&mut self.jacobian.warm);
            warm.record_step(t, inputs.end(), &self.state.q);
            self.jacobian.warm = warm;
        }
        self.state.newton_iterations = iterations;
        Ok(iterations)
    }

    /// The internal step over fractions `s` of the coupling step [t, t + h];
    /// where Newton fails (a snap, a contact or a slack part changing state
    /// within the step), the step is repeated as two halves, down to
    /// 1/2^HALVINGS of it, before the failure is reported. Returns Newton's
    /// iterations and the internal steps taken.
    fn halving_step(
        &mut self,
        t: f64,
        h: f64,
        inputs: &Inputs<'_>,
        s: [f64; 2],
        depth: u32,
    ) -> Result<(u32, u32), UnitError> {
        let t0 = t + s[0] * h;
        let length = (s[1] - s[0]) * h;
        match self.internal_step(t0, length, inputs, s) {
            Ok(iterations) => Ok((iterations, 1)),
            Err(error) if depth >= HALVINGS => Err(error),
            Err(_) => {
                let middle = 0.5 * (s[0] + s[1]);
                let (a, m) = self.halving_step(t, h, inputs, [s[0], middle], depth + 1)?;
                let (b, n) = self.halving_step(t, h, inputs, [middle, s[1]], depth + 1)?;
                Ok((a + b, m + n))
            }
        }
    }

    /// One HHT-alpha step from `t0` of length `h`, the inputs at fractions `s`
    /// of the coupling step.
    fn internal_step(
        &mut self,
        t0: f64,
        h: f64,
        inputs: &Inputs<'_>,
        s: [f64; 2],
    ) -> Result<u32, UnitError> {
        let t1 = t0 + h;
        let n = self.state.q.len();
        let mut w = std::mem::take(&mut self.work);
        w.f0.resize(n, 0.0);
        w.f1.resize(n, 0.0);
        self.end_loads(inputs, s[0], &mut w.f0);
        self.end_loads(inputs, s[1], &mut w.f1);
        for (f, g) in
            w.f0.iter_mut()
                .chain(w.f1.iter_mut())
                .zip(self.weight.iter().cycle())
        {
            *f += g;
        }
        w.g0.clone_from(&self.state.force);
        self.held_motion(inputs, (t1, h), s, &mut w.held);
        self.hold_waves((t1, h), &w.held, &mut w.predicted);
        self.linear_loads(t0, t1, &mut w);
        let mut hht = std::mem::take(&mut self.hht);
        let linear = self.linear.is_some();
        let loads = StepLoads {
            t0,
            t1,
            h,
            f0: if linear { &w.linear_f0 } else { &w.f0 },
            f1: if linear { &w.linear_f1 } else { &w.f1 },
            g0: (!linear).then_some(w.g0.as_slice()),
            held: &w.held,
        };
        let newton = NewtonSettings {
            tolerance: self.params.tolerance,
            max_iterations: self.params.max_iterations,
        };
        let result = hht.step(self, &loads, newton);
        self.hht = hht;
        let iterations = match result {
            Ok(iterations) => iterations,
            Err(error) => {
                self.work = w;
                return Err(error);
            }
        };
        if let Err(error) = require_finite_state("line3d positions", &self.state.q) {
            self.work = w;
            return Err(error);
        }
        self.state.t = t1;
        self.end_of_step(w, h, 1.0);
        Ok(iterations)
    }

    /// The step's end evaluated at the current state under the loads `w.f1`
    /// and the water's force `w.water1` (force, reactions, energies, powers;
    /// `w` is put back), and the trapezoid h / 2 (weight p0 + p1) of each
    /// power into the ledger, p0 the powers before: weight 1 for a step, -1
    /// for a correction (the moved end's share replaces the last one's).
    fn end_of_step(&mut self, w: Work, h: f64, weight: f64) {
        let before = self.state.ledger.power;
        let (q, v) = (
            std::mem::take(&mut self.state.q),
            std::mem::take(&mut self.state.v),
        );
        let surroundings = self.evaluate_end(&q, &v, self.state.t, (&w.f1, &w.water1));
        self.work = w;
        self.state.q = q;
        self.state.v = v;
        self.update_linear_energy();
        self.evaluate_end_powers(surroundings);
        let ledger = &mut self.state.ledger;
        for ((work, start), end) in ledger.work.iter_mut().zip(before).zip(ledger.power) {
            *work += 0.5 * h * (weight * start + end);
        }
    }

    /// The last coupling step with its end inputs moved by `change`, to first
    /// order (`Unit::correct_step`): the coordinates move by the step's
    /// derivatives (the columns its Jacobian solved for), the velocities and
    /// accelerations by Newmark's relations for a change of the end
    /// coordinates, and the end's force, reactions and energy ledger are
    /// evaluated again at the moved state (the ledger's last trapezoid with
    /// the moved end powers). `inputs`: the moved end inputs.
    pub(super) fn correct_last_step(
        &mut self,
        inputs: &Inputs<'_>,
        change: &[f64],
    ) -> Result<(), UnitError> {
        let n = self.state.q.len();
        let mut w = std::mem::take(&mut self.work);
        // `w.f1` holds the coordinates' change first, then the moved loads.
        w.f1.clear();
        w.f1.resize(n, 0.0);
        let known = self.jacobian.ready && self.jacobian.warm.add_change(change, &mut w.f1);
        if !known {
            self.work = w;
            return Err(UnitError::State(
                "line3d: a step correction needs the step's Jacobian, taken after a whole step"
                    .into(),
            ));
        }
        let (_, beta, gamma) = self.hht.parameters();
        let h = self.jacobian.h;
        let s = &mut self.state;
        for (i, dq) in w.f1.iter().enumerate() {
            s.q[i] += dq;
            s.v[i] += gamma / (beta * h) * dq;
            s.a[i] += dq / (beta * h * h);
        }
        self.jacobian.ready = false;
        self.end_loads(inputs, 1.0, &mut w.f1);
        for (f, g) in w.f1.iter_mut().zip(&self.weight) {
            *f += g;
        }
        self.end_of_step(w, h, -1.0);
        require_finite_state("line3d positions", &self.state.q)
    }

    /// The waves' kinematics for the step ending at `t1` (s), `h` long, taken
    /// once at the nodes' predicted end positions `q + h v + h^2 a / 2` (the
    /// `held` DOFs' at their prescribed ones; `predicted`: a buffer), unless
    /// the line is linear (it holds its water's force itself) or has no waves.
    fn hold_waves(
        &mut self,
        (t1, h): (f64, f64),
        held: &[(usize, [f64; 3])],
        predicted: &mut Vec<f64>,
    ) {
        if self.linear.is_some() || !self.environment.has_waves() {
            return;
        }
        let s = &self.state;
        predicted.clear();
        predicted.extend(
            (s.q.iter().zip(&s.v).zip(&s.a)).map(|((q, v), a)| q + h * v + 0.5 * h * h * a),
        );
        for &(d, [q, _, _]) in held {
            predicted[d] = q;
        }
        self.environment.hold_waves(predicted, t1);
    }

    /// The prescribed motion of the held DOFs at the step's end.
    fn held_motion(
        &self,
        inputs: &Inputs<'_>,
        (t1, h): (f64, f64),
        s: [f64; 2],
        held: &mut Vec<(usize, [f64; 3])>,
    ) {
        held.clear();
        for (k, end) in [&self.params.start, &self.params.end].iter().enumerate() {
            let node = if k == 0 { 0 } else { self.mechanics.nodes - 1 };
            for c in 0..DOF {
                let d = DOF * node + c;
                if self.state.released[k] {
                    continue;
                }
                let motion = match (end.condition, self.first_input[k]) {
                    (EndCondition::Force, _) => continue,
                    (EndCondition::Velocity, Some(first)) => {
                        // Newmark from the node's own start motion, as the
                        // integrator moves the neighbour that drives it: a
                        // cut between two sections stays closed and its
                        // reaction's inertia is the integrator's.
                        let start = [self.state.q[d], self.state.v[d], self.state.a[d]];
                        let v1 = inputs.at(first + c, s[1]);
                        follow_velocity(start, v1, h, self.hht.parameters())
                    }
                    _ => {
                        let m = end_motion(end, t1);
                        [m[0][c], m[1][c], m[2][c]]
                    }
                };
                held.push((d, motion));
            }
        }
    }

    /// The force g at (q, v, t) into the state, the reactions of the held
    /// ends (M a + g - f, reversed) and the loaded ends' loads (reversed);
    /// `external` is f: the weight and the loads on loaded ends (N), and
    /// `water` the water's force a linear line's step held. Returns the powers
    /// (W) of the water, friction and the seabed's damper, from the same pass
    /// over the nodes.
    fn evaluate_end(
        &mut self,
        q: &[f64],
        v: &[f64],
        t: f64,
        (external, water): (&[f64], &[f64]),
    ) -> [f64; 3] {
        let mut force = std::mem::take(&mut self.state.force);
        force.resize(q.len(), 0.0);
        force.fill(0.0);
        let surroundings = match self.linear.as_mut() {
            Some(l) => {
                l.force(q, v, water, &mut force);
                let [friction, damper] = l.seabed_dissipation(v);
                [l.water_power(water, v), friction, damper]
            }
            None => {
                self.mechanics.add_force(q, v, 1.0, None, &mut force);
                self.environment.add_force_and_powers(q, v, t, &mut force)
            }
        };
        let n = q.len();
        for (k, end) in [&self.params.start, &self.params.end].iter().enumerate() {
            let node = if k == 0 { 0 } else { self.mechanics.nodes - 1 };
            for c in 0..DOF {
                let d = DOF * node + c;
                let columns = d.saturating_sub(BAND)..(d + BAND + 1).min(n);
                let ma: f64 = columns.map(|j| self.mass.get(d, j) * self.state.a[j]).sum();
                self.state.reaction[DOF * k + c] = match end.condition {
                    _ if self.state.released[k] => 0.0,
                    EndCondition::Force => -(external[d] - self.weight[d]),
                    _ => -(ma + force[d] - external[d]),
                };
            }
        }
        self.state.force = force;
        surroundings
    }

    /// The powers (W) at the current state into the ledger: the ends' from
    /// their reactions, the axial damper's, and `surroundings` (water,
    /// friction, seabed damper) as `evaluate_end` found them.
    fn evaluate_end_powers(&mut self, surroundings: [f64; 3]) {
        let (q, v) = (&self.state.q, &self.state.v);
        let mut power = [0.0; 5];
        let last = self.mechanics.nodes - 1;
        for (k, node_index) in [0, last].into_iter().enumerate() {
            let on_line: nalgebra::Vector3<f64> =
                -nalgebra::Vector3::from_column_slice(&self.state.reaction[DOF * k..DOF * k + DOF]);
            power[ENDS] += on_line.dot(&node(v, node_index));
        }
        [power[WATER], power[FRICTION], power[SEABED_DAMPER]] = surroundings;
        power[AXIAL_DAMPER] = match &self.linear {
            Some(l) => l.axial_dissipation(v),
            None => self.mechanics.damper_power(q, v),
        };
        self.state.ledger.power = power;
    }

    /// Kinetic, strain and potential energy (J; potential of the weight and
    /// of the seabed's spring).
    /// (The linear model's own where the line is linear.)
    pub(super) fn energies(&self) -> [f64; 3] {
        let q = &self.state.q;
        let kinetic = 0.5 * self.mass.quadratic_form(&self.state.v);
        let mut potential: f64 = -self.weight.iter().zip(q).map(|(w, x)| w * x).sum::<f64>();
        if self.linear.is_some() {
            let [strain, seabed] = self.state.linear_energy;
            return [kinetic, strain, potential + seabed];
        }
        let strain = self.mechanics.strain_energy(q);
        if let Some(seabed) = &self.environment.seabed {
            potential += self.environment.seabed_energy(seabed, q);
        }
        [kinetic, strain, potential]
    }

    /// A linear line's energies at the current state into the state.
    fn update_linear_energy(&mut self) {
        if let Some(l) = &mut self.linear {
            self.state.linear_energy = l.energies(&self.state.q);
        }
    }

    /// The water's force (N) at (q, v, t) into `out` (zeros without water).
    fn water(&self, q: &[f64], v: &[f64], t: f64, out: &mut Vec<f64>) {
        out.clear();
        out.resize(q.len(), 0.0);
        if self.linear.is_some() {
            self.environment.add_hydrodynamic_force(q, v, t, out);
        }
    }

    /// A linear line's step loads: f + water - offset at the step's start
    /// and end, the water's force at the start state with the water's motion
    /// at `t0` and `t1`, its drag linearised there (its tangent D_0 in the
    /// step's damping, the water's forces less D_0 v_0: no-op on a nonlinear
    /// line).
    fn linear_loads(&mut self, t0: f64, t1: f64, w: &mut Work) {
        let waves = self.environment.has_waves();
        if waves {
            self.water(&self.state.q, &self.state.v, t1, &mut w.water1);
        }
        let Some(l) = &mut self.linear else {
            return;
        };
        let (q, v) = (&self.state.q, &self.state.v);
        w.water0.clear();
        w.water0.resize(q.len(), 0.0);
        let tangent = l.has_drag.then(|| {
            l.water_tangent.fill_zero();
            &mut l.water_tangent
        });
        (self.environment).add_hydrodynamic_force_with_tangent(q, v, t0, &mut w.water0, tangent);
        if !waves {
            // A current alone does not change over the step.
            w.water1.clone_from(&w.water0);
        }
        l.linearise_water(v, [&mut w.water0, &mut w.water1]);
        l.step_loads(&w.f0, &w.water0, &mut w.linear_f0);
        l.step_loads(&w.f1, &w.water1, &mut w.linear_f1);
    }
}

impl SecondOrderSystem for Line3d {
    fn label(&self) -> &str {
        "line3d"
    }

    fn matrices(&self) -> Matrices<'_> {
        Matrices {
            mass: &self.mass,
            damping: self.linear.as_ref().map(|l| &l.step_damping),
            stiffness: self.linear.as_ref().map(|l| &l.stiffness),
            varies: self.linear.as_ref().is_some_and(|l| l.has_drag),
        }
    }

    motion_fields!(state);

    fn is_linear(&self) -> bool {
        self.linear.is_some()
    }

    fn nonlinear_force(
        &mut self,
        q: &[f64],
        v: &[f64],
        t: f64,
        tangent: Option<(&mut SymmetricBand, TangentScales)>,
        force: &mut Vec<f64>,
    ) {
        force.resize(q.len(), 0.0);
        force.fill(0.0);
        let (mut band, scales) = TangentScales::split(tangent);
        let (k, c) = (scales.stiffness, scales.damping);
        let mechanics_tangent = band.as_mut().map(|b| (&mut **b, k, c));
        self.mechanics.add_force(q, v, k, mechanics_tangent, force);
        let environment_tangent = band.map(|b| (b, k, c));
        self.environment
            .add_force(q, v, t, k, environment_tangent, force);
    }
}
