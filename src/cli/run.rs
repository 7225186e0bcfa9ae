//! `slipfront run CASE.toml`: a case run to its end, its recording, MCAP log and event
//! catalogs written, interrupted cleanly by SIGINT or SIGTERM.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use crate::case;
use crate::cli::checkpoints::{self, Saver};
use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, ViewerArgs, compact_recording, fail, print};
use crate::cli::outputs::{self, Named, check_writable};
use crate::cli::signals::Stop;
use crate::progress::ProgressMode;
use crate::record::checkpoint::{CheckpointInfo, SavedCase, SavedOutputs};
use crate::record::schema::RecordingPlan;
use crate::run::{Checkpoints, LoopOptions, Outcome, RunMemory, run};
use crate::scene;
use crate::sink::Sink;
use crate::sink::catalog::CatalogSink;
use crate::sink::mcap::McapSink;
use crate::sink::rerun::{RerunSink, open_stream};

#[derive(Debug, Args)]
pub struct RunArgs {
    /// The case file (TOML, SI units; see cases/ and the README).
    pub case: PathBuf,
    /// Override a case key, e.g. --set time.t_end=50, --set friction.rstar_law=eq4, or
    /// --set time.integrator=NAME to name the time integrator instead of `auto` (the default,
    /// which prints what it chose and why): wilson (Wilson's θ method, fixed steps of time.dt),
    /// tsit5 (Tsitouras' adaptive explicit 5(4) pair, tolerance 1e-8 per step unless
    /// time.tolerance says otherwise), sdirk4 (an adaptive L-stable implicit Runge–Kutta 4(3),
    /// tolerance 1e-7), central (explicit central differences, sub-stepped to their stability
    /// limit: the fastest on fine meshes) or cycle (Wilson's steps sized by the contact's
    /// rates, from time.dt in a slip to time.dt_max in stick: earthquake cycles at plate rates).
    /// Repeatable; checked by the same rules as the file.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// Folder for every output (created if missing).
    #[arg(long, value_name = "DIR", default_value = "recordings")]
    pub out_dir: PathBuf,
    /// Path of the slip-event CSV [default: <out-dir>/<case-stem>.events.csv]; a block's
    /// rupture CSV goes beside it as <stem>.ruptures.csv.
    #[arg(long, value_name = "PATH")]
    pub events: Option<PathBuf>,
    /// Path of the Rerun recording [default: <out-dir>/<case-stem>.rrd].
    #[arg(long, value_name = "PATH", conflicts_with = "no_rrd")]
    pub rrd: Option<PathBuf>,
    /// Write no .rrd recording.
    #[arg(long)]
    pub no_rrd: bool,
    #[command(flatten)]
    pub viewer: ViewerArgs,
    /// Also write the recorded steps to an MCAP log (protobuf; Foxglove, `mcap` readers,
    /// `slipfront replay`).
    #[arg(long, value_name = "PATH")]
    pub mcap: Option<PathBuf>,
    /// Write a checkpoint every SECONDS of simulated time, and at the end, to
    /// <out-dir>/<case-stem>.ckpt (the latest replaces the one before), from which
    /// `slipfront resume` continues the run or extends it. Without a value: every tenth of
    /// time.t_end.
    #[arg(long, value_name = "SECONDS", num_args = 0..=1, default_missing_value = "")]
    pub checkpoint_every: Option<String>,
    /// With --checkpoint-every, also keep each checkpoint as <case-stem>.<T>s.ckpt (T the multiple of the interval it was taken at, e.g. 300s).
    #[arg(long, requires = "checkpoint_every")]
    pub keep_checkpoints: bool,
    /// How to show progress on stderr: auto (a bar in a terminal, else a line every 10 s for
    /// a batch job's log: simulated time, steps, simulated seconds per wall second, the end
    /// estimated from the recent rate), bar, lines or none.
    #[arg(long, value_enum, default_value = "auto", value_name = "HOW")]
    pub progress: ProgressMode,
    /// Print nothing but errors: no progress, no summary.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Runs `slipfront run`: the case read and checked, its outputs opened, the loop run with
/// SIGINT and SIGTERM caught, and the outcome reported.
pub fn command(args: RunArgs) -> ExitCode {
    let (case, outputs) = match prepare(&args) {
        Ok(prepared) => prepared,
        Err(exit) => return exit,
    };
    let mut scene = match scene::build(&case) {
        Ok(scene) => scene,
        Err(e) => return fail(EXIT_FAILED, e),
    };
    let block = scene.layout().kind.has_body();
    if let (Some(warning), false) = (scene.layout().probe_spread_warning(), args.quiet) {
        warning.lines().for_each(|line| eprintln!("slipfront: warning: {line}"));
    }
    let _locks = match outputs.claim(&args, block) {
        Ok(locks) => locks,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    say_replaced(&_locks, &args);
    let mut sinks = match outputs.sinks(&args, &case) {
        Ok(sinks) => sinks,
        Err(exit) => return exit,
    };
    let mut saver = match outputs.saver(&args, &case) {
        Ok(saver) => saver,
        Err(exit) => return exit,
    };
    let stop = Stop::catch();
    let mut save = |memory: &RunMemory, label: f64| saver.as_mut().map_or(Ok(()), |s| s.save(memory, label));
    let checkpoints = outputs.every.map(|every| Checkpoints { every, save: &mut save });
    let outcome = run(
        scene.as_mut(),
        &case.time,
        &mut sinks,
        LoopOptions {
            progress: !args.quiet,
            progress_mode: args.progress,
            interrupt: Some(&stop.flag),
            checkpoints,
            ..LoopOptions::for_case(&case)
        },
    );
    drop(sinks);
    if let Some(rrd) = &outputs.rrd {
        compact_recording(rrd);
    }
    let mut written = outputs.written(&args, block);
    if let Some(saver) = &saver {
        written = format!("{written}; {}", saver.summary());
    }
    report(Reporting { case_file: &args.case, quiet: args.quiet }, &case, outcome, &written, &stop, scene.time())
}

/// One line on stderr naming the files of an earlier run that this one replaces (a rerun with
/// other `--set` values writes the same `<out-dir>/<case-stem>.*`), unless quiet.
fn say_replaced(locks: &outputs::Locks, args: &RunArgs) {
    let replaced = locks.replaced();
    if args.quiet || replaced.is_empty() {
        return;
    }
    let names: Vec<String> = replaced.iter().map(|p| p.display().to_string()).collect();
    eprintln!(
        "slipfront: replacing an earlier run's {} (--out-dir DIR or --rrd/--events PATH keep it)",
        names.join(", ")
    );
}

/// Where a run's outputs go, and how often it checkpoints (simulated s).
struct Outputs {
    stem: String,
    events: PathBuf,
    ruptures: PathBuf,
    /// The openings CSV, where a contact's normal traction evolves.
    openings: Option<PathBuf>,
    rrd: Option<PathBuf>,
    every: Option<f64>,
}

/// Reads and checks the case and the output folder, and names the outputs.
fn prepare(args: &RunArgs) -> Result<(case::Case, Outputs), ExitCode> {
    let case = case::load(&args.case, &args.overrides)
        .map_err(|e| fail(EXIT_INVALID, format!("{}: {e}", args.case.display())))?;
    fits_in_memory(&case).map_err(|e| fail(EXIT_INVALID, format!("{}: {e}", args.case.display())))?;
    let stem = args.case.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "case".into());
    std::fs::create_dir_all(&args.out_dir)
        .map_err(|e| fail(EXIT_INVALID, format!("cannot create output folder {}: {e}", args.out_dir.display())))?;
    check_writable(&args.out_dir)
        .map_err(|e| fail(EXIT_INVALID, format!("output folder {} is not writable: {e}", args.out_dir.display())))?;
    let events = args.events.clone().unwrap_or_else(|| args.out_dir.join(format!("{stem}.events.csv")));
    let ruptures = ruptures_path_for(&events);
    let openings = case.scene.has_evolving_normal().then(|| crate::sink::catalog::openings_path_for(&events));
    let rrd = (!args.no_rrd).then(|| args.rrd.clone().unwrap_or_else(|| args.out_dir.join(format!("{stem}.rrd"))));
    let every = match &args.checkpoint_every {
        None => None,
        Some(value) => Some(
            checkpoints::interval((!value.is_empty()).then_some(value.as_str()), case.time.t_end)
                .map_err(|e| fail(EXIT_INVALID, e))?,
        ),
    };
    Ok((case, Outputs { stem, events, ruptures, openings, rrd, every }))
}

impl Outputs {
    /// The catalog's CSV writer, the MCAP log and the Rerun recording, as the arguments ask.
    fn sinks(&self, args: &RunArgs, case: &case::Case) -> Result<Vec<Box<dyn Sink>>, ExitCode> {
        let plan = RecordingPlan::for_case(&self.stem, case);
        let stream = open_stream(self.rrd.as_deref(), &args.viewer.viewer(), &self.stem, plan.recording_id.as_deref())
            .map_err(|e| fail(EXIT_INVALID, e))?;
        let mut sinks: Vec<Box<dyn Sink>> =
            vec![Box::new(CatalogSink::new(self.events.clone(), Some(self.ruptures.clone())))];
        if let Some(path) = &args.mcap {
            sinks.push(Box::new(McapSink::create(path, plan.clone()).map_err(|e| fail(EXIT_INVALID, e))?));
        }
        if let Some(stream) = stream {
            sinks.push(Box::new(RerunSink::new(stream, plan)));
        }
        Ok(sinks)
    }

    /// The checkpoints' writer, if the run checkpoints: the case's text and overrides, where
    /// the outputs go, the recording id and the interval.
    fn saver(&self, args: &RunArgs, case: &case::Case) -> Result<Option<Saver>, ExitCode> {
        let Some(every) = self.every else { return Ok(None) };
        let text = case::read(&args.case).map_err(|e| fail(EXIT_INVALID, e))?;
        let info = CheckpointInfo {
            written_by: env!("CARGO_PKG_VERSION").into(),
            case: SavedCase {
                path: args.case.clone(),
                stem: self.stem.clone(),
                text,
                overrides: args.overrides.clone(),
            },
            outputs: SavedOutputs::new(
                &args.out_dir,
                &self.events,
                &self.ruptures,
                self.rrd.as_deref(),
                args.mcap.as_deref(),
            ),
            recording_id: RecordingPlan::for_case(&self.stem, case).recording_id,
            every,
        };
        Ok(Some(Saver::new(&args.out_dir, info, args.keep_checkpoints)))
    }

    /// Every file the run writes, with the option that names it: the recording, the MCAP
    /// log, the event catalog and, for a block, the rupture catalog beside it, and the opening
    /// catalog where a contact's normal traction evolves.
    fn named<'a>(&'a self, args: &'a RunArgs, block: bool) -> Vec<Named<'a>> {
        let mut named: Vec<Named<'a>> = self.rrd.iter().map(|path| Named { role: "--rrd", path }).collect();
        named.extend(args.mcap.iter().map(|path| Named { role: "--mcap", path }));
        named.push(Named { role: "--events", path: &self.events });
        if block {
            named.push(Named { role: "the rupture catalog", path: &self.ruptures });
        }
        if let Some(path) = &self.openings {
            named.push(Named { role: "the opening catalog", path });
        }
        named
    }

    /// Refuses outputs that collide with each other or with the case file, or whose folder
    /// cannot be written, and locks them for the run ([`outputs::claim`]).
    fn claim(&self, args: &RunArgs, block: bool) -> Result<outputs::Locks, String> {
        outputs::claim(&[Named { role: "case file", path: &args.case }], &self.named(args, block))
    }

    /// The files written, for the summary.
    fn written(&self, args: &RunArgs, block: bool) -> String {
        self.named(args, block).iter().map(|n| n.path.display().to_string()).collect::<Vec<_>>().join(", ")
    }
}

/// What the summary names: the case file, and whether to print it at all.
pub(crate) struct Reporting<'a> {
    pub case_file: &'a Path,
    pub quiet: bool,
}

/// The summary line of a completed run, or the error of one that was not, and its exit code.
pub(crate) fn report(
    reporting: Reporting<'_>,
    case: &case::Case,
    outcome: Outcome,
    written: &str,
    stop: &Stop,
    time: f64,
) -> ExitCode {
    match outcome {
        Outcome::Completed { steps, rejected, wall, catalog, .. } => {
            if !reporting.quiet {
                let rejected = if case.time.adaptive_tolerance().is_some() {
                    format!(" (adaptive, {rejected} rejected)")
                } else {
                    String::new()
                };
                // Ruptures group the events of neighbouring segments: a block's contact has
                // several segments and a rupture catalog; a point or spring block has one.
                let ruptures = match &case.scene {
                    case::SceneSpec::Block(_) => format!(", {} ruptures", catalog.ruptures.len()),
                    _ => String::new(),
                };
                let line = format!(
                    "slipfront: {} ({}): {steps} steps{rejected} to t = {} s in {:.2} s; {} slip events{ruptures}: {written}",
                    reporting.case_file.display(),
                    case.scene.kind(),
                    case.time.t_end,
                    wall.as_secs_f64(),
                    catalog.events.len(),
                );
                let chosen = match &case.time.chosen_because {
                    Some(why) => format!("  time.integrator = \"auto\" chose {}: {why}\n", case.time.method.name()),
                    None => String::new(),
                };
                if let Err(exit) = print(&format!("{line}\n{chosen}")) {
                    return exit;
                }
            }
            ExitCode::SUCCESS
        }
        Outcome::Interrupted { steps, .. } => {
            let (code, name) = stop.exit();
            fail(code, format!("interrupted by {name} after {steps} steps (t = {time} s); outputs finished: {written}"))
        }
        Outcome::Failed { error, .. } => {
            fail(EXIT_FAILED, format!("run failed at {error}; outputs hold every step before it: {written}"))
        }
        Outcome::Sink(error) => {
            fail(EXIT_FAILED, format!("{error}; the run stopped there, and the other outputs were finished: {written}"))
        }
    }
}

/// Refuses a block mesh whose estimated memory ([`scene::block::estimated_memory`]) exceeds
/// what the machine has available (`MemAvailable` of `/proc/meminfo`; no check where that is
/// unknown).
pub(crate) fn fits_in_memory(case: &case::Case) -> Result<(), String> {
    let (what, dofs, bytes) = match &case.scene {
        case::SceneSpec::Block(b) => {
            let (dofs, bytes) = scene::block::estimated_memory(b.nx, b.ny);
            (format!("scene.nx × scene.ny = {} × {}", b.nx, b.ny), dofs, bytes)
        }
        case::SceneSpec::Mesh(m) => {
            let dofs = m.unknowns().unwrap_or(0) as f64;
            let (contact_nodes, _) = m.contact_sizes();
            (format!("scene.file = \"{}\"", m.file), dofs, scene::block::body_memory(dofs, contact_nodes))
        }
        _ => return Ok(()),
    };
    let Some(available) = available_memory() else { return Ok(()) };
    if bytes <= available {
        return Ok(());
    }
    Err(format!(
        "{what} is too large: {dofs:.3e} degrees of freedom need about {} of memory, and {} is available; use a \
         coarser mesh",
        human_bytes(bytes),
        human_bytes(available)
    ))
}

/// `MemAvailable` of `/proc/meminfo`, in bytes.
fn available_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

fn human_bytes(bytes: f64) -> String {
    let units = ["B", "kB", "MB", "GB", "TB", "PB", "EB"];
    let power = ((bytes.max(1.0).log10() / 3.0).floor() as usize).min(units.len() - 1);
    format!("{:.1} {}", bytes / 1e3f64.powi(power as i32), units[power])
}

/// `<dir>/<x>.ruptures.csv` beside `<dir>/<x>.events.csv` (or `<stem>.ruptures.csv`).
pub(crate) fn ruptures_path_for(events: &Path) -> PathBuf {
    let name = events.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let stem = name.strip_suffix(".events.csv").or_else(|| name.strip_suffix(".csv")).unwrap_or(&name);
    events.with_file_name(format!("{stem}.ruptures.csv"))
}
