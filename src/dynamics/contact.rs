//! The contact force boundary `S_c`: Gauss points that carry friction states (paper §2.2).

use crate::friction::FrictionParams;

/// One integration point of the contact boundary. Its relative tangential displacement is
/// `ū = Σ_a N_a u[dof_a] - u_base` (eq. 12 with the shape functions `Ñ` of eq. 13), and it
/// contributes `weight · Ñᵀ f_t` to the nodal forces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// Tangential degrees of freedom of the body that the point interpolates.
    pub dofs: [usize; 2],
    /// Shape function values at the point (the second is 0 for a single-node point).
    pub shape: [f64; 2],
    /// Integration weight: Gauss weight × Jacobian (m per unit thickness), or 1 per unit area.
    pub weight: f64,
    /// Position along the surface (m), for output.
    pub x: f64,
}

impl ContactPoint {
    /// A point that follows a single degree of freedom with unit weight (per unit area).
    pub fn single(dof: usize) -> Self {
        Self { dofs: [dof, dof], shape: [1.0, 0.0], weight: 1.0, x: 0.0 }
    }

    /// `Σ_a N_a field[dof_a]`.
    pub fn interpolate(&self, field: &[f64]) -> f64 {
        self.shape[0] * field[self.dofs[0]] + self.shape[1] * field[self.dofs[1]]
    }

    /// `forces += scale · Ñᵀ`.
    pub fn scatter(&self, scale: f64, forces: &mut [f64]) {
        forces[self.dofs[0]] += scale * self.shape[0];
        forces[self.dofs[1]] += scale * self.shape[1];
    }
}

/// The frictional boundary: its law, its points, and the base it slides against.
#[derive(Debug, Clone)]
pub struct ContactBoundary {
    pub params: FrictionParams,
    pub points: Vec<ContactPoint>,
    /// Normal traction `f_n ≥ 0` at each point (Pa), held constant.
    pub traction_n: Vec<f64>,
    /// Velocity of the base (main body) along `x` (m/s), reached after `base_ramp`.
    pub base_velocity: f64,
    /// Time over which the base accelerates smoothly from rest (s); 0 starts it impulsively.
    pub base_ramp: f64,
    /// Direction (±1) in which the drive loads `f_t`: sets the sign of the initial traction `f0`.
    pub loading_direction: f64,
}

impl ContactBoundary {
    /// Base velocity at `t`: `v s³ (10 - 15 s + 6 s²)`, `s = t/T`, during the ramp `T`, then
    /// `v`. Acceleration and jerk are continuous and vanish at both ends of the ramp, so the
    /// start excites the stiff contact modes as little as a polynomial ramp can.
    pub fn base_velocity_at(&self, t: f64) -> f64 {
        let ramp = self.base_ramp;
        if t >= ramp {
            self.base_velocity
        } else {
            let s = t / ramp;
            self.base_velocity * s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)
        }
    }

    /// Base displacement at `t`, the integral of [`Self::base_velocity_at`].
    pub fn base_displacement_at(&self, t: f64) -> f64 {
        let ramp = self.base_ramp;
        if t >= ramp {
            self.base_velocity * (t - 0.5 * ramp)
        } else {
            let s = t / ramp;
            self.base_velocity * ramp * s * s * s * s * (2.5 - 3.0 * s + s * s)
        }
    }
}
