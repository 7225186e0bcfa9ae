//! The paper's four observations (MODEL.md, §3.3 of the paper) measured on an event catalog, so
//! that a sweep, a test and a user's own study judge a run the same way.
//!
//! Definitions: the left and right ends are the first and last segments; a segment's re-slip is
//! any slip after its first; ruptures "nucleated on the left" start in the left third of the
//! surface (the paper's segments A, B) and stay "local" if they do not reach the right third
//! (E, F); a rupture "reaches the whole surface" if every segment slipped.

use crate::case::{Case, NormalTractionSpec, SceneSpec};
use crate::catalog::events::{Rupture, SlipEvent};
use crate::validate::shortest;

/// What the catalog says about the paper's observations.
#[derive(Debug, Clone, PartialEq)]
pub struct Observations {
    pub segments: usize,
    /// Onsets of the left end's slips (s).
    pub left_onsets: Vec<f64>,
    /// `1/R*` before each of the left end's re-slips.
    pub left_reslip_structure: Vec<f64>,
    /// Slip of each of the left end's events (m).
    pub left_slips: Vec<f64>,
    pub right_onsets: Vec<f64>,
    /// `1/R*` before each of the right end's slips.
    pub right_structure: Vec<f64>,
    pub right_slips: Vec<f64>,
    /// Ruptures nucleated in the left third that reached the right third.
    pub left_ruptures_escaping: usize,
    /// Ruptures nucleated in the left third.
    pub left_ruptures: usize,
    /// Ruptures that reached the right end without covering the whole surface.
    pub right_ruptures_partial: usize,
    /// Ruptures that covered the whole surface.
    pub whole_ruptures: usize,
}

impl Observations {
    /// Measures a catalog of `segments` segments; events need `structure_before`.
    pub fn measure(events: &[SlipEvent], ruptures: &[Rupture], segments: usize) -> Self {
        let of = |segment: usize| events.iter().filter(move |e| e.segment == segment);
        let structure = |e: &SlipEvent| e.structure_before.unwrap_or(f64::NAN);
        let third = segments / 3;
        Self {
            segments,
            left_onsets: of(0).map(|e| e.onset).collect(),
            left_reslip_structure: of(0).skip(1).map(structure).collect(),
            left_slips: of(0).map(|e| e.slip).collect(),
            right_onsets: of(segments - 1).map(|e| e.onset).collect(),
            right_structure: of(segments - 1).map(structure).collect(),
            right_slips: of(segments - 1).map(|e| e.slip).collect(),
            left_ruptures_escaping: ruptures
                .iter()
                .filter(|r| r.nucleation_segment < third && r.last_segment >= segments - third)
                .count(),
            left_ruptures: ruptures.iter().filter(|r| r.nucleation_segment < third).count(),
            right_ruptures_partial: ruptures
                .iter()
                .filter(|r| r.last_segment == segments - 1 && r.segments_slipped < segments)
                .count(),
            whole_ruptures: ruptures.iter().filter(|r| r.segments_slipped == segments).count(),
        }
    }

    /// A single number that is 0 when every observation holds as the paper states it:
    /// 5 slips at the left end re-slipping at `1/R*` ≈ 1.5, one slip at the right end at
    /// `1/R*` ≈ 1.9, no escaping left rupture, no partial rupture through the right end.
    pub fn misfit(&self) -> f64 {
        let mean = |v: &[f64]| if v.is_empty() { f64::NAN } else { v.iter().sum::<f64>() / v.len() as f64 };
        let z_left = mean(&self.left_reslip_structure);
        let z_right = mean(&self.right_structure);
        (self.left_onsets.len() as f64 - 5.0).abs()
            + 2.0 * (self.right_onsets.len() as f64 - 1.0).abs()
            + if z_left.is_nan() { 5.0 } else { (z_left - 1.5).abs() / 0.1 }
            + if z_right.is_nan() { 5.0 } else { (z_right - 1.9).abs() / 0.05 }
            + 2.0 * (self.left_ruptures_escaping + self.right_ruptures_partial) as f64
    }
}

/// Whether the paper's observations 1–3 hold in one run, by the criteria below (fixed when the
/// paper case was first calibrated, before its chaos was known; see [`crate::study::ensemble`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Verdict {
    /// 1. The left end slips 4 to 6 times (the paper: 5), re-slipping at a mean `1/R*` in
    ///    [1.4, 1.75] (the paper: ≈ 1.5, before the structure has recovered).
    pub left_end: bool,
    /// 2. The right end slips once, at `1/R*` ≥ 1.85 (the paper: ≈ 1.9), and further than 4 ×
    ///    the left end's median slip.
    pub right_end: bool,
    /// 3. Ruptures nucleated in the left third occur and none reaches the right third; at least
    ///    one rupture covers the whole surface and none reaches the right end without doing so.
    pub propagation: bool,
}

impl Verdict {
    pub fn all(self) -> bool {
        self.left_end && self.right_end && self.propagation
    }
}

impl Observations {
    /// The [`Verdict`] on this run.
    pub fn verdict(&self) -> Verdict {
        let mean = |v: &[f64]| if v.is_empty() { f64::NAN } else { v.iter().sum::<f64>() / v.len() as f64 };
        let left_end =
            (4..=6).contains(&self.left_onsets.len()) && (1.4..=1.75).contains(&mean(&self.left_reslip_structure));
        let right_end = self.right_onsets.len() == 1
            && self.right_structure[0] >= 1.85
            && !self.left_slips.is_empty()
            && self.right_slips[0] > 4.0 * median(&self.left_slips);
        let propagation = self.left_ruptures > 0
            && self.left_ruptures_escaping == 0
            && self.whole_ruptures > 0
            && self.right_ruptures_partial == 0;
        Verdict { left_end, right_end, propagation }
    }
}

/// The span the paper's observations 1 and 2 count slips in (s).
pub const PAPER_SPAN: f64 = 1000.0;

/// Whether the paper's observations 1–3 ([`Verdict`]) say anything of a run of `case`, and if
/// not, why. They name the contact's ends and thirds by their normal stress (low at the left,
/// high at the right) and count slips in the paper's 1000 s, so they apply to its family only:
/// the block scene (any size or mesh density), at least 3 segments, a normal traction that never
/// falls from the left end to the right and ends higher than it starts, and `t_end` = 1000 s.
/// Friction, material and loading may differ: whether the observations still hold is then
/// what a study asks.
pub fn paper_family(case: &Case) -> Result<(), String> {
    let SceneSpec::Block(block) = &case.scene else {
        let kind = match case.scene {
            SceneSpec::Point(_) => "point",
            SceneSpec::SpringBlock(_) => "spring_block",
            SceneSpec::Block(_) => "block",
            SceneSpec::Mesh(_) => "mesh",
        };
        return Err(format!("scene.kind = \"{kind}\", not the paper's block"));
    };
    if block.nx < 3 {
        return Err(format!("scene.nx = {}: the observations compare the contact's thirds", block.nx));
    }
    let rising = match &block.normal_traction {
        NormalTractionSpec::Uniform { .. } => false,
        NormalTractionSpec::Linear { left, right } => left < right,
        NormalTractionSpec::Table { value, .. } => {
            value.windows(2).all(|w| w[0] <= w[1]) && value.first() < value.last()
        }
    };
    if !rising {
        return Err("the normal traction does not rise from the left end to the right, as the paper's does".into());
    }
    if (case.time.t_end - PAPER_SPAN).abs() > 1e-9 * PAPER_SPAN {
        return Err(format!(
            "time.t_end = {} s: the observations count slips in the paper's {} s",
            shortest(case.time.t_end),
            PAPER_SPAN
        ));
    }
    Ok(())
}

/// Median of a non-empty list.
pub fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
}
