//! A full disk stops a run, never hangs it: on a 1 MiB tmpfs the paper case, with and without
//! an MCAP log, ends every time within seconds with exit 1 and the operating system's "No space
//! left on device", its catalogs finished, and its recording and log readable and valid up to
//! their last row (`slipfront check --partial`). A resume that fills the disk leaves every file
//! it would have replaced as it was.
//!
//! Rerun's own file writer hung here in some tries (its writer thread ended at the error while
//! a flush waited on it for ever), and in the others reported "File-writer thread shut down
//! prematurely" instead of the OS error; `slipfront::sink::recording_file` replaced it. The
//! race showed in about one try in three, so the test repeats the run 20 times each way.
//!
//! Mounting needs root (as in CI); elsewhere the test says it is skipped, unless
//! `SLIPFRONT_REQUIRE_TMPFS` is set, which makes a failed mount a failure.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::{binary, case_path};

/// A small tmpfs (1 MiB unless said) mounted for the test, unmounted when dropped.
struct Tiny(PathBuf);

impl Tiny {
    fn mount(tag: &str) -> Option<Self> {
        Self::mount_of(tag, "1M")
    }

    fn mount_of(tag: &str, size: &str) -> Option<Self> {
        let dir = std::env::temp_dir().join(format!("slipfront-full-disk-{tag}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mounted = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
            .arg(&dir)
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        if mounted {
            return Some(Self(dir));
        }
        let _ = std::fs::remove_dir(&dir);
        assert!(
            std::env::var_os("SLIPFRONT_REQUIRE_TMPFS").is_none(),
            "cannot mount a tmpfs (SLIPFRONT_REQUIRE_TMPFS is set): run as root"
        );
        eprintln!("SKIPPED: cannot mount a tmpfs here (needs root)");
        None
    }

    fn empty(&self) {
        for entry in std::fs::read_dir(&self.0).unwrap() {
            std::fs::remove_file(entry.unwrap().path()).unwrap();
        }
    }
}

impl Drop for Tiny {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
        let _ = std::fs::remove_dir(&self.0);
    }
}

/// Runs the paper case into `dir` with `extra` arguments, killing it after 60 s; returns its
/// exit code (None if killed), stderr and wall time.
fn run_into(dir: &Path, extra: &[&str]) -> (Option<i32>, String, Duration) {
    let start = Instant::now();
    let mut child = binary()
        .args(["run", &case_path("paper_triangular.toml"), "--quiet", "--out-dir", dir.to_str().unwrap()])
        .args(extra)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            break;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let output = child.wait_with_output().unwrap();
    (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned(), start.elapsed())
}

/// `slipfront check --partial FILE` passes.
fn passes_partial_check(path: &Path) {
    let output = binary().args(["check", "--partial"]).arg(path).output().unwrap();
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "check --partial {}:\n{text}{}",
        path.display(),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// A catalog CSV is finished: a header and whole lines of as many fields.
fn is_finished_csv(path: &Path) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(text.ends_with('\n'), "{} ends mid-line", path.display());
    let mut lines = text.lines();
    let fields = lines.next().expect("a header").split(',').count();
    assert!(fields > 3, "{}: header", path.display());
    for line in lines {
        assert_eq!(line.split(',').count(), fields, "{}: {line}", path.display());
    }
}

fn twenty_tries(with_mcap: bool) {
    let Some(tiny) = Tiny::mount(if with_mcap { "mcap" } else { "rrd" }) else { return };
    let mcap = tiny.0.join("paper.mcap");
    let args: Vec<&str> = if with_mcap { vec!["--mcap", mcap.to_str().unwrap()] } else { Vec::new() };
    for attempt in 1..=20 {
        tiny.empty();
        let (code, stderr, wall) = run_into(&tiny.0, &args);
        assert_eq!(code, Some(1), "try {attempt}: exit {code:?} after {wall:?}: {stderr}");
        assert!(wall < Duration::from_secs(10), "try {attempt} took {wall:?}: {stderr}");
        assert!(stderr.contains("No space left on device"), "try {attempt}: {stderr}");
        assert!(!stderr.contains("panicked"), "try {attempt}: {stderr}");
        is_finished_csv(&tiny.0.join("paper_triangular.events.csv"));
        is_finished_csv(&tiny.0.join("paper_triangular.ruptures.csv"));
        passes_partial_check(&tiny.0.join("paper_triangular.rrd"));
        if with_mcap {
            passes_partial_check(&mcap);
        }
    }
}

#[test]
fn a_full_disk_stops_the_run_with_the_os_error_twenty_times_in_a_row() {
    twenty_tries(false);
}

#[test]
fn a_full_disk_stops_the_run_and_its_mcap_log_twenty_times_in_a_row() {
    twenty_tries(true);
}

/// The sha256 of every file in `dir`, by name.
fn fingerprint(dir: &Path) -> Vec<String> {
    let mut names: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    names.sort();
    let output = Command::new("sha256sum").args(&names).output().unwrap();
    assert!(output.status.success());
    String::from_utf8(output.stdout).unwrap().lines().map(str::to_string).collect()
}

#[test]
fn a_full_disk_during_a_resume_leaves_every_output_as_it_was() {
    // The paper case to 600 s with its log (7 MB), checkpointed at 300 s, run on a 16 MiB tmpfs,
    // which a file then fills but for 1.5 MB: too little for the resume's continued recording
    // and log, written beside the files they would replace.
    let Some(tiny) = Tiny::mount_of("resume", "16M") else { return };
    let mcap = tiny.0.join("paper_triangular.mcap");
    let (code, stderr, _) = run_into(
        &tiny.0,
        &[
            "--set",
            "time.t_end=600",
            "--checkpoint-every",
            "300",
            "--keep-checkpoints",
            "--mcap",
            mcap.to_str().unwrap(),
        ],
    );
    assert_eq!(code, Some(0), "{stderr}");
    fill_but(&tiny.0.join("filler"), 1_500_000);
    let before = fingerprint(&tiny.0);
    for attempt in 1..=3 {
        let output =
            binary().arg("resume").arg(tiny.0.join("paper_triangular.300s.ckpt")).arg("--quiet").output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(fingerprint(&tiny.0), before, "try {attempt}: the failed resume changed the outputs: {stderr}");
        assert_eq!(output.status.code(), Some(1), "try {attempt}: {stderr}");
        assert!(stderr.contains("No space left on device") && stderr.contains("nothing was changed"), "{stderr}");
    }
    passes_check(&tiny.0.join("paper_triangular.rrd"));
}

/// Writes `path` until the disk is full, then shortens it by `free` bytes.
fn fill_but(path: &Path, free: u64) {
    use std::io::Write;
    let mut file = std::fs::File::create(path).unwrap();
    let block = vec![0u8; 1 << 16];
    while file.write_all(&block).is_ok() {}
    let len = file.metadata().unwrap().len();
    file.set_len(len.saturating_sub(free)).unwrap();
}

/// `slipfront check FILE` passes.
fn passes_check(path: &Path) {
    let output = binary().arg("check").arg(path).output().unwrap();
    assert!(output.status.success(), "check {}: {}", path.display(), String::from_utf8_lossy(&output.stdout));
}

/// Fills the file system of `dir` with a file of zeros until it refuses more.
fn fill(dir: &Path) {
    use std::io::Write;
    let mut filler = std::fs::File::create(dir.join("filler")).unwrap();
    let block = vec![0_u8; 4096];
    while filler.write_all(&block).is_ok() {}
}

#[test]
fn a_catalog_that_cannot_be_written_on_a_full_disk_keeps_what_it_held() {
    // The run writes each catalog's header when it starts and the whole catalog when it ends;
    // the end's write, with the disk full, must leave the header, not an empty file (which the
    // run's output lock then removed) or a line cut short.
    use slipfront::sink::catalog::write_catalog;
    let Some(tiny) = Tiny::mount("catalog") else { return };
    let path = tiny.0.join("run.events.csv");
    let header = "segment,onset_s\n";
    let whole = format!("{header}{}", "3,420.195505\n".repeat(1000));
    write_catalog(&path, header).unwrap();
    fill(&tiny.0);
    let error = write_catalog(&path, &whole).unwrap_err().0;
    assert!(error.contains("No space left on device"), "{error}");
    assert_eq!(std::fs::read_to_string(&path).unwrap(), header, "the catalog after the failed write");
    // With room again, the same write gives the whole catalog. The filler is emptied before it
    // is removed: a child that another test spawned while the filler was open may still hold a
    // copy of its descriptor until it executes, and an unlinked file frees its blocks only when
    // the last descriptor closes; emptied, its blocks are free at once.
    std::fs::File::create(tiny.0.join("filler")).unwrap();
    std::fs::remove_file(tiny.0.join("filler")).unwrap();
    write_catalog(&path, &whole).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), whole);
    // A catalog that does not start with what the file holds replaces it.
    write_catalog(&path, header).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), header);
}
