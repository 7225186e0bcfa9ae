//! Newton's method with backtracking for one step's nonlinear system, shared by the full and the
//! condensed linear solvers ([`crate::dynamics::LinearSolver`]).

use crate::dynamics::error::StepError;
use crate::dynamics::settings::Settings;

/// One step's nonlinear system as Newton's method sees it: a residual at a trial, and the
/// correction that zeroes its linearization.
pub(crate) trait NewtonProblem {
    /// What an evaluation yields besides the residual (contact tangents, restarts).
    type Evaluation;

    /// The residual at `x`, and what [`Self::correct`] needs there. `previous` is the last
    /// accepted evaluation (`None` at the predictor).
    fn evaluate(
        &mut self,
        x: &[f64],
        previous: Option<&Self::Evaluation>,
    ) -> Result<(Vec<f64>, Self::Evaluation), StepError>;

    /// Turns `delta`, the negated residual on entry, into Newton's correction.
    fn correct(&mut self, evaluation: &Self::Evaluation, delta: &mut [f64]) -> Result<(), StepError>;
}

/// Where Newton's method stopped.
pub(crate) struct Converged<E> {
    /// The solution.
    pub(crate) x: Vec<f64>,
    /// The last evaluation.
    pub(crate) evaluation: E,
    /// The last correction, if it was taken without evaluating again: it was below tolerance,
    /// so its effect on the residual is of the order of its square.
    pub(crate) unevaluated: Option<Vec<f64>>,
}

/// Solves `problem` from the predictor `x`. Converged when a correction is below
/// `settings.tolerance` times the larger of `|x|` and `scale`; a correction that does not lower
/// the residual's norm is halved, down to 1/64, so that stick/slip switches cannot make it grow.
pub(crate) fn newton<P: NewtonProblem>(
    problem: &mut P,
    settings: &Settings,
    scale: f64,
    mut x: Vec<f64>,
) -> Result<Converged<P::Evaluation>, StepError> {
    let (mut residual, mut evaluation) = problem.evaluate(&x, None)?;
    let mut norm = l2(&residual);
    let mut last_correction = f64::INFINITY;
    for _ in 0..settings.max_iterations {
        let mut delta: Vec<f64> = residual.iter().map(|r| -r).collect();
        problem.correct(&evaluation, &mut delta)?;
        let correction = max_abs(&delta);
        if !correction.is_finite() {
            return Err(StepError::NonFinite);
        }
        if correction <= settings.tolerance * max_abs(&x).max(scale) {
            x.iter_mut().zip(&delta).for_each(|(u, d)| *u += d);
            return Ok(Converged { x, evaluation, unevaluated: Some(delta) });
        }
        let mut step_length = 1.0;
        let (trial, (trial_residual, trial_evaluation), trial_norm) = loop {
            let candidate: Vec<f64> = x.iter().zip(&delta).map(|(u, d)| u + step_length * d).collect();
            let candidate_evaluation = problem.evaluate(&candidate, Some(&evaluation))?;
            let candidate_norm = l2(&candidate_evaluation.0);
            if candidate_norm <= norm || step_length < 1.0 / 64.0 {
                break (candidate, candidate_evaluation, candidate_norm);
            }
            step_length *= 0.5;
        };
        last_correction = step_length * correction;
        x = trial;
        residual = trial_residual;
        evaluation = trial_evaluation;
        norm = trial_norm;
        if last_correction <= settings.tolerance * max_abs(&x).max(scale) {
            return Ok(Converged { x, evaluation, unevaluated: None });
        }
    }
    Err(StepError::NotConverged { iterations: settings.max_iterations, correction: last_correction })
}

pub(crate) fn l2(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

pub(crate) fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}
