//! The section's energy and its balance: kinetic, strain and potential energy,
//! and the work done on the section by everything outside them (its held or
//! driven ends, loads that vary, drag and current, moving contact surfaces,
//! Rayleigh damping), summed step by step. What the balance leaves over,
//! E - E0 - W, is the energy the time stepping made: zero for the trapezoidal
//! rule on a linear structure, negative where numerical damping removes
//! energy, positive where the stepping pumps energy in (the trapezoidal rule
//! on an unresolved nonlinear structure) — what the run's watch on energy
//! growth reads (issue 27), as commercial codes check their energy balance.

use super::NonlinearSection;
use super::params::DofCondition;
use crate::beam::boundary::TimeFunction;

/// The balance since the start of the dynamics (J).
#[derive(Copy, Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(super) struct EnergyLedger {
    /// Kinetic + strain + potential energy at the start (J).
    start: f64,
    /// Work done on the section from outside its energy since the start (J).
    work: f64,
    /// The power (W) moving contact surfaces put into the section at the
    /// current time.
    surface_power: f64,
}

impl NonlinearSection {
    /// Kinetic, strain and potential energy (J) at the current time; the
    /// potential is the contact energy plus that of the weight and the constant
    /// end loads, -f . q (zero at the stress-free shape). A linear section's strain energy is its linear model's potential
    /// (with the contact springs in it, so its contact energy is not added).
    pub fn energies(&self) -> [f64; 3] {
        let kinetic = 0.5 * self.m.quadratic_form(&self.state.v);
        let (strain, contact) = match &self.linear {
            Some(l) => (l.potential(&self.state.q), 0.0),
            None => (
                (self.state.strain_energy).unwrap_or_else(|| self.strain_energy()),
                self.state.contact.energy,
            ),
        };
        let mut work: f64 = self
            .weight
            .iter()
            .zip(&self.state.q)
            .map(|(w, q)| w * q)
            .sum();
        for r in &self.ends {
            if let DofCondition::Force(TimeFunction::Constant(f)) = r.condition {
                work += f * self.state.q[r.dof];
            }
        }
        [kinetic, strain, contact - work]
    }

    /// The elements' strain energy (J) at the current state.
    pub(super) fn strain_energy(&self) -> f64 {
        (0..self.model.elements.len())
            .map(|e| {
                self.model.elements[e].strain_energy(
                    self.model.formulation,
                    &super::model::element_dofs(&self.state.q, e),
                )
            })
            .sum()
    }

    /// Work (J) done on the section since the start of its dynamics by
    /// everything outside its kinetic, strain and potential energy: held and
    /// driven ends (their reactions), loads that vary in time or come from a
    /// coupled unit, drag and current, moving contact surfaces, and Rayleigh
    /// damping (negative: what it removed).
    pub fn external_work(&self) -> f64 {
        self.state.ledger.work
    }

    /// The energy (J) the time stepping made since the start, E - E0 - W,
    /// given the current `energies` (kinetic, strain, potential). Negative
    /// where numerical damping removed energy; positive growth is energy no
    /// physics put in.
    pub fn energy_error(&self, energies: [f64; 3]) -> f64 {
        let energy: f64 = energies.iter().sum();
        energy - self.state.ledger.start - self.state.ledger.work
    }

    /// The forces on the section from outside its energy at the current
    /// state (N, N m per DOF) into `out`, the external `load` given: the load
    /// less the weight and the constant end loads, the support reactions at
    /// the held DOFs, less drag and Rayleigh damping. After the restoring
    /// forces at that state (`refresh_forces` keeps its drag).
    fn outside_force(&self, load: &[f64], out: &mut [f64]) {
        for ((o, f), w) in out.iter_mut().zip(load).zip(&self.weight) {
            *o = f - w;
        }
        // The end elements' load moments (`moments.rs`) stay in: they follow
        // the end element's normal, so no potential of the lumped weight holds
        // their work.
        for r in &self.ends {
            match r.condition {
                DofCondition::Force(TimeFunction::Constant(f)) => out[r.dof] -= f,
                _ if r.is_kinematic() => {
                    // Assigned, not added: one DOF may be held twice.
                    out[r.dof] = load[r.dof] - self.weight[r.dof] + self.state.reaction[r.dof];
                }
                _ => {}
            }
        }
        let s = &self.state;
        if self.linear.is_some() {
            // The linear model's forces do not keep the drag at the state.
            (self.environment).add_drag_force(&self.model, (&s.q, &s.v), -1.0, out);
        } else {
            for (o, d) in out.iter_mut().zip(&self.drag_at_state) {
                *o -= d;
            }
        }
        if let Some(c) = &self.c {
            c.mul_add(-1.0, &s.v, out);
        }
    }

    /// Opens the balance at the start of the dynamics under the external
    /// `load` there.
    pub(super) fn open_ledger(&mut self, load: &[f64]) {
        let mut outside = std::mem::take(&mut self.state.outside);
        outside.resize(load.len(), 0.0);
        self.outside_force(load, &mut outside);
        self.state.outside = outside;
        self.state.ledger = EnergyLedger {
            start: self.energies().iter().sum(),
            work: 0.0,
            surface_power: self.surface_power(),
        };
    }

    /// The power (W) moving contact surfaces put into the section at the
    /// current state: the rate of their energy at a fixed shape (the force on
    /// the pipe times the surface's velocity), by a central difference over
    /// `SURFACE_DT`, of the surfaces whose laws act by their force at the
    /// step's end (those acting by their discrete gradient: `surface_jump`). Taken before `finish`
    /// updates the Lagrangian parameters, with those the step used.
    pub(super) fn surface_power(&self) -> f64 {
        let contacts = &self.environment.contacts;
        if !contacts.moves_by(false) {
            return 0.0;
        }
        let s = &self.state;
        let energy = |t| contacts.moving_energy(&self.model, (&s.q, t, &s.lambda), false);
        (energy(s.t + SURFACE_DT) - energy(s.t - SURFACE_DT)) / (2.0 * SURFACE_DT)
    }

    /// The energy (J) moving surfaces whose laws act by their discrete
    /// gradient put in over a step to `t1`: those take the surface
    /// where it is at the step's end over the whole step, so the surface
    /// moves at the step's start, its shape fixed: the contact energy of the
    /// state at the step's start between its time and `t1`. Zero otherwise.
    pub(super) fn surface_jump(&self, t1: f64) -> f64 {
        let contacts = &self.environment.contacts;
        if !contacts.moves_by(true) {
            return 0.0;
        }
        let s = &self.state;
        let energy = |t| contacts.moving_energy(&self.model, (&s.q, t, &s.lambda), true);
        energy(t1) - energy(s.t)
    }

    /// Adds a step of length `h` (s) from `q0` to the current state: the
    /// trapezoidal rule on the outside forces under the external `load` at
    /// its end and on the moving surfaces' power (`surface_power`, at its
    /// end), and their `surface_jump`. `scratch` takes the end's outside
    /// force.
    pub(super) fn record_step(
        &mut self,
        load: &[f64],
        (q0, h): (&[f64], f64),
        (surface_power, surface_jump): (f64, f64),
        scratch: &mut Vec<f64>,
    ) {
        scratch.resize(load.len(), 0.0);
        self.outside_force(load, scratch);
        let s = &mut self.state;
        let work: f64 = (s.outside.iter().zip(scratch.iter()))
            .zip(s.q.iter().zip(q0))
            .map(|((f0, f1), (q1, q0))| 0.5 * (f0 + f1) * (q1 - q0))
            .sum();
        let ledger = &mut s.ledger;
        ledger.work += work + 0.5 * (ledger.surface_power + surface_power) * h + surface_jump;
        ledger.surface_power = surface_power;
        std::mem::swap(&mut s.outside, scratch);
    }
}

/// The time step (s) of the surfaces' power's central difference: small
/// against their motions' periods (seconds), large against round-off of
/// their energy.
const SURFACE_DT: f64 = 1e-4;
