//! Time integration of a linear elastic body with a frictional contact boundary (paper §2.2).

pub mod adaptive;
pub mod body;
pub mod central;
pub mod condensed;
pub mod contact;
mod newton;
mod operator;
pub mod runge_kutta;
pub mod sdirk;
pub mod sparse;
pub mod templates;
pub mod wilson;

pub use adaptive::{AdaptiveError, StepControl};
pub use body::LinearBody;
pub use contact::{ContactBoundary, ContactPoint};
pub use wilson::{Dynamics, EnergyLedger, LinearSolver, State, StepError, WilsonSettings, condensation_pays};
