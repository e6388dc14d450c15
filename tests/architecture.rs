//! Keeps `ARCHITECTURE.md` an honest map of the code: no line of it is over 400 characters
//! (a map, not a diary), every `.rs` file under `src/` is named in it (as a path relative to
//! `src/`, in backticks), and every `.rs` file it names exists.

use std::path::{Path, PathBuf};

const MAX_LINE: usize = 400;

/// Folders whose files the map names from the repository root; any other path is relative to
/// `src/`.
const ROOT_PREFIXES: [&str; 6] = [
    "native/",
    "geometry-bridge/",
    "plugins/",
    "tests/",
    "examples/",
    "benches/",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn map() -> String {
    let path = root().join("ARCHITECTURE.md");
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()))
}

/// Every `.rs` file under `dir`, as a path relative to `base` with `/` separators.
fn rust_files(base: &Path, dir: &Path, out: &mut Vec<String>) {
    let entries =
        std::fs::read_dir(dir).unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()));
    for entry in entries {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(base, &path, out);
        } else if path.extension().is_some_and(|x| x == "rs") {
            let rel = path.strip_prefix(base).expect("under the base folder");
            let parts: Vec<String> = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            out.push(parts.join("/"));
        }
    }
}

/// The contents of every inline code span (text between a pair of backticks on one line).
fn code_spans(text: &str) -> Vec<&str> {
    text.lines()
        .flat_map(|line| line.split('`').skip(1).step_by(2))
        .collect()
}

#[test]
fn no_line_of_the_map_is_over_400_characters() {
    let long: Vec<String> = map()
        .lines()
        .enumerate()
        .filter(|(_, line)| line.chars().count() > MAX_LINE)
        .map(|(k, line)| format!("line {}: {} characters", k + 1, line.chars().count()))
        .collect();
    assert!(
        long.is_empty(),
        "ARCHITECTURE.md is a map, not a diary: lines over {MAX_LINE} characters:\n{}",
        long.join("\n")
    );
}

#[test]
fn every_source_file_is_named() {
    let text = map();
    let src = root().join("src");
    let mut files = Vec::new();
    rust_files(&src, &src, &mut files);
    files.sort();
    assert!(
        !files.is_empty(),
        "no .rs files found under {}",
        src.display()
    );
    let missing: Vec<&String> = files
        .iter()
        .filter(|f| !text.contains(&format!("`{f}`")))
        .collect();
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md does not name these files of src/ (as `folder/file.rs`):\n{}",
        missing
            .iter()
            .map(|f| f.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
}

#[test]
fn every_named_file_exists() {
    let text = map();
    let root = root();
    let mut missing: Vec<String> = code_spans(&text)
        .into_iter()
        .map(str::trim)
        .filter(|s| s.ends_with(".rs") && !s.contains(char::is_whitespace))
        .filter(|s| {
            let path = if ROOT_PREFIXES.iter().any(|p| s.starts_with(p)) {
                root.join(s)
            } else {
                root.join("src").join(s)
            };
            !path.is_file()
        })
        .map(str::to_string)
        .collect();
    missing.sort();
    missing.dedup();
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md names files that do not exist (paths relative to src/, or to the \
         repository root for {ROOT_PREFIXES:?}):\n{}",
        missing.join("\n")
    );
}
