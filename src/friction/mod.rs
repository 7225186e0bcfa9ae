//! The super/subloading surface friction model (paper §2.1, MODEL.md): no I/O, no scene.
//!
//! * [`params`]: material constants (Table 1) and which `R*` rule is used.
//! * [`state`]: what a contact point carries between steps.
//! * [`law`]: the rate form, eqs. (1)-(9).
//! * [`ln`]: the logarithm of `R` in eqs. (4)-(5), several points at once.
//! * [`update`]: the implicit step a solver calls, with its consistent tangent (held or evolving
//!   normal traction).
//! * [`expint`]: the exponential integral that makes the `R` rule exact.

pub mod expint;
pub mod law;
pub mod ln;
pub mod params;
pub mod state;
pub mod update;

pub use params::{FrictionParams, RStarLaw};
pub use state::ContactState;
pub use update::{FrictionError, Restart, Update, update, update_evolving, update_from, update_with};
