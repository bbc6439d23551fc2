//! Orthonormal polynomial families of the standard input variables: Legendre
//! for a uniform input mapped to [-1, 1], Hermite (probabilists') for a
//! standard normal one. Orthonormal under the variable's density, so a
//! chaos expansion's coefficients give its moments and Sobol' indices directly.

use serde::Deserialize;

/// A polynomial family, by the distribution of its standard variable.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Family {
    /// Uniform on [-1, 1]: sqrt(2n + 1) P_n.
    Legendre,
    /// Standard normal: He_n / sqrt(n!).
    Hermite,
}

impl Family {
    /// The orthonormal polynomials of degrees 0..=`degree` at `xi`, into `out`.
    pub fn eval_into(self, degree: usize, xi: f64, out: &mut Vec<f64>) {
        out.clear();
        out.push(1.0);
        if degree == 0 {
            return;
        }
        out.push(xi);
        // Plain recurrences first, normalised after.
        for n in 1..degree {
            let nf = n as f64;
            let next = match self {
                Family::Legendre => ((2.0 * nf + 1.0) * xi * out[n] - nf * out[n - 1]) / (nf + 1.0),
                Family::Hermite => xi * out[n] - nf * out[n - 1],
            };
            out.push(next);
        }
        let mut factorial = 1.0;
        for (n, v) in out.iter_mut().enumerate() {
            match self {
                Family::Legendre => *v *= (2.0 * n as f64 + 1.0).sqrt(),
                Family::Hermite => {
                    if n > 0 {
                        factorial *= n as f64;
                    }
                    *v /= factorial.sqrt();
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Gauss-Legendre by the trapezoid on a fine grid is enough for a check.
    #[test]
    fn the_families_are_orthonormal_under_their_densities() {
        let (mut a, mut b) = (Vec::new(), Vec::new());
        // Legendre: density 1/2 on [-1, 1].
        let n = 200_000;
        let mut gram = [[0.0; 6]; 6];
        for k in 0..=n {
            let x = -1.0 + 2.0 * k as f64 / n as f64;
            let w = if k == 0 || k == n { 0.5 } else { 1.0 } * (2.0 / n as f64) * 0.5;
            Family::Legendre.eval_into(5, x, &mut a);
            for i in 0..6 {
                for j in 0..6 {
                    gram[i][j] += w * a[i] * a[j];
                }
            }
        }
        // Hermite: standard normal density on [-12, 12].
        let mut hgram = [[0.0; 6]; 6];
        for k in 0..=n {
            let x = -12.0 + 24.0 * k as f64 / n as f64;
            let w =
                if k == 0 || k == n { 0.5 } else { 1.0 } * (24.0 / n as f64) * (-0.5 * x * x).exp()
                    / (2.0 * std::f64::consts::PI).sqrt();
            Family::Hermite.eval_into(5, x, &mut b);
            for i in 0..6 {
                for j in 0..6 {
                    hgram[i][j] += w * b[i] * b[j];
                }
            }
        }
        for i in 0..6 {
            for j in 0..6 {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!(
                    (gram[i][j] - want).abs() < 1e-6,
                    "Legendre {i} {j}: {}",
                    gram[i][j]
                );
                assert!(
                    (hgram[i][j] - want).abs() < 1e-6,
                    "Hermite {i} {j}: {}",
                    hgram[i][j]
                );
            }
        }
    }
}
