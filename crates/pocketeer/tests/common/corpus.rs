//! Finding drawings: every DXF file under a folder, for the fixture tests and the ignored
//! corpus tests (the CLI's tests include this file too).

use std::path::{Path, PathBuf};

/// Every DXF file under `root`, in subfolders too, sorted; panics when `root` cannot be read.
pub fn dxf_files(root: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut dirs = vec![root.to_path_buf()];
    while let Some(d) = dirs.pop() {
        let entries = std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display()));
        for p in entries.flatten().map(|e| e.path()) {
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dxf")) {
                files.push(p);
            }
        }
    }
    files.sort();
    files
}

/// The drawings of the folder `POCKETEER_CORPUS` names. The corpus tests are ignored and run
/// by name: without the folder they have nothing to judge, which is a failure, not a pass.
pub fn corpus_from_env() -> Vec<PathBuf> {
    let root =
        std::env::var_os("POCKETEER_CORPUS").expect("POCKETEER_CORPUS names the folder of drawings to judge");
    dxf_files(Path::new(&root))
}
