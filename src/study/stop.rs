//! Stop rules of a study's members, so that a sweep pays only for what it asks: a member stops
//! after the first rupture that covered the whole surface, or once nothing has slipped for a
//! while. A rule is a sink that watches the frames and raises the member's stop flag; the run
//! then ends after the current step with every output finished, as an interrupted run does.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};

use serde::Deserialize;

use crate::catalog::events::Catalog;
use crate::frame::{Ending, Frame, Layout};
use crate::sink::{Sink, SinkError};

/// `[stop]` of a study file.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StopSpec {
    /// Stop once every segment has slipped in one rupture (between two moments when none
    /// slips) and the contact sticks again.
    #[serde(default)]
    pub after_whole_rupture: bool,
    /// Stop once no segment has slipped for this long (s), counted from the last slip or the
    /// start.
    pub quiet_for: Option<f64>,
}

impl StopSpec {
    pub fn is_empty(&self) -> bool {
        !self.after_whole_rupture && self.quiet_for.is_none()
    }

    /// The rules' own checks.
    pub fn check(&self) -> Result<(), String> {
        match self.quiet_for {
            Some(t) if !(t.is_finite() && t > 0.0) => {
                Err(format!("stop.quiet_for = {} must be a positive number of seconds", crate::validate::shortest(t)))
            }
            _ => Ok(()),
        }
    }
}

/// The rules watching one member's run.
pub struct StopRules<'a> {
    spec: StopSpec,
    threshold: f64,
    /// The member's stop flag (the run loop's interrupt), and the study's (Ctrl-C), passed on.
    member: &'a AtomicBool,
    study: Option<&'a AtomicBool>,
    /// Why a rule stopped the member.
    pub fired: &'a OnceLock<String>,
    slipped: Vec<bool>,
    last_slip: f64,
}

impl<'a> StopRules<'a> {
    pub fn new(
        spec: StopSpec,
        threshold: f64,
        member: &'a AtomicBool,
        study: Option<&'a AtomicBool>,
        fired: &'a OnceLock<String>,
    ) -> Self {
        Self { spec, threshold, member, study, fired, slipped: Vec::new(), last_slip: 0.0 }
    }

    fn fire(&self, why: String) {
        let _ = self.fired.set(why);
        self.member.store(true, Ordering::SeqCst);
    }
}

impl Sink for StopRules<'_> {
    fn begin(&mut self, layout: &Layout) -> Result<(), SinkError> {
        self.slipped = vec![false; layout.segments.len()];
        Ok(())
    }

    fn record(&mut self, frame: &Frame) -> Result<(), SinkError> {
        if self.study.is_some_and(|f| f.load(Ordering::SeqCst)) {
            self.member.store(true, Ordering::SeqCst);
        }
        let mut any = false;
        for (seen, s) in self.slipped.iter_mut().zip(&frame.segments) {
            if s.slip_rate > self.threshold {
                *seen = true;
                any = true;
            }
        }
        if any {
            self.last_slip = frame.time;
        } else {
            if self.spec.after_whole_rupture && !self.slipped.is_empty() && self.slipped.iter().all(|&s| s) {
                self.fire(format!("after a whole-surface rupture, at {:.2} s", frame.time));
            }
            self.slipped.iter_mut().for_each(|s| *s = false);
        }
        if let Some(quiet) = self.spec.quiet_for
            && frame.time - self.last_slip >= quiet
        {
            self.fire(format!("nothing slipped for {quiet} s, at {:.2} s", frame.time));
        }
        Ok(())
    }

    fn finish(&mut self, _: Ending, _: Option<&Frame>, _: &Catalog) -> Result<(), SinkError> {
        Ok(())
    }
}
