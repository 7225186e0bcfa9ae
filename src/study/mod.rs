//! Working with runs and their files: ensembles of perturbed runs, figures drawn from a
//! recording, and the replay of an MCAP log into a recording.

pub mod ensemble;
pub mod figures;
pub mod replay;
