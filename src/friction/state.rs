//! The state a contact point carries between steps.

use crate::friction::params::FrictionParams;

/// State of one contact (Gauss) point.
///
/// Conventions (MODEL.md): `f` is the traction the base exerts on the block; the normal `n`
/// points from the base into the block, so `f_n > 0` in compression; in 2D the tangential axis is
/// `x` and `f_t` is signed. The normal sliding ratio `R` is not stored: the subloading surface
/// passes through the current traction, so it is derived ([`ContactState::sliding_ratio`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactState {
    /// Tangential traction `f_t` (Pa), signed along `x`.
    pub traction_t: f64,
    /// Normal traction `f_n ≥ 0` (Pa); prescribed and held constant by every scene.
    pub traction_n: f64,
    /// Degree of structure `1/R*` (-), in `[1, μ_s/μ_k]`.
    pub structure: f64,
    /// Accumulated plastic slip `∫ Λ dt = ∫ |v̄ᵖ| dt` (m).
    pub plastic_slip: f64,
}

impl ContactState {
    /// The initial state: traction `f0` in `direction` (the sign the drive loads `f_t` in),
    /// structure `structure0`, no plastic slip. A point without normal traction carries none.
    pub fn initial(params: &FrictionParams, traction_n: f64, direction: f64) -> Self {
        let traction_t = if traction_n > 0.0 { params.f0 * direction.signum() } else { 0.0 };
        Self { traction_t, traction_n, structure: params.initial_structure(), plastic_slip: 0.0 }
    }

    /// Similarity ratio of the superloading surface, `R* = 1 / (1/R*)`.
    pub fn r_star(&self) -> f64 {
        1.0 / self.structure
    }

    /// Normal sliding ratio `R = |f_t| R* / (μ_k f_n)`: eq. (3) solved for `R`.
    /// A point without normal traction has `R = 0` (it carries no traction).
    /// The quotient is taken either way and then chosen, so that lanes of points compile to
    /// vector instructions ([`crate::friction::law::rates_on_branches`]).
    #[inline(always)]
    pub fn sliding_ratio(&self, params: &FrictionParams) -> f64 {
        let ratio = self.traction_t.abs() / (params.mu_k * self.traction_n * self.structure);
        if self.traction_n > 0.0 { ratio } else { 0.0 }
    }

    /// Friction coefficient of the current superloading surface, `μ_k / R*` (eq. 2).
    pub fn static_coefficient(&self, params: &FrictionParams) -> f64 {
        params.mu_k * self.structure
    }

    /// Tangential unit vector `t = f_t / |f_t|` along `x` (0 when there is no traction).
    pub fn direction(&self) -> f64 {
        if self.traction_t > 0.0 {
            1.0
        } else if self.traction_t < 0.0 {
            -1.0
        } else {
            0.0
        }
    }
}
