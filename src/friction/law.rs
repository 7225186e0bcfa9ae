//! The rate form of the super/subloading surface friction model, eqs. (1)-(9) of the paper with
//! the sign conventions of MODEL.md, in 2D: `n = (0, 1)`, `t = (sign f_t, 0)`.
//!
//! [`traction_rate`] gives the full 2D rate of eq. (6). The scalar [`tangential_rate`] gives its
//! tangential component for a relative sliding velocity `(v̄_t, v̄_n)`: under a held normal
//! traction `v̄_n = 0` (the paper's §3.2); under an evolving one the normal row of eq. (6) is
//! `ḟ_n = -α_n v̄_n` in loading and unloading alike, and `v̄_n` enters `ḟ_t` through eq. (5)'s
//! `α_n (R/R*) μ_k n·v̄` (docs/model.md, "The normal terms").

use nalgebra::{Matrix2, Vector2};

use crate::friction::ln::ln_lanes;
use crate::friction::params::FrictionParams;
use crate::friction::state::ContactState;

/// Normal sliding-yield surface, eq. (1): `f_t/f_n - μ_k`.
pub fn normal_yield_surface(params: &FrictionParams, traction_t: f64, traction_n: f64) -> f64 {
    traction_t.abs() / traction_n - params.mu_k
}

/// Superloading-sliding surface, eq. (2): `f_t/f_n - μ_k/R*`.
pub fn superloading_surface(params: &FrictionParams, state: &ContactState) -> f64 {
    state.traction_t.abs() / state.traction_n - params.mu_k * state.structure
}

/// Subloading-sliding surface, eq. (3): `f_t/f_n - (R/R*) μ_k`, for a given `R`.
pub fn subloading_surface(params: &FrictionParams, state: &ContactState, sliding_ratio: f64) -> f64 {
    state.traction_t.abs() / state.traction_n - sliding_ratio * state.structure * params.mu_k
}

/// Decay term of eq. (4) per unit plastic slip, `(1/R* - 1)^m`.
pub fn decay(params: &FrictionParams, structure: f64) -> f64 {
    power(structure - 1.0, params.m)
}

/// `d/d(1/R*)` of [`decay`]; infinite at `1/R* = 1` when `m < 1`.
pub fn decay_slope(params: &FrictionParams, structure: f64) -> f64 {
    power_slope(structure - 1.0, params.m)
}

/// Healing term of eq. (4), `(1 - μ_k/(μ_s R*))^n`.
pub fn healing(params: &FrictionParams, structure: f64) -> f64 {
    power(1.0 - params.kinetic_static_ratio() * structure, params.n)
}

/// `max(x, 0)^e`, without `powf` for the paper's `e = 1`.
fn power(x: f64, exponent: f64) -> f64 {
    let x = x.max(0.0);
    if exponent == 1.0 { x } else { general_power(x, exponent) }
}

/// `x^e` out of line: inlined, LLVM turns the branch in [`power`] into a select that always
/// evaluates `pow` (20× the time of the paper's `e = 1` path).
#[cold]
#[inline(never)]
fn general_power(x: f64, exponent: f64) -> f64 {
    x.powf(exponent)
}

/// `d/d(1/R*)` of [`healing`]; infinite at `1/R* = μ_s/μ_k` when `n < 1`.
pub fn healing_slope(params: &FrictionParams, structure: f64) -> f64 {
    let a = params.kinetic_static_ratio();
    -a * power_slope(1.0 - a * structure, params.n)
}

/// `d/dx max(x, 0)^e` for `e > 0`, with the one-sided limit at `x = 0`.
fn power_slope(x: f64, exponent: f64) -> f64 {
    if exponent == 1.0 {
        1.0
    } else if x > 0.0 {
        exponent * general_power(x, exponent - 1.0)
    } else if exponent < 1.0 {
        f64::INFINITY
    } else {
        0.0
    }
}

/// Rate of the degree of structure, eq. (4) rewritten for `1/R*`:
///
/// `d(1/R*)/dt = -Ṙ*/R*² = -γ κ (1/R* - 1)^m Λ + γ ξ (1 - μ_k/(μ_s R*))^n`,
///
/// with `γ = 1` (consistent law) or `1/μ_k` (eq. 4 as printed).
pub fn structure_rate(params: &FrictionParams, structure: f64, plastic_multiplier: f64) -> f64 {
    structure_rate_of(params, (decay(params, structure), healing(params, structure)), plastic_multiplier)
}

/// [`structure_rate`] from its decay and healing terms at the point's `1/R*`
/// ([`decay`], [`healing`]).
#[inline(always)]
pub fn structure_rate_of(params: &FrictionParams, (decay, healing): (f64, f64), plastic_multiplier: f64) -> f64 {
    let gamma = params.rstar_scale();
    -gamma * params.kappa * decay * plastic_multiplier + gamma * params.xi * healing
}

/// `∂/∂(1/R*)` of [`structure_rate`] at fixed `Λ`:
/// `-γ κ m (1/R* - 1)^{m-1} Λ - γ ξ n (μ_k/μ_s) (1 - μ_k/(μ_s R*))^{n-1}`.
pub fn structure_rate_slope(params: &FrictionParams, structure: f64, plastic_multiplier: f64) -> f64 {
    let gamma = params.rstar_scale();
    -gamma * params.kappa * decay_slope(params, structure) * plastic_multiplier
        + gamma * params.xi * healing_slope(params, structure)
}

/// Rate of `R*` itself, eq. (4) (with `γ`): `Ṙ* = γ R*² [κ (1/R* - 1)^m Λ - ξ (1 - μ_k/(μ_s R*))^n]`.
pub fn r_star_rate(params: &FrictionParams, structure: f64, plastic_multiplier: f64) -> f64 {
    -structure_rate(params, structure, plastic_multiplier) / (structure * structure)
}

/// The denominator shared by eqs. (5), (7), (8):
///
/// `D = α_t + r (-ln R)/R* μ_k f_n - γ κ R (1/R* - 1)^m μ_k f_n`.
///
/// `D → ∞` as `R → 0`.
pub fn denominator(params: &FrictionParams, state: &ContactState) -> f64 {
    let ratio = state.sliding_ratio(params);
    let mu_f = params.mu_k * state.traction_n;
    let gamma = params.rstar_scale();
    params.alpha_t + params.r * (-ratio.ln()) * state.structure * mu_f
        - gamma * params.kappa * ratio * decay(params, state.structure) * mu_f
}

/// Numerator of eq. (5) for a relative sliding velocity `v̄ = (v̄_t, v̄_n)`:
/// `(α_n (R/R*) μ_k n - α_t t)·v̄ - γ ξ R (1 - μ_k/(μ_s R*))^n μ_k f_n`.
fn numerator(params: &FrictionParams, state: &ContactState, v_rel: Vector2<f64>) -> f64 {
    let ratio = state.sliding_ratio(params);
    let mu_f = params.mu_k * state.traction_n;
    let gamma = params.rstar_scale();
    params.alpha_n * ratio * state.structure * params.mu_k * v_rel.y
        - params.alpha_t * state.direction() * v_rel.x
        - gamma * params.xi * ratio * healing(params, state.structure) * mu_f
}

/// Plastic multiplier `Λ` of eq. (5). Loading if `Λ > 0`, unloading otherwise (eq. 9).
/// A point without traction (`R = 0`) has `Λ = 0`: `D` is infinite there.
pub fn plastic_multiplier(params: &FrictionParams, state: &ContactState, v_rel: Vector2<f64>) -> f64 {
    if state.traction_n <= 0.0 || state.traction_t == 0.0 {
        return 0.0;
    }
    numerator(params, state, v_rel) / denominator(params, state)
}

/// Elastic tensor `C^e = -α_n n⊗n - α_t (I - n⊗n)`.
pub fn elastic_tensor(params: &FrictionParams) -> Matrix2<f64> {
    Matrix2::new(-params.alpha_t, 0.0, 0.0, -params.alpha_n)
}

/// Elastoplastic tensor `C^ep` of eq. (7).
pub fn elastoplastic_tensor(params: &FrictionParams, state: &ContactState) -> Matrix2<f64> {
    let t = Vector2::new(state.direction(), 0.0);
    let n = Vector2::new(0.0, 1.0);
    let ratio = state.sliding_ratio(params);
    // (R/R*) = R (1/R*): the similarity ratio of the subloading surface, eq. (3).
    let flow = n * (params.alpha_n * ratio * state.structure * params.mu_k) - t * params.alpha_t;
    elastic_tensor(params) - (t * params.alpha_t) * flow.transpose() / denominator(params, state)
}

/// Healing coefficient `C^c` of eq. (8): `α_t γ ξ R (1 - μ_k/(μ_s R*))^n μ_k f_n / D`.
pub fn healing_coefficient(params: &FrictionParams, state: &ContactState) -> f64 {
    if state.traction_t == 0.0 {
        return 0.0;
    }
    let ratio = state.sliding_ratio(params);
    let mu_f = params.mu_k * state.traction_n;
    params.alpha_t * params.rstar_scale() * params.xi * ratio * healing(params, state.structure) * mu_f
        / denominator(params, state)
}

/// Traction rate of eq. (6), switched by eq. (9): `ḟ = C^ep v̄ + C^c t` while loading
/// (`Λ > 0`), `ḟ = C^e v̄` otherwise. Returns the rate and `Λ` (clipped at 0).
pub fn traction_rate(params: &FrictionParams, state: &ContactState, v_rel: Vector2<f64>) -> (Vector2<f64>, f64) {
    let lambda = plastic_multiplier(params, state, v_rel);
    if lambda > 0.0 {
        let t = Vector2::new(state.direction(), 0.0);
        let rate = elastoplastic_tensor(params, state) * v_rel + t * healing_coefficient(params, state);
        (rate, lambda)
    } else {
        (elastic_tensor(params) * v_rel, 0.0)
    }
}

/// Tangential traction rate `ḟ_t`, with its partial derivatives, as the dynamic solver needs them
/// at the end of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialRate {
    /// `ḟ_t` (Pa/s).
    pub rate: f64,
    /// `Λ ≥ 0` (m/s).
    pub plastic_multiplier: f64,
    /// `∂ḟ_t/∂v̄_t`: the `tt` entry of `C^ep` (loading) or `C^e` (unloading) (Pa/m).
    pub d_velocity: f64,
    /// `∂ḟ_t/∂f_t` at fixed `v̄_t` and `1/R*` (1/s).
    pub d_traction: f64,
    /// `∂ḟ_t/∂(1/R*)` at fixed `v̄_t` and `f_t` (Pa/s).
    pub d_structure: f64,
    /// `∂ḟ_t/∂v̄_n`: the `tn` entry of `C^ep`, `-α_t t α_n (R/R*) μ_k / D` (loading), 0
    /// (unloading) (Pa/m).
    pub d_normal_velocity: f64,
}

impl TangentialRate {
    /// `(∂Λ/∂f_t, ∂Λ/∂(1/R*), ∂Λ/∂v̄_t)`, from the tangential part of eq. (6) while loading,
    /// `ḟ_t = -α_t v̄_t - α_t t Λ` (all 0 while unloading, where `Λ = 0`).
    pub fn plastic_multiplier_partials(&self, params: &FrictionParams, state: &ContactState) -> [f64; 3] {
        let sigma = state.direction();
        if self.plastic_multiplier <= 0.0 || sigma == 0.0 {
            return [0.0; 3];
        }
        let scale = -1.0 / (params.alpha_t * sigma);
        [scale * self.d_traction, scale * self.d_structure, scale * (self.d_velocity + params.alpha_t)]
    }
}

/// What eqs. (5) and (9) give at a loading point, and the terms its partials reuse.
struct Loading {
    sigma: f64,
    structure: f64,
    mu_f: f64,
    gamma: f64,
    ratio: f64,
    /// `-ln R`.
    u: f64,
    healing: f64,
    decay: f64,
    denominator: f64,
    /// `Λ > 0`.
    lambda: f64,
}

/// `Λ` of eq. (5) for `v̄ = (v̄_t, v̄_n)` where it is positive (eq. 9: loading); otherwise the
/// rate of eq. (6) that holds instead: unloading (`ḟ_t = -α_t v̄_t`), or nothing transmitted
/// without normal traction. `-ln R` is evaluated only where loading is possible: a numerator
/// `N ≤ 0` over a denominator that is positive whatever `ln R` (`R ≤ 1` and
/// `α_t > γ κ R (1/R* - 1)^m μ_k f_n`) is unloading, as `N/D` would say.
#[inline(always)]
fn loading(params: &FrictionParams, state: &ContactState, v_t: f64, v_n: f64) -> Result<Loading, TangentialRate> {
    let elastic = TangentialRate {
        rate: -params.alpha_t * v_t,
        plastic_multiplier: 0.0,
        d_velocity: -params.alpha_t,
        d_traction: 0.0,
        d_structure: 0.0,
        d_normal_velocity: 0.0,
    };
    if state.traction_n <= 0.0 {
        // No normal traction: nothing is transmitted.
        return Err(TangentialRate {
            rate: 0.0,
            plastic_multiplier: 0.0,
            d_velocity: 0.0,
            d_traction: 0.0,
            d_structure: 0.0,
            d_normal_velocity: 0.0,
        });
    }
    if state.traction_t == 0.0 {
        return Err(elastic);
    }
    let sigma = state.direction();
    let z = state.structure;
    let mu_f = params.mu_k * state.traction_n;
    let gamma = params.rstar_scale();
    let ratio = state.sliding_ratio(params);
    let h = healing(params, z);
    let g = decay(params, z);
    // Eq. (5)'s numerator; its normal term is +0 where v̄_n = 0, which leaves the tangential
    // terms' sum unchanged to the bit.
    let numer = -params.alpha_t * sigma * v_t + params.alpha_n * ratio * z * params.mu_k * v_n
        - gamma * params.xi * ratio * h * mu_f;
    let softening = gamma * params.kappa * ratio * g * mu_f;
    if numer <= 0.0 && ratio <= 1.0 && params.alpha_t > softening {
        return Err(elastic);
    }
    let u = -ratio.ln();
    let denom = params.alpha_t + params.r * u * z * mu_f - softening;
    let lambda = numer / denom;
    if lambda <= 0.0 {
        return Err(elastic);
    }
    Ok(Loading { sigma, structure: z, mu_f, gamma, ratio, u, healing: h, decay: g, denominator: denom, lambda })
}

/// `ḟ_t` of eq. (6) switched by eq. (9) and `Λ` (eq. 5, clipped at 0) for `v̄ = (v̄_t, v̄_n)`:
/// [`tangential_rate`] without its partial derivatives, which an explicit integrator does not
/// use (the rate form's right-hand side evaluates it at every contact point of every stage).
#[inline(always)]
pub fn tangential_rate_and_multiplier(params: &FrictionParams, state: &ContactState, v_t: f64, v_n: f64) -> (f64, f64) {
    match loading(params, state, v_t, v_n) {
        Ok(l) => (-params.alpha_t * v_t - params.alpha_t * l.sigma * l.lambda, l.lambda),
        Err(other) => (other.rate, other.plastic_multiplier),
    }
}

/// Whether a point loads by eq. (9) (`Λ > 0` in eq. 5) at `v̄ = (v̄_t, 0)`: the branch of
/// eq. (6) it follows from this state ([`tangential_rate_on_branch`]).
pub fn loads(params: &FrictionParams, state: &ContactState, v_t: f64) -> bool {
    loading(params, state, v_t, 0.0).is_ok()
}

/// `ḟ_t` of eq. (6) and `Λ` of eq. (5) on one branch of eq. (6) for `v̄ = (v̄_t, 0)`, continued
/// past eq. (9)'s switch: on the loading branch `Λ = N/D` unclipped (negative where eq. 9
/// would unload), on the unloading branch `Λ = 0`. Each branch is smooth in the state, so an
/// integrator that holds a point on one branch over a step and ends the step where the
/// branch's switching function changes sign meets no kink inside a step. Returns
/// `(ḟ_t, Λ, N)`, `N` the numerator of eq. (5), whose sign is eq. (9)'s switch (the
/// denominator `D` is positive: `R ≤ 1` and `α_t > γ κ R (1/R* - 1)^m μ_k f_n` for the
/// paper's constants); `N` is NaN where eq. (9) does not apply (no normal traction, or
/// `f_t = 0`, where the point is elastic).
#[inline(always)]
pub fn tangential_rate_on_branch(
    params: &FrictionParams,
    state: &ContactState,
    v_t: f64,
    loading: bool,
) -> (f64, f64, f64) {
    let rates = rates_on_branch(params, state, v_t, loading);
    (rates.traction, rates.plastic_multiplier, rates.numerator)
}

/// A point's rates on one branch of eq. (6) ([`rates_on_branch`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BranchRates {
    /// `ḟ_t` (Pa/s).
    pub traction: f64,
    /// `Λ` (m/s): `N/D` unclipped on the loading branch, 0 on the unloading one.
    pub plastic_multiplier: f64,
    /// `N`, eq. (9)'s switching function (Pa/s); NaN where eq. (9) does not apply.
    pub numerator: f64,
    /// `d(1/R*)/dt` of eq. (4) for that `Λ` (1/s).
    pub structure: f64,
}

/// [`tangential_rate_on_branch`] and [`structure_rate`] together, the decay and healing terms
/// of eq. (4) evaluated once for both: what the rate form's right-hand side needs of each
/// point held on its branch ([`rates_on_branches`] for one point).
#[inline(always)]
pub fn rates_on_branch(params: &FrictionParams, state: &ContactState, v_t: f64, loading: bool) -> BranchRates {
    let points = BranchPoints {
        traction_t: [state.traction_t],
        traction_n: [state.traction_n],
        structure: [state.structure],
        v_t: [v_t],
        loading: [loading],
    };
    let rates = rates_on_branches(params, &points);
    BranchRates {
        traction: rates.traction[0],
        plastic_multiplier: rates.plastic_multiplier[0],
        numerator: rates.numerator[0],
        structure: rates.structure[0],
    }
}

/// `L` points, lane by lane: each one's friction state, relative sliding velocity `v̄_t` (with
/// `v̄_n = 0`) and branch of eq. (6) (`true`: loading). The input of [`rates_on_branches`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BranchPoints<const L: usize> {
    /// `f_t` (Pa).
    pub traction_t: [f64; L],
    /// `f_n` (Pa); a lane with `f_n ≤ 0` transmits nothing.
    pub traction_n: [f64; L],
    /// `1/R*`.
    pub structure: [f64; L],
    /// `v̄_t` (m/s).
    pub v_t: [f64; L],
    /// The branch each point is held on.
    pub loading: [bool; L],
}

impl<const L: usize> BranchPoints<L> {
    /// `L` points that transmit nothing (`f_n = 0`, `1/R* = 1`, at rest): where a group of
    /// points is padded to `L`.
    pub fn at_rest() -> Self {
        Self { traction_t: [0.0; L], traction_n: [0.0; L], structure: [1.0; L], v_t: [0.0; L], loading: [false; L] }
    }
}

/// [`BranchRates`] of `L` points, lane by lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BranchRateLanes<const L: usize> {
    /// `ḟ_t` (Pa/s).
    pub traction: [f64; L],
    /// `Λ` (m/s).
    pub plastic_multiplier: [f64; L],
    /// `N`, eq. (9)'s switching function (Pa/s); NaN where eq. (9) does not apply.
    pub numerator: [f64; L],
    /// `d(1/R*)/dt` of eq. (4) (1/s).
    pub structure: [f64; L],
}

/// Each point's rates on its branch of eq. (6), continued past eq. (9)'s switch
/// ([`tangential_rate_on_branch`]), and `d(1/R*)/dt` of eq. (4) for its `Λ`, for `L` points at
/// once. Every lane computes the same operations in the same order, its branches chosen by
/// selects, so that the lanes compile to vector instructions: `ḟ_t = -α_t v̄_t` (unloading, or
/// `f_t = 0`) or `-α_t v̄_t - α_t t Λ` (loading) or 0 (`f_n ≤ 0`); `Λ = N/D` of eq. (5) on the
/// loading branch, 0 elsewhere; `N` NaN where eq. (9) does not apply. `ln R` is taken only in
/// the lanes that load. Each lane's result is the same to the bit whatever `L`.
#[inline(always)]
pub fn rates_on_branches<const L: usize>(params: &FrictionParams, at: &BranchPoints<L>) -> BranchRateLanes<L> {
    let (alpha_t, gamma) = (params.alpha_t, params.rstar_scale());
    // Eq. (4)'s terms first, lane by lane: `max(x, 0)^e` branches on its exponent.
    let decays: [f64; L] = std::array::from_fn(|l| decay(params, at.structure[l]));
    let healings: [f64; L] = std::array::from_fn(|l| healing(params, at.structure[l]));
    let [mut sigma, mut mu_f, mut ratio, mut numer] = [[0.0; L]; 4];
    let (mut at_rest, mut applies, mut loads) = ([false; L], [false; L], [false; L]);
    for l in 0..L {
        let (f_t, f_n, z) = (at.traction_t[l], at.traction_n[l], at.structure[l]);
        // `t = sign f_t`; where `f_t = 0` eq. (9) does not apply and `t` is not used.
        sigma[l] = 1.0f64.copysign(f_t);
        mu_f[l] = params.mu_k * f_n;
        ratio[l] =
            ContactState { traction_t: f_t, traction_n: f_n, structure: z, plastic_slip: 0.0 }.sliding_ratio(params);
        numer[l] = -alpha_t * sigma[l] * at.v_t[l] - gamma * params.xi * ratio[l] * healings[l] * mu_f[l];
        // Eq. (9) applies where the normal traction is positive and `f_t ≠ 0`.
        at_rest[l] = f_n <= 0.0;
        applies[l] = !at_rest[l] & (f_t != 0.0);
        loads[l] = applies[l] & at.loading[l];
    }
    // `ln 1 = 0` where a lane does not load.
    let log_ratio: [f64; L] = ln_lanes(std::array::from_fn(|l| if loads[l] { ratio[l] } else { 1.0 }));
    let mut out =
        BranchRateLanes { traction: [0.0; L], plastic_multiplier: [0.0; L], numerator: [0.0; L], structure: [0.0; L] };
    for l in 0..L {
        let softening = gamma * params.kappa * ratio[l] * decays[l] * mu_f[l];
        let denom = alpha_t - params.r * log_ratio[l] * at.structure[l] * mu_f[l] - softening;
        let quotient = numer[l] / denom;
        let lambda = if loads[l] { quotient } else { 0.0 };
        let elastic = -alpha_t * at.v_t[l];
        let loaded = elastic - alpha_t * sigma[l] * lambda;
        let held = if loads[l] { loaded } else { elastic };
        out.traction[l] = if at_rest[l] { 0.0 } else { held };
        out.plastic_multiplier[l] = lambda;
        out.numerator[l] = if applies[l] { numer[l] } else { f64::NAN };
        out.structure[l] = structure_rate_of(params, (decays[l], healings[l]), lambda);
    }
    out
}

/// [`traction_rate`] for `v̄ = (v̄_t, v̄_n)`, tangential component, with partial derivatives.
pub fn tangential_rate(params: &FrictionParams, state: &ContactState, v_t: f64, v_n: f64) -> TangentialRate {
    let l = match loading(params, state, v_t, v_n) {
        Ok(l) => l,
        Err(other) => return other,
    };
    let Loading { sigma, structure: z, mu_f, gamma, ratio, u, healing: h, decay: g, denominator: denom, lambda } = l;
    // Partials of N and D with respect to R and to 1/R* at fixed R.
    let dn_dratio = params.alpha_n * z * params.mu_k * v_n - gamma * params.xi * h * mu_f;
    let dn_dz =
        params.alpha_n * ratio * params.mu_k * v_n - gamma * params.xi * ratio * healing_slope(params, z) * mu_f;
    let dg_dz = decay_slope(params, z);
    let dd_dratio = -params.r * z * mu_f / ratio - gamma * params.kappa * g * mu_f;
    let dd_dz = params.r * u * mu_f - gamma * params.kappa * ratio * dg_dz * mu_f;
    let dlambda_dratio = (dn_dratio - lambda * dd_dratio) / denom;
    let dlambda_dz_fixed_ratio = (dn_dz - lambda * dd_dz) / denom;
    // R = |f_t| / (μ_k f_n z).
    let dratio_dtraction = sigma / (mu_f * z);
    let dratio_dz = -ratio / z;
    TangentialRate {
        rate: -params.alpha_t * v_t - params.alpha_t * sigma * lambda,
        plastic_multiplier: lambda,
        d_velocity: -params.alpha_t * (1.0 - params.alpha_t / denom),
        d_traction: -params.alpha_t * sigma * dlambda_dratio * dratio_dtraction,
        d_structure: -params.alpha_t * sigma * (dlambda_dratio * dratio_dz + dlambda_dz_fixed_ratio),
        d_normal_velocity: -params.alpha_t * sigma * params.alpha_n * ratio * z * params.mu_k / denom,
    }
}
