//! The S-lay pipe of the nonlinear section's tests and example: a 12 inch steel
//! pipe from a vessel over a curved stinger of rollers down to a flat seabed,
//! held by a tensioner force at the vessel end, optionally heaving.

use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::{Driver, Time};

/// Seabed height (m, water surface at 0).
pub(crate) const SEABED: f64 = -40.0;
/// The vessel end (m): firing line horizontal.
pub(crate) const VESSEL: [f64; 2] = [300.0, 5.0];
/// Stinger radius (m); rollers every 5 m of arc.
pub(crate) const STINGER_RADIUS: f64 = 100.0;
/// Stinger angle at its tip (deg).
pub(crate) const STINGER_ANGLE: f64 = 30.0;
/// Submerged weight (N/m).
pub(crate) const WEIGHT: f64 = 400.0;
/// Tensioner force (N).
pub(crate) const TENSION: f64 = 100.0e3;
/// Bending stiffness (N m^2).
pub(crate) const BENDING_STIFFNESS: f64 = 1.0e7;

/// One S-lay scene.
#[derive(Clone, Debug)]
pub(crate) struct Slay {
    /// Elements of the pipe.
    pub elements: usize,
    /// Contact law (a TOML table) of the seabed (N/m^2).
    pub seabed_law: String,
    /// Contact law of the rollers (N/m).
    pub stinger_law: String,
    /// Vessel heave: amplitude (m) and angular frequency (rad/s); the stinger moves
    /// with it.
    pub heave: Option<(f64, f64)>,
    /// Further parameters (TOML lines).
    pub extra: String,
}

impl Slay {
    /// Penalty contact (1e6 N/m^2 on the seabed, 1e6 N/m per roller), no heave.
    pub(crate) fn new(elements: usize) -> Slay {
        Slay {
            elements,
            seabed_law: r#"{ kind = "penalty", penalty = 1.0e6 }"#.into(),
            stinger_law: r#"{ kind = "penalty", penalty = 1.0e6 }"#.into(),
            heave: None,
            extra: String::new(),
        }
    }

    /// The unit's parameters as TOML.
    pub(crate) fn toml(&self) -> String {
        let (positions, tops) = rollers();
        let points = start_points();
        let length: f64 = points
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum();
        let listed: Vec<String> = points
            .iter()
            .map(|p| format!("[{:.4}, {:.4}]", p[0], p[1]))
            .collect();
        let lift = VESSEL[1] - SEABED;
        let (end_z, motion) = match self.heave {
            Some((a, w)) => (
                format!("{{ offset = {lift}, amplitude = {a}, angular_frequency = {w} }}"),
                format!(
                    ", motion = {{ kind = \"sine\", amplitude = {a}, angular_frequency = {w} }}"
                ),
            ),
            None => (format!("{lift}"), String::new()),
        };
        format!(
            r#"
static_start = true
start_shape = "points"
start_points = [{points}]
start = [0.0, {SEABED}]
segments = [{{ length = {length:.3}, elements = {n}, axial_stiffness = 3.0e9, bending_stiffness = {BENDING_STIFFNESS}, mass_per_length = 100.0, submerged_weight = {WEIGHT}, diameter = 0.32, drag_normal = 1.0, added_mass_normal = 1.0 }}]
ends.start = {{ kind = "fixed" }}
ends.end = {{ x = {{ force = {TENSION} }}, z = {{ displacement = {end_z} }}, rotation = "held" }}
contact = {{ method = {seabed}, surface = {{ shape = {{ kind = "flat", height = {SEABED} }} }} }}
stinger = {{ method = {stinger}, surface = {{ shape = {{ kind = "rollers", positions = {positions:?}, tops = {tops:?}, radius = 0.5 }}{motion} }} }}
{extra}
"#,
            points = listed.join(", "),
            n = self.elements,
            seabed = self.seabed_law,
            stinger = self.stinger_law,
            extra = self.extra,
        )
    }

    /// The unit, initialised (static start).
    pub(crate) fn solved(&self) -> Result<Driver<NonlinearSection>, String> {
        let params: NonlinearParams = toml::from_str(&self.toml()).map_err(|e| e.to_string())?;
        let unit = NonlinearSection::new(params).map_err(|e| e.to_string())?;
        let mut driver = Driver::new(unit);
        driver.initialize(Time::ZERO).map_err(|e| e.to_string())?;
        Ok(driver)
    }
}

/// Roller x positions and tops (m) along the stinger arc, the first 2 m from the
/// vessel end.
pub(crate) fn rollers() -> (Vec<f64>, Vec<f64>) {
    let arc = STINGER_RADIUS * STINGER_ANGLE.to_radians();
    let count = (arc / 5.0).round() as usize;
    (0..=count)
        .map(|k| {
            let phi = (k as f64 * 5.0 / STINGER_RADIUS).min(STINGER_ANGLE.to_radians());
            (
                VESSEL[0] - 2.0 - STINGER_RADIUS * phi.sin(),
                VESSEL[1] - STINGER_RADIUS * (1.0 - phi.cos()),
            )
        })
        .unzip()
}

/// Start polyline from the laid end: the seabed, the catenary from its touchdown
/// to the stinger tip (horizontal tension: the tensioner force less the weight
/// times the height), the stinger arc 1 cm above the rollers.
pub(crate) fn start_points() -> Vec<[f64; 2]> {
    let phi = STINGER_ANGLE.to_radians();
    let tip = [
        VESSEL[0] - STINGER_RADIUS * phi.sin(),
        VESSEL[1] - STINGER_RADIUS * (1.0 - phi.cos()),
    ];
    let a = (TENSION - WEIGHT * (VESSEL[1] - SEABED)) / WEIGHT;
    let span = a * (1.0 + (tip[1] - SEABED) / a).acosh();
    let touchdown = tip[0] - span;
    let mut points = vec![[0.0, SEABED]];
    for k in 0..=10 {
        let x = span * k as f64 / 10.0;
        points.push([touchdown + x, SEABED + a * ((x / a).cosh() - 1.0)]);
    }
    for k in 1..=10 {
        let p = phi * (1.0 - k as f64 / 10.0);
        points.push([
            VESSEL[0] - STINGER_RADIUS * p.sin(),
            VESSEL[1] - STINGER_RADIUS * (1.0 - p.cos()) + 0.01,
        ]);
    }
    points
}

/// The outputs of a driver by name.
pub(crate) fn output(driver: &Driver<NonlinearSection>, name: &str) -> f64 {
    let ports = &driver.description().outputs;
    let mut out = vec![0.0; ports.len()];
    driver.outputs(&mut out).expect("outputs");
    let i = ports
        .iter()
        .position(|p| p.name == name)
        .unwrap_or_else(|| panic!("no output {name}"));
    out[i]
}
