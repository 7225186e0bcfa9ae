//! A symmetric sparse matrix with a fixed pattern, and its Cholesky factorization by `faer`.
//!
//! The pattern (both triangles, CSC) is built once from the element connectivity; values are
//! refilled in place. The symbolic factorization is computed once and reused for every
//! numeric refactorization.

use faer::Side;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, Lu, SymbolicLlt, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};

/// Symmetric matrix stored with both triangles in compressed sparse columns.
#[derive(Debug, Clone)]
pub struct SymmetricMatrix {
    pattern: SymbolicSparseColMat<usize>,
    values: Vec<f64>,
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
        Self { pattern, values }
    }

    /// Dimension.
    pub fn size(&self) -> usize {
        self.pattern.nrows()
    }

    /// Stored values, in pattern order.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Mutable stored values, in pattern order.
    pub fn values_mut(&mut self) -> &mut [f64] {
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

    /// `y = A x`.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        let col_ptr = self.pattern.col_ptr();
        let row_idx = self.pattern.row_idx();
        for (j, &xj) in x.iter().enumerate() {
            if xj == 0.0 {
                continue;
            }
            for k in col_ptr[j]..col_ptr[j + 1] {
                y[row_idx[k]] += self.values[k] * xj;
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

/// Sparse Cholesky factorization `A = L Lᵀ` of a [`SymmetricMatrix`], symbolic part reused;
/// an indefinite matrix (strongly softening contact tangents at large steps) falls back to
/// sparse LU with partial pivoting.
pub struct Cholesky {
    symbolic: SymbolicLlt<usize>,
    numeric: Option<Factors>,
    symbolic_lu: Option<SymbolicLu<usize>>,
}

enum Factors {
    Llt(Llt<usize, f64>),
    Lu(Box<Lu<usize, f64>>),
}

impl Cholesky {
    /// Analyzes the pattern of `matrix` (fill-reducing ordering, elimination tree) once.
    pub fn analyze(matrix: &SymmetricMatrix) -> Result<Self, FactorError> {
        let symbolic =
            SymbolicLlt::try_new(matrix.pattern.as_ref(), Side::Lower).map_err(|_| FactorError::OutOfMemory)?;
        Ok(Self { symbolic, numeric: None, symbolic_lu: None })
    }

    /// Numeric factorization of `matrix`, which must have the analyzed pattern.
    pub fn factor(&mut self, matrix: &SymmetricMatrix) -> Result<(), FactorError> {
        self.numeric = None;
        match Llt::try_new_with_symbolic(self.symbolic.clone(), matrix.as_faer(), Side::Lower) {
            Ok(llt) => {
                self.numeric = Some(Factors::Llt(llt));
                return Ok(());
            }
            Err(faer::sparse::linalg::LltError::Generic(_)) => return Err(FactorError::OutOfMemory),
            Err(faer::sparse::linalg::LltError::Numeric(_)) => {}
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
        match self.numeric.as_ref().expect("factor() must succeed before solve_in_place()") {
            Factors::Llt(llt) => llt.solve_in_place(rhs),
            Factors::Lu(lu) => lu.solve_in_place(rhs),
        }
    }
}

/// Supernodal Cholesky factorization of a fixed [`SymmetricMatrix`], for many solves with one
/// factor (the condensed body operator): the supernodes' dense blocks make each solve, and
/// above all the block solves for the contact compliance, far faster than the simplicial
/// factor faer picks by default at these sizes.
pub struct SupernodalCholesky {
    symbolic: faer::sparse::linalg::cholesky::SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// Scratch for single right-hand sides, kept between solves.
    scratch: std::cell::RefCell<faer::dyn_stack::MemBuffer>,
}

impl SupernodalCholesky {
    /// Analyzes and factors `matrix`, which must be positive definite.
    pub fn new(matrix: &SymmetricMatrix) -> Result<Self, FactorError> {
        use faer::dyn_stack::{MemBuffer, MemStack};
        use faer::linalg::cholesky::llt::factor::LltRegularization;
        use faer::sparse::linalg::SupernodalThreshold;
        use faer::sparse::linalg::cholesky::{CholeskySymbolicParams, SymmetricOrdering, factorize_symbolic_cholesky};

        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic =
            factorize_symbolic_cholesky(matrix.pattern.as_ref(), Side::Lower, SymmetricOrdering::Amd, params)
                .map_err(|_| FactorError::OutOfMemory)?;
        let mut values = Vec::new();
        values.try_reserve_exact(symbolic.len_val()).map_err(|_| FactorError::OutOfMemory)?;
        values.resize(symbolic.len_val(), 0.0);
        let par = faer::Par::Seq;
        let mut memory = MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()))
            .map_err(|_| FactorError::OutOfMemory)?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                matrix.as_faer(),
                Side::Lower,
                LltRegularization::default(),
                par,
                MemStack::new(&mut memory),
                Default::default(),
            )
            .map_err(|_| FactorError::NotPositiveDefinite)?;
        let scratch =
            MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, par)).map_err(|_| FactorError::OutOfMemory)?;
        Ok(Self { symbolic, values, scratch: std::cell::RefCell::new(scratch) })
    }

    /// Solves `A x = b` in place.
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        let n = rhs.len();
        let mut scratch = self.scratch.borrow_mut();
        self.solve_with(faer::MatMut::from_column_major_slice_mut(rhs, n, 1), &mut scratch);
    }

    /// Solves `A X = B` in place for every column of `rhs`.
    pub fn solve_columns_in_place(&self, rhs: faer::MatMut<'_, f64>) {
        let mut scratch =
            faer::dyn_stack::MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(rhs.ncols(), faer::Par::Seq));
        self.solve_with(rhs, &mut scratch);
    }

    fn solve_with(&self, rhs: faer::MatMut<'_, f64>, scratch: &mut faer::dyn_stack::MemBuffer) {
        let llt = faer::sparse::linalg::cholesky::LltRef::<usize, f64>::new(&self.symbolic, &self.values);
        llt.solve_in_place_with_conj(faer::Conj::No, rhs, faer::Par::Seq, faer::dyn_stack::MemStack::new(scratch));
    }
}
