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

use std::fmt;

use super::body::LinearBody;
use super::condensed::Condensation;
use super::contact::ContactBoundary;
use super::newton::{NewtonProblem, max_abs, newton};
use super::operator::Operator;
use super::sparse::FactorError;
use crate::friction::{ContactState, FrictionError, Restart, update_from};

/// Settings of the integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WilsonSettings {
    /// Wilson's `θ` (≥ 1.37 for unconditional stability on linear problems; 1.4 by default).
    pub theta: f64,
    /// Newton converges when the displacement correction is below `tolerance` times the larger
    /// of the step's displacement and `velocity_scale × τ`.
    pub tolerance: f64,
    /// A velocity typical of the problem (the drive), m/s.
    pub velocity_scale: f64,
    /// Newton iterations allowed per step.
    pub max_iterations: usize,
    /// With `Some(share)`, the energy balance is kept from the start and a step after which the
    /// integrator has created more than `share` of the work put in (or of the contact's
    /// kinetic-strength energy, early on) fails with [`StepError::EnergyCreated`].
    pub energy_tolerance: Option<f64>,
    /// How each Newton iteration solves for its correction.
    pub linear_solver: LinearSolver,
}

impl Default for WilsonSettings {
    fn default() -> Self {
        Self {
            theta: 1.4,
            tolerance: 1e-10,
            velocity_scale: 1e-3,
            max_iterations: 40,
            energy_tolerance: None,
            linear_solver: LinearSolver::Full,
        }
    }
}

/// How each Newton iteration solves for its correction. Both give the same steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinearSolver {
    /// The whole system `6/τ² M + K + K_c`, refactored (sparse Cholesky) whenever a contact
    /// tangent changes: cheapest for small bodies, and for steps that change every time.
    Full,
    /// Condensed onto the contact ([`super::condensed`]): the body factored once per `τ`, a
    /// dense system of the contact's unknowns per iteration. For large bodies at a fixed step.
    Condensed,
}

/// Bodies with at least this many unknowns are condensed onto their contact when the step is
/// fixed (see [`LinearSolver`]); the paper's 10 × 1 mesh (22 unknowns) is not.
pub const CONDENSE_FROM_DOFS: usize = 1000;

/// ... unless the contact has more unknowns than this: its dense matrices (`8 k²` bytes each)
/// and their LU (`2k³/3` operations) would outgrow the sparse operator of a long thin body.
pub const CONDENSE_UP_TO_CONTACT_DOFS: usize = 2048;

/// Whether a fixed-step body of `dofs` unknowns with `contact_dofs` at its contact is better
/// condensed ([`LinearSolver::Condensed`]).
pub fn condensation_pays(dofs: usize, contact_dofs: usize) -> bool {
    dofs >= CONDENSE_FROM_DOFS && contact_dofs <= CONDENSE_UP_TO_CONTACT_DOFS
}

/// Kinematic and contact state at one instant.
#[derive(Debug, Clone)]
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
    /// it ([`super::runge_kutta`]); empty otherwise (Wilson's method knows only `Δp`).
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

/// Why a step failed.
#[derive(Debug, Clone, PartialEq)]
pub enum StepError {
    /// The friction update of one contact point failed.
    Friction { point: usize, state: ContactState, error: FrictionError },
    /// Newton's method did not converge.
    NotConverged { iterations: usize, correction: f64 },
    /// The linear solve failed.
    Factor(FactorError),
    /// A non-finite value appeared.
    NonFinite,
    /// The integrator created more energy than its tolerance allows (the step is too coarse
    /// for the dynamics): `created` as a share of the work put in.
    EnergyCreated { share: f64, tolerance: f64 },
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StepError::Friction { point, state, error } => write!(
                f,
                "contact point {point} (f_t = {} Pa, f_n = {} Pa, 1/R* = {}): {error}",
                state.traction_t, state.traction_n, state.structure
            ),
            StepError::NotConverged { iterations, correction } => write!(
                f,
                "Newton's method did not converge in {iterations} iterations (last displacement correction {correction:e} m)"
            ),
            StepError::Factor(e) => write!(f, "{e}"),
            StepError::NonFinite => write!(f, "a non-finite value appeared in the solution"),
            StepError::EnergyCreated { share, tolerance } => write!(
                f,
                "the energy balance does not close: the integrator has created energy equal to {:.3}% of the \
                 work put in (allowed: {:.3}%), so the time step is too coarse for this case's dynamics",
                100.0 * share,
                100.0 * tolerance
            ),
        }
    }
}

impl std::error::Error for StepError {}

/// How many times a failing step may be halved (down to 1/1024 of it).
pub const MAX_HALVINGS: u32 = 10;

impl StepError {
    /// Whether a shorter step may succeed where this one failed.
    pub(crate) fn cured_by_shorter_steps(&self) -> bool {
        match self {
            StepError::NotConverged { .. } | StepError::Factor(FactorError::NotPositiveDefinite) => true,
            StepError::Friction { error, .. } => error.cured_by_shorter_steps(),
            _ => false,
        }
    }
}

/// Running energy balance (J per unit thickness, or J/m² per unit area).
///
/// `initial + work_base + work_load = kinetic + strain + contact_elastic + dissipation + numerical`,
/// where `initial` is what was stored when tracking began and `numerical` is what the
/// integrator itself dissipates (or adds).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergyLedger {
    /// `∫ Σ w f_t v_base dt`: work the moving base does through the contact.
    pub work_base: f64,
    /// `∫ f⁰(t)·v dt`: work of the external load beyond the initial equilibrium.
    pub work_load: f64,
    /// `½ vᵀ M v`.
    pub kinetic: f64,
    /// `½ uᵀ K u + uᵀ f_c(0)` (the second term is the work against the initial traction).
    pub strain: f64,
    /// `Σ w (f_t² - f_t(0)²) / (2 α_t)`: energy stored in the contact's elastic springs.
    pub contact_elastic: f64,
    /// `∫ Σ w Λ |f_t| dt`: frictional dissipation.
    pub dissipation: f64,
    /// Kinetic + strain + contact-elastic energy when tracking began (0 from the initial
    /// equilibrium at rest).
    pub initial: f64,
}

impl EnergyLedger {
    /// The integrator's own dissipation: input minus everything accounted for.
    pub fn numerical(&self) -> f64 {
        self.initial + self.work_base + self.work_load
            - (self.kinetic + self.strain + self.contact_elastic + self.dissipation)
    }
}

/// The dynamic system and its integrator.
pub struct Dynamics {
    pub body: LinearBody,
    pub contact: ContactBoundary,
    pub settings: WilsonSettings,
    pub state: State,
    initial_traction: Vec<f64>,
    pub(super) initial_contact_force: Vec<f64>,
    /// Newton's operator `c₀ M + K + K_c`, built at its first use (Tsitouras' pair and
    /// central differences never need it).
    operator: Option<Operator>,
    ledger: Option<EnergyLedger>,
    /// `Σ w (μ_k f_n)² / 2α_t`: the contact springs' energy at kinetic strength, the scale the
    /// energy check uses before much work has been done.
    energy_scale: f64,
    split_steps: u64,
    /// Where each contact point's last update ended, to start the next step's first trial.
    restarts: Vec<Option<Restart>>,
    /// The body operators of the last few `τ` (most recent last), for [`LinearSolver::Condensed`].
    condensations: Vec<Condensation>,
    /// The Runge–Kutta integrator's memory, when it is the one stepping.
    pub(super) runge_kutta: Option<super::runge_kutta::RungeKutta>,
    /// Central differences' memory, when they are the ones stepping.
    pub(super) central: Option<super::central::CentralDifference>,
}

/// How many `τ` keep their factored body operator (a halved step needs another; each holds a
/// factor of the whole body).
const CONDENSATIONS_KEPT: usize = 2;

/// A saved state of [`Dynamics`] (see [`Dynamics::snapshot`]).
#[derive(Clone)]
pub(crate) struct Snapshot {
    pub(crate) state: State,
    ledger: Option<EnergyLedger>,
}

/// The contact points' response to trial slips over `τ`.
struct ContactResponse {
    /// `w f_t` of each point.
    weighted_traction: Vec<f64>,
    /// `-w ∂f_t/∂Δū` of each point (its share of `K_c`).
    stiffness: Vec<f64>,
    restarts: Vec<Option<Restart>>,
}

/// The step's system on all unknowns, solved with the sparse Jacobian `6/τ² M + K + K_c`.
struct FullSystem<'a> {
    dynamics: &'a mut Dynamics,
    tau: f64,
}

impl NewtonProblem for FullSystem<'_> {
    type Evaluation = ContactResponse;

    fn evaluate(
        &mut self,
        du_theta: &[f64],
        previous: Option<&ContactResponse>,
    ) -> Result<(Vec<f64>, ContactResponse), StepError> {
        let restarts = previous.map_or(&self.dynamics.restarts, |p| &p.restarts);
        self.dynamics.evaluate(du_theta, self.tau, restarts)
    }

    fn correct(&mut self, evaluation: &ContactResponse, delta: &mut [f64]) -> Result<(), StepError> {
        self.dynamics.factor_operator(6.0 / (self.tau * self.tau), &evaluation.stiffness)?;
        self.dynamics.solve_operator(delta);
        Ok(())
    }
}

/// The step's system condensed onto the contact unknowns `x` ([`super::condensed`]):
/// `x - Pᵀw - G F(x) = 0`.
struct CondensedSystem<'a> {
    dynamics: &'a Dynamics,
    condensation: &'a Condensation,
    tau: f64,
    /// How far the base moves over `τ`.
    base: f64,
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
        let slips: Vec<f64> = c.points.iter().map(|p| p.interpolate(x) - self.base).collect();
        let restarts = previous.map_or(&self.dynamics.restarts, |p| &p.restarts);
        let response = self.dynamics.contact_response(&slips, self.tau, restarts)?;
        let g = c.compliance_times(&c.forces(&response.weighted_traction));
        let residual = x.iter().zip(&self.free_contact).zip(g).map(|((x, w), g)| x - w - g).collect();
        Ok((residual, response))
    }

    fn correct(&mut self, evaluation: &ContactResponse, delta: &mut [f64]) -> Result<(), StepError> {
        self.condensation.solve_newton(&evaluation.stiffness, delta).map_err(StepError::Factor)
    }
}

impl Dynamics {
    /// Sets up the system at rest in its initial equilibrium.
    pub fn new(body: LinearBody, contact: ContactBoundary, settings: WilsonSettings) -> Result<Self, StepError> {
        let n = body.dofs();
        let states: Vec<ContactState> = contact
            .traction_n
            .iter()
            .map(|&fn_| ContactState::initial(&contact.params, fn_, contact.loading_direction))
            .collect();
        let initial_traction: Vec<f64> = states.iter().map(|s| s.traction_t).collect();
        let mut initial_contact_force = vec![0.0; n];
        for (point, s) in contact.points.iter().zip(&states) {
            point.scatter(point.weight * s.traction_t, &mut initial_contact_force);
        }
        let n_points = contact.points.len();
        let p = &contact.params;
        let energy_scale = contact
            .points
            .iter()
            .zip(&contact.traction_n)
            .map(|(point, f_n)| point.weight * (p.mu_k * f_n).powi(2) / (2.0 * p.alpha_t))
            .sum();
        let mut dynamics = Self {
            state: State {
                time: 0.0,
                step: 0,
                displacement: vec![0.0; n],
                velocity: vec![0.0; n],
                acceleration: vec![0.0; n],
                contact: states,
                plastic_increment: vec![0.0; n_points],
                plastic_rate: Vec::new(),
            },
            body,
            contact,
            settings,
            initial_traction,
            initial_contact_force,
            operator: None,
            ledger: None,
            energy_scale,
            split_steps: 0,
            restarts: Vec::new(),
            condensations: Vec::new(),
            runge_kutta: None,
            central: None,
        };
        if dynamics.settings.energy_tolerance.is_some() {
            dynamics.track_energy();
        }
        Ok(dynamics)
    }

    /// Keeps an [`EnergyLedger`] from now on (costs one product with `K` per step).
    pub fn track_energy(&mut self) {
        let mut ledger = EnergyLedger::default();
        self.refresh_stored_energy(&mut ledger);
        ledger.initial = ledger.kinetic + ledger.strain + ledger.contact_elastic;
        self.ledger = Some(ledger);
    }

    /// The energy balance so far, if tracked.
    pub fn energy(&self) -> Option<EnergyLedger> {
        self.ledger
    }

    /// Advances the state by `dt`. A step that fails in a way a shorter step can cure (Newton
    /// not converging across a stick/slip switch, `1/R*` leaving its range, a singular
    /// operator) is retried as two half steps, down to `dt / 2^MAX_HALVINGS`; the state is left
    /// untouched by a failed attempt.
    /// With central differences in use ([`Self::use_central_differences`]), the step is theirs.
    pub fn step(&mut self, dt: f64) -> Result<(), StepError> {
        if self.central.is_some() {
            return self.central_step(dt);
        }
        self.step_halving(dt, 0)
    }

    fn step_halving(&mut self, dt: f64, depth: u32) -> Result<(), StepError> {
        match self.try_step(dt) {
            Err(e) if depth < MAX_HALVINGS && e.cured_by_shorter_steps() => {
                self.split_steps += 1;
                self.two_halves(dt, |d, half| d.step_halving(half, depth + 1))
            }
            result => result,
        }
    }

    /// Advances by `dt` as two steps of `dt/2` taken by `half_step`, reported as one step: the
    /// step counter moves by one and `plastic_increment` holds the slip of both halves.
    pub(crate) fn two_halves(
        &mut self,
        dt: f64,
        mut half_step: impl FnMut(&mut Self, f64) -> Result<(), StepError>,
    ) -> Result<(), StepError> {
        half_step(self, 0.5 * dt)?;
        let first = self.state.plastic_increment.clone();
        half_step(self, 0.5 * dt)?;
        for (p, f) in self.state.plastic_increment.iter_mut().zip(first) {
            *p += f;
        }
        self.state.step -= 1;
        Ok(())
    }

    /// Everything a step changes, to undo a trial step.
    pub(crate) fn snapshot(&self) -> Snapshot {
        Snapshot { state: self.state.clone(), ledger: self.ledger }
    }

    /// Returns to `snapshot`.
    pub(crate) fn restore(&mut self, snapshot: Snapshot) {
        self.state = snapshot.state;
        self.ledger = snapshot.ledger;
    }

    fn try_step(&mut self, dt: f64) -> Result<(), StepError> {
        if self.settings.linear_solver == LinearSolver::Condensed {
            return self.try_step_condensed(dt);
        }
        let tau = self.settings.theta * dt;
        let predictor = (0..self.body.dofs()).map(|i| self.predictor(i, tau)).collect();
        let (settings, scale) = (self.settings, self.newton_scale(tau));
        let converged = newton(&mut FullSystem { dynamics: self, tau }, &settings, scale, predictor)?;
        let acceleration = self.theta_acceleration(&converged.x, tau);
        self.finish_step(dt, &acceleration, &converged.evaluation.restarts)
    }

    /// The predictor of unknown `i` over `τ`: constant acceleration.
    fn predictor(&self, i: usize, tau: f64) -> f64 {
        tau * self.state.velocity[i] + 0.5 * tau * tau * self.state.acceleration[i]
    }

    /// Displacements below which Newton's corrections count as converged on their own scale:
    /// the drive's velocity over `τ`.
    fn newton_scale(&self, tau: f64) -> f64 {
        self.settings.velocity_scale.max(f64::MIN_POSITIVE) * tau
    }

    /// Residual of the equation of motion at `t_n + τ` for a trial displacement increment
    /// `u_θ - u_n`, and the contact tangents; `restarts` (empty, or one per point) are an earlier
    /// trial's, from the same state.
    fn evaluate(
        &self,
        du_theta: &[f64],
        tau: f64,
        restarts: &[Option<Restart>],
    ) -> Result<(Vec<f64>, ContactResponse), StepError> {
        let mut residual = self.body_residual(du_theta, tau);
        let base = self.base_increment(tau);
        let slips: Vec<f64> = self.contact.points.iter().map(|p| p.interpolate(du_theta) - base).collect();
        let response = self.contact_response(&slips, tau, restarts)?;
        for (point, &t) in self.contact.points.iter().zip(&response.weighted_traction) {
            point.scatter(-t, &mut residual);
        }
        Ok((residual, response))
    }

    /// The residual of the equation of motion at `t_n + τ` without the contact forces:
    /// `K u_θ + M a_θ - f⁰ + f_c(0)`.
    fn body_residual(&self, du_theta: &[f64], tau: f64) -> Vec<f64> {
        let s = &self.state;
        let acceleration = self.theta_acceleration(du_theta, tau);
        let u_theta: Vec<f64> = s.displacement.iter().zip(du_theta).map(|(u, d)| u + d).collect();
        let mut residual = vec![0.0; du_theta.len()];
        self.body.stiffness.mul_vec(&u_theta, &mut residual);
        let t_theta = s.time + tau;
        for (i, r) in residual.iter_mut().enumerate() {
            *r +=
                self.body.mass[i] * acceleration[i] - t_theta * self.body.load_rate[i] + self.initial_contact_force[i];
        }
        residual
    }

    /// How far the base moves over `[t_n, t_n + τ]`.
    fn base_increment(&self, tau: f64) -> f64 {
        let t = self.state.time;
        self.contact.base_displacement_at(t + tau) - self.contact.base_displacement_at(t)
    }

    /// Updates every contact point over `τ` by its relative slip increment.
    fn contact_response(
        &self,
        slips: &[f64],
        tau: f64,
        restarts: &[Option<Restart>],
    ) -> Result<ContactResponse, StepError> {
        let params = &self.contact.params;
        let count = self.contact.points.len();
        let mut response = ContactResponse {
            weighted_traction: Vec::with_capacity(count),
            stiffness: Vec::with_capacity(count),
            restarts: Vec::with_capacity(count),
        };
        for (k, ((point, state), &slip)) in self.contact.points.iter().zip(&self.state.contact).zip(slips).enumerate() {
            let restart = restarts.get(k).copied().flatten();
            let updated = update_from(params, state, slip, tau, restart).map_err(|error| StepError::Friction {
                point: k,
                state: *state,
                error,
            })?;
            response.weighted_traction.push(point.weight * updated.state.traction_t);
            response.stiffness.push(-point.weight * updated.tangent);
            response.restarts.push(updated.restart);
        }
        Ok(response)
    }

    /// One step with Newton's method condensed onto the contact ([`super::condensed`]).
    fn try_step_condensed(&mut self, dt: f64) -> Result<(), StepError> {
        let tau = self.settings.theta * dt;
        let condensation = self.take_condensation(tau)?;
        let result = self.newton_condensed(&condensation, dt);
        self.condensations.push(condensation);
        result
    }

    /// The body operator of `τ`, factored now if it is not kept.
    fn take_condensation(&mut self, tau: f64) -> Result<Condensation, StepError> {
        // The run loop's steps differ from each other by rounding (t_end/steps against the time
        // reached); an operator within 1e-12 of τ changes the step by less than Newton's
        // tolerance.
        if let Some(k) = self.condensations.iter().position(|c| (c.tau - tau).abs() <= 1e-12 * tau) {
            return Ok(self.condensations.remove(k));
        }
        if self.condensations.len() >= CONDENSATIONS_KEPT {
            self.condensations.remove(0);
        }
        Condensation::new(&self.body, &self.contact.points, tau).map_err(StepError::Factor)
    }

    fn newton_condensed(&mut self, c: &Condensation, dt: f64) -> Result<(), StepError> {
        let tau = self.settings.theta * dt;
        // w = -A⁻¹ r₀: the body's response without contact forces.
        let mut free = self.body_residual(&vec![0.0; self.body.dofs()], tau);
        free.iter_mut().for_each(|r| *r = -*r);
        c.solve_body(&mut free);
        let predictor = c.dofs.iter().map(|&d| self.predictor(d, tau)).collect();
        let (settings, scale) = (self.settings, self.newton_scale(tau));
        let mut system = CondensedSystem {
            dynamics: self,
            condensation: c,
            tau,
            base: self.base_increment(tau),
            free_contact: c.dofs.iter().map(|&d| free[d]).collect(),
        };
        let converged = newton(&mut system, &settings, scale, predictor)?;
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
        let acceleration = self.theta_acceleration(&du_theta, tau);
        self.finish_step(dt, &acceleration, &converged.evaluation.restarts)
    }

    /// `a_θ = 6/τ² (u_θ - u_n) - 6/τ v_n - 2 a_n`.
    fn theta_acceleration(&self, du_theta: &[f64], tau: f64) -> Vec<f64> {
        let s = &self.state;
        let c0 = 6.0 / (tau * tau);
        du_theta
            .iter()
            .zip(s.velocity.iter().zip(&s.acceleration))
            .map(|(du, (v, a))| c0 * du - 6.0 / tau * v - 2.0 * a)
            .collect()
    }

    /// Assembles and factors `c₀ M + K + K_c` unless the factored one is the same: Newton's
    /// operator of Wilson's step (`c₀ = 6/τ²`) and of the implicit Runge–Kutta stages
    /// ([`super::sdirk`], `c₀ = 1/(hγ)²`). `contact_stiffness` holds each point's `-w ∂f_t/∂ū`.
    pub(super) fn factor_operator(&mut self, c0: f64, contact_stiffness: &[f64]) -> Result<(), StepError> {
        let operator = match self.operator.as_mut() {
            Some(operator) => operator,
            None => self.operator.insert(Operator::new(&self.body, &self.contact).map_err(StepError::Factor)?),
        };
        operator.factor(&self.body, &self.contact, c0, contact_stiffness).map_err(StepError::Factor)
    }

    /// Solves with the operator [`Self::factor_operator`] factored last.
    pub(super) fn solve_operator(&self, rhs: &mut [f64]) {
        self.operator.as_ref().expect("the operator is factored before it is solved with").solve_in_place(rhs);
    }

    /// Interpolates back to `t_{n+1}`, advances the contact states over `Δt`, and updates the
    /// energy ledger.
    /// `restarts` are the points' updates over `τ = θΔt`: their slip, scaled by `1/θ`, starts the
    /// updates over `Δt`.
    fn finish_step(
        &mut self,
        dt: f64,
        acceleration_theta: &[f64],
        restarts: &[Option<Restart>],
    ) -> Result<(), StepError> {
        let n = self.body.dofs();
        let theta = self.settings.theta;
        let old = &self.state;
        let base = self.contact.base_displacement_at(old.time + dt) - self.contact.base_displacement_at(old.time);
        // Work on a copy: a failure below leaves the state as it was.
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
        let mut next_restarts = Vec::with_capacity(self.contact.points.len());
        for (k, point) in self.contact.points.iter().enumerate() {
            let slip = point.interpolate(&du) - base;
            let restart = restarts[k].map(|r| r.scaled(1.0 / theta));
            let updated = update_from(&self.contact.params, &old.contact[k], slip, dt, restart)
                .map_err(|error| StepError::Friction { point: k, state: old.contact[k], error })?;
            s.contact[k] = updated.state;
            s.plastic_increment[k] = updated.plastic_increment;
            next_restarts.push(updated.restart.map(|r| r.scaled(theta)));
        }
        s.time = old.time + dt;
        s.step = old.step + 1;
        let old = std::mem::replace(&mut self.state, next);
        // Over the next τ = θΔt the slip is about θ times this step's.
        self.restarts = next_restarts;

        if let Some(mut ledger) = self.ledger.take() {
            let power_base = |state: &State| -> f64 {
                let v = self.contact.base_velocity_at(state.time);
                self.contact.points.iter().zip(&state.contact).map(|(p, c)| p.weight * c.traction_t * v).sum()
            };
            let power_load = |state: &State| -> f64 {
                self.body.load_rate.iter().zip(&state.velocity).map(|(f, v)| state.time * f * v).sum()
            };
            ledger.work_base += 0.5 * dt * (power_base(&old) + power_base(&self.state));
            // The load is linear in time and the velocity quadratic over the step (linear
            // acceleration), so Simpson's rule integrates the load's power exactly.
            let t_mid = old.time + 0.5 * dt;
            let power_load_mid: f64 = self
                .body
                .load_rate
                .iter()
                .zip(old.velocity.iter().zip(&old.acceleration).zip(&self.state.acceleration))
                .map(|(f, ((v, a0), a1))| t_mid * f * (v + 0.5 * dt * a0 + 0.125 * dt * (a1 - a0)))
                .sum();
            ledger.work_load += dt / 6.0 * (power_load(&old) + 4.0 * power_load_mid + power_load(&self.state));
            ledger.dissipation += self
                .contact
                .points
                .iter()
                .enumerate()
                .map(|(k, p)| {
                    p.weight
                        * self.state.plastic_increment[k]
                        * 0.5
                        * (old.contact[k].traction_t.abs() + self.state.contact[k].traction_t.abs())
                })
                .sum::<f64>();
            self.refresh_stored_energy(&mut ledger);
            self.ledger = Some(ledger);
            if let Some(tolerance) = self.settings.energy_tolerance {
                // Early on, measured against the contact's strength energy rather than the little
                // work done so far.
                let reference = (ledger.initial + ledger.work_base + ledger.work_load).max(self.energy_scale);
                let share = -ledger.numerical() / reference;
                if share > tolerance {
                    return Err(StepError::EnergyCreated { share, tolerance });
                }
            }
        }
        Ok(())
    }

    fn refresh_stored_energy(&self, ledger: &mut EnergyLedger) {
        let s = &self.state;
        ledger.kinetic = self.body.kinetic_energy(&s.velocity);
        ledger.strain = self.body.strain_energy(&s.displacement)
            + s.displacement.iter().zip(&self.initial_contact_force).map(|(u, f)| u * f).sum::<f64>();
        let alpha = self.contact.params.alpha_t;
        ledger.contact_elastic = self
            .contact
            .points
            .iter()
            .zip(&s.contact)
            .zip(&self.initial_traction)
            .map(|((p, c), f0)| p.weight * (c.traction_t * c.traction_t - f0 * f0) / (2.0 * alpha))
            .sum();
    }

    /// How many steps (or half steps) so far had to be split in two to converge.
    pub fn split_steps(&self) -> u64 {
        self.split_steps
    }

    /// Largest nodal imbalance of the total equation `M a + K u = f⁰ + f_c - f_c(0)` in the
    /// current state (N/m or Pa), computed when asked. Wilson's method enforces equilibrium at
    /// `t_n + θΔt`, so this is the interpolation error, not an accumulated drift.
    pub fn imbalance(&self) -> f64 {
        let s = &self.state;
        let mut imbalance = vec![0.0; self.body.dofs()];
        self.body.stiffness.mul_vec(&s.displacement, &mut imbalance);
        for (i, e) in imbalance.iter_mut().enumerate() {
            *e = s.time * self.body.load_rate[i]
                - self.initial_contact_force[i]
                - self.body.mass[i] * s.acceleration[i]
                - *e;
        }
        for (point, c) in self.contact.points.iter().zip(&s.contact) {
            point.scatter(point.weight * c.traction_t, &mut imbalance);
        }
        max_abs(&imbalance)
    }
}
