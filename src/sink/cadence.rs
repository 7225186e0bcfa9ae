//! When a file sink hands what it has buffered to the disk: at least every [`EVERY`] of wall
//! clock and at most every [`ROWS`] recorded rows, whichever comes first. A process killed
//! without warning (SIGKILL, the out-of-memory killer, a batch system's time limit) then loses
//! at most that much of its recording and log: a second of computing, not the hundreds of
//! simulated seconds a chunk filled by rows alone would hold.
//!
//! [`ROWS`] weighs two costs. Each chunk costs Rerun a schema and an IPC message, whatever its
//! rows: on the paper case, chunks of 4 096 rows instead of 512 take Rerun's thread from about
//! 97 ms to 59 ms of CPU time. The last chunk is encoded while the run waits at its end, so it
//! should not be long. 2 048 rows cost the same CPU time as 4 096 and half the wait, and a killed
//! run loses at most half as many rows ([docs/performance.md](../../docs/performance.md), "The
//! recording's chunks").

use std::time::{Duration, Instant};

/// The longest a recorded row waits in memory.
pub const EVERY: Duration = Duration::from_secs(1);

/// The most rows held in memory, and so the most rows in a chunk of the file.
pub const ROWS: usize = 2048;

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
