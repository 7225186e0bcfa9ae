//! Writing checkpoints for `slipfront run --checkpoint-every` and `slipfront resume`: where they
//! go (`<out-dir>/<stem>.ckpt`, and with `--keep-checkpoints` `<stem>.<T>s.ckpt` besides, T the multiple of the
//! interval, or `t_end` for the run's last),
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

/// `.<name>.resuming` beside `path`: where a resumed run writes what will replace `path` once
/// the run has finished it.
pub fn resuming(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!(".{name}.resuming"))
}

/// Writes a run's checkpoints and counts what they cost.
pub struct Saver {
    pub path: PathBuf,
    keep: bool,
    info: CheckpointInfo,
    /// Whether checkpoints go first to their [`resuming`] names, for [`Saver::commit`] (a
    /// resumed run's, which must not replace the checkpoint it continues before its outputs
    /// are in place).
    staged: bool,
    /// The checkpoints written under their staged names, with the names they go to.
    pending: Vec<(PathBuf, PathBuf)>,
    /// Checkpoints written, their total size (bytes) and time.
    pub written: u64,
    pub bytes: u64,
    pub spent: Duration,
}

impl Saver {
    /// Checkpoints of the run `info` describes, to `<out_dir>/<stem>.ckpt`.
    pub fn new(out_dir: &Path, info: CheckpointInfo, keep: bool) -> Self {
        let path = out_dir.join(format!("{}.ckpt", info.case.stem));
        Self { path, keep, info, staged: false, pending: Vec::new(), written: 0, bytes: 0, spent: Duration::ZERO }
    }

    /// The same writer, writing every checkpoint under its [`resuming`] name until
    /// [`Saver::commit`].
    /// Staged checkpoints left by a resume that was killed are removed first.
    pub fn staged(self) -> Self {
        let folder = crate::record::checkpoint::folder_of(&self.path);
        let stem = format!(".{}.", self.info.case.stem);
        for entry in std::fs::read_dir(&folder).into_iter().flatten().flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            let staged = name.ends_with(".ckpt.resuming") || name.ends_with(".ckpt.resuming.writing");
            if staged && name.trim_start_matches('.').starts_with(&stem[1..]) {
                let _ = std::fs::remove_file(entry.path());
            }
        }
        Self { staged: true, ..self }
    }

    /// Writes `memory` as the latest checkpoint (and, when kept, under `label`, the time it
    /// stands for: the multiple of the interval it was taken after, or the run's `t_end`).
    pub fn save(&mut self, memory: &RunMemory, label: f64) -> Result<(), String> {
        let start = Instant::now();
        // Named to 6 significant digits: `300s` for a checkpoint at 300.007 s, not
        // `300.00000000000006s`; the exact time is inside, and `resume` prints it.
        let label: f64 = format!("{label:.5e}").parse().unwrap_or(label);
        let kept = self.keep.then(|| self.path.with_file_name(format!("{}.{label}s.ckpt", self.info.case.stem)));
        if let Some(kept) = kept.as_ref().filter(|k| k.exists() && !k.is_file()) {
            return Err(format!("cannot keep the checkpoint as {}: it is not a file", kept.display()));
        }
        let (path, kept) = match self.staged {
            false => (self.path.clone(), kept),
            true => {
                let mut staged = |path: &PathBuf| {
                    let pair = (resuming(path), path.clone());
                    if !self.pending.contains(&pair) {
                        self.pending.push(pair.clone());
                    }
                    pair.0
                };
                let latest = staged(&self.path.clone());
                (latest, kept.as_ref().map(staged))
            }
        };
        self.bytes += checkpoint::write(&path, kept.as_deref(), &self.info, memory)?;
        self.written += 1;
        self.spent += start.elapsed();
        Ok(())
    }

    /// Renames the staged checkpoints to their own names, the latest last; a checkpoint that
    /// was never written leaves the one before in place.
    pub fn commit(&mut self) -> Result<(), String> {
        self.pending.sort_by_key(|(_, path)| *path == self.path);
        for (staged, path) in &self.pending {
            std::fs::rename(staged, path)
                .map_err(|e| format!("cannot rename {} to {}: {e}", staged.display(), path.display()))?;
        }
        self.pending.clear();
        Ok(())
    }

    /// Removes the staged checkpoints.
    pub fn discard(&mut self) {
        for (staged, _) in self.pending.drain(..) {
            let _ = std::fs::remove_file(staged);
        }
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
