//! `slipfront study STUDY.toml`: every member of an ensemble or sweep of a case, run on the
//! cores (or a shard of them, for a batch scheduler), into one folder that a Rerun server reads
//! as one dataset, with a table of every member's events and a summary.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, fail, print};
use crate::cli::signals::Stop;
use crate::study::runner::{Options, run_members};
use crate::study::spec::{self, Shard};
use crate::study::summary;

#[derive(Debug, Args)]
pub struct StudyArgs {
    /// The study file (TOML): `case` (the base case, relative to the study file), `[set]`
    /// overrides for every member, and `[ensemble]` (key, step, members) and/or `[sweep]`
    /// (key = [values]); see docs/studies.md.
    pub study: PathBuf,
    /// Members run at once [default: the machine's cores].
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,
    /// Run only the members whose index is I-1 modulo N (1 ≤ I ≤ N), e.g. from a Slurm job
    /// array; shards writing into one folder (or copied into one) make the whole study.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<Shard>,
    /// The study's outputs go into <out-dir>/<study-stem>/.
    #[arg(long, value_name = "DIR", default_value = "recordings")]
    pub out_dir: PathBuf,
    /// Skip members whose outputs are complete (their <member>.done.toml exists).
    #[arg(long)]
    pub resume: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Runs `slipfront study`.
pub fn command(args: StudyArgs) -> ExitCode {
    if args.jobs == Some(0) {
        return fail(EXIT_INVALID, "--jobs 0: at least one member must run at a time");
    }
    let study = match spec::load(&args.study) {
        Ok(study) => study,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    let dir = args.out_dir.join(&study.name);
    if let Err(e) = std::fs::create_dir_all(&dir) {
        return fail(EXIT_INVALID, format!("cannot create the study's folder {}: {e}", dir.display()));
    }
    let selected: Vec<_> = study.members.iter().filter(|m| args.shard.is_none_or(|s| s.holds(m.index))).collect();
    let jobs = args.jobs.unwrap_or_else(crate::study::ensemble::available_threads);
    let stop = Stop::catch();
    let options = Options { jobs, resume: args.resume, progress: !args.quiet, interrupt: Some(&stop.flag) };
    let ran = run_members(&study, &selected, &dir, &options);
    let finished = match summary::write(&study, &dir) {
        Ok(finished) => finished,
        Err(e) => return fail(EXIT_FAILED, e),
    };
    let (ran, skipped) = match ran {
        Ok(counts) => counts,
        Err(e) => return fail(EXIT_FAILED, format!("study {}: {e}", study.name)),
    };
    if stop.requested() {
        let (code, name) = stop.exit();
        return fail(code, format!("interrupted by {name}; rerun with --resume to run the members left"));
    }
    if args.quiet {
        return ExitCode::SUCCESS;
    }
    let line = format!(
        "slipfront study {}: {ran} members run, {skipped} already done; {finished} of {} finished in {} \
         (summary.md, events.csv)\n",
        study.name,
        study.members.len(),
        dir.display()
    );
    print(&line).err().unwrap_or(ExitCode::SUCCESS)
}
