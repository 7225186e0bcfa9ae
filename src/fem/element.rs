//! The plane-strain elements: the four-node isoparametric quadrilateral (Q4) with 2 × 2 Gauss
//! integration, and the three-node constant-strain triangle (T3); their lumped masses.

use nalgebra::{Matrix3, SMatrix, Vector2};

/// Gauss points of the 2-point rule on `[-1, 1]`, weights 1.
pub const GAUSS_2: [f64; 2] = [-0.577_350_269_189_625_8, 0.577_350_269_189_625_8];

/// Natural coordinates of the corners, counter-clockwise from the bottom left.
const CORNERS: [(f64, f64); 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];

/// Isotropic linear elasticity in plane strain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneStrain {
    /// Young's modulus `E` (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio `ν`.
    pub poisson_ratio: f64,
}

impl PlaneStrain {
    /// Shear modulus `G = E / 2(1+ν)`.
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// `D` relating `(σ_xx, σ_yy, τ_xy)` to `(ε_xx, ε_yy, γ_xy)`.
    pub fn elasticity(&self) -> Matrix3<f64> {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
        Matrix3::new(c * (1.0 - nu), c * nu, 0.0, c * nu, c * (1.0 - nu), 0.0, 0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0)
    }
}

/// Element stiffness `K_e = Σ Bᵀ D B det J` (per unit thickness) for corners `coords`
/// (counter-clockwise), degrees of freedom ordered `(x₀, y₀, x₁, y₁, …)`.
pub fn stiffness(material: &PlaneStrain, coords: &[Vector2<f64>; 4]) -> SMatrix<f64, 8, 8> {
    let d = material.elasticity();
    let mut k = SMatrix::<f64, 8, 8>::zeros();
    for &xi in &GAUSS_2 {
        for &eta in &GAUSS_2 {
            // dN/dξ, dN/dη at the Gauss point.
            let mut dn = [[0.0; 2]; 4];
            for (a, &(xa, ya)) in CORNERS.iter().enumerate() {
                dn[a] = [0.25 * xa * (1.0 + ya * eta), 0.25 * ya * (1.0 + xa * xi)];
            }
            let mut jac = nalgebra::Matrix2::<f64>::zeros();
            for a in 0..4 {
                jac[(0, 0)] += dn[a][0] * coords[a].x;
                jac[(0, 1)] += dn[a][0] * coords[a].y;
                jac[(1, 0)] += dn[a][1] * coords[a].x;
                jac[(1, 1)] += dn[a][1] * coords[a].y;
            }
            let det = jac.determinant();
            let inv = jac.try_inverse().expect("a non-degenerate element");
            let mut b = SMatrix::<f64, 3, 8>::zeros();
            for a in 0..4 {
                let dx = inv[(0, 0)] * dn[a][0] + inv[(0, 1)] * dn[a][1];
                let dy = inv[(1, 0)] * dn[a][0] + inv[(1, 1)] * dn[a][1];
                b[(0, 2 * a)] = dx;
                b[(1, 2 * a + 1)] = dy;
                b[(2, 2 * a)] = dy;
                b[(2, 2 * a + 1)] = dx;
            }
            k += b.transpose() * d * b * det;
        }
    }
    k
}

/// Element stiffness of the constant-strain triangle (per unit thickness) for corners
/// `coords` (counter-clockwise), degrees of freedom ordered `(x₀, y₀, x₁, y₁, x₂, y₂)`:
/// `K_e = Bᵀ D B A` with the constant `B` of the linear shape functions.
pub fn triangle_stiffness(material: &PlaneStrain, coords: &[Vector2<f64>; 3]) -> SMatrix<f64, 6, 6> {
    let twice_area = signed_double_area(coords);
    let mut b = SMatrix::<f64, 3, 6>::zeros();
    for a in 0..3 {
        let (j, k) = ((a + 1) % 3, (a + 2) % 3);
        // ∂N_a/∂x = (y_j - y_k)/2A, ∂N_a/∂y = (x_k - x_j)/2A.
        let dx = (coords[j].y - coords[k].y) / twice_area;
        let dy = (coords[k].x - coords[j].x) / twice_area;
        b[(0, 2 * a)] = dx;
        b[(1, 2 * a + 1)] = dy;
        b[(2, 2 * a)] = dy;
        b[(2, 2 * a + 1)] = dx;
    }
    b.transpose() * material.elasticity() * b * (0.5 * twice_area)
}

/// Twice the signed area of a polygon (shoelace formula): positive when counter-clockwise.
pub fn signed_double_area(coords: &[Vector2<f64>]) -> f64 {
    let n = coords.len();
    (0..n).map(|a| coords[a].x * coords[(a + 1) % n].y - coords[(a + 1) % n].x * coords[a].y).sum()
}

/// Lumped mass per corner node of a cell of `area` and `corners` nodes: `ρ A / corners`. For a
/// triangle and a parallelogram this is the row sum of the consistent mass matrix.
pub fn lumped_mass(density: f64, area: f64, corners: usize) -> f64 {
    density / corners as f64 * area
}

/// `∫ N_a dA` for each corner of the bilinear quadrilateral `coords` (counter-clockwise), by
/// the 2 × 2 Gauss rule, exact here (`N_a det J` is quadratic in each natural coordinate): the
/// row sums of its consistent mass per unit density, each corner's share of a body force. A
/// parallelogram's are `A/4` each, its lumped mass.
pub fn shape_integrals(coords: &[Vector2<f64>; 4]) -> [f64; 4] {
    let mut integrals = [0.0; 4];
    for &xi in &GAUSS_2 {
        for &eta in &GAUSS_2 {
            let mut jac = nalgebra::Matrix2::<f64>::zeros();
            for (a, &(xa, ya)) in CORNERS.iter().enumerate() {
                let (dxi, deta) = (0.25 * xa * (1.0 + ya * eta), 0.25 * ya * (1.0 + xa * xi));
                jac += nalgebra::Matrix2::new(
                    dxi * coords[a].x,
                    dxi * coords[a].y,
                    deta * coords[a].x,
                    deta * coords[a].y,
                );
            }
            let det = jac.determinant();
            for (a, &(xa, ya)) in CORNERS.iter().enumerate() {
                integrals[a] += 0.25 * (1.0 + xa * xi) * (1.0 + ya * eta) * det;
            }
        }
    }
    integrals
}
