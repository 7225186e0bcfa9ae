//! The MCAP log format: the frames a recording is made of, as protobuf messages, so that
//! robotics tools (Foxglove, the `mcap` readers) read them and `slipfront replay` can turn them
//! back into exactly the recording of the live run.
//!
//! | topic | message | when |
//! |---|---|---|
//! | `/slipfront/run` | `Run` (TOML header: plan, layout) | once, at t = 0 |
//! | `/contact/segments` | `SegmentStates` (arrays over segments) | every recorded step |
//! | `/body/nodes` | `NodeDisplacements` (recorded contact-surface nodes) | every recorded step, blocks |
//! | `/body/mesh` | `MeshDisplacements` (every node) | every recorded step, with spatial views |
//! | `/contact/totals` | `Totals` (friction force, base, block) | every recorded step |
//! | `/events` | `SlipEvent` | at each event's onset |
//! | `/ruptures` | `Rupture` | at each rupture's onset |
//! | `/slipfront/ending` | `Ending` (TOML) | once, at the last recorded time |
//!
//! Messages are stamped with simulated time in nanoseconds (`log_time` = `publish_time`).

use serde::{Deserialize, Serialize};

use crate::frame::Layout;
use crate::record::schema::RecordingPlan;

/// Version tag of the header.
pub const FORMAT: &str = "slipfront-mcap/1";

pub const TOPIC_RUN: &str = "/slipfront/run";
pub const TOPIC_SEGMENTS: &str = "/contact/segments";
pub const TOPIC_NODES: &str = "/body/nodes";
pub const TOPIC_MESH: &str = "/body/mesh";
pub const TOPIC_TOTALS: &str = "/contact/totals";
pub const TOPIC_EVENTS: &str = "/events";
pub const TOPIC_RUPTURES: &str = "/ruptures";
pub const TOPIC_ENDING: &str = "/slipfront/ending";

/// Every topic and its message type.
pub const TOPICS: [(&str, &str); 8] = [
    (TOPIC_RUN, "Run"),
    (TOPIC_SEGMENTS, "SegmentStates"),
    (TOPIC_NODES, "NodeDisplacements"),
    (TOPIC_MESH, "MeshDisplacements"),
    (TOPIC_TOTALS, "Totals"),
    (TOPIC_EVENTS, "SlipEvent"),
    (TOPIC_RUPTURES, "Rupture"),
    (TOPIC_ENDING, "Ending"),
];

/// The `Run` message's header: everything needed to rebuild the recording.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LogHeader {
    pub format: String,
    /// The plan, with the recorded segments and nodes resolved to indices.
    pub plan: RecordingPlan,
    pub layout: Layout,
}

/// Simulated time (s) as MCAP nanoseconds.
pub fn nanos(time: f64) -> u64 {
    (time.max(0.0) * 1e9).round() as u64
}
