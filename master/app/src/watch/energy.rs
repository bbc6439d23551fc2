//! The watch on energy growth: a `nonlinear` section reports its energy
//! balance, the energy its time stepping made since the start
//! (`energy_error`, J: kinetic + strain + potential energy now, less at the
//! start, less the work done on it from outside). Rayleigh and numerical
//! damping only remove energy, so a stable run keeps it at round-off or
//! below zero; the trapezoidal rule (`alpha = 0`) on a structure whose mesh
//! does not resolve its bending can pump energy in without bound, with loads
//! that still look possible (the steel catenary riser at 50 elements: 2.6 MN
//! at the top where the converged run stays at 1.06 MN). A section's error
//! beyond `energy_growth` times the largest energy any section exchanged so
//! far (its kinetic energy, or the change of its strain or potential energy,
//! or its external work), and beyond 1e-4 of its strain energy (the floor its
//! solver knows the balance to), is a warning, once per section.

use slender_coupling::coupler::Master;
use slender_scene::spec::WatchSpec;

/// The part of a section's strain energy its balance is known to: the
/// energies are sums over the elements of a state solved to a relative
/// tolerance of about 1e-6, so a pretensioned line (a mooring line holding
/// 220 kJ) shows errors of some 1e-5 of it from its first step, before it
/// has exchanged anything with its surroundings.
const SOLVER_FLOOR: f64 = 1e-4;

/// The ports of one section's balance, and its start energies (J).
struct Balance {
    unit: usize,
    error: usize,
    work: usize,
    kinetic: usize,
    strain: (usize, f64),
    potential: (usize, f64),
    warned: bool,
}

impl Balance {
    /// The section's largest energy exchanged at the current time (J).
    fn exchanged(&self, outputs: &[f64]) -> f64 {
        let (strain, strain0) = self.strain;
        let (potential, potential0) = self.potential;
        [
            outputs[self.kinetic].abs(),
            outputs[self.work].abs(),
            (outputs[strain] - strain0).abs(),
            (outputs[potential] - potential0).abs(),
        ]
        .into_iter()
        .filter(|e| e.is_finite())
        .fold(0.0, f64::max)
    }
}

/// The watch on the sections' energy balances over a run.
pub(super) struct EnergyWatch {
    sections: Vec<Balance>,
    fraction: f64,
    /// The largest energy any section exchanged so far (J).
    scale: f64,
}

impl EnergyWatch {
    /// Every unit with the balance's outputs, after `Master::initialize`.
    pub(super) fn new(master: &Master, spec: &WatchSpec) -> EnergyWatch {
        let sections = (0..master.unit_names().count())
            .filter_map(|unit| {
                let ports = &master.description(unit).outputs;
                let find = |name: &str| ports.iter().position(|p| p.name == name);
                let outputs = master.outputs(unit);
                let strain = find("strain_energy")?;
                let potential = find("potential_energy")?;
                Some(Balance {
                    unit,
                    error: find("energy_error")?,
                    work: find("external_work")?,
                    kinetic: find("kinetic_energy")?,
                    strain: (strain, outputs[strain]),
                    potential: (potential, outputs[potential]),
                    warned: false,
                })
            })
            .collect();
        EnergyWatch {
            sections,
            fraction: spec.energy_growth,
            scale: 0.0,
        }
    }

    /// Checks the balances after a step at simulated time `t` (s), adding a
    /// warning to `warnings` per section the first time its energy error goes
    /// beyond the bound.
    pub(super) fn observe(&mut self, master: &Master, t: f64, warnings: &mut Vec<String>) {
        for b in &self.sections {
            self.scale = self.scale.max(b.exchanged(master.outputs(b.unit)));
        }
        for b in self.sections.iter_mut().filter(|b| !b.warned) {
            let outputs = master.outputs(b.unit);
            let error = outputs[b.error];
            let floor = SOLVER_FLOOR * outputs[b.strain.0].abs();
            let bound = (self.fraction * self.scale).max(floor);
            if bound > 0.0 && error > bound {
                b.warned = true;
                let name = master.unit_names().nth(b.unit).unwrap_or("?");
                warnings.push(format!(
                    "implausible energy growth: `{name}.energy_error` = {error:.4e} J at t = {t} s, beyond {:.4e} J (output.watch.energy_growth = {} times the largest energy a section exchanged, {:.4e} J, and at least {SOLVER_FLOOR:e} of its strain energy): the time stepping puts energy in: refine the mesh where the section bends most, shorten the step (stiff contact), or damp numerically (integrator alpha > 0)",
                    bound, self.fraction, self.scale
                ));
            }
        }
    }
}
