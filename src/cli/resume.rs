//! `slipfront resume CHECKPOINT`: a run continued from its checkpoint to its end (or to a new
//! `time.t_end`), its recording, MCAP log and catalogs left as those of one uninterrupted run.
//!
//! All or nothing: everything is checked before any output is touched (the checkpoint, its
//! case, the options, and that the recording and log beside it are its run's up to its step);
//! the continued outputs and checkpoints are written beside the files they replace
//! ([`checkpoints::resuming`]) and renamed over them only once the run has finished them. A
//! resume that is refused, fails to write (a full disk) or is killed leaves every file as it was.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use crate::case;
use crate::cli::checkpoints::{self, Saver, resuming};
use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, compact_recording, fail};
use crate::cli::outputs::{self, Named};
use crate::cli::run::{Reporting, fits_in_memory, report};
use crate::cli::signals::Stop;
use crate::record::checkpoint::{self, Checkpoint, CheckpointInfo, SavedOutputs};
use crate::record::continuation::{verify_log, verify_recording};
use crate::record::schema::RecordingPlan;
use crate::run::{Checkpoints, LoopOptions, Outcome, RunMemory, run};
use crate::scene::{self, Scene};
use crate::sink::catalog::CatalogSink;
use crate::sink::mcap::McapSink;
use crate::sink::rerun::{RerunSink, Viewer, open_stream};
use crate::sink::{Continuation, Sink, SinkMemory};

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
    /// Folder for every output [default: the checkpoint's own, where the run's outputs are
    /// continued in place]. The recording and log are continued from the checkpoint's folder.
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

/// Runs `slipfront resume`: the checkpoint, its case and the files it continues checked, the
/// loop run from the saved state into files beside the outputs, those renamed over the
/// outputs once finished, and the outcome reported.
pub fn command(args: ResumeArgs) -> ExitCode {
    let (checkpoint, case, every) = match prepare(&args) {
        Ok(prepared) => prepared,
        Err(exit) => return exit,
    };
    let mut scene = match restored_scene(&args, &case, &checkpoint) {
        Ok(scene) => scene,
        Err(exit) => return exit,
    };
    let info = &checkpoint.info;
    let folder = checkpoint::folder_of(&args.checkpoint);
    let out_dir = args.out_dir.clone().unwrap_or_else(|| folder.clone());
    let outputs = Outputs::new(&info.outputs.in_folder(&folder), args.out_dir.as_deref());
    if let Err(e) = outputs.verify(&args.checkpoint, &checkpoint) {
        return fail(EXIT_INVALID, format!("{e}; nothing was changed"));
    }
    if let Err(e) = std::fs::create_dir_all(&out_dir) {
        return fail(EXIT_INVALID, format!("cannot create output folder {}: {e}", out_dir.display()));
    }
    let block = scene.layout().kind.has_body();
    let _locks = match outputs.claim(&args.checkpoint, block) {
        Ok(locks) => locks,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    let mut sinks = match outputs.sinks(info, &case) {
        Ok(sinks) => sinks,
        Err(e) => {
            outputs.discard();
            return fail(EXIT_INVALID, e);
        }
    };
    let saved = CheckpointInfo { every, outputs: outputs.saved(&out_dir), ..info.clone() };
    let mut saver = Saver::new(&out_dir, saved, args.keep_checkpoints).staged();
    let mut save = |memory: &RunMemory, label: f64| saver.save(memory, label);
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
    if let Outcome::Sink(error) = outcome {
        outputs.discard();
        saver.discard();
        return fail(
            EXIT_FAILED,
            format!("{error}; the resume stopped there and nothing was changed: {}", outputs.written(block)),
        );
    }
    if let Err(e) = outputs.commit(block).and_then(|()| saver.commit()) {
        saver.discard();
        return fail(EXIT_FAILED, e);
    }
    let written = format!(
        "continued from t = {from_time:.3} s (step {from_step}): {}; {}",
        outputs.written(block),
        saver.summary()
    );
    let reporting = Reporting { case_file: &info.case.path, quiet: args.quiet };
    report(reporting, &case, outcome, &written, &stop, scene.time())
}

/// Reads the checkpoint and its case with the overrides allowed on resume, and the interval
/// between the resumed run's checkpoints.
fn prepare(args: &ResumeArgs) -> Result<(Checkpoint, case::Case, f64), ExitCode> {
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
    // A mesh is read from beside the case file, where the run found it.
    let case_dir = saved.case_dir();
    let case = case::from_str_at(&saved.text, &overrides, &case_dir)
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
    let every = match args.checkpoint_every.as_deref() {
        Some(value) => checkpoints::interval(Some(value), case.time.t_end).map_err(|e| fail(EXIT_INVALID, e))?,
        None => checkpoint.info.every,
    };
    Ok((checkpoint, case, every))
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

/// One file of a resumed run: the file it replaces (`target`), written first as `staged`
/// beside it.
struct Output {
    role: &'static str,
    target: PathBuf,
    staged: PathBuf,
}

impl Output {
    fn new(role: &'static str, target: PathBuf) -> Self {
        Self { role, staged: resuming(&target), target }
    }
}

/// Where a resumed run reads the earlier run's files and writes its own.
struct Outputs {
    events: Output,
    ruptures: Output,
    /// The recording and the log: the earlier run's file, and the continued one.
    rrd: Option<(PathBuf, Output)>,
    mcap: Option<(PathBuf, Output)>,
}

impl Outputs {
    /// The earlier run's outputs (`saved`, in the checkpoint's folder), continued in place or,
    /// with `out_dir`, under the same file names there.
    fn new(saved: &SavedOutputs, out_dir: Option<&Path>) -> Self {
        let target = |path: &Path| match out_dir {
            Some(dir) => dir.join(path.file_name().unwrap_or_default()),
            None => path.to_path_buf(),
        };
        let continued = |role, previous: &PathBuf| (previous.clone(), Output::new(role, target(previous)));
        Self {
            events: Output::new("the event catalog", target(&saved.events)),
            ruptures: Output::new("the rupture catalog", target(&saved.ruptures)),
            rrd: saved.rrd.as_ref().map(|p| continued("the recording", p)),
            mcap: saved.mcap.as_ref().map(|p| continued("the MCAP log", p)),
        }
    }

    /// The files written, the catalogs last: the order in which they are put in place.
    fn files(&self, block: bool) -> Vec<&Output> {
        let mut files: Vec<&Output> = self.rrd.iter().chain(&self.mcap).map(|(_, output)| output).collect();
        files.push(&self.events);
        if block {
            files.push(&self.ruptures);
        }
        files
    }

    /// Checks, before anything is written, that the recording and the log the checkpoint
    /// continues are there, regular files, decodable without ending the process
    /// ([`crate::cli::isolated`]), and its run's up to its step
    /// ([`crate::record::continuation`]).
    fn verify(&self, path: &Path, checkpoint: &Checkpoint) -> Result<(), String> {
        let id = checkpoint.info.recording_id.clone().unwrap_or_default();
        for (previous, output) in self.rrd.iter().chain(&self.mcap) {
            if !previous.exists() {
                return Err(format!(
                    "{} continues {}, which is missing: restore it, or start the run again",
                    path.display(),
                    previous.display()
                ));
            }
            crate::files::open_regular(previous, &format!("{} is the file the checkpoint's run wrote", output.role))?;
        }
        let memories = &checkpoint.run.sinks;
        if let Some((previous, _)) = &self.rrd {
            let memory = memories
                .iter()
                .find_map(|m| if let SinkMemory::Recording(r) = m { Some(r) } else { None })
                .ok_or("the checkpoint's run wrote no recording to continue")?;
            if let Some(failure) = crate::cli::isolated::decoder_failure(previous) {
                return Err(format!("{failure}: the run cannot be continued from it"));
            }
            verify_recording(previous, &id, memory.through as i64, memory.rows, &memory.digests)?;
        }
        if let Some((previous, _)) = &self.mcap {
            let memory = memories
                .iter()
                .find_map(|m| if let SinkMemory::Log(l) = m { Some(l) } else { None })
                .ok_or("the checkpoint's run wrote no MCAP log to continue")?;
            verify_log(previous, &id, memory.rows, &memory.digests)?;
        }
        Ok(())
    }

    /// Checks and locks the outputs ([`outputs::claim`]).
    fn claim(&self, checkpoint: &Path, block: bool) -> Result<outputs::Locks, String> {
        let named: Vec<Named<'_>> =
            self.files(block).iter().map(|output| Named { role: output.role, path: &output.target }).collect();
        outputs::claim(&[Named { role: "checkpoint", path: checkpoint }], &named)
    }

    /// The catalog writer, the continued log and the continued recording, each writing its
    /// staged file.
    fn sinks(&self, info: &CheckpointInfo, case: &case::Case) -> Result<Vec<Box<dyn Sink>>, String> {
        let mut plan = RecordingPlan::for_case(&info.case.stem, case);
        plan.recording_id = info.recording_id.clone();
        let catalogs = CatalogSink::new(self.events.staged.clone(), Some(self.ruptures.staged.clone()));
        let mut sinks: Vec<Box<dyn Sink>> = vec![Box::new(catalogs)];
        let continuation = |(previous, output): &(PathBuf, Output)| Continuation {
            previous: previous.clone(),
            writing: output.staged.clone(),
        };
        if let Some(log) = &self.mcap {
            let sink = McapSink::create(&log.1.staged, plan.clone())?;
            sinks.push(Box::new(sink.continuing(continuation(log))));
        }
        if let Some(recording) = &self.rrd {
            let stream =
                open_stream(Some(&recording.1.staged), &Viewer::None, &info.case.stem, plan.recording_id.as_deref())?
                    .ok_or("no recording stream")?;
            sinks.push(Box::new(RerunSink::new(stream, plan).continuing(continuation(recording))));
        }
        Ok(sinks)
    }

    /// The outputs as the next checkpoints record them.
    fn saved(&self, out_dir: &Path) -> SavedOutputs {
        let target = |c: &Option<(PathBuf, Output)>| c.as_ref().map(|(_, output)| output.target.clone());
        let (rrd, mcap) = (target(&self.rrd), target(&self.mcap));
        SavedOutputs::new(out_dir, &self.events.target, &self.ruptures.target, rrd.as_deref(), mcap.as_deref())
    }

    /// Compacts the continued recording and renames every staged file over its target, the
    /// catalogs last, then makes the renames durable. A compaction that fails leaves the
    /// recording as written, which is complete.
    fn commit(&self, block: bool) -> Result<(), String> {
        if let Some((_, recording)) = &self.rrd {
            compact_recording(&recording.staged);
        }
        let mut renamed = Vec::new();
        for output in self.files(block) {
            if let Err(e) = std::fs::rename(&output.staged, &output.target) {
                self.discard();
                return Err(format!(
                    "cannot rename {} to {}: {e}; {} continued, the rest as they were",
                    output.staged.display(),
                    output.target.display(),
                    if renamed.is_empty() { "none".to_string() } else { renamed.join(", ") }
                ));
            }
            renamed.push(output.target.display().to_string());
        }
        let folders: std::collections::BTreeSet<PathBuf> =
            self.files(block).iter().map(|o| checkpoint::folder_of(&o.target)).collect();
        for folder in folders {
            let _ = std::fs::File::open(folder).and_then(|f| f.sync_all());
        }
        Ok(())
    }

    /// Removes every staged file (a resume that stopped before it finished its outputs).
    fn discard(&self) {
        for output in self.files(true) {
            let _ = std::fs::remove_file(&output.staged);
        }
    }

    fn written(&self, block: bool) -> String {
        self.files(block).iter().map(|o| o.target.display().to_string()).collect::<Vec<_>>().join(", ")
    }
}
