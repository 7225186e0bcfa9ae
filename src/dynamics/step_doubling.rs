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

use crate::dynamics::control::{AdaptiveError, ErrorScaling, StepControl};
use crate::dynamics::integrator::{Integrator, Statistics};
use crate::dynamics::memory::{IntegratorMemory, mismatch};
use crate::dynamics::state::State;
use crate::dynamics::system::System;
use crate::dynamics::wilson::Wilson;

/// Step doubling of the second-order Wilson step: the error per unit step falls as `h²`.
const STEP_DOUBLING: ErrorScaling = ErrorScaling { per_unit_step: true, root: f64::sqrt, max_growth: 4.0 };

/// Wilson's method with steps chosen by step doubling.
pub struct StepDoubling {
    wilson: Wilson,
    control: StepControl,
    statistics: Statistics,
}

impl StepDoubling {
    pub fn new(control: StepControl) -> Self {
        Self { wilson: Wilson::default(), control, statistics: Statistics::default() }
    }
}

impl Integrator for StepDoubling {
    /// Takes one step of at most `limit` (s) chosen by step doubling (module docs); returns the
    /// step taken. The state after it is the two-halves solution, reported as one step.
    fn advance(&mut self, system: &mut System, limit: f64) -> Result<f64, AdaptiveError> {
        let (wilson, control) = (&mut self.wilson, &mut self.control);
        loop {
            let h = control.next.min(limit);
            let start = system.snapshot();
            let whole = wilson.step(system, h).map(|()| system.state.clone());
            system.restore(start.clone());
            let halves = system.two_halves(h, |s, half| wilson.step(s, half));
            // Any failure of an attempt (no convergence, 1/R* out of range, a non-finite value)
            // counts as an infinite error: the step shrinks, down to dt_min.
            let (error, failure) = match (&whole, halves) {
                (Ok(whole), Ok(())) => (local_error(system, whole, &system.state) / 3.0, None),
                (Err(_), Ok(())) => (f64::INFINITY, None),
                (_, Err(e)) => (f64::INFINITY, Some(e)),
            };
            // Differences below the Newton tolerance's reach are rounding noise, not error: a
            // per-unit-step bound smaller than that would shrink the step without end.
            let noise = 10.0 * system.settings.tolerance;
            if error <= (control.tolerance * h).max(noise) {
                self.statistics.accepted += 1;
                control.next = control.resize(h, error, STEP_DOUBLING);
                return Ok(h);
            }
            system.restore(start);
            self.statistics.rejected += 1;
            control.next = control.resize(h, error, STEP_DOUBLING).min(0.5 * h);
            if control.next < control.dt_min {
                return Err(match failure {
                    Some(e) => AdaptiveError::Step(e),
                    None => AdaptiveError::StepTooSmall { dt: control.next, dt_min: control.dt_min, error },
                });
            }
        }
    }

    fn memory(&self) -> IntegratorMemory {
        IntegratorMemory::StepDoubling {
            wilson: self.wilson.remembered(),
            control: self.control.clone(),
            statistics: self.statistics,
        }
    }

    /// Takes back the Wilson memory, the counts and the next step; the step limits stay the
    /// case's.
    fn restore(&mut self, system: &System, memory: IntegratorMemory) -> Result<(), String> {
        match memory {
            IntegratorMemory::StepDoubling { wilson, control, statistics } => {
                self.wilson.take_back(system, wilson)?;
                self.control.resume_from(&control)?;
                self.statistics = statistics;
                Ok(())
            }
            other => Err(mismatch(format!("saved by {}, the case steps with adaptive Wilson steps", other.name()))),
        }
    }

    fn longest_next_step(&self, limit: f64) -> f64 {
        self.control.next.min(limit)
    }

    fn statistics(&self) -> Statistics {
        self.statistics
    }
}

/// The largest scaled difference between two states of `system` reached from the same start.
fn local_error(system: &System, a: &State, b: &State) -> f64 {
    let traction = a
        .contact
        .iter()
        .zip(&b.contact)
        .enumerate()
        .filter(|(_, (_, c))| c.traction_n > 0.0)
        .map(|(k, (x, y))| {
            let params = system.contact.params(k);
            let range = (params.max_structure() - 1.0).max(f64::MIN_POSITIVE);
            let strength = params.mu_s * y.traction_n;
            ((x.traction_t - y.traction_t).abs() / strength).max((x.structure - y.structure).abs() / range)
        })
        .fold(0.0_f64, f64::max);
    let v_ref = system.settings.velocity_scale.max(f64::MIN_POSITIVE);
    let velocity =
        a.velocity.iter().zip(&b.velocity).map(|(x, y)| (x - y).abs() / y.abs().max(v_ref)).fold(0.0_f64, f64::max);
    traction.max(velocity)
}
