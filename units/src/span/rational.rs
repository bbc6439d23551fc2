//! Rational approximations of H_{U2 -> U5} (seed 004 sec. 5.2) in the variable
//! x = (beta L)^4 = -L^4 s (c_d + mu s) / EI, so that an approximation of degree N/2
//! in x is of order N in s:
//!
//! - Taylor: sin, sinh truncated at xi^(N-1), cos, cosh at xi^N (xi = beta L),
//!   combined (eq. 5.11);
//! - term Pade: [N/2 / N/2] Pade approximants of sin, sinh, cos, cosh in xi,
//!   combined (eqs. 5.13-5.14);
//! - function Pade: a [N/2 / N/2] Pade
//!   approximant in x of f(x) = (sin xi + sinh xi) / (xi (cos xi cosh xi + 1))
//!   (eq. 5.15).
//!
//! In each, H ~ L num(x) / den(x); polynomials have ascending coefficients.

use super::transfer::{C64, Span};
use crate::contract::UnitError;

/// H ~ L num(x) / den(x) with x = (beta L)^4; `den` is monic (highest coefficient 1).
#[derive(Clone, Debug, PartialEq)]
pub struct RationalX {
    /// Numerator coefficients, lowest power first.
    pub num: Vec<f64>,
    /// Denominator coefficients, lowest power first (monic).
    pub den: Vec<f64>,
}

impl RationalX {
    /// The approximation at s for `span`.
    pub fn eval(&self, span: &Span, s: C64) -> C64 {
        let x = span.beta4(s) * span.length.powi(4);
        let p = |c: &[f64]| {
            c.iter()
                .rev()
                .fold(C64::new(0.0, 0.0), |acc, &k| acc * x + k)
        };
        span.length * p(&self.num) / p(&self.den)
    }
}

type Q = num_rational::BigRational;

fn q(n: i64) -> Q {
    Q::from_integer(n.into())
}

fn factorial(n: usize) -> Q {
    (1..=n as i64).fold(q(1), |acc, k| acc * q(k))
}

fn to_f64(x: &Q) -> f64 {
    num_traits::ToPrimitive::to_f64(x).unwrap_or(f64::NAN)
}

/// Taylor coefficients (ascending in xi) of sin, sinh, cos, cosh up to degree `n`,
/// exact.
fn series(kind: &str, n: usize) -> Vec<Q> {
    (0..=n)
        .map(|k| {
            let f = q(1) / factorial(k);
            match (kind, k % 4) {
                ("sin", 1) | ("sinh", 1) | ("sinh", 3) | ("cos", 0) | ("cosh", 0) | ("cosh", 2) => {
                    f
                }
                ("sin", 3) | ("cos", 2) => -f,
                _ => q(0),
            }
        })
        .collect()
}

fn multiply(a: &[Q], b: &[Q]) -> Vec<Q> {
    let mut out = vec![q(0); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

fn add(a: &[Q], b: &[Q]) -> Vec<Q> {
    (0..a.len().max(b.len()))
        .map(|i| {
            a.get(i).cloned().unwrap_or_else(|| q(0)) + b.get(i).cloned().unwrap_or_else(|| q(0))
        })
        .collect()
}

/// A polynomial in xi whose powers, after dividing by xi^shift, are multiples of 4,
/// as a polynomial in x = xi^4 (exact: the other powers must vanish).
fn to_x(p: &[Q], shift: usize) -> Result<Vec<Q>, UnitError> {
    let zero = q(0);
    let mut out = Vec::new();
    for (k, c) in p.iter().enumerate() {
        if k < shift {
            if *c != zero {
                return Err(UnitError::Numerical(
                    "the polynomial is not divisible by xi".into(),
                ));
            }
            continue;
        }
        if (k - shift) % 4 == 0 {
            out.push(c.clone());
        } else if *c != zero {
            return Err(UnitError::Numerical(format!(
                "power xi^{} does not cancel",
                k - shift
            )));
        }
    }
    while out.len() > 1 && out.last() == Some(&zero) {
        out.pop();
    }
    Ok(out)
}

fn check_order(order: usize) -> Result<(), UnitError> {
    if order >= 2 && order % 2 == 0 && order <= 24 {
        Ok(())
    } else {
        Err(UnitError::parameter(
            "order",
            order,
            "expected an even order in s from 2 to 24",
        ))
    }
}

/// [n / m] Pade approximant of the series `c` (ascending), in exact arithmetic:
/// numerator of degree n, denominator of degree m with constant 1. Exactness
/// matters: the span's series are nearly geometric, and its higher poles live
/// 20 and more decades below the leading terms, beyond any float.
pub fn pade(c: &[Q], n: usize, m: usize) -> Result<(Vec<Q>, Vec<Q>), UnitError> {
    if c.len() < n + m + 1 {
        return Err(UnitError::Numerical(format!(
            "Pade [{n}/{m}] needs {} coefficients",
            n + m + 1
        )));
    }
    let coef = |k: isize| if k < 0 { q(0) } else { c[k as usize].clone() };
    // Gauss-Jordan on sum_j b_j c_{k-j} = -c_k, k = n+1..n+m.
    let mut a: Vec<Vec<Q>> = (0..m)
        .map(|r| {
            let mut row: Vec<Q> = (0..m)
                .map(|j| coef((n + 1 + r) as isize - (j + 1) as isize))
                .collect();
            row.push(-coef((n + 1 + r) as isize));
            row
        })
        .collect();
    let zero = q(0);
    for col in 0..m {
        let pivot = (col..m).find(|&r| a[r][col] != zero).ok_or_else(|| {
            UnitError::Numerical(format!("Pade [{n}/{m}] does not exist (singular system)"))
        })?;
        a.swap(col, pivot);
        let p = a[col][col].clone();
        for v in a[col].iter_mut() {
            *v = v.clone() / p.clone();
        }
        let pivot_row = a[col].clone();
        for (r, row) in a.iter_mut().enumerate() {
            if r != col && row[col] != zero {
                let f = row[col].clone();
                for (v, p) in row.iter_mut().zip(&pivot_row) {
                    *v -= f.clone() * p.clone();
                }
            }
        }
    }
    let mut den = vec![q(1)];
    den.extend(a.iter().map(|row| row[m].clone()));
    let num = (0..=n)
        .map(|k| (0..=k.min(m)).fold(q(0), |acc, j| acc + den[j].clone() * coef((k - j) as isize)))
        .collect();
    Ok((num, den))
}

fn rational(num: Vec<Q>, den: Vec<Q>) -> RationalX {
    let lead = den.last().cloned().unwrap_or_else(|| q(1));
    RationalX {
        num: num.iter().map(|c| to_f64(&(c / &lead))).collect(),
        den: den.iter().map(|c| to_f64(&(c / &lead))).collect(),
    }
}

/// Taylor approximation of order `order` in s (eq. 5.11 for order 8).
pub fn taylor_u2_u5(order: usize) -> Result<RationalX, UnitError> {
    check_order(order)?;
    let odd = add(&series("sin", order - 1), &series("sinh", order - 1));
    let even = add(
        &multiply(&series("cos", order), &series("cosh", order)),
        &[q(1)],
    );
    Ok(rational(to_x(&odd, 1)?, to_x(&even, 0)?))
}

/// Term-wise Pade approximation of order `order` in s (eq. 5.14 for order 8);
/// orders divisible by 4 (the [k/k] approximants of sin and cos exist for even k).
pub fn term_pade_u2_u5(order: usize) -> Result<RationalX, UnitError> {
    check_order(order)?;
    if order % 4 != 0 {
        return Err(UnitError::parameter(
            "order",
            order,
            "the term-wise Pade approximation needs an order divisible by 4",
        ));
    }
    let k = order / 2;
    let p = |kind| pade(&series(kind, 2 * k), k, k);
    let ((sn, sd), (shn, shd), (cn, cd), (chn, chd)) =
        (p("sin")?, p("sinh")?, p("cos")?, p("cosh")?);
    let odd = add(&multiply(&sn, &shd), &multiply(&shn, &sd));
    let cos_den = multiply(&cd, &chd);
    let num = multiply(&odd, &cos_den);
    let den = multiply(&multiply(&sd, &shd), &add(&multiply(&cn, &chn), &cos_den));
    Ok(rational(to_x(&num, 1)?, to_x(&den, 0)?))
}

/// Function Pade approximation of order `order` in s (eq. 5.15 for order 8).
pub fn function_pade_u2_u5(order: usize) -> Result<RationalX, UnitError> {
    check_order(order)?;
    let k = order / 2;
    // f(x) = N(x) / D(x), N = 2 sum x^j / (4j+1)!, D = 2 + sum_{j>=1} (-4)^j x^j / (4j)!.
    let terms = 2 * k + 1;
    let n: Vec<Q> = (0..terms).map(|j| q(2) / factorial(4 * j + 1)).collect();
    let d: Vec<Q> = (0..terms)
        .map(|j| {
            if j == 0 {
                q(2)
            } else {
                q((-4i64).pow(j as u32)) / factorial(4 * j)
            }
        })
        .collect();
    let mut f: Vec<Q> = Vec::with_capacity(terms);
    for i in 0..terms {
        let mut v = n[i].clone();
        for j in 1..=i {
            v -= d[j].clone() * f[i - j].clone();
        }
        f.push(v / d[0].clone());
    }
    let (num, den) = pade(&f, k, k)?;
    Ok(rational(num, den))
}
