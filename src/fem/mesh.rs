//! A structured rectangle of bilinear quadrilaterals (paper Fig. 6: 10 × 1 elements).

use crate::fem::element::GAUSS_2;

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
    /// The x (m) of bottom element `k`'s contact point at the reference coordinate `xi` in
    /// `[-1, 1]` (a Gauss point of [`crate::fem::element::GAUSS_2`]).
    pub fn contact_point_x(&self, k: usize, xi: f64) -> f64 {
        (k as f64 + 0.5 * (1.0 + xi)) * self.dx()
    }

    /// The x (m) of every contact point from the left: two Gauss points per bottom element.
    pub fn contact_abscissae(&self) -> impl Iterator<Item = f64> + '_ {
        (0..self.nx).flat_map(move |k| GAUSS_2.map(|xi| self.contact_point_x(k, xi)))
    }

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
}
