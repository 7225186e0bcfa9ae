//! Running a study's members: on the cores, a shard of them, skipping those already done.
//!
//! Each member writes into the study's folder what `slipfront run` writes for a case
//! (`member-0007.rrd`, `.events.csv`, `.ruptures.csv`), then, last, `member-0007.done.toml`:
//! its parameters, how its run ended and what its catalog says of the paper's observations.
//! That record is written beside and renamed into place, so a member is complete exactly when
//! it exists: `--resume` skips those members, and a killed study loses only the members in
//! flight.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::catalog::observations::Observations;
use crate::frame::Needs;
use crate::record::schema::RecordingPlan;
use crate::run::{LoopOptions, Outcome, run};
use crate::scene;
use crate::sink::Sink;
use crate::sink::catalog::CatalogSink;
use crate::sink::rerun::{RerunSink, Viewer, open_stream};
use crate::study::spec::{Member, Study};
use crate::study::stop::StopRules;

/// What a finished member leaves as `<name>.done.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MemberRecord {
    pub index: usize,
    pub row: usize,
    pub k: usize,
    /// The varying keys and their values (TOML text), in the study's order.
    pub parameters: Vec<(String, String)>,
    /// `completed`, `failed`, or `stopped` and why, by a stop rule (an interrupted member has
    /// no record).
    pub ending: String,
    /// Why the run failed, if it did.
    pub error: Option<String>,
    pub segments: usize,
    pub slip_events: usize,
    pub ruptures: usize,
    /// Slip events per segment, from the left.
    pub slips_per_segment: Vec<usize>,
    /// The paper's observations 1–3 ([`crate::catalog::observations::Verdict`]); block scenes.
    pub verdict: Option<[bool; 3]>,
}

/// The paths of a member's outputs in `dir`.
pub fn output(dir: &Path, member: &str, suffix: &str) -> PathBuf {
    dir.join(format!("{member}{suffix}"))
}

/// Reads a member's record, if it finished.
pub fn record_of(dir: &Path, member: &str) -> Option<MemberRecord> {
    let text = std::fs::read_to_string(output(dir, member, ".done.toml")).ok()?;
    toml::from_str(&text).ok()
}

/// How a study is run.
pub struct Options<'a> {
    pub jobs: usize,
    /// Skip members whose record exists.
    pub resume: bool,
    /// Print a line per finished member on stderr.
    pub progress: bool,
    /// Set to stop: members in flight finish their current step and leave no record.
    pub interrupt: Option<&'a AtomicBool>,
}

/// Runs `selected` members of `study` into `dir`; returns how many ran and how many were
/// skipped as done.
pub fn run_members(
    study: &Study,
    selected: &[&Member],
    dir: &Path,
    options: &Options,
) -> Result<(usize, usize), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let todo: Vec<&Member> =
        selected.iter().copied().filter(|m| !(options.resume && record_of(dir, &m.name).is_some())).collect();
    let skipped = selected.len() - todo.len();
    let next = AtomicUsize::new(0);
    let finished = AtomicUsize::new(0);
    let errors = Mutex::new(Vec::new());
    let started = Instant::now();
    std::thread::scope(|scope| {
        for _ in 0..options.jobs.clamp(1, todo.len().max(1)) {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::SeqCst);
                    let stopped = options.interrupt.is_some_and(|f| f.load(Ordering::SeqCst));
                    if i >= todo.len() || stopped {
                        break;
                    }
                    let member = todo[i];
                    match run_member(study, member, dir, options.interrupt) {
                        Ok(Some(record)) => {
                            let done = finished.fetch_add(1, Ordering::SeqCst) + 1;
                            if options.progress {
                                eprintln!(
                                    "slipfront study {}: [{done}/{}] {} {} ({}): {} slip events, {} ruptures; {:.0} s elapsed",
                                    study.name,
                                    todo.len(),
                                    member.name,
                                    record.ending,
                                    describe(&record.parameters),
                                    record.slip_events,
                                    record.ruptures,
                                    started.elapsed().as_secs_f64()
                                );
                            }
                        }
                        Ok(None) => {}
                        Err(e) => errors.lock().unwrap_or_else(|e| e.into_inner()).push(format!("{}: {e}", member.name)),
                    }
                }
            });
        }
    });
    let errors = errors.into_inner().unwrap_or_else(|e| e.into_inner());
    if let Some(first) = errors.first() {
        return Err(first.clone());
    }
    Ok((finished.into_inner(), skipped))
}

/// `key = value, ...` for people.
pub fn describe(parameters: &[(String, String)]) -> String {
    if parameters.is_empty() {
        return "the base case".into();
    }
    parameters.iter().map(|(k, v)| format!("{k} = {v}")).collect::<Vec<_>>().join(", ")
}

/// Runs one member into `dir` and writes its record; `None` if it was interrupted (it then
/// leaves no record, and `--resume` runs it again).
fn run_member(
    study: &Study,
    member: &Member,
    dir: &Path,
    interrupt: Option<&AtomicBool>,
) -> Result<Option<MemberRecord>, String> {
    let case = &member.case;
    let mut scene = scene::build(case).map_err(|e| e.to_string())?;
    let layout = scene.layout().clone();
    let rrd = output(dir, &member.name, ".rrd");
    let name = format!("{}-{}", study.name, member.name);
    let ruptures = (layout.kind.has_body()).then(|| output(dir, &member.name, ".ruptures.csv"));
    let (stop, fired) = (AtomicBool::new(false), OnceLock::new());
    let mut sinks: Vec<Box<dyn Sink + '_>> =
        vec![Box::new(CatalogSink::new(output(dir, &member.name, ".events.csv"), ruptures))];
    if study.recordings {
        let plan = RecordingPlan::for_case(&name, case);
        let stream = open_stream(Some(&rrd), &Viewer::None, &name, plan.recording_id.as_deref())?
            .ok_or("no recording stream")?;
        sinks.push(Box::new(RerunSink::new(stream, plan)));
    }
    let rules = !study.stop.is_empty();
    if rules {
        let threshold = case.slip_rate_threshold();
        sinks.push(Box::new(StopRules::new(study.stop.clone(), threshold, &stop, interrupt, &fired)));
    }
    let options = LoopOptions {
        interrupt: if rules { Some(&stop) } else { interrupt },
        needs: Needs { segment_state: true, ..Needs::default() },
        ..LoopOptions::for_case(case)
    };
    let outcome = run(scene.as_mut(), &case.time, &mut sinks, options);
    drop(sinks);
    if study.recordings {
        // A compaction that fails leaves the recording as written, which is complete.
        let _ = crate::record::compact::compact(&rrd);
    }
    let (ending, error, catalog) = match outcome {
        Outcome::Completed { catalog, .. } => ("completed".to_string(), None, catalog),
        Outcome::Failed { error, catalog } => ("failed".to_string(), Some(error.to_string()), catalog),
        Outcome::Interrupted { catalog, .. } if fired.get().is_some() => {
            (format!("stopped {}", fired.get().expect("checked")), None, catalog)
        }
        Outcome::Interrupted { .. } => return Ok(None),
        Outcome::Sink(e) => return Err(e.to_string()),
    };
    let segments = layout.segments.len();
    let verdict = (layout.kind.has_body() && segments >= 3).then(|| {
        let v = Observations::measure(&catalog.events, &catalog.ruptures, segments).verdict();
        [v.left_end, v.right_end, v.propagation]
    });
    let mut slips_per_segment = vec![0; segments];
    for e in &catalog.events {
        slips_per_segment[e.segment] += 1;
    }
    let record = MemberRecord {
        index: member.index,
        row: member.row,
        k: member.k,
        parameters: member.parameters.iter().map(|(k, v)| (k.clone(), v.to_string())).collect(),
        ending,
        error,
        segments,
        slip_events: catalog.events.len(),
        ruptures: catalog.ruptures.len(),
        slips_per_segment,
        verdict,
    };
    write_atomically(&output(dir, &member.name, ".done.toml"), &toml::to_string(&record).map_err(|e| e.to_string())?)?;
    Ok(Some(record))
}

/// Writes `text` beside `path` and renames it into place.
pub fn write_atomically(path: &Path, text: &str) -> Result<(), String> {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let temporary = path.with_file_name(format!(".{name}.writing"));
    std::fs::write(&temporary, text)
        .and_then(|()| std::fs::rename(&temporary, path))
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}
