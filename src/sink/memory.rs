//! What each sink remembers across a checkpoint ([`crate::sink::Sink::checkpoint`]), as data.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::record::schema::DecimatorMemory;
use crate::sink::spacetime::SpaceTimeMemory;

/// What a sink remembers across a checkpoint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum SinkMemory {
    /// Nothing: the sink writes its file from the catalog at the end (the catalog CSVs).
    Nothing,
    /// The Rerun recording's ([`RecordingMemory`]).
    Recording(RecordingMemory),
    /// The MCAP log's ([`LogMemory`]).
    Log(LogMemory),
}

/// What the Rerun sink remembers across a checkpoint: the step it was taken at (the
/// recording holds every row up to it), the rows and last time recorded, every series' digest
/// over those rows (by which `slipfront resume` knows the recording it continues as this run's
/// up to the checkpoint), the decimators' memories, the slip front's last state and the
/// space-time map so far.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecordingMemory {
    pub through: u64,
    pub rows: u64,
    pub last_time: f64,
    pub digests: BTreeMap<String, String>,
    pub decimator: DecimatorMemory,
    pub views: (Option<(u64, f64)>, Vec<bool>),
    pub slip_front: Option<Vec<bool>>,
    pub spacetime: Option<SpaceTimeMemory>,
}

/// What the MCAP sink remembers across a checkpoint: the rows written (the log holds them
/// all), the digest of each per-row topic's messages so far
/// ([`crate::record::digest::MessageDigest`]), the last message's sequence number, the last
/// time recorded, and the decimator's memory.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LogMemory {
    pub rows: u64,
    pub digests: BTreeMap<String, String>,
    pub sequence: u32,
    pub last_time: f64,
    pub decimator: DecimatorMemory,
}
