//! Issue 28: every concrete command the README and the user guide's chapters
//! (`docs/guide/*.md`) show (a fenced line or an inline `slender ...` naming an
//! example scene; not a ```console block, which shows a refusal) still works
//! as written (the tutorials run in full in tutorials.rs). Runs
//! and mode analyses run for real, over ten of their scene's steps (a run's
//! own `--duration` replaced); study,
//! fidelity and uq commands are checked up to their first run (arguments,
//! scene, every key and section they name) by `--max-runs 0`, which they
//! refuse only after everything else was accepted, since their grids take
//! minutes to hours (their figures are measured in BENCHMARKS.md and by the
//! study tests). Commands on a previous command's results (`results/...`) and
//! the span commands (span_cli.rs) are left out. Every figure the README shows
//! is made again by its command, in full (seconds).

use crate::common;

use common::{slender, text};
use std::path::Path;

/// The README and the guide's chapters, as text.
fn documents() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = vec![root.join("README.md")];
    let mut chapters: Vec<_> = std::fs::read_dir(root.join("docs/guide"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    chapters.sort();
    files.extend(chapters);
    files
        .iter()
        .map(|f| std::fs::read_to_string(f).unwrap())
        .collect()
}

/// The commands with an example scene of the README and the guide, each as
/// its words.
fn readme_commands() -> Vec<Vec<String>> {
    documents().iter().flat_map(|d| commands_of(d)).collect()
}

/// The commands with an example scene of one document, each as its words.
fn commands_of(readme: &str) -> Vec<Vec<String>> {
    let mut commands = Vec::new();
    let mut in_block = false;
    let mut shown = false;
    let mut pending = String::new();
    for line in readme.lines() {
        if let Some(fence) = line.trim_start().strip_prefix("```") {
            in_block = !in_block;
            shown = in_block && fence == "console";
            continue;
        }
        if !in_block || shown {
            continue;
        }
        let line = line.split(" #").next().unwrap_or(line).trim();
        let continued = !pending.is_empty();
        if continued || line.starts_with("slender ") || line.starts_with("cargo run --release -- ")
        {
            pending.push_str(line.trim_end_matches('\\'));
            pending.push(' ');
            if !line.ends_with('\\') {
                commands.push(std::mem::take(&mut pending));
            }
        }
    }
    // Inline code spans, which may break across lines.
    let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    commands.extend(
        flat.split('`')
            .skip(1)
            .step_by(2)
            .filter(|span| span.starts_with("slender "))
            .map(str::to_owned),
    );
    commands
        .iter()
        .map(|c| {
            let words = c.split_whitespace().map(str::to_owned);
            let words: Vec<String> = words.skip_while(|w| w != "slender" && w != "--").collect();
            words.into_iter().skip(1).collect()
        })
        .filter(|w: &Vec<String>| w.iter().any(|w| w.starts_with("examples/")))
        .collect()
}

/// The scene's step (s), to run ten of them.
fn step_of(scene: &str) -> f64 {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let table: toml::Table = std::fs::read_to_string(root.join(scene))
        .unwrap()
        .parse()
        .unwrap();
    table["simulation"]["step"].as_float().unwrap()
}

#[test]
fn every_readme_command_with_an_example_scene_works_as_written() {
    let commands = readme_commands();
    assert!(commands.len() >= 10, "{commands:?}");
    let dir = tempfile::tempdir().unwrap();
    for (k, words) in commands.iter().enumerate() {
        let out = dir.path().join(k.to_string());
        let out = out.to_str().unwrap();
        // The results go to the test's folder, whatever the document names;
        // a run's own `--duration` (a 3-hour sea) gives way to ten steps.
        let mut args: Vec<String> = Vec::new();
        let mut given = words.iter();
        while let Some(word) = given.next() {
            match word.as_str() {
                "--out" => _ = given.next(),
                "--duration" if words[0] == "run" => _ = given.next(),
                _ => args.push(word.clone()),
            }
        }
        let scene = words.iter().find(|w| w.starts_with("examples/")).unwrap();
        let checked_to_the_start = matches!(words[0].as_str(), "study" | "fidelity" | "uq");
        match words[0].as_str() {
            "run" => {
                let ten_steps = format!("{}", 10.0 * step_of(scene));
                args.extend(["--quiet".into(), "--duration".into(), ten_steps]);
            }
            "study" | "fidelity" | "uq" => args.extend(["--max-runs".into(), "0".into()]),
            _ => {}
        }
        match (words[0].as_str(), words.get(1).map(String::as_str)) {
            ("run" | "modes" | "study" | "fidelity" | "uq", _) => {
                args.extend(["--out".into(), out.into()]);
            }
            ("fmu", Some("export")) => args.extend(["--out".into(), format!("{out}.fmu")]),
            _ => {}
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let output = slender(&args);
        let (stdout, stderr) = (text(&output.stdout), text(&output.stderr));
        eprintln!(
            "slender {}: exit {:?}",
            words.join(" "),
            output.status.code()
        );
        if checked_to_the_start {
            assert_eq!(output.status.code(), Some(2), "{words:?}: {stderr}");
            assert!(
                stderr.contains("more than the bound of 0"),
                "{words:?} refused before its size was checked: {stderr}"
            );
        } else {
            assert!(output.status.success(), "{words:?}: {stdout}{stderr}");
        }
    }
}

/// The texts of an SVG figure (titles, ticks, key entries), unescaped as
/// written.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| t.split_once('>').map(|(_, rest)| rest))
        .map(|t| t.split("</text>").next().unwrap_or("").trim().to_owned())
        .collect()
}

/// Every figure the README or the guide shows (`![...](docs/figures/X.svg)`,
/// `../figures/X.svg` from a chapter; each once) is made again
/// by the command in the fenced block just before it: the same points, the
/// same key (every combination by number), titles and axes. Costs, and so the
/// points' places along the cost axis, its ticks and which run within the
/// tolerance is cheapest, vary with the machine.
#[test]
fn every_readme_figure_is_reproduced_by_its_command() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = tempfile::tempdir().unwrap();
    let mut figures = 0;
    let mut made_already = std::collections::BTreeSet::new();
    for readme in documents() {
        for (before, after) in readme
            .split("figures/")
            .zip(readme.split("figures/").skip(1))
            .filter(|(before, _)| before.ends_with("](docs/") || before.ends_with("](../"))
        {
            let name = after.split(')').next().unwrap();
            if !made_already.insert(name.to_owned()) {
                continue;
            }
            let block = before
                .rsplit("```")
                .nth(1)
                .expect("a fenced command before the figure");
            let words: Vec<&str> = block.split_whitespace().filter(|w| *w != "\\").collect();
            assert_eq!(words[0], "slender", "{block}");
            let out = dir.path().join(name);
            let mut args: Vec<&str> = words[1..].to_vec();
            args.extend(["--out", out.to_str().unwrap()]);
            let run = slender(&args);
            // Every run of the figure's study finishes (the S-lay grid's static
            // touchdown section under a span chord stopped at 21.1 s until chords
            // took the section's compliance and axial mass).
            assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
            let made = std::fs::read_to_string(out.join("fidelity.svg")).unwrap();
            let shown = std::fs::read_to_string(root.join("docs/figures").join(name)).unwrap();
            assert_eq!(
                made.matches("<circle").count(),
                shown.matches("<circle").count(),
                "{name}: points"
            );
            let lasting = |svg: &str| -> Vec<String> {
                texts(svg)
                    .into_iter()
                    .filter(|t| t.contains('=') || t.chars().any(char::is_alphabetic))
                    // Which run within tolerance is cheapest is a matter of cost.
                    .filter(|t| !t.contains("cheapest"))
                    .collect()
            };
            assert_eq!(lasting(&made), lasting(&shown), "{name}: titles and key");
            figures += 1;
        }
    }
    assert!(figures >= 1, "the README shows no figure");
}

/// The `slender fidelity` commands of an example scene's comments (`#`
/// lines, continued with `\`), each as its words.
fn comment_commands(scene_text: &str) -> Vec<Vec<String>> {
    let comments: String = (scene_text.lines())
        .filter_map(|l| l.trim_start().strip_prefix('#'))
        .map(|l| format!("{}\n", l.trim()))
        .collect();
    let fenced = format!("```\n{comments}```\n");
    commands_of(&fenced)
        .into_iter()
        .filter(|w| w.first().map(String::as_str) == Some("fidelity"))
        .collect()
}

/// Issue 48: the quantities a study judges are part of the scene (`[output]
/// quantities`), so the README, the guide and the example's own comment judge
/// a combination on the same ones: a fidelity command on a scene that
/// declares them gives no other `--quantities`.
#[test]
fn fidelity_commands_judge_the_quantities_their_scene_declares() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut commands: Vec<Vec<String>> = readme_commands();
    let mut declaring = 0;
    for entry in std::fs::read_dir(root.join("examples")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            commands.extend(comment_commands(&std::fs::read_to_string(&path).unwrap()));
        }
    }
    for words in commands.iter().filter(|w| w[0] == "fidelity") {
        let scene = words.iter().find(|w| w.starts_with("examples/")).unwrap();
        let table: toml::Table = std::fs::read_to_string(root.join(scene))
            .unwrap()
            .parse()
            .unwrap();
        let Some(declared) = table.get("output").and_then(|o| o.get("quantities")) else {
            continue;
        };
        let declared: Vec<&str> = (declared.as_array().unwrap().iter())
            .map(|q| q.as_str().unwrap())
            .collect();
        declaring += 1;
        if let Some(k) = words.iter().position(|w| w == "--quantities") {
            let given: Vec<&str> = words[k + 1].split(',').collect();
            assert_eq!(
                given, declared,
                "{words:?} judges other quantities than {scene}"
            );
        }
    }
    // The riser's and the S-lay's commands (README, guide, comments).
    assert!(
        declaring >= 4,
        "{declaring} commands on scenes that declare quantities"
    );
}
