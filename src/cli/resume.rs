//! `slipfront resume CHECKPOINT`: a run continued from its checkpoint to its end (or to a new
//! `time.t_end`), its recording, MCAP log and catalogs left as those of one uninterrupted run.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use crate::case;
use crate::cli::checkpoints::{self, Saver};
use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, compact_recording, fail};
use crate::cli::outputs::{self, Named};
use crate::cli::run::{Reporting, fits_in_memory, report};
use crate::cli::signals::Stop;
use crate::record::checkpoint::{self, Checkpoint, CheckpointInfo, SavedOutputs};
use crate::record::schema::RecordingPlan;
use crate::run::{Checkpoints, LoopOptions, RunMemory, run};
use crate::scene::{self, Scene};
use crate::sink::catalog::CatalogSink;
use crate::sink::mcap::McapSink;
use crate::sink::rerun::{RerunSink, Viewer, open_stream};
use crate::sink::{Continuation, Sink};

/// The one case key a resumed run may change: the rest would make it another run.
pub const RESUMABLE_KEYS: [&str; 1] = ["time.t_end"];

#[derive(Debug, Args)]
pub struct ResumeArgs {
    /// The checkpoint (<case-stem>.ckpt) of a run started with --checkpoint-every.
    pub checkpoint: PathBuf,
    /// Override time.t_end, to extend the run (or end it sooner, not before the checkpoint):
    /// --set time.t_end=2000. No other key: a resumed run is the same run.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// Folder for every output [default: the run's own]. The recording and log are continued
    /// from where the run wrote them.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
    /// Checkpoint every SECONDS of simulated time [default: as the run did].
    #[arg(long, value_name = "SECONDS")]
    pub checkpoint_every: Option<String>,
    /// Also keep each checkpoint as <case-stem>.<T>s.ckpt (T the multiple of the interval it was taken at, e.g. 300s).
    #[arg(long)]
    pub keep_checkpoints: bool,
    /// Print nothing but errors: no progress bar, no summary.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Runs `slipfront resume`: the checkpoint read and checked against its case, the outputs
/// continued, the loop run from the saved state, and the outcome reported.
pub fn command(args: ResumeArgs) -> ExitCode {
    let (checkpoint, case) = match prepare(&args) {
        Ok(prepared) => prepared,
        Err(exit) => return exit,
    };
    let mut scene = match restored_scene(&args, &case, &checkpoint) {
        Ok(scene) => scene,
        Err(exit) => return exit,
    };
    let info = &checkpoint.info;
    let out_dir = args.out_dir.clone().unwrap_or_else(|| info.outputs.out_dir.clone());
    if let Err(e) = std::fs::create_dir_all(&out_dir) {
        return fail(EXIT_INVALID, format!("cannot create output folder {}: {e}", out_dir.display()));
    }
    let outputs = Outputs::new(info, &out_dir);
    let block = scene.layout().kind.has_body();
    let _locks = match outputs.claim(&args.checkpoint, block) {
        Ok(locks) => locks,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    let mut sinks = match outputs.sinks(info, &case) {
        Ok(sinks) => sinks,
        Err(exit) => return exit,
    };
    let every = match args.checkpoint_every.as_deref() {
        Some(value) => match checkpoints::interval(Some(value), case.time.t_end) {
            Ok(every) => every,
            Err(e) => return fail(EXIT_INVALID, e),
        },
        None => info.every,
    };
    let mut saver = Saver::new(
        &out_dir,
        CheckpointInfo { every, outputs: outputs.saved(&out_dir), ..info.clone() },
        args.keep_checkpoints,
    );
    let mut save = |memory: &RunMemory| saver.save(memory);
    let (from_time, from_step) = checkpoint.time_and_step();
    let stop = Stop::catch();
    let outcome = run(
        scene.as_mut(),
        &case.time,
        &mut sinks,
        LoopOptions {
            progress: !args.quiet,
            interrupt: Some(&stop.flag),
            checkpoints: Some(Checkpoints { every, save: &mut save }),
            resume: Some(checkpoint.run),
            ..LoopOptions::for_case(&case)
        },
    );
    drop(sinks);
    outputs.tidy();
    let written = format!(
        "continued from t = {from_time:.3} s (step {from_step}): {}; {}",
        outputs.written(block),
        saver.summary()
    );
    let reporting = Reporting { case_file: &info.case.path, quiet: args.quiet };
    report(reporting, &case, outcome, &written, &stop, scene.time())
}

/// Reads the checkpoint and its case with the overrides allowed on resume.
fn prepare(args: &ResumeArgs) -> Result<(Checkpoint, case::Case), ExitCode> {
    let checkpoint = checkpoint::read(&args.checkpoint).map_err(|e| fail(EXIT_INVALID, e))?;
    for item in &args.overrides {
        let key = item.split_once('=').map_or(item.as_str(), |(k, _)| k).trim();
        if !RESUMABLE_KEYS.contains(&key) {
            return Err(fail(
                EXIT_INVALID,
                format!(
                    "--set {item}: only {} can change when a run resumes; {key} would make it another run \
                     (start that one with slipfront run)",
                    RESUMABLE_KEYS.join(", ")
                ),
            ));
        }
    }
    let saved = &checkpoint.info.case;
    let overrides: Vec<String> = saved.overrides.iter().chain(&args.overrides).cloned().collect();
    let case = case::from_str(&saved.text, &overrides)
        .map_err(|e| fail(EXIT_INVALID, format!("{} (the case saved in it): {e}", args.checkpoint.display())))?;
    fits_in_memory(&case).map_err(|e| fail(EXIT_INVALID, format!("{}: {e}", args.checkpoint.display())))?;
    let (time, _) = checkpoint.time_and_step();
    if case.time.t_end < time {
        return Err(fail(
            EXIT_INVALID,
            format!(
                "time.t_end = {} lies before the checkpoint's time, {time} s: a run resumes forward",
                crate::validate::shortest(case.time.t_end)
            ),
        ));
    }
    Ok((checkpoint, case))
}

/// The case's scene in the checkpoint's state; a state that does not fit the case (another
/// mesh, another integrator) is refused.
fn restored_scene(args: &ResumeArgs, case: &case::Case, checkpoint: &Checkpoint) -> Result<Box<dyn Scene>, ExitCode> {
    let mut scene = scene::build(case).map_err(|e| fail(EXIT_FAILED, e))?;
    scene
        .restore(checkpoint.run.scene.clone())
        .map_err(|e| fail(EXIT_INVALID, format!("{}: {e}", args.checkpoint.display())))?;
    Ok(scene)
}

/// Where a resumed run reads the earlier run's files and writes its own.
struct Outputs {
    events: PathBuf,
    ruptures: PathBuf,
    rrd: Option<Continuation>,
    mcap: Option<Continuation>,
}

impl Outputs {
    /// The outputs in `out_dir` under the earlier run's file names.
    fn new(info: &CheckpointInfo, out_dir: &Path) -> Self {
        let target = |path: &Path| out_dir.join(path.file_name().unwrap_or_default());
        let continuation = |previous: &PathBuf| {
            let target = target(previous);
            let name = target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            Continuation {
                previous: previous.clone(),
                writing: target.with_file_name(format!(".{name}.resuming")),
                target,
            }
        };
        Self {
            events: target(&info.outputs.events),
            ruptures: target(&info.outputs.ruptures),
            rrd: info.outputs.rrd.as_ref().map(continuation),
            mcap: info.outputs.mcap.as_ref().map(continuation),
        }
    }

    fn named(&self, block: bool) -> Vec<Named<'_>> {
        let mut named: Vec<Named<'_>> =
            self.rrd.iter().map(|c| Named { role: "the recording", path: &c.target }).collect();
        named.extend(self.mcap.iter().map(|c| Named { role: "the MCAP log", path: &c.target }));
        named.push(Named { role: "the event catalog", path: &self.events });
        if block {
            named.push(Named { role: "the rupture catalog", path: &self.ruptures });
        }
        named
    }

    /// Checks and locks the outputs; the earlier run's recording and log must be there, and
    /// must decode without ending the process ([`crate::cli::isolated`]).
    fn claim(&self, checkpoint: &Path, block: bool) -> Result<outputs::Locks, String> {
        for c in self.rrd.iter().chain(&self.mcap) {
            if !c.previous.is_file() {
                return Err(format!(
                    "{} continues {}, which is missing: restore it, or start the run again",
                    checkpoint.display(),
                    c.previous.display()
                ));
            }
        }
        if let Some(c) = &self.rrd
            && let Some(failure) = crate::cli::isolated::decoder_failure(&c.previous)
        {
            return Err(format!("{failure}: the run cannot be continued from it"));
        }
        outputs::claim(&[Named { role: "checkpoint", path: checkpoint }], &self.named(block))
    }

    /// The catalog writer, the continued log and the continued recording.
    fn sinks(&self, info: &CheckpointInfo, case: &case::Case) -> Result<Vec<Box<dyn Sink>>, ExitCode> {
        let mut plan = RecordingPlan::for_case(&info.case.stem, case);
        plan.recording_id = info.recording_id.clone();
        let mut sinks: Vec<Box<dyn Sink>> =
            vec![Box::new(CatalogSink::new(self.events.clone(), Some(self.ruptures.clone())))];
        if let Some(c) = &self.mcap {
            let sink = McapSink::create(&c.writing, plan.clone()).map_err(|e| fail(EXIT_INVALID, e))?;
            sinks.push(Box::new(sink.continuing(c.clone())));
        }
        if let Some(c) = &self.rrd {
            let stream = open_stream(Some(&c.writing), &Viewer::None, &info.case.stem, plan.recording_id.as_deref())
                .map_err(|e| fail(EXIT_INVALID, e))?
                .expect("a file was asked for");
            sinks.push(Box::new(RerunSink::new(stream, plan).continuing(c.clone())));
        }
        Ok(sinks)
    }

    /// The outputs as the next checkpoints record them.
    fn saved(&self, out_dir: &Path) -> SavedOutputs {
        let rrd = self.rrd.as_ref().map(|c| c.target.as_path());
        let mcap = self.mcap.as_ref().map(|c| c.target.as_path());
        SavedOutputs::new(out_dir, &self.events, &self.ruptures, rrd, mcap)
    }

    /// Compacts the recording; removes a file that was being written but never reached its
    /// target (the run stopped before its continued part was on the disk).
    fn tidy(&self) {
        for c in self.rrd.iter().chain(&self.mcap) {
            let _ = std::fs::remove_file(&c.writing);
        }
        if let Some(c) = &self.rrd {
            compact_recording(&c.target);
        }
    }

    fn written(&self, block: bool) -> String {
        self.named(block).iter().map(|n| n.path.display().to_string()).collect::<Vec<_>>().join(", ")
    }
}
