//! A contact or loaded boundary along a chain of mesh edges: its segments, their local frames,
//! and their Gauss points (eq. 13's line integrals).
//!
//! A chain is ordered with the body on its left (counter-clockwise around the body, see
//! [`crate::fem::body_mesh::Mesh::boundary_chain`]). On segment `k` from node `a` to node `b`
//! the unit tangent is `t = (X_b - X_a)/L`, and the normal `n = (-t_y, t_x)` points into the
//! body, from the main body: the paper's bottom contact, traversed from left to right, has
//! `t = +x` and `n = +y`.

use crate::fem::element::GAUSS_2;

/// Where a Gauss point of a curve lies: its coordinates and its arc length from the chain's
/// first node (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvePoint {
    pub x: f64,
    pub y: f64,
    pub arc: f64,
}

/// One segment of a chain: its end nodes, length, frame and extent along the chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Mesh nodes at its start and end.
    pub nodes: [usize; 2],
    /// Length `L` (m).
    pub length: f64,
    /// Unit tangent `t`.
    pub tangent: [f64; 2],
    /// Unit normal `n`, into the body.
    pub normal: [f64; 2],
    /// Arc length of its start and end from the chain's first node (m).
    pub arc: [f64; 2],
    /// Coordinates of its start and end (m).
    pub ends: [[f64; 2]; 2],
}

impl Segment {
    /// The midpoint's coordinates (m).
    pub fn centre(&self) -> [f64; 2] {
        let [a, b] = self.ends;
        [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]
    }
}

/// A Gauss point of a segment: the segment's shape function values, weight and position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussPoint {
    /// `[N_a, N_b]` at the point.
    pub shape: [f64; 2],
    /// Gauss weight × Jacobian: `L/2` (m per unit thickness).
    pub weight: f64,
    pub position: CurvePoint,
}

/// The segments of the chain through `nodes` (at least two) at `coordinates`.
pub fn segments(nodes: &[usize], coordinates: &[[f64; 2]]) -> Vec<Segment> {
    let mut arc = 0.0;
    nodes
        .windows(2)
        .map(|pair| {
            let ([xa, ya], [xb, yb]) = (coordinates[pair[0]], coordinates[pair[1]]);
            let (dx, dy) = (xb - xa, yb - ya);
            let length = dx.hypot(dy);
            let tangent = [dx / length, dy / length];
            let start = arc;
            arc += length;
            Segment {
                nodes: [pair[0], pair[1]],
                length,
                tangent,
                normal: [-tangent[1], tangent[0]],
                arc: [start, arc],
                ends: [[xa, ya], [xb, yb]],
            }
        })
        .collect()
}

/// The shape functions `[N_a, N_b]` at the two Gauss points of a segment.
pub fn gauss_shapes() -> [[f64; 2]; 2] {
    GAUSS_2.map(|xi| [0.5 * (1.0 - xi), 0.5 * (1.0 + xi)])
}

/// A coordinate at a point of shape values `shape` between the ends' `a` and `b`:
/// `a + N_b (b - a)`.
pub fn interpolate(a: f64, b: f64, shape: [f64; 2]) -> f64 {
    a + shape[1] * (b - a)
}

impl Segment {
    /// The two-point Gauss rule on the segment; positions by [`interpolate`].
    pub fn gauss_points(&self, coordinates: &[[f64; 2]]) -> [GaussPoint; 2] {
        let ([xa, ya], [xb, yb]) = (coordinates[self.nodes[0]], coordinates[self.nodes[1]]);
        gauss_shapes().map(|shape| {
            let along = |a: f64, b: f64| interpolate(a, b, shape);
            GaussPoint {
                shape,
                weight: 0.5 * self.length,
                position: CurvePoint { x: along(xa, xb), y: along(ya, yb), arc: self.arc[0] + shape[1] * self.length },
            }
        })
    }
}
