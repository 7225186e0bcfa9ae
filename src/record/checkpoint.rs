//! The checkpoint file (`<stem>.ckpt`): everything a run needs to continue, written atomically
//! (to a file beside it, synced, then renamed over it), so that the path always holds a whole
//! checkpoint.
//!
//! | bytes | what |
//! |---|---|
//! | 8 | `SLPFCKPT` |
//! | 4 | format version (u32, little-endian), [`FORMAT`] |
//! | 8 | length of the body (u64) |
//! | 4 | `xxh32` of the body (u32, seed [`SEED`]) |
//! | rest | the body: a [`Checkpoint`] in `postcard` (binary serde; floats as their exact bits) |
//!
//! A file that is not a checkpoint, of another format or slipfront version, cut short, or
//! changed by even one bit is refused with a message saying which.

use std::io::Write;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::run::RunMemory;

/// The first bytes of every checkpoint.
pub const MAGIC: &[u8; 8] = b"SLPFCKPT";
/// The version of the envelope above and of the body's layout.
pub const FORMAT: u32 = 4;
/// The largest checkpoint read (bytes): a checkpoint holds one run's state, 10 MB for a
/// 1000 × 100 mesh.
pub const MAX_CHECKPOINT_BYTES: u64 = 4 << 30;
/// Seed of the body's checksum.
pub const SEED: u32 = 0x51f0_c4e7;
const HEADER: usize = 8 + 4 + 8 + 4;

/// A run's checkpoint: what run it continues, and the state of its loop.
#[derive(Debug, Clone)]
pub struct Checkpoint {
    pub info: CheckpointInfo,
    /// The state of the run loop, its scene, catalog and sinks.
    pub run: RunMemory,
}

/// What run a checkpoint continues.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckpointInfo {
    /// The slipfront version that wrote it; another version does not read it.
    pub written_by: String,
    pub case: SavedCase,
    pub outputs: SavedOutputs,
    /// The recording id of the run's recording and log.
    pub recording_id: Option<String>,
    /// The interval between checkpoints (simulated s).
    pub every: f64,
}

/// The case a checkpoint continues, as the run read it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SavedCase {
    /// The case file as given on the command line (for messages; the text below is what counts).
    pub path: PathBuf,
    /// The name the outputs were given (`<stem>.rrd`, …).
    pub stem: String,
    pub text: String,
    pub overrides: Vec<String>,
}

impl SavedCase {
    /// The folder of the case file, which the files it names (a mesh) are relative to.
    pub fn case_dir(&self) -> PathBuf {
        self.path.parent().filter(|d| !d.as_os_str().is_empty()).map_or_else(|| PathBuf::from("."), PathBuf::from)
    }
}

/// Where the run wrote its outputs, relative to the checkpoint's own folder (a file name for
/// an output beside it), so that a folder copied or moved elsewhere resumes in place and never
/// touches the one it came from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SavedOutputs {
    pub events: PathBuf,
    pub ruptures: PathBuf,
    pub rrd: Option<PathBuf>,
    pub mcap: Option<PathBuf>,
}

impl SavedOutputs {
    /// The outputs at these paths, named relative to `folder`, where the checkpoint is written.
    pub fn new(folder: &Path, events: &Path, ruptures: &Path, rrd: Option<&Path>, mcap: Option<&Path>) -> Self {
        let relative = |p: &Path| relative_to(p, folder);
        Self {
            events: relative(events),
            ruptures: relative(ruptures),
            rrd: rrd.map(relative),
            mcap: mcap.map(relative),
        }
    }

    /// The outputs of a checkpoint in `folder`.
    pub fn in_folder(&self, folder: &Path) -> Self {
        let join = |p: &PathBuf| folder.join(p);
        Self {
            events: join(&self.events),
            ruptures: join(&self.ruptures),
            rrd: self.rrd.as_ref().map(join),
            mcap: self.mcap.as_ref().map(join),
        }
    }
}

/// `path` relative to `folder`, both made absolute first, through `..` where `path` lies
/// outside it: `out/x.rrd` from `out` is `x.rrd`, `other/x.rrd` is `../other/x.rrd`.
pub fn relative_to(path: &Path, folder: &Path) -> PathBuf {
    let absolute = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    let (path, folder) = (absolute(path), absolute(folder));
    let (to, from): (Vec<_>, Vec<_>) = (path.components().collect(), folder.components().collect());
    let common = to.iter().zip(&from).take_while(|(a, b)| a == b).count();
    let mut relative: PathBuf = from[common..].iter().map(|_| std::path::Component::ParentDir).collect();
    relative.extend(&to[common..]);
    relative
}

/// The folder a checkpoint at `path` is in (`.` for a bare file name).
pub fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

impl Checkpoint {
    /// Simulated time (s) and steps of the saved state.
    pub fn time_and_step(&self) -> (f64, u64) {
        self.run.scene.time_and_step()
    }
}

/// Encodes a checkpoint as a file's bytes.
pub fn encode(info: &CheckpointInfo, run: &RunMemory) -> Result<Vec<u8>, String> {
    let body = postcard::to_stdvec(&(info, run)).map_err(|e| format!("cannot encode the checkpoint: {e}"))?;
    let mut bytes = Vec::with_capacity(HEADER + body.len());
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&FORMAT.to_le_bytes());
    bytes.extend_from_slice(&(body.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&xxhash_rust::xxh32::xxh32(&body, SEED).to_le_bytes());
    bytes.extend_from_slice(&body);
    Ok(bytes)
}

/// Decodes a checkpoint file's bytes; `name` stands for the file in messages.
pub fn decode(bytes: &[u8], name: &str) -> Result<Checkpoint, String> {
    if bytes.len() < HEADER || &bytes[..8] != MAGIC {
        return Err(format!("{name} is not a slipfront checkpoint (it does not start with SLPFCKPT)"));
    }
    let word = |at: usize, len: usize| bytes[at..at + len].iter().rev().fold(0_u64, |v, &b| v << 8 | b as u64);
    let format = word(8, 4);
    if format != FORMAT as u64 {
        return Err(format!("{name} is a checkpoint of format {format}; this slipfront reads format {FORMAT}"));
    }
    let (declared, checksum) = (word(12, 8), word(20, 4));
    let body = &bytes[HEADER..];
    if body.len() as u64 != declared {
        return Err(format!(
            "{name} is {}: its header declares {declared} bytes of state, the file holds {}",
            if (body.len() as u64) < declared { "cut short" } else { "damaged" },
            body.len()
        ));
    }
    if xxhash_rust::xxh32::xxh32(body, SEED) as u64 != checksum {
        return Err(format!("{name} is damaged: its checksum does not match its contents"));
    }
    let (info, run): (CheckpointInfo, RunMemory) = postcard::from_bytes(body)
        .map_err(|e| format!("{name} cannot be decoded ({e}): is it from another slipfront?"))?;
    let version = env!("CARGO_PKG_VERSION");
    if info.written_by != version {
        return Err(format!(
            "{name} was written by slipfront {}; this is slipfront {version}, which does not continue other \
             versions' runs: resume it with slipfront {}",
            info.written_by, info.written_by
        ));
    }
    Ok(Checkpoint { info, run })
}

/// Reads the checkpoint at `path`.
pub fn read(path: &Path) -> Result<Checkpoint, String> {
    let bytes = crate::files::read_capped(
        path,
        MAX_CHECKPOINT_BYTES,
        "a checkpoint is the <stem>.ckpt file of a run started with --checkpoint-every",
    )?;
    decode(&bytes, &path.display().to_string())
}

/// Writes `checkpoint` to `path` atomically: to `.<name>.writing` beside it, synced, then
/// renamed over it; with `keep`, also linked as `keep` (a checkpoint kept under its time).
/// Returns the bytes written.
pub fn write(path: &Path, keep: Option<&Path>, info: &CheckpointInfo, run: &RunMemory) -> Result<u64, String> {
    let bytes = encode(info, run)?;
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let writing = path.with_file_name(format!(".{name}.writing"));
    let error = |e: std::io::Error| format!("cannot write the checkpoint {}: {e}", path.display());
    let mut file = std::fs::File::create(&writing).map_err(error)?;
    let written = file.write_all(&bytes).and_then(|()| file.sync_all());
    drop(file);
    if let Err(e) = written {
        let _ = std::fs::remove_file(&writing);
        return Err(error(e));
    }
    if let Some(keep) = keep {
        let _ = std::fs::remove_file(keep);
        if let Err(e) = std::fs::hard_link(&writing, keep) {
            let _ = std::fs::remove_file(&writing);
            return Err(format!("cannot keep the checkpoint as {}: {e}", keep.display()));
        }
    }
    if let Err(e) = std::fs::rename(&writing, path) {
        let _ = std::fs::remove_file(&writing);
        return Err(error(e));
    }
    if let Some(folder) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        // The rename itself reaches the disk with the folder.
        let _ = std::fs::File::open(folder).and_then(|f| f.sync_all());
    }
    Ok(bytes.len() as u64)
}
