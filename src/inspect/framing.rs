//! Walks the framing of an untrusted `.rrd` or `.mcap` before a decoder sees it, and finds the
//! longest prefix whose records could be what they claim.
//!
//! Both decoders trust a length in a record header and allocate it before reading: the RRD
//! decoder of `re_log_encoding` 0.36 a message's `len`, the `mcap` 0.25 reader a chunk's
//! `uncompressed_size`. A damaged header claiming exabytes aborts the process (an allocation
//! failure is not a panic that can be caught). Fuzzing found both (`fuzz/run.sh`). The readers
//! therefore decode only the prefix before the first record that claims more than the file
//! holds (or, for a compressed MCAP chunk, more than [`MAX_CHUNK_BYTES`]), and say where they
//! stopped; everything before it is kept, as for any other damage.

use crate::inspect::arrow_message;

/// The largest uncompressed MCAP chunk believed (1 GiB). slipfront writes chunks of under 1 MiB;
/// other writers default to a few MiB.
pub const MAX_CHUNK_BYTES: u64 = 1 << 30;

/// The prefix to decode, and why it stops short of the whole input.
#[derive(Debug, Clone, PartialEq)]
pub struct Plausible {
    pub len: u64,
    pub problem: Option<String>,
}

impl Plausible {
    /// The plausible prefix of `bytes`.
    pub fn prefix<'a>(&self, bytes: &'a [u8]) -> &'a [u8] {
        &bytes[..usize::try_from(self.len).unwrap_or(bytes.len()).min(bytes.len())]
    }

    /// Puts why the input was shortened, if it was, in front of the reader's own `problem`.
    pub fn report_into(self, problem: &mut Option<String>) {
        if let Some(cut) = self.problem {
            *problem = Some(match problem.take() {
                Some(other) => format!("{cut}; {other}"),
                None => cut,
            });
        }
    }
}

/// Reads `buf.len()` bytes at `offset`; false if the input ends first.
pub trait ReadAt {
    fn read_at(&mut self, offset: u64, buf: &mut [u8]) -> bool;
}

impl ReadAt for &[u8] {
    fn read_at(&mut self, offset: u64, buf: &mut [u8]) -> bool {
        let Ok(start) = usize::try_from(offset) else { return false };
        match self.get(start..start.saturating_add(buf.len())) {
            Some(src) if src.len() == buf.len() => {
                buf.copy_from_slice(src);
                true
            }
            _ => false,
        }
    }
}

impl ReadAt for std::fs::File {
    fn read_at(&mut self, offset: u64, buf: &mut [u8]) -> bool {
        std::os::unix::fs::FileExt::read_exact_at(self, buf, offset).is_ok()
    }
}

fn u64_at(bytes: &[u8]) -> u64 {
    u64::from_le_bytes(bytes[..8].try_into().expect("8 bytes"))
}

/// Rerun's RRF2 framing: a 12-byte stream header (`RRF2`, version, options), then messages of a
/// 16-byte header (`kind`, `len`, little-endian u64) and `len` bytes; after the `End` message
/// (kind 0) a 32-byte stream footer, and possibly another stream.
pub fn rrd(input: &mut impl ReadAt, total: u64) -> Plausible {
    walk_rrd(input, total, |input, kind, pos, len| {
        if kind == ARROW_MSG
            && let Some(problem) = arrow_problem(input, pos + 16, len)
        {
            return Err(Plausible {
                len: pos,
                problem: Some(format!("the message at byte {pos}: {problem}; read up to it")),
            });
        }
        Ok(())
    })
}

/// How many `ArrowMsg` messages (chunks) the plausible prefix of an `.rrd` holds, from their
/// headers alone.
pub fn rrd_chunks(input: &mut impl ReadAt, total: u64) -> u64 {
    let mut chunks = 0;
    walk_rrd(input, total, |_, kind, _, _| {
        chunks += u64::from(kind == ARROW_MSG);
        Ok(())
    });
    chunks
}

/// Walks the messages of [`rrd`]'s framing, handing each `(kind, header position, len)` whose
/// length fits the input to `message`, which may stop the walk with its own verdict.
fn walk_rrd<R: ReadAt>(
    input: &mut R,
    total: u64,
    mut message: impl FnMut(&mut R, u64, u64, u64) -> Result<(), Plausible>,
) -> Plausible {
    let whole = Plausible { len: total, problem: None };
    let mut pos = 0u64;
    'streams: loop {
        let mut header = [0u8; 12];
        if !input.read_at(pos, &mut header) || !matches!(&header[..4], b"RRF0" | b"RRF1" | b"RRF2") {
            // The end, or bytes the decoder will judge itself (not a recording, trailing bytes).
            return whole;
        }
        pos += 12;
        loop {
            let mut head = [0u8; 16];
            if !input.read_at(pos, &mut head) {
                return whole;
            }
            let (kind, len) = (u64_at(&head[..8]), u64_at(&head[8..]));
            if kind > 3 {
                // The decoder takes an unknown kind for the start of a concatenated stream.
                continue 'streams;
            }
            let room = total.saturating_sub(pos + 16);
            if len > room {
                return Plausible {
                    len: pos,
                    problem: Some(format!(
                        "the message at byte {pos} claims {len} bytes but only {room} follow; read up to it"
                    )),
                };
            }
            if let Err(verdict) = message(input, kind, pos, len) {
                return verdict;
            }
            pos += 16 + len;
            if kind == 0 {
                pos += 32;
                continue 'streams;
            }
        }
    }
}

/// The RRD message kind of an `ArrowMsg`.
const ARROW_MSG: u64 = 2;

/// What is wrong inside the `ArrowMsg` of `len` bytes at `pos` ([`arrow_message::problem`]);
/// `len` was checked against the input's size, so reading it allocates no more than the file.
fn arrow_problem(input: &mut impl ReadAt, pos: u64, len: u64) -> Option<String> {
    let mut message = vec![0u8; usize::try_from(len).ok()?];
    if !input.read_at(pos, &mut message) {
        return None;
    }
    arrow_message::problem(&message)
}

/// MCAP framing: the 8-byte magic, then records of an opcode byte, a little-endian u64 length
/// and that many bytes. A chunk (opcode 0x06) starts with its start and end times and its
/// uncompressed size.
pub fn mcap(input: &mut impl ReadAt, total: u64) -> Plausible {
    let whole = Plausible { len: total, problem: None };
    let mut pos = 8u64;
    loop {
        let mut record = [0u8; 9 + 24];
        let have_chunk_header = input.read_at(pos, &mut record);
        if !have_chunk_header && !input.read_at(pos, &mut record[..9]) {
            return whole;
        }
        let (opcode, len) = (record[0], u64_at(&record[1..9]));
        let room = total.saturating_sub(pos + 9);
        if len > room {
            // A record cut off at the end is an ordinary truncation, which the reader reports; a
            // length far beyond the file is damage in the header.
            return if len > total {
                Plausible {
                    len: pos,
                    problem: Some(format!(
                        "the record at byte {pos} claims {len} bytes but only {room} follow; read up to it"
                    )),
                }
            } else {
                whole
            };
        }
        if opcode == 0x06 && have_chunk_header {
            let uncompressed = u64_at(&record[9 + 16..]);
            let problem = if uncompressed > MAX_CHUNK_BYTES {
                Some(format!(
                    "the chunk at byte {pos} claims {uncompressed} bytes uncompressed (more than \
                     {MAX_CHUNK_BYTES} is taken for damage); read up to it"
                ))
            } else {
                chunk_problem(input, pos, len, uncompressed)
            };
            if problem.is_some() {
                return Plausible { len: pos, problem };
            }
        }
        if opcode == 0x02 {
            // The footer: nothing follows but the closing magic.
            return whole;
        }
        pos += 9 + len;
    }
}

/// Checks the records inside the chunk at `pos` (record length `len`): each must fit in what
/// is left of the chunk's `uncompressed` bytes, or the reader would allocate what it claims.
fn chunk_problem(input: &mut impl ReadAt, pos: u64, len: u64, uncompressed: u64) -> Option<String> {
    let damaged = |what: &str| Some(format!("the chunk at byte {pos} is damaged ({what}); read up to it"));
    let Ok(size) = usize::try_from(len) else { return damaged("too large") };
    let mut body = vec![0u8; size];
    if !input.read_at(pos + 9, &mut body) {
        return None; // cut off at the end: an ordinary truncation
    }
    // start time, end time, uncompressed size (u64 each), CRC (u32), compression (u32 length
    // and the name), records length (u64), records.
    let name_len = body.get(28..32).map(|b| u32::from_le_bytes(b.try_into().expect("4 bytes")) as usize)?;
    let name = body.get(32..32 + name_len)?;
    let records_len = body.get(32 + name_len..40 + name_len).map(u64_at)?;
    let records = body.get(40 + name_len..)?;
    let records = &records[..usize::try_from(records_len).unwrap_or(usize::MAX).min(records.len())];
    let plain;
    let plain: &[u8] = match name {
        b"" => records,
        b"zstd" => match zstd::bulk::decompress(records, uncompressed as usize) {
            Ok(bytes) => {
                plain = bytes;
                &plain
            }
            Err(_) => return damaged("its zstd data does not decompress"),
        },
        b"lz4" => {
            use std::io::Read;
            let mut bytes = Vec::new();
            let decoder = lz4_flex::frame::FrameDecoder::new(records);
            if decoder.take(uncompressed.saturating_add(1)).read_to_end(&mut bytes).is_err() {
                return damaged("its lz4 data does not decompress");
            }
            plain = bytes;
            &plain
        }
        // Other compressions are refused by the reader itself.
        _ => return None,
    };
    // The `mcap` 0.25 reader decompresses until it has the chunk's declared size: data that
    // ends sooner makes it spin for ever (fuzzing found a 15 kB log that did).
    if name != b"" && plain.len() as u64 != uncompressed {
        return damaged(&format!(
            "its {} data gives {} bytes, not the {uncompressed} it declares",
            String::from_utf8_lossy(name),
            plain.len()
        ));
    }
    let mut at = 0usize;
    while at + 9 <= plain.len() {
        let inner = u64_at(&plain[at + 1..at + 9]);
        let room = (plain.len() - at - 9) as u64;
        if inner > room {
            return damaged(&format!("a record inside claims {inner} bytes, {room} remain"));
        }
        at += 9 + inner as usize;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_rrd_message_claiming_more_than_the_file_cuts_the_input_before_it() {
        let mut data = b"RRF2\0\0\x24\0\0\0\0\0".to_vec();
        data.extend_from_slice(&2u64.to_le_bytes());
        data.extend_from_slice(&4u64.to_le_bytes());
        data.extend_from_slice(b"abcd");
        let sound = data.len() as u64;
        data.extend_from_slice(&2u64.to_le_bytes());
        data.extend_from_slice(&u64::MAX.to_le_bytes());
        let plausible = rrd(&mut data.as_slice(), data.len() as u64);
        assert_eq!(plausible.len, sound);
        assert!(plausible.problem.unwrap().contains(&format!("message at byte {sound} claims")));
    }

    #[test]
    fn an_mcap_chunk_claiming_an_exabyte_cuts_the_input_before_it() {
        let mut data = b"\x89MCAP0\r\n".to_vec();
        data.push(0x01);
        data.extend_from_slice(&4u64.to_le_bytes());
        data.extend_from_slice(b"\0\0\0\0");
        let sound = data.len() as u64;
        data.push(0x06);
        data.extend_from_slice(&24u64.to_le_bytes());
        data.extend_from_slice(&[0u8; 16]);
        data.extend_from_slice(&(1u64 << 61).to_le_bytes());
        let plausible = mcap(&mut data.as_slice(), data.len() as u64);
        assert_eq!(plausible.len, sound);
        assert!(plausible.problem.unwrap().contains("uncompressed"));
    }
}
