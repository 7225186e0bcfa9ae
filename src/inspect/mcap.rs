//! Reads a slipfront MCAP log back into frames and a catalog.
//!
//! Damaged files yield what came before the damage: messages are read in file order and the
//! first error ends the reading, with [`Log::problem`] saying where and why. Channels of other
//! producers are counted in [`Log::skipped`] and otherwise ignored.

use std::collections::BTreeMap;
use std::path::Path;

use prost::Message as _;

use crate::catalog::events::Catalog;
use crate::frame::{Frame, SegmentSample};
use crate::inspect::ReadError;
use crate::inspect::framing;
use crate::inspect::unwind::{DecoderPanicked, quietly};
use crate::record::mcap::{self as format, LogHeader};
use crate::record::proto;
use crate::record::schema::RunEnding;

/// The largest MCAP log read (bytes): a log is read whole, and its frames held in memory.
pub const MAX_LOG_BYTES: u64 = 16 << 30;

/// What a log is, for the refusal of anything else.
pub const LOG: &str = "an MCAP log is a .mcap file that slipfront wrote, read whole into memory";

/// A log read back.
#[derive(Debug, Clone)]
pub struct Log {
    pub header: LogHeader,
    /// Complete frames, by step.
    pub frames: Vec<Frame>,
    pub catalog: Catalog,
    /// How the run ended, if the log got that far.
    pub ending: Option<RunEnding>,
    /// Messages decoded.
    pub messages: usize,
    /// Why reading stopped early or what was dropped, if anything.
    pub problem: Option<String>,
    /// Messages of channels that are not slipfront's, by topic.
    pub skipped: BTreeMap<String, usize>,
}

/// The parts of a frame as they arrive, one message per topic.
#[derive(Default)]
struct Parts {
    segments: Option<proto::SegmentStates>,
    nodes: Option<proto::NodeDisplacements>,
    mesh: Option<proto::MeshDisplacements>,
    totals: Option<proto::Totals>,
}

/// Reads `path`. Errors only when nothing usable is there (not MCAP, no run header).
pub fn read(path: &Path) -> Result<Log, ReadError> {
    // Whatever does not start as an MCAP file does is refused before it is read whole.
    let (mut file, len) = crate::files::open_regular(path, LOG).map_err(|e| ReadError(e.to_string()))?;
    let mut magic = [0u8; 8];
    if len >= 8 && (std::io::Read::read_exact(&mut file, &mut magic).is_err() || magic != *mcap::MAGIC) {
        return Err(ReadError(format!(
            "{} is not an MCAP file: it does not start with the MCAP magic",
            path.display()
        )));
    }
    let bytes = crate::files::read_capped(path, MAX_LOG_BYTES, LOG).map_err(|e| ReadError(e.to_string()))?;
    from_bytes(&bytes, &path.display().to_string())
}

/// As [`read`], from the bytes of a log; `name` stands for the file in messages.
pub fn from_bytes(bytes: &[u8], name: &str) -> Result<Log, ReadError> {
    if bytes.is_empty() {
        return Err(ReadError(format!("{name} is empty: no MCAP log to read")));
    }
    // The MCAP parser trusts the sizes in record headers: give it only the prefix whose sizes
    // are plausible. Should it still panic on what it reads, say so rather than abort.
    let plausible = framing::mcap(&mut &*bytes, bytes.len() as u64);
    let mut log = quietly(|| decode(plausible.prefix(bytes), name)).unwrap_or_else(|DecoderPanicked| {
        Err(ReadError(format!("{name}: the MCAP reader failed on damaged data; nothing was recovered")))
    })?;
    plausible.report_into(&mut log.problem);
    Ok(log)
}

fn decode(bytes: &[u8], name: &str) -> Result<Log, ReadError> {
    let stream = mcap::MessageStream::new(bytes).map_err(|e| ReadError(format!("{name} is not an MCAP file: {e}")))?;
    let mut read = Reading::default();
    let mut messages = 0usize;
    let mut problem = None;
    let mut skipped: BTreeMap<String, usize> = BTreeMap::new();
    for message in stream {
        let message = match message {
            Ok(m) => m,
            Err(e) => {
                problem = Some(format!(
                    "the log is damaged after {messages} messages ({e}); the messages before it were kept"
                ));
                break;
            }
        };
        let schema = message.channel.schema.as_ref().map(|s| s.name.as_str()).unwrap_or("");
        let topic = message.channel.topic.as_str();
        let known = format::TOPICS.iter().any(|(t, m)| *t == topic && schema == proto::full_name(m));
        if !known || message.channel.message_encoding != "protobuf" {
            *skipped.entry(topic.to_string()).or_default() += 1;
            continue;
        }
        if let Err(e) = read.take(topic, &message.data, messages + 1) {
            problem = Some(format!("{e}; the messages before it were kept"));
            break;
        }
        messages += 1;
    }
    let Some(header) = read.header else {
        let others = if skipped.is_empty() {
            String::new()
        } else {
            format!(" (it holds {:?})", skipped.keys().collect::<Vec<_>>())
        };
        return Err(ReadError(format!(
            "{name} holds no slipfront run header on {}{others}: not a slipfront log, or damaged before it",
            format::TOPIC_RUN
        )));
    };
    let (frames, incomplete) = assemble(&header, read.parts);
    if incomplete > 0 {
        let note = format!("{incomplete} recorded steps were incomplete and dropped");
        problem = Some(match problem {
            Some(p) => format!("{p}; {note}"),
            None => note,
        });
    }
    let mut catalog = read.catalog;
    catalog.events.sort_by(|a, b| a.onset.total_cmp(&b.onset).then(a.segment.cmp(&b.segment)));
    catalog.ruptures.sort_by(|a, b| a.onset.total_cmp(&b.onset));
    Ok(Log { header, frames, catalog, ending: read.ending, messages, problem, skipped })
}

/// What the messages read so far hold.
#[derive(Default)]
struct Reading {
    header: Option<LogHeader>,
    parts: BTreeMap<u32, Parts>,
    catalog: Catalog,
    ending: Option<RunEnding>,
}

impl Reading {
    /// Decodes message number `number`, on a known `topic`, into what it holds.
    fn take(&mut self, topic: &str, data: &[u8], number: usize) -> Result<(), String> {
        let bad = |e: prost::DecodeError| format!("message {number} on {topic} does not decode: {e}");
        match topic {
            format::TOPIC_RUN => {
                let run = proto::Run::decode(data).map_err(bad)?;
                let parsed: LogHeader =
                    toml::from_str(&run.header).map_err(|e| format!("the run header is unreadable: {e}"))?;
                if parsed.format != format::FORMAT {
                    return Err(format!("log format {} is not {}", parsed.format, format::FORMAT));
                }
                self.header = Some(parsed);
            }
            format::TOPIC_SEGMENTS => {
                let m = proto::SegmentStates::decode(data).map_err(bad)?;
                let step = m.step;
                self.parts.entry(step).or_default().segments = Some(m);
            }
            format::TOPIC_NODES => {
                let m = proto::NodeDisplacements::decode(data).map_err(bad)?;
                let step = m.step;
                self.parts.entry(step).or_default().nodes = Some(m);
            }
            format::TOPIC_MESH => {
                let m = proto::MeshDisplacements::decode(data).map_err(bad)?;
                let step = m.step;
                self.parts.entry(step).or_default().mesh = Some(m);
            }
            format::TOPIC_TOTALS => {
                let m = proto::Totals::decode(data).map_err(bad)?;
                let step = m.step;
                self.parts.entry(step).or_default().totals = Some(m);
            }
            format::TOPIC_EVENTS => self.catalog.events.push(proto::SlipEvent::decode(data).map_err(bad)?.into()),
            format::TOPIC_RUPTURES => self.catalog.ruptures.push(proto::Rupture::decode(data).map_err(bad)?.into()),
            format::TOPIC_ENDING => {
                let m = proto::Ending::decode(data).map_err(bad)?;
                self.ending =
                    Some(toml::from_str(&m.ending).map_err(|e| format!("the ending record is unreadable: {e}"))?);
            }
            _ => unreachable!("known topics only"),
        }
        Ok(())
    }
}

/// Builds frames from their parts; returns them and how many steps lacked a part.
fn assemble(header: &LogHeader, parts: BTreeMap<u32, Parts>) -> (Vec<Frame>, usize) {
    let layout = &header.layout;
    let segments = layout.segments.len();
    let nodes_expected = match &header.plan.spec.nodes {
        crate::case::Selection::Indices(list) => !list.is_empty(),
        _ => false,
    };
    let mesh_expected = header.plan.spec.spatial && layout.mesh.is_some();
    // Every node of the mesh, once per axis: a message that decodes with fewer (damage inside a
    // chunk whose checksum the reader does not test) would leave the drawing without them.
    let mesh_nodes = layout.mesh.as_ref().map_or(0, |m| m.nodes.len());
    let whole = |m: &proto::MeshDisplacements| m.u_x.len() == mesh_nodes && m.u_y.len() == mesh_nodes;
    let mut frames = Vec::with_capacity(parts.len());
    let mut incomplete = 0;
    let mut previous_time = 0.0;
    for (step, p) in parts {
        let (Some(s), Some(totals)) = (p.segments, p.totals) else {
            incomplete += 1;
            continue;
        };
        if (nodes_expected && p.nodes.is_none())
            || (mesh_expected && !p.mesh.as_ref().is_some_and(whole))
            || s.slip_rate.len() != segments
        {
            incomplete += 1;
            continue;
        }
        let at = |v: &Vec<f64>, k: usize| v.get(k).copied().unwrap_or(0.0);
        let samples = (0..segments)
            .map(|k| SegmentSample {
                traction_t: at(&s.traction_t, k),
                traction_n: at(&s.traction_n, k),
                sliding_ratio: at(&s.sliding_ratio, k),
                r_star: at(&s.r_star, k),
                structure: at(&s.structure, k),
                slip_rate: at(&s.slip_rate, k),
                slip: at(&s.slip, k),
                // An evolving contact's segment is open where its mean normal traction is 0
                // (it is 0 at every point then); a held contact's never is.
                open: layout.segment_evolves(k) && !s.traction_n.is_empty() && at(&s.traction_n, k) <= 0.0,
            })
            .collect();
        let mut surface_nodes = vec![[0.0; 2]; layout.surface_nodes.len()];
        if let Some(n) = &p.nodes {
            for (i, &j) in n.nodes.iter().enumerate() {
                if let Some(slot) = surface_nodes.get_mut(j as usize) {
                    *slot = [at(&n.u_x, i), at(&n.u_y, i)];
                }
            }
        }
        let mesh = p.mesh.map(|m| m.u_x.iter().zip(&m.u_y).map(|(x, y)| [*x, *y]).collect()).unwrap_or_default();
        let dt = if frames.is_empty() { 0.0 } else { s.time - previous_time };
        previous_time = s.time;
        frames.push(Frame {
            step: step as u64,
            time: s.time,
            dt,
            segments: samples,
            surface_nodes,
            mesh,
            friction_force: totals.friction_force,
            // The log keeps the body's total only.
            contact_forces: Vec::new(),
            base_displacement: totals.base_u_x,
            block: layout.kind.has_block().then_some([totals.block_x, totals.block_v]),
        });
    }
    (frames, incomplete)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_whose_mesh_message_lacks_nodes_is_dropped() {
        // A damaged chunk can decode into a shorter mesh message; replaying it drew the mesh
        // from nodes that were not there, and panicked.
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/fuzz/regressions/mcap_read/ok-paper_triangular.mcap");
        let log = from_bytes(&std::fs::read(path).unwrap(), "log").unwrap();
        assert!(log.header.plan.spec.spatial, "a log with the spatial views");
        let nodes = log.header.layout.mesh.as_ref().expect("a block").nodes.len();
        let segments = log.header.layout.segments.len();
        let step = |mesh_nodes: usize| {
            let parts = Parts {
                segments: Some(proto::SegmentStates { slip_rate: vec![0.0; segments], ..Default::default() }),
                totals: Some(proto::Totals::default()),
                nodes: Some(proto::NodeDisplacements::default()),
                mesh: Some(proto::MeshDisplacements {
                    u_x: vec![0.0; mesh_nodes],
                    u_y: vec![0.0; mesh_nodes],
                    ..Default::default()
                }),
            };
            assemble(&log.header, BTreeMap::from([(0, parts)]))
        };
        assert_eq!((step(nodes).0.len(), step(nodes).1), (1, 0));
        assert_eq!((step(nodes - 1).0.len(), step(nodes - 1).1), (0, 1));
    }
}
