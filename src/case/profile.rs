//! A value that varies along a contact (its normal traction): uniform, linear, or piecewise
//! linear through a table, in the contact's arc length or in x or y; or lithostatic,
//! `K γ depth` below a level.

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
    /// Lithostatic: `K γ (level - y)` below `level`, 0 above it (y upward).
    Lithostatic {
        /// The height `y` of the free surface depth is measured from (m); required.
        level: Option<f64>,
        /// The unit weight `γ` of what lies above (N/m³).
        unit_weight: f64,
        /// `K`: 1 under a horizontal surface, `K0` (the earth pressure at rest) on a vertical
        /// shaft; default 1.
        #[serde(default = "one")]
        coefficient: f64,
    },
}

fn one() -> f64 {
    1.0
}

impl ProfileSpec {
    /// The value at `point`.
    pub fn at(&self, point: CurvePoint) -> f64 {
        match self {
            ProfileSpec::Uniform { value } => *value,
            ProfileSpec::Linear { along, at, value } => linear(along.of(point), *at, *value),
            ProfileSpec::Table { along, at, value } => table(along.of(point), at, value),
            ProfileSpec::Lithostatic { level, unit_weight, coefficient } => {
                lithostatic(point.y, level.unwrap_or(f64::NAN), *unit_weight, *coefficient)
            }
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
            ProfileSpec::Lithostatic { level, unit_weight, coefficient } => {
                match level {
                    Some(level) => {
                        c.finite("level", *level);
                    }
                    None => c.fail(
                        "level",
                        "none",
                        "is needed: the height y (m) of the surface that depth is measured down from (f_n = \
                         coefficient × unit_weight × (level - y) below it, 0 above)",
                    ),
                }
                c.non_negative("unit_weight", *unit_weight);
                if c.finite("coefficient", *coefficient) && *coefficient < 0.0 {
                    c.fail(
                        "coefficient",
                        *coefficient,
                        "must not be negative: K is 1 under a horizontal surface and K0 (about 0.4 to 0.6 in \
                         sand) on a vertical shaft",
                    );
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

/// The lithostatic stress `K γ (level - y)` at height `y` below `level`, 0 above it.
pub fn lithostatic(y: f64, level: f64, unit_weight: f64, coefficient: f64) -> f64 {
    coefficient * unit_weight * (level - y).max(0.0)
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
