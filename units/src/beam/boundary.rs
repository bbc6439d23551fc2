//! Boundary conditions of a beam end: two of deflection, rotation, moment and
//! shear, each a function of time or a coupled input.

use crate::contract::UnitError;
use crate::sea::SeaState;
use crate::signal::series::SineSeries;
pub use crate::signal::sine::Sine;
use crate::signal::sine::smoothstep;
use serde::{Deserialize, Serialize};

/// The four end quantities. Moment is EI y'' (N m), shear EI y''' (N).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Transverse deflection (m).
    Deflection,
    /// Rotation of the section (rad).
    Rotation,
    /// Bending moment (N m).
    Moment,
    /// Shear force (N).
    Shear,
}

impl Quantity {
    /// The work-conjugate quantity: prescribing both is degenerate.
    pub fn dual(self) -> Quantity {
        match self {
            Quantity::Deflection => Quantity::Shear,
            Quantity::Shear => Quantity::Deflection,
            Quantity::Rotation => Quantity::Moment,
            Quantity::Moment => Quantity::Rotation,
        }
    }

    /// Name as in scenes and port names.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Deflection => "deflection",
            Quantity::Rotation => "rotation",
            Quantity::Moment => "moment",
            Quantity::Shear => "shear",
        }
    }

    /// Whether it is kinematic (a Dirichlet condition) rather than a load.
    pub fn is_kinematic(self) -> bool {
        matches!(self, Quantity::Deflection | Quantity::Rotation)
    }

    /// Local DOF at the node (0: y, 1: theta) the quantity acts on.
    pub fn dof(self) -> usize {
        match self {
            Quantity::Deflection | Quantity::Shear => 0,
            Quantity::Rotation | Quantity::Moment => 1,
        }
    }
}

/// A prescribed value over time.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(
    untagged,
    expecting = "expected a number, \"input\" or a table { offset, amplitude, angular_frequency, phase, decay_amplitude, decay_rate, sines, fade_in, sea } (an unknown key in the table also gives this)"
)]
pub enum TimeFunction {
    /// A constant.
    Constant(f64),
    /// `"input"`: the value comes from a coupled input port.
    Input(InputMarker),
    /// `offset + amplitude sin(angular_frequency t + phase)` and/or
    /// `+ decay_amplitude exp(-decay_rate t)`.
    Expression(Expression),
}

/// The word "input".
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum InputMarker {
    /// The value is read from a coupled input (the scene writes `"input"`).
    Input,
}

/// Sum of a constant, a sine and a decaying exponential (SI units, t in s).
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(from = "ExpressionSpec", into = "ExpressionSpec")]
pub struct Expression {
    /// Constant part (the quantity's SI unit).
    pub offset: f64,
    /// Amplitude of the sine (the quantity's SI unit).
    pub amplitude: f64,
    /// rad/s
    pub angular_frequency: f64,
    /// rad
    pub phase: f64,
    /// Amplitude of the decaying exponential (the quantity's SI unit).
    pub decay_amplitude: f64,
    /// 1/s
    pub decay_rate: f64,
    /// More sines added to it (a vessel's motion as a sum of wave
    /// components), then the sea state's.
    pub sines: Vec<Sine>,
    /// Duration (s) over which the sines fade in from t = 0 by the quintic
    /// smoothstep `r = x^3 (10 - 15 x + 6 x^2)`, x = t / fade_in (continuous
    /// in value, velocity and acceleration, so a motion started this way
    /// launches no wave); 0 (default) starts them at full amplitude. The
    /// offset and the decay are not faded.
    pub fade_in: f64,
    /// An irregular sea whose sines were added to `sines` (kept to be checked).
    pub sea: Option<SeaState>,
    /// The sine and `sines` as a series summed fast (a sea's components by
    /// phasors), made when the expression is read; an expression built by
    /// hand (`..Expression::default()`), whose series does not hold its
    /// sines, sums them one by one. Boxed: most expressions are a sine.
    pub series: Box<SineSeries>,
}

/// An expression as a scene writes it (a sea state's sines not among its
/// `sines`: they are made from the sea when it is read).
#[derive(Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
struct ExpressionSpec {
    offset: f64,
    amplitude: f64,
    angular_frequency: f64,
    phase: f64,
    decay_amplitude: f64,
    decay_rate: f64,
    sines: Vec<Sine>,
    fade_in: f64,
    sea: Option<SeaState>,
}

impl From<ExpressionSpec> for Expression {
    fn from(spec: ExpressionSpec) -> Expression {
        let mut sines = spec.sines;
        sines.extend(spec.sea.iter().flat_map(SeaState::sines));
        let mut e = Expression {
            offset: spec.offset,
            amplitude: spec.amplitude,
            angular_frequency: spec.angular_frequency,
            phase: spec.phase,
            decay_amplitude: spec.decay_amplitude,
            decay_rate: spec.decay_rate,
            sines,
            fade_in: spec.fade_in,
            sea: spec.sea,
            series: Box::default(),
        };
        e.series = Box::new(SineSeries::new(&e.all_sines().collect::<Vec<_>>()));
        e
    }
}

impl Expression {
    /// Its own sine, then `sines`.
    fn all_sines(&self) -> impl Iterator<Item = Sine> + '_ {
        let first = Sine {
            amplitude: self.amplitude,
            angular_frequency: self.angular_frequency,
            phase: self.phase,
            decay: 0.0,
        };
        std::iter::once(first).chain(self.sines.iter().cloned())
    }

    /// Adds the sum of its sines and its two time derivatives at t (s) to
    /// `out`.
    fn add_sines(&self, out: &mut [f64; 3], t: f64) {
        if self.series.len() == 1 + self.sines.len() {
            return self.series.add_to(out, t);
        }
        for s in self.all_sines() {
            let v = s.eval(t);
            (0..3).for_each(|i| out[i] += v[i]);
        }
    }
}

/// The expression as a scene writes it: without the sines its sea added, so
/// that reading it back gives it again (the sea adds them once more).
impl From<Expression> for ExpressionSpec {
    fn from(e: Expression) -> ExpressionSpec {
        let mut sines = e.sines;
        let added = e.sea.as_ref().map(SeaState::sines).unwrap_or_default();
        if !added.is_empty() && sines.ends_with(&added) {
            sines.truncate(sines.len() - added.len());
        }
        ExpressionSpec {
            offset: e.offset,
            amplitude: e.amplitude,
            angular_frequency: e.angular_frequency,
            phase: e.phase,
            decay_amplitude: e.decay_amplitude,
            decay_rate: e.decay_rate,
            sines,
            fade_in: e.fade_in,
            sea: e.sea,
        }
    }
}

impl TimeFunction {
    /// Value and its first two time derivatives at t; `None` for an input.
    pub fn eval(&self, t: f64) -> Option<[f64; 3]> {
        match self {
            TimeFunction::Constant(c) => Some([*c, 0.0, 0.0]),
            TimeFunction::Input(_) => None,
            TimeFunction::Expression(e) => {
                let ex = e.decay_amplitude * (-e.decay_rate * t).exp();
                let [r, dr, ddr] = smoothstep(t, e.fade_in);
                let faded = r < 1.0;
                let mut v = match faded {
                    true => [0.0; 3],
                    false => [
                        e.offset + ex,
                        -e.decay_rate * ex,
                        e.decay_rate * e.decay_rate * ex,
                    ],
                };
                e.add_sines(&mut v, t);
                if !faded {
                    return Some(v);
                }
                // (r S)' = r' S + r S', (r S)'' = r'' S + 2 r' S' + r S''.
                let [s, ds, dds] = v;
                Some([
                    e.offset + ex + r * s,
                    -e.decay_rate * ex + dr * s + r * ds,
                    e.decay_rate * e.decay_rate * ex + ddr * s + 2.0 * dr * ds + r * dds,
                ])
            }
        }
    }

    /// Checks its values (finite, `fade_in` and decays >= 0), naming the
    /// first bad one under `key`.
    pub(crate) fn validate(&self, key: &str) -> Result<(), UnitError> {
        if let TimeFunction::Expression(Expression { sea: Some(sea), .. }) = self {
            sea.validate(&format!("{key}.sea"))?;
        }
        let expected = "expected finite values, fade_in >= 0 (s) and each sine's decay >= 0 (1/s)";
        match self {
            TimeFunction::Constant(c) if !c.is_finite() => {
                Err(UnitError::parameter(key, *c, expected))
            }
            TimeFunction::Constant(_) | TimeFunction::Input(_) => Ok(()),
            TimeFunction::Expression(e) => match first_bad_field(e) {
                Some((field, value)) => Err(UnitError::parameter(
                    &format!("{key}.{field}"),
                    value,
                    expected,
                )),
                None => Ok(()),
            },
        }
    }
}

/// The first field of `e` out of range (its name as the scene writes it, and
/// its value), or None.
fn first_bad_field(e: &Expression) -> Option<(String, f64)> {
    let fields = [
        ("offset", e.offset),
        ("amplitude", e.amplitude),
        ("angular_frequency", e.angular_frequency),
        ("phase", e.phase),
        ("decay_amplitude", e.decay_amplitude),
        ("decay_rate", e.decay_rate),
    ];
    if let Some((name, v)) = fields.iter().find(|(_, v)| !v.is_finite()) {
        return Some(((*name).to_owned(), *v));
    }
    if !(e.fade_in.is_finite() && e.fade_in >= 0.0) {
        return Some(("fade_in".into(), e.fade_in));
    }
    e.sines.iter().enumerate().find_map(|(k, s)| {
        let values = [
            ("amplitude", s.amplitude),
            ("angular_frequency", s.angular_frequency),
            ("phase", s.phase),
        ];
        let bad = values.into_iter().find(|(_, v)| !v.is_finite());
        let decay = (!(s.decay.is_finite() && s.decay >= 0.0)).then_some(("decay", s.decay));
        bad.or(decay)
            .map(|(name, v)| (format!("sines[{k}].{name}"), v))
    })
}

/// One condition at an end.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Condition {
    /// What is prescribed at the end.
    pub quantity: Quantity,
    /// Its value over time, or a coupled input.
    pub value: TimeFunction,
}

/// The two conditions at each end.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Boundary {
    /// At x = 0.
    pub left: [Condition; 2],
    /// At x = L.
    pub right: [Condition; 2],
}

impl Boundary {
    /// Refuses degenerate pairs: the same quantity twice, or a quantity with its
    /// work conjugate (deflection with shear, rotation with moment).
    pub fn validate(&self) -> Result<(), UnitError> {
        for (end, pair) in [("left", &self.left), ("right", &self.right)] {
            let (a, b) = (pair[0].quantity, pair[1].quantity);
            if a == b || a.dual() == b {
                return Err(UnitError::parameter(
                    &format!("boundary.{end}"),
                    format!("{} and {}", a.name(), b.name()),
                    "degenerate: choose two of deflection, rotation, moment, shear that are not work conjugates (deflection-shear and rotation-moment are)",
                ));
            }
            for (i, c) in pair.iter().enumerate() {
                c.value.validate(&format!("boundary.{end}[{i}].value"))?;
            }
        }
        Ok(())
    }

    /// The conditions as (end: 0 left / 1 right, condition), left first.
    pub fn all(&self) -> impl Iterator<Item = (usize, &Condition)> {
        self.left
            .iter()
            .map(|c| (0, c))
            .chain(self.right.iter().map(|c| (1, c)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_faded_sine_starts_at_rest_and_keeps_its_derivatives() {
        let f: TimeFunction = toml::from_str::<toml::Table>(
            "f = { offset = 1.0, amplitude = 2.0, angular_frequency = 0.628, phase = 0.4, fade_in = 20.0 }",
        )
        .unwrap()["f"]
            .clone()
            .try_into()
            .unwrap();
        // At rest at the offset at t = 0: value, velocity and acceleration.
        assert_eq!(f.eval(0.0).unwrap(), [1.0, 0.0, 0.0]);
        let at = |t: f64| f.eval(t).unwrap();
        let h = 1e-4;
        for t in [0.5, 7.0, 13.3, 19.99, 20.0, 31.0] {
            let [_, dv, ddv] = at(t);
            assert!(
                (dv - (at(t + h)[0] - at(t - h)[0]) / (2.0 * h)).abs() < 1e-7,
                "{t}"
            );
            assert!(
                (ddv - (at(t + h)[1] - at(t - h)[1]) / (2.0 * h)).abs() < 1e-6,
                "{t}"
            );
        }
        // Full amplitude from the fade's end on.
        let t = 25.0;
        assert!((at(t)[0] - (1.0 + 2.0 * (0.628 * t + 0.4).sin())).abs() < 1e-14);
        let negative: TimeFunction = toml::from_str::<toml::Table>("f = { fade_in = -1.0 }")
            .unwrap()["f"]
            .clone()
            .try_into()
            .unwrap();
        assert!(negative.validate("f").is_err());
    }

    #[test]
    fn a_sum_of_sines_has_the_derivatives_of_its_values() {
        let f: TimeFunction = toml::from_str::<toml::Table>(
            "f = { offset = 2.0, amplitude = 1.5, angular_frequency = 0.6, sines = [{ amplitude = 0.5, angular_frequency = 1.1, phase = 0.3 }, { amplitude = 0.2, angular_frequency = 0.4 }] }",
        )
        .unwrap()["f"]
            .clone()
            .try_into()
            .unwrap();
        let t = 3.7;
        let [v, dv, ddv] = f.eval(t).unwrap();
        let want =
            2.0 + 1.5 * (0.6 * t).sin() + 0.5 * (1.1 * t + 0.3).sin() + 0.2 * (0.4 * t).sin();
        assert!((v - want).abs() < 1e-14);
        let h = 1e-4;
        let at = |t: f64| f.eval(t).unwrap();
        assert!((dv - (at(t + h)[0] - at(t - h)[0]) / (2.0 * h)).abs() < 1e-7);
        assert!((ddv - (at(t + h)[1] - at(t - h)[1]) / (2.0 * h)).abs() < 1e-7);
        let bad: Result<TimeFunction, _> =
            toml::from_str::<toml::Table>("f = { sines = [{ amplitude = 1.0, period = 3.0 }] }")
                .unwrap()["f"]
                .clone()
                .try_into();
        assert!(bad.is_err());
    }
}
