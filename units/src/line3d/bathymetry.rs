//! A seabed given by its depth on a rectangular grid (`seabed.bathymetry`),
//! bilinear in each cell: the surveyed seabed a mooring line or a riser lies
//! on. Outside the grid the edge values hold (a flat apron).

use crate::contract::{UnitError, require_finite};
use serde::{Deserialize, Serialize};

/// Depths (m, positive down) at the grid's nodes.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Bathymetry {
    /// The grid's x and y coordinates (m), each increasing, at least two.
    pub x: Vec<f64>,
    /// The grid's y coordinates (m), increasing, at least two.
    pub y: Vec<f64>,
    /// `depth[j][i]` at (x[i], y[j]) (m below z = 0): one row per y.
    pub depth: Vec<Vec<f64>>,
}

impl Bathymetry {
    /// Checks the grid's axes and rows, naming the key.
    pub fn validate(&self) -> Result<(), UnitError> {
        for (key, axis) in [("x", &self.x), ("y", &self.y)] {
            let key = format!("seabed.bathymetry.{key}");
            if axis.len() < 2 {
                return Err(UnitError::parameter(
                    &key,
                    axis.len(),
                    "at least two values",
                ));
            }
            for (i, v) in axis.iter().enumerate() {
                require_finite(&format!("{key}[{i}]"), *v)?;
                if i > 0 && *v <= axis[i - 1] {
                    return Err(UnitError::parameter(
                        &format!("{key}[{i}]"),
                        v,
                        "increasing values",
                    ));
                }
            }
        }
        if self.depth.len() != self.y.len() {
            return Err(UnitError::parameter(
                "seabed.bathymetry.depth",
                format!("{} rows", self.depth.len()),
                &format!("one row per y value ({})", self.y.len()),
            ));
        }
        for (j, row) in self.depth.iter().enumerate() {
            let key = format!("seabed.bathymetry.depth[{j}]");
            if row.len() != self.x.len() {
                return Err(UnitError::parameter(
                    &key,
                    format!("{} values", row.len()),
                    &format!("one value per x value ({})", self.x.len()),
                ));
            }
            for (i, d) in row.iter().enumerate() {
                require_finite(&format!("{key}[{i}]"), *d)?;
            }
        }
        Ok(())
    }

    /// The seabed's height z (m, up) at (x, y) and its slopes dz/dx, dz/dy:
    /// bilinear in the cell holding the point, the edge values held outside.
    pub fn at(&self, x: f64, y: f64) -> (f64, [f64; 2]) {
        let (i, fx, inside_x) = cell(&self.x, x);
        let (j, fy, inside_y) = cell(&self.y, y);
        let z = |a: usize, b: usize| -self.depth[b][a];
        let (z00, z10, z01, z11) = (z(i, j), z(i + 1, j), z(i, j + 1), z(i + 1, j + 1));
        let height = z00 * (1.0 - fx) * (1.0 - fy)
            + z10 * fx * (1.0 - fy)
            + z01 * (1.0 - fx) * fy
            + z11 * fx * fy;
        let (dx, dy) = (self.x[i + 1] - self.x[i], self.y[j + 1] - self.y[j]);
        let slope_x = ((z10 - z00) * (1.0 - fy) + (z11 - z01) * fy) / dx;
        let slope_y = ((z01 - z00) * (1.0 - fx) + (z11 - z10) * fx) / dy;
        (
            height,
            [
                if inside_x { slope_x } else { 0.0 },
                if inside_y { slope_y } else { 0.0 },
            ],
        )
    }
}

/// The cell of the increasing `axis` holding `v`: its index, the fraction
/// across it (clamped to [0, 1]) and whether `v` lies within the axis.
fn cell(axis: &[f64], v: f64) -> (usize, f64, bool) {
    let last = axis.len() - 1;
    let i = axis.partition_point(|&a| a <= v).clamp(1, last) - 1;
    let f = (v - axis[i]) / (axis[i + 1] - axis[i]);
    (i, f.clamp(0.0, 1.0), (0.0..=1.0).contains(&f))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> Bathymetry {
        Bathymetry {
            x: vec![0.0, 10.0, 30.0],
            y: vec![-5.0, 5.0],
            depth: vec![vec![100.0, 98.0, 104.0], vec![101.0, 99.0, 103.0]],
        }
    }

    #[test]
    fn the_grid_is_bilinear_in_each_cell_and_flat_beyond_its_edges() {
        let g = grid();
        // Nodes.
        assert_eq!(g.at(10.0, -5.0).0, -98.0);
        assert_eq!(g.at(30.0, 5.0).0, -103.0);
        // The middle of the first cell: the mean of its corners.
        let (z, [sx, sy]) = g.at(5.0, 0.0);
        assert!((z + 99.5).abs() < 1e-12);
        assert!(
            (sx - 0.2).abs() < 1e-12 && (sy + 0.1).abs() < 1e-12,
            "{sx} {sy}"
        );
        // Beyond the edges the edge values hold, without slope across them.
        let (z, [sx, _]) = g.at(50.0, 0.0);
        assert!((z + 103.5).abs() < 1e-12 && sx == 0.0);
        // Slopes are the height's differences (exact within a cell, where
        // the height is linear along each axis).
        let h = 1e-4;
        for (x, y) in [(3.0, 1.0), (17.0, -2.0)] {
            let (_, [sx, sy]) = g.at(x, y);
            let ddx = (g.at(x + h, y).0 - g.at(x - h, y).0) / (2.0 * h);
            let ddy = (g.at(x, y + h).0 - g.at(x, y - h).0) / (2.0 * h);
            assert!((sx - ddx).abs() < 1e-8 && (sy - ddy).abs() < 1e-8);
        }
    }

    #[test]
    fn a_malformed_grid_is_refused_by_key() {
        let mut g = grid();
        g.x[1] = -1.0;
        assert!(
            g.validate()
                .unwrap_err()
                .to_string()
                .contains("bathymetry.x[1]")
        );
        let mut g = grid();
        g.depth[1].pop();
        assert!(
            g.validate()
                .unwrap_err()
                .to_string()
                .contains("bathymetry.depth[1]")
        );
        let mut g = grid();
        g.depth.pop();
        assert!(
            g.validate()
                .unwrap_err()
                .to_string()
                .contains("one row per y")
        );
        assert!(grid().validate().is_ok());
    }
}
