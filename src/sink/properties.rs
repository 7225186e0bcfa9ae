//! The recording's properties: what a Rerun dataset's segment table shows as columns, one row
//! per recording, so that many runs can be told apart and selected by their parameters.
//!
//! * `case`: every value of the case file after the overrides, by its `--set` key
//!   (`friction.mu_s`; a dataset server's segment table shows it as `property:case:friction_mu_s`),
//!   numbers as floats.
//! * `run`: the slipfront version, the case's name, the overrides as given, the integrator and
//!   its tolerance or step, the simulated time, and the contact's segments.

use std::sync::Arc;

use rerun::AnyValues;
use rerun::RecordingStream;
use rerun::external::arrow::array::{ArrayRef, BooleanArray, Float64Array, Int64Array, StringArray};

use crate::record::schema::{RecordingPlan, RunInfo};

/// The property groups' names.
pub const CASE: &str = "case";
pub const RUN: &str = "run";

/// Logs both property groups (static).
pub fn log(rec: &RecordingStream, plan: &RecordingPlan, info: &RunInfo) -> rerun::RecordingStreamResult<()> {
    let mut case = AnyValues::default();
    for (key, value) in &plan.parameters {
        // A key is a non-empty dotted path (the case's own keys), which is a valid identifier.
        if let Ok(id) = rerun::ComponentIdentifier::try_new(key) {
            case = case.with_component_from_data(id, toml_array(value));
        }
    }
    if !plan.parameters.is_empty() {
        rec.send_property(CASE, &case)?;
    }
    let text = |s: &str| -> ArrayRef { Arc::new(StringArray::from(vec![s.to_string()])) };
    let number = |x: f64| -> ArrayRef { Arc::new(Float64Array::from(vec![x])) };
    let count = |n: usize| -> ArrayRef { Arc::new(Int64Array::from(vec![n as i64])) };
    let mut run = AnyValues::default()
        .with_component_from_data("slipfront_version", text(&info.slipfront_version))
        .with_component_from_data("case", text(&plan.case))
        .with_component_from_data("overrides", text(&plan.overrides.join(" ")))
        .with_component_from_data("integrator", text(plan.integrator.name()))
        .with_component_from_data("stepping", text(&plan.stepping()))
        .with_component_from_data("t_end", number(plan.t_end))
        .with_component_from_data("dt", number(plan.dt))
        .with_component_from_data("segments", count(info.segments))
        .with_component_from_data("recorded_segments", count(info.recorded_segments.len()));
    if let Some(tolerance) = plan.tolerance {
        run = run.with_component_from_data("tolerance", number(tolerance));
    }
    if let Some(accuracy) = plan.accuracy {
        run = run.with_component_from_data("accuracy", number(accuracy));
    }
    rec.send_property(RUN, &run)
}

/// One TOML value as a one-element Arrow array: every number as a float, so that a column has
/// one type across runs however a value was written (`--set time.t_end=500` is an integer in
/// TOML, `t_end = 500.0` a float).
fn toml_array(value: &toml::Value) -> ArrayRef {
    match value {
        toml::Value::Float(x) => Arc::new(Float64Array::from(vec![*x])),
        toml::Value::Integer(n) => Arc::new(Float64Array::from(vec![*n as f64])),
        toml::Value::Boolean(b) => Arc::new(BooleanArray::from(vec![*b])),
        toml::Value::String(s) => Arc::new(StringArray::from(vec![s.clone()])),
        other => Arc::new(StringArray::from(vec![other.to_string()])),
    }
}
