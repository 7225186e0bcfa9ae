//! Checkpoints and `slipfront resume`: a run continued from a checkpoint ends exactly as the
//! uninterrupted run does (its catalogs byte for byte, its recording and log row for row, its
//! final state bit for bit, its adaptive steps one for one), whether it was stopped by the
//! checkpoint's own schedule, killed with SIGKILL, or finished and then extended; and every
//! damaged or foreign checkpoint is refused with exit 2 and a message.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use common::{binary, case_path};
use slipfront::record::checkpoint;

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slipfront-ckpt-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(args: &[&str]) -> Output {
    binary().args(args).output().unwrap()
}

fn ok(output: Output, what: &str) -> Output {
    assert!(output.status.success(), "{what}: {}", String::from_utf8_lossy(&output.stderr));
    output
}

/// `slipfront run cases/paper_triangular.toml` into `dir` with `extra` arguments.
fn run_paper(dir: &Path, extra: &[&str]) {
    let case = case_path("paper_triangular.toml");
    let mut args = vec!["run", case.as_str(), "--quiet", "--out-dir", dir.to_str().unwrap()];
    args.extend_from_slice(extra);
    ok(run(&args), &format!("run {extra:?}"));
}

fn resume(checkpoint: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["resume", checkpoint.to_str().unwrap(), "--quiet"];
    args.extend_from_slice(extra);
    run(&args)
}

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The two runs' catalogs are the same bytes.
fn assert_same_catalogs(a: &Path, b: &Path) {
    for name in ["paper_triangular.events.csv", "paper_triangular.ruptures.csv"] {
        let (x, y) = (read(&a.join(name)), read(&b.join(name)));
        assert!(x.len() > 100, "{name} holds events");
        assert!(x == y, "{name} differs between {} and {}", a.display(), b.display());
    }
}

/// The two recordings hold the same recording id and the same rows of every series, and
/// `slipfront check` passes the second.
fn assert_same_recordings(a: &Path, b: &Path) {
    let (x, y) = (slipfront::inspect::rrd::read(a).unwrap(), slipfront::inspect::rrd::read(b).unwrap());
    assert!(x.problem.is_none() && y.problem.is_none(), "{:?} {:?}", x.problem, y.problem);
    assert_eq!(x.recording_id, y.recording_id, "one run, one recording id");
    assert_eq!(x.series.keys().collect::<Vec<_>>(), y.series.keys().collect::<Vec<_>>());
    for (name, series) in &x.series {
        let other = &y.series[name];
        assert_eq!(series.steps, other.steps, "{name}: steps");
        assert_eq!(series.times, other.times, "{name}: times");
        let same = series.values.iter().zip(&other.values).all(|(p, q)| p.to_bits() == q.to_bits());
        assert!(same, "{name}: values");
    }
    ok(run(&["check", b.to_str().unwrap()]), "check of the resumed recording");
    official(&["rrd", "verify"], &[b], "verified without error");
    // Rerun's own comparison of the data of two recordings (all but the log_time timeline),
    // after Rerun's own compaction of each into one chunk per entity: the runs hand their rows
    // to the file in chunks whose bounds a checkpoint moves (it flushes what is buffered), and
    // `rrd compare` compares chunk by chunk, in order unless `--unordered` (the static styles
    // the two logged at their starts compact in different orders).
    let merged = |path: &Path| {
        let out = path.with_extension("merged.rrd");
        let limits = ["--max-rows", "1000000000", "--max-rows-if-unsorted", "1000000000", "--max-size", "4GiB"];
        official(&[&["rrd", "optimize"][..], &limits, &["-o", out.to_str().unwrap()]].concat(), &[path], "");
        out
    };
    let (merged_a, merged_b) = (merged(a), merged(b));
    if merged_a.is_file() && merged_b.is_file() {
        official(&["rrd", "compare", "--unordered"], &[&merged_a, &merged_b], "");
    }
}

/// Runs the official `rerun` CLI (`python3 -m rerun ARGS PATHS`) and requires success and
/// `says` in its output; skipped, with a message, where the SDK is not installed and the
/// environment does not require it.
fn official(args: &[&str], paths: &[&Path], says: &str) {
    let output = Command::new("python3").args(["-m", "rerun"]).args(args).args(paths).output();
    let text = output
        .as_ref()
        .map(|o| format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)));
    match (&output, &text) {
        (Ok(_), Ok(text)) if text.contains("No module named rerun") => skip("the `rerun` CLI"),
        (Ok(out), Ok(text)) => {
            let cut = (0..=text.len().min(4000)).rev().find(|&k| text.is_char_boundary(k)).unwrap_or(0);
            assert!(out.status.success(), "rerun {args:?} failed:\n{}", &text[..cut]);
            assert!(text.contains(says), "{text}");
        }
        _ => skip("python3"),
    }
}

fn skip(what: &str) {
    assert!(
        std::env::var_os("SLIPFRONT_REQUIRE_OFFICIAL_TOOLS").is_none(),
        "{what} is required (SLIPFRONT_REQUIRE_OFFICIAL_TOOLS is set) but missing"
    );
    eprintln!("SKIPPED: {what} (pip install \"rerun-sdk[datafusion]==0.36.*\") is not installed");
}

/// The final state (scene and catalog detector) of two checkpoints is the same, bit for bit;
/// for an adaptive method that includes its counts of accepted and rejected steps.
fn assert_same_final_state(a: &Path, b: &Path) {
    let (x, y) = (checkpoint::read(a).unwrap(), checkpoint::read(b).unwrap());
    let bits = |c: &checkpoint::Checkpoint| postcard::to_stdvec(&(&c.run.scene, &c.run.detector, c.run.steps)).unwrap();
    assert!(bits(&x) == bits(&y), "the final states of {} and {} differ", a.display(), b.display());
}

/// Runs the paper case to 600 s with `method`, checkpointing every 300 s and keeping them;
/// resumes from the 300 s one into another folder; both end alike.
fn resumed_from_the_middle(method: &str) {
    let (whole, resumed) = (scratch(&format!("{method}-whole")), scratch(&format!("{method}-resumed")));
    let integrator = format!("time.integrator={method}");
    let common = ["--set", integrator.as_str(), "--set", "time.t_end=600", "--checkpoint-every", "300"];
    run_paper(
        &whole,
        &[&common[..], &["--keep-checkpoints", "--mcap", whole.join("paper_triangular.mcap").to_str().unwrap()]]
            .concat(),
    );
    let middle = kept_checkpoints(&whole).into_iter().next().expect("a kept checkpoint");
    let (time, _) = checkpoint::read(&middle).unwrap().time_and_step();
    assert!((300.0..300.5).contains(&time), "the checkpoint is taken at the first step past 300 s, not {time}");
    ok(resume(&middle, &["--out-dir", resumed.to_str().unwrap()]), "resume");
    assert_same_catalogs(&whole, &resumed);
    assert_same_final_state(&whole.join("paper_triangular.ckpt"), &resumed.join("paper_triangular.ckpt"));
    assert_same_recordings(&whole.join("paper_triangular.rrd"), &resumed.join("paper_triangular.rrd"));
    assert_same_logs(&whole.join("paper_triangular.mcap"), &resumed.join("paper_triangular.mcap"));
}

/// The checkpoints kept in `dir` (`<stem>.<T>s.ckpt`), by time.
fn kept_checkpoints(dir: &Path) -> Vec<PathBuf> {
    let mut kept: Vec<(f64, PathBuf)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().ends_with("s.ckpt"))
        .map(|p| (checkpoint::read(&p).unwrap().time_and_step().0, p))
        .collect();
    kept.sort_by(|a, b| a.0.total_cmp(&b.0));
    kept.into_iter().map(|(_, p)| p).collect()
}

/// The two MCAP logs hold the same messages (topic, sequence, time, bytes).
fn assert_same_logs(a: &Path, b: &Path) {
    let messages = |path: &Path| -> Vec<(String, u32, u64, Vec<u8>)> {
        let bytes = read(path);
        mcap::MessageStream::new(&bytes)
            .unwrap()
            .map(|m| {
                let m = m.unwrap();
                (m.channel.topic.clone(), m.sequence, m.log_time, m.data.to_vec())
            })
            .collect()
    };
    let (x, y) = (messages(a), messages(b));
    assert!(x.len() > 1000, "the log holds the run");
    assert!(x == y, "the logs differ: {} against {} messages", x.len(), y.len());
}

#[test]
fn wilson_resumed_from_its_middle_checkpoint_ends_as_the_uninterrupted_run() {
    resumed_from_the_middle("wilson");
}

#[test]
fn central_differences_resumed_from_the_middle_end_as_the_uninterrupted_run() {
    resumed_from_the_middle("central");
}

#[test]
fn tsit5_resumed_from_the_middle_takes_the_same_adaptive_steps() {
    resumed_from_the_middle("tsit5");
}

#[test]
fn sdirk4_resumed_from_the_middle_takes_the_same_adaptive_steps() {
    resumed_from_the_middle("sdirk4");
}

#[test]
fn cycle_steps_resumed_from_the_middle_take_the_same_steps() {
    resumed_from_the_middle("cycle");
}

#[test]
fn a_run_killed_with_sigkill_resumes_to_the_uninterrupted_catalogs() {
    let (whole, killed) = (scratch("kill-whole"), scratch("kill-killed"));
    let common = ["--set", "time.integrator=wilson", "--set", "time.t_end=600"];
    run_paper(&whole, &common);
    let case = case_path("paper_triangular.toml");
    let mut child = binary()
        .args(["run", &case, "--quiet", "--out-dir", killed.to_str().unwrap(), "--checkpoint-every", "50"])
        .args(common)
        .spawn()
        .unwrap();
    let latest = killed.join("paper_triangular.ckpt");
    let start = Instant::now();
    while !latest.exists() {
        assert!(start.elapsed() < Duration::from_secs(60), "no checkpoint within 60 s");
        std::thread::sleep(Duration::from_millis(2));
    }
    assert!(child.try_wait().unwrap().is_none(), "the run must still be going when it is killed");
    let sent = Command::new("kill").args(["-KILL", &child.id().to_string()]).status().unwrap();
    assert!(sent.success());
    let status = child.wait().unwrap();
    use std::os::unix::process::ExitStatusExt;
    assert_eq!(status.signal(), Some(9), "killed by SIGKILL");
    let (time, _) = checkpoint::read(&latest).unwrap().time_and_step();
    assert!(time < 600.0, "killed before the end, checkpoint at {time} s");
    ok(resume(&latest, &[]), "resume after SIGKILL");
    assert_same_catalogs(&whole, &killed);
    assert_same_recordings(&whole.join("paper_triangular.rrd"), &killed.join("paper_triangular.rrd"));
    let left: Vec<_> = std::fs::read_dir(&killed).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert!(!left.iter().any(|n| n.to_string_lossy().starts_with('.')), "no partial files left: {left:?}");
}

/// Every series of `extended` (a run to T resumed with a later `t_end`) holds the rows of
/// `longer` (the straight run) at the same steps, times and values, bit for bit; besides them
/// it may hold the first run's closing frame at T, and nothing else.
fn assert_same_series_at_shared_steps(longer: &Path, extended: &Path, t: f64) {
    let (x, y) = (slipfront::inspect::rrd::read(longer).unwrap(), slipfront::inspect::rrd::read(extended).unwrap());
    assert!(x.problem.is_none() && y.problem.is_none(), "{:?} {:?}", x.problem, y.problem);
    assert_eq!(x.series.keys().collect::<Vec<_>>(), y.series.keys().collect::<Vec<_>>());
    for (name, series) in &x.series {
        let rows = |s: &slipfront::inspect::Series| -> std::collections::BTreeMap<i64, (u64, u64)> {
            s.steps.iter().zip(&s.times).zip(&s.values).map(|((&k, t), v)| (k, (t.to_bits(), v.to_bits()))).collect()
        };
        let (straight, continued) = (rows(series), rows(&y.series[name]));
        assert!(straight.len() > 100, "{name}: {} rows", straight.len());
        for (step, row) in &straight {
            assert_eq!(continued.get(step), Some(row), "{name}: step {step} differs or is missing");
        }
        let extra: Vec<f64> = continued
            .iter()
            .filter(|(step, _)| !straight.contains_key(step))
            .map(|(_, (time, _))| f64::from_bits(*time))
            .collect();
        assert!(
            extra.iter().all(|&time| time == t) && extra.len() <= 1,
            "{name}: rows the straight run lacks: {extra:?}"
        );
    }
}

/// The paper case run to `t` with a checkpoint every `every` s, then extended by
/// `resume --set time.t_end=2t`, against the straight run to `2t`: the same catalogs, byte for
/// byte, and the same rows of every series. No step of the first run may depend on its end (a
/// step shortened to land on `t`, a step bound derived from `t_end`) nor on the checkpoints.
fn extended_as_the_longer_run(tag: &str, sets: &[&str], t: f64, every: f64) {
    let (longer, extended) = (scratch(&format!("extend-{tag}-long")), scratch(&format!("extend-{tag}")));
    let sets: Vec<String> = sets.iter().flat_map(|s| ["--set".to_string(), s.to_string()]).collect();
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let (end, twice, every) = (format!("time.t_end={t}"), format!("time.t_end={}", 2.0 * t), every.to_string());
    run_paper(&longer, &[&sets[..], &["--set", &twice]].concat());
    run_paper(&extended, &[&sets[..], &["--set", &end, "--checkpoint-every", &every]].concat());
    ok(resume(&extended.join("paper_triangular.ckpt"), &["--set", &twice]), "extend");
    assert_same_catalogs(&longer, &extended);
    let rrd = "paper_triangular.rrd";
    assert_same_series_at_shared_steps(&longer.join(rrd), &extended.join(rrd), t);
    ok(run(&["check", extended.join(rrd).to_str().unwrap()]), "check the extended recording");
}

#[test]
fn a_finished_run_extended_ends_as_the_longer_run_with_every_integrator() {
    // To 450 s (the first rupture, 420 to 430 s, inside the first run) and on to 900 s, where
    // the chaos after the first slips makes any difference in a step visible in the events.
    for method in ["wilson", "central", "tsit5", "sdirk4", "cycle"] {
        extended_as_the_longer_run(method, &[&format!("time.integrator={method}")], 450.0, 200.0);
    }
    // Wilson's adaptive steps (step doubling) are slow through the slips: to 250 and 500 s.
    extended_as_the_longer_run("wilson-adaptive", &["time.integrator=wilson", "time.tolerance=1e-4"], 250.0, 100.0);
}

/// Resuming `checkpoint` fails with exit 2 and a message containing `says`.
fn refused(checkpoint: &Path, extra: &[&str], says: &str) {
    let start = Instant::now();
    let output = resume(checkpoint, extra);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{}: {stderr}", checkpoint.display());
    assert!(stderr.contains(says), "{}: expected {says:?} in {stderr}", checkpoint.display());
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(start.elapsed() < Duration::from_secs(60));
}

#[test]
fn damaged_and_foreign_checkpoints_are_refused_with_a_message() {
    let dir = scratch("bad");
    let case = case_path("spring_block.toml");
    ok(
        run(&[
            "run",
            &case,
            "--quiet",
            "--out-dir",
            dir.to_str().unwrap(),
            "--set",
            "time.t_end=20",
            "--checkpoint-every",
            "10",
        ]),
        "spring block",
    );
    let good = dir.join("spring_block.ckpt");
    let bytes = read(&good);
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    };
    refused(&write("case.ckpt", &read(Path::new(&case))), &[], "is not a slipfront checkpoint");
    refused(&write("empty.ckpt", b""), &[], "is not a slipfront checkpoint");
    refused(&write("cut.ckpt", &bytes[..bytes.len() / 2]), &[], "cut short");
    let mut format = bytes.clone();
    format[8] = 9;
    refused(&write("format.ckpt", &format), &[], "format 9");
    // Every bit of the body is covered by the checksum; flips in the header are caught by the
    // magic, format, length or checksum checks.
    for at in [0, 8, 12, 20, 24, 25, bytes.len() / 2, bytes.len() - 1] {
        let mut flipped = bytes.clone();
        flipped[at] ^= 0x10;
        let path = write(&format!("flip-{at}.ckpt"), &flipped);
        let output = resume(&path, &[]);
        assert_eq!(
            output.status.code(),
            Some(2),
            "a bit flipped at byte {at}: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let mut parsed = checkpoint::read(&good).unwrap();
    parsed.info.written_by = "0.0.1".into();
    refused(
        &write("version.ckpt", &checkpoint::encode(&parsed.info, &parsed.run).unwrap()),
        &[],
        "written by slipfront 0.0.1",
    );
    let mut other = checkpoint::read(&good).unwrap();
    other.info.case.text = std::fs::read_to_string(case_path("paper_triangular.toml")).unwrap();
    refused(
        &write("other-case.ckpt", &checkpoint::encode(&other.info, &other.run).unwrap()),
        &[],
        "does not fit this case",
    );
    refused(&good, &["--set", "friction.mu_s=0.7"], "only time.t_end can change");
    refused(&good, &["--set", "time.t_end=5"], "lies before the checkpoint's time");
    refused(&good, &["--checkpoint-every", "0"], "--checkpoint-every 0");
    std::fs::remove_file(dir.join("spring_block.rrd")).unwrap();
    refused(&good, &[], "which is missing");
}

/// The resumed run steps from the checkpoint's state, not from the case's start: the same
/// checkpoint with every node's velocity changed by 1 mm/s ends with another catalog, while the
/// checkpoint as written ends with the uninterrupted one (the paper case slips first at 420 s,
/// after the checkpoint at 300 s).
#[test]
fn a_resumed_run_steps_from_the_state_its_checkpoint_holds() {
    let (whole, kicked) = (scratch("kick-whole"), scratch("kick-resumed"));
    let common = ["--set", "time.integrator=wilson", "--set", "time.t_end=600", "--no-rrd"];
    run_paper(&whole, &[&common[..], &["--checkpoint-every", "300", "--keep-checkpoints"]].concat());
    let middle = kept_checkpoints(&whole).into_iter().next().expect("a kept checkpoint");
    let mut saved = checkpoint::read(&middle).unwrap();
    let slipfront::scene::SceneMemory::Dynamic { system, .. } = &mut saved.run.scene else {
        panic!("the paper case is a body")
    };
    system.state.velocity.iter_mut().for_each(|v| *v += 1e-3);
    let path = kicked.join("kicked.ckpt");
    std::fs::write(&path, checkpoint::encode(&saved.info, &saved.run).unwrap()).unwrap();
    ok(resume(&path, &["--out-dir", kicked.to_str().unwrap()]), "resume the kicked checkpoint");
    let name = "paper_triangular.events.csv";
    let (original, changed) = (read(&whole.join(name)), read(&kicked.join(name)));
    assert!(changed.len() > 100, "the kicked run slips too");
    assert!(original != changed, "a changed state must change what follows");
}
