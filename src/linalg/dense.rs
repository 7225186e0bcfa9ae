//! A small matrix kept dense beside its sparse pattern, for the product `y = A x` that the
//! explicit right-hand sides take at every evaluation.
//!
//! On the paper's 10 × 1 mesh `K` is 22 × 22 with 124 stored entries: the sparse product reads
//! a row index and a value per entry and adds into memory, about 15 instructions per entry.
//! Dense columns padded to whole blocks of [`BLOCK`] rows let each block of `y` stay in
//! registers while every column is added in, two or four entries per instruction (SSE2,
//! AVX2), with no index read.
//!
//! **The same result to the bit as the sparse product** ([`super::sparse::SymmetricMatrix`]
//! sums column by column): each `y_i` is `0 + a_i0 x_0 + a_i1 x_1 + …` in the order of the
//! columns in both. The dense form also adds what the sparse one skips inside each block's band
//! of columns, the pattern's zeros and the columns with `x_j = 0`, each term `±0`; adding `±0`
//! leaves every sum as it was: a sum that starts at `+0` can only become `-0` by adding `-0` to
//! `-0`, so it is never `-0`, and `y + (±0) = y` for every other `y` (round to nearest). That holds for finite `x` and `A`; a
//! state that is not finite is rejected by every integrator whatever its product.

use std::ops::Range;

/// Rows per block: eight `f64`, two AVX2 registers of accumulators (four SSE2 ones).
const BLOCK: usize = 8;

/// The largest matrix kept dense: 64 rows padded to 64 are 32 KiB, a first-level cache.
const MAX_SIZE: usize = 64;

/// Dense storage pays where it stores at most this many slots per stored entry: a slot costs
/// about one instruction in the product (1.2 on the paper case, AVX2), a sparse entry about 15.
const MAX_SLOTS_PER_ENTRY: usize = 8;

/// An `n × n` matrix in blocks of [`BLOCK`] rows (`n` rounded up, the padding zero), each
/// block stored column after column: the block of rows `8b … 8b + 7` of column `j` is
/// `values[b n + j]`. `columns[b]` is the range of columns from block `b`'s first column with
/// a stored entry to its last; outside it the block is zero and the product skips it (a
/// banded matrix's band).
#[derive(Debug, Clone)]
pub struct DenseColumns {
    n: usize,
    values: Vec<[f64; BLOCK]>,
    columns: Vec<Range<usize>>,
}

impl DenseColumns {
    /// The dense form of the `n × n` matrix whose `stored` entries are `(row, col, value)`,
    /// where it pays ([`MAX_SIZE`], [`MAX_SLOTS_PER_ENTRY`]); `None` where the sparse product
    /// is cheaper.
    pub fn of(n: usize, stored: usize, entries: impl Iterator<Item = (usize, usize, f64)>) -> Option<Self> {
        let blocks = n.div_ceil(BLOCK);
        if n == 0 || n > MAX_SIZE || blocks * BLOCK * n > MAX_SLOTS_PER_ENTRY * stored {
            return None;
        }
        let mut values = vec![[0.0; BLOCK]; blocks * n];
        let mut columns = vec![n..0; blocks];
        for (i, j, value) in entries {
            values[i / BLOCK * n + j][i % BLOCK] = value;
            let span = &mut columns[i / BLOCK];
            *span = span.start.min(j)..span.end.max(j + 1);
        }
        for span in &mut columns {
            // A block without stored entries: no column.
            span.start = span.start.min(span.end);
        }
        Some(Self { n, values, columns })
    }

    /// `y = A x`, column by column in the order of the columns, compiled for the widest
    /// vectors the processor has (`pulp`'s runtime dispatch; every width gives the same sums
    /// to the bit, no multiply and add being fused).
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        pulp::Arch::new().dispatch(Product { a: self, x, y });
    }
}

/// [`DenseColumns::mul_vec`] for `pulp`'s dispatch.
struct Product<'a> {
    a: &'a DenseColumns,
    x: &'a [f64],
    y: &'a mut [f64],
}

impl pulp::WithSimd for Product<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<V: pulp::Simd>(self, _: V) {
        let Self { a, x, y } = self;
        let x = &x[..a.n];
        let blocks = a.values.chunks_exact(a.n).zip(&a.columns);
        for ((block, span), y) in blocks.zip(y[..a.n].chunks_mut(BLOCK)) {
            let mut sum = [0.0_f64; BLOCK];
            for (column, &xj) in block[span.clone()].iter().zip(&x[span.clone()]) {
                for (s, a) in sum.iter_mut().zip(column) {
                    *s += a * xj;
                }
            }
            for (y, s) in y.iter_mut().zip(sum) {
                *y = s;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::linalg::sparse::SymmetricMatrix;

    /// A symmetric `n × n` matrix whose pattern holds the diagonal and each pair `(i, j)` where
    /// `keep` says so, valued from `values` (wide magnitudes, both signs).
    fn matrix(n: usize, keep: &[bool], values: &[f64]) -> SymmetricMatrix {
        let mut triplets = Vec::new();
        let mut k = 0;
        for i in 0..n {
            for j in i..n {
                let (value, kept) = (values[k % values.len()], keep[k % keep.len()]);
                k += 1;
                if i == j {
                    triplets.push((i, i, value));
                } else if kept {
                    triplets.push((i, j, value));
                    triplets.push((j, i, value));
                }
            }
        }
        SymmetricMatrix::from_triplets(n, &triplets)
    }

    fn value() -> impl Strategy<Value = f64> {
        (-1.0..1.0_f64, -300..300_i32).prop_map(|(m, e)| m * 10f64.powi(e))
    }

    /// An entry of `x`: exact zeros of both signs often, else any magnitude.
    fn entry() -> impl Strategy<Value = f64> {
        prop_oneof![1 => Just(0.0), 1 => Just(-0.0), 6 => value()]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// Every sum the dense columns give is the sparse product's, to the bit.
        #[test]
        fn the_dense_product_is_the_sparse_one_to_the_bit(
            n in 1..=MAX_SIZE,
            keep in prop::collection::vec(prop::bool::weighted(0.4), 1..300),
            values in prop::collection::vec(value(), 1..300),
            x in prop::collection::vec(entry(), MAX_SIZE),
        ) {
            let a = matrix(n, &keep, &values);
            let entries = a.values().len();
            let Some(dense) = DenseColumns::of(n, entries, a.entries()) else {
                // Too sparse for dense columns: the rule, and nothing to compare.
                prop_assert!(n.div_ceil(BLOCK) * BLOCK * n > MAX_SLOTS_PER_ENTRY * entries);
                return Ok(());
            };
            let (mut by_dense, mut by_pattern) = (vec![f64::NAN; n], vec![f64::NAN; n]);
            dense.mul_vec(&x[..n], &mut by_dense);
            a.sparse_mul_vec(&x[..n], &mut by_pattern);
            for (i, (d, s)) in by_dense.iter().zip(&by_pattern).enumerate() {
                prop_assert_eq!(d.to_bits(), s.to_bits(), "row {}: {} against {}", i, d, s);
            }
        }
    }

    /// The paper's 10 × 1 mesh (22 unknowns, 124 stored entries) is kept dense; a chain of 22
    /// (64 entries) and anything over 64 unknowns are not.
    #[test]
    fn small_full_enough_matrices_are_kept_dense() {
        let none = std::iter::empty::<(usize, usize, f64)>();
        assert!(DenseColumns::of(22, 124, none.clone()).is_some());
        assert!(DenseColumns::of(22, 64, none.clone()).is_none());
        assert!(DenseColumns::of(65, 65 * 65, none.clone()).is_none());
        assert!(DenseColumns::of(0, 0, none).is_none());
    }

    /// Each block reads the columns of its band only: a tridiagonal 16 × 16 matrix's blocks
    /// of rows 0–7 and 8–15 read columns 0–8 and 7–15.
    #[test]
    fn each_block_reads_its_band() {
        let tridiagonal = (0..16_usize).flat_map(|i| [i.checked_sub(1), Some(i), Some(i + 1)].map(|j| (i, j)));
        let entries: Vec<_> = tridiagonal.filter_map(|(i, j)| j.filter(|&j| j < 16).map(|j| (i, j, 1.0))).collect();
        let dense = DenseColumns::of(16, entries.len(), entries.into_iter()).expect("kept dense");
        assert_eq!(dense.columns, [0..9, 7..16]);
    }

    /// Values refilled in place are the ones multiplied.
    #[test]
    fn refilled_values_are_multiplied() {
        let mut a = matrix(5, &[true], &[1.0, 2.0, -3.0]);
        let x = [1.0, -2.0, 0.5, 3.0, 0.25];
        let (mut before, mut after) = ([0.0; 5], [0.0; 5]);
        a.mul_vec(&x, &mut before);
        a.values_mut().iter_mut().for_each(|v| *v *= 2.0);
        a.mul_vec(&x, &mut after);
        for (b, a) in before.iter().zip(&after) {
            assert_eq!(*a, 2.0 * b);
        }
    }
}
