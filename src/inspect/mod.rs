//! Reading recordings back and checking them (`slipfront check`).

pub mod arrow_message;
pub mod catalog;
pub mod check;
pub mod export;
pub mod framing;
pub mod mcap;
pub mod rrd;
pub mod unwind;

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;

/// A recording as read back: what `check` and the tests judge.
#[derive(Debug, Clone, Default)]
pub struct Recording {
    /// The recording id of its data (not its blueprint), if any data was read.
    pub recording_id: Option<String>,
    /// Scalar time series by entity path (without a leading `/`), sorted by step.
    pub series: BTreeMap<String, Series>,
    /// Every entity path with data in the recording store.
    pub entities: BTreeSet<String>,
    /// Static text documents by entity path.
    pub static_texts: BTreeMap<String, String>,
    /// Text-log entries: entity, `sim_time` (s), text.
    pub text_logs: Vec<(String, f64, String)>,
    /// Views of the blueprint stored in the file.
    pub views: Vec<View>,
    /// Messages decoded, and of them blueprint chunks.
    pub messages: usize,
    pub blueprint_messages: usize,
    /// Why decoding stopped early, if it did.
    pub problem: Option<String>,
}

/// How far (relative, of the time, at least 1 s) a time may pass a series' last row and still
/// be its last row's: rounding in the sum of steps, the same tolerance by which `check` lets a
/// run's last row stand for its end.
pub const END_TOLERANCE: f64 = 1e-6;

/// One scalar series.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Series {
    pub steps: Vec<i64>,
    /// `sim_time` (s).
    pub times: Vec<f64>,
    pub values: Vec<f64>,
}

impl Series {
    fn sort_by_step(&mut self) {
        if self.steps.windows(2).all(|w| w[0] <= w[1]) {
            return;
        }
        let mut order: Vec<usize> = (0..self.steps.len()).collect();
        order.sort_by_key(|&i| self.steps[i]);
        self.steps = order.iter().map(|&i| self.steps[i]).collect();
        self.times = order.iter().map(|&i| self.times[i]).collect();
        self.values = order.iter().map(|&i| self.values[i]).collect();
    }

    /// The value at the last row at or before `time` (s), with that row's time; `None` where
    /// `time` lies outside the rows: before the first, or after the last by more than
    /// [`END_TOLERANCE`] of it (a recording does not hold the value of a time it never reached).
    pub fn at(&self, time: f64) -> Option<(f64, f64)> {
        let last = *self.times.last()?;
        if time > last + END_TOLERANCE * last.abs().max(1.0) {
            return None;
        }
        let i = self.times.partition_point(|&t| t <= time + 1e-9 * time.abs().max(1.0));
        (i > 0).then(|| (self.times[i - 1], self.values[i - 1]))
    }
}

/// A view of a stored blueprint.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct View {
    /// `Spatial2D`, `TimeSeries`, `TextLog`, ...
    pub class: String,
    pub name: String,
    pub origin: String,
    /// Entity-path queries.
    pub contents: Vec<String>,
    /// The view properties stored beside it (`TimeAxis`, `PlotLegend`, ...).
    pub properties: Vec<String>,
}

/// A recording that cannot be read at all.
#[derive(Debug, Clone, PartialEq)]
pub struct ReadError(pub String);

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

impl std::error::Error for ReadError {}
