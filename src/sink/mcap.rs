//! The MCAP sink (`slipfront run --mcap PATH`): the recorded frames as protobuf messages
//! ([`crate::record::mcap`]), zstd-compressed chunks with a summary and chunk indexes.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use mcap::records::MessageHeader;
use mcap::{WriteOptions, Writer};
use prost::Message as _;

use crate::case::Selection;
use crate::catalog::events::Catalog;
use crate::frame::Ending;
use crate::frame::Quantity;
use crate::frame::{Frame, Layout, Needs};
use crate::record::digest::MessageDigest;
use crate::record::mcap::{self as mcap_log, LogHeader, nanos};
use crate::record::proto;
use crate::record::schema::{Decimator, RecordingPlan, RunEnding, selection};
use crate::sink::cadence::Cadence;
use crate::sink::memory::LogMemory;
use crate::sink::{Continuation, Sink, SinkError, SinkMemory, sync};

/// Writes a slipfront MCAP log.
pub struct McapSink {
    path: PathBuf,
    writer: Option<Writer<BufWriter<File>>>,
    plan: RecordingPlan,
    decimator: Decimator,
    channels: BTreeMap<&'static str, u16>,
    sequence: u32,
    nodes: Vec<usize>,
    mesh: bool,
    rows: u64,
    /// When the open chunk is finished and written ([`Cadence`]).
    cadence: Cadence,
    last_time: f64,
    needs: Needs,
    /// The log this one continues, for a resumed run.
    continuation: Option<Continuation>,
    /// The digest of each per-row topic's messages so far.
    digests: BTreeMap<&'static str, MessageDigest>,
}

impl McapSink {
    /// Creates the file now, so that an unwritable path fails before the run.
    pub fn create(path: &Path, plan: RecordingPlan) -> Result<Self, String> {
        let file = File::create(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        let writer = WriteOptions::new()
            .compression_threads(0)
            .library(concat!("slipfront ", env!("CARGO_PKG_VERSION")))
            .create(BufWriter::new(file))
            .map_err(|e| format!("cannot start the MCAP log {}: {e}", path.display()))?;
        let needs = Needs { segment_state: plan.spec.quantities.iter().any(|q| q.needs_state()), ..Needs::default() };
        Ok(Self {
            path: path.to_path_buf(),
            writer: Some(writer),
            decimator: Decimator::new(&plan),
            plan,
            channels: BTreeMap::new(),
            sequence: 0,
            nodes: Vec::new(),
            mesh: false,
            rows: 0,
            cadence: Cadence::default(),
            last_time: 0.0,
            needs,
            continuation: None,
            digests: BTreeMap::new(),
        })
    }

    /// The same sink continuing the log of an interrupted run ([`Continuation`]); it was
    /// created at the continuation's `writing` path.
    pub fn continuing(mut self, continuation: Continuation) -> Self {
        self.continuation = Some(continuation);
        self
    }

    /// The topics written once per recorded row.
    fn row_topics(&self) -> Vec<&'static str> {
        let mut topics = vec![mcap_log::TOPIC_SEGMENTS, mcap_log::TOPIC_TOTALS];
        if !self.nodes.is_empty() {
            topics.push(mcap_log::TOPIC_NODES);
        }
        if self.mesh {
            topics.push(mcap_log::TOPIC_MESH);
        }
        topics
    }

    /// Copies the continued log's rows up to the checkpoint into this one, checks that they
    /// are all there, and continues the topics' digests over them.
    fn continue_log(&mut self, memory: &LogMemory) -> Result<(), SinkError> {
        let Some(continuation) = self.continuation.clone() else { return Ok(()) };
        let topics = self.row_topics();
        let Some(writer) = self.writer.as_mut() else {
            return Err(SinkError(format!("{} was abandoned after an earlier write error", self.path.display())));
        };
        let copied =
            crate::record::continuation::copy_log(&continuation.previous, writer, &self.channels, &topics, memory.rows)
                .map_err(SinkError)?;
        if let Some((topic, (count, _))) = copied.iter().find(|(_, (c, _))| *c != memory.rows) {
            return Err(SinkError(format!(
                "{} holds {count} messages on {topic} before the checkpoint, where the checkpoint counts {} rows: \
                 it is not this run's log up to its checkpoint",
                continuation.previous.display(),
                memory.rows
            )));
        }
        if let Err(e) = writer.flush() {
            return Err(self.abandon("cannot write", e));
        }
        self.digests = copied.into_iter().map(|(topic, (_, digest))| (topic, digest)).collect();
        Ok(())
    }

    fn write(&mut self, topic: &'static str, time: f64, data: &[u8]) -> Result<(), SinkError> {
        let channel_id = self.channels[topic];
        self.sequence = self.sequence.wrapping_add(1);
        let header =
            MessageHeader { channel_id, sequence: self.sequence, log_time: nanos(time), publish_time: nanos(time) };
        let Some(writer) = self.writer.as_mut() else {
            return Err(SinkError(format!("{} was abandoned after an earlier write error", self.path.display())));
        };
        writer.write_to_known_channel(&header, data).map_err(|e| self.abandon("cannot write", e))?;
        if let Some(digest) = self.digests.get_mut(topic) {
            digest.add(header.sequence, header.log_time, data);
        }
        Ok(())
    }

    /// Gives up the log after a write error (a full disk, say) and says why. The `mcap` writer
    /// panics if dropped after a failed write (0.25: its `Drop` finishes the file through a
    /// writer the failure took away), so it is forgotten instead: the bytes already written stay
    /// a readable log up to the last complete chunk.
    fn abandon(&mut self, doing: &str, e: mcap::McapError) -> SinkError {
        if let Some(writer) = self.writer.take() {
            std::mem::forget(writer);
        }
        let cause = std::error::Error::source(&e).map(|s| format!(": {s}")).unwrap_or_default();
        SinkError(format!("{doing} {}: {e}{cause}", self.path.display()))
    }
}

impl McapSink {
    /// Writes one recorded step on every topic the plan asks for.
    fn write_row(&mut self, frame: &Frame) -> Result<(), SinkError> {
        let step =
            u32::try_from(frame.step).map_err(|_| SinkError(format!("step {} exceeds the log's u32", frame.step)))?;
        let wanted = |q: Quantity| self.plan.spec.quantities.contains(&q);
        let column = |q: Quantity| -> Vec<f64> {
            if wanted(q) { frame.segments.iter().map(|s| q.of(s)).collect() } else { Vec::new() }
        };
        let segments = proto::SegmentStates {
            time: frame.time,
            step,
            traction_t: column(Quantity::TractionT),
            traction_n: column(Quantity::TractionN),
            sliding_ratio: column(Quantity::R),
            r_star: column(Quantity::RStar),
            structure: column(Quantity::Structure),
            // The spatial and space-time views colour every segment by its slip rate.
            slip_rate: frame.segments.iter().map(|s| s.slip_rate).collect(),
            slip: column(Quantity::Slip),
        };
        self.write(mcap_log::TOPIC_SEGMENTS, frame.time, &segments.encode_to_vec())?;
        if !self.nodes.is_empty() {
            let nodes = proto::NodeDisplacements {
                time: frame.time,
                step,
                nodes: self.nodes.iter().map(|&j| j as u32).collect(),
                u_x: self.nodes.iter().map(|&j| frame.surface_nodes[j][0]).collect(),
                u_y: self.nodes.iter().map(|&j| frame.surface_nodes[j][1]).collect(),
            };
            self.write(mcap_log::TOPIC_NODES, frame.time, &nodes.encode_to_vec())?;
        }
        if self.mesh {
            let mesh = proto::MeshDisplacements {
                time: frame.time,
                step,
                u_x: frame.mesh.iter().map(|u| u[0]).collect(),
                u_y: frame.mesh.iter().map(|u| u[1]).collect(),
            };
            self.write(mcap_log::TOPIC_MESH, frame.time, &mesh.encode_to_vec())?;
        }
        let [block_x, block_v] = frame.block.unwrap_or([0.0, 0.0]);
        let totals = proto::Totals {
            time: frame.time,
            step,
            friction_force: frame.friction_force,
            base_u_x: frame.base_displacement,
            block_x,
            block_v,
        };
        self.write(mcap_log::TOPIC_TOTALS, frame.time, &totals.encode_to_vec())?;
        self.rows += 1;
        self.last_time = frame.time;
        if self.cadence.row() {
            // Ends the chunk and hands it to the disk: a killed run's log is readable to here.
            let writer = self.writer.as_mut().expect("checked by write");
            writer.flush().map_err(|e| self.abandon("cannot write", e))?;
        }
        Ok(())
    }
}

impl Sink for McapSink {
    fn needs(&self) -> Needs {
        self.needs
    }

    fn begin(&mut self, layout: &Layout) -> Result<(), SinkError> {
        let (segments, nodes) = selection(&self.plan.spec, layout);
        self.mesh = self.plan.spec.spatial && layout.mesh.is_some();
        self.needs.surface_nodes = !nodes.is_empty();
        self.needs.mesh = self.mesh;
        self.nodes = nodes.clone();
        let mut plan = self.plan.clone();
        plan.spec.segments = Selection::Indices(segments);
        plan.spec.nodes = Selection::Indices(nodes);
        let header = LogHeader { format: mcap_log::FORMAT.into(), plan, layout: layout.clone() };
        let text = toml::to_string(&header).map_err(|e| SinkError(format!("cannot describe the run: {e}")))?;
        let descriptor = proto::file_descriptor_set();
        for (topic, message) in mcap_log::TOPICS {
            let writer = self.writer.as_mut().expect("the writer lives until finish");
            let channel = writer
                .add_schema(&proto::full_name(message), "protobuf", &descriptor)
                .and_then(|schema| writer.add_channel(schema, topic, "protobuf", &BTreeMap::new()));
            let channel = channel.map_err(|e| self.abandon("cannot write", e))?;
            self.channels.insert(topic, channel);
        }
        self.digests = self.row_topics().into_iter().map(|topic| (topic, MessageDigest::default())).collect();
        self.write(mcap_log::TOPIC_RUN, 0.0, &proto::Run { header: text }.encode_to_vec())
    }

    fn record(&mut self, frame: &Frame) -> Result<(), SinkError> {
        if self.decimator.keep(frame) { self.write_row(frame) } else { Ok(()) }
    }

    fn writes(&self, frame: &Frame) -> bool {
        self.decimator.would_keep(frame)
    }

    fn checkpoint(&mut self) -> Result<SinkMemory, SinkError> {
        let Some(writer) = self.writer.as_mut() else {
            return Err(SinkError(format!("{} was abandoned after an earlier write error", self.path.display())));
        };
        if let Err(e) = writer.flush() {
            return Err(self.abandon("cannot write", e));
        }
        sync(&self.path)?;
        Ok(SinkMemory::Log(LogMemory {
            rows: self.rows,
            digests: self.digests.iter().map(|(topic, digest)| (topic.to_string(), digest.hex())).collect(),
            sequence: self.sequence,
            last_time: self.last_time,
            decimator: self.decimator.memory(),
        }))
    }

    fn resume(&mut self, saved: &[SinkMemory]) -> Result<(), SinkError> {
        let Some(memory) = saved.iter().find_map(|m| match m {
            SinkMemory::Log(memory) => Some(memory),
            _ => None,
        }) else {
            return Err(SinkError("the checkpoint's run wrote no MCAP log to continue".into()));
        };
        self.continue_log(memory)?;
        (self.rows, self.sequence, self.last_time) = (memory.rows, memory.sequence, memory.last_time);
        self.decimator.resume(memory.decimator);
        Ok(())
    }

    fn finish(&mut self, ending: Ending, last: Option<&Frame>, catalog: &Catalog) -> Result<(), SinkError> {
        if self.writer.is_none() || self.channels.is_empty() {
            return Ok(());
        }
        if let Some(frame) = last
            && self.decimator.keep_last(frame)
        {
            self.write_row(frame)?;
        }
        for e in &catalog.events {
            self.write(mcap_log::TOPIC_EVENTS, e.onset, &proto::SlipEvent::from(e).encode_to_vec())?;
        }
        for r in &catalog.ruptures {
            self.write(mcap_log::TOPIC_RUPTURES, r.onset, &proto::Rupture::from(r).encode_to_vec())?;
        }
        let summary = RunEnding::new(ending, self.last_time, self.rows, catalog, Default::default());
        let text = toml::to_string(&summary).map_err(|e| SinkError(format!("cannot describe the ending: {e}")))?;
        self.write(mcap_log::TOPIC_ENDING, self.last_time, &proto::Ending { ending: text }.encode_to_vec())?;
        // The summary and chunk indexes are written here; readers that seek need them.
        let writer = self.writer.as_mut().expect("checked above");
        if let Err(e) = writer.finish() {
            return Err(self.abandon("cannot finish", e));
        }
        let writer = self.writer.take().expect("checked above");
        writer.into_inner().flush().map_err(|e| SinkError(format!("cannot finish {}: {e}", self.path.display())))
    }
}

impl Ending {
    /// `completed`, `failed` or `interrupted`, as the logs record it.
    pub fn name(self) -> &'static str {
        match self {
            Ending::Completed => "completed",
            Ending::Failed => "failed",
            Ending::Interrupted => "interrupted",
        }
    }
}
