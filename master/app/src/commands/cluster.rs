//! The Slurm scripts of a study split into shards (`uq`, `cases`): a job
//! array of one shard per task, and `submit.sh`, which submits it and the
//! merge that runs once every shard has succeeded.

use super::{CliError, report_written};
use std::path::{Path, PathBuf};

/// A sharded study as Slurm runs it.
pub(super) struct ArrayJob<'a> {
    /// The subcommand (`uq`, `cases`): the jobs' names and the array script's.
    pub command: &'a str,
    pub scene: &'a Path,
    /// The results folder, where the scripts and the logs go.
    pub dir: &'a Path,
    /// The subcommand's other arguments, each already a shell word.
    pub args: Vec<String>,
    pub jobs: usize,
    pub shards: usize,
}

/// Writes `<command>-shards.sbatch` and `submit.sh` into the job's folder.
pub(super) fn slurm_scripts(job: &ArrayJob) -> Result<(), CliError> {
    let exe = std::env::current_exe().map_err(CliError::failure)?;
    let scene = std::fs::canonicalize(job.scene)
        .map_err(|e| CliError::input(format!("{}: {e}", job.scene.display())))?;
    let out = std::fs::canonicalize(job.dir).map_err(CliError::failure)?;
    let mut common = format!("--out {:?}", out.display().to_string());
    for a in &job.args {
        common += &format!(" {a}");
    }
    let (name, n, jobs, o) = (job.command, job.shards, job.jobs, out.display());
    let command = format!(
        "{} {name} {} {common}",
        shell_word(&exe.display().to_string()),
        shell_word(&scene.display().to_string())
    );
    // The merge's command goes inside the single quotes of `--wrap '...'`.
    let wrapped = command.replace('\'', "'\\''");
    let array = format!(
        "#!/bin/sh\n#SBATCH --job-name=slender-{name}\n#SBATCH --array=1-{n}\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task={jobs}\n#SBATCH --output={o}/shard-%a.log\n{command} --jobs {jobs} --shard \"$SLURM_ARRAY_TASK_ID/{n}\"\n",
    );
    let submit = format!(
        "#!/bin/sh\n# Submits the {n} shards as a job array, then the merge once all succeed.\nset -e\njob=$(sbatch --parsable {o}/{name}-shards.sbatch)\nsbatch --dependency=afterok:\"$job\" --job-name=slender-{name}-merge --output={o}/merge.log --wrap '{wrapped} --jobs {jobs} --merge'\n",
    );
    let write = |file: &str, text: &str| -> Result<PathBuf, CliError> {
        let path = job.dir.join(file);
        slender_app::whole::write(&path, text)
            .map_err(|e| CliError::failure(format!("{}: {e}", path.display())))?;
        Ok(path)
    };
    let files = vec![
        write(&format!("{name}-shards.sbatch"), &array)?,
        write("submit.sh", &submit)?,
    ];
    report_written(&files);
    println!("submit with: sh {}", out.join("submit.sh").display());
    Ok(())
}

/// `text` as one word of a POSIX shell command: in double quotes, with the
/// characters the shell reads there (`"`, `\`, `$`, `` ` ``) escaped.
pub(super) fn shell_word(text: &str) -> String {
    let mut word = String::from('"');
    for c in text.chars() {
        if matches!(c, '"' | '\\' | '$' | '`') {
            word.push('\\');
        }
        word.push(c);
    }
    word.push('"');
    word
}

/// The `shard-K-of-N` folders a sharded study wrote under `dir` (the study's
/// `command`, `uq` or `cases`, names the call that makes them when there are
/// none).
pub(super) fn shard_folders(dir: &Path, command: &str) -> Result<Vec<PathBuf>, CliError> {
    let entries =
        std::fs::read_dir(dir).map_err(|e| CliError::input(format!("{}: {e}", dir.display())))?;
    let folders: Vec<PathBuf> = (entries.flatten())
        .filter(|e| e.file_name().to_string_lossy().starts_with("shard-"))
        .map(|e| e.path())
        .collect();
    if folders.is_empty() {
        return Err(CliError::input(format!(
            "{}: no shard-K-of-N folders to merge (run `slender {command} SCENE --shard K/N` first)",
            dir.display()
        )));
    }
    Ok(folders)
}
