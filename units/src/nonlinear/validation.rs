//! Checks of the nonlinear section's parameters ([`NonlinearParams::validate`]):
//! each refusal names the key and says what was expected.

use super::params::{Current, Integrator, NonlinearParams, Segment, StartShape};
use crate::contract::{
    UnitError, require_finite, require_in_range, require_non_negative, require_positive,
};

impl NonlinearParams {
    /// Checks every parameter, naming the first bad one.
    pub fn validate(&self) -> Result<(), UnitError> {
        if self.segments.is_empty() {
            return Err(UnitError::parameter(
                "segments",
                "[]",
                "at least one segment",
            ));
        }
        require_finite("start[0]", self.start[0])?;
        require_finite("start[1]", self.start[1])?;
        for (i, s) in self.segments.iter().enumerate() {
            validate_segment(&format!("segments[{i}]"), s)?;
        }
        require_non_negative("rayleigh_mass", self.rayleigh_mass)?;
        require_non_negative("rayleigh_stiffness", self.rayleigh_stiffness)?;
        require_positive("water_density", self.water_density)?;
        require_in_range("load_steps", f64::from(self.load_steps), 1.0, 10_000.0, "")?;
        require_in_range(
            "max_substeps",
            f64::from(self.max_substeps),
            1.0,
            1024.0,
            "",
        )?;
        self.integrator.validate()?;
        let length = self.length();
        for (i, &s) in self.stations.iter().enumerate() {
            require_in_range(&format!("stations[{i}]"), s, 0.0, length, "m")?;
        }
        for (i, support) in self.supports.iter().enumerate() {
            require_in_range(&format!("supports[{i}].at"), support.at, 0.0, length, "m")?;
            if self.node_at(support.at).is_none() {
                return Err(UnitError::parameter(
                    &format!("supports[{i}].at"),
                    support.at,
                    "the arc length of a node (segment ends and element boundaries)",
                ));
            }
        }
        for (i, l) in self.loads.iter().enumerate() {
            if l.from.is_nan() || l.to.is_nan() || l.from > l.to {
                return Err(UnitError::parameter(
                    &format!("loads[{i}]"),
                    format!("from = {}, to = {}", l.from, l.to),
                    "expected from <= to",
                ));
            }
            l.x.validate(&format!("loads[{i}].x"))?;
            l.z.validate(&format!("loads[{i}].z"))?;
        }
        if let Some(c) = &self.current {
            validate_current(c)?;
        }
        super::contact::validate(self)?;
        self.validate_start_points()?;
        self.ends.validate()?;
        let hydro = self.segments.iter().any(|s| {
            s.drag_normal + s.drag_tangential + s.added_mass_normal + s.added_mass_tangential > 0.0
        });
        if self.current.is_some() && !hydro {
            return Err(UnitError::parameter(
                "current",
                "a current profile",
                "drag coefficients and a diameter on some segment (a current without drag acts on nothing)",
            ));
        }
        Ok(())
    }
}

impl NonlinearParams {
    /// `start_points` are given exactly when `start_shape = "points"`: at least two
    /// finite points, consecutive ones distinct.
    fn validate_start_points(&self) -> Result<(), UnitError> {
        let points = &self.start_points;
        let wanted = self.start_shape == StartShape::Points;
        if wanted == points.is_empty() {
            return Err(UnitError::parameter(
                "start_points",
                format!("{} points", points.len()),
                "at least two points exactly when start_shape = \"points\"",
            ));
        }
        let bad = points.iter().flatten().any(|v| !v.is_finite())
            || points.windows(2).any(|w| w[0] == w[1]);
        if bad || (wanted && points.len() < 2) {
            return Err(UnitError::parameter(
                "start_points",
                format!("{points:?}"),
                "at least two finite points, consecutive ones distinct",
            ));
        }
        Ok(())
    }
}

impl Integrator {
    /// Checks the integrator's settings.
    fn validate(&self) -> Result<(), UnitError> {
        if let Integrator::Hht { alpha, .. } = *self {
            require_in_range("integrator.alpha", alpha, 0.0, 1.0 / 3.0, "")?;
        }
        if let Integrator::Hht {
            tolerance,
            max_iterations,
            ..
        }
        | Integrator::EnergyConserving {
            tolerance,
            max_iterations,
        } = *self
        {
            require_in_range("integrator.tolerance", tolerance, 1e-15, 1e-2, "")?;
            require_in_range(
                "integrator.max_iterations",
                f64::from(max_iterations),
                1.0,
                1000.0,
                "",
            )?;
        }
        Ok(())
    }
}

fn validate_segment(key: &str, s: &Segment) -> Result<(), UnitError> {
    require_in_range(&format!("{key}.length"), s.length, 1e-3, 1e6, "m")?;
    let angle = format!("{key}.angle_deg");
    require_in_range(&angle, s.angle_deg, -360.0, 360.0, "deg")?;
    require_in_range(
        &format!("{key}.elements"),
        s.elements as f64,
        1.0,
        100_000.0,
        "",
    )?;
    require_in_range(
        &format!("{key}.axial_stiffness"),
        s.axial_stiffness,
        1.0,
        1e13,
        "N",
    )?;
    require_in_range(
        &format!("{key}.bending_stiffness"),
        s.bending_stiffness,
        1e-9,
        1e12,
        "N m^2",
    )?;
    require_in_range(
        &format!("{key}.mass_per_length"),
        s.mass_per_length,
        1e-6,
        1e6,
        "kg/m",
    )?;
    // As heavy or as buoyant as 1e6 kg/m in water (mass_per_length's bound).
    require_in_range(
        &format!("{key}.submerged_weight"),
        s.submerged_weight,
        -1e8,
        1e8,
        "N/m",
    )?;
    for (name, v) in [
        ("diameter", s.diameter),
        ("drag_normal", s.drag_normal),
        ("drag_tangential", s.drag_tangential),
        ("added_mass_normal", s.added_mass_normal),
        ("added_mass_tangential", s.added_mass_tangential),
    ] {
        require_in_range(&format!("{key}.{name}"), v, 0.0, 100.0, "")?;
    }
    let hydro = s.drag_normal + s.drag_tangential + s.added_mass_normal + s.added_mass_tangential;
    if hydro > 0.0 && s.diameter <= 0.0 {
        return Err(UnitError::parameter(
            &format!("{key}.diameter"),
            s.diameter,
            "a diameter > 0 where drag or added-mass coefficients are given",
        ));
    }
    Ok(())
}

fn validate_current(c: &Current) -> Result<(), UnitError> {
    if c.z.is_empty() || c.z.len() != c.velocity.len() {
        return Err(UnitError::parameter(
            "current",
            format!("{} depths, {} velocities", c.z.len(), c.velocity.len()),
            "as many velocities as depths, at least one",
        ));
    }
    if c.z.windows(2).any(|w| w[0] >= w[1]) || c.z.iter().chain(&c.velocity).any(|v| !v.is_finite())
    {
        return Err(UnitError::parameter(
            "current.z",
            format!("{:?}", c.z),
            "finite, strictly increasing depths",
        ));
    }
    Ok(())
}
