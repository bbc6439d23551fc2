//! Seed 002's benchmark structures as `nonlinear` section parameters (TOML
//! text, to which a caller adds its own keys): the steel section (E = 210 GPa,
//! D = 50 mm with the exact area, rho = 7800 kg/m^3), the simply supported
//! cable (20 m, 20 elements, 59 free DOFs) and the simple frame (two 10 m
//! members at 90 deg, 20 elements each, 118 free DOFs). The reduced bases and
//! the geometrically nonlinear section are verified on them.

use std::f64::consts::PI;

/// EA, EI and mass per length of the steel section, as TOML keys.
pub fn steel() -> String {
    let (e, d, rho) = (210e9, 0.05, 7800.0);
    let area = PI * d * d / 4.0;
    let inertia = PI * d.powi(4) / 64.0;
    format!(
        "axial_stiffness = {}, bending_stiffness = {}, mass_per_length = {}",
        e * area,
        e * inertia,
        rho * area
    )
}

/// The pinned-pinned cable, with `extra` TOML lines.
pub fn cable(extra: &str) -> String {
    format!(
        r#"
formulation = "seed002"
segments = [{{ length = 20.0, elements = 20, {} }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ kind = "pinned" }}
{extra}
"#,
        steel()
    )
}

/// The frame: column and beam, far ends pinned, the corner held in x.
pub fn frame(extra: &str) -> String {
    format!(
        r#"
formulation = "seed002"
segments = [{{ length = 10.0, angle_deg = 90.0, elements = 20, {s} }}, {{ length = 10.0, elements = 20, {s} }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ kind = "pinned" }}
supports = [{{ at = 10.0, x = true }}]
{extra}
"#,
        s = steel()
    )
}
