//! The static start of a cut structure: the whole structure's equilibrium, solved
//! once while the scene is written out, gives each section its start shape and
//! the displacement of its cut start, so every section's own static solve and the
//! master's initial iterations land on that equilibrium.

use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::{Driver, Time, Unit};
use toml::{Table, Value};

/// The whole structure at rest in equilibrium.
pub struct Equilibrium {
    section: Driver<NonlinearSection>,
}

/// Points per metre of the start shape handed to each section (at least 20).
const POINTS_PER_METRE: f64 = 2.0;

impl Equilibrium {
    /// Solves the model's statics; the error says why it cannot.
    pub fn solve(model: &Table) -> Result<Equilibrium, String> {
        let params: NonlinearParams = Value::Table(model.clone())
            .try_into()
            .map_err(|e| format!("`structure.model`: {e}"))?;
        let unit = NonlinearSection::new(params).map_err(|e| format!("`structure.model`: {e}"))?;
        if !unit.description().inputs.is_empty() {
            return Err("`structure.model.static_start`: the structure's statics are solved on their own, so its ends cannot take coupled inputs".into());
        }
        let mut section = Driver::new(unit);
        section.initialize(Time::ZERO).map_err(|e| {
            format!("`structure.model.static_start`: the whole structure's statics: {e}")
        })?;
        Ok(Equilibrium { section })
    }

    /// Sets a section's static start: the equilibrium shape over [from, to] as its
    /// start polyline, and its moving cut ends (`moving`: start, end) where the
    /// equilibrium puts them.
    pub fn start_section(
        &self,
        unit: &mut Table,
        (from, to): (f64, f64),
        moving: (bool, bool),
    ) -> Result<(), String> {
        let section = self.section.unit();
        let points = ((to - from) * POINTS_PER_METRE).ceil().max(20.0) as usize;
        let shape: Vec<Value> = (0..=points)
            .map(|k| {
                let p = section.position_at(from + (to - from) * k as f64 / points as f64);
                Value::Array(vec![Value::Float(p[0]), Value::Float(p[1])])
            })
            .collect();
        let parameters = unit
            .get_mut("parameters")
            .and_then(Value::as_table_mut)
            .ok_or("a section without parameters")?;
        parameters.insert("static_start".into(), Value::Boolean(true));
        parameters.insert("start_shape".into(), Value::String("points".into()));
        parameters.insert("start_points".into(), Value::Array(shape));
        for (key, at, is_moving) in [("start", from, moving.0), ("end", to, moving.1)] {
            if !is_moving {
                continue;
            }
            let mut end = Table::new();
            for (dof, d) in ["x", "z", "rotation"].iter().zip(self.displacement_at(at)) {
                let mut condition = Table::new();
                condition.insert("velocity_from".into(), Value::Float(d));
                end.insert((*dof).into(), Value::Table(condition));
            }
            let ends = parameters
                .entry("ends")
                .or_insert_with(|| Value::Table(Table::new()))
                .as_table_mut()
                .ok_or("`ends` is not a table")?;
            ends.insert(key.into(), Value::Table(end));
        }
        Ok(())
    }

    /// Displacement (x, z from the stress-free position, m; rotation, rad) at arc
    /// length `s`, linear between the nodes.
    fn displacement_at(&self, s: f64) -> [f64; 3] {
        let section = self.section.unit();
        let model = section.model();
        let (e, xi) = model.locate(s);
        let q = section.displacements();
        std::array::from_fn(|k| (1.0 - xi) * q[3 * e + k] + xi * q[3 * e + 3 + k])
    }
}
