//! `slipfront study`: bad study files refused before anything runs, shards that add up to the
//! whole study (the tables of a part naming the members missing), a killed study resumed to the
//! same files, and the output folder read by the official Rerun SDK as one dataset, in the
//! test's own process and served by `rerun server` to another.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::{paper_study, read_study, serve_study, study_files};

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slipfront-study-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The paper case for its 1000 s, 2 sweep rows × 2 ensemble members ([`paper_study`]).
fn small_study(dir: &Path, extra: &str) -> PathBuf {
    paper_study(dir, 2, extra)
}

fn study(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_slipfront")).arg("study").args(args).output().unwrap();
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    (out.status.code().unwrap_or(-1), text)
}

#[test]
fn bad_study_files_are_refused_before_anything_runs() {
    let dir = scratch("bad");
    let cases = [
        ("[set]\n\"friction.mu_x\" = 1.0\n", "mu_x"),
        ("[sweep]\n\"scene.nothing\" = [1.0]\n", "nothing"),
        ("[sweep]\n\"scene.nx\" = []\n", "sweep.\"scene.nx\" = []: a sweep key needs at least one value"),
        (
            "[ensemble]\nkey = \"friction.structure0\"\nstep = 1e-9\nmembers = 0\n",
            "ensemble.members = 0 must be at least 1",
        ),
        (
            "[sweep]\n\"friction.mu_k\" = [0.2, 0.5]\n",
            "member 1 (row 1, k = 0): friction.mu_k = 0.5 must be less than friction.mu_s = 0.4",
        ),
        (
            "[ensemble]\nkey = \"friction.kappa\"\nstep = 0.0\nmembers = 2\n",
            "ensemble.step = 0 must be a finite number other than 0",
        ),
        ("colour = \"red\"\n", "unknown field `colour`"),
        (
            "[ensemble]\nkey = \"friction.structure0\"\nstep = 1e-12\nmembers = 1000000000000\n",
            "the study has 1000000000000 members: at most 100000 are allowed",
        ),
    ];
    for (body, expected) in cases {
        let path = dir.join("bad.toml");
        std::fs::write(&path, format!("case = \"{}/cases/paper_triangular.toml\"\n{body}", env!("CARGO_MANIFEST_DIR")))
            .unwrap();
        let out = dir.join("out");
        let (code, text) = study(&[path.to_str().unwrap(), "--out-dir", out.to_str().unwrap()]);
        assert_eq!(code, 2, "{body}: {text}");
        assert!(text.contains(expected), "{body}: expected {expected:?} in {text}");
        assert!(!out.exists(), "{body}: nothing may be written");
    }
    let path = small_study(&dir, "");
    let (code, text) = study(&[path.to_str().unwrap(), "--shard", "3/2"]);
    assert_eq!(code, 2, "{text}");
    assert!(text.contains("--shard 3/2: expected I/N with 1 ≤ I ≤ N"), "{text}");
}

#[test]
fn shards_add_up_to_the_whole_study_and_a_killed_study_resumes_to_the_same_files() {
    let dir = scratch("shards");
    let path = small_study(&dir, "");
    let path = path.to_str().unwrap();
    let whole = dir.join("whole");
    let (code, text) = study(&[path, "--out-dir", whole.to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 0, "{text}");
    // Two shards into one folder, one after the other as two machines would.
    let sharded = dir.join("sharded");
    let out = sharded.to_str().unwrap();
    let (code, text) = study(&[path, "--out-dir", out, "--shard", "1/2", "--quiet"]);
    assert_eq!(code, 0, "{text}");
    // The tables of half a study name the members missing, and say so by their exit.
    let (code, text) = study(&[path, "--out-dir", out, "--summarize"]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("2 of 4 finished, 0 failed, 2 missing") && text.contains("2 members missing"), "{text}");
    let summary = std::fs::read_to_string(sharded.join("small/summary.md")).unwrap();
    for member in ["member-0001", "member-0003"] {
        assert!(summary.contains(&format!("- {member} (")), "{summary}");
    }
    assert!(summary.contains("## Missing members") && !summary.contains("- member-0000 ("), "{summary}");
    let (code, text) = study(&[path, "--out-dir", out, "--shard", "2/2", "--quiet"]);
    assert_eq!(code, 0, "{text}");
    let (code, text) = study(&[path, "--out-dir", out, "--summarize", "--quiet"]);
    assert_eq!(code, 0, "{text}");
    let expected = study_files(&whole.join("small"));
    assert_eq!(expected.len(), 4 * 3 + 3, "4 members × (events, ruptures, done) + events.csv, summary.md, summary.png");
    assert_eq!(study_files(&sharded.join("small")), expected, "sharded and whole studies differ");
    let summary = String::from_utf8(expected.iter().find(|(n, _)| n == "summary.md").unwrap().1.clone()).unwrap();
    assert!(
        summary.contains("4 of 4 members finished, 0 failed, 0 not run or not verified (2 rows of 2 members)"),
        "{summary}"
    );

    // A study killed (SIGKILL, which it cannot see) after its first member, then resumed.
    let resumed = dir.join("resumed");
    let mut child = Command::new(env!("CARGO_BIN_EXE_slipfront"))
        .args(["study", path, "--out-dir", resumed.to_str().unwrap(), "--jobs", "1", "--quiet"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while !resumed.join("small/member-0000.done.toml").exists() {
        assert!(started.elapsed() < Duration::from_secs(60), "the first member did not finish");
        std::thread::sleep(Duration::from_millis(20));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(!resumed.join("small/member-0003.done.toml").exists(), "the study was killed before its end");
    let (code, text) = study(&[path, "--out-dir", resumed.to_str().unwrap(), "--resume"]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("verified and kept"), "{text}");
    let after: Vec<(String, Vec<u8>)> =
        study_files(&resumed.join("small")).into_iter().filter(|(n, _)| !n.starts_with('.')).collect();
    assert_eq!(after, expected, "the resumed study differs from the uninterrupted one");
}

#[test]
fn the_official_sdk_reads_the_study_folder_as_one_dataset() {
    let dir = scratch("dataset");
    let path = small_study(&dir, "");
    let out = dir.join("out");
    let (code, text) = study(&[path.to_str().unwrap(), "--out-dir", out.to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 0, "{text}");
    let Some(output) = read_study(out.join("small").to_str().unwrap()) else { return };
    // One segment per member, its parameters in the segment table.
    let segments: Vec<&str> = output.lines().filter(|l| l.starts_with("segment,")).collect();
    assert_eq!(segments.len(), 4, "{output}");
    for (k, left) in [(0, "300.0"), (1, "300.0"), (0, "350.0"), (1, "350.0")] {
        let structure = if k == 0 { "2.0" } else { "1.999999999" };
        assert!(
            segments.iter().any(|l| l.ends_with(&format!(",{left},{structure}"))),
            "no member with left = {left}, structure0 = {structure}: {output}"
        );
    }
    // One query across every member: the friction force's last value in each.
    let finals: Vec<&str> = output.lines().filter(|l| l.starts_with("final,")).collect();
    assert_eq!(finals.len(), 4, "{output}");
    // A colleague's query of the folder served by `rerun server`, from another process: the same.
    let Some(served) = serve_study(&out.join("small")) else { return };
    assert_eq!(served, output, "served and read in process, the study differs");
}

#[test]
fn a_stop_rule_ends_a_member_early_with_its_outputs_finished() {
    let dir = scratch("stop");
    // Nothing slips in the paper case before about 400 s: `quiet_for = 100` stops every member
    // at 100 s, recorded as such, its recording complete to that step.
    let path = small_study(&dir, "[set]\n\"time.integrator\" = \"wilson\"\n[stop]\nquiet_for = 100.0\n");
    let out = dir.join("out");
    let (code, text) = study(&[path.to_str().unwrap(), "--out-dir", out.to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 0, "{text}");
    let record = std::fs::read_to_string(out.join("small/member-0000.done.toml")).unwrap();
    assert!(record.contains("ending = \"stopped nothing slipped for 100 s, at 100.00 s\""), "{record}");
    let summary = std::fs::read_to_string(out.join("small/summary.md")).unwrap();
    assert!(summary.contains("(0 completed, 2 stopped by a rule); failed: 0"), "{summary}");
    // Stopped before the paper's 1000 s, its observations are not judged.
    assert!(
        summary.contains(
            "- verdicts: stopped nothing slipped for 100 s, at 100.00 s, before the paper's 1000 s: its \
             observations are not evaluated"
        ) && !out.join("small/summary.png").exists(),
        "{summary}"
    );
    let check = Command::new(env!("CARGO_BIN_EXE_slipfront"))
        .args(["check", out.join("small/member-0000.rrd").to_str().unwrap()])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&check.stdout);
    assert!(check.status.success() && text.contains("run interrupted") && text.contains("up to t = 100"), "{text}");
    // Without recordings, only the catalogs and records are written.
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, format!("recordings = false\n{text}")).unwrap();
    let lean = dir.join("lean");
    let (code, text) = study(&[path.to_str().unwrap(), "--out-dir", lean.to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 0, "{text}");
    let names: Vec<String> = std::fs::read_dir(lean.join("small"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        names.iter().all(|n| !n.ends_with(".rrd")) && names.contains(&"member-0003.done.toml".to_string()),
        "{names:?}"
    );
    // A rule that cannot hold is refused with the study file.
    let bad = small_study(&dir, "[stop]\nquiet_for = -5.0\n");
    let (code, text) = study(&[bad.to_str().unwrap(), "--out-dir", out.to_str().unwrap()]);
    assert_eq!(code, 2, "{text}");
    assert!(text.contains("stop.quiet_for = -5 must be a positive number of seconds"), "{text}");
}

/// A study file `name.toml` in `dir` of the shipped case `case` with `body` after it.
fn study_file(dir: &Path, name: &str, case: &str, body: &str) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, format!("case = \"{}/cases/{case}\"\n{body}", env!("CARGO_MANIFEST_DIR"))).unwrap();
    path
}

#[test]
fn the_papers_verdicts_are_given_only_for_the_papers_case() {
    let dir = scratch("verdicts");
    // The paper's block for its 1000 s, a row under its rising triangle and one under a falling
    // one (1300 Pa at the left, 1200 Pa at the right).
    let paper = study_file(
        &dir,
        "family",
        "paper_triangular.toml",
        "[sweep]\n\"scene.normal_traction.left\" = [350.0, 1300.0]\n",
    );
    let out = dir.join("out");
    let (code, text) = study(&[paper.to_str().unwrap(), "--out-dir", out.to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 0, "{text}");
    let summary = std::fs::read_to_string(out.join("family/summary.md")).unwrap();
    let rows: Vec<&str> = summary.split("## Row ").skip(1).collect();
    assert_eq!(rows.len(), 2, "{summary}");
    assert!(rows[0].contains("- verdicts: 1. left end ") && !rows[0].contains("not evaluated"), "{summary}");
    assert!(
        rows[1].contains(
            "- verdicts: not the paper's case: its observations are not evaluated (the normal traction does not \
             rise from the left end to the right, as the paper's does)"
        ) && !rows[1].contains("1. left end"),
        "{summary}"
    );
    assert!(summary.contains("on the members of the paper's family only"), "{summary}");
    assert!(out.join("family/summary.png").is_file(), "one row is judged: its figure is drawn");

    // Not the paper's block, and the paper's block for less than its 1000 s: no verdict, no figure.
    for (name, case, body, why) in [
        (
            "spring",
            "spring_block.toml",
            "[set]\n\"time.t_end\" = 50.0\n[sweep]\n\"friction.mu_s\" = [0.4, 0.5]\n",
            "scene.kind = \"spring_block\", not the paper's block",
        ),
        (
            "short",
            "paper_triangular.toml",
            "[set]\n\"time.t_end\" = 50.0\n",
            "time.t_end = 50 s: the observations count slips in the paper's 1000 s",
        ),
    ] {
        let path = study_file(&dir, name, case, body);
        let (code, text) = study(&[path.to_str().unwrap(), "--out-dir", out.to_str().unwrap(), "--quiet"]);
        assert_eq!(code, 0, "{text}");
        let summary = std::fs::read_to_string(out.join(format!("{name}/summary.md"))).unwrap();
        let said = format!("not the paper's case: its observations are not evaluated ({why})");
        assert!(summary.contains(&format!("Verdicts: {said}.")), "{name}: {summary}");
        assert_eq!(summary.matches(&format!("- verdicts: {said}\n")).count(), summary.matches("## Row ").count());
        assert!(!summary.contains("left end"), "{name}: {summary}");
        assert!(!out.join(format!("{name}/summary.png")).exists(), "{name}: no verdicts, no figure");
    }
}

#[test]
fn the_summary_figure_names_the_rows_by_their_swept_values() {
    use slipfront::study::{spec, summary::row_axis};
    let shipped =
        spec::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/studies/normal_stress_sweep.toml")).unwrap();
    let (axis, labels) = row_axis(&shipped);
    assert_eq!(axis, "scene.normal_traction.left (Pa) / scene.normal_traction.right (Pa)");
    assert_eq!(labels.len(), 18);
    assert_eq!((labels[0].as_str(), labels[17].as_str()), ("0/1200", "500/1400"));
    // A grid: the keys in alphabetical order, the last varying fastest; text without quotes.
    let dir = scratch("axis");
    let grid = study_file(
        &dir,
        "grid",
        "paper_triangular.toml",
        "[sweep]\n\"time.integrator\" = [\"wilson\", \"tsit5\"]\n\"friction.xi\" = [0.1, 0.05]\n",
    );
    let (axis, labels) = row_axis(&spec::load(&grid).unwrap());
    assert_eq!(axis, "friction.xi (1/s) / time.integrator");
    assert_eq!(labels, ["0.1/wilson", "0.1/tsit5", "0.05/wilson", "0.05/tsit5"]);
    let (axis, labels) = row_axis(&spec::load(&small_study(&dir, "")).unwrap());
    assert_eq!((axis.as_str(), labels), ("scene.normal_traction.left (Pa)", vec!["300".to_string(), "350".into()]));
}
