//! Openings of contacts whose normal traction evolves: where the contact lifts off its main
//! body and both tractions vanish, from the frames (no I/O here; [`crate::sink::catalog`]
//! writes them).
//!
//! A segment is open in a frame where every one of its contact points is
//! ([`crate::frame::SegmentSample::open`]). An opening of a contact lasts from the first frame
//! in which one of its segments is open to the first in which none is; the adaptive
//! integrators end a step on every point's opening and closing, so their frames lie on them,
//! and fixed steps place them within a step. It records the segments that opened and the
//! largest length along the contact open at once.

use crate::frame::Frame;

/// One opening of one contact.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Opening {
    /// The contact (0 for a body of one contact).
    pub contact: usize,
    /// Time of the first frame with an open segment (s).
    pub onset: f64,
    /// Time of the first frame after it with none; the last frame's time if the run ended first.
    pub end: f64,
    /// Whether it closed before the run ended.
    pub closed: bool,
    /// The first and last segment that opened (numbered along all contacts).
    pub first_segment: usize,
    pub last_segment: usize,
    /// The largest length along the contact open at one frame (m).
    pub largest_length: f64,
}

/// Finds openings in a stream of frames.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct OpeningDetector {
    /// Each segment's length along its contact (m); empty: no contact evolves, nothing to find.
    lengths: Vec<f64>,
    /// Segments per contact (one contact holding all where empty).
    contacts: Vec<usize>,
    /// Each contact's opening under way.
    current: Vec<Option<Opening>>,
    openings: Vec<Opening>,
    /// The last frame's time.
    last_time: f64,
}

impl OpeningDetector {
    /// A detector for segments of `lengths` (m) on contacts of `contacts` segments each.
    pub fn new(lengths: Vec<f64>, contacts: Vec<usize>) -> Self {
        let count = contacts.len().max(1);
        Self { lengths, contacts, current: vec![None; count], openings: Vec::new(), last_time: 0.0 }
    }

    /// Feeds one frame.
    pub fn record(&mut self, frame: &Frame) {
        if self.lengths.is_empty() {
            return;
        }
        self.last_time = frame.time;
        let ranges = self.ranges();
        for (c, range) in ranges.into_iter().enumerate() {
            let open: Vec<usize> = range.filter(|&k| frame.segments.get(k).is_some_and(|s| s.open)).collect();
            let length: f64 = open.iter().map(|&k| self.lengths[k]).sum();
            match (&mut self.current[c], open.first(), open.last()) {
                (Some(opening), Some(&first), Some(&last)) => {
                    opening.first_segment = opening.first_segment.min(first);
                    opening.last_segment = opening.last_segment.max(last);
                    opening.largest_length = opening.largest_length.max(length);
                }
                (current @ None, Some(&first), Some(&last)) => {
                    *current = Some(Opening {
                        contact: c,
                        onset: frame.time,
                        end: frame.time,
                        closed: false,
                        first_segment: first,
                        last_segment: last,
                        largest_length: length,
                    });
                }
                (current @ Some(_), _, _) => {
                    let mut opening = current.take().expect("an opening under way");
                    opening.end = frame.time;
                    opening.closed = true;
                    self.openings.push(opening);
                }
                (None, _, _) => {}
            }
        }
    }

    /// The openings, by onset, those still under way ended at the last frame.
    pub fn finish(&mut self) -> Vec<Opening> {
        let last = self.last_time;
        let mut all = std::mem::take(&mut self.openings);
        all.extend(self.current.iter_mut().filter_map(Option::take).map(|o| Opening { end: last, ..o }));
        all.sort_by(|a, b| a.onset.total_cmp(&b.onset).then(a.contact.cmp(&b.contact)));
        all
    }

    fn ranges(&self) -> Vec<std::ops::Range<usize>> {
        if self.contacts.is_empty() {
            return vec![0..self.lengths.len()];
        }
        let mut start = 0;
        self.contacts
            .iter()
            .map(|&n| {
                start += n;
                start - n..start
            })
            .collect()
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
    fn an_opening_lasts_from_the_first_open_frame_to_the_first_closed_one_per_contact() {
        // Two contacts of two segments; segment lengths 1, 2 | 3, 4 m.
        let mut d = OpeningDetector::new(vec![1.0, 2.0, 3.0, 4.0], vec![2, 2]);
        d.record(&frame(0.0, &[false, false, false, false]));
        d.record(&frame(0.1, &[true, false, false, false]));
        d.record(&frame(0.2, &[true, true, false, true]));
        d.record(&frame(0.3, &[false, false, false, true]));
        d.record(&frame(0.4, &[false, false, false, false]));
        d.record(&frame(0.5, &[false, true, false, false]));
        let openings = d.finish();
        assert_eq!(openings.len(), 3);
        assert_eq!((openings[0].contact, openings[0].onset, openings[0].end), (0, 0.1, 0.3));
        assert_eq!((openings[0].first_segment, openings[0].last_segment, openings[0].largest_length), (0, 1, 3.0));
        assert!(openings[0].closed);
        assert_eq!(
            (openings[1].contact, openings[1].onset, openings[1].end, openings[1].largest_length),
            (1, 0.2, 0.4, 4.0)
        );
        assert_eq!((openings[2].onset, openings[2].end, openings[2].closed), (0.5, 0.5, false));
    }
}
