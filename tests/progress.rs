//! Progress of a run whose stderr is not a terminal (a batch job's log): a line at the stated
//! cadence, saying the simulated time, the steps, the rate and the end; nothing when asked for
//! none or quiet.

mod common;

use std::process::Stdio;
use std::time::Instant;

use common::{binary, case_path};

/// Runs the paper case with Wilson's method (about 2.5 s) into a folder named by `tag`, with
/// stderr piped, the line interval set to `every` seconds (if any) and `extra` arguments;
/// returns what it wrote on stderr, line by line, and the wall-clock seconds the run took.
fn progress_lines(tag: &str, every: Option<f64>, extra: &[&str]) -> (Vec<String>, f64) {
    // A folder of its own: a run that replaced another's outputs would say so on stderr.
    let out = std::env::temp_dir().join(format!("slipfront-progress-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let mut cmd = binary();
    cmd.args(["run", &case_path("paper_triangular.toml"), "--set", "time.integrator=wilson", "--no-rrd", "--out-dir"])
        .arg(&out)
        .args(extra)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    match every {
        Some(every) => cmd.env("SLIPFRONT_PROGRESS_EVERY", every.to_string()),
        None => cmd.env_remove("SLIPFRONT_PROGRESS_EVERY"),
    };
    let start = Instant::now();
    let output = cmd.output().unwrap();
    let wall = start.elapsed().as_secs_f64();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stderr = String::from_utf8(output.stderr).unwrap();
    (stderr.lines().map(String::from).collect(), wall)
}

#[test]
fn a_log_gets_a_line_at_the_stated_cadence() {
    let every = 0.25;
    let (lines, wall) = progress_lines("cadence", Some(every), &[]);
    // The run cannot print faster than its cadence, and prints at every interval it lives through.
    let most = (wall / every).floor() as usize;
    assert!(lines.len() <= most, "{} lines in {wall:.2} s at one per {every} s:\n{}", lines.len(), lines.join("\n"));
    assert!(
        lines.len() + 2 >= most / 2 && lines.len() >= 3,
        "{} lines in {wall:.2} s:\n{}",
        lines.len(),
        lines.join("\n")
    );
    let mut last_time = 0.0;
    for line in &lines {
        // slipfront: [0:00:01] t = 347.0 s of 1000 s (34.7 %), step 34696, 347 simulated s per wall s, end in about 2 s
        let elapsed = line.strip_prefix("slipfront: [").and_then(|rest| rest.split_once("] ")).map(|(e, _)| e);
        let clock = |e: &str| {
            let parts: Vec<&str> = e.split(':').collect();
            parts.len() == 3
                && parts[1].len() == 2
                && parts[2].len() == 2
                && parts.iter().all(|p| p.parse::<u32>().is_ok())
        };
        assert!(elapsed.is_some_and(clock), "an elapsed time H:MM:SS first: {line}");
        let t: f64 = line.split("t = ").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
        assert!(t > last_time && t < 1000.0, "simulated time rises: {line}");
        last_time = t;
        assert!(line.contains(" s of 1000 s ("), "{line}");
        assert!(line.contains(", step "), "{line}");
        assert!(line.contains(" simulated s per wall s, end in "), "the rate and the end: {line}");
    }
}

#[test]
fn the_default_cadence_is_ten_seconds() {
    // A run of about 2.5 s prints no progress line at all, and then its summary on stdout.
    let (lines, wall) = progress_lines("default", None, &[]);
    assert!(wall < 10.0 || lines.len() <= (wall / 10.0) as usize, "{wall} s");
    if wall < 10.0 {
        assert!(lines.is_empty(), "{lines:?}");
    }
}

#[test]
fn none_and_quiet_print_nothing() {
    for (tag, extra) in [("none", &["--progress", "none"][..]), ("quiet", &["--quiet"][..])] {
        let (lines, _) = progress_lines(tag, Some(0.1), extra);
        assert!(lines.is_empty(), "{extra:?}: {lines:?}");
    }
    let (lines, _) = progress_lines("lines", Some(0.1), &["--progress", "lines"]);
    assert!(!lines.is_empty(), "--progress lines");
}
