//! The event catalog sink: `<stem>.events.csv`, for a block `<stem>.ruptures.csv`, and where a
//! contact's normal traction evolves `<stem>.openings.csv`.

use std::fmt::Write as _;
use std::path::PathBuf;

use crate::catalog::events::{Catalog, Rupture, SlipEvent};
use crate::catalog::openings::Opening;
use crate::frame::Ending;
use crate::frame::{Frame, Layout};
use crate::sink::{Sink, SinkError};

/// Header of the events CSV.
pub const EVENTS_HEADER: &str = "segment,onset_s,end_s,slip_m,peak_slip_rate_m_s,traction_before_pa,traction_after_pa";
/// Header of the ruptures CSV.
pub const RUPTURES_HEADER: &str = "onset_s,end_s,nucleation_segment,first_segment,last_segment,segments_slipped,max_slip_m,friction_force_drop_n_per_m";
/// Header of the ruptures CSV of an axisymmetric body, whose forces are totals around the
/// ring, in N.
pub const RUPTURES_HEADER_RING: &str =
    "onset_s,end_s,nucleation_segment,first_segment,last_segment,segments_slipped,max_slip_m,friction_force_drop_n";

/// Header of the openings CSV.
pub const OPENINGS_HEADER: &str = "segment,onset_s,end_s,closed,length_m";

/// Writes the catalogs when the run ends (completed, failed or interrupted).
pub struct CatalogSink {
    events_path: PathBuf,
    ruptures_path: Option<PathBuf>,
    /// Where a contact's normal traction evolves.
    openings_path: Option<PathBuf>,
    /// Whether the body is a ring (its force drops in N).
    ring: bool,
}

impl CatalogSink {
    /// `ruptures_path` is used for block scenes only.
    pub fn new(events_path: PathBuf, ruptures_path: Option<PathBuf>) -> Self {
        Self { events_path, ruptures_path, openings_path: None, ring: false }
    }
}

impl Sink for CatalogSink {
    fn begin(&mut self, layout: &Layout) -> Result<(), SinkError> {
        if !layout.kind.has_body() {
            self.ruptures_path = None;
        }
        self.ring = layout.axisymmetric;
        self.openings_path = layout.evolving_normal.then(|| openings_path_for(&self.events_path));
        // Fail now, not after the run, if the file cannot be written.
        write_catalog(&self.events_path, &events_csv(&[]))?;
        if let Some(path) = &self.openings_path {
            write_catalog(path, &openings_csv(&[]))?;
        }
        if let Some(path) = &self.ruptures_path {
            write_catalog(path, &ruptures_csv_in(&[], self.ring))?;
        }
        Ok(())
    }

    fn record(&mut self, _frame: &Frame) -> Result<(), SinkError> {
        Ok(())
    }

    fn finish(&mut self, _ending: Ending, _last: Option<&Frame>, catalog: &Catalog) -> Result<(), SinkError> {
        write_catalog(&self.events_path, &events_csv(&catalog.events))?;
        if let Some(path) = &self.ruptures_path {
            write_catalog(path, &ruptures_csv_in(&catalog.ruptures, self.ring))?;
        }
        if let Some(path) = &self.openings_path {
            write_catalog(path, &openings_csv(&catalog.openings))?;
        }
        Ok(())
    }
}

/// Writes a catalog whole, in the file the run holds locked. Where the file already holds the
/// start of `text` (its header, written by [`CatalogSink::begin`]), only the rest is added and
/// a failed addition is cut off again, so that a full disk leaves the catalog as it was, never
/// empty or cut mid-line.
pub fn write_catalog(path: &PathBuf, text: &str) -> Result<(), SinkError> {
    let cannot = |e: std::io::Error| SinkError(format!("cannot write {}: {e}", path.display()));
    // Only a regular file no longer than `text` is read (`--events /dev/full` never ends).
    match crate::files::read_capped(path, text.len() as u64, "a catalog") {
        Ok(held) if !held.is_empty() && text.as_bytes().starts_with(&held) => {
            extend(path, held.len() as u64, text).map_err(cannot)
        }
        _ => std::fs::write(path, text).map_err(cannot),
    }
}

/// Adds `text` past its first `held` bytes (which the file already holds) and sets the file's
/// length to it; on failure puts the length back to `held`, which needs no space.
fn extend(path: &PathBuf, held: u64, text: &str) -> std::io::Result<()> {
    use std::os::unix::fs::FileExt;
    let file = std::fs::OpenOptions::new().write(true).open(path)?;
    let added =
        file.write_all_at(&text.as_bytes()[held as usize..], held).and_then(|()| file.set_len(text.len() as u64));
    if added.is_err() {
        let _ = file.set_len(held);
    }
    added
}

/// The events CSV text.
pub fn events_csv(events: &[SlipEvent]) -> String {
    let mut out = String::from(EVENTS_HEADER);
    out.push('\n');
    for e in events {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{}",
            e.segment, e.onset, e.end, e.slip, e.peak_slip_rate, e.traction_before, e.traction_after
        );
    }
    out
}

/// The ruptures CSV text of a plane body (force drops in N/m).
pub fn ruptures_csv(ruptures: &[Rupture]) -> String {
    ruptures_csv_in(ruptures, false)
}

/// The ruptures CSV text; force drops in N around a `ring`, else in N/m.
pub fn ruptures_csv_in(ruptures: &[Rupture], ring: bool) -> String {
    let mut out = String::from(if ring { RUPTURES_HEADER_RING } else { RUPTURES_HEADER });
    out.push('\n');
    for r in ruptures {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{}",
            r.onset,
            r.end,
            r.nucleation_segment,
            r.first_segment,
            r.last_segment,
            r.segments_slipped,
            r.max_slip,
            r.friction_force_drop
        );
    }
    out
}

/// The openings CSV text.
pub fn openings_csv(openings: &[Opening]) -> String {
    let mut out = String::from(OPENINGS_HEADER);
    out.push('\n');
    for o in openings {
        let _ = writeln!(out, "{},{},{},{},{}", o.segment, o.onset, o.end, o.closed, o.length);
    }
    out
}

/// `<dir>/<x>.openings.csv` beside `<dir>/<x>.events.csv` (or `<stem>.openings.csv`).
pub fn openings_path_for(events: &std::path::Path) -> PathBuf {
    let name = events.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let stem = name.strip_suffix(".events.csv").or_else(|| name.strip_suffix(".csv")).unwrap_or(&name);
    events.with_file_name(format!("{stem}.openings.csv"))
}
