//! Working with runs and their files: studies (ensembles and sweeps of a case, run on the cores
//! or in shards, summarized), figures drawn from a recording, and the replay of an MCAP log
//! into a recording.

pub mod contact_figures;
pub mod ensemble;
pub mod figures;
pub mod record;
pub mod replay;
pub mod runner;
pub mod slurm;
pub mod spec;
pub mod stop;
pub mod summary;
