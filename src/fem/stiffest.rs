//! An upper bound on the highest angular frequency `ω_max` of a body of lumped mass with its
//! contact's elastic springs, from its cells alone, before anything is assembled.
//!
//! The element eigenvalue inequality: where `K = Σ K_e` and `M = Σ M_e` with every `M_e`
//! positive definite, `λ_max(K, M) ≤ max_e λ_max(K_e, M_e)` (Irons 1970; Hughes, *The Finite
//! Element Method*, 1987, §9.1). Each cell here is its stiffness, the consistent springs of the
//! contact segments along its edges (`α ∫ Ñᵀ Ñ ds` along the spring's direction, as the contact
//! integrates them) and its share of the lumped mass; `ω_max ≤ max over cells of √λ_max`.
//! Constraints only lower `ω_max`, so the bound holds for any boundary conditions.

use nalgebra::{DMatrix, Vector2};

use crate::fem::element::{PlaneStrain, shape_integrals, signed_double_area, stiffness, triangle_stiffness};

/// An elastic spring of a contact segment along a cell's edge: between the cell's corners
/// `nodes` (indices in its corner list), of modulus `modulus` (Pa/m), acting along the unit
/// vector `direction`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeSpring {
    pub nodes: [usize; 2],
    pub direction: Vector2<f64>,
    pub modulus: f64,
}

/// `√λ_max` of one cell (rad/s): corners `coords` counter-clockwise (three or four), of
/// `material` and `density`, with `springs` along its edges.
/// `NaN` for a cell this bound cannot read: not convex and counter-clockwise, or a material,
/// density or spring that is not finite and positive (a case refused later for it).
pub fn cell_frequency(coords: &[Vector2<f64>], material: &PlaneStrain, density: f64, springs: &[EdgeSpring]) -> f64 {
    let positive = |x: f64| x.is_finite() && x > 0.0;
    let readable = convex(coords)
        && positive(material.youngs_modulus)
        && (0.0..0.5).contains(&material.poisson_ratio)
        && positive(density)
        && springs
            .iter()
            .all(|s| s.modulus.is_finite() && s.modulus >= 0.0 && s.nodes.iter().all(|&n| n < coords.len()));
    if !readable {
        return f64::NAN;
    }
    let (mut k, masses) = match coords {
        [a, b, c] => {
            let area = 0.5 * signed_double_area(coords);
            (
                DMatrix::from_column_slice(6, 6, triangle_stiffness(material, &[*a, *b, *c]).as_slice()),
                vec![density * area / 3.0; 3],
            )
        }
        [a, b, c, d] => {
            let corners = [*a, *b, *c, *d];
            let masses = shape_integrals(&corners).iter().map(|s| density * s).collect();
            (DMatrix::from_column_slice(8, 8, stiffness(material, &corners).as_slice()), masses)
        }
        _ => return f64::NAN,
    };
    for spring in springs {
        let [a, b] = spring.nodes;
        let length = (coords[b] - coords[a]).norm();
        // ∫ N_i N_j ds over a linear segment: L/3 on the diagonal, L/6 off it.
        for (i, j, share) in [(a, a, 2.0), (b, b, 2.0), (a, b, 1.0), (b, a, 1.0)] {
            for (p, q) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                k[(2 * i + p, 2 * j + q)] +=
                    spring.modulus * length * share / 6.0 * spring.direction[p] * spring.direction[q];
            }
        }
    }
    let scale: Vec<f64> = masses.iter().flat_map(|m| [1.0 / m.sqrt(); 2]).collect();
    let n = scale.len();
    let scaled = DMatrix::from_fn(n, n, |i, j| scale[i] * k[(i, j)] * scale[j]);
    scaled.symmetric_eigenvalues().iter().copied().fold(0.0, f64::max).sqrt()
}

/// The largest of the cells' frequencies: the bound, or `NaN` if one cell could not be read.
pub fn largest(frequencies: impl IntoIterator<Item = f64>) -> f64 {
    frequencies.into_iter().fold(0.0, |a: f64, b| if a.is_nan() || b.is_nan() { f64::NAN } else { a.max(b) })
}

/// Whether every turn along `coords` is to the left: a strictly convex, counter-clockwise cell
/// of three or four finite corners.
fn convex(coords: &[Vector2<f64>]) -> bool {
    let n = coords.len();
    (3..=4).contains(&n)
        && coords.iter().all(|c| c.x.is_finite() && c.y.is_finite())
        && (0..n).all(|a| {
            let (p, q, r) = (coords[a], coords[(a + 1) % n], coords[(a + 2) % n]);
            (q - p).perp(&(r - q)) > 0.0
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cell_on_springs_alone_rings_at_the_springs_frequency() {
        // With E → 0 a square cell of side h on a tangential spring along its bottom edge is two
        // masses ρh²/4 joined by the segment's consistent springs: λ_max = α (L/6)(2 + 1) / m.
        let h = 0.5;
        let coords = [Vector2::new(0.0, 0.0), Vector2::new(h, 0.0), Vector2::new(h, h), Vector2::new(0.0, h)];
        let material = PlaneStrain { youngs_modulus: 1e-12, poisson_ratio: 0.0 };
        let spring = EdgeSpring { nodes: [0, 1], direction: Vector2::new(1.0, 0.0), modulus: 1e6 };
        let omega = cell_frequency(&coords, &material, 1000.0, &[spring]);
        let expected = (1e6 * h * 3.0 / 6.0 / (1000.0 * h * h / 4.0)).sqrt();
        assert!((omega / expected - 1.0).abs() < 1e-9, "{omega} against {expected}");
    }

    #[test]
    fn a_cell_it_cannot_read_gives_nan_not_a_panic() {
        let square = [Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(0.0, 1.0)];
        let flat = [Vector2::new(0.0, 0.0), Vector2::new(0.0, 0.0), Vector2::new(0.0, 1.0), Vector2::new(0.0, 1.0)];
        let material = PlaneStrain { youngs_modulus: 1e3, poisson_ratio: 0.0 };
        assert!(cell_frequency(&flat, &material, 1000.0, &[]).is_nan());
        assert!(cell_frequency(&square, &material, 0.0, &[]).is_nan());
        assert!(cell_frequency(&square, &PlaneStrain { youngs_modulus: -1.0, poisson_ratio: 0.0 }, 1.0, &[]).is_nan());
        assert!(cell_frequency(&square, &material, 1000.0, &[]).is_finite());
    }
}
