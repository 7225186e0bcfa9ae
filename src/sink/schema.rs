//! The recording schema: timelines, entity paths and units, shared by the writer
//! ([`super::recording`]) and the reader (`slipfront check`). The README's table is this module.

use serde::{Deserialize, Serialize};

use crate::scene::SegmentSample;

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

/// A per-segment quantity: `contact/segments/{k}/{name}`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Quantity {
    #[serde(rename = "traction_t")]
    TractionT,
    #[serde(rename = "traction_n")]
    TractionN,
    #[serde(rename = "R")]
    R,
    #[serde(rename = "R_star")]
    RStar,
    #[serde(rename = "structure")]
    Structure,
    #[serde(rename = "slip_rate")]
    SlipRate,
    #[serde(rename = "slip")]
    Slip,
}

impl Quantity {
    pub const ALL: [Quantity; 7] = [
        Quantity::TractionT,
        Quantity::TractionN,
        Quantity::R,
        Quantity::RStar,
        Quantity::Structure,
        Quantity::SlipRate,
        Quantity::Slip,
    ];

    /// Last component of the entity path.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::TractionT => "traction_t",
            Quantity::TractionN => "traction_n",
            Quantity::R => "R",
            Quantity::RStar => "R_star",
            Quantity::Structure => "structure",
            Quantity::SlipRate => "slip_rate",
            Quantity::Slip => "slip",
        }
    }

    /// Symbol and unit, for series names.
    pub fn label(self) -> &'static str {
        match self {
            Quantity::TractionT => "f_t (Pa)",
            Quantity::TractionN => "f_n (Pa)",
            Quantity::R => "R",
            Quantity::RStar => "R*",
            Quantity::Structure => "1/R*",
            Quantity::SlipRate => "slip rate (m/s)",
            Quantity::Slip => "slip (m)",
        }
    }

    /// The value in a segment sample.
    pub fn of(self, s: &SegmentSample) -> f64 {
        match self {
            Quantity::TractionT => s.traction_t,
            Quantity::TractionN => s.traction_n,
            Quantity::R => s.sliding_ratio,
            Quantity::RStar => s.r_star,
            Quantity::Structure => s.structure,
            Quantity::SlipRate => s.slip_rate,
            Quantity::Slip => s.slip,
        }
    }

    /// Whether the scene must compute the full segment state for it.
    pub fn needs_state(self) -> bool {
        matches!(self, Quantity::TractionN | Quantity::R | Quantity::RStar | Quantity::Structure)
    }
}

/// `contact/segments/{k}/{quantity}`.
pub fn segment_entity(segment: usize, quantity: Quantity) -> String {
    format!("contact/segments/{segment}/{}", quantity.name())
}

/// `body/nodes/{j}/u_x` (axis 0) or `u_y` (axis 1): contact-surface node `j` from the left.
pub fn node_entity(node: usize, axis: usize) -> String {
    format!("body/nodes/{node}/{}", if axis == 0 { "u_x" } else { "u_y" })
}

/// What a recording holds, written into it as TOML at [`RUN_INFO`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunInfo {
    pub slipfront_version: String,
    /// Case file stem.
    pub case: String,
    /// Scene kind.
    pub kind: String,
    pub t_end: f64,
    pub dt: f64,
    /// Planned steps.
    pub steps: u64,
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
}
