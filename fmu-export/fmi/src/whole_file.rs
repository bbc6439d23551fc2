//! An archive (an FMU, an SSP) written whole: under a temporary name beside
//! its place, then renamed over it. The rename replaces whatever is at the
//! place, a symbolic link included, instead of writing through it (a planted
//! `out/left.fmu -> ../victim` would have had the victim overwritten), and a
//! failed write leaves no half archive under the final name.

use std::fs::{File, OpenOptions};
use std::io;
use std::path::{Path, PathBuf};

/// The temporary file for `out` (`NAME.partial`), made new: a file or a link
/// left there by an earlier failure is removed first, not followed.
pub(crate) fn create(out: &Path) -> io::Result<(File, PathBuf)> {
    let mut name = out.file_name().unwrap_or_default().to_os_string();
    name.push(".partial");
    let partial = out.with_file_name(name);
    match std::fs::remove_file(&partial) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => return Err(e),
        _ => {}
    }
    let file = OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&partial)?;
    Ok((file, partial))
}

/// Puts the finished `partial` in its place `out`.
pub(crate) fn finish(partial: &Path, out: &Path) -> io::Result<()> {
    std::fs::rename(partial, out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    #[test]
    fn a_link_at_the_place_is_replaced_not_written_through() {
        let dir = tempfile::tempdir().unwrap();
        let victim = dir.path().join("victim.txt");
        std::fs::write(&victim, "keep").unwrap();
        let out = dir.path().join("left.fmu");
        std::os::unix::fs::symlink(&victim, &out).unwrap();
        // A link planted at the temporary name as well.
        std::os::unix::fs::symlink(&victim, dir.path().join("left.fmu.partial")).unwrap();
        let (mut file, partial) = create(&out).unwrap();
        file.write_all(b"archive").unwrap();
        finish(&partial, &out).unwrap();
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep");
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "archive");
        assert!(
            !std::fs::symlink_metadata(&out)
                .unwrap()
                .file_type()
                .is_symlink()
        );
    }
}
