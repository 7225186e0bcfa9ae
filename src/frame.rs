//! The contract between the scenes, the run loop and the sinks: what a scene is made of
//! ([`Layout`]), what one step of it shows ([`Frame`], [`SegmentSample`], the paper's `f_t`,
//! `R`, `R*`, `1/R*` and slip per segment), what the sinks ask to be computed ([`Needs`]), and
//! how a run ended ([`Ending`]). Nothing here computes or writes: scenes fill frames, sinks
//! read them.

use std::fmt;

use serde::{Deserialize, Serialize};

pub use crate::frame::drawing::MeshDrawing;

pub mod drawing;

/// What the sinks of a run need in each frame.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Needs {
    /// Per-segment `R`, `R*` and `f_n`. Traction, slip, slip rate and `1/R*` are in every
    /// frame: the catalog reads them.
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
    /// A body from a Gmsh mesh.
    Mesh,
}

impl SceneKind {
    /// The case file's name for it.
    pub fn name(self) -> &'static str {
        match self {
            SceneKind::Point => "point",
            SceneKind::SpringBlock => "spring_block",
            SceneKind::Block => "block",
            SceneKind::Mesh => "mesh",
        }
    }

    /// Whether the scene is an elastic body of finite elements (the block, a mesh): contacts
    /// along its boundary, forces per unit thickness, ruptures.
    pub fn has_body(self) -> bool {
        matches!(self, SceneKind::Block | SceneKind::Mesh)
    }

    /// Whether frames of this scene carry a block displacement and velocity.
    pub fn has_block(self) -> bool {
        self == SceneKind::SpringBlock
    }

    /// Unit of the total friction force: per unit thickness for a block, per unit area else.
    pub fn force_unit(self) -> &'static str {
        if self.has_body() { "N/m" } else { "Pa" }
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
    /// Contact segments in order along each contact, contact after contact, with their extent
    /// along the contact's arc length (m; the block's x).
    pub segments: Vec<SegmentInfo>,
    /// Contact-surface nodes in the same order, with their arc length (m). Empty without a body.
    pub surface_nodes: Vec<NodeInfo>,
    /// The contacts, in order: how many of [`Self::segments`] and [`Self::surface_nodes`] each
    /// holds. Empty in recordings from before several contacts: one contact holds them all.
    #[serde(default)]
    pub contacts: Vec<ContactInfo>,
    /// What the spatial view draws of a body.
    #[serde(default, deserialize_with = "crate::frame::drawing::either_form")]
    pub mesh: Option<MeshDrawing>,
    /// The driving velocity (m/s).
    pub driving_velocity: f64,
    /// Whether the segments' slip rates are instantaneous values at each frame's time (the
    /// Runge–Kutta integrator's `Λ`) rather than means `Δp/Δt` over the step that led to it.
    #[serde(default)]
    pub instantaneous_slip_rate: bool,
    /// Whether the body is a ring about the y axis (x the radius): its contact forces are
    /// totals around the circumference, in N rather than N per unit thickness.
    #[serde(default)]
    pub axisymmetric: bool,
    /// Whether some contact's normal traction evolves, so that a segment can be open.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub evolving_normal: bool,
}

/// One contact of a body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactInfo {
    /// The name the case gives it (its mesh group's).
    pub name: String,
    /// Its segments and surface nodes (the next ones of [`Layout::segments`] and
    /// [`Layout::surface_nodes`]).
    pub segments: usize,
    pub nodes: usize,
    /// Whether its normal traction evolves, so that its segments can be open.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub evolving: bool,
}

impl Layout {
    /// Unit of the total friction force: N around a ring, N/m per unit thickness of a plane
    /// body, Pa per unit area of a point or spring block.
    pub fn force_unit(&self) -> &'static str {
        if self.axisymmetric { "N" } else { self.kind.force_unit() }
    }

    /// Whether segment `k` lies on a contact whose normal traction evolves (and so can be
    /// open). A layout that does not say it per contact (one contact, or a file written before
    /// the contacts said it) answers for the whole body.
    pub fn segment_evolves(&self, k: usize) -> bool {
        if !self.contacts.iter().any(|c| c.evolving) {
            return self.evolving_normal;
        }
        let mut start = 0;
        for contact in &self.contacts {
            if k < start + contact.segments {
                return contact.evolving;
            }
            start += contact.segments;
        }
        false
    }

    /// The contacts, with the segment and node ranges each holds: [`Self::contacts`], or one
    /// contact holding everything.
    pub fn contact_ranges(&self) -> Vec<(String, std::ops::Range<usize>, std::ops::Range<usize>)> {
        if self.contacts.is_empty() {
            return vec![("contact".into(), 0..self.segments.len(), 0..self.surface_nodes.len())];
        }
        let (mut s, mut n) = (0, 0);
        self.contacts
            .iter()
            .map(|c| {
                let range = (c.name.clone(), s..s + c.segments, n..n + c.nodes);
                (s, n) = (s + c.segments, n + c.nodes);
                range
            })
            .collect()
    }
}

impl Layout {
    /// Named probes that crowd into less than half of their contact: the probe plots colour
    /// the probes from the contact's start (purple) to its end (yellow), and their names (the
    /// paper's "Nodes 1~6", left to right) promise a spread. `None` while they spread, or with
    /// fewer than three.
    pub fn probe_spread_warning(&self) -> Option<String> {
        let mut warnings = Vec::new();
        for (contact, segments, nodes) in self.contact_ranges() {
            let length = self.segments[segments.clone()].iter().map(|s| s.right).fold(0.0, f64::max)
                - self.segments[segments.clone()].iter().map(|s| s.left).fold(f64::INFINITY, f64::min);
            let named_segments: Vec<f64> =
                self.segments[segments].iter().filter(|s| s.name.is_some()).map(|s| 0.5 * (s.left + s.right)).collect();
            let named_nodes: Vec<f64> =
                self.surface_nodes[nodes].iter().filter(|n| n.name.is_some()).map(|n| n.x).collect();
            for (what, at) in [("segments", named_segments), ("nodes", named_nodes)] {
                let (low, high) = at.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
                if at.len() >= 3 && length > 0.0 && high - low < 0.5 * length {
                    let of =
                        if self.contacts.len() > 1 { format!("contact {contact:?}") } else { "the contact".into() };
                    warnings.push(format!(
                        "the {} named probes.{what} lie within {} to {} m of {of}'s {} m (arc length), though the \
                         probe plots colour them from its start to its end as if they spread along it: place them \
                         along the whole contact in the case's [probes], by position (x = ... or at = [x, y], in m) \
                         to hold them there when the mesh changes",
                        at.len(),
                        crate::validate::shortest(low),
                        crate::validate::shortest(high),
                        crate::validate::shortest(length)
                    ));
                }
            }
        }
        (!warnings.is_empty()).then(|| warnings.join("\n"))
    }
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
    /// Whether the segment is open: its contact's normal traction evolves and has fallen to 0
    /// at every one of its points.
    pub open: bool,
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
    /// `(u_x, u_y)` of every node the drawing uses ([`MeshDrawing::nodes`], m), when needed.
    pub mesh: Vec<[f64; 2]>,
    /// Total friction force `Σ w f_t` (N/m for a plane body, N around an axisymmetric one, Pa
    /// for unit-area scenes).
    pub friction_force: f64,
    /// Each contact's own `Σ w f_t` where the body has several (its tractions along its own
    /// tangent); empty where it has one.
    pub contact_forces: Vec<f64>,
    /// Displacement of the base (m); for a spring-block, of the spring's far end; for a mesh,
    /// of its first contact's main body along its drive.
    pub base_displacement: f64,
    /// Block displacement and velocity (spring-block scenes).
    pub block: Option<[f64; 2]>,
}

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

/// How a run ended, as the sinks are told.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    Completed,
    Failed,
    Interrupted,
}
