//! What the commands share: exit codes, the error line, and where a live copy goes.

use std::io::Write;
use std::process::ExitCode;

use clap::Args;

use crate::sink::rerun::Viewer;

/// Exit code for invalid input (case, arguments, output folder).
pub const EXIT_INVALID: u8 = 2;
/// Exit code for a failure during the run.
pub const EXIT_FAILED: u8 = 1;
/// Exit code after Ctrl-C (128 + SIGINT); SIGTERM gives 143 (128 + SIGTERM).
pub const EXIT_INTERRUPTED: u8 = 130;

/// Where a live copy of the recording goes.
#[derive(Debug, Args)]
pub struct ViewerArgs {
    /// Stream to a new Rerun viewer (the `rerun` executable on PATH).
    #[arg(long, conflicts_with = "connect")]
    pub spawn: bool,
    /// Stream to a running Rerun viewer, e.g. rerun+http://127.0.0.1:9876/proxy.
    #[arg(long, value_name = "URL")]
    pub connect: Option<String>,
}

impl ViewerArgs {
    pub fn viewer(&self) -> Viewer {
        match (&self.connect, self.spawn) {
            (Some(url), _) => Viewer::Connect(url.clone()),
            (None, true) => Viewer::Spawn,
            (None, false) => Viewer::None,
        }
    }
}

/// Prints `slipfront: message` on stderr and returns `code`.
pub(crate) fn fail(code: u8, message: impl std::fmt::Display) -> ExitCode {
    eprintln!("slipfront: {message}");
    ExitCode::from(code)
}

/// Writes `text` to standard output. A closed pipe (`slipfront check X.rrd | head -1`) ends
/// the output quietly, as Unix tools do; any other failure (a full device) is an error, exit 1.
pub(crate) fn print(text: &str) -> Result<(), ExitCode> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(fail(EXIT_FAILED, format!("cannot write to standard output: {e}"))),
    }
}

/// Compacts a finished recording of many chunks ([`crate::record::compact::compact_if_worthwhile`]);
/// a failure leaves the file as the run wrote it, which is complete, and is said on stderr.
pub(crate) fn compact_recording(path: &std::path::Path) {
    if !path.is_file() {
        return;
    }
    if let Err(e) = crate::record::compact::compact_if_worthwhile(path) {
        eprintln!("slipfront: {e}; {} is kept as written, in its small chunks", path.display());
    }
}
