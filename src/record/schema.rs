//! The recording schema: timelines, entity paths and units, shared by the writer
//! ([`crate::sink::rerun`]) and the reader (`slipfront check`). The README's table is this module.

use std::collections::BTreeMap;

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
/// Total friction force `Σ w f_t` (N/m; N around an axisymmetric ring; Pa for unit-area scenes).
pub const FRICTION_FORCE: &str = "contact/friction_force";
/// Displacement of the base along x (m); for a spring-block, of the spring's far end; for a
/// mesh, of its first contact's main body along its drive (the direction it first moves in,
/// or along the contact's tangent where its velocity is given as a speed along it).
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
/// The space-time view: slip rate against time (across) and position (down), and the cursor.
pub const SPACETIME: &str = "spacetime";
pub const SPACETIME_IMAGE: &str = "spacetime/slip_rate";
pub const SPACETIME_NOW: &str = "spacetime/now";
/// Tick labels of the space-time view: x in m across, `sim_time` in s down.
pub const SPACETIME_AXES: &str = "spacetime/axes";
/// Text log of slip events and ruptures at their onsets.
pub const EVENTS: &str = "events";

/// The layout of the time series, written into [`RunInfo::series_layout`]: one entity per
/// quantity, one instance per recorded segment or node (Rerun's multi-instance `Scalars`).
pub const SERIES_LAYOUT: &str = "instances";
/// The layout of recordings from before [`RunInfo::series_layout`]: one entity per segment and
/// quantity (`contact/segments/{k}/{quantity}`, `body/nodes/{j}/u_x`).
pub const OLD_SERIES_LAYOUT: &str = "entity per segment";

/// `contact/{quantity}`: one instance per recorded segment, left to right.
pub fn segment_entity(quantity: Quantity) -> String {
    format!("contact/{}", quantity.name())
}

/// `body/u_x` (axis 0) or `body/u_y` (axis 1): one instance per recorded contact-surface node.
pub fn node_entity(axis: usize) -> &'static str {
    if axis == 0 { "body/u_x" } else { "body/u_y" }
}

/// The name a reader gives instance `i` of a multi-instance entity: `entity[i]`.
pub fn instance_series(entity: &str, i: usize) -> String {
    format!("{entity}[{i}]")
}

/// Whether the schema writes `entity` with one instance per recorded segment or node.
pub fn is_instanced(entity: &str) -> bool {
    entity == node_entity(0)
        || entity == node_entity(1)
        || entity.strip_prefix("contact/").is_some_and(|q| Quantity::ALL.iter().any(|k| k.name() == q))
}

/// Stick/slip state of every recorded segment (`StateChange`, one lane per segment), logged when
/// any segment changes state.
pub const CONTACT_STATE: &str = "contact/state";
/// The state values of [`CONTACT_STATE`].
pub const STICK: &str = "stick";
pub const SLIP: &str = "slip";
/// The lane state of an open segment (its contact's normal traction has fallen to 0).
pub const OPEN: &str = "open";
/// Profiles along x at the playhead (`BarChart`s over the segments' centres, in m).
pub const PROFILE: &str = "profile";
pub const PROFILE_STATIC_STRENGTH: &str = "profile/static_strength";
pub const PROFILE_KINETIC_STRENGTH: &str = "profile/kinetic_strength";
pub const PROFILE_TRACTION: &str = "profile/traction_t";
pub const PROFILE_SLIP_RATE: &str = "profile/slip_rate";
pub const PROFILE_STRUCTURE: &str = "profile/structure";

/// A profile entity of one contact: `profile/{quantity}` where the scene has one contact (the
/// constants above), `profile/{contact}/{quantity}` where it has several.
pub fn profile_entity(contact: Option<&str>, quantity: &str) -> String {
    match contact {
        None => format!("{PROFILE}/{quantity}"),
        Some(contact) => format!("{PROFILE}/{contact}/{quantity}"),
    }
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
    /// The kinetic friction coefficient `μ_k`, for the strength profiles; `None` in logs from
    /// before it was stored.
    #[serde(default)]
    pub mu_k: Option<f64>,
    /// Every value the case file gives, after the overrides, by its `--set` key
    /// (`friction.mu_s`); empty in logs from before they were stored.
    #[serde(default)]
    pub parameters: BTreeMap<String, toml::Value>,
    /// The `--set` overrides, as given.
    #[serde(default)]
    pub overrides: Vec<String>,
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
            mu_k: Some(case.friction.mu_k),
            parameters: flatten(&case.source.table),
            overrides: case.source.overrides.clone(),
            spec: case.record.clone(),
        }
    }

    /// How the run steps, for people: `in N steps of dt s`, or the adaptive integrator and its
    /// tolerance, and why where `auto` chose it.
    pub fn stepping(&self) -> String {
        stepping(self.integrator, self.tolerance, self.steps, self.dt, &self.chosen_because, self.accuracy)
    }
}

/// The values of a case table by dotted key (`scene.normal_traction.left`); arrays and other
/// non-scalar values as their TOML text.
pub fn flatten(table: &toml::Table) -> BTreeMap<String, toml::Value> {
    fn walk(prefix: &str, table: &toml::Table, out: &mut BTreeMap<String, toml::Value>) {
        for (key, value) in table {
            let key = if prefix.is_empty() { key.clone() } else { format!("{prefix}.{key}") };
            match value {
                toml::Value::Table(inner) => walk(&key, inner, out),
                toml::Value::String(_) | toml::Value::Float(_) | toml::Value::Integer(_) | toml::Value::Boolean(_) => {
                    out.insert(key, value.clone());
                }
                other => {
                    out.insert(key, toml::Value::String(other.to_string()));
                }
            }
        }
    }
    let mut out = BTreeMap::new();
    walk("", table, &mut out);
    out
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

/// One scalar entity of the schema: one instance per source.
#[derive(Debug, Clone, PartialEq)]
pub struct EntitySpec {
    /// Entity path.
    pub path: String,
    /// What each instance reads from a frame.
    pub sources: Vec<Source>,
    /// Name of each instance in plots, with the unit (`A · x = 0.5 m: f_t (Pa)`).
    pub labels: Vec<String>,
    /// Position of each instance along the surface as a fraction of its width, for colouring;
    /// `None` for totals.
    pub positions: Vec<Option<f64>>,
}

impl EntitySpec {
    /// The names readers give its series: the path itself for a total, `path[i]` for
    /// instance `i` of a multi-instance entity ([`is_instanced`]).
    pub fn series_names(&self) -> Vec<String> {
        if is_instanced(&self.path) {
            (0..self.sources.len()).map(|i| instance_series(&self.path, i)).collect()
        } else {
            vec![self.path.clone()]
        }
    }
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

/// The name of segment `k` in plots: its probe name and centre (`A · x = 0.5 m`).
pub fn segment_label(layout: &Layout, k: usize) -> String {
    let seg = &layout.segments[k];
    let x = 0.5 * (seg.left + seg.right);
    match &seg.name {
        Some(name) => format!("{name} · x = {x} m"),
        None if layout.segments.len() > 1 => format!("segment {k} · x = {x} m"),
        None => "contact".to_string(),
    }
}

/// The name of contact-surface node `j` in plots (`Node 1 · x = 0 m`).
pub fn node_label(layout: &Layout, j: usize) -> String {
    let node = &layout.surface_nodes[j];
    format!("{} · x = {} m", node.name.clone().unwrap_or_else(|| format!("node {j}")), node.x)
}

/// Every scalar entity of a recording, in the order they are written.
pub fn series_plan(layout: &Layout, segments: &[usize], nodes: &[usize], quantities: &[Quantity]) -> Vec<EntitySpec> {
    let width = layout.segments.last().map_or(1.0, |s| s.right).max(f64::MIN_POSITIVE);
    let at = |x: f64| Some(if layout.segments.len() > 1 { x / width } else { 0.5 });
    let mut plan = Vec::new();
    for &q in quantities {
        plan.push(EntitySpec {
            path: segment_entity(q),
            sources: segments.iter().map(|&k| Source::Segment(k, q)).collect(),
            labels: segments.iter().map(|&k| format!("{}: {}", segment_label(layout, k), q.label())).collect(),
            positions: segments
                .iter()
                .map(|&k| at(0.5 * (layout.segments[k].left + layout.segments[k].right)))
                .collect(),
        });
    }
    if !nodes.is_empty() {
        for (axis, symbol) in [(0, "u_x (m)"), (1, "u_y (m)")] {
            plan.push(EntitySpec {
                path: node_entity(axis).into(),
                sources: nodes.iter().map(|&j| Source::Node(j, axis)).collect(),
                labels: nodes.iter().map(|&j| format!("{}: {symbol}", node_label(layout, j))).collect(),
                positions: nodes.iter().map(|&j| at(layout.surface_nodes[j].x)).collect(),
            });
        }
    }
    let total = |path: &str, source, label: String, position: Option<f64>| EntitySpec {
        path: path.into(),
        sources: vec![source],
        labels: vec![label],
        positions: vec![position],
    };
    plan.push(total(FRICTION_FORCE, Source::FrictionForce, format!("friction force ({})", layout.force_unit()), None));
    let spring = layout.kind == SceneKind::SpringBlock;
    let base = match layout.kind {
        SceneKind::SpringBlock => "spring end u_x (m)",
        SceneKind::Mesh => "main body displacement along its drive (m)",
        _ => "base u_x (m)",
    };
    plan.push(total(BASE_UX, Source::Base, base.into(), None));
    if spring {
        plan.push(total(BLOCK_X, Source::BlockX, "block x (m)".into(), Some(0.0)));
        plan.push(total(BLOCK_V, Source::BlockV, "block v (m/s)".into(), Some(1.0)));
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
    /// How the series are laid out in entities: [`SERIES_LAYOUT`] (written by this slipfront),
    /// or, in recordings from before this field, [`OLD_SERIES_LAYOUT`].
    #[serde(default = "old_series_layout")]
    pub series_layout: String,
    /// Every scalar time series, by the name a reader gives it ([`EntitySpec::series_names`]).
    pub series: Vec<String>,
    /// Whether the spatial and space-time views were logged.
    pub spatial: bool,
    pub magnification: f64,
    pub slip_rate_threshold: f64,
    /// In stick, every `stick_every`-th step is recorded; every `slip_every`-th while a
    /// segment slips.
    pub stick_every: u64,
    #[serde(default = "every_step")]
    pub slip_every: u64,
    /// The contacts' names, where the scene has several (each has its own profiles); empty
    /// for one.
    #[serde(default)]
    pub contacts: Vec<String>,
    /// Whether the body is a ring about the y axis: its friction force is a total around the
    /// circumference, in N.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub axisymmetric: bool,
    /// The arc length of each recorded segment's centre along its contact (m), for profiles;
    /// empty in recordings from before it.
    #[serde(default)]
    pub segment_centres: Vec<f64>,
}

impl RunInfo {
    /// The traction profile of every contact, where the views have profiles: a body of more
    /// than one segment.
    pub fn traction_profiles(&self) -> Vec<String> {
        if !(self.kind.has_body() && self.segments > 1) {
            return Vec::new();
        }
        if self.contacts.is_empty() {
            return vec![PROFILE_TRACTION.to_string()];
        }
        self.contacts.iter().map(|c| profile_entity(Some(c), "traction_t")).collect()
    }

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
        series: &[EntitySpec],
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
            series_layout: SERIES_LAYOUT.into(),
            series: series.iter().flat_map(EntitySpec::series_names).collect(),
            spatial,
            magnification: plan.spec.magnification,
            slip_rate_threshold: plan.slip_rate_threshold,
            stick_every: plan.spec.stick_every,
            slip_every: plan.spec.slip_every,
            contacts: layout.contacts.iter().map(|c| c.name.clone()).collect(),
            axisymmetric: layout.axisymmetric,
            segment_centres: segments
                .iter()
                .map(|&k| 0.5 * (layout.segments[k].left + layout.segments[k].right))
                .collect(),
        }
    }

    /// Unit of the friction force: N around a ring, else the scene kind's.
    pub fn force_unit(&self) -> &'static str {
        if self.axisymmetric { "N" } else { self.kind.force_unit() }
    }
}

fn old_series_layout() -> String {
    OLD_SERIES_LAYOUT.into()
}

/// Which steps a recording keeps: every step while any segment slips faster than the event
/// threshold, every `stick_every`-th otherwise, and always the first and the last (at `t_end`,
/// or the last good step of a run that failed or was interrupted, see [`Decimator::keep_last`]).
#[derive(Debug, Clone)]
pub struct Decimator {
    threshold: f64,
    stick_every: u64,
    slip_every: u64,
    t_end: f64,
    last: Option<u64>,
    /// Whether a segment slipped in the frame recorded last.
    slipping: bool,
}

/// A [`Decimator`]'s memory, for a checkpoint: the step recorded last, and whether a segment
/// slipped in it.
pub type DecimatorMemory = (Option<u64>, bool);

impl Decimator {
    pub fn new(plan: &RecordingPlan) -> Self {
        Self {
            threshold: plan.slip_rate_threshold,
            stick_every: plan.spec.stick_every,
            slip_every: plan.spec.slip_every,
            t_end: plan.t_end,
            last: None,
            slipping: false,
        }
    }

    /// Whether `frame` is recorded (and, if so, remembers it): the first, every step where the
    /// contact goes from stick (no segment slips) to slip and back, every `slip_every`-th step
    /// while a segment slips (with the default 1, every one: every event's onset and end then lie
    /// on recorded rows or between the rows either side), in stick the first step of
    /// every `stick_every` (steps `k stick_every` when none is skipped), and the frame at
    /// `t_end`. The stick steps are counted from step 0, not from the last recorded: so the
    /// frame at `t_end` shifts none of them, and a run extended past its end records the rows
    /// a longer run records.
    pub fn keep(&mut self, frame: &Frame) -> bool {
        let keep = self.would_keep(frame);
        if keep {
            self.last = Some(frame.step);
            self.slipping = self.slips(frame);
        }
        keep
    }

    fn slips(&self, frame: &Frame) -> bool {
        frame.segments.iter().any(|s| s.slip_rate > self.threshold)
    }

    /// Whether [`Self::keep`] would record `frame`, remembering nothing. It reads the frame's
    /// step, time and slip rates only.
    pub fn would_keep(&self, frame: &Frame) -> bool {
        match self.last {
            None => true,
            Some(last) => {
                let slips = self.slips(frame);
                let every = if slips { self.slip_every } else { self.stick_every };
                slips != self.slipping || frame.step / every > last / every || frame.time >= self.t_end * (1.0 - 1e-12)
            }
        }
    }

    /// Whether the run's last frame still has to be recorded (and, if so, remembers it).
    pub fn keep_last(&mut self, frame: &Frame) -> bool {
        let keep = self.last != Some(frame.step);
        self.last = Some(frame.step);
        self.slipping = self.slips(frame);
        keep
    }

    /// The step recorded last and whether it slipped, for a checkpoint.
    pub fn memory(&self) -> DecimatorMemory {
        (self.last, self.slipping)
    }

    /// Continues after the step recorded last.
    pub fn resume(&mut self, (last, slipping): DecimatorMemory) {
        (self.last, self.slipping) = (last, slipping);
    }
}

/// Frames of the drawn views (the block, the profiles along x) over a run: a view frame is
/// written at most every `t_end / VIEW_FRAMES` while a segment slips and every
/// `t_end / STICK_VIEW_FRAMES` otherwise, so the views scrub smoothly through a rupture without
/// repeating every row of the time series.
pub const VIEW_FRAMES: f64 = 10_000.0;
pub const STICK_VIEW_FRAMES: f64 = 500.0;

/// Which recorded steps also get a view frame: the first, every step where a segment changes
/// between stick and slip, and otherwise steps at least [`VIEW_FRAMES`] apart in slip and
/// [`STICK_VIEW_FRAMES`] apart in stick; the last through [`ViewDecimator::keep_last`].
#[derive(Debug, Clone)]
pub struct ViewDecimator {
    threshold: f64,
    slip_gap: f64,
    stick_gap: f64,
    last: Option<(u64, f64)>,
    slipping: Vec<bool>,
}

impl ViewDecimator {
    pub fn new(plan: &RecordingPlan) -> Self {
        Self {
            threshold: plan.slip_rate_threshold,
            slip_gap: plan.t_end / VIEW_FRAMES,
            stick_gap: plan.t_end / STICK_VIEW_FRAMES,
            last: None,
            slipping: Vec::new(),
        }
    }

    /// Whether recorded `frame` gets a view frame (and, if so, remembers it).
    pub fn keep(&mut self, frame: &Frame) -> bool {
        let slipping: Vec<bool> = frame.segments.iter().map(|s| s.slip_rate > self.threshold).collect();
        let keep = match self.last {
            None => true,
            Some((_, last)) => {
                let gap = if slipping.iter().any(|&s| s) { self.slip_gap } else { self.stick_gap };
                slipping != self.slipping || frame.time - last >= gap * (1.0 - 1e-9)
            }
        };
        self.slipping = slipping;
        if keep {
            self.last = Some((frame.step, frame.time));
        }
        keep
    }

    /// Whether the run's last recorded frame still needs its view frame.
    pub fn keep_last(&mut self, frame: &Frame) -> bool {
        let keep = self.last.map(|(step, _)| step) != Some(frame.step);
        self.last = Some((frame.step, frame.time));
        keep
    }

    /// The last view frame's step and time, and which segments slipped at the last recorded
    /// frame, for a checkpoint.
    pub fn memory(&self) -> (Option<(u64, f64)>, Vec<bool>) {
        (self.last, self.slipping.clone())
    }

    /// Continues from [`Self::memory`].
    pub fn resume(&mut self, (last, slipping): (Option<(u64, f64)>, Vec<bool>)) {
        (self.last, self.slipping) = (last, slipping);
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

/// `slip_every` of a recording written before it existed: every step.
fn every_step() -> u64 {
    1
}
