//! The linear part of the equation of motion (14): lumped mass, stiffness, external load rate.

use crate::linalg::sparse::SymmetricMatrix;

/// `M a + K u = f⁰(t) + f_c`, with `M` diagonal (lumped) and `f⁰` growing linearly in time.
/// Degrees of freedom with prescribed zero displacement (the fixed top) are not stored.
#[derive(Debug, Clone)]
pub struct LinearBody {
    /// Lumped mass per degree of freedom (kg per unit thickness, or kg/m² per unit area).
    pub mass: Vec<f64>,
    /// Stiffness `K` (N/m per unit thickness, or Pa/m per unit area).
    pub stiffness: SymmetricMatrix,
    /// External load rate `ḟ⁰`, constant in time; the load is `f⁰(t) = ḟ⁰ t` beyond the initial
    /// equilibrium.
    pub load_rate: Vec<f64>,
}

impl LinearBody {
    /// Number of degrees of freedom.
    pub fn dofs(&self) -> usize {
        self.mass.len()
    }

    /// Kinetic energy `½ vᵀ M v`.
    pub fn kinetic_energy(&self, velocity: &[f64]) -> f64 {
        0.5 * self.mass.iter().zip(velocity).map(|(m, v)| m * v * v).sum::<f64>()
    }

    /// Strain energy `½ uᵀ K u` of the displacement from the initial equilibrium.
    pub fn strain_energy(&self, displacement: &[f64]) -> f64 {
        0.5 * self.stiffness.quadratic_form(displacement)
    }
}
