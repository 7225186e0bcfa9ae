//! How the implicit solves of a step are set up: Wilson's `θ`, Newton's tolerance and
//! iteration limit, the energy guard, and which linear solver Newton's corrections use.

/// Settings of the implicit solves (Wilson's method, SDIRK's stages) and the energy guard.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Wilson's `θ` (≥ 1.37 for unconditional stability on linear problems; 1.4 by default).
    pub theta: f64,
    /// Newton converges when the displacement correction is below `tolerance` times the larger
    /// of the step's displacement and `velocity_scale × τ`.
    pub tolerance: f64,
    /// A velocity typical of the problem (the drive), m/s.
    pub velocity_scale: f64,
    /// Newton iterations allowed per step.
    pub max_iterations: usize,
    /// With `Some(share)`, the energy balance is kept from the start and a step after which the
    /// integrator has created more than `share` of the work put in (or of the contact's
    /// kinetic-strength energy or the body's kinetic energy at the drive's speed, early on) fails with
    /// [`StepError::EnergyCreated`].
    pub energy_tolerance: Option<f64>,
    /// How each Newton iteration solves for its correction.
    pub linear_solver: LinearSolver,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            theta: 1.4,
            tolerance: 1e-10,
            velocity_scale: 1e-3,
            max_iterations: 40,
            energy_tolerance: None,
            linear_solver: LinearSolver::Full,
        }
    }
}

/// How each Newton iteration solves for its correction. Both give the same steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinearSolver {
    /// The whole system `6/τ² M + K + K_c`, refactored (sparse Cholesky) whenever a contact
    /// tangent changes: cheapest for small bodies, and for steps that change every time.
    Full,
    /// Condensed onto the contact ([`crate::dynamics::condensed`]): the body factored once per `τ`, a
    /// dense system of the contact's unknowns per iteration. For large bodies at a fixed step.
    Condensed,
}

/// Bodies with at least this many unknowns are condensed onto their contact when the step is
/// fixed (see [`LinearSolver`]); the paper's 10 × 1 mesh (22 unknowns) is not.
pub const CONDENSE_FROM_DOFS: usize = 1000;

/// ... unless the contact has more unknowns than this: its dense matrices (`8 k²` bytes each)
/// and their LU (`2k³/3` operations) would outgrow the sparse operator of a long thin body.
pub const CONDENSE_UP_TO_CONTACT_DOFS: usize = 2048;

/// Whether a fixed-step body of `dofs` unknowns with `contact_dofs` at its contact is better
/// condensed ([`LinearSolver::Condensed`]).
pub fn condensation_pays(dofs: usize, contact_dofs: usize) -> bool {
    dofs >= CONDENSE_FROM_DOFS && contact_dofs <= CONDENSE_UP_TO_CONTACT_DOFS
}
