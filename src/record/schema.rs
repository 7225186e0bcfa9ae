//! The recording schema: timelines, entity paths and units, shared by the writer
//! ([`crate::sink::rerun`]) and the reader (`slipfront check`). The README's table is this module.

use serde::{Deserialize, Serialize};

use crate::case::{Case, RecordSpec};
use crate::dynamics::Method;
use crate::frame::{Frame, Layout, Quantity, SceneKind};

/// Application id of every recording.
pub const APP_ID: &str = "slipfront";
/// Simulated time (a duration timeline, seconds).
pub const SIM_TIME: &str = "sim_time";
/// Step counter (a sequence timeline; 0 is the initial state).
pub const STEP: &str = "step";

/// Static `TextDocument` (TOML) describing the run: what was recorded, so a reader knows what
/// to expect ([`RunInfo`]).
pub const RUN_INFO: &str = "slipfront/run";
/// Static `TextDocument` (TOML) written last: how the run ended ([`RunEnding`]).
pub const RUN_ENDING: &str = "slipfront/ending";
/// Total friction force `Σ w f_t` (N/m; Pa for unit-area scenes).
pub const FRICTION_FORCE: &str = "contact/friction_force";
/// Displacement of the base along x (m); for a spring-block, of the spring's far end.
pub const BASE_UX: &str = "base/u_x";
/// Spring-block displacement (m) and velocity (m/s).
pub const BLOCK_X: &str = "block/x";
pub const BLOCK_V: &str = "block/v";
/// The spatial view: deformed mesh lines, contact segments coloured by state, the base.
pub const SPATIAL: &str = "spatial";
pub const SPATIAL_MESH: &str = "spatial/mesh";
pub const SPATIAL_CONTACT: &str = "spatial/contact";
pub const SPATIAL_BASE: &str = "spatial/base";
pub const SPATIAL_SPRING: &str = "spatial/spring";
/// The space-time view: slip rate against position (across) and time (down), and the cursor.
pub const SPACETIME: &str = "spacetime";
pub const SPACETIME_IMAGE: &str = "spacetime/slip_rate";
pub const SPACETIME_NOW: &str = "spacetime/now";
/// Text log of slip events and ruptures at their onsets.
pub const EVENTS: &str = "events";

/// `contact/segments/{k}/{quantity}`.
pub fn segment_entity(segment: usize, quantity: Quantity) -> String {
    format!("contact/segments/{segment}/{}", quantity.name())
}

/// `body/nodes/{j}/u_x` (axis 0) or `u_y` (axis 1): contact-surface node `j` from the left.
pub fn node_entity(node: usize, axis: usize) -> String {
    format!("body/nodes/{node}/{}", if axis == 0 { "u_x" } else { "u_y" })
}

/// The run a recording (or MCAP log) describes, known before it starts.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecordingPlan {
    /// Case file stem.
    pub case: String,
    pub t_end: f64,
    pub dt: f64,
    /// Planned steps.
    pub steps: u64,
    /// The time integrator (`time.integrator`); Wilson's in recordings from before it was named.
    #[serde(default)]
    pub integrator: Method,
    /// The adaptive steps' tolerance, if steps are adaptive (`time.tolerance`, or Tsit5's default).
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// The Rerun recording id ([`recording_id`]); `None` in logs from before it was stored.
    #[serde(default)]
    pub recording_id: Option<String>,
    /// Why `time.integrator = "auto"` chose [`Self::integrator`]; `None` where the case named it.
    #[serde(default)]
    pub chosen_because: Option<String>,
    /// `time.accuracy`, where the case set the method's step or tolerance by it.
    #[serde(default)]
    pub accuracy: Option<f64>,
    pub slip_rate_threshold: f64,
    pub spec: RecordSpec,
}

impl RecordingPlan {
    /// The plan of a run of `case`, whose file stem is `name`.
    pub fn for_case(name: &str, case: &Case) -> Self {
        Self {
            case: name.into(),
            t_end: case.time.t_end,
            dt: case.time.dt,
            steps: case.time.steps(),
            integrator: case.time.method,
            tolerance: case.time.adaptive_tolerance(),
            recording_id: Some(recording_id(name, case)),
            chosen_because: case.time.chosen_because.clone(),
            accuracy: case.time.accuracy,
            slip_rate_threshold: case.slip_rate_threshold(),
            spec: case.record.clone(),
        }
    }

    /// How the run steps, for people: `in N steps of dt s`, or the adaptive integrator and its
    /// tolerance, and why where `auto` chose it.
    pub fn stepping(&self) -> String {
        stepping(self.integrator, self.tolerance, self.steps, self.dt, &self.chosen_because, self.accuracy)
    }
}

/// The recording id of a run of `case` named `name`: the name and an `xxh32` of the slipfront
/// version and every value of the case as resolved (its `Debug` form, floats in their shortest
/// round-trip digits). It is the same for every run of the same case and version, and differs
/// between any two runs that differ in a value (an override, an ensemble member's `1/R*`), so
/// that a Rerun server, which merges recordings of one id into one dataset segment, merges only
/// copies of the same run.
pub fn recording_id(name: &str, case: &Case) -> String {
    let text = format!("slipfront {} {case:?}", env!("CARGO_PKG_VERSION"));
    format!("{name}-{:08x}", xxhash_rust::xxh32::xxh32(text.as_bytes(), 0))
}

/// [`Method::describe`], with `time.accuracy` where it set the step or tolerance, and the reason
/// where `auto` chose the method.
fn stepping(
    method: Method,
    tolerance: Option<f64>,
    steps: u64,
    dt: f64,
    chosen_because: &Option<String>,
    accuracy: Option<f64>,
) -> String {
    let mut text = method.describe(tolerance, steps, dt);
    if let Some(accuracy) = accuracy {
        text.push_str(&format!(" (time.accuracy = {accuracy:e})"));
    }
    if let Some(why) = chosen_because {
        text.push_str(&format!("; time.integrator = \"auto\" chose {}: {why}", method.name()));
    }
    text
}

/// What a series reads from a frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Source {
    Segment(usize, Quantity),
    /// Contact-surface node and axis (0 = x, 1 = y).
    Node(usize, usize),
    FrictionForce,
    Base,
    BlockX,
    BlockV,
}

impl Source {
    /// The series' value in `frame`.
    pub fn of(self, frame: &Frame) -> f64 {
        match self {
            Source::Segment(k, q) => q.of(&frame.segments[k]),
            Source::Node(j, axis) => frame.surface_nodes[j][axis],
            Source::FrictionForce => frame.friction_force,
            Source::Base => frame.base_displacement,
            Source::BlockX => frame.block.map_or(f64::NAN, |b| b[0]),
            Source::BlockV => frame.block.map_or(f64::NAN, |b| b[1]),
        }
    }
}

/// One scalar time series of the schema.
#[derive(Debug, Clone, PartialEq)]
pub struct SeriesSpec {
    /// Entity path.
    pub path: String,
    pub source: Source,
    /// Name shown in plots, with the unit.
    pub label: String,
    /// Position along the surface as a fraction of its width, for colouring; `None` for totals.
    pub position: Option<f64>,
}

/// The segments and nodes that get time series under `spec`.
pub fn selection(spec: &RecordSpec, layout: &Layout) -> (Vec<usize>, Vec<usize>) {
    let named_segments: Vec<usize> =
        layout.segments.iter().enumerate().filter(|(_, s)| s.name.is_some()).map(|(k, _)| k).collect();
    let named_nodes: Vec<usize> =
        layout.surface_nodes.iter().enumerate().filter(|(_, n)| n.name.is_some()).map(|(k, _)| k).collect();
    (
        spec.segments.resolve(layout.segments.len(), &named_segments),
        spec.nodes.resolve(layout.surface_nodes.len(), &named_nodes),
    )
}

/// Every series of a recording, in the order they are written.
pub fn series_plan(layout: &Layout, segments: &[usize], nodes: &[usize], quantities: &[Quantity]) -> Vec<SeriesSpec> {
    let width = layout.segments.last().map_or(1.0, |s| s.right).max(f64::MIN_POSITIVE);
    let at = |x: f64| Some(if layout.segments.len() > 1 { x / width } else { 0.5 });
    let mut plan = Vec::new();
    for &k in segments {
        let seg = &layout.segments[k];
        let name = match &seg.name {
            Some(name) => format!("{name} (segment {k})"),
            None if layout.segments.len() > 1 => format!("segment {k}"),
            None => "contact".to_string(),
        };
        for &q in quantities {
            plan.push(SeriesSpec {
                path: segment_entity(k, q),
                source: Source::Segment(k, q),
                label: format!("{name}: {}", q.label()),
                position: at(0.5 * (seg.left + seg.right)),
            });
        }
    }
    for &j in nodes {
        let node = &layout.surface_nodes[j];
        let name = node.name.clone().unwrap_or_else(|| format!("node {j}"));
        for (axis, symbol) in [(0, "u_x (m)"), (1, "u_y (m)")] {
            plan.push(SeriesSpec {
                path: node_entity(j, axis),
                source: Source::Node(j, axis),
                label: format!("{name}: {symbol}"),
                position: at(node.x),
            });
        }
    }
    let total = |path: &str, source, label: String| SeriesSpec { path: path.into(), source, label, position: None };
    plan.push(total(FRICTION_FORCE, Source::FrictionForce, format!("friction force ({})", layout.kind.force_unit())));
    let spring = layout.kind == SceneKind::SpringBlock;
    plan.push(total(BASE_UX, Source::Base, if spring { "spring end u_x (m)" } else { "base u_x (m)" }.into()));
    if spring {
        plan.push(SeriesSpec { position: Some(0.0), ..total(BLOCK_X, Source::BlockX, "block x (m)".into()) });
        plan.push(SeriesSpec { position: Some(1.0), ..total(BLOCK_V, Source::BlockV, "block v (m/s)".into()) });
    }
    plan
}

/// What a recording holds, written into it as TOML at [`RUN_INFO`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunInfo {
    pub slipfront_version: String,
    /// Case file stem.
    pub case: String,
    /// Scene kind.
    pub kind: crate::frame::SceneKind,
    pub t_end: f64,
    pub dt: f64,
    /// Planned steps (fixed steps only).
    pub steps: u64,
    /// See [`RecordingPlan::integrator`].
    #[serde(default)]
    pub integrator: Method,
    /// See [`RecordingPlan::tolerance`].
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// See [`RecordingPlan::chosen_because`].
    #[serde(default)]
    pub chosen_because: Option<String>,
    /// See [`RecordingPlan::accuracy`].
    #[serde(default)]
    pub accuracy: Option<f64>,
    /// Contact segments of the scene.
    pub segments: usize,
    pub recorded_segments: Vec<usize>,
    /// Label of each recorded segment (its probe name, else `segment k`).
    pub segment_labels: Vec<String>,
    pub recorded_nodes: Vec<usize>,
    /// Label of each recorded node (its probe name, else `node j`).
    pub node_labels: Vec<String>,
    /// Which recorded segments and nodes are named probes.
    pub probe_segments: Vec<usize>,
    pub probe_nodes: Vec<usize>,
    pub quantities: Vec<Quantity>,
    /// Every scalar time series, by entity path.
    pub series: Vec<String>,
    /// Whether the spatial and space-time views were logged.
    pub spatial: bool,
    pub magnification: f64,
    pub slip_rate_threshold: f64,
    /// In stick, every `stick_every`-th step is recorded; every step while a segment slips.
    pub stick_every: u64,
}

impl RunInfo {
    /// How the run steps ([`RecordingPlan::stepping`]).
    pub fn stepping(&self) -> String {
        stepping(self.integrator, self.tolerance, self.steps, self.dt, &self.chosen_because, self.accuracy)
    }

    /// The description of a run over `layout` recording `series`.
    pub fn new(
        plan: &RecordingPlan,
        layout: &Layout,
        segments: &[usize],
        nodes: &[usize],
        series: &[SeriesSpec],
        spatial: bool,
    ) -> Self {
        let (named_segments, named_nodes): (Vec<usize>, Vec<usize>) = (
            layout.segments.iter().enumerate().filter(|(_, s)| s.name.is_some()).map(|(k, _)| k).collect(),
            layout.surface_nodes.iter().enumerate().filter(|(_, n)| n.name.is_some()).map(|(k, _)| k).collect(),
        );
        Self {
            slipfront_version: env!("CARGO_PKG_VERSION").into(),
            case: plan.case.clone(),
            kind: layout.kind,
            t_end: plan.t_end,
            dt: plan.dt,
            steps: plan.steps,
            integrator: plan.integrator,
            tolerance: plan.tolerance,
            chosen_because: plan.chosen_because.clone(),
            accuracy: plan.accuracy,
            segments: layout.segments.len(),
            recorded_segments: segments.to_vec(),
            segment_labels: segments
                .iter()
                .map(|&k| layout.segments[k].name.clone().unwrap_or_else(|| format!("segment {k}")))
                .collect(),
            recorded_nodes: nodes.to_vec(),
            node_labels: nodes
                .iter()
                .map(|&j| layout.surface_nodes[j].name.clone().unwrap_or_else(|| format!("node {j}")))
                .collect(),
            probe_segments: named_segments,
            probe_nodes: named_nodes,
            quantities: plan.spec.quantities.clone(),
            series: series.iter().map(|s| s.path.clone()).collect(),
            spatial,
            magnification: plan.spec.magnification,
            slip_rate_threshold: plan.slip_rate_threshold,
            stick_every: plan.spec.stick_every,
        }
    }
}

/// Which steps a recording keeps: every step while any segment slips faster than the event
/// threshold, every `stick_every`-th otherwise, and always the first and the last (at `t_end`,
/// or the last good step of a run that failed or was interrupted, see [`Decimator::keep_last`]).
#[derive(Debug, Clone)]
pub struct Decimator {
    threshold: f64,
    stick_every: u64,
    t_end: f64,
    last: Option<u64>,
}

impl Decimator {
    pub fn new(plan: &RecordingPlan) -> Self {
        Self { threshold: plan.slip_rate_threshold, stick_every: plan.spec.stick_every, t_end: plan.t_end, last: None }
    }

    /// Whether `frame` is recorded (and, if so, remembers it).
    pub fn keep(&mut self, frame: &Frame) -> bool {
        let keep = match self.last {
            None => true,
            Some(last) => {
                frame.segments.iter().any(|s| s.slip_rate > self.threshold)
                    || frame.step >= last + self.stick_every
                    || frame.time >= self.t_end * (1.0 - 1e-12)
            }
        };
        if keep {
            self.last = Some(frame.step);
        }
        keep
    }

    /// Whether the run's last frame still has to be recorded (and, if so, remembers it).
    pub fn keep_last(&mut self, frame: &Frame) -> bool {
        let keep = self.last != Some(frame.step);
        self.last = Some(frame.step);
        keep
    }
}

/// How the run ended, written into the recording at [`RUN_ENDING`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunEnding {
    /// `completed`, `failed` or `interrupted`.
    pub ending: String,
    /// Time of the last recorded row (s).
    pub last_time: f64,
    /// Rows recorded per series.
    pub rows: u64,
    pub slip_events: usize,
    pub ruptures: usize,
    /// The digest of every series as written ([`crate::record::digest`]), by entity path;
    /// empty in MCAP logs (whose chunks carry CRCs) and in recordings from before digests.
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub digests: std::collections::BTreeMap<String, String>,
}

impl RunEnding {
    pub fn new(
        ending: crate::frame::Ending,
        last_time: f64,
        rows: u64,
        catalog: &crate::catalog::events::Catalog,
        digests: std::collections::BTreeMap<String, String>,
    ) -> Self {
        Self {
            ending: ending.name().into(),
            last_time,
            rows,
            slip_events: catalog.events.len(),
            ruptures: catalog.ruptures.len(),
            digests,
        }
    }
}
