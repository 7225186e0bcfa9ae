//! Writing checkpoints for `slipfront run --checkpoint-every` and `slipfront resume`: where they
//! go (`<out-dir>/<stem>.ckpt`, and with `--keep-checkpoints` `<stem>.<T>s.ckpt` besides, T the multiple of the interval),
//! what run they describe, and what they cost.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crate::record::checkpoint::{self, CheckpointInfo};
use crate::run::RunMemory;

/// The interval `--checkpoint-every` gives without a value: a tenth of the run.
pub const DEFAULT_SHARE: f64 = 0.1;

/// The interval (simulated s) that `--checkpoint-every VALUE` asks for; `None` (the option
/// without a value) is [`DEFAULT_SHARE`] of `t_end`.
pub fn interval(value: Option<&str>, t_end: f64) -> Result<f64, String> {
    let Some(value) = value else { return Ok(DEFAULT_SHARE * t_end) };
    match value.trim().parse::<f64>() {
        Ok(every) if every.is_finite() && every > 0.0 => Ok(every),
        _ => Err(format!(
            "--checkpoint-every {value}: not a positive number of simulated seconds (e.g. --checkpoint-every 100)"
        )),
    }
}

/// Writes a run's checkpoints and counts what they cost.
pub struct Saver {
    pub path: PathBuf,
    keep: bool,
    info: CheckpointInfo,
    /// Checkpoints written, their total size (bytes) and time.
    pub written: u64,
    pub bytes: u64,
    pub spent: Duration,
}

impl Saver {
    /// Checkpoints of the run `info` describes, to `<out_dir>/<stem>.ckpt`.
    pub fn new(out_dir: &Path, info: CheckpointInfo, keep: bool) -> Self {
        let path = out_dir.join(format!("{}.ckpt", info.case.stem));
        Self { path, keep, info, written: 0, bytes: 0, spent: Duration::ZERO }
    }

    /// Writes `memory` as the latest checkpoint (and, when kept, under its time).
    pub fn save(&mut self, memory: &RunMemory) -> Result<(), String> {
        let start = Instant::now();
        let (time, _) = memory.scene.time_and_step();
        // Named by the multiple of the interval it was taken at (after the first step reaching
        // it), to 6 significant digits: `300s` for a checkpoint at 300.007 s, not
        // `300.00000000000006s`; the exact time is inside, and `resume` prints it.
        let every = self.info.every;
        let multiple = ((time / every) * (1.0 + 1e-12)).floor() * every;
        let label: f64 = format!("{multiple:.5e}").parse().unwrap_or(multiple);
        let kept = self.keep.then(|| self.path.with_file_name(format!("{}.{label}s.ckpt", self.info.case.stem)));
        self.bytes += checkpoint::write(&self.path, kept.as_deref(), &self.info, memory)?;
        self.written += 1;
        self.spent += start.elapsed();
        Ok(())
    }

    /// `N checkpoints (size, time)` for the summary line.
    pub fn summary(&self) -> String {
        format!(
            "{} checkpoint{} ({:.1} MB, {:.2} s) in {}",
            self.written,
            if self.written == 1 { "" } else { "s" },
            self.bytes as f64 / 1e6,
            self.spent.as_secs_f64(),
            self.path.display()
        )
    }
}
