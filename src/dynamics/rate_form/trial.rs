//! One trial step of the Runge–Kutta driver ([`super::driver`]): the buffers it fills and the
//! memory keeps between steps, so that no step allocates.

/// One trial step: the new state, its rate and `Λ` there, and the error. Its vectors are
/// buffers that the driver hands round ([`super::memory::RungeKutta::spares`]).
#[derive(Debug, Clone, Default)]
pub(super) struct Trial {
    pub(super) y: Vec<f64>,
    pub(super) rate: Vec<f64>,
    pub(super) lambda: Vec<f64>,
    /// Eq. (9)'s switching function per point at `y`, where the points are held on branches.
    pub(super) numerator: Vec<f64>,
    pub(super) error: f64,
}
