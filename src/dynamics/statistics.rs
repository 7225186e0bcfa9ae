//! What an integrator counts over a run.

/// What an integrator has counted over a run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Statistics {
    /// Adaptive steps accepted.
    pub accepted: u64,
    /// Adaptive attempts rejected by the error estimate or by a failed solve.
    pub rejected: u64,
    /// Newton iterations of an implicit Runge–Kutta method's stages: one right-hand side and
    /// one solve with the factored operator each.
    pub newton_iterations: u64,
    /// Factorizations of its operator (linearizations).
    pub factorizations: u64,
}
