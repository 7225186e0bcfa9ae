//! The time loop: advances a scene step by step, keeps the event catalog, and hands every frame
//! to the sinks.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::case::{Case, TimeSpec};
use crate::catalog::events::{Catalog, EventDetector};
use crate::frame::Ending;
use crate::frame::{Frame, Layout, Needs};
use crate::progress::{Progress, ProgressMode};
use crate::scene::{RunError, Scene, SceneMemory};
use crate::sink::{Sink, SinkError, SinkMemory};

/// How a run ended. Every variant but `Sink` comes with the catalog up to the last good step.
#[derive(Debug)]
pub enum Outcome {
    /// All steps done: `steps` taken, and with adaptive stepping `rejected` attempts besides;
    /// an implicit Runge–Kutta method's Newton iterations and factorizations (0 otherwise).
    Completed {
        steps: u64,
        rejected: u64,
        newton_iterations: u64,
        factorizations: u64,
        wall: Duration,
        catalog: Catalog,
    },
    /// Stopped at a signal after `steps` steps; the sinks were finished.
    Interrupted { steps: u64, catalog: Catalog },
    /// A step failed; the sinks were finished with everything up to the last good step.
    Failed { error: RunError, catalog: Catalog },
    /// A sink could not write.
    Sink(SinkError),
}

/// Options of the loop.
pub struct LoopOptions<'a> {
    /// Show progress on stderr, as [`Self::progress_mode`] says.
    pub progress: bool,
    /// A bar in a terminal or lines in a log ([`ProgressMode::Auto`]), or as asked.
    pub progress_mode: ProgressMode,
    /// Set (e.g. by a signal handler) to stop after the current step.
    pub interrupt: Option<&'a AtomicBool>,
    /// Slip-rate threshold (m/s) and merge window (s) of the event catalog.
    pub slip_rate_threshold: f64,
    pub merge_within: f64,
    /// What the caller needs in every frame beyond what the sinks need (the catalog's event
    /// detector needs nothing more: every frame holds `1/R*` for its onsets).
    pub needs: Needs,
    /// Checkpoints to write, if any.
    pub checkpoints: Option<Checkpoints<'a>>,
    /// The loop's memory from a checkpoint, to continue from (the scene already restored
    /// from it): the sinks continue their files, and no initial frame is recorded.
    pub resume: Option<RunMemory>,
}

/// Checkpoints of a run: after the first step at or past every multiple of `every` simulated
/// seconds, and at the end of a completed run (after its last step, or before its closing
/// steps: [`run`]), the loop's [`RunMemory`] (the sinks' files on the disk up to that step)
/// is handed to `save`, with the time it stands for: the multiple, or `t_end`.
pub struct Checkpoints<'a> {
    pub every: f64,
    pub save: &'a mut dyn FnMut(&RunMemory, f64) -> Result<(), String>,
}

/// The run loop's state at a checkpoint: the steps taken and the last one's length, the
/// scene, the event detector with its open events and merge windows, and every sink's memory.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct RunMemory {
    pub steps: u64,
    pub last_dt: f64,
    pub scene: SceneMemory,
    pub detector: EventDetector,
    pub sinks: Vec<SinkMemory>,
}

impl LoopOptions<'_> {
    /// The case's catalog settings, without a progress bar, an interrupt flag or extra needs.
    pub fn for_case(case: &Case) -> Self {
        Self {
            progress: false,
            progress_mode: ProgressMode::Auto,
            interrupt: None,
            slip_rate_threshold: case.slip_rate_threshold(),
            merge_within: case.events.merge_within,
            needs: Needs::default(),
            checkpoints: None,
            resume: None,
        }
    }
}

/// What the frames of a run hold: every frame what the event detector and the caller need
/// (`every`), and a frame that some sink writes ([`Sink::writes`]) also what the sinks need
/// (`written`: the surface nodes, the drawn mesh). Most steps of a run in stick are not
/// written, so their frames skip the parts only written rows read.
#[derive(Debug, Clone, Copy)]
struct FrameNeeds {
    every: Needs,
    written: Needs,
}

/// The sinks and the event detector that observe a run, and the last frames they were given.
struct Observers<'s, 'b> {
    sinks: &'s mut [Box<dyn Sink + 'b>],
    detector: EventDetector,
    needs: FrameNeeds,
    /// Which sinks need more than `needs.every` ([`Sink::needs`]): only they are asked
    /// whether they write a frame.
    needy: Vec<bool>,
    /// The last frame built with `needs.written`.
    last: Option<Frame>,
    /// A later step's frame, built with `needs.every` only because no sink wrote it.
    unwritten: Option<Frame>,
}

impl Observers<'_, '_> {
    /// Hands every sink's buffers to the disk and saves the loop's memory after step `steps`
    /// (of `dt`) through `checkpoints`, as standing for the time `label`.
    fn checkpoint(
        &mut self,
        scene: &dyn Scene,
        steps: u64,
        dt: f64,
        checkpoints: &mut Checkpoints<'_>,
        label: f64,
    ) -> Result<(), SinkError> {
        let sinks = self.sinks.iter_mut().map(|sink| sink.checkpoint()).collect::<Result<Vec<_>, _>>()?;
        let memory = RunMemory { steps, last_dt: dt, scene: scene.memory(), detector: self.detector.clone(), sinks };
        (checkpoints.save)(&memory, label).map_err(SinkError)
    }

    /// Hands the frame of `scene`'s current state, after a step of `dt`, to the detector and
    /// every sink: with the parts only written rows read if some sink writes it.
    fn record_step(&mut self, scene: &dyn Scene, dt: f64) -> Result<(), SinkError> {
        let FrameNeeds { every, written } = self.needs;
        let frame = scene.frame(every, dt);
        let needy = self.sinks.iter().zip(&self.needy).filter(|(_, needy)| **needy);
        if every == written || needy.into_iter().any(|(sink, _)| sink.writes(&frame)) {
            let frame = if every == written { frame } else { scene.frame(written, dt) };
            self.unwritten = None;
            self.record(frame)
        } else {
            self.detector.record(&frame);
            let result = self.sinks.iter_mut().try_for_each(|sink| sink.record(&frame));
            self.unwritten = Some(frame);
            result
        }
    }

    /// Hands `frame`, built with `needs.written`, to the detector and every sink.
    fn record(&mut self, frame: Frame) -> Result<(), SinkError> {
        self.detector.record(&frame);
        let result = self.sinks.iter_mut().try_for_each(|sink| sink.record(&frame));
        self.last = Some(frame);
        result
    }

    /// Closes the catalog and finishes every sink (all of them, even after one fails) with the
    /// last good step's frame: built again in full from `scene` if no sink wrote it, where the
    /// scene still holds that step (Wilson's failed steps leave it as it was; an integrator
    /// whose failed step moved it does not), else the last frame a sink wrote.
    fn finish(mut self, ending: Ending, scene: &dyn Scene) -> Result<Catalog, SinkError> {
        if let Some(light) = self.unwritten.take() {
            let full = scene.frame(self.needs.written, light.dt);
            if full.step == light.step && full.time.to_bits() == light.time.to_bits() {
                self.last = Some(full);
            }
        }
        let catalog = self.detector.into_catalog();
        let mut first_error = Ok(());
        for sink in self.sinks.iter_mut() {
            let result = sink.finish(ending, self.last.as_ref(), &catalog);
            if first_error.is_ok() {
                first_error = result;
            }
        }
        first_error.map(|()| catalog)
    }
}

/// Runs `scene` from its current time to `time.t_end`: in steps of `time.dt` (on the grid
/// `k dt`), or in the steps an adaptive integrator chooses. The loop is begin → (step →
/// record)* → finish; every sink is finished however the run ends.
///
/// **A run's past does not depend on its end.** No step is shortened to land on `t_end`: a
/// step that may end past it (`t_end` off the grid of `dt`, or an adaptive step longer than
/// what is left) is taken as a longer run takes it, from a copy of the scene. If it does end
/// past `t_end`, the scene goes back to that copy, which is the run's last checkpoint, and the
/// run closes with steps that land on `t_end` ([`close`]). Those closing steps are the only
/// ones a longer run does not share, and no checkpoint holds them: a finished run extended by
/// `resume --set time.t_end=...` continues from the copy and takes every step the longer run
/// takes.
pub fn run(
    scene: &mut dyn Scene,
    time: &TimeSpec,
    sinks: &mut [Box<dyn Sink + '_>],
    mut options: LoopOptions<'_>,
) -> Outcome {
    let resume = options.resume.take();
    let mut k: u64 = resume.as_ref().map_or(0, |r| r.steps);
    let mut observers = match begin(scene, sinks, &options, resume) {
        Ok(begun) => begun,
        Err(e) => return Outcome::Sink(e),
    };
    let adaptive = time.adaptive_tolerance().is_some();
    let start = Instant::now();
    let mode = if options.progress { options.progress_mode } else { ProgressMode::None };
    let mut progress = Progress::new(mode, scene.time(), time.t_end);
    let mut checkpoints = options.checkpoints.take();
    let mut next_checkpoint = checkpoints.as_ref().map_or(f64::INFINITY, |c| after(scene.time(), c.every));
    let mut last_dt = 0.0;
    // Times within this of t_end are t_end.
    let slack = 1e-9 * time.dt;
    let mut closed = false;
    while time.t_end - scene.time() > slack {
        if options.interrupt.is_some_and(|flag| flag.load(Ordering::SeqCst)) {
            progress.clear();
            return match observers.finish(Ending::Interrupted, scene) {
                Ok(catalog) => Outcome::Interrupted { steps: k, catalog },
                Err(e) => Outcome::Sink(e),
            };
        }
        let limit = step_limit(scene, time, adaptive, k + 1);
        let before = (scene.time() + scene.longest_next_step(limit) > time.t_end + slack).then(|| scene.memory());
        let step = scene.advance(limit);
        if let Some(before) = before
            && (step.is_err() || scene.time() > time.t_end + slack)
        {
            // Past t_end: the run's shared past ends before this step.
            let closer = Closer { time, slack, last_dt };
            match closer.close_from(before, scene, &mut observers, &mut k, checkpoints.as_mut(), &mut progress) {
                Ok(()) => {
                    closed = true;
                    break;
                }
                Err(Closing::Run(error)) => return failed(&mut progress, observers, scene, error),
                Err(Closing::Sink(e)) => {
                    progress.clear();
                    let _ = observers.finish(Ending::Failed, scene);
                    return Outcome::Sink(e);
                }
            }
        }
        k += 1;
        let dt = match step {
            Ok(dt) => dt,
            Err(error) => return failed(&mut progress, observers, scene, error),
        };
        last_dt = dt;
        let mut recorded = observers.record_step(scene, dt);
        if let Some(c) = checkpoints.as_mut().filter(|c| scene.time() >= next_checkpoint - 1e-9 * c.every) {
            let label = next_checkpoint;
            recorded = recorded.and_then(|()| observers.checkpoint(scene, k, dt, c, label));
            next_checkpoint = after(scene.time(), c.every);
        }
        if let Err(e) = recorded {
            progress.clear();
            let _ = observers.finish(Ending::Failed, scene);
            return Outcome::Sink(e);
        }
        progress.show(k, scene.time());
    }
    progress.clear();
    // The end of a completed run is a checkpoint too, from which it can be extended (a closed
    // run's was written before its closing steps).
    if let Some(c) =
        checkpoints.as_mut().filter(|c| !closed && next_checkpoint - c.every < scene.time() - 1e-9 * c.every)
        && let Err(e) = observers.checkpoint(scene, k, last_dt, c, time.t_end)
    {
        let _ = observers.finish(Ending::Failed, scene);
        return Outcome::Sink(e);
    }
    let statistics = scene.statistics();
    match observers.finish(Ending::Completed, scene) {
        Ok(catalog) => Outcome::Completed {
            steps: k,
            rejected: statistics.rejected,
            newton_iterations: statistics.newton_iterations,
            factorizations: statistics.factorizations,
            wall: start.elapsed(),
            catalog,
        },
        Err(e) => Outcome::Sink(e),
    }
}

/// Why the closing steps stopped.
enum Closing {
    Run(RunError),
    Sink(SinkError),
}

/// How a run that stepped past `t_end` ends ([`run`]).
struct Closer<'t> {
    time: &'t TimeSpec,
    /// Times within this of `t_end` are `t_end`.
    slack: f64,
    /// The last shared step's length.
    last_dt: f64,
}

impl Closer<'_> {
    /// Returns the scene to `before` (the state after step `k`, the last a longer run shares),
    /// writes the run's last checkpoint there, and closes the run with steps of at most what is
    /// left, each recorded, until `t_end`. Nothing continues from the closing steps.
    fn close_from(
        &self,
        before: SceneMemory,
        scene: &mut dyn Scene,
        observers: &mut Observers<'_, '_>,
        k: &mut u64,
        checkpoints: Option<&mut Checkpoints<'_>>,
        progress: &mut Progress,
    ) -> Result<(), Closing> {
        scene.restore(before).map_err(|message| {
            Closing::Run(RunError {
                step: *k + 1,
                time: scene.time(),
                segment: None,
                message: format!("cannot return to the state before the step past t_end: {message}"),
            })
        })?;
        if let Some(c) = checkpoints {
            observers.checkpoint(scene, *k, self.last_dt, c, self.time.t_end).map_err(Closing::Sink)?;
        }
        while self.time.t_end - scene.time() > self.slack {
            *k += 1;
            let dt = scene.advance(self.time.t_end - scene.time()).map_err(Closing::Run)?;
            observers.record_step(scene, dt).map_err(Closing::Sink)?;
            progress.show(*k, scene.time());
        }
        Ok(())
    }
}

/// Finishes the sinks of a run whose step failed.
fn failed(progress: &mut Progress, observers: Observers<'_, '_>, scene: &dyn Scene, error: RunError) -> Outcome {
    progress.clear();
    match observers.finish(Ending::Failed, scene) {
        Ok(catalog) => Outcome::Failed { error, catalog },
        Err(e) => Outcome::Sink(e),
    }
}

/// The first multiple of `every` after `time` (with a little slack for rounding in the time).
fn after(time: f64, every: f64) -> f64 {
    every * ((time / every + 1e-9).floor() + 1.0)
}

/// Begins every sink (all of them even if one fails, so that the others are finished as
/// valid, empty files of a failed run) and records the initial frame, or, resuming, hands
/// every sink its memory and the detector its own. Returns the observers.
fn begin<'s, 'b>(
    scene: &dyn Scene,
    sinks: &'s mut [Box<dyn Sink + 'b>],
    options: &LoopOptions<'_>,
    resume: Option<RunMemory>,
) -> Result<Observers<'s, 'b>, SinkError> {
    let layout: Layout = scene.layout().clone();
    let mut begun = Ok(());
    for sink in sinks.iter_mut() {
        let result = sink.begin(&layout);
        if begun.is_ok() {
            begun = result;
        }
    }
    // Asked after `begin`: a sink learns from the layout what it will read (an MCAP log's
    // node selection, say).
    let written = sinks.iter().fold(options.needs, |n, s| n.union(s.needs()));
    // Every frame holds what the detector reads (each segment's traction, slip, rate and `1/R*`);
    // the segments' full state only frames a sink writes.
    let every = options.needs;
    let detector = EventDetector::new(layout.segments.len(), options.slip_rate_threshold, options.merge_within)
        .with_instantaneous_rates(layout.instantaneous_slip_rate)
        .with_contacts(layout.contacts.iter().map(|c| c.segments).collect());
    let detector = if layout.evolving_normal {
        detector.with_openings(layout.segments.iter().map(|s| s.right - s.left).collect())
    } else {
        detector
    };
    let needs = FrameNeeds { every, written };
    let needy = sinks.iter().map(|s| s.needs().union(every) != every).collect();
    let mut observers = Observers { sinks, detector, needs, needy, last: None, unwritten: None };
    if let Err(e) = begun {
        // The initial state is the last good step: the sinks that began keep it.
        observers.last = Some(scene.frame(written, 0.0));
        let _ = observers.finish(Ending::Failed, scene);
        return Err(e);
    }
    if let Some(memory) = resume {
        let resumed = observers.sinks.iter_mut().try_for_each(|sink| sink.resume(&memory.sinks));
        observers.detector = memory.detector;
        observers.last = Some(scene.frame(written, memory.last_dt));
        if let Err(e) = resumed {
            let _ = observers.finish(Ending::Failed, scene);
            return Err(e);
        }
        return Ok(observers);
    }
    if let Err(e) = observers.record(scene.frame(written, 0.0)) {
        let _ = observers.finish(Ending::Failed, scene);
        return Err(e);
    }
    Ok(observers)
}

/// The most step `k` may take: with fixed steps, to `k dt` exactly (no drift); with adaptive
/// ones, no limit (the error control chooses). Never shortened to `t_end` ([`run`]).
fn step_limit(scene: &dyn Scene, time: &TimeSpec, adaptive: bool, k: u64) -> f64 {
    if adaptive { f64::INFINITY } else { k as f64 * time.dt - scene.time() }
}
