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
        return same_file::is_same_file(a, b).unwrap_or(false);
    }
    absolute(a) == absolute(b)
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

/// Writes `bytes` to `path` atomically: other programs and a failed run see the old file or
/// the whole new one, never part of it. The error names the file.
///
/// There is no `fsync` before the rename. What we write is derived from the drawing and the
/// flags and is made again by running again; waiting for the disk cost 1.3 ms of a 3.5 ms
/// offset of a 75-hole plate (more than half the run's own work). Linux's ext4 (by its
/// default `auto_da_alloc`) and btrfs write a file's data before a rename that replaces
/// another file is committed, which covers the case that matters: a good old program.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        std::fs::rename(&tmp, path)
    })();
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        format!("{}: cannot write: {e}", path.display())
    })
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
