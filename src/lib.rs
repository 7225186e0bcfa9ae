//! slipfront: dynamic finite elements with a frictional contact boundary that follows the
//! super/subloading surface friction model (Yasuike & Toyoda), streamed to Rerun.
//!
//! Data flows one way, top to bottom:
//!
//! 1. [`case`] reads a TOML case into a validated [`case::Case`] (SI units throughout).
//! 2. [`scene`] assembles it into a model: the friction law ([`friction`], eqs. 1-9), the
//!    plane-strain body ([`fem`]) and its time integration ([`dynamics`], eq. 14), on the
//!    sparse solvers of [`linalg`].
//! 3. [`run`] advances the scene step by step and describes each step as a [`frame::Frame`].
//! 4. [`catalog`] turns frames into slip events and ruptures; the [`sink`]s write frames and
//!    catalogs to files (Rerun `.rrd`, MCAP, CSV) in the formats [`record`] defines.
//! 5. Readers come back through [`record`]: [`inspect`] (`slipfront check`) and [`study`]
//!    (replay, figures, ensembles). [`cli`] is the command line over all of it.
//!
//! Nothing below [`frame`] does I/O.

pub mod case;
pub mod catalog;
pub mod cli;
pub mod dynamics;
pub mod fem;
pub mod files;
pub mod frame;
pub mod friction;
pub mod fuzzing;
pub mod inspect;
pub mod linalg;
pub mod progress;
pub mod record;
pub mod run;
pub mod scene;
pub mod sink;
pub mod study;
pub mod validate;
