//! The first part of a resumed run's files: what the interrupted run wrote up to its
//! checkpoint, copied from its recording and its MCAP log into the files the resumed run
//! writes, so that each holds the whole run as one.
//!
//! A recording keeps every temporal row up to the checkpoint's step, except the catalog's text
//! log (written again, whole, when the run ends); its static parts (the run description,
//! styles, the blueprint) and anything written when the earlier run ended are left out, since
//! the resumed run writes them again. A log keeps the first `rows` messages of each per-step
//! topic, with their original sequence numbers and times.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufReader, Write};
use std::path::Path;

use rerun::RecordingStream;
use rerun::TimelineName;
use rerun::external::arrow::array::BooleanArray;
use rerun::external::re_log_encoding::DecoderApp;
use rerun::log::{Chunk, LogMsg};

use crate::record::schema;

/// Sends every temporal row of `previous` up to step `through` to `rec`, but those of the
/// `skip` entities. Refuses a recording of another run (another recording id). Returns the
/// rows copied per entity. A file that ends mid-message (a killed run) yields what came
/// before; the caller checks that it reaches the checkpoint.
pub fn copy_recording(
    previous: &Path,
    rec: &RecordingStream,
    recording_id: &str,
    through: i64,
    skip: &[&str],
) -> Result<BTreeMap<String, usize>, String> {
    let read_error = |e: &dyn std::fmt::Display| format!("cannot read {}: {e}", previous.display());
    let file = File::open(previous).map_err(|e| read_error(&e))?;
    let decoder = DecoderApp::decode_eager(BufReader::new(file)).map_err(|e| read_error(&e))?;
    let step = TimelineName::from(schema::STEP);
    let mut rows: BTreeMap<String, usize> = BTreeMap::new();
    for message in decoder {
        let Ok(LogMsg::ArrowMsg(store, arrow)) = message else {
            if message.is_err() {
                break;
            }
            continue;
        };
        if store.is_blueprint() {
            continue;
        }
        let id = store.recording_id().as_str();
        if id != recording_id {
            return Err(format!(
                "{} is the recording of another run (recording id {id}; the checkpoint's run is {recording_id})",
                previous.display()
            ));
        }
        let chunk = Chunk::from_arrow_msg(&arrow).map_err(|e| read_error(&e))?;
        let entity = chunk.entity_path().to_string();
        if chunk.is_static() || skip.iter().any(|s| entity == *s || entity == format!("/{s}")) {
            continue;
        }
        let Some(steps) = chunk.timelines().get(&step) else { continue };
        let keep: Vec<bool> = steps.times_raw().iter().map(|&s| s <= through).collect();
        let kept = keep.iter().filter(|&&k| k).count();
        if kept == 0 {
            continue;
        }
        let chunk = if kept == keep.len() {
            chunk
        } else {
            chunk.filtered(&BooleanArray::from(keep)).ok_or_else(|| read_error(&"a chunk could not be cut"))?
        };
        *rows.entry(entity).or_default() += kept;
        rec.send_chunk(chunk);
    }
    Ok(rows)
}

/// Writes the first `rows` messages of each of `topics` in the MCAP log `previous` to
/// `writer`, on the writer's channels for the same topics (`channels`), with their original
/// sequence numbers and times. A log cut mid-chunk (a killed run) yields its complete chunks.
/// Returns the messages copied per topic.
pub fn copy_log<W: Write + std::io::Seek>(
    previous: &Path,
    writer: &mut mcap::Writer<W>,
    channels: &BTreeMap<&'static str, u16>,
    topics: &[&'static str],
    rows: u64,
) -> Result<BTreeMap<&'static str, u64>, String> {
    let bytes = std::fs::read(previous).map_err(|e| format!("cannot read {}: {e}", previous.display()))?;
    let mut copied: BTreeMap<&'static str, u64> = topics.iter().map(|t| (*t, 0)).collect();
    let stream = mcap::MessageStream::new(&bytes).map_err(|e| format!("cannot read {}: {e}", previous.display()))?;
    for message in stream {
        let Ok(message) = message else { break };
        let Some((&topic, count)) = copied.iter_mut().find(|(t, _)| **t == message.channel.topic) else { continue };
        if *count >= rows {
            continue;
        }
        let header = mcap::records::MessageHeader {
            channel_id: channels[topic],
            sequence: message.sequence,
            log_time: message.log_time,
            publish_time: message.publish_time,
        };
        writer
            .write_to_known_channel(&header, &message.data)
            .map_err(|e| format!("cannot copy {} into the resumed log: {e}", previous.display()))?;
        *count += 1;
        if copied.values().all(|&c| c >= rows) {
            break;
        }
    }
    Ok(copied)
}
