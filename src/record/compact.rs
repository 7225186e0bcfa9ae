//! Compaction of a finished recording: each entity's consecutive chunks merged into few large
//! ones.
//!
//! During a run the recording goes to the disk in chunks, at least every second and every
//! 2 048 rows ([`crate::sink::cadence`]), so that a killed run loses little. A viewer and a
//! dataset server read few large chunks faster than many small ones, so once the run has ended
//! the file is rewritten with every entity's chunks concatenated up to [`MAX_ROWS`] rows,
//! written beside it and renamed over it: at any moment the path holds either the file the
//! run wrote or its complete compacted copy.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufReader, BufWriter};
use std::path::{Path, PathBuf};

use rerun::SizeBytes;
use rerun::external::re_build_info::CrateVersion;
use rerun::external::re_log_encoding::{DecoderApp, Encoder, EncodingOptions};
use rerun::log::{Chunk, LogMsg};

/// The most rows one compacted chunk holds.
pub const MAX_ROWS: usize = 65_536;
/// The most bytes (in memory) one compacted chunk holds: an entity is merged until either
/// bound, so that compaction holds at most this much per entity whatever the file's size (a
/// 1000 × 100 mesh's rows hold 100 000 points each: by rows alone, compacting its 1000 s
/// recording took more than the machine's 24 GB).
pub const MAX_BYTES: u64 = 32 << 20;

/// Chunks before and after.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Compacted {
    pub chunks_before: usize,
    pub chunks_after: usize,
}

/// The most chunks a recording may hold and be left as written by [`compact_if_worthwhile`].
/// The paper case's 1000 s holds about 150 (its 28 entities written every 2 048 rows), and
/// compacting it would cost a third of what writing it does;
/// a small run that flushed every second of wall clock for an hour holds 100 000.
pub const LEFT_AS_WRITTEN: u64 = 2048;

/// [`compact`]s the recording at `path` if it holds more than [`LEFT_AS_WRITTEN`] chunks
/// (counted from the file's message headers). Returns `None` when it is left as written.
pub fn compact_if_worthwhile(path: &Path) -> Result<Option<Compacted>, String> {
    let mut file = File::open(path).map_err(|e| format!("cannot compact {}: {e}", path.display()))?;
    let total = file.metadata().map(|m| m.len()).unwrap_or(0);
    if crate::inspect::framing::rrd_chunks(&mut file, total) <= LEFT_AS_WRITTEN {
        return Ok(None);
    }
    compact(path).map(Some)
}

/// Rewrites the recording at `path` with its chunks merged; on any error the file is left as
/// it was.
pub fn compact(path: &Path) -> Result<Compacted, String> {
    let temporary = temporary_path(path);
    let result = write_compacted(path, &temporary);
    match result {
        Ok(counts) => std::fs::rename(&temporary, path)
            .map(|()| counts)
            .map_err(|e| format!("cannot replace {} by its compacted copy: {e}", path.display())),
        Err(e) => {
            let _ = std::fs::remove_file(&temporary);
            Err(e)
        }
    }
}

/// `.{name}.compacting` beside `path`.
fn temporary_path(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!(".{name}.compacting"))
}

/// Streams `path` into `out`: chunks held per (store, entity, static or not) and merged while
/// concatenable; every other message (store info, blueprint activation) first sends what is
/// held, so it keeps its place after the chunks it follows.
fn write_compacted(path: &Path, out: &Path) -> Result<Compacted, String> {
    let read_error = |e: &dyn std::fmt::Display| format!("cannot compact {}: {e}", path.display());
    let write_error = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", out.display());
    let file = File::open(path).map_err(|e| read_error(&e))?;
    let decoder = DecoderApp::decode_eager(BufReader::new(file)).map_err(|e| read_error(&e))?;
    let writer = BufWriter::new(File::create(out).map_err(|e| write_error(&e))?);
    let mut encoder = Encoder::new_eager(CrateVersion::LOCAL, EncodingOptions::PROTOBUF_COMPRESSED, writer)
        .map_err(|e| write_error(&e))?;
    // Each entity's held pieces with the position of its first one, so that the file keeps the
    // order the run wrote: its description first, its ending record last.
    let mut held: BTreeMap<(String, String, bool), Held> = BTreeMap::new();
    let mut counts = Compacted { chunks_before: 0, chunks_after: 0 };
    let mut send_held = |held: &mut BTreeMap<_, Held>, encoder: &mut Encoder<_>| {
        let mut entities: Vec<Held> = std::mem::take(held).into_values().collect();
        entities.sort_by_key(|h| h.first);
        for entity in entities {
            let chunk = merged(entity.pieces).map_err(|e| write_error(&e))?;
            let message = chunk.to_arrow_msg().map_err(|e| write_error(&e))?;
            encoder.append(&LogMsg::ArrowMsg(entity.store, message)).map_err(|e| write_error(&e))?;
            counts.chunks_after += 1;
        }
        Ok::<(), String>(())
    };
    for message in decoder {
        let message = message.map_err(|e| read_error(&e))?;
        let LogMsg::ArrowMsg(store, arrow) = &message else {
            send_held(&mut held, &mut encoder)?;
            encoder.append(&message).map_err(|e| write_error(&e))?;
            continue;
        };
        counts.chunks_before += 1;
        let chunk = Chunk::from_arrow_msg(arrow).map_err(|e| read_error(&e))?;
        let key = (format!("{store:?}"), chunk.entity_path().to_string(), chunk.is_static());
        let bytes = chunk.heap_size_bytes();
        if let Some(entity) = held.get_mut(&key)
            && entity.rows + chunk.num_rows() <= MAX_ROWS
            && entity.bytes + bytes <= MAX_BYTES
            && entity.pieces.last().is_some_and(|last| last.concatenable(&chunk))
        {
            entity.rows += chunk.num_rows();
            entity.bytes += bytes;
            entity.pieces.push(chunk);
            continue;
        }
        if let Some(full) = held.remove(&key) {
            send_held(&mut BTreeMap::from([(key.clone(), full)]), &mut encoder)?;
        }
        let entity = Held {
            first: counts.chunks_before,
            store: store.clone(),
            rows: chunk.num_rows(),
            bytes,
            pieces: vec![chunk],
        };
        held.insert(key, entity);
    }
    send_held(&mut held, &mut encoder)?;
    encoder.finish().map_err(|e| write_error(&e))?;
    let writer = encoder.into_inner().map_err(|e| write_error(&e))?;
    let file = writer.into_inner().map_err(|e| write_error(&e))?;
    file.sync_all().map_err(|e| write_error(&e))?;
    Ok(counts)
}

/// One entity's chunks waiting to be merged.
struct Held {
    /// Position of the first piece in the file.
    first: usize,
    store: rerun::StoreId,
    rows: usize,
    /// Their size in memory.
    bytes: u64,
    pieces: Vec<Chunk>,
}

/// The pieces concatenated in order, pairwise as a balanced tree, so that each row is copied
/// about log2(pieces) times rather than once per later piece.
fn merged(mut pieces: Vec<Chunk>) -> rerun::log::ChunkResult<Chunk> {
    while pieces.len() > 1 {
        let mut next = Vec::with_capacity(pieces.len().div_ceil(2));
        let mut pairs = pieces.chunks_exact(2);
        for pair in &mut pairs {
            next.push(Chunk::concat_and_sort(&pair[0], &pair[1])?);
        }
        next.extend(pairs.remainder().iter().cloned());
        pieces = next;
    }
    Ok(pieces.pop().expect("an entity is held with at least one piece"))
}
