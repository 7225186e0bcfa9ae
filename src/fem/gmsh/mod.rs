//! Reading Gmsh mesh files into a [`Mesh`]: MSH 4.1 (ASCII and binary) and MSH 2.2 (ASCII),
//! with their physical groups by name.
//!
//! A file is refused with a [`MeshError`] that names the file and the place (a line of an ASCII
//! file, a byte offset of a binary one, or an element or node by its tag), never with a panic;
//! no count a header declares allocates more than the rest of the file can hold.

mod element_types;
mod physical_names;
mod raw;
mod source;
mod v2;
mod v4;

use crate::fem::body_mesh::{Mesh, MeshError};
use source::Source;
use std::io::Read;

/// The largest mesh file read (1 GiB): enough for tens of millions of nodes in ASCII.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// The versions of the format that are read.
const SUPPORTED: &str = "MSH 4.1 (ASCII or binary) and MSH 2.2 (ASCII)";

/// Reads a Gmsh file into a Mesh. `name` is how errors name the file.
pub fn read(path: &std::path::Path) -> Result<Mesh, MeshError> {
    read_with_digest(path).map(|(mesh, _)| mesh)
}

/// [`read`], and a digest of the file's bytes (xxh32), which names the mesh a run used.
pub fn read_with_digest(path: &std::path::Path) -> Result<(Mesh, u64), MeshError> {
    let bytes = read_bytes(path)?;
    let digest = u64::from(xxhash_rust::xxh32::xxh32(&bytes, 0));
    parse(&bytes, &path.display().to_string()).map(|mesh| (mesh, digest))
}

/// The bytes of a mesh file: a regular file of at most [`MAX_FILE_BYTES`].
fn read_bytes(path: &std::path::Path) -> Result<Vec<u8>, MeshError> {
    let name = path.display().to_string();
    let refuse = |message: String| MeshError::new(message).in_file(&name);
    let mut file = open(path).map_err(|e| refuse(format!("cannot be read: {e}")))?;
    let meta = file.metadata().map_err(|e| refuse(format!("cannot be read: {e}")))?;
    if !meta.is_file() {
        return Err(refuse(
            "is not a regular file (a directory, a device or a pipe): a mesh is read from a file".into(),
        ));
    }
    let too_large = || refuse(format!("is larger than {MAX_FILE_BYTES} bytes (1 GiB), the largest mesh file read"));
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_large());
    }
    let mut bytes = Vec::new();
    (&mut file).take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes).map_err(|e| refuse(format!("cannot be read: {e}")))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large()); // it grew while being read
    }
    Ok(bytes)
}

/// Opens `path` for reading without waiting: a pipe with no writer would block `open` itself.
fn open(path: &std::path::Path) -> std::io::Result<std::fs::File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    std::os::unix::fs::OpenOptionsExt::custom_flags(&mut options, libc::O_NONBLOCK);
    options.open(path)
}

/// Reads the bytes of a Gmsh file into a Mesh. `name` is how errors name the file.
pub fn parse(bytes: &[u8], name: &str) -> Result<Mesh, MeshError> {
    if bytes.len() as u64 > MAX_FILE_BYTES {
        let message = format!("is larger than {MAX_FILE_BYTES} bytes (1 GiB), the largest mesh file read");
        return Err(MeshError::new(message).in_file(name));
    }
    let mut src = Source::new(bytes);
    let raw = match mesh_format(&mut src) {
        Ok(Version::V4) => v4::read(&mut src),
        Ok(Version::V2) => v2::read(&mut src),
        Err(e) => Err(e),
    };
    raw.and_then(|raw| raw.into_mesh(&src)).map_err(|e| e.in_file(name))
}

enum Version {
    V4,
    V2,
}

/// `$MeshFormat`: the version, ASCII or binary, the size of a `size_t`, and in a binary file
/// the integer 1 that shows its byte order. Leaves `src` in binary mode for a binary file.
fn mesh_format(src: &mut Source) -> Result<Version, MeshError> {
    match src.section() {
        Ok(Some((name, _))) if name == "$MeshFormat" => {}
        _ => return Err(src.error(0, "not a Gmsh mesh file: it does not start with $MeshFormat")),
    }
    let (version, at) = src.word("the format's version")?;
    let version = match version {
        b"4.1" => Version::V4,
        b"2.2" => Version::V2,
        _ => {
            let v = source::shown(version);
            return Err(src.error(at, format!("MSH version {v} is not read: slipfront reads {SUPPORTED}")));
        }
    };
    let (file_type, at) = src.parsed::<u8>("the file type (0 for ASCII, 1 for binary)")?;
    let (size_t, size_at) = src.parsed::<u64>("the size of a size_t")?;
    match (&version, file_type) {
        (_, 0) => {}
        (Version::V4, 1) => binary_header(src, size_t, size_at)?,
        (Version::V2, 1) => {
            return Err(src.error(at, format!("MSH 2.2 binary is not read: slipfront reads {SUPPORTED}")));
        }
        _ => return Err(src.error(at, format!("the file type is {file_type}: 0 for ASCII, 1 for binary"))),
    }
    src.end_section("$MeshFormat")?;
    Ok(version)
}

/// The rest of a binary file's `$MeshFormat`: the size of a `size_t` must be 8, and the
/// integer 1 that follows must read as 1 in little-endian order.
fn binary_header(src: &mut Source, size_t: u64, at: usize) -> Result<(), MeshError> {
    src.binary = true;
    if size_t != 8 {
        return Err(src.error(
            at,
            format!(
                "the file's size_t is {size_t} bytes: slipfront reads binary files with an 8-byte size_t (64-bit Gmsh)"
            ),
        ));
    }
    src.newline()?;
    let at = src.pos();
    match src.raw_i32("the byte order's marker (the integer 1)")? {
        1 => Ok(()),
        0x0100_0000 => Err(src.error(at, "the file is big-endian: slipfront reads little-endian binary files")),
        other => Err(src.error(at, format!("the byte order's marker is {other}, not 1: the header is damaged"))),
    }
}
