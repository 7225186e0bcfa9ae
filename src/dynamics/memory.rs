//! What each integrator remembers between steps, as data: written into a checkpoint and given
//! back on resume, so that the resumed run takes exactly the steps the uninterrupted one takes.
//! Workspaces and factorizations that a step rebuilds from this memory bit for bit are not
//! kept; a factorization whose reuse changes results (the condensed Newton matrix that
//! preconditions the next) is kept as the values it was factored at.

use serde::{Deserialize, Serialize};

use crate::dynamics::control::StepControl;
use crate::dynamics::rate_form::memory::RungeKutta;
use crate::dynamics::statistics::Statistics;
use crate::friction::Restart;

/// An integrator's memory ([`crate::dynamics::Integrator::memory`]).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum IntegratorMemory {
    Wilson(WilsonMemory),
    StepDoubling { wilson: WilsonMemory, control: StepControl, statistics: Statistics },
    Central(CentralMemory),
    Cycle { wilson: WilsonMemory, control: StepControl, statistics: Statistics },
    RateForm { control: StepControl, memory: Option<Box<RungeKutta>>, statistics: Statistics },
}

impl IntegratorMemory {
    /// The integrator it belongs to, for messages.
    pub fn name(&self) -> &'static str {
        match self {
            IntegratorMemory::Wilson(_) => "Wilson's method",
            IntegratorMemory::StepDoubling { .. } => "adaptive Wilson steps",
            IntegratorMemory::Central(_) => "central differences",
            IntegratorMemory::Cycle { .. } => "cycle steps",
            IntegratorMemory::RateForm { .. } => "a Runge–Kutta method on the rate form",
        }
    }
}

/// Wilson's method: where each contact point's last consistency solve ended, and for the
/// condensed solver each kept body operator's `τ` with the contact stiffnesses its Newton
/// matrix was last factored at (the preconditioner of the next solve).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct WilsonMemory {
    pub restarts: Vec<Option<Restart>>,
    pub condensations: Vec<(f64, Option<Vec<f64>>)>,
}

/// Central differences: each contact point's last consistency solve and interpolated
/// displacement, and the highest frequency that sets the sub-steps.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CentralMemory {
    pub restarts: Vec<Option<Restart>>,
    pub contact_displacement: Vec<f64>,
    pub omega_max: f64,
}

/// A memory that does not fit the integrator or the system it is given back to.
pub fn mismatch(what: impl std::fmt::Display) -> String {
    format!("the checkpoint's integrator memory does not fit this case: {what}")
}

/// Checks that a saved per-point vector has one entry per contact point.
pub fn check_points<T>(saved: &[T], points: usize, what: &str) -> Result<(), String> {
    if saved.len() == points {
        Ok(())
    } else {
        Err(mismatch(format!("{} {what} saved for {points} contact points", saved.len())))
    }
}
