//! A section in its chord frame (scene kind `chord`): a small-deflection model
//! of a section between two neighbours, seed 004's FE `beam` or the span's
//! transfer matrix (`span_coupling`), about the straight line (the chord)
//! between its ends in the structure's equilibrium. The unit changes frames at
//! its two cuts so that its neighbours see global positions and forces.
//!
//! One end (`moving`) follows its neighbour's position and rotation and returns
//! the force and moment it exerts there; the other (loaded) end takes its
//! neighbour's force and moment and returns the displacement that neighbour
//! follows. Everything is a deviation from the state at initialisation (the
//! equilibrium): transverse to the chord the inner model answers, along the
//! chord (`axial`) the section is a spring (`axial_stiffness`) carrying a mass
//! at its loaded end (`axial_mass`), a spring alone (the loaded end moves
//! further than the moving one by the change of its axial force over the
//! stiffness; the force passes through) or, without either, a rigid link. The
//! static part of the forces is the section's
//! own balance: the loaded end's force and moment at initialisation plus the
//! section's submerged weight, exact for any shape.

mod axial;
mod ports;

use crate::beam::boundary::{Boundary, Condition, InputMarker, Quantity, TimeFunction};
use crate::beam::{Beam, BeamParams};
use crate::contract::{
    Hold, Inputs, StateSlot, StepReport, Time, Unit, UnitDescription, UnitError, require_finite,
    require_positive,
};
use crate::span::coupling::{Orientation, SpanCoupling, SpanCouplingParams};
use axial::{Axial, AxialState};
use ports::{describe, inner_ports, set_dependencies};
use serde::{Deserialize, Serialize};

/// The small-deflection model in the chord frame.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ChordModel {
    /// Seed 004's Hermite FE beam with tension (kind `beam`).
    Beam,
    /// The span's exact transfer matrix as a rational fit (kind `span_coupling`).
    Span,
}

/// The end that follows its neighbour's motion.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MovingEnd {
    /// The section's start follows the neighbour before it.
    Start,
    /// The section's end follows the neighbour after it.
    End,
}

/// Parameters (SI units; positions in the structure's x, z plane).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ChordParams {
    /// How the chord carries load (a straight beam or the span's transfer matrix).
    pub model: ChordModel,
    /// Which end follows its neighbour's motion (the other is held).
    pub moving: MovingEnd,
    /// The section's start and end in the equilibrium (m): the chord.
    pub start: [f64; 2],
    /// The section's end in the equilibrium (m).
    pub end: [f64; 2],
    /// The section's submerged weight (N, downwards) and where it acts (m).
    pub weight: f64,
    /// Where the submerged weight acts ([x, z], m).
    pub weight_at: [f64; 2],
    /// The loaded end's neighbour's displacement in the equilibrium (x, z from
    /// its stress-free position, m; rotation, rad): what it is handed at rest.
    pub loaded_end_displacement: [f64; 3],
    /// EI (N m^2).
    pub flexural_rigidity: f64,
    /// Mass per length moving transversely, added mass included (kg/m).
    pub mass_per_length: f64,
    /// Viscous damping of the transverse motion c_d (N s/m^2), default 0.
    #[serde(default)]
    pub damping_per_length: f64,
    /// The constant axial tension T of the inner model (N).
    #[serde(default)]
    pub tension: f64,
    /// The section's axial stiffness along its chord, EA over its arc length
    /// (N/m): the loaded end moves along the chord by the change of its axial
    /// force over it (the section stretches); none: a rigid link.
    #[serde(default)]
    pub axial_stiffness: Option<f64>,
    /// The mass (kg) the loaded end carries along the chord, with the
    /// stiffness: the section's inertia in that motion; none: quasi-static.
    #[serde(default)]
    pub axial_mass: Option<f64>,
    /// Beam elements, default 20.
    #[serde(default = "twenty")]
    pub elements: usize,
    /// Numerical damping: HHT-alpha of the beam, theta = 1/2 + alpha of the span.
    #[serde(default)]
    pub alpha: f64,
    /// Span: poles of the fit (even), default 24.
    #[serde(default = "twenty_four")]
    pub order: usize,
    /// Span: band of the fit (rad/s), default 2 pi 10.
    #[serde(default = "ten_hz")]
    pub band: f64,
}

impl ChordParams {
    /// Beam elements when the scene gives none (`elements`).
    pub const DEFAULT_ELEMENTS: usize = 20;
    /// The span fit's order when the scene gives none (`order`).
    pub const DEFAULT_ORDER: usize = 24;
    /// The span fit's band (rad/s: 10 Hz) when the scene gives none (`band`).
    pub const DEFAULT_BAND: f64 = 2.0 * std::f64::consts::PI * 10.0;
}

fn twenty() -> usize {
    ChordParams::DEFAULT_ELEMENTS
}

fn twenty_four() -> usize {
    ChordParams::DEFAULT_ORDER
}

fn ten_hz() -> f64 {
    ChordParams::DEFAULT_BAND
}

/// The chord's frame: origin at the start, `e` along it, `n` turned +90 deg.
#[derive(Copy, Clone, Debug)]
struct Frame {
    e: [f64; 2],
    n: [f64; 2],
}

impl Frame {
    fn along(&self, v: [f64; 2]) -> f64 {
        v[0] * self.e[0] + v[1] * self.e[1]
    }

    fn across(&self, v: [f64; 2]) -> f64 {
        v[0] * self.n[0] + v[1] * self.n[1]
    }

    /// Global components of `a` along the chord and `b` across it.
    fn global(&self, a: f64, b: f64) -> [f64; 2] {
        [a * self.e[0] + b * self.n[0], a * self.e[1] + b * self.n[1]]
    }
}

/// z-component of the planar cross product r x f (N m).
fn cross(r: [f64; 2], f: [f64; 2]) -> f64 {
    r[0] * f[1] - r[1] * f[0]
}

/// What the unit holds from its initialisation: the inputs it deviates from and
/// the static force and moment its moving end exerts.
#[derive(Copy, Clone, Debug, Default)]
struct Reference {
    inputs: [f64; 6],
    static_force_across: f64,
    static_moment: f64,
}

/// Inner port indices: inputs (moving deflection, rotation; loaded moment,
/// shear) and outputs (moving moment, shear; loaded deflection, rotation).
#[derive(Copy, Clone, Debug)]
struct InnerPorts {
    inputs: [usize; 4],
    outputs: [usize; 4],
    output_count: usize,
}

/// Outputs of the inner model the unit reads at most (a beam without stations).
const MAX_INNER_OUTPUTS: usize = 16;

/// The unit.
pub struct Chord {
    params: ChordParams,
    description: UnitDescription,
    frame: Frame,
    inner: Box<dyn Unit>,
    ports: InnerPorts,
    reference: Reference,
    axial: Axial,
}

impl Chord {
    /// Builds the unit and its inner model; fails on a degenerate chord or a
    /// parameter the inner model refuses.
    pub fn new(params: ChordParams) -> Result<Chord, UnitError> {
        let values = params
            .start
            .iter()
            .chain(&params.end)
            .chain(&params.weight_at)
            .chain(&params.loaded_end_displacement)
            .chain([&params.weight, &params.tension]);
        for &v in values {
            require_finite(
                "start, end, weight, weight_at, loaded_end_displacement, tension",
                v,
            )?;
        }
        let d = [
            params.end[0] - params.start[0],
            params.end[1] - params.start[1],
        ];
        let length = d[0].hypot(d[1]);
        require_positive("the chord's length |end - start|", length)?;
        let axial = Axial::new(params.axial_stiffness, params.axial_mass, params.alpha)?;
        let e = [d[0] / length, d[1] / length];
        let frame = Frame {
            e,
            n: [-e[1], e[0]],
        };
        let inner = inner_model(&params, length)?;
        let ports = inner_ports(&params, inner.description())?;
        let mut description = describe(params.moving);
        description.capabilities.step_jacobian = inner.description().capabilities.step_jacobian;
        set_dependencies(&mut description, inner.description(), &ports, &axial);
        Ok(Chord {
            params,
            description,
            frame,
            inner,
            ports,
            reference: Reference::default(),
            axial,
        })
    }

    /// Each inner input ramps as its outer source does (the loads follow the
    /// loaded end's force inputs, the motions the moving end's position).
    fn inner_holds(&self, inputs: Inputs<'_>) -> [Hold; 4] {
        let mut holds = [Hold::Ramp; 4];
        for (k, &port) in self.ports.inputs.iter().enumerate() {
            holds[port] = inputs.hold(if k < 2 { 0 } else { 3 });
        }
        holds
    }

    /// The loaded end sits at x = L of the inner model (else at x = 0).
    fn loaded_at_end(&self) -> bool {
        self.params.moving == MovingEnd::Start
    }

    /// The inner model's four inputs from six outer input values, in the inner
    /// port order.
    fn local(&self, outer: &[f64]) -> [f64; 4] {
        let r = &self.reference.inputs;
        let dp = [outer[0] - r[0], outer[1] - r[1]];
        let df = [outer[3] - r[3], outer[4] - r[4]];
        let dm = outer[5] - r[5];
        // Moment EI y'' and shear EI y''' - T y' of the inner model at the loaded
        // end from the transverse force and moment applied there.
        let applied = self.frame.across(df);
        let (moment, shear) = if self.loaded_at_end() {
            (dm, -applied)
        } else {
            (-dm, applied)
        };
        let values = [self.frame.across(dp), outer[2] - r[2], moment, shear];
        let mut local = [0.0; 4];
        for (k, &port) in self.ports.inputs.iter().enumerate() {
            local[port] = values[k];
        }
        local
    }
}

/// The inner model over the chord, at rest, its ends coupled.
fn inner_model(params: &ChordParams, length: f64) -> Result<Box<dyn Unit>, UnitError> {
    let input = || TimeFunction::Input(InputMarker::Input);
    let kinematic = [
        Condition {
            quantity: Quantity::Deflection,
            value: input(),
        },
        Condition {
            quantity: Quantity::Rotation,
            value: input(),
        },
    ];
    let loads = [
        Condition {
            quantity: Quantity::Moment,
            value: input(),
        },
        Condition {
            quantity: Quantity::Shear,
            value: input(),
        },
    ];
    Ok(match params.model {
        ChordModel::Beam => {
            let boundary = match params.moving {
                MovingEnd::Start => Boundary {
                    left: kinematic,
                    right: loads,
                },
                MovingEnd::End => Boundary {
                    left: loads,
                    right: kinematic,
                },
            };
            let mut beam = BeamParams::new(
                length,
                params.elements,
                params.flexural_rigidity,
                params.mass_per_length,
                boundary,
            );
            beam.tension = params.tension;
            beam.damping_per_length = params.damping_per_length;
            beam.alpha = params.alpha;
            Box::new(Beam::new(beam)?)
        }
        ChordModel::Span => Box::new(SpanCoupling::new(SpanCouplingParams {
            flexural_rigidity: params.flexural_rigidity,
            mass_per_length: params.mass_per_length,
            damping_per_length: params.damping_per_length,
            length,
            tension: params.tension,
            orientation: match params.moving {
                MovingEnd::Start => Orientation::UpperMotion,
                MovingEnd::End => Orientation::LowerMotion,
            },
            order: params.order,
            band: params.band,
            discretization: Default::default(),
            alpha: params.alpha,
        })?),
    })
}

impl Unit for Chord {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    /// The loaded end's force and moment: the section's balance at rest.
    fn static_inputs(&self) -> Vec<usize> {
        self.description.load_inputs()
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        let mut r = [0.0; 6];
        r.copy_from_slice(inputs.end());
        let p = &self.params;
        let (mover, loaded) = match p.moving {
            MovingEnd::Start => (p.start, p.end),
            MovingEnd::End => (p.end, p.start),
        };
        // The section's balance: the moving end's neighbour carries the loaded
        // end's force and the weight, and their moments about the moving end.
        let force = [r[3], r[4] - p.weight];
        let arm = |q: [f64; 2]| [q[0] - mover[0], q[1] - mover[1]];
        let moment =
            r[5] + cross(arm(loaded), [r[3], r[4]]) + cross(arm(p.weight_at), [0.0, -p.weight]);
        self.reference = Reference {
            inputs: r,
            static_force_across: self.frame.across(force),
            static_moment: moment,
        };
        self.axial.initialize();
        let holds = [Hold::Ramp; 4];
        let zero = [0.0; 4];
        self.inner.initialize(t0, Inputs::new(&holds, &zero, &zero))
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let (start, end) = (self.local(inputs.start()), self.local(inputs.end()));
        let holds = self.inner_holds(inputs);
        let report = self
            .inner
            .do_step(t, h, Inputs::new(&holds, &start, &end))?;
        let (slide, force) = self.along(inputs.end());
        self.axial.do_step(h, slide, force);
        self.axial.require_finite()?;
        Ok(report)
    }

    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        self.assemble(self.inner_outputs(inputs), inputs.end(), out);
    }

    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        self.inner.save_state(slot.store_nested(&self.axial.state)?)
    }

    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        let (axial, inner) = slot.load_nested::<AxialState>()?;
        self.inner.restore_state(&inner)?;
        self.axial.state = *axial;
        Ok(())
    }

    /// Through the inner model's (where it gives one: `span`): the outer inputs
    /// reach the inner ones and the inner outputs the outer ones by affine maps,
    /// so each column is the change of the outputs under a unit change of one
    /// input, the inner outputs moved by the inner Jacobian.
    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        let (start, end) = (self.local(inputs.start()), self.local(inputs.end()));
        let holds = self.inner_holds(inputs);
        let n = self.ports.output_count;
        let mut inner_jacobian = [0.0; MAX_INNER_OUTPUTS * 4];
        let inner_jacobian = &mut inner_jacobian[..4 * n];
        self.inner
            .step_jacobian(Inputs::new(&holds, &start, &end), inner_jacobian)?;
        let now = inputs.end();
        let base_inner = self.inner_outputs(inputs);
        let mut base = [0.0; 7];
        self.assemble(base_inner, now, &mut base);
        for j in 0..6 {
            let mut moved = [0.0; 6];
            moved.copy_from_slice(now);
            moved[j] += 1.0;
            let local = self.local(&moved);
            let d_local: [f64; 4] = std::array::from_fn(|p| local[p] - end[p]);
            let inner = std::array::from_fn(|k| {
                let row = self.ports.outputs[k];
                base_inner[k]
                    + (0..4)
                        .map(|p| inner_jacobian[row * 4 + p] * d_local[p])
                        .sum::<f64>()
            });
            let mut out = [0.0; 7];
            self.assemble(inner, &moved, &mut out);
            for (i, (o, b)) in out.iter().zip(&base).enumerate() {
                jacobian[i * 6 + j] = o - b;
            }
        }
        Ok(())
    }
}

impl Chord {
    /// The moving end's slide along the chord (m) and the change of the
    /// loaded end's axial force along it (N) from the outer inputs `now`.
    fn along(&self, now: &[f64]) -> (f64, f64) {
        let r = &self.reference.inputs;
        (
            self.frame.along([now[0] - r[0], now[1] - r[1]]),
            self.frame.along([now[3] - r[3], now[4] - r[4]]),
        )
    }

    /// The inner model's moment and shear at the moving end and deflection
    /// and rotation at the loaded end, with the outer inputs `inputs`.
    fn inner_outputs(&self, inputs: Inputs<'_>) -> [f64; 4] {
        let (start, end) = (self.local(inputs.start()), self.local(inputs.end()));
        let holds = self.inner_holds(inputs);
        let mut inner = [0.0; MAX_INNER_OUTPUTS];
        let inner = &mut inner[..self.ports.output_count];
        self.inner.outputs(Inputs::new(&holds, &start, &end), inner);
        self.ports.outputs.map(|k| inner[k])
    }

    /// The unit's outputs from the inner model's four and the outer end
    /// inputs `now`.
    fn assemble(&self, inner: [f64; 4], now: &[f64], out: &mut [f64]) {
        let [moment, shear, deflection, rotation] = inner;
        // The transverse force and moment applied on the section at its moving
        // end; it exerts the opposite on the neighbour.
        let (applied_force, applied_moment) = if self.loaded_at_end() {
            (shear, -moment)
        } else {
            (-shear, moment)
        };
        let r = &self.reference;
        let (slide, axial_force) = self.along(now);
        let (along_chord, pull) = self.axial.response(slide, axial_force);
        let axial = self
            .frame
            .along([r.inputs[3], r.inputs[4] - self.params.weight])
            + pull;
        let across = r.static_force_across - applied_force;
        let force = self.frame.global(axial, across);
        out[0] = force[0];
        out[1] = force[1];
        out[2] = r.static_moment - applied_moment;
        let moved = self.frame.global(along_chord, deflection);
        let d = &self.params.loaded_end_displacement;
        out[3] = d[0] + moved[0];
        out[4] = d[1] + moved[1];
        out[5] = d[2] + rotation;
        // Tension: the loaded end's neighbour pulls away from the section.
        let outward = if self.loaded_at_end() { 1.0 } else { -1.0 };
        out[6] = outward * self.frame.along([now[3], now[4]]);
    }
}

#[cfg(test)]
mod tests;
