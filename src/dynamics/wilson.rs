//! Wilson's θ method for the equation of motion (14) of the paper's §2.2.
//!
//! The paper integrates the *rate* form `M v̈ + (K - K_c) v = ḟ⁰ + ḟᶜ` with a linear jerk over
//! `τ = θ Δt`. For a linear system that scheme has exactly the eigenvalues of Wilson's method on
//! the *total* form `M a + K u = f⁰ + f_c` with a linear acceleration, plus one extra eigenvalue
//! equal to 1: the integration constant of the rate equation, which nothing damps. A velocity
//! jump (the base starting at `t = 0`) or a damped transient leaves a permanent equilibrium
//! offset in that mode (measured: -211 N/m on a stuck contact whose force should be 50 N/m), and
//! feeding the offset back makes the scheme unstable. This module therefore integrates the total
//! form, which is the same scheme with that mode removed (`tests/wilson_theta.rs` checks the
//! eigenvalues):
//!
//! * `a_θ = 6/τ² (u_θ - u_n) - 6/τ v_n - 2 a_n` (linear acceleration over `τ`),
//! * `M a_θ + K u_θ = f⁰(t_n + τ) + f_c(u_θ)`, where the contact forces
//!   `f_c = Σ w Ñᵀ f_t` come from the implicit friction update over `[t_n, t_n + τ]` with the
//!   body's relative displacement (eq. 13),
//! * Newton's method with the consistent Jacobian `6/τ² M + K + K_c`,
//!   `K_c = -Σ w Ñᵀ (∂f_t/∂Δū) Ñ` (eq. 14's `K_c`),
//! * back to `t_{n+1}`: `a_{n+1} = a_n + (a_θ - a_n)/θ`, `v_{n+1} = v_n + Δt (a_n + a_{n+1})/2`,
//!   `u_{n+1} = u_n + Δt v_n + Δt² (2 a_n + a_{n+1})/6`, and the Gauss-point states advanced
//!   over `Δt` with the body's displacement increment.
//!
//! `θ ≥ 1.37` makes the method unconditionally stable on linear problems; `θ = 1.4` is the
//! default. The Jacobian is refactored only when the contact tangents change.

use crate::dynamics::condensed::Condensation;
use crate::dynamics::control::AdaptiveError;
use crate::dynamics::error::{MAX_HALVINGS, StepError};
use crate::dynamics::integrator::Integrator;
use crate::dynamics::memory::{IntegratorMemory, WilsonMemory, check_points, mismatch};
use crate::dynamics::newton::{NewtonProblem, newton};
use crate::dynamics::settings::LinearSolver;
use crate::dynamics::state::State;
use crate::dynamics::system::System;
use crate::friction::{Restart, update_with};

/// Wilson's method's memory between steps.
#[derive(Default)]
pub struct Wilson {
    /// Where each contact point's last update ended, to start the next step's first trial.
    restarts: Vec<Option<Restart>>,
    /// The body operators of the last few `τ` (most recent last), for [`LinearSolver::Condensed`].
    condensations: Vec<Condensation>,
}

/// How many `τ` keep their factored body operator (a halved step needs another; each holds a
/// factor of the whole body).
const CONDENSATIONS_KEPT: usize = 2;

/// The contact points' response to trial slips over `τ`.
struct ContactResponse {
    /// `w f_t` of each point.
    weighted_traction: Vec<f64>,
    /// `-w ∂f_t/∂Δū` of each point (its share of `K_c`); where a contact's normal evolves,
    /// followed by each point's change of its normal spring
    /// ([`crate::dynamics::ContactBoundary::normal_stiffness`]).
    stiffness: Vec<f64>,
    restarts: Vec<Option<Restart>>,
}

/// The step's system on all unknowns, solved with the sparse Jacobian `6/τ² M + K + K_c`.
struct FullSystem<'a> {
    system: &'a mut System,
    /// Where each point's last update ended (Wilson's memory), for the first trial.
    restarts: &'a [Option<Restart>],
    tau: f64,
}

impl NewtonProblem for FullSystem<'_> {
    type Evaluation = ContactResponse;

    fn evaluate(
        &mut self,
        du_theta: &[f64],
        previous: Option<&ContactResponse>,
    ) -> Result<(Vec<f64>, ContactResponse), StepError> {
        let restarts = previous.map_or(self.restarts, |p| &p.restarts);
        evaluate(self.system, du_theta, self.tau, restarts)
    }

    fn correct(&mut self, evaluation: &ContactResponse, delta: &mut [f64]) -> Result<(), StepError> {
        self.system.factor_operator(6.0 / (self.tau * self.tau), &evaluation.stiffness)?;
        self.system.solve_operator(delta);
        Ok(())
    }
}

/// The step's system condensed onto the contact unknowns `x` ([`crate::dynamics::condensed`]):
/// `x - Pᵀw - G F(x) = 0`.
struct CondensedSystem<'a> {
    system: &'a System,
    /// As in [`FullSystem`].
    restarts: &'a [Option<Restart>],
    condensation: &'a Condensation,
    tau: f64,
    /// How far the main body moves over `τ` along each point's tangent.
    base: Vec<f64>,
    /// `Pᵀ w`.
    free_contact: Vec<f64>,
}

impl NewtonProblem for CondensedSystem<'_> {
    type Evaluation = ContactResponse;

    fn evaluate(
        &mut self,
        x: &[f64],
        previous: Option<&ContactResponse>,
    ) -> Result<(Vec<f64>, ContactResponse), StepError> {
        let c = self.condensation;
        let slips: Vec<f64> = c.points.iter().zip(&self.base).map(|(p, base)| p.interpolate(x) - base).collect();
        let restarts = previous.map_or(self.restarts, |p| &p.restarts);
        let response = contact_response(self.system, &slips, &[], self.tau, restarts)?;
        let g = c.compliance_times(&c.forces(&response.weighted_traction));
        let residual = x.iter().zip(&self.free_contact).zip(g).map(|((x, w), g)| x - w - g).collect();
        Ok((residual, response))
    }

    fn correct(&mut self, evaluation: &ContactResponse, delta: &mut [f64]) -> Result<(), StepError> {
        self.condensation.solve_newton(&evaluation.stiffness, delta).map_err(StepError::Factor)
    }
}

impl Wilson {
    /// Advances `system` by `dt`. A step that fails in a way a shorter step can cure (Newton
    /// not converging across a stick/slip switch, `1/R*` leaving its range, a singular
    /// operator) is retried as two half steps, down to `dt / 2^MAX_HALVINGS`; the state is left
    /// untouched by a failed attempt.
    pub fn step(&mut self, system: &mut System, dt: f64) -> Result<(), StepError> {
        self.step_halving(system, dt, 0)
    }

    fn step_halving(&mut self, system: &mut System, dt: f64, depth: u32) -> Result<(), StepError> {
        match self.try_step(system, dt) {
            Err(e) if depth < MAX_HALVINGS && e.cured_by_shorter_steps() => {
                system.count_split();
                let before = system.snapshot();
                let halves = system.two_halves(dt, |s, half| self.step_halving(s, half, depth + 1));
                if halves.is_err() {
                    // The first half may have succeeded: a failed step leaves the state as it was.
                    system.restore(before);
                }
                halves
            }
            result => result,
        }
    }

    fn try_step(&mut self, system: &mut System, dt: f64) -> Result<(), StepError> {
        if system.settings.linear_solver == LinearSolver::Condensed {
            return self.try_step_condensed(system, dt);
        }
        let tau = system.settings.theta * dt;
        let start = (0..system.body.dofs()).map(|i| predictor(system, i, tau)).collect();
        let (settings, scale) = (system.settings, newton_scale(system, tau));
        let converged = newton(&mut FullSystem { system, restarts: &self.restarts, tau }, &settings, scale, start)?;
        let acceleration = theta_acceleration(system, &converged.x, tau);
        self.finish_step(system, dt, &acceleration, &converged.evaluation.restarts)
    }

    /// One step with Newton's method condensed onto the contact ([`crate::dynamics::condensed`]).
    fn try_step_condensed(&mut self, system: &mut System, dt: f64) -> Result<(), StepError> {
        let tau = system.settings.theta * dt;
        let condensation = self.take_condensation(system, tau)?;
        let result = self.newton_condensed(system, &condensation, dt);
        self.condensations.push(condensation);
        result
    }

    /// The body operator of `τ`, factored now if it is not kept.
    fn take_condensation(&mut self, system: &System, tau: f64) -> Result<Condensation, StepError> {
        // The run loop's steps differ from each other by rounding (t_end/steps against the time
        // reached); an operator within 1e-12 of τ changes the step by less than Newton's
        // tolerance.
        if let Some(k) = self.condensations.iter().position(|c| (c.tau - tau).abs() <= 1e-12 * tau) {
            return Ok(self.condensations.remove(k));
        }
        if self.condensations.len() >= CONDENSATIONS_KEPT {
            self.condensations.remove(0);
        }
        Condensation::new(&system.body, &system.contact.points, tau).map_err(StepError::Factor)
    }

    fn newton_condensed(&mut self, system: &mut System, c: &Condensation, dt: f64) -> Result<(), StepError> {
        let tau = system.settings.theta * dt;
        // w = -A⁻¹ r₀: the body's response without contact forces.
        let mut free = body_residual(system, &vec![0.0; system.body.dofs()], tau);
        free.iter_mut().for_each(|r| *r = -*r);
        c.solve_body(&mut free);
        let start = c.dofs.iter().map(|&d| predictor(system, d, tau)).collect();
        let (settings, scale) = (system.settings, newton_scale(system, tau));
        let mut problem = CondensedSystem {
            system,
            restarts: &self.restarts,
            condensation: c,
            tau,
            base: system.contact.base_slips(system.state.time, system.state.time + tau),
            free_contact: c.dofs.iter().map(|&d| free[d]).collect(),
        };
        let converged = newton(&mut problem, &settings, scale, start)?;
        // Δu_θ = w + A⁻¹ P F for the contact forces F, linearized over a correction taken
        // without evaluating: F(x + δ) ≈ F(x) - K_c δ.
        let mut forces = c.forces(&converged.evaluation.weighted_traction);
        if let Some(delta) = &converged.unevaluated {
            let change = c.contact_stiffness_times(&converged.evaluation.stiffness, delta);
            forces.iter_mut().zip(change).for_each(|(f, dk)| *f -= dk);
        }
        let mut du_theta = vec![0.0; free.len()];
        for (&dof, f) in c.dofs.iter().zip(&forces) {
            du_theta[dof] = *f;
        }
        c.solve_body(&mut du_theta);
        du_theta.iter_mut().zip(&free).for_each(|(u, w)| *u += w);
        let acceleration = theta_acceleration(system, &du_theta, tau);
        self.finish_step(system, dt, &acceleration, &converged.evaluation.restarts)
    }

    /// Interpolates back to `t_{n+1}` ([`end_of_step`]), advances the contact states over `Δt`
    /// ([`advance_contact`]), and updates the energy ledger ([`System::account_energy`]).
    /// `restarts` are the points' updates over `τ = θΔt`: their slip, scaled by `1/θ`, starts the
    /// updates over `Δt`.
    fn finish_step(
        &mut self,
        system: &mut System,
        dt: f64,
        acceleration_theta: &[f64],
        restarts: &[Option<Restart>],
    ) -> Result<(), StepError> {
        // Work on a copy: a failure below leaves the state as it was.
        let (mut next, du) = end_of_step(system, dt, acceleration_theta)?;
        let next_restarts = advance_contact(system, &mut next, &du, dt, restarts)?;
        let old = std::mem::replace(&mut system.state, next);
        if let Err(e) = system.account_energy(&old, dt) {
            system.state = old;
            return Err(e);
        }
        // Over the next τ = θΔt the slip is about θ times this step's.
        self.restarts = next_restarts;
        Ok(())
    }
}

impl Wilson {
    /// The restarts and the kept operators' `τ` and Newton factorizations.
    pub(crate) fn remembered(&self) -> WilsonMemory {
        WilsonMemory {
            restarts: self.restarts.clone(),
            condensations: self.condensations.iter().map(|c| (c.tau, c.newton_stiffness())).collect(),
        }
    }

    /// Takes back [`Self::remembered`]: the kept operators are factored again at their `τ`,
    /// and their Newton matrices at the stiffnesses saved.
    pub(crate) fn take_back(&mut self, system: &System, memory: WilsonMemory) -> Result<(), String> {
        if !memory.restarts.is_empty() {
            check_points(&memory.restarts, system.contact.points.len(), "restarts")?;
        }
        let mut condensations = Vec::with_capacity(memory.condensations.len());
        for (tau, newton) in memory.condensations {
            if !(tau.is_finite() && tau > 0.0) || system.settings.linear_solver != LinearSolver::Condensed {
                return Err(mismatch("a condensed operator saved for a case that does not condense"));
            }
            let c = Condensation::new(&system.body, &system.contact.points, tau).map_err(mismatch)?;
            if let Some(stiffness) = newton {
                check_points(&stiffness, c.points.len(), "contact stiffnesses")?;
                c.keep_newton(&stiffness).map_err(mismatch)?;
            }
            condensations.push(c);
        }
        self.restarts = memory.restarts;
        self.condensations = condensations;
        Ok(())
    }
}

impl Integrator for Wilson {
    /// One fixed step of `limit` ([`Wilson::step`]).
    fn advance(&mut self, system: &mut System, limit: f64) -> Result<f64, AdaptiveError> {
        self.step(system, limit).map(|()| limit).map_err(AdaptiveError::Step)
    }

    fn memory(&self) -> IntegratorMemory {
        IntegratorMemory::Wilson(self.remembered())
    }

    fn restore(&mut self, system: &System, memory: IntegratorMemory) -> Result<(), String> {
        match memory {
            IntegratorMemory::Wilson(memory) => self.take_back(system, memory),
            other => Err(mismatch(format!("saved by {}, the case steps with Wilson's method", other.name()))),
        }
    }
}

/// The kinematics at `t_{n+1}` from `a_θ`: `a_{n+1} = a_n + (a_θ - a_n)/θ`,
/// `v_{n+1} = v_n + Δt (a_n + a_{n+1})/2`, `u_{n+1} = u_n + Δt v_n + Δt² (2 a_n + a_{n+1})/6`.
/// Returns the new state (contact not yet advanced) and the displacement increment.
fn end_of_step(system: &System, dt: f64, acceleration_theta: &[f64]) -> Result<(State, Vec<f64>), StepError> {
    let n = system.body.dofs();
    let theta = system.settings.theta;
    let old = &system.state;
    let mut next = old.clone();
    let s = &mut next;
    let mut du = vec![0.0; n];
    for i in 0..n {
        let a1 = old.acceleration[i] + (acceleration_theta[i] - old.acceleration[i]) / theta;
        s.acceleration[i] = a1;
        s.velocity[i] = old.velocity[i] + 0.5 * dt * (old.acceleration[i] + a1);
        du[i] = dt * old.velocity[i] + dt * dt * (2.0 * old.acceleration[i] + a1) / 6.0;
        s.displacement[i] = old.displacement[i] + du[i];
    }
    if s.velocity.iter().chain(&s.displacement).any(|x| !x.is_finite()) {
        return Err(StepError::NonFinite);
    }
    Ok((next, du))
}

/// Advances every contact point of `next` over `Δt` by the slip the displacement increment `du`
/// gives it (eq. 13), and the time and step counter; returns the restarts for the next `τ`.
fn advance_contact(
    system: &System,
    next: &mut State,
    du: &[f64],
    dt: f64,
    restarts: &[Option<Restart>],
) -> Result<Vec<Option<Restart>>, StepError> {
    let (old, contact, theta) = (&system.state, &system.contact, system.settings.theta);
    let base = contact.base_slips(old.time, old.time + dt);
    let mut next_restarts = Vec::with_capacity(contact.points.len());
    for (k, point) in contact.points.iter().enumerate() {
        let slip = point.interpolate(du) - base[k];
        let restart = restarts[k].map(|r| r.scaled(1.0 / theta));
        let traction_n = contact.evolves(k).then(|| contact.normal_traction_at(k, &next.displacement));
        let updated = update_with(contact.params(k), &old.contact[k], slip, traction_n, dt, restart)
            .map_err(|error| StepError::Friction { point: k, state: old.contact[k], error })?;
        next.contact[k] = updated.state;
        next.plastic_increment[k] = updated.plastic_increment;
        next_restarts.push(updated.restart.map(|r| r.scaled(theta)));
    }
    next.time = old.time + dt;
    next.step = old.step + 1;
    Ok(next_restarts)
}

/// The predictor of unknown `i` over `τ`: constant acceleration.
fn predictor(system: &System, i: usize, tau: f64) -> f64 {
    tau * system.state.velocity[i] + 0.5 * tau * tau * system.state.acceleration[i]
}

/// Displacements below which Newton's corrections count as converged on their own scale:
/// the drive's velocity over `τ`.
fn newton_scale(system: &System, tau: f64) -> f64 {
    system.settings.velocity_scale.max(f64::MIN_POSITIVE) * tau
}

/// Residual of the equation of motion at `t_n + τ` for a trial displacement increment
/// `u_θ - u_n`, and the contact tangents; `restarts` (empty, or one per point) are an earlier
/// trial's, from the same state.
fn evaluate(
    system: &System,
    du_theta: &[f64],
    tau: f64,
    restarts: &[Option<Restart>],
) -> Result<(Vec<f64>, ContactResponse), StepError> {
    let mut residual = body_residual(system, du_theta, tau);
    let t = system.state.time;
    let base = system.contact.base_slips(t, t + tau);
    let slips: Vec<f64> =
        system.contact.points.iter().zip(&base).map(|(p, base)| p.interpolate(du_theta) - base).collect();
    // An evolving normal traction at t_n + τ, and its force beyond K's spring.
    let normals = if system.contact.any_evolving() {
        let u_theta: Vec<f64> = system.state.displacement.iter().zip(du_theta).map(|(u, d)| u + d).collect();
        let mut extra = vec![0.0; residual.len()];
        let normals = system.contact.scatter_normal_corrections(&u_theta, &mut extra);
        residual.iter_mut().zip(extra).for_each(|(r, e)| *r -= e);
        normals
    } else {
        Vec::new()
    };
    let response = contact_response(system, &slips, &normals, tau, restarts)?;
    for (point, &t) in system.contact.points.iter().zip(&response.weighted_traction) {
        point.scatter(-t, &mut residual);
    }
    Ok((residual, response))
}

/// The residual of the equation of motion at `t_n + τ` without the contact forces:
/// `K u_θ + M a_θ - f⁰ + f_c(0)`.
fn body_residual(system: &System, du_theta: &[f64], tau: f64) -> Vec<f64> {
    let s = &system.state;
    let acceleration = theta_acceleration(system, du_theta, tau);
    let u_theta: Vec<f64> = s.displacement.iter().zip(du_theta).map(|(u, d)| u + d).collect();
    let mut residual = vec![0.0; du_theta.len()];
    system.body.stiffness.mul_vec(&u_theta, &mut residual);
    let load = system.body.load_at(s.time + tau);
    for (i, r) in residual.iter_mut().enumerate() {
        *r += system.body.mass[i] * acceleration[i] - load.at(i) + system.initial_contact_force[i];
    }
    residual
}

/// Updates every contact point over `τ` by its relative slip increment, evolving points to
/// their normal tractions `normals` at `t_n + τ` (empty where no contact's normal evolves).
///
/// Newton's operator takes each point's `-w ∂f_t/∂Δū_t` and an open point's normal spring
/// taken away; the consistent tangent's `tn` coupling of an evolving point
/// (`-α_n w ∂f_t/∂f_n`, [`crate::friction::Update::normal_tangent`]) would make it
/// unsymmetric, so the iteration leaves it out: the residual stays exact, and Newton converges
/// linearly where the coupling is strong (loading points near opening).
fn contact_response(
    system: &System,
    slips: &[f64],
    normals: &[f64],
    tau: f64,
    restarts: &[Option<Restart>],
) -> Result<ContactResponse, StepError> {
    let contact = &system.contact;
    let count = contact.points.len();
    let mut response = ContactResponse {
        weighted_traction: Vec::with_capacity(count),
        stiffness: Vec::with_capacity(if normals.is_empty() { count } else { 2 * count }),
        restarts: Vec::with_capacity(count),
    };
    for (k, ((point, state), &slip)) in contact.points.iter().zip(&system.state.contact).zip(slips).enumerate() {
        let restart = restarts.get(k).copied().flatten();
        let traction_n = (!normals.is_empty() && contact.evolves(k)).then(|| normals[k]);
        let updated = update_with(contact.params(k), state, slip, traction_n, tau, restart)
            .map_err(|error| StepError::Friction { point: k, state: *state, error })?;
        response.weighted_traction.push(point.weight * updated.state.traction_t);
        response.stiffness.push(-point.weight * updated.tangent);
        response.restarts.push(updated.restart);
    }
    if !normals.is_empty() {
        response.stiffness.extend(normals.iter().enumerate().map(|(k, &f_n)| contact.normal_stiffness(k, f_n)));
    }
    Ok(response)
}

/// `a_θ = 6/τ² (u_θ - u_n) - 6/τ v_n - 2 a_n`.
fn theta_acceleration(system: &System, du_theta: &[f64], tau: f64) -> Vec<f64> {
    let s = &system.state;
    let c0 = 6.0 / (tau * tau);
    du_theta
        .iter()
        .zip(s.velocity.iter().zip(&s.acceleration))
        .map(|(du, (v, a))| c0 * du - 6.0 / tau * v - 2.0 * a)
        .collect()
}
