//! The rate form integrated as one system of ODEs by Tsitouras' explicit Runge–Kutta 5(4) pair.
//!
//! Wilson's θ method ([`super::wilson`]) integrates the total form with an implicit friction
//! update over each step; it is second-order accurate, so a tight error costs many steps. The
//! paper's equations are also a system of ODEs in `y = (u, v, f_t, 1/R*, p)`:
//!
//! * `u̇ = v`, `M v̇ = ḟ⁰ t - K u + Σ w Ñᵀ (f_t - f_t⁰)`: eq. (14) in total form, `u` measured
//!   from the initial equilibrium as in [`super::wilson`];
//! * `ḟ_t` of eq. (6), switched by eq. (9), for the relative sliding velocity
//!   `v̄_t = Ñ v - v_base(t)` of eq. (13) ([`crate::friction::law::tangential_rate`]);
//! * `d(1/R*)/dt` of eq. (4) ([`crate::friction::law::structure_rate`]) and `ṗ = Λ` of eq. (5).
//!
//! Tsitouras' pair (Ch. Tsitouras, "Runge–Kutta pairs of order 5(4) satisfying only the first
//! column simplifying assumption", Comput. Math. Appl. 62 (2011) 770–775, Table 1) advances it
//! with the fifth-order solution and estimates the error from the embedded fourth-order one;
//! its last stage is the next step's first (FSAL), six right-hand sides per step. The error of
//! each component is measured against its own size plus a physical scale (below) and the
//! largest must stay within `tolerance` per step; the next step is `0.9 h (tolerance/error)^{1/5}`,
//! limited to a factor 5 up or 5 down.
//!
//! The method is explicit, and the body and its contact springs are undamped: their modes have
//! imaginary eigenvalues `±iω`. Like every explicit fifth-order pair, Tsitouras' amplifies them
//! slightly (its stability function has `|R(iy)| = 1.00013` at `y = hω = 1`, 1.026 at 2, 1.28
//! at 3; on the negative real axis it is stable up to 3.5), so the error control keeps `hω` of
//! the stiffest mode, the contact spring `α_t` on the lumped mass it carries, near 1 to 2. That
//! mode has `ω ≈ 45 rad/s` on the paper's 10 × 1 mesh, where the steps average 0.02 s, and
//! `ω ≈ 450 rad/s` on 1000 × 100, where they are about 3 ms.
//!
//! The exact flow keeps every point's `R ≤ 1` and `1/R*` in `[1, μ_s/μ_k]`; the pair keeps
//! them only to its local error, so each accepted state is put back on that set where it has
//! left it, and its rate evaluated again ([`Dynamics::project`]).
//!
//! Stick/slip transitions are located, not stepped over: when a step carries a contact point's
//! plastic slip rate `Λ` across the event threshold, the step is shortened to end just past the
//! crossing (found by the Illinois variant of regula falsi on `Λ - threshold` with fifth-order
//! steps from the step's start), so that a frame lies on every onset and every end.

use super::adaptive::{AdaptiveError, ErrorScaling, StepControl};
use super::sdirk::Sdirk4;
use super::wilson::{Dynamics, StepError};
use crate::friction::{ContactState, law};

/// The Runge–Kutta method that integrates the rate form.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Tsitouras' explicit 5(4) pair (this module).
    Tsit5,
    /// Hairer and Wanner's L-stable SDIRK 4(3) ([`super::sdirk`]).
    Sdirk4,
}

/// Nodes `c_2 … c_7` (Tsitouras 2011, Table 1).
const C: [f64; 6] = [0.161, 0.327, 0.9, 0.980_025_540_904_509_7, 1.0, 1.0];

/// Coefficients `a_ij` of stages 2 … 7; the last row is the fifth-order solution's weights `b`.
const A: [[f64; 6]; 6] = [
    [0.161, 0.0, 0.0, 0.0, 0.0, 0.0],
    [-0.008_480_655_492_356_989, 0.335_480_655_492_357, 0.0, 0.0, 0.0, 0.0],
    [2.897_153_057_105_493_5, -6.359_448_489_975_075, 4.362_295_432_869_581_5, 0.0, 0.0, 0.0],
    [5.325_864_828_439_257, -11.748_883_564_062_828, 7.495_539_342_889_836_5, -0.092_495_066_361_755_25, 0.0, 0.0],
    [
        5.861_455_442_946_42,
        -12.920_969_317_847_11,
        8.159_367_898_576_159,
        -0.071_584_973_281_401,
        -0.028_269_050_394_068_383,
        0.0,
    ],
    [
        0.096_460_766_818_065_23,
        0.01,
        0.479_889_650_414_499_6,
        1.379_008_574_103_742,
        -3.290_069_515_436_081,
        2.324_710_524_099_774,
    ],
];

/// `b - b̂`: the difference of the fifth- and fourth-order solutions, per stage.
const ERROR: [f64; 7] = [
    -0.001_780_011_052_225_777,
    -0.000_816_434_459_656_746_9,
    0.007_880_878_010_261_995,
    -0.144_711_007_173_262_9,
    0.582_357_165_452_555_2,
    -0.458_082_105_929_186_97,
    1.0 / 66.0,
];

/// The pair's error is per step and falls as `h⁵`: the next step is `0.9 h (tolerance/error)^{1/5}`,
/// at most 5 times the last.
const FIFTH_ORDER: ErrorScaling = ErrorScaling { per_unit_step: false, root: fifth_root, max_growth: 5.0 };

fn fifth_root(x: f64) -> f64 {
    x.powf(0.2)
}

/// SDIRK's embedded estimate is that of its third-order solution: per step, falling as `h⁴`.
const FOURTH_ORDER: ErrorScaling = ErrorScaling { per_unit_step: false, root: fourth_root, max_growth: 5.0 };

fn fourth_root(x: f64) -> f64 {
    x.sqrt().sqrt()
}

/// Root-finding steps allowed when locating a crossing.
const MAX_LOCATING_STEPS: usize = 60;

/// The integrator's memory between steps: the state as one vector, its rate (the next step's
/// first stage), and every point's `Λ` there.
#[derive(Debug, Clone)]
pub struct RungeKutta {
    /// Step and time of the state `y` describes; another means [`Dynamics::state`] was changed
    /// from outside, and `y` is rebuilt.
    at: (u64, f64),
    y: Vec<f64>,
    rate: Vec<f64>,
    lambda: Vec<f64>,
    /// Physical scale of each component, added to its size in the error measure.
    scale: Vec<f64>,
    pair: Pair,
}

/// A method with its workspace.
#[derive(Debug, Clone)]
enum Pair {
    Tsit5(Tsit5),
    Sdirk4(Box<Sdirk4>),
}

impl Pair {
    fn method(&self) -> Method {
        match self {
            Pair::Tsit5(_) => Method::Tsit5,
            Pair::Sdirk4(_) => Method::Sdirk4,
        }
    }

    fn scaling(&self) -> ErrorScaling {
        match self {
            Pair::Tsit5(_) => FIFTH_ORDER,
            Pair::Sdirk4(_) => FOURTH_ORDER,
        }
    }
}

/// Tsitouras' 5(4) pair on `ẏ = f(t, y)`: its stages and one step.
#[derive(Debug, Clone)]
pub struct Tsit5 {
    stages: [Vec<f64>; 7],
    work: Vec<f64>,
}

impl Tsit5 {
    /// Workspace for systems of `len` unknowns.
    pub fn new(len: usize) -> Self {
        Self { stages: std::array::from_fn(|_| vec![0.0; len]), work: vec![0.0; len] }
    }

    /// One step of `h` from `y` at `t`, whose rate `f(t, y)` is `rate`; `f(t, y, ẏ)` fills
    /// `ẏ`. Returns the error estimate `max_j |(y₅ - y₄)_j| / (scale_j + max(|y_j|, |y₅_j|))`
    /// (infinite if anything is not finite); the fifth-order solution `y₅` and its rate are
    /// then [`Self::solution`] and [`Self::solution_rate`] (FSAL: the last stage is there).
    pub fn step(
        &mut self,
        y: &[f64],
        rate: &[f64],
        t: f64,
        h: f64,
        scale: &[f64],
        mut f: impl FnMut(f64, &[f64], &mut [f64]),
    ) -> f64 {
        let len = y.len();
        self.stages[0].copy_from_slice(rate);
        for (i, row) in A.iter().enumerate() {
            for j in 0..len {
                let mut sum = 0.0;
                for (a, k) in row.iter().zip(&self.stages).take(i + 1) {
                    sum += a * k[j];
                }
                self.work[j] = y[j] + h * sum;
            }
            // The last row is b: the last stage is evaluated at y₅ itself.
            f(t + C[i] * h, &self.work, &mut self.stages[i + 1]);
        }
        let mut error: f64 = 0.0;
        for j in 0..len {
            let e: f64 = ERROR.iter().zip(&self.stages).map(|(w, k)| w * k[j]).sum::<f64>() * h;
            let size = scale[j] + y[j].abs().max(self.work[j].abs());
            error = error.max((e / size).abs());
        }
        if error.is_finite() && self.work.iter().chain(&self.stages[6]).all(|x| x.is_finite()) {
            error
        } else {
            f64::INFINITY
        }
    }

    /// The fifth-order solution of the last [`Self::step`].
    pub fn solution(&self) -> &[f64] {
        &self.work
    }

    /// Its rate `f(t + h, y₅)`.
    pub fn solution_rate(&self) -> &[f64] {
        &self.stages[6]
    }
}

/// One trial step: the new state, its rate and `Λ` there, and the error.
struct Trial {
    y: Vec<f64>,
    rate: Vec<f64>,
    lambda: Vec<f64>,
    error: f64,
}

impl Dynamics {
    /// Takes one step of at most `limit` (s) with `method` (Tsitouras' pair, module docs, or
    /// SDIRK, [`super::sdirk`]), its size chosen by `control` (`control.tolerance` is the error
    /// allowed per step), shortened to end just past the first instant where a contact point's
    /// plastic slip rate crosses `threshold` (m/s). Returns the step taken.
    pub fn runge_kutta_step(
        &mut self,
        method: Method,
        control: &mut StepControl,
        limit: f64,
        threshold: f64,
    ) -> Result<f64, AdaptiveError> {
        let mut rk = match self.runge_kutta.take() {
            Some(rk) if rk.at == (self.state.step, self.state.time) && rk.pair.method() == method => rk,
            _ => RungeKutta::new(self, method),
        };
        let result = self.runge_kutta_attempts(&mut rk, control, limit, threshold);
        if let Pair::Sdirk4(pair) = &mut rk.pair {
            control.newton_iterations += std::mem::take(&mut pair.iterations);
            control.factorizations += std::mem::take(&mut pair.linearizations);
        }
        self.runge_kutta = Some(rk);
        result
    }

    fn runge_kutta_attempts(
        &mut self,
        rk: &mut RungeKutta,
        control: &mut StepControl,
        limit: f64,
        threshold: f64,
    ) -> Result<f64, AdaptiveError> {
        let t = self.state.time;
        let scaling = rk.pair.scaling();
        let tolerance = control.tolerance;
        let mut rejected = false;
        loop {
            let h = control.next.min(limit);
            // A failed implicit solve counts as an infinite error: the step shrinks.
            let (trial, failure) = match rk.trial(self, t, h, tolerance) {
                Ok(trial) => (Some(trial), None),
                Err(failure) => (None, Some(failure)),
            };
            let error = trial.as_ref().map_or(f64::INFINITY, |trial| trial.error);
            if let Some(trial) = trial.filter(|_| error <= tolerance) {
                control.accepted += 1;
                control.next = control.resize(h, error, scaling);
                if rejected {
                    control.next = control.next.min(h);
                }
                let (h, trial) = rk.crossing(self, t, h, &trial, threshold, tolerance).unwrap_or((h, trial));
                self.accept_runge_kutta(rk, t + h, trial);
                return Ok(h);
            }
            control.rejected += 1;
            rejected = true;
            control.next = control.resize(h, error, scaling).min(0.5 * h);
            if control.next < control.dt_min {
                return Err(match (error.is_finite(), failure) {
                    (true, _) => AdaptiveError::StepTooSmall { dt: control.next, dt_min: control.dt_min, error },
                    (false, Some(failure)) => AdaptiveError::Step(failure),
                    (false, None) => AdaptiveError::Step(StepError::NonFinite),
                });
            }
        }
    }

    /// Makes `trial`, reached at `time`, the state.
    fn accept_runge_kutta(&mut self, rk: &mut RungeKutta, time: f64, mut trial: Trial) {
        if self.project(&mut trial.y) {
            self.rate_form(time, &trial.y, &mut trial.rate, &mut trial.lambda);
        }
        let n = self.body.dofs();
        let m = self.contact.points.len();
        let s = &mut self.state;
        s.displacement.copy_from_slice(&trial.y[..n]);
        s.velocity.copy_from_slice(&trial.y[n..2 * n]);
        s.acceleration.copy_from_slice(&trial.rate[n..2 * n]);
        for (i, c) in s.contact.iter_mut().enumerate() {
            let slip = trial.y[2 * n + 2 * m + i];
            s.plastic_increment[i] = slip - c.plastic_slip;
            c.traction_t = trial.y[2 * n + i];
            c.structure = trial.y[2 * n + m + i];
            c.plastic_slip = slip;
        }
        s.plastic_rate.clone_from(&trial.lambda);
        s.time = time;
        s.step += 1;
        rk.at = (s.step, s.time);
        rk.y = trial.y;
        rk.rate = trial.rate;
        rk.lambda = trial.lambda;
    }

    /// Puts a state that a step's error has carried just outside the set the exact flow never
    /// leaves back on its edge: `1 ≤ 1/R* ≤ μ_s/μ_k`, where eq. (4)'s decay and healing vanish,
    /// and `R ≤ 1`, that is `|f_t| ≤ μ_k f_n (1/R*)`, where `Ṙ = -r ln(R) Λ` vanishes (it is
    /// negative above). The implicit update meets these exactly; the explicit pair only to its
    /// local error (`R = 1 + 2e-11` at tolerance 1e-8 under 1e-3 Pa of normal traction). Returns
    /// whether anything moved.
    fn project(&self, y: &mut [f64]) -> bool {
        let n = self.body.dofs();
        let m = self.contact.points.len();
        let params = &self.contact.params;
        let (traction, structure) = y[2 * n..2 * n + 2 * m].split_at_mut(m);
        let mut moved = false;
        for ((f_t, z), &f_n) in traction.iter_mut().zip(structure.iter_mut()).zip(&self.contact.traction_n) {
            let inside = z.clamp(1.0, params.max_structure());
            if inside != *z {
                *z = inside;
                moved = true;
            }
            let strength = params.mu_k * f_n * *z;
            if f_n > 0.0 && f_t.abs() > strength {
                *f_t = strength.copysign(*f_t);
                moved = true;
            }
        }
        moved
    }

    /// The right-hand side `ẏ = f(t, y)` (module docs); fills `lambda` with each point's `Λ`.
    pub(super) fn rate_form(&self, t: f64, y: &[f64], rate: &mut [f64], lambda: &mut [f64]) {
        let n = self.body.dofs();
        let m = self.contact.points.len();
        let (u, rest) = y.split_at(n);
        let (v, rest) = rest.split_at(n);
        let (traction, rest) = rest.split_at(m);
        let (structure, slip) = rest.split_at(m);
        let (du, rest) = rate.split_at_mut(n);
        let (dv, rest) = rest.split_at_mut(n);
        let (dtraction, rest) = rest.split_at_mut(m);
        let (dstructure, dslip) = rest.split_at_mut(m);
        du.copy_from_slice(v);
        // M v̇ = ḟ⁰ t - K u + Σ w Ñᵀ f_t - f_c⁰.
        self.body.stiffness.mul_vec(u, dv);
        for (i, a) in dv.iter_mut().enumerate() {
            *a = t * self.body.load_rate[i] - *a - self.initial_contact_force[i];
        }
        let params = &self.contact.params;
        let base = self.contact.base_velocity_at(t);
        for (i, point) in self.contact.points.iter().enumerate() {
            point.scatter(point.weight * traction[i], dv);
            let state = ContactState {
                traction_t: traction[i],
                traction_n: self.contact.traction_n[i],
                structure: structure[i],
                plastic_slip: slip[i],
            };
            let r = law::tangential_rate(params, &state, point.interpolate(v) - base);
            dtraction[i] = r.rate;
            dstructure[i] = law::structure_rate(params, structure[i], r.plastic_multiplier);
            dslip[i] = r.plastic_multiplier;
            lambda[i] = r.plastic_multiplier;
        }
        for (a, mass) in dv.iter_mut().zip(&self.body.mass) {
            *a /= mass;
        }
    }
}

impl RungeKutta {
    /// Reads the state of `dynamics` into one vector, for `method`.
    fn new(dynamics: &Dynamics, method: Method) -> Self {
        let s = &dynamics.state;
        let n = dynamics.body.dofs();
        let m = s.contact.len();
        let mut y = Vec::with_capacity(2 * n + 3 * m);
        y.extend_from_slice(&s.displacement);
        y.extend_from_slice(&s.velocity);
        y.extend(s.contact.iter().map(|c| c.traction_t));
        y.extend(s.contact.iter().map(|c| c.structure));
        y.extend(s.contact.iter().map(|c| c.plastic_slip));
        // Scales: the displacement that changes a point's traction by its static strength
        // (`δ = μ_s f_n / α_t`) for u and p; for v, the velocity whose kinetic energy in the
        // contact's spring mode (`ω² = α_t w / m`) equals that spring's energy at `δ`, `ω δ`,
        // or the drive's velocity if larger; the static strength for f_t; the range
        // `μ_s/μ_k - 1` for 1/R*.
        let params = &dynamics.contact.params;
        let strength = params.mu_s * dynamics.contact.traction_n.iter().fold(0.0_f64, |a, &b| a.max(b));
        let strength = if strength > 0.0 { strength } else { 1.0 };
        let length = strength / params.alpha_t;
        let omega = dynamics
            .contact
            .points
            .iter()
            .flat_map(|p| p.dofs.map(|d| (p.weight * params.alpha_t / dynamics.body.mass[d]).sqrt()))
            .fold(0.0_f64, f64::max);
        let mut scale = vec![length; n];
        scale.extend(std::iter::repeat_n(dynamics.settings.velocity_scale.max(omega * length), n));
        scale.extend(std::iter::repeat_n(strength, m));
        scale.extend(std::iter::repeat_n((params.max_structure() - 1.0).max(f64::MIN_POSITIVE), m));
        scale.extend(std::iter::repeat_n(length, m));
        let mut rate = vec![0.0; y.len()];
        let mut lambda = vec![0.0; m];
        dynamics.rate_form(s.time, &y, &mut rate, &mut lambda);
        let len = y.len();
        let pair = match method {
            Method::Tsit5 => Pair::Tsit5(Tsit5::new(len)),
            Method::Sdirk4 => Pair::Sdirk4(Box::new(Sdirk4::new(len, m))),
        };
        Self { at: (s.step, s.time), y, rate, lambda, scale, pair }
    }

    /// One step of `h` from the current state at `t`; `tolerance` is the error allowed per step.
    /// Fails where an implicit method's solve does.
    fn trial(&mut self, dynamics: &mut Dynamics, t: f64, h: f64, tolerance: f64) -> Result<Trial, StepError> {
        match &mut self.pair {
            Pair::Tsit5(pair) => {
                let mut lambda = vec![0.0; self.lambda.len()];
                let error = pair.step(&self.y, &self.rate, t, h, &self.scale, |t, y, rate| {
                    dynamics.rate_form(t, y, rate, &mut lambda)
                });
                let (y, rate) = (pair.solution().to_vec(), pair.solution_rate().to_vec());
                Ok(Trial { y, rate, lambda, error })
            }
            Pair::Sdirk4(pair) => {
                let error = pair.step(dynamics, &self.y, &self.rate, t, h, &self.scale, tolerance)?;
                let (y, rate) = (pair.solution().to_vec(), pair.solution_rate().to_vec());
                Ok(Trial { y, rate, lambda: pair.solution_lambda().to_vec(), error })
            }
        }
    }

    /// If the accepted `trial` of `h` from `t` carries some point's `Λ` across `level`, the
    /// shortened step that ends just past the first such crossing, and its state.
    fn crossing(
        &mut self,
        dynamics: &mut Dynamics,
        t: f64,
        h: f64,
        trial: &Trial,
        level: f64,
        tolerance: f64,
    ) -> Option<(f64, Trial)> {
        let side = |lambda: f64| lambda > level;
        // The point whose crossing comes first by linear interpolation of Λ over the step.
        let (point, _) = self
            .lambda
            .iter()
            .zip(&trial.lambda)
            .enumerate()
            .filter(|(_, (a, b))| side(**a) != side(**b))
            .map(|(i, (a, b))| (i, (level - a) / (b - a)))
            .min_by(|x, y| x.1.total_cmp(&y.1))?;
        let before = side(self.lambda[point]);
        let g = |lambda: &[f64]| lambda[point] - level;
        // Illinois: regula falsi that halves the weight of an end kept twice in a row.
        let (mut lo, mut g_lo) = (0.0, g(&self.lambda));
        let (mut hi, mut g_hi) = (h, g(&trial.lambda));
        let mut past: Option<Trial> = None;
        let mut kept = 0_i32;
        for _ in 0..MAX_LOCATING_STEPS {
            if hi - lo <= 4.0 * f64::EPSILON * (t + hi).abs() {
                break;
            }
            let mut s = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
            if !(s > lo && s < hi) {
                s = 0.5 * (lo + hi);
            }
            let Ok(attempt) = self.trial(dynamics, t, s, tolerance) else { break };
            let value = g(&attempt.lambda);
            if !value.is_finite() {
                break;
            }
            if side(attempt.lambda[point]) == before {
                lo = s;
                g_lo = value;
                if kept == -1 {
                    g_hi *= 0.5;
                }
                kept = -1;
            } else {
                hi = s;
                g_hi = value;
                past = Some(attempt);
                if kept == 1 {
                    g_lo *= 0.5;
                }
                kept = 1;
            }
        }
        past.map(|trial| (hi, trial))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `y'' = -y` as `(y, y')`, whose solution from `(1, 0)` is `(cos t, -sin t)`.
    fn oscillator(_: f64, y: &[f64], rate: &mut [f64]) {
        rate[0] = y[1];
        rate[1] = -y[0];
    }

    /// Error at `t = 1` after `steps` equal steps against the closed form.
    fn global_error(steps: usize) -> f64 {
        let mut pair = Tsit5::new(2);
        let (mut y, mut rate, h) = (vec![1.0, 0.0], vec![0.0, -1.0], 1.0 / steps as f64);
        for k in 0..steps {
            pair.step(&y, &rate, k as f64 * h, h, &[1.0, 1.0], oscillator);
            y.copy_from_slice(pair.solution());
            rate.copy_from_slice(pair.solution_rate());
        }
        (y[0] - 1.0_f64.cos()).abs().max((y[1] + 1.0_f64.sin()).abs())
    }

    #[test]
    fn the_tableau_is_consistent() {
        for (i, row) in A.iter().enumerate() {
            let sum: f64 = row.iter().sum();
            assert!((sum - C[i]).abs() < 1e-14, "row {i}: Σ a = {sum}, c = {}", C[i]);
        }
        let weights: f64 = A[5].iter().sum();
        assert!((weights - 1.0).abs() < 1e-14, "Σ b = {weights}");
        let error: f64 = ERROR.iter().sum();
        assert!(error.abs() < 1e-14, "Σ (b - b̂) = {error}");
    }

    #[test]
    fn the_solution_converges_at_fifth_order() {
        // Against the closed form: halving the step divides the error by 2⁵.
        let errors: Vec<f64> = [8, 16, 32, 64].iter().map(|&n| global_error(n)).collect();
        for pair in errors.windows(2) {
            let order = (pair[0] / pair[1]).log2();
            assert!((4.7..5.5).contains(&order), "observed order {order} from errors {errors:?}");
        }
    }

    #[test]
    fn the_error_estimate_is_that_of_the_fourth_order_solution() {
        // The estimate of one step is y₅ - y₄ ≈ the local error of y₄, C h⁵.
        let estimate = |h: f64| {
            let mut pair = Tsit5::new(2);
            pair.step(&[1.0, 0.0], &[0.0, -1.0], 0.0, h, &[1.0, 1.0], oscillator)
        };
        let ratios: Vec<f64> = [0.4, 0.2, 0.1].iter().map(|&h| (estimate(h) / estimate(h / 2.0)).log2()).collect();
        for order in &ratios {
            assert!((4.5..5.5).contains(order), "estimate scales as h^{order}; all: {ratios:?}");
        }
        let mut pair = Tsit5::new(2);
        let estimate = pair.step(&[1.0, 0.0], &[0.0, -1.0], 0.0, 0.1, &[1.0, 1.0], oscillator);
        let y5 = pair.solution();
        let true_error = (y5[0] - 0.1_f64.cos()).abs().max((y5[1] + 0.1_f64.sin()).abs());
        // y₅'s own error is much smaller than the estimate (which measures y₄'s).
        assert!(true_error < estimate, "y5 error {true_error:e}, estimate {estimate:e}");
    }
}
