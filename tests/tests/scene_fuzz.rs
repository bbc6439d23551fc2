//! Seeded mutation fuzzing of the example scenes through the scene checker (what
//! `slender check` runs): every mutant must give a scene or an error, never a
//! panic and never a hang (issue 11), and no error in Rust's words: type names,
//! debug forms, a number's 309 digits (issue 27).
//!
//! The suite runs `SLENDER_FUZZ_MUTANTS` mutants (default 5000); the ignored test
//! `hundred_thousand_scene_mutants_never_panic_or_hang` runs 100 000:
//! `cargo test --release -p slender-tests --test integration -- scene_fuzz:: --ignored --nocapture`.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use slender_scene::Scene;
use slender_tests::root;
use std::path::PathBuf;
use std::sync::mpsc;
use std::time::Duration;

/// Values that probe ranges, overflow and parsing.
const NUMBERS: [&str; 14] = [
    "0",
    "-1",
    "1e308",
    "-1e308",
    "1e-300",
    "nan",
    "inf",
    "-inf",
    "1e125",
    "4294967296",
    "-0.0",
    "0.5",
    "9.2e9",
    "123456789012",
];

/// Strings that probe names, paths and CSV headers.
const STRINGS: [&str; 8] = [
    "\"\"",
    "\"../../x\"",
    "\"a,b\"",
    "\"x\\ny\"",
    "\"\u{e9}t\u{e9}\"",
    "\"none\"",
    "\"jacobi\"",
    "\"a.b\"",
];

fn examples() -> Vec<(PathBuf, String)> {
    let mut scenes: Vec<(PathBuf, String)> = std::fs::read_dir(root().join("examples"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p, text)
        })
        .collect();
    scenes.sort();
    scenes
}

/// One random change to a scene's text.
fn mutate(text: &str, rng: &mut ChaCha8Rng) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    if lines.is_empty() {
        return text.to_owned();
    }
    let i = rng.random_range(0..lines.len());
    match rng.random_range(0..6) {
        0 => lines[i] = replace_token(&lines[i], rng, true),
        1 => lines[i] = replace_token(&lines[i], rng, false),
        2 => {
            lines.remove(i);
        }
        3 => {
            let copy = lines[i].clone();
            lines.insert(i, copy);
        }
        4 => {
            let j = rng.random_range(0..lines.len());
            lines.swap(i, j);
        }
        _ => {
            let mut bytes = lines[i].clone().into_bytes();
            if !bytes.is_empty() {
                let k = rng.random_range(0..bytes.len());
                bytes[k] = b"[]{}=,.\"0-e#x "[rng.random_range(0..14)];
            }
            lines[i] = String::from_utf8_lossy(&bytes).into_owned();
        }
    }
    lines.join("\n")
}

/// Replaces a number (or a quoted string) on the line by a probing value.
fn replace_token(line: &str, rng: &mut ChaCha8Rng, number: bool) -> String {
    let spans: Vec<(usize, usize)> = if number {
        let mut spans = Vec::new();
        let b = line.as_bytes();
        let mut k = 0;
        while k < b.len() {
            if b[k].is_ascii_digit()
                && (k == 0 || !b[k - 1].is_ascii_alphanumeric() && b[k - 1] != b'_')
            {
                let start = k;
                while k < b.len() && (b[k].is_ascii_alphanumeric() || b"+-._".contains(&b[k])) {
                    k += 1;
                }
                spans.push((start, k));
            } else {
                k += 1;
            }
        }
        spans
    } else {
        let quotes: Vec<usize> = line.match_indices('"').map(|(i, _)| i).collect();
        quotes
            .chunks(2)
            .filter(|q| q.len() == 2)
            .map(|q| (q[0], q[1] + 1))
            .collect()
    };
    if spans.is_empty() {
        return line.to_owned();
    }
    let (start, end) = spans[rng.random_range(0..spans.len())];
    let value = if number {
        NUMBERS[rng.random_range(0..NUMBERS.len())]
    } else {
        STRINGS[rng.random_range(0..STRINGS.len())]
    };
    format!("{}{value}{}", &line[..start], &line[end..])
}

/// What a refusal must not say, since a scene's author does not write Rust:
/// type names, serde's terms, debug forms, a number in hundreds of digits.
fn in_rust_words(message: &str) -> Option<&'static str> {
    const WORDS: [&str; 16] = [
        "expected f32",
        "expected f64",
        "expected u8",
        "expected u16",
        "expected u32",
        "expected u64",
        "expected usize",
        "expected i32",
        "expected i64",
        "a map",
        "unit variant",
        "untagged enum",
        "identifier",
        "expected struct",
        "expected enum",
        "Some(",
    ];
    if let Some(word) = WORDS.iter().find(|w| message.contains(*w)) {
        return Some(word);
    }
    let mut run = 0;
    for c in message.chars() {
        run = if c.is_ascii_digit() { run + 1 } else { 0 };
        if run > 20 {
            return Some("a number of more than 20 digits");
        }
    }
    None
}

/// Checks `count` mutants (1 to 3 changes each) on `threads` threads; panics name
/// the seed and the mutant. Returns (scenes accepted, scenes refused).
fn fuzz(count: usize, seed: u64, threads: usize) -> (usize, usize) {
    let scenes = examples();
    let (tx, rx) = mpsc::channel();
    for worker in 0..threads {
        let tx = tx.clone();
        let scenes = scenes.clone();
        std::thread::spawn(move || {
            let mut rng = ChaCha8Rng::seed_from_u64(seed ^ worker as u64);
            for n in (worker..count).step_by(threads) {
                let (path, text) = &scenes[rng.random_range(0..scenes.len())];
                let mut mutant = text.clone();
                for _ in 0..rng.random_range(1..=3) {
                    mutant = mutate(&mutant, &mut rng);
                }
                let outcome = std::panic::catch_unwind(|| {
                    Scene::parse(path, mutant.clone()).map_err(|e| e.to_string())
                });
                if tx.send((n, path.clone(), mutant, outcome)).is_err() {
                    return;
                }
            }
        });
    }
    drop(tx);
    let (mut accepted, mut refused) = (0, 0);
    for _ in 0..count {
        // A hang guard, not a timing assertion: one check takes milliseconds.
        let (n, path, mutant, outcome) = rx
            .recv_timeout(Duration::from_secs(120))
            .unwrap_or_else(|_| panic!("a scene check did not return within 120 s (seed {seed})"));
        match outcome {
            Ok(Ok(_)) => accepted += 1,
            Ok(Err(message)) => {
                if let Some(word) = in_rust_words(&message) {
                    panic!(
                        "mutant {n} of {} (seed {seed}) is refused in Rust's words ({word}): {message}\n{mutant}",
                        path.display()
                    );
                }
                refused += 1;
            }
            Err(_) => panic!(
                "mutant {n} of {} (seed {seed}) panicked:\n{mutant}",
                path.display()
            ),
        }
    }
    (accepted, refused)
}

#[test]
fn mutated_example_scenes_give_a_scene_or_an_error_never_a_panic() {
    let count = std::env::var("SLENDER_FUZZ_MUTANTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(5000);
    let (accepted, refused) = fuzz(count, 11, 2);
    println!("{count} mutants: {accepted} accepted, {refused} refused with an error");
    assert!(
        refused > count / 10,
        "the mutations barely changed anything"
    );
}

#[test]
#[ignore = "100 000 mutants take minutes; run on demand (see the module docs)"]
fn hundred_thousand_scene_mutants_never_panic_or_hang() {
    let (accepted, refused) = fuzz(100_000, 2026, 2);
    println!("100000 mutants: {accepted} accepted, {refused} refused with an error");
}
