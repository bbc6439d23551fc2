//! `slender study` and `slender fidelity` resume (issue 28): a study killed
//! part-way keeps the runs it finished in its results folder (`runs/`), and
//! the same command again reads them back instead of running them; a changed
//! scene or `--fresh` runs everything anew.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use crate::common;
use common::{slender, text};

/// A study of seven runs on the truncation scene (a copy in `dir`).
fn study_args(scene: &Path, out: &Path) -> Vec<String> {
    [
        "study",
        scene.to_str().unwrap(),
        "--vary",
        "step=0.02,0.01,0.005",
        "--vary",
        "elements=10,20,40,80",
        "--duration",
        "10",
        "--out",
        out.to_str().unwrap(),
    ]
    .map(String::from)
    .to_vec()
}

fn run(args: &[String]) -> std::process::Output {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    slender(&args)
}

/// The study table without its cost columns (which a run timed again changes).
fn without_costs(csv: &Path) -> Vec<String> {
    std::fs::read_to_string(csv)
        .unwrap()
        .lines()
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            [&fields[..8], &fields[10..]].concat().join(",")
        })
        .collect()
}

/// The kept runs in a results folder.
fn kept(out: &Path) -> usize {
    std::fs::read_dir(out.join("runs")).map_or(0, |d| {
        d.flatten()
            .filter(|e| e.path().extension().is_some_and(|x| x == "toml"))
            .count()
    })
}

/// Lines of progress that say their run was read back.
fn reused(stdout: &[u8]) -> usize {
    text(stdout)
        .lines()
        .filter(|l| l.contains("(reused)"))
        .count()
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slender-resume-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
#[cfg(unix)]
fn a_killed_study_resumes_with_the_runs_it_finished() {
    let dir = scratch("study");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let scene = dir.join("truncation_study.toml");
    std::fs::copy(root.join("examples/truncation_study.toml"), &scene).unwrap();
    // The same study whole, in a folder of its own: what the resumed one must give.
    let whole = run(&study_args(&scene, &dir.join("whole")));
    assert!(whole.status.success(), "{}", text(&whole.stderr));
    assert_eq!(reused(&whole.stdout), 0);

    // Killed (SIGKILL: no clean-up) once it has kept its first run.
    let out = dir.join("o");
    let args = study_args(&scene, &out);
    let mut child = Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(&args)
        .current_dir(&root)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut polls = 0;
    while kept(&out) == 0 && child.try_wait().unwrap().is_none() {
        polls += 1;
        assert!(polls < 60_000, "no run kept");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let finished = kept(&out);
    eprintln!("{finished} of 7 runs kept when killed");
    assert!(finished >= 1);
    assert!(!out.join("study.csv").exists() || finished == 7);

    let resumed = run(&args);
    assert!(resumed.status.success(), "{}", text(&resumed.stderr));
    assert_eq!(
        reused(&resumed.stdout),
        finished,
        "{}",
        text(&resumed.stdout)
    );
    assert_eq!(kept(&out), 7);
    assert_eq!(
        without_costs(&out.join("study.csv")),
        without_costs(&dir.join("whole/study.csv"))
    );

    // Again: every run read back, the table the same to the last byte.
    let table = std::fs::read_to_string(out.join("study.csv")).unwrap();
    let again = run(&args);
    assert_eq!(reused(&again.stdout), 7, "{}", text(&again.stdout));
    assert_eq!(
        std::fs::read_to_string(out.join("study.csv")).unwrap(),
        table
    );

    // Another duration, a changed scene, or --fresh: every run anew.
    let mut longer = args.clone();
    longer[7] = "5".into();
    assert_eq!(reused(&run(&longer).stdout), 0);
    let mut text_of_scene = std::fs::read_to_string(&scene).unwrap();
    text_of_scene.push_str("\n# changed\n");
    std::fs::write(&scene, text_of_scene).unwrap();
    assert_eq!(reused(&run(&args).stdout), 0);
    assert_eq!(reused(&run(&args).stdout), 7);
    let mut fresh = args.clone();
    fresh.push("--fresh".into());
    assert_eq!(reused(&run(&fresh).stdout), 0);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_fidelity_study_reads_back_its_finished_runs_but_not_failed_ones() {
    let dir = scratch("fidelity");
    let out = dir.join("o").to_str().unwrap().to_owned();
    let args = [
        "fidelity",
        "examples/structure_hanging_pipe.toml",
        // span needs a static start, which this scene has not: a failed run.
        "--section",
        "middle=nonlinear:5,span",
        "--duration",
        "1",
        "--out",
        &out,
    ];
    let first = slender(&args);
    assert_eq!(first.status.code(), Some(1), "{}", text(&first.stderr));
    assert_eq!(reused(&first.stdout), 0);
    let table = std::fs::read_to_string(dir.join("o/fidelity.csv")).unwrap();
    let again = slender(&args);
    assert_eq!(again.status.code(), Some(1));
    let progress = text(&again.stdout);
    assert!(progress.contains("reference (monolithic): ") && progress.contains("(reused)"));
    // The reference, its finer level (its error's estimate) and the
    // partition read back; the failed span run again.
    assert_eq!(reused(&again.stdout), 3, "{progress}");
    assert!(progress.contains("middle=span: FAILED"), "{progress}");
    assert_eq!(
        std::fs::read_to_string(dir.join("o/fidelity.csv")).unwrap(),
        table
    );
    std::fs::remove_dir_all(dir).unwrap();
}

/// A second fidelity study asked differently into the same folder is refused
/// (it overwrote the first one's tables and figures, issue 49 #3), naming
/// both requests and `--out`; the same request resumes, and `--fresh`
/// replaces the folder's study.
#[test]
fn a_different_study_into_the_same_folder_is_refused_unless_fresh() {
    let dir = scratch("another");
    let out = dir.join("o").to_str().unwrap().to_owned();
    let asked = |choices: &str, fresh: bool| {
        let mut args = vec![
            "fidelity",
            "examples/structure_hanging_pipe.toml",
            "--section",
            choices,
            "--duration",
            "1",
            "--out",
            &out,
        ];
        if fresh {
            args.push("--fresh");
        }
        slender(&args)
    };
    let first = asked("middle=nonlinear:5", false);
    assert!(first.status.success(), "{}", text(&first.stderr));
    let table = std::fs::read_to_string(dir.join("o/fidelity.csv")).unwrap();
    let other = asked("middle=nonlinear:3", false);
    assert_eq!(other.status.code(), Some(2), "{}", text(&other.stderr));
    let message = text(&other.stderr);
    assert!(
        message.contains("holds another study") && message.contains("--out"),
        "{message}"
    );
    // Both requests in the command line's words, not the plan's Debug.
    let words = |choice: &str| {
        format!(
            "slender fidelity examples/structure_hanging_pipe.toml --section middle={choice} --tolerance 0.01 --reference estimate --duration 1"
        )
    };
    assert!(
        message.contains(&words("nonlinear:5")) && message.contains(&words("nonlinear:3")),
        "{message}"
    );
    assert!(!message.contains("FidelityPlan"), "{message}");
    assert_eq!(
        std::fs::read_to_string(dir.join("o/request.txt")).unwrap(),
        words("nonlinear:5") + "\n"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("o/fidelity.csv")).unwrap(),
        table
    );
    assert!(asked("middle=nonlinear:5", false).status.success());
    let replaced = asked("middle=nonlinear:3", true);
    assert!(replaced.status.success(), "{}", text(&replaced.stderr));
    assert_ne!(
        std::fs::read_to_string(dir.join("o/fidelity.csv")).unwrap(),
        table
    );
    std::fs::remove_dir_all(dir).unwrap();
}
