//! What a scene asks of its recorded signals after the run (issue 50): the
//! statistics over a window, the most probable maxima over a longer duration,
//! the power spectra, and the fatigue damage of a tension or a stress. The
//! app computes them (`slender_app::statistics`, `extremes`, `spectrum`,
//! `fatigue`); this module holds what the scene says and checks it before a
//! run, so a misspelt signal or a missing section property is refused at
//! `check`, not after hours of simulation.

use crate::Scene;
use crate::SceneError;
use serde::Deserialize;
use slender_coupling::system::System;
use slender_units::contract::Causality;
use slender_units::sea::spectrum::Spectrum;

/// `[output] statistics = { from = S, extremes = { duration = D }, spectra = { segment = L } }`.
#[derive(Copy, Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StatisticsSpec {
    /// The window's start (s): the build-up before it is left out; default
    /// the simulation's start.
    #[serde(default)]
    pub from: Option<f64>,
    /// The most probable maximum of every signal over a longer duration.
    #[serde(default)]
    pub extremes: Option<ExtremesSpec>,
    /// The power spectral density of every signal (Welch).
    #[serde(default)]
    pub spectra: Option<SpectraSpec>,
}

/// `extremes = { duration = D, threshold = K }`: the storm the maxima are
/// extrapolated to, and the peaks-over-threshold level.
#[derive(Copy, Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtremesSpec {
    /// The duration the most probable maximum is for (s; 10800 for the
    /// 3-hour storm of DNV-OS-E301).
    pub duration: f64,
    /// The threshold of the peaks-over-threshold fit, in standard deviations
    /// above the mean (default 1.4: about 38 % of a narrow-band Gaussian
    /// process's peaks pass it).
    #[serde(default = "default_threshold")]
    pub threshold: f64,
}

fn default_threshold() -> f64 {
    1.4
}

/// `spectra = { segment = L }`: Welch's averaged periodograms.
#[derive(Copy, Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectraSpec {
    /// The length of each segment (s): the frequency resolution is its
    /// inverse; default an eighth of the window (15 half-overlapping segments).
    #[serde(default)]
    pub segment: Option<f64>,
}

/// `[output] envelopes = { from = S }`: the smallest, largest and mean
/// tension, curvature and bending moment along every unit that reports them.
#[derive(Copy, Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvelopesSpec {
    /// The window's start (s); default the statistics' `from`, or the start.
    #[serde(default)]
    pub from: Option<f64>,
}

/// `[[output.fatigue]]`: the fatigue damage of one point of a line.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FatigueSpec {
    /// The result's name (a row of `summary.json`'s `fatigue`).
    pub name: String,
    /// The recorded tension (N).
    pub tension: String,
    /// A recorded bending moment (N m): the stress is taken at the outer
    /// fibre on both sides of the section, the worse side reported.
    #[serde(default)]
    pub moment: Option<String>,
    /// The T-N or S-N curve.
    pub curve: FatigueCurve,
    /// The nominal cross-section area (m2) for the stress; a chain's may be
    /// given by `chain_diameter` instead.
    #[serde(default)]
    pub area: Option<f64>,
    /// A chain's bar diameter (m): the nominal area is two bars,
    /// 2 pi d^2 / 4 (DNV-OS-E301).
    #[serde(default)]
    pub chain_diameter: Option<f64>,
    /// The section modulus (m3) of the outer fibre, with `moment`.
    #[serde(default)]
    pub section_modulus: Option<f64>,
    /// The reference breaking strength (N) of API RP 2SK's curves.
    #[serde(default)]
    pub breaking_load: Option<f64>,
    /// The stress concentration factor on the nominal stress (default 1).
    #[serde(default)]
    pub scf: Option<f64>,
    /// The window's start (s); default the statistics' `from`, or the start.
    #[serde(default)]
    pub from: Option<f64>,
    /// DNV-RP-C203's thickness effect (S-N curves): the thickness a crack
    /// grows through (m); ranges are raised by (t / t_ref)^k above t_ref.
    #[serde(default)]
    pub thickness: Option<f64>,
    /// The thickness effect's reference t_ref (m; default 0.025, welded
    /// connections other than tubular joints; 0.016 for tubular joints).
    #[serde(default)]
    pub reference_thickness: Option<f64>,
    /// The thickness exponent k (default the curve's, DNV-RP-C203 Tables
    /// 2-1 and 2-2).
    #[serde(default)]
    pub thickness_exponent: Option<f64>,
    /// DNV-RP-C203's mean stress effect (S-N curves): the compressive part of
    /// each cycle's range reduced (default none, as welded).
    #[serde(default)]
    pub mean_stress: Option<MeanStress>,
}

/// Where DNV-RP-C203 (2.5) lets the compressive part of a stress range count
/// less: the range becomes its tensile part plus a factor times its
/// compressive part, f_m = (s_t + c s_c) / (s_t + s_c).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MeanStress {
    /// Base material not significantly affected by welding residual
    /// stresses (cut-outs, the pipe wall away from welds): c = 0.6.
    BaseMaterial,
    /// Welded connections after post-weld heat treatment: c = 0.8.
    PostWeldHeatTreated,
}

impl MeanStress {
    /// The factor on the compressive part of a range.
    pub fn compressive_factor(self) -> f64 {
        match self {
            MeanStress::BaseMaterial => 0.6,
            MeanStress::PostWeldHeatTreated => 0.8,
        }
    }
}

/// The fatigue curves slender knows, each with its source (parameters in
/// `slender_app::fatigue`).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FatigueCurve {
    /// DNV-OS-E301 T-N curve, studless chain (stress range on the nominal area).
    DnvStudlessChain,
    /// DNV-OS-E301 T-N curve, studlink chain.
    DnvStudlinkChain,
    /// DNV-OS-E301 T-N curve, six-strand wire rope.
    DnvSixStrandRope,
    /// DNV-OS-E301 T-N curve, spiral-strand wire rope.
    DnvSpiralStrandRope,
    /// API RP 2SK T-N curve, common studless chain (range over breaking strength).
    ApiStudlessChain,
    /// API RP 2SK T-N curve, common studlink chain.
    ApiStudlinkChain,
    /// API RP 2SK T-N curve, six- or multi-strand rope (mean load dependent).
    ApiSixStrandRope,
    /// API RP 2SK T-N curve, spiral-strand rope (mean load dependent).
    ApiSpiralStrandRope,
    /// DNV-RP-C203 S-N curve B1 in air.
    DnvC203B1Air,
    /// DNV-RP-C203 S-N curve C in air.
    DnvC203CAir,
    /// DNV-RP-C203 S-N curve D in air.
    DnvC203DAir,
    /// DNV-RP-C203 S-N curve E in air.
    DnvC203EAir,
    /// DNV-RP-C203 S-N curve F in air.
    DnvC203FAir,
    /// DNV-RP-C203 S-N curve F1 in air.
    DnvC203F1Air,
    /// DNV-RP-C203 S-N curve B1 in seawater with cathodic protection.
    DnvC203B1SeawaterCp,
    /// DNV-RP-C203 S-N curve C in seawater with cathodic protection.
    DnvC203CSeawaterCp,
    /// DNV-RP-C203 S-N curve D in seawater with cathodic protection.
    DnvC203DSeawaterCp,
    /// DNV-RP-C203 S-N curve E in seawater with cathodic protection.
    DnvC203ESeawaterCp,
    /// DNV-RP-C203 S-N curve F in seawater with cathodic protection.
    DnvC203FSeawaterCp,
    /// DNV-RP-C203 S-N curve F1 in seawater with cathodic protection.
    DnvC203F1SeawaterCp,
}

impl FatigueCurve {
    /// DNV-RP-C203's S-N curves (welded steel), the ones its thickness and
    /// mean stress effects apply to.
    pub fn is_dnv_c203(self) -> bool {
        use FatigueCurve::*;
        matches!(
            self,
            DnvC203B1Air
                | DnvC203CAir
                | DnvC203DAir
                | DnvC203EAir
                | DnvC203FAir
                | DnvC203F1Air
                | DnvC203B1SeawaterCp
                | DnvC203CSeawaterCp
                | DnvC203DSeawaterCp
                | DnvC203ESeawaterCp
                | DnvC203FSeawaterCp
                | DnvC203F1SeawaterCp
        )
    }

    /// API RP 2SK's curves take the range over the breaking strength, not a stress.
    pub fn needs_breaking_load(self) -> bool {
        use FatigueCurve::*;
        matches!(
            self,
            ApiStudlessChain | ApiStudlinkChain | ApiSixStrandRope | ApiSpiralStrandRope
        )
    }
}

impl Scene {
    /// Refuses what `[output] statistics` and `[[output.fatigue]]` ask for
    /// and cannot be given: a window before the start, a duration or segment
    /// that is not a positive time, a signal the scene does not record, a
    /// missing or non-positive section property, two results of one name.
    pub(crate) fn check_analysis(&self, system: &System) -> Result<(), SceneError> {
        let output = &self.spec.output;
        if let Some(s) = output.statistics {
            self.check_from("output.statistics.from", s.from)?;
            if let Some(e) = s.extremes {
                self.check_positive("output.statistics.extremes.duration", Some(e.duration))?;
                if !(e.threshold.is_finite() && e.threshold >= 0.0) {
                    let key = "output.statistics.extremes.threshold";
                    let expected =
                        "expected a number of standard deviations above the mean, 0 or more";
                    return Err(self.error(None, key, format!("{}: {expected}", e.threshold)));
                }
            }
            if let Some(p) = s.spectra {
                self.check_positive("output.statistics.spectra.segment", p.segment)?;
            }
        }
        if let Some(e) = output.envelopes {
            self.check_from("output.envelopes.from", e.from)?;
        }
        for (i, f) in output.fatigue.iter().enumerate() {
            let key = format!("output.fatigue[{i}]");
            if output.fatigue[..i].iter().any(|g| g.name == f.name) {
                return Err(self.error(None, &key, format!("`{}` is named twice", f.name)));
            }
            for s in std::iter::once(&f.tension).chain(&f.moment) {
                self.check_recorded(system, &key, s)?;
            }
            self.check_fatigue_properties(&key, f)?;
        }
        Ok(())
    }

    /// A window start at or after the run's start (None: the start).
    fn check_from(&self, key: &str, from: Option<f64>) -> Result<(), SceneError> {
        let start = self.start.as_secs();
        match from {
            Some(from) if !(from.is_finite() && from >= start) => Err(self.error(
                None,
                key,
                format!("{from}: expected a time (s) at or after the run's start, {start}"),
            )),
            _ => Ok(()),
        }
    }

    /// A finite value above zero (None: not given, allowed).
    fn check_positive(&self, key: &str, value: Option<f64>) -> Result<(), SceneError> {
        match value {
            Some(v) if !(v.is_finite() && v > 0.0) => {
                Err(self.error(None, key, format!("{v}: expected a positive number")))
            }
            _ => Ok(()),
        }
    }

    /// A unit's output that the run records.
    fn check_recorded(&self, system: &System, key: &str, signal: &str) -> Result<(), SceneError> {
        system
            .resolve(signal, Causality::Output)
            .map_err(|m| self.error(None, key, m))?;
        let signals = &self.spec.output.signals;
        if !signals.is_empty() && !signals.iter().any(|s| s == signal) {
            return Err(self.error(None, key, format!("`{signal}` is not among output.signals")));
        }
        Ok(())
    }

    /// The section properties the curve and the signals need, each positive.
    fn check_fatigue_properties(&self, key: &str, f: &FatigueSpec) -> Result<(), SceneError> {
        let given = [
            ("area", f.area),
            ("chain_diameter", f.chain_diameter),
            ("section_modulus", f.section_modulus),
            ("breaking_load", f.breaking_load),
            ("scf", f.scf),
            ("thickness", f.thickness),
            ("reference_thickness", f.reference_thickness),
        ];
        for (name, value) in given {
            self.check_positive(&format!("{key}.{name}"), value)?;
        }
        self.check_from(&format!("{key}.from"), f.from)?;
        let missing = |what: &str| self.error(None, key, format!("the curve needs {what}"));
        if f.curve.needs_breaking_load() {
            if f.breaking_load.is_none() {
                return Err(missing("`breaking_load` (N)"));
            }
            if f.moment.is_some() {
                return Err(missing("a tension range alone (no `moment`)"));
            }
        } else if f.area.is_some() == f.chain_diameter.is_some() {
            return Err(missing("one of `area` (m2) and `chain_diameter` (m)"));
        }
        if f.moment.is_some() != f.section_modulus.is_some() {
            return Err(self.error(
                None,
                key,
                "`moment` and `section_modulus` (m3) are given together or not at all",
            ));
        }
        self.check_c203_effects(key, f)
    }

    /// DNV-RP-C203's thickness and mean stress effects: with its curves
    /// only, the exponent with a thickness, k in [0, 1].
    fn check_c203_effects(&self, key: &str, f: &FatigueSpec) -> Result<(), SceneError> {
        let asked = [
            ("thickness", f.thickness.is_some()),
            ("reference_thickness", f.reference_thickness.is_some()),
            ("thickness_exponent", f.thickness_exponent.is_some()),
            ("mean_stress", f.mean_stress.is_some()),
        ];
        if let Some((name, _)) = asked.iter().find(|(_, given)| *given)
            && !f.curve.is_dnv_c203()
        {
            return Err(self.error(
                None,
                &format!("{key}.{name}"),
                "DNV-RP-C203's effects apply to its S-N curves (`dnv_c203_...`), not to a chain's or a rope's T-N curve",
            ));
        }
        if f.thickness.is_none()
            && (f.reference_thickness.is_some() || f.thickness_exponent.is_some())
        {
            return Err(self.error(
                None,
                &format!("{key}.thickness"),
                "missing: `reference_thickness` and `thickness_exponent` need the `thickness` (m) a crack grows through",
            ));
        }
        match f.thickness_exponent {
            Some(k) if !(0.0..=1.0).contains(&k) => Err(self.error(
                None,
                &format!("{key}.thickness_exponent"),
                format!("{k}: expected an exponent from 0 to 1 (DNV-RP-C203's run from 0 to 0.25)"),
            )),
            _ => Ok(()),
        }
    }
}

impl Scene {
    /// A warning per sea that repeats within the window analysed from
    /// `from` (s) to the run's end: its statistics, extremes and fatigue are
    /// then those of one repeat period, however long the run. A sea made of
    /// components at equal frequency steps dw repeats after 2 pi / dw
    /// (`slender_units::sea::spectrum::Spectrum::repeat_period`); the warning names the
    /// units and the components that would not repeat.
    pub fn sea_repeat_warnings(&self, from: f64) -> Vec<String> {
        let window = self.end().as_secs() - from;
        let mut seas: Vec<(f64, usize, [f64; 2], Vec<String>)> = Vec::new();
        for (name, s) in self.seas_by_unit() {
            let period = s.repeat_period();
            if period >= window {
                continue;
            }
            match seas.iter_mut().find(|x| x.0 == period) {
                Some(x) if !x.3.contains(&name) => x.3.push(name),
                Some(_) => {}
                None => seas.push((period, s.components, s.band, vec![name])),
            }
        }
        (seas.into_iter())
            .map(|(period, components, band, units)| {
                let needed = (components as f64 * window / period).ceil();
                format!(
                    "the sea of {} ({components} components over [{}, {}] x the peak frequency) repeats every {period:.1} s: the {window} s analysed see the same waves {:.1} times, so their statistics, extremes and fatigue are those of {period:.1} s; give the spectrum `components = {needed}` or more for a sea that does not repeat",
                    units.join(", "),
                    band[0],
                    band[1],
                    window / period
                )
            })
            .collect()
    }

    /// The wave spectra the scene's units are driven by, each once (the
    /// same sea on several units counted once), in unit order.
    pub fn sea_spectra(&self) -> Vec<Spectrum> {
        let mut seas: Vec<Spectrum> = Vec::new();
        for (_, s) in self.seas_by_unit() {
            if !seas.contains(&s) {
                seas.push(s);
            }
        }
        seas
    }

    /// Each unit's name with each wave spectrum among its parameters.
    fn seas_by_unit(&self) -> Vec<(String, Spectrum)> {
        let mut seas = Vec::new();
        for unit in &self.spec.units {
            // A written-out unit's typed parameters are searched as the
            // table they write (once, after a run).
            let written = (unit.written.as_ref()).and_then(|p| p.to_table().ok());
            let parameters = (unit.parameters.as_ref().map(|p| p.get_ref())).or(written.as_ref());
            if let Some(parameters) = parameters {
                let name = unit.name.get_ref();
                seas.extend(
                    spectra_in(parameters)
                        .into_iter()
                        .map(|s| (name.clone(), s)),
                );
            }
        }
        seas
    }
}

/// Every wave spectrum among a unit's parameters (a `spectrum` table that
/// reads as one, at any depth).
fn spectra_in(table: &toml::Table) -> Vec<Spectrum> {
    let mut found = Vec::new();
    for (key, value) in table {
        let Some(inner) = value.as_table() else {
            continue;
        };
        if key == "spectrum"
            && let Ok(s) = Spectrum::deserialize(value.clone())
        {
            found.push(s);
        } else {
            found.extend(spectra_in(inner));
        }
    }
    found
}

/// A structure cut into sections: a `[structure]`, or a line of a
/// `[mooring]`, so that what a section reports along itself (an envelope)
/// can be placed on the structure beside the twin's.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionedStructure {
    /// Its name (`structure.name`, a mooring line's `name`).
    pub name: String,
    /// Its twin's unit (which a structure without `reference` does not have).
    pub twin: String,
    /// Each section's unit with the arc length (m) of its start.
    pub sections: Vec<(String, f64)>,
}

impl Scene {
    /// The `[structure]`, or each line of the `[mooring]` (its arc from its
    /// anchor): every structure whose sections line up along it.
    pub fn sectioned_structures(&self) -> Vec<SectionedStructure> {
        let structure =
            (self.keys().ok()).and_then(|table| crate::structure::layout(&table).ok().flatten());
        if let Some(layout) = structure {
            return vec![sectioned(layout)];
        }
        match crate::mooring::of_scene(self) {
            Ok(Some(mooring)) => (mooring.line_layouts().into_iter())
                .map(|(_, layout)| sectioned(layout))
                .collect(),
            _ => Vec::new(),
        }
    }
}

fn sectioned(layout: crate::structure::Layout) -> SectionedStructure {
    SectionedStructure {
        twin: crate::structure::reference_name(&layout.name),
        sections: (layout.sections.into_iter())
            .map(|s| (s.unit, s.from))
            .collect(),
        name: layout.name,
    }
}
