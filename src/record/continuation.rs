//! The first part of a resumed run's files: what the interrupted run wrote up to its
//! checkpoint, checked against the checkpoint and then copied from its recording and its MCAP
//! log into the files the resumed run writes, so that each holds the whole run as one.
//!
//! Before anything is written, [`verify_recording`] and [`verify_log`] establish that the files
//! beside a checkpoint are its run's up to its step: the same recording id, every row up to the
//! step there, and the same digests of those rows as the checkpoint holds. Both read through the
//! guarded readers of [`crate::inspect`], so damage is an error, never a decoder's panic.
//!
//! A recording keeps every temporal row up to the checkpoint's step, except the catalog's text
//! log (written again, whole, when the run ends); its static parts (the run description,
//! styles, the blueprint) and anything written when the earlier run ended are left out, since
//! the resumed run writes them again. A log keeps the first `rows` messages of each per-step
//! topic, with their original sequence numbers and times.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufReader, Seek, SeekFrom, Write};
use std::path::Path;

use prost::Message as _;
use rerun::RecordingStream;
use rerun::TimelineName;
use rerun::external::arrow::array::BooleanArray;
use rerun::external::re_log_encoding::DecoderApp;
use rerun::log::{Chunk, LogMsg};

use crate::inspect::framing;
use crate::inspect::mcap::{LOG, MAX_LOG_BYTES};
use crate::inspect::unwind::quietly;
use crate::record::digest::{MessageDigest, SeriesDigest};
use crate::record::mcap::{LogHeader, TOPIC_RUN};
use crate::record::{proto, schema};

/// Checks that `previous` is the recording of run `recording_id` up to step `through`: every
/// series of `digests` holds `rows` rows up to it, with that digest ([`SeriesDigest`]). A file
/// that ends after the step (a killed run) passes; one of another run, cut before the step, or
/// with a changed row does not, and the error says which.
pub fn verify_recording(
    previous: &Path,
    recording_id: &str,
    through: i64,
    rows: u64,
    digests: &BTreeMap<String, String>,
) -> Result<(), String> {
    let name = previous.display();
    let recording = crate::inspect::rrd::read(previous).map_err(|e| e.0)?;
    match recording.recording_id.as_deref() {
        Some(id) if id == recording_id => {}
        Some(id) => {
            return Err(format!(
                "{name} is the recording of another run (recording id {id}; the checkpoint's run is {recording_id})"
            ));
        }
        None => return Err(format!("{name} holds no recorded data of a run")),
    }
    let ended = recording.problem.as_ref().map(|p| format!(" ({p})")).unwrap_or_default();
    let empty = crate::inspect::Series::default();
    for (path, digest) in digests {
        let series = recording.series.get(path).unwrap_or(&empty);
        let kept = series.steps.partition_point(|&step| step <= through);
        if kept as u64 != rows {
            return Err(format!(
                "{name} holds {kept} rows of {path} up to step {through}, where the checkpoint counts {rows}: {}",
                if (kept as u64) < rows {
                    format!("it is cut short or damaged before the checkpoint{ended}")
                } else {
                    "it is not this run's recording".to_string()
                }
            ));
        }
        if !SeriesDigest::matches(&series.steps[..kept], &series.times[..kept], &series.values[..kept], digest) {
            return Err(format!(
                "the rows of {path} in {name} up to step {through} differ from those the checkpoint's run wrote: \
                 the recording is damaged{ended}"
            ));
        }
    }
    Ok(())
}

/// Checks that the MCAP log `previous` is run `recording_id`'s up to its checkpoint: its run
/// header names that id, and each topic of `digests` holds at least `rows` messages whose first
/// `rows` have that digest ([`MessageDigest`]).
pub fn verify_log(
    previous: &Path,
    recording_id: &str,
    rows: u64,
    digests: &BTreeMap<String, String>,
) -> Result<(), String> {
    let name = previous.display();
    let bytes = crate::files::read_capped(previous, MAX_LOG_BYTES, LOG)?;
    let topics: Vec<&str> = digests.keys().map(String::as_str).collect();
    let scanned = first_rows(&bytes, &name.to_string(), &topics, rows, |_, _| Ok(()))?;
    let header: Option<LogHeader> = scanned
        .header
        .as_deref()
        .and_then(|data| proto::Run::decode(data).ok())
        .and_then(|run| toml::from_str(&run.header).ok());
    match header.and_then(|h| h.plan.recording_id) {
        Some(id) if id == recording_id => {}
        Some(id) => {
            return Err(format!(
                "{name} is the MCAP log of another run (recording id {id}; the checkpoint's run is {recording_id})"
            ));
        }
        None => {
            return Err(match &scanned.problem {
                Some(problem) => format!("{name} is cut short or damaged before the checkpoint ({problem})"),
                None => format!("{name} has no readable run header at {TOPIC_RUN}: it is not this run's log"),
            });
        }
    }
    for (topic, digest) in digests {
        let (count, found) = &scanned.topics[topic.as_str()];
        if *count != rows {
            return Err(format!(
                "{name} holds {count} messages on {topic} where the checkpoint counts {rows}: it is cut short or \
                 damaged before the checkpoint{}",
                scanned.problem.as_ref().map(|p| format!(" ({p})")).unwrap_or_default()
            ));
        }
        if found.hex() != *digest {
            return Err(format!(
                "the messages on {topic} in {name} up to the checkpoint differ from those its run wrote: the log is \
                 damaged"
            ));
        }
    }
    Ok(())
}

/// Sends every temporal row of `previous` up to step `through` to `rec`, but those of the
/// `skip` entities. A file that ends mid-message (a killed run), or goes on with a message of
/// another recording id, yields what came before; the caller checks that it reaches the
/// checkpoint. Returns the rows copied per entity. A decoder's panic on damaged bytes is an
/// error.
pub fn copy_recording(
    previous: &Path,
    rec: &RecordingStream,
    recording_id: &str,
    through: i64,
    skip: &[&str],
) -> Result<BTreeMap<String, usize>, String> {
    quietly(|| copy_chunks(previous, rec, recording_id, through, skip)).unwrap_or_else(|_| {
        Err(format!("cannot read {}: the Rerun decoder failed on damaged data", previous.display()))
    })
}

/// [`copy_recording`], unguarded.
fn copy_chunks(
    previous: &Path,
    rec: &RecordingStream,
    recording_id: &str,
    through: i64,
    skip: &[&str],
) -> Result<BTreeMap<String, usize>, String> {
    let read_error = |e: &dyn std::fmt::Display| format!("cannot read {}: {e}", previous.display());
    let mut file = File::open(previous).map_err(|e| read_error(&e))?;
    let total = file.metadata().map_err(|e| read_error(&e))?.len();
    let plausible = framing::rrd(&mut file, total);
    file.seek(SeekFrom::Start(0)).map_err(|e| read_error(&e))?;
    let reader = BufReader::new(std::io::Read::take(file, plausible.len));
    let decoder = DecoderApp::decode_eager(reader).map_err(|e| read_error(&e))?;
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
        if store.recording_id().as_str() != recording_id {
            // As the reader that verified the file: a message of another run ends what is this
            // run's; the caller checks that what came before reaches the checkpoint.
            break;
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
/// Returns the messages copied per topic, and their digest.
pub fn copy_log<W: Write + std::io::Seek>(
    previous: &Path,
    writer: &mut mcap::Writer<W>,
    channels: &BTreeMap<&'static str, u16>,
    topics: &[&'static str],
    rows: u64,
) -> Result<BTreeMap<&'static str, (u64, MessageDigest)>, String> {
    let name = previous.display().to_string();
    let bytes = crate::files::read_capped(previous, MAX_LOG_BYTES, LOG)?;
    let scanned = first_rows(&bytes, &name, topics, rows, |topic, message| {
        let header = mcap::records::MessageHeader {
            channel_id: channels[topic],
            sequence: message.sequence,
            log_time: message.log_time,
            publish_time: message.publish_time,
        };
        writer
            .write_to_known_channel(&header, &message.data)
            .map_err(|e| format!("cannot copy {name} into the resumed log: {e}"))
    })?;
    Ok(topics.iter().map(|&topic| (topic, scanned.topics[topic].clone())).collect())
}

/// What [`first_rows`] found: the run header's bytes, each topic's count and digest, and
/// where the log stopped being readable, if it did.
struct Scanned<'t> {
    header: Option<Vec<u8>>,
    topics: BTreeMap<&'t str, (u64, MessageDigest)>,
    problem: Option<String>,
}

/// Hands the first `rows` messages of each of `topics` in the log `bytes` to `visit`, in file
/// order, counting and digesting them. Reads only the prefix whose record sizes are plausible
/// ([`framing::mcap`]); the first unreadable message ends the reading, and a parser's panic is
/// an error.
fn first_rows<'t>(
    bytes: &[u8],
    name: &str,
    topics: &[&'t str],
    rows: u64,
    mut visit: impl FnMut(&'t str, &mcap::Message) -> Result<(), String>,
) -> Result<Scanned<'t>, String> {
    let plausible = framing::mcap(&mut &*bytes, bytes.len() as u64);
    let prefix = plausible.prefix(bytes);
    let mut scanned = Scanned {
        header: None,
        topics: topics.iter().map(|&t| (t, (0, MessageDigest::default()))).collect(),
        problem: None,
    };
    let scan = quietly(|| -> Result<(), String> {
        let stream = mcap::MessageStream::new(prefix).map_err(|e| format!("{name} is not an MCAP log: {e}"))?;
        for message in stream {
            let message = match message {
                Ok(message) => message,
                Err(e) => {
                    scanned.problem = Some(e.to_string());
                    break;
                }
            };
            if message.channel.topic == TOPIC_RUN && scanned.header.is_none() {
                scanned.header = Some(message.data.to_vec());
            }
            let Some((&topic, (count, digest))) = scanned.topics.iter_mut().find(|(t, _)| **t == message.channel.topic)
            else {
                continue;
            };
            if *count >= rows {
                continue;
            }
            visit(topic, &message)?;
            digest.add(message.sequence, message.log_time, &message.data);
            *count += 1;
            if scanned.topics.values().all(|(c, _)| *c >= rows) && scanned.header.is_some() {
                break;
            }
        }
        Ok(())
    });
    match scan {
        Ok(result) => result?,
        Err(_) => return Err(format!("cannot read {name}: the MCAP reader failed on damaged data")),
    }
    plausible.report_into(&mut scanned.problem);
    Ok(scanned)
}
