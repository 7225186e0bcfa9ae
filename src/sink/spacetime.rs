//! The space-time map: the peak slip rate of every segment (down, from x = 0 at the top) in
//! every time bin (across), as values, with time running the same way as the state lanes. It
//! is a depth image of `log10` slip rate coloured by Rerun's own colormap over a fixed range,
//! so hovering shows the value; tick labels give x in m and `sim_time` in s, and the cursor
//! ([`crate::sink::geometry`]) marks the playhead.

use rerun::RecordingStream;

use crate::frame::Layout;
use crate::record::schema;

/// Time bins of the map (its columns), spread over `[0, t_end]`.
pub const TIME_BINS: usize = 1000;
/// Target height of the map in view units; each segment gets an equal share.
const HEIGHT: usize = 250;

/// Height of one segment's lane of the map (view units).
fn lane_height(segments: usize) -> usize {
    (HEIGHT / segments.max(1)).max(1)
}

/// Height of the map for `segments` segments (view units).
pub fn map_height(segments: usize) -> usize {
    segments.max(1) * lane_height(segments)
}

/// The peak slip rate per (segment, time bin) of the recorded steps.
pub struct SpaceTime {
    /// The span whose [`TIME_BINS`] bins the map has: `t_end`, or the first `t_end` of a run
    /// that was extended, whose map then has as many more bins of the same width as it needs.
    t_span: f64,
    /// Time bins (columns).
    bins: usize,
    segments: usize,
    /// Row-major: a row of `bins` per segment.
    peaks: Vec<f32>,
}

/// The space-time map as a checkpoint keeps it.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SpaceTimeMemory {
    pub t_span: f64,
    pub bins: usize,
    pub segments: usize,
    pub peaks: Vec<f32>,
}

/// The most multiples of its bins' first span a map grows to before its bins widen.
const MOST_SPANS: usize = 4;

impl SpaceTimeMemory {
    /// The same map in bins twice as wide.
    fn coarsened(&self) -> Self {
        let bins = self.bins.div_ceil(2);
        let peaks = self
            .peaks
            .chunks(self.bins)
            .flat_map(|row| row.chunks(2).map(|pair| pair.iter().fold(0.0_f32, |m, v| m.max(*v))).collect::<Vec<_>>())
            .collect();
        Self { t_span: 2.0 * self.t_span, bins, segments: self.segments, peaks }
    }
}

impl SpaceTime {
    pub fn new(t_end: f64, segments: usize) -> Self {
        Self { t_span: t_end, bins: TIME_BINS, segments, peaks: vec![0.0; TIME_BINS * segments] }
    }

    /// Adds a recorded step's slip rates (recorded steps only, so that a replayed log draws
    /// the same map).
    pub fn push(&mut self, time: f64, rates: impl Iterator<Item = f64>) {
        let bin = ((time / self.t_span * TIME_BINS as f64) as usize).min(self.bins - 1);
        for (k, rate) in rates.take(self.segments).enumerate() {
            let cell = &mut self.peaks[k * self.bins + bin];
            *cell = cell.max(rate as f32);
        }
    }

    /// The map so far, for a checkpoint.
    pub fn memory(&self) -> SpaceTimeMemory {
        SpaceTimeMemory { t_span: self.t_span, bins: self.bins, segments: self.segments, peaks: self.peaks.clone() }
    }

    /// Continues the saved map up to `t_end`: its bins as they were, and more of the same width
    /// if `t_end` lies beyond them.
    pub fn resume(&mut self, saved: SpaceTimeMemory, t_end: f64) -> Result<(), String> {
        let fits = saved.segments == self.segments
            && saved.bins >= 1
            && saved.peaks.len() == saved.bins * saved.segments
            && saved.t_span.is_finite()
            && saved.t_span > 0.0;
        if !fits {
            return Err("the checkpoint's space-time map does not fit this run".into());
        }
        let mut saved = saved;
        // A run extended far beyond its first span gets wider bins, each the peak of two.
        while t_end / saved.t_span > MOST_SPANS as f64 && saved.bins > 1 {
            saved = saved.coarsened();
        }
        let needed = (t_end / saved.t_span * TIME_BINS as f64).ceil().min((MOST_SPANS * TIME_BINS) as f64);
        let bins = if needed.is_finite() { saved.bins.max(needed as usize) } else { saved.bins };
        let mut peaks = vec![0.0; bins * self.segments];
        for (row, saved_row) in peaks.chunks_mut(bins).zip(saved.peaks.chunks(saved.bins)) {
            row[..saved.bins].copy_from_slice(saved_row);
        }
        (self.t_span, self.bins, self.peaks) = (saved.t_span, bins, peaks);
        Ok(())
    }

    /// Logs the map and its tick labels (static): `log10` of the peak slip rate (m/s), from a
    /// hundredth of the event `threshold` (anything slower shows as that floor) to the peak.
    pub fn log(&self, rec: &RecordingStream, layout: &Layout, threshold: f64) -> rerun::RecordingStreamResult<()> {
        let floor = (threshold / 100.0).log10() as f32;
        let peak = self.peaks.iter().fold(0.0_f32, |m, v| m.max(*v)) as f64;
        let top = peak.max(threshold * 10.0).log10() as f32;
        let bytes: Vec<u8> = self
            .peaks
            .iter()
            .map(|&v| if v > 0.0 { v.log10().max(floor) } else { floor })
            .flat_map(f32::to_le_bytes)
            .collect();
        let format = rerun::components::ImageFormat::depth(
            [self.bins as u32, self.segments as u32],
            rerun::datatypes::ChannelDatatype::F32,
        );
        rec.log_static(
            schema::SPACETIME_IMAGE,
            &rerun::DepthImage::new(bytes, format)
                .with_meter(1.0)
                .with_colormap(rerun::components::Colormap::Inferno)
                .with_depth_range([floor as f64, top as f64]),
        )?;
        let lane = lane_height(self.segments) as f32;
        rec.log_static(schema::SPACETIME_IMAGE, &rerun::Transform3D::from_scale([1.0, lane, 1.0]))?;
        let (positions, labels) = self.ticks(layout);
        rec.log_static(
            schema::SPACETIME_AXES,
            &rerun::Points2D::new(positions)
                .with_labels(labels)
                .with_radii([rerun::Radius::new_ui_points(2.0)])
                .with_colors([rerun::Color::from_rgb(200, 200, 200)]),
        )
    }

    /// Tick marks: `sim_time` (s) under the map every tenth of the run; on its left, each
    /// contact's arc length (m; the block's x) at round lengths over its band of lanes, and the
    /// contact's name where there are several (none for a surface without a length, such as a
    /// spring-block's).
    fn ticks(&self, layout: &Layout) -> (Vec<[f32; 2]>, Vec<String>) {
        let height = map_height(self.segments) as f64;
        let lane = lane_height(self.segments) as f64;
        let mut positions = Vec::new();
        let mut labels = Vec::new();
        let t_end = self.t_span * self.bins as f64 / TIME_BINS as f64;
        for t in ticks_over(t_end, 10.0) {
            positions.push([(t / self.t_span * TIME_BINS as f64) as f32, (height + 15.0) as f32]);
            labels.push(format!("{} s", shortest(t)));
        }
        let several = layout.contacts.len() > 1;
        for (name, segments, _) in layout.contact_ranges() {
            let Some((first, last)) =
                layout.segments.get(segments.start).zip(layout.segments.get(segments.end.wrapping_sub(1)))
            else {
                continue;
            };
            let (start, length) = (first.left, last.right - first.left);
            let (top, band) = (segments.start as f64 * lane, segments.len() as f64 * lane);
            if several {
                positions.push([-120.0, top as f32]);
                labels.push(name);
            }
            for x in ticks_over(length, if several { 3.0 } else { 5.0 }) {
                positions.push([-30.0, (top + x / length * band) as f32]);
                labels.push(format!("{} m", shortest(start + x)));
            }
        }
        (positions, labels)
    }
}

/// Round values from 0 to `span`, about `count` intervals apart; none for a span that is not a
/// positive number.
fn ticks_over(span: f64, count: f64) -> Vec<f64> {
    if !(span.is_finite() && span > 0.0) {
        return Vec::new();
    }
    let step = round_step(span / count);
    (0..=(2.0 * count) as usize).map(|i| i as f64 * step).take_while(|&v| v <= span * (1.0 + 1e-9)).collect()
}

/// The round number (1, 2 or 5 × 10ⁿ) nearest above `x`.
fn round_step(x: f64) -> f64 {
    let decade = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * decade).find(|&s| s >= x * (1.0 - 1e-9)).unwrap_or(10.0 * decade)
}

/// `x` with at most 6 significant digits, without trailing zeros.
fn shortest(x: f64) -> String {
    let text = format!("{:.6}", x);
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_steps_are_one_two_or_five_times_a_power_of_ten() {
        assert_eq!(round_step(2.0), 2.0);
        assert_eq!(round_step(100.0), 100.0);
        assert_eq!(round_step(130.0), 200.0);
        assert_eq!(round_step(0.03), 0.05);
        assert_eq!(shortest(400.0), "400");
        assert_eq!(ticks_over(1000.0, 10.0).len(), 11);
        assert_eq!(ticks_over(10.0, 5.0), [0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
        assert!(ticks_over(0.0, 5.0).is_empty() && ticks_over(f64::NAN, 5.0).is_empty());
        assert_eq!(shortest(0.25), "0.25");
    }
}
