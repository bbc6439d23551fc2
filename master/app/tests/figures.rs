//! The figures read right (issue 28): every kind is rendered and its SVG read
//! back. Tick labels of an axis are numbers (or the swept names), distinct,
//! and far enough apart not to run into each other; axes carry their units;
//! no figure is empty; point numbers and keys stay on the page.

use crate::common;

use slender_app::figures::{study, tradeoff};
use slender_app::study::StudyRow;
use std::path::Path;

/// A `<text>` of an SVG: position, anchor, vertical offset, size and content.
#[derive(Debug)]
struct Text {
    x: f64,
    y: f64,
    anchor: String,
    dy: String,
    size: f64,
    content: String,
}

fn attribute(tag: &str, name: &str) -> String {
    let key = format!(" {name}=\"");
    tag.find(&key)
        .and_then(|i| tag[i + key.len()..].split('"').next())
        .unwrap_or("")
        .to_owned()
}

fn texts(svg: &str) -> Vec<Text> {
    svg.split("<text")
        .skip(1)
        .map(|part| {
            let (tag, rest) = part.split_once('>').expect("a text tag closes");
            let content = rest.split("</text>").next().unwrap_or("").trim().to_owned();
            Text {
                x: attribute(tag, "x").parse().unwrap_or(f64::NAN),
                y: attribute(tag, "y").parse().unwrap_or(f64::NAN),
                anchor: attribute(tag, "text-anchor"),
                dy: attribute(tag, "dy"),
                size: attribute(tag, "font-size").parse().unwrap_or(10.0),
                content,
            }
        })
        .collect()
}

/// Tick labels by axis: runs of consecutive texts that are x ticks (centred,
/// hanging below the axis) at one height, or y ticks (right-aligned, centred
/// on their tick) at one x; plotters writes an axis's labels together.
fn axes(texts: &[Text]) -> Vec<Vec<&Text>> {
    let mut groups: Vec<Vec<&Text>> = Vec::new();
    let mut last: Option<(bool, f64)> = None;
    for t in texts {
        let key = match (t.anchor.as_str(), t.dy.as_str()) {
            ("middle", "0.76em") if !t.content.contains(' ') => Some((true, t.y)),
            ("end", "0.5ex") => Some((false, t.x)),
            _ => None,
        };
        match (key, last) {
            (Some(k), Some(l)) if k == l => groups.last_mut().expect("a run").push(t),
            (Some(_), _) => groups.push(vec![t]),
            (None, _) => {}
        }
        last = key;
    }
    groups.into_iter().filter(|g| g.len() >= 2).collect()
}

/// Asserts that every axis's labels are distinct, that x labels do not overlap
/// (0.6 em a character), and that numeric labels print zero as `0`.
fn assert_readable(svg: &str, what: &str) -> usize {
    let all = texts(svg);
    let axes = axes(&all);
    for axis in &axes {
        let mut labels: Vec<&str> = axis.iter().map(|t| t.content.as_str()).collect();
        labels.sort();
        labels.dedup();
        assert_eq!(
            labels.len(),
            axis.len(),
            "{what}: repeated tick labels {axis:?}"
        );
        let mut along: Vec<&&Text> = axis.iter().collect();
        along.sort_by(|a, b| a.x.total_cmp(&b.x));
        for pair in along.windows(2) {
            let half = |t: &Text| 0.3 * t.size * t.content.chars().count() as f64;
            if pair[0].y == pair[1].y {
                assert!(
                    pair[1].x - pair[0].x > half(pair[0]) + half(pair[1]),
                    "{what}: tick labels run into each other: {:?} and {:?}",
                    pair[0].content,
                    pair[1].content
                );
            }
        }
        for t in axis {
            if let Ok(v) = t.content.parse::<f64>() {
                assert!(
                    v == 0.0 || v.abs() > 1e-12,
                    "{what}: round-off printed as a tick: {}",
                    t.content
                );
                assert!(
                    !t.content.starts_with("0.000"),
                    "{what}: a tick reads {}",
                    t.content
                );
            }
        }
    }
    axes.len()
}

fn contains(svg: &str, text: &str) -> bool {
    texts(svg).iter().any(|t| t.content.contains(text))
}

fn row(group: &str, settings: &[(&str, &str)], errors: &[f64], cost: f64) -> StudyRow {
    let value = settings[0].1.parse().unwrap_or(f64::NAN);
    StudyRow {
        group: group.into(),
        settings: settings
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect(),
        value,
        reference: errors.iter().all(|e| *e == 0.0),
        errors: errors
            .iter()
            .enumerate()
            .map(|(i, e)| (format!("q{i}"), *e))
            .collect(),
        orders: vec![],
        iterations_per_step: 1.0,
        start_change: None,
        cost_per_simulated_second: cost,
        cost_spread: f64::NAN,
        error: None,
        floored: Vec::new(),
    }
}

/// One-at-a-time sweeps of numbers (tolerances over five decades, close
/// steps) and of names, and a grid of two settings.
fn study_rows() -> Vec<StudyRow> {
    let mut rows = Vec::new();
    for (k, tol) in ["1e-8", "1e-7", "1e-6", "1e-5", "1e-4", "1e-3"]
        .iter()
        .enumerate()
    {
        let e = if k == 0 {
            0.0
        } else {
            1e-9 * 10f64.powi(k as i32)
        };
        rows.push(row(
            "velocity_tolerance",
            &[("velocity_tolerance", tol)],
            &[e, 2.0 * e],
            0.01 / (k + 1) as f64,
        ));
    }
    for (k, step) in ["0.005", "0.01", "0.02", "0.05", "0.06", "0.1"]
        .iter()
        .enumerate()
    {
        let e = if k == 0 { 0.0 } else { 0.01 * k as f64 };
        rows.push(row(
            "step",
            &[("step", step)],
            &[e, e / 3.0],
            0.2 / (k + 1) as f64,
        ));
    }
    for (k, scheme) in [
        "iterative_jacobi",
        "iterative_gauss_seidel",
        "gauss_seidel",
        "jacobi",
    ]
    .iter()
    .enumerate()
    {
        let e = if k == 0 {
            0.0
        } else {
            10f64.powi(k as i32 * 8 - 12)
        };
        rows.push(row(
            "master.scheme",
            &[("master.scheme", scheme)],
            &[e, e],
            1e-3 / (k + 1) as f64,
        ));
    }
    let mut failed = row(
        "master.scheme",
        &[("master.scheme", "newton")],
        &[f64::NAN, f64::NAN],
        f64::NAN,
    );
    failed.error = Some("did not converge".into());
    rows.push(failed);
    for (i, step) in ["0.001", "0.002", "0.005"].iter().enumerate() {
        for (j, scheme) in ["iterative_jacobi", "jacobi"].iter().enumerate() {
            let e = if i + j == 0 {
                0.0
            } else {
                1e-6 * 10f64.powi((i + 4 * j) as i32)
            };
            rows.push(row(
                "grid",
                &[("step", step), ("master.scheme", scheme)],
                &[e, e],
                1e-3 / (i + 1) as f64,
            ));
        }
    }
    rows
}

#[test]
fn every_study_group_is_drawn_with_readable_axes() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("study.svg");
    let unit_of = |key: &str| {
        if key == "step" {
            "s".into()
        } else if key == "velocity_tolerance" {
            "m/s".into()
        } else {
            String::new()
        }
    };
    study::study(&path, "study", &study_rows(), &unit_of).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    // Four groups, two panels each, an x and a y axis per panel.
    assert!(
        assert_readable(&svg, "study.svg") >= 14,
        "too few axes drawn"
    );
    for title in [
        "velocity_tolerance (m/s)",
        "step (s)",
        "master.scheme",
        "cost (s per simulated s)",
        "worst epsilon (-)",
    ] {
        assert!(
            contains(&svg, title),
            "study.svg has no axis titled {title}"
        );
    }
    assert!(
        contains(&svg, "1e-8") && contains(&svg, "1e-4"),
        "the tolerance axis has no decade ticks"
    );
    assert!(
        contains(&svg, "reference") && contains(&svg, "failed"),
        "the reference and the failed run are not marked"
    );
    // The names sweep: the bars (one per indicator and value, and per cost).
    let bars = svg.matches("<rect").count();
    assert!(
        bars >= 1 + 3 * 2 + 4 + 6 * 2,
        "study.svg has {bars} rectangles: bars or cells missing"
    );
    assert!(
        svg.matches("<circle").count() >= 5 * 2 * 2,
        "study.svg: markers missing"
    );
}

#[test]
fn error_against_cost_numbers_every_point_and_keeps_the_key_on_the_page() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("error_cost.svg");
    let points: Vec<tradeoff::Point> = (0..40)
        .map(|k| tradeoff::Point {
            label: format!("upper=nonlinear middle=linear:{k} lower=static"),
            cost: 0.05 * (1.0 + 0.001 * k as f64),
            error: 1e-3 * (1.0 + 0.002 * (k % 7) as f64),
        })
        .collect();
    let figure = tradeoff::Tradeoff {
        title: "crowded",
        error_label: "worst epsilon (-)",
        points,
        tolerance: Some(0.01),
        reference_cost: Some(0.1),
        chosen: Some(3),
    };
    tradeoff::draw(&path, &figure).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert_readable(&svg, "error_cost.svg");
    let width: f64 = attribute(&svg[..svg.find('>').unwrap()], "width")
        .parse()
        .unwrap();
    let height: f64 = attribute(&svg[..svg.find('>').unwrap()], "height")
        .parse()
        .unwrap();
    let all = texts(&svg);
    for k in 1..=40 {
        let numbers = all
            .iter()
            .filter(|t| t.content == k.to_string() && t.anchor == "start")
            .count();
        assert_eq!(numbers, 1, "point {k} is numbered {numbers} times");
    }
    for t in &all {
        let right = t.x + 0.6 * t.size * t.content.chars().count() as f64;
        assert!(
            right <= width && t.y <= height,
            "{:?} runs off the page",
            t.content
        );
    }
    assert_eq!(
        tradeoff::pareto(&figure.points)
            .iter()
            .filter(|p| **p)
            .count(),
        1
    );
}

#[test]
fn run_figures_title_their_axes_with_units_and_print_zero_as_zero() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b1");
    let run = common::slender(&[
        "run",
        "examples/b1_two_masses.toml",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", common::text(&run.stderr));
    let svg = std::fs::read_to_string(Path::new(&out).join("displacements.svg")).unwrap();
    assert_readable(&svg, "displacements.svg");
    assert!(
        contains(&svg, "value (m)") && contains(&svg, "value (m/s)"),
        "the panels' y axes carry no unit"
    );
    assert!(contains(&svg, "time (s)"));
    assert!(
        texts(&svg).iter().any(|t| t.content == "0"),
        "no tick reads 0"
    );
}
