//! `[structure.top_load]`: the structure's top end loaded by outputs of other
//! scene units (seed 000's characteristic load, a vessel model, an FMU), in x
//! and z, whatever fidelity the last section has. The static force at t = 0
//! (`static`, N) holds the structure in its equilibrium.

use super::cuts::{link, port};
use super::sections::Fidelity;
use toml::{Table, Value};

/// The top load: the outputs driving x and z, and the force at rest.
#[derive(Clone, Debug)]
pub(super) struct TopLoad {
    x: String,
    z: String,
    at_rest: [f64; 2],
}

impl TopLoad {
    /// `structure.top_load`, None when absent; the model's own end must leave x
    /// and z to it.
    pub(super) fn of(structure: &Table, model: &Table) -> Result<Option<TopLoad>, String> {
        let Some(t) = structure.get("top_load") else {
            return Ok(None);
        };
        let t = t
            .as_table()
            .ok_or("`structure.top_load`: expected a table { x = \"unit.port\", z = \"unit.port\", static = [fx, fz] }")?;
        let output = |k: &str| {
            t.get(k)
                .and_then(Value::as_str)
                .filter(|s| s.contains('.'))
                .map(str::to_owned)
                .ok_or(format!(
                    "`structure.top_load.{k}`: expected the output driving the top's {k} force, \"unit.port\""
                ))
        };
        let at_rest = t
            .get("static")
            .and_then(Value::as_array)
            .filter(|a| a.len() == 2)
            .and_then(|a| {
                let n = |v: &Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
                Some([n(&a[0])?, n(&a[1])?])
            })
            .filter(|f| f.iter().all(|v| v.is_finite()))
            .ok_or("`structure.top_load.static`: expected [fx, fz], the load at rest (N)")?;
        let end = model
            .get("ends")
            .and_then(|e| e.get("end"))
            .and_then(Value::as_table);
        if let Some(k) =
            end.and_then(|e| ["kind", "x", "z"].into_iter().find(|k| e.contains_key(*k)))
        {
            return Err(format!(
                "`structure.model.ends.end.{k}`: the top's x and z are loaded by `structure.top_load`; leave them out"
            ));
        }
        Ok(Some(TopLoad {
            x: output("x")?,
            z: output("z")?,
            at_rest,
        }))
    }

    /// The model loaded at its top by the force at rest (for its equilibrium).
    pub(super) fn held_at_rest(&self, model: &Table) -> Table {
        let mut model = model.clone();
        self.set_end(&mut model, Value::Float, self.at_rest);
        model
    }

    /// The model as the units take it: the top force a coupled input.
    pub(super) fn take_input(&self, model: &mut Table) {
        self.set_end(model, |_| Value::String("input".into()), self.at_rest);
    }

    fn set_end(&self, model: &mut Table, force: impl Fn(f64) -> Value, f: [f64; 2]) {
        let ends = model
            .entry("ends")
            .or_insert_with(|| Value::Table(Table::new()));
        let Some(ends) = ends.as_table_mut() else {
            return;
        };
        let end = ends
            .entry("end")
            .or_insert_with(|| Value::Table(Table::new()));
        if let Some(end) = end.as_table_mut() {
            for (dof, value) in [("x", f[0]), ("z", f[1])] {
                let mut condition = Table::new();
                condition.insert("force".into(), force(value));
                end.insert(dof.into(), Value::Table(condition));
            }
        }
    }

    /// The connections from the load to a unit's top.
    pub(super) fn links(&self, unit: &str, fidelity: Fidelity) -> Vec<Value> {
        vec![
            link(self.x.clone(), port(unit, fidelity, true, "force_x")),
            link(self.z.clone(), port(unit, fidelity, true, "force_z")),
        ]
    }

    /// The force at rest as the first guess of the unit's top-force inputs.
    pub(super) fn first_guess(&self, unit: &mut Table, fidelity: Fidelity) {
        let side = fidelity.model().end_names()[1];
        super::statics::first_guess_force(unit, side, self.at_rest);
    }
}
