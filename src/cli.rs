//! The command line: `slipfront run CASE.toml ...`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use signal_hook::consts::{SIGINT, SIGTERM};

use clap::{Args, Parser, Subcommand};

use crate::case;
use crate::figures;
use crate::inspect::{self, check::Expectations, check::check};
use crate::mcap_log;
use crate::replay;
use crate::run::{LoopOptions, Outcome, run};
use crate::scene;
use crate::sink::Sink;
use crate::sink::catalog::CatalogSink;
use crate::sink::mcap::McapSink;
use crate::sink::recording::{RerunSink, Viewer, open_stream};
use crate::sink::schema::RecordingPlan;

/// Exit code for invalid input (case, arguments, output folder).
pub const EXIT_INVALID: u8 = 2;
/// Exit code for a failure during the run.
pub const EXIT_FAILED: u8 = 1;
/// Exit code after Ctrl-C (128 + SIGINT); SIGTERM gives 143 (128 + SIGTERM).
pub const EXIT_INTERRUPTED: u8 = 130;

/// Frictional stick-slip with the super/subloading surface friction model: a dynamic finite
/// element solver whose contact follows Yasuike & Toyoda's model, with an event catalog of
/// every slip.
#[derive(Debug, Parser)]
#[command(name = "slipfront", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a case file and write its Rerun recording and event catalog to the output folder.
    ///
    /// Exit codes: 0 success, 1 the run failed (the outputs hold everything up to the last good
    /// step), 2 invalid input, 130 interrupted by Ctrl-C (SIGINT), 143 by SIGTERM (outputs
    /// finished up to the last step in both).
    Run(RunArgs),
    /// Check a recording: the schema's entities, sim_time monotonic and covering the run, no NaN
    /// or Inf, equal row counts, the stored blueprint, and optional expectations.
    ///
    /// Exit codes: 0 pass, 1 mismatch, 2 unreadable.
    Check(CheckArgs),
    /// Draw PNG plots like the paper's Figures 8 (displacement at the probe nodes) and 9
    /// (traction and 1/R* at the probe segments) from a recording.
    Figures(FiguresArgs),
    /// Re-emit a slipfront MCAP log to Rerun with the live schema and blueprint.
    ///
    /// Writes <FILE-stem>.replay.rrd beside the log unless --rrd, --spawn or --connect says
    /// otherwise. Exit codes: 0 replayed, 1 the log is damaged (what could be recovered was
    /// replayed), 2 unreadable or invalid arguments.
    Replay(ReplayArgs),
}

/// Where a live copy of the recording goes.
#[derive(Debug, Args)]
pub struct ViewerArgs {
    /// Stream to a new Rerun viewer (the `rerun` executable on PATH).
    #[arg(long, conflicts_with = "connect")]
    pub spawn: bool,
    /// Stream to a running Rerun viewer, e.g. rerun+http://127.0.0.1:9876/proxy.
    #[arg(long, value_name = "URL")]
    pub connect: Option<String>,
}

impl ViewerArgs {
    pub fn viewer(&self) -> Viewer {
        match (&self.connect, self.spawn) {
            (Some(url), _) => Viewer::Connect(url.clone()),
            (None, true) => Viewer::Spawn,
            (None, false) => Viewer::None,
        }
    }
}

#[derive(Debug, Args)]
pub struct ReplayArgs {
    /// The MCAP log (written by `slipfront run --mcap`).
    pub log: PathBuf,
    /// Write the replay to this recording.
    #[arg(long, value_name = "PATH")]
    pub rrd: Option<PathBuf>,
    #[command(flatten)]
    pub viewer: ViewerArgs,
    /// Pace the replay: simulated seconds per wall-clock second (default: as fast as possible).
    #[arg(long, value_name = "FACTOR")]
    pub speed: Option<f64>,
}

#[derive(Debug, Args)]
pub struct FiguresArgs {
    /// The recording (.rrd).
    pub recording: PathBuf,
    /// Folder for the PNG files (created if missing).
    #[arg(long, value_name = "DIR", default_value = "recordings")]
    pub out: PathBuf,
}

#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The recording (.rrd) or MCAP log (.mcap).
    pub recording: PathBuf,
    /// Expectations (TOML): `[events] slip_events = [lo, hi]`, `ruptures = [lo, hi]`, and
    /// `[[at]] entity = "...", time = t, min = a, max = b` (the last row at or before t).
    #[arg(long, value_name = "EXPECT.toml")]
    pub expect: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct RunArgs {
    /// The case file (TOML, SI units; see cases/ and the README).
    pub case: PathBuf,
    /// Override a case key, e.g. --set time.t_end=50, --set friction.rstar_law=eq4, or
    /// --set time.integrator=tsit5 (Tsitouras' adaptive 5(4) pair instead of Wilson's θ method,
    /// tolerance 1e-8 per step unless time.tolerance says otherwise),
    /// --set time.integrator=sdirk4 (an adaptive L-stable implicit Runge–Kutta 4(3): long steps
    /// through stick, tolerance 1e-7 per step unless time.tolerance says otherwise) or
    /// --set time.integrator=central (explicit central differences, sub-stepped to their
    /// stability limit: the fastest on fine meshes). Repeatable; checked by the same rules as
    /// the file.
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
    /// Print nothing but errors: no progress bar, no summary.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Runs the command line and returns the process exit code.
pub fn main_with(cli: Cli) -> ExitCode {
    match cli.command {
        Command::Run(args) => run_command(args),
        Command::Check(args) => check_command(args),
        Command::Figures(args) => figures_command(args),
        Command::Replay(args) => replay_command(args),
    }
}

fn fail(code: u8, message: impl std::fmt::Display) -> ExitCode {
    eprintln!("slipfront: {message}");
    ExitCode::from(code)
}

fn run_command(args: RunArgs) -> ExitCode {
    let case = match case::load(&args.case, &args.overrides) {
        Ok(case) => case,
        Err(e) => return fail(EXIT_INVALID, format!("{}: {e}", args.case.display())),
    };
    if let Err(e) = fits_in_memory(&case) {
        return fail(EXIT_INVALID, format!("{}: {e}", args.case.display()));
    }
    let stem = args.case.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "case".into());
    if let Err(e) = std::fs::create_dir_all(&args.out_dir) {
        return fail(EXIT_INVALID, format!("cannot create output folder {}: {e}", args.out_dir.display()));
    }
    if let Err(e) = check_writable(&args.out_dir) {
        return fail(EXIT_INVALID, format!("output folder {} is not writable: {e}", args.out_dir.display()));
    }
    let events_path = args.events.clone().unwrap_or_else(|| args.out_dir.join(format!("{stem}.events.csv")));
    let ruptures_path = ruptures_path_for(&events_path);
    let mut scene = match scene::build(&case) {
        Ok(scene) => scene,
        Err(e) => return fail(EXIT_FAILED, e),
    };
    let rrd_path = if args.no_rrd {
        None
    } else {
        Some(args.rrd.clone().unwrap_or_else(|| args.out_dir.join(format!("{stem}.rrd"))))
    };
    let viewer = args.viewer.viewer();
    let stream = match open_stream(rrd_path.as_deref(), &viewer, &stem) {
        Ok(stream) => stream,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    let plan = RecordingPlan::for_case(&stem, &case);
    let mut sinks: Vec<Box<dyn Sink>> =
        vec![Box::new(CatalogSink::new(events_path.clone(), Some(ruptures_path.clone())))];
    if let Some(path) = &args.mcap {
        match McapSink::create(path, plan.clone()) {
            Ok(sink) => sinks.push(Box::new(sink)),
            Err(e) => return fail(EXIT_INVALID, e),
        }
    }
    if let Some(stream) = stream {
        sinks.push(Box::new(RerunSink::new(stream, plan)));
    }
    // SIGINT and SIGTERM stop the loop after the current step; the sinks then finish their
    // files, and the exit code is 128 + the signal's number, as a shell expects. A second
    // signal while finishing ends the process at once.
    let interrupt = Arc::new(AtomicBool::new(false));
    let signal = Arc::new(AtomicUsize::new(0));
    for number in [SIGINT, SIGTERM] {
        // Registering can only fail for signals that cannot be caught; these two can.
        let _ = signal_hook::flag::register_conditional_shutdown(number, 128 + number, interrupt.clone());
        let _ = signal_hook::flag::register(number, interrupt.clone());
        let _ = signal_hook::flag::register_usize(number, signal.clone(), number as usize);
    }
    let outcome = run(
        scene.as_mut(),
        &case.time,
        &mut sinks,
        LoopOptions { progress: !args.quiet, interrupt: Some(&interrupt), ..LoopOptions::for_case(&case) },
    );
    let mut outputs: Vec<String> = rrd_path.iter().chain(&args.mcap).map(|p| p.display().to_string()).collect();
    outputs.push(events_path.display().to_string());
    if scene.layout().kind == scene::SceneKind::Block {
        outputs.push(ruptures_path.display().to_string());
    }
    let written = outputs.join(", ");
    match outcome {
        Outcome::Completed { steps, rejected, wall, catalog, .. } => {
            if !args.quiet {
                let rejected = if case.time.adaptive_tolerance().is_some() {
                    format!(" (adaptive, {rejected} rejected)")
                } else {
                    String::new()
                };
                println!(
                    "slipfront: {} ({}): {steps} steps{rejected} to t = {} s in {:.2} s; {} slip events, {} ruptures: {written}",
                    args.case.display(),
                    case.scene.kind(),
                    case.time.t_end,
                    wall.as_secs_f64(),
                    catalog.events.len(),
                    catalog.ruptures.len(),
                );
            }
            ExitCode::SUCCESS
        }
        Outcome::Interrupted { steps, .. } => {
            let (code, name) = match signal.load(Ordering::SeqCst) {
                n if n == SIGTERM as usize => (128 + SIGTERM as u8, "SIGTERM"),
                _ => (EXIT_INTERRUPTED, "SIGINT"),
            };
            fail(
                code,
                format!(
                    "interrupted by {name} after {steps} steps (t = {} s); outputs finished: {written}",
                    scene.time()
                ),
            )
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
fn fits_in_memory(case: &case::Case) -> Result<(), String> {
    let case::SceneSpec::Block(b) = &case.scene else { return Ok(()) };
    let (dofs, bytes) = scene::block::estimated_memory(b.nx, b.ny);
    let Some(available) = available_memory() else { return Ok(()) };
    if bytes <= available {
        return Ok(());
    }
    Err(format!(
        "scene.nx × scene.ny = {} × {} is too large: {dofs:.3e} degrees of freedom need about {} of memory, \
         and {} is available; use a coarser mesh",
        b.nx,
        b.ny,
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

fn check_command(args: CheckArgs) -> ExitCode {
    let expect = match &args.expect {
        Some(path) => match Expectations::load(path) {
            Ok(e) => e,
            Err(e) => return fail(EXIT_INVALID, e),
        },
        None => Expectations::default(),
    };
    let report = if is_mcap(&args.recording) {
        // An MCAP log is judged by the recording it replays into, plus its own damage.
        let log = match mcap_log::reader::read(&args.recording) {
            Ok(log) => log,
            Err(e) => return fail(EXIT_INVALID, e),
        };
        let recording = match replay::replayed_recording(&log) {
            Ok(r) => r,
            Err(e) => return fail(EXIT_INVALID, e),
        };
        let mut report = check(&recording, &expect);
        report.summary.insert(0, format!("MCAP log: {} messages, {} recorded steps", log.messages, log.frames.len()));
        if let Some(problem) = &log.problem {
            report.problems.insert(0, format!("the log is damaged: {problem}"));
        }
        if !log.skipped.is_empty() {
            report.summary.push(format!("skipped channels of other producers: {:?}", log.skipped));
        }
        report
    } else {
        match inspect::rrd::read(&args.recording) {
            Ok(recording) => check(&recording, &expect),
            Err(e) => return fail(EXIT_INVALID, e),
        }
    };
    print!("{}", report.render());
    if report.passed() { ExitCode::SUCCESS } else { ExitCode::from(EXIT_FAILED) }
}

/// Whether `path` is an MCAP log: named `.mcap`, or starting with the MCAP magic bytes.
fn is_mcap(path: &Path) -> bool {
    use std::io::Read;
    let mut magic = [0u8; 8];
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("mcap"))
        || (std::fs::File::open(path).and_then(|mut f| f.read_exact(&mut magic)).is_ok() && magic == *mcap::MAGIC)
}

fn replay_command(args: ReplayArgs) -> ExitCode {
    if let Some(speed) = args.speed
        && !(speed.is_finite() && speed > 0.0)
    {
        return fail(EXIT_INVALID, format!("--speed {speed}: must be a finite number greater than 0"));
    }
    let log = match mcap_log::reader::read(&args.log) {
        Ok(log) => log,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    for (topic, count) in &log.skipped {
        eprintln!("slipfront: skipping {count} messages on {topic}: not a slipfront channel");
    }
    let viewer = args.viewer.viewer();
    let rrd = args.rrd.clone().or_else(|| {
        (viewer == Viewer::None).then(|| {
            let stem = args.log.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "log".into());
            args.log.with_file_name(format!("{stem}.replay.rrd"))
        })
    });
    let stream = match open_stream(rrd.as_deref(), &viewer, &log.header.plan.case) {
        Ok(Some(stream)) => stream,
        Ok(None) => return fail(EXIT_INVALID, "nothing to replay into"),
        Err(e) => return fail(EXIT_INVALID, e),
    };
    if let Err(e) = replay::replay(&log, stream, args.speed) {
        return fail(EXIT_FAILED, e);
    }
    let last = log.frames.last().map_or(0.0, |f| f.time);
    let into = rrd.map_or_else(|| "the viewer".to_string(), |p| p.display().to_string());
    match &log.problem {
        Some(problem) => fail(
            EXIT_FAILED,
            format!(
                "{}: {problem}; replayed {} recorded steps up to t = {last} s into {into}",
                args.log.display(),
                log.frames.len()
            ),
        ),
        None => {
            println!("slipfront: replayed {} recorded steps up to t = {last} s into {into}", log.frames.len());
            ExitCode::SUCCESS
        }
    }
}

fn figures_command(args: FiguresArgs) -> ExitCode {
    let recording = match inspect::rrd::read(&args.recording) {
        Ok(r) => r,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    match figures::write_figures(&recording, &args.out) {
        Ok(paths) => {
            for path in paths {
                println!("{}", path.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => fail(EXIT_FAILED, e),
    }
}

/// `<dir>/<x>.ruptures.csv` beside `<dir>/<x>.events.csv` (or `<stem>.ruptures.csv`).
fn ruptures_path_for(events: &Path) -> PathBuf {
    let name = events.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let stem = name.strip_suffix(".events.csv").or_else(|| name.strip_suffix(".csv")).unwrap_or(&name);
    events.with_file_name(format!("{stem}.ruptures.csv"))
}

fn check_writable(dir: &Path) -> std::io::Result<()> {
    let probe = dir.join(format!(".slipfront-write-test-{}", std::process::id()));
    std::fs::write(&probe, b"")?;
    std::fs::remove_file(&probe)
}
