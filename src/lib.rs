//! slipfront: dynamic finite elements with a frictional contact boundary that follows the
//! super/subloading surface friction model (Yasuike & Toyoda), streamed to Rerun.

pub mod case;
pub mod cli;
pub mod dynamics;
pub mod ensemble;
pub mod fem;
pub mod figures;
pub mod friction;
pub mod fuzzing;
pub mod inspect;
pub mod mcap_log;
pub mod replay;
pub mod run;
pub mod scene;
pub mod sink;
pub mod validate;
