//! A symmetric sparse matrix with a fixed pattern, and its Cholesky factorization by `faer`.
//!
//! The pattern (both triangles, CSC) is built once from the element connectivity; values are
//! refilled in place. The symbolic factorization is computed once and reused for every
//! numeric refactorization.

use std::cell::RefCell;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Par, Side};

use crate::linalg::dense::DenseColumns;

/// Symmetric matrix stored with both triangles in compressed sparse columns; a small one also
/// in dense columns, for its product ([`DenseColumns`]).
#[derive(Debug, Clone)]
pub struct SymmetricMatrix {
    pattern: SymbolicSparseColMat<usize>,
    values: Vec<f64>,
    /// The same values in dense columns, where that product is cheaper; dropped when the
    /// values are refilled ([`Self::values_mut`]).
    dense: Option<DenseColumns>,
}

impl SymmetricMatrix {
    /// Builds the matrix from `(row, col, value)` triplets; duplicates are summed. Each off-
    /// diagonal entry must be given for both triangles (as element assembly naturally does).
    pub fn from_triplets(n: usize, triplets: &[(usize, usize, f64)]) -> Self {
        let mut counts = vec![0usize; n + 1];
        let mut sorted: Vec<(usize, usize, f64)> = triplets.to_vec();
        sorted.sort_unstable_by_key(|&(i, j, _)| (j, i));
        let mut row_idx = Vec::with_capacity(sorted.len());
        let mut values: Vec<f64> = Vec::with_capacity(sorted.len());
        let mut last: Option<(usize, usize)> = None;
        for (i, j, v) in sorted {
            assert!(i < n && j < n, "triplet ({i}, {j}) outside a {n}x{n} matrix");
            if last == Some((i, j)) {
                *values.last_mut().expect("a previous entry") += v;
            } else {
                row_idx.push(i);
                values.push(v);
                counts[j + 1] += 1;
                last = Some((i, j));
            }
        }
        for j in 0..n {
            counts[j + 1] += counts[j];
        }
        let pattern = SymbolicSparseColMat::new_checked(n, n, counts, None, row_idx);
        let mut matrix = Self { pattern, values, dense: None };
        matrix.dense = DenseColumns::of(n, matrix.values.len(), matrix.entries());
        matrix
    }

    /// Dimension.
    pub fn size(&self) -> usize {
        self.pattern.nrows()
    }

    /// Stored values, in pattern order.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Mutable stored values, in pattern order. The product is then the sparse one.
    pub fn values_mut(&mut self) -> &mut [f64] {
        self.dense = None;
        &mut self.values
    }

    /// Index into [`Self::values`] of entry `(i, j)`, if it is in the pattern.
    pub fn position(&self, i: usize, j: usize) -> Option<usize> {
        let start = self.pattern.col_ptr()[j];
        let end = self.pattern.col_ptr()[j + 1];
        self.pattern.row_idx()[start..end].binary_search(&i).ok().map(|k| start + k)
    }

    /// Every stored entry as `(row, col, value)`.
    pub fn entries(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        let col_ptr = self.pattern.col_ptr();
        let row_idx = self.pattern.row_idx();
        (0..self.size()).flat_map(move |j| (col_ptr[j]..col_ptr[j + 1]).map(move |k| (row_idx[k], j, self.values[k])))
    }

    /// `y = A x`, summed column by column: from the dense columns where the matrix has them
    /// (the same sums to the bit, [`DenseColumns`]), else from the pattern.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        match &self.dense {
            Some(dense) => dense.mul_vec(x, y),
            None => self.sparse_mul_vec(x, y),
        }
    }

    /// `y = A x` from the pattern, column by column. (A gather by rows, reading column `i` as
    /// row `i`, took the same 9 % of the paper case's profile, and where assembly leaves the
    /// two triangles different in their last bits, as on a rotated mesh, it computes `Aᵀ x`: a
    /// rounding of its own.)
    pub fn sparse_mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        let col_ptr = self.pattern.col_ptr();
        let row_idx = self.pattern.row_idx();
        for (j, &xj) in x.iter().enumerate() {
            if xj == 0.0 {
                continue;
            }
            let column = col_ptr[j]..col_ptr[j + 1];
            for (&row, &value) in row_idx[column.clone()].iter().zip(&self.values[column]) {
                y[row] += value * xj;
            }
        }
    }

    /// `xᵀ A x`.
    pub fn quadratic_form(&self, x: &[f64]) -> f64 {
        let col_ptr = self.pattern.col_ptr();
        let row_idx = self.pattern.row_idx();
        let mut sum = 0.0;
        for (j, &xj) in x.iter().enumerate() {
            let mut column = 0.0;
            for k in col_ptr[j]..col_ptr[j + 1] {
                column += self.values[k] * x[row_idx[k]];
            }
            sum += xj * column;
        }
        sum
    }

    fn as_faer(&self) -> SparseColMatRef<'_, usize, f64> {
        SparseColMatRef::new(self.pattern.as_ref(), &self.values)
    }
}

/// Why a factorization failed.
#[derive(Debug, Clone, PartialEq)]
pub enum FactorError {
    /// The matrix is not positive definite (e.g. strongly softening contact tangents).
    NotPositiveDefinite,
    /// Memory could not be allocated.
    OutOfMemory,
}

impl std::fmt::Display for FactorError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FactorError::NotPositiveDefinite => write!(f, "the step's operator is singular"),
            FactorError::OutOfMemory => write!(f, "out of memory while factoring the step's operator"),
        }
    }
}

impl std::error::Error for FactorError {}

/// Matrices of at least this many unknowns are factored with supernodes, where `faer`'s own
/// heuristic picks the simplicial factor. Their dense blocks factor the 300 × 30 mesh's operator
/// about 4.5× faster, though a single right-hand side solves about 2× slower (perf, SDIRK4's
/// first 5 s: 81 s → 68 s in all); blocks of right-hand sides, the condensed compliance's, gain
/// most. The paper's 10 × 1 mesh (22 unknowns) keeps the simplicial factor.
pub const SUPERNODAL_FROM: usize = 1000;

/// Sparse Cholesky factorization `A = L Lᵀ` of a [`SymmetricMatrix`]: the symbolic part, the
/// factor's storage and the workspaces are made once and reused by every refactorization and
/// solve. An indefinite matrix (strongly softening contact tangents at large steps) falls back
/// to sparse LU with partial pivoting.
pub struct Cholesky {
    symbolic: SymbolicCholesky<usize>,
    /// `L`'s values, valid while `numeric` is [`Factors::Llt`].
    values: Vec<f64>,
    numeric: Option<Factors>,
    factor_scratch: MemBuffer,
    /// Scratch for single right-hand sides.
    solve_scratch: RefCell<MemBuffer>,
    symbolic_lu: Option<SymbolicLu<usize>>,
}

enum Factors {
    Llt,
    Lu(Box<Lu<usize, f64>>),
}

impl Cholesky {
    /// Analyzes the pattern of `matrix` once: fill-reducing ordering (AMD), elimination tree,
    /// and supernodes from [`SUPERNODAL_FROM`] unknowns on.
    pub fn analyze(matrix: &SymmetricMatrix) -> Result<Self, FactorError> {
        let threshold = if matrix.size() >= SUPERNODAL_FROM {
            SupernodalThreshold::FORCE_SUPERNODAL
        } else {
            SupernodalThreshold::AUTO
        };
        let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
        let symbolic =
            factorize_symbolic_cholesky(matrix.pattern.as_ref(), Side::Lower, SymmetricOrdering::Amd, params)
                .map_err(|_| FactorError::OutOfMemory)?;
        let mut values = Vec::new();
        values.try_reserve_exact(symbolic.len_val()).map_err(|_| FactorError::OutOfMemory)?;
        values.resize(symbolic.len_val(), 0.0);
        let factor_scratch =
            MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()))
                .map_err(|_| FactorError::OutOfMemory)?;
        let solve_scratch = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
            .map_err(|_| FactorError::OutOfMemory)?;
        Ok(Self {
            symbolic,
            values,
            numeric: None,
            factor_scratch,
            solve_scratch: RefCell::new(solve_scratch),
            symbolic_lu: None,
        })
    }

    /// Analyzes and factors `matrix` (a body operator factored once).
    pub fn new(matrix: &SymmetricMatrix) -> Result<Self, FactorError> {
        let mut cholesky = Self::analyze(matrix)?;
        cholesky.factor(matrix)?;
        Ok(cholesky)
    }

    /// Numeric factorization of `matrix`, which must have the analyzed pattern.
    pub fn factor(&mut self, matrix: &SymmetricMatrix) -> Result<(), FactorError> {
        self.numeric = None;
        let llt = self.symbolic.factorize_numeric_llt(
            &mut self.values,
            matrix.as_faer(),
            Side::Lower,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.factor_scratch),
            Default::default(),
        );
        // Its storage and workspace were allocated by `analyze`: only a pivot can fail.
        if llt.is_ok() {
            self.numeric = Some(Factors::Llt);
            return Ok(());
        }
        if self.symbolic_lu.is_none() {
            self.symbolic_lu =
                Some(SymbolicLu::try_new(matrix.pattern.as_ref()).map_err(|_| FactorError::OutOfMemory)?);
        }
        let symbolic = self.symbolic_lu.clone().expect("set above");
        let lu = Lu::try_new_with_symbolic(symbolic, matrix.as_faer()).map_err(|_| FactorError::NotPositiveDefinite)?;
        self.numeric = Some(Factors::Lu(Box::new(lu)));
        Ok(())
    }

    /// Solves `A x = b` in place (`rhs` holds `b` on entry, `x` on exit).
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        let n = rhs.len();
        let rhs = faer::MatMut::from_column_major_slice_mut(rhs, n, 1);
        self.solve_with(rhs, &mut self.solve_scratch.borrow_mut());
    }

    /// Solves `A X = B` in place for every column of `rhs`.
    pub fn solve_columns_in_place(&self, rhs: faer::MatMut<'_, f64>) {
        let mut scratch = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(rhs.ncols(), Par::Seq));
        self.solve_with(rhs, &mut scratch);
    }

    fn solve_with(&self, rhs: faer::MatMut<'_, f64>, scratch: &mut MemBuffer) {
        match self.numeric.as_ref().expect("factor() must succeed before a solve") {
            Factors::Llt => LltRef::<usize, f64>::new(&self.symbolic, &self.values).solve_in_place_with_conj(
                faer::Conj::No,
                rhs,
                Par::Seq,
                MemStack::new(scratch),
            ),
            Factors::Lu(lu) => lu.solve_in_place(rhs),
        }
    }
}
