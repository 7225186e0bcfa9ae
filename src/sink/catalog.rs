//! The event catalog sink: `<stem>.events.csv` and, for a block, `<stem>.ruptures.csv`.

use std::fmt::Write as _;
use std::path::PathBuf;

use crate::catalog::events::{Catalog, Rupture, SlipEvent};
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

/// Writes the catalogs when the run ends (completed, failed or interrupted).
pub struct CatalogSink {
    events_path: PathBuf,
    ruptures_path: Option<PathBuf>,
    /// Whether the body is a ring (its force drops in N).
    ring: bool,
}

impl CatalogSink {
    /// `ruptures_path` is used for block scenes only.
    pub fn new(events_path: PathBuf, ruptures_path: Option<PathBuf>) -> Self {
        Self { events_path, ruptures_path, ring: false }
    }
}

impl Sink for CatalogSink {
    fn begin(&mut self, layout: &Layout) -> Result<(), SinkError> {
        if !layout.kind.has_body() {
            self.ruptures_path = None;
        }
        self.ring = layout.axisymmetric;
        // Fail now, not after the run, if the file cannot be written.
        write_file(&self.events_path, &events_csv(&[]))?;
        if let Some(path) = &self.ruptures_path {
            write_file(path, &ruptures_csv_in(&[], self.ring))?;
        }
        Ok(())
    }

    fn record(&mut self, _frame: &Frame) -> Result<(), SinkError> {
        Ok(())
    }

    fn finish(&mut self, _ending: Ending, _last: Option<&Frame>, catalog: &Catalog) -> Result<(), SinkError> {
        write_file(&self.events_path, &events_csv(&catalog.events))?;
        if let Some(path) = &self.ruptures_path {
            write_file(path, &ruptures_csv_in(&catalog.ruptures, self.ring))?;
        }
        Ok(())
    }
}

fn write_file(path: &PathBuf, text: &str) -> Result<(), SinkError> {
    std::fs::write(path, text).map_err(|e| SinkError(format!("cannot write {}: {e}", path.display())))
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
