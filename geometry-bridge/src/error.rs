//! Typed errors. Every error names the file it concerns, so a CLI can print it as is.
use thiserror::Error;

/// Why reading, repairing or querying a CAD model failed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CadError {
    #[error("{file}: file not found")]
    NotFound { file: String },
    #[error("{file}: unknown CAD format (expected .step/.stp, .iges/.igs or .brep/.brp)")]
    UnknownFormat { file: String },
    #[error("{file}: not a readable {format} file")]
    Unreadable { file: String, format: &'static str },
    #[error("{file}: no shapes could be transferred from the file")]
    Empty { file: String },
    #[error(
        "{file}: contains no solid ({faces} faces, {open_shells} open shells); sew the faces first"
    )]
    NoSolid {
        file: String,
        faces: usize,
        open_shells: usize,
    },
    #[error("{file}: solid {solid} is bounded by open shell {shell} ({free_edges} edges used by only one face)")]
    OpenShell {
        file: String,
        solid: usize,
        shell: usize,
        free_edges: usize,
    },
    #[error("{file}: invalid topology: {message}")]
    Topology { file: String, message: String },
    #[error("{file}: {what} {index} does not exist")]
    NoSuchEntity {
        file: String,
        what: &'static str,
        index: usize,
    },
    #[error("{file}: OpenCASCADE failed in {operation}: {message}")]
    Occt {
        file: String,
        operation: &'static str,
        message: String,
    },
}

/// Problems found in a model that do not make it unusable.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
pub enum CadWarning {
    #[error("shell {shell} is declared open by the file but every edge is shared by two faces")]
    ShellDeclaredOpen { shell: usize },
    #[error("{faces} faces belong to no shell")]
    FacesOutsideShells { faces: usize },
}
