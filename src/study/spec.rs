//! A study file: a base case and how its members differ.
//!
//! ```toml
//! case = "../paper_triangular.toml"      # the base case, relative to this file
//! [set]                                   # overrides for every member, keys as in --set
//! "time.t_end" = 500.0
//! [ensemble]                              # optional: member k moves `key` by k × step
//! key = "friction.structure0"
//! step = -1.0e-9
//! members = 8
//! [sweep]                                 # optional: the product of these lists
//! "scene.normal_traction.left" = [300.0, 350.0]
//! [[rows]]                                # optional: rows given one by one (same keys in each)
//! "scene.normal_traction.right" = 1200.0
//! recordings = true                       # optional: false writes the catalogs only
//! [stop]                                  # optional: end a member early
//! after_whole_rupture = true              # once a rupture has covered the whole surface
//! quiet_for = 200.0                       # or once nothing has slipped for 200 s
//! ```
//!
//! Members are numbered row by row: row `r` (each of the `[[rows]]`, or one empty row, combined
//! with the product of the sweep lists, keys in alphabetical order, the last key varying
//! fastest), ensemble member `k` within it, index `r × members + k`. Every member is built and
//! validated before any runs.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::case::{self, Case};
use crate::study::stop::StopSpec;
use crate::validate::shortest;

/// The study file as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct StudyFile {
    case: String,
    #[serde(default)]
    set: BTreeMap<String, toml::Value>,
    ensemble: Option<EnsembleSpec>,
    #[serde(default)]
    sweep: BTreeMap<String, Vec<toml::Value>>,
    #[serde(default)]
    rows: Vec<BTreeMap<String, toml::Value>>,
    #[serde(default)]
    stop: StopSpec,
    #[serde(default = "yes")]
    recordings: bool,
}

fn yes() -> bool {
    true
}

/// `[ensemble]`: member `k` moves `key` by `k × step` from the case's value.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct EnsembleSpec {
    key: String,
    step: f64,
    members: usize,
}

/// One member of a study: its place, its overrides and its case.
#[derive(Debug, Clone)]
pub struct Member {
    pub index: usize,
    /// Its sweep row and its index in the ensemble.
    pub row: usize,
    pub k: usize,
    /// The file stem of its outputs (`member-0007`).
    pub name: String,
    /// What sets it apart: the sweep keys and the ensemble key with their values, in order.
    pub parameters: Vec<(String, toml::Value)>,
    /// Every override it runs with, `[set]` first.
    pub overrides: Vec<String>,
    pub case: Case,
}

/// A study: its name, its base case's file, and every member.
#[derive(Debug, Clone)]
pub struct Study {
    /// The study file's stem: the name of its output folder.
    pub name: String,
    pub case_path: PathBuf,
    /// The keys that vary: the sweep's, then the ensemble's.
    pub varying: Vec<String>,
    /// How many of them are swept.
    pub swept: usize,
    /// When a member stops before `t_end` ([`crate::study::stop`]).
    pub stop: StopSpec,
    /// Whether each member writes its `.rrd` (`recordings = false`: catalogs only).
    pub recordings: bool,
    pub rows: usize,
    pub members_per_row: usize,
    pub members: Vec<Member>,
}

/// Reads `path` and builds every member, or says what is wrong: the key, the value and what is
/// allowed, naming the member whose case is invalid.
pub fn load(path: &Path) -> Result<Study, String> {
    let text = crate::files::read_text_capped(path, MAX_STUDY_BYTES, "a study file is a few kilobytes of TOML")?;
    let file: StudyFile = toml::from_str(&text).map_err(|e| format!("{}: {}", path.display(), e.message()))?;
    let name = path.file_stem().map_or_else(|| "study".into(), |s| s.to_string_lossy().into_owned());
    let case_path = path.parent().unwrap_or(Path::new(".")).join(&file.case);
    let base = case::read(&case_path).map_err(|e| format!("{}: case = \"{}\": {e}", path.display(), file.case))?;
    check_shape(&file).map_err(|e| format!("{}: {e}", path.display()))?;
    let rows = all_rows(&file);
    let per_row = file.ensemble.as_ref().map_or(1, |e| e.members);
    let mut members = Vec::with_capacity(rows.len() * per_row);
    for (r, row) in rows.iter().enumerate() {
        for k in 0..per_row {
            let member =
                build(&file, (&base, case_path.parent().unwrap_or(Path::new("."))), r, row, k, r * per_row + k)
                    .map_err(|e| format!("{}: member {} (row {r}, k = {k}): {e}", path.display(), r * per_row + k))?;
            members.push(member);
        }
    }
    let mut varying: Vec<String> = rows[0].iter().map(|(key, _)| key.clone()).collect();
    let swept = varying.len();
    varying.extend(file.ensemble.as_ref().map(|e| e.key.clone()));
    Ok(Study {
        name,
        case_path,
        varying,
        swept,
        stop: file.stop,
        recordings: file.recordings,
        rows: rows.len(),
        members_per_row: per_row,
        members,
    })
}

/// The largest study file read (bytes): a few kilobytes of TOML, a long list of `[[rows]]`
/// included.
pub const MAX_STUDY_BYTES: u64 = 4 << 20;

/// The most members a study may have: each is validated before any runs, and each writes its
/// own files.
pub const MAX_MEMBERS: usize = 100_000;

/// The rules a study file's shape must meet before any member is built.
fn check_shape(file: &StudyFile) -> Result<(), String> {
    file.stop.check()?;
    let members = file
        .sweep
        .values()
        .map(Vec::len)
        .chain([file.rows.len().max(1), file.ensemble.as_ref().map_or(1, |e| e.members)])
        .try_fold(1usize, |n, k| n.checked_mul(k));
    if members.is_none_or(|n| n > MAX_MEMBERS) {
        return Err(format!(
            "the study has {} members: at most {MAX_MEMBERS} are allowed; split it into several study files",
            members.map_or_else(|| "more than 2^64".to_string(), |n| n.to_string())
        ));
    }
    for (key, values) in &file.sweep {
        if values.is_empty() {
            return Err(format!("sweep.\"{key}\" = []: a sweep key needs at least one value"));
        }
        if file.set.contains_key(key) {
            return Err(format!("sweep.\"{key}\" is also in [set]: give a key in one place"));
        }
    }
    if let Some(first) = file.rows.first() {
        for (i, row) in file.rows.iter().enumerate() {
            if row.keys().ne(first.keys()) {
                return Err(format!("rows[{i}] sets other keys than rows[0]: every row gives the same keys"));
            }
            if let Some(key) = row.keys().find(|k| file.sweep.contains_key(*k) || file.set.contains_key(*k)) {
                return Err(format!("rows[{i}].\"{key}\" is also swept or set: give a key in one place"));
            }
        }
        if first.is_empty() {
            return Err("rows[0] is empty: a row gives at least one key".into());
        }
    }
    if let Some(e) = &file.ensemble {
        if file.rows.first().is_some_and(|r| r.contains_key(&e.key)) {
            return Err(format!("ensemble.key = \"{}\" is also in [[rows]]: give a key in one place", e.key));
        }
        if e.members == 0 {
            return Err("ensemble.members = 0 must be at least 1".into());
        }
        if !(e.step.is_finite() && e.step != 0.0) {
            return Err(format!("ensemble.step = {} must be a finite number other than 0", shortest(e.step)));
        }
        if file.sweep.contains_key(&e.key) || file.set.contains_key(&e.key) {
            return Err(format!("ensemble.key = \"{}\" is also swept or set: give a key in one place", e.key));
        }
    }
    Ok(())
}

/// The product of the sweep lists, keys in order, the last varying fastest; one empty row
/// without a sweep.
fn sweep_rows(sweep: &BTreeMap<String, Vec<toml::Value>>) -> Vec<Vec<(String, toml::Value)>> {
    let mut rows: Vec<Vec<(String, toml::Value)>> = vec![Vec::new()];
    for (key, values) in sweep {
        rows = rows
            .into_iter()
            .flat_map(|row| {
                values.iter().map(move |v| {
                    let mut next = row.clone();
                    next.push((key.clone(), v.clone()));
                    next
                })
            })
            .collect();
    }
    rows
}

/// Every row: each of `[[rows]]` (or one empty row) with each combination of the sweep.
fn all_rows(file: &StudyFile) -> Vec<Vec<(String, toml::Value)>> {
    let given: Vec<Vec<(String, toml::Value)>> = if file.rows.is_empty() {
        vec![Vec::new()]
    } else {
        file.rows.iter().map(|row| row.iter().map(|(k, v)| (k.clone(), v.clone())).collect()).collect()
    };
    let swept = sweep_rows(&file.sweep);
    given.iter().flat_map(|g| swept.iter().map(move |s| [g.clone(), s.clone()].concat())).collect()
}

/// `key=value` as `--set` takes it.
fn assignment(key: &str, value: &toml::Value) -> String {
    format!("{key}={value}")
}

/// Member `index`: sweep row `row` and ensemble member `k`, its case built and validated.
fn build(
    file: &StudyFile,
    (base, dir): (&str, &Path),
    r: usize,
    row: &[(String, toml::Value)],
    k: usize,
    index: usize,
) -> Result<Member, String> {
    let mut overrides: Vec<String> = file.set.iter().map(|(key, v)| assignment(key, v)).collect();
    overrides.extend(row.iter().map(|(key, v)| assignment(key, v)));
    let mut parameters = row.to_vec();
    if let Some(e) = &file.ensemble {
        let case = case::from_str_at(base, &overrides, dir).map_err(|err| err.to_string())?;
        let start = value_at(&case.source.table, &e.key).ok_or_else(|| {
            format!("ensemble.key = \"{}\": the case does not give this key a number; set it in [set]", e.key)
        })?;
        let value = toml::Value::Float(start + k as f64 * e.step);
        overrides.push(assignment(&e.key, &value));
        parameters.push((e.key.clone(), value));
    }
    let case = case::from_str_at(base, &overrides, dir).map_err(|err| err.to_string())?;
    Ok(Member { index, row: r, k, name: format!("member-{index:04}"), parameters, overrides, case })
}

/// The number at a dotted key of a case table.
fn value_at(table: &toml::Table, key: &str) -> Option<f64> {
    let mut node: &toml::Value = table.get(key.split('.').next()?)?;
    for part in key.split('.').skip(1) {
        node = node.as_table()?.get(part)?;
    }
    node.as_float().or_else(|| node.as_integer().map(|n| n as f64))
}

/// `--shard I/N`: run the members whose index is `I - 1` modulo `N`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        let parse = |s: &str| s.trim().parse::<usize>().ok();
        match text.split_once('/').map(|(i, n)| (parse(i), parse(n))) {
            Some((Some(index), Some(count))) if count >= 1 && (1..=count).contains(&index) => Ok(Self { index, count }),
            _ => Err(format!("--shard {text}: expected I/N with 1 ≤ I ≤ N, e.g. --shard 1/4")),
        }
    }
}

impl Shard {
    /// Whether member `index` belongs to this shard.
    pub fn holds(&self, index: usize) -> bool {
        index % self.count == self.index - 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweep_rows_are_the_product_with_the_last_key_fastest() {
        let sweep = BTreeMap::from([
            ("a".to_string(), vec![toml::Value::Integer(1), toml::Value::Integer(2)]),
            ("b".to_string(), vec![toml::Value::Integer(3), toml::Value::Integer(4), toml::Value::Integer(5)]),
        ]);
        let rows = sweep_rows(&sweep);
        assert_eq!(rows.len(), 6);
        assert_eq!(
            rows[1],
            vec![("a".to_string(), toml::Value::Integer(1)), ("b".to_string(), toml::Value::Integer(4))]
        );
        assert_eq!(sweep_rows(&BTreeMap::new()), vec![Vec::new()]);
    }

    #[test]
    fn shards_split_the_members_without_overlap() {
        let shards: Vec<Shard> = ["1/3", "2/3", "3/3"].iter().map(|s| s.parse().unwrap()).collect();
        for index in 0..10 {
            assert_eq!(shards.iter().filter(|s| s.holds(index)).count(), 1);
        }
        for bad in ["3/2", "0/2", "1/0", "x/2", "2"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }
}
