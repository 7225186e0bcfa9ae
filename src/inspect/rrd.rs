//! Reads a Rerun recording (`.rrd`) back into a [`Recording`].

use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;

use rerun::external::re_log_encoding::{DecoderApp, DecoderIterator, RrdManifest};
use rerun::log::{Chunk, LogMsg};
use rerun::{ComponentIdentifier, TimelineName};

use crate::inspect::framing::{self, Plausible};
use crate::inspect::unwind::{DecoderPanicked, quietly};
use crate::inspect::{ReadError, Recording, View};
use crate::record::schema;

/// Decodes every message of `path`. A file that ends mid-message (a run killed while writing)
/// yields what came before, with [`Recording::problem`] saying where it stopped.
pub fn read(path: &Path) -> Result<Recording, ReadError> {
    let open_error = |e: std::io::Error| ReadError(format!("cannot open {}: {e}", path.display()));
    let (mut file, total) = crate::files::open_regular(path, "a recording is a .rrd file that slipfront wrote")
        .map_err(|e| ReadError(e.to_string()))?;
    if total == 0 {
        return Err(ReadError(format!("{} is empty: no recording to read", path.display())));
    }
    let plausible = framing::rrd(&mut file, total);
    let footer = footer_checksum_problem(&mut file, total);
    file.seek(SeekFrom::Start(0)).map_err(open_error)?;
    decode(BufReader::new(std::io::Read::take(file, plausible.len)), &path.display().to_string(), plausible, footer)
}

/// The store of the blueprint a recording carries (written with its run description, before
/// the first columns), read from the file's first messages; `None` if it has no blueprint.
pub fn blueprint_store(path: &Path) -> Result<Option<rerun::external::re_log_types::StoreId>, ReadError> {
    let open_error = |e: std::io::Error| ReadError(format!("cannot open {}: {e}", path.display()));
    let (mut file, total) = crate::files::open_regular(path, "a recording is a .rrd file that slipfront wrote")
        .map_err(|e| ReadError(e.to_string()))?;
    let plausible = framing::rrd(&mut file, total);
    file.seek(SeekFrom::Start(0)).map_err(open_error)?;
    let reader = BufReader::new(std::io::Read::take(file, plausible.len));
    let name = path.display();
    let mut decoder =
        DecoderApp::decode_eager(reader).map_err(|e| ReadError(format!("{name} is not a Rerun recording: {e}")))?;
    for _ in 0..BLUEPRINT_WITHIN {
        match quietly(|| decoder.next()) {
            Ok(Some(Ok(message))) if message.store_id().is_blueprint() => return Ok(Some(message.store_id().clone())),
            Ok(Some(Ok(_))) => {}
            Ok(None) => return Ok(None),
            Ok(Some(Err(e))) => return Err(ReadError(format!("{name} is damaged before its blueprint: {e}"))),
            Err(DecoderPanicked) => return Err(ReadError(format!("{name} is damaged before its blueprint"))),
        }
    }
    Ok(None)
}

/// The messages a recording's blueprint is looked for in: slipfront writes it among the first
/// few (the store's description, the run description, the series' styles).
const BLUEPRINT_WITHIN: usize = 1000;

/// The stream footer's checksum against the footer it points to, where the file ends with
/// one (a recording cut before its footer has none): 32 bytes at the end, the footer's
/// `start` and `len` (u64) and its `xxh32` (u32, seed 7850921), then `RRF2`, `FOOT` and the
/// footer count (u32), all little-endian.
fn footer_checksum_problem(file: &mut (impl Read + Seek), total: u64) -> Option<String> {
    const SIZE: u64 = 32;
    const SEED: u32 = 7_850_921;
    let mut tail = [0u8; SIZE as usize];
    file.seek(SeekFrom::Start(total.checked_sub(SIZE)?)).ok()?;
    file.read_exact(&mut tail).ok()?;
    if &tail[20..24] != b"RRF2" || &tail[24..28] != b"FOOT" {
        return None;
    }
    let word = |at: usize| u64::from_le_bytes(tail[at..at + 8].try_into().expect("8 bytes"));
    let (start, len) = (word(0), word(8));
    let crc = u32::from_le_bytes(tail[16..20].try_into().expect("4 bytes"));
    let end = start.checked_add(len).filter(|&end| end <= total - SIZE);
    let Some(end) = end else {
        return Some(format!("the footer points outside the file (bytes {start} + {len} of {total})"));
    };
    let mut payload = vec![0u8; (end - start) as usize];
    file.seek(SeekFrom::Start(start)).ok()?;
    file.read_exact(&mut payload).ok()?;
    (xxhash_rust::xxh32::xxh32(&payload, SEED) != crc)
        .then(|| "the footer's checksum does not match its bytes".to_string())
}

/// As [`read`], from the bytes of a recording; `name` stands for the file in messages.
pub fn from_bytes(bytes: &[u8], name: &str) -> Result<Recording, ReadError> {
    if bytes.is_empty() {
        return Err(ReadError(format!("{name} is empty: no recording to read")));
    }
    let plausible = framing::rrd(&mut &*bytes, bytes.len() as u64);
    let footer = footer_checksum_problem(&mut std::io::Cursor::new(bytes), bytes.len() as u64);
    decode(plausible.prefix(bytes), name, plausible, footer)
}

/// Decodes the prefix [`framing::rrd`] found plausible; a shortened input, or a `footer`
/// checksum that does not match ([`footer_checksum_problem`]), is reported as the recording's
/// problem.
fn decode(
    reader: impl std::io::BufRead,
    name: &str,
    plausible: Plausible,
    footer: Option<String>,
) -> Result<Recording, ReadError> {
    let mut decoder =
        DecoderApp::decode_eager(reader).map_err(|e| ReadError(format!("{name} is not a Rerun recording: {e}")))?;
    // The Arrow IPC reader under the decoder can panic on damaged bytes (arrow-buffer 58 slices
    // out of bounds; found by fuzzing). A panic ends the reading like any other damage, keeping
    // the messages before it.
    let mut panicked = false;
    let messages = std::iter::from_fn(|| {
        if panicked {
            return None;
        }
        match quietly(|| decoder.next()) {
            Ok(next) => next.map(|m| m.map_err(|e| e.to_string())),
            Err(_) => {
                panicked = true;
                Some(Err("the Rerun decoder failed on damaged data".to_string()))
            }
        }
    });
    let mut recording = from_messages(messages);
    if recording.problem.is_none() {
        recording.problem = footer.or_else(|| footer_problem(&decoder));
    }
    plausible.report_into(&mut recording.problem);
    Ok(recording)
}

/// What is wrong with the footers the decoder read, if anything: each footer's manifest (the
/// index of every chunk a finished recording ends with) must decode and pass Rerun's own
/// sanity checks, as `rerun rrd verify` requires. A recording cut before its footer has none.
fn footer_problem<R: std::io::BufRead>(decoder: &DecoderIterator<LogMsg, R>) -> Option<String> {
    let manifests = match quietly(|| decoder.rrd_manifests()) {
        Ok(Ok(manifests)) => manifests,
        Ok(Err(e)) => return Some(format!("the footer's chunk index is corrupt: {e}")),
        Err(DecoderPanicked) => return Some("the footer's chunk index is corrupt".to_string()),
    };
    manifests.iter().find_map(|raw| match quietly(|| RrdManifest::try_new(raw)) {
        Ok(Ok(_)) => None,
        Ok(Err(e)) => Some(format!("the footer's chunk index is corrupt: {e}")),
        Err(DecoderPanicked) => Some("the footer's chunk index is corrupt".to_string()),
    })
}

/// The components and timelines a recording is read by.
struct Names {
    scalars: ComponentIdentifier,
    text: ComponentIdentifier,
    log_text: ComponentIdentifier,
    /// Blueprint components (`rerun.blueprint.archetypes.ViewBlueprint`, `ViewContents`); the
    /// archetypes themselves are not re-exported by the `rerun` crate.
    class: ComponentIdentifier,
    display_name: ComponentIdentifier,
    origin: ComponentIdentifier,
    query: ComponentIdentifier,
    step: TimelineName,
    time: TimelineName,
}

impl Names {
    fn new() -> Self {
        Self {
            scalars: rerun::Scalars::descriptor_scalars().component,
            text: rerun::TextDocument::descriptor_text().component,
            log_text: rerun::TextLog::descriptor_text().component,
            class: ComponentIdentifier::from("ViewBlueprint:class_identifier"),
            display_name: ComponentIdentifier::from("ViewBlueprint:display_name"),
            origin: ComponentIdentifier::from("ViewBlueprint:space_origin"),
            query: ComponentIdentifier::from("ViewContents:query"),
            step: TimelineName::from(schema::STEP),
            time: TimelineName::from(schema::SIM_TIME),
        }
    }
}

/// Builds a [`Recording`] from log messages (a file's, or an in-memory stream's).
pub fn from_messages(messages: impl Iterator<Item = Result<LogMsg, String>>) -> Recording {
    let names = Names::new();
    let mut recording = Recording::default();
    let mut views: std::collections::BTreeMap<String, View> = Default::default();
    for message in messages {
        let message = match message {
            Ok(m) => m,
            Err(e) => {
                recording.problem = Some(format!("decoding stopped after {} messages: {e}", recording.messages));
                break;
            }
        };
        recording.messages += 1;
        let LogMsg::ArrowMsg(store, arrow) = message else { continue };
        let chunk = match Chunk::from_arrow_msg(&arrow) {
            Ok(c) => c,
            Err(e) => {
                recording.problem = Some(format!("message {} is not a valid chunk: {e}", recording.messages));
                break;
            }
        };
        if store.is_blueprint() {
            recording.blueprint_messages += 1;
            read_view(&chunk, &names, &mut views);
        } else {
            let id = store.recording_id().as_str();
            let first = recording.recording_id.get_or_insert_with(|| id.to_string());
            if first != id {
                // One file is one run: a message under another id is damage (or a file put
                // together from two), and nothing from it on is that run's.
                recording.problem = Some(format!(
                    "message {} belongs to recording {id}, not to the file's {first}",
                    recording.messages
                ));
                break;
            }
            read_data(&chunk, &names, &mut recording);
        }
    }
    recording.views = views.into_values().filter(|v| !v.class.is_empty()).collect();
    for series in recording.series.values_mut() {
        series.sort_by_step();
    }
    recording
}

/// The entity path without its leading `/`.
fn entity_of(chunk: &Chunk) -> String {
    chunk.entity_path().to_string().trim_start_matches('/').to_string()
}

/// A blueprint chunk: a view's class, name and origin, or its contents.
fn read_view(chunk: &Chunk, names: &Names, views: &mut std::collections::BTreeMap<String, View>) {
    let entity = entity_of(chunk);
    let strings = |id: ComponentIdentifier| -> Vec<String> {
        chunk.iter_slices::<String>(id).flatten().map(|s| s.as_str().to_string()).collect()
    };
    let Some(id) = entity.strip_prefix("view/") else { return };
    if let Some(id) = id.strip_suffix("/ViewContents") {
        let view = views.entry(id.to_string()).or_default();
        view.contents.extend(strings(names.query));
    } else if let Some((id, property)) = id.split_once('/').filter(|(_, p)| !p.contains('/')) {
        views.entry(id.to_string()).or_default().properties.push(property.to_string());
    } else if !id.contains('/') {
        let view = views.entry(id.to_string()).or_default();
        if let Some(c) = strings(names.class).pop() {
            view.class = c;
        }
        if let Some(n) = strings(names.display_name).pop() {
            view.name = n;
        }
        if let Some(o) = strings(names.origin).pop() {
            view.origin = o;
        }
    }
}

/// A recording chunk: static texts, scalar series by step and time, and text logs.
fn read_data(chunk: &Chunk, names: &Names, recording: &mut Recording) {
    let entity = entity_of(chunk);
    recording.entities.insert(entity.clone());
    if chunk.is_static() {
        for texts in chunk.iter_slices::<String>(names.text) {
            if let Some(t) = texts.last() {
                recording.static_texts.insert(entity.clone(), t.as_str().to_string());
            }
        }
        return;
    }
    if chunk.components().get_array(names.scalars).is_some() {
        read_scalars(chunk, names, &entity, recording);
    }
    if chunk.components().get_array(names.log_text).is_some() {
        let times = chunk.iter_component_indices(names.time, names.log_text);
        for ((time, _), texts) in times.zip(chunk.iter_slices::<String>(names.log_text)) {
            for t in texts {
                recording.text_logs.push((entity.clone(), time.as_i64() as f64 / 1e9, t.as_str().to_string()));
            }
        }
    }
}

/// A chunk of `Scalars`: a total as one series named by its entity, a multi-instance entity of
/// the schema ([`schema::is_instanced`]) as one series per instance, `entity[i]`.
fn read_scalars(chunk: &Chunk, names: &Names, entity: &str, recording: &mut Recording) {
    let instanced = schema::is_instanced(entity);
    let steps = chunk.iter_component_indices(names.step, names.scalars);
    let times = chunk.iter_component_indices(names.time, names.scalars);
    for (((step, _), (time, _)), values) in steps.zip(times).zip(chunk.iter_slices::<f64>(names.scalars)) {
        let (step, time) = (step.as_i64(), time.as_i64() as f64 / 1e9);
        let row: Vec<(String, f64)> = if instanced {
            values.iter().enumerate().map(|(i, v)| (schema::instance_series(entity, i), *v)).collect()
        } else {
            vec![(entity.to_string(), values.first().copied().unwrap_or(f64::NAN))]
        };
        for (name, value) in row {
            let series = recording.series.entry(name).or_default();
            series.steps.push(step);
            series.times.push(time);
            series.values.push(value);
        }
    }
}
