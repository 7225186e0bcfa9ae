//! Opening the files slipfront is given to read: case and study files, expectations,
//! checkpoints, a study's member records and catalogs, recordings and logs. Each is refused
//! unless it is a regular file, before it is opened for reading (a named pipe would block the
//! read for ever, a device such as `/dev/zero` never ends), and, where it is read whole, unless
//! it is at most the cap its kind states. The refusal names the file, the cap and what the file
//! should be.

use std::fmt;
use std::fs::{File, Metadata, OpenOptions};
use std::io::Read;
use std::os::unix::fs::{FileTypeExt, MetadataExt, OpenOptionsExt};
use std::path::{Path, PathBuf};

/// A file that was not read, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct Unreadable {
    pub path: PathBuf,
    /// Why, without the path: `it is a named pipe (FIFO), not a regular file; …`.
    pub reason: String,
}

impl fmt::Display for Unreadable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot read {}: {}", self.path.display(), self.reason)
    }
}

impl From<Unreadable> for String {
    fn from(e: Unreadable) -> Self {
        e.to_string()
    }
}

/// Opens `path` for reading if it is a regular file; `what` says what it should be (`a case
/// file is a few kilobytes of TOML`). Returns the file and its length. The file's type is read
/// before it is opened, and it is opened without blocking, then checked again, so that neither
/// a named pipe nor one swapped in between is ever waited on.
pub fn open_regular(path: &Path, what: &str) -> Result<(File, u64), Unreadable> {
    let refuse = |reason: String| Unreadable { path: path.to_path_buf(), reason };
    let before = std::fs::metadata(path).map_err(|e| refuse(e.to_string()))?;
    not_regular(&before).map_or(Ok(()), |kind| Err(refuse(format!("it is {kind}, not a regular file; {what}"))))?;
    let file =
        OpenOptions::new().read(true).custom_flags(libc::O_NONBLOCK).open(path).map_err(|e| refuse(e.to_string()))?;
    let opened = file.metadata().map_err(|e| refuse(e.to_string()))?;
    if not_regular(&opened).is_some() || (opened.dev(), opened.ino()) != (before.dev(), before.ino()) {
        return Err(refuse(format!("it was replaced while being opened; {what}")));
    }
    Ok((file, opened.len()))
}

/// Reads the whole of `path` if it is a regular file ([`open_regular`]) of at most `cap` bytes.
pub fn read_capped(path: &Path, cap: u64, what: &str) -> Result<Vec<u8>, Unreadable> {
    let refuse = |reason: String| Unreadable { path: path.to_path_buf(), reason };
    let too_large = || refuse(format!("it is larger than {}; {what}", size(cap)));
    let (file, len) = open_regular(path, what)?;
    if len > cap {
        return Err(too_large());
    }
    // At most one byte past the cap, in case the file grows while it is read.
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(cap + 1).read_to_end(&mut bytes).map_err(|e| refuse(e.to_string()))?;
    if bytes.len() as u64 > cap {
        return Err(too_large());
    }
    Ok(bytes)
}

/// As [`read_capped`], for a text file (UTF-8).
pub fn read_text_capped(path: &Path, cap: u64, what: &str) -> Result<String, Unreadable> {
    let bytes = read_capped(path, cap, what)?;
    String::from_utf8(bytes)
        .map_err(|e| Unreadable { path: path.to_path_buf(), reason: format!("it is not UTF-8 text ({e}); {what}") })
}

/// What a file that is not a regular one is, for the refusal.
fn not_regular(metadata: &Metadata) -> Option<&'static str> {
    let kind = metadata.file_type();
    match () {
        _ if kind.is_file() => None,
        _ if kind.is_dir() => Some("a folder"),
        _ if kind.is_fifo() => Some("a named pipe (FIFO)"),
        _ if kind.is_char_device() => Some("a character device"),
        _ if kind.is_block_device() => Some("a block device"),
        _ if kind.is_socket() => Some("a socket"),
        _ => Some("not a file"),
    }
}

/// A cap in its binary unit: `4 MiB`, `1 GiB`.
pub fn size(bytes: u64) -> String {
    let units = [(1 << 30, "GiB"), (1 << 20, "MiB"), (1 << 10, "KiB")];
    match units.iter().find(|(unit, _)| bytes >= *unit && bytes.is_multiple_of(*unit)) {
        Some((unit, name)) => format!("{} {name}", bytes / unit),
        None => format!("{bytes} bytes"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_regular_file_within_its_cap_is_read() {
        let dir = std::env::temp_dir().join(format!("slipfront-files-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("f.toml");
        std::fs::write(&file, b"12345").unwrap();
        assert_eq!(read_capped(&file, 5, "x").unwrap(), b"12345");
        let refused = read_capped(&file, 4, "a case file is small").unwrap_err();
        assert_eq!(refused.reason, "it is larger than 4 bytes; a case file is small");
        let fifo = dir.join("pipe");
        let name = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: mkfifo reads a NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
        let refused = read_capped(&fifo, 4, "x").unwrap_err();
        assert!(refused.reason.starts_with("it is a named pipe (FIFO), not a regular file"), "{refused}");
        let refused = read_capped(Path::new("/dev/zero"), 1 << 20, "x").unwrap_err();
        assert!(refused.reason.starts_with("it is a character device"), "{refused}");
        assert!(read_capped(&dir, 4, "x").unwrap_err().reason.starts_with("it is a folder"));
        assert_eq!((size(4 << 20), size(1 << 30), size(1000)), ("4 MiB".into(), "1 GiB".into(), "1000 bytes".into()));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
