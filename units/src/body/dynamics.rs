//! The rigid body's equations of motion about its reference point, global
//! axes: `M(R) du/dt = Q(pose, u, t) - gyro(R, u)` with `u` the reference
//! point's velocity and the angular velocity.
//!
//! The rigid mass is Newton-Euler's at the centre of gravity moved to the
//! reference point (`S^T M_cg S`, exact for any rotation); the added mass is
//! constant about the reference point in global axes. The weight acts at the
//! centre of gravity as it turns (exact), the buoyancy `rho g V` upward at the
//! reference point; the linear hydrostatic and additional restoring act on
//! the displacement from rest `eta` (translations and the roll, pitch and yaw
//! angles, z-y'-x''), as the potential `eta^T C eta / 2`: the moment is
//! `E^-T Q_angles`, with `E` the map from the angles' rates to the angular
//! velocity, so the restoring does no net work over a closed path.

use super::params::BodyParams;
use crate::contract::UnitError;
use nalgebra::{Matrix3, Matrix6, UnitQuaternion, Vector3, Vector6};

/// The body's pose and velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Motion {
    /// The reference point's position (m), global.
    pub position: Vector3<f64>,
    /// The body's rotation from its frame to the global one.
    pub rotation: UnitQuaternion<f64>,
    /// The reference point's velocity (m/s) and the angular velocity
    /// (rad/s), global axes.
    pub velocity: Vector6<f64>,
}

/// The body's constant data, in nalgebra's types.
#[derive(Clone, Debug)]
pub(crate) struct Model {
    mass: f64,
    /// About the centre of gravity, body axes (kg m^2).
    inertia: Matrix3<f64>,
    /// The centre of gravity in the body's frame (m).
    cg: Vector3<f64>,
    weight: f64,
    buoyancy: f64,
    /// Hydrostatic plus additional restoring.
    pub stiffness: Matrix6<f64>,
    added_mass: Matrix6<f64>,
    damping_linear: Matrix6<f64>,
    damping_quadratic: Matrix6<f64>,
    mean_force: Vector6<f64>,
    /// The reference point at rest (m).
    pub reference: Vector3<f64>,
    /// The fairleads in the body's frame (m).
    pub fairleads: Vec<Vector3<f64>>,
}

/// The inertia tensor about the centre of gravity in the body's axes.
pub(crate) fn inertia_tensor(p: &BodyParams) -> Matrix3<f64> {
    let [ixx, iyy, izz] = p.inertia;
    let [ixy, ixz, iyz] = p.inertia_products;
    Matrix3::new(ixx, -ixy, -ixz, -ixy, iyy, -iyz, -ixz, -iyz, izz)
}

fn matrix6(rows: &[[f64; 6]; 6]) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| rows[i][j])
}

/// The cross-product matrix of `v` (`skew(v) w = v x w`).
pub(crate) fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// Roll, pitch and yaw (rad) of a rotation (z-y'-x'': R = Rz Ry Rx).
pub(crate) fn angles(rotation: &UnitQuaternion<f64>) -> Vector3<f64> {
    let (roll, pitch, yaw) = rotation.euler_angles();
    Vector3::new(roll, pitch, yaw)
}

/// The map `E` from the angles' rates to the angular velocity (global axes)
/// at pitch `theta` and yaw `psi`.
pub(crate) fn rate_map(theta: f64, psi: f64) -> Matrix3<f64> {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = psi.sin_cos();
    Matrix3::new(cp * ct, -sp, 0.0, sp * ct, cp, 0.0, -st, 0.0, 1.0)
}

/// The time derivative of [`rate_map`] at angle rates `rates`.
pub(crate) fn rate_map_derivative(theta: f64, psi: f64, rates: &Vector3<f64>) -> Matrix3<f64> {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = psi.sin_cos();
    let by_theta = Matrix3::new(-cp * st, 0.0, 0.0, -sp * st, 0.0, 0.0, -ct, 0.0, 0.0);
    let by_psi = Matrix3::new(-sp * ct, -cp, 0.0, cp * ct, -sp, 0.0, 0.0, 0.0, 0.0);
    by_theta * rates.y + by_psi * rates.z
}

impl Model {
    /// The model of checked parameters `p`.
    pub(crate) fn new(p: &BodyParams) -> Model {
        let add = |a: &[[f64; 6]; 6], b: &[[f64; 6]; 6]| matrix6(a) + matrix6(b);
        Model {
            mass: p.mass,
            inertia: inertia_tensor(p),
            cg: Vector3::from(p.centre_of_gravity),
            weight: p.mass * p.gravity,
            buoyancy: p.water_density * p.gravity * p.displaced_volume,
            stiffness: add(&p.hydrostatic_stiffness, &p.additional_stiffness),
            added_mass: matrix6(&p.added_mass),
            damping_linear: matrix6(&p.damping_linear),
            damping_quadratic: matrix6(&p.damping_quadratic),
            mean_force: Vector6::from(p.mean_force),
            reference: Vector3::from(p.reference),
            fairleads: p
                .fairleads
                .iter()
                .map(|f| Vector3::from(f.position))
                .collect(),
        }
    }

    /// The displacement from rest: translations (m) and roll, pitch, yaw (rad).
    pub(crate) fn displacement(&self, m: &Motion) -> Vector6<f64> {
        let mut eta = Vector6::zeros();
        eta.fixed_rows_mut::<3>(0)
            .copy_from(&(m.position - self.reference));
        eta.fixed_rows_mut::<3>(3).copy_from(&angles(&m.rotation));
        eta
    }

    /// The mass matrix about the reference point (rigid and added).
    pub(crate) fn mass_matrix(&self, rotation: &UnitQuaternion<f64>) -> Matrix6<f64> {
        let r = rotation.to_rotation_matrix();
        let c = r * self.cg;
        let inertia = r.matrix() * self.inertia * r.matrix().transpose();
        let sc = skew(&c);
        let mut m = Matrix6::zeros();
        m.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&(Matrix3::identity() * self.mass));
        m.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-self.mass * sc));
        m.fixed_view_mut::<3, 3>(3, 0).copy_from(&(self.mass * sc));
        m.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(inertia - self.mass * sc * sc));
        m + self.added_mass
    }

    /// The loads at the reference point (N, N m) but the inertial ones: the
    /// conservative ones ([`Model::restoring`]) and those that do work
    /// ([`Model::applied`]).
    pub(crate) fn loads(
        &self,
        m: &Motion,
        forces: &[f64],
        external: &Vector6<f64>,
    ) -> Result<Vector6<f64>, UnitError> {
        Ok(self.restoring(m)? + self.applied(m, forces, external))
    }

    /// The weight at the centre of gravity, the buoyancy and the linear
    /// restoring (N, N m): the loads of the potential energy.
    fn restoring(&self, m: &Motion) -> Result<Vector6<f64>, UnitError> {
        let r = m.rotation.to_rotation_matrix();
        let mut q = Vector6::zeros();
        add_point_load(
            &mut q,
            &(r * self.cg),
            &Vector3::new(0.0, 0.0, -self.weight),
        );
        q[2] += self.buoyancy;
        let eta = self.displacement(m);
        let restoring = -self.stiffness * eta;
        for i in 0..3 {
            q[i] += restoring[i];
        }
        let map = rate_map(eta[4], eta[5]);
        let inverse = map.transpose().try_inverse().ok_or_else(|| {
            UnitError::Numerical(format!(
                "the body pitched to {:.3} rad: the roll-pitch-yaw angles its restoring acts on are singular at 90 degrees",
                eta[4]
            ))
        })?;
        let moment = inverse * restoring.fixed_rows::<3>(3);
        for i in 0..3 {
            q[3 + i] += moment[i];
        }
        Ok(q)
    }

    /// The fairleads' `forces` (x, y, z each, global), the `external` load,
    /// the mean load and the damping (N, N m): the loads that do work.
    pub(crate) fn applied(
        &self,
        m: &Motion,
        forces: &[f64],
        external: &Vector6<f64>,
    ) -> Vector6<f64> {
        let q = self.mean_force + external + self.fairlead_loads(m, forces);
        let u = &m.velocity;
        let quadratic = u.map(|x| x.abs() * x);
        q - self.damping_linear * u - self.damping_quadratic * quadratic
    }

    /// The fairleads' `forces` (x, y, z each, global) as a load at the
    /// reference point (N, N m).
    pub(crate) fn fairlead_loads(&self, m: &Motion, forces: &[f64]) -> Vector6<f64> {
        let r = m.rotation.to_rotation_matrix();
        let mut q = Vector6::zeros();
        for (k, p) in self.fairleads.iter().enumerate() {
            let f = Vector3::new(forces[3 * k], forces[3 * k + 1], forces[3 * k + 2]);
            add_point_load(&mut q, &(r * p), &f);
        }
        q
    }

    /// The velocity-dependent inertial loads: the centripetal force of an
    /// off-centre mass and the gyroscopic moment, at the reference point.
    fn gyroscopic(&self, m: &Motion) -> Vector6<f64> {
        let r = m.rotation.to_rotation_matrix();
        let c = r * self.cg;
        let w = Vector3::new(m.velocity[3], m.velocity[4], m.velocity[5]);
        let inertia = r.matrix() * self.inertia * r.matrix().transpose();
        let centripetal = self.mass * w.cross(&w.cross(&c));
        let moment = c.cross(&centripetal) + w.cross(&(inertia * w));
        let mut g = Vector6::zeros();
        g.fixed_rows_mut::<3>(0).copy_from(&centripetal);
        g.fixed_rows_mut::<3>(3).copy_from(&moment);
        g
    }

    /// The acceleration (m/s^2, rad/s^2) under the fairleads' `forces` and
    /// the `external` load.
    pub(crate) fn acceleration(
        &self,
        m: &Motion,
        forces: &[f64],
        external: &Vector6<f64>,
    ) -> Result<Vector6<f64>, UnitError> {
        let rhs = self.loads(m, forces, external)? - self.gyroscopic(m);
        self.mass_matrix(&m.rotation)
            .lu()
            .solve(&rhs)
            .ok_or_else(|| UnitError::Numerical("the body's mass matrix is singular".into()))
    }

    /// Kinetic energy (rigid and added mass) and the potential energy of
    /// the weight, buoyancy and restoring (J), zero at rest.
    pub(crate) fn energies(&self, m: &Motion) -> [f64; 2] {
        let u = &m.velocity;
        let kinetic = 0.5 * u.dot(&(self.mass_matrix(&m.rotation) * u));
        let eta = self.displacement(m);
        let r = m.rotation.to_rotation_matrix();
        let lift = (m.position + r * self.cg).z - (self.reference + self.cg).z;
        let potential = 0.5 * eta.dot(&(self.stiffness * eta)) + self.weight * lift
            - self.buoyancy * (m.position.z - self.reference.z);
        [kinetic, potential]
    }

    /// Position, velocity and acceleration (global) of the point at `p` in
    /// the body's frame, for the body's motion `m` and acceleration `a`.
    pub(crate) fn point(
        &self,
        m: &Motion,
        a: &Vector6<f64>,
        p: &Vector3<f64>,
    ) -> [Vector3<f64>; 3] {
        let arm = m.rotation * p;
        let w = Vector3::new(m.velocity[3], m.velocity[4], m.velocity[5]);
        let alpha = Vector3::new(a[3], a[4], a[5]);
        let v = Vector3::new(m.velocity[0], m.velocity[1], m.velocity[2]);
        let acc = Vector3::new(a[0], a[1], a[2]);
        [
            m.position + arm,
            v + w.cross(&arm),
            acc + alpha.cross(&arm) + w.cross(&w.cross(&arm)),
        ]
    }
}

/// Adds the force `f` (N) applied at `arm` (m) from the reference point to
/// the load `q`.
fn add_point_load(q: &mut Vector6<f64>, arm: &Vector3<f64>, f: &Vector3<f64>) {
    let moment = arm.cross(f);
    for i in 0..3 {
        q[i] += f[i];
        q[3 + i] += moment[i];
    }
}
