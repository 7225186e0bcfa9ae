//! A recording's time series as a tidy table (`slipfront export`): a column per series, named
//! with its unit, a row per recorded step, within a time window and thinned to a least spacing.
//!
//! Column names are identifiers in pandas, polars and R: the quantity, its unit, and for a
//! per-segment or per-node series the segment or node number (`traction_t_Pa_seg3`,
//! `u_x_m_node5`, `friction_force_N_per_m`). `R`, `R_star` and `structure` (`1/R*`) are
//! dimensionless and carry no unit.

use std::collections::BTreeMap;

use crate::frame::{Quantity, SceneKind};
use crate::inspect::Recording;
use crate::record::schema::{self, RunInfo};
use crate::record::table::{Column, Table};
use crate::validate::shortest;

/// Which rows and columns to export.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Selection {
    /// Entity paths (`contact/traction_t`), series (`contact/traction_t[3]`) or column names
    /// (`traction_t_Pa_seg3`); every series when empty.
    pub series: Vec<String>,
    /// The time window (s), both ends included.
    pub from: Option<f64>,
    pub to: Option<f64>,
    /// The least simulated time (s) between two rows: a row is kept when it is at least this
    /// long after the last row kept.
    pub every: Option<f64>,
}

/// One series of a recording, as exported: the reader's name (`contact/traction_t[3]`), its
/// entity path and its column name.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportedSeries {
    pub series: String,
    pub entity: String,
    pub column: String,
}

/// The run description a recording carries ([`schema::RUN_INFO`]).
pub fn run_info(recording: &Recording) -> Result<RunInfo, String> {
    let text = recording.static_texts.get(schema::RUN_INFO).ok_or_else(|| {
        format!("the recording has no run description ({}): not a slipfront recording", schema::RUN_INFO)
    })?;
    toml::from_str(text).map_err(|e| format!("the run description at {} is unreadable: {e}", schema::RUN_INFO))
}

/// Every series the recording holds, in the order the run description lists them.
pub fn available(recording: &Recording, info: &RunInfo) -> Vec<ExportedSeries> {
    info.series
        .iter()
        .filter(|name| recording.series.contains_key(*name))
        .map(|name| {
            let (entity, instance) = split(name);
            ExportedSeries {
                series: name.clone(),
                entity: entity.to_string(),
                column: column_name(entity, instance, info),
            }
        })
        .collect()
}

/// The table of `selection` from `recording`. Errors name what was asked and what is there.
pub fn table(recording: &Recording, selection: &Selection) -> Result<Table, String> {
    check_window(selection)?;
    let info = run_info(recording)?;
    let chosen = choose(available(recording, &info), &selection.series)?;
    let mut rows: BTreeMap<i64, f64> = BTreeMap::new();
    for exported in &chosen {
        let series = &recording.series[&exported.series];
        rows.extend(series.steps.iter().copied().zip(series.times.iter().copied()));
    }
    let inside = |t: f64| selection.from.is_none_or(|from| t >= from) && selection.to.is_none_or(|to| t <= to);
    let mut kept: Vec<(i64, f64)> = Vec::new();
    for (step, time) in rows.into_iter().filter(|&(_, t)| inside(t)) {
        let spaced = match (selection.every, kept.last()) {
            (Some(every), Some(&(_, last))) => time - last >= every * (1.0 - 1e-9),
            _ => true,
        };
        if spaced {
            kept.push((step, time));
        }
    }
    let columns = chosen
        .iter()
        .map(|exported| {
            let series = &recording.series[&exported.series];
            let by_step: BTreeMap<i64, f64> = series.steps.iter().copied().zip(series.values.iter().copied()).collect();
            Column {
                name: exported.column.clone(),
                values: kept.iter().map(|(step, _)| by_step.get(step).copied()).collect(),
            }
        })
        .collect();
    Ok(Table { steps: kept.iter().map(|r| r.0).collect(), times: kept.iter().map(|r| r.1).collect(), columns })
}

/// The window and spacing asked for, checked: finite, `from <= to`, a positive spacing.
pub fn check_window(selection: &Selection) -> Result<(), String> {
    for (key, value) in [("--from", selection.from), ("--to", selection.to)] {
        if let Some(v) = value.filter(|v| !v.is_finite()) {
            return Err(format!("{key} = {} must be a finite time in seconds", shortest(v)));
        }
    }
    if let (Some(from), Some(to)) = (selection.from, selection.to)
        && from > to
    {
        return Err(format!("--from = {} must not be after --to = {}", shortest(from), shortest(to)));
    }
    if let Some(every) = selection.every.filter(|e| !(e.is_finite() && *e > 0.0)) {
        return Err(format!("--every = {} must be a positive time in seconds", shortest(every)));
    }
    Ok(())
}

/// The series `asked` names, in the recording's order; all of them if nothing is asked.
fn choose(all: Vec<ExportedSeries>, asked: &[String]) -> Result<Vec<ExportedSeries>, String> {
    if asked.is_empty() {
        return Ok(all);
    }
    let matches = |e: &ExportedSeries, name: &str| e.entity == name || e.series == name || e.column == name;
    if let Some(unknown) = asked.iter().find(|name| !all.iter().any(|e| matches(e, name))) {
        let mut entities: Vec<&str> = all.iter().map(|e| e.entity.as_str()).collect();
        entities.dedup();
        return Err(format!(
            "--series = {unknown} is not in the recording: give an entity ({}), one of its series \
             (contact/traction_t[0]) or a column name (slipfront export --list shows them)",
            entities.join(", ")
        ));
    }
    Ok(all.into_iter().filter(|e| asked.iter().any(|name| matches(e, name))).collect())
}

/// `contact/traction_t[3]` → (`contact/traction_t`, Some(3)); a total has no instance.
fn split(series: &str) -> (&str, Option<usize>) {
    match series.strip_suffix(']').and_then(|s| s.rsplit_once('[')) {
        Some((entity, index)) => (entity, index.parse().ok()),
        None => (series, None),
    }
}

/// The column of instance `instance` of `entity`: quantity, unit, segment or node number.
fn column_name(entity: &str, instance: Option<usize>, info: &RunInfo) -> String {
    let unit = unit_of(entity, info.kind, info.axisymmetric).map(|u| format!("_{u}")).unwrap_or_default();
    let quantity = match entity {
        schema::FRICTION_FORCE => "friction_force",
        schema::BASE_UX => "base_u_x",
        schema::BLOCK_X => "block_x",
        schema::BLOCK_V => "block_v",
        other => other.rsplit('/').next().unwrap_or(other),
    };
    let place = match instance {
        None => String::new(),
        Some(i) if entity.starts_with("body/") => format!("_node{}", info.recorded_nodes.get(i).copied().unwrap_or(i)),
        Some(i) => format!("_seg{}", info.recorded_segments.get(i).copied().unwrap_or(i)),
    };
    format!("{quantity}{unit}{place}")
}

/// The unit of an entity's values as it goes in a column name (`N_per_m`, `m_per_s`), `None`
/// for a dimensionless one.
fn unit_of(entity: &str, kind: SceneKind, ring: bool) -> Option<&'static str> {
    let quantity = Quantity::ALL.iter().find(|q| schema::segment_entity(**q) == entity);
    if let Some(quantity) = quantity {
        return match quantity {
            Quantity::TractionT | Quantity::TractionN => Some("Pa"),
            Quantity::R | Quantity::RStar | Quantity::Structure => None,
            Quantity::SlipRate => Some("m_per_s"),
            Quantity::Slip => Some("m"),
        };
    }
    match entity {
        schema::FRICTION_FORCE if ring => Some("N"),
        schema::FRICTION_FORCE if kind.has_body() => Some("N_per_m"),
        schema::FRICTION_FORCE => Some("Pa"),
        schema::BLOCK_V => Some("m_per_s"),
        _ => Some("m"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_series_splits_into_entity_and_instance() {
        assert_eq!(split("contact/traction_t[3]"), ("contact/traction_t", Some(3)));
        assert_eq!(split("contact/friction_force"), ("contact/friction_force", None));
    }

    #[test]
    fn units_follow_the_schema() {
        assert_eq!(unit_of("contact/friction_force", SceneKind::Block, false), Some("N_per_m"));
        assert_eq!(unit_of("contact/friction_force", SceneKind::SpringBlock, false), Some("Pa"));
        assert_eq!(unit_of("contact/structure", SceneKind::Block, false), None);
        assert_eq!(unit_of("contact/slip_rate", SceneKind::Block, false), Some("m_per_s"));
        assert_eq!(unit_of("body/u_y", SceneKind::Block, false), Some("m"));
        assert_eq!(unit_of("block/v", SceneKind::SpringBlock, false), Some("m_per_s"));
        assert_eq!(unit_of("contact/friction_force", SceneKind::Mesh, true), Some("N"));
    }

    #[test]
    fn a_window_backwards_or_a_spacing_not_positive_is_refused() {
        let bad = |s: Selection| check_window(&s).unwrap_err();
        assert_eq!(
            bad(Selection { from: Some(5.0), to: Some(1.0), ..Default::default() }),
            "--from = 5 must not be after --to = 1"
        );
        assert_eq!(
            bad(Selection { every: Some(0.0), ..Default::default() }),
            "--every = 0 must be a positive time in seconds"
        );
        assert_eq!(
            bad(Selection { to: Some(f64::NAN), ..Default::default() }),
            "--to = NaN must be a finite time in seconds"
        );
    }
}
