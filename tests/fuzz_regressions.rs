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
