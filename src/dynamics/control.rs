//! Step-size control of the adaptive integrators: the next step from the last one's error
//! estimate, within the case's smallest and largest step.

use crate::dynamics::error::StepError;

/// Step-size control of one run.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StepControl {
    /// Local error allowed per second of simulated time (1/s), in the scaled units described
    /// in the module docs.
    pub tolerance: f64,
    /// Largest step (s).
    pub dt_max: f64,
    /// Smallest step (s); a step that would need less stops the run.
    pub dt_min: f64,
    /// The step the next attempt starts from (s).
    pub next: f64,
}

impl StepControl {
    /// Starts with a step of `dt`.
    pub fn new(tolerance: f64, dt: f64, dt_max: f64, dt_min: f64) -> Self {
        Self { tolerance, dt_max, dt_min, next: dt.min(dt_max) }
    }

    /// Continues from a saved control: its next step, clamped to this run's limits (the same
    /// unless the run was extended).
    pub fn resume_from(&mut self, saved: &StepControl) -> Result<(), String> {
        if !(saved.next.is_finite() && saved.next > 0.0) {
            return Err(format!(
                "the checkpoint's next step {} s is not a positive number",
                crate::validate::shortest(saved.next)
            ));
        }
        self.next = saved.next.min(self.dt_max);
        Ok(())
    }

    /// The next step after one of `h` whose estimated error was `error`: `h` times
    /// `0.9 root(allowed/error)`, within `[0.2, max_growth]`, and at most `dt_max`. The error
    /// allowed is `tolerance`, times `h` where the error is per unit step.
    pub(crate) fn resize(&self, h: f64, error: f64, scaling: ErrorScaling) -> f64 {
        let allowed = if scaling.per_unit_step { self.tolerance * h } else { self.tolerance };
        let factor = if error > 0.0 { 0.9 * (scaling.root)(allowed / error) } else { scaling.max_growth };
        (h * factor.clamp(0.2, scaling.max_growth)).min(self.dt_max)
    }
}

/// How an integrator's error estimate scales with its step, for [`StepControl::resize`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct ErrorScaling {
    /// The error is compared with `tolerance × h` (per unit step) rather than `tolerance`.
    pub per_unit_step: bool,
    /// The `q`-th root, for an error estimate that falls as `h^q` relative to what is allowed.
    pub root: fn(f64) -> f64,
    /// The largest factor by which one step may exceed the last.
    pub max_growth: f64,
}

/// Why an adaptive step could not be taken.
#[derive(Debug, Clone, PartialEq)]
pub enum AdaptiveError {
    /// The integrator failed in a way a shorter step does not cure.
    Step(StepError),
    /// The error estimate asked for a step below `dt_min`.
    StepTooSmall { dt: f64, dt_min: f64, error: f64 },
}

impl std::fmt::Display for AdaptiveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AdaptiveError::Step(e) => write!(f, "{e}"),
            AdaptiveError::StepTooSmall { dt, dt_min, error } => write!(
                f,
                "the error estimate {error:.3e} asks for a step of {dt:.3e} s, below the smallest allowed \
                 {dt_min:.3e} s: raise time.tolerance"
            ),
        }
    }
}
