//! The elastic catenary in its vertical plane (Irvine; MoorPy's `catenary`
//! without seabed friction): a line of unstretched length L, axial stiffness
//! EA and weight w per length from an anchor to a fairlead XF across and ZF
//! above it, hanging free or with its lower part lying on a flat seabed at the
//! anchor's level. It gives the 3D line its start shape and the closed form its
//! statics are checked against.

use crate::contract::UnitError;

/// A line's data for the catenary (SI units).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct CatenaryLine {
    /// Unstretched length (m), EA (N), weight in water per length (N/m, > 0).
    pub length: f64,
    /// EA (N).
    pub axial_stiffness: f64,
    /// Weight in water per length (N/m, > 0).
    pub weight: f64,
    /// Whether a seabed at the anchor's level carries the line.
    pub seabed: bool,
}

/// The solution: horizontal tension H and the fairlead's vertical force VF (N).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Catenary {
    /// The line solved.
    pub line: CatenaryLine,
    /// Horizontal tension H (N).
    pub horizontal: f64,
    /// The fairlead's vertical force VF (N).
    pub vertical: f64,
}

impl CatenaryLine {
    /// (XF, ZF) of the fairlead for tensions (H, VF).
    fn span(&self, h: f64, vf: f64) -> [f64; 2] {
        let c = Catenary {
            line: *self,
            horizontal: h,
            vertical: vf,
        };
        c.point(self.length)
    }

    /// Solves for (H, VF) given the fairlead's offset (XF > 0 across, ZF
    /// above), by Newton on both from the classic estimate (bounded: 100
    /// iterations, halving a step that leaves H > 0).
    pub fn solve(&self, xf: f64, zf: f64) -> Result<Catenary, UnitError> {
        let (l, w) = (self.length, self.weight);
        if let Some(slack) = self.slack(xf, zf) {
            return Ok(slack);
        }
        let chord = (xf * xf + zf * zf).sqrt();
        let lambda = if l <= chord {
            0.2
        } else {
            (3.0 * ((l * l - zf * zf) / (xf * xf) - 1.0)).sqrt()
        };
        let mut x = [
            (w * xf / (2.0 * lambda)).abs().max(1e-3 * w * l),
            0.5 * w * (zf / lambda.tanh() + l),
        ];
        for _ in 0..100 {
            let r = self.residual(x, xf, zf);
            let scale = xf.abs().max(zf.abs()).max(1.0);
            if r[0].abs().max(r[1].abs()) < 1e-12 * scale {
                return Ok(Catenary {
                    line: *self,
                    horizontal: x[0],
                    vertical: x[1],
                });
            }
            let jac = self.jacobian(x, xf, zf);
            let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
            let dh = -(jac[1][1] * r[0] - jac[0][1] * r[1]) / det;
            let dv = -(-jac[1][0] * r[0] + jac[0][0] * r[1]) / det;
            let mut step = 1.0;
            while x[0] + step * dh <= 0.0 && step > 1e-6 {
                step *= 0.5;
            }
            x = [x[0] + step * dh, x[1] + step * dv];
        }
        Err(UnitError::Numerical(format!(
            "elastic catenary: no solution found for a fairlead {xf} m across and {zf} m above the anchor (length {l} m)"
        )))
    }

    /// With a seabed, a line long enough to lie along the whole span and
    /// hang straight up to the fairlead: no horizontal tension, the hanging
    /// part's weight at the top (its elastic stretch counted). None when
    /// the line is taut enough to need the catenary.
    fn slack(&self, xf: f64, zf: f64) -> Option<Catenary> {
        if !self.seabed || zf <= 0.0 {
            return None;
        }
        let (w, ea) = (self.weight, self.axial_stiffness);
        // zf = L_h + w L_h^2 / (2 EA), for the hanging length L_h.
        let hanging = 2.0 * zf / (1.0 + (1.0 + 2.0 * w * zf / ea).sqrt());
        (self.length - hanging >= xf).then_some(Catenary {
            line: *self,
            horizontal: 0.0,
            vertical: w * hanging,
        })
    }

    fn residual(&self, x: [f64; 2], xf: f64, zf: f64) -> [f64; 2] {
        let [sx, sz] = self.span(x[0], x[1]);
        [sx - xf, sz - zf]
    }

    /// Central differences of the residual (relative steps).
    fn jacobian(&self, x: [f64; 2], xf: f64, zf: f64) -> [[f64; 2]; 2] {
        let mut jac = [[0.0; 2]; 2];
        for k in 0..2 {
            let d = 1e-6 * x[k].abs().max(1e-3 * self.weight * self.length);
            let (mut plus, mut minus) = (x, x);
            plus[k] += d;
            minus[k] -= d;
            let (rp, rm) = (self.residual(plus, xf, zf), self.residual(minus, xf, zf));
            for r in 0..2 {
                jac[r][k] = (rp[r] - rm[r]) / (2.0 * d);
            }
        }
        jac
    }
}

impl Catenary {
    /// Length lying on the seabed (m).
    pub fn laid_length(&self) -> f64 {
        let l = self.line;
        if l.seabed && self.vertical < l.weight * l.length {
            l.length - self.vertical / l.weight
        } else {
            0.0
        }
    }

    /// The point at unstretched arc `s` from the anchor (m across, m above).
    pub fn point(&self, s: f64) -> [f64; 2] {
        let l = self.line;
        let (h, w, ea) = (self.horizontal, l.weight, l.axial_stiffness);
        let laid = self.laid_length();
        if h <= 0.0 && laid > 0.0 {
            // Slack: lying (straight, so a span shorter than the laid
            // length is overshot), then hanging straight up.
            if s <= laid {
                return [s, 0.0];
            }
            let hanging = s - laid;
            return [laid, hanging + w * hanging * hanging / (2.0 * ea)];
        }
        if laid > 0.0 {
            if s <= laid {
                return [s * (1.0 + h / ea), 0.0];
            }
            let v = w * (s - laid);
            return [
                laid + h / w * (v / h).asinh() + h * s / ea,
                h / w * ((1.0 + (v / h).powi(2)).sqrt() - 1.0) + v * v / (2.0 * ea * w),
            ];
        }
        let va = self.vertical - w * l.length;
        let v = va + w * s;
        [
            h / w * ((v / h).asinh() - (va / h).asinh()) + h * s / ea,
            h / w * ((1.0 + (v / h).powi(2)).sqrt() - (1.0 + (va / h).powi(2)).sqrt())
                + (va * s + 0.5 * w * s * s) / ea,
        ]
    }

    /// Effective tension (N) at arc `s`.
    pub fn tension(&self, s: f64) -> f64 {
        let l = self.line;
        let v = if self.laid_length() > 0.0 {
            (l.weight * (s - self.laid_length())).max(0.0)
        } else {
            self.vertical - l.weight * (l.length - s)
        };
        self.horizontal.hypot(v)
    }
}
