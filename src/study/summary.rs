//! What a study's members say together: `events.csv`, every finished member's slip events with
//! its parameters as columns, and `summary.md`, per sweep row the statistics over its finished
//! members with their uncertainty, and the failed members with their errors. Both are made from
//! the files in the study's folder, so shards that copy their members into one folder make the
//! same summary as one machine would.
//!
//! Only what verifies counts ([`crate::study::record`]): a member whose record or outputs do not
//! verify, or whose record is of other parameters, is not finished. Counts and verdicts are read
//! from each member's own catalogs, never from its record. Failed members are counted apart and
//! left out of every statistic; members missing (never run, interrupted, or not verifying) are
//! named with why, so that a study summarised with members missing says so.

use std::fmt::Write as _;
use std::path::Path;

use crate::case::units::with_unit;
use crate::catalog::events::{Rupture, SlipEvent};
use crate::catalog::observations::{Observations, PAPER_SPAN, paper_family};
use crate::inspect::catalog;
use crate::study::figures::{Proportions, plot_proportions};
use crate::study::record::{MemberRecord, Standing, output, standing};
use crate::study::runner::{describe, members, write_atomically};
use crate::study::spec::{Member, Study};

/// The largest member catalog read (bytes).
pub const MAX_CATALOG_BYTES: u64 = 1 << 30;

/// A finished member as its catalogs tell it.
struct Finished<'s> {
    member: &'s Member,
    record: MemberRecord,
    /// The events CSV's data lines, for `events.csv`.
    lines: Vec<String>,
    events: usize,
    ruptures: usize,
    slips_per_segment: Vec<usize>,
    /// The paper's observations 1–3 ([`crate::catalog::observations::Verdict`]), or why they
    /// are not evaluated ([`judge`]).
    verdict: Result<[bool; 3], String>,
}

/// How many of a study's members are finished and failed, as [`write`] found them, and the
/// members missing with why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Counts {
    pub finished: usize,
    pub failed: usize,
    pub missing: Vec<String>,
}

/// Writes `events.csv`, `summary.md` and `summary.png` into `dir` from the members that verify
/// there.
pub fn write(study: &Study, dir: &Path) -> Result<Counts, String> {
    let mut finished = Vec::new();
    let mut failed = Vec::new();
    let mut missing = Vec::new();
    for member in &study.members {
        match standing(dir, study, member) {
            Standing::Finished(record) => match read_catalogs(dir, member, record) {
                Some(member) => finished.push(member),
                None => missing.push((member, "its catalogs cannot be read".to_string())),
            },
            Standing::Failed(record) => failed.push((member, record)),
            Standing::NotRun => missing.push((member, "no record: not run, or interrupted".to_string())),
            Standing::Stale => missing.push((member, "a record of other parameters than the study file's".into())),
            Standing::Unverified(why) => missing.push((member, format!("does not verify: {why}"))),
        }
    }
    write_atomically(&dir.join("events.csv"), &events_table(study, &finished))?;
    write_atomically(&dir.join("summary.md"), &summary(study, &finished, &failed, &missing))?;
    verdict_figure(study, &dir.join("summary.png"), &finished)?;
    let missing = missing.iter().map(|(member, why)| format!("{}: {why}", member.name)).collect();
    Ok(Counts { finished: finished.len(), failed: failed.len(), missing })
}

/// The member's catalogs, read and measured; `None` if they cannot be (they verified, so only
/// a file changed since, or one too large, is left out).
fn read_catalogs<'s>(dir: &Path, member: &'s Member, record: MemberRecord) -> Option<Finished<'s>> {
    let read = |suffix: &str| {
        let path = output(dir, &member.name, suffix);
        let text = crate::files::read_text_capped(&path, MAX_CATALOG_BYTES, "a member's catalog is a CSV file").ok()?;
        Some((path.display().to_string(), text))
    };
    let (name, text) = read(".events.csv")?;
    let mut events: Vec<SlipEvent> = catalog::events(&text, &name).ok()?;
    let ruptures = match read(".ruptures.csv") {
        Some((name, text)) => catalog::ruptures(&text, &name).ok()?,
        None => Vec::new(),
    };
    let segments = record.segments;
    let mut slips_per_segment = vec![0; segments];
    for e in &events {
        *slips_per_segment.get_mut(e.segment)? += 1;
    }
    let verdict = judge(member, &record, &mut events, &ruptures);
    Some(Finished {
        member,
        lines: text.lines().skip(1).filter(|l| !l.is_empty()).map(str::to_string).collect(),
        events: events.len(),
        ruptures: ruptures.len(),
        slips_per_segment,
        verdict,
        record,
    })
}

/// The paper's observations 1–3 on a finished member, or why they are not evaluated: its case
/// is not of the paper's family ([`paper_family`]), it stopped by a rule before the paper's
/// 1000 s, or its record lacks `1/R*` at its events' onsets.
fn judge(
    member: &Member,
    record: &MemberRecord,
    events: &mut [SlipEvent],
    ruptures: &[Rupture],
) -> Result<[bool; 3], String> {
    paper_family(&member.case).map_err(|why| format!("{NOT_THE_PAPERS} ({why})"))?;
    if record.ending != "completed" {
        return Err(format!(
            "{}, before the paper's {PAPER_SPAN} s: its observations are not evaluated",
            record.ending
        ));
    }
    if record.onset_structure.len() != events.len() {
        return Err("the record lacks 1/R* at the events' onsets: the observations are not evaluated".into());
    }
    for (event, structure) in events.iter_mut().zip(&record.onset_structure) {
        event.structure_before = Some(*structure).filter(|s| !s.is_nan());
    }
    let v = Observations::measure(events, ruptures, record.segments).verdict();
    Ok([v.left_end, v.right_end, v.propagation])
}

/// What the summary says where a case is not of the paper's family.
pub const NOT_THE_PAPERS: &str = "not the paper's case: its observations are not evaluated";

/// Every finished member's events, its index, row, ensemble index and parameters first.
fn events_table(study: &Study, finished: &[Finished<'_>]) -> String {
    let mut out = String::from("member,row,k");
    for key in &study.varying {
        let _ = write!(out, ",{key}");
    }
    out.push_str(",segment,onset_s,end_s,slip_m,peak_slip_rate_m_s,traction_before_pa,traction_after_pa\n");
    for f in finished {
        let values: String = f.member.parameters.iter().map(|(_, v)| format!("{v},")).collect();
        for line in &f.lines {
            let _ = writeln!(out, "{},{},{},{values}{line}", f.member.index, f.member.row, f.member.k);
        }
    }
    out
}

/// `summary.png`: per row, the share of finished members in which each of the paper's
/// observations holds, with its 95 % interval, against the rows' swept values ([`row_axis`]);
/// none where no member was judged (a study of another case than the paper's).
fn verdict_figure(study: &Study, path: &Path, finished: &[Finished<'_>]) -> Result<(), String> {
    if finished.iter().all(|f| f.verdict.is_err()) {
        let _ = std::fs::remove_file(path);
        return Ok(());
    }
    let labels = ["1. left end", "2. right end", "3. propagation", "all three"];
    let series: Vec<Proportions> = labels
        .iter()
        .enumerate()
        .map(|(i, label)| Proportions {
            label: label.to_string(),
            counts: (0..study.rows)
                .map(|row| {
                    let judged: Vec<[bool; 3]> = finished
                        .iter()
                        .filter(|f| f.member.row == row)
                        .filter_map(|f| f.verdict.clone().ok())
                        .collect();
                    let held = judged.iter().filter(|v| if i == 3 { v.iter().all(|&b| b) } else { v[i] }).count();
                    (held, judged.len())
                })
                .collect(),
        })
        .collect();
    let title = format!("{}: the paper's observations per row, with Wilson 95 % intervals", study.name);
    let (axis, labels) = row_axis(study);
    plot_proportions(path, &title, (&axis, &labels), &series, wilson_interval)
}

/// How `summary.png` names its rows: the swept keys with their units (`scene.normal_traction.left
/// (Pa)`, several joined by ` / `), and per row its values in the same order (`300/1200`).
/// A study without a sweep has one row, the base case.
pub fn row_axis(study: &Study) -> (String, Vec<String>) {
    let keys = &study.varying[..study.swept];
    if keys.is_empty() {
        return ("the base case (nothing swept)".into(), vec!["base case".into(); study.rows]);
    }
    let axis = keys.iter().map(|k| with_unit(k)).collect::<Vec<_>>().join(" / ");
    let labels = (0..study.rows)
        .map(|row| {
            let member = &study.members[row * study.members_per_row];
            member.parameters[..study.swept].iter().map(|(_, v)| value_text(v)).collect::<Vec<_>>().join("/")
        })
        .collect();
    (axis, labels)
}

/// A swept value as a label: numbers in their shortest form, text without quotes.
fn value_text(value: &toml::Value) -> String {
    match value {
        toml::Value::Float(x) => crate::validate::shortest(*x),
        toml::Value::String(text) => text.clone(),
        other => other.to_string(),
    }
}

/// The Wilson score interval of a proportion `x / n` at 95 % (`z = 1.96`).
pub fn wilson_interval(x: usize, n: usize) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let (x, n, z) = (x as f64, n as f64, 1.96_f64);
    let p = x / n;
    let centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
    let half = z / (1.0 + z * z / n) * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt();
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

/// Mean and standard error of the mean.
fn mean_and_error(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    if values.len() < 2 {
        return (mean, f64::NAN);
    }
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (variance / n).sqrt())
}

/// `summary.md`: per sweep row, the members finished and failed, the finished members' slips
/// per segment and event counts (mean ± standard error), and the paper's observations as
/// proportions with a 95 % interval; then every failed member with its error, and every member
/// missing with why.
fn summary(
    study: &Study,
    finished: &[Finished<'_>],
    failed: &[(&Member, MemberRecord)],
    missing: &[(&Member, String)],
) -> String {
    let total = study.members.len();
    let mut out = format!(
        "# Study {}\n\n{} of {total} members finished, {} failed, {} not run or not verified ({} of {}). \
         Base case: `{}`.\n\n",
        study.name,
        finished.len(),
        failed.len(),
        missing.len(),
        plural(study.rows, "row"),
        members(study.members_per_row),
        study.case_path.display()
    );
    out.push_str("Mean ± standard error over a row's finished members, counted from their catalogs; failed members are left out. ");
    match study.members.iter().map(|m| paper_family(&m.case)).find(Result::is_ok) {
        Some(_) => out.push_str(
            "Verdicts: the paper's observations 1–3 (`Verdict`: left end, right end, propagation) as members holding \
             / members, with the Wilson 95 % interval of the proportion, on the members of the paper's family only \
             (its block of at least 3 segments under a normal traction rising from left to right, run for its whole \
             1000 s).\n\n",
        ),
        None => {
            let why = study.members.first().and_then(|m| paper_family(&m.case).err()).unwrap_or_default();
            let _ = write!(out, "Verdicts: {NOT_THE_PAPERS} ({why}).\n\n");
        }
    }
    for row in 0..study.rows {
        let first = &study.members[row * study.members_per_row];
        let swept: Vec<(String, String)> =
            first.parameters[..study.swept].iter().map(|(k, v)| (k.clone(), v.to_string())).collect();
        let _ = writeln!(out, "## Row {row}: {}\n", describe(&swept));
        let members: Vec<&Finished<'_>> = finished.iter().filter(|f| f.member.row == row).collect();
        let failures = failed.iter().filter(|(m, _)| m.row == row).count();
        row_statistics(&mut out, &members, failures);
    }
    if !failed.is_empty() {
        out.push_str("## Failed members\n\n");
        for (member, record) in failed {
            let error = record.error.as_deref().unwrap_or("no error given").replace('\n', " ");
            let _ = writeln!(out, "- {} ({}): {error}", member.name, describe(&member_parameters(member)));
        }
        out.push('\n');
    }
    if !missing.is_empty() {
        out.push_str(
            "## Missing members\n\nNot in any statistic above; `--resume` (or the shard's task run again) runs them.\n\n",
        );
        for (member, why) in missing {
            let _ = writeln!(out, "- {} ({}): {why}", member.name, describe(&member_parameters(member)));
        }
        out.push('\n');
    }
    out
}

/// A member's varying keys and their values as text.
fn member_parameters(member: &Member) -> Vec<(String, String)> {
    member.parameters.iter().map(|(k, v)| (k.clone(), v.to_string())).collect()
}

/// `1 row`, `2 rows`.
pub fn plural(n: usize, word: &str) -> String {
    if n == 1 { format!("1 {word}") } else { format!("{n} {word}s") }
}

/// The statistics of one row's finished members.
fn row_statistics(out: &mut String, members: &[&Finished<'_>], failed: usize) {
    let count = |prefix: &str| members.iter().filter(|f| f.record.ending.starts_with(prefix)).count();
    let _ = writeln!(
        out,
        "- members finished: {} ({} completed, {} stopped by a rule); failed: {failed}",
        members.len(),
        count("completed"),
        count("stopped"),
    );
    if members.is_empty() {
        out.push('\n');
        return;
    }
    let stat = |f: &dyn Fn(&Finished<'_>) -> f64| {
        let (mean, error) = mean_and_error(&members.iter().map(|m| f(m)).collect::<Vec<_>>());
        if error.is_nan() { format!("{mean:.2}") } else { format!("{mean:.2} ± {error:.2}") }
    };
    let _ = writeln!(out, "- slip events: {}; ruptures: {}", stat(&|m| m.events as f64), stat(&|m| m.ruptures as f64));
    let segments = members.iter().map(|m| m.slips_per_segment.len()).max().unwrap_or(0);
    let per_segment: Vec<String> = (0..segments)
        .map(|s| stat(&|m: &Finished<'_>| m.slips_per_segment.get(s).copied().unwrap_or(0) as f64))
        .collect();
    let _ = writeln!(out, "- slips per segment, from the left: {}", per_segment.join(" | "));
    let judged: Vec<[bool; 3]> = members.iter().filter_map(|m| m.verdict.clone().ok()).collect();
    let unjudged: Vec<&String> = members.iter().filter_map(|m| m.verdict.as_ref().err()).collect();
    if let (true, Some(why)) = (judged.is_empty(), unjudged.first()) {
        let _ = writeln!(out, "- verdicts: {why}");
    } else if let Some(why) = unjudged.first() {
        let _ = writeln!(out, "- not judged: {} ({why})", plural(unjudged.len(), "member"));
    }
    if !judged.is_empty() {
        let n = judged.len();
        let share = |held: usize| {
            let (lo, hi) = wilson_interval(held, n);
            format!("{held}/{n} [{lo:.2}, {hi:.2}]")
        };
        let count = |i: usize| judged.iter().filter(|v| v[i]).count();
        let all = judged.iter().filter(|v| v.iter().all(|&b| b)).count();
        let _ = writeln!(
            out,
            "- verdicts: 1. left end {}; 2. right end {}; 3. propagation {}; all three {}",
            share(count(0)),
            share(count(1)),
            share(count(2)),
            share(all)
        );
    }
    out.push('\n');
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wilson_interval_matches_published_values() {
        // Newcombe (1998), Table I: 81/263 → [0.2553, 0.3662]; 15/148 → [0.0624, 0.1605].
        let (lo, hi) = wilson_interval(81, 263);
        assert!((lo - 0.2553).abs() < 5e-5 && (hi - 0.3662).abs() < 5e-5, "{lo} {hi}");
        let (lo, hi) = wilson_interval(15, 148);
        assert!((lo - 0.0624).abs() < 5e-5 && (hi - 0.1605).abs() < 5e-5, "{lo} {hi}");
        assert_eq!(wilson_interval(0, 0), (0.0, 1.0));
    }
}
