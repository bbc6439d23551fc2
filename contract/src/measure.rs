//! Units of measure as SI base-unit exponents: ports declare their unit by name,
//! connections compare them ("N.m" and "J" are the same), and the FMI layer writes
//! and reads them as `UnitDefinitions`.

/// Exponents of kg, m, s, A, K, mol, cd, rad (the order of FMI's `BaseUnit`).
pub type Exponents = [i32; 8];

/// The named units slender's ports and documents use.
const NAMED: [(&str, Exponents); 13] = [
    ("kg", [1, 0, 0, 0, 0, 0, 0, 0]),
    ("m", [0, 1, 0, 0, 0, 0, 0, 0]),
    ("s", [0, 0, 1, 0, 0, 0, 0, 0]),
    ("A", [0, 0, 0, 1, 0, 0, 0, 0]),
    ("K", [0, 0, 0, 0, 1, 0, 0, 0]),
    ("mol", [0, 0, 0, 0, 0, 1, 0, 0]),
    ("cd", [0, 0, 0, 0, 0, 0, 1, 0]),
    ("rad", [0, 0, 0, 0, 0, 0, 0, 1]),
    ("N", [1, 1, -2, 0, 0, 0, 0, 0]),
    ("Pa", [1, -1, -2, 0, 0, 0, 0, 0]),
    ("J", [1, 2, -2, 0, 0, 0, 0, 0]),
    ("W", [1, 2, -3, 0, 0, 0, 0, 0]),
    ("Hz", [0, 0, -1, 0, 0, 0, 0, 0]),
];

/// The SI base-unit exponents of a unit written as products and quotients of named
/// units with optional integer powers, e.g. "N.m", "m/s", "m/s^2", "kg/m", "1/s",
/// a space multiplying as a dot does ("N m^2", "N s/m^2").
/// `None` for an empty name or a symbol it does not know.
pub fn si_exponents(name: &str) -> Option<Exponents> {
    if name.trim().is_empty() {
        return None;
    }
    let mut exponents = [0; 8];
    let mut sign = 1;
    let mut token = String::new();
    let mut apply = |token: &str, sign: i32| -> Option<()> {
        if token.is_empty() || token == "1" {
            return Some(());
        }
        let (symbol, power) = match token.split_once('^') {
            Some((s, p)) => (s, p.parse::<i32>().ok()?),
            None => (token, 1),
        };
        let (_, e) = NAMED.iter().find(|(n, _)| *n == symbol)?;
        for (total, part) in exponents.iter_mut().zip(e) {
            *total += sign * power * part;
        }
        Some(())
    };
    for c in name.chars() {
        match c {
            '.' | '*' | '/' => {
                apply(&token, sign)?;
                token.clear();
                if c == '/' {
                    sign = -1;
                }
            }
            // A space multiplies, as the docs write "N m^2" and "N s/m^2".
            c if c.is_whitespace() => {
                apply(&token, sign)?;
                token.clear();
            }
            c => token.push(c),
        }
    }
    apply(&token, sign)?;
    Some(exponents)
}

/// Whether two unit names mean the same SI unit: equal names, or equal exponents
/// when both are understood (e.g. "N.m" and "J" are not told apart: both are
/// kg m^2 s^-2).
pub fn same_unit(a: &str, b: &str) -> bool {
    a == b || matches!((si_exponents(a), si_exponents(b)), (Some(x), Some(y)) if x == y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compound_units_reduce_to_base_exponents() {
        assert_eq!(si_exponents("N.m").unwrap(), [1, 2, -2, 0, 0, 0, 0, 0]);
        // Written with spaces, as the scene reference does (issue 49 #15).
        assert_eq!(si_exponents("N m^2"), si_exponents("N.m^2"));
        assert_eq!(si_exponents("N m^2").unwrap(), [1, 3, -2, 0, 0, 0, 0, 0]);
        assert_eq!(si_exponents("N s/m^2"), si_exponents("kg/m.s"));
        assert_eq!(si_exponents(" m / s "), si_exponents("m/s"));
        assert_eq!(si_exponents("m/s^2").unwrap(), [0, 1, -2, 0, 0, 0, 0, 0]);
        assert_eq!(si_exponents("1/s").unwrap(), [0, 0, -1, 0, 0, 0, 0, 0]);
        assert!(si_exponents("furlong").is_none());
        assert!(si_exponents("").is_none());
        assert!(same_unit("N*m", "N.m"));
        assert!(!same_unit("N", "m"));
    }
}
