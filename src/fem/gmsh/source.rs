//! A cursor over a mesh file's bytes: whitespace-separated ASCII words, little-endian binary
//! numbers, sections (`$Nodes` ... `$EndNodes`), and where each thing is (a line of an ASCII
//! file, a byte offset of a binary one) for the messages that refuse it.

use crate::fem::body_mesh::{MeshError, Place};
use std::str::FromStr;

pub(super) struct Source<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// Whether the file's data sections are binary (MSH 4.1 binary): then [`Source::int`],
    /// [`Source::size`] and [`Source::real`] read 4, 8 and 8 little-endian bytes, else a word.
    pub binary: bool,
}

/// How much of a word a message shows.
const SHOWN: usize = 24;

impl<'a> Source<'a> {
    pub fn new(bytes: &'a [u8]) -> Self {
        Source { bytes, pos: 0, binary: false }
    }

    /// The offset of the next byte to read.
    pub fn pos(&self) -> usize {
        self.pos
    }

    /// The offset of the next thing to read: in an ASCII file, of the next word.
    pub fn here(&mut self) -> usize {
        if !self.binary {
            self.skip_space();
        }
        self.pos
    }

    /// Where offset `at` is, as a message says it: its line in an ASCII file, the offset itself
    /// in a binary one.
    pub fn place(&self, at: usize) -> Place {
        if self.binary {
            Place::Byte(at)
        } else {
            let before = &self.bytes[..at.min(self.bytes.len())];
            Place::Line(1 + before.iter().filter(|&&b| b == b'\n').count())
        }
    }

    /// A refusal at offset `at`.
    pub fn error(&self, at: usize, message: impl Into<String>) -> MeshError {
        MeshError::at(self.place(at), message)
    }

    /// The refusal of a file that ends while `what` is still expected.
    fn truncated(&self, what: &str) -> MeshError {
        self.error(self.bytes.len(), format!("the file ends where {what} should be: it is truncated"))
    }

    fn skip_space(&mut self) {
        while self.pos < self.bytes.len() && self.bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// Whether only whitespace is left.
    pub fn at_end(&mut self) -> bool {
        self.skip_space();
        self.pos >= self.bytes.len()
    }

    /// The next whitespace-separated word, and its offset.
    pub fn word(&mut self, what: &str) -> Result<(&'a [u8], usize), MeshError> {
        if self.at_end() {
            return Err(self.truncated(what));
        }
        let start = self.pos;
        while self.pos < self.bytes.len() && !self.bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        Ok((&self.bytes[start..self.pos], start))
    }

    /// The next word read as a `T`, and its offset; `what` names it in a refusal.
    pub fn parsed<T: FromStr>(&mut self, what: &str) -> Result<(T, usize), MeshError> {
        let (word, at) = self.word(what)?;
        match std::str::from_utf8(word).ok().and_then(|w| w.parse().ok()) {
            Some(value) => Ok((value, at)),
            None => Err(self.error(at, format!("expected {what}, found \"{}\"", shown(word)))),
        }
    }

    /// A double-quoted name on the current line (`"body"`); it may hold spaces.
    pub fn quoted(&mut self, what: &str) -> Result<String, MeshError> {
        while self.pos < self.bytes.len() && matches!(self.bytes[self.pos], b' ' | b'\t') {
            self.pos += 1;
        }
        let at = self.pos;
        let rest = &self.bytes[at..];
        let line = &rest[..rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len())];
        let inner = line.strip_prefix(b"\"").and_then(|l| l.iter().position(|&b| b == b'"').map(|end| &l[..end]));
        match inner.and_then(|name| std::str::from_utf8(name).ok()) {
            Some(name) => {
                self.pos = at + name.len() + 2;
                Ok(name.to_owned())
            }
            None => Err(self.error(at, format!("expected {what} in double quotes, found \"{}\"", shown(line)))),
        }
    }

    /// The next section's header (`$Nodes`), and its offset; `None` at the end of the file. In a
    /// binary file the header's newline is consumed too, since binary data follow it directly.
    pub fn section(&mut self) -> Result<Option<(String, usize)>, MeshError> {
        if self.at_end() {
            return Ok(None);
        }
        let (word, at) = self.word("a section")?;
        if word.first() != Some(&b'$') {
            let found = shown(word);
            return Err(self.error(at, format!("expected a section header such as $Nodes, found \"{found}\"")));
        }
        if self.binary {
            self.newline()?;
        }
        Ok(Some((String::from_utf8_lossy(word).into_owned(), at)))
    }

    /// The end of the section `name` (`$Nodes` ends at `$EndNodes`).
    pub fn end_section(&mut self, name: &str) -> Result<(), MeshError> {
        let end = format!("$End{}", &name[1..]);
        let (word, at) = self.word(&end)?;
        if word != end.as_bytes() {
            let found = shown(word);
            return Err(self.error(at, format!("expected {end} to end {name}, found \"{found}\"")));
        }
        Ok(())
    }

    /// Skips the section `name`, whose header has been read, to the end of its `$End` line.
    pub fn skip_section(&mut self, name: &str) -> Result<(), MeshError> {
        let end = format!("$End{}", &name[1..]);
        match self.bytes[self.pos..].windows(end.len()).position(|w| w == end.as_bytes()) {
            Some(p) => {
                self.pos += p + end.len();
                Ok(())
            }
            None => Err(self.truncated(&end)),
        }
    }

    /// One line end (`\n` or `\r\n`), where a binary block starts or a word must end.
    pub fn newline(&mut self) -> Result<(), MeshError> {
        if self.bytes.get(self.pos) == Some(&b'\r') {
            self.pos += 1;
        }
        match self.bytes.get(self.pos) {
            Some(b'\n') => {
                self.pos += 1;
                Ok(())
            }
            Some(_) => Err(self.error(self.pos, "expected the end of the line")),
            None => Err(self.truncated("the end of the line")),
        }
    }

    /// The next `N` bytes.
    fn take<const N: usize>(&mut self, what: &str) -> Result<[u8; N], MeshError> {
        let bytes = self.bytes.get(self.pos..self.pos + N).ok_or_else(|| self.truncated(what))?;
        self.pos += N;
        Ok(bytes.try_into().unwrap_or([0; N]))
    }

    /// A 4-byte little-endian integer, in a binary or an ASCII file.
    pub fn raw_i32(&mut self, what: &str) -> Result<i32, MeshError> {
        Ok(i32::from_le_bytes(self.take(what)?))
    }

    /// An `int` of the file: a word in ASCII, 4 little-endian bytes in binary.
    pub fn int(&mut self, what: &str) -> Result<i32, MeshError> {
        if self.binary { self.raw_i32(what) } else { Ok(self.parsed(what)?.0) }
    }

    /// A `size_t` of the file: a word in ASCII, 8 little-endian bytes in binary.
    pub fn size(&mut self, what: &str) -> Result<u64, MeshError> {
        if self.binary { Ok(u64::from_le_bytes(self.take(what)?)) } else { Ok(self.parsed(what)?.0) }
    }

    /// A `double` of the file: a word in ASCII, 8 little-endian bytes in binary.
    pub fn real(&mut self, what: &str) -> Result<f64, MeshError> {
        if self.binary { Ok(f64::from_le_bytes(self.take(what)?)) } else { Ok(self.parsed(what)?.0) }
    }

    /// How many of `count` items, each at least `min_bytes` long in the file, the rest of the
    /// file can hold: the capacity to reserve for them, so that no count a header declares
    /// drives an allocation larger than the file.
    pub fn capacity(&self, count: u64, min_bytes: usize) -> usize {
        let fit = (self.bytes.len() - self.pos.min(self.bytes.len())) / min_bytes.max(1);
        usize::try_from(count).map_or(fit, |count| count.min(fit))
    }

    /// The fewest bytes an `int` or `size_t` takes in this file: 4 or 8 in binary, a digit and
    /// a separator in ASCII.
    pub fn min_bytes(&self, binary_bytes: usize) -> usize {
        if self.binary { binary_bytes } else { 2 }
    }
}

/// The start of a word as a message shows it: at most [`SHOWN`] characters.
pub(super) fn shown(word: &[u8]) -> String {
    let text = String::from_utf8_lossy(&word[..word.len().min(4 * SHOWN)]);
    let mut shown: String = text.chars().take(SHOWN).collect();
    if shown.len() < text.len() || word.len() > 4 * SHOWN {
        shown.push('…');
    }
    shown
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_and_places_in_ascii() {
        let mut s = Source::new(b"$Nodes\n 12 x \n\"my body\" 3\n");
        assert_eq!(s.section().unwrap(), Some(("$Nodes".to_owned(), 0)));
        assert_eq!(s.parsed::<u64>("a count").unwrap(), (12, 8));
        let e = s.parsed::<u64>("a count").unwrap_err();
        assert_eq!(e.to_string(), "line 2: expected a count, found \"x\"");
        assert_eq!(s.quoted("a name").unwrap_err().to_string(), "line 2: expected a name in double quotes, found \"\"");
    }

    #[test]
    fn names_ends_and_truncation() {
        let mut s = Source::new(b"2 \"my body\" 3\n$EndPhysicalNames");
        assert_eq!(s.parsed::<i32>("a dimension").unwrap().0, 2);
        assert_eq!(s.quoted("a name").unwrap(), "my body");
        assert_eq!(s.int("a tag").unwrap(), 3);
        s.end_section("$PhysicalNames").unwrap();
        assert!(s.at_end());
        assert_eq!(
            s.int("a tag").unwrap_err().to_string(),
            "line 2: the file ends where a tag should be: it is truncated"
        );
    }

    #[test]
    fn binary_numbers_are_little_endian_and_bounded() {
        let mut bytes = vec![1, 0, 0, 0];
        bytes.extend(7u64.to_le_bytes());
        bytes.extend(0.5f64.to_le_bytes());
        let mut s = Source::new(&bytes);
        s.binary = true;
        assert_eq!(s.int("an int").unwrap(), 1);
        assert_eq!(s.capacity(u64::MAX, 8), 2);
        assert_eq!(s.size("a size").unwrap(), 7);
        assert_eq!(s.real("a real").unwrap(), 0.5);
        assert_eq!(
            s.real("a real").unwrap_err().to_string(),
            "byte 20: the file ends where a real should be: it is truncated"
        );
    }

    #[test]
    fn long_words_are_cut_short() {
        assert_eq!(shown(&[b'a'; 30]), format!("{}…", "a".repeat(24)));
        assert_eq!(shown(b"\xff"), "\u{fffd}");
    }
}
