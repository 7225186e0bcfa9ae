//! The axisymmetric elements: a body of revolution about the y axis, meshed in its half-plane
//! `r = x ≥ 0`, `z = y`. The four-node quadrilateral (2 × 2 Gauss points) and the three-node
//! triangle (the interior three-point rule, exact for quadratics) carry, besides the in-plane
//! strains, the hoop strain `ε_θ = u_r / r`, and every integral over the body is weighted by
//! `2π r`: stiffness, mass and body force are those of the whole ring, so forces are in N, not
//! N per unit thickness (Zienkiewicz & Taylor, *The Finite Element Method*, vol. 1, ch. 5).
//!
//! Every point of integration lies inside its cell, so `r > 0` there even for a cell with an
//! edge on the axis, where `u_r = 0` is imposed by the assembly.

use nalgebra::{Matrix4, SMatrix, Vector2};

use crate::fem::element::{GAUSS_2, PlaneStrain};

/// Natural coordinates of the Q4 corners, counter-clockwise from the bottom left.
const CORNERS: [(f64, f64); 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];

/// Barycentric coordinates of the triangle's interior three-point rule (weights 1/3 each).
const TRIANGLE_POINTS: [[f64; 3]; 3] =
    [[2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0], [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0], [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0]];

/// `D` relating `(σ_rr, σ_zz, τ_rz, σ_θθ)` to `(ε_rr, ε_zz, γ_rz, ε_θθ)`: isotropic linear
/// elasticity with the hoop components.
pub fn elasticity(material: &PlaneStrain) -> Matrix4<f64> {
    let (e, nu) = (material.youngs_modulus, material.poisson_ratio);
    let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let (a, b, g) = (c * (1.0 - nu), c * nu, c * (1.0 - 2.0 * nu) / 2.0);
    Matrix4::new(a, b, 0.0, b, b, a, 0.0, b, 0.0, 0.0, g, 0.0, b, b, 0.0, a)
}

/// What one cell contributes to the ring: its stiffness (degrees of freedom
/// `(r₀, z₀, r₁, z₁, …)`) and `∫ N_a 2π r dA` per corner, the row sums of its consistent mass
/// per unit density (its lumped mass, and its body force per unit of `ρ g`).
pub struct Ring<const D: usize> {
    pub stiffness: SMatrix<f64, D, D>,
    pub volumes: Vec<f64>,
}

/// One point of integration: the shape functions, their derivatives in `(r, z)`, and
/// `2π r × weight × Jacobian`.
struct Point<const N: usize> {
    shape: [f64; N],
    gradient: [[f64; 2]; N],
    measure: f64,
}

/// Accumulates `Bᵀ D B 2π r dA` and `N_a 2π r dA` over `points`, with the hoop row
/// `ε_θ = Σ N_a u_r,a / r` (eq. of the axisymmetric strain, Zienkiewicz & Taylor 5.2).
fn ring<const N: usize, const D: usize>(material: &PlaneStrain, points: &[Point<N>], radius: &[f64; N]) -> Ring<D> {
    let d = elasticity(material);
    let mut stiffness = SMatrix::<f64, D, D>::zeros();
    let mut volumes = vec![0.0; N];
    for p in points {
        let r: f64 = (0..N).map(|a| p.shape[a] * radius[a]).sum();
        let mut b = SMatrix::<f64, 4, D>::zeros();
        for a in 0..N {
            let [dr, dz] = p.gradient[a];
            b[(0, 2 * a)] = dr;
            b[(1, 2 * a + 1)] = dz;
            b[(2, 2 * a)] = dz;
            b[(2, 2 * a + 1)] = dr;
            b[(3, 2 * a)] = p.shape[a] / r;
            volumes[a] += p.shape[a] * p.measure;
        }
        stiffness += b.transpose() * d * b * p.measure;
    }
    Ring { stiffness, volumes }
}

/// The bilinear quadrilateral of corners `coords` (`(r, z)`, counter-clockwise, absolute: the
/// radius enters the hoop strain and the weight).
pub fn quad(material: &PlaneStrain, coords: &[Vector2<f64>; 4]) -> Ring<8> {
    let mut points = Vec::with_capacity(4);
    for &xi in &GAUSS_2 {
        for &eta in &GAUSS_2 {
            let mut shape = [0.0; 4];
            let mut natural = [[0.0; 2]; 4];
            for (a, &(xa, ya)) in CORNERS.iter().enumerate() {
                shape[a] = 0.25 * (1.0 + xa * xi) * (1.0 + ya * eta);
                natural[a] = [0.25 * xa * (1.0 + ya * eta), 0.25 * ya * (1.0 + xa * xi)];
            }
            let mut jac = nalgebra::Matrix2::<f64>::zeros();
            for a in 0..4 {
                jac[(0, 0)] += natural[a][0] * coords[a].x;
                jac[(0, 1)] += natural[a][0] * coords[a].y;
                jac[(1, 0)] += natural[a][1] * coords[a].x;
                jac[(1, 1)] += natural[a][1] * coords[a].y;
            }
            let det = jac.determinant();
            let inv = jac.try_inverse().expect("a non-degenerate element");
            let gradient = natural
                .map(|[dxi, deta]| [inv[(0, 0)] * dxi + inv[(0, 1)] * deta, inv[(1, 0)] * dxi + inv[(1, 1)] * deta]);
            let r: f64 = (0..4).map(|a| shape[a] * coords[a].x).sum();
            points.push(Point { shape, gradient, measure: 2.0 * std::f64::consts::PI * r * det });
        }
    }
    ring(material, &points, &coords.map(|c| c.x))
}

/// The linear triangle of corners `coords` (`(r, z)`, counter-clockwise, absolute), integrated
/// by the interior three-point rule: exact for the mass and body force (`N_a r` is quadratic),
/// and the usual rule for the hoop terms `N_a N_b / r`.
pub fn triangle(material: &PlaneStrain, coords: &[Vector2<f64>; 3]) -> Ring<6> {
    let twice_area = crate::fem::element::signed_double_area(coords);
    let gradient: [[f64; 2]; 3] = std::array::from_fn(|a| {
        let (j, k) = ((a + 1) % 3, (a + 2) % 3);
        [(coords[j].y - coords[k].y) / twice_area, (coords[k].x - coords[j].x) / twice_area]
    });
    let points: Vec<Point<3>> = TRIANGLE_POINTS
        .iter()
        .map(|&shape| {
            let r: f64 = (0..3).map(|a| shape[a] * coords[a].x).sum();
            Point { shape, gradient, measure: 2.0 * std::f64::consts::PI * r * twice_area / 6.0 }
        })
        .collect();
    ring(material, &points, &coords.map(|c| c.x))
}

#[cfg(test)]
mod tests {
    use super::*;

    const STEEL: PlaneStrain = PlaneStrain { youngs_modulus: 200e9, poisson_ratio: 0.3 };

    /// A ring's volume is `2π r̄ A` (Pappus), and a rigid translation along the axis strains
    /// nothing; a radial one strains the hoop, so it does store energy.
    #[test]
    fn a_ring_has_pappus_volume_and_no_strain_under_axial_translation() {
        let quad_corners =
            [Vector2::new(1.0, 0.0), Vector2::new(1.5, 0.0), Vector2::new(1.5, 0.4), Vector2::new(1.0, 0.4)];
        let q = quad(&STEEL, &quad_corners);
        let volume: f64 = q.volumes.iter().sum();
        let pappus = 2.0 * std::f64::consts::PI * 1.25 * 0.5 * 0.4;
        assert!((volume - pappus).abs() < 1e-14 * pappus, "{volume} against {pappus}");
        let triangle_corners = [Vector2::new(0.0, 0.0), Vector2::new(0.6, 0.0), Vector2::new(0.0, 0.9)];
        let t = triangle(&STEEL, &triangle_corners);
        let volume: f64 = t.volumes.iter().sum();
        let pappus = 2.0 * std::f64::consts::PI * 0.2 * 0.5 * 0.6 * 0.9;
        assert!((volume - pappus).abs() < 1e-14 * pappus, "{volume} against {pappus}");
        let axial = SMatrix::<f64, 8, 1>::from_fn(|i, _| if i % 2 == 1 { 1.0 } else { 0.0 });
        assert!((q.stiffness * axial).norm() < 1e-6 * q.stiffness.norm());
        let radial = SMatrix::<f64, 8, 1>::from_fn(|i, _| if i % 2 == 0 { 1.0 } else { 0.0 });
        assert!((radial.transpose() * q.stiffness * radial)[(0, 0)] > 0.0);
    }
}
