//! Decoding a recording once in a child process before decoding it here. Rerun's decoder,
//! through `arrow-ipc`, allocates what a damaged Arrow message claims before reading it: a
//! claim of 8.2e18 bytes aborts the process (an allocation failure is not a panic, so no
//! unwinding catches it), and a large but satisfiable one runs for minutes in gigabytes. A
//! child (`slipfront __decode-rrd FILE`, hidden) decodes the file first under a cap on its
//! address space; only if it finishes does this process decode the same file. A child that
//! dies reports the file as damaged.

use std::path::Path;
use std::process::{Command, Stdio};

/// The hidden subcommand of the child.
pub const DECODE_RRD: &str = "__decode-rrd";

/// The child's address space: room for the decoded recording (many times the file) above a
/// floor that the runtime's own reservations (thread stacks, allocator arenas) fit in.
fn address_space(file_len: u64) -> u64 {
    (4u64 << 30).max(file_len.saturating_mul(64))
}

/// Why decoding `path` would end the process, if it would: `None` when the child decoded it
/// (whether or not it found damage, which the caller's own decoding then reports).
pub fn decoder_failure(path: &Path) -> Option<String> {
    let exe = std::env::current_exe().ok()?;
    let status = Command::new(exe)
        .arg(DECODE_RRD)
        .arg(path)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .ok()?;
    if status.success() {
        return None;
    }
    use std::os::unix::process::ExitStatusExt;
    let how = match status.signal() {
        Some(6) => "aborted it (an allocation a damaged Arrow message claims)".to_string(),
        Some(signal) => format!("killed it with signal {signal}"),
        None => format!("ended it with exit code {}", status.code().unwrap_or(-1)),
    };
    Some(format!("decoding {} {how}: the file is damaged", path.display()))
}

/// The child: decodes `path` under the cap on its address space and exits 0 when the decoder
/// returns, whatever it found.
pub fn decode_in_child(path: &Path) -> std::process::ExitCode {
    let len = std::fs::metadata(path).map_or(0, |m| m.len());
    let limit = address_space(len);
    let cap = libc::rlimit { rlim_cur: limit, rlim_max: limit };
    // SAFETY: setrlimit reads the struct passed by reference and touches no Rust state.
    unsafe { libc::setrlimit(libc::RLIMIT_AS, &cap) };
    let _ = crate::inspect::rrd::read(path);
    std::process::ExitCode::SUCCESS
}
