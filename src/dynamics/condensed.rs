//! The step's Newton iteration condensed onto the contact's degrees of freedom.
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
//! factored once per `τ` (supernodal Cholesky), and `G` costs `k` solves with it, once per `τ`;
//! a step then costs two solves with `A` (for `w`, and for `Δu` at the end), where the full
//! system needed a sparse refactorization of all `n` unknowns per Newton iteration.
//!
//! Newton's matrix changes with every contact tangent, but slowly: its dense LU is kept and
//! preconditions GMRES on the next matrices (two `k × k` products per GMRES iteration instead
//! of `2k³/3` for a new LU), and is refactored only when GMRES needs more than
//! [`GMRES_ITERATIONS`] iterations. The two formulations have the same solution;
//! `tests/block_fem.rs` checks that they produce the same trajectories.

use faer::Mat;
use faer::linalg::solvers::{PartialPivLu, Solve};

use crate::dynamics::body::LinearBody;
use crate::dynamics::contact::ContactPoint;
use crate::linalg::sparse::{Cholesky, FactorError, SymmetricMatrix};

/// Right-hand sides solved together while computing `G` (memory: `n` values each).
const BLOCK: usize = 64;

/// GMRES iterations allowed before Newton's matrix is refactored instead.
pub const GMRES_ITERATIONS: usize = 20;

/// GMRES stops at this residual relative to the right-hand side: the Newton correction is then
/// exact to rounding, and Newton's quadratic convergence is kept.
const GMRES_TOLERANCE: f64 = 1e-13;

/// The body operator of one `τ`, factored, and its compliance at the contact.
pub(crate) struct Condensation {
    /// The `τ` that `A` belongs to (s).
    pub(crate) tau: f64,
    operator: Cholesky,
    /// The body's degree of freedom of each contact unknown, ascending.
    pub(crate) dofs: Vec<usize>,
    /// The contact points with their degrees of freedom renumbered to contact unknowns, so that
    /// [`ContactPoint::interpolate`] and [`ContactPoint::scatter`] work on `k`-vectors.
    pub(crate) points: Vec<ContactPoint>,
    /// `G = Pᵀ A⁻¹ P` (`k × k`, symmetric).
    compliance: Mat<f64>,
    /// The latest factored Newton matrix, the preconditioner of the next.
    newton: std::cell::RefCell<Option<NewtonMatrix>>,
}

impl Condensation {
    /// Factors `A = 6/τ² M + K` and computes `G`.
    pub(crate) fn new(body: &LinearBody, points: &[ContactPoint], tau: f64) -> Result<Self, FactorError> {
        let n = body.dofs();
        let c0 = 6.0 / (tau * tau);
        let mut triplets: Vec<(usize, usize, f64)> = body.stiffness.entries().collect();
        triplets.extend((0..n).map(|i| (i, i, c0 * body.mass[i])));
        let matrix = SymmetricMatrix::from_triplets(n, &triplets);
        let operator = Cholesky::new(&matrix)?;

        let mut dofs: Vec<usize> = points.iter().flat_map(|p| p.tangential.terms().map(|(dof, _)| dof)).collect();
        dofs.sort_unstable();
        dofs.dedup();
        let index = |dof: usize| dofs.binary_search(&dof).expect("every point's dofs are listed");
        let local_points =
            points.iter().map(|p| ContactPoint { tangential: p.tangential.renumbered(index), ..*p }).collect();

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
        Ok(Self { tau, operator, dofs, points: local_points, compliance, newton: std::cell::RefCell::new(None) })
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
    pub(crate) fn forces(&self, weighted_traction: &[f64]) -> Vec<f64> {
        let mut forces = vec![0.0; self.size()];
        for (point, &t) in self.points.iter().zip(weighted_traction) {
            point.scatter(t, &mut forces);
        }
        forces
    }

    /// `K_c δ` for each point's contact stiffness `-w ∂f_t/∂Δū`.
    pub(crate) fn contact_stiffness_times(&self, stiffness: &[f64], delta: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.size()];
        for (point, &k) in self.points.iter().zip(stiffness) {
            point.scatter(k * point.interpolate(delta), &mut out);
        }
        out
    }

    /// `(I + G K_c) v`.
    fn newton_times(&self, stiffness: &[f64], v: &[f64]) -> Vec<f64> {
        let kv = self.contact_stiffness_times(stiffness, v);
        let gkv = self.compliance_times(&kv);
        v.iter().zip(gkv).map(|(a, b)| a + b).collect()
    }

    /// The contact stiffnesses the kept Newton matrix was factored at, if one is kept.
    pub(crate) fn newton_stiffness(&self) -> Option<Vec<f64>> {
        self.newton.borrow().as_ref().map(|m| m.stiffness.clone())
    }

    /// Factors and keeps the Newton matrix of `stiffness`, as [`Self::solve_newton`] last did.
    pub(crate) fn keep_newton(&self, stiffness: &[f64]) -> Result<(), FactorError> {
        let matrix = self.newton_matrix(stiffness)?;
        *self.newton.borrow_mut() = Some(matrix);
        Ok(())
    }

    /// Solves Newton's system `(I + G K_c) δ = rhs` in place: by the kept LU if `K_c` is the
    /// same, else by GMRES preconditioned with it, else by a new LU.
    pub(crate) fn solve_newton(&self, stiffness: &[f64], rhs: &mut [f64]) -> Result<(), FactorError> {
        let mut kept = self.newton.borrow_mut();
        if let Some(matrix) = kept.as_ref() {
            if matrix.stiffness == stiffness {
                matrix.solve_in_place(rhs);
                return Ok(());
            }
            let solution = gmres(
                |v| self.newton_times(stiffness, v),
                |v| matrix.solve_in_place(v),
                rhs,
                GMRES_TOLERANCE,
                GMRES_ITERATIONS,
            );
            if let Some(solution) = solution {
                rhs.copy_from_slice(&solution);
                return Ok(());
            }
        }
        *kept = None;
        let matrix = self.newton_matrix(stiffness)?;
        matrix.solve_in_place(rhs);
        *kept = Some(matrix);
        Ok(())
    }

    /// Factors Newton's matrix `I + G K_c` (dense LU with partial pivoting).
    fn newton_matrix(&self, stiffness: &[f64]) -> Result<NewtonMatrix, FactorError> {
        let k = self.size();
        let mut matrix = Mat::<f64>::identity(k, k);
        // (G K_c)[:, b] = Σ_p k_p c_a c_b G[:, a], c the point's tangential factors.
        for (point, &kp) in self.points.iter().zip(stiffness) {
            if kp == 0.0 {
                continue;
            }
            for (dof_a, c_a) in point.tangential.terms() {
                for (dof_b, c_b) in point.tangential.terms() {
                    let scale = kp * c_a * c_b;
                    if scale == 0.0 {
                        continue;
                    }
                    let source = self.compliance.col(dof_a);
                    let target = matrix.as_mut().col_mut(dof_b).try_as_col_major_mut().expect("contiguous column");
                    let source = source.try_as_col_major().expect("contiguous column");
                    for (t, g) in target.as_slice_mut().iter_mut().zip(source.as_slice()) {
                        *t += scale * g;
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
        Ok(NewtonMatrix { stiffness: stiffness.to_vec(), lu })
    }
}

/// `I + G K_c` for one `K_c`, factored.
struct NewtonMatrix {
    stiffness: Vec<f64>,
    lu: PartialPivLu<f64>,
}

impl NewtonMatrix {
    fn solve_in_place(&self, rhs: &mut [f64]) {
        let k = rhs.len();
        self.lu.solve_in_place(faer::MatMut::from_column_major_slice_mut(rhs, k, 1));
    }
}

/// GMRES with right preconditioning (Saad, *Iterative Methods for Sparse Linear Systems*,
/// Alg. 9.5), from `x = 0`, without restarts: the solution of `apply(x) = b` once the residual
/// is below `tolerance · |b|`, or `None` after `max_iterations`.
fn gmres(
    apply: impl Fn(&[f64]) -> Vec<f64>,
    precondition: impl Fn(&mut [f64]),
    b: &[f64],
    tolerance: f64,
    max_iterations: usize,
) -> Option<Vec<f64>> {
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
    let beta = dot(b, b).sqrt();
    if beta == 0.0 {
        return Some(vec![0.0; b.len()]);
    }
    if !beta.is_finite() {
        return None;
    }
    let mut basis: Vec<Vec<f64>> = vec![b.iter().map(|v| v / beta).collect()];
    // Columns of the Hessenberg matrix after the Givens rotations: upper triangular.
    let mut triangle: Vec<Vec<f64>> = Vec::new();
    let mut rotations: Vec<(f64, f64)> = Vec::new();
    let mut g = vec![beta];
    for j in 0..max_iterations {
        let mut z = basis[j].clone();
        precondition(&mut z);
        let mut w = apply(&z);
        let mut column = vec![0.0; j + 2];
        // Modified Gram-Schmidt.
        for (i, v) in basis.iter().enumerate() {
            let h = dot(&w, v);
            column[i] = h;
            w.iter_mut().zip(v).for_each(|(w, v)| *w -= h * v);
        }
        let norm = dot(&w, &w).sqrt();
        column[j + 1] = norm;
        for (i, &(c, s)) in rotations.iter().enumerate() {
            let (a, b) = (column[i], column[i + 1]);
            column[i] = c * a + s * b;
            column[i + 1] = -s * a + c * b;
        }
        let r = column[j].hypot(column[j + 1]);
        if r == 0.0 || !r.is_finite() {
            return None;
        }
        let (c, s) = (column[j] / r, column[j + 1] / r);
        rotations.push((c, s));
        column[j] = r;
        column[j + 1] = 0.0;
        g.push(-s * g[j]);
        g[j] *= c;
        triangle.push(column);
        if g[j + 1].abs() <= tolerance * beta || norm == 0.0 {
            let m = j + 1;
            let mut y = vec![0.0; m];
            for i in (0..m).rev() {
                let sum = g[i] - (i + 1..m).map(|l| triangle[l][i] * y[l]).sum::<f64>();
                y[i] = sum / triangle[i][i];
            }
            let mut x = vec![0.0; b.len()];
            for (yi, v) in y.iter().zip(&basis) {
                x.iter_mut().zip(v).for_each(|(x, v)| *x += yi * v);
            }
            precondition(&mut x);
            return Some(x);
        }
        basis.push(w.iter().map(|v| v / norm).collect());
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// GMRES against a direct solve on a nonsymmetric system, preconditioned by a nearby matrix.
    #[test]
    fn gmres_solves_a_nearby_system() {
        let n = 30;
        let a =
            Mat::<f64>::from_fn(n, n, |i, j| if i == j { 4.0 + i as f64 } else { 1.0 / (1.0 + (i + 2 * j) as f64) });
        let near = Mat::<f64>::from_fn(n, n, |i, j| a[(i, j)] * if i == j { 1.1 } else { 0.9 });
        let lu = PartialPivLu::new(near.as_ref());
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let apply = |x: &[f64]| (0..n).map(|i| (0..n).map(|j| a[(i, j)] * x[j]).sum()).collect::<Vec<f64>>();
        let precondition = |v: &mut [f64]| lu.solve_in_place(faer::MatMut::from_column_major_slice_mut(v, n, 1));
        let x = gmres(apply, precondition, &b, 1e-13, 30).expect("converges");
        let residual = apply(&x).iter().zip(&b).map(|(r, b)| (r - b).abs()).fold(0.0, f64::max);
        assert!(residual <= 1e-12, "residual {residual:e}");
        assert!(gmres(apply, precondition, &b, 1e-13, 2).is_none(), "two iterations cannot reach 1e-13 here");
    }
}
