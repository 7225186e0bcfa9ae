//! Helpers shared by the integration tests that compare integrators on the shipped cases.

// Each test file compiles its own copy and uses only some of them.
#![allow(dead_code)]

use slipfront::case::{self, Case};
use slipfront::run::{LoopOptions, Outcome, run};
use slipfront::scene;

/// The release binary under test.
pub fn binary() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_slipfront"))
}

/// The path of the shipped case file `cases/<file>`.
pub fn case_path(file: &str) -> String {
    format!("{}/cases/{file}", env!("CARGO_MANIFEST_DIR"))
}

/// The shipped case `cases/<name>.toml` with `--set` overrides.
pub fn load(name: &str, overrides: &[&str]) -> Case {
    let path = format!("{}/cases/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let owned: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    case::load(std::path::Path::new(&path), &owned).unwrap_or_else(|e| panic!("{name} {overrides:?}: {e}"))
}

/// Mean tangential traction of each segment at `t = every, 2 every, …, t_end`, stepping the
/// scene (any body) to land on each instant.
pub fn tractions(case: &Case, every: f64) -> Vec<Vec<f64>> {
    let mut scene = scene::build(case).unwrap();
    let adaptive = case.time.adaptive_tolerance().is_some();
    let samples = (case.time.t_end / every).round() as usize;
    let mut out = Vec::new();
    for k in 1..=samples {
        let target = k as f64 * every;
        while scene.time() < target - 1e-9 {
            let left = target - scene.time();
            scene.advance(if adaptive { left } else { case.time.dt.min(left) }).unwrap();
        }
        let frame = scene.frame(Default::default(), 0.0);
        out.push(frame.segments.iter().map(|s| s.traction_t).collect());
    }
    out
}

pub fn max_difference(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    a.iter().flatten().zip(b.iter().flatten()).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// `(segment, onset)` of every slip event of a run of `case`, without output files.
pub fn onsets(case: &Case) -> Vec<(usize, f64)> {
    let mut scene = scene::build(case).unwrap();
    match run(scene.as_mut(), &case.time, &mut Vec::new(), LoopOptions::for_case(case)) {
        Outcome::Completed { catalog, .. } => catalog.events.iter().map(|e| (e.segment, e.onset)).collect(),
        other => panic!("the run did not complete: {other:?}"),
    }
}

/// Largest relative onset error `|t - t_ref| / t_ref` over the events of `reference`
/// ([`onsets`]), matching the k-th event of each segment; `None` if
/// the run does not have the reference's events.
pub fn onset_error(run: &[(usize, f64)], reference: &[(usize, f64)]) -> Option<f64> {
    if run.len() != reference.len() {
        return None;
    }
    let mut worst = 0.0_f64;
    for segment in reference.iter().map(|e| e.0) {
        let mine = run.iter().filter(|e| e.0 == segment).map(|e| e.1);
        let theirs = reference.iter().filter(|e| e.0 == segment).map(|e| e.1);
        for (t, r) in mine.zip(theirs) {
            worst = worst.max((t - r).abs() / r);
        }
    }
    Some(worst)
}

/// The paper case's segment tractions every 5 s up to 400 s ([`tractions`]) by each run of
/// `runs` (`--set` overrides), against Tsitouras' pair at `reference` tolerance: each run's
/// largest difference (Pa), and the reference's own, against the same method at `check`.
pub fn traction_errors_against_tsit5(reference: &str, check: &str, runs: &[[String; 2]]) -> (f64, Vec<f64>) {
    let paper = |sets: &[&str]| {
        let mut all = vec!["time.t_end=400"];
        all.extend_from_slice(sets);
        tractions(&load("paper_triangular", &all), 5.0)
    };
    let tsit5 = |tolerance: &str| paper(&["time.integrator=tsit5", &format!("time.tolerance={tolerance}")]);
    let reference = tsit5(reference);
    let converged = max_difference(&tsit5(check), &reference);
    let errors = runs.iter().map(|[a, b]| max_difference(&paper(&[a, b]), &reference)).collect();
    (converged, errors)
}

/// Skips an independent check whose tool is missing, loudly; fails instead where
/// `SLIPFRONT_REQUIRE_OFFICIAL_TOOLS` is set (as in CI, which installs them).
pub fn skip_missing<T>(what: &str) -> Option<T> {
    assert!(
        std::env::var_os("SLIPFRONT_REQUIRE_OFFICIAL_TOOLS").is_none(),
        "{what} is required (SLIPFRONT_REQUIRE_OFFICIAL_TOOLS is set) but missing"
    );
    eprintln!("SKIPPED: {what} is not installed; the independent check did not run");
    None
}

/// A fenced block of a Markdown file: its language tag (empty if none), the line its fence is
/// on (from 1) and its text.
#[derive(Debug, Clone)]
pub struct Fenced {
    pub lang: String,
    pub line: usize,
    pub body: String,
}

/// Every fenced block (```` ``` ````) of `markdown`, in order.
pub fn fenced_blocks(markdown: &str) -> Vec<Fenced> {
    let mut blocks = Vec::new();
    let mut open: Option<Fenced> = None;
    for (i, line) in markdown.lines().enumerate() {
        let fence = line.trim_start().strip_prefix("```");
        match (fence, open.take()) {
            (Some(_), Some(block)) => blocks.push(block),
            (Some(lang), None) => {
                open = Some(Fenced { lang: lang.trim().to_string(), line: i + 1, body: String::new() })
            }
            (None, Some(mut block)) => {
                block.body.push_str(line);
                block.body.push('\n');
                open = Some(block);
            }
            (None, None) => {}
        }
    }
    blocks
}

/// The commands of a shell block: continuation lines joined, comments and blank lines dropped.
pub fn shell_commands(body: &str) -> Vec<String> {
    let joined = body.replace("\\\n", " ");
    joined
        .lines()
        .map(|line| if line.trim_start().starts_with('#') { "" } else { line.split(" #").next().unwrap_or("") })
        .map(|line| line.split_whitespace().collect::<Vec<_>>().join(" "))
        .filter(|line| !line.is_empty())
        .collect()
}

/// The text of `## heading` in `markdown`, up to the next `## ` heading.
pub fn section<'a>(markdown: &'a str, heading: &str) -> &'a str {
    let start = markdown.find(&format!("\n## {heading}\n")).unwrap_or_else(|| panic!("no section \"{heading}\""));
    let rest = &markdown[start + 1..];
    let end = rest[3..].find("\n## ").map_or(rest.len(), |e| e + 4);
    &rest[..end]
}

/// Every file of a study folder but the recordings (and the logs' subfolder, and files being
/// written), by name, with its bytes; of the members' records, all but their digests of the
/// recordings (Rerun's chunk ids are random) and their own digest.
pub fn study_files(dir: &std::path::Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file() && p.extension().is_none_or(|e| e != "rrd"))
        .filter(|p| !p.file_name().unwrap().to_string_lossy().starts_with('.'))
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            let mut bytes = std::fs::read(&p).unwrap();
            if name.ends_with(".done.toml") {
                let mut record: toml::Table = std::str::from_utf8(&bytes).unwrap().parse().unwrap();
                record.remove("digest");
                if let Some(toml::Value::Array(outputs)) = record.get_mut("outputs") {
                    outputs.retain(|o| !o[0].as_str().unwrap().ends_with(".rrd"));
                }
                bytes = record.to_string().into_bytes();
            }
            (name, bytes)
        })
        .collect();
    files.sort();
    files
}

/// What `tests/python/read_study.py TARGET` prints (a study folder, or the URL of a server
/// serving one as `study`): each member's parameters and last friction force, through the
/// official Rerun SDK; `None` where the SDK or Python is missing ([`skip_missing`]).
pub fn read_study(target: &str) -> Option<String> {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/python/read_study.py");
    match std::process::Command::new("python3").arg(script).arg(target).output() {
        Ok(o) if o.status.code() == Some(3) => skip_missing("the official Rerun Python SDK"),
        Ok(o) => {
            assert!(o.status.success(), "read_study.py {target}: {}", String::from_utf8_lossy(&o.stderr));
            Some(String::from_utf8(o.stdout).unwrap())
        }
        Err(_) => skip_missing("python3"),
    }
}

/// What [`read_study`] prints when it queries `folder` served by the `rerun server` command
/// (`rerun server -d study=FOLDER`, the binary the Python SDK ships, run as its own process so
/// that its process id is the server's) on a free local port, as a colleague would; the server
/// is stopped by its process id afterwards.
pub fn serve_study(folder: &std::path::Path) -> Option<String> {
    let locate = "import os, rerun_cli; print(os.path.join(os.path.dirname(rerun_cli.__file__), 'rerun'))";
    let rerun = match std::process::Command::new("python3").args(["-c", locate]).output() {
        Ok(o) if o.status.success() => String::from_utf8(o.stdout).unwrap().trim().to_string(),
        _ => return skip_missing("the rerun CLI of the Python SDK"),
    };
    let port = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
    let dataset = format!("study={}", folder.display());
    let server = std::process::Command::new(&rerun)
        .args(["server", "--host", "127.0.0.1", "--port", &port.to_string(), "-d", &dataset])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("{rerun}: {e}"));
    let _server = Stopped(server);
    read_study(&format!("rerun+http://127.0.0.1:{port}"))
}

/// A child process killed (by its process id) and waited for when dropped, a failed test too.
pub struct Stopped(pub std::process::Child);

impl Drop for Stopped {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// `small.toml` in `dir`: a study of the paper case for its whole 1000 s, so that the paper's
/// verdicts and `summary.png` are made (about 1.7 s a member, recording included, with the
/// default integrator), 2 sweep rows (`scene.normal_traction.left` 300 and 350 Pa) of `members`
/// ensemble members 1e-9 apart in initial `1/R*`, and `extra` lines.
pub fn paper_study(dir: &std::path::Path, members: usize, extra: &str) -> std::path::PathBuf {
    let path = dir.join("small.toml");
    let text = format!(
        "case = \"{}/cases/paper_triangular.toml\"\n\
         [ensemble]\nkey = \"friction.structure0\"\nstep = -1.0e-9\nmembers = {members}\n\
         [sweep]\n\"scene.normal_traction.left\" = [300.0, 350.0]\n{extra}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::write(&path, text).unwrap();
    path
}
