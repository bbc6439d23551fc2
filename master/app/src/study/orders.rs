//! Observed orders of convergence of a sweep's runs (seed 000 Appendix B):
//! p = ln(e_i / e_j) / ln(h_i / h_j) to the next finer run, given only where
//! the error falls with every refinement.

use super::StudyRow;
use super::setting::Refinement;

/// p = ln(e_i / e_j) / ln(h_i / h_j) between each non-reference run and the next
/// finer one (h the step, or 1 / elements).
pub(super) fn observed_orders(refinement: Refinement, rows: &mut [StudyRow]) {
    let size = |v: f64| match refinement {
        Refinement::Smaller => v,
        Refinement::Larger => 1.0 / v,
        Refinement::None => f64::NAN,
    };
    if refinement == Refinement::None {
        return;
    }
    let by_size = |mut ks: Vec<usize>| {
        ks.sort_by(|&a, &b| size(rows[b].value).total_cmp(&size(rows[a].value)));
        ks
    };
    let order = by_size((0..rows.len()).filter(|&k| !rows[k].reference).collect());
    // Every run, the reference too: an indicator against the run's own twin
    // has an error there as well.
    let all = by_size((0..rows.len()).collect());
    for i in 0..rows.first().map_or(0, |r| r.errors.len()) {
        // An order means something only where the error falls with every
        // refinement: where it does not, the reference is not finer than
        // every run (an in-run twin at one of the meshes) and none is given.
        let falls = all
            .windows(2)
            .all(|w| rows[w[1]].errors[i].1 < rows[w[0]].errors[i].1);
        // Against an analytic solution in the run (an `exact` indicator) the
        // reference run has an error of its own: the finest pair counts too.
        let in_run = rows
            .iter()
            .any(|r| r.reference && r.errors[i].1.is_finite() && r.errors[i].1 > 0.0);
        let pairs = if in_run { &all } else { &order };
        for pair in pairs.windows(2).filter(|_| falls) {
            let (coarse, fine) = (pair[0], pair[1]);
            let ratio = (size(rows[coarse].value) / size(rows[fine].value)).ln();
            let p = (rows[coarse].errors[i].1 / rows[fine].errors[i].1).ln() / ratio;
            rows[coarse].orders[i].1 = if p.is_finite() { p } else { f64::NAN };
        }
    }
}
