//! Adaptive time stepping for Wilson's θ method by step doubling.
//!
//! A step of `h` is taken twice: once whole (`A`) and once as two halves (`B`). Wilson's
//! method with linear acceleration is second-order accurate, so its local error is `C h³`;
//! `B` carries two local errors of `C (h/2)³`, and `A - B = ¾ C h³` estimates `B`'s error as
//! `(A - B)/3`. The control is per unit step: `B` is kept when that estimate is within
//! `tolerance × h` (`tolerance` is an error per second of simulated time), so that the errors
//! of many long steps through stick cannot add up to more than those of a few short ones
//! through a slip; the global error then stays near `tolerance × t_end`. (Controlled per step
//! instead, the long stick phases accumulate an error that moves the paper case's first onset
//! by 0.3 s at a per-step tolerance of 1e-6.) The next step is `h (tolerance h/error)^{1/2}`
//! with a safety factor of 0.9, limited to a factor 4 up or 5 down. Differences below ten
//! times the Newton tolerance are taken as rounding noise and always accepted.
//!
//! The error is measured where stick-slip lives: the tangential traction of every contact
//! point relative to its static strength `μ_s f_n`, its degree of structure `1/R*` relative to
//! its range `μ_s/μ_k - 1`, and every nodal velocity relative to its own size or the driving
//! velocity, whichever is larger. Through stick all three vary slowly and steps grow to
//! `dt_max`; a slip's onset (where the friction law switches from elastic to plastic, a kink
//! in time) makes `A` and `B` disagree, and the step shrinks until the onset is resolved.

use super::wilson::{Dynamics, State, StepError};

/// Step-size control of one run.
#[derive(Debug, Clone, PartialEq)]
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
    /// Steps taken (accepted).
    pub accepted: u64,
    /// Attempts rejected by the error estimate or by a failed solve.
    pub rejected: u64,
    /// Newton iterations of an implicit Runge–Kutta method's stages ([`super::sdirk`]): one
    /// right-hand side and one solve with the factored operator each.
    pub newton_iterations: u64,
    /// Factorizations of its operator (linearizations).
    pub factorizations: u64,
}

impl StepControl {
    /// Starts with a step of `dt`.
    pub fn new(tolerance: f64, dt: f64, dt_max: f64, dt_min: f64) -> Self {
        Self {
            tolerance,
            dt_max,
            dt_min,
            next: dt.min(dt_max),
            accepted: 0,
            rejected: 0,
            newton_iterations: 0,
            factorizations: 0,
        }
    }

    /// Integrator steps solved so far: three per attempt (one whole, two halves).
    pub fn solves(&self) -> u64 {
        3 * (self.accepted + self.rejected)
    }

    /// The next step after one of `h` whose estimated error was `error`: `h` times
    /// `0.9 root(allowed/error)`, within `[0.2, max_growth]`, and at most `dt_max`. The error
    /// allowed is `tolerance`, times `h` where the error is per unit step.
    pub(super) fn resize(&self, h: f64, error: f64, scaling: ErrorScaling) -> f64 {
        let allowed = if scaling.per_unit_step { self.tolerance * h } else { self.tolerance };
        let factor = if error > 0.0 { 0.9 * (scaling.root)(allowed / error) } else { scaling.max_growth };
        (h * factor.clamp(0.2, scaling.max_growth)).min(self.dt_max)
    }
}

/// How an integrator's error estimate scales with its step, for [`StepControl::resize`].
#[derive(Debug, Clone, Copy)]
pub(super) struct ErrorScaling {
    /// The error is compared with `tolerance × h` (per unit step) rather than `tolerance`.
    pub per_unit_step: bool,
    /// The `q`-th root, for an error estimate that falls as `h^q` relative to what is allowed.
    pub root: fn(f64) -> f64,
    /// The largest factor by which one step may exceed the last.
    pub max_growth: f64,
}

/// Step doubling of the second-order Wilson step: the error per unit step falls as `h²`.
const STEP_DOUBLING: ErrorScaling = ErrorScaling { per_unit_step: true, root: f64::sqrt, max_growth: 4.0 };

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

impl Dynamics {
    /// Takes one step of at most `limit` (s) chosen by step doubling (module docs); returns the
    /// step taken. The state after it is the two-halves solution, reported as one step.
    pub fn adaptive_step(&mut self, control: &mut StepControl, limit: f64) -> Result<f64, AdaptiveError> {
        loop {
            let h = control.next.min(limit);
            let start = self.snapshot();
            let whole = self.step(h).map(|()| self.state.clone());
            self.restore(start.clone());
            let halves = self.two_halves(h, |d, half| d.step(half));
            // Any failure of an attempt (no convergence, 1/R* out of range, a non-finite value)
            // counts as an infinite error: the step shrinks, down to dt_min.
            let (error, failure) = match (&whole, halves) {
                (Ok(whole), Ok(())) => (self.local_error(whole, &self.state) / 3.0, None),
                (Err(_), Ok(())) => (f64::INFINITY, None),
                (_, Err(e)) => (f64::INFINITY, Some(e)),
            };
            // Differences below the Newton tolerance's reach are rounding noise, not error: a
            // per-unit-step bound smaller than that would shrink the step without end.
            let noise = 10.0 * self.settings.tolerance;
            if error <= (control.tolerance * h).max(noise) {
                control.accepted += 1;
                control.next = control.resize(h, error, STEP_DOUBLING);
                return Ok(h);
            }
            self.restore(start);
            control.rejected += 1;
            control.next = control.resize(h, error, STEP_DOUBLING).min(0.5 * h);
            if control.next < control.dt_min {
                return Err(match failure {
                    Some(e) => AdaptiveError::Step(e),
                    None => AdaptiveError::StepTooSmall { dt: control.next, dt_min: control.dt_min, error },
                });
            }
        }
    }

    /// The largest scaled difference between two states reached from the same start.
    fn local_error(&self, a: &State, b: &State) -> f64 {
        let params = &self.contact.params;
        let range = (params.max_structure() - 1.0).max(f64::MIN_POSITIVE);
        let traction = a
            .contact
            .iter()
            .zip(&b.contact)
            .filter(|(_, c)| c.traction_n > 0.0)
            .map(|(x, y)| {
                let strength = params.mu_s * y.traction_n;
                ((x.traction_t - y.traction_t).abs() / strength).max((x.structure - y.structure).abs() / range)
            })
            .fold(0.0_f64, f64::max);
        let v_ref = self.settings.velocity_scale.max(f64::MIN_POSITIVE);
        let velocity =
            a.velocity.iter().zip(&b.velocity).map(|(x, y)| (x - y).abs() / y.abs().max(v_ref)).fold(0.0_f64, f64::max);
        traction.max(velocity)
    }
}
