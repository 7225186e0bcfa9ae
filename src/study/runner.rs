//! Running a study's members: on the cores, a shard of them, skipping those already done.
//!
//! Each member writes into the study's folder what `slipfront run` writes for a case
//! (`member-0007.rrd`, `.events.csv`, `.ruptures.csv`), holding a lock on each while it runs
//! ([`crate::cli::outputs`] refuses a second writer), then, last, `member-0007.done.toml`: its
//! parameters, how its run ended and the digests by which it is verified
//! ([`crate::study::record`]). That record is written beside and renamed into place, and the
//! member's old record is removed before it runs again, so a member is complete exactly when its
//! record exists and verifies: `--resume` skips those members and runs every other one, and a
//! killed study loses only the members in flight. A member whose run fails is recorded as
//! failed, with its error.

use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::Instant;

use crate::cli::outputs::{self, Named};
use crate::record::schema::RecordingPlan;
use crate::run::{LoopOptions, Outcome, run};
use crate::scene;
use crate::sink::Sink;
use crate::sink::catalog::CatalogSink;
use crate::sink::rerun::{RerunSink, Viewer, open_stream};
use crate::study::record::{DONE, MemberRecord, Standing, file_digest, identity, output, run_name, standing};
use crate::study::spec::{Member, Study};
use crate::study::stop::StopRules;

/// How a study is run.
pub struct Options<'a> {
    pub jobs: usize,
    /// Print a line per finished member on stderr.
    pub progress: bool,
    /// Set to stop: members in flight finish their current step and leave no record.
    pub interrupt: Option<&'a AtomicBool>,
}

/// Why the members that run now run: with `--resume`, each selected member that is not done.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Plan {
    /// Members verified as done, skipped.
    pub kept: usize,
    /// Members to run: without a record, failed before, of other parameters (the study file
    /// changed), and whose record or outputs do not verify (with the first reason).
    pub not_run: usize,
    pub failed: usize,
    pub stale: usize,
    pub unverified: Vec<String>,
}

impl Plan {
    /// `--resume: 3 members verified and kept; to run: 2 without a record, ...`, for people.
    pub fn describe(&self) -> String {
        let mut reasons = Vec::new();
        for (n, why) in [
            (self.not_run, "without a record"),
            (self.failed, "failed before"),
            (self.stale, "of other parameters than the study file's"),
            (self.unverified.len(), "whose record or outputs do not verify"),
        ] {
            if n > 0 {
                reasons.push(format!("{n} {why}"));
            }
        }
        let mut text = format!("--resume: {} verified and kept", members(self.kept));
        if !reasons.is_empty() {
            text.push_str(&format!("; to run: {}", reasons.join(", ")));
        }
        if let Some(first) = self.unverified.first() {
            text.push_str(&format!(" (first: {first})"));
        }
        text
    }
}

/// `1 member`, `2 members`.
pub fn members(n: usize) -> String {
    if n == 1 { "1 member".into() } else { format!("{n} members") }
}

/// What running the members did.
#[derive(Debug, Default)]
pub struct Ran {
    /// Members run to a record, and of them failed.
    pub ran: usize,
    pub failed: usize,
    /// Members not run because their outputs could not be claimed (another command holds
    /// them), and why.
    pub busy: Vec<String>,
    /// Members whose record could not be written, and why.
    pub unwritable: Vec<String>,
}

/// Why a member left no record: another command holds its outputs (nothing was written), or
/// its record or an output's digest could not be written or read.
enum Unrecorded {
    Busy(String),
    Unwritable(String),
}

/// The members of `selected` to run in `dir`: all of them, or with `resume` those not done.
pub fn plan<'m>(study: &Study, selected: &[&'m Member], dir: &Path, resume: bool) -> (Vec<&'m Member>, Plan) {
    if !resume {
        return (selected.to_vec(), Plan::default());
    }
    let mut plan = Plan::default();
    let mut todo = Vec::new();
    for &member in selected {
        match standing(dir, study, member) {
            Standing::Finished(_) => {
                plan.kept += 1;
                continue;
            }
            Standing::Failed(_) => plan.failed += 1,
            Standing::NotRun => plan.not_run += 1,
            Standing::Stale => plan.stale += 1,
            Standing::Unverified(why) => plan.unverified.push(format!("{}: {why}", member.name)),
        }
        todo.push(member);
    }
    (todo, plan)
}

/// Runs `todo` members of `study` into `dir`.
pub fn run_members(study: &Study, todo: &[&Member], dir: &Path, options: &Options) -> Ran {
    let next = AtomicUsize::new(0);
    let ran = Mutex::new(Ran::default());
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
                    let result = run_member(study, member, dir, options.interrupt);
                    let mut ran = ran.lock().unwrap_or_else(|e| e.into_inner());
                    match result {
                        Ok(Some((record, events, ruptures))) => {
                            ran.ran += 1;
                            ran.failed += usize::from(record.failed());
                            if options.progress {
                                let how = match &record.error {
                                    Some(error) => format!("failed: {error}"),
                                    None => format!("{}: {events} slip events, {ruptures} ruptures", record.ending),
                                };
                                eprintln!(
                                    "slipfront study {}: [{}/{}] {} ({}) {how}; {:.0} s elapsed",
                                    study.name,
                                    ran.ran,
                                    todo.len(),
                                    member.name,
                                    describe(&record.parameters),
                                    started.elapsed().as_secs_f64()
                                );
                            }
                        }
                        Ok(None) => {}
                        Err(Unrecorded::Busy(e)) => ran.busy.push(format!("{}: {e}", member.name)),
                        Err(Unrecorded::Unwritable(e)) => ran.unwritable.push(format!("{}: {e}", member.name)),
                    }
                }
            });
        }
    });
    ran.into_inner().unwrap_or_else(|e| e.into_inner())
}

/// `key = value, ...` for people.
pub fn describe(parameters: &[(String, String)]) -> String {
    if parameters.is_empty() {
        return "the base case".into();
    }
    parameters.iter().map(|(k, v)| format!("{k} = {v}")).collect::<Vec<_>>().join(", ")
}

/// Runs one member into `dir` and writes its record (a failed run too, with its error);
/// returns the record and the catalog's counts, `None` if it was interrupted (it then leaves no
/// record, and `--resume` runs it again), or why its outputs could not be claimed (another
/// command is writing them; nothing was written).
fn run_member(
    study: &Study,
    member: &Member,
    dir: &Path,
    interrupt: Option<&AtomicBool>,
) -> Result<Option<(MemberRecord, usize, usize)>, Unrecorded> {
    let case = &member.case;
    let record = |ending: &str, error: Option<String>, segments: usize| MemberRecord {
        index: member.index,
        row: member.row,
        k: member.k,
        parameters: member.parameters.iter().map(|(k, v)| (k.clone(), v.to_string())).collect(),
        identity: identity(study, member),
        ending: ending.to_string(),
        error,
        segments,
        onset_structure: Vec::new(),
        outputs: Vec::new(),
        digest: String::new(),
    };
    let done = output(dir, &member.name, DONE);
    let mut scene = match scene::build(case) {
        Ok(scene) => scene,
        Err(e) => {
            let failed = record("failed", Some(e.to_string()), 0);
            return seal(&done, failed, dir).map(|r| Some((r, 0, 0))).map_err(Unrecorded::Unwritable);
        }
    };
    let layout = scene.layout().clone();
    let rrd = output(dir, &member.name, ".rrd");
    let events = output(dir, &member.name, ".events.csv");
    let ruptures = (layout.kind.has_body()).then(|| output(dir, &member.name, ".ruptures.csv"));
    let mut named = vec![Named { role: "the event catalog", path: &events }];
    named.extend(ruptures.as_deref().map(|path| Named { role: "the rupture catalog", path }));
    if study.recordings {
        named.push(Named { role: "the recording", path: &rrd });
    }
    let _locks = outputs::claim(&[], &named).map_err(Unrecorded::Busy)?;
    let _ = std::fs::remove_file(&done);
    let (stop, fired) = (AtomicBool::new(false), OnceLock::new());
    let mut sinks: Vec<Box<dyn Sink + '_>> = vec![Box::new(CatalogSink::new(events.clone(), ruptures.clone()))];
    let mut failure = None;
    if study.recordings {
        let name = run_name(study, member);
        let plan = RecordingPlan::for_case(&name, case);
        match open_stream(Some(&rrd), &Viewer::None, &name, plan.recording_id.as_deref()) {
            Ok(Some(stream)) => sinks.push(Box::new(RerunSink::new(stream, plan))),
            Ok(None) => failure = Some("no recording stream".to_string()),
            Err(e) => failure = Some(e),
        }
    }
    let rules = !study.stop.is_empty();
    if rules {
        let threshold = case.slip_rate_threshold();
        sinks.push(Box::new(StopRules::new(study.stop.clone(), threshold, &stop, interrupt, &fired)));
    }
    let options = LoopOptions { interrupt: if rules { Some(&stop) } else { interrupt }, ..LoopOptions::for_case(case) };
    let outcome = match &failure {
        Some(_) => None,
        None => Some(run(scene.as_mut(), &case.time, &mut sinks, options)),
    };
    drop(sinks);
    if study.recordings && rrd.is_file() {
        // A compaction that fails leaves the recording as written, which is complete.
        let _ = crate::record::compact::compact_if_worthwhile(&rrd);
    }
    let segments = layout.segments.len();
    let (mut written, catalog) = match outcome {
        None => (record("failed", failure, segments), None),
        Some(Outcome::Completed { catalog, .. }) => (record("completed", None, segments), Some(catalog)),
        Some(Outcome::Failed { error, catalog }) => {
            (record("failed", Some(error.to_string()), segments), Some(catalog))
        }
        Some(Outcome::Interrupted { catalog, .. }) if fired.get().is_some() => {
            (record(&format!("stopped {}", fired.get().expect("checked")), None, segments), Some(catalog))
        }
        Some(Outcome::Interrupted { .. }) => return Ok(None),
        Some(Outcome::Sink(e)) => (record("failed", Some(e.to_string()), segments), None),
    };
    let counts = catalog.as_ref().map_or((0, 0), |c| (c.events.len(), c.ruptures.len()));
    if let Some(catalog) = &catalog {
        written.onset_structure = catalog.events.iter().map(|e| e.structure_before.unwrap_or(f64::NAN)).collect();
    }
    for path in named.iter().map(|n| n.path).filter(|p| p.is_file()) {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        written.outputs.push((name, file_digest(path).map_err(Unrecorded::Unwritable)?));
    }
    seal(&done, written, dir).map(|r| Some((r, counts.0, counts.1))).map_err(Unrecorded::Unwritable)
}

/// Seals `record` ([`MemberRecord::sealed`]) and writes it to `path`.
fn seal(path: &Path, record: MemberRecord, dir: &Path) -> Result<MemberRecord, String> {
    let record = record.sealed()?;
    let text = toml::to_string(&record).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    write_atomically(path, &text)?;
    Ok(record)
}

/// Writes `text` beside `path` (under a name of this process's own) and renames it into place.
pub fn write_atomically(path: &Path, text: &str) -> Result<(), String> {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let temporary = path.with_file_name(format!(".{name}.{}.writing", std::process::id()));
    std::fs::write(&temporary, text).and_then(|()| std::fs::rename(&temporary, path)).map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        format!("cannot write {}: {e}", path.display())
    })
}
