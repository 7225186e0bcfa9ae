//! A digest of each recorded time series. The Rerun sink writes it with the run's ending
//! record; `slipfront check` recomputes it from the rows it decodes. A value changed inside a
//! recording that still decodes (a flipped bit in an uncompressed value buffer) is then
//! reported as damage rather than read as data. The footer's checksum covers only the footer,
//! and Rerun's chunks carry no checksum of their own.

use xxhash_rust::xxh3::Xxh3;
use xxhash_rust::xxh32::Xxh32;

/// Seed of every series digest.
const SEED: u32 = 0x51f0_0001;

/// The running digest of one series: 64-bit `xxh3` over each row's step, its time in whole
/// nanoseconds as the recording stores it ([`nanos`]), and the bits of its value, each as
/// eight little-endian bytes, in the order the rows were written (by step). Written as 16
/// hexadecimal digits; recordings written before it hold the 8 digits of a 32-bit `xxh32`
/// over the same bytes, which [`SeriesDigest::matches`] still verifies.
#[derive(Clone)]
pub struct SeriesDigest(Xxh3);

impl Default for SeriesDigest {
    fn default() -> Self {
        Self(Xxh3::with_seed(u64::from(SEED)))
    }
}

impl SeriesDigest {
    /// Adds one row.
    pub fn add(&mut self, step: i64, seconds: f64, value: f64) {
        self.0.update(&row(step, seconds, value));
    }

    /// Adds the rows `(steps[i], nanos[i], values(i))` in one update of the hash, the same
    /// digest as [`SeriesDigest::add`] row by row at a fraction of its calls. `row_bytes` is a
    /// buffer of `24 × rows` bytes whose steps and times [`SeriesDigest::rows_template`] wrote;
    /// only the values are written here.
    pub fn add_rows(&mut self, row_bytes: &mut [u8], values: impl Iterator<Item = f64>) {
        for (row, value) in row_bytes.chunks_exact_mut(24).zip(values) {
            row[16..].copy_from_slice(&value.to_bits().to_le_bytes());
        }
        self.0.update(row_bytes);
    }

    /// The rows' steps and times as [`SeriesDigest::add`] hashes them, with room for values.
    pub fn rows_template(steps: &[i64], seconds: &[f64], row_bytes: &mut Vec<u8>) {
        row_bytes.clear();
        for (step, time) in steps.iter().zip(seconds) {
            row_bytes.extend_from_slice(&step.to_le_bytes());
            row_bytes.extend_from_slice(&nanos(*time).to_le_bytes());
            row_bytes.extend_from_slice(&[0; 8]);
        }
    }

    /// The digest of the rows added so far, as 16 hexadecimal digits.
    pub fn hex(&self) -> String {
        format!("{:016x}", self.0.digest())
    }

    /// The digest of a whole series.
    pub fn of(steps: &[i64], seconds: &[f64], values: &[f64]) -> String {
        let mut digest = Self::default();
        for ((step, time), value) in steps.iter().zip(seconds).zip(values) {
            digest.add(*step, *time, *value);
        }
        digest.hex()
    }

    /// Whether a whole series has the digest `written`: 16 digits as [`SeriesDigest::of`]
    /// gives them, or the 8 digits of the `xxh32` that recordings and checkpoints written
    /// before it hold.
    pub fn matches(steps: &[i64], seconds: &[f64], values: &[f64], written: &str) -> bool {
        if written.len() != 8 {
            return Self::of(steps, seconds, values) == written;
        }
        let mut digest = Xxh32::new(SEED);
        for ((step, time), value) in steps.iter().zip(seconds).zip(values) {
            digest.update(&row(*step, *time, *value));
        }
        format!("{:08x}", digest.digest()) == written
    }
}

/// One row's bytes as the series digests hash them.
fn row(step: i64, seconds: f64, value: f64) -> [u8; 24] {
    let mut row = [0u8; 24];
    row[..8].copy_from_slice(&step.to_le_bytes());
    row[8..16].copy_from_slice(&nanos(seconds).to_le_bytes());
    row[16..].copy_from_slice(&value.to_bits().to_le_bytes());
    row
}

/// The running digest of one topic of an MCAP log: `xxh32` over each message's sequence
/// number, log time (ns) and length, each little-endian, and its bytes, in the order written.
/// A checkpoint keeps it, so that `slipfront resume` knows the log it continues as this run's.
#[derive(Clone)]
pub struct MessageDigest(Xxh32);

impl Default for MessageDigest {
    fn default() -> Self {
        Self(Xxh32::new(SEED))
    }
}

impl MessageDigest {
    /// Adds one message.
    pub fn add(&mut self, sequence: u32, log_time: u64, data: &[u8]) {
        self.0.update(&sequence.to_le_bytes());
        self.0.update(&log_time.to_le_bytes());
        self.0.update(&(data.len() as u64).to_le_bytes());
        self.0.update(data);
    }

    /// The digest of the messages added so far, as 8 hexadecimal digits.
    pub fn hex(&self) -> String {
        format!("{:08x}", self.0.digest())
    }
}

/// Seconds as the recording stores them: whole nanoseconds, rounded as Rerun's
/// `TimeColumn::new_duration_secs` rounds them.
pub fn nanos(seconds: f64) -> i64 {
    (1e9 * seconds).round() as i64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_digest_sees_every_bit_of_every_row() {
        let steps = [0_i64, 1, 2];
        let times = [0.0, 0.01, 0.02];
        let values = [1.0, -2.5, 3.25];
        let whole = SeriesDigest::of(&steps, &times, &values);
        assert_eq!(whole, SeriesDigest::of(&steps, &times, &values), "deterministic");
        for bit in 0..64 {
            let mut changed = values;
            changed[1] = f64::from_bits(changed[1].to_bits() ^ (1 << bit));
            assert_ne!(SeriesDigest::of(&steps, &times, &changed), whole, "value bit {bit}");
        }
        assert_ne!(SeriesDigest::of(&[0, 1, 3], &times, &values), whole, "a step");
        assert_ne!(SeriesDigest::of(&steps, &[0.0, 0.01, 0.020000001], &values), whole, "a time");
        assert_ne!(SeriesDigest::of(&steps[..2], &times[..2], &values[..2]), whole, "a row less");
        // Rows added in bulk give the digest of rows added one by one.
        let mut bulk = SeriesDigest::default();
        let mut template = Vec::new();
        SeriesDigest::rows_template(&steps[..1], &times[..1], &mut template);
        bulk.add_rows(&mut template, values[..1].iter().copied());
        SeriesDigest::rows_template(&steps[1..], &times[1..], &mut template);
        bulk.add_rows(&mut template, values[1..].iter().copied());
        assert_eq!(bulk.hex(), whole);
        // Times as read back (whole nanoseconds over 1e9) give the same digest.
        let read: Vec<f64> = times.iter().map(|t| nanos(*t) as f64 / 1e9).collect();
        assert_eq!(SeriesDigest::of(&steps, &read, &values), whole);
        assert!(SeriesDigest::matches(&steps, &times, &values, &whole));
        assert!(!SeriesDigest::matches(&steps, &times, &[1.0, -2.5, 3.5], &whole));
    }

    /// The 16 digits are XXH3-64 with the seed, as the reference implementation gives them for
    /// the same bytes; the 8 digits of recordings written before are XXH32 of those bytes.
    #[test]
    fn digests_are_the_reference_hashes_of_the_rows() {
        let (steps, times, values) = ([3_i64, 4], [0.5, 0.75], [1.5_f64, -0.0]);
        let mut bytes = Vec::new();
        for i in 0..2 {
            bytes.extend_from_slice(&steps[i].to_le_bytes());
            bytes.extend_from_slice(&((times[i] * 1e9) as i64).to_le_bytes());
            bytes.extend_from_slice(&values[i].to_bits().to_le_bytes());
        }
        let xxh3 = xxhash_rust::xxh3::xxh3_64_with_seed(&bytes, u64::from(SEED));
        assert_eq!(SeriesDigest::of(&steps, &times, &values), format!("{xxh3:016x}"));
        let xxh32 = xxhash_rust::xxh32::xxh32(&bytes, SEED);
        assert!(SeriesDigest::matches(&steps, &times, &values, &format!("{xxh32:08x}")));
        assert!(!SeriesDigest::matches(&steps, &times, &values, &format!("{:08x}", xxh32 ^ 1)));
    }
}
