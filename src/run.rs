//! The time loop: advances a scene step by step and hands every frame to the sinks.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::case::TimeSpec;
use crate::scene::{Needs, RunError, Scene};
use crate::sink::{Ending, Sink, SinkError};

/// How a run ended.
#[derive(Debug)]
pub enum Outcome {
    /// All steps done.
    Completed { steps: u64, wall: Duration },
    /// Stopped at a signal after `steps` steps; the sinks were finished.
    Interrupted { steps: u64 },
    /// A step failed; the sinks were finished with everything up to the last good step.
    Failed(RunError),
    /// A sink could not write.
    Sink(SinkError),
}

/// Options of the loop.
pub struct LoopOptions<'a> {
    /// Show a progress bar on stderr once the run has taken longer than a second.
    pub progress: bool,
    /// Set (e.g. by a signal handler) to stop after the current step.
    pub interrupt: Option<&'a AtomicBool>,
}

/// Runs `scene` from its current time to `time.t_end` in steps of `time.dt` (the last one
/// shortened to land on `t_end`).
pub fn run(
    scene: &mut dyn Scene,
    time: &TimeSpec,
    sinks: &mut [Box<dyn Sink + '_>],
    options: LoopOptions<'_>,
) -> Outcome {
    let needs = sinks.iter().fold(Needs::default(), |n, s| n.union(s.needs()));
    let layout = scene.layout().clone();
    for sink in sinks.iter_mut() {
        if let Err(e) = sink.begin(&layout) {
            return Outcome::Sink(e);
        }
    }
    let finish = |sinks: &mut [Box<dyn Sink + '_>], ending: Ending| -> Result<(), SinkError> {
        let mut first_error = Ok(());
        for sink in sinks.iter_mut() {
            let result = sink.finish(ending);
            if first_error.is_ok() {
                first_error = result;
            }
        }
        first_error
    };
    let initial = scene.frame(needs, 0.0);
    for sink in sinks.iter_mut() {
        if let Err(e) = sink.record(&initial) {
            let _ = finish(sinks, Ending::Failed);
            return Outcome::Sink(e);
        }
    }

    let steps = time.steps();
    let start = Instant::now();
    let bar = ProgressBar::with_draw_target(Some(steps), ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} steps, t = {msg} s, eta {eta}")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    let mut shown = false;
    for k in 1..=steps {
        if options.interrupt.is_some_and(|flag| flag.load(Ordering::SeqCst)) {
            bar.finish_and_clear();
            return match finish(sinks, Ending::Interrupted) {
                Ok(()) => Outcome::Interrupted { steps: k - 1 },
                Err(e) => Outcome::Sink(e),
            };
        }
        let target = if k == steps { time.t_end } else { k as f64 * time.dt };
        let dt = target - scene.time();
        if let Err(error) = scene.advance(dt) {
            bar.finish_and_clear();
            return match finish(sinks, Ending::Failed) {
                Ok(()) => Outcome::Failed(error),
                Err(e) => Outcome::Sink(e),
            };
        }
        let frame = scene.frame(needs, dt);
        for sink in sinks.iter_mut() {
            if let Err(e) = sink.record(&frame) {
                bar.finish_and_clear();
                let _ = finish(sinks, Ending::Failed);
                return Outcome::Sink(e);
            }
        }
        if options.progress && k % 64 == 0 {
            if !shown && start.elapsed() > Duration::from_secs(1) {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                shown = true;
            }
            bar.set_position(k);
            bar.set_message(format!("{:.1}", scene.time()));
        }
    }
    bar.finish_and_clear();
    match finish(sinks, Ending::Completed) {
        Ok(()) => Outcome::Completed { steps, wall: start.elapsed() },
        Err(e) => Outcome::Sink(e),
    }
}
