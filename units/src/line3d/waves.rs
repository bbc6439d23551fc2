//! Airy (linear) wave kinematics for the 3D line: velocity and acceleration of
//! the water under a sum of wave components travelling towards one heading,
//! with the finite-depth or deep-water dispersion relation. Above the mean
//! surface the kinematics are stretched (Wheeler): the profile at z is the one
//! at `(z - eta) h / (h + eta)` below the still water line (`z - eta` in deep
//! water), so the water under a crest moves as at the surface and a node above
//! the instantaneous surface is dry (no hydrodynamic force).

use super::params::Waves;
use nalgebra::Vector3;

/// Gravity (m/s^2) for the dispersion relation.
pub const GRAVITY: f64 = 9.81;

/// One component: elevation `amplitude sin(omega t + phase - k . x)` (m).
#[derive(Clone, Debug)]
struct Component {
    amplitude: f64,
    omega: f64,
    phase: f64,
    wavenumber: f64,
}

/// The waves of a line.
#[derive(Clone, Debug)]
pub struct AiryWaves {
    components: Vec<Component>,
    /// Unit vector of the heading (x, y).
    direction: [f64; 2],
    /// Water depth (m); infinite for deep water.
    depth: f64,
    /// Seconds over which the waves grow from calm.
    fade_in: f64,
}

/// The water's motion at a point and time.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Kinematics {
    /// Surface elevation above the point (m).
    pub elevation: f64,
    /// Velocity (m/s) and acceleration (m/s^2).
    pub velocity: Vector3<f64>,
    pub acceleration: Vector3<f64>,
}

/// The wavenumber k (1/m) of angular frequency `omega` (rad/s) on water of
/// depth `h` (m, infinite for deep water): omega^2 = g k tanh(k h), by Newton
/// from the deep-water value (bounded: 100 iterations, converges in a few).
pub fn wavenumber(omega: f64, h: f64) -> f64 {
    let deep = omega * omega / GRAVITY;
    if !h.is_finite() {
        return deep;
    }
    let mut k = deep.max((omega * omega / (GRAVITY * h)).sqrt());
    for _ in 0..100 {
        let th = (k * h).tanh();
        let f = GRAVITY * k * th - omega * omega;
        let df = GRAVITY * (th + k * h * (1.0 - th * th));
        let dk = f / df;
        k -= dk;
        if dk.abs() < 1e-14 * k {
            break;
        }
    }
    k
}

impl AiryWaves {
    /// From the scene's waves (`water_depth = 0`: deep water).
    pub fn new(waves: &Waves) -> AiryWaves {
        let depth = if waves.water_depth > 0.0 {
            waves.water_depth
        } else {
            f64::INFINITY
        };
        let sines = match &waves.spectrum {
            Some(spectrum) => spectrum.sines(),
            None => waves.sines.clone(),
        };
        let components = sines
            .iter()
            .map(|s| Component {
                amplitude: s.amplitude,
                omega: s.angular_frequency,
                phase: s.phase,
                wavenumber: wavenumber(s.angular_frequency, depth),
            })
            .collect();
        let heading = waves.heading_deg.to_radians();
        AiryWaves {
            components,
            direction: [heading.cos(), heading.sin()],
            depth,
            fade_in: waves.fade_in,
        }
    }

    /// Elevation (m) at plan position (x, y) and time t (s), faded in.
    pub fn elevation(&self, x: f64, y: f64, t: f64) -> f64 {
        let along = x * self.direction[0] + y * self.direction[1];
        let full: f64 = self
            .components
            .iter()
            .map(|c| c.amplitude * (c.omega * t + c.phase - c.wavenumber * along).sin())
            .sum();
        crate::signal::sine::fade(self.fade_in, t)[0] * full
    }

    /// The water's kinematics at `p` and `t`; `None` above the surface.
    pub fn at(&self, p: &Vector3<f64>, t: f64) -> Option<Kinematics> {
        let eta = self.elevation(p.x, p.y, t);
        if p.z > eta {
            return None;
        }
        let h = self.depth;
        let z = if h.is_finite() {
            (p.z - eta) * h / (h + eta)
        } else {
            p.z - eta
        };
        let along = p.x * self.direction[0] + p.y * self.direction[1];
        let (mut horizontal, mut vertical) = ([0.0; 2], [0.0; 2]);
        for c in &self.components {
            let (horizontal_shape, vertical_shape) = shapes(c.wavenumber, z, h);
            let theta = c.omega * t + c.phase - c.wavenumber * along;
            let (sin, cos) = theta.sin_cos();
            let aw = c.amplitude * c.omega;
            horizontal[0] += aw * horizontal_shape * sin;
            horizontal[1] += aw * c.omega * horizontal_shape * cos;
            vertical[0] += aw * vertical_shape * cos;
            vertical[1] -= aw * c.omega * vertical_shape * sin;
        }
        let [dx, dy] = self.direction;
        // Faded in: r u, and r a + r' u for the acceleration.
        let [r, rate, _] = crate::signal::sine::fade(self.fade_in, t);
        let velocity = Vector3::new(horizontal[0] * dx, horizontal[0] * dy, vertical[0]);
        let acceleration = Vector3::new(horizontal[1] * dx, horizontal[1] * dy, vertical[1]);
        Some(Kinematics {
            elevation: eta,
            velocity: velocity * r,
            acceleration: acceleration * r + velocity * rate,
        })
    }
}

/// cosh(k (z + h)) / sinh(k h) and sinh(k (z + h)) / sinh(k h), both
/// exp(k z) in deep water (z <= 0 below the still water line).
fn shapes(k: f64, z: f64, h: f64) -> (f64, f64) {
    if !h.is_finite() || k * h > 20.0 {
        let e = (k * z).exp();
        return (e, e);
    }
    let depth = (z + h).max(0.0);
    let s = (k * h).sinh();
    ((k * depth).cosh() / s, (k * depth).sinh() / s)
}
