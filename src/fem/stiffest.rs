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
pub fn cell_frequency(coords: &[Vector2<f64>], material: &PlaneStrain, density: f64, springs: &[EdgeSpring]) -> f64 {
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
}
