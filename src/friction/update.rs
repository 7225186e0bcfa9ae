//! The implicit update of a contact point over one step: the discrete counterpart of eqs. (5)-(9).
//!
//! Given the state at `t_n` and a prescribed relative tangential displacement increment `Δū`
//! over `Δt`, the update returns the state at `t_{n+1}` and the consistent tangent `∂f_t/∂Δū`.
//!
//! * Traction: elastic predictor `f_trial = f_n - α_t Δū`, plastic corrector along `t` (radial
//!   return, exact in 1D): `|f_{n+1}| = |f_trial| - α_t Δp`, where `Δp = ∫ Λ dt ≥ 0`.
//! * Degree of structure `z = 1/R*`: the trapezoidal rule on eq. (4),
//!   `z₁ = z₀ - γκ Δp [(z₀-1)^m + (z₁-1)^m]/2 + γξ Δt [(1-a z₀)^n + (1-a z₁)^n]/2`, `a = μ_k/μ_s`,
//!   implicit in `z₁` (the decay term is integrated in `p`, the healing term in `t`); a healing
//!   that relaxes within the step (`γξΔt n a > 1`) is weighted so that its linear part decays
//!   by the exact `e^{-γξΔt a}` ([`healing_weights`]), monotonically, where the trapezoidal rule
//!   would overshoot `μ_s/μ_k`.
//! * Normal sliding ratio: `Ṙ = -r ln(R) Λ` integrated exactly, `Ψ(R₁) = Ψ(R₀) + r Δp`
//!   (see [`crate::friction::expint`]).
//! * Consistency: the subloading surface passes through the new traction,
//!   `|f_{n+1}| = R₁ μ_k f_n z₁` (eq. 3). This scalar equation is solved by safeguarded Newton
//!   in `v = ln(-ln R₁)`, where `Ψ(R₁)` and so `Δp` are explicit (no inverse of `E1`), and `Δp`
//!   is then polished in the consistency condition itself; loading (`Δp > 0`) happens exactly
//!   when the elastic predictor lies outside the current subloading surface, the discrete form
//!   of `Λ > 0` in eq. (9).
//!
//! Traction reversal: when the predictor changes the sign of `f_t`, the path passed through
//! `f_t = 0`, where `R = 0`; the corrector then starts from `Ψ(0) = 0` in the new direction. No
//! `ln 0` is ever evaluated.

use std::fmt;

use crate::friction::expint::{psi, psi_at_ln_u};
use crate::friction::law::{decay, decay_slope, healing, healing_slope};
use crate::friction::params::FrictionParams;
use crate::friction::state::ContactState;

/// Relative slack allowed at the bounds of `R` and `1/R*` for rounding only.
const ROUNDING: f64 = 1e-12;

/// Result of one update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Update {
    /// State at the end of the step.
    pub state: ContactState,
    /// Plastic slip increment `Δp = ∫ Λ dt ≥ 0` (m).
    pub plastic_increment: f64,
    /// Consistent tangent `∂f_t/∂Δū` (Pa/m): `-α_t` in unloading, `-α_t (1 - α_t/|∂ψ/∂Δp|)` in
    /// loading; 0 where there is no normal traction.
    pub tangent: f64,
    /// `∂(1/R*)/∂Δū` (1/m).
    pub structure_tangent: f64,
    /// `∂f_t/∂f_n` at the end of the step (-), the normal traction's share of the consistent
    /// tangent: `σ α_t R μ_k (1/R*)/|∂ψ/∂Δp|` in loading, 0 otherwise. An evolving normal
    /// traction `f_n = f_n⁰ - α_n ū_n` makes `∂f_t/∂Δū_n = -α_n` times it, the discrete `tn`
    /// entry of eq. (7)'s `C^ep`.
    pub normal_tangent: f64,
    /// `∂(1/R*)/∂f_n` at the end of the step (1/Pa).
    pub structure_normal_tangent: f64,
    /// Where the consistency solve ended (loading only), to start the next update of the same
    /// point from the same state with [`update_from`].
    pub restart: Option<Restart>,
}

/// The end of one consistency solve: a starting point for the next solve of the same point
/// (Newton's next trial of the step, the same step over another `dt`, or the next step), which
/// then starts next to its root instead of from the elastic guess. It is taken only where the
/// root is unique (see [`update_from`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Restart {
    /// `R` at the start of the step on the loaded side.
    ratio_start: f64,
    /// `Ψ(R)` at the start of the step.
    psi_start: f64,
    /// The solution `Δp` (m).
    plastic_increment: f64,
    /// Where the solve ended, when `R` moved.
    root: Option<Root>,
}

/// The end of a consistency solve in its unknown `v = ln(-ln R)`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
struct Root {
    ln_u: f64,
    /// `R`.
    ratio: f64,
    /// `Ψ(R)`.
    psi: f64,
}

impl Restart {
    /// The same restart with its `Δp` scaled (for a step of another length).
    pub fn scaled(self, factor: f64) -> Self {
        Self { plastic_increment: self.plastic_increment * factor, ..self }
    }
}

/// A contact state the model does not admit, or an update that found no solution.
#[derive(Debug, Clone, PartialEq)]
pub enum FrictionError {
    /// `1/R*` would leave `[1, μ_s/μ_k]`: the step is too large for the trapezoidal rule.
    StructureOutOfRange { structure: f64, min: f64, max: f64, plastic_increment: f64, dt: f64 },
    /// `R` outside `[0, 1]` at the start of a step.
    SlidingRatioOutOfRange { sliding_ratio: f64 },
    /// A non-finite input (increment, step, state).
    NonFinite { what: &'static str, value: f64 },
    /// The consistency equation did not converge.
    NotConverged { residual: f64 },
}

impl fmt::Display for FrictionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FrictionError::StructureOutOfRange { structure, min, max, plastic_increment, dt } => write!(
                f,
                "degree of structure 1/R* = {structure} leaves [{min}, {max}] in a step of dt = {dt} s \
                 with plastic slip {plastic_increment} m: the trapezoidal update of eq. (4) needs a smaller step"
            ),
            FrictionError::SlidingRatioOutOfRange { sliding_ratio } => {
                write!(f, "normal sliding ratio R = {sliding_ratio} is outside [0, 1]")
            }
            FrictionError::NonFinite { what, value } => write!(f, "{what} is not finite ({value})"),
            FrictionError::NotConverged { residual } => {
                write!(f, "the consistency condition did not converge (residual {residual} Pa)")
            }
        }
    }
}

impl std::error::Error for FrictionError {}

impl FrictionError {
    /// Whether the same slip over a shorter step may succeed: `1/R*` leaving its range in the
    /// trapezoidal rule of eq. (4), or the consistency solve not converging.
    pub fn cured_by_shorter_steps(&self) -> bool {
        matches!(self, FrictionError::StructureOutOfRange { .. } | FrictionError::NotConverged { .. })
    }
}

/// Advances one contact point by the relative tangential displacement `slip_increment` (m) over
/// `dt` (s). See the module documentation for the scheme.
pub fn update(
    params: &FrictionParams,
    state: &ContactState,
    slip_increment: f64,
    dt: f64,
) -> Result<Update, FrictionError> {
    update_from(params, state, slip_increment, dt, None)
}

/// [`update`], starting the consistency solve from `restart`, the [`Update::restart`] of an
/// earlier update of the same point: from the same `state` (another trial of the step), or from
/// the previous step. The result is the same up to the solver's tolerance; only the work differs.
pub fn update_from(
    params: &FrictionParams,
    state: &ContactState,
    slip_increment: f64,
    dt: f64,
    restart: Option<Restart>,
) -> Result<Update, FrictionError> {
    if state.traction_n <= 0.0 {
        check_inputs(slip_increment, dt)?;
        return without_strength(params, state, slip_increment, dt);
    }
    update_pressed(params, state, slip_increment, state.traction_n, dt, restart)
}

/// [`update_from`] for a point whose normal traction evolves (`ḟ_n = -α_n v̄_n`, integrated
/// exactly by the caller): `traction_n` is its value at the end of the step. The subloading
/// surface the step ends on is the end's, `|f_t| = R μ_k f_n (1/R*)` with the new `f_n`; `R`
/// at the start is the start's. Where `traction_n ≤ 0` the contact is open: both tractions
/// are zero and the degree of structure is held (no traction, so no plastic slip to decay it,
/// and no real contact to heal; docs/model.md, "Opening and closing"). A point that was open
/// and closes starts again from `f_t = 0`.
pub fn update_evolving(
    params: &FrictionParams,
    state: &ContactState,
    slip_increment: f64,
    traction_n: f64,
    dt: f64,
    restart: Option<Restart>,
) -> Result<Update, FrictionError> {
    if !traction_n.is_finite() {
        return Err(FrictionError::NonFinite { what: "normal traction", value: traction_n });
    }
    if traction_n <= 0.0 {
        check_inputs(slip_increment, dt)?;
        return Ok(Update {
            state: ContactState { traction_t: 0.0, traction_n: 0.0, ..*state },
            plastic_increment: 0.0,
            tangent: 0.0,
            structure_tangent: 0.0,
            normal_tangent: 0.0,
            structure_normal_tangent: 0.0,
            restart: None,
        });
    }
    if state.traction_n <= 0.0 {
        let closing = ContactState { traction_t: 0.0, traction_n, ..*state };
        return update_pressed(params, &closing, slip_increment, traction_n, dt, None);
    }
    update_pressed(params, state, slip_increment, traction_n, dt, restart)
}

/// [`update_from`] where `traction_n` is `None` (the normal traction held), [`update_evolving`]
/// to `traction_n` at the end of the step otherwise.
pub fn update_with(
    params: &FrictionParams,
    state: &ContactState,
    slip_increment: f64,
    traction_n: Option<f64>,
    dt: f64,
    restart: Option<Restart>,
) -> Result<Update, FrictionError> {
    match traction_n {
        None => update_from(params, state, slip_increment, dt, restart),
        Some(f_n) => update_evolving(params, state, slip_increment, f_n, dt, restart),
    }
}

fn check_inputs(slip_increment: f64, dt: f64) -> Result<(), FrictionError> {
    if !slip_increment.is_finite() {
        return Err(FrictionError::NonFinite { what: "relative slip increment", value: slip_increment });
    }
    if !dt.is_finite() || dt < 0.0 {
        return Err(FrictionError::NonFinite { what: "time step", value: dt });
    }
    Ok(())
}

/// The update of a point pressed at the start (`state.traction_n > 0`) and at the end
/// (`traction_n > 0`) of the step.
fn update_pressed(
    params: &FrictionParams,
    state: &ContactState,
    slip_increment: f64,
    traction_n: f64,
    dt: f64,
    restart: Option<Restart>,
) -> Result<Update, FrictionError> {
    if !slip_increment.is_finite() {
        return Err(FrictionError::NonFinite { what: "relative slip increment", value: slip_increment });
    }
    if !dt.is_finite() || dt < 0.0 {
        return Err(FrictionError::NonFinite { what: "time step", value: dt });
    }
    let alpha = params.alpha_t;
    let z0 = state.structure;
    let mu_f = params.mu_k * traction_n;
    let trial = state.traction_t - alpha * slip_increment;
    let healed = solve_structure(params, z0, 0.0, dt)?;
    let elastic = Update {
        state: ContactState { traction_t: trial, traction_n, structure: healed.value, ..*state },
        plastic_increment: 0.0,
        tangent: -alpha,
        structure_tangent: 0.0,
        normal_tangent: 0.0,
        structure_normal_tangent: 0.0,
        restart: None,
    };
    if trial == 0.0 {
        return Ok(elastic);
    }
    let sigma = trial.signum();
    let reversed = state.traction_t * sigma <= 0.0;
    // R at the start is the start's: on the surface through the start's tractions.
    let ratio_start = if reversed { 0.0 } else { state.traction_t.abs() / (params.mu_k * state.traction_n * z0) };
    if ratio_start.is_nan() || ratio_start > 1.0 + ROUNDING {
        return Err(FrictionError::SlidingRatioOutOfRange { sliding_ratio: ratio_start });
    }
    let trial_abs = trial.abs();
    if trial_abs / (mu_f * healed.value) <= ratio_start {
        return Ok(elastic); // unloading: the predictor lies inside the subloading surface
    }
    let loading = Loading { params, z0, dt, traction_n, mu_f, trial_abs, ratio_start, healed: healed.value };
    let (last, root, psi_start) = loading.return_to_surface(restart)?;
    Ok(loading.update(state, sigma, &last, root, psi_start))
}

/// No normal traction: no strength, no traction; all relative sliding is plastic.
fn without_strength(
    params: &FrictionParams,
    state: &ContactState,
    slip_increment: f64,
    dt: f64,
) -> Result<Update, FrictionError> {
    let z0 = state.structure;
    let increment = slip_increment.abs();
    let structure = solve_structure(params, z0, increment, dt)?;
    Ok(Update {
        state: ContactState {
            traction_t: 0.0,
            structure: structure.value,
            plastic_slip: state.plastic_slip + increment,
            ..*state
        },
        plastic_increment: increment,
        tangent: 0.0,
        structure_tangent: structure.d_plastic * slip_increment.signum(),
        normal_tangent: 0.0,
        structure_normal_tangent: 0.0,
        restart: None,
    })
}

/// A loading step: the trial traction lies outside the subloading surface, and the step ends
/// on it (eq. 3) with plastic slip.
struct Loading<'a> {
    params: &'a FrictionParams,
    /// `1/R*` at the start.
    z0: f64,
    dt: f64,
    /// `f_n` at the end of the step.
    traction_n: f64,
    /// `μ_k f_n` at the end of the step.
    mu_f: f64,
    /// `|f_trial|`.
    trial_abs: f64,
    /// `R` at the start.
    ratio_start: f64,
    /// `1/R*` healed over the step without slip.
    healed: f64,
}

impl Loading<'_> {
    /// The end of the step on the subloading surface, the root's position for a restart, and
    /// `Ψ(R₀)`.
    fn return_to_surface(&self, restart: Option<Restart>) -> Result<(OnSurface, Option<Root>, f64), FrictionError> {
        let Loading { params, z0, dt, mu_f, trial_abs, ratio_start, healed, .. } = *self;
        let alpha = params.alpha_t;
        // Loading: find the end of the step on the subloading surface, ψ = |f_trial| - α_t Δp -
        // R μ_k f_n z(Δp) = 0 with Ψ(R) = Ψ(R₀) + r Δp. Ψ(R) at the start is the restart's only if
        // it started from the same R.
        let psi_start =
            restart.filter(|r| r.ratio_start == self.ratio_start).map_or_else(|| psi(ratio_start), |r| r.psi_start);
        let max_increment = trial_abs / alpha;
        // A trial so far that the decay of 1/R* overshoots 1 lies beyond the root; only an
        // overshoot at the solution itself is an error.
        let too_far =
            |e: &FrictionError| matches!(e, FrictionError::StructureOutOfRange { structure, .. } if *structure < 1.0);
        let ends_on_surface = |increment: f64, ratio: f64, log_ratio: f64| -> Result<OnSurface, FrictionError> {
            let structure = solve_structure(params, z0, increment, dt)?;
            // ∂ψ/∂Δp = -(α_t + hardening), with dR/dΔp = r (-ln R) from Ψ'(R) = 1/(-ln R). The
            // hardening is kept apart from α_t: next to a very stiff contact it would be lost.
            let hardening = mu_f * (params.r * log_ratio * structure.value + ratio * structure.d_plastic);
            let value = trial_abs - alpha * increment - ratio * mu_f * structure.value;
            Ok(OnSurface { increment, value, hardening, ratio, structure })
        };

        // What a converged ψ may not exceed.
        let tolerance = 1e-9 * trial_abs.max(mu_f);
        // A restart starts the solve only where ψ is monotone and so has one root: else the root
        // found could depend on where the solve started, and it starts from the same point always.
        let restart_near = restart.filter(|_| single_root(params, mu_f));
        let (end, root) = if psi_start.is_infinite() {
            // R₀ = 1 stays 1 (Ṙ = 0): the unknown is q = -Δp, in which ψ increases.
            let start = restart_near.map_or(0.0, |r| -r.plastic_increment.clamp(0.0, max_increment));
            let at = |q: f64| {
                let end = ends_on_surface(-q, 1.0, 0.0)?;
                Ok(Trial { slope: alpha + end.hardening, noise: 8.0 * f64::EPSILON * trial_abs, end })
            };
            (solve_consistency(at, -max_increment, 0.0, start, &too_far, tolerance)?, None)
        } else {
            // The unknown is v = ln(-ln R), in which Ψ(R) = E1(e^v) is explicit: each trial costs
            // one evaluation of E1 where Δp as the unknown needs an inversion of Ψ. Δp(v) =
            // (Ψ(R(v)) - Ψ(R₀))/r falls as v rises (dΔp/dv = -R/r), and ψ rises with it.
            let v_start = if ratio_start > 0.0 { (-ratio_start.ln()).ln() } else { LN_U_MAX };
            // E1(u) ≥ -γ - ln u, so below this Δp(v) exceeds |f_trial|/α_t, where ψ < 0. Far below
            // -745, u = e^v is 0, R is 1 and E1 is -γ - v.
            let v_floor = -(psi_start + params.r * max_increment) - 1.0;
            let at = |v: f64| {
                let (u, ratio, psi_end) = psi_at_ln_u(v);
                let increment = (psi_end - psi_start) / params.r;
                let end = ends_on_surface(increment.max(0.0), ratio, u)?;
                let noise = 8.0 * f64::EPSILON * (trial_abs + alpha * (psi_end + psi_start) / params.r);
                Ok(Trial { slope: (alpha + end.hardening) * ratio / params.r, noise, end })
            };
            // Start from the restart's end, moved along dΨ/dv = -R to the restart's Δp; without
            // one, from the R whose surface passes through the trial traction (no plastic slip).
            let guess = restart_near
                .and_then(|r| {
                    r.root.map(|root| root.ln_u - (psi_start + params.r * r.plastic_increment - root.psi) / root.ratio)
                })
                .filter(|v| *v > v_floor && *v < v_start)
                .unwrap_or_else(|| {
                    let ratio = (trial_abs / (mu_f * healed)).min(1.0 - 1e-3);
                    (-ratio.ln()).ln().clamp(v_floor, v_start)
                });
            let end = solve_consistency(at, v_floor, v_start, guess, &too_far, tolerance)?;
            let root = Root { ln_u: end.0, ratio: end.1.end.ratio, psi: psi_start + params.r * end.1.end.increment };
            (end, Some(root))
        };
        Ok((end.1.end, root, psi_start))
    }

    /// The update that ends on the surface at `last`, with traction of sign `sigma`.
    fn update(&self, state: &ContactState, sigma: f64, last: &OnSurface, root: Option<Root>, psi_start: f64) -> Update {
        let Loading { params, z0, dt, traction_n, mu_f, ratio_start, .. } = *self;
        let alpha = params.alpha_t;
        let (increment, structure) = polish_increment(params, z0, dt, last.ratio * mu_f, last);
        let stiffness = alpha + last.hardening; // |∂ψ/∂Δp|
        // The traction on the subloading surface, |f| = R μ_k f_n / R*: exact on the surface side,
        // where |f_trial| - α_t Δp would carry the cancellation of a large trial traction.
        let traction = sigma * last.ratio * mu_f * structure.value;
        // ∂Δp/∂|f_trial| = 1/|∂ψ/∂Δp|, ∂|f_trial|/∂Δū = -α_t σ.
        let d_increment = -alpha * sigma / stiffness;
        // ∂ψ/∂f_n = -R μ_k (1/R*) at fixed Δp: ∂Δp/∂f_n = -R μ_k (1/R*)/|∂ψ/∂Δp|.
        let d_increment_normal = -last.ratio * params.mu_k * structure.value / stiffness;
        Update {
            state: ContactState {
                traction_t: traction,
                traction_n,
                structure: structure.value,
                plastic_slip: state.plastic_slip + increment,
            },
            plastic_increment: increment,
            // -α_t (1 - α_t/(α_t + h)) = -α_t h/(α_t + h), without the cancellation.
            tangent: -alpha * last.hardening / stiffness,
            structure_tangent: structure.d_plastic * d_increment,
            normal_tangent: -sigma * alpha * d_increment_normal,
            structure_normal_tangent: structure.d_plastic * d_increment_normal,
            restart: Some(Restart { ratio_start, psi_start, plastic_increment: increment, root }),
        }
    }
}

/// `Δp` and `1/R*` at the end, polished by the consistency condition at the solution's `R`:
/// one Newton step on `α_t Δp + R μ_k f_n z(Δp) = |f_trial|` in `Δp` alone, whose residual is
/// the trial's `-ψ`. `(Ψ(R) - Ψ(R₀))/r` carries the rounding of `Ψ(R₀)/r`, large next to a small
/// `Δp`; the step brings `Δp` to the rounding of the tractions, so that it depends on `R` alone
/// and not on where the solve for `R` stopped. `surface` is `R μ_k f_n`.
fn polish_increment(params: &FrictionParams, z0: f64, dt: f64, surface: f64, end: &OnSurface) -> (f64, Structure) {
    let unpolished = (end.increment, end.structure);
    let slope = params.alpha_t + surface * end.structure.d_plastic;
    // Where the structure's decay outruns α_t (see [`single_root`]) the step is no better.
    if slope <= 0.5 * params.alpha_t {
        return unpolished;
    }
    let increment = (end.increment + end.value / slope).max(0.0);
    if increment == end.increment || !increment.is_finite() {
        return unpolished;
    }
    solve_structure(params, z0, increment, dt).map_or(unpolished, |structure| (increment, structure))
}

/// Whether `ψ` is monotone in `Δp` for every state, and so has one root: `|∂ψ/∂Δp| = α_t +
/// μ_k f_n (r (-ln R) z + R z')` with `z' = dz/dΔp ≥ -γκ max (z - 1)^m` (the trapezoidal rule's
/// `∂F/∂z ≥ 1`), so `α_t > μ_k f_n γκ max (z - 1)^m` suffices. It holds by a wide margin for the
/// paper's constants (a stiff contact) and fails where the structure's decay outruns it.
fn single_root(params: &FrictionParams, mu_f: f64) -> bool {
    let largest_decay = decay(params, params.max_structure()).max(decay(params, 1.0));
    params.alpha_t > mu_f * params.rstar_scale() * params.kappa * largest_decay
}

/// Upper bound of `v = ln u = ln(-ln R)`: `R = e^{-735}`, which is 0 to every traction (`Ψ`
/// is then below 1e-321).
const LN_U_MAX: f64 = 6.6;

/// The consistency function at one trial of its unknown (`v` or `q`, see [`update_from`]).
struct Trial {
    /// `dψ/d(unknown)`, positive.
    slope: f64,
    /// Rounding noise of `ψ`: the size of its terms times a few ulps.
    noise: f64,
    end: OnSurface,
}

/// The end of the step that a trial's `Δp` and `R` give.
#[derive(Debug, Clone, Copy)]
struct OnSurface {
    /// `Δp` (m).
    increment: f64,
    /// `ψ` (Pa).
    value: f64,
    /// `|∂ψ/∂Δp| - α_t`.
    hardening: f64,
    /// `R`.
    ratio: f64,
    structure: Structure,
}

/// Safeguarded Newton for `ψ(x) = 0` on `[lo, hi]`, where `ψ` increases from negative to
/// positive, from `start`. A trial that `too_far` rejects lies below the root. Returns the
/// root and the trial there; an error if `ψ` could not be brought to zero.
fn solve_consistency(
    at: impl Fn(f64) -> Result<Trial, FrictionError>,
    mut lo: f64,
    mut hi: f64,
    start: f64,
    too_far: &impl Fn(&FrictionError) -> bool,
    tolerance: f64,
) -> Result<(f64, Trial), FrictionError> {
    let mut x = start;
    let mut last = match at(x) {
        Ok(t) => t,
        Err(e) if too_far(&e) && x < hi => {
            x = hi;
            at(hi)?
        }
        Err(e) => return Err(e),
    };
    let mut overshoot = None;
    let (mut last_step, mut step_before_last) = (f64::INFINITY, f64::INFINITY);
    // A few ulps of x: a trial closer than this would change nothing.
    let ulps = |x: f64| 4.0 * f64::EPSILON * x.abs().max(1.0);
    for _ in 0..200 {
        if last.end.value.abs() <= last.noise {
            break;
        }
        if last.end.value > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let newton = x - last.end.value / last.slope;
        // Bisect when Newton leaves the bracket or fails to halve the step before last (it can
        // cycle between the ends where ψ bends strongly).
        let contracts = (newton - x).abs() <= 0.5 * step_before_last;
        let next = if newton.is_finite() && newton > lo && newton < hi && contracts { newton } else { 0.5 * (lo + hi) };
        let step = (next - x).abs();
        step_before_last = last_step;
        last_step = step;
        let rounding = ulps(x);
        if next == newton && step <= rounding {
            break;
        }
        match at(next) {
            Ok(t) => {
                x = next;
                last = t;
            }
            Err(e) if too_far(&e) && next < hi => {
                lo = next;
                overshoot = Some(e);
                if hi - lo <= rounding {
                    break;
                }
                continue;
            }
            Err(e) => return Err(e),
        }
        if step <= rounding || hi - lo <= rounding {
            break;
        }
    }
    // ψ cannot be resolved below its rounding noise, nor below its change between neighbouring
    // floating-point values of x.
    let resolution = last.noise + last.slope * ulps(x);
    if last.end.value.is_nan() || last.end.value.abs() > tolerance.max(resolution) {
        // Closing in on the edge where 1/R* leaves its range means the root lies beyond it.
        return Err(overshoot.unwrap_or(FrictionError::NotConverged { residual: last.end.value }));
    }
    Ok((x, last))
}

/// `1/R*` at the end of a step and its derivative with respect to the plastic slip increment.
#[derive(Debug, Clone, Copy)]
struct Structure {
    value: f64,
    d_plastic: f64,
}

/// The weights `(w₀, w₁)` of eq. (4)'s healing term at the start and the end of a step of
/// `dt`, with `w₀ + w₁ = γξΔt`. With `x = γξΔt n a` (`a = μ_k/μ_s`; the healing's rate of
/// relaxation over the step, linearized): the trapezoidal rule's `(γξΔt/2, γξΔt/2)` for `x ≤ 1`,
/// where its factor on the healing's linear part, `(1 - x/2)/(1 + x/2)`, lies within `x³/12` of
/// the exact `e^{-x}`; above, the weighting `w₁ = θ γξΔt` with
/// `θ = (x - 1 + e^{-x}) / (x (1 - e^{-x}))`, which makes that factor `e^{-x}` itself: for
/// `n = 1` without slip the step is the exact solution `μ_s/μ_k - (μ_s/μ_k - z₀) e^{-γξaΔt}`.
/// Either factor is positive, so `1/R*` approaches `μ_s/μ_k` monotonically however stiff the
/// healing; the trapezoidal rule alone would reflect it about the bound (towards
/// `2 μ_s/μ_k - z₀` as `ξΔt → ∞`) and out of its range. The paper's `ξ = 0.1/s` at
/// `Δt = 0.01 s` is `x = 5e-4`.
fn healing_weights(params: &FrictionParams, dt: f64) -> (f64, f64) {
    let full = params.rstar_scale() * params.xi * dt;
    let x = full * params.n.max(1.0) * params.kinetic_static_ratio();
    if x <= 1.0 {
        return (0.5 * full, 0.5 * full);
    }
    let decayed = (-x).exp();
    let theta = (x - 1.0 + decayed) / (x * (1.0 - decayed));
    ((1.0 - theta) * full, theta * full)
}

/// Solves the trapezoidal rule for the degree of structure (see the module documentation).
/// `F(z)` is strictly increasing (`F' ≥ 1`), so the root is unique; if it lies outside
/// `[1, μ_s/μ_k]` the step is too large for the rule and an error says so.
fn solve_structure(
    params: &FrictionParams,
    z0: f64,
    plastic_increment: f64,
    dt: f64,
) -> Result<Structure, FrictionError> {
    let gamma = params.rstar_scale();
    let decay_weight = 0.5 * gamma * params.kappa * plastic_increment;
    let (heal_start, heal_end) = healing_weights(params, dt);
    if params.m == 1.0 && params.n == 1.0 && z0.is_finite() {
        // The paper's exponents make F linear in z inside [1, μ_s/μ_k]:
        // F(z) = (1 + w_d + w_h a) z - (fixed + w_d + w_h). A root inside the range is returned
        // here, after one Newton correction that polishes the rounding; anything else takes
        // the general path below, which tells a bound reached from a step too large.
        let a = params.kinetic_static_ratio();
        let fixed = z0 - decay_weight * (z0 - 1.0) + heal_start * (1.0 - a * z0);
        let slope = 1.0 + decay_weight + heal_end * a;
        let inverse_slope = 1.0 / slope;
        let constant = fixed + decay_weight + heal_end;
        let z = constant * inverse_slope;
        if z >= 1.0 && z * a <= 1.0 {
            let polished = z - (slope * z - constant) * inverse_slope;
            let z = if polished < 1.0 {
                1.0
            } else if polished * a > 1.0 {
                params.max_structure()
            } else {
                polished
            };
            let d_plastic = -0.5 * gamma * params.kappa * ((z0 - 1.0) + (z - 1.0)) * inverse_slope;
            return Ok(Structure { value: z, d_plastic });
        }
    }
    let fixed = z0 - decay_weight * decay(params, z0) + heal_start * healing(params, z0);
    let f = |z: f64| z - fixed + decay_weight * decay(params, z) - heal_end * healing(params, z);
    let df = |z: f64| 1.0 + decay_weight * decay_slope(params, z) - heal_end * healing_slope(params, z);
    let min = 1.0;
    let max = 1.0 / params.kinetic_static_ratio();
    let out_of_range =
        |structure: f64| FrictionError::StructureOutOfRange { structure, min, max, plastic_increment, dt };
    if !z0.is_finite() {
        return Err(FrictionError::NonFinite { what: "degree of structure", value: z0 });
    }
    let f_min = f(min);
    let f_max = f(max);
    // Past a bound, the rule's rate there decides: with an exponent below 1 it vanishes like a
    // fractional power, the exact solution reaches the bound within the step and stays there;
    // with an exponent of 1 or more it approaches the bound only asymptotically, so crossing it
    // means the step is too large for the trapezoidal rule.
    if f_min > ROUNDING * max {
        if params.m < 1.0 && plastic_increment > 0.0 {
            return Ok(Structure { value: min, d_plastic: 0.0 });
        }
        return Err(out_of_range(min - f_min));
    }
    if f_max < -ROUNDING * max {
        if params.n < 1.0 && dt > 0.0 {
            return Ok(Structure { value: max, d_plastic: 0.0 });
        }
        return Err(out_of_range(max - f_max));
    }
    // (With the paper's exponents this is reached only for a root outside the range by
    // rounding; the closed form above has taken every other.)
    let z = newton_structure(&f, &df, z0.clamp(min, max), min, max);
    let slope = df(z);
    // ∂F/∂Δp = γκ/2 [(z₀-1)^m + (z-1)^m]; dz/dΔp = -(∂F/∂Δp)/(∂F/∂z).
    let d_plastic = if slope.is_finite() {
        -0.5 * gamma * params.kappa * (decay(params, z0) + decay(params, z)) / slope
    } else {
        0.0
    };
    Ok(Structure { value: z, d_plastic })
}

/// Safeguarded Newton for the increasing `f` on `[min, max]`, where it changes sign.
fn newton_structure(f: &impl Fn(f64) -> f64, df: &impl Fn(f64) -> f64, start: f64, min: f64, max: f64) -> f64 {
    let (mut lo, mut hi) = (min, max);
    let mut z = start;
    for _ in 0..200 {
        let value = f(z);
        // F is a sum of terms of size max: below a few ulps of that it is rounding noise.
        if value.abs() <= 4.0 * f64::EPSILON * max {
            break;
        }
        if value < 0.0 {
            lo = z;
        } else {
            hi = z;
        }
        let slope = df(z);
        let newton = z - value / slope;
        let next = if newton.is_finite() && newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
        let step = (next - z).abs();
        z = next;
        if step <= 2.0 * f64::EPSILON * z || hi - lo <= 2.0 * f64::EPSILON * hi {
            break;
        }
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's constants with healing `xi`.
    fn params(xi: f64) -> FrictionParams {
        FrictionParams { xi, ..FrictionParams::paper() }
    }

    #[test]
    fn stiff_healing_relaxes_to_the_bound_as_the_exact_solution_does() {
        // Without slip and with n = 1, eq. (4) is dz/dt = γξ(1 - a z): z(t) = 1/a - (1/a - z₀) e^{-γξat}.
        // Above x = γξaΔt = 1 the step is that solution; below, the trapezoidal rule, within
        // x³/12 of it; at every ξ up to 1e12/s the step stays inside [z₀, μ_s/μ_k].
        let (z0, dt) = (1.2, 0.01);
        for xi in [1e-3, 0.1, 10.0, 100.0, 199.0, 201.0, 1e3, 1e4, 1e6, 1e8, 1e12] {
            let p = params(xi);
            let (a, max) = (p.kinetic_static_ratio(), p.max_structure());
            let z = solve_structure(&p, z0, 0.0, dt).unwrap().value;
            let x = p.rstar_scale() * xi * a * dt;
            let exact = max - (max - z0) * (-x).exp();
            assert!((z0..=max).contains(&z), "ξ = {xi}: 1/R* = {z} leaves [{z0}, {max}]");
            let allowed = if x <= 1.0 { (max - z0) * x.powi(3) / 12.0 + 1e-15 } else { 4.0 * f64::EPSILON * max };
            assert!((z - exact).abs() <= allowed, "ξ = {xi} (x = {x}): {z} against the exact {exact}");
        }
    }

    #[test]
    fn stiff_healing_with_slip_stays_in_range() {
        // Decay and healing together, through the general path (m = 2, n = 0.5 and 2) and the
        // linear one, at healing from the paper's to 1e10/s and slips up to 1 mm in one step.
        // (A slip whose decay the trapezoidal rule overshoots, 1 m here, is refused with an
        // error that asks for a smaller step, which the integrators take.)
        for (m, n) in [(1.0, 1.0), (2.0, 0.5), (0.5, 2.0), (2.0, 2.0)] {
            for xi in [0.1, 1e3, 1e6, 1e10] {
                for slip in [0.0, 1e-6, 1e-3] {
                    for z0 in [1.0, 1.5, 2.0] {
                        let p = FrictionParams { m, n, ..params(xi) };
                        let z = solve_structure(&p, z0, slip, 0.01).unwrap().value;
                        assert!((1.0..=p.max_structure()).contains(&z), "m {m} n {n} ξ {xi} Δp {slip} z₀ {z0}: {z}");
                    }
                }
            }
        }
    }
}
