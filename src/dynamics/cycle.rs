//! Earthquake-cycle stepping: Wilson's θ method with steps set by how fast the contact's state
//! changes, from `time.dt` through a slip to days through stick.
//!
//! Under a slow drive (a plate rate of 1e-9 m/s) the contact loads over years and slips over
//! hours. An error estimate of the body's motion cannot tell the two apart: through stick it
//! sees the elastic ringing relative to velocities of nanometres per second and holds the step
//! near the body's periods (docs/performance.md, "Slow loading"). Earthquake-cycle codes size
//! the step from the fault's own rates instead: Lapusta et al. (2000, *J. Geophys. Res.* 105,
//! 23765) take a fixed share of the state's characteristic slip per step. Here every contact
//! point's state `(f_t, 1/R*, p)` of eqs. (1)–(9) may change in one step by at most
//! `tolerance` of its own scale: the traction by its static strength `μ_s f_n`, the degree of
//! structure by its range `μ_s/μ_k - 1`, the plastic slip by the elastic slip at that
//! strength, `μ_s f_n / α_t` ([`largest_change`]). The next step is the last one times
//! `tolerance / change`, at most twice it, within `[dt, dt_max]`; a step whose change exceeds
//! twice the tolerance is taken again, shorter. A step of `dt`, the one that resolves a slip's
//! dynamics, is always accepted.
//!
//! **Quasi-static steps.** A Wilson step far longer than every period of the body resolves
//! none of its modes; its velocities then carry the method's overshoot rather than the load's
//! (measured on the paper's block at 1e-9 m/s: after steps of 1e5 s the contact crept on
//! them, and the event catalog filled with slips at 0.2 Pa of traction). After a step longer
//! than [`QUASI_STATIC_RADIANS`] of the body's slowest mode, the state is put on the
//! quasi-static path: velocities the step's mean `Δu/Δt`, accelerations 0. Inertia's share of
//! the equation of motion over such a step is below `1/100²` of the stiffness's. Such a step
//! is solved with `θ = 1`, at its own end: with a larger `θ` its end is interpolated from the
//! solve at `t + θΔt` through the method's acceleration cubic, which after long steps leaves the
//! body behind the base and the contact carrying the base's motion (docs/model.md).

use crate::dynamics::control::{AdaptiveError, StepControl};
use crate::dynamics::error::StepError;
use crate::dynamics::integrator::{Integrator, Statistics};
use crate::dynamics::memory::{IntegratorMemory, mismatch};
use crate::dynamics::operator::Operator;
use crate::dynamics::state::State;
use crate::dynamics::system::System;
use crate::dynamics::wilson::Wilson;
use crate::linalg::lanczos::largest_eigenvalue;

/// The most a step may grow over the last one.
const MAX_GROWTH: f64 = 2.0;

/// A step whose change exceeds this many times the tolerance is taken again.
const REJECT_ABOVE: f64 = 2.0;

/// A step of more than this many radians of the body's slowest mode ends on the quasi-static
/// path (module docs).
pub const QUASI_STATIC_RADIANS: f64 = 100.0;

/// Lanczos steps that find the slowest mode ([`slowest_frequency`]).
const LANCZOS_STEPS: usize = 60;

/// Wilson's method with steps from the contact's rates (module docs).
pub struct CycleSteps {
    wilson: Wilson,
    control: StepControl,
    statistics: Statistics,
    /// Steps at least this long (s) end on the quasi-static path; infinite where the slowest
    /// mode is not known.
    quasi_static: f64,
}

impl CycleSteps {
    /// `control.tolerance` is the change allowed per step, `control.dt_min` the step through a
    /// slip (`time.dt`).
    pub fn new(control: StepControl, system: &System) -> Self {
        let quasi_static = slowest_frequency(system).map_or(f64::INFINITY, |omega| QUASI_STATIC_RADIANS / omega);
        Self { wilson: Wilson::default(), control, statistics: Statistics::default(), quasi_static }
    }

    /// The next step after one of `h` that changed the contact by `change`.
    /// One Wilson step of `h`; on the quasi-static path with `θ = 1`, so that the step's end is
    /// the equilibrium solved for (see the module documentation).
    fn step(&mut self, system: &mut System, h: f64) -> Result<(), StepError> {
        if h < self.quasi_static {
            return self.wilson.step(system, h);
        }
        let theta = std::mem::replace(&mut system.settings.theta, 1.0);
        let outcome = self.wilson.step(system, h);
        system.settings.theta = theta;
        outcome
    }

    fn next_step(&self, h: f64, change: f64) -> f64 {
        let c = &self.control;
        let factor = if change > 0.0 { c.tolerance / change } else { MAX_GROWTH };
        (h * factor.min(MAX_GROWTH)).clamp(c.dt_min, c.dt_max)
    }
}

impl Integrator for CycleSteps {
    /// One step of at most `limit` (module docs); returns the step taken.
    fn advance(&mut self, system: &mut System, limit: f64) -> Result<f64, AdaptiveError> {
        loop {
            let h = self.control.next.min(limit);
            let start = system.snapshot();
            let outcome = self.step(system, h).map(|()| largest_change(system, &start.state));
            let floor = h <= self.control.dt_min * (1.0 + 1e-12);
            match outcome {
                Ok(change) if floor || change <= REJECT_ABOVE * self.control.tolerance => {
                    self.statistics.accepted += 1;
                    self.control.next = self.next_step(h, change);
                    if h >= self.quasi_static {
                        onto_quasi_static_path(system, &start.state, h);
                    }
                    return Ok(h);
                }
                Ok(change) => {
                    system.restore(start);
                    self.statistics.rejected += 1;
                    self.control.next = self.next_step(h, change).min(0.5 * h);
                }
                Err(e) if floor => return Err(AdaptiveError::Step(e)),
                Err(_) => {
                    system.restore(start);
                    self.statistics.rejected += 1;
                    self.control.next = (0.25 * h).max(self.control.dt_min);
                }
            }
        }
    }

    fn memory(&self) -> IntegratorMemory {
        IntegratorMemory::Cycle {
            wilson: self.wilson.remembered(),
            control: self.control.clone(),
            statistics: self.statistics,
        }
    }

    /// Takes back the Wilson memory, the counts and the next step; the step limits stay the
    /// case's.
    fn restore(&mut self, system: &System, memory: IntegratorMemory) -> Result<(), String> {
        match memory {
            IntegratorMemory::Cycle { wilson, control, statistics } => {
                self.wilson.take_back(system, wilson)?;
                self.control.resume_from(&control)?;
                self.control.next = self.control.next.max(self.control.dt_min);
                self.statistics = statistics;
                Ok(())
            }
            other => Err(mismatch(format!("saved by {}, the case steps with cycle steps", other.name()))),
        }
    }

    fn longest_next_step(&self, limit: f64) -> f64 {
        self.control.next.min(limit)
    }

    fn statistics(&self) -> Statistics {
        self.statistics
    }
}

/// Puts the state after a step of `h` from `before` on the quasi-static path: each velocity
/// the step's mean, each acceleration 0 (module docs).
fn onto_quasi_static_path(system: &mut System, before: &State, h: f64) {
    let state = &mut system.state;
    for ((v, a), (u, u0)) in
        state.velocity.iter_mut().zip(&mut state.acceleration).zip(state.displacement.iter().zip(&before.displacement))
    {
        *v = (u - u0) / h;
        *a = 0.0;
    }
}

/// The largest change of a contact point's state from `before` to `system`'s state, each part
/// relative to its scale (module docs); points without normal traction are left out.
fn largest_change(system: &System, before: &State) -> f64 {
    before
        .contact
        .iter()
        .zip(&system.state.contact)
        .enumerate()
        .filter(|(_, (_, after))| after.traction_n > 0.0)
        .map(|(k, (old, new))| {
            let params = system.contact.params(k);
            let strength = params.mu_s * new.traction_n;
            let range = (params.max_structure() - 1.0).max(f64::MIN_POSITIVE);
            let elastic_slip = strength / params.alpha_t;
            ((new.traction_t - old.traction_t).abs() / strength)
                .max((new.structure - old.structure).abs() / range)
                .max((new.plastic_slip - old.plastic_slip).abs() / elastic_slip)
        })
        .fold(0.0_f64, f64::max)
}

/// The body's slowest angular frequency (rad/s) on its contact's elastic springs (`α_t` along
/// each point's tangent): `1/√θ` for the largest Ritz value `θ` of the symmetric
/// `M^{½} (K + K_t)⁻¹ M^{½}` after [`LANCZOS_STEPS`] steps of Lanczos' iteration
/// ([`largest_eigenvalue`], which [`crate::dynamics::central::highest_frequency`] runs on
/// `M^{-½} (K + K_t) M^{-½}`). `θ` approaches the largest eigenvalue from below, so
/// the frequency approaches `ω_min` from above (`tests/cycle.rs` compares it with a dense
/// eigensolver). `None` where `K + K_t` cannot be factored (a body free to move along its
/// contact's normal).
pub fn slowest_frequency(system: &System) -> Option<f64> {
    let (body, contact) = (&system.body, &system.contact);
    let springs: Vec<f64> =
        (0..contact.points.len()).map(|k| contact.params(k).alpha_t * contact.points[k].weight).collect();
    let mut operator = Operator::new(body, contact).ok()?;
    operator.factor(body, contact, 0.0, &springs).ok()?;
    let root: Vec<f64> = body.mass.iter().map(|m| m.sqrt()).collect();
    let apply = |x: &[f64], y: &mut [f64]| {
        y.iter_mut().zip(x.iter().zip(&root)).for_each(|(y, (x, r))| *y = x * r);
        operator.solve_in_place(y);
        y.iter_mut().zip(&root).for_each(|(y, r)| *y *= r);
    };
    let largest = largest_eigenvalue(body.dofs(), LANCZOS_STEPS, apply);
    (largest.is_finite() && largest > 0.0).then(|| 1.0 / largest.sqrt())
}
