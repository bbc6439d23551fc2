//! Morison drag on each element from the water velocity relative to the element,
//! split between its two nodes. Element directions are those of the static state
//! (the dynamics is linear about it); the drag itself is the full quadratic law.

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
        Drag {
            normal: 0.5 * rho * diameter * cd_normal * element_length,
            tangential: 0.5
                * rho
                * std::f64::consts::PI
                * diameter
                * cd_tangential
                * element_length,
            directions,
            current,
        }
    }

    /// Adds the nodal drag forces (N) for node velocities `v` (m/s, one per node)
    /// into `forces`.
    pub fn add_forces(&self, v: &[[f64; 2]], forces: &mut [[f64; 2]]) {
        for (e, dir) in self.directions.iter().enumerate() {
            let u = [
                self.current[e] - 0.5 * (v[e][0] + v[e + 1][0]),
                -0.5 * (v[e][1] + v[e + 1][1]),
            ];
            let ut = u[0] * dir[0] + u[1] * dir[1];
            let un = [u[0] - ut * dir[0], u[1] - ut * dir[1]];
            let un_norm = (un[0] * un[0] + un[1] * un[1]).sqrt();
            let fx = self.normal * un_norm * un[0] + self.tangential * ut.abs() * ut * dir[0];
            let fz = self.normal * un_norm * un[1] + self.tangential * ut.abs() * ut * dir[1];
            for node in [e, e + 1] {
                forces[node][0] += 0.5 * fx;
                forces[node][1] += 0.5 * fz;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
