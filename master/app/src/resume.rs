//! Finished runs of a study kept in its results folder (`runs/`), so that a
//! `study` or `fidelity` stopped part-way (Ctrl-C, a killed job, a crash)
//! resumes where it stopped: run again with the same scene and options, each
//! run already finished is read back instead of run again, as `uq` reuses its
//! `runs.csv`. A run is kept only when it finished without error (a failed or
//! interrupted one is run again), under a key made of the scene file's text,
//! the options that shape a run (duration, repeats, cost units, reference) and
//! the run's own settings, so a changed scene or option runs everything anew.
//! Its file (TOML, which keeps NaN and infinities as JSON does not) is written
//! whole (`whole.rs`): a run killed while being kept leaves nothing half-read.

use crate::AppError;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::path::{Path, PathBuf};

/// The kept runs of one study.
pub struct Kept {
    dir: PathBuf,
    /// The hash of the scene's text and the study's options.
    study: u64,
    /// The study as asked, in words, and whether it may replace another
    /// study the folder holds (`--fresh`): see [`Kept::claim`].
    request: Option<(String, bool)>,
}

/// What a kept run's file holds: its settings in words (to tell a hash
/// collision from a match) and its outcome.
#[derive(Serialize, serde::Deserialize)]
struct Entry<T> {
    run: String,
    outcome: T,
}

impl Kept {
    /// The kept runs in `folder/runs` of the study of `scene` with `options`
    /// (the options that shape every run, in words); `Err` when the scene
    /// cannot be read or the folder made.
    pub fn new(folder: &Path, scene: &Path, options: &str) -> Result<Kept, AppError> {
        let text = std::fs::read(scene).map_err(|e| AppError::files(scene, e))?;
        let dir = folder.join("runs");
        std::fs::create_dir_all(&dir).map_err(|e| AppError::files(&dir, e))?;
        let study = fnv1a(fnv1a(FNV_OFFSET, &text), options.as_bytes());
        Ok(Kept {
            dir,
            study,
            request: None,
        })
    }

    /// The same, for the study asked as `request` (in words; `fresh`: it may
    /// replace another study the folder holds).
    pub fn asking(self, request: String, fresh: bool) -> Kept {
        Kept {
            request: Some((request, fresh)),
            ..self
        }
    }

    /// Claims the folder for the study asked, once it is known to be valid
    /// (called before its first run): a folder holding another study asked
    /// differently is refused unless `fresh`, rather than have its tables and
    /// figures overwritten; `request.txt` then says what it holds.
    pub fn claim(&self) -> Result<(), AppError> {
        let Some((request, fresh)) = &self.request else {
            return Ok(());
        };
        let folder = self.dir.parent().unwrap_or(Path::new("."));
        let asked = folder.join("request.txt");
        if let Ok(held) = std::fs::read_to_string(&asked)
            && held.trim_end() != request
            && !fresh
        {
            return Err(AppError::Asked(format!(
                "{} holds another study, asked as\n  {}\nthis one is asked as\n  {request}\ngive --out to keep both, or --fresh to replace it",
                folder.display(),
                held.trim_end()
            )));
        }
        crate::whole::write(&asked, format!("{request}\n")).map_err(|e| AppError::files(&asked, e))
    }

    fn file(&self, run: &str) -> PathBuf {
        self.dir
            .join(format!("{:016x}.toml", fnv1a(self.study, run.as_bytes())))
    }

    /// The outcome kept for `run` (its settings in words), if any.
    pub fn get<T: DeserializeOwned>(&self, run: &str) -> Option<T> {
        let text = std::fs::read_to_string(self.file(run)).ok()?;
        let entry: Entry<T> = toml::from_str(&text).ok()?;
        (entry.run == run).then_some(entry.outcome)
    }

    /// Keeps `outcome` for `run`; `Err` says why it could not be written.
    pub fn put<T: Serialize>(&self, run: &str, outcome: &T) -> Result<(), AppError> {
        let entry = Entry {
            run: run.to_owned(),
            outcome,
        };
        let file = self.file(run);
        let text = toml::to_string(&entry).map_err(|e| AppError::files(&file, e))?;
        crate::whole::write(&file, text).map_err(|e| AppError::files(&file, e))
    }
}

/// A run's outcome, read back or made now.
pub struct Fetched<T> {
    /// The outcome.
    pub outcome: T,
    /// Read back from an earlier study, not run now.
    pub reused: bool,
    /// What the progress line adds: " (reused)", or why it was not kept.
    pub note: String,
}

/// The outcome of `run` read back from `kept` when it is there, else made by
/// `make` and kept when `keep` says it may be (a run finished without error).
pub fn run_or_reuse<T: Serialize + DeserializeOwned>(
    kept: Option<&Kept>,
    run: &str,
    keep: impl Fn(&T) -> bool,
    make: impl FnOnce() -> T,
) -> Fetched<T> {
    let made = |outcome: T, note: String| Fetched {
        outcome,
        reused: false,
        note,
    };
    let Some(kept) = kept else {
        return made(make(), String::new());
    };
    if let Some(outcome) = kept.get(run) {
        return Fetched {
            outcome,
            reused: true,
            note: " (reused)".to_owned(),
        };
    }
    let outcome = make();
    let note = match keep(&outcome).then(|| kept.put(run, &outcome)) {
        Some(Err(e)) => format!(" (not kept to resume: {e})"),
        _ => String::new(),
    };
    made(outcome, note)
}

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;

/// 64-bit FNV-1a of `bytes` from `hash`: stable across builds and platforms
/// (the standard library's hasher is not), which a key kept on disk needs.
fn fnv1a(mut hash: u64, bytes: &[u8]) -> u64 {
    for b in bytes {
        hash ^= u64::from(*b);
        hash = hash.wrapping_mul(0x0100_0000_01b3);
    }
    hash
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize, serde::Deserialize)]
    struct Outcome {
        values: Vec<f64>,
        note: Option<String>,
        count: Option<u64>,
    }

    #[test]
    fn a_run_is_read_back_only_for_the_same_scene_options_and_settings() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("s.toml");
        std::fs::write(&scene, "a = 1").unwrap();
        let kept = Kept::new(dir.path(), &scene, "duration 10").unwrap();
        kept.put("step=0.01", &vec![1.0, 2.0]).unwrap();
        assert_eq!(kept.get::<Vec<f64>>("step=0.01"), Some(vec![1.0, 2.0]));
        // Non-finite values and absent options come back as they were.
        let odd = (vec![f64::INFINITY, -0.5], None::<String>, Some(3u64));
        kept.put(
            "odd",
            &Outcome {
                values: odd.0.clone(),
                note: odd.1.clone(),
                count: odd.2,
            },
        )
        .unwrap();
        let back: Outcome = kept.get("odd").unwrap();
        assert_eq!((back.values, back.note, back.count), odd);
        kept.put(
            "nan",
            &Outcome {
                values: vec![f64::NAN],
                note: None,
                count: None,
            },
        )
        .unwrap();
        assert!(kept.get::<Outcome>("nan").unwrap().values[0].is_nan());
        assert_eq!(kept.get::<Vec<f64>>("step=0.02"), None);
        let other_options = Kept::new(dir.path(), &scene, "duration 20").unwrap();
        assert_eq!(other_options.get::<Vec<f64>>("step=0.01"), None);
        std::fs::write(&scene, "a = 2").unwrap();
        let changed = Kept::new(dir.path(), &scene, "duration 10").unwrap();
        assert_eq!(changed.get::<Vec<f64>>("step=0.01"), None);
        // A run kept only when it may be, read back the second time.
        let made = std::cell::Cell::new(0);
        let make = || {
            made.set(made.get() + 1);
            vec![made.get() as f64]
        };
        let first = run_or_reuse(Some(&kept), "new", |_| true, make);
        assert_eq!((first.outcome, first.reused), (vec![1.0], false));
        let again = run_or_reuse(Some(&kept), "new", |_| true, make);
        assert_eq!((again.outcome, again.reused), (vec![1.0], true));
        assert_eq!(again.note, " (reused)");
        run_or_reuse(Some(&kept), "failed", |_| false, make);
        let second = run_or_reuse(Some(&kept), "failed", |_| false, make);
        assert_eq!((second.outcome, second.reused), (vec![3.0], false));
        // The FNV-1a reference value of "a" (64 bit).
        assert_eq!(fnv1a(FNV_OFFSET, b"a"), 0xaf63_dc4c_8601_ec8c);
    }
}
