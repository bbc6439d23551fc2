//! A line whose end lets go (`released_at`, a mooring line breaking at its
//! fairlead): free from then on, pulling nothing, swinging down to hang
//! below its anchor without the time stepping putting energy in. (On a
//! seabed the fall ends in impacts on its penalty springs that a step of
//! 0.1 s does not resolve: a line that breaks onto the seabed needs a
//! `max_step` of its own, as the moored body's test shows.)

use super::tests::{line, output, started};
use crate::contract::Time;

#[test]
fn a_released_end_swings_free_below_its_anchor_and_pulls_nothing() {
    let mut p = line(20, 30.0, "drag_normal = 1.2\nadded_mass_normal = 1.0");
    p.end.released_at = Some(5.0);
    let mut d = started(p);
    let h = Time::from_secs(0.1).unwrap();
    let mut t = Time::ZERO;
    let mut largest_error = 0.0_f64;
    let stored = |d: &_| output(d, "potential_energy") + output(d, "strain_energy");
    let before = stored(&d);
    for k in 0..3000 {
        d.do_step(t, h).unwrap_or_else(|e| panic!("step {k}: {e}"));
        t += h;
        largest_error = largest_error.max(output(&d, "energy_error"));
        if t.as_secs() > 5.05 {
            for c in ["x", "y", "z"] {
                assert_eq!(output(&d, &format!("end_force_{c}")), 0.0, "{t:?}");
            }
        }
    }
    // The energy the fall set free, which drag and the seabed took.
    let freed = before - stored(&d);
    let kinetic = output(&d, "kinetic_energy");
    let z = output(&d, "end_position_z");
    eprintln!(
        "released line: {freed:.4e} J set free; after 295 s kinetic {kinetic:.3e} J, end at z {z:.3} m; largest energy error {largest_error:.3e} J"
    );
    // Hanging below the anchor (0, 0, -100), 350 m of line, nearly at rest.
    let (x, y) = (output(&d, "end_position_x"), output(&d, "end_position_y"));
    assert!(z < -440.0 && x.hypot(y) < 0.1 * 350.0, "{x} {y} {z}");
    assert!(kinetic < 1e-2 * freed, "{kinetic:e} of {freed:e}");
    // HHT-alpha 0.3 only removes energy: the balance's error is the
    // quadrature of the drag's work over the swing.
    assert!(
        largest_error < 1e-3 * freed,
        "{largest_error:e} of {freed:e}"
    );
}
