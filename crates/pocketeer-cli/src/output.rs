//! Writing output files so that a failed run never leaves a half-written file in place of a
//! good one (write a temporary file beside the target, then rename it over the target), and
//! refusing outputs that would overwrite an input or each other.

use std::io::Write;
use std::path::{Path, PathBuf};

/// True for the path `-`: standard output.
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// The file name of `p` alone, for headers and titles.
pub fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// How a message names the output: its path, or `standard output`.
pub fn describe(path: &Path) -> String {
    if is_stdout(path) {
        "standard output".to_string()
    } else {
        path.display().to_string()
    }
}

/// Writes `bytes` to `path`, or to standard output when `path` is `-`.
pub fn write_output(path: &Path, bytes: &[u8]) -> Result<(), String> {
    if is_stdout(path) {
        let mut out = std::io::stdout().lock();
        return out
            .write_all(bytes)
            .and_then(|()| out.flush())
            .or_else(|e| {
                // A reader that stops early (`| head`) is not an error.
                if e.kind() == std::io::ErrorKind::BrokenPipe {
                    Ok(())
                } else {
                    Err(e)
                }
            })
            .map_err(|e| format!("cannot write to standard output: {e}"));
    }
    write_atomic(path, bytes)
}

/// True when `a` and `b` name one file: the same file on disk (by identity, so hard links and
/// other spellings of the path count) or, where either does not exist yet, the same absolute
/// path.
pub fn same_file(a: &Path, b: &Path) -> bool {
    if a.exists() && b.exists() {
        return identical(a, b);
    }
    absolute(a) == absolute(b)
}

/// Whether two existing paths lead to one file. On Unix by device and inode, read without
/// opening either: opening a named pipe waits for a writer, which would hang the run.
#[cfg(unix)]
fn identical(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(a), Ok(b)) => (a.dev(), a.ino()) == (b.dev(), b.ino()),
        _ => false,
    }
}

/// Whether two existing paths lead to one file.
#[cfg(not(unix))]
fn identical(a: &Path, b: &Path) -> bool {
    same_file::is_same_file(a, b).unwrap_or(false)
}

/// `p` made absolute with its folder resolved (links and `..` followed) where it exists.
fn absolute(p: &Path) -> PathBuf {
    let abs = std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    match (abs.parent(), abs.file_name()) {
        (Some(dir), Some(name)) => dir.canonicalize().map_or(abs.clone(), |d| d.join(name)),
        _ => abs,
    }
}

/// Refuses a run whose outputs (flag and path) would overwrite one of its `inputs` or each
/// other; `-` (standard output) may be named once.
pub fn guard(inputs: &[&Path], outputs: &[(&str, &Path)]) -> Result<(), String> {
    for (k, &(flag, out)) in outputs.iter().enumerate() {
        if is_stdout(out) {
            if outputs[..k].iter().any(|&(_, o)| is_stdout(o)) {
                return Err(format!("{flag} -: only one output can go to standard output"));
            }
            continue;
        }
        if let Some(input) = inputs.iter().find(|i| same_file(i, out)) {
            return Err(format!(
                "{flag} {} is the file being read ({}): refusing to overwrite it; choose another output file",
                out.display(),
                input.display()
            ));
        }
        if let Some(&(other, _)) = outputs[..k]
            .iter()
            .find(|&&(_, o)| !is_stdout(o) && same_file(o, out))
        {
            return Err(format!(
                "{other} and {flag} both name {}: give each output its own file",
                out.display()
            ));
        }
    }
    Ok(())
}

/// Writes `bytes` to `path` so that other programs and a failed run see the old file or the
/// whole new one, never part of it (see [`Destination`] for what that means for each kind of
/// file). The error names the file.
///
/// There is no `fsync` before the rename. What we write is derived from the drawing and the
/// flags and is made again by running again; waiting for the disk cost 1.3 ms of a 3.5 ms
/// offset of a 75-hole plate (more than half the run's own work). Linux's ext4 (by its
/// default `auto_da_alloc`) and btrfs write a file's data before a rename that replaces
/// another file is committed, which covers the case that matters: a good old program.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let result = match Destination::of(path) {
        Destination::Replace { file, permissions } => replace(&file, bytes, permissions),
        Destination::InPlace => std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .and_then(|mut f| f.write_all(bytes)),
    };
    result.map_err(|e| format!("{}: cannot write: {e}", path.display()))
}

/// How an output path is written.
#[derive(Debug, PartialEq)]
enum Destination {
    /// A regular file, or none yet: a temporary file written beside `file` and renamed over
    /// it, with the old file's `permissions` where there was one. A symbolic link leads to
    /// its file, which is the one replaced: the link stays a link.
    Replace {
        file: PathBuf,
        permissions: Option<std::fs::Permissions>,
    },
    /// Anything else that exists (a device such as `/dev/null`, a named pipe): written
    /// through, as it is. It cannot be replaced and must not be: a file renamed over
    /// `/dev/null` by a run with the rights to do so would break the whole system.
    InPlace,
}

impl Destination {
    /// How `path` is written (see the variants).
    fn of(path: &Path) -> Destination {
        match std::fs::metadata(path) {
            Ok(m) if m.is_file() => {
                let link = std::fs::symlink_metadata(path).is_ok_and(|l| l.file_type().is_symlink());
                Destination::Replace {
                    // The file a link leads to; the path itself where that cannot be settled.
                    file: match link {
                        true => std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()),
                        false => path.to_path_buf(),
                    },
                    permissions: Some(m.permissions()),
                }
            }
            // A folder: the rename fails with a message that says so.
            Ok(m) if m.is_dir() => Destination::Replace {
                file: path.to_path_buf(),
                permissions: None,
            },
            Ok(_) => Destination::InPlace,
            Err(_) => Destination::Replace {
                file: dangling_link_target(path),
                permissions: None,
            },
        }
    }
}

/// Where a path that leads to no file yet should be made: the end of its chain of symbolic
/// links (as a shell's `>` does), or the path itself.
fn dangling_link_target(path: &Path) -> PathBuf {
    let mut p = path.to_path_buf();
    // As many links as the kernel follows (Linux's MAXSYMLINKS); a loop ends there.
    for _ in 0..40 {
        let Ok(to) = std::fs::read_link(&p) else {
            return p;
        };
        p = match p.parent() {
            Some(dir) if to.is_relative() => dir.join(to),
            _ => to,
        };
    }
    path.to_path_buf()
}

/// Writes `bytes` to a temporary file beside `file`, gives it `permissions`, and renames it
/// over `file`; the temporary file is removed when any step fails.
fn replace(file: &Path, bytes: &[u8], permissions: Option<std::fs::Permissions>) -> std::io::Result<()> {
    let dir = match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    let name = file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        if let Some(p) = permissions {
            f.set_permissions(p)?;
        }
        std::fs::rename(&tmp, file)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_the_file_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.txt");
        std::fs::write(&target, "old").unwrap();
        write_atomic(&target, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    #[cfg(unix)]
    fn a_link_stays_a_link_and_its_file_is_replaced_with_its_permissions() {
        use std::os::unix::fs::{symlink, PermissionsExt};
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("job42.nc");
        std::fs::write(&file, "old").unwrap();
        std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o640)).unwrap();
        let link = dir.path().join("current.nc");
        symlink("job42.nc", &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "new");
        let mode = std::fs::metadata(&file).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o640);
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
        // A link to no file yet: the file is made where it leads.
        let dangling = dir.path().join("next.nc");
        symlink("sub/next-job.nc", &dangling).unwrap();
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        write_atomic(&dangling, b"next").unwrap();
        assert!(std::fs::symlink_metadata(&dangling)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(
            std::fs::read_to_string(dir.path().join("sub/next-job.nc")).unwrap(),
            "next"
        );
    }

    #[test]
    #[cfg(unix)]
    fn devices_are_written_through_never_replaced() {
        // Deciding only: a regression here must not replace the machine's /dev/null.
        assert_eq!(Destination::of(Path::new("/dev/null")), Destination::InPlace);
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.nc");
        assert!(matches!(
            Destination::of(&file),
            Destination::Replace {
                permissions: None,
                ..
            }
        ));
    }

    #[test]
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    fn a_named_pipe_is_written_through_and_guarding_it_does_not_wait_for_a_writer() {
        use std::io::Read;
        let dir = tempfile::tempdir().unwrap();
        let pipe = dir.path().join("to-the-machine");
        let c = std::ffi::CString::new(pipe.to_str().unwrap()).unwrap();
        // SAFETY: a NUL-terminated path that lives through the call.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let drawing = dir.path().join("part.dxf");
        std::fs::write(&drawing, "0\nEOF\n").unwrap();
        // Opening the pipe to compare it would wait for a writer: on another thread, with a
        // time limit, so that such a regression fails instead of hanging.
        let (tx, rx) = std::sync::mpsc::channel();
        let (d, p) = (drawing.clone(), pipe.clone());
        std::thread::spawn(move || tx.send(guard(&[&d], &[("-o", &p)]).is_ok()));
        let guarded = rx.recv_timeout(std::time::Duration::from_secs(10));
        assert_eq!(guarded, Ok(true), "guarding a named pipe waited for a writer");
        let reader = {
            let pipe = pipe.clone();
            std::thread::spawn(move || {
                let mut text = String::new();
                std::fs::File::open(&pipe)
                    .unwrap()
                    .read_to_string(&mut text)
                    .unwrap();
                text
            })
        };
        write_atomic(&pipe, b"G0 X0\n").unwrap();
        // Before waiting for the reader, which waits for ever on a pipe replaced by a file.
        assert!(!std::fs::metadata(&pipe).unwrap().is_file());
        assert_eq!(reader.join().unwrap(), "G0 X0\n");
    }

    #[test]
    fn outputs_may_not_overwrite_inputs_or_each_other() {
        let dir = tempfile::tempdir().unwrap();
        let drawing = dir.path().join("plate.dxf");
        std::fs::write(&drawing, "0\nEOF\n").unwrap();
        let link = dir.path().join("same.dxf");
        std::fs::hard_link(&drawing, &link).unwrap();
        let other = dir.path().join("sub/../plate.dxf");
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        for out in [&drawing, &link, &other] {
            let err = guard(&[&drawing], &[("-o", out)]).unwrap_err();
            assert!(err.contains("refusing to overwrite"), "{err}");
        }
        let nc = dir.path().join("plate.nc");
        assert!(guard(
            &[&drawing],
            &[("-o", &nc), ("--svg", &dir.path().join("plate.svg"))]
        )
        .is_ok());
        let err = guard(
            &[&drawing],
            &[("-o", &nc), ("--svg", &dir.path().join("sub/../plate.nc"))],
        )
        .unwrap_err();
        assert!(err.contains("-o and --svg both name"), "{err}");
        let stdout = Path::new("-");
        assert!(guard(&[&drawing], &[("-o", stdout), ("--svg", &nc)]).is_ok());
        assert!(guard(&[&drawing], &[("-o", stdout), ("--svg", stdout)]).is_err());
    }

    #[test]
    fn a_missing_folder_is_an_error_naming_the_file() {
        let err = write_atomic(Path::new("no/such/folder/out.txt"), b"x").unwrap_err();
        assert!(err.contains("no/such/folder/out.txt"), "{err}");
    }
}
