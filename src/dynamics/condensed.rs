//! The step's Newton iteration condensed onto the contact's degrees of freedom (issue 6).
//!
//! The body is linear and only the contact is not. With `A = 6/τ² M + K`, fixed for a given
//! `τ = θΔt`, the equation of motion (14) at `t_n + τ` reads
//!
//! `A Δu + r₀ = P F(Pᵀ Δu)`,
//!
//! where `P` picks the `k` tangential degrees of freedom the contact points interpolate, `F` are
//! their nodal contact forces `Σ w Ñᵀ f_t` and `r₀` is the rest of the residual at `Δu = 0`. So
//! `Δu = w + A⁻¹ P F(x)` with `w = -A⁻¹ r₀`, and the contact unknowns `x = Pᵀ Δu` solve the
//! small system
//!
//! `g(x) = x - Pᵀ w - G F(x) = 0`,  `G = Pᵀ A⁻¹ P` (the body's compliance at the contact),
//!
//! by Newton's method with `∂g/∂x = I + G K_c`, `K_c = -∂F/∂x` (eq. 14's `K_c`). `A` is
//! factored once per `τ`, and `G` costs `k` solves with it, once per `τ`; a step then costs two
//! solves with `A` (for `w`, and for `Δu` at the end) and a dense `k × k` LU per Newton iteration
//! whose contact tangents changed, where the full system needed a sparse refactorization of all
//! `n` unknowns. The two formulations have the same solution; `tests/block_fem.rs` checks that
//! they produce the same trajectories.

use faer::Mat;
use faer::linalg::solvers::{PartialPivLu, Solve};

use super::body::LinearBody;
use super::contact::ContactPoint;
use super::sparse::{Cholesky, FactorError, SymmetricMatrix};

/// Right-hand sides solved together while computing `G` (memory: `n` values each).
const BLOCK: usize = 64;

/// The body operator of one `τ`, factored, and its compliance at the contact.
pub(crate) struct Condensation {
    /// The `τ` that `A` belongs to (s).
    pub(crate) tau: f64,
    operator: Cholesky,
    /// The body's degree of freedom of each contact unknown, ascending.
    pub(crate) dofs: Vec<usize>,
    /// The contact unknowns each point interpolates.
    pub(crate) local: Vec<[usize; 2]>,
    /// `G = Pᵀ A⁻¹ P` (`k × k`, symmetric).
    compliance: Mat<f64>,
}

impl Condensation {
    /// Factors `A = 6/τ² M + K` and computes `G`.
    pub(crate) fn new(body: &LinearBody, points: &[ContactPoint], tau: f64) -> Result<Self, FactorError> {
        let n = body.dofs();
        let c0 = 6.0 / (tau * tau);
        let mut triplets: Vec<(usize, usize, f64)> = body.stiffness.entries().collect();
        triplets.extend((0..n).map(|i| (i, i, c0 * body.mass[i])));
        let matrix = SymmetricMatrix::from_triplets(n, &triplets);
        let mut operator = Cholesky::analyze(&matrix)?;
        operator.factor(&matrix)?;

        let mut dofs: Vec<usize> = points.iter().flat_map(|p| p.dofs).collect();
        dofs.sort_unstable();
        dofs.dedup();
        let index = |dof: usize| dofs.binary_search(&dof).expect("every point's dofs are listed");
        let local = points.iter().map(|p| [index(p.dofs[0]), index(p.dofs[1])]).collect();

        let k = dofs.len();
        let mut compliance = Mat::<f64>::zeros(k, k);
        let mut block = Mat::<f64>::zeros(n, BLOCK.min(k));
        for start in (0..k).step_by(BLOCK) {
            let width = BLOCK.min(k - start);
            let mut columns = block.as_mut().subcols_mut(0, width);
            columns.fill(0.0);
            for j in 0..width {
                columns[(dofs[start + j], j)] = 1.0;
            }
            operator.solve_columns_in_place(columns.as_mut());
            for j in 0..width {
                for (i, &dof) in dofs.iter().enumerate() {
                    compliance[(i, start + j)] = columns[(dof, j)];
                }
            }
        }
        Ok(Self { tau, operator, dofs, local, compliance })
    }

    /// Number of contact unknowns `k`.
    pub(crate) fn size(&self) -> usize {
        self.dofs.len()
    }

    /// `A⁻¹ b` in place.
    pub(crate) fn solve_body(&self, rhs: &mut [f64]) {
        self.operator.solve_in_place(rhs);
    }

    /// `G f`.
    pub(crate) fn compliance_times(&self, forces: &[f64]) -> Vec<f64> {
        let k = self.size();
        let mut out = vec![0.0; k];
        for (j, &f) in forces.iter().enumerate() {
            if f != 0.0 {
                let column = self.compliance.col(j);
                for (o, g) in out.iter_mut().zip(column.iter()) {
                    *o += g * f;
                }
            }
        }
        out
    }

    /// `F = Σ w Ñᵀ f_t` on the contact unknowns, for each point's `weight × traction`.
    pub(crate) fn forces(&self, points: &[ContactPoint], weighted_traction: &[f64]) -> Vec<f64> {
        let mut forces = vec![0.0; self.size()];
        for ((point, local), &t) in points.iter().zip(&self.local).zip(weighted_traction) {
            forces[local[0]] += point.shape[0] * t;
            forces[local[1]] += point.shape[1] * t;
        }
        forces
    }

    /// `K_c δ` for each point's contact stiffness `-w ∂f_t/∂Δū`.
    pub(crate) fn contact_stiffness_times(
        &self,
        points: &[ContactPoint],
        stiffness: &[f64],
        delta: &[f64],
    ) -> Vec<f64> {
        let mut out = vec![0.0; self.size()];
        for ((point, local), &k) in points.iter().zip(&self.local).zip(stiffness) {
            let [n0, n1] = point.shape;
            let slip = n0 * delta[local[0]] + n1 * delta[local[1]];
            out[local[0]] += k * n0 * slip;
            out[local[1]] += k * n1 * slip;
        }
        out
    }

    /// Factors Newton's matrix `I + G K_c` (dense LU with partial pivoting).
    pub(crate) fn newton_matrix(
        &self,
        points: &[ContactPoint],
        stiffness: &[f64],
    ) -> Result<NewtonMatrix, FactorError> {
        let k = self.size();
        let mut matrix = Mat::<f64>::identity(k, k);
        // (G K_c)[:, b] = Σ_p k_p N_a N_b G[:, a].
        for ((point, local), &kp) in points.iter().zip(&self.local).zip(stiffness) {
            if kp == 0.0 {
                continue;
            }
            for a in 0..2 {
                for b in 0..2 {
                    let scale = kp * point.shape[a] * point.shape[b];
                    if scale == 0.0 {
                        continue;
                    }
                    let (column_a, column_b) = (local[a], local[b]);
                    for i in 0..k {
                        matrix[(i, column_b)] += scale * self.compliance[(i, column_a)];
                    }
                }
            }
        }
        let lu = PartialPivLu::new(matrix.as_ref());
        // Partial pivoting leaves a zero (or non-finite) pivot only for a singular matrix.
        let u = lu.U();
        if (0..k).any(|i| u[(i, i)] == 0.0 || !u[(i, i)].is_finite()) {
            return Err(FactorError::NotPositiveDefinite);
        }
        Ok(NewtonMatrix { lu })
    }
}

/// `I + G K_c`, factored.
pub(crate) struct NewtonMatrix {
    lu: PartialPivLu<f64>,
}

impl NewtonMatrix {
    /// Solves in place.
    pub(crate) fn solve_in_place(&self, rhs: &mut [f64]) {
        let k = rhs.len();
        self.lu.solve_in_place(faer::MatMut::from_column_major_slice_mut(rhs, k, 1));
    }
}
