//! Hard cases of the nonlinear section (issue 12, stability and bad input): stiff
//! rollers, vessel heave at the pipe's first natural period, 100 ms steps, a line
//! snapping from slack to taut; each runs its full duration with finite, bounded
//! values. Bad input stops with the time and the reason.

use crate::support::slay::{Slay, TENSION, output};
use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::{Driver, Time};

/// Steps `driver` to `duration` (s) at `h` (s); returns the largest tension and
/// |moment| seen (N, N m), panicking on an error or a non-finite output.
fn run(driver: &mut Driver<NonlinearSection>, h: f64, duration: f64) -> (f64, f64) {
    let step = Time::from_secs(h).expect("step");
    let steps = (duration / h).round() as usize;
    let (mut t, mut tension, mut moment) = (Time::ZERO, 0.0f64, 0.0f64);
    let mut out = vec![0.0; driver.description().outputs.len()];
    for _ in 0..steps {
        driver
            .do_step(t, step)
            .unwrap_or_else(|e| panic!("t = {} s: {e}", t.as_secs()));
        t += step;
        driver.outputs(&mut out).expect("outputs");
        assert!(
            out.iter().all(|v| v.is_finite()),
            "non-finite output at t = {} s",
            t.as_secs()
        );
        tension = tension.max(output(driver, "max_tension"));
        moment = moment.max(output(driver, "max_moment"));
    }
    (tension, moment)
}

fn first_period(slay: &Slay) -> f64 {
    let d = slay.solved().expect("static");
    d.modes(1).expect("modes").modes[0].period
}

#[test]
fn an_slay_pipe_on_rollers_of_penalty_1e8_heaving_at_its_first_period_stays_bounded() {
    let mut slay = Slay::new(132);
    slay.stinger_law = r#"{ kind = "penalty", penalty = 1.0e8 }"#.into();
    slay.extra = r#"integrator = { kind = "hht", alpha = 0.1 }"#.into();
    let period = first_period(&slay);
    println!("first period about the static shape: {period:.2} s");
    slay.heave = Some((1.5, 2.0 * std::f64::consts::PI / period));
    let mut d = slay.solved().expect("static");
    let (tension, moment) = run(&mut d, 0.05, 10.0 * period);
    println!(
        "heave 1.5 m at the first period: max tension {tension:.0} N, max moment {moment:.0} N m"
    );
    // Drag limits the response: tension within a few times the static one.
    assert!(tension < 5.0 * TENSION, "max tension {tension} N");
}

#[test]
fn an_slay_pipe_heaving_runs_with_100_ms_steps() {
    let mut slay = Slay::new(132);
    slay.heave = Some((2.0, 0.8));
    slay.extra = r#"integrator = { kind = "hht", alpha = 0.1 }"#.into();
    let mut coarse = slay.solved().expect("static");
    let (tension, _) = run(&mut coarse, 0.1, 200.0);
    let mut fine = slay.solved().expect("static");
    let (reference, _) = run(&mut fine, 0.025, 200.0);
    println!("max tension at 100 ms {tension:.0} N, at 25 ms {reference:.0} N");
    // Stable and bounded; the long step filters the snap loads at the rollers
    // and touchdown (about 30 % lower peak tension than at 25 ms).
    assert!(
        tension > TENSION && tension < reference * 1.05,
        "{tension} N against {reference} N"
    );
}

/// 50 m of line between a pinned anchor and a top moved 1 m in and out around a
/// chord of 49.5 m: slack at the bottom of each cycle, snapped taut (stretched
/// by 0.5 m, 1 %) at the top.
fn snapping_line(bending_stiffness: f64, h: f64) -> f64 {
    let text = format!(
        r#"
segments = [{{ length = 50.0, elements = 50, axial_stiffness = 1.0e8, bending_stiffness = {bending_stiffness}, mass_per_length = 50.0, submerged_weight = 300.0, diameter = 0.1, drag_normal = 1.2, added_mass_normal = 1.0 }}]
static_start = true
start_shape = "catenary"
ends.start = {{ kind = "pinned" }}
ends.end = {{ kind = "pinned", x = {{ displacement = {{ offset = -0.5, amplitude = 1.0, angular_frequency = 0.5 }} }} }}
integrator = {{ kind = "hht", alpha = 0.1 }}
"#
    );
    let params: NonlinearParams = toml::from_str(&text).expect("parameters");
    let mut d = Driver::new(NonlinearSection::new(params).expect("valid"));
    d.initialize(Time::ZERO).expect("static");
    let (tension, _) = run(&mut d, h, 60.0);
    println!("EI = {bending_stiffness} N m^2, h = {h} s: max tension {tension:.0} N");
    tension
}

#[test]
fn a_line_snapping_from_slack_to_taut_runs_its_full_duration() {
    // From a wire rope (EI = 1e4 N m^2) to a chain-like line (EI = 10, below an
    // element's buckling load in the slack phase), at 10 and 100 ms.
    for (bending_stiffness, h) in [(1.0e4, 0.01), (1.0e4, 0.1), (10.0, 0.01), (10.0, 0.1)] {
        let tension = snapping_line(bending_stiffness, h);
        // Taut by 0.5 m over 50 m at the top of each cycle: EA * 0.01 = 1 MN.
        assert!(
            tension > 0.95e6 && tension < 1.2e6,
            "max tension {tension} N"
        );
    }
}

fn initialize_error(text: &str) -> String {
    let params: NonlinearParams = toml::from_str(text).expect("parameters");
    let mut d = Driver::new(NonlinearSection::new(params).expect("valid"));
    match d.initialize(Time::ZERO) {
        Ok(()) => panic!("initialize succeeded"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_line_that_cannot_hold_its_load_stops_with_the_load_level_reached() {
    // Nothing holds the line: its weight has no equilibrium.
    let e = initialize_error(
        r#"
static_start = true
segments = [{ length = 10.0, elements = 10, axial_stiffness = 1e8, bending_stiffness = 1e4, mass_per_length = 10.0, submerged_weight = 100.0 }]
"#,
    );
    println!("{e}");
    assert!(
        e.contains("static solve failed at t = 0 s") && e.contains("load level"),
        "{e}"
    );
}

#[test]
fn an_slay_shape_newton_cannot_reach_from_the_straight_line_stops_with_the_load_level() {
    // From the stress-free line on the seabed the pipe would have to pass through
    // the rollers to reach the stinger: the solve stops and says how far it got.
    let slay = Slay::new(66);
    let text = slay
        .toml()
        .replace("start_shape = \"points\"", "")
        .lines()
        .filter(|l| !l.starts_with("start_points"))
        .collect::<Vec<_>>()
        .join("\n");
    let e = initialize_error(&text);
    println!("{e}");
    assert!(
        e.contains("static solve failed at t = 0 s") && e.contains("load level"),
        "{e}"
    );
}

#[test]
fn contact_deeper_than_the_mesh_represents_stops_with_the_time_and_reason() {
    let mut slay = Slay::new(66);
    slay.seabed_law = r#"{ kind = "penalty", penalty = 10.0 }"#.into();
    let e = slay.solved().err().expect("refused");
    println!("{e}");
    assert!(
        e.contains("at t = 0 s") && e.contains("deep in a contact surface"),
        "{e}"
    );
}
