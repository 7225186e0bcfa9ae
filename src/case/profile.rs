//! A value that varies along a contact (its normal traction): uniform, linear, or piecewise
//! linear through a table, in the contact's arc length or in x or y.

use serde::Deserialize;

use crate::fem::curve::CurvePoint;
use crate::validate::Checker;

/// The coordinate a profile varies in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Along {
    /// Arc length from the contact's first node (m; counter-clockwise around the body).
    Arc,
    X,
    Y,
}

impl Along {
    /// The coordinate of `point`.
    pub fn of(self, point: CurvePoint) -> f64 {
        match self {
            Along::Arc => point.arc,
            Along::X => point.x,
            Along::Y => point.y,
        }
    }
}

/// `normal_traction` of a mesh contact.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ProfileSpec {
    /// The same everywhere.
    Uniform { value: f64 },
    /// The straight line through `(at[0], value[0])` and `(at[1], value[1])`.
    Linear { along: Along, at: [f64; 2], value: [f64; 2] },
    /// Piecewise linear through `(at[i], value[i])`, `at` increasing and covering the contact.
    Table { along: Along, at: Vec<f64>, value: Vec<f64> },
}

impl ProfileSpec {
    /// The value at `point`.
    pub fn at(&self, point: CurvePoint) -> f64 {
        match self {
            ProfileSpec::Uniform { value } => *value,
            ProfileSpec::Linear { along, at, value } => linear(along.of(point), *at, *value),
            ProfileSpec::Table { along, at, value } => table(along.of(point), at, value),
        }
    }

    /// Checks the form's own rules; values at the contact's points are checked where the mesh
    /// is known.
    pub fn check(&self, c: &mut Checker<'_>) {
        match self {
            ProfileSpec::Uniform { value } => c.non_negative("value", *value),
            ProfileSpec::Linear { at, value, .. } => {
                for i in 0..2 {
                    c.finite(&format!("at[{i}]"), at[i]);
                    c.finite(&format!("value[{i}]"), value[i]);
                }
                if at[0] == at[1] {
                    c.fail("at", format!("{at:?}"), "must name two different positions");
                }
            }
            ProfileSpec::Table { at, value, .. } => {
                if at.len() < 2 || at.len() != value.len() {
                    let rule = format!("must have at least 2 entries, as many as {} ({})", c.key("value"), value.len());
                    c.fail("at", format!("{at:?}"), rule);
                    return;
                }
                for (i, v) in value.iter().enumerate() {
                    c.non_negative(&format!("value[{i}]"), *v);
                }
                if !at.iter().all(|v| v.is_finite()) || !at.windows(2).all(|w| w[1] > w[0]) {
                    c.fail("at", format!("{at:?}"), "must be finite and strictly increasing");
                }
            }
        }
    }

    /// The range of coordinates a table covers; `None` for the other forms.
    pub fn covers(&self) -> Option<(Along, f64, f64)> {
        match self {
            ProfileSpec::Table { along, at, .. } => Some((*along, at[0], at[at.len() - 1])),
            _ => None,
        }
    }
}

/// The straight line through `(at[0], value[0])` and `(at[1], value[1])` at `s`:
/// `v₀ + (v₁ - v₀) ((s - a₀)/(a₁ - a₀))`.
pub fn linear(s: f64, at: [f64; 2], value: [f64; 2]) -> f64 {
    value[0] + (value[1] - value[0]) * ((s - at[0]) / (at[1] - at[0]))
}

/// Piecewise linear through `(at[i], value[i])` at `s` (`at` increasing; the end pieces
/// extended beyond the table).
pub fn table(s: f64, at: &[f64], value: &[f64]) -> f64 {
    let k = at.partition_point(|&a| a <= s).clamp(1, at.len() - 1);
    let (a0, a1, v0, v1) = (at[k - 1], at[k], value[k - 1], value[k]);
    v0 + (v1 - v0) * (s - a0) / (a1 - a0)
}
