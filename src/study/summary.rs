//! What a study's finished members say together: `events.csv`, every member's slip events with
//! its parameters as columns, and `summary.md`, per sweep row the statistics over its members
//! with their uncertainty. Both are made from the files in the study's folder, so shards that
//! copy their members into one folder make the same summary as one machine would.

use std::fmt::Write as _;
use std::path::Path;

use crate::study::figures::{Proportions, plot_proportions};
use crate::study::runner::{MemberRecord, output, record_of, write_atomically};
use crate::study::spec::Study;

/// Writes `events.csv` and `summary.md` into `dir` from the members finished there; returns
/// how many are finished.
pub fn write(study: &Study, dir: &Path) -> Result<usize, String> {
    let records: Vec<MemberRecord> = study.members.iter().filter_map(|m| record_of(dir, &m.name)).collect();
    write_atomically(&dir.join("events.csv"), &events_table(study, dir, &records)?)?;
    write_atomically(&dir.join("summary.md"), &summary(study, &records))?;
    verdict_figure(study, &dir.join("summary.png"), &records)?;
    Ok(records.len())
}

/// Every finished member's events, its index, row, ensemble index and parameters first.
fn events_table(study: &Study, dir: &Path, records: &[MemberRecord]) -> Result<String, String> {
    let mut out = String::from("member,row,k");
    for key in &study.varying {
        let _ = write!(out, ",{key}");
    }
    out.push_str(",segment,onset_s,end_s,slip_m,peak_slip_rate_m_s,traction_before_pa,traction_after_pa\n");
    for record in records {
        let name = &study.members[record.index].name;
        let path = output(dir, name, ".events.csv");
        let text = std::fs::read_to_string(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let values: Vec<&str> = record.parameters.iter().map(|(_, v)| v.as_str()).collect();
        for line in text.lines().skip(1).filter(|l| !l.is_empty()) {
            let _ = writeln!(out, "{},{},{},{}{line}", record.index, record.row, record.k, prefix(&values));
        }
    }
    Ok(out)
}

/// `v1,v2,` (or nothing).
fn prefix(values: &[&str]) -> String {
    values.iter().map(|v| format!("{v},")).collect()
}

/// `summary.png`: per row, the share of members in which each of the paper's observations
/// holds, with its 95 % interval; none for studies of scenes without verdicts.
fn verdict_figure(study: &Study, path: &Path, records: &[MemberRecord]) -> Result<(), String> {
    if records.iter().all(|r| r.verdict.is_none()) {
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
                    let judged: Vec<[bool; 3]> =
                        records.iter().filter(|r| r.row == row).filter_map(|r| r.verdict).collect();
                    let held = judged.iter().filter(|v| if i == 3 { v.iter().all(|&b| b) } else { v[i] }).count();
                    (held, judged.len())
                })
                .collect(),
        })
        .collect();
    let title = format!("{}: the paper's observations per row, with Wilson 95 % intervals", study.name);
    plot_proportions(path, &title, study.rows, &series, wilson_interval)
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

/// `summary.md`: per sweep row, the members finished, their slips per segment and event counts
/// (mean ± standard error), and the paper's observations as proportions with a 95 % interval.
fn summary(study: &Study, records: &[MemberRecord]) -> String {
    let mut out = format!(
        "# Study {}\n\n{} of {} members finished ({} of {} members). Base case: `{}`.\n\n",
        study.name,
        records.len(),
        study.members.len(),
        plural(study.rows, "row"),
        study.members_per_row,
        study.case_path.display()
    );
    out.push_str(
        "Mean ± standard error over a row's finished members. Verdicts: the paper's observations 1–3 \
         (`Verdict`: left end, right end, propagation) as members holding / members, with the Wilson 95 % \
         interval of the proportion.\n\n",
    );
    for row in 0..study.rows {
        let members: Vec<&MemberRecord> = records.iter().filter(|r| r.row == row).collect();
        let first = &study.members[row * study.members_per_row];
        let swept: Vec<(String, String)> =
            first.parameters[..study.swept].iter().map(|(k, v)| (k.clone(), v.to_string())).collect();
        let _ = writeln!(out, "## Row {row}: {}\n", crate::study::runner::describe(&swept));
        row_statistics(&mut out, &members);
    }
    out
}

/// `1 row`, `2 rows`.
fn plural(n: usize, word: &str) -> String {
    if n == 1 { format!("1 {word}") } else { format!("{n} {word}s") }
}

/// The statistics of one row.
fn row_statistics(out: &mut String, members: &[&MemberRecord]) {
    let count = |prefix: &str| members.iter().filter(|m| m.ending.starts_with(prefix)).count();
    let _ = writeln!(
        out,
        "- members finished: {} ({} completed, {} stopped by a rule, {} failed)",
        members.len(),
        count("completed"),
        count("stopped"),
        count("failed")
    );
    if members.is_empty() {
        out.push('\n');
        return;
    }
    let stat = |f: &dyn Fn(&MemberRecord) -> f64| {
        let (mean, error) = mean_and_error(&members.iter().map(|m| f(m)).collect::<Vec<_>>());
        if error.is_nan() { format!("{mean:.2}") } else { format!("{mean:.2} ± {error:.2}") }
    };
    let _ =
        writeln!(out, "- slip events: {}; ruptures: {}", stat(&|m| m.slip_events as f64), stat(&|m| m.ruptures as f64));
    let segments = members.iter().map(|m| m.segments).max().unwrap_or(0);
    let per_segment: Vec<String> = (0..segments)
        .map(|s| stat(&|m: &MemberRecord| m.slips_per_segment.get(s).copied().unwrap_or(0) as f64))
        .collect();
    let _ = writeln!(out, "- slips per segment, from the left: {}", per_segment.join(" | "));
    let judged: Vec<[bool; 3]> = members.iter().filter_map(|m| m.verdict).collect();
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
