//! The linear part of the equation of motion (14): lumped mass, stiffness, external load.

use crate::dynamics::motion::Motion;
use crate::linalg::sparse::SymmetricMatrix;

/// `M a + K u = f⁰(t) + f_c`, with `M` diagonal (lumped). Degrees of freedom with prescribed
/// displacement (a fixed or moving boundary, eq. 10's `S_v`) are not stored: their motion acts
/// on the others as a load ([`Load`]).
#[derive(Debug, Clone)]
pub struct LinearBody {
    /// Lumped mass per degree of freedom (kg per unit thickness, or kg/m² per unit area).
    pub mass: Vec<f64>,
    /// Stiffness `K` (N/m per unit thickness, or Pa/m per unit area).
    pub stiffness: SymmetricMatrix,
    /// The external load `f⁰(t) = Σ pattern · g(t)` beyond the initial equilibrium.
    pub loads: Vec<Load>,
}

/// One external load: a fixed pattern of nodal forces scaled by a function of time.
#[derive(Debug, Clone)]
pub struct Load {
    /// Nodal forces per unit of [`Self::history`] (N/m per unit thickness, or Pa).
    pub pattern: Vec<f64>,
    pub history: LoadHistory,
}

/// How a [`Load`] grows with time.
#[derive(Debug, Clone)]
pub enum LoadHistory {
    /// `g(t) = t`: a spring's far end moving at a constant velocity (the spring block).
    Linear,
    /// `g(t)` = a component of a prescribed displacement (m): the pattern is `-K_fp` of the
    /// boundary's degrees of freedom along that component, so that a moving boundary pulls on
    /// the body through its stiffness.
    Displacement { motion: Motion, component: usize },
    /// `g(t)` rises smoothly from 0 to 1 over `ramp` seconds (`s³ (10 - 15 s + 6 s²)`) and stays
    /// there: a prescribed traction on `S_t` (eq. 10); `ramp = 0` applies it at once.
    Ramp { ramp: f64 },
    /// `g(t)` rises as [`Self::Ramp`], and falls the same way from `duration` on: a traction
    /// applied for a while, then removed.
    Pulse { ramp: f64, duration: f64 },
}

impl LoadHistory {
    /// `g(t)`.
    pub fn at(&self, t: f64) -> f64 {
        match self {
            LoadHistory::Linear => t,
            LoadHistory::Displacement { motion, component } => motion.displacement_at(t)[*component],
            LoadHistory::Ramp { ramp } => Motion::constant([1.0, 0.0], *ramp).velocity_at(t)[0],
            LoadHistory::Pulse { ramp, duration } => {
                let rise = |t: f64| Motion::constant([1.0, 0.0], *ramp).velocity_at(t)[0];
                rise(t) - rise(t - duration)
            }
        }
    }
}

/// The external load at one instant, read per degree of freedom ([`LinearBody::load_at`]).
/// Without allocating for none or one load: the rate form's right-hand side asks for it at
/// every stage.
pub enum LoadAt<'a> {
    None,
    One(&'a [f64], f64),
    Several(Vec<(&'a [f64], f64)>),
}

impl LoadAt<'_> {
    /// `f⁰_i(t)`: `+0` without loads.
    #[inline]
    pub fn at(&self, i: usize) -> f64 {
        match self {
            LoadAt::None => 0.0,
            LoadAt::One(pattern, g) => pattern[i] * g,
            LoadAt::Several(terms) => terms.iter().map(|(pattern, g)| pattern[i] * g).sum(),
        }
    }

    /// `forces_i ← f⁰_i - forces_i - offset_i` for every degree of freedom: [`Self::at`] with
    /// the load's kind matched once, not per degree of freedom, so that the loop vectorizes.
    pub fn minus(&self, forces: &mut [f64], offset: &[f64]) {
        let rows = forces.iter_mut().zip(offset);
        match self {
            LoadAt::None => rows.for_each(|(f, o)| *f = 0.0 - *f - o),
            LoadAt::One(pattern, g) => rows.zip(*pattern).for_each(|((f, o), p)| *f = p * g - *f - o),
            LoadAt::Several(_) => rows.enumerate().for_each(|(i, (f, o))| *f = self.at(i) - *f - o),
        }
    }
}

impl LinearBody {
    /// A body without external load.
    pub fn new(mass: Vec<f64>, stiffness: SymmetricMatrix) -> Self {
        Self { mass, stiffness, loads: Vec::new() }
    }

    /// Number of degrees of freedom.
    pub fn dofs(&self) -> usize {
        self.mass.len()
    }

    /// The external load `f⁰(t)`, to be read per degree of freedom.
    pub fn load_at(&self, t: f64) -> LoadAt<'_> {
        match self.loads.as_slice() {
            [] => LoadAt::None,
            [l] => LoadAt::One(&l.pattern, l.history.at(t)),
            loads => LoadAt::Several(loads.iter().map(|l| (l.pattern.as_slice(), l.history.at(t))).collect()),
        }
    }

    /// Kinetic energy `½ vᵀ M v`.
    pub fn kinetic_energy(&self, velocity: &[f64]) -> f64 {
        0.5 * self.mass.iter().zip(velocity).map(|(m, v)| m * v * v).sum::<f64>()
    }

    /// Strain energy `½ uᵀ K u` of the displacement from the initial equilibrium.
    pub fn strain_energy(&self, displacement: &[f64]) -> f64 {
        0.5 * self.stiffness.quadratic_form(displacement)
    }
}
