//! A 3D line as its elastic catenary (scene kind `catenary3d`): the static
//! section of a 3D structure, the cheapest fidelity of a mooring line's lower
//! part. Its start is an anchor held in place, on a flat seabed at the
//! anchor's level or hanging free; its end is held, moved by sines or moved
//! by coupled velocities; each step the line is in static equilibrium through
//! its ends (the closed form of [`super::catenary`], MoorPy's `catenary`
//! without seabed friction), and the forces its ends exert follow from it.
//!
//! What it leaves out, by design: the line's inertia, drag, added mass and
//! waves (a quasi-static line), bending, the seabed's friction and a sloped
//! seabed (refused). It takes the same parameters as `line3d` (the dynamic
//! coefficients are not used; `elements` places the stations its fields are
//! reported at), so a structure's section changes fidelity by one word.
//!
//! A coupled end follows its velocity inputs by Newmark's rule with the
//! `alpha` of the 3D line (from its own start motion), as the dynamic line
//! beside it moves the node that drives it: the cut stays closed.

use super::catenary::{Catenary, CatenaryLine};
use super::outputs::{AXES, CATENARY_OUTPUTS, EXTRA_OUTPUTS, check_field_request};
use super::params::{EndCondition, Line3dParams};
use super::step::{end_motion, follow_velocity};
use crate::contract::{
    Capabilities, Field, Inputs, Port, PortKind, StepReport, Time, Unit, UnitDescription, UnitError,
};
use crate::integrators::hht::parameters_of;
use nalgebra::Vector3;

crate::state_struct! {
    /// The end's motion and the catenary's tensions.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct CatenaryState {
        /// The end's position (m), velocity (m/s) and acceleration (m/s^2).
        end: [[f64; 3]; 3],
        /// Horizontal tension and the end's vertical force (N).
        tensions: [f64; 2],
    }
}

/// The unit.
pub struct CatenarySection {
    params: Line3dParams,
    line: CatenaryLine,
    description: UnitDescription,
    state: CatenaryState,
    /// HHT-alpha's (alpha, beta, gamma) and the last step's length (s).
    newmark: (f64, f64, f64),
    last_step: f64,
}

impl CatenarySection {
    /// Builds the unit, refusing what the catenary cannot represent.
    pub fn new(params: Line3dParams) -> Result<CatenarySection, UnitError> {
        params.validate()?;
        let refuse = |key: &str, value: &str, why: &str| UnitError::parameter(key, value, why);
        if params.start.condition != EndCondition::Fixed {
            return Err(refuse(
                "start.condition",
                "not fixed",
                "\"fixed\": the catenary's start is its anchor",
            ));
        }
        if params.end.condition == EndCondition::Force {
            return Err(refuse(
                "end.condition",
                "force",
                "\"fixed\", \"motion\" or \"velocity\": a static line's end is moved; its force is an output",
            ));
        }
        if params.end.released_at.is_some() {
            return Err(refuse(
                "end.released_at",
                "given",
                "no release on a catenary (a quasi-static line has no free end): model the line's top section as `line3d`",
            ));
        }
        if params.submerged_weight <= 0.0 {
            return Err(refuse(
                "submerged_weight",
                "0",
                "> 0: the catenary hangs by its weight",
            ));
        }
        if let Some(s) = &params.seabed {
            let at_anchor = s.depth.is_some_and(|depth| {
                (params.start.position[2] + depth).abs() <= 1e-6 * params.length.max(1.0)
            });
            if s.slope != [0.0, 0.0] || !at_anchor {
                return Err(refuse(
                    "seabed",
                    "sloped, a grid or below the anchor",
                    "a flat seabed at the anchor's level (z = -depth), as the elastic catenary with seabed contact has it",
                ));
            }
        }
        let line = CatenaryLine {
            length: params.length,
            axial_stiffness: params.axial_stiffness,
            weight: params.submerged_weight,
            seabed: params.seabed.is_some(),
        };
        let newmark = parameters_of(params.alpha);
        let coupled = params.end.condition == EndCondition::Velocity;
        let description = UnitDescription {
            kind: "catenary3d".into(),
            inputs: if coupled {
                AXES.iter()
                    .map(|a| Port::input(&format!("end_velocity_{a}"), PortKind::Velocity))
                    .collect()
            } else {
                Vec::new()
            },
            outputs: output_ports(),
            capabilities: Capabilities {
                step_jacobian: coupled,
                step_correction: coupled,
                ..Capabilities::default()
            },
        };
        Ok(CatenarySection {
            state: CatenaryState {
                end: [params.end.position, [0.0; 3], [0.0; 3]],
                tensions: [0.0; 2],
            },
            params,
            line,
            description,
            newmark,
            last_step: 0.0,
        })
    }

    /// The plan direction from the anchor to an end at `end` (m) and the
    /// horizontal span (m).
    fn plan(&self, end: &[f64; 3]) -> ([f64; 2], f64) {
        let a = &self.params.start.position;
        let (dx, dy) = (end[0] - a[0], end[1] - a[1]);
        let across = dx.hypot(dy);
        if across > 0.0 {
            ([dx / across, dy / across], across)
        } else {
            ([1.0, 0.0], across)
        }
    }

    /// The catenary through the anchor and an end at `end` (m). A line
    /// lying on the seabed (its end at the anchor's level or below) is a bar
    /// stretched along it.
    fn solve(&self, end: &[f64; 3]) -> Result<Catenary, UnitError> {
        let (_, across) = self.plan(end);
        let up = end[2] - self.params.start.position[2];
        let l = self.line.length;
        if self.line.seabed && up <= 1e-9 * l {
            return Ok(Catenary {
                line: self.line,
                horizontal: self.line.axial_stiffness * (across / l - 1.0).max(0.0),
                vertical: 0.0,
            });
        }
        self.line.solve(across.max(1e-9 * l), up)
    }

    /// The forces (N) the end and the start exert on what holds them, for
    /// the catenary `c` in the plan direction `u`.
    fn forces_of(&self, c: &Catenary, [ux, uy]: [f64; 2]) -> [[f64; 3]; 2] {
        let (h, vf) = (c.horizontal, c.vertical);
        let va = if c.laid_length() > 0.0 {
            0.0
        } else {
            vf - self.line.weight * self.line.length
        };
        [[-h * ux, -h * uy, -vf], [h * ux, h * uy, va]]
    }

    /// The force (N) the end at `end` (m) exerts on what holds it: a
    /// fairlead's pull for a mooring system's statics.
    pub fn end_force(&self, end: &[f64; 3]) -> Result<[f64; 3], UnitError> {
        Ok(self.forces(end)?[0])
    }

    /// The forces the end at `end` (m) and the start exert (N).
    fn forces(&self, end: &[f64; 3]) -> Result<[[f64; 3]; 2], UnitError> {
        Ok(self.forces_of(&self.solve(end)?, self.plan(end).0))
    }

    /// d(end force, start force) / d(end position) by central differences.
    fn stiffness(&self) -> Result<[[[f64; 3]; 3]; 2], UnitError> {
        let delta = 1e-6 * self.params.length;
        let mut k = [[[0.0; 3]; 3]; 2];
        for j in 0..3 {
            let (mut plus, mut minus) = (self.state.end[0], self.state.end[0]);
            plus[j] += delta;
            minus[j] -= delta;
            let (fp, fm) = (self.forces(&plus)?, self.forces(&minus)?);
            for (side, rows) in k.iter_mut().enumerate() {
                for (i, row) in rows.iter_mut().enumerate() {
                    row[j] = (fp[side][i] - fm[side][i]) / (2.0 * delta);
                }
            }
        }
        Ok(k)
    }

    /// The catenary the state holds.
    fn current(&self) -> Catenary {
        Catenary {
            line: self.line,
            horizontal: self.state.tensions[0],
            vertical: self.state.tensions[1],
        }
    }

    /// x, y, z per station (`elements + 1`, evenly spaced in unstretched
    /// arc, the anchor first) and the effective tension per element: the
    /// 3D line's fields but its bending ones, which a catenary has none of.
    fn field_list(&self) -> Vec<Field> {
        let nodes = self.params.elements + 1;
        let mut fields: Vec<Field> = AXES
            .iter()
            .map(|a| {
                let what =
                    "position of each station (evenly spaced in unstretched arc), anchor first";
                Field::per_node(a, "m", what, nodes)
            })
            .collect();
        fields.push(Field::per_element(
            "tension",
            "N",
            "effective tension at each element's middle, anchor first (the closed form)",
            nodes - 1,
        ));
        fields
    }

    /// The current values of field `index` into `out`.
    fn write_field(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
        let stations = self.params.elements + 1;
        let lengths = [stations, stations, stations, stations - 1];
        let names = ["x", "y", "z", "tension"];
        check_field_request(
            ("a catenary", "the catenary"),
            &names,
            &lengths,
            index,
            out.len(),
        )?;
        let c = self.current();
        let ds = self.line.length / self.params.elements as f64;
        let (u, _) = self.plan(&self.state.end[0]);
        let anchor = &self.params.start.position;
        for (k, o) in out.iter_mut().enumerate() {
            *o = if index == 3 {
                c.tension((k as f64 + 0.5) * ds)
            } else {
                let [across, up] = c.point(k as f64 * ds);
                anchor[index] + [u[0] * across, u[1] * across, up][index]
            };
        }
        Ok(())
    }

    /// The end's motion at the step's end: prescribed, or by Newmark from
    /// its start motion and the velocity input at the step's end.
    fn moved(&self, t1: f64, h: f64, inputs: &Inputs<'_>) -> [[f64; 3]; 3] {
        if self.params.end.condition != EndCondition::Velocity {
            return end_motion(&self.params.end, t1);
        }
        let [q0, v0, a0] = self.state.end;
        let mut out = [[0.0; 3]; 3];
        for c in 0..3 {
            let [q, v, a] =
                follow_velocity([q0[c], v0[c], a0[c]], inputs.at(c, 1.0), h, self.newmark);
            [out[0][c], out[1][c], out[2][c]] = [q, v, a];
        }
        out
    }
}

/// Per end its position, velocity and force (x, y, z), then the extras.
fn output_ports() -> Vec<Port> {
    let mut out = Vec::new();
    for side in super::SIDES {
        for (quantity, kind) in [
            ("position", PortKind::Displacement),
            ("velocity", PortKind::Velocity),
            ("force", PortKind::Force),
        ] {
            for a in AXES {
                out.push(Port::output(&format!("{side}_{quantity}_{a}"), kind));
            }
        }
    }
    // Tensions, the top's angle and azimuth, the touchdown, the largest tension.
    for (name, unit) in &EXTRA_OUTPUTS[..CATENARY_OUTPUTS] {
        out.push(Port::output(name, PortKind::Generic).with_unit(unit));
    }
    out
}

impl Unit for CatenarySection {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        let mut end = end_motion(&self.params.end, t0.as_secs());
        if self.params.end.condition == EndCondition::Velocity {
            end[0] = self.params.end.position;
            end[1] = std::array::from_fn(|c| inputs.at(c, 1.0));
            end[2] = [0.0; 3];
        }
        let c = self.solve(&end[0])?;
        self.state = CatenaryState {
            end,
            tensions: [c.horizontal, c.vertical],
        };
        Ok(())
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let h = h.as_secs();
        let end = self.moved(t.as_secs() + h, h, &inputs);
        let c = self.solve(&end[0])?;
        self.state = CatenaryState {
            end,
            tensions: [c.horizontal, c.vertical],
        };
        self.last_step = h;
        Ok(StepReport::default())
    }

    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        let end = &self.state.end;
        let c = self.current();
        let (u, _) = self.plan(&end[0]);
        let forces = self.forces_of(&c, u);
        let start = &self.params.start.position;
        out[0..3].copy_from_slice(start);
        out[3..6].fill(0.0);
        out[6..9].copy_from_slice(&forces[1]);
        out[9..12].copy_from_slice(&end[0]);
        out[12..15].copy_from_slice(&end[1]);
        out[15..18].copy_from_slice(&forces[0]);
        let top = Vector3::from(forces[0]);
        let tension = top.norm();
        let laid = c.laid_length();
        let stretched = laid * (1.0 + c.horizontal / self.line.axial_stiffness);
        // A slack line lying on the seabed pulls nothing: no angle.
        let angle = if tension > 0.0 {
            (-top.z / tension).clamp(-1.0, 1.0).acos().to_degrees()
        } else {
            0.0
        };
        out[18..26].copy_from_slice(&[
            tension,
            angle,
            top.y.atan2(top.x).to_degrees(),
            Vector3::from(forces[1]).norm(),
            laid,
            start[0] + u[0] * stretched,
            start[1] + u[1] * stretched,
            tension,
        ]);
    }

    slender_contract::state_in_field!(state: CatenaryState);

    fn fields(&self) -> Vec<Field> {
        self.field_list()
    }

    fn field_values(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
        self.write_field(index, out)
    }

    /// Exact: the end's motion follows the changed velocity by Newmark (as
    /// the step moved it) and the catenary is solved again at its position.
    fn correct_step(&mut self, _inputs: Inputs<'_>, change: &[f64]) -> Result<(), UnitError> {
        let h = self.last_step;
        if self.params.end.condition != EndCondition::Velocity || h <= 0.0 {
            return Err(UnitError::State(
                "catenary3d: a step correction needs a step taken with a coupled end velocity"
                    .into(),
            ));
        }
        let (_, beta, gamma) = self.newmark;
        let mut end = self.state.end;
        for (c, dv) in change.iter().enumerate().take(3) {
            end[0][c] += beta * h / gamma * dv;
            end[1][c] += dv;
            end[2][c] += dv / (gamma * h);
        }
        let c = self.solve(&end[0])?;
        self.state = CatenaryState {
            end,
            tensions: [c.horizontal, c.vertical],
        };
        Ok(())
    }

    /// The end's position moves by beta h / gamma per unit velocity input
    /// (Newmark), its velocity by one; the forces through the catenary's
    /// stiffness (central differences). The other outputs are NaN.
    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        let n_in = inputs.len();
        jacobian.fill(f64::NAN);
        let (_, beta, gamma) = self.newmark;
        let dq = beta * self.last_step / gamma;
        let k = self.stiffness()?;
        for j in 0..n_in {
            for i in 0..3 {
                let d = f64::from(u8::from(i == j));
                jacobian[i * n_in + j] = 0.0;
                jacobian[(3 + i) * n_in + j] = 0.0;
                jacobian[(6 + i) * n_in + j] = k[1][i][j] * dq;
                jacobian[(9 + i) * n_in + j] = d * dq;
                jacobian[(12 + i) * n_in + j] = d;
                jacobian[(15 + i) * n_in + j] = k[0][i][j] * dq;
            }
        }
        Ok(())
    }
}
