//! Why a case could not be used: every variant is the user's input (exit code 2).

use std::fmt;

use crate::validate::Violation;

/// Why a case could not be used. Every variant is the user's input (exit code 2).
#[derive(Debug)]
pub enum CaseError {
    /// The file could not be read.
    Io { path: String, message: String },
    /// Not TOML, or not the shape of a case (missing, unknown or mistyped keys).
    Parse(String),
    /// A `--set` argument is malformed or names no key.
    Override(String),
    /// Parsed, but values break rules.
    Invalid(Vec<Violation>),
    /// A file the case names (a mesh) is unreadable or refused; the message names it and where.
    Mesh(String),
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CaseError::Io { path, message } => write!(f, "cannot read case file {path}: {message}"),
            CaseError::Parse(message) => write!(f, "{message}"),
            CaseError::Override(message) => write!(f, "{message}"),
            CaseError::Mesh(message) => write!(f, "scene.file: {message}"),
            CaseError::Invalid(violations) => {
                for (i, v) in violations.iter().enumerate() {
                    if i > 0 {
                        writeln!(f)?;
                    }
                    write!(f, "{v}")?;
                }
                Ok(())
            }
        }
    }
}

impl std::error::Error for CaseError {}
