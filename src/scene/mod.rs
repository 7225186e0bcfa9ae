//! Scenes assemble a case into a model, advance it, and describe each step as a [`Frame`] for
//! the sinks. A scene computes for a frame only what the sinks asked for ([`Needs`]).

pub mod block;
pub mod point;
pub mod spring_block;

use std::fmt;

use serde::{Deserialize, Serialize};

use crate::case::{Case, Integrator, SceneSpec};
use crate::dynamics::runge_kutta::Method;
use crate::dynamics::{AdaptiveError, StepControl, StepError};
use crate::friction::{ContactState, FrictionError, FrictionParams};

/// What the sinks of a run need in each frame.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Needs {
    /// Per-segment `R`, `R*`, `1/R*`, `f_n` (the catalog needs only traction, slip and rate).
    pub segment_state: bool,
    /// Contact-surface node displacements.
    pub surface_nodes: bool,
    /// Displacement of every mesh node (spatial views).
    pub mesh: bool,
}

impl Needs {
    pub fn union(self, other: Needs) -> Needs {
        Needs {
            segment_state: self.segment_state || other.segment_state,
            surface_nodes: self.surface_nodes || other.surface_nodes,
            mesh: self.mesh || other.mesh,
        }
    }
}

/// The kinds of scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SceneKind {
    Point,
    SpringBlock,
    Block,
}

impl SceneKind {
    /// The case file's name for it.
    pub fn name(self) -> &'static str {
        match self {
            SceneKind::Point => "point",
            SceneKind::SpringBlock => "spring_block",
            SceneKind::Block => "block",
        }
    }

    /// Whether frames of this scene carry a block displacement and velocity.
    pub fn has_block(self) -> bool {
        self == SceneKind::SpringBlock
    }

    /// Unit of the total friction force: per unit thickness for a block, per unit area else.
    pub fn force_unit(self) -> &'static str {
        match self {
            SceneKind::Block => "N/m",
            _ => "Pa",
        }
    }
}

impl fmt::Display for SceneKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What a scene is made of, for sinks that label and place things.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Layout {
    pub kind: SceneKind,
    /// Contact segments from the left, with their extent along x (m).
    pub segments: Vec<SegmentInfo>,
    /// Contact-surface nodes from the left, with their x (m). Empty without a body.
    pub surface_nodes: Vec<NodeInfo>,
    /// The mesh, for block scenes.
    pub mesh: Option<crate::fem::StructuredMesh>,
    /// The driving velocity (m/s).
    pub driving_velocity: f64,
    /// Whether the segments' slip rates are instantaneous values at each frame's time (the
    /// Runge–Kutta integrator's `Λ`) rather than means `Δp/Δt` over the step that led to it.
    #[serde(default)]
    pub instantaneous_slip_rate: bool,
}

/// A contact segment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SegmentInfo {
    pub left: f64,
    pub right: f64,
    /// Probe name, if the case gives one.
    pub name: Option<String>,
}

/// A contact-surface node.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NodeInfo {
    pub x: f64,
    pub name: Option<String>,
}

/// One segment at one instant: Gauss-point values averaged over the segment.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SegmentSample {
    /// Tangential traction `f_t` (Pa).
    pub traction_t: f64,
    /// Normal traction `f_n` (Pa).
    pub traction_n: f64,
    /// Normal sliding ratio `R`.
    pub sliding_ratio: f64,
    /// `R*`.
    pub r_star: f64,
    /// Degree of structure `1/R*`.
    pub structure: f64,
    /// Plastic slip rate over the last step, `Δp/Δt` (m/s).
    pub slip_rate: f64,
    /// Accumulated plastic slip `p` (m).
    pub slip: f64,
}

/// Everything a sink may observe after a step (or at `t = 0`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Frame {
    pub step: u64,
    /// Time (s).
    pub time: f64,
    /// The step that led here (s); 0 for the initial frame.
    pub dt: f64,
    pub segments: Vec<SegmentSample>,
    /// `(u_x, u_y)` of the contact-surface nodes (m), when needed.
    pub surface_nodes: Vec<[f64; 2]>,
    /// `(u_x, u_y)` of every mesh node (m), top row included, when needed.
    pub mesh: Vec<[f64; 2]>,
    /// Total friction force `Σ w f_t` (N/m for a block, Pa for unit-area scenes).
    pub friction_force: f64,
    /// Displacement of the base (m); for a spring-block, of the spring's far end.
    pub base_displacement: f64,
    /// Block displacement and velocity (spring-block scenes).
    pub block: Option<[f64; 2]>,
}

/// A failure while running: the step it happened in, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct RunError {
    pub step: u64,
    pub time: f64,
    /// Segment of the contact point involved, if any.
    pub segment: Option<usize>,
    pub message: String,
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "step {} (t = {} s)", self.step, self.time)?;
        if let Some(s) = self.segment {
            write!(f, ", segment {s}")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for RunError {}

/// A model that can be advanced and observed.
pub trait Scene {
    fn layout(&self) -> &Layout;
    /// Current time (s).
    fn time(&self) -> f64;
    /// Advances by `dt`.
    fn advance(&mut self, dt: f64) -> Result<(), RunError>;
    /// Advances by one step of at most `limit` (s) chosen by `control`; returns the step taken.
    /// Scenes without dynamics (the point scene) take `limit` whole.
    fn advance_adaptive(&mut self, _control: &mut StepControl, limit: f64) -> Result<f64, RunError> {
        self.advance(limit).map(|()| limit)
    }
    /// Describes the current state; `dt` is the step just taken.
    fn frame(&self, needs: Needs, dt: f64) -> Frame;
}

/// Builds the scene a case describes.
pub fn build(case: &Case) -> Result<Box<dyn Scene>, RunError> {
    Ok(match &case.scene {
        SceneSpec::Point(spec) => Box::new(point::PointScene::new(case.friction.clone(), spec.clone())),
        SceneSpec::SpringBlock(spec) => Box::new(spring_block::SpringBlockScene::new(case, spec)?),
        SceneSpec::Block(spec) => Box::new(block::BlockScene::new(case, spec)?),
    })
}

/// Averages the Gauss points `(weight, state, plastic slip rate)` into a segment sample.
pub fn segment_sample(
    params: &FrictionParams,
    points: impl Iterator<Item = (f64, ContactState, f64)>,
    full: bool,
) -> SegmentSample {
    let mut sample = SegmentSample::default();
    let mut total = 0.0;
    for (weight, state, rate) in points {
        total += weight;
        sample.traction_t += weight * state.traction_t;
        sample.slip += weight * state.plastic_slip;
        sample.slip_rate += weight * rate;
        if full {
            sample.traction_n += weight * state.traction_n;
            sample.sliding_ratio += weight * state.sliding_ratio(params);
            sample.r_star += weight * state.r_star();
            sample.structure += weight * state.structure;
        }
    }
    let inv = 1.0 / total;
    sample.traction_t *= inv;
    sample.slip *= inv;
    sample.slip_rate *= inv;
    sample.traction_n *= inv;
    sample.sliding_ratio *= inv;
    sample.r_star *= inv;
    sample.structure *= inv;
    sample
}

/// The integrator of a dynamic scene, set up as the case's `time.integrator` asks.
pub fn dynamics_for(
    case: &Case,
    body: crate::dynamics::LinearBody,
    contact: crate::dynamics::ContactBoundary,
    settings: crate::dynamics::WilsonSettings,
    segment_of_point: impl Fn(usize) -> usize,
) -> Result<crate::dynamics::Dynamics, RunError> {
    let mut dynamics =
        crate::dynamics::Dynamics::new(body, contact, settings).map_err(|e| step_error(e, 0, 0.0, segment_of_point))?;
    if case.time.integrator == Integrator::Central {
        dynamics.use_central_differences();
    }
    Ok(dynamics)
}

/// Advances a dynamic scene's integrator by `dt`, reporting a failure with the step, the time
/// it started from and the segment of the contact point involved.
pub fn advance_dynamics(
    dynamics: &mut crate::dynamics::Dynamics,
    dt: f64,
    segment_of_point: impl Fn(usize) -> usize,
) -> Result<(), RunError> {
    let (step, time) = (dynamics.state.step + 1, dynamics.state.time);
    dynamics.step(dt).map_err(|e| step_error(e, step, time, segment_of_point))
}

/// One adaptive step of `dynamics` by `integrator`: Wilson's method by step doubling
/// ([`crate::dynamics::adaptive`]), or Tsitouras' pair or SDIRK with the crossings of the
/// slip-rate `threshold` (m/s) located ([`crate::dynamics::runge_kutta`]). Failures as in
/// [`advance_dynamics`].
pub fn advance_dynamics_adaptive(
    dynamics: &mut crate::dynamics::Dynamics,
    control: &mut StepControl,
    limit: f64,
    (integrator, threshold): (Integrator, f64),
    segment_of_point: impl Fn(usize) -> usize,
) -> Result<f64, RunError> {
    let (step, time) = (dynamics.state.step + 1, dynamics.state.time);
    let taken = match integrator {
        Integrator::Wilson => dynamics.adaptive_step(control, limit),
        Integrator::Tsit5 => dynamics.runge_kutta_step(Method::Tsit5, control, limit, threshold),
        Integrator::Sdirk4 => dynamics.runge_kutta_step(Method::Sdirk4, control, limit, threshold),
        // Central differences take fixed frames (their cases refuse a tolerance).
        Integrator::Central => dynamics.step(limit).map(|()| limit).map_err(AdaptiveError::Step),
    };
    taken.map_err(|e| match e {
        AdaptiveError::Step(e) => step_error(e, step, time, segment_of_point),
        e @ AdaptiveError::StepTooSmall { .. } => RunError { step, time, segment: None, message: e.to_string() },
    })
}

/// Turns a dynamic step failure into a [`RunError`] for the scene's segment numbering.
pub fn step_error(error: StepError, step: u64, time: f64, segment_of_point: impl Fn(usize) -> usize) -> RunError {
    let segment = match &error {
        StepError::Friction { point, .. } => Some(segment_of_point(*point)),
        _ => None,
    };
    let mut message = error.to_string();
    if matches!(error, StepError::EnergyCreated { .. }) {
        message.push_str(": use a smaller time.dt (or raise time.energy_tolerance)");
    }
    RunError { step, time, segment, message }
}

/// Turns a friction failure of the single point of a point scene into a [`RunError`].
pub fn friction_error(error: FrictionError, state: &ContactState, step: u64, time: f64) -> RunError {
    RunError {
        step,
        time,
        segment: Some(0),
        message: format!(
            "f_t = {} Pa, f_n = {} Pa, 1/R* = {}: {error}",
            state.traction_t, state.traction_n, state.structure
        ),
    }
}
