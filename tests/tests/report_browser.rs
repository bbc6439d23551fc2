//! The HTML reports (issue 28) in a real headless browser (Debian's chromium):
//! a run's and a study's `report.html` render with no console error, hold
//! their tables, inline figures and tooltips, sort a table when a header is
//! clicked, and make a screenshot far from blank. A page with a script error
//! is run through the same check first, to show the check can fail.
//!
//! Needs chromium (`./scripts/test.sh` installs it as root); ignored in a plain
//! `cargo test`, run by test.sh with `--ignored`.

use slender_tests::root;
use std::path::Path;
use std::process::Command;

const CHROMIUM: &str = "/usr/bin/chromium";

/// Chromium headless on `page` with `extra` arguments: (stdout, console lines).
fn chromium(page: &Path, extra: &[&str]) -> (String, Vec<String>) {
    let out = Command::new(CHROMIUM)
        .args([
            "--headless=new",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
        ])
        .args(["--enable-logging=stderr", "--v=0"])
        .args(extra)
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("chromium runs");
    let console = String::from_utf8_lossy(&out.stderr)
        .lines()
        .filter(|l| l.contains(":CONSOLE"))
        .map(String::from)
        .collect();
    (String::from_utf8_lossy(&out.stdout).into_owned(), console)
}

fn slender(args: &[&str]) {
    let out = Command::new(root().join("target/release/slender"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("slender runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The size of a screenshot of `page` (PNG bytes).
fn screenshot(page: &Path, png: &Path) -> u64 {
    let shot = format!("--screenshot={}", png.display());
    chromium(page, &[&shot, "--window-size=1400,2000"]);
    std::fs::metadata(png).expect("a screenshot").len()
}

#[test]
#[ignore = "needs chromium: ./scripts/test.sh installs it (as root)"]
fn reports_render_in_a_headless_browser_with_their_tables_figures_and_tooltips() {
    assert!(
        Path::new(CHROMIUM).exists(),
        "no {CHROMIUM}: apt-get install chromium"
    );
    let dir = tempfile::tempdir().unwrap();
    let (study, run) = (dir.path().join("study"), dir.path().join("run"));
    let s = study.to_str().unwrap();
    slender(&[
        "study",
        "examples/b3_force_displacement.toml",
        "--vary",
        "step=0.001,0.002,0.005,0.01",
        "--out",
        s,
    ]);
    slender(&[
        "run",
        "examples/b1_two_masses.toml",
        "--out",
        run.to_str().unwrap(),
    ]);

    // The check sees a script error when there is one.
    let bad = dir.path().join("bad.html");
    std::fs::write(
        &bad,
        "<html><body><script>undefinedFunction();</script></body></html>",
    )
    .unwrap();
    let (_, console) = chromium(&bad, &["--dump-dom"]);
    assert!(
        console
            .iter()
            .any(|l| l.contains("Uncaught ReferenceError")),
        "{console:?}"
    );

    let page = study.join("report.html");
    let (dom, console) = chromium(&page, &["--dump-dom"]);
    assert!(console.is_empty(), "console: {console:?}");
    assert!(
        dom.contains("Made by <code>slender study examples/b3_force_displacement.toml"),
        "no command"
    );
    assert_eq!(
        dom.matches("<svg").count(),
        2,
        "study.svg and error_cost.svg inline"
    );
    assert_eq!(dom.matches("<tr>").count(), 5, "a header and four runs");
    // Every run is drawn, each with a tooltip: B3's worst error is its `exact`
    // indicator's, against the analytic solution, so the reference run has
    // one too.
    let hover = &dom[dom.find("class=\"hover\"").expect("a hover layer")..];
    assert_eq!(hover.matches("<title>").count(), 4);
    assert!(
        hover.contains("step=0.002 (error"),
        "{}",
        &hover[..300.min(hover.len())]
    );
    assert!(
        !dom.contains("src=\"http") && !dom.contains("href=\"http"),
        "a report fetches nothing"
    );

    sorts_by_cost_on_a_click(&page, dir.path());
    run_page_renders(&run, &page, dir.path());
}

/// The run's page: outcome and units tables, its one plot; screenshots of it
/// and of the study's `page` against a blank page's.
fn run_page_renders(run: &Path, page: &Path, dir: &Path) {
    let run_page = run.join("report.html");
    let (dom, console) = chromium(&run_page, &["--dump-dom"]);
    assert!(console.is_empty(), "console: {console:?}");
    assert!(
        dom.contains("<td>completed</td>") && dom.contains("<td>left.velocity</td><td>m/s</td>")
    );
    assert_eq!(dom.matches("<svg").count(), 1, "the run's one plot inline");

    // Screenshots: the reports against a blank page.
    let blank = dir.join("blank.html");
    std::fs::write(&blank, "<html><body></body></html>").unwrap();
    let empty = screenshot(&blank, &dir.join("blank.png"));
    let full = screenshot(page, &dir.join("study.png"));
    let single = screenshot(&run_page, &dir.join("run.png"));
    println!("screenshots: blank {empty} B, study {full} B, run {single} B");
    assert!(
        full > 5 * empty && single > 5 * empty,
        "a report's screenshot is nearly blank"
    );
}

/// Clicking the study table's cost header sorts its runs, cheapest first;
/// a second click, dearest first. Judged on the cost cells themselves: the
/// runs' costs are wall-clock times, so which step is cheapest may change
/// from one run to the next.
fn sorts_by_cost_on_a_click(page: &Path, dir: &Path) {
    let html = std::fs::read_to_string(page).unwrap();
    // The header by its words (the columns before it vary with the indicators).
    let click =
        "[...document.querySelectorAll('th')].find(h => h.textContent.startsWith('cost')).click();";
    for (clicks, ascending) in [(1, true), (2, false)] {
        let clicked = dir.join(format!("clicked{clicks}.html"));
        let script = format!("<script>{}</script></body>", click.repeat(clicks));
        std::fs::write(&clicked, html.replace("</body>", &script)).unwrap();
        let (dom, console) = chromium(&clicked, &["--dump-dom"]);
        assert!(console.is_empty(), "console: {console:?}");
        let (steps, costs) = steps_and_costs(&dom);
        let mut sorted_steps = steps.clone();
        sorted_steps.sort();
        assert_eq!(
            sorted_steps,
            ["0.001", "0.002", "0.005", "0.01"],
            "{steps:?}"
        );
        let in_order = costs
            .windows(2)
            .all(|w| (w[0] <= w[1]) == ascending || w[0] == w[1]);
        assert!(
            in_order,
            "{clicks} click(s): costs {costs:?} (steps {steps:?})"
        );
    }
}

/// The study table's runs in the page's order: each row's step and cost.
fn steps_and_costs(dom: &str) -> (Vec<String>, Vec<f64>) {
    let cells = |row: &str| -> Vec<String> {
        row.split("<t")
            .skip(1)
            .filter_map(|c| c.split_once('>').map(|(_, rest)| rest))
            .map(|c| c.split('<').next().unwrap_or_default().to_string())
            .collect()
    };
    let header = dom
        .split("<tr>")
        .skip(1)
        .find(|r| r.starts_with("<th"))
        .expect("a header row");
    let cost = cells(header)
        .iter()
        .position(|h| h.starts_with("cost"))
        .expect("a cost column");
    dom.split("<tr><td>step</td>")
        .skip(1)
        .map(|r| {
            let row = cells(&format!(
                "<td>step</td>{}",
                r.split("</tr>").next().unwrap()
            ));
            (row[1].clone(), row[cost].parse::<f64>().expect("a cost"))
        })
        .unzip()
}
