//! Start shapes of a static solve: the inextensible catenary through two
//! points, and the catenary that lies on a flat seabed from its lower end and
//! touches down tangentially (a riser or a mooring line with a laid part), so a
//! static solve from the `catenary` start begins above the seabed, near its
//! equilibrium, at any mesh.

/// A start shape: position (m) and tangent angle (rad, from +x) at arc
/// length `s` (m) from the start.
pub(super) trait Shape {
    fn at(&self, s: f64) -> ([f64; 2], f64);
}

/// An inextensible catenary of a given length between two points, or the straight
/// line when the chord is at least that long.
#[derive(Copy, Clone, Debug)]
pub(super) struct Catenary {
    start: [f64; 2],
    end: [f64; 2],
    length: f64,
    /// Catenary parameter a = H / w (m); infinite for the straight line.
    a: f64,
    /// Horizontal position of the vertex relative to the start, in the frame where
    /// x increases from start to end (m).
    x0: f64,
}

impl Catenary {
    /// The catenary through `start` and `end` of arc length `length` (m).
    pub(super) fn through(start: [f64; 2], end: [f64; 2], length: f64) -> Catenary {
        let (dx, dz) = ((end[0] - start[0]).abs(), end[1] - start[1]);
        let span = (length * length - dz * dz).max(0.0).sqrt();
        if dx < 1e-9 || span <= dx * (1.0 + 1e-12) {
            return Catenary {
                start,
                end,
                length,
                a: f64::INFINITY,
                x0: 0.0,
            };
        }
        // 2 a sinh(dx / 2a) = span is decreasing in a: bisection on ln a (bounded).
        let f = |a: f64| 2.0 * a * (dx / (2.0 * a)).sinh() - span;
        let (mut lo, mut hi) = ((dx * 1e-6).ln(), (dx * 1e9).ln());
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            let v = f(mid.exp());
            if !v.is_finite() || v > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let a = (0.5 * (lo + hi)).exp();
        let x0 = 0.5 * dx - a * (dz / (2.0 * a * (dx / (2.0 * a)).sinh())).asinh();
        Catenary {
            start,
            end,
            length,
            a,
            x0,
        }
    }

    /// The lowest height (m) of the shape.
    pub(super) fn lowest(&self) -> f64 {
        let ends = self.start[1].min(self.end[1]);
        if !self.a.is_finite() {
            return ends;
        }
        // The vertex, where it lies between the ends.
        let dx = (self.end[0] - self.start[0]).abs();
        if self.x0 > 0.0 && self.x0 < dx {
            ends.min(self.start[1] - self.a * ((-self.x0 / self.a).cosh() - 1.0))
        } else {
            ends
        }
    }
}

impl Shape for Catenary {
    fn at(&self, s: f64) -> ([f64; 2], f64) {
        let sign = if self.end[0] >= self.start[0] {
            1.0
        } else {
            -1.0
        };
        if !self.a.is_finite() {
            let (dx, dz) = (self.end[0] - self.start[0], self.end[1] - self.start[1]);
            let f = s / self.length;
            return (
                [self.start[0] + f * dx, self.start[1] + f * dz],
                dz.atan2(dx),
            );
        }
        let (a, x0) = (self.a, self.x0);
        let u = (s / a + (-x0 / a).sinh()).asinh();
        let x = x0 + a * u;
        let z = a * (u.cosh() - (-x0 / a).cosh());
        let angle = u.tanh().atan2(sign / u.cosh());
        ([self.start[0] + sign * x, self.start[1] + z], angle)
    }
}

/// A catenary with a laid part: from its lower end along a flat seabed at
/// height `seabed`, then lifting off tangentially (horizontal tension H = w a)
/// up to its upper end. With h the upper end's height above the seabed, the
/// suspended length is `s = sqrt(h^2 + 2 h a)` and its horizontal reach `x = a
/// asinh(s / a)`; `a` makes the laid length plus the reach the ends' distance.
#[derive(Copy, Clone, Debug)]
pub(super) struct GroundedCatenary {
    /// The lower end (on the seabed) and the direction (+1 or -1 in x) to the
    /// upper end.
    lower: [f64; 2],
    sign: f64,
    /// Whether the structure starts at the upper end (arc lengths reversed).
    from_upper: bool,
    length: f64,
    laid: f64,
    a: f64,
}

impl GroundedCatenary {
    /// The shape of `length` (m) between `start` and `end` on a seabed at
    /// height `seabed` (m), if one end lies on it (within `tolerance`, m)
    /// and the ends are far enough apart to lift the line off but not to
    /// pull it straight (0 < length - distance < height of the upper end).
    pub(super) fn through(
        start: [f64; 2],
        end: [f64; 2],
        length: f64,
        (seabed, tolerance): (f64, f64),
    ) -> Option<GroundedCatenary> {
        let from_upper = start[1] > end[1];
        let (lower, upper) = if from_upper {
            (end, start)
        } else {
            (start, end)
        };
        let h = upper[1] - seabed;
        let distance = (upper[0] - lower[0]).abs();
        let slack = length - distance;
        if (lower[1] - seabed).abs() > tolerance || h <= 0.0 || slack <= 0.0 || slack >= h {
            return None;
        }
        // s - x falls from h (a -> 0) to 0 (a -> infinity): bisection on ln a.
        let gap = |a: f64| {
            let s = (h * h + 2.0 * h * a).sqrt();
            s - a * (s / a).asinh() - slack
        };
        let (mut lo, mut hi) = ((h * 1e-9).ln(), (h * 1e9).ln());
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if gap(mid.exp()) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let a = (0.5 * (lo + hi)).exp();
        let suspended = (h * h + 2.0 * h * a).sqrt();
        Some(GroundedCatenary {
            lower: [lower[0], seabed],
            sign: if upper[0] >= lower[0] { 1.0 } else { -1.0 },
            from_upper,
            length,
            laid: (length - suspended).max(0.0),
            a,
        })
    }

    /// The laid length (m) from the lower end to the touchdown point.
    #[cfg(test)]
    pub(super) fn laid_length(&self) -> f64 {
        self.laid
    }
}

impl Shape for GroundedCatenary {
    fn at(&self, s: f64) -> ([f64; 2], f64) {
        let sigma = if self.from_upper { self.length - s } else { s };
        let (point, angle) = if sigma <= self.laid {
            let x = self.lower[0] + self.sign * sigma;
            (
                [x, self.lower[1]],
                if self.sign > 0.0 {
                    0.0
                } else {
                    std::f64::consts::PI
                },
            )
        } else {
            let (a, u) = (self.a, sigma - self.laid);
            let x = self.lower[0] + self.sign * (self.laid + a * (u / a).asinh());
            let z = self.lower[1] + (a * a + u * u).sqrt() - a;
            ([x, z], u.atan2(self.sign * a))
        };
        // Along the structure from its upper end, the tangent turns round.
        let angle = if self.from_upper {
            angle + std::f64::consts::PI
        } else {
            angle
        };
        (point, angle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grounded_catenary_spans_its_ends_and_leaves_the_seabed_tangentially() {
        // The riser of issue 26: 2000 m from an anchor at -1000 m to a top
        // at 0 m, 1356.43 m away: 765.10 m laid, a = 262.49 m, 12 deg at top.
        let (start, end) = ([0.0, -1000.0], [1356.4308733403304, 0.0]);
        for (a, b) in [(start, end), (end, start)] {
            let shape = GroundedCatenary::through(a, b, 2000.0, (-1000.0, 1e-6)).unwrap();
            assert!((shape.laid_length() - 765.1028434649488).abs() < 1e-6);
            let (p0, _) = shape.at(0.0);
            let (p1, angle) = shape.at(2000.0);
            assert!((p0[0] - a[0]).hypot(p0[1] - a[1]) < 1e-6, "{p0:?}");
            assert!((p1[0] - b[0]).hypot(p1[1] - b[1]) < 1e-6, "{p1:?}");
            // The tangent at the top: 12 deg from the vertical.
            let top = if b == end {
                angle
            } else {
                shape.at(0.0).1 - std::f64::consts::PI
            };
            assert!(
                (top.to_degrees() - 78.0).abs() < 1e-6,
                "{}",
                top.to_degrees()
            );
            // Arc length is arc length: the chord of small steps.
            let (mut previous, mut total) = (shape.at(0.0).0, 0.0);
            for k in 1..=20000 {
                let p = shape.at(2000.0 * k as f64 / 20000.0).0;
                total += (p[0] - previous[0]).hypot(p[1] - previous[1]);
                previous = p;
            }
            assert!((total - 2000.0).abs() < 1e-3, "{total}");
        }
        // Too slack to lift off, or pulled straight, or the lower end afloat.
        assert!(GroundedCatenary::through(start, [900.0, 0.0], 2000.0, (-1000.0, 1e-6)).is_none());
        assert!(GroundedCatenary::through(start, [1800.0, 0.0], 2000.0, (-1000.0, 1e-6)).is_some());
        assert!(GroundedCatenary::through([0.0, -990.0], end, 2000.0, (-1000.0, 1.0)).is_none());
    }

    #[test]
    fn a_free_catenary_knows_its_lowest_point() {
        let c = Catenary::through([0.0, 0.0], [100.0, 0.0], 150.0);
        let lowest = (0..=1000)
            .map(|k| c.at(0.15 * k as f64).0[1])
            .fold(f64::INFINITY, f64::min);
        assert!(
            (c.lowest() - lowest).abs() < 1e-3,
            "{} {lowest}",
            c.lowest()
        );
    }
}
