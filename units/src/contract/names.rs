//! Names of units and ports: hints for near misses in scenes and FMUs.

/// "; did you mean `x`?" when a candidate is close to `wrong`, else "".
pub fn did_you_mean<'a>(wrong: &str, candidates: impl Iterator<Item = &'a str>) -> String {
    candidates
        .map(|c| (strsim::levenshtein(wrong, c), c))
        .filter(|(d, c)| *d <= 2.max(c.len() / 3))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| format!("; did you mean `{c}`?"))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_misses_get_a_hint_and_far_ones_do_not() {
        let names = ["top_force", "bottom_velocity"];
        assert_eq!(
            did_you_mean("top_forse", names.into_iter()),
            "; did you mean `top_force`?"
        );
        assert_eq!(did_you_mean("xyz", names.into_iter()), "");
    }
}
