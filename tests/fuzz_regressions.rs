//! Replays every input kept under `fuzz/regressions/<target>/` (crashes the fuzzer found, once
//! fixed, and hand-made seeds) through the same entry points the fuzz targets drive
//! (`slipfront::fuzzing`): each must return, without a panic or an abort. The two `crash-*`
//! inputs made the MCAP and RRD decoders allocate exabytes that damaged headers claimed, which
//! aborted the process; `slipfront::inspect::framing` now cuts such inputs before the damage.
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
    for (path, data) in &inputs {
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
    inputs.len()
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
fn decoder_aborts_are_reported_as_damage() {
    // Inputs under `fuzz/regressions/rrd_check/` end any process that decodes them: an Arrow
    // message inside declares a body of 8.2e18 bytes (`crash-*`), or a large satisfiable one that
    // ran for minutes in over 4 GB (`oom-*`), which `arrow-ipc` allocates before reading. The
    // binary's `check` and `figures` decode a recording first in a child under a cap on its
    // address space (`slipfront::cli::isolated`): each must end within seconds with exit 1 and
    // the damage named, never by a signal.
    let inputs = inputs("rrd_check");
    assert!(!inputs.is_empty(), "fuzz/regressions/rrd_check holds inputs");
    let out = std::env::temp_dir().join(format!("slipfront-rrd-check-{}", std::process::id()));
    for (path, _) in &inputs {
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
            assert_eq!(output.status.code(), Some(1), "{args:?} {}: {text}", path.display());
            assert!(text.contains("the file is damaged"), "{args:?} {}: {text}", path.display());
            assert!(started.elapsed().as_secs() < 30, "{args:?} {} took {:?}", path.display(), started.elapsed());
        }
    }
}
