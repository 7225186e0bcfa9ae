//! `resume`, `study`, `check --expect` and `figures` under hostile use, one test per class of
//! failure. A refused, failed or killed resume leaves every output as it was (the sha256 of
//! every file before and after); a checkpoint resumes its own folder, wherever that is; every
//! file slipfront reads is refused unless it is a regular file within its cap; a study owns its
//! folder, trusts only the members that verify and reports failed members as failed; `figures`
//! refuses what `check` fails; mistakes in expectations and options are invalid input (exit 2).

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use common::{binary, case_path};

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slipfront-hostile-rs-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn code(output: &Output) -> i32 {
    output.status.code().unwrap_or(-1)
}

fn text(output: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr))
}

fn slipfront(args: &[&str]) -> Output {
    binary().args(args).output().unwrap()
}

/// Exit 2, `says` in the message, no panic.
fn assert_invalid(output: &Output, says: &str) {
    let all = text(output);
    assert_eq!(code(output), 2, "expected exit 2: {all}");
    assert!(all.contains(says), "expected {says:?} in: {all}");
    assert!(!all.contains("panicked"), "{all}");
}

/// The sha256 of every file in `dir`, hidden ones included, by name (a folder as `folder`).
fn fingerprint(dir: &Path) -> BTreeMap<String, String> {
    let name = |path: &Path| path.file_name().unwrap().to_string_lossy().into_owned();
    let (folders, mut files): (Vec<PathBuf>, Vec<PathBuf>) =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).partition(|p| p.is_dir());
    files.sort();
    let output = Command::new("sha256sum").args(&files).output().unwrap();
    assert!(output.status.success(), "sha256sum: {}", text(&output));
    let mut sums: BTreeMap<String, String> = String::from_utf8(output.stdout)
        .unwrap()
        .lines()
        .map(|line| {
            let (hash, path) = line.split_once("  ").unwrap();
            (name(Path::new(path)), hash.to_string())
        })
        .collect();
    sums.extend(folders.iter().map(|f| (name(f), "folder".to_string())));
    sums
}

/// Copies the files of `from` into a new folder `to`.
fn copy_folder(from: &Path, to: &Path) {
    let _ = std::fs::remove_dir_all(to);
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, to.join(path.file_name().unwrap())).unwrap();
    }
}

const STEM: &str = "paper_triangular";

fn file(dir: &Path, suffix: &str) -> PathBuf {
    dir.join(format!("{STEM}{suffix}"))
}

/// The paper case to 600 s (Wilson), checkpointed every 300 s and kept, with an MCAP log: the
/// folder every resume test starts from (made once, copied by each test).
fn original() -> &'static Path {
    static ORIGINAL: OnceLock<PathBuf> = OnceLock::new();
    ORIGINAL.get_or_init(|| {
        let dir = scratch("original");
        let mcap = file(&dir, ".mcap");
        let case = case_path("paper_triangular.toml");
        let output = slipfront(&[
            "run",
            &case,
            "--quiet",
            "--out-dir",
            dir.to_str().unwrap(),
            "--set",
            "time.t_end=600",
            "--set",
            "time.integrator=wilson",
            "--checkpoint-every",
            "300",
            "--keep-checkpoints",
            "--mcap",
            mcap.to_str().unwrap(),
        ]);
        assert_eq!(code(&output), 0, "{}", text(&output));
        dir
    })
}

/// A copy of [`original`] in a folder of its own, and its 300 s checkpoint.
fn copy_of_original(tag: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(tag);
    copy_folder(original(), &dir);
    let middle = file(&dir, ".300s.ckpt");
    (dir, middle)
}

fn resume(checkpoint: &Path, extra: &[&str]) -> Output {
    binary().arg("resume").arg(checkpoint).arg("--quiet").args(extra).output().unwrap()
}

/// Resuming `checkpoint` is refused (exit 2, `says`), and every file of `dir` is as it was.
fn refused_without_a_trace(dir: &Path, checkpoint: &Path, extra: &[&str], says: &str) {
    let before = fingerprint(dir);
    let output = resume(checkpoint, extra);
    assert_invalid(&output, says);
    assert_eq!(fingerprint(dir), before, "a refused resume changed the folder: {}", text(&output));
}

#[test]
fn a_resume_refused_for_a_foreign_cut_or_flipped_recording_changes_no_file() {
    // Another run's recording beside the checkpoint.
    let (dir, middle) = copy_of_original("foreign");
    let other = scratch("foreign-other");
    let case = case_path("paper_triangular.toml");
    let output = slipfront(&["run", &case, "--quiet", "--out-dir", other.to_str().unwrap(), "--set", "time.t_end=400"]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    std::fs::copy(file(&other, ".rrd"), file(&dir, ".rrd")).unwrap();
    refused_without_a_trace(&dir, &middle, &[], "is the recording of another run");
    // Another run's log.
    let (dir, middle) = copy_of_original("foreign-log");
    let log = other.join("log.mcap");
    let output = slipfront(&[
        "run",
        &case,
        "--quiet",
        "--out-dir",
        other.to_str().unwrap(),
        "--set",
        "time.t_end=400",
        "--mcap",
        log.to_str().unwrap(),
    ]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    std::fs::copy(&log, file(&dir, ".mcap")).unwrap();
    refused_without_a_trace(&dir, &middle, &[], "is the MCAP log of another run");
    // A recording and a log cut before the checkpoint's step (300 s of 600 s). Both hold their
    // rows in time order, and the first 300 s (600 rows in stick) lie in the first tenth of the
    // recording's bytes (every step after the first slips at 420 s is a row); the log's first
    // chunk, up to 2 048 rows, reaches past them. The refusal says "cut short" whether the cut leaves
    // the log's run header readable (which depends on when the wall-clock cadence flushed) or
    // not.
    for (suffix, fraction) in [(".rrd", 10), (".mcap", 8)] {
        let (dir, middle) = copy_of_original(&format!("cut{suffix}"));
        let path = file(&dir, suffix);
        let bytes = std::fs::read(&path).unwrap();
        std::fs::write(&path, &bytes[..bytes.len() / fraction]).unwrap();
        refused_without_a_trace(&dir, &middle, &[], "cut short");
    }
}

/// What a resume over the recording with the byte at `at` flipped did: refused it (exit 2,
/// nothing changed) or left the flip behind (exit 0, the uninterrupted run's series and
/// catalogs, the flip outside the rows up to the checkpoint); anything else fails.
fn resume_over_a_flip(tag: &str, bytes: &[u8], at: usize) -> bool {
    let whole = original();
    let (dir, middle) = copy_of_original(tag);
    let mut flipped = bytes.to_vec();
    flipped[at] ^= 0x10;
    std::fs::write(file(&dir, ".rrd"), &flipped).unwrap();
    let before = fingerprint(&dir);
    let output = resume(&middle, &[]);
    let all = text(&output);
    assert!(!all.contains("panicked"), "a flip at byte {at}: {all}");
    let refused = match code(&output) {
        2 => {
            assert!(all.contains("nothing was changed"), "a flip at byte {at}: {all}");
            assert_eq!(fingerprint(&dir), before, "a flip at byte {at}: a refused resume changed the folder");
            true
        }
        0 => {
            // The flip lay outside the series' rows up to the checkpoint (in a static part,
            // written again, or in rows past it, not copied): the continued recording holds
            // the uninterrupted run's series, row for row.
            let check = slipfront(&["check", file(&dir, ".rrd").to_str().unwrap()]);
            assert_eq!(code(&check), 0, "a flip at byte {at}: {}", text(&check));
            let read = |path: &Path| slipfront::inspect::rrd::read(path).unwrap().series;
            assert!(read(&file(&dir, ".rrd")) == read(&file(whole, ".rrd")), "a flip at byte {at} spread");
            for suffix in [".events.csv", ".ruptures.csv"] {
                assert_eq!(std::fs::read(file(&dir, suffix)).unwrap(), std::fs::read(file(whole, suffix)).unwrap());
            }
            false
        }
        other => panic!("a flip at byte {at}: exit {other}: {all}"),
    };
    std::fs::remove_dir_all(&dir).unwrap();
    refused
}

#[test]
fn a_flipped_byte_in_the_recording_is_refused_or_left_behind_never_copied() {
    let bytes = std::fs::read(file(original(), ".rrd")).unwrap();
    // 24 offsets spread over the first sixteenth of the file, most of it the rows up to 300 s.
    let refused = (0..24)
        .filter(|k| resume_over_a_flip(&format!("flip-{k}"), &bytes, 1000 + k * (bytes.len() / 16 - 1000) / 24))
        .count();
    println!("{refused} of 24 flips refused, {} left behind", 24 - refused);
    assert!(refused >= 10, "{refused} of 24 flips refused, {} left behind", 24 - refused);
}

#[test]
fn a_message_under_another_recording_id_ends_what_is_the_runs() {
    // Every message names its run's recording id in plain bytes; a flip there makes that
    // message another run's. Early in the file (a row up to the checkpoint) the resume is
    // refused; late (past it) the message is left behind. Eight of them, spread over the file.
    let bytes = std::fs::read(file(original(), ".rrd")).unwrap();
    let id = slipfront::inspect::rrd::read(&file(original(), ".rrd")).unwrap().recording_id.unwrap();
    let at: Vec<usize> =
        bytes.windows(id.len()).enumerate().filter(|(_, w)| *w == id.as_bytes()).map(|(i, _)| i).collect();
    assert!(at.len() > 16, "the recording id occurs {} times", at.len());
    let picked: Vec<usize> = (1..=8).map(|k| at[k * (at.len() - 1) / 8]).collect();
    let refused =
        picked.iter().enumerate().filter(|(k, at)| resume_over_a_flip(&format!("id-{k}"), &bytes, **at)).count();
    println!("{refused} of 8 flipped ids refused");
    assert!(refused >= 1, "no flipped id early enough to be refused: {picked:?} of {}", bytes.len());
}

/// Starts `slipfront resume` of `checkpoint` to 3000 s, writing a checkpoint every 100 s.
fn long_resume(checkpoint: &Path) -> std::process::Child {
    binary()
        .arg("resume")
        .arg(checkpoint)
        .args(["--quiet", "--set", "time.t_end=3000", "--checkpoint-every", "100"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

#[test]
fn a_resume_killed_at_any_moment_leaves_every_output_as_it_was() {
    // The resume from 300 s to 3000 s takes seconds; SIGKILL at moments from its start, while it
    // copies the earlier rows, and while it runs and checkpoints.
    let mut last = None;
    for wait in [10, 100, 300, 600, 1000, 1600, 2400] {
        let (dir, middle) = copy_of_original(&format!("kill-{wait}"));
        let before = fingerprint(&dir);
        let mut child = long_resume(&middle);
        std::thread::sleep(Duration::from_millis(wait));
        assert!(child.try_wait().unwrap().is_none(), "the resume ended before {wait} ms");
        child.kill().unwrap();
        child.wait().unwrap();
        let after: BTreeMap<String, String> =
            fingerprint(&dir).into_iter().filter(|(name, _)| !name.starts_with('.')).collect();
        assert_eq!(after, before, "killed after {wait} ms: the outputs changed");
        if let Some((dir, _)) = last.replace((dir, middle)) {
            std::fs::remove_dir_all(dir).unwrap();
        }
    }
    // The files the last one was writing are cleared by the next resume, which ends as one run
    // would.
    let (dir, middle) = last.unwrap();
    let output = resume(&middle, &[]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    let left: Vec<String> = fingerprint(&dir).into_keys().filter(|n| n.starts_with('.')).collect();
    assert!(left.is_empty(), "files left behind: {left:?}");
    for suffix in [".events.csv", ".ruptures.csv"] {
        assert!(std::fs::read(file(&dir, suffix)).unwrap() == std::fs::read(file(original(), suffix)).unwrap());
    }
    assert_eq!(code(&slipfront(&["check", file(&dir, ".rrd").to_str().unwrap()])), 0);
}

#[test]
fn a_copied_or_moved_folder_resumes_in_place_and_never_touches_another() {
    let (a, _) = copy_of_original("copied-a");
    let before = fingerprint(&a);
    let b = scratch("copied-b");
    copy_folder(&a, &b);
    let output = resume(&file(&b, ".300s.ckpt"), &["--set", "time.t_end=700"]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    assert_eq!(fingerprint(&a), before, "resuming the copy changed the original folder");
    let check = slipfront(&["check", file(&b, ".rrd").to_str().unwrap()]);
    assert!(text(&check).contains("up to t = 700 s"), "the copy was extended in place: {}", text(&check));
    // A moved folder resumes where it is; the folder it came from is not made again.
    let moved = scratch("moved");
    std::fs::remove_dir(&moved).unwrap();
    std::fs::rename(&a, &moved).unwrap();
    let output = resume(&file(&moved, ".300s.ckpt"), &[]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    assert!(!a.exists(), "resuming a moved folder made the old one again");
    // An output missing: refused, nothing made.
    std::fs::remove_file(file(&moved, ".rrd")).unwrap();
    refused_without_a_trace(&moved, &file(&moved, ".300s.ckpt"), &[], "which is missing");
    assert!(!a.exists());
}

/// Runs `command`, killing it after `limit`; returns its output and whether it ended by itself.
fn bounded(mut command: Command, limit: Duration) -> (Output, bool) {
    let mut child = command.stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() && start.elapsed() < limit {
        std::thread::sleep(Duration::from_millis(20));
    }
    let ended = child.try_wait().unwrap().is_some();
    if !ended {
        let _ = child.kill();
    }
    (child.wait_with_output().unwrap(), ended)
}

/// The largest resident set (bytes) of any child process of the tests so far.
fn largest_child() -> u64 {
    // SAFETY: getrusage writes the struct it is given.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    assert_eq!(unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage) }, 0);
    usage.ru_maxrss as u64 * 1024
}

/// The most memory a refusal may take: far below what reading a device for seconds takes,
/// far above what any command of these tests needs (the paper case runs in 200 MB).
const REFUSAL_MEMORY: u64 = 2 << 30;

/// `slipfront ARGS` ends within 10 s, without reading gigabytes, refused with exit 2 and `says`.
fn refused_at_once(args: &[&str], says: &str) {
    let mut command = binary();
    command.args(args);
    let (output, ended) = bounded(command, Duration::from_secs(10));
    assert!(ended, "slipfront {args:?} was still reading after 10 s");
    assert!(largest_child() < REFUSAL_MEMORY, "slipfront {args:?} read {} MB", largest_child() >> 20);
    assert_invalid(&output, says);
}

/// A named pipe at `path`.
fn fifo(path: &Path) {
    let made = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(made.success());
}

#[test]
fn every_reader_refuses_a_device_a_pipe_or_an_oversized_file_before_reading_it() {
    let dir = scratch("readers");
    let pipe = dir.join("pipe");
    fifo(&pipe);
    let pipe = pipe.to_str().unwrap();
    let spring = case_path("spring_block.toml");
    let recording = dir.join("spring_block.rrd");
    let output = slipfront(&["run", &spring, "--quiet", "--out-dir", dir.to_str().unwrap(), "--set", "time.t_end=5"]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    let rrd = recording.to_str().unwrap();
    for input in ["/dev/zero", pipe] {
        let what = if input == pipe { "a named pipe (FIFO), not a regular file" } else { "a character device" };
        refused_at_once(&["resume", input], what);
        let study = dir.join("s.toml");
        std::fs::write(&study, format!("case = \"{input}\"\n")).unwrap();
        refused_at_once(&["study", study.to_str().unwrap(), "--out-dir", dir.to_str().unwrap()], what);
        refused_at_once(&["check", rrd, "--expect", input], what);
        refused_at_once(&["study", input, "--out-dir", dir.to_str().unwrap()], what);
        refused_at_once(&["check", input], what);
        refused_at_once(&["figures", input, "--out", dir.to_str().unwrap()], what);
        refused_at_once(&["replay", input], what);
        refused_at_once(&["run", input, "--out-dir", dir.to_str().unwrap()], what);
    }
    // Regular files over their caps (sparse: nothing is written, and nothing must be read).
    for (name, size, args, says) in [
        ("big.ckpt", 5u64 << 30, vec!["resume"], "it is larger than 4 GiB"),
        ("big-study.toml", 5 << 20, vec!["study"], "it is larger than 4 MiB"),
        ("big-expect.toml", 5 << 20, vec!["check", rrd, "--expect"], "it is larger than 4 MiB"),
    ] {
        let path = dir.join(name);
        std::fs::File::create(&path).unwrap().set_len(size).unwrap();
        let mut all = args.clone();
        all.push(path.to_str().unwrap());
        refused_at_once(&all, says);
    }
}

#[test]
fn a_study_resume_over_a_record_linked_to_a_device_runs_the_member_again() {
    let dir = scratch("record-link");
    let study = small_study(&dir, "points", POINTS);
    let out = dir.join("out");
    let output = study_command(&study, &out, &["--quiet"]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    let record = out.join("points/member-0001.done.toml");
    std::fs::remove_file(&record).unwrap();
    std::os::unix::fs::symlink("/dev/zero", &record).unwrap();
    let mut command = binary();
    command.arg("study").arg(&study).arg("--out-dir").arg(&out).arg("--resume");
    let (output, ended) = bounded(command, Duration::from_secs(20));
    assert!(ended, "study --resume read /dev/zero for 20 s");
    assert!(largest_child() < REFUSAL_MEMORY, "study --resume read {} MB", largest_child() >> 20);
    assert_eq!(code(&output), 0, "{}", text(&output));
    assert!(text(&output).contains("1 whose record or outputs do not verify"), "{}", text(&output));
    assert!(text(&output).contains("a character device"), "{}", text(&output));
    assert!(std::fs::symlink_metadata(&record).unwrap().is_file(), "the member wrote its record again");
}

/// The study file `<name>.toml` in `dir`, `body` with `CRATE` standing for the crate's folder.
fn small_study(dir: &Path, name: &str, body: &str) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, body.replace("CRATE", env!("CARGO_MANIFEST_DIR"))).unwrap();
    path
}

/// Three spring-block members, a second each.
const POINTS: &str = "case = \"CRATE/cases/spring_block.toml\"\n[set]\n\"time.t_end\" = 30.0\n\
                      [sweep]\n\"scene.stiffness\" = [250.0, 500.0, 1000.0]\n";

/// The paper case for its 1000 s (so that its verdicts and `summary.png` are made), 2 rows of 2
/// members.
const PAPER: &str = "case = \"CRATE/cases/paper_triangular.toml\"\n[set]\n\"time.t_end\" = 1000.0\n\
                     [ensemble]\nkey = \"friction.structure0\"\nstep = -1.0e-9\n\
                     members = 2\n[sweep]\n\"scene.normal_traction.left\" = [300.0, 350.0]\n";

fn study_command(study: &Path, out: &Path, extra: &[&str]) -> Output {
    binary().arg("study").arg(study).arg("--out-dir").arg(out).args(extra).output().unwrap()
}

/// The files of a study folder that do not depend on Rerun's random chunk ids: the catalogs,
/// the tables and the figure.
fn tables(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            name.ends_with(".csv") || name.starts_with("summary.")
        })
        .map(|p| (p.file_name().unwrap().to_string_lossy().into_owned(), std::fs::read(&p).unwrap()))
        .collect()
}

#[test]
fn a_second_study_into_the_same_folder_is_refused_and_shards_share_it() {
    let dir = scratch("two-studies");
    let study = small_study(&dir, "paper", PAPER);
    let out = dir.join("out");
    let mut first = binary()
        .arg("study")
        .arg(&study)
        .arg("--out-dir")
        .arg(&out)
        .args(["--jobs", "1", "--quiet"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !out.join("paper/member-0000.events.csv").exists() {
        assert!(start.elapsed() < Duration::from_secs(60), "the first study did not start");
        std::thread::sleep(Duration::from_millis(20));
    }
    for extra in [&[][..], &["--shard", "1/2"], &["--resume"]] {
        let output = study_command(&study, &out, extra);
        assert_invalid(&output, "is being written by another slipfront study");
    }
    // Another study file of the same name is refused the same way.
    let other = scratch("two-studies-other");
    let edited = small_study(&other, "paper", &PAPER.replace("1000.0", "990.0"));
    assert_invalid(&study_command(&edited, &out, &[]), "is being written by another slipfront study");
    let status = first.wait().unwrap();
    assert!(status.success(), "the first study failed");
    for k in 0..4 {
        let check = slipfront(&["check", out.join(format!("paper/member-000{k}.rrd")).to_str().unwrap()]);
        assert_eq!(code(&check), 0, "member {k}: {}", text(&check));
    }
    // Two shards at once share the folder, and make the whole study's tables.
    let shared = dir.join("shared");
    let shards: Vec<std::process::Child> = ["1/2", "2/2"]
        .iter()
        .map(|shard| {
            binary()
                .arg("study")
                .arg(&study)
                .arg("--out-dir")
                .arg(&shared)
                .args(["--jobs", "1", "--quiet", "--shard", shard])
                .spawn()
                .unwrap()
        })
        .collect();
    for mut shard in shards {
        assert!(shard.wait().unwrap().success());
    }
    let output = study_command(&study, &shared, &["--resume", "--quiet"]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    assert_eq!(tables(&shared.join("paper")), tables(&out.join("paper")), "the shards differ from one study");
}

/// A study record's values, edited, its digest made again as the study would (a careful
/// hand edit).
fn resealed(path: &Path, edit: impl FnOnce(&mut toml::Table)) {
    let mut table: toml::Table = std::fs::read_to_string(path).unwrap().parse().unwrap();
    edit(&mut table);
    let text = toml::to_string(&table).unwrap();
    let record: slipfront::study::record::MemberRecord = toml::from_str(&text).unwrap();
    std::fs::write(path, toml::to_string(&record.sealed().unwrap()).unwrap()).unwrap();
}

#[test]
fn study_resume_runs_again_every_member_whose_record_or_outputs_do_not_verify() {
    let dir = scratch("records");
    let study = small_study(&dir, "paper", PAPER);
    let clean = dir.join("clean");
    let output = study_command(&study, &clean, &["--quiet"]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    let expected = tables(&clean.join("paper"));
    assert!(expected.contains_key("summary.png"), "the paper's case for its 1000 s has its verdicts drawn");

    let out = dir.join("out");
    copy_folder(&clean.join("paper"), &out.join("paper"));
    let folder = out.join("paper");
    let record = |k: usize| folder.join(format!("member-000{k}.done.toml"));
    let edit = |k: usize, from: &str, to: &str| {
        let text = std::fs::read_to_string(record(k)).unwrap();
        assert!(text.contains(from), "{text}");
        std::fs::write(record(k), text.replacen(from, to, 1)).unwrap();
    };
    // Tampered: how a member's run ended, edited by hand.
    edit(0, "ending = \"completed\"", "ending = \"stopped by hand\"");
    // Out of range: a record of member 99.
    edit(1, "index = 1\n", "index = 99\n");
    // Orphaned: a record whose recording was deleted, and one whose catalog was edited.
    std::fs::remove_file(folder.join("member-0002.rrd")).unwrap();
    let events = folder.join("member-0003.events.csv");
    let catalog = std::fs::read_to_string(&events).unwrap();
    std::fs::write(&events, format!("{catalog}0,1,2,3,4,5,6\n")).unwrap();
    let output = study_command(&study, &out, &["--resume"]);
    let said = text(&output);
    assert_eq!(code(&output), 0, "{said}");
    assert!(tables(&folder) == expected, "the study mixed what did not verify into its tables: {said}");
    assert!(
        said.contains("--resume: 0 members verified and kept; to run: 4 whose record or outputs do not verify"),
        "{said}"
    );
    assert!(said.contains("member-0000.done.toml was changed after its member ran"), "{said}");
    let summary = String::from_utf8(expected["summary.md"].clone()).unwrap();
    assert!(summary.contains("4 of 4 members finished, 0 failed"), "{summary}");
    // A record of member 99 resealed, so that it verifies as a record: another member's.
    resealed(&record(1), |t| {
        t.insert("index".into(), toml::Value::Integer(99));
    });
    let output = study_command(&study, &out, &["--resume"]);
    let said = text(&output);
    assert_eq!(code(&output), 0, "{said}");
    assert!(
        said.contains("3 members verified and kept; to run: 1 of other parameters than the study file's"),
        "{said}"
    );
    assert_eq!(tables(&folder), expected);

    // Stale: the study file edited (another step, then fewer members) is resumed as the new
    // study: the members whose parameters changed run again, and the old ones are left out.
    let stepped = small_study(&dir, "paper", &PAPER.replace("-1.0e-9", "-2.0e-9"));
    let output = study_command(&stepped, &out, &["--resume"]);
    let said = text(&output);
    assert_eq!(code(&output), 0, "{said}");
    assert!(
        said.contains("2 members verified and kept; to run: 2 of other parameters than the study file's"),
        "{said}"
    );
    let events_table = std::fs::read_to_string(folder.join("events.csv")).unwrap();
    assert!(events_table.contains(",1.999999998,") && !events_table.contains(",1.999999999,"), "{events_table}");
    let fewer = small_study(&dir, "paper", &PAPER.replace("members = 2", "members = 1"));
    let output = study_command(&fewer, &out, &["--resume"]);
    let said = text(&output);
    assert_eq!(code(&output), 0, "{said}");
    assert!(said.contains("2 of 2 finished"), "{said}");
    assert!(said.contains("records of members the study no longer has are left out"), "{said}");
    let summary = std::fs::read_to_string(folder.join("summary.md")).unwrap();
    assert!(summary.contains("2 of 2 members finished"), "{summary}");
}

#[test]
fn failed_members_are_counted_apart_listed_with_their_error_and_run_again() {
    let dir = scratch("failing");
    // The paper case fails its first step at time.dt = 100 s or 50 s (the energy balance does
    // not close); at 0.01 s it runs.
    let study = small_study(
        &dir,
        "failing",
        "case = \"CRATE/cases/paper_triangular.toml\"\n[set]\n\"time.t_end\" = 300.0\n\
         \"time.integrator\" = \"wilson\"\n[sweep]\n\"time.dt\" = [0.01, 100.0, 50.0]\n",
    );
    let out = dir.join("out");
    let output = study_command(&study, &out, &[]);
    let said = text(&output);
    assert_eq!(code(&output), 1, "{said}");
    assert!(said.contains("1 of 3 finished, 2 failed"), "{said}");
    assert!(said.contains("2 members failed (their errors are in summary.md)"), "{said}");
    let summary = std::fs::read_to_string(out.join("failing/summary.md")).unwrap();
    assert!(summary.contains("1 of 3 members finished, 2 failed"), "{summary}");
    assert!(summary.contains("- members finished: 0 (0 completed, 0 stopped by a rule); failed: 1"), "{summary}");
    assert!(summary.contains("## Failed members"), "{summary}");
    assert!(summary.contains("- member-0001 (time.dt = 100.0): step 1 (t = 0 s): the energy balance does not close"));
    // Only the finished member is in the statistics and the events table.
    let events = std::fs::read_to_string(out.join("failing/events.csv")).unwrap();
    assert!(events.lines().skip(1).all(|l| l.starts_with("0,0,0,")), "{events}");
    let output = study_command(&study, &out, &["--resume"]);
    let said = text(&output);
    assert_eq!(code(&output), 1, "{said}");
    assert!(said.contains("--resume: 1 member verified and kept; to run: 2 failed before"), "{said}");
}

#[test]
fn figures_refuses_a_recording_that_check_fails() {
    let dir = scratch("figures");
    let spring = case_path("spring_block.toml");
    let output = slipfront(&[
        "run",
        &spring,
        "--quiet",
        "--out-dir",
        dir.to_str().unwrap(),
        "--set",
        "time.t_end=20",
        "--set",
        "time.integrator=wilson",
    ]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    let bytes = std::fs::read(dir.join("spring_block.rrd")).unwrap();
    // A one-bit change of a value that still decodes: only the series digests see it. Mutants
    // that would abort the decoder are weeded out in a child first, as `check` does.
    let mutant = dir.join("mutant.rrd");
    let flipped = (0..1000)
        .map(|k| {
            let mut copy = bytes.clone();
            copy[k * bytes.len() / 1000] ^= 1 << (k % 8);
            copy
        })
        .find(|copy| {
            std::fs::write(&mutant, copy).unwrap();
            let decoded = binary().arg("__decode-rrd").arg(&mutant).status().unwrap().success();
            let Some(recording) = decoded.then(|| slipfront::inspect::rrd::from_bytes(copy, "x").ok()).flatten() else {
                return false;
            };
            let report = slipfront::inspect::check::check(&recording, &Default::default());
            recording.problem.is_none() && report.problems.iter().any(|p| p.contains("differ from the digest"))
        })
        .expect("a flip that changes a value and still decodes");
    let damaged = dir.join("damaged.rrd");
    std::fs::write(&damaged, flipped).unwrap();
    assert_eq!(code(&slipfront(&["check", damaged.to_str().unwrap()])), 1);
    let figures = dir.join("figures");
    let output = slipfront(&["figures", damaged.to_str().unwrap(), "--out", figures.to_str().unwrap()]);
    assert_eq!(code(&output), 1, "{}", text(&output));
    assert!(text(&output).contains("fails `slipfront check`") && text(&output).contains("no figures drawn"));
    assert!(!figures.exists() || std::fs::read_dir(&figures).unwrap().next().is_none(), "figures were drawn");
}

#[test]
fn mistakes_in_expectations_and_options_are_invalid_input_and_leave_nothing_behind() {
    let dir = scratch("smaller");
    let spring = case_path("spring_block.toml");
    let output = slipfront(&["run", &spring, "--quiet", "--out-dir", dir.to_str().unwrap(), "--set", "time.t_end=5"]);
    assert_eq!(code(&output), 0, "{}", text(&output));
    let rrd = dir.join("spring_block.rrd");
    let expect = dir.join("expect.toml");
    for (body, says) in [
        ("entity = \"contact/frcition_force\"\ntime = 1.0\nmin = 0.0\n", "is not a series of this recording"),
        ("entity = \"contact/friction_force\"\ntime = 1.0\n", "at[0] gives neither min nor max"),
    ] {
        std::fs::write(&expect, format!("[[at]]\n{body}")).unwrap();
        assert_invalid(&slipfront(&["check", rrd.to_str().unwrap(), "--expect", expect.to_str().unwrap()]), says);
    }
    // A refused resume option leaves no file behind.
    let (dir, middle) = copy_of_original("every-0");
    refused_without_a_trace(&dir, &middle, &["--checkpoint-every", "0"], "--checkpoint-every 0");
    // A kept checkpoint's name taken by a folder: named in the message, no partial file left.
    let (dir, middle) = copy_of_original("kept-folder");
    std::fs::remove_file(file(&dir, ".600s.ckpt")).unwrap();
    std::fs::create_dir(file(&dir, ".600s.ckpt")).unwrap();
    let before = fingerprint(&dir);
    let output = resume(&middle, &["--keep-checkpoints"]);
    assert_eq!(code(&output), 1, "{}", text(&output));
    let name = file(&dir, ".600s.ckpt");
    assert!(text(&output).contains(&format!("cannot keep the checkpoint as {}: it is not a file", name.display())));
    assert_eq!(fingerprint(&dir), before, "the failed resume changed the folder");
    let run_dir = scratch("kept-folder-run");
    std::fs::create_dir(run_dir.join("spring_block.5s.ckpt")).unwrap();
    let output = slipfront(&[
        "run",
        &spring,
        "--quiet",
        "--out-dir",
        run_dir.to_str().unwrap(),
        "--set",
        "time.t_end=10",
        "--checkpoint-every",
        "5",
        "--keep-checkpoints",
    ]);
    assert_eq!(code(&output), 1, "{}", text(&output));
    assert!(text(&output).contains("spring_block.5s.ckpt: it is not a file"), "{}", text(&output));
    let left: Vec<String> = fingerprint(&run_dir).into_keys().filter(|n| n.ends_with(".writing")).collect();
    assert!(left.is_empty(), "{left:?}");
}
