//! The shape of a cell from its corners: counter-clockwise, clockwise, or unusable (a zero
//! Jacobian at a corner, or one whose sign changes from corner to corner).

/// The sine of the angle between a corner's two edges below which the corner's Jacobian counts
/// as zero (the corner is flat, or two of its nodes coincide).
pub(super) const FLAT_SINE: f64 = 1e-12;

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Shape {
    CounterClockwise,
    Clockwise,
    /// A zero Jacobian at corner `corner` (an index into the cell's nodes).
    Flat {
        corner: usize,
    },
    /// The Jacobian is positive at some corners and negative at others: a non-convex or
    /// self-crossing quadrilateral.
    Folded,
}

/// The shape of the linear triangle or bilinear quadrilateral with corners `corners` (node
/// indices into `nodes`, in order around it). At corner k the Jacobian of the element map has
/// the sign of the cross product of the edges to the next and to the previous corner (for the
/// bilinear map on [-1, 1]², det J at a corner is a quarter of it); det J is affine in each
/// reference coordinate, so positive at every corner means positive everywhere.
pub(super) fn shape(corners: &[usize], nodes: &[[f64; 2]]) -> Shape {
    let n = corners.len();
    let mut positive = 0;
    for k in 0..n {
        let at = nodes[corners[k]];
        let next = nodes[corners[(k + 1) % n]];
        let previous = nodes[corners[(k + n - 1) % n]];
        let sine = unit_cross([next[0] - at[0], next[1] - at[1]], [previous[0] - at[0], previous[1] - at[1]]);
        // A NaN sine (a zero-length edge, or coordinates too far apart to subtract) is flat too.
        if sine.is_nan() || sine.abs() <= FLAT_SINE {
            return Shape::Flat { corner: k };
        }
        positive += usize::from(sine > 0.0);
    }
    match positive {
        p if p == n => Shape::CounterClockwise,
        0 => Shape::Clockwise,
        _ => Shape::Folded,
    }
}

/// The sine of the angle from `a` to `b`: the cross product of the two unit vectors (each
/// normalised first, so that no product overflows).
fn unit_cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (la, lb) = (a[0].hypot(a[1]), b[0].hypot(b[1]));
    (a[0] / la) * (b[1] / lb) - (a[1] / la) * (b[0] / lb)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

    #[test]
    fn a_square_is_counter_clockwise_one_way_and_clockwise_the_other() {
        assert_eq!(shape(&[0, 1, 2, 3], &SQUARE), Shape::CounterClockwise);
        assert_eq!(shape(&[0, 3, 2, 1], &SQUARE), Shape::Clockwise);
        assert_eq!(shape(&[0, 1, 2], &SQUARE), Shape::CounterClockwise);
        assert_eq!(shape(&[2, 1, 0], &SQUARE), Shape::Clockwise);
    }

    #[test]
    fn crossed_dented_and_flat_cells_are_found() {
        // Self-crossing (a bow tie): the corners alternate in sign.
        assert_eq!(shape(&[0, 1, 3, 2], &SQUARE), Shape::Folded);
        // A dart: the corner at (0.2, 0.2) points inward, so its Jacobian is negative.
        let dart = [[0.0, 0.0], [1.0, 0.0], [0.2, 0.2], [0.0, 1.0]];
        assert_eq!(shape(&[0, 1, 2, 3], &dart), Shape::Folded);
        // Three collinear nodes: a triangle with no area, a quad with a straight corner.
        let line = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.0, 1.0]];
        assert_eq!(shape(&[0, 1, 2], &line), Shape::Flat { corner: 0 });
        assert_eq!(shape(&[0, 1, 2, 3], &line), Shape::Flat { corner: 1 });
        // Two coincident corners, and coordinates too far apart to subtract.
        assert_eq!(shape(&[0, 0, 2], &SQUARE), Shape::Flat { corner: 0 });
        let huge = [[-1.7e308, 0.0], [1.7e308, 0.0], [0.0, 1.0]];
        assert!(matches!(shape(&[0, 1, 2], &huge), Shape::Flat { .. }));
    }
}
