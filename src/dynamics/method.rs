//! Which integrator does what: every rule about the time integrators in one place. A case
//! names a [`Method`] (`time.integrator`); this module says what tolerance it takes, whether
//! its steps are adaptive, what it reports, and builds it ([`Stepping::integrator`]).

use serde::{Deserialize, Serialize};

use crate::dynamics::central::{CentralDifference, highest_frequency};
use crate::dynamics::control::StepControl;
use crate::dynamics::cycle::CycleSteps;
use crate::dynamics::integrator::Integrator;
use crate::dynamics::rate_form::driver::{RateForm, Tableau};
use crate::dynamics::rate_form::tsit5::bounded_growth;
use crate::dynamics::step_doubling::StepDoubling;
use crate::dynamics::system::System;
use crate::dynamics::wilson::Wilson;

/// `time.integrator`: the time integrator of dynamic scenes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Wilson's θ method with the implicit friction update (the paper's §2.2): fixed steps of
    /// `dt`, or adaptive by step doubling when `tolerance` is set.
    #[default]
    Wilson,
    /// Tsitouras' 5(4) pair on the rate equations (4)-(6), (14), always adaptive, with the
    /// instants where a contact point's slip rate crosses the event threshold located
    /// ([`crate::dynamics::rate_form`]). `tolerance` is its local error per step.
    Tsit5,
    /// Hairer and Wanner's L-stable SDIRK 4(3) on the same rate equations, always adaptive,
    /// crossings located as for `Tsit5` ([`crate::dynamics::rate_form::sdirk4`]). `tolerance`
    /// is its local error per step.
    Sdirk4,
    /// Explicit central differences for the body with the implicit friction update of each
    /// step ([`crate::dynamics::central`]): frames every `dt`, each taken in the fewest equal
    /// sub-steps the stability limit allows. No `tolerance`.
    Central,
    /// Wilson's θ method with steps from the contact's rates, for slow drives and earthquake
    /// cycles ([`crate::dynamics::cycle`]): `dt` through a slip, up to `dt_max` through stick,
    /// steps far longer than the body's slowest period ending on the quasi-static path.
    /// `tolerance` is the largest change of a contact point's state in one step, relative to
    /// its scale.
    Cycle,
}

/// `time.integrator` as a case file gives it: a method by name, or `auto` (the default), which
/// [`choose`] resolves for the scene.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Choice {
    #[default]
    Auto,
    Named(Method),
}

/// Every value `time.integrator` takes.
pub const CHOICES: [&str; 6] = ["auto", "wilson", "tsit5", "sdirk4", "central", "cycle"];

impl<'de> Deserialize<'de> for Choice {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        match name.as_str() {
            "auto" => Ok(Choice::Auto),
            _ => Method::from_name(&name)
                .map(Choice::Named)
                .ok_or_else(|| serde::de::Error::unknown_variant(&name, &CHOICES)),
        }
    }
}

/// What [`choose`] needs to know of a case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Problem {
    /// One contact point under a prescribed motion.
    Point,
    /// A body of `unknowns` (a rigid block has one), whose healing relaxes `1/R*` at the rate
    /// `γ ξ n μ_k/μ_s` (1/s; eq. 4 linearized, `n` at least 1): `healing` is that rate times
    /// `dt`, the number of healing times in a step; `stiffness`: an upper bound on the highest
    /// angular frequency of the body on its contact's elastic springs times `dt`, the radians
    /// its stiffest mode turns in a step ([`crate::fem::stiffest`]; `None` where not bounded);
    /// `loading`: the drive's time to load the weakest contact point by its elastic slip at
    /// its static strength, `μ_s f_n / (α_t v)`, in radians of that mode (`None` where either is
    /// not known); `evolving`: some contact's normal traction evolves.
    Body { unknowns: usize, healing: f64, stiffness: Option<f64>, loading: Option<f64>, evolving: bool },
}

/// The most radians the stiffest mode of a small body may turn in a step of `dt` for `auto` to
/// give it Tsitouras' pair, which is explicit: its stability holds its steps to about
/// `0.76/ω_max` ([`bounded_growth`]), where Wilson's implicit step takes `dt`. Measured on the
/// paper's block with `α_t` raised (300 s, CPU, 2026-11-26): at 1.4 radians per step the pair
/// takes a third of Wilson's time, at 3.2 the same, at 4.5 1.4 times it, at 14 five times; an
/// evolving contact with `α_n = 1e12` (447 radians) 51 s against Wilson's 0.24 s for 100 s.
/// Up to 6 the pair's far smaller onset errors are worth its time.
pub const AUTO_PAIR_STIFFNESS: f64 = 6.0;

/// The fewest radians of its stiffest mode in which the drive loads a small body's contact
/// ([`Problem::Body`]'s `loading`) for `auto` to give it cycle steps: 1 600 times the paper's
/// drive (6.3 radians at 1 mm/s). The paper's block at 1e-9 m/s (6.3e6 radians) runs 100 years
/// in 132 s with them, where Wilson's method with adaptive steps stops after a day of simulated
/// time and SDIRK4 reaches 28 000 s in 90 s (docs/performance.md, "Slow loading").
pub const AUTO_CYCLE_LOADING: f64 = 1e4;

/// The most unknowns of a body that `auto` gives to Tsitouras' pair; larger bodies get central
/// differences. On the paper's 10 × 1 mesh (44 unknowns) the pair runs 1000 s in half the time of
/// Wilson's method at dt = 0.01 s with 50× less onset error; on 100 × 10 (2 222 unknowns) central
/// differences cost 6 ms per simulated second against the pair's 17 ms, and on 1000 × 100 they
/// take 8 minutes where the pair takes 3.5 hours (docs/performance.md).
pub const AUTO_PAIR_UNKNOWNS: usize = 1000;

/// `time.integrator = "auto"`: the method for `problem`, and why. A small body whose healing
/// is stiff on the case's `dt` gets Wilson's method: Tsitouras' pair would be held by its
/// stability to steps of a fraction of the healing time (the spring block at `ξ = 1e6/s`:
/// 65 million steps, 45 s, against Wilson's 0.5 s).
pub fn choose(problem: Problem) -> (Method, String) {
    match problem {
        Problem::Point => {
            (Method::Wilson, "a point scene prescribes its motion; Wilson's implicit friction update is its own".into())
        }
        Problem::Body { unknowns, loading: Some(turns), .. } if turns > AUTO_CYCLE_LOADING => (
            Method::Cycle,
            format!(
                "a body of {unknowns} unknowns whose drive loads its weakest contact point by its elastic slip \
                 (μ_s f_n/α_t) in {turns:.1e} radians of its stiffest mode (more than {AUTO_CYCLE_LOADING:e}): \
                 stick lasts far longer than the body's periods, and cycle steps grow through it to the \
                 loading's own time scale"
            ),
        ),
        Problem::Body { unknowns, healing, .. } if unknowns <= AUTO_PAIR_UNKNOWNS && healing > 1.0 => (
            Method::Wilson,
            format!(
                "a body of {unknowns} unknown{} whose healing time (1/(ξ n μ_k/μ_s)) is {} times shorter than \
                 time.dt: an explicit pair would be held to steps of a fraction of it, where Wilson's implicit \
                 update steps over it",
                if unknowns == 1 { "" } else { "s" },
                crate::validate::shortest(healing)
            ),
        ),
        Problem::Body { unknowns, stiffness: Some(turn), .. }
            if unknowns <= AUTO_PAIR_UNKNOWNS && turn > AUTO_PAIR_STIFFNESS =>
        {
            (
                Method::Wilson,
                format!(
                    "a body of {unknowns} unknown{} whose stiffest mode, on the contact's elastic springs, turns up to \
                     {} radians in a step of time.dt (more than {AUTO_PAIR_STIFFNESS}): Tsitouras' explicit pair would be \
                     held by its stability to steps of under one radian of it, where Wilson's implicit step takes time.dt",
                    if unknowns == 1 { "" } else { "s" },
                    if turn >= 10.0 { format!("{turn:.0}") } else { format!("{turn:.1}") }
                ),
            )
        }
        Problem::Body { unknowns, .. } if unknowns <= AUTO_PAIR_UNKNOWNS => (
            Method::Tsit5,
            format!(
                "a body of {unknowns} unknown{} (at most {AUTO_PAIR_UNKNOWNS}): Tsitouras' adaptive pair is the \
                 fastest at the accuracy asked",
                if unknowns == 1 { "" } else { "s" }
            ),
        ),
        Problem::Body { unknowns, evolving: true, .. } => (
            Method::Wilson,
            format!(
                "a body of {unknowns} unknowns (more than {AUTO_PAIR_UNKNOWNS}) whose contact's normal traction \
                 evolves: central differences do not damp a stiff contact's chatter as it closes, where Wilson's θ \
                 does (cases/cylinder_on_base.toml: 1828 openings of its segments in 1.2 s against 163, in 12 s \
                 against 5 s)"
            ),
        ),
        Problem::Body { unknowns, .. } => (
            Method::Central,
            format!(
                "a body of {unknowns} unknowns (more than {AUTO_PAIR_UNKNOWNS}): central differences, whose step \
                 needs no solve, are the fastest on fine meshes"
            ),
        ),
    }
}

/// The range `time.accuracy` must lie in.
pub const ACCURACY_RANGE: (f64, f64) = (1e-9, 1e-2);

/// How each method's setting maps to the relative error of slip-onset times on the paper case
/// (onset error over onset time; the first four onsets, 420–429 s, against SciPy's Radau at
/// rtol 1e-11; 2026-11): at most about 300 × the tolerance for `tsit5` (230 to 400 measured
/// from 1e-8 to 1e-10) and for `sdirk4` (72 to 345 from 1e-7 to 7e-9), `1.6 dt²` for Wilson's
/// fixed steps (dt in s; 1.55 to 1.9 from 0.01 to 0.001 s) and `0.5 dt²` for central
/// differences (0.28 to 0.46 from 0.01 to 0.0018 s). Onset errors scatter by a factor of a
/// few about these from one setting to the next; docs/performance.md has the measurements.
const ONSET_ERROR_PER_TOLERANCE: [(Method, f64); 2] = [(Method::Tsit5, 300.0), (Method::Sdirk4, 300.0)];
const ONSET_ERROR_PER_STEP_SQUARED: [(Method, f64); 2] = [(Method::Wilson, 1.6), (Method::Central, 0.5)];

/// Local error per step of `tsit5` when `time.tolerance` is not given.
pub const TSIT5_DEFAULT_TOLERANCE: f64 = 1e-8;

/// Local error per step of `sdirk4` when `time.tolerance` is not given.
pub const SDIRK4_DEFAULT_TOLERANCE: f64 = 1e-7;

/// The smallest local error per step that `sdirk4` is let hold. Its stages are recovered as
/// `(Y - known)/(hγ)`, whose rounding grows as the step shrinks, and through a slip the error
/// estimate stops falling with the step: the spring block fails at 1e-13 (796 s) and the paper
/// case at 1e-12 (776 s), each with a step below the smallest allowed; both run their 1000 s at
/// 1e-11.
pub const SDIRK4_SMALLEST_TOLERANCE: f64 = 1e-11;

/// The smallest local error per step that `tsit5` is let hold. Through a slip's onset the pair
/// walks the logarithmic singularity of `Λ` with steps of picoseconds, where rounding in the
/// time itself stops the error estimate from falling: the spring block fails at 3e-14 (796.87 s,
/// asking for a step of 0.66 ps) and runs its 1000 s at 1e-13.
pub const TSIT5_SMALLEST_TOLERANCE: f64 = 1e-13;

/// The largest change of a contact point's state in one cycle step when `time.tolerance` is
/// not given ([`crate::dynamics::cycle`]).
pub const CYCLE_DEFAULT_TOLERANCE: f64 = 0.01;

/// Most steps a run may take, to refuse a typo such as `dt = 1e-12` before it starts.
pub const MAX_STEPS: f64 = 1e9;

/// What `time.tolerance` means for a method, and the range it must lie in.
pub struct ToleranceRule {
    /// The smallest tolerance allowed (inclusive), if any; else it must be above 0.
    pub smallest: Option<f64>,
    /// The largest (inclusive).
    pub largest: f64,
    /// What it means, for error messages.
    pub meaning: String,
}

impl Method {
    /// The method a case file names `name`, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        [Method::Wilson, Method::Tsit5, Method::Sdirk4, Method::Central, Method::Cycle]
            .into_iter()
            .find(|m| m.name() == name)
    }

    /// The setting that aims at a relative onset error of `accuracy` (`time.accuracy`): the
    /// Runge–Kutta methods' tolerance, or the fixed step of Wilson's method and central
    /// differences, never longer than the case's `dt` (which also spaces their frames). Returns
    /// `(dt, tolerance)`.
    pub fn for_accuracy(self, accuracy: f64, dt: f64) -> (f64, Option<f64>) {
        let per = |table: &[(Method, f64)]| table.iter().find(|(m, _)| *m == self).map(|(_, c)| *c);
        if let Some(c) = per(&ONSET_ERROR_PER_TOLERANCE) {
            let smallest = self.tolerance_rule().and_then(|r| r.smallest).unwrap_or(0.0);
            (dt, Some((accuracy / c).max(smallest)))
        } else {
            let c = per(&ONSET_ERROR_PER_STEP_SQUARED).expect("every method has a mapping");
            (dt.min((accuracy / c).sqrt()), None)
        }
    }

    /// The case file's name for it.
    pub fn name(self) -> &'static str {
        match self {
            Method::Wilson => "wilson",
            Method::Tsit5 => "tsit5",
            Method::Sdirk4 => "sdirk4",
            Method::Central => "central",
            Method::Cycle => "cycle",
        }
    }

    /// What `time.tolerance` means for this method and where it must lie; `None` where the
    /// method takes no tolerance (central differences).
    pub fn tolerance_rule(self) -> Option<ToleranceRule> {
        let (smallest, meaning) = match self {
            Method::Wilson => (None, "a relative local error per second, 1/s".to_string()),
            Method::Sdirk4 => (
                Some(SDIRK4_SMALLEST_TOLERANCE),
                "a relative local error per step of sdirk4; below that, rounding in its stages \
                 can exceed it through the slips"
                    .to_string(),
            ),
            Method::Tsit5 => (
                Some(TSIT5_SMALLEST_TOLERANCE),
                "a relative local error per step of tsit5; below that, rounding in the time itself can \
                 exceed it at a slip's onset"
                    .to_string(),
            ),
            Method::Cycle => (
                None,
                "the largest change of a contact point's traction, structure or plastic slip in one step, \
                 relative to its static strength, its range and its elastic slip"
                    .to_string(),
            ),
            Method::Central => return None,
        };
        Some(ToleranceRule { smallest, largest: 0.1, meaning })
    }

    /// The tolerance of adaptive stepping, if steps are adaptive: `tolerance` as given, or for
    /// the Runge–Kutta methods (always adaptive) their default.
    pub fn adaptive_tolerance(self, tolerance: Option<f64>) -> Option<f64> {
        match self {
            Method::Wilson => tolerance,
            Method::Tsit5 => Some(tolerance.unwrap_or(TSIT5_DEFAULT_TOLERANCE)),
            Method::Sdirk4 => Some(tolerance.unwrap_or(SDIRK4_DEFAULT_TOLERANCE)),
            Method::Cycle => Some(tolerance.unwrap_or(CYCLE_DEFAULT_TOLERANCE)),
            Method::Central => None,
        }
    }

    /// Whether the method keeps an energy ledger and guards it (`time.energy_tolerance`):
    /// Wilson's method does; the Runge–Kutta methods' error control bounds their steps; central
    /// differences conserve energy up to their truncation error.
    pub fn guards_energy(self) -> bool {
        matches!(self, Method::Wilson | Method::Cycle)
    }

    /// Whether the method reports each point's plastic slip rate `Λ` at the end of a step
    /// (the Runge–Kutta methods) rather than the step's mean `Δp/Δt`.
    pub fn instantaneous_slip_rate(self) -> bool {
        matches!(self, Method::Tsit5 | Method::Sdirk4)
    }

    /// Whether every step is one of Wilson's method of `dt`: the only stepping for which a
    /// large body is condensed onto its contact ([`crate::dynamics::condensed`]).
    pub fn fixed_implicit_steps(self, tolerance: Option<f64>) -> bool {
        self == Method::Wilson && tolerance.is_none()
    }

    /// Whether the method integrates a scene without a body (the point scene, driven by a
    /// prescribed slip history): only Wilson's method, whose implicit friction update is the
    /// point scene's own.
    pub fn steps_a_point(self) -> bool {
        self == Method::Wilson
    }

    /// Smallest adaptive step (s) over a run of `t_end`: below this a run stops rather than
    /// crawl. The Runge–Kutta methods may go down to a few roundings of the time itself (4 ulp
    /// of `t_end`): they walk through the logarithmic singularity of `Λ` where a traction
    /// changes sign (`R → 0` in the `-ln R` of eq. 5's denominator) with steps that grow
    /// geometrically from picoseconds.
    /// Cycle steps never go below `dt`, the step through a slip.
    pub fn dt_min(self, t_end: f64, dt: f64) -> f64 {
        match self {
            Method::Cycle => dt,
            Method::Wilson | Method::Central => t_end / MAX_STEPS,
            Method::Tsit5 | Method::Sdirk4 => 4.0 * f64::EPSILON * t_end,
        }
    }

    /// How a run steps, for people: `in N steps of dt s`, or the adaptive method and its
    /// tolerance (`tolerance` as from [`Self::adaptive_tolerance`]).
    pub fn describe(self, tolerance: Option<f64>, steps: u64, dt: f64) -> String {
        match (self, tolerance) {
            (Method::Wilson, None) => format!("in {steps} steps of {dt} s"),
            (Method::Wilson, Some(tolerance)) => {
                format!("in adaptive Wilson steps from {dt} s, tolerance {tolerance:e} per simulated second")
            }
            (Method::Central, _) => {
                format!("in {steps} frames of {dt} s by central differences, each sub-stepped to the stability limit")
            }
            (Method::Tsit5, tolerance) => format!(
                "by Tsitouras' 5(4) pair from a step of {dt} s, tolerance {:e} per step",
                tolerance.unwrap_or(TSIT5_DEFAULT_TOLERANCE)
            ),
            (Method::Sdirk4, tolerance) => format!(
                "by the L-stable SDIRK 4(3) from a step of {dt} s, tolerance {:e} per step",
                tolerance.unwrap_or(SDIRK4_DEFAULT_TOLERANCE)
            ),
            (Method::Cycle, tolerance) => format!(
                "in Wilson steps from {dt} s through a slip to time.dt_max through stick, each changing the \
                 contact's state by at most {:e} of its scale",
                tolerance.unwrap_or(CYCLE_DEFAULT_TOLERANCE)
            ),
        }
    }
}

/// How a run steps: the method and the numbers it needs, from the case's `[time]` and
/// `[events]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stepping {
    pub method: Method,
    /// The fixed step, or the first adaptive one (s).
    pub dt: f64,
    /// The adaptive tolerance ([`Method::adaptive_tolerance`]); `None` for fixed steps.
    pub tolerance: Option<f64>,
    /// Largest and smallest adaptive step (s).
    pub dt_max: f64,
    pub dt_min: f64,
    /// The slip rate (m/s) whose crossings the Runge–Kutta methods locate.
    pub slip_rate_threshold: f64,
}

impl Stepping {
    /// The integrator for `system`.
    pub fn integrator(&self, system: &System) -> Box<dyn Integrator> {
        let control = |tolerance, dt_max: f64| StepControl::new(tolerance, self.dt, dt_max, self.dt_min);
        let rate_form = |tableau, tolerance, dt_max| {
            Box::new(RateForm::new(tableau, control(tolerance, dt_max), self.slip_rate_threshold))
        };
        match (self.method, self.tolerance) {
            (Method::Wilson, None) => Box::new(Wilson::default()),
            (Method::Wilson, Some(tolerance)) => Box::new(StepDoubling::new(control(tolerance, self.dt_max))),
            (Method::Central, _) => Box::new(CentralDifference::for_system(system)),
            (Method::Cycle, tolerance) => {
                Box::new(CycleSteps::new(control(tolerance.unwrap_or(CYCLE_DEFAULT_TOLERANCE), self.dt_max), system))
            }
            (Method::Tsit5, tolerance) => rate_form(
                Tableau::Tsit5,
                tolerance.unwrap_or(TSIT5_DEFAULT_TOLERANCE),
                self.dt_max.min(tsit5_bounded_step(system)),
            ),
            (Method::Sdirk4, tolerance) => {
                rate_form(Tableau::Sdirk4, tolerance.unwrap_or(SDIRK4_DEFAULT_TOLERANCE), self.dt_max)
            }
        }
    }
}

/// How fast Tsitouras' pair may amplify an undamped mode: by at most [`TSIT5_GROWTH`] in every
/// [`TSIT5_GROWTH_TIME`] seconds of simulated time, a growth rate of `ln 2 / 1000` per second.
/// A rate, not a growth over the run, so that no step depends on when the run ends: a run
/// extended past its end takes the steps a longer run takes.
pub const TSIT5_GROWTH: f64 = 2.0;

/// See [`TSIT5_GROWTH`] (s): the paper's simulated time.
pub const TSIT5_GROWTH_TIME: f64 = 1000.0;

/// The largest step of Tsitouras' pair that amplifies no undamped mode of `system` with its
/// contact stuck faster than [`TSIT5_GROWTH`] per [`TSIT5_GROWTH_TIME`]: `hω_max` from
/// [`bounded_growth`], `ω_max` the highest frequency. Every explicit fifth-order pair amplifies
/// undamped modes (`|R(iy)| > 1` above `y = 0.47798` for this one), and its error control alone
/// keeps `hω` of the stiffest mode near 1 to 2: a stuck contact's ringing then grows without
/// bound, from 1e-4 to 7 N/m rms in 100 s on the paper case (`tests/stuck_limit.rs`).
fn tsit5_bounded_step(system: &System) -> f64 {
    let omega = highest_frequency(&system.body, &system.contact);
    bounded_growth(omega * TSIT5_GROWTH_TIME, TSIT5_GROWTH) / omega
}
