//! Airy (linear) wave kinematics for the 3D line: velocity and acceleration of
//! the water under a sum of wave components travelling towards one heading,
//! with the finite-depth or deep-water dispersion relation. Above the mean
//! surface the kinematics are stretched (Wheeler): the profile at z is the one
//! at `(z - eta) h / (h + eta)` below the still water line (`z - eta` in deep
//! water), so the water under a crest moves as at the surface and a node above
//! the instantaneous surface is dry (no hydrodynamic force).

use super::params::Waves;
use nalgebra::Vector3;

thread_local! {
    /// The components' (sin, cos) of their phase at one point: a buffer that
    /// grows once per thread.
    static PHASES: std::cell::RefCell<Vec<(f64, f64)>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Gravity (m/s^2) for the dispersion relation.
pub const GRAVITY: f64 = 9.81;

/// One component: elevation `amplitude sin(omega t + phase - k . x)` (m),
/// and `1 / sinh(k h)` of its depth profile (0 where it is deep water's).
#[derive(Clone, Debug)]
struct Component {
    amplitude: f64,
    omega: f64,
    phase: f64,
    wavenumber: f64,
    inverse_sinh: f64,
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
    /// Acceleration (m/s^2).
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
            .map(|s| {
                let k = wavenumber(s.angular_frequency, depth);
                Component {
                    amplitude: s.amplitude,
                    omega: s.angular_frequency,
                    phase: s.phase,
                    wavenumber: k,
                    inverse_sinh: if deep(k, depth) {
                        0.0
                    } else {
                        1.0 / (k * depth).sinh()
                    },
                }
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
    /// Each component's phase is taken once for the elevation and the
    /// kinematics (kept in a per-thread buffer: evaluated at every node in
    /// every Newton iteration).
    pub fn at(&self, p: &Vector3<f64>, t: f64) -> Option<Kinematics> {
        let along = p.x * self.direction[0] + p.y * self.direction[1];
        PHASES.with_borrow_mut(|phases| {
            phases.clear();
            phases.extend(
                (self.components.iter())
                    .map(|c| (c.omega * t + c.phase - c.wavenumber * along).sin_cos()),
            );
            let full: f64 = (self.components.iter().zip(phases.iter()))
                .map(|(c, (sin, _))| c.amplitude * sin)
                .sum();
            let eta = crate::signal::sine::fade(self.fade_in, t)[0] * full;
            if p.z > eta {
                return None;
            }
            Some(self.kinematics_below(p.z, eta, t, phases))
        })
    }

    /// The kinematics at height `z` under the elevation `eta` at `t`, the
    /// components' phases' (sin, cos) given.
    fn kinematics_below(&self, z: f64, eta: f64, t: f64, phases: &[(f64, f64)]) -> Kinematics {
        let h = self.depth;
        let z = if h.is_finite() {
            (z - eta) * h / (h + eta)
        } else {
            z - eta
        };
        let (mut horizontal, mut vertical) = ([0.0; 2], [0.0; 2]);
        for (c, &(sin, cos)) in self.components.iter().zip(phases) {
            let (horizontal_shape, vertical_shape) = shapes(c, z, h);
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
        Kinematics {
            elevation: eta,
            velocity: velocity * r,
            acceleration: acceleration * r + velocity * rate,
        }
    }
}

/// Whether a component of wavenumber `k` (1/m) sees water of depth `h` (m)
/// as deep (its profile then `exp(k z)`).
fn deep(k: f64, h: f64) -> bool {
    !h.is_finite() || k * h > 20.0
}

/// cosh(k (z + h)) / sinh(k h) and sinh(k (z + h)) / sinh(k h) of component
/// `c`, both exp(k z) in deep water (z <= 0 below the still water line): one
/// exponential each (the kinematics are evaluated at every node in every
/// Newton iteration).
fn shapes(c: &Component, z: f64, h: f64) -> (f64, f64) {
    let k = c.wavenumber;
    if deep(k, h) {
        let e = (k * z).exp();
        return (e, e);
    }
    let e = (k * (z + h).max(0.0)).exp();
    let inverse = 1.0 / e;
    (
        0.5 * (e + inverse) * c.inverse_sinh,
        0.5 * (e - inverse) * c.inverse_sinh,
    )
}
