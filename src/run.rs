//! The time loop: advances a scene step by step, keeps the event catalog, and hands every frame
//! to the sinks.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::case::{Case, TimeSpec};
use crate::dynamics::StepControl;
use crate::scene::{Frame, Layout, Needs, RunError, Scene};
use crate::sink::events::{Catalog, EventDetector};
use crate::sink::{Ending, Sink, SinkError};

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
    /// Show a progress bar on stderr once the run has taken longer than a second.
    pub progress: bool,
    /// Set (e.g. by a signal handler) to stop after the current step.
    pub interrupt: Option<&'a AtomicBool>,
    /// Slip-rate threshold (m/s) and merge window (s) of the event catalog.
    pub slip_rate_threshold: f64,
    pub merge_within: f64,
    /// What the caller needs in every frame beyond what the sinks need (e.g.
    /// [`Needs::segment_state`], for `1/R*` at the onsets of the catalog's events).
    pub needs: Needs,
}

impl LoopOptions<'_> {
    /// The case's catalog settings, without a progress bar, an interrupt flag or extra needs.
    pub fn for_case(case: &Case) -> Self {
        Self {
            progress: false,
            interrupt: None,
            slip_rate_threshold: case.slip_rate_threshold(),
            merge_within: case.events.merge_within,
            needs: Needs::default(),
        }
    }
}

/// The sinks and the event detector that observe a run, and the last frame they were given.
struct Observers<'s, 'b> {
    sinks: &'s mut [Box<dyn Sink + 'b>],
    detector: EventDetector,
    last: Option<Frame>,
}

impl Observers<'_, '_> {
    fn record(&mut self, frame: Frame) -> Result<(), SinkError> {
        self.detector.record(&frame);
        let result = self.sinks.iter_mut().try_for_each(|sink| sink.record(&frame));
        self.last = Some(frame);
        result
    }

    /// Closes the catalog and finishes every sink (all of them, even after one fails).
    fn finish(self, ending: Ending) -> Result<Catalog, SinkError> {
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

/// Runs `scene` from its current time to `time.t_end` in steps of `time.dt` (the last one
/// shortened to land on `t_end`).
pub fn run(
    scene: &mut dyn Scene,
    time: &TimeSpec,
    sinks: &mut [Box<dyn Sink + '_>],
    options: LoopOptions<'_>,
) -> Outcome {
    let layout: Layout = scene.layout().clone();
    // Every sink begins even if one fails (a full disk under one file), so that the others
    // are finished as valid, empty files of a failed run.
    let mut begun = Ok(());
    for sink in sinks.iter_mut() {
        let result = sink.begin(&layout);
        if begun.is_ok() {
            begun = result;
        }
    }
    // Asked after `begin`: a sink learns from the layout what it will read (an MCAP log's
    // node selection, say).
    let needs = sinks.iter().fold(options.needs, |n, s| n.union(s.needs()));
    let detector = EventDetector::new(layout.segments.len(), options.slip_rate_threshold, options.merge_within)
        .with_instantaneous_rates(layout.instantaneous_slip_rate);
    let mut observers = Observers { sinks, detector, last: None };
    if let Err(e) = begun {
        // The initial state is the last good step: the sinks that began keep it.
        observers.last = Some(scene.frame(needs, 0.0));
        let _ = observers.finish(Ending::Failed);
        return Outcome::Sink(e);
    }
    if let Err(e) = observers.record(scene.frame(needs, 0.0)) {
        let _ = observers.finish(Ending::Failed);
        return Outcome::Sink(e);
    }

    let steps = time.steps();
    let start = Instant::now();
    // Progress in thousandths of the simulated span, so that fixed and adaptive steps show alike.
    let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {msg}, eta {eta}")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    let mut control =
        time.adaptive_tolerance().map(|tolerance| StepControl::new(tolerance, time.dt, time.dt_max(), time.dt_min()));
    let mut shown = false;
    let mut k: u64 = 0;
    loop {
        let done = match &control {
            Some(_) => time.t_end - scene.time() <= 1e-9 * time.dt,
            None => k == steps,
        };
        if done {
            break;
        }
        if options.interrupt.is_some_and(|flag| flag.load(Ordering::SeqCst)) {
            bar.finish_and_clear();
            return match observers.finish(Ending::Interrupted) {
                Ok(catalog) => Outcome::Interrupted { steps: k, catalog },
                Err(e) => Outcome::Sink(e),
            };
        }
        k += 1;
        let advanced = match &mut control {
            Some(control) => scene.advance_adaptive(control, time.t_end - scene.time()),
            None => {
                // Step ends at k dt exactly (no drift), the last one at t_end.
                let target = if k == steps { time.t_end } else { k as f64 * time.dt };
                let dt = target - scene.time();
                scene.advance(dt).map(|()| dt)
            }
        };
        let dt = match advanced {
            Ok(dt) => dt,
            Err(error) => {
                bar.finish_and_clear();
                return match observers.finish(Ending::Failed) {
                    Ok(catalog) => Outcome::Failed { error, catalog },
                    Err(e) => Outcome::Sink(e),
                };
            }
        };
        if let Err(e) = observers.record(scene.frame(needs, dt)) {
            bar.finish_and_clear();
            let _ = observers.finish(Ending::Failed);
            return Outcome::Sink(e);
        }
        if options.progress && k.is_multiple_of(64) {
            if !shown && start.elapsed() > Duration::from_secs(1) {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                shown = true;
            }
            bar.set_position((1000.0 * scene.time() / time.t_end) as u64);
            bar.set_message(format!("t = {:.1} of {} s, step {k}", scene.time(), time.t_end));
        }
    }
    let steps = k;
    let counts = control.as_ref().map_or((0, 0, 0), |c| (c.rejected, c.newton_iterations, c.factorizations));
    let (rejected, newton_iterations, factorizations) = counts;
    bar.finish_and_clear();
    match observers.finish(Ending::Completed) {
        Ok(catalog) => {
            Outcome::Completed { steps, rejected, newton_iterations, factorizations, wall: start.elapsed(), catalog }
        }
        Err(e) => Outcome::Sink(e),
    }
}
