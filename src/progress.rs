//! A run's progress on stderr: a bar in a terminal, or a line every 10 s of wall clock where
//! stderr is a file or a pipe (a batch job's log). Both say the simulated time, the steps, the
//! simulated seconds per wall second and when the run should end, estimated from the recent
//! rate (the last [`RATE_WINDOW`] of wall clock) and said to be unknown while it cannot be told.

use std::collections::VecDeque;
use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How progress is shown.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum ProgressMode {
    /// A bar where stderr is a terminal, lines elsewhere.
    #[default]
    Auto,
    /// A bar, redrawn in place (drawn only where stderr is a terminal).
    Bar,
    /// A line every 10 s.
    Lines,
    /// Nothing.
    None,
}

/// Wall clock between two progress lines.
pub const LINE_EVERY: Duration = Duration::from_secs(10);
/// The environment variable that sets another interval between lines, in seconds (for tests).
pub const LINE_EVERY_VARIABLE: &str = "SLIPFRONT_PROGRESS_EVERY";
/// The wall clock over which the rate of the end's estimate is measured.
pub const RATE_WINDOW: Duration = Duration::from_secs(30);
/// The bar appears once the run has taken this long.
const BAR_AFTER: Duration = Duration::from_secs(1);
/// Redraws of the bar at most this often.
const BAR_EVERY: Duration = Duration::from_millis(200);

/// The simulated seconds per wall second over the recent past, from samples of (wall clock,
/// simulated time).
#[derive(Debug, Clone)]
pub struct RecentRate {
    window: Duration,
    samples: VecDeque<(Duration, f64)>,
}

impl RecentRate {
    pub fn new(window: Duration) -> Self {
        Self { window, samples: VecDeque::new() }
    }

    /// Adds the simulated time `t` reached at wall clock `wall`, forgetting samples older than
    /// the window (but keeping the newest of them, so the window is spanned).
    pub fn push(&mut self, wall: Duration, t: f64) {
        self.samples.push_back((wall, t));
        while self.samples.len() > 2 && wall.saturating_sub(self.samples[1].0) >= self.window {
            self.samples.pop_front();
        }
    }

    /// Simulated seconds per wall second over the samples kept; `None` before two samples a
    /// tenth of a second apart, and when the simulated time did not advance.
    pub fn rate(&self) -> Option<f64> {
        let (&(w0, t0), &(w1, t1)) = (self.samples.front()?, self.samples.back()?);
        let wall = (w1.saturating_sub(w0)).as_secs_f64();
        (wall >= 0.1 && t1 > t0).then(|| (t1 - t0) / wall)
    }

    /// Wall seconds until `t_end` from `t` at the recent rate, if it can be told.
    pub fn remaining(&self, t: f64, t_end: f64) -> Option<f64> {
        self.rate().map(|rate| (t_end - t).max(0.0) / rate)
    }
}

/// A duration for people: `45 s`, `6 min 20 s`, `2 h 05 min`.
pub fn human(seconds: f64) -> String {
    let s = seconds.round() as u64;
    match s {
        0..60 => format!("{s} s"),
        60..3600 => format!("{} min {:02} s", s / 60, s % 60),
        _ => format!("{} h {:02} min", s / 3600, (s % 3600) / 60),
    }
}

/// What a progress report says after step `k` at simulated time `t` of `t_end`.
pub fn describe(k: u64, t: f64, t_end: f64, rate: &RecentRate) -> String {
    let speed = match rate.rate() {
        Some(r) => format!("{} simulated s per wall s", significant(r)),
        None => "rate unknown".to_string(),
    };
    let end = match rate.remaining(t, t_end) {
        Some(left) if left < 0.5 => "end in under 1 s".to_string(),
        Some(left) => format!("end in about {}", human(left)),
        None => "end unknown".to_string(),
    };
    format!("t = {t:.1} s of {t_end} s ({:.1} %), step {k}, {speed}, {end}", 100.0 * t / t_end)
}

/// Three significant digits (`0.00123`, `2.31`, `1540`).
fn significant(x: f64) -> String {
    let digits = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.digits$}")
}

/// A run's progress on stderr, as its mode says.
pub struct Progress {
    mode: ProgressMode,
    start: Instant,
    t_end: f64,
    rate: RecentRate,
    every: Duration,
    next: Duration,
    bar: Option<ProgressBar>,
}

impl Progress {
    /// Progress of a run to `t_end` from simulated time `t`, starting now; `Auto` resolved by
    /// whether stderr is a terminal.
    pub fn new(mode: ProgressMode, t: f64, t_end: f64) -> Self {
        let mode = match mode {
            ProgressMode::Auto if std::io::stderr().is_terminal() => ProgressMode::Bar,
            ProgressMode::Auto => ProgressMode::Lines,
            other => other,
        };
        let every = if mode == ProgressMode::Bar { BAR_EVERY } else { line_every() };
        let mut rate = RecentRate::new(RATE_WINDOW);
        rate.push(Duration::ZERO, t);
        let next = if mode == ProgressMode::Bar { BAR_AFTER } else { every };
        Self { mode, start: Instant::now(), t_end, rate, every, next, bar: None }
    }

    /// After step `k`, at simulated time `t`: a line or a redraw when one is due.
    pub fn show(&mut self, k: u64, t: f64) {
        if self.mode == ProgressMode::None {
            return;
        }
        let wall = self.start.elapsed();
        if wall < self.next {
            return;
        }
        self.next = wall + self.every;
        self.rate.push(wall, t);
        let text = describe(k, t, self.t_end, &self.rate);
        if self.mode == ProgressMode::Lines {
            let _ = writeln!(std::io::stderr().lock(), "slipfront: [{}] {text}", clock(wall));
            return;
        }
        let t_end = self.t_end;
        let bar = self.bar.get_or_insert_with(|| {
            let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::stderr()).with_elapsed(wall);
            bar.set_style(
                ProgressStyle::with_template("{elapsed_precise} [{bar:20}] {msg}")
                    .expect("a valid template")
                    .progress_chars("=> "),
            );
            bar
        });
        bar.set_position((1000.0 * t / t_end) as u64);
        bar.set_message(text);
    }

    /// Removes the bar, if one was drawn.
    pub fn clear(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// `SLIPFRONT_PROGRESS_EVERY` seconds if set to a positive number, else [`LINE_EVERY`].
fn line_every() -> Duration {
    std::env::var(LINE_EVERY_VARIABLE)
        .ok()
        .and_then(|v| v.parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0)
        .map_or(LINE_EVERY, Duration::from_secs_f64)
}

/// Wall clock as `h:mm:ss`.
fn clock(wall: Duration) -> String {
    let s = wall.as_secs();
    format!("{}:{:02}:{:02}", s / 3600, (s % 3600) / 60, s % 60)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(seconds: f64) -> Duration {
        Duration::from_secs_f64(seconds)
    }

    #[test]
    fn the_end_is_unknown_until_the_simulated_time_advances() {
        let mut rate = RecentRate::new(RATE_WINDOW);
        rate.push(at(0.0), 0.0);
        assert_eq!(rate.remaining(0.0, 100.0), None, "one sample");
        rate.push(at(10.0), 0.0);
        assert_eq!(rate.remaining(0.0, 100.0), None, "no progress in 10 s");
        assert!(describe(64, 0.0, 100.0, &rate).ends_with("rate unknown, end unknown"));
    }

    #[test]
    fn the_end_follows_the_recent_rate_not_the_average() {
        let mut rate = RecentRate::new(at(30.0));
        // 50 simulated s in the first 10 s, then a crawl: 1 simulated s per 10 s for 60 s.
        rate.push(at(0.0), 0.0);
        rate.push(at(10.0), 50.0);
        for k in 1..=6 {
            rate.push(at(10.0 + 10.0 * k as f64), 50.0 + k as f64);
        }
        // The window keeps the samples from 40 s to 70 s: 3 s in 30 s.
        assert!((rate.rate().unwrap() - 0.1).abs() < 1e-12, "{:?}", rate.rate());
        assert!((rate.remaining(56.0, 100.0).unwrap() - 440.0).abs() < 1e-9);
        assert_eq!(human(440.0), "7 min 20 s");
        // The average over the run (56 s in 70 s) would have said 55 s.
    }

    #[test]
    fn durations_and_rates_read_plainly() {
        assert_eq!(human(0.4), "0 s");
        assert_eq!(human(7265.0), "2 h 01 min");
        assert_eq!(significant(2.3149), "2.31");
        assert_eq!(significant(0.0012345), "0.00123");
        assert_eq!(significant(1540.2), "1540");
    }
}
