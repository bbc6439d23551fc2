use super::aggregate::{Durations, gumbel_fit, report};
use super::{CasesPlan, Heading, SeaState, set_sea, table};

fn plan(seas: usize, headings: usize, seeds: u64) -> CasesPlan {
    CasesPlan {
        seas: (0..seas)
            .map(|i| SeaState {
                significant_height: 2.0 + i as f64,
                peak_period: 8.0 + i as f64,
                probability: 0.5,
            })
            .collect(),
        headings: (0..headings)
            .map(|i| Heading {
                degrees: 30.0 * i as f64,
                probability: 1.0 / headings as f64,
            })
            .collect(),
        seeds,
        jobs: 1,
        duration: None,
        shard: None,
        max_runs: 100,
        overrides: Vec::new(),
    }
}

#[test]
fn the_matrix_runs_seeds_inside_headings_inside_sea_states() {
    let p = plan(2, 2, 2);
    let cases = p.cases();
    assert_eq!(cases.len(), 8);
    assert_eq!(
        (cases[0].sea, cases[0].heading, cases[0].seed),
        (0, Some(0), 1)
    );
    assert_eq!(
        (cases[3].sea, cases[3].heading, cases[3].seed),
        (0, Some(1), 2)
    );
    assert_eq!(
        (cases[7].sea, cases[7].heading, cases[7].seed),
        (1, Some(1), 2)
    );
    assert_eq!(
        p.describe(&cases[3]),
        "Hs 2 m, Tp 8 s, heading 30 deg, seed 2"
    );
    assert_eq!(plan(1, 0, 3).cases()[2].heading, None);
}

#[test]
fn every_spectrum_of_the_scene_gets_the_sea_state() {
    let mut scene: toml::Table = toml::from_str(
        r#"
[mooring.waves]
spectrum = { kind = "jonswap", significant_height = 6.0, peak_period = 10.0 }
[[units]]
name = "wave"
parameters = { sea = { spectrum = { kind = "jonswap", significant_height = 1.0, peak_period = 5.0 } } }
[[units]]
name = "other"
parameters = { spectrum = [1.0, 2.0], table = { spectrum = 3 } }
"#,
    )
    .unwrap();
    let sea = SeaState {
        significant_height: 3.5,
        peak_period: 9.0,
        probability: 0.2,
    };
    assert_eq!(set_sea(&mut scene, &sea, Some(45.0), 4), 2);
    let waves = &scene["mooring"]["waves"];
    assert_eq!(
        waves["spectrum"]["significant_height"].as_float(),
        Some(3.5)
    );
    assert_eq!(waves["spectrum"]["seed"].as_integer(), Some(4));
    assert_eq!(waves["heading_deg"].as_float(), Some(45.0));
    let unit = &scene["units"][0]["parameters"]["sea"];
    assert_eq!(unit["spectrum"]["peak_period"].as_float(), Some(9.0));
    // A key named `spectrum` that is no wave spectrum is left alone.
    assert_eq!(
        scene["units"][1]["parameters"]["table"]["spectrum"].as_integer(),
        Some(3)
    );
    assert_eq!(set_sea(&mut toml::Table::new(), &sea, None, 1), 0);
}

#[test]
fn a_row_read_back_is_the_row_written_and_another_plans_rows_are_not_read() {
    let p = plan(2, 2, 2);
    let columns = vec!["s/max".to_owned(), "f/damage_per_year".to_owned()];
    let rows = [
        (vec![1.0 / 3.0, f64::NAN], None),
        (vec![f64::NAN, f64::NAN], Some("diverged".to_owned())),
        (vec![2.5e-7, 1e300], None),
    ];
    let text = table::header(&columns)
        + &table::row(&p, 0, &rows[0])
        + &table::row(&p, 5, &rows[1])
        + &table::row(&p, 7, &rows[2]);
    let read = table::read(&text, &p, &columns);
    assert_eq!(read.len(), 8);
    let first = read[0].as_ref().expect("row 0");
    assert_eq!(first.0[0].to_bits(), (1.0f64 / 3.0).to_bits());
    assert!(first.0[1].is_nan());
    assert!(read[5].is_none(), "a failed case runs again");
    assert_eq!(read[7].as_ref().expect("row 7").0, vec![2.5e-7, 1e300]);
    // The same file read for another scatter (or other columns) keeps nothing.
    let mut other = plan(2, 2, 2);
    other.seas[0].probability = 0.4;
    assert!(table::read(&text, &other, &columns)[0].is_none());
    assert!(
        table::read(&text, &p, &columns[..1])
            .iter()
            .all(Option::is_none)
    );
}

#[test]
fn a_gumbel_fit_of_gumbel_maxima_gives_back_its_parameters() {
    // Inverse CDF: x = location - scale ln(-ln u).
    let (location, scale) = (1.2e6, 4.0e4);
    let mut seed = 9u64;
    let maxima: Vec<f64> = (0..40_000)
        .map(|_| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let u = ((seed >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
            location - scale * (-u.ln()).ln()
        })
        .collect();
    let (l, s) = gumbel_fit(&maxima).expect("fit");
    assert!((l / location - 1.0).abs() < 1e-3, "{l}");
    assert!((s / scale - 1.0).abs() < 0.02, "{s}");
    assert!(gumbel_fit(&maxima[..2]).is_none());
}

#[test]
fn the_matrix_gives_the_largest_groups_extreme_and_the_damage_weighed_by_probability() {
    // Two sea states (probabilities 0.7 and 0.3), three seeds each.
    let mut p = plan(2, 0, 3);
    (p.seas[0].probability, p.seas[1].probability) = (0.7, 0.3);
    let columns: Vec<String> = [
        "t/max",
        "t/rayleigh_mpm",
        "t/weibull_mpm",
        "f/damage_per_year",
    ]
    .map(String::from)
    .to_vec();
    let row = |max: f64, damage: f64| Some((vec![max, max + 1.0, f64::NAN, damage], None));
    let rows = vec![
        row(10.0, 1e-3),
        row(12.0, 2e-3),
        row(11.0, 3e-3),
        row(20.0, 1e-2),
        row(22.0, 1e-2),
        None,
    ];
    let durations = Durations {
        window_s: 100.0,
        storm_s: None,
    };
    let failed = vec![(5, "diverged".into())];
    let r = report(
        "s.toml".into(),
        &p,
        (columns.as_slice(), durations),
        &rows,
        failed,
    );
    assert_eq!((r.groups[0].completed, r.groups[1].completed), (3, 2));
    // Three seeds: Gumbel on the maxima; two: the mean Rayleigh MPM (no Weibull fit).
    let (g0, g1) = (&r.groups[0].extremes[0], &r.groups[1].extremes[0]);
    assert_eq!(g0.basis, "gumbel");
    let sd = 1.0f64; // of 10, 12, 11
    let scale = sd * 6f64.sqrt() / std::f64::consts::PI;
    assert!((g0.value - (11.0 - 0.5772156649015329 * scale)).abs() < 1e-12);
    assert_eq!((g1.basis, g1.value), ("rayleigh", 22.0));
    assert_eq!((r.design[0].value, r.design[0].group), (22.0, 1));
    let f = &r.fatigue[0];
    let total = 0.7 * 2e-3 + 0.3 * 1e-2;
    assert!((f.damage_per_year - total).abs() < 1e-15, "{f:?}");
    assert!((f.life_years * total - 1.0).abs() < 1e-12);
    assert!((r.probability_sum - 1.0).abs() < 1e-15);
    assert!(super::markdown::to_markdown(&r).contains("| 5 | diverged |"));
    // Over a storm of e windows the Gumbel location moves by one scale.
    let storm = Durations {
        window_s: 100.0,
        storm_s: Some(100.0 * std::f64::consts::E),
    };
    let r = report(
        "s.toml".into(),
        &p,
        (columns.as_slice(), storm),
        &rows,
        Vec::new(),
    );
    let (location, scale) = r.groups[0].extremes[0].gumbel.expect("fit");
    assert!((r.groups[0].extremes[0].value - (location + scale)).abs() < 1e-12);
}
