//! Every command and example in README.md and docs/*.md runs as written.
//!
//! The fenced blocks of each file are read in order: every command of a `sh` block, every `toml`
//! and `python` block, and every error line shown in a plain block (`slipfront: ...`) must be in
//! [`LISTED`], in the same order, with how it is run. A command that appears in the docs without
//! being listed fails this test, naming it: list it, and say how CI runs it. Commands run in one
//! scratch folder that holds a copy of `cases/`, in the order README.md, then docs/ by name,
//! through `sh` with `slipfront` and the examples on `PATH` (`cargo run --release --` is the
//! binary this test was built with). A run is shortened only where the docs say how CI runs it;
//! the text of the shortening must be in the file. Plain blocks of command synopses
//! (`slipfront run CASE.toml [--set KEY=VALUE]...`) are checked against each command's `--help`.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{fenced_blocks, shell_commands, skip_missing};

/// How CI runs one command or block of the docs.
#[derive(Debug, Clone, Copy)]
enum How {
    /// As written.
    Run,
    /// As written, with these arguments appended; the file says so.
    Shortened(&'static str),
    /// This command instead (a placeholder filled, a scheduler's line run locally); the file
    /// says so where it is a shortening.
    Mirror(&'static str),
    /// Not run here, and why.
    Skip(&'static str),
    /// A TOML block, written to this path (from the scratch folder) for the commands after it.
    Toml(&'static str),
    /// A TOML block written to a path after a prefix, then checked by a command.
    TomlChecked { path: &'static str, prefix: &'static str, command: &'static str },
    /// A Python block, run with `python3` in the scratch folder.
    Python,
    /// An error line a user sees, from this command (its stderr must end with the line).
    Output(&'static str),
}

use How::*;

/// Every command and block of the docs, file by file, in order.
const LISTED: &[(&str, &[(&str, How)])] = &[
    (
        "README.md",
        &[
            ("cargo run --release -- run cases/paper_triangular.toml", Run),
            ("cargo test --release", Skip("the suite this test belongs to")),
            ("cargo run --release -- run cases/spring_block.toml --set time.t_end=500", Run),
            ("cargo run --release -- run cases/paper_triangular.toml --set time.integrator=wilson", Run),
            ("rerun recordings/paper_triangular.rrd", Skip("opens a window; scripts/viewer_shots.sh screenshots it")),
            // With no display (removed below), it writes the blueprint and prints how to open it.
            ("cargo run --release -- view recordings/paper_triangular.rrd --at 425.3", Run),
            ("toml: [events]", Toml("expect.toml")),
            ("cargo run --release -- check recordings/paper_triangular.rrd --expect expect.toml", Run),
            ("cargo run --release -- run cases/paper_triangular.toml --mcap recordings/paper_triangular.mcap", Run),
            ("cargo run --release -- replay recordings/paper_triangular.mcap", Run),
            ("cargo run --release -- figures recordings/paper_triangular.rrd --out recordings/figures", Run),
            (
                "cargo run --release -- export recordings/paper_triangular.rrd --out recordings/paper_triangular.feather",
                Run,
            ),
            ("cargo run --release -- study cases/studies/paper_ensemble.toml", Run),
            (
                "slipfront: cases/spring_block.toml: friction.mu_k = 0.5 must be less than friction.mu_s = 0.4",
                Output("slipfront run cases/spring_block.toml --set friction.mu_k=0.5"),
            ),
        ],
    ),
    (
        "docs/applications.md",
        &[
            ("slipfront run cases/pile_pullout.toml", Run),
            ("slipfront figures recordings/pile_pullout.rrd --at 1,2,3,3.75,5,30", Run),
            ("slipfront run cases/fault_at_depth.toml", Run),
            ("slipfront figures recordings/fault_at_depth.rrd --at 400,570,576,580,584,590", Run),
            ("slipfront study cases/studies/fault_ensemble.toml", Shortened("--shard 1/16")),
            (
                "python3 scripts/fault_depth_bins.py recordings/fault_ensemble/events.csv",
                Mirror(concat!(
                    "python3 ",
                    env!("CARGO_MANIFEST_DIR"),
                    "/scripts/fault_depth_bins.py recordings/fault_ensemble/events.csv"
                )),
            ),
            ("slipfront run cases/cylinder_on_base.toml", Run),
            ("slipfront figures recordings/cylinder_on_base.rrd --at 0.4,0.7,0.95,1.05", Run),
        ],
    ),
    (
        "docs/cases.md",
        &[(
            "slipfront: cases/spring_block.toml: friction.mu_k = 0.5 must be less than friction.mu_s = 0.4",
            Output("slipfront run cases/spring_block.toml --set friction.mu_k=0.5"),
        )],
    ),
    (
        "docs/checkpoints.md",
        &[
            (
                "slipfront run CASE.toml --checkpoint-every 100",
                Mirror("slipfront run cases/paper_triangular.toml --checkpoint-every 100"),
            ),
            (
                "slipfront run CASE.toml --checkpoint-every",
                Mirror("slipfront run cases/paper_triangular.toml --checkpoint-every"),
            ),
            (
                "slipfront run CASE.toml --checkpoint-every 100 --keep-checkpoints",
                Mirror("slipfront run cases/paper_triangular.toml --checkpoint-every 100 --keep-checkpoints"),
            ),
            ("slipfront resume recordings/CASE.ckpt", Mirror("slipfront resume recordings/paper_triangular.ckpt")),
            (
                "slipfront resume recordings/CASE.ckpt --set time.t_end=5000",
                Mirror("slipfront resume recordings/paper_triangular.ckpt --set time.t_end=5000"),
            ),
            (
                "slipfront resume recordings/CASE.300s.ckpt --out-dir elsewhere/",
                Mirror("slipfront resume recordings/paper_triangular.300s.ckpt --out-dir elsewhere/"),
            ),
            (
                "slipfront resume recordings/CASE.ckpt || slipfront run CASE.toml --checkpoint-every 100",
                Mirror(
                    "slipfront resume recordings/paper_triangular.ckpt || slipfront run cases/paper_triangular.toml --checkpoint-every 100",
                ),
            ),
        ],
    ),
    (
        "docs/paper.md",
        &[
            (
                "cargo run --release --example perturbation -- cases/paper_triangular.toml --set friction.structure0=1.999999999998 --every 10",
                Run,
            ),
            ("cargo test --release --test paper_case -- --nocapture", Skip("part of the suite this test belongs to")),
            ("cargo run --release --example integrator_ensemble", Shortened("-- --members 2")),
            ("slipfront study cases/studies/normal_stress_sweep.toml", Shortened("--shard 1/64")),
        ],
    ),
    (
        "docs/recording.md",
        &[
            (
                "toml: [events]",
                TomlChecked {
                    path: "expect-full.toml",
                    prefix: "",
                    command: "slipfront check recordings/paper_triangular.rrd --expect expect-full.toml",
                },
            ),
            (
                "cargo run --release -- export recordings/paper_triangular.rrd --out recordings/paper_triangular.feather",
                Run,
            ),
            (
                "cargo run --release -- export recordings/paper_triangular.rrd --series contact/friction_force --series base/u_x --from 400 --to 450 --out recordings/pullout.csv",
                Run,
            ),
            ("python: import pandas as pd", Python),
            ("python: import rerun as rr", Python),
        ],
    ),
    (
        "docs/studies.md",
        &[
            (
                "toml: case = \"../paper_triangular.toml\" # the base case, relative to this file",
                Toml("cases/studies/STUDY.toml"),
            ),
            (
                "toml: [[rows]]",
                TomlChecked {
                    path: "cases/studies/rows.toml",
                    prefix: "case = \"../paper_triangular.toml\"\n[set]\n\"time.t_end\" = 100.0\n",
                    command: "slipfront study cases/studies/rows.toml --out-dir rows",
                },
            ),
            ("slipfront study cases/studies/paper_ensemble.toml", Skip("README.md's command, run above (about 2 min)")),
            (
                "slipfront study STUDY.toml --jobs 4 --out-dir runs",
                Mirror("slipfront study cases/studies/STUDY.toml --jobs 4 --out-dir runs"),
            ),
            ("slipfront study STUDY.toml --resume", Mirror("slipfront study cases/studies/STUDY.toml --resume")),
            ("slipfront study STUDY.toml --shard 3/8", Mirror("slipfront study cases/studies/STUDY.toml --shard 3/8")),
            ("slipfront study STUDY.toml --summarize", Mirror("slipfront study cases/studies/STUDY.toml --summarize")),
            (
                "slipfront study cases/studies/paper_ensemble.toml --slurm-array 8 --jobs 4 --out-dir /scratch/$USER/runs",
                Mirror(
                    "slipfront study cases/studies/paper_ensemble.toml --slurm-array 8 --jobs 4 --out-dir slurm/runs",
                ),
            ),
            (
                "sbatch --partition=compute --time=00:10:00 /scratch/$USER/runs/paper_ensemble/slurm/paper_ensemble.sbatch",
                // Task 8 of the array outside Slurm, where no job can be submitted (tests/slurm.rs
                // submits such a script to a Slurm cluster it brings up).
                Mirror(
                    "SLURM_CONF=/dev/null SLURM_ARRAY_TASK_ID=8 SLURM_ARRAY_JOB_ID=0 bash slurm/runs/paper_ensemble/slurm/paper_ensemble.sbatch",
                ),
            ),
            (
                "for i in 1 2 3 4; do ssh node$i \"cd $PWD && slipfront study cases/studies/paper_ensemble.toml --shard $i/4 --resume --quiet\" & done; wait",
                Mirror(
                    "for i in 1 2 3 4; do slipfront study cases/studies/paper_ensemble.toml --shard $i/4 --resume --quiet & done; wait",
                ),
            ),
            ("slipfront study cases/studies/paper_ensemble.toml --summarize", Run),
            (
                "parallel -j 8 slipfront study cases/studies/paper_ensemble.toml --jobs 1 --shard {}/8 --resume --quiet ::: $(seq 8)",
                Mirror("slipfront study cases/studies/paper_ensemble.toml --jobs 1 --shard 8/8 --resume --quiet"),
            ),
            ("slipfront study cases/studies/paper_ensemble.toml --resume", Run),
            (
                "rerun server -d study=recordings/paper_ensemble",
                Skip("serves until stopped; tests/study.rs serves a study so and queries it from another process"),
            ),
            (
                "python: # A colleague's Python, anywhere the server can be reached.",
                Skip("needs the server above; tests/study.rs runs this query (tests/python/read_study.py) against one"),
            ),
            ("python: import rerun as rr", Python),
        ],
    ),
    (
        "docs/validation.md",
        &[
            ("cargo test --release", Skip("the suite this test belongs to")),
            (
                "cargo test --release --test stress -- --ignored",
                Skip(".ci/run runs the stress matrix's long rows itself"),
            ),
        ],
    ),
];

/// One item of a file, as the docs hold it.
#[derive(Debug, Clone)]
enum Item {
    Command(String),
    Toml { key: String, body: String },
    Python { key: String, body: String },
    Output(String),
}

impl Item {
    fn key(&self) -> &str {
        match self {
            Item::Command(c) | Item::Output(c) => c,
            Item::Toml { key, .. } | Item::Python { key, .. } => key,
        }
    }
}

/// The items of a Markdown file, in order, and its command synopses.
fn items(markdown: &str) -> (Vec<Item>, Vec<String>) {
    let (mut items, mut synopses) = (Vec::new(), Vec::new());
    for block in fenced_blocks(markdown) {
        let first = block.body.lines().next().unwrap_or("").split_whitespace().collect::<Vec<_>>().join(" ");
        match block.lang.as_str() {
            "sh" => items.extend(shell_commands(&block.body).into_iter().map(Item::Command)),
            "toml" => items.push(Item::Toml { key: format!("toml: {first}"), body: block.body }),
            "python" => items.push(Item::Python { key: format!("python: {first}"), body: block.body }),
            _ => {
                for line in block.body.lines().map(str::trim) {
                    if line.starts_with("slipfront: ") {
                        items.push(Item::Output(line.to_string()));
                    } else if line.starts_with("slipfront ")
                        && !line.split_whitespace().take(3).any(|w| w.ends_with(':'))
                    {
                        // A synopsis; `slipfront study NAME: ...` is a message, not one.
                        synopses.push(line.to_string());
                    }
                }
            }
        }
    }
    (items, synopses)
}

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The Markdown files whose commands run: README.md, then docs/*.md by name.
fn markdown_files() -> Vec<String> {
    let mut docs: Vec<String> = std::fs::read_dir(repo().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    docs.sort();
    std::iter::once("README.md".to_string()).chain(docs).collect()
}

#[test]
fn every_command_in_the_docs_is_listed_in_order() {
    let mut problems = Vec::new();
    for file in markdown_files() {
        let text = std::fs::read_to_string(repo().join(&file)).unwrap();
        let found: Vec<String> = items(&text).0.iter().map(|i| i.key().to_string()).collect();
        let listed: Vec<String> = LISTED
            .iter()
            .find(|(f, _)| *f == file)
            .map(|(_, l)| l.iter().map(|(k, _)| k.to_string()).collect())
            .unwrap_or_default();
        for new in found.iter().filter(|f| !listed.contains(f)) {
            problems.push(format!(
                "{file}: `{new}` is not in tests/docs_commands.rs's LISTED: add it, with how CI runs it"
            ));
        }
        for gone in listed.iter().filter(|l| !found.contains(l)) {
            problems.push(format!("{file}: `{gone}` is listed but no longer in the file: remove it from LISTED"));
        }
        if problems.is_empty() && found != listed {
            problems.push(format!("{file}: the commands are listed in another order than the file's:\n{found:#?}"));
        }
        for (_, how) in LISTED.iter().filter(|(f, _)| *f == file).flat_map(|(_, l)| l.iter()) {
            if let Shortened(extra) = how {
                assert!(text.contains(&format!("`{extra}`")), "{file} does not say CI shortens a run with `{extra}`");
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn every_synopsis_names_options_the_command_has() {
    for file in markdown_files() {
        let text = std::fs::read_to_string(repo().join(&file)).unwrap();
        for line in items(&text).1 {
            let words: Vec<&str> = line.split_whitespace().collect();
            let output = common::binary().args([words[1], "--help"]).output().unwrap();
            let help = String::from_utf8_lossy(&output.stdout);
            assert!(output.status.success(), "{file}: `slipfront {} --help` failed", words[1]);
            for flag in words.iter().flat_map(|w| w.split(['[', ']', '|'])).filter(|w| w.starts_with("--")) {
                assert!(
                    help.contains(&format!("{flag} "))
                        || help.contains(&format!("{flag}\n"))
                        || help.contains(&format!("{flag} <")),
                    "{file}: `{line}` names {flag}, which `slipfront {} --help` does not have",
                    words[1]
                );
            }
        }
    }
}

/// The scratch folder: a copy of `cases/`, and `bin/` with `slipfront` and the examples.
fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slipfront-docs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    copy_dir(&repo().join("cases"), &dir.join("cases"));
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let slipfront = PathBuf::from(env!("CARGO_BIN_EXE_slipfront"));
    std::os::unix::fs::symlink(&slipfront, bin.join("slipfront")).unwrap();
    for example in ["perturbation", "integrator_ensemble"] {
        let built = slipfront.parent().unwrap().join("examples").join(example);
        assert!(built.is_file(), "{} is not built (cargo test builds the examples)", built.display());
        std::os::unix::fs::symlink(built, bin.join(example)).unwrap();
    }
    dir
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &to.join(entry.file_name()));
        } else {
            std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
        }
    }
}

/// `cargo run --release [--quiet] -- ARGS` as `slipfront ARGS`, and `cargo run --release
/// --example NAME [-- ARGS]` as `NAME ARGS`.
fn as_installed(command: &str) -> String {
    let command = command
        .replace("cargo run --release --quiet -- ", "slipfront ")
        .replace("cargo run --release -- ", "slipfront ");
    match command.strip_prefix("cargo run --release --example ") {
        Some(rest) => rest.replacen(" -- ", " ", 1),
        None => command,
    }
}

/// Runs `command` through `sh` in `dir`, with `bin/` first on `PATH`; panics with its output if
/// it fails. Returns its stderr.
fn sh(dir: &Path, command: &str, expect_success: bool) -> String {
    let path = format!("{}:{}", dir.join("bin").display(), std::env::var("PATH").unwrap_or_default());
    let started = std::time::Instant::now();
    // No window opens: `slipfront view` prints how to open the recording instead.
    let output = Command::new("sh")
        .args(["-c", command])
        .current_dir(dir)
        .env("PATH", path)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    println!("{:6.1} s  {command}", started.elapsed().as_secs_f64());
    assert_eq!(
        output.status.success(),
        expect_success,
        "`{command}` in {}:\n{}{stderr}",
        dir.display(),
        String::from_utf8_lossy(&output.stdout)
    );
    stderr
}

#[test]
fn every_command_in_the_docs_runs_as_written() {
    let dir = scratch();
    for file in markdown_files() {
        let text = std::fs::read_to_string(repo().join(&file)).unwrap();
        let listed = LISTED.iter().find(|(f, _)| *f == file).map_or(&[][..], |(_, l)| *l);
        for item in items(&text).0 {
            let Some((_, how)) = listed.iter().find(|(k, _)| *k == item.key()) else {
                panic!("{file}: `{}` is not listed (see every_command_in_the_docs_is_listed_in_order)", item.key());
            };
            match (how, &item) {
                (Run, Item::Command(c)) => drop(sh(&dir, &as_installed(c), true)),
                (Shortened(extra), Item::Command(c)) => drop(sh(&dir, &as_installed(&format!("{c} {extra}")), true)),
                (Mirror(instead), Item::Command(_)) => drop(sh(&dir, instead, true)),
                (Skip(why), _) => println!("  skipped  {}: {why}", item.key()),
                (Toml(path), Item::Toml { body, .. }) => std::fs::write(dir.join(path), body).unwrap(),
                (TomlChecked { path, prefix, command }, Item::Toml { body, .. }) => {
                    std::fs::write(dir.join(path), format!("{prefix}{body}")).unwrap();
                    sh(&dir, command, true);
                }
                (Python, Item::Python { body, .. }) => {
                    let output = match Command::new("python3").arg("-c").arg(body).current_dir(&dir).output() {
                        Ok(o) => o,
                        Err(_) => return skip_missing::<()>("python3").unwrap_or(()),
                    };
                    let stderr = String::from_utf8_lossy(&output.stderr);
                    if stderr.contains("ModuleNotFoundError") {
                        skip_missing::<()>(&format!("{file}'s Python recipe needs a package: {}", stderr.trim()));
                        continue;
                    }
                    assert!(output.status.success(), "{file}: the Python block `{}` failed:\n{stderr}", item.key());
                    println!("  python   {}", item.key());
                }
                (Output(command), Item::Output(line)) => {
                    let stderr = sh(&dir, command, false);
                    assert_eq!(stderr.trim_end().lines().last(), Some(line.as_str()), "{file}: `{command}`");
                }
                (how, item) => panic!("{file}: {how:?} does not fit {item:?}"),
            }
        }
    }
    // Kept for a look when a command fails (the panic above leaves it); removed once all pass.
    let _ = std::fs::remove_dir_all(&dir);
}
