//! Replays every input kept under `fuzz/regressions/<target>/` (crashes the fuzzer found, once
//! fixed, and hand-made seeds) through the same entry points the fuzz targets drive
//! (`slipfront::fuzzing`): each must return, without a panic or an abort. The `crash-*` and
//! `oom-*` inputs made the MCAP and RRD decoders allocate lengths that damaged headers claimed
//! (a record's length, an Arrow message's body), which aborted the process;
//! `slipfront::inspect::framing` and `slipfront::inspect::arrow_message` now stop the readers
//! before the damage.
//!
//! The fuzzing itself: `fuzz/run.sh` (see README, "Stability").

use std::path::PathBuf;

fn inputs(target: &str) -> Vec<(PathBuf, Vec<u8>)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions").join(target);
    let mut files: Vec<PathBuf> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).filter(|p| p.is_file()).collect();
    files.sort();
    files.into_iter().map(|p| (p.clone(), std::fs::read(&p).unwrap())).collect()
}

fn replay(target: &str, entry: fn(&[u8]) -> bool) -> usize {
    let inputs = inputs(target);
    assert!(!inputs.is_empty(), "fuzz/regressions/{target} holds inputs");
    // Inputs that once made a reader spin (`timeout-*`, as libFuzzer names them) are replayed
    // through the binary under a time limit instead (`spinning_inputs_end_within_seconds`): a
    // regression here would hang the test rather than fail it.
    let inputs = inputs.iter().filter(|(p, _)| !p.file_name().unwrap().to_string_lossy().starts_with("timeout-"));
    for (path, data) in inputs.clone() {
        let result = std::panic::catch_unwind(|| entry(data));
        assert!(result.is_ok(), "{} panicked", path.display());
        // `ok-*` inputs are valid and must be accepted, `bad-*` ones refused; crash reproducers
        // (`crash-*`, as libFuzzer names them) need only return.
        let name = path.file_name().unwrap().to_string_lossy();
        let accepted = result.unwrap();
        if name.starts_with("ok-") {
            assert!(accepted, "{} was refused", path.display());
        } else if name.starts_with("bad-") {
            assert!(!accepted, "{} was accepted", path.display());
        }
    }
    inputs.count()
}

#[test]
fn case_parsing_regressions() {
    replay("case_parse", slipfront::fuzzing::case_parse);
}

#[test]
fn mcap_reading_regressions() {
    replay("mcap_read", slipfront::fuzzing::mcap_read);
}

#[test]
fn rrd_reading_regressions() {
    replay("rrd_read", slipfront::fuzzing::rrd_read);
}

#[test]
fn gmsh_reading_regressions() {
    replay("gmsh_read", slipfront::fuzzing::gmsh_read);
    // The meshes the corpus is seeded with are all accepted.
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases/meshes");
    let mut seeds = 0;
    for path in std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()) {
        if path.extension().is_some_and(|x| x == "msh") {
            seeds += 1;
            assert!(slipfront::fuzzing::gmsh_read(&std::fs::read(&path).unwrap()), "{} was refused", path.display());
        }
    }
    assert!(seeds >= 6, "the committed meshes are there ({seeds})");
}

#[test]
fn damaged_recordings_make_check_and_figures_fail_with_a_message() {
    // Every damaged input under `fuzz/regressions/rrd_read/` through the binary's `check` and
    // `figures`: each must end within seconds with exit 1 or 2 and a message, never by a signal
    // (an abort is SIGABRT, exit 134 in a shell). Two of them used to end any process that
    // decoded them: an Arrow message inside declares a body of 8.2e18 bytes (`crash-90d08cdc…`)
    // or a satisfiable 13 GB (`oom-0eda7c66…`), which `arrow-ipc` allocated before reading;
    // `slipfront::inspect::arrow_message` now stops the reader before them, and says so.
    let inputs = inputs("rrd_read");
    let out = std::env::temp_dir().join(format!("slipfront-rrd-check-{}", std::process::id()));
    let mut damaged = 0;
    // `bad-old-layout.rrd` is whole, in an older layout that `check` and `figures` refuse.
    let is_damaged = |p: &std::path::Path| {
        let name = p.file_name().unwrap().to_string_lossy();
        !name.starts_with("ok-") && name != "bad-old-layout.rrd"
    };
    for (path, _) in inputs.iter().filter(|(p, _)| is_damaged(p)) {
        damaged += 1;
        let name = path.file_name().unwrap().to_string_lossy();
        let claims_a_body = name.starts_with("crash-90d08cdc") || name.starts_with("oom-0eda7c66");
        for args in [vec!["check"], vec!["figures", "--out", out.to_str().unwrap()]] {
            let started = std::time::Instant::now();
            let output = std::process::Command::new(env!("CARGO_BIN_EXE_slipfront"))
                .args(&args[..1])
                .arg(path)
                .args(&args[1..])
                .output()
                .unwrap();
            let text =
                format!("{}{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
            assert!(
                matches!(output.status.code(), Some(1 | 2)),
                "{args:?} {}: {:?} {text}",
                path.display(),
                output.status
            );
            assert!(!text.contains("panicked") && !text.trim().is_empty(), "{args:?} {}: {text}", path.display());
            if claims_a_body {
                assert!(text.contains("an Arrow IPC message claims a body of"), "{args:?} {}: {text}", path.display());
            }
            assert!(started.elapsed().as_secs() < 30, "{args:?} {} took {:?}", path.display(), started.elapsed());
        }
    }
    assert!(damaged >= 7, "the damaged recordings are there ({damaged})");
}

#[test]
fn spinning_inputs_end_within_seconds() {
    // `timeout-6ea5f884…`: a 15 kB MCAP log whose zstd chunk decompresses to fewer bytes than it
    // declares, on which the `mcap` 0.25 reader looped for ever (`check` ran past 2 minutes).
    // `slipfront::inspect::framing` now refuses such a chunk. Each `timeout-*` input goes
    // through `slipfront check`, which must end within 30 s with an exit code.
    let mut spinning = 0;
    for target in ["case_parse", "mcap_read", "rrd_read"] {
        for (path, _) in inputs(target) {
            if !path.file_name().unwrap().to_string_lossy().starts_with("timeout-") {
                continue;
            }
            spinning += 1;
            let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_slipfront"))
                .arg("check")
                .arg(&path)
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::null())
                .spawn()
                .unwrap();
            let started = std::time::Instant::now();
            let status = loop {
                if let Some(status) = child.try_wait().unwrap() {
                    break status;
                }
                if started.elapsed() > std::time::Duration::from_secs(30) {
                    child.kill().unwrap();
                    panic!("check {} still ran after 30 s", path.display());
                }
                std::thread::sleep(std::time::Duration::from_millis(20));
            };
            assert!(matches!(status.code(), Some(1 | 2)), "check {}: {status:?}", path.display());
        }
    }
    assert!(spinning >= 1, "the spinning inputs are kept");
}
