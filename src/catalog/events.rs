//! Slip events and ruptures detected from frames: no I/O here (see [`crate::sink::catalog`]).
//!
//! A segment slips while its plastic slip rate exceeds the threshold. The slip rate of a step,
//! `Δp/Δt`, is the mean over the step, so it is placed at the step's midpoint; onsets and ends
//! are where the linear interpolation between midpoints crosses the threshold, and the slip and
//! traction there are interpolated between frames. Where the slip rates are instantaneous
//! (the Runge–Kutta integrator's `Λ`, [`crate::frame::Layout::instantaneous_slip_rate`]), they
//! are placed at the frames' times instead. With a merge window `w > 0`, a segment's
//! event that starts less than `w` after its previous one ended continues that event (the slip
//! rate of a decelerating segment can flicker about the threshold in its tail).

use crate::catalog::openings::{Opening, OpeningDetector};
use crate::frame::Frame;

/// The catalog of a run: its slip events (by onset), their grouping into ruptures, and the
/// openings of contacts whose normal traction evolves.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Catalog {
    pub events: Vec<SlipEvent>,
    pub ruptures: Vec<Rupture>,
    pub openings: Vec<Opening>,
}

/// One slip event of one segment.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SlipEvent {
    pub segment: usize,
    /// Time the slip rate rose through the threshold (s).
    pub onset: f64,
    /// Time it fell back below (s); the last frame's time if the run ended first.
    pub end: f64,
    /// Plastic slip between onset and end (m).
    pub slip: f64,
    /// Largest step-mean slip rate during the event (m/s).
    pub peak_slip_rate: f64,
    /// Segment tangential traction at the onset (Pa).
    pub traction_before: f64,
    /// Segment tangential traction at the end (Pa).
    pub traction_after: f64,
    /// Total friction force at the onset and end (N/m, or Pa per unit area).
    pub friction_force_before: f64,
    pub friction_force_after: f64,
    /// Segment degree of structure `1/R*` at the onset (`None` in a catalog read from a file
    /// that does not hold it).
    pub structure_before: Option<f64>,
}

/// Simultaneous slip events of neighbouring segments grouped into one rupture.
#[derive(Debug, Clone, PartialEq)]
pub struct Rupture {
    pub onset: f64,
    pub end: f64,
    /// The segment that slipped first.
    pub nucleation_segment: usize,
    /// Leftmost and rightmost segments that slipped.
    pub first_segment: usize,
    pub last_segment: usize,
    /// Number of distinct segments that slipped.
    pub segments_slipped: usize,
    /// Largest slip of a segment (m).
    pub max_slip: f64,
    /// Total friction force at the onset minus at the end (N/m).
    pub friction_force_drop: f64,
}

#[derive(Debug, Clone, Copy, Default, serde::Serialize, serde::Deserialize)]
struct Sample {
    time: f64,
    slip: f64,
    traction: f64,
    force: f64,
    /// 0 when the frame did not carry it.
    structure: f64,
}

#[derive(Debug, Clone, Copy, serde::Serialize, serde::Deserialize)]
struct Open {
    onset: f64,
    slip_at_onset: f64,
    traction_before: f64,
    force_before: f64,
    structure_before: f64,
    peak: f64,
}

#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
struct SegmentTrack {
    /// Previous step's (midpoint, slip rate).
    rate: Option<(f64, f64)>,
    /// The last two frames.
    previous: Option<Sample>,
    current: Option<Sample>,
    open: Option<Open>,
    /// The last closed event, held while a merge could still extend it.
    closed: Option<(Open, Sample)>,
}

impl SegmentTrack {
    /// Linear interpolation of the sampled history at `t`.
    fn at(&self, t: f64) -> Sample {
        let cur = self.current.expect("a frame was recorded");
        match self.previous {
            Some(prev) if t < cur.time && cur.time > prev.time => {
                let w = ((t - prev.time) / (cur.time - prev.time)).clamp(0.0, 1.0);
                Sample {
                    time: t,
                    slip: prev.slip + w * (cur.slip - prev.slip),
                    traction: prev.traction + w * (cur.traction - prev.traction),
                    force: prev.force + w * (cur.force - prev.force),
                    structure: prev.structure + w * (cur.structure - prev.structure),
                }
            }
            _ => Sample { time: t, ..cur },
        }
    }
}

/// Finds slip events in a stream of frames.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct EventDetector {
    threshold: f64,
    merge_within: f64,
    /// Slip rates are instantaneous, at the frame's time (not step means at the midpoint).
    instantaneous: bool,
    tracks: Vec<SegmentTrack>,
    events: Vec<SlipEvent>,
    /// Segments per contact, where the body has several: a rupture stays on one contact, and
    /// an event's friction force is its contact's. Empty: one contact.
    #[serde(default)]
    contacts: Vec<usize>,
    /// The openings of contacts whose normal traction evolves.
    #[serde(default)]
    openings: OpeningDetector,
}

impl EventDetector {
    /// A detector for `segments` segments and a slip-rate threshold (m/s), merging a segment's
    /// events separated by less than `merge_within` (s; 0 merges nothing).
    pub fn new(segments: usize, threshold: f64, merge_within: f64) -> Self {
        Self {
            threshold,
            merge_within,
            instantaneous: false,
            tracks: vec![SegmentTrack::default(); segments],
            events: Vec::new(),
            contacts: Vec::new(),
            openings: OpeningDetector::default(),
        }
    }

    /// The same detector for a body of several contacts with `segments` segments each, in
    /// order ([`crate::frame::Layout::contacts`]).
    pub fn with_contacts(mut self, segments: Vec<usize>) -> Self {
        self.contacts = if segments.len() > 1 { segments } else { Vec::new() };
        self
    }

    /// The same detector for frames whose slip rates are instantaneous values at the frame's
    /// time ([`crate::frame::Layout::instantaneous_slip_rate`]).
    pub fn with_instantaneous_rates(mut self, instantaneous: bool) -> Self {
        self.instantaneous = instantaneous;
        self
    }

    /// The same detector also finding openings, for segments of `lengths` (m) along contacts
    /// whose normal traction evolves ([`crate::catalog::openings`]).
    pub fn with_openings(mut self, lengths: Vec<f64>) -> Self {
        self.openings = OpeningDetector::new(lengths);
        self
    }

    /// Feeds one frame (the initial frame, with `dt = 0`, included).
    pub fn record(&mut self, frame: &Frame) {
        self.openings.record(frame);
        let contact_of = contact_of(&self.contacts);
        for (k, (track, seg)) in self.tracks.iter_mut().zip(&frame.segments).enumerate() {
            let sample = Sample {
                time: frame.time,
                slip: seg.slip,
                traction: seg.traction_t,
                force: frame.contact_forces.get(contact_of(k)).copied().unwrap_or(frame.friction_force),
                structure: seg.structure,
            };
            track.previous = track.current.replace(sample);
            if frame.dt <= 0.0 {
                continue;
            }
            let mid = if self.instantaneous { frame.time } else { frame.time - 0.5 * frame.dt };
            let rate = seg.slip_rate;
            let (t0, r0) = track.rate.unwrap_or((track.previous.map_or(0.0, |p| p.time), 0.0));
            let crossing = |level: f64| if rate == r0 { mid } else { t0 + (level - r0) / (rate - r0) * (mid - t0) };
            match track.open {
                None if rate > self.threshold => {
                    let onset = crossing(self.threshold).clamp(t0, mid);
                    track.open = match track.closed.take() {
                        Some((previous, end)) if onset - end.time < self.merge_within => {
                            Some(Open { peak: previous.peak.max(rate), ..previous })
                        }
                        earlier => {
                            if let Some((previous, end)) = earlier {
                                self.events.push(close(k, previous, end));
                            }
                            let at = track.at(onset);
                            Some(Open {
                                onset,
                                slip_at_onset: at.slip,
                                traction_before: at.traction,
                                force_before: at.force,
                                structure_before: at.structure,
                                peak: rate,
                            })
                        }
                    };
                }
                Some(ref mut open) if rate > self.threshold => open.peak = open.peak.max(rate),
                Some(open) => {
                    let end = crossing(self.threshold).clamp(t0, mid);
                    track.closed = Some((open, track.at(end)));
                    track.open = None;
                }
                None => {}
            }
            track.rate = Some((mid, rate));
        }
    }

    /// Closes events still open at the last frame.
    pub fn finish(&mut self) {
        for (k, track) in self.tracks.iter_mut().enumerate() {
            if let Some((previous, end)) = track.closed.take() {
                self.events.push(close(k, previous, end));
            }
            if let (Some(open), Some(last)) = (track.open.take(), track.current) {
                self.events.push(close(k, open, last));
            }
        }
        self.events.sort_by(|a, b| a.onset.total_cmp(&b.onset).then(a.segment.cmp(&b.segment)));
    }

    /// Events closed so far (all of them, by onset, once [`Self::finish`] has run).
    pub fn events(&self) -> &[SlipEvent] {
        &self.events
    }

    /// Closes open events and returns the catalog.
    pub fn into_catalog(mut self) -> Catalog {
        self.finish();
        let ruptures = ruptures_by_contact(&self.events, &self.contacts);
        let openings = self.openings.finish();
        Catalog { events: self.events, ruptures, openings }
    }
}

fn close(segment: usize, open: Open, at: Sample) -> SlipEvent {
    SlipEvent {
        segment,
        onset: open.onset,
        end: at.time,
        slip: at.slip - open.slip_at_onset,
        peak_slip_rate: open.peak,
        traction_before: open.traction_before,
        traction_after: at.traction,
        friction_force_before: open.force_before,
        friction_force_after: at.force,
        structure_before: (open.structure_before > 0.0).then_some(open.structure_before),
    }
}

/// The contact of segment `k` for contacts of `segments` segments each (0 for one contact).
fn contact_of(segments: &[usize]) -> impl Fn(usize) -> usize + '_ {
    move |k| {
        let mut end = 0;
        segments
            .iter()
            .position(|n| {
                end += n;
                k < end
            })
            .unwrap_or(0)
    }
}

/// [`ruptures`] on each contact of `segments` segments each (one contact where empty), in the
/// order of their onsets: a rupture never spans two contacts.
pub fn ruptures_by_contact(events: &[SlipEvent], segments: &[usize]) -> Vec<Rupture> {
    if segments.len() <= 1 {
        return ruptures(events);
    }
    let contact_of = contact_of(segments);
    let mut all: Vec<Rupture> = (0..segments.len())
        .flat_map(|c| {
            let own: Vec<SlipEvent> = events.iter().filter(|e| contact_of(e.segment) == c).cloned().collect();
            ruptures(&own)
        })
        .collect();
    all.sort_by(|a, b| a.onset.total_cmp(&b.onset));
    all
}

/// Groups events whose time intervals overlap (transitively) into ruptures.
pub fn ruptures(events: &[SlipEvent]) -> Vec<Rupture> {
    let mut sorted: Vec<&SlipEvent> = events.iter().collect();
    sorted.sort_by(|a, b| a.onset.total_cmp(&b.onset));
    let mut groups: Vec<Vec<&SlipEvent>> = Vec::new();
    let mut group_end = f64::NEG_INFINITY;
    for event in sorted {
        match groups.last_mut() {
            Some(group) if event.onset <= group_end => {
                group.push(event);
                group_end = group_end.max(event.end);
            }
            _ => {
                groups.push(vec![event]);
                group_end = event.end;
            }
        }
    }
    groups
        .into_iter()
        .map(|group| {
            let first = group[0];
            let last_ending = group.iter().max_by(|a, b| a.end.total_cmp(&b.end)).expect("non-empty group");
            let mut segments: Vec<usize> = group.iter().map(|e| e.segment).collect();
            segments.sort_unstable();
            segments.dedup();
            Rupture {
                onset: first.onset,
                end: last_ending.end,
                nucleation_segment: first.segment,
                first_segment: segments[0],
                last_segment: segments[segments.len() - 1],
                segments_slipped: segments.len(),
                max_slip: group.iter().map(|e| e.slip).fold(0.0, f64::max),
                friction_force_drop: first.friction_force_before - last_ending.friction_force_after,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn event(segment: usize, onset: f64, end: f64) -> SlipEvent {
        SlipEvent {
            segment,
            onset,
            end,
            slip: 0.01,
            peak_slip_rate: 0.1,
            traction_before: 1.0,
            traction_after: 0.5,
            friction_force_before: 10.0,
            friction_force_after: 8.0,
            structure_before: None,
        }
    }

    /// Events that overlap in time on segments 3 and 4 are one rupture on one contact, and two
    /// where segment 3 ends the first contact and 4 starts the second: a rupture stays on its
    /// contact, and the ruptures come in the order of their onsets.
    #[test]
    fn a_rupture_never_spans_two_contacts() {
        let events = [event(4, 1.0, 3.0), event(3, 1.5, 2.5), event(0, 2.0, 2.2), event(6, 9.0, 9.5)];
        let one = ruptures_by_contact(&events, &[]);
        assert_eq!(one.len(), 2);
        assert_eq!((one[0].first_segment, one[0].last_segment, one[0].segments_slipped), (0, 4, 3));
        let two = ruptures_by_contact(&events, &[4, 4]);
        let spans: Vec<(f64, usize, usize)> = two.iter().map(|r| (r.onset, r.first_segment, r.last_segment)).collect();
        assert_eq!(spans, [(1.0, 4, 4), (1.5, 0, 3), (9.0, 6, 6)]);
    }
}
