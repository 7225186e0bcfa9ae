//! Time integration of a linear elastic body with a frictional contact boundary (paper §2.2).
//!
//! The assembled model is a [`System`] (body, contact, [`State`], energy ledger). Every method
//! implements [`Integrator`]; [`Method`] holds the rules of which one a case gets and builds
//! it through [`Stepping`].

pub mod body;
pub mod central;
pub mod condensed;
pub mod contact;
pub mod control;
pub mod cycle;
pub mod energy;
pub mod error;
pub mod integrator;
pub mod memory;
pub mod method;
pub mod motion;
mod newton;
mod operator;
pub mod rate_form;
pub mod settings;
pub mod state;
pub mod statistics;
pub mod step_doubling;
pub mod system;
pub mod wilson;

pub use body::{LinearBody, Load, LoadHistory};
pub use contact::{ContactBoundary, ContactPoint, ContactSurface, MainBody, NormalBehaviour, Projection};
pub use control::{AdaptiveError, StepControl};
pub use energy::EnergyLedger;
pub use error::StepError;
pub use integrator::{Integrator, Statistics};
pub use memory::IntegratorMemory;
pub use method::{Method, Stepping};
pub use motion::Motion;
pub use settings::{LinearSolver, Settings, condensation_pays};
pub use state::State;
pub use system::{System, SystemMemory};
pub use wilson::Wilson;
