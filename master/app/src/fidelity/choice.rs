//! What `slender fidelity` is asked to try per section: `NAME=CHOICE,...`,
//! each choice a fidelity with an optional count and sub-steps.

use serde::Serialize;
use std::str::FromStr;

/// One way to model a section: a fidelity and, optionally, its element count
/// (`nonlinear:16`; for `reduced` the number of modes, `reduced:4`; for `span`
/// the order of its fit, `span:24`); without a count, the model's own mesh over
/// the section (6 modes, order 24); and, optionally, its sub-steps per
/// coupling step after a slash (`nonlinear:16/4`, `cable/2`: multi-rate);
/// and for `reduced`, a training window in seconds after `@`, after which its
/// forces go through sampled elements (`reduced:6@5`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Choice {
    /// The fidelity's name (e.g. `nonlinear`).
    pub fidelity: String,
    /// Its elements (`:N`), when given.
    pub elements: Option<usize>,
    /// Its substeps per synchronisation step (`/N`), when given.
    pub substeps: Option<u32>,
    /// A reduced section's training window (s, `@T`), when given.
    pub training: Option<f64>,
}

impl Choice {
    /// As written on the command line.
    pub fn label(&self) -> String {
        let mut label = match self.elements {
            Some(n) => format!("{}:{n}", self.fidelity),
            None => self.fidelity.clone(),
        };
        if let Some(t) = self.training {
            label += &format!("@{t}");
        }
        if let Some(s) = self.substeps {
            label += &format!("/{s}");
        }
        label
    }
}

/// A section's choices: `NAME=CHOICE,CHOICE,...`.
#[derive(Clone, Debug)]
pub struct SectionChoices {
    /// The section's name.
    pub section: String,
    /// Its choices, in the order given.
    pub choices: Vec<Choice>,
}

impl FromStr for SectionChoices {
    type Err = String;
    fn from_str(s: &str) -> Result<SectionChoices, String> {
        let (section, list) = s.split_once('=').ok_or(format!(
            "`{s}`: expected NAME=CHOICE,CHOICE,..., e.g. lower=nonlinear,cable,nonlinear:16,nonlinear/4"
        ))?;
        let choices = list
            .split(',')
            .map(|c| {
                let (c, substeps) = match c.split_once('/') {
                    Some((model, n)) => (
                        model,
                        Some(n.parse::<u32>().ok().filter(|&n| n >= 1).ok_or(format!(
                            "`{s}`: `{c}/{n}`: the sub-steps after `/` must be a whole number >= 1"
                        ))?),
                    ),
                    None => (c, None),
                };
                let (c, training) = match c.split_once('@') {
                    Some((model, t)) => (model, Some(seconds(s, c, t)?)),
                    None => (c, None),
                };
                let (fidelity, elements) = match c.split_once(':') {
                    Some((f, n)) => (
                        f,
                        Some(n.parse::<usize>().ok().filter(|&n| n >= 1).ok_or(format!(
                            "`{s}`: `{c}`: the element count after `:` must be a whole number >= 1"
                        ))?),
                    ),
                    None => (c, None),
                };
                if !slender_scene::structure::FIDELITIES.contains(&fidelity) {
                    return Err(format!(
                        "`{s}`: `{fidelity}` is not a fidelity; expected one of {}",
                        slender_scene::structure::FIDELITIES.join(", ")
                    ));
                }
                if training.is_some() && fidelity != "reduced" {
                    return Err(format!(
                        "`{s}`: `{c}@`: a training window is for `reduced` (its forces sampled after it)"
                    ));
                }
                Ok(Choice {
                    fidelity: fidelity.to_owned(),
                    elements,
                    substeps,
                    training,
                })
            })
            .collect::<Result<Vec<_>, String>>()?;
        if choices.is_empty() || section.is_empty() {
            return Err(format!(
                "`{s}`: expected a section name and at least one choice"
            ));
        }
        if let Some((k, c)) = (choices.iter().enumerate()).find(|(k, c)| choices[..*k].contains(c))
        {
            return Err(format!(
                "`{s}`: `{}` is listed twice (choice {}); each choice runs once",
                c.label(),
                k + 1
            ));
        }
        Ok(SectionChoices {
            section: section.to_owned(),
            choices,
        })
    }
}

impl SectionChoices {
    /// Two of the choices that make the same run on a section whose model
    /// mesh is `mesh` elements (`nonlinear` and `nonlinear:N` with N that
    /// mesh), if any: the earlier first.
    pub(super) fn same_run(&self, mesh: usize) -> Option<(&Choice, &Choice)> {
        let resolved = |c: &Choice| {
            let mut c = c.clone();
            if c.elements.is_none() && slender_scene::structure::takes_model_mesh(&c.fidelity) {
                c.elements = Some(mesh);
            }
            c
        };
        let all = &self.choices;
        (all.iter().enumerate())
            .flat_map(|(k, later)| all[..k].iter().map(move |earlier| (earlier, later)))
            .find(|(earlier, later)| resolved(earlier) == resolved(later))
    }
}

/// The training window after `@` in choice `c` of `s`: seconds > 0.
fn seconds(s: &str, c: &str, t: &str) -> Result<f64, String> {
    t.parse::<f64>()
        .ok()
        .filter(|t| t.is_finite() && *t > 0.0)
        .ok_or(format!(
            "`{s}`: `{c}`: the training window after `@` must be a number of seconds > 0"
        ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_choice_takes_a_count_and_sub_steps() {
        let c: SectionChoices = "lower=nonlinear:16/4,cable/2,reduced:6,reduced:6@5/2"
            .parse()
            .unwrap();
        let labels: Vec<String> = c.choices.iter().map(Choice::label).collect();
        assert_eq!(
            labels,
            ["nonlinear:16/4", "cable/2", "reduced:6", "reduced:6@5/2"]
        );
        assert_eq!(c.choices[3].training, Some(5.0));
        let e = "lower=cable@5".parse::<SectionChoices>().unwrap_err();
        assert!(e.contains("a training window is for `reduced`"), "{e}");
        let e = "lower=reduced:6@0".parse::<SectionChoices>().unwrap_err();
        assert!(e.contains("seconds > 0"), "{e}");
        assert_eq!(c.choices[0].substeps, Some(4));
        assert_eq!(c.choices[2].substeps, None);
        let e = "lower=nonlinear/0".parse::<SectionChoices>().unwrap_err();
        assert!(e.contains("sub-steps"), "{e}");
        // A choice twice would run twice (issue 27).
        let e = "lower=cable,nonlinear:16,cable"
            .parse::<SectionChoices>()
            .unwrap_err();
        assert!(e.contains("`cable` is listed twice (choice 3)"), "{e}");
    }
}
