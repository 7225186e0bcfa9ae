//! A structured rectangle of bilinear quadrilaterals (paper Fig. 6: 10 × 1 elements).

/// `nx × ny` rectangular elements over `[0, W] × [0, H]`; `y = 0` is the contact surface and
/// `y = H` the fixed top.
///
/// Nodes are numbered row by row from the bottom left: node `(i, j)` has id `j (nx+1) + i`.
/// Only nodes below the top carry degrees of freedom: node id `k < (nx+1) ny` owns
/// `2k` (x) and `2k + 1` (y).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StructuredMesh {
    pub width: f64,
    pub height: f64,
    pub nx: usize,
    pub ny: usize,
}

impl StructuredMesh {
    /// Element size along x (m).
    pub fn dx(&self) -> f64 {
        self.width / self.nx as f64
    }

    /// Element size along y (m).
    pub fn dy(&self) -> f64 {
        self.height / self.ny as f64
    }

    /// Number of nodes, the fixed top row included.
    pub fn nodes(&self) -> usize {
        (self.nx + 1) * (self.ny + 1)
    }

    /// Node id of column `i`, row `j`.
    pub fn node(&self, i: usize, j: usize) -> usize {
        j * (self.nx + 1) + i
    }

    /// Coordinates of node `id`.
    pub fn position(&self, id: usize) -> (f64, f64) {
        let i = id % (self.nx + 1);
        let j = id / (self.nx + 1);
        (i as f64 * self.dx(), j as f64 * self.dy())
    }

    /// Number of free degrees of freedom (all but the top row).
    pub fn dofs(&self) -> usize {
        2 * (self.nx + 1) * self.ny
    }

    /// The x and y degrees of freedom of node `id`, or `None` on the fixed top.
    pub fn node_dofs(&self, id: usize) -> Option<[usize; 2]> {
        if id < (self.nx + 1) * self.ny { Some([2 * id, 2 * id + 1]) } else { None }
    }

    /// Corner nodes of element `(i, j)`, counter-clockwise from the bottom left.
    pub fn element_nodes(&self, i: usize, j: usize) -> [usize; 4] {
        [self.node(i, j), self.node(i + 1, j), self.node(i + 1, j + 1), self.node(i, j + 1)]
    }

    /// Contact-surface node `i` (bottom row, from 0 at the left).
    pub fn surface_node(&self, i: usize) -> usize {
        self.node(i, 0)
    }

    /// A nested-dissection order of the free degrees of freedom (`order[new] = old`): the free
    /// nodes' grid is split across its longer side by one grid line, the two halves are
    /// ordered first (recursively) and the line last. A Q4 element couples only neighbouring
    /// grid lines, so each line separates its halves, and a Cholesky factor in this order fills
    /// in like `n log n` (George, 1973); on long strips faer's AMD leaves several times more.
    pub fn nested_dissection(&self) -> Vec<usize> {
        let mut nodes = Vec::with_capacity((self.nx + 1) * self.ny);
        self.dissect(0..self.nx + 1, 0..self.ny, &mut nodes);
        nodes.iter().flat_map(|&id| [2 * id, 2 * id + 1]).collect()
    }

    fn dissect(&self, columns: std::ops::Range<usize>, rows: std::ops::Range<usize>, order: &mut Vec<usize>) {
        const LEAF: usize = 8;
        let (width, height) = (columns.len(), rows.len());
        if width == 0 || height == 0 {
            return;
        }
        if width <= LEAF && height <= LEAF {
            for j in rows {
                for i in columns.clone() {
                    order.push(self.node(i, j));
                }
            }
        } else if width >= height {
            let middle = columns.start + width / 2;
            self.dissect(columns.start..middle, rows.clone(), order);
            self.dissect(middle + 1..columns.end, rows.clone(), order);
            order.extend(rows.map(|j| self.node(middle, j)));
        } else {
            let middle = rows.start + height / 2;
            self.dissect(columns.clone(), rows.start..middle, order);
            self.dissect(columns.clone(), middle + 1..rows.end, order);
            order.extend(columns.map(|i| self.node(i, middle)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The nested-dissection order lists every free degree of freedom exactly once, the two of
    /// a node together, and ends with the first separator: the middle grid line of the longer
    /// side.
    #[test]
    fn nested_dissection_is_a_permutation_ending_in_the_first_separator() {
        for (nx, ny) in [(1, 1), (10, 1), (13, 7), (40, 4), (7, 30), (100, 10)] {
            let mesh = StructuredMesh { width: 1.0, height: 1.0, nx, ny };
            let order = mesh.nested_dissection();
            let mut sorted = order.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..mesh.dofs()).collect::<Vec<_>>(), "{nx} × {ny}");
            assert!(order.chunks(2).all(|pair| pair[1] == pair[0] + 1 && pair[0] % 2 == 0));
            let (width, height) = (nx + 1, ny);
            if width > 8 || height > 8 {
                let separator: Vec<usize> = if width >= height {
                    (0..height).map(|j| mesh.node(width / 2, j)).collect()
                } else {
                    (0..width).map(|i| mesh.node(i, height / 2)).collect()
                };
                let tail: Vec<usize> =
                    order[order.len() - 2 * separator.len()..].iter().step_by(2).map(|d| d / 2).collect();
                assert_eq!(tail, separator, "{nx} × {ny}");
            }
        }
    }
}
