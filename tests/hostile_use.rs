//! Hostile use of the command line, one test per class of failure: outputs that would clobber
//! each other, their inputs or another run's; standard output closed or full; the signals a
//! batch system or a closed terminal sends; expectations, selections and derived bounds that
//! validation must judge exactly; a case file that is no case file. Each class fails (exit 0
//! with a corrupt file, a panic, a hang or a refusal of valid input) without the mechanism
//! that this test pins.

use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;

use common::{binary, case_path as case};

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slipfront-hostile-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn code(output: &Output) -> i32 {
    output.status.code().unwrap_or(-1)
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// `slipfront run CASE --quiet --out-dir DIR ARGS...` with a short spring block by default.
fn run(case_path: &str, dir: &Path, args: &[&str]) -> Output {
    binary().arg("run").arg(case_path).arg("--quiet").arg("--out-dir").arg(dir).args(args).output().unwrap()
}

fn spring(dir: &Path, args: &[&str]) -> Output {
    let mut all = vec!["--set", "time.t_end=5"];
    all.extend_from_slice(args);
    run(&case("spring_block.toml"), dir, &all)
}

fn assert_refused(output: &Output, message: &str) {
    let text = stderr(output);
    assert_eq!(code(output), 2, "expected exit 2, stderr: {text}");
    assert!(text.contains(message), "expected `{message}` in: {text}");
    assert!(!text.contains("panicked"), "{text}");
}

#[test]
fn two_outputs_on_one_path_are_refused_before_solving() {
    let dir = scratch("collide");
    let same = dir.join("x");
    let x = same.to_str().unwrap();
    for (a, b, roles) in
        [("--rrd", "--mcap", "--rrd"), ("--rrd", "--events", "--events"), ("--mcap", "--events", "--events")]
    {
        let output = spring(&dir, &[a, x, b, x]);
        assert_refused(&output, "name the same file: give each output its own path");
        assert!(stderr(&output).contains(roles), "{}", stderr(&output));
    }
    // A block writes its rupture catalog beside the events: --rrd may not take that name.
    let ruptures = dir.join("paper_triangular.ruptures.csv");
    let output =
        run(&case("paper_triangular.toml"), &dir, &["--set", "time.t_end=1", "--rrd", ruptures.to_str().unwrap()]);
    assert_refused(&output, "the rupture catalog");
}

#[test]
fn an_output_never_overwrites_an_input() {
    let dir = scratch("inputs");
    let copy = dir.join("c.toml");
    std::fs::copy(case("spring_block.toml"), &copy).unwrap();
    let before = std::fs::read(&copy).unwrap();
    let output = run(copy.to_str().unwrap(), &dir, &["--set", "time.t_end=5", "--rrd", copy.to_str().unwrap()]);
    assert_refused(&output, "would overwrite the case file it reads");
    assert_eq!(std::fs::read(&copy).unwrap(), before, "the case file was changed");

    let log = dir.join("log.mcap");
    assert_eq!(code(&spring(&dir, &["--mcap", log.to_str().unwrap()])), 0);
    let before = std::fs::read(&log).unwrap();
    let output = binary().arg("replay").arg(&log).arg("--rrd").arg(&log).output().unwrap();
    assert_refused(&output, "would overwrite the MCAP log it reads");
    assert_eq!(std::fs::read(&log).unwrap(), before, "the log was changed");
}

#[test]
fn a_second_writer_of_the_same_output_is_refused() {
    let dir = scratch("lock");
    let events = dir.join("spring_block.events.csv");
    // Another slipfront command holding the file, as a run in progress does.
    let held = File::create(&events).unwrap();
    held.try_lock().unwrap();
    let output = spring(&dir, &[]);
    assert_refused(&output, "is being written by another slipfront command");
    drop(held);
    assert_eq!(code(&spring(&dir, &[])), 0, "{}", stderr(&spring(&dir, &[])));
}

#[test]
fn outputs_in_a_missing_folder_are_refused_before_solving() {
    let dir = scratch("missing");
    let output = spring(&dir, &["--events", "/nonexistent-slipfront-folder/e.csv"]);
    assert_refused(&output, "the folder /nonexistent-slipfront-folder does not exist");
}

/// A finished spring-block recording to read back.
fn recording(dir: &Path) -> PathBuf {
    assert_eq!(code(&spring(dir, &[])), 0);
    dir.join("spring_block.rrd")
}

#[test]
fn a_full_standard_output_is_an_error_and_a_closed_one_ends_quietly() {
    let dir = scratch("stdout");
    let rrd = recording(&dir);
    let full = binary().arg("check").arg(&rrd).stdout(File::create("/dev/full").unwrap()).output().unwrap();
    assert_eq!(code(&full), 1, "{}", stderr(&full));
    assert!(stderr(&full).contains("cannot write to standard output"), "{}", stderr(&full));
    assert!(!stderr(&full).contains("panicked"), "{}", stderr(&full));

    let mut child = binary().arg("check").arg(&rrd).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    drop(child.stdout.take()); // the reader goes away before anything is written
    let closed = child.wait_with_output().unwrap();
    assert_eq!(code(&closed), 0, "{}", stderr(&closed));
    assert!(stderr(&closed).is_empty(), "a closed pipe should end quietly: {}", stderr(&closed));
}

/// Starts the paper case for long enough to be stopped, sends `signal` once it runs, and
/// returns the run's output and folder.
fn stopped_by(signal: &str) -> (Output, PathBuf) {
    let dir = scratch(&format!("signal-{signal}"));
    let child = binary()
        .arg("run")
        .arg(case("paper_triangular.toml"))
        .args(["--quiet", "--set", "time.t_end=100000", "--out-dir"])
        .arg(&dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let events = dir.join("paper_triangular.events.csv");
    let start = Instant::now();
    while std::fs::metadata(&events).map_or(true, |m| m.len() == 0) && start.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(50));
    }
    std::thread::sleep(Duration::from_millis(300));
    let sent = Command::new("kill").arg(format!("-{signal}")).arg(child.id().to_string()).status().unwrap();
    assert!(sent.success());
    (child.wait_with_output().unwrap(), dir)
}

#[test]
fn hang_up_and_user_signals_stop_a_run_with_its_outputs_finished() {
    for (signal, exit) in [("HUP", 129), ("USR1", 138), ("USR2", 140)] {
        let (output, dir) = stopped_by(signal);
        assert_eq!(code(&output), exit, "SIG{signal}: {}", stderr(&output));
        assert!(stderr(&output).contains(&format!("interrupted by SIG{signal}")), "{}", stderr(&output));
        let check = binary().arg("check").arg(dir.join("paper_triangular.rrd")).output().unwrap();
        assert_eq!(code(&check), 0, "SIG{signal}: {}", String::from_utf8_lossy(&check.stdout));
    }
}

#[test]
fn an_expectation_that_is_not_a_finite_number_is_refused() {
    let dir = scratch("expect");
    let rrd = recording(&dir);
    for (line, message) in [
        ("min = nan", "at[0].min = NaN must be a finite number"),
        ("max = inf", "at[0].max = inf must be a finite number"),
        ("min = 2.0\nmax = 1.0", "at[0].min = 2 must not exceed at[0].max = 1"),
    ] {
        let expect = dir.join("expect.toml");
        std::fs::write(&expect, format!("[[at]]\nentity = \"contact/friction_force\"\ntime = 1.0\n{line}\n")).unwrap();
        let output = binary().arg("check").arg(&rrd).arg("--expect").arg(&expect).output().unwrap();
        assert_refused(&output, message);
    }
}

#[test]
fn repeated_selections_are_refused() {
    let dir = scratch("duplicates");
    assert_refused(
        &spring(&dir, &["--set", "record.quantities=[\"slip\",\"slip\"]"]),
        "record.quantities[1] = \"slip\" repeats quantities[0]: list each quantity once",
    );
    let paper = case("paper_triangular.toml");
    let output =
        run(&paper, &dir, &["--set", "time.t_end=1", "--set", "record.segments=[1,1]", "--set", "record.nodes=[2,2]"]);
    assert_refused(&output, "record.segments[1] = 1 repeats segments[0]: list each index once");
    assert!(stderr(&output).contains("record.nodes[1] = 2 repeats nodes[0]"), "{}", stderr(&output));
}

#[test]
fn a_bound_derived_from_two_inputs_accepts_its_own_exact_value() {
    let dir = scratch("derived");
    let decimals = ["--set", "friction.mu_s=0.3", "--set", "friction.mu_k=0.1", "--set"];
    // 0.3/0.1 rounds to 2.9999999999999996, below the 3 it is in exact arithmetic: accepted. A
    // value really above the bound is still refused.
    for (structure0, refused) in [("friction.structure0=3.0", false), ("friction.structure0=3.0001", true)] {
        let output = spring(&dir, &[&decimals[..], &[structure0]].concat());
        match refused {
            false => assert_eq!(code(&output), 0, "{structure0}: {}", stderr(&output)),
            true => {
                assert_refused(&output, "friction.structure0 = 3.0001 must lie in [1, friction.mu_s/friction.mu_k]")
            }
        }
    }
}

#[test]
fn a_selection_that_is_no_selection_names_the_allowed_forms() {
    let dir = scratch("selection");
    let output = run(&case("paper_triangular.toml"), &dir, &["--set", "time.t_end=1", "--set", "record.segments=none"]);
    assert_refused(&output, "unknown selection \"none\", expected \"all\", \"probes\", \"auto\" or a list of indices");
}

#[test]
fn a_replay_pace_out_of_range_is_refused() {
    let dir = scratch("speed");
    let log = dir.join("log.mcap");
    assert_eq!(code(&spring(&dir, &["--mcap", log.to_str().unwrap()])), 0);
    for (speed, shown) in [("1e-20", "1e-20"), ("0", "0"), ("-1", "-1"), ("nan", "NaN"), ("1e300", "1e300")] {
        let output = binary().arg("replay").arg(&log).arg(format!("--speed={speed}")).output().unwrap();
        assert_refused(
            &output,
            &format!("--speed {shown}: must lie in [1e-6, 1e12] (simulated seconds per wall-clock second)"),
        );
    }
}

#[test]
fn a_case_file_larger_than_any_case_is_refused_without_reading_it_all() {
    let dir = scratch("size");
    let big = dir.join("big.toml");
    std::fs::write(&big, vec![b'#'; 5 << 20]).unwrap();
    assert_refused(&run(big.to_str().unwrap(), &dir, &[]), "it is larger than 4 MiB");
    let start = Instant::now();
    let output = run("/dev/zero", &dir, &[]);
    assert_refused(&output, "it is a character device, not a regular file");
    assert!(start.elapsed() < Duration::from_secs(20), "reading /dev/zero took {:?}", start.elapsed());
}

#[test]
fn numbers_in_messages_are_written_in_their_shortest_form() {
    let dir = scratch("shortest");
    for (set, shown) in [
        ("time.dt=1e-320", "time.dt = 1e-320 "),
        ("record.magnification=-1e300", "record.magnification = -1e300 "),
        ("friction.f0=-1e-7", "friction.f0 = -1e-7 "),
    ] {
        let output = spring(&dir, &["--set", set]);
        assert_refused(&output, shown);
        let longest = stderr(&output).lines().map(str::len).max().unwrap_or(0);
        assert!(longest < 200, "a {longest}-character line: {}", stderr(&output));
    }
}

#[test]
fn an_initial_traction_above_the_initial_strength_is_invalid_input() {
    let dir = scratch("strength");
    // The spring block: f_n = 1000 Pa, mu_k = 0.2, 1/R* = 2: strength 400 Pa.
    let above = spring(&dir, &["--set", "friction.f0=400.0001"]);
    assert_refused(&above, "friction.f0 = 400.0001 must not exceed the initial strength mu_k (1/R*) f_n = 400 Pa");
    assert_refused(&spring(&dir, &["--set", "scene.normal_traction=1e-300"]), "f_n = 1e-300 Pa");
    assert_eq!(code(&spring(&dir, &["--set", "friction.f0=400"])), 0, "the bound itself is allowed");
    // The block: the weakest loaded contact point is a Gauss point of the first element, where
    // the linear traction from 0 Pa gives (1 - 1/sqrt 3)/2 x 1 m / 10 m x 1200 Pa = 25.36 Pa.
    let output = run(
        &case("paper_triangular.toml"),
        &dir,
        &["--set", "time.t_end=1", "--set", "scene.normal_traction.left=0", "--set", "friction.f0=11"],
    );
    assert_refused(&output, "f_n = 25.358983848");
}

#[test]
fn a_paced_replay_stopped_by_a_signal_finishes_its_recording() {
    let dir = scratch("replay-signal");
    let log = dir.join("log.mcap");
    assert_eq!(code(&spring(&dir, &["--set", "time.t_end=200", "--mcap", log.to_str().unwrap()])), 0);
    let replayed = dir.join("replayed.rrd");
    for (signal, exit) in [("INT", 130), ("TERM", 143)] {
        // 200 simulated seconds at 10 per second: 20 s of pacing, stopped after about one.
        let child = binary()
            .arg("replay")
            .arg(&log)
            .arg("--rrd")
            .arg(&replayed)
            .args(["--speed", "10"])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(1000));
        let sent = Command::new("kill").arg(format!("-{signal}")).arg(child.id().to_string()).status().unwrap();
        assert!(sent.success());
        let start = Instant::now();
        let output = child.wait_with_output().unwrap();
        assert!(start.elapsed() < Duration::from_secs(10), "SIG{signal}: took {:?} to stop", start.elapsed());
        assert_eq!(code(&output), exit, "SIG{signal}: {}", stderr(&output));
        assert!(stderr(&output).contains(&format!("interrupted by SIG{signal}")), "{}", stderr(&output));
        let check = binary().arg("check").arg(&replayed).output().unwrap();
        let report = String::from_utf8_lossy(&check.stdout);
        assert_eq!(code(&check), 0, "SIG{signal}: {report}");
        assert!(report.contains("run interrupted"), "SIG{signal}: {report}");
    }
}

/// Runs `command` and kills it after `limit`; returns its output and whether it ended by itself.
fn bounded(mut command: Command, limit: Duration) -> (Output, bool) {
    let mut child = command.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() && start.elapsed() < limit {
        std::thread::sleep(Duration::from_millis(50));
    }
    let ended = child.try_wait().unwrap().is_some();
    if !ended {
        let _ = child.kill();
    }
    (child.wait_with_output().unwrap(), ended)
}

#[test]
fn a_viewer_endpoint_that_never_answers_is_refused_within_seconds() {
    let dir = scratch("silent");
    // Accepts TCP connections (the kernel completes them) and never reads or answers.
    let silent = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("rerun+http://127.0.0.1:{}/proxy", silent.local_addr().unwrap().port());
    let refused = |output: &std::process::Output, what: &str| {
        assert_eq!(code(output), 2, "{what}: {}", stderr(output));
        let message =
            format!("--connect {url}: the endpoint accepted the connection but did not answer as a Rerun viewer");
        assert!(stderr(output).contains(&message), "{what}: {}", stderr(output));
    };
    let mut command = binary();
    command.arg("run").arg(case("spring_block.toml")).args(["--quiet", "--set", "time.t_end=5", "--connect", &url]);
    command.arg("--out-dir").arg(&dir);
    let started = std::time::Instant::now();
    let (output, ended) = bounded(command, Duration::from_secs(60));
    assert!(ended, "the run hung on a silent viewer endpoint: {}", stderr(&output));
    assert!(started.elapsed() < Duration::from_secs(30), "refused only after {:?}", started.elapsed());
    refused(&output, "run");
    assert!(!dir.join("spring_block.rrd").exists(), "a refused run writes no recording");

    let log = dir.join("log.mcap");
    assert_eq!(code(&spring(&dir, &["--mcap", log.to_str().unwrap()])), 0);
    let mut command = binary();
    command.arg("replay").arg(&log).arg("--rrd").arg(dir.join("replayed.rrd")).args(["--connect", &url]);
    let (output, ended) = bounded(command, Duration::from_secs(60));
    assert!(ended, "the replay hung on a silent viewer endpoint: {}", stderr(&output));
    refused(&output, "replay");
    drop(silent);
}

#[test]
fn damage_that_a_decoder_panics_on_is_reported_as_damage() {
    // The kept regressions of the fuzz targets that once panicked inside the Arrow or MCAP
    // readers: each must end as a damaged-file report, without a panic message.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions");
    let mut seen = 0;
    for target in ["rrd_read", "mcap_read"] {
        for entry in std::fs::read_dir(root.join(target)).unwrap() {
            let path = entry.unwrap().path();
            if !path.file_name().unwrap().to_string_lossy().starts_with("crash-") {
                continue;
            }
            seen += 1;
            for command in ["check", "figures"] {
                let mut run = binary();
                run.arg(command).arg(&path);
                if command == "figures" {
                    run.arg("--out").arg(scratch("damaged-figures"));
                }
                let output = run.output().unwrap();
                let all = format!("{}{}", String::from_utf8_lossy(&output.stdout), stderr(&output));
                assert!([1, 2].contains(&code(&output)), "{command} {}: exit {}: {all}", path.display(), code(&output));
                assert!(!all.contains("panicked"), "{command} {}: {all}", path.display());
            }
        }
    }
    assert!(seen >= 3, "the crash regressions are missing ({seen} found)");
}

#[test]
fn an_empty_recording_is_unreadable_and_figures_say_when_a_file_is_damaged() {
    let dir = scratch("empty");
    let empty = dir.join("empty.rrd");
    File::create(&empty).unwrap();
    for command in ["check", "figures"] {
        let mut run = binary();
        run.arg(command).arg(&empty);
        if command == "figures" {
            run.arg("--out").arg(&dir);
        }
        let output = run.output().unwrap();
        assert_eq!(code(&output), 2, "{command}: {}", stderr(&output));
        assert!(stderr(&output).contains("is empty: no recording to read"), "{command}: {}", stderr(&output));
    }
    // A recording cut off inside its last chunk: figures are drawn, and the damage is named.
    let rrd = recording(&dir);
    let bytes = std::fs::read(&rrd).unwrap();
    let cut = dir.join("cut.rrd");
    std::fs::write(&cut, &bytes[..bytes.len() - 5000]).unwrap();
    let output = binary().arg("figures").arg(&cut).arg("--out").arg(dir.join("figures")).output().unwrap();
    assert_eq!(code(&output), 1, "{}", stderr(&output));
    assert!(stderr(&output).contains("is damaged"), "{}", stderr(&output));
}

#[test]
fn damage_to_a_recordings_footer_fails_check() {
    let dir = scratch("footer");
    let rrd = recording(&dir);
    let bytes = std::fs::read(&rrd).unwrap();
    let n = bytes.len();
    // The stream footer's last 32 bytes point at the footer: start and length, little-endian.
    assert_eq!(&bytes[n - 8..n - 4], b"FOOT", "a finished recording ends with its stream footer");
    let start = u64::from_le_bytes(bytes[n - 32..n - 24].try_into().unwrap()) as usize;
    let len = u64::from_le_bytes(bytes[n - 24..n - 16].try_into().unwrap()) as usize;
    let footer: Vec<usize> = (start..start + len).chain(n - 32..n - 12).collect();
    let damaged = dir.join("damaged.rrd");
    for k in 0..24 {
        let at = footer[k * footer.len() / 24];
        let mut copy = bytes.clone();
        copy[at] ^= 0x10;
        std::fs::write(&damaged, &copy).unwrap();
        let output = binary().arg("check").arg(&damaged).output().unwrap();
        let report = String::from_utf8_lossy(&output.stdout);
        assert_ne!(
            code(&output),
            0,
            "a flip at byte {at} of {n} (footer {start}..{}) passed check: {report}",
            start + len
        );
        assert!(!stderr(&output).contains("panicked"), "{}", stderr(&output));
    }
}
