//! `slipfront study STUDY.toml`: every member of an ensemble or sweep of a case, run on the
//! cores (or a shard of them, for a batch scheduler), into one folder that a Rerun server reads
//! as one dataset, with a table of every member's events and a summary; or a Slurm job array
//! that runs it (`--slurm-array`), or the tables alone (`--summarize`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, fail, print};
use crate::cli::outputs::claim_folder;
use crate::cli::signals::Stop;
use crate::study::record::DONE;
use crate::study::runner::{Options, members, plan, run_members};
use crate::study::spec::{self, Shard, Study};
use crate::study::summary::plural;
use crate::study::{slurm, summary};

#[derive(Debug, Args)]
pub struct StudyArgs {
    /// The study file (TOML): `case` (the base case, relative to the study file), `[set]`
    /// overrides for every member, and `[ensemble]` (key, step, members) and/or `[sweep]`
    /// (key = [values]); see docs/studies.md.
    pub study: PathBuf,
    /// Members run at once [default: the machine's cores; with --slurm-array, 1], each on one
    /// core.
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,
    /// Run only the members whose index is I-1 modulo N (1 ≤ I ≤ N), e.g. from a Slurm job
    /// array; shards writing into one folder (or copied into one) make the whole study.
    #[arg(long, value_name = "I/N", conflicts_with_all = ["slurm_array", "summarize"])]
    pub shard: Option<Shard>,
    /// Run nothing: write a Slurm batch script, <out-dir>/<study-stem>/slurm/<study-stem>.sbatch,
    /// that runs the study as a job array of N tasks (task I runs --shard I/N --resume with
    /// --jobs cores) and then a job that writes the tables (--summarize). Submit it with sbatch.
    #[arg(long, value_name = "N", conflicts_with_all = ["resume", "summarize"])]
    pub slurm_array: Option<usize>,
    /// Run nothing: write events.csv, summary.md and summary.png from the members in the folder,
    /// naming the members missing. Exit 1 if any member is missing or failed.
    #[arg(long, conflicts_with_all = ["resume", "jobs"])]
    pub summarize: bool,
    /// The study's outputs go into <out-dir>/<study-stem>/.
    #[arg(long, value_name = "DIR", default_value = "recordings")]
    pub out_dir: PathBuf,
    /// Skip the members that are done: whose record (<member>.done.toml) and outputs verify and
    /// whose parameters are the study file's. Every other member runs again, failed ones too.
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
    if let Some(tasks) = args.slurm_array {
        return write_array_job(&args, &study, tasks);
    }
    let dir = args.out_dir.join(&study.name);
    if args.summarize && !dir.is_dir() {
        return fail(
            EXIT_INVALID,
            format!("--summarize: {} is not a folder: give the --out-dir the study ran into", dir.display()),
        );
    }
    if let Err(e) = std::fs::create_dir_all(&dir) {
        return fail(EXIT_INVALID, format!("cannot create the study's folder {}: {e}", dir.display()));
    }
    // Shards share the folder, and so does the summary, which only reads the members' files.
    let _folder = match claim_folder(&dir, args.shard.is_some() || args.summarize) {
        Ok(lock) => lock,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    if args.summarize {
        return summarize(&study, &dir, args.quiet);
    }
    let selected: Vec<_> = study.members.iter().filter(|m| args.shard.is_none_or(|s| s.holds(m.index))).collect();
    let (todo, plan) = plan(&study, &selected, &dir, args.resume);
    if args.resume && !args.quiet {
        eprintln!("slipfront study {}: {}", study.name, plan.describe());
    }
    let jobs = args.jobs.unwrap_or_else(crate::study::ensemble::available_threads);
    let stop = Stop::catch();
    let options = Options { jobs, progress: !args.quiet, interrupt: Some(&stop.flag) };
    let ran = run_members(&study, &todo, &dir, &options);
    let counts = match summary::write(&study, &dir) {
        Ok(counts) => counts,
        Err(e) => return fail(EXIT_FAILED, e),
    };
    if stop.requested() {
        let (code, name) = stop.exit();
        return fail(code, format!("interrupted by {name}; rerun with --resume to run the members left"));
    }
    if let Some(first) = ran.busy.first() {
        return fail(
            EXIT_INVALID,
            format!("{} not run: their outputs could not be claimed ({first})", members(ran.busy.len())),
        );
    }
    if let Some(first) = ran.unwritable.first() {
        return fail(EXIT_FAILED, format!("{} left no record ({first})", members(ran.unwritable.len())));
    }
    if !args.quiet {
        let orphans = orphaned_records(&study, &dir);
        let left_out = match orphans {
            0 => String::new(),
            n => format!("; {n} records of members the study no longer has are left out"),
        };
        let line = format!(
            "slipfront study {}: {} run ({} failed), {} verified and kept; {} of {} finished, {} failed in {} \
             (summary.md, events.csv){left_out}\n",
            study.name,
            members(ran.ran),
            ran.failed,
            plan.kept,
            counts.finished,
            study.members.len(),
            counts.failed,
            dir.display()
        );
        if let Err(exit) = print(&line) {
            return exit;
        }
    }
    if ran.failed > 0 {
        return fail(
            EXIT_FAILED,
            format!("{} failed (their errors are in summary.md); --resume runs them again", members(ran.failed)),
        );
    }
    ExitCode::SUCCESS
}

/// `--summarize`: the tables from the members in `dir`; exit 1 if any is missing or failed.
fn summarize(study: &Study, dir: &Path, quiet: bool) -> ExitCode {
    let counts = match summary::write(study, dir) {
        Ok(counts) => counts,
        Err(e) => return fail(EXIT_FAILED, e),
    };
    let total = study.members.len();
    if !quiet {
        let line = format!(
            "slipfront study {}: {} of {total} finished, {} failed, {} missing in {} (summary.md, events.csv)\n",
            study.name,
            counts.finished,
            counts.failed,
            counts.missing.len(),
            dir.display()
        );
        if let Err(exit) = print(&line) {
            return exit;
        }
    }
    if let Some(first) = counts.missing.first() {
        return fail(
            EXIT_FAILED,
            format!(
                "{} missing (first: {first}); summary.md names them all: run them with --resume, or run again the \
                 shards that hold them",
                members(counts.missing.len())
            ),
        );
    }
    if counts.failed > 0 {
        return fail(EXIT_FAILED, format!("{} failed (their errors are in summary.md)", members(counts.failed)));
    }
    ExitCode::SUCCESS
}

/// `--slurm-array N`: writes the study's Slurm batch script ([`slurm`]), with every path
/// absolute, and says how to submit it.
fn write_array_job(args: &StudyArgs, study: &Study, tasks: usize) -> ExitCode {
    if let Err(e) = slurm::check_tasks(tasks, study.members.len()) {
        return fail(EXIT_INVALID, e);
    }
    let jobs = args.jobs.unwrap_or(1);
    let paths = array_job_paths(args, study);
    let (study_file, out_dir, slipfront) = match paths {
        Ok(paths) => paths,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    let job = slurm::ArrayJob {
        slipfront: &slipfront,
        study_file: &study_file,
        out_dir: &out_dir,
        name: &study.name,
        tasks,
        jobs,
        members: study.members.len(),
    };
    let path = slurm::script_path(&out_dir, &study.name);
    if let Err(e) = crate::study::runner::write_atomically(&path, &slurm::script(&job)) {
        return fail(EXIT_INVALID, e);
    }
    if args.quiet {
        return ExitCode::SUCCESS;
    }
    let line = format!(
        "slipfront study {}: wrote {}: {} as a Slurm job array of {} of {}, logs beside it; submit it with\n  \
         sbatch --partition=NAME --time=HH:MM:SS {}\n",
        study.name,
        path.display(),
        members(study.members.len()),
        plural(tasks, "task"),
        plural(jobs, "core"),
        path.display()
    );
    match print(&line) {
        Ok(()) => ExitCode::SUCCESS,
        Err(exit) => exit,
    }
}

/// The absolute paths an array job's script names: the study file, the `--out-dir` (each
/// checked for what a `#SBATCH` line can hold) and the `slipfront` binary; the folder of its
/// logs is created.
fn array_job_paths(args: &StudyArgs, study: &Study) -> Result<(PathBuf, PathBuf, PathBuf), String> {
    let study_file = std::fs::canonicalize(&args.study).map_err(|e| format!("{}: {e}", args.study.display()))?;
    let out_dir =
        std::path::absolute(&args.out_dir).map_err(|e| format!("--out-dir {}: {e}", args.out_dir.display()))?;
    slurm::check_path(&out_dir, "--out-dir")?;
    slurm::check_path(Path::new(&study.name), "the study's name")?;
    let slipfront = std::env::current_exe().map_err(|e| format!("cannot tell where slipfront is: {e}"))?;
    let logs = slurm::folder(&out_dir, &study.name);
    std::fs::create_dir_all(&logs).map_err(|e| format!("cannot create the folder {}: {e}", logs.display()))?;
    Ok((study_file, out_dir, slipfront))
}

/// Records in `dir` of members `study` does not have (the study file was edited to fewer).
fn orphaned_records(study: &Study, dir: &Path) -> usize {
    let names: std::collections::BTreeSet<String> = study.members.iter().map(|m| format!("{}{DONE}", m.name)).collect();
    std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("member-") && n.ends_with(DONE) && !names.contains(n))
        .count()
}
