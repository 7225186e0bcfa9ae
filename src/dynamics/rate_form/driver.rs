//! The adaptive driver of the Runge–Kutta methods on the rate form ([`super`]): steps sized by
//! the embedded error estimate ([`StepControl`]), accepted states put back on the set the exact
//! flow never leaves ([`System::project`]), and every crossing of the slip-rate threshold
//! located so that a frame lies on each onset and end.

use crate::dynamics::control::{AdaptiveError, ErrorScaling, StepControl};
use crate::dynamics::error::StepError;
use crate::dynamics::integrator::{Integrator, Statistics};
use crate::dynamics::memory::{IntegratorMemory, mismatch};
use crate::dynamics::rate_form::memory::{Pair, RungeKutta};
use crate::dynamics::rate_form::sdirk4::{FOURTH_ORDER, Sdirk4};
use crate::dynamics::rate_form::trial::Trial;
use crate::dynamics::rate_form::tsit5::{FIFTH_ORDER, Tsit5, dense_weights};
use crate::dynamics::system::System;

/// The Runge–Kutta tableau that integrates the rate form.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tableau {
    /// Tsitouras' explicit 5(4) pair ([`super::tsit5`]).
    Tsit5,
    /// Hairer and Wanner's L-stable SDIRK 4(3) ([`super::sdirk4`]).
    Sdirk4,
}

/// What a located crossing watches: a point's plastic slip rate against the event threshold,
/// or an evolving point's normal traction against 0.
#[derive(Debug, Clone, Copy)]
enum Watch {
    Slip(usize),
    Normal(usize),
}

/// Root-finding steps allowed when locating a crossing.
const MAX_LOCATING_STEPS: usize = 60;

impl Pair {
    fn scaling(&self) -> ErrorScaling {
        match self {
            Pair::Tsit5(_) => FIFTH_ORDER,
            Pair::Sdirk4(_) => FOURTH_ORDER,
        }
    }
}

/// Where an accepted trial of Tsitouras' pair carries a point across eq. (9)'s switch
/// ([`RungeKutta::first_switch`]).
enum Switch {
    /// The point's branch already disagrees with eq. (9) where the step starts (a switch
    /// located a little early, then undone by the flow, or a state the projection moved): it
    /// is switched there, and the step taken again.
    Now(usize),
    /// The first switch, at the fraction `theta` of the step, of the point given.
    At(f64, usize),
}

/// A Runge–Kutta method on the rate form, with its step-size control and its memory.
pub struct RateForm {
    tableau: Tableau,
    control: StepControl,
    /// The slip-rate level (m/s) whose crossings are located.
    threshold: f64,
    memory: Option<RungeKutta>,
    statistics: Statistics,
}

impl RateForm {
    pub fn new(tableau: Tableau, control: StepControl, threshold: f64) -> Self {
        Self { tableau, control, threshold, memory: None, statistics: Statistics::default() }
    }
}

impl Integrator for RateForm {
    /// Takes one step of at most `limit` (s), its size chosen by the step-size control
    /// (`tolerance` is the error allowed per step), shortened to end just past the first
    /// instant where a contact point's plastic slip rate crosses the threshold. Returns the
    /// step taken.
    fn advance(&mut self, system: &mut System, limit: f64) -> Result<f64, AdaptiveError> {
        let mut rk = match self.memory.take() {
            Some(rk) if rk.at == (system.state.step, system.state.time) => rk,
            _ => RungeKutta::new(system, self.tableau),
        };
        let result = attempts(system, &mut rk, &mut self.control, &mut self.statistics, limit, self.threshold);
        if let Pair::Sdirk4(pair) = &mut rk.pair {
            self.statistics.newton_iterations += std::mem::take(&mut pair.iterations);
            self.statistics.factorizations += std::mem::take(&mut pair.linearizations);
        }
        self.memory = Some(rk);
        result
    }

    fn memory(&self) -> IntegratorMemory {
        IntegratorMemory::RateForm {
            control: self.control.clone(),
            memory: self.memory.clone().map(Box::new),
            statistics: self.statistics,
        }
    }

    /// Takes back the state vector, its rate (the first stage of the next step), the method's
    /// linearization, the counts and the next step; the step limits stay the case's.
    fn restore(&mut self, system: &System, memory: IntegratorMemory) -> Result<(), String> {
        let IntegratorMemory::RateForm { control, memory, statistics } = memory else {
            return Err(mismatch(format!("saved by {}, the case steps with a Runge–Kutta method", memory.name())));
        };
        if let Some(rk) = &memory {
            rk.fits(system, self.tableau)?;
        }
        self.control.resume_from(&control)?;
        self.memory = memory.map(|rk| *rk);
        self.statistics = statistics;
        Ok(())
    }

    fn longest_next_step(&self, limit: f64) -> f64 {
        self.control.next.min(limit)
    }

    fn statistics(&self) -> Statistics {
        self.statistics
    }
}

fn attempts(
    system: &mut System,
    rk: &mut RungeKutta,
    control: &mut StepControl,
    statistics: &mut Statistics,
    limit: f64,
    threshold: f64,
) -> Result<f64, AdaptiveError> {
    let t = system.state.time;
    let scaling = rk.pair.scaling();
    let tolerance = control.tolerance;
    let mut rejected = false;
    let mut trial = rk.spare();
    // Points switched where the step starts, each at most once per step (no ping-pong).
    let mut switched_now: Vec<usize> = Vec::new();
    loop {
        let mut h = control.next.min(limit);
        // A failed implicit solve counts as an infinite error: the step shrinks.
        let failure = rk.trial(system, t, h, tolerance, &mut trial).err();
        let error = if failure.is_none() { trial.error } else { f64::INFINITY };
        let mut switching = None;
        if error <= tolerance {
            // Eq. (9)'s first switch inside the step ends it there, on the trial's dense output.
            match rk.first_switch(system, t, h, &trial) {
                Some(Switch::Now(point)) if !switched_now.contains(&point) => {
                    statistics.rejected += 1;
                    switched_now.push(point);
                    rk.switch_branch(system, t, point);
                    continue;
                }
                Some(Switch::At(theta, point)) if theta * h > 0.0 && t + theta * h > t => {
                    control.next = control.resize(h, error, scaling);
                    rk.cut(system, (t, h, theta), point, &mut trial);
                    h *= theta;
                    switching = Some((point, control.next));
                }
                _ => {}
            }
        }
        if error <= tolerance {
            statistics.accepted += 1;
            control.next = match switching {
                // The step was cut at the switch, not by its error: the next one is the step
                // the error allowed.
                Some((_, next)) => next,
                None => control.resize(h, error, scaling),
            };
            if rejected {
                control.next = control.next.min(h);
            }
            let (located, trial) = match rk.crossing(system, t, h, &trial, threshold, tolerance) {
                Some((located, past)) => {
                    rk.give_back(trial);
                    (Some(located), past)
                }
                None => (None, trial),
            };
            // The switch is reached unless a threshold crossing ended the step before it.
            let switch = switching.filter(|_| located.is_none()).map(|(point, _)| point);
            let h = located.unwrap_or(h);
            accept(system, rk, t + h, trial, switch);
            return Ok(h);
        }
        statistics.rejected += 1;
        rejected = true;
        control.next = control.resize(h, error, scaling).min(0.5 * h);
        if control.next < control.dt_min {
            return Err(match (error.is_finite(), failure) {
                (true, _) => AdaptiveError::StepTooSmall { dt: control.next, dt_min: control.dt_min, error },
                (false, Some(failure)) => AdaptiveError::Step(failure),
                (false, None) => AdaptiveError::Step(StepError::NonFinite),
            });
        }
    }
}

/// Makes `trial`, reached at `time`, the state; the vectors it replaces become a spare. With
/// `switch`, that point's branch of eq. (6) changes there (the trial ended on its switch, and
/// its rate is already the new branch's: [`RungeKutta::cut`]).
fn accept(system: &mut System, rk: &mut RungeKutta, time: f64, mut trial: Trial, switch: Option<usize>) {
    if let Some(point) = switch {
        rk.branches[point] = !rk.branches[point];
    }
    if system.project(&mut trial.y) {
        rk.evaluate(system, time, &trial.y, &mut trial.rate, &mut trial.lambda, &mut trial.numerator);
    }
    let n = system.body.dofs();
    let m = system.contact.points.len();
    let s = &mut system.state;
    s.displacement.copy_from_slice(&trial.y[..n]);
    s.velocity.copy_from_slice(&trial.y[n..2 * n]);
    s.acceleration.copy_from_slice(&trial.rate[n..2 * n]);
    for (i, c) in s.contact.iter_mut().enumerate() {
        let slip = trial.y[2 * n + 2 * m + i];
        s.plastic_increment[i] = slip - c.plastic_slip;
        c.traction_t = trial.y[2 * n + i];
        c.structure = trial.y[2 * n + m + i];
        c.plastic_slip = slip;
        if system.contact.evolves(i) {
            c.traction_n = system.contact.normal_traction_at(i, &trial.y[..n]);
        }
    }
    s.plastic_rate.clone_from(&trial.lambda);
    s.time = time;
    s.step += 1;
    rk.at = (s.step, s.time);
    std::mem::swap(&mut rk.y, &mut trial.y);
    std::mem::swap(&mut rk.rate, &mut trial.rate);
    std::mem::swap(&mut rk.lambda, &mut trial.lambda);
    std::mem::swap(&mut rk.numerator, &mut trial.numerator);
    rk.give_back(trial);
}

impl RungeKutta {
    /// Reads the state of `dynamics` into one vector, for `method`.
    fn new(dynamics: &System, tableau: Tableau) -> Self {
        let s = &dynamics.state;
        let n = dynamics.body.dofs();
        let m = s.contact.len();
        let mut y = Vec::with_capacity(2 * n + 3 * m);
        y.extend_from_slice(&s.displacement);
        y.extend_from_slice(&s.velocity);
        y.extend(s.contact.iter().map(|c| c.traction_t));
        y.extend(s.contact.iter().map(|c| c.structure));
        y.extend(s.contact.iter().map(|c| c.plastic_slip));
        // Scales: the displacement that changes a point's traction by its static strength
        // (`δ = μ_s f_n / α_t`) for u and p; for v, the velocity whose kinetic energy in the
        // contact's spring mode (`ω² = α_t w / m`) equals that spring's energy at `δ`, `ω δ`,
        // or the drive's velocity if larger; the static strength for f_t; the range
        // `μ_s/μ_k - 1` for 1/R*. With several contacts, the largest of each.
        let contact = &dynamics.contact;
        let surfaces = || contact.surfaces.iter().map(|s| &s.params);
        let alpha_t = surfaces().map(|p| p.alpha_t).fold(0.0_f64, f64::max);
        let strength = (0..m).map(|k| contact.params(k).mu_s * contact.traction_n[k]).fold(0.0_f64, f64::max);
        let strength = if strength > 0.0 { strength } else { 1.0 };
        let length = strength / alpha_t;
        let omega = contact
            .points
            .iter()
            .flat_map(|p| p.tangential.terms().map(|(d, _)| (p.weight * alpha_t / dynamics.body.mass[d]).sqrt()))
            .fold(0.0_f64, f64::max);
        let structure_range = surfaces().map(|p| p.max_structure() - 1.0).fold(0.0_f64, f64::max);
        let mut scale = vec![length; n];
        scale.extend(std::iter::repeat_n(dynamics.settings.velocity_scale.max(omega * length), n));
        scale.extend(std::iter::repeat_n(strength, m));
        scale.extend(std::iter::repeat_n(structure_range.max(f64::MIN_POSITIVE), m));
        scale.extend(std::iter::repeat_n(length, m));
        let mut rate = vec![0.0; y.len()];
        let mut lambda = vec![0.0; m];
        let len = y.len();
        let (pair, mut branches) = match tableau {
            Tableau::Tsit5 => (Pair::Tsit5(Tsit5::new(len)), Vec::with_capacity(m)),
            Tableau::Sdirk4 => (Pair::Sdirk4(Box::new(Sdirk4::new(len, m))), Vec::new()),
        };
        if tableau == Tableau::Tsit5 {
            dynamics.branches(s.time, &y, &mut branches);
        }
        let mut numerator = vec![f64::NAN; branches.len()];
        let mut rk = Self {
            at: (s.step, s.time),
            y,
            rate: Vec::new(),
            lambda: Vec::new(),
            branches,
            numerator: Vec::new(),
            scale,
            pair,
            spares: Vec::new(),
        };
        rk.evaluate(dynamics, s.time, &rk.y.clone(), &mut rate, &mut lambda, &mut numerator);
        (rk.rate, rk.lambda, rk.numerator) = (rate, lambda, numerator);
        rk
    }

    /// The right-hand side at `y` and `t`: with each point held on its branch of eq. (6)
    /// where [`Self::branches`] are kept, else switched by eq. (9).
    fn evaluate(
        &self,
        dynamics: &System,
        t: f64,
        y: &[f64],
        rate: &mut [f64],
        lambda: &mut [f64],
        numerator: &mut Vec<f64>,
    ) {
        if self.branches.is_empty() {
            dynamics.rate_form(t, y, rate, lambda);
        } else {
            numerator.resize(self.branches.len(), f64::NAN);
            dynamics.rate_form_on_branches(t, y, rate, lambda, &self.branches, numerator);
        }
    }

    /// Switches `point` to the other branch of eq. (6) at the current state (time `t`), and
    /// evaluates the rate there again: the next step's first stage.
    fn switch_branch(&mut self, dynamics: &System, t: f64, point: usize) {
        self.branches[point] = !self.branches[point];
        let (mut rate, mut lambda, mut numerator) =
            (std::mem::take(&mut self.rate), std::mem::take(&mut self.lambda), std::mem::take(&mut self.numerator));
        self.evaluate(dynamics, t, &self.y, &mut rate, &mut lambda, &mut numerator);
        (self.rate, self.lambda, self.numerator) = (rate, lambda, numerator);
    }

    /// The first point whose switching function (eq. 9) an accepted `trial` of `h` from `t`
    /// carries to the side of the other branch: where, by Illinois' regula falsi on the
    /// switching function along the step's fourth-order dense output, and the fraction of the
    /// step just past it. `None` with no held branches (SDIRK4) or no switch.
    fn first_switch(&self, dynamics: &System, t: f64, h: f64, trial: &Trial) -> Option<Switch> {
        let Pair::Tsit5(pair) = &self.pair else { return None };
        let against = |loading: bool, g: f64| if loading { g < 0.0 } else { g > 0.0 };
        let mut first: Option<(f64, usize)> = None;
        for (i, &loading) in self.branches.iter().enumerate() {
            let (g0, g1) = (self.numerator[i], trial.numerator[i]);
            if !against(loading, g1) {
                continue;
            }
            if !g0.is_finite() || g0 == 0.0 || against(loading, g0) {
                return Some(Switch::Now(i));
            }
            let theta = self.locate_switch(dynamics, pair, t, h, i, (g0, g1));
            if first.is_none_or(|(earliest, _)| theta < earliest) {
                first = Some((theta, i));
            }
        }
        first.map(|(theta, i)| Switch::At(theta, i))
    }

    /// The fraction of the step of `h` from `t` just past point `i`'s switch, along the dense
    /// output of `pair`'s last step, its switching function being `ends` at the two ends.
    fn locate_switch(&self, dynamics: &System, pair: &Tsit5, t: f64, h: f64, i: usize, ends: (f64, f64)) -> f64 {
        let n = dynamics.body.dofs();
        let m = self.branches.len();
        let g = |theta: f64| {
            let weights = dense_weights(theta);
            let at = |j: usize| pair.dense_component(j, self.y[j], h, &weights);
            dynamics.switching_at(i, t + theta * h, |dof| at(n + dof), at(2 * n + i), at(2 * n + m + i))
        };
        let ((mut lo, mut g_lo), (mut hi, mut g_hi)) = ((0.0, ends.0), (1.0, ends.1));
        let mut kept = 0_i32;
        for _ in 0..MAX_LOCATING_STEPS {
            if hi - lo <= 1e-12 {
                break;
            }
            let mut s = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
            if !(s > lo && s < hi) {
                s = 0.5 * (lo + hi);
            }
            let value = g(s);
            if !value.is_finite() {
                break;
            }
            if (value > 0.0) == (g_lo > 0.0) && value != 0.0 {
                (lo, g_lo) = (s, value);
                if kept == -1 {
                    g_hi *= 0.5;
                }
                kept = -1;
            } else {
                (hi, g_hi) = (s, value);
                if kept == 1 {
                    g_lo *= 0.5;
                }
                kept = 1;
            }
        }
        hi
    }

    /// Ends Tsitouras' trial of `h` from `t` at the fraction `theta` of its step, just past
    /// `point`'s switch of eq. (9): `trial` becomes the step's dense output there, with its
    /// rate, `Λ` and switching functions on the branches that hold from there (`point`'s
    /// changed; [`accept`] changes it for good). No step is taken again.
    fn cut(&mut self, dynamics: &System, (t, h, theta): (f64, f64, f64), point: usize, trial: &mut Trial) {
        let Pair::Tsit5(pair) = &mut self.pair else { return };
        pair.dense_output(&self.y, h, theta, &mut trial.y);
        self.branches[point] = !self.branches[point];
        self.evaluate(dynamics, t + theta * h, &trial.y, &mut trial.rate, &mut trial.lambda, &mut trial.numerator);
        self.branches[point] = !self.branches[point];
    }

    /// A trial's buffers: one handed back earlier, or new ones.
    fn spare(&mut self) -> Trial {
        self.spares.pop().unwrap_or_default()
    }

    /// Keeps `trial`'s buffers for a later [`Self::spare`].
    fn give_back(&mut self, trial: Trial) {
        self.spares.push(trial);
    }

    /// Whether this memory, saved in a checkpoint, fits `dynamics` stepped by `tableau`.
    fn fits(&self, dynamics: &System, tableau: Tableau) -> Result<(), String> {
        let m = dynamics.contact.points.len();
        let len = 2 * dynamics.body.dofs() + 3 * m;
        let sized =
            [self.y.len(), self.rate.len(), self.scale.len()].iter().all(|&l| l == len) && self.lambda.len() == m;
        let held = |count: usize| self.branches.len() == count && self.numerator.len() == count;
        let pair = match (&self.pair, tableau) {
            (Pair::Tsit5(pair), Tableau::Tsit5) => pair.fits(len) && held(m),
            (Pair::Sdirk4(pair), Tableau::Sdirk4) => pair.fits(len, m) && held(0),
            _ => return Err(mismatch("saved by the other Runge–Kutta method")),
        };
        if sized && pair {
            Ok(())
        } else {
            Err(mismatch(format!("its state vector is not the {len} unknowns of this case's rate form")))
        }
    }

    /// One step of `h` from the current state at `t` into `out`; `tolerance` is the error
    /// allowed per step. Fails where an implicit method's solve does.
    fn trial(
        &mut self,
        dynamics: &mut System,
        t: f64,
        h: f64,
        tolerance: f64,
        out: &mut Trial,
    ) -> Result<(), StepError> {
        out.lambda.resize(self.lambda.len(), 0.0);
        out.numerator.resize(self.branches.len(), f64::NAN);
        let (error, y, rate) = match &mut self.pair {
            Pair::Tsit5(pair) => {
                let (lambda, numerator, branches) = (&mut out.lambda, &mut out.numerator, &self.branches);
                let error = pair.step(&self.y, &self.rate, t, h, &self.scale, |t, y, rate| {
                    dynamics.rate_form_on_branches(t, y, rate, lambda, branches, numerator)
                });
                (error, pair.solution(), pair.solution_rate())
            }
            Pair::Sdirk4(pair) => {
                let error = pair.step(dynamics, &self.y, &self.rate, t, h, &self.scale, tolerance)?;
                out.lambda.copy_from_slice(pair.solution_lambda());
                (error, pair.solution(), pair.solution_rate())
            }
        };
        out.error = error;
        out.y.clear();
        out.y.extend_from_slice(y);
        out.rate.clear();
        out.rate.extend_from_slice(rate);
        Ok(())
    }

    /// If the accepted `trial` of `h` from `t` carries some point's `Λ` across `level`, or an
    /// evolving point's normal traction through 0 (it opens or closes), the shortened step
    /// that ends just past the first such crossing, and its state.
    fn crossing(
        &mut self,
        dynamics: &mut System,
        t: f64,
        h: f64,
        trial: &Trial,
        level: f64,
        tolerance: f64,
    ) -> Option<(f64, Trial)> {
        let side = |lambda: f64| lambda > level;
        // The point whose crossing comes first by linear interpolation of Λ over the step.
        let slip = self
            .lambda
            .iter()
            .zip(&trial.lambda)
            .enumerate()
            .filter(|(_, (a, b))| side(**a) != side(**b))
            .map(|(i, (a, b))| (Watch::Slip(i), (level - a) / (b - a)));
        let n = dynamics.body.dofs();
        let normal = |dynamics: &System, y: &[f64], i: usize| dynamics.contact.normal_trial(i, &y[..n]);
        let contact = &dynamics.contact;
        let opening = (0..contact.points.len())
            .filter(|&i| contact.evolves(i))
            .map(|i| (i, normal(dynamics, &self.y, i), normal(dynamics, &trial.y, i)))
            .filter(|(_, a, b)| (*a > 0.0) != (*b > 0.0))
            .map(|(i, a, b)| (Watch::Normal(i), -a / (b - a)));
        let (watch, _) = slip.chain(opening).min_by(|x, y| x.1.total_cmp(&y.1))?;
        let value = |dynamics: &System, lambda: &[f64], y: &[f64]| match watch {
            Watch::Slip(point) => lambda[point] - level,
            Watch::Normal(point) => normal(dynamics, y, point),
        };
        let before = value(dynamics, &self.lambda, &self.y) > 0.0;
        // Illinois: regula falsi that halves the weight of an end kept twice in a row.
        let (mut lo, mut g_lo) = (0.0, value(dynamics, &self.lambda, &self.y));
        let (mut hi, mut g_hi) = (h, value(dynamics, &trial.lambda, &trial.y));
        let mut past: Option<Trial> = None;
        let mut attempt = self.spare();
        let mut kept = 0_i32;
        for _ in 0..MAX_LOCATING_STEPS {
            if hi - lo <= 4.0 * f64::EPSILON * (t + hi).abs() {
                break;
            }
            let mut s = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
            if !(s > lo && s < hi) {
                s = 0.5 * (lo + hi);
            }
            if self.trial(dynamics, t, s, tolerance, &mut attempt).is_err() {
                break;
            }
            let at = value(dynamics, &attempt.lambda, &attempt.y);
            if !at.is_finite() {
                break;
            }
            if (at > 0.0) == before {
                lo = s;
                g_lo = at;
                if kept == -1 {
                    g_hi *= 0.5;
                }
                kept = -1;
            } else {
                hi = s;
                g_hi = at;
                let spare = past.replace(attempt).unwrap_or_else(|| self.spare());
                attempt = spare;
                if kept == 1 {
                    g_lo *= 0.5;
                }
                kept = 1;
            }
        }
        self.give_back(attempt);
        past.map(|trial| (hi, trial))
    }
}
