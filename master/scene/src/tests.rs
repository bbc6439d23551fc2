//! Refusals of a scene as a user writes it, read through `Scene::parse`
//! (its spec, its `[structure]` and the units it writes out), and the
//! helpers the crate's tests share.

use crate::{Scene, SceneError};
use std::path::Path;

/// A structure example the tests edit: a hanging pipe in three sections.
pub(crate) const HANGING_PIPE: &str = include_str!("../../../examples/structure_hanging_pipe.toml");

/// The scene `text`, named `pipe.toml` in messages.
pub(crate) fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::parse(Path::new("pipe.toml"), text.to_owned())
}

/// The 1-based number of the first line of `text` containing `needle`.
pub(crate) fn line_of(text: &str, needle: &str) -> usize {
    1 + text
        .lines()
        .position(|l| l.contains(needle))
        .expect("the line")
}

#[test]
fn a_section_key_it_does_not_take_is_refused_at_its_line() {
    // It was silently ignored: a misspelt `elements` left the mesh as it was.
    let text = HANGING_PIPE.replacen(
        "[[structure.sections]]",
        "[[structure.sections]]\nelemnts = 10",
        1,
    );
    let error = parse(&text).expect_err("an unknown key").to_string();
    let line = line_of(&text, "elemnts");
    assert!(error.starts_with(&format!("pipe.toml:{line}:")), "{error}");
    assert!(
        error.contains("`structure.sections[0].elemnts`: unknown field"),
        "{error}"
    );
    assert!(error.contains("`elements`"), "the keys it takes: {error}");
}

#[test]
fn a_structure_value_of_the_wrong_type_says_what_was_expected() {
    let text = HANGING_PIPE.replacen(
        "[[structure.sections]]",
        "[[structure.sections]]\nsubsteps = 2.5",
        1,
    );
    let error = parse(&text).expect_err("a fraction").to_string();
    assert!(
        error.contains("`structure.sections[0].substeps`"),
        "{error}"
    );
    assert!(error.contains("expected a whole number"), "{error}");
    assert!(!error.contains("i64"), "Rust words: {error}");
    let text = HANGING_PIPE.replacen("\n[structure]\n", "\n[structure]\nnmae = \"x\"\n", 1);
    let error = parse(&text).expect_err("an unknown key").to_string();
    assert!(
        error.starts_with(&format!("pipe.toml:{}:", line_of(&text, "nmae"))),
        "{error}"
    );
    assert!(
        error.contains("unknown field `nmae`, expected one of `name`"),
        "{error}"
    );
}

#[test]
fn an_end_motion_fade_in_that_is_not_a_time_is_refused() {
    // It was taken: inf removed the motion, NaN and -1 left it unfaded.
    let motion = "amplitude = 0.5, angular_frequency = 1.5";
    for fade in ["inf", "nan", "-1.0"] {
        let text = HANGING_PIPE.replacen(motion, &format!("{motion}, fade_in = {fade}"), 1);
        let error = parse(&text).expect_err(fade).to_string();
        assert!(
            error.contains("ends.start.x.displacement.fade_in"),
            "{fade}: {error}"
        );
        assert!(error.contains("fade_in >= 0 (s)"), "{fade}: {error}");
    }
}

#[test]
fn a_duration_shorter_than_a_step_is_refused() {
    // 1e-12 s rounded to no step at all, and the run "completed".
    let text = HANGING_PIPE.replacen("duration = ", "duration = 1e-12 # ", 1);
    let error = parse(&text).expect_err("no step").to_string();
    assert!(error.contains("simulation.duration"), "{error}");
    assert!(error.contains("shorter than one step"), "{error}");
}

#[test]
fn a_structure_without_segments_or_with_an_angle_past_a_turn_is_refused() {
    let segments = HANGING_PIPE
        .lines()
        .find(|l| l.starts_with("segments = "))
        .expect("segments");
    let text = HANGING_PIPE.replacen(segments, "segments = []", 1);
    let error = parse(&text).expect_err("no segment").to_string();
    assert!(error.contains("at least one segment"), "{error}");
    let text = HANGING_PIPE.replacen("angle_deg = -90.0", "angle_deg = 1e308", 1);
    let error = parse(&text).expect_err("1e308 deg").to_string();
    assert!(
        error.contains("segments[0].angle_deg") && error.contains("-360 to 360 deg"),
        "{error}"
    );
}

#[test]
fn a_fidelity_is_written_in_a_scene_as_on_the_command_line() {
    // `name:count` as `slender fidelity --section` takes it: the same
    // expansion as the fidelity and its count written apart.
    let with = |section: &str| {
        let text = HANGING_PIPE.replacen(
            "name = \"middle\"",
            &format!("name = \"middle\"\n{section}"),
            1,
        );
        parse(&text).map(|scene| scene.source().expect("the expansion").to_owned())
    };
    let short = with("fidelity = \"nonlinear:4\"").unwrap();
    assert_eq!(
        short,
        with("fidelity = \"nonlinear\"\nelements = 4").unwrap()
    );
    assert_ne!(short, with("fidelity = \"nonlinear\"").unwrap());
    for (written, expected) in [
        (
            "fidelity = \"nonlinear:0\"",
            "the count after `:` is a whole number of at least 1",
        ),
        (
            "fidelity = \"nonlinear:4/2\"",
            "sub-steps are the section's `substeps` key",
        ),
        (
            "fidelity = \"nonlinear:4\"\nelements = 4",
            "the element count is given twice",
        ),
    ] {
        let error = with(written).expect_err(written).to_string();
        assert!(error.contains(expected), "{written}: {error}");
    }
}

#[test]
fn a_step_that_is_not_a_whole_number_of_nanoseconds_is_refused() {
    // 1/3 ms was rounded to 333 333 ns: an FMU's own clock fell behind and
    // its fmi2DoStep failed after 500 000 steps.
    let step = HANGING_PIPE
        .lines()
        .find(|l| l.starts_with("step = "))
        .expect("step");
    let text = HANGING_PIPE.replacen(step, "step = 0.0003333333333333333", 1);
    let error = parse(&text).expect_err("1/3 ms").to_string();
    assert!(error.contains("simulation.step"), "{error}");
    assert!(
        error.contains("not a whole number of nanoseconds"),
        "{error}"
    );
    assert!(error.contains("3.33333e-4 s"), "{error}");
    // Steps written in decimals stay whole: 0.1 s, 1 ms, 2 ns.
    for fine in ["0.1", "0.001", "0.000000002"] {
        let text = HANGING_PIPE
            .replacen(step, &format!("step = {fine}"), 1)
            .replacen("duration = ", "duration = 0.2 # ", 1);
        if let Err(e) = parse(&text) {
            assert!(!e.to_string().contains("nanoseconds"), "{fine}: {e}");
        }
    }
}

#[test]
fn a_statistics_window_before_the_start_is_refused() {
    let scene = |statistics: &str| {
        let text = format!(
            "[simulation]\nduration = 10.0\nstep = 0.5\n[master]\nscheme = \"jacobi\"\n[[units]]\nname = \"m\"\nkind = \"oscillator\"\nparameters = {{ mass = 1.0, stiffness = 1.0 }}\n[output]\nstatistics = {statistics}\n"
        );
        parse(&text).map(|_| ()).map_err(|e| e.to_string())
    };
    assert_eq!(scene("{ from = 2.0 }"), Ok(()));
    assert_eq!(scene("{}"), Ok(()));
    // Past the end (a run shortened by --duration): no statistics, a warning.
    assert_eq!(scene("{ from = 10.0 }"), Ok(()));
    for (bad, says) in [
        (
            "{ from = -1.0 }",
            "output.statistics.from: -1: expected a time (s) at or after the run's start, 0",
        ),
        (
            "{ from = nan }",
            "output.statistics.from: NaN: expected a time",
        ),
        ("{ form = 2.0 }", "unknown field `form`"),
    ] {
        let error = scene(bad).expect_err(bad);
        assert!(error.contains(says), "{bad}: {error}");
    }
}

#[test]
fn a_sections_mesh_is_the_models_elements_over_it() {
    // 30 elements over 30 m, cut at 10 and 20 m; the written units agree.
    let table: toml::Table = HANGING_PIPE.parse().expect("TOML");
    let layout = crate::structure::layout(&table)
        .expect("a layout")
        .expect("a structure");
    let meshes: Vec<usize> = layout.sections.iter().map(|s| s.mesh).collect();
    assert_eq!(meshes, [10, 10, 10]);
    let scene = parse(HANGING_PIPE).expect("the example");
    for (section, mesh) in layout.sections.iter().zip(meshes) {
        let unit = (scene.spec.units.iter())
            .find(|u| u.name.get_ref() == &section.unit)
            .expect("the section's unit");
        let Some(crate::structure::Parameters::Nonlinear(parameters)) = &unit.written else {
            panic!("{}: not a nonlinear unit", section.name);
        };
        let written: usize = parameters.segments.iter().map(|s| s.elements).sum();
        assert_eq!(written, mesh, "{}", section.name);
    }
    assert!(crate::structure::takes_model_mesh("nonlinear"));
    assert!(crate::structure::takes_model_mesh("linear"));
    assert!(!crate::structure::takes_model_mesh("reduced"));
    assert!(!crate::structure::takes_model_mesh("cable"));
}

/// An oscillator scene with `output` in its `[output]`, parsed.
fn analysis_scene(output: &str) -> Result<(), String> {
    let text = format!(
        "[simulation]\nduration = 10.0\nstep = 0.5\n[master]\nscheme = \"jacobi\"\n[[units]]\nname = \"m\"\nkind = \"oscillator\"\nparameters = {{ mass = 1.0, stiffness = 1.0 }}\n[output]\n{output}\n"
    );
    parse(&text).map(|_| ()).map_err(|e| e.to_string())
}

/// A fatigue entry of the oscillator's displacement with `rest` added.
fn analysis_fatigue(rest: &str) -> String {
    format!("[[output.fatigue]]\nname = \"f\"\ntension = \"m.displacement\"\n{rest}")
}

#[test]
fn extremes_spectra_and_fatigue_a_scene_can_give_are_accepted() {
    let (scene, fatigue) = (analysis_scene, analysis_fatigue);
    let chain = "curve = \"dnv_studless_chain\"\nchain_diameter = 0.1";
    for good in [
        "statistics = { extremes = { duration = 10800.0 }, spectra = {} }".to_owned(),
        "statistics = { spectra = { segment = 2.0 } }".to_owned(),
        "envelopes = { from = 2.0 }".to_owned(),
        fatigue(chain),
        fatigue("curve = \"api_studless_chain\"\nbreaking_load = 1e6"),
        fatigue(
            "curve = \"dnv_c203_d_seawater_cp\"\narea = 0.02\nmoment = \"m.velocity\"\nsection_modulus = 1e-3\nscf = 1.2\nfrom = 2.0",
        ),
        fatigue(
            "curve = \"dnv_c203_f1_air\"\narea = 0.02\nthickness = 0.04\nreference_thickness = 0.016\nthickness_exponent = 0.3\nmean_stress = \"post_weld_heat_treated\"",
        ),
    ] {
        assert_eq!(scene(&good), Ok(()), "{good}");
    }
}

#[test]
fn extremes_spectra_and_fatigue_that_cannot_be_given_are_refused_before_the_run() {
    let (scene, fatigue) = (analysis_scene, analysis_fatigue);
    let chain = "curve = \"dnv_studless_chain\"\nchain_diameter = 0.1";
    for (bad, says) in [
        (
            "statistics = { extremes = { duration = 0.0 } }".to_owned(),
            "output.statistics.extremes.duration: 0: expected a positive number",
        ),
        (
            "statistics = { extremes = {} }".to_owned(),
            "missing field `duration`",
        ),
        (
            "statistics = { spectra = { segment = -1.0 } }".to_owned(),
            "output.statistics.spectra.segment: -1: expected a positive number",
        ),
        (
            fatigue("curve = \"studless\"\narea = 1.0"),
            "unknown variant `studless`, expected one of `dnv_studless_chain`",
        ),
        (
            fatigue("curve = \"dnv_studless_chain\""),
            "output.fatigue[0]: the curve needs one of `area` (m2) and `chain_diameter` (m)",
        ),
        (
            fatigue("curve = \"dnv_studless_chain\"\narea = 1.0\nchain_diameter = 0.1"),
            "needs one of `area`",
        ),
        (
            fatigue("curve = \"api_studlink_chain\""),
            "output.fatigue[0]: the curve needs `breaking_load` (N)",
        ),
        (
            fatigue(
                "curve = \"api_studlink_chain\"\nbreaking_load = 1e6\nmoment = \"m.velocity\"\nsection_modulus = 1.0",
            ),
            "a tension range alone",
        ),
        (
            fatigue(&format!("{chain}\nmoment = \"m.velocity\"")),
            "`moment` and `section_modulus` (m3) are given together",
        ),
        (
            fatigue(&format!("{chain}\nscf = 0.0")),
            "output.fatigue[0].scf: 0: expected a positive number",
        ),
        (
            fatigue(&format!("{chain}\nfrom = -3.0")),
            "output.fatigue[0].from: -3: expected a time",
        ),
        (
            "envelopes = { from = -2.0 }".to_owned(),
            "output.envelopes.from: -2: expected a time",
        ),
        ("envelopes = { to = 2.0 }".to_owned(), "unknown field `to`"),
        (
            fatigue(&format!("{chain}\ntension = \"m.tension\"")),
            "duplicate key",
        ),
        (
            fatigue(chain).replace("m.displacement", "m.tension"),
            "output.fatigue[0]: ",
        ),
        (
            format!("signals = [\"m.velocity\"]\n{}", fatigue(chain)),
            "output.fatigue[0]: `m.displacement` is not among output.signals",
        ),
        (
            format!("{}\n{}", fatigue(chain), fatigue(chain)),
            "output.fatigue[1]: `f` is named twice",
        ),
    ] {
        let error = scene(&bad).expect_err(&bad);
        assert!(error.contains(says), "{bad}: {error}");
    }
}

#[test]
fn dnv_rp_c203_effects_that_cannot_be_given_are_refused_before_the_run() {
    let (scene, fatigue) = (analysis_scene, analysis_fatigue);
    let chain = "curve = \"dnv_studless_chain\"\nchain_diameter = 0.1";
    for (bad, says) in [
        (
            fatigue(&format!("{chain}\nthickness = 0.03")),
            "output.fatigue[0].thickness: DNV-RP-C203's effects apply to its S-N curves",
        ),
        (
            fatigue(
                "curve = \"api_studless_chain\"\nbreaking_load = 1e6\nmean_stress = \"base_material\"",
            ),
            "output.fatigue[0].mean_stress: DNV-RP-C203's effects apply",
        ),
        (
            fatigue("curve = \"dnv_c203_d_air\"\narea = 0.02\nmean_stress = \"welded\""),
            "unknown variant `welded`, expected `base_material` or `post_weld_heat_treated`",
        ),
        (
            fatigue("curve = \"dnv_c203_d_air\"\narea = 0.02\nthickness = -0.03"),
            "output.fatigue[0].thickness: -0.03: expected a positive number",
        ),
        (
            fatigue("curve = \"dnv_c203_d_air\"\narea = 0.02\nreference_thickness = 0.016"),
            "output.fatigue[0].thickness: missing: `reference_thickness` and `thickness_exponent` need",
        ),
        (
            fatigue(
                "curve = \"dnv_c203_d_air\"\narea = 0.02\nthickness = 0.05\nthickness_exponent = 2.0",
            ),
            "output.fatigue[0].thickness_exponent: 2: expected an exponent from 0 to 1",
        ),
    ] {
        let error = scene(&bad).expect_err(&bad);
        assert!(error.contains(says), "{bad}: {error}");
    }
}

#[test]
fn a_sea_that_repeats_within_the_analysed_window_is_named_with_the_components_it_needs() {
    // 200 components over [0.5, 5] x wp at Tp = 10 s: dw = 4.5 wp / 200,
    // repeating every 2 pi / dw = 444.4 s.
    let text = |duration: f64| {
        format!(
            "[simulation]\nduration = {duration}\nstep = 0.5\n[master]\nscheme = \"jacobi\"\n[[units]]\nname = \"wave\"\nkind = \"signal\"\nparameters = {{ quantity = \"displacement\", sea = {{ spectrum = {{ kind = \"jonswap\", significant_height = 4.0, peak_period = 10.0 }} }} }}\n"
        )
    };
    let scene = parse(&text(1000.0)).expect("scene");
    let warnings = scene.sea_repeat_warnings(100.0);
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    let w = &warnings[0];
    assert!(w.starts_with("the sea of wave (200 components over [0.5, 5] x the peak frequency) repeats every 444.4 s: the 900 s analysed see the same waves 2.0 times"), "{w}");
    assert!(
        w.ends_with("give the spectrum `components = 405` or more for a sea that does not repeat"),
        "{w}"
    );
    assert!(
        scene.sea_repeat_warnings(600.0).is_empty(),
        "400 s: no repeat"
    );
    assert!(
        parse(&text(400.0))
            .expect("scene")
            .sea_repeat_warnings(0.0)
            .is_empty()
    );
}

#[test]
fn an_indicator_of_the_largest_magnitude_takes_any_number_of_references() {
    let indicator = |rest: &str| {
        analysis_scene(&format!(
            "[[output.indicators]]\nname = \"i\"\nsignals = [\"m.displacement\", \"m.velocity\"]\nreference = [\"m.displacement\"]\n{rest}"
        ))
    };
    assert_eq!(indicator("combine = \"largest\""), Ok(()));
    let error = indicator("").expect_err("two signals against one reference");
    assert!(
        error.contains("as many reference signals as signals") && error.contains("largest"),
        "{error}"
    );
    let error = indicator("combine = \"max\"").expect_err("not a way to combine");
    assert!(error.contains("unknown variant `max`"), "{error}");
    // One component: the largest magnitude at each sample, over the shorter.
    let (a, b) = ([1.0, -3.0, 0.5], [-2.0, 1.0]);
    let largest = crate::spec::Combine::Largest.apply(vec![&a, &b]);
    assert_eq!(largest.len(), 1);
    assert_eq!(&*largest[0], &[2.0, 3.0]);
    assert_eq!(crate::spec::Combine::Each.apply(vec![&a, &b]).len(), 2);
}
