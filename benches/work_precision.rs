//! Work-precision benchmark: error against wall time for the spring-block and the
//! paper case, across step sizes (fixed Wilson-θ) and tolerances (adaptive Wilson-θ by step
//! doubling, Tsitouras' explicit 5(4) pair and the L-stable SDIRK 4(3) on the rate form), and
//! `time.integrator = "auto"` (the default) at its default and at several `time.accuracy`.
//!
//! `cargo bench --bench work_precision` writes `recordings/bench/work_precision.md` (the table)
//! and `recordings/bench/work_precision.png` (the plot). `-- --quick` skips the finest
//! references and the repeated timings (for a smoke run).
//!
//! Errors are measured against a reference by Tsitouras' pair at a tolerance far below the
//! rows' (1e-13, 1e-12 for the paper case), whose own error is shown twice: against the same
//! method at a tolerance 10× looser, and against an independent one, Wilson-θ at a much finer
//! fixed step (second order: its difference from the reference is its own error).
//!
//! - onset: the largest relative error `|t - t_ref| / t_ref` of slip-event onsets, matching the
//!   k-th event of each segment; infinite if the runs have different events. The paper case is
//!   compared up to 450 s only: its event sequence is chaotic after its first slips (see
//!   `slipfront::study::ensemble`), and any change of step rearranges later events.
//! - traction: the relative L2 error of the total friction force over the first 300 s (the
//!   paper case: elastic waves and quasi-static loading before slip), and over the whole
//!   1000 s for the spring block (whose first slip comes at 790 s).
//! - after the slips (paper case): the same over 431–450 s, after the first rupture and the
//!   slip that follows it have ended (430.1 s) and before the events that no reference can
//!   check. The slips leave the block's undamped modes ringing; this is the error of that
//!   ringing, and the steps counted are those inside the window.
//!
//! Wall times are medians of three runs of the solver and event catalog (no files written),
//! taken one after another in this process (one run when it takes over 10 s).
//!
//! Last, the paper case as `slipfront run cases/paper_triangular.toml` runs it (1000 s, no
//! integrator named, the release binary as a child process), with its `.rrd` and with
//! `--no-rrd` in interleaved pairs: CPU time per run and per attempted step, and the
//! recording's share of it.

use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

use slipfront::case::{self, Case};
use slipfront::catalog::events::Catalog;
use slipfront::frame::Ending;
use slipfront::frame::{Frame, Layout};
use slipfront::run::{LoopOptions, Outcome, run};
use slipfront::scene;
use slipfront::sink::{Sink, SinkError};
use slipfront::study::figures::{WorkPrecisionCurve, plot_work_precision};

/// Collects `(t, total friction force)` of every step.
#[derive(Default)]
struct ForceTrace {
    times: Vec<f64>,
    force: Vec<f64>,
}

impl Sink for &mut ForceTrace {
    fn begin(&mut self, _: &Layout) -> Result<(), SinkError> {
        Ok(())
    }
    fn record(&mut self, frame: &Frame) -> Result<(), SinkError> {
        self.times.push(frame.time);
        self.force.push(frame.friction_force);
        Ok(())
    }
    fn finish(&mut self, _: Ending, _: Option<&Frame>, _: &Catalog) -> Result<(), SinkError> {
        Ok(())
    }
}

/// One run's results.
struct Measured {
    wall: f64,
    steps: u64,
    rejected: u64,
    /// SDIRK's Newton iterations and factorizations.
    newton: (u64, u64),
    /// Onsets of each segment's events, in order.
    onsets: BTreeMap<usize, Vec<f64>>,
    trace: ForceTrace,
}

fn load(name: &str, overrides: &[String]) -> Case {
    let path = format!("{}/cases/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    case::load(Path::new(&path), overrides).unwrap_or_else(|e| panic!("{name} {overrides:?}: {e}"))
}

fn measure_once(case: &Case) -> Result<Measured, String> {
    let mut scene = scene::build(case).expect("the benchmark's cases build");
    let mut trace = ForceTrace::default();
    let started = Instant::now();
    let outcome = {
        let mut sinks: Vec<Box<dyn Sink + '_>> = vec![Box::new(&mut trace)];
        run(scene.as_mut(), &case.time, &mut sinks, LoopOptions::for_case(case))
    };
    let wall = started.elapsed().as_secs_f64();
    let (steps, rejected, newton, catalog) = match outcome {
        Outcome::Completed { steps, rejected, newton_iterations, factorizations, catalog, .. } => {
            (steps, rejected, (newton_iterations, factorizations), catalog)
        }
        Outcome::Failed { error, .. } => return Err(format!("stopped at t = {:.1} s: {}", error.time, error.message)),
        other => return Err(format!("{other:?}")),
    };
    let mut onsets: BTreeMap<usize, Vec<f64>> = BTreeMap::new();
    for e in &catalog.events {
        onsets.entry(e.segment).or_default().push(e.onset);
    }
    Ok(Measured { wall, steps, rejected, newton, onsets, trace })
}

/// Runs `repeats` times and keeps the last run with the median wall time.
fn measure(case: &Case, repeats: usize) -> Result<Measured, String> {
    let mut walls = Vec::new();
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let m = measure_once(case)?;
        walls.push(m.wall);
        let long = m.wall > 10.0;
        last = Some(m);
        // Runs this long vary by less than a few per cent; one is enough.
        if long {
            break;
        }
    }
    walls.sort_by(f64::total_cmp);
    let mut m = last.expect("at least one run");
    m.wall = walls[walls.len() / 2];
    Ok(m)
}

/// Largest relative onset error over the reference's events before `horizon`.
fn onset_error(run: &Measured, reference: &Measured, horizon: f64) -> f64 {
    let mut worst = 0.0_f64;
    for (segment, ref_onsets) in &reference.onsets {
        let ref_onsets: Vec<f64> = ref_onsets.iter().copied().filter(|&t| t < horizon).collect();
        let onsets: Vec<f64> = run
            .onsets
            .get(segment)
            .map(|v| v.iter().copied().filter(|&t| t < horizon + 1.0).collect())
            .unwrap_or_default();
        if onsets.len() < ref_onsets.len() {
            return f64::INFINITY;
        }
        for (t, r) in onsets.iter().zip(&ref_onsets) {
            worst = worst.max((t - r).abs() / r);
        }
    }
    for (segment, onsets) in &run.onsets {
        let extra = onsets.iter().filter(|&&t| t < horizon - 1.0).count();
        let expected = reference.onsets.get(segment).map_or(0, |v| v.iter().filter(|&&t| t < horizon).count());
        if extra > expected {
            return f64::INFINITY;
        }
    }
    worst
}

/// Linear interpolation of a trace at `t`.
fn at(trace: &ForceTrace, t: f64) -> f64 {
    let i = trace.times.partition_point(|&x| x < t);
    if i == 0 {
        return trace.force[0];
    }
    if i >= trace.times.len() {
        return *trace.force.last().expect("non-empty trace");
    }
    let (t0, t1) = (trace.times[i - 1], trace.times[i]);
    let w = if t1 > t0 { (t - t0) / (t1 - t0) } else { 1.0 };
    trace.force[i - 1] * (1.0 - w) + trace.force[i] * w
}

/// Relative L2 error of the friction force over `[from, to]`, on a grid of 0.01 s.
fn traction_error(run: &Measured, reference: &Measured, (from, to): (f64, f64)) -> f64 {
    let n = ((to - from) / 0.01).round() as usize;
    let (mut diff, mut norm) = (0.0, 0.0);
    for k in 0..=n {
        let t = from + k as f64 * 0.01;
        let r = at(&reference.trace, t);
        diff += (at(&run.trace, t) - r).powi(2);
        norm += r * r;
    }
    (diff / norm).sqrt()
}

/// Steps of `run` that end inside `(from, to]`.
fn steps_within(run: &Measured, (from, to): (f64, f64)) -> u64 {
    run.trace.times.iter().filter(|&&t| t > from && t <= to).count() as u64
}

/// How `ours` compares with Wilson's `theirs` (steps, attempts or time): "N× fewer …" or, where
/// `ours` is the larger, "N× more …".
fn compared(theirs: f64, ours: f64, fewer: &str, more: &str) -> String {
    if ours <= theirs { format!("{:.1}× {fewer}", theirs / ours) } else { format!("{:.1}× {more}", ours / theirs) }
}

struct Benchmark {
    name: &'static str,
    title: &'static str,
    t_end: f64,
    horizon: f64,
    window: f64,
    /// The window after the first slips, where there is one.
    after_slips: Option<(f64, f64)>,
    fixed: &'static [f64],
    tolerances: &'static [f64],
    tsit5: &'static [f64],
    sdirk4: &'static [f64],
    /// Tsitouras' pair's tolerance for the reference.
    reference_tolerance: f64,
    /// Wilson-θ's step for the independent check of the reference.
    check_dt: f64,
}

struct Row {
    integrator: &'static str,
    setting: String,
    m: Result<Measured, String>,
    onset: f64,
    traction: f64,
    /// Traction error after the first slips and the steps taken there.
    after_slips: Option<(f64, u64)>,
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let repeats = if quick { 1 } else { 3 };
    let benchmarks = [
        Benchmark {
            name: "spring_block",
            title: "spring block, 1000 s",
            t_end: 1000.0,
            horizon: 1000.0,
            window: 1000.0,
            after_slips: None,
            fixed: &[0.05, 0.02, 0.01, 0.005, 0.002, 0.001],
            tolerances: &[1e-4, 1e-5, 1e-6, 1e-7],
            tsit5: &[1e-6, 1e-8, 1e-10, 1e-12],
            sdirk4: &[1e-6, 1e-7, 1e-8, 1e-9],
            reference_tolerance: 1e-13,
            check_dt: if quick { 2e-4 } else { 5e-5 },
        },
        Benchmark {
            name: "paper_triangular",
            title: "paper case, 450 s",
            t_end: 450.0,
            horizon: 450.0,
            window: 300.0,
            after_slips: Some((431.0, 450.0)),
            fixed: &[0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001],
            tolerances: &[1e-5, 1e-6, 1e-7],
            tsit5: &[1e-5, 1e-6, 1e-7, 1e-8, 1e-10],
            sdirk4: &[1e-6, 5e-7, 3e-7, 2e-7, 1e-7, 1e-8],
            reference_tolerance: 1e-12,
            check_dt: if quick { 2e-3 } else { 5e-4 },
        },
    ];
    let mut report = String::from(
        "# Work-precision benchmark\n\nGenerated by `cargo bench --bench work_precision`. Errors against a \
         reference by Tsitouras' pair at a far tighter tolerance (checked below against the same method 10× \
         looser and against Wilson-θ at a much finer step); wall times are medians of 3 runs (1 when over 10 s) \
         of the solver and event catalog, without output files. `work` counts integrator steps solved for \
         Wilson-θ (one per fixed step, three per adaptive attempt: one whole step and two halves) and \
         right-hand sides for Tsitouras' pair (six per attempt, besides the steps that locate slip-rate \
         crossings), and Newton iterations (one right-hand side and one solve each, with the steps that locate \
         crossings) and factorizations for SDIRK4 (five stages per attempt).\n",
    );
    let mut panels = Vec::new();
    for b in &benchmarks {
        let with = |extra: &[String]| {
            let mut o = vec![format!("time.t_end={}", b.t_end)];
            o.extend_from_slice(extra);
            load(b.name, &o)
        };
        let tsit5 = |tolerance: f64| with(&["time.integrator=tsit5".into(), format!("time.tolerance={tolerance:e}")]);
        eprintln!("{}: reference by tsit5 at tolerance {:e}", b.name, b.reference_tolerance);
        let reference = measure(&tsit5(b.reference_tolerance), 1).expect("the reference completes");
        let looser = measure(&tsit5(10.0 * b.reference_tolerance), 1).expect("the check completes");
        let wilson = |dt: f64| with(&["time.integrator=wilson".into(), format!("time.dt={dt}")]);
        let check = measure(&wilson(b.check_dt), 1).expect("the check completes");
        let mut rows = Vec::new();
        for &dt in b.fixed {
            eprintln!("{}: fixed dt = {dt}", b.name);
            let m = measure(&wilson(dt), repeats);
            rows.push(Row {
                integrator: "Wilson-θ fixed",
                setting: format!("dt = {dt} s"),
                onset: 0.0,
                traction: 0.0,
                after_slips: None,
                m,
            });
        }
        // `auto` (no integrator named) at its default and at several accuracies.
        for accuracy in [None, Some(1e-5), Some(1e-6), Some(1e-7)] {
            eprintln!("{}: auto, accuracy {accuracy:?}", b.name);
            let case = with(&accuracy.map(|a| vec![format!("time.accuracy={a:e}")]).unwrap_or_default());
            let chosen = case.time.method.name();
            let m = measure(&case, repeats);
            rows.push(Row {
                integrator: "auto",
                setting: accuracy.map_or(format!("default ({chosen})"), |a| format!("accuracy = {a:e} ({chosen})")),
                onset: 0.0,
                traction: 0.0,
                after_slips: None,
                m,
            });
        }
        // The adaptive rows: Wilson-θ by step doubling, then the two Runge–Kutta methods.
        let adaptive: [(&'static str, &[f64], &str); 3] = [
            ("Wilson-θ adaptive", b.tolerances, "wilson"),
            ("Tsit5", b.tsit5, "tsit5"),
            ("SDIRK4", b.sdirk4, "sdirk4"),
        ];
        for (integrator, tolerances, key) in adaptive {
            for &tol in tolerances {
                eprintln!("{}: {key} tolerance = {tol}", b.name);
                let case = with(&[format!("time.integrator={key}"), format!("time.tolerance={tol:e}")]);
                let m = measure(&case, repeats);
                rows.push(Row {
                    integrator,
                    setting: format!("tolerance = {tol:e}"),
                    onset: 0.0,
                    traction: 0.0,
                    after_slips: None,
                    m,
                });
            }
        }
        for row in &mut rows {
            if let Ok(m) = &row.m {
                row.onset = onset_error(m, &reference, b.horizon);
                row.traction = traction_error(m, &reference, (0.0, b.window));
                row.after_slips =
                    b.after_slips.map(|window| (traction_error(m, &reference, window), steps_within(m, window)));
            }
        }
        report.push_str(&format!(
            "\n## {}\n\nReference: Tsit5 at tolerance {:e}, {} steps, {:.2} s wall. Its checks: Tsit5 at \
             tolerance {:e} differs from it by {:.2e} in onset and {:.2e} in traction; Wilson-θ at dt = {} s \
             (independent, second order) by {:.2e} and {:.2e}.{}\n\n| integrator | setting | steps | rejected | work | \
             wall (s) | onset error | traction L2 error | after the slips: traction L2 error (steps there) |\n\
             |---|---|---|---|---|---|---|---|---|\n",
            b.title,
            b.reference_tolerance,
            reference.steps,
            reference.wall,
            10.0 * b.reference_tolerance,
            onset_error(&looser, &reference, b.horizon),
            traction_error(&looser, &reference, (0.0, b.window)),
            b.check_dt,
            onset_error(&check, &reference, b.horizon),
            traction_error(&check, &reference, (0.0, b.window)),
            b.after_slips.map_or(String::new(), |window| format!(
                " After the slips ({} to {} s, {} of its steps), the two differ from it by {:.2e} and {:.2e} \
                 in traction.",
                window.0,
                window.1,
                steps_within(&reference, window),
                traction_error(&looser, &reference, window),
                traction_error(&check, &reference, window)
            )),
        ));
        for row in &rows {
            let line = match &row.m {
                Ok(m) => {
                    let work = match row.integrator {
                        "Tsit5" => format!("{} rhs", 6 * (m.steps + m.rejected)),
                        "Wilson-θ adaptive" => format!("{} solves", 3 * (m.steps + m.rejected)),
                        "SDIRK4" => format!("{} Newton, {} factorizations", m.newton.0, m.newton.1),
                        "auto" => format!("{} attempts", m.steps + m.rejected),
                        _ => format!("{} solves", m.steps),
                    };
                    let after = row.after_slips.map_or("–".into(), |(e, steps)| format!("{e:.2e} ({steps})"));
                    format!(
                        "| {} | {} | {} | {} | {} | {:.3} | {:.2e} | {:.2e} | {after} |\n",
                        row.integrator, row.setting, m.steps, m.rejected, work, m.wall, row.onset, row.traction
                    )
                }
                Err(why) => format!("| {} | {} | {why} | | | | | | |\n", row.integrator, row.setting),
            };
            report.push_str(&line);
        }
        for metric in [Metric::Onset, Metric::AfterSlips] {
            for method in ["Tsit5", "SDIRK4", "auto"] {
                report.push_str(&equal_error(&rows, method, metric));
            }
        }
        for (metric, pick) in [("onset", 0), ("traction", 1)] {
            let curves = ["Wilson-θ fixed", "Wilson-θ adaptive", "Tsit5", "SDIRK4", "auto"]
                .iter()
                .map(|name| WorkPrecisionCurve {
                    label: name.to_string(),
                    points: rows
                        .iter()
                        .filter(|r| r.integrator == *name)
                        .filter_map(|r| {
                            r.m.as_ref().ok().map(|m| (m.wall, if pick == 0 { r.onset } else { r.traction }))
                        })
                        .collect(),
                })
                .collect();
            panels.push((format!("{}: {metric} error", b.title), curves));
        }
    }
    let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("recordings/bench");
    std::fs::create_dir_all(&out).expect("recordings/bench is writable");
    eprintln!("paper_triangular: slipfront run, 1000 s, with and without its recording");
    report.push_str(&paper_case_as_run(if quick { 1 } else { 7 }, &out));
    std::fs::write(out.join("work_precision.md"), &report).expect("the table is written");
    plot_work_precision(&out.join("work_precision.png"), &panels).expect("the plot is written");
    println!("{report}");
    println!("wrote {} and work_precision.png", out.join("work_precision.md").display());
}

/// The error by which [`equal_error`] matches rows.
#[derive(Clone, Copy, PartialEq)]
enum Metric {
    /// Onset error; the whole run's steps, attempts and wall time are compared.
    Onset,
    /// Traction error after the slips; the steps inside that window are compared.
    AfterSlips,
}

impl Metric {
    /// The row's error and the steps compared, if it has this metric.
    fn of(self, row: &Row, m: &Measured) -> Option<(f64, u64)> {
        match self {
            Metric::Onset => Some((row.onset, m.steps)),
            Metric::AfterSlips => row.after_slips,
        }
    }
}

/// For each fixed Wilson-θ row with a finite error by `metric`, the row of `method` with the
/// fewest steps at an error at most as large: the ratio of steps, and for the onset error of
/// attempts (steps and rejections) and of wall time.
fn equal_error(rows: &[Row], method: &str, metric: Metric) -> String {
    fn measured(r: &Row, metric: Metric) -> Option<(&Measured, f64, u64)> {
        r.m.as_ref().ok().and_then(|m| metric.of(r, m).map(|(e, steps)| (m, e, steps)))
    }
    let (what, mut text) = match metric {
        Metric::Onset => ("onset", format!("\nAt equal or smaller onset error, {method} against fixed Wilson-θ:\n\n")),
        Metric::AfterSlips => (
            "traction after the slips",
            format!(
                "\nAt equal or smaller traction error after the slips, {method} against fixed Wilson-θ, steps inside \
                 that window:\n\n"
            ),
        ),
    };
    if rows.iter().all(|r| measured(r, metric).is_none()) {
        return String::new();
    }
    for fixed in rows.iter().filter(|r| r.integrator == "Wilson-θ fixed") {
        let Some((f, f_error, f_steps)) = measured(fixed, metric).filter(|(_, e, _)| e.is_finite()) else { continue };
        let best = rows
            .iter()
            .filter(|r| r.integrator == method)
            .filter_map(|r| measured(r, metric).map(|x| (r, x)))
            .filter(|(_, (_, e, _))| *e <= f_error)
            .min_by_key(|(_, (_, _, steps))| *steps);
        text.push_str(&match best {
            Some((r, (m, e, steps))) if metric == Metric::Onset => format!(
                "- Wilson-θ {} ({what} error {f_error:.1e}, {f_steps} steps, {:.3} s): {method} {} ({e:.1e}) takes \
                 {steps} steps and {} rejected, {} and {}, in {:.3} s, {}\n",
                fixed.setting,
                f.wall,
                r.setting,
                m.rejected,
                compared(f_steps as f64, steps as f64, "fewer steps", "more steps"),
                compared(f_steps as f64, (steps + m.rejected) as f64, "fewer attempts", "more attempts"),
                m.wall,
                compared(f.wall, m.wall, "less time", "more time")
            ),
            Some((r, (_, e, steps))) => format!(
                "- Wilson-θ {} ({what} error {f_error:.1e}, {f_steps} steps): {method} {} ({e:.1e}) takes {steps} \
                 steps, {}\n",
                fixed.setting,
                r.setting,
                compared(f_steps as f64, steps as f64, "fewer", "more")
            ),
            None => {
                format!("- Wilson-θ {} ({what} error {f_error:.1e}): no {method} row is as accurate\n", fixed.setting)
            }
        });
    }
    text
}

/// One `slipfront run` of the paper case (1000 s, no integrator named) as a child process, its
/// outputs in `out`: the CPU time of the process and its threads (user + system, s, from
/// `wait4`), and its steps and rejected attempts from the summary it prints.
fn run_paper_case(extra: &[&str], out: &Path) -> (f64, u64, u64) {
    use std::io::Read;
    let case = format!("{}/cases/paper_triangular.toml", env!("CARGO_MANIFEST_DIR"));
    // Reaped by `wait4` below, which std's `wait` cannot replace: it also returns the usage.
    #[allow(clippy::zombie_processes)]
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_slipfront"))
        .args(["run", &case, "--progress", "none", "--out-dir", out.to_str().expect("a UTF-8 path")])
        .args(extra)
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("slipfront runs");
    let (mut status, mut usage) = (0, unsafe { std::mem::zeroed::<libc::rusage>() });
    // SAFETY: waits for our own child, which std has not reaped; `usage` is a plain struct.
    let reaped = unsafe { libc::wait4(child.id() as libc::pid_t, &mut status, 0, &mut usage) };
    assert!(reaped > 0 && status == 0, "slipfront run {extra:?} failed (status {status})");
    let mut summary = String::new();
    child.stdout.take().expect("piped").read_to_string(&mut summary).expect("the summary is text");
    let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    let number_before = |text: &str, marker: &str| -> u64 {
        let head = &text[..text.find(marker).unwrap_or_else(|| panic!("no {marker:?} in {text}"))];
        head.rsplit(|c: char| !c.is_ascii_digit()).next().and_then(|n| n.parse().ok()).expect("a count")
    };
    let steps = number_before(&summary, " steps (adaptive");
    let rejected = number_before(&summary, " rejected)");
    (seconds(usage.ru_utime) + seconds(usage.ru_stime), steps, rejected)
}

/// The paper case as `slipfront run cases/paper_triangular.toml` runs it, with its `.rrd` and
/// with `--no-rrd`, in `pairs` interleaved pairs of whole processes after one pair not counted:
/// each one's CPU time (median), per attempted step, and the recording's share (the median of
/// the pairs' ratios).
fn paper_case_as_run(pairs: usize, out: &Path) -> String {
    let scratch = out.join("paper_case_runs");
    let (mut with, mut without, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
    let mut counts = (0, 0);
    for pair in 0..=pairs {
        let (a, steps, rejected) = run_paper_case(&[], &scratch);
        let (b, ..) = run_paper_case(&["--no-rrd"], &scratch);
        counts = (steps, rejected);
        if pair > 0 {
            with.push(a);
            without.push(b);
            ratios.push(a / b);
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (a, b) = (median(&mut with), median(&mut without));
    let low = ratios.iter().copied().fold(f64::INFINITY, f64::min);
    let high = ratios.iter().copied().fold(0.0_f64, f64::max);
    let ratio = median(&mut ratios);
    let attempts = counts.0 + counts.1;
    let _ = std::fs::remove_dir_all(&scratch);
    format!(
        "\n## The paper case with no integrator named, as `slipfront run` runs it\n\n\
         `slipfront run cases/paper_triangular.toml` (1000 s; Tsitouras' pair at tolerance 1e-8), with its `.rrd` \
         and with `--no-rrd`, {pairs} interleaved pairs of whole processes after one not counted. CPU is user + \
         system time of the process and its threads (the recording is encoded on a thread of its own).\n\n\
         | run | steps | rejected | attempts | CPU (s), median | CPU per attempt (µs) |\n|---|---|---|---|---|---|\n\
         | with its `.rrd` | {} | {} | {attempts} | {a:.3} | {:.2} |\n\
         | `--no-rrd` | {} | {} | {attempts} | {b:.3} | {:.2} |\n\n\
         The recording's share: CPU with it over CPU without, {ratio:.3} (median of the pairs; {low:.3} to {high:.3}).\n",
        counts.0,
        counts.1,
        1e6 * a / attempts as f64,
        counts.0,
        counts.1,
        1e6 * b / attempts as f64,
    )
}
