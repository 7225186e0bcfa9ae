//! Why a mesh is refused, and where: the file, the place in it, and the message; and how
//! messages name nodes and cells (by their tags in the file when there are tags).

use std::fmt;

/// Where in a file a refusal points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Place {
    /// A line (from 1) of an ASCII file.
    Line(usize),
    /// A byte offset (from 0) in a binary file.
    Byte(usize),
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Place::Line(n) => write!(f, "line {n}"),
            Place::Byte(n) => write!(f, "byte {n}"),
        }
    }
}

/// Why a mesh is refused: which file, where (a line of an ASCII file, a byte offset of a binary
/// one, or, in the message, an element or node named by its tag with its nodes' tags), and
/// what is allowed. Displays as `FILE: line 42: message`.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshError {
    file: Option<String>,
    place: Option<Place>,
    message: String,
}

impl MeshError {
    /// A refusal that points nowhere in particular (a mesh built in memory, or a rule about the
    /// whole mesh).
    pub fn new(message: impl Into<String>) -> Self {
        MeshError { file: None, place: None, message: message.into() }
    }

    /// A refusal at `place` in the file.
    pub fn at(place: Place, message: impl Into<String>) -> Self {
        MeshError { file: None, place: Some(place), message: message.into() }
    }

    /// The same refusal, naming `file` (unless it already names one).
    pub fn in_file(mut self, file: &str) -> Self {
        self.file.get_or_insert_with(|| file.to_owned());
        self
    }

    pub fn file(&self) -> Option<&str> {
        self.file.as_deref()
    }

    pub fn place(&self) -> Option<Place> {
        self.place
    }

    pub fn message(&self) -> &str {
        &self.message
    }
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(file) = &self.file {
            write!(f, "{file}: ")?;
        }
        if let Some(place) = self.place {
            write!(f, "{place}: ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for MeshError {}

/// How a message names node `i`: `node 17` by its tag when `tags` has one, else `node #3` by
/// its index.
pub(super) fn node_label(tags: &[u64], i: usize) -> String {
    match tags.get(i) {
        Some(tag) => format!("node {tag}"),
        None => format!("node #{i}"),
    }
}

/// How a message names cell `c` with its nodes: `element 23 (nodes 1 2 21 22)` by tags when
/// there are tags, else `cell #0 (nodes #0 #1 #12 #11)` by indices.
pub(super) fn cell_label(cell_tags: &[u64], node_tags: &[u64], c: usize, nodes: &[usize]) -> String {
    let name = match cell_tags.get(c) {
        Some(tag) => format!("element {tag}"),
        None => format!("cell #{c}"),
    };
    let nodes: Vec<String> = nodes.iter().map(|&n| node_label(node_tags, n)["node ".len()..].to_owned()).collect();
    format!("{name} (nodes {})", nodes.join(" "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_error_reads_file_place_message() {
        let e = MeshError::at(Place::Line(42), "bad").in_file("a.msh");
        assert_eq!(e.to_string(), "a.msh: line 42: bad");
        assert_eq!(
            MeshError::at(Place::Byte(7), "bad").in_file("b.msh").in_file("c").to_string(),
            "b.msh: byte 7: bad"
        );
        assert_eq!(MeshError::new("bad").to_string(), "bad");
    }

    #[test]
    fn labels_use_tags_when_there_are_tags() {
        assert_eq!(cell_label(&[23], &[5, 6, 7], 0, &[0, 2, 1]), "element 23 (nodes 5 7 6)");
        assert_eq!(cell_label(&[], &[], 4, &[0, 2, 1]), "cell #4 (nodes #0 #2 #1)");
    }
}
