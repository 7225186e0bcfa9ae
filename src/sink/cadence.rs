//! When a file sink hands what it has buffered to the disk: at least every [`EVERY`] of wall
//! clock and at most every [`ROWS`] recorded rows, whichever comes first. A process killed
//! without warning (SIGKILL, the out-of-memory killer, a batch system's time limit) then loses
//! at most that much of its recording and log, not the hundreds of simulated seconds a chunk of
//! thousands of rows holds.

use std::time::{Duration, Instant};

/// The longest a recorded row waits in memory.
pub const EVERY: Duration = Duration::from_secs(1);

/// The most rows held in memory.
pub const ROWS: usize = 512;

/// The clock and the count since the last hand-over.
#[derive(Debug)]
pub struct Cadence {
    since: Instant,
    rows: usize,
}

impl Default for Cadence {
    fn default() -> Self {
        Self { since: Instant::now(), rows: 0 }
    }
}

impl Cadence {
    /// Counts one recorded row; whether what is buffered should go to the disk now (the
    /// cadence then restarts).
    pub fn row(&mut self) -> bool {
        self.rows += 1;
        let due = self.rows >= ROWS || self.since.elapsed() >= EVERY;
        if due {
            *self = Self::default();
        }
        due
    }
}
