//! The rate form integrated by an L-stable singly diagonally implicit Runge–Kutta method of
//! order 4 with an embedded third-order solution.
//!
//! Tsitouras' pair ([`crate::dynamics::rate_form`]) integrates the paper's rate equations explicitly, so
//! its steps cannot outgrow the undamped contact mode (`hω ≈ 1`) however slowly the block is
//! loaded. This module integrates the same system `y = (u, v, f_t, 1/R*, p)`, with the same
//! right-hand side, by the SDIRK method of Hairer and Wanner (*Solving Ordinary Differential
//! Equations II*, 2nd ed., §IV.6, Table 6.5, `γ = 1/4`): five implicit stages
//!
//! `Y_i = y_n + h Σ_{j<i} a_ij K_j + h γ K_i`, `K_i = f(t_n + c_i h, Y_i)`,
//!
//! stiffly accurate (`y_{n+1} = Y_5`) and L-stable, so a mode far faster than the step is damped
//! as Wilson's θ method damps it rather than amplified, and steps through stick grow to what the
//! slow loading allows. The embedded third-order solution estimates the error; like Hairer's
//! codes, the estimate is filtered through `(I - hγJ)⁻¹`, so that a stiff mode's difference
//! between the two solutions, which both damp it, does not hold the step down.
//!
//! Each stage is solved by Newton's method with the Jacobian `J = ∂f/∂y` of the step's start
//! (renewed at the current iterate when the iteration converges slowly). `I - hγJ` is never
//! formed: `u = hγ v + …` and each contact point's `(f_t, 1/R*, p)` are eliminated (a 2 × 2
//! block per point), leaving the body's velocities with the symmetric operator
//! `M/(hγ)² + K + K_c` of Wilson's method ([`System::factor_operator`]), factored once per
//! linearization. `K_c` holds each point's `-w ∂ḟ_t/∂v̄_t` after its own state has been
//! eliminated, the same `-w ∂f_t/∂Δū` the implicit friction update gives Wilson's step.
//!
//! Threshold crossings of the slip rate are located as for Tsitouras' pair
//! ([`crate::dynamics::rate_form`]).

use crate::dynamics::control::ErrorScaling;
use crate::dynamics::error::StepError;
use crate::dynamics::system::System;
use crate::friction::{ContactState, FrictionParams, law};

/// SDIRK's embedded estimate is that of its third-order solution: per step, falling as `h⁴`.
pub(crate) const FOURTH_ORDER: ErrorScaling = ErrorScaling { per_unit_step: false, root: fourth_root, max_growth: 5.0 };

fn fourth_root(x: f64) -> f64 {
    x.sqrt().sqrt()
}

/// The diagonal `γ` of the tableau.
pub const GAMMA: f64 = 0.25;

/// Nodes `c_i`.
const C: [f64; 5] = [0.25, 0.75, 11.0 / 20.0, 0.5, 1.0];

/// `a_ij` below the diagonal; the last row is also the weights `b` (stiffly accurate).
const A: [[f64; 4]; 5] = [
    [0.0, 0.0, 0.0, 0.0],
    [0.5, 0.0, 0.0, 0.0],
    [17.0 / 50.0, -1.0 / 25.0, 0.0, 0.0],
    [371.0 / 1360.0, -137.0 / 2720.0, 15.0 / 544.0, 0.0],
    [25.0 / 24.0, -49.0 / 48.0, 125.0 / 16.0, -85.0 / 12.0],
];

/// Weights `b̂` of the embedded third-order solution.
const B_HAT: [f64; 5] = [59.0 / 48.0, -17.0 / 96.0, 225.0 / 32.0, -85.0 / 12.0, 0.0];

/// The weights `b`: the last row of `A` and `γ`.
const fn weights() -> [f64; 5] {
    [A[4][0], A[4][1], A[4][2], A[4][3], GAMMA]
}

/// Newton's iterations allowed per stage and linearization.
const MAX_NEWTON: usize = 10;

/// A stage has converged when Newton's remaining error, estimated from the rate of
/// convergence, is below this share of the step's tolerance.
const NEWTON_SHARE: f64 = 0.03;

/// A rate of convergence above this asks for a new linearization.
const SLOW: f64 = 0.5;

/// One contact point's part of `I - hγJ`: its rates of `(f_t, 1/R*)` depend on themselves
/// (`L`, 2 × 2) and on the relative sliding velocity `v̄_t` (`b`); `Λ = ṗ` on all three.
#[derive(Debug, Clone, Copy, Default, serde::Serialize, serde::Deserialize)]
struct PointLinearization {
    /// `(I - hγ L)⁻¹`.
    inverse: [[f64; 2]; 2],
    /// `(I - hγ L)⁻¹ hγ b`: how `(δf_t, δ(1/R*))` follow `δv̄_t`.
    follow: [f64; 2],
    /// `(∂Λ/∂f_t, ∂Λ/∂(1/R*), ∂Λ/∂v̄_t)`.
    lambda: [f64; 3],
    /// `((I - hγ L)⁻¹ b)_f`: `∂ḟ_t/∂v̄_t` once the point's own state is eliminated.
    traction_follows_velocity: f64,
}

impl PointLinearization {
    /// The block of a point in `state`, sliding at `v_t` relative to the base, for `g = hγ`,
    /// from the analytic partials of eqs. (4)–(6).
    fn at(params: &FrictionParams, state: &ContactState, (v_t, v_n): (f64, f64), g: f64) -> Self {
        let r = law::tangential_rate(params, state, v_t, v_n);
        let lambda = r.plastic_multiplier_partials(params, state);
        // d(1/R*)/dt = -γ κ (1/R* - 1)^m Λ + γ ξ (…)^n (eq. 4).
        let decay = -params.rstar_scale() * params.kappa * law::decay(params, state.structure);
        let slope = law::structure_rate_slope(params, state.structure, r.plastic_multiplier);
        let l = [[r.d_traction, r.d_structure], [decay * lambda[0], decay * lambda[1] + slope]];
        let b = [r.d_velocity, decay * lambda[2]];
        let a = [[1.0 - g * l[0][0], -g * l[0][1]], [-g * l[1][0], 1.0 - g * l[1][1]]];
        let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        let inverse = [[a[1][1] / det, -a[0][1] / det], [-a[1][0] / det, a[0][0] / det]];
        let times_b = |row: [f64; 2]| row[0] * b[0] + row[1] * b[1];
        let follow = [g * times_b(inverse[0]), g * times_b(inverse[1])];
        Self { inverse, follow, lambda, traction_follows_velocity: times_b(inverse[0]) }
    }

    fn is_finite(&self) -> bool {
        self.inverse.iter().flatten().chain(&self.follow).chain(&self.lambda).all(|x| x.is_finite())
    }
}

/// The method's stages and workspace on `ẏ = f(t, y)` of one [`System`].
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Sdirk4 {
    stages: [Vec<f64>; 5],
    /// The stage iterate; after a step, the solution `y_{n+1}`.
    work: Vec<f64>,
    /// The known part of the stage, `y_n + h Σ_{j<i} a_ij K_j`.
    known: Vec<f64>,
    correction: Vec<f64>,
    rate: Vec<f64>,
    lambda: Vec<f64>,
    /// `hγ` of the linearization and its points.
    g: f64,
    points: Vec<PointLinearization>,
    /// Each point's change of its normal spring in the linearization
    /// ([`crate::dynamics::ContactBoundary::normal_stiffness`]); empty where no normal evolves.
    #[serde(default)]
    normal_stiffness: Vec<f64>,
    /// Linearizations (factorizations of the body's operator) so far.
    pub(super) linearizations: u64,
    /// Newton iterations (right-hand sides and solves) so far.
    pub(super) iterations: u64,
}

impl Sdirk4 {
    /// Workspace for a system of `len` unknowns with `points` contact points.
    pub fn new(len: usize, points: usize) -> Self {
        Self {
            stages: std::array::from_fn(|_| vec![0.0; len]),
            work: vec![0.0; len],
            known: vec![0.0; len],
            correction: vec![0.0; len],
            rate: vec![0.0; len],
            lambda: vec![0.0; points],
            g: 0.0,
            points: vec![PointLinearization::default(); points],
            normal_stiffness: Vec::new(),
            linearizations: 0,
            iterations: 0,
        }
    }

    /// Whether the workspace is for `len` unknowns and `points` contact points.
    pub(super) fn fits(&self, len: usize, points: usize) -> bool {
        let vectors = [&self.work, &self.known, &self.correction, &self.rate];
        vectors.iter().chain(self.stages.iter().collect::<Vec<_>>().iter()).all(|v| v.len() == len)
            && self.lambda.len() == points
            && self.points.len() == points
    }

    /// One step of `h` from `y` at `t`, whose rate is `rate`. Returns the filtered error
    /// estimate `max_j |((I - hγJ)⁻¹ (y - ŷ))_j| / (scale_j + max(|y_j|, |y_{n+1,j}|))`; the
    /// solution, its rate and each point's `Λ` are then [`Self::solution`],
    /// [`Self::solution_rate`] and [`Self::solution_lambda`]. Newton's iterations stop at
    /// [`NEWTON_SHARE`] of `tolerance` in the same measure.
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &mut self,
        dynamics: &mut System,
        y: &[f64],
        rate: &[f64],
        t: f64,
        h: f64,
        scale: &[f64],
        tolerance: f64,
    ) -> Result<f64, StepError> {
        let g = GAMMA * h;
        self.linearize(dynamics, t, y, g)?;
        for i in 0..5 {
            for j in 0..y.len() {
                let sum: f64 = A[i].iter().zip(&self.stages).take(i).map(|(a, k)| a * k[j]).sum();
                self.known[j] = y[j] + h * sum;
            }
            // Predictor: the last stage's rate (the step's first rate for the first stage).
            let guess = if i == 0 { rate } else { &self.stages[i - 1] };
            for ((w, known), k) in self.work.iter_mut().zip(&self.known).zip(guess) {
                *w = known + g * k;
            }
            self.solve_stage(dynamics, t + C[i] * h, scale, tolerance)?;
            for j in 0..y.len() {
                self.stages[i][j] = (self.work[j] - self.known[j]) / g;
            }
        }
        // y - ŷ = h Σ (b - b̂) K, filtered.
        let b = weights();
        for j in 0..y.len() {
            self.correction[j] = h * (0..5).map(|k| (b[k] - B_HAT[k]) * self.stages[k][j]).sum::<f64>();
        }
        let mut error = std::mem::take(&mut self.correction);
        self.solve(dynamics, &mut error);
        let estimate = (0..y.len())
            .map(|j| error[j].abs() / (scale[j] + y[j].abs().max(self.work[j].abs())))
            .fold(0.0_f64, f64::max);
        self.correction = error;
        dynamics.rate_form(t + h, &self.work, &mut self.rate, &mut self.lambda);
        if estimate.is_finite() && self.work.iter().chain(&self.rate).all(|x| x.is_finite()) {
            Ok(estimate)
        } else {
            Err(StepError::NonFinite)
        }
    }

    /// `y_{n+1}` of the last [`Self::step`].
    pub fn solution(&self) -> &[f64] {
        &self.work
    }

    /// `f(t + h, y_{n+1})`.
    pub fn solution_rate(&self) -> &[f64] {
        &self.rate
    }

    /// Each point's `Λ` at `y_{n+1}`.
    pub fn solution_lambda(&self) -> &[f64] {
        &self.lambda
    }

    /// Newton's method on `Y = known + hγ f(t, Y)` from `Y = work`.
    fn solve_stage(&mut self, dynamics: &mut System, t: f64, scale: &[f64], tolerance: f64) -> Result<(), StepError> {
        let goal = NEWTON_SHARE * tolerance;
        let mut renewed = false;
        let mut previous = f64::INFINITY;
        let mut iterations = 0;
        loop {
            dynamics.rate_form(t, &self.work, &mut self.rate, &mut self.lambda);
            for j in 0..self.work.len() {
                self.correction[j] = self.known[j] + self.g * self.rate[j] - self.work[j];
            }
            let mut correction = std::mem::take(&mut self.correction);
            self.solve(dynamics, &mut correction);
            let mut size: f64 = 0.0;
            for ((w, d), s) in self.work.iter_mut().zip(&correction).zip(scale) {
                *w += d;
                size = size.max(d.abs() / (s + w.abs()));
            }
            self.correction = correction;
            self.iterations += 1;
            iterations += 1;
            if !size.is_finite() {
                return Err(StepError::NonFinite);
            }
            let rho = size / previous;
            if size <= goal || (rho < 1.0 && rho / (1.0 - rho) * size <= goal) {
                return Ok(());
            }
            if rho > SLOW || iterations >= MAX_NEWTON {
                if renewed {
                    return Err(StepError::NotConverged { iterations, correction: size });
                }
                let work = self.work.clone();
                self.linearize(dynamics, t, &work, self.g)?;
                renewed = true;
                previous = f64::INFINITY;
                continue;
            }
            previous = size;
        }
    }

    /// Linearizes `f` at `(t, y)` for the stage operator `I - gJ`: each point's block, and the
    /// body's operator factored.
    fn linearize(&mut self, dynamics: &mut System, t: f64, y: &[f64], g: f64) -> Result<(), StepError> {
        let n = dynamics.body.dofs();
        let m = dynamics.contact.points.len();
        let v = &y[n..2 * n];
        let base = dynamics.contact.base_velocities(t);
        let mut stiffness = Vec::with_capacity(m);
        let contact = &dynamics.contact;
        let u = &y[..n];
        // Evolving normal tractions at y, and an open point's spring taken away; the coupling of
        // ḟ_t to v̄_n stays out of Newton's matrix (it would be unsymmetric), not of the residual.
        let normals: Vec<f64> = if contact.any_evolving() {
            (0..m)
                .map(|i| if contact.evolves(i) { contact.normal_traction_at(i, u) } else { contact.traction_n[i] })
                .collect()
        } else {
            Vec::new()
        };
        for (i, point) in dynamics.contact.points.iter().enumerate() {
            let params = dynamics.contact.params(i);
            let mut state = ContactState {
                traction_t: y[2 * n + i],
                traction_n: normals.get(i).copied().unwrap_or(dynamics.contact.traction_n[i]),
                structure: y[2 * n + m + i],
                plastic_slip: y[2 * n + 2 * m + i],
            };
            let v_t = point.interpolate(v) - dynamics.contact.base_along(i, &base);
            let v_n = if normals.is_empty() { 0.0 } else { point.normal.apply(v) };
            let mut linearization = PointLinearization::at(params, &state, (v_t, v_n), g);
            if !linearization.is_finite() {
                // With m < 1 or n < 1, eq. (4)'s powers have infinite slopes at the ends of
                // 1/R*'s range. Newton's matrix is then taken a hair inside the range; the
                // residual it corrects stays the exact one.
                let hair = 1e-9 * (params.max_structure() - 1.0);
                state.structure = state.structure.clamp(1.0 + hair, params.max_structure() - hair);
                linearization = PointLinearization::at(params, &state, (v_t, v_n), g);
            }
            self.points[i] = linearization;
            stiffness.push(-point.weight * linearization.traction_follows_velocity);
        }
        if stiffness.iter().any(|k| !k.is_finite()) {
            return Err(StepError::NonFinite);
        }
        self.normal_stiffness = normals.iter().enumerate().map(|(i, &f_n)| contact.normal_stiffness(i, f_n)).collect();
        stiffness.extend_from_slice(&self.normal_stiffness);
        self.g = g;
        self.linearizations += 1;
        dynamics.factor_operator(1.0 / (g * g), &stiffness)
    }

    /// Solves `(I - gJ) δ = r` in place for the last linearization (module docs).
    fn solve(&self, dynamics: &System, r: &mut [f64]) {
        let n = dynamics.body.dofs();
        let m = dynamics.contact.points.len();
        let g = self.g;
        let (ru, rest) = r.split_at_mut(n);
        let (rv, rest) = rest.split_at_mut(n);
        let (rf, rest) = rest.split_at_mut(m);
        let (rz, rp) = rest.split_at_mut(m);
        // (M/g² + K + K_c) δv = (M r_v - g K r_u + g Σ w Ñᵀ q_f)/g², q = (I - gL)⁻¹ (r_f, r_z).
        let mut dv = vec![0.0; n];
        dynamics.body.stiffness.mul_vec(ru, &mut dv);
        // K + K_c along the evolving points' normals (their open springs taken away).
        for ((point, &k), i) in dynamics.contact.points.iter().zip(&self.normal_stiffness).zip(0..) {
            if k != 0.0 && dynamics.contact.evolves(i) {
                point.normal.scatter(k * point.normal.apply(ru), &mut dv);
            }
        }
        for ((d, mass), r) in dv.iter_mut().zip(&dynamics.body.mass).zip(rv.iter()) {
            *d = mass * r - g * *d;
        }
        let mut q = Vec::with_capacity(m);
        for (i, (point, p)) in dynamics.contact.points.iter().zip(&self.points).enumerate() {
            let qi =
                [p.inverse[0][0] * rf[i] + p.inverse[0][1] * rz[i], p.inverse[1][0] * rf[i] + p.inverse[1][1] * rz[i]];
            point.scatter(g * point.weight * qi[0], &mut dv);
            q.push(qi);
        }
        dv.iter_mut().for_each(|d| *d /= g * g);
        dynamics.solve_operator(&mut dv);
        for (i, (point, p)) in dynamics.contact.points.iter().zip(&self.points).enumerate() {
            let dvbar = point.interpolate(&dv);
            let df = q[i][0] + p.follow[0] * dvbar;
            let dz = q[i][1] + p.follow[1] * dvbar;
            rp[i] += g * (p.lambda[0] * df + p.lambda[1] * dz + p.lambda[2] * dvbar);
            rf[i] = df;
            rz[i] = dz;
        }
        for ((u, v), d) in ru.iter_mut().zip(rv.iter_mut()).zip(&dv) {
            *u += g * d;
            *v = *d;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::Settings;
    use crate::dynamics::{Motion, NormalBehaviour};
    use crate::fem::{Assembled, Material, PlaneStrain};
    use crate::friction::FrictionParams;
    use crate::scene::block::block;
    use nalgebra::{Complex, DMatrix, DVector};

    #[test]
    fn the_eliminated_solve_inverts_the_stage_operator_of_finite_differences() {
        // A 4 × 2 block with the paper's contact, in a state where every kind of point occurs:
        // loading near its strength (f_t at R = 0.9 with the base pulling ahead), unloading,
        // and one without normal traction. The solve of (I - gJ) δ = r by elimination against
        // a dense J formed by central differences of the right-hand side itself.
        let material =
            Material { elasticity: PlaneStrain { youngs_modulus: 1.0e3, poisson_ratio: 0.0 }, density: 1000.0 };
        let params = FrictionParams::paper();
        let traction_n = |x: f64| if x < 0.5 { 0.0 } else { 300.0 + 200.0 * x };
        let base = Motion::constant([1e-3, 0.0], 0.0);
        let Assembled { body, contact, .. } =
            block(4.0, 1.0, 4, 2, material, params.clone(), (&traction_n, NormalBehaviour::Held), base);
        let mut dynamics = System::new(body, contact, Settings::default()).unwrap();
        let n = dynamics.body.dofs();
        let m = dynamics.contact.points.len();
        let mut y = vec![0.0; 2 * n + 3 * m];
        for (j, value) in y.iter_mut().enumerate().take(2 * n) {
            // Displacements of 1e-4 m and velocities of 1e-4 m/s, varied over the unknowns.
            *value = 1e-4 * ((j as f64 * 0.7).sin());
        }
        for (i, f_n) in dynamics.contact.traction_n.clone().into_iter().enumerate() {
            let structure = 1.5 + 0.05 * i as f64;
            // Every other point is loaded towards its strength, the others back from it.
            let share = if i % 2 == 0 { 0.9 } else { 0.3 };
            y[2 * n + i] = share * params.mu_k * f_n * structure;
            y[2 * n + m + i] = structure;
            y[2 * n + 2 * m + i] = 1e-3;
        }
        let t = 20.0;
        let mut rate = vec![0.0; y.len()];
        let mut lambda = vec![0.0; m];
        dynamics.rate_form(t, &y, &mut rate, &mut lambda);
        assert!(lambda.iter().any(|&l| l > 0.0), "some point is loading: {lambda:?}");
        assert!(lambda.contains(&0.0), "some point is not: {lambda:?}");

        let g = 0.05;
        let mut method = Sdirk4::new(y.len(), m);
        method.linearize(&mut dynamics, t, &y, g).unwrap();
        let len = y.len();
        let mut jacobian = DMatrix::<f64>::zeros(len, len);
        let (mut plus, mut minus) = (vec![0.0; len], vec![0.0; len]);
        for k in 0..len {
            let step = 1e-7 * y[k].abs().max(1e-6);
            let mut shifted = y.clone();
            shifted[k] += step;
            dynamics.rate_form(t, &shifted, &mut plus, &mut lambda);
            shifted[k] -= 2.0 * step;
            dynamics.rate_form(t, &shifted, &mut minus, &mut lambda);
            for j in 0..len {
                jacobian[(j, k)] = (plus[j] - minus[j]) / (2.0 * step);
            }
        }
        let operator = DMatrix::<f64>::identity(len, len) - jacobian * g;
        let r: Vec<f64> = (0..len).map(|j| (j as f64 * 1.3).cos() * y[j].abs().max(1e-6)).collect();
        let mut delta = r.clone();
        method.solve(&dynamics, &mut delta);
        let back = &operator * DVector::from_vec(delta.clone());
        let dense = operator.lu().solve(&DVector::from_vec(r.clone())).unwrap();
        let worst = (0..len).map(|j| (delta[j] - dense[j]).abs() / dense[j].abs().max(1e-9)).fold(0.0, f64::max);
        // Normwise: the rows of I - gJ mix unknowns of very different sizes.
        let size = r.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let residual = (0..len).map(|j| (back[j] - r[j]).abs()).fold(0.0, f64::max) / size;
        println!("eliminated against dense: {worst:e}; residual {residual:e}");
        assert!(worst < 1e-6, "eliminated and dense solutions differ by {worst:e} (relative)");
        assert!(residual < 1e-6, "(I - gJ) δ - r = {residual:e} (relative)");
    }

    /// The order conditions up to order 4 (Hairer, Nørsett, Wanner I, §II.2), with `A`'s
    /// diagonal `γ`.
    fn conditions(b: &[f64; 5]) -> [f64; 8] {
        let a = |i: usize, j: usize| {
            if i == j {
                GAMMA
            } else if j < i {
                A[i][j]
            } else {
                0.0
            }
        };
        let ac: Vec<f64> = (0..5).map(|i| (0..5).map(|j| a(i, j) * C[j]).sum()).collect();
        let ac2: Vec<f64> = (0..5).map(|i| (0..5).map(|j| a(i, j) * C[j] * C[j]).sum()).collect();
        let aac: Vec<f64> = (0..5).map(|i| (0..5).map(|j| a(i, j) * ac[j]).sum()).collect();
        let dot = |x: &dyn Fn(usize) -> f64| (0..5).map(|i| b[i] * x(i)).sum::<f64>();
        [
            dot(&|_| 1.0) - 1.0,
            dot(&|i| C[i]) - 0.5,
            dot(&|i| C[i] * C[i]) - 1.0 / 3.0,
            dot(&|i| ac[i]) - 1.0 / 6.0,
            dot(&|i| C[i].powi(3)) - 0.25,
            dot(&|i| C[i] * ac[i]) - 0.125,
            dot(&|i| ac2[i]) - 1.0 / 12.0,
            dot(&|i| aac[i]) - 1.0 / 24.0,
        ]
    }

    #[test]
    fn the_tableau_has_order_four_and_its_embedded_solution_order_three() {
        for (i, row) in A.iter().enumerate() {
            let sum: f64 = row.iter().sum::<f64>() + GAMMA;
            assert!((sum - C[i]).abs() < 1e-14, "row {i}: Σ a = {sum}, c = {}", C[i]);
        }
        let fourth = conditions(&weights());
        assert!(fourth.iter().all(|e| e.abs() < 1e-13), "b: {fourth:?}");
        let embedded = conditions(&B_HAT);
        assert!(embedded[..4].iter().all(|e| e.abs() < 1e-13), "b̂ up to order 3: {embedded:?}");
        // … and not of order 4, or it would estimate nothing.
        assert!(embedded[4..].iter().any(|e| e.abs() > 1e-3), "b̂ at order 4: {embedded:?}");
    }

    /// `R(z) = 1 + z bᵀ (I - zA)⁻¹ 1` by forward substitution.
    fn stability(z: Complex<f64>) -> Complex<f64> {
        let b = weights();
        let one = Complex::new(1.0, 0.0);
        let mut stage = [Complex::new(0.0, 0.0); 5];
        for i in 0..5 {
            let known = one + z * (0..i).map(|j| stage[j] * A[i][j]).sum::<Complex<f64>>();
            stage[i] = known / (one - z * GAMMA);
        }
        one + z * (0..5).map(|i| stage[i] * b[i]).sum::<Complex<f64>>()
    }

    #[test]
    fn the_method_is_l_stable() {
        // Stiffly accurate: R(∞) = 0. |R| ≤ 1 on the negative axis (damped modes) and on the
        // imaginary axis (the body's undamped ones), and R(z) ≈ e^z for small z.
        assert!(stability(Complex::new(-1e12, 0.0)).norm() < 1e-10);
        assert!(stability(Complex::new(0.0, 1e12)).norm() < 1e-10);
        for k in 0..400 {
            let x = (10.0_f64).powf(-3.0 + 9.0 * k as f64 / 400.0);
            for z in [Complex::new(-x, 0.0), Complex::new(0.0, x)] {
                let r = stability(z).norm();
                assert!(r <= 1.0 + 1e-15, "|R({z})| = {r}");
            }
        }
        let z = Complex::new(-0.01, 0.02);
        assert!((stability(z) - z.exp()).norm() < 1e-10);
    }
}
