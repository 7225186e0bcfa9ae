//! The Runge–Kutta methods' memory between steps ([`super::driver`]), as data that a
//! checkpoint keeps.

use crate::dynamics::rate_form::sdirk4::Sdirk4;
use crate::dynamics::rate_form::tsit5::Tsit5;

/// The integrator's memory between steps: the state as one vector, its rate (the next step's
/// first stage), and every point's `Λ` there.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct RungeKutta {
    /// Step and time of the state `y` describes; another means [`crate::dynamics::System::state`] was changed
    /// from outside, and `y` is rebuilt.
    pub(super) at: (u64, f64),
    pub(super) y: Vec<f64>,
    pub(super) rate: Vec<f64>,
    pub(super) lambda: Vec<f64>,
    /// The branch of eq. (6) each point is held on over the next step (`true`: loading), for
    /// Tsitouras' pair; empty for SDIRK4, which switches by eq. (9) at every evaluation.
    pub(super) branches: Vec<bool>,
    /// Eq. (9)'s switching function at `y` per point (NaN where it does not apply), with
    /// `branches`.
    pub(super) numerator: Vec<f64>,
    /// Physical scale of each component, added to its size in the error measure.
    pub(super) scale: Vec<f64>,
    pub(super) pair: Pair,
    /// Buffers of trial steps, kept so that no step allocates (not state).
    #[serde(skip)]
    pub(super) spares: Vec<super::trial::Trial>,
}

/// A method with its workspace. One per run, so the size of the unboxed Tsitouras variant (the
/// default's, read on every step) costs nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub(super) enum Pair {
    Tsit5(Tsit5),
    Sdirk4(Box<Sdirk4>),
}
