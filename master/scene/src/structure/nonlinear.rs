//! The `nonlinear` and `linear` fidelities of a section: the model's own
//! unit over the section's arc-length range, coupled at its cuts (`linear`:
//! stepped linearised about its start, `linear = true`).

use super::Built;
use super::cuts::{End, coupled_end};
use super::layout::SectionOutputs;
use super::model::{SectionAt, SectionModel, outputs_of};
use super::sections::{Cut, Fidelity, Segment};
use super::unit::SectionUnit;
use slender_units::nonlinear::NonlinearParams;
use slender_units::nonlinear::params::{DistributedLoad, Segment as ModelSegment, Support};

/// The `nonlinear` fidelity (the geometrically nonlinear unit) and, with
/// `linear`, the `linear` one (that unit linearised about its start).
pub(super) struct Section {
    linear: bool,
}

/// The `nonlinear` fidelity.
pub(super) const NONLINEAR: Section = Section { linear: false };

/// The `linear` fidelity.
pub(super) const LINEAR: Section = Section { linear: true };

/// The `nonlinear` unit's outputs: end forces, the touchdown point
/// interpolated where the seabed gap closes (`touchdown_arc`), sag-bend and
/// overbend moments, and stations (not through an FMU, whose outputs are
/// fixed when it is exported).
pub(super) fn section_outputs(fmu: bool, seabed: bool, stinger: bool) -> SectionOutputs {
    let ends = ["start", "end"];
    let mut outputs = outputs_of(ends, false, Some("touchdown_arc"), true, (seabed, stinger));
    outputs.stations = !fmu;
    outputs
}

impl SectionModel for Section {
    fn name(&self) -> &'static str {
        if self.linear { "linear" } else { "nonlinear" }
    }
    fn is_section_unit(&self) -> bool {
        true
    }
    fn outputs(&self, fmu: bool, seabed: bool, stinger: bool, _: bool) -> SectionOutputs {
        section_outputs(fmu, seabed, stinger)
    }
    fn unit(&self, at: &SectionAt) -> Result<SectionUnit, String> {
        at.built.section_unit(at.cut(), at.ends)
    }
    /// A linear section cannot follow a stinger's moving rollers.
    fn refuse(&self, built: &Built, cut: &Cut) -> Result<(), String> {
        match self.linear {
            true => built.refuse_linear_on_stinger(cut),
            false => Ok(()),
        }
    }
    fn contact_state_kept(&self) -> Option<&'static str> {
        (self.linear).then_some(
            "a linear section cannot follow: it keeps the seabed as springs where it lay",
        )
    }
}

/// The `nonlinear` unit of one section: the model's segments clipped to its range,
/// its start at the stress-free position of the cut, the structure's ends at the
/// structure's ends, and at a cut (`coupling`: start, end; None at the
/// structure's ends) a moving or loaded end.
pub(super) fn section_unit(
    name: &str,
    model: &NonlinearParams,
    segments: &[Segment],
    cut: &Cut,
    coupling: (Option<End>, Option<End>),
) -> Result<SectionUnit, String> {
    let parameters = section_parameters(model, segments, cut, coupling)?;
    Ok(SectionUnit::nonlinear(
        super::unit_name(name, &cut.name),
        parameters,
    ))
}

/// The parameters of [`section_unit`]'s unit.
pub(super) fn section_parameters(
    model: &NonlinearParams,
    segments: &[Segment],
    cut: &Cut,
    coupling: (Option<End>, Option<End>),
) -> Result<NonlinearParams, String> {
    let mut parameters = model.clone();
    let (mut position, mut arc) = (model.start, 0.0f64);
    let mut clipped = Vec::new();
    // The model's own (unrounded) element count on each clipped segment.
    let mut density = Vec::new();
    let mut start = None;
    for s in segments {
        let (c, sn) = (
            s.angle_deg.to_radians().cos(),
            s.angle_deg.to_radians().sin(),
        );
        if let Some(elements) = s.elements_over(cut.from, cut.to) {
            if start.is_none() {
                let d = cut.from - arc;
                start = Some([position[0] + d * c, position[1] + d * sn]);
            }
            let length = s.overlap(cut.from, cut.to);
            clipped.push(ModelSegment {
                length,
                elements: elements as usize,
                ..s.properties.clone()
            });
            density.push(s.elements * length / s.length);
        }
        position = [position[0] + s.length * c, position[1] + s.length * sn];
        arc += s.length;
    }
    if let Some(n) = cut.elements {
        distribute(&mut clipped, &density, n);
    }
    parameters.start = start.ok_or(format!("section `{}` is empty", cut.name))?;
    parameters.segments = clipped;
    let length = segments.iter().map(|s| s.length).sum();
    let along = along(model, cut, length)?;
    (parameters.supports, parameters.loads, parameters.stations) =
        (along.supports, along.loads, along.stations);
    for (end, coupled) in [
        (&mut parameters.ends.start, coupling.0),
        (&mut parameters.ends.end, coupling.1),
    ] {
        if let Some(coupled) = coupled {
            *end = coupled_end(coupled);
        }
    }
    Ok(parameters)
}

/// The model's `supports`, `loads` and `stations` inside a section, in the
/// section's own arc length (m from its start).
pub(super) struct Along {
    pub supports: Vec<Support>,
    pub loads: Vec<DistributedLoad>,
    pub stations: Vec<f64>,
}

/// The model's `supports`, `loads` and `stations` that fall inside the section,
/// in the section's own arc length (m from its start): a load clipped to it, a
/// station in [from, to) (the last section keeps its end). A support at a cut
/// is refused: the cut's coupling moves or loads that node.
pub(super) fn along(model: &NonlinearParams, cut: &Cut, length: f64) -> Result<Along, String> {
    let tolerance = 1e-9 * length;
    let last = cut.to >= length - tolerance;
    let mut supports = Vec::new();
    for (i, support) in model.supports.iter().enumerate() {
        let at = support.at;
        let at_cut =
            |c: f64| c > tolerance && c < length - tolerance && (at - c).abs() <= tolerance;
        if at_cut(cut.from) || at_cut(cut.to) {
            return Err(format!(
                "`structure.model.supports[{i}].at` = {at}: a support at the cut of section `{}`; move the cut or the support",
                cut.name
            ));
        }
        if at > cut.from - tolerance && at < cut.to + tolerance {
            supports.push(Support {
                at: at - cut.from,
                ..support.clone()
            });
        }
    }
    let loads = (model.loads.iter())
        .filter_map(|load| {
            let from = load.from.max(cut.from);
            let to = load.to.min(cut.to);
            (to > from + tolerance).then(|| DistributedLoad {
                from: from - cut.from,
                to: to - cut.from,
                ..load.clone()
            })
        })
        .collect();
    let stations = (model.stations.iter().copied())
        .filter(|&s| s >= cut.from - tolerance && (s < cut.to - tolerance || last))
        .map(|s| (s - cut.from).max(0.0))
        .collect();
    Ok(Along {
        supports,
        loads,
        stations,
    })
}

/// Spreads `n` elements over the clipped segments in proportion to the
/// model's own counts there (`weights`), so a graded mesh stays graded (a
/// uniform one: in proportion to the lengths); at least one each, the
/// remainders to the largest fractions, so they sum to `n` where `n` is at
/// least the number of segments.
fn distribute(segments: &mut [ModelSegment], weights: &[f64], n: usize) {
    let total: f64 = weights.iter().sum();
    let shares: Vec<f64> = weights.iter().map(|w| n as f64 * w / total).collect();
    let mut counts: Vec<usize> = shares.iter().map(|s| (s.floor() as usize).max(1)).collect();
    let mut order: Vec<usize> = (0..shares.len()).collect();
    order.sort_by(|&a, &b| {
        (shares[b] - shares[b].floor()).total_cmp(&(shares[a] - shares[a].floor()))
    });
    let mut left = n.saturating_sub(counts.iter().sum());
    // The fractions sum to less than the number of segments: one pass.
    for &k in &order {
        if left == 0 {
            break;
        }
        counts[k] += 1;
        left -= 1;
    }
    for (segment, e) in segments.iter_mut().zip(counts) {
        segment.elements = e;
    }
}

impl super::Built {
    /// A `nonlinear` or `linear` section's unit, started from the
    /// equilibrium where there is one.
    pub(super) fn section_unit(
        &self,
        cut: &Cut,
        (start, end): (Option<End>, Option<End>),
    ) -> Result<SectionUnit, String> {
        let mut unit = section_unit(&self.name, &self.model, &self.segments, cut, (start, end))?;
        if let Some(parameters) = unit.nonlinear_mut() {
            parameters.linear |= cut.fidelity == Fidelity::Linear;
            if let Some(equilibrium) = &self.statics {
                equilibrium.start_section(parameters, (cut.from, cut.to));
            }
        }
        if let Some(equilibrium) = &self.statics {
            let loaded = (
                start.is_some_and(|e| !e.moving),
                end.is_some_and(|e| !e.moving),
            );
            equilibrium.first_guess_loads(&mut unit, (cut.from, cut.to), loaded);
        }
        Ok(unit)
    }
}
