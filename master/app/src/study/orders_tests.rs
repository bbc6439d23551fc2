//! Observed orders: given where the error falls with every refinement, not
//! where the reference is not finer than every run.

use super::StudyRow;
use super::orders::observed_orders;
use super::setting::Refinement;

fn row(elements: f64, error: f64, reference: bool) -> StudyRow {
    StudyRow {
        group: "lower.elements".into(),
        settings: Vec::new(),
        value: elements,
        reference,
        errors: vec![("bottom".into(), error)],
        orders: vec![("bottom".into(), f64::NAN)],
        iterations_per_step: 1.0,
        start_change: None,
        cost_per_simulated_second: 1.0,
        cost_spread: f64::NAN,
        error: None,
        floored: Vec::new(),
    }
}

#[test]
fn an_order_is_given_where_the_error_falls_with_each_refinement_only() {
    // Halving the element size divides the error by 4: order 2.
    let mut rows = vec![
        row(5.0, 4e-3, false),
        row(10.0, 1e-3, false),
        row(20.0, 0.0, true),
    ];
    observed_orders(Refinement::Larger, &mut rows);
    assert!(
        (rows[0].orders[0].1 - 2.0).abs() < 1e-12,
        "{:?}",
        rows[0].orders
    );
    // The hanging pipe against its in-run twin at the 10-element mesh: the
    // errors (2.3e-3, 2e-11, 5.8e-4 at the reference) do not fall with
    // refinement, so no order (it printed 26.6).
    let mut rows = vec![
        row(5.0, 2.33e-3, false),
        row(10.0, 2.2e-11, false),
        row(20.0, 5.8e-4, true),
    ];
    observed_orders(Refinement::Larger, &mut rows);
    assert!(
        rows.iter().all(|r| r.orders[0].1.is_nan()),
        "{:?}",
        rows[0].orders
    );
}

#[test]
fn against_an_analytic_solution_the_finest_pair_has_an_order_too() {
    // B3's `exact` indicator over steps 10, 5, 2.5, 1.25 ms (measured errors):
    // the reference run's own error counts, so 2.5 ms gets its order (1.93),
    // where it printed '-'.
    let mut rows = vec![
        row(0.01, 5.89e-1, false),
        row(0.005, 4.03e-1, false),
        row(0.0025, 1.58e-1, false),
        row(0.00125, 4.14e-2, true),
    ];
    observed_orders(Refinement::Smaller, &mut rows);
    let expected = (1.58e-1f64 / 4.14e-2).ln() / 2f64.ln();
    assert!(
        (rows[2].orders[0].1 - expected).abs() < 1e-12,
        "{:?}",
        rows[2].orders
    );
    assert!(rows[3].orders[0].1.is_nan(), "the finest has no finer run");
}
