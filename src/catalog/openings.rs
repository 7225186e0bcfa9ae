//! Openings of contacts whose normal traction evolves: where the contact lifts off its main
//! body and both tractions vanish, from the frames (no I/O here; [`crate::sink::catalog`]
//! writes them).
//!
//! A segment is open in a frame where every one of its contact points is
//! ([`crate::frame::SegmentSample::open`]). An opening of a segment lasts from the first frame
//! in which it is open (its onset: it opened, or it started open) to the first in which it is
//! not (its end: it closed); the adaptive integrators end a step on every point's opening and
//! closing, so their frames lie on them, and fixed steps place them within a step. A contact
//! that opens from its edges inwards, or closes from its middle outwards, shows as the onsets or
//! ends of its segments in order along it.

use crate::frame::Frame;

/// One opening of one segment.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Opening {
    /// The segment (numbered along all contacts).
    pub segment: usize,
    /// Time of the first frame in which it is open (s).
    pub onset: f64,
    /// Time of the first frame after it in which it is pressed; the last frame's time if the
    /// run ended first.
    pub end: f64,
    /// Whether it closed before the run ended.
    pub closed: bool,
    /// The segment's length along its contact (m).
    pub length: f64,
}

/// Finds openings in a stream of frames.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct OpeningDetector {
    /// Each segment's length along its contact (m); empty: no contact evolves, nothing to find.
    lengths: Vec<f64>,
    /// Each segment's opening under way: its onset.
    current: Vec<Option<f64>>,
    openings: Vec<Opening>,
    /// The last frame's time.
    last_time: f64,
}

impl OpeningDetector {
    /// A detector for segments of `lengths` (m).
    pub fn new(lengths: Vec<f64>) -> Self {
        let count = lengths.len();
        Self { lengths, current: vec![None; count], openings: Vec::new(), last_time: 0.0 }
    }

    /// Feeds one frame.
    pub fn record(&mut self, frame: &Frame) {
        if self.lengths.is_empty() {
            return;
        }
        self.last_time = frame.time;
        for (k, current) in self.current.iter_mut().enumerate() {
            let open = frame.segments.get(k).is_some_and(|s| s.open);
            match (*current, open) {
                (None, true) => *current = Some(frame.time),
                (Some(onset), false) => {
                    self.openings.push(Opening {
                        segment: k,
                        onset,
                        end: frame.time,
                        closed: true,
                        length: self.lengths[k],
                    });
                    *current = None;
                }
                _ => {}
            }
        }
    }

    /// The openings, by onset and segment, those still under way ended at the last frame.
    pub fn finish(&mut self) -> Vec<Opening> {
        let last = self.last_time;
        let mut all = std::mem::take(&mut self.openings);
        for (k, current) in self.current.iter_mut().enumerate() {
            if let Some(onset) = current.take() {
                all.push(Opening { segment: k, onset, end: last, closed: false, length: self.lengths[k] });
            }
        }
        all.sort_by(|a, b| a.onset.total_cmp(&b.onset).then(a.segment.cmp(&b.segment)));
        all
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::SegmentSample;

    fn frame(time: f64, open: &[bool]) -> Frame {
        let segments = open.iter().map(|&open| SegmentSample { open, ..Default::default() }).collect();
        Frame { time, dt: 0.1, segments, ..Frame::default() }
    }

    #[test]
    fn an_opening_lasts_from_the_first_open_frame_to_the_first_pressed_one() {
        let mut d = OpeningDetector::new(vec![1.0, 2.0, 3.0]);
        d.record(&frame(0.0, &[true, false, false]));
        d.record(&frame(0.1, &[false, true, false]));
        d.record(&frame(0.2, &[false, true, false]));
        d.record(&frame(0.3, &[true, false, false]));
        let openings = d.finish();
        let rows: Vec<(usize, f64, f64, bool, f64)> =
            openings.iter().map(|o| (o.segment, o.onset, o.end, o.closed, o.length)).collect();
        assert_eq!(rows, vec![(0, 0.0, 0.1, true, 1.0), (1, 0.1, 0.3, true, 2.0), (0, 0.3, 0.3, false, 1.0)]);
    }
}
