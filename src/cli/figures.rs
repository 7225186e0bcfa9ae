//! `slipfront figures RECORDING.rrd [--out DIR] [--at T,...]`: the paper's Figures 8 and 9 as PNG
//! files, and for a body its force–displacement curve and profiles along its contacts.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use crate::cli::check::RECORDING;
use crate::cli::common::{EXIT_FAILED, EXIT_INVALID, fail, print};
use crate::inspect;
use crate::inspect::check::{Expectations, check, check_partial};
use crate::record::schema::RUN_ENDING;
use crate::study::{contact_figures, figures};

#[derive(Debug, Args)]
pub struct FiguresArgs {
    /// The recording (.rrd).
    pub recording: PathBuf,
    /// Folder for the PNG files (created if missing).
    #[arg(long, value_name = "DIR", default_value = "recordings")]
    pub out: PathBuf,
    /// Draw a file that may end early (a run killed before it wrote its ending), judged as
    /// `check --partial` judges it.
    #[arg(long)]
    pub partial: bool,
    /// For a body: the times (s, comma-separated) of the profiles along the contacts' arc length
    /// in <case>_profiles.png; default a quarter, half, three quarters and the end of the run.
    #[arg(long, value_delimiter = ',', value_name = "SECONDS")]
    pub at: Vec<f64>,
}

/// Runs `slipfront figures`: a recording that `check` (or with `--partial`, `check --partial`)
/// would fail is refused, exit 1, with no figures drawn: figures of a damaged file would show
/// the damage as data.
pub fn command(args: FiguresArgs) -> ExitCode {
    if let Err(e) = crate::files::open_regular(&args.recording, RECORDING) {
        return fail(EXIT_INVALID, e);
    }
    if let Some(failure) = crate::cli::isolated::decoder_failure(&args.recording) {
        return fail(EXIT_FAILED, format!("{failure}; no figures drawn"));
    }
    let recording = match inspect::rrd::read(&args.recording) {
        Ok(r) => r,
        Err(e) => return fail(EXIT_INVALID, e),
    };
    let expect = Expectations::default();
    let report = if args.partial { check_partial(&recording, &expect) } else { check(&recording, &expect) };
    if !report.passed() {
        let early = if args.partial || recording.static_texts.contains_key(RUN_ENDING) {
            ""
        } else {
            " (a file cut off before its run ended is drawn with --partial)"
        };
        return fail(
            EXIT_FAILED,
            format!(
                "{} fails `slipfront check`: {}; no figures drawn{early}",
                args.recording.display(),
                report.problems.join("; ")
            ),
        );
    }
    let end = figures::recorded_end(&recording);
    if let Some(t) = args.at.iter().find(|t| !(t.is_finite() && (0.0..=end).contains(*t))) {
        return fail(
            EXIT_INVALID,
            format!(
                "--at {}: a profile's time must lie in the recorded span, 0 to {} s",
                crate::validate::shortest(*t),
                crate::validate::shortest(end)
            ),
        );
    }
    let drawn = figures::write_figures(&recording, &args.out).and_then(|mut paths| {
        paths.extend(contact_figures::write(&recording, &args.out, &args.at)?);
        Ok(paths)
    });
    match drawn {
        Ok(paths) => {
            let listing: String = paths.iter().map(|path| format!("{}\n", path.display())).collect();
            print(&listing).err().unwrap_or(ExitCode::SUCCESS)
        }
        Err(e) => fail(EXIT_FAILED, e),
    }
}
