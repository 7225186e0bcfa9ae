//! `slipfront export`: tables read back by pandas and polars equal to the recording bit for
//! bit, the selection, window and thinning, the MCAP log's table equal to the recording's, clear
//! errors, and the docs' Python recipes run as written.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{binary, case_path, fenced_blocks, section, shell_commands, skip_missing};
use slipfront::inspect::rrd;

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slipfront-export-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the paper case into `out` (with an MCAP log) and returns the recording's path.
fn paper_run(out: &Path, sets: &[&str]) -> PathBuf {
    let mut cmd = binary();
    cmd.args(["run", &case_path("paper_triangular.toml"), "--quiet", "--out-dir"]).arg(out);
    cmd.arg("--mcap").arg(out.join("paper_triangular.mcap"));
    for s in sets {
        cmd.args(["--set", s]);
    }
    assert!(cmd.status().unwrap().success());
    out.join("paper_triangular.rrd")
}

/// `slipfront export ARGS...`: exit code, stdout, stderr.
fn export(args: &[&str]) -> (i32, String, String) {
    let out = binary().arg("export").args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

#[test]
fn pandas_and_polars_read_the_recordings_values_bit_for_bit() {
    let out = scratch("bits");
    let rrd = paper_run(&out, &["time.t_end=450"]);
    let (feather, csv) = (out.join("all.feather"), out.join("all.csv"));
    assert_eq!(export(&[s(&rrd), "--out", s(&feather)]).0, 0);
    assert_eq!(export(&[s(&rrd), "--out", s(&csv)]).0, 0);
    // The MCAP log of the same run gives the same table, byte for byte.
    let from_mcap = out.join("mcap.csv");
    assert_eq!(export(&[s(&out.join("paper_triangular.mcap")), "--out", s(&from_mcap)]).0, 0);
    assert_eq!(std::fs::read(&from_mcap).unwrap(), std::fs::read(&csv).unwrap(), "the MCAP log's table");

    let recording = rrd::read(&rrd).unwrap();
    let rows = recording.series["contact/friction_force"].steps.len();
    let series = recording.series.len();
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/python/read_export.py");
    let output = Command::new("python3").arg(script).arg(&rrd).arg(&feather).arg(&csv).output();
    let text = match output {
        Ok(o) if o.status.success() => String::from_utf8(o.stdout).unwrap(),
        Ok(o) if o.status.code() == Some(3) => {
            return skip_missing::<()>(&format!(
                "pandas, polars, pyarrow or the Rerun SDK ({}; pip install polars pyarrow pandas \"rerun-sdk[datafusion]==0.36.*\")",
                String::from_utf8_lossy(&o.stderr).trim()
            ))
            .unwrap_or(());
        }
        Ok(o) => panic!("the exported tables differ from the recording:\n{}", String::from_utf8_lossy(&o.stderr)),
        Err(_) => return skip_missing::<()>("python3").unwrap_or(()),
    };
    println!("{text}");
    assert!(text.contains(&format!("rows {rows} columns {}", series + 2)), "every row and series: {text}");
    // What docs/recording.md says of the whole-recording query.
    assert!(
        text.contains("whole-recording to_pandas: ArrowNotImplementedError") && text.contains("dense_union"),
        "{text}"
    );
}

#[test]
fn a_selection_a_window_and_thinning() {
    let out = scratch("select");
    let rrd = paper_run(&out, &["time.t_end=450"]);
    let (code, stdout, _) = export(&[
        s(&rrd),
        "--series",
        "contact/friction_force,traction_t_Pa_seg9",
        "--series",
        "contact/structure[0]",
        "--from",
        "400",
        "--to",
        "440",
        "--every",
        "0.5",
        "--out",
        "-",
    ]);
    assert_eq!(code, 0);
    let mut lines = stdout.lines();
    assert_eq!(lines.next().unwrap(), "step,sim_time_s,traction_t_Pa_seg9,structure_seg0,friction_force_N_per_m");
    let recording = rrd::read(&rrd).unwrap();
    // The rows a greedy pass keeps: inside the window, each at least 0.5 s after the last kept.
    let all = &recording.series["contact/friction_force"];
    let mut expected: Vec<i64> = Vec::new();
    let mut last: Option<f64> = None;
    for (&step, &time) in all.steps.iter().zip(&all.times) {
        if (400.0..=440.0).contains(&time) && last.is_none_or(|l| time - l >= 0.5 * (1.0 - 1e-9)) {
            expected.push(step);
            last = Some(time);
        }
    }
    let mut steps = Vec::new();
    for line in lines {
        let fields: Vec<&str> = line.split(',').collect();
        let step: i64 = fields[0].parse().unwrap();
        let row = all.steps.binary_search(&step).unwrap();
        assert_eq!(fields[1].parse::<f64>().unwrap().to_bits(), all.times[row].to_bits(), "time at step {step}");
        for (field, series) in
            fields[2..].iter().zip(["contact/traction_t[9]", "contact/structure[0]", "contact/friction_force"])
        {
            let recorded = &recording.series[series];
            let row = recorded.steps.binary_search(&step).unwrap();
            assert_eq!(
                field.parse::<f64>().unwrap().to_bits(),
                recorded.values[row].to_bits(),
                "{series} at step {step}"
            );
        }
        steps.push(step);
    }
    assert_eq!(steps, expected, "the rows kept");
    // The window holds rows much denser than 0.5 s in slip: thinning removed some.
    let inside = all.times.iter().filter(|t| (400.0..=440.0).contains(*t)).count();
    assert!(steps.len() < inside, "{} of {inside} rows kept", steps.len());
}

#[test]
fn bad_arguments_are_refused_with_exit_2() {
    let out = scratch("bad");
    let rrd = paper_run(&out, &["time.t_end=20"]);
    let refused = |args: &[&str], says: &str| {
        let (code, _, stderr) = export(args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    };
    refused(&[s(&rrd), "--series", "contact/nothing"], "--series = contact/nothing is not in the recording");
    refused(&[s(&rrd), "--from", "5", "--to", "1"], "--from = 5 must not be after --to = 1");
    refused(&[s(&rrd), "--every", "0"], "--every = 0 must be a positive time in seconds");
    refused(&[s(&rrd), "--out", s(&out.join("table.txt"))], "name the table .csv, .feather, .arrow or .ipc");
    refused(&[s(&rrd), "--out", s(&rrd), "--format", "csv"], "is the input itself");
    refused(&[s(&out.join("missing.rrd"))], "no such file");
    refused(&[s(&out.join("paper_triangular.events.csv")), "--out", "-"], "not a Rerun recording");
    refused(&[s(&out.join("paper_triangular.events.csv"))], "is the input itself");
    refused(&[s(&rrd), "--format", "xlsx"], "invalid value 'xlsx'");
    assert!(rrd::read(&rrd).unwrap().problem.is_none(), "the input is untouched");
}

#[test]
fn the_docs_python_recipes_run_as_written() {
    let docs = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/recording.md")).unwrap();
    let blocks = fenced_blocks(section(&docs, "Reading results in Python"));
    let work = scratch("docs");
    std::fs::create_dir_all(work.join("recordings")).unwrap();
    paper_run(&work.join("recordings"), &[]);
    let mut ran = 0;
    for block in &blocks {
        match block.lang.as_str() {
            "sh" => {
                for command in shell_commands(&block.body) {
                    let args = command.strip_prefix("cargo run --release -- ").expect("a slipfront command");
                    let status = binary().args(args.split(' ')).current_dir(&work).status().unwrap();
                    assert!(status.success(), "{command}");
                }
            }
            "python" => {
                let output = match Command::new("python3").arg("-c").arg(&block.body).current_dir(&work).output() {
                    Ok(o) => o,
                    Err(_) => return skip_missing::<()>("python3").unwrap_or(()),
                };
                let stderr = String::from_utf8_lossy(&output.stderr);
                if stderr.contains("ModuleNotFoundError") {
                    return skip_missing::<()>(&format!("a Python package of the recipe: {}", stderr.trim()))
                        .unwrap_or(());
                }
                assert!(output.status.success(), "the recipe at line {} failed:\n{stderr}", block.line);
                println!("{}", String::from_utf8_lossy(&output.stdout));
            }
            other => panic!("an unexpected {other:?} block in the section"),
        }
        ran += 1;
    }
    assert_eq!(ran, 3, "the section's command block and its two recipes");
}
