//! A segment's values as the frames report them: the contact points' friction states (eqs.
//! 1-9) averaged over the segment with their integration weights.

use crate::frame::SegmentSample;
use crate::friction::{ContactState, FrictionParams};

/// Averages the Gauss points `(weight, state, plastic slip rate)` into a segment sample: its
/// traction, slip, slip rate and `1/R*`, and with `full` its `f_n`, `R` and `R*`.
pub fn segment_sample(
    params: &FrictionParams,
    points: impl Iterator<Item = (f64, ContactState, f64)>,
    full: bool,
) -> SegmentSample {
    let mut sample = SegmentSample::default();
    let mut total = 0.0;
    for (weight, state, rate) in points {
        total += weight;
        sample.traction_t += weight * state.traction_t;
        sample.slip += weight * state.plastic_slip;
        sample.slip_rate += weight * rate;
        sample.structure += weight * state.structure;
        if full {
            sample.traction_n += weight * state.traction_n;
            sample.sliding_ratio += weight * state.sliding_ratio(params);
            sample.r_star += weight * state.r_star();
        }
    }
    let inv = 1.0 / total;
    sample.traction_t *= inv;
    sample.slip *= inv;
    sample.slip_rate *= inv;
    sample.traction_n *= inv;
    sample.sliding_ratio *= inv;
    sample.r_star *= inv;
    sample.structure *= inv;
    sample
}
