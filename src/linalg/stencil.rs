//! A sparse matrix of 2 × 2 node blocks whose rows repeat along runs of nodes.
//!
//! On a structured mesh of identical elements, with the two degrees of freedom of each node
//! stored together (node `k` owns `2k` and `2k + 1`), every interior node's rows of `K` are the
//! same stencil of 2 × 2 blocks at the same node offsets: the 1000 × 100 block's 101 101 nodes
//! form a few hundred runs of equal stencils (one per grid row's interior, and short runs
//! along the edges). Along a run, each block of the stencil adds a shifted copy of `x` (and of
//! `x` with each node's two values swapped, for the off-diagonal entries of the block) times
//! two alternating coefficients: contiguous loops that vectorize, and that read only `x`
//! (1.6 MB) where a compressed sparse matrix reads 58 MB. Explicit time stepping
//! ([`crate::dynamics::central`]) does one product per step.

use crate::linalg::sparse::SymmetricMatrix;

/// Entries of two stencils that differ by at most this share of the stencil's largest are the
/// same (a few roundings of its sum).
pub const SAME: f64 = 1e-14;

/// Consecutive nodes `first..first + len` whose rows share `blocks`.
#[derive(Debug, Clone, PartialEq)]
struct Run {
    first: usize,
    len: usize,
    /// `(node offset Δ, [a_xx, a_xy, a_yx, a_yy])`: the block coupling node `k` to node `k + Δ`.
    blocks: Vec<(isize, [f64; 4])>,
}

/// [`TemplateMatrix::mul_nodes`] for `pulp`'s dispatch.
struct MulNodes<'a> {
    runs: &'a [Run],
    x: &'a [f64],
    swapped: &'a [f64],
    y: &'a mut [f64],
    first: usize,
}

impl pulp::WithSimd for MulNodes<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Self { runs, x, swapped, y, first } = self;
        for run in runs {
            let start = 2 * (run.first - first);
            let out = &mut y[start..start + 2 * run.len];
            if run.blocks.is_empty() {
                out.fill(0.0);
            }
            for (b, &(offset, [xx, xy, yx, yy])) in run.blocks.iter().enumerate() {
                let from = 2 * run.first.wrapping_add_signed(offset);
                let (direct, cross) = (&x[from..from + 2 * run.len], &swapped[from..from + 2 * run.len]);
                // The first block writes, the others add (no pass to clear `out`).
                let assign = b == 0;
                // Two nodes at a time: four lanes with the coefficients (xx, yy, xx, yy) and
                // (xy, yx, xy, yx).
                let mut out4 = out.chunks_exact_mut(4);
                let (direct4, cross4) = (direct.chunks_exact(4), cross.chunks_exact(4));
                let (direct_rest, cross_rest) = (direct4.remainder(), cross4.remainder());
                for ((o, d), c) in (&mut out4).zip(direct4).zip(cross4) {
                    let terms =
                        [xx * d[0] + xy * c[0], yy * d[1] + yx * c[1], xx * d[2] + xy * c[2], yy * d[3] + yx * c[3]];
                    accumulate(o, &terms, assign);
                }
                let o = out4.into_remainder();
                if o.len() == 2 {
                    let terms = [xx * direct_rest[0] + xy * cross_rest[0], yy * direct_rest[1] + yx * cross_rest[1]];
                    accumulate(o, &terms, assign);
                }
            }
        }
    }
}

/// `out = terms` or `out += terms`.
#[inline(always)]
fn accumulate(out: &mut [f64], terms: &[f64], assign: bool) {
    for (o, t) in out.iter_mut().zip(terms) {
        *o = if assign { *t } else { *o + t };
    }
}

/// A symmetric matrix of `2 × nodes` rows stored as runs of equal node stencils (see the
/// module documentation). Its products equal those of the matrix it was built from up to the
/// rounding of its entries' sums ([`SAME`]).
#[derive(Debug, Clone)]
pub struct TemplateMatrix {
    runs: Vec<Run>,
    size: usize,
}

impl TemplateMatrix {
    /// Collects the node stencils of `matrix`, or `None` if it has an odd number of rows (no
    /// node pairs). Nodes share a run if their stencils have the same offsets and values equal
    /// to [`SAME`] of the stencil's largest: assembly sums an interior node's four elements in
    /// different orders, so equal stencils differ in the last bits.
    pub fn new(matrix: &SymmetricMatrix) -> Option<Self> {
        let n = matrix.size();
        if !n.is_multiple_of(2) {
            return None;
        }
        let mut stencils: Vec<Vec<(isize, [f64; 4])>> = vec![Vec::new(); n / 2];
        // Column j holds row j's entries (symmetric).
        for (col, row, value) in matrix.entries() {
            let (node, p) = (row / 2, row % 2);
            let (other, d) = (col / 2, col % 2);
            let offset = other as isize - node as isize;
            let stencil = &mut stencils[node];
            let position = match stencil.iter().position(|(o, _)| *o == offset) {
                Some(k) => k,
                None => {
                    stencil.push((offset, [0.0; 4]));
                    stencil.len() - 1
                }
            };
            stencil[position].1[2 * p + d] = value;
        }
        let mut runs: Vec<Run> = Vec::new();
        for (node, mut blocks) in stencils.into_iter().enumerate() {
            blocks.sort_by_key(|(o, _)| *o);
            let same = |a: &[(isize, [f64; 4])], b: &[(isize, [f64; 4])]| {
                let scale = a.iter().flat_map(|(_, block)| block.iter()).fold(0.0_f64, |m, v| m.max(v.abs()));
                a.len() == b.len()
                    && a.iter()
                        .zip(b)
                        .all(|(x, y)| x.0 == y.0 && x.1.iter().zip(&y.1).all(|(u, v)| (u - v).abs() <= SAME * scale))
            };
            match runs.last_mut() {
                Some(run) if same(&run.blocks, &blocks) => run.len += 1,
                _ => runs.push(Run { first: node, len: 1, blocks }),
            }
        }
        Some(Self { runs, size: n })
    }

    /// Number of runs of equal stencils.
    pub fn runs(&self) -> usize {
        self.runs.len()
    }

    /// `y = A x` for the nodes `first..first + y.len()/2`, given `swapped`, `x` with each node's
    /// two values exchanged; `runs` must cover those nodes. Compiled for the widest vectors the
    /// processor has (`pulp`'s runtime dispatch, as `faer` does).
    fn mul_nodes(runs: &[Run], x: &[f64], swapped: &[f64], y: &mut [f64], first: usize) {
        pulp::Arch::new().dispatch(MulNodes { runs, x, swapped, y, first });
    }

    /// Splits the runs into about `parts` consecutive groups of similar size: `(runs, first
    /// node, nodes)` for each.
    pub fn chunks(&self, parts: usize) -> Vec<(usize, usize, usize)> {
        let nodes = self.size / 2;
        let target = nodes.div_ceil(parts.max(1)).max(1);
        let mut chunks = Vec::new();
        let (mut begin, mut count) = (0, 0);
        for (k, run) in self.runs.iter().enumerate() {
            count += run.len;
            if count >= target || k + 1 == self.runs.len() {
                chunks.push((begin, k + 1, count));
                begin = k + 1;
                count = 0;
            }
        }
        chunks
    }

    /// `y = A x` on the nodes of chunk `(begin, end, _)` of [`Self::chunks`]; `y` holds that
    /// chunk's rows.
    pub fn mul_chunk(&self, (begin, end): (usize, usize), x: &[f64], swapped: &[f64], y: &mut [f64]) {
        let runs = &self.runs[begin..end];
        let first = runs.first().map_or(0, |r| r.first);
        Self::mul_nodes(runs, x, swapped, y, first);
    }

    /// `x` with each node's two values exchanged.
    pub fn swap_pairs(x: &[f64], swapped: &mut [f64]) {
        for (s, x) in swapped.chunks_exact_mut(2).zip(x.chunks_exact(2)) {
            s[0] = x[1];
            s[1] = x[0];
        }
    }

    /// `y = A x`.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        let mut swapped = vec![0.0; x.len()];
        Self::swap_pairs(x, &mut swapped);
        Self::mul_nodes(&self.runs, x, &swapped, y, 0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of 2-D nodes with coupled x and y and a different last node: the interior
    /// nodes share one run, and the products agree with the compressed matrix, whole and by
    /// chunks.
    #[test]
    fn repeated_node_stencils_share_a_run_and_multiply_alike() {
        let nodes = 40;
        let n = 2 * nodes;
        let mut triplets = Vec::new();
        let block = [[2.0, 0.3], [0.3, 1.5]];
        for k in 0..nodes {
            for (p, row) in block.iter().enumerate() {
                for (d, &value) in row.iter().enumerate() {
                    let end = if k == nodes - 1 && p == d { 1.0 } else { 0.0 };
                    triplets.push((2 * k + p, 2 * k + d, 2.0 * value + end));
                    if k + 1 < nodes {
                        triplets.push((2 * k + p, 2 * (k + 1) + d, -value));
                        triplets.push((2 * (k + 1) + d, 2 * k + p, -value));
                    }
                }
            }
        }
        let matrix = SymmetricMatrix::from_triplets(n, &triplets);
        let templates = TemplateMatrix::new(&matrix).expect("an even size");
        assert_eq!(templates.runs(), 3, "first node, interior nodes, last node");
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin()).collect();
        let (mut y, mut expected) = (vec![0.0; n], vec![0.0; n]);
        templates.mul_vec(&x, &mut y);
        matrix.mul_vec(&x, &mut expected);
        let mut swapped = vec![0.0; n];
        TemplateMatrix::swap_pairs(&x, &mut swapped);
        let mut by_chunks = vec![0.0; n];
        let mut node = 0;
        for (begin, end, count) in templates.chunks(2) {
            templates.mul_chunk((begin, end), &x, &swapped, &mut by_chunks[2 * node..2 * (node + count)]);
            node += count;
        }
        for ((a, b), c) in y.iter().zip(&expected).zip(&by_chunks) {
            assert!((a - b).abs() <= 1e-15 * b.abs().max(1.0), "{a} against {b}");
            assert_eq!(a, c);
        }
        assert!(TemplateMatrix::new(&SymmetricMatrix::from_triplets(1, &[(0, 0, 1.0)])).is_none());
    }
}
