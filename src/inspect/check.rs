//! `slipfront check`: does a recording hold what the schema promises, and what the user
//! expects of it?
//!
//! The recording describes itself ([`RunInfo`] at `slipfront/run`, [`RunEnding`] at
//! `slipfront/ending`), so the check needs no case file: every series it lists must exist with
//! the same rows, `sim_time` must rise with `step` from 0 to the end of the run, and no value
//! may be NaN or infinite. An expectations file adds value ranges at given times and event
//! counts.

use std::fmt::Write as _;
use std::path::Path;

use serde::Deserialize;

use crate::inspect::{END_TOLERANCE, Recording, Series};
use crate::record::digest::SeriesDigest;
use crate::record::schema::{self, RunEnding, RunInfo};
use crate::validate::shortest;

/// Optional expectations (`--expect EXPECT.toml`).
///
/// ```toml
/// [events]
/// slip_events = [4, 6]      # inclusive range
/// ruptures = [1, 10]
///
/// [[at]]
/// entity = "contact/friction_force"
/// time = 40.0               # s: the last recorded row at or before it (within the recording)
/// min = 199.0
/// max = 201.0
///
/// [[at]]
/// entity = "contact/structure"
/// segment = 3               # per-segment entities: which segment (node = j for body/u_x)
/// time = 300.0
/// min = 1.0
/// ```
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Expectations {
    #[serde(default)]
    pub events: EventExpectations,
    #[serde(default)]
    pub at: Vec<ValueExpectation>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EventExpectations {
    pub slip_events: Option<[usize; 2]>,
    pub ruptures: Option<[usize; 2]>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ValueExpectation {
    pub entity: String,
    /// The segment (of `contact/{quantity}`) or contact-surface node (of `body/u_x`, `body/u_y`)
    /// whose instance is meant, numbered from 0 at the left.
    pub segment: Option<usize>,
    pub node: Option<usize>,
    pub time: f64,
    pub min: Option<f64>,
    pub max: Option<f64>,
}

impl Expectations {
    /// Reads an expectations file; errors name the file and the key.
    pub fn load(path: &Path) -> Result<Self, String> {
        let text =
            crate::files::read_text_capped(path, MAX_EXPECT_BYTES, "an expectations file is a few lines of TOML")?;
        let expect: Self = toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        expect.validate().map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(expect)
    }

    /// Refuses what no recording could be judged by: a bound or time that is not a finite
    /// number (`min = nan` would pass everything), an empty range, and an `[[at]]` without a
    /// bound (it would pass whatever the value).
    fn validate(&self) -> Result<(), String> {
        for (i, at) in self.at.iter().enumerate() {
            if at.min.is_none() && at.max.is_none() {
                return Err(format!("at[{i}] gives neither min nor max: give at least one bound"));
            }
            for (key, value) in [("time", Some(at.time)), ("min", at.min), ("max", at.max)] {
                if let Some(v) = value
                    && !v.is_finite()
                {
                    return Err(format!("at[{i}].{key} = {v} must be a finite number"));
                }
            }
            if let (Some(min), Some(max)) = (at.min, at.max)
                && min > max
            {
                return Err(format!("at[{i}].min = {min} must not exceed at[{i}].max = {max}"));
            }
        }
        for (key, range) in [("slip_events", self.events.slip_events), ("ruptures", self.events.ruptures)] {
            if let Some([lo, hi]) = range
                && lo > hi
            {
                return Err(format!(
                    "events.{key} = [{lo}, {hi}] is empty: the first bound must not exceed the second"
                ));
            }
        }
        Ok(())
    }
}

/// The largest expectations file read (bytes).
pub const MAX_EXPECT_BYTES: u64 = 4 << 20;

/// Whether every `[[at]]` of `expect` names a series `recording` lists: an entity the
/// recording does not have, or a segment or node it does not record, is a mistake in the
/// expectations (invalid input), not a failure of the recording. `None` where the recording
/// has no readable run description (`check` reports that).
pub fn unknown_series(recording: &Recording, expect: &Expectations) -> Option<String> {
    let info: RunInfo = toml::from_str(recording.static_texts.get(schema::RUN_INFO)?).ok()?;
    for (i, at) in expect.at.iter().enumerate() {
        let name = match series_name(at, &info) {
            Ok(name) => name,
            Err(e) => return Some(format!("at[{i}]: {e}")),
        };
        if !info.series.contains(&name) && info.series.iter().any(|s| s.starts_with(&format!("{name}["))) {
            return Some(format!(
                "at[{i}].entity = \"{}\" has one series per recorded segment or node: give segment = k or node = j",
                at.entity
            ));
        }
        if !info.series.contains(&name) {
            let mut entities: Vec<&str> =
                info.series.iter().map(|s| s.split_once('[').map_or(s.as_str(), |(entity, _)| entity)).collect();
            entities.dedup();
            return Some(format!(
                "at[{i}].entity = \"{}\" is not a series of this recording; its entities are: {}",
                at.entity,
                entities.join(", ")
            ));
        }
    }
    None
}

/// The outcome of a check.
#[derive(Debug, Clone, Default)]
pub struct Report {
    /// What was found, one line each.
    pub summary: Vec<String>,
    /// What is wrong, one line each; empty means the recording passes.
    pub problems: Vec<String>,
}

impl Report {
    pub fn passed(&self) -> bool {
        self.problems.is_empty()
    }

    /// The report as printed by `slipfront check`.
    pub fn render(&self) -> String {
        let mut out = String::new();
        for line in &self.summary {
            let _ = writeln!(out, "{line}");
        }
        if self.passed() {
            let _ = writeln!(out, "PASS");
        } else {
            for line in &self.problems {
                let _ = writeln!(out, "FAIL: {line}");
            }
        }
        out
    }
}

/// Checks `recording` against its own description and `expect`.
pub fn check(recording: &Recording, expect: &Expectations) -> Report {
    judge(recording, expect, false)
}

/// As [`check`], for a file that may end early (a run killed, or stopped by a full disk, before
/// it wrote its ending or its footer): where the reading stopped is reported, not failed, and
/// what was read is judged; a file with its ending record in full, one without on everything
/// it holds (run description, time axis from 0 and rising, one row per
/// step, the same steps in every series, finite values, blueprint), and what only the end of a
/// run writes (the ending record, the last time, the space-time map) is not asked for. The
/// summary says how far it reaches.
pub fn check_partial(recording: &Recording, expect: &Expectations) -> Report {
    judge(recording, expect, true)
}

/// Whether a file is judged as one that may end before its run's ending record.
pub fn ends_early(recording: &Recording, partial: bool) -> bool {
    partial && !recording.static_texts.contains_key(schema::RUN_ENDING)
}

fn judge(recording: &Recording, expect: &Expectations, partial: bool) -> Report {
    let mut report = Report::default();
    let early = ends_early(recording, partial);
    if let Some(problem) = &recording.problem {
        if partial {
            report.summary.push(format!("the file ends early: {problem}"));
        } else {
            report.problems.push(format!("the file is damaged: {problem}"));
        }
    }
    let Some((info, ending)) = describe(recording, &mut report, early) else { return report };
    let reference = check_series(recording, &info, early, &mut report);
    match reference {
        Some((path, series)) => check_time_axis(path, series, &info, ending.as_ref(), early, &mut report),
        // A file that may end early and ends before its first rows (the run stopped, or its
        // disk filled, before the first hand-over) is valid as far as it goes.
        None if early => report.summary.push("the file ends before the first rows of any series".into()),
        None if !info.series.is_empty() => report.problems.push("none of the listed series is present".into()),
        None => {}
    }
    check_spatial(recording, &info, early, &mut report);
    if let Some(e) = &ending {
        check_digests(recording, e, &mut report);
        check_events(recording, &info, e, expect, &mut report);
    }
    check_blueprint(recording, &mut report);
    check_expectations(recording, &info, expect, &mut report);
    report
}

/// The run description and ending record, summarized; `None` (with the problem) where the
/// description is missing or unreadable.
fn describe(recording: &Recording, report: &mut Report, early: bool) -> Option<(RunInfo, Option<RunEnding>)> {
    let Some(info_text) = recording.static_texts.get(schema::RUN_INFO) else {
        report.problems.push(format!(
            "no run description at {}: not a slipfront recording, or cut off at its start",
            schema::RUN_INFO
        ));
        return None;
    };
    let info: RunInfo = match toml::from_str(info_text) {
        Ok(info) => info,
        Err(e) => {
            report.problems.push(format!("the run description at {} is unreadable: {e}", schema::RUN_INFO));
            return None;
        }
    };
    if info.series_layout != schema::SERIES_LAYOUT {
        report.problems.push(format!(
            "this recording lays its series out as \"{}\" (written by slipfront {}); this slipfront reads \"{}\" \
             (one entity per quantity, one instance per segment or node): run the case again, or check the \
             file with the slipfront that wrote it",
            info.series_layout,
            info.slipfront_version,
            schema::SERIES_LAYOUT
        ));
        return None;
    }
    let ending: Option<RunEnding> = recording.static_texts.get(schema::RUN_ENDING).and_then(|t| toml::from_str(t).ok());
    report.summary.push(format!(
        "{} ({} scene, {} segments), t_end = {} s {}",
        info.case,
        info.kind,
        info.segments,
        info.t_end,
        info.stepping()
    ));
    if info.axisymmetric {
        report.summary.push(format!(
            "axisymmetric: x is the radius, y the axis; {} is the total around the circumference, in {}",
            schema::FRICTION_FORCE,
            info.force_unit()
        ));
    }
    match &ending {
        None if early => report.summary.push(format!(
            "no ending record at {}: the run did not finish writing this file; judged up to its last row (--partial)",
            schema::RUN_ENDING
        )),
        None => report.problems.push(format!(
            "no ending record at {}: the recording stops before the run finished writing it (truncated? \
             `check --partial` judges what it holds)",
            schema::RUN_ENDING
        )),
        Some(e) => report.summary.push(format!(
            "run {}: {} rows per series up to t = {} s; {} slip events, {} ruptures",
            e.ending, e.rows, e.last_time, e.slip_events, e.ruptures
        )),
    }
    Some((info, ending))
}

/// Every listed series present, with the same rows and finite values; returns the first
/// present one, the reference for the time axis. In a file that ends early ([`check_partial`])
/// the series need not all reach its end, since each is its own entity and a cut can fall
/// between them: the reference is the longest, every other must hold its first rows exactly,
/// and the summary says how far all of them reach.
fn check_series<'r>(
    recording: &'r Recording,
    info: &'r RunInfo,
    early: bool,
    report: &mut Report,
) -> Option<(&'r str, &'r Series)> {
    let present: Vec<(&str, &Series)> =
        info.series.iter().filter_map(|path| recording.series.get(path).map(|s| (path.as_str(), s))).collect();
    let reference =
        if early { present.iter().copied().max_by_key(|(_, s)| s.steps.len()) } else { present.first().copied() };
    let missing = info.series.iter().filter(|path| !recording.series.contains_key(*path));
    if early {
        let missing = missing.count();
        if missing > 0 {
            report.summary.push(format!("{missing} series hold no rows: the file ends before their first rows"));
        }
    } else {
        report.problems.extend(missing.map(|path| format!("missing series {path}")));
    }
    if let Some((first, s)) = reference {
        for (path, series) in present.iter().filter(|(path, _)| *path != first) {
            let same = if early { s.steps.starts_with(&series.steps) } else { s.steps == series.steps };
            if !same {
                report.problems.push(format!(
                    "{path} has {} rows at other steps than {first} ({} rows)",
                    series.steps.len(),
                    s.steps.len()
                ));
            }
        }
        if early && let Some((path, shortest)) = present.iter().min_by_key(|(_, s)| s.steps.len()) {
            let reach = shortest.times.last().map_or("no row".into(), |t| format!("t = {t} s"));
            report
                .summary
                .push(format!("every series present reaches {reach} ({path}, {} rows)", shortest.steps.len()));
        }
    }
    let non_finite: Vec<String> = present
        .iter()
        .filter_map(|(path, series)| {
            let i = series.values.iter().position(|v| !v.is_finite())?;
            Some(format!("{path} = {} at step {} (t = {} s)", series.values[i], series.steps[i], series.times[i]))
        })
        .collect();
    report.problems.extend(non_finite.iter().take(5).cloned());
    if non_finite.len() > 5 {
        report.problems.push(format!("{} more series hold NaN or infinite values", non_finite.len() - 5));
    }
    reference
}

/// Every series' rows against the digest written with them ([`SeriesDigest`]): a value, step
/// or time changed inside a recording that still decodes is damage, not data.
fn check_digests(recording: &Recording, ending: &RunEnding, report: &mut Report) {
    let changed: Vec<&String> = ending
        .digests
        .iter()
        .filter(|(path, digest)| {
            recording.series.get(*path).is_some_and(|s| !SeriesDigest::matches(&s.steps, &s.times, &s.values, digest))
        })
        .map(|(path, _)| path)
        .collect();
    if let Some(first) = changed.first() {
        report.problems.push(format!(
            "the rows of {first}{} differ from the digest written with them: the recording is damaged",
            if changed.len() > 1 { format!(" and {} more series", changed.len() - 1) } else { String::new() }
        ));
    }
}

/// `sim_time` rising with the step from 0 to the run's end, one row per step, as many rows as
/// the run reports.
fn check_time_axis(
    path: &str,
    series: &Series,
    info: &RunInfo,
    ending: Option<&RunEnding>,
    early: bool,
    report: &mut Report,
) {
    let problems = &mut report.problems;
    let rows = series.steps.len();
    report.summary.push(format!("{} series x {rows} rows", info.series.len()));
    if let Some(i) = series.times.windows(2).position(|w| w[1] < w[0]) {
        problems.push(format!(
            "sim_time decreases in {path} at step {}: {} s then {} s",
            series.steps[i + 1],
            series.times[i],
            series.times[i + 1]
        ));
    }
    if series.steps.windows(2).any(|w| w[1] == w[0]) {
        problems.push(format!("{path} has two rows at the same step"));
    }
    let first = series.times.first().copied().unwrap_or(f64::NAN);
    let last = series.times.last().copied().unwrap_or(f64::NAN);
    if first != 0.0 {
        problems.push(format!("sim_time starts at {first} s, not at 0"));
    }
    let expected_end = match ending {
        Some(e) if e.ending != "completed" => e.last_time,
        _ => info.t_end,
    };
    if early {
        let step = series.steps.last().copied().unwrap_or_default();
        report.summary.push(format!("readable up to t = {last} s (step {step}) of the run's {} s", info.t_end));
    } else if (last - expected_end).abs() > END_TOLERANCE * expected_end.max(1.0) {
        problems.push(format!("sim_time ends at {last} s, the run at {expected_end} s"));
    }
    if let Some(e) = ending
        && e.rows as usize != rows
    {
        problems.push(format!("{rows} rows recorded, the run reports {}", e.rows));
    }
    report.summary.push(format!("sim_time from {first} s to {last} s"));
}

/// The spatial views' entities, where the run recorded them; the space-time map, drawn when
/// the run ends, only in a file that reached its end.
fn check_spatial(recording: &Recording, info: &RunInfo, early: bool, report: &mut Report) {
    if info.spatial {
        let mut entities: Vec<String> =
            [schema::SPATIAL_CONTACT, schema::SPATIAL_MESH].into_iter().map(String::from).collect();
        if !early {
            entities.extend([schema::SPACETIME_IMAGE, schema::SPACETIME_NOW].map(String::from));
        }
        entities.push(schema::CONTACT_STATE.into());
        entities.extend(info.traction_profiles());
        for entity in entities {
            if !recording.entities.contains(entity.as_str()) {
                report.problems.push(format!("missing entity {entity} of the spatial views"));
            }
        }
    }
}

/// The stored blueprint's views.
fn check_blueprint(recording: &Recording, report: &mut Report) {
    if recording.views.is_empty() {
        report.problems.push("no blueprint views stored".into());
    } else {
        report.summary.push(format!(
            "blueprint: {}",
            recording.views.iter().map(|v| format!("{} \"{}\"", v.class, v.name)).collect::<Vec<_>>().join(", ")
        ));
    }
}

/// The event log against the catalog's counts, and the expected counts.
fn check_events(recording: &Recording, info: &RunInfo, e: &RunEnding, expect: &Expectations, report: &mut Report) {
    let problems = &mut report.problems;
    let logged = recording.text_logs.iter().filter(|(entity, _, _)| entity == schema::EVENTS).count();
    let expected = e.slip_events + if info.kind.has_body() { e.ruptures } else { 0 };
    if logged != expected {
        problems.push(format!("{logged} entries in the event log, the catalog holds {expected}"));
    }
    if let Some([lo, hi]) = expect.events.slip_events
        && !(lo..=hi).contains(&e.slip_events)
    {
        problems.push(format!("{} slip events, expected {lo} to {hi}", e.slip_events));
    }
    if let Some([lo, hi]) = expect.events.ruptures
        && !(lo..=hi).contains(&e.ruptures)
    {
        problems.push(format!("{} ruptures, expected {lo} to {hi}", e.ruptures));
    }
}

/// Each `[[at]]` expectation: the series' last row at or before its time, within its range; a
/// time outside the recording fails.
fn check_expectations(recording: &Recording, info: &RunInfo, expect: &Expectations, report: &mut Report) {
    for (i, at) in expect.at.iter().enumerate() {
        let name = match series_name(at, info) {
            Ok(name) => name,
            Err(e) => {
                report.problems.push(format!("at[{i}]: {e}"));
                continue;
            }
        };
        let Some(series) = recording.series.get(&name) else {
            report.problems.push(format!("at[{i}]: no series {name}"));
            continue;
        };
        match series.at(at.time) {
            None => report.problems.push(outside(i, at.time, &name, series)),
            Some((t, v)) => {
                let low = at.min.is_some_and(|m| v < m);
                let high = at.max.is_some_and(|m| v > m);
                let range =
                    format!("[{}, {}]", at.min.map_or("-inf".into(), shortest), at.max.map_or("inf".into(), shortest));
                let fails = low || high || !v.is_finite();
                let (v, t) = (shortest(v), shortest(t));
                if fails {
                    report.problems.push(format!("at[{i}]: {name} = {v} at t = {t} s, expected in {range}"));
                } else {
                    report.summary.push(format!("{name} = {v} at t = {t} s, in {range}"));
                }
            }
        }
    }
}

/// Why `[[at]]` number `i` cannot be judged: its time lies outside the rows of `series`
/// (`name`), which are said, rather than a value the run never reached taken from its last row.
fn outside(i: usize, time: f64, name: &str, series: &Series) -> String {
    let (Some(&first), Some(&last)) = (series.times.first(), series.times.last()) else {
        return format!("at[{i}]: {name} holds no rows");
    };
    let side = if time < first { "before the first row" } else { "after the last row" };
    format!(
        "at[{i}].time = {} s is {side} of the recording: {name} spans t = {} to {} s",
        shortest(time),
        shortest(first),
        shortest(last)
    )
}

/// The series an expectation names: its entity, and for a per-segment or per-node entity the
/// instance of its `segment` or `node` among the recorded ones.
fn series_name(at: &ValueExpectation, info: &RunInfo) -> Result<String, String> {
    let entity = at.entity.trim_start_matches('/');
    let (key, index, recorded) = match (at.segment, at.node) {
        (None, None) => return Ok(entity.to_string()),
        (Some(_), Some(_)) => return Err("give segment or node, not both".into()),
        (Some(k), None) => ("segment", k, &info.recorded_segments),
        (None, Some(j)) => ("node", j, &info.recorded_nodes),
    };
    let position = recorded.iter().position(|&r| r == index).ok_or_else(|| {
        format!("{key} = {index} is not recorded (the recorded {key}s are {recorded:?}); see [record] in the case")
    })?;
    Ok(schema::instance_series(entity, position))
}
