//! Morison drag on each element from the water velocity relative to the element,
//! split between its two nodes. Element directions are those of the static state
//! (the dynamics is linear about it); the drag itself is the full quadratic law.
//!
//! For time stepping the drag is split into its linearisation about the cable at
//! rest in the current, a damping matrix `B` the integrator factorises once, and a
//! remainder `f(v) - f(0) + B v` it iterates on.

/// Drag per unit length: 1/2 rho D Cd_n |u_n| u_n normal, 1/2 rho pi D Cd_t |u_t| u_t
/// along the element, on the relative velocity u = current - structure.
#[derive(Clone, Debug)]
pub struct Drag {
    /// 1/2 rho D Cd_n L0 (N s^2/m^2 per element).
    normal: f64,
    /// 1/2 rho pi D Cd_t L0.
    tangential: f64,
    /// Static element directions.
    directions: Vec<[f64; 2]>,
    /// Current velocity (x) at each element's mid-height.
    current: Vec<f64>,
    /// Per element: drag at rest and its linearisation -df/dv_e (for the element's
    /// mean velocity v_e).
    at_rest: Vec<[f64; 2]>,
    linear: Vec<[[f64; 2]; 2]>,
}

impl Drag {
    /// Drag for elements with static `directions` and mid-height current speeds.
    pub fn new(
        rho: f64,
        diameter: f64,
        cd_normal: f64,
        cd_tangential: f64,
        element_length: f64,
        directions: Vec<[f64; 2]>,
        current: Vec<f64>,
    ) -> Drag {
        let normal = 0.5 * rho * diameter * cd_normal * element_length;
        let tangential =
            0.5 * rho * std::f64::consts::PI * diameter * cd_tangential * element_length;
        let mut drag = Drag {
            normal,
            tangential,
            at_rest: Vec::with_capacity(directions.len()),
            linear: Vec::with_capacity(directions.len()),
            directions,
            current,
        };
        for e in 0..drag.directions.len() {
            let f = drag.element_force(e, [0.0, 0.0]);
            drag.at_rest.push(f);
            // d(|s| s)/ds = 2 |s| along each of the normal and tangential directions.
            let dir = drag.directions[e];
            let ut = drag.current[e] * dir[0];
            let un = [drag.current[e] - ut * dir[0], -ut * dir[1]];
            let un_norm = (un[0] * un[0] + un[1] * un[1]).sqrt();
            let nrm = [-dir[1], dir[0]];
            let mut b = [[0.0; 2]; 2];
            for (r, row) in b.iter_mut().enumerate() {
                for (c, v) in row.iter_mut().enumerate() {
                    *v = 2.0 * normal * un_norm * nrm[r] * nrm[c]
                        + 2.0 * tangential * ut.abs() * dir[r] * dir[c];
                }
            }
            drag.linear.push(b);
        }
        drag
    }

    /// Drag force (N) on element e moving with mean velocity `v`.
    fn element_force(&self, e: usize, v: [f64; 2]) -> [f64; 2] {
        let dir = self.directions[e];
        let u = [self.current[e] - v[0], -v[1]];
        let ut = u[0] * dir[0] + u[1] * dir[1];
        let un = [u[0] - ut * dir[0], u[1] - ut * dir[1]];
        let un_norm = (un[0] * un[0] + un[1] * un[1]).sqrt();
        [
            self.normal * un_norm * un[0] + self.tangential * ut.abs() * ut * dir[0],
            self.normal * un_norm * un[1] + self.tangential * ut.abs() * ut * dir[1],
        ]
    }

    /// d r_e / d v_e of element `e`'s remainder at its mean velocity `v`:
    /// `B_e - D(v)`, D the drag's own derivative with respect to the relative
    /// velocity (2 c |s| n n^T along each of the normal and tangential
    /// directions).
    pub fn remainder_tangent(&self, e: usize, v: [f64; 2]) -> [[f64; 2]; 2] {
        let dir = self.directions[e];
        let nrm = [-dir[1], dir[0]];
        let u = [self.current[e] - v[0], -v[1]];
        let s = (u[0] * nrm[0] + u[1] * nrm[1]).abs();
        let t = (u[0] * dir[0] + u[1] * dir[1]).abs();
        let b = &self.linear[e];
        std::array::from_fn(|r| {
            std::array::from_fn(|c| {
                b[r][c]
                    - 2.0 * self.normal * s * nrm[r] * nrm[c]
                    - 2.0 * self.tangential * t * dir[r] * dir[c]
            })
        })
    }

    /// The linearised drag as a nodal damping matrix (N s/m) for a chain of nodes:
    /// each element's `B` acts on its mean velocity and splits half to each node.
    #[allow(clippy::needless_range_loop)] // (r, c) index the block and the DOFs alike
    pub fn damping(&self) -> crate::numerics::banded::SymmetricBand {
        let nodes = self.directions.len() + 1;
        let mut m = crate::numerics::banded::SymmetricBand::zeros(2 * nodes, super::elements::BAND);
        for (e, b) in self.linear.iter().enumerate() {
            for r in 0..2 {
                for c in 0..2 {
                    let v = 0.25 * b[r][c];
                    let (a0, a1) = (2 * e + r, 2 * (e + 1) + r);
                    let (b0, b1) = (2 * e + c, 2 * (e + 1) + c);
                    if a0 >= b0 {
                        m.add(a0, b0, v);
                        m.add(a1, b1, v);
                    }
                    m.add(a1, b0, v);
                }
            }
        }
        m
    }

    /// Adds the remainder `f(v) - f(0) + B v` of every element, split between its
    /// nodes, into `forces` (node velocities `v`, m/s).
    pub fn add_remainder(&self, v: &[[f64; 2]], forces: &mut [[f64; 2]]) {
        for e in 0..self.directions.len() {
            let ve = [0.5 * (v[e][0] + v[e + 1][0]), 0.5 * (v[e][1] + v[e + 1][1])];
            let f = self.element_force(e, ve);
            let b = &self.linear[e];
            let r = [
                f[0] - self.at_rest[e][0] + b[0][0] * ve[0] + b[0][1] * ve[1],
                f[1] - self.at_rest[e][1] + b[1][0] * ve[0] + b[1][1] * ve[1],
            ];
            for node in [e, e + 1] {
                forces[node][0] += 0.5 * r[0];
                forces[node][1] += 0.5 * r[1];
            }
        }
    }

    /// Adds the nodal drag forces (N) for node velocities `v` (m/s, one per node)
    /// into `forces`.
    pub fn add_forces(&self, v: &[[f64; 2]], forces: &mut [[f64; 2]]) {
        for e in 0..self.directions.len() {
            let ve = [0.5 * (v[e][0] + v[e + 1][0]), 0.5 * (v[e][1] + v[e + 1][1])];
            let f = self.element_force(e, ve);
            for node in [e, e + 1] {
                forces[node][0] += 0.5 * f[0];
                forces[node][1] += 0.5 * f[1];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_remainder_is_second_order_small_near_rest() {
        let d = Drag::new(
            1000.0,
            0.2,
            1.2,
            0.3,
            10.0,
            vec![[0.6, 0.8], [0.0, 1.0]],
            vec![0.7, 0.4],
        );
        let remainder = |eps: f64| {
            let v = [[0.0; 2], [0.3 * eps, -0.2 * eps], [0.1 * eps, 0.2 * eps]];
            let mut f = vec![[0.0; 2]; 3];
            d.add_remainder(&v, &mut f);
            f.iter().map(|x| x[0].abs() + x[1].abs()).sum::<f64>()
        };
        let ratio = remainder(1e-3) / remainder(2e-3);
        assert!(
            (ratio - 0.25).abs() < 0.01,
            "remainder not quadratic: ratio {ratio}"
        );
    }

    #[test]
    fn a_vertical_element_in_a_current_feels_the_normal_drag_only() {
        let d = Drag::new(1000.0, 0.2, 1.0, 0.0, 10.0, vec![[0.0, 1.0]], vec![2.0]);
        let mut f = vec![[0.0; 2]; 2];
        d.add_forces(&[[0.0; 2], [0.0; 2]], &mut f);
        // 1/2 * 1000 * 0.2 * 1 * 10 * 2 * 2 = 4000 N, half per node.
        assert!((f[0][0] - 2000.0).abs() < 1e-9 && (f[1][0] - 2000.0).abs() < 1e-9);
        assert_eq!(f[0][1], 0.0);
        // Moving with the water: no drag.
        let mut f = vec![[0.0; 2]; 2];
        d.add_forces(&[[2.0, 0.0], [2.0, 0.0]], &mut f);
        assert_eq!(f[0][0], 0.0);
    }
}
