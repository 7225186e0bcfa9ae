//! The state of the body and its contact at one instant: displacements, velocities and
//! accelerations of the nodes, and every contact point's friction state (eqs. 1-9).

use crate::friction::ContactState;

/// Kinematic and contact state at one instant.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct State {
    /// Time (s).
    pub time: f64,
    /// Completed steps.
    pub step: u64,
    /// Displacement from the initial equilibrium (m).
    pub displacement: Vec<f64>,
    pub velocity: Vec<f64>,
    pub acceleration: Vec<f64>,
    /// Friction state of every contact point.
    pub contact: Vec<ContactState>,
    /// Plastic slip `Δp` of every contact point over the last step (m).
    pub plastic_increment: Vec<f64>,
    /// Plastic slip rate `Λ` of every contact point at `time` (m/s), where the integrator has
    /// it ([`crate::dynamics::rate_form`]); empty otherwise (Wilson's method knows only `Δp`).
    pub plastic_rate: Vec<f64>,
}

impl State {
    /// Plastic slip rate of contact point `point` (m/s): `Λ` at `time` where known, else the
    /// mean `Δp/Δt` over the step `dt` that led here (0 for the initial state).
    pub fn slip_rate(&self, point: usize, dt: f64) -> f64 {
        match self.plastic_rate.get(point) {
            Some(&rate) => rate,
            None if dt > 0.0 => self.plastic_increment[point] / dt,
            None => 0.0,
        }
    }
}
