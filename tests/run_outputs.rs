//! What a run says about its outputs: a rerun that replaces an earlier run's files says so, a
//! rupture catalog only where the summary counts ruptures, a negative friction-force drop in
//! that catalog is a slow slip that the moving base kept loading, and the recording holds the
//! step on which each slip ends.

mod common;

use std::path::{Path, PathBuf};

use common::{binary, case_path};
use slipfront::inspect::rrd;

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slipfront-outputs-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `slipfront run cases/<file> --set ...` into `out`: (stdout, stderr).
fn run(file: &str, sets: &[&str], out: &Path) -> (String, String) {
    let mut cmd = binary();
    cmd.args(["run", &case_path(file), "--progress", "none", "--out-dir"]).arg(out);
    for s in sets {
        cmd.args(["--set", s]);
    }
    let output = cmd.output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    (String::from_utf8(output.stdout).unwrap(), String::from_utf8(output.stderr).unwrap())
}

#[test]
fn a_rerun_says_which_files_of_an_earlier_run_it_replaces() {
    let out = scratch("rerun");
    let (_, first) = run("spring_block.toml", &["time.t_end=50"], &out);
    assert_eq!(first, "", "nothing to replace on a first run");
    let (_, second) = run("spring_block.toml", &["time.t_end=60"], &out);
    let lines: Vec<&str> = second.lines().collect();
    assert_eq!(lines.len(), 1, "{second}");
    assert!(lines[0].starts_with("slipfront: replacing an earlier run's "), "{second}");
    for name in ["spring_block.rrd", "spring_block.events.csv"] {
        assert!(lines[0].contains(&out.join(name).display().to_string()), "{name}: {second}");
    }
    assert!(lines[0].contains("--out-dir DIR"), "{second}");
    // Quiet means quiet.
    let output = binary()
        .args(["run", &case_path("spring_block.toml"), "--quiet", "--set", "time.t_end=50", "--out-dir"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(output.stderr.is_empty(), "{}", String::from_utf8_lossy(&output.stderr));
}

#[test]
fn ruptures_are_counted_where_a_rupture_catalog_is_written() {
    let out = scratch("ruptures");
    // The spring block slips twice in its 1000 s: events, and no rupture catalog or count.
    let (summary, _) = run("spring_block.toml", &[], &out);
    assert!(summary.contains(" slip events: "), "{summary}");
    assert!(!summary.contains(" ruptures: "), "{summary}");
    assert!(!out.join("spring_block.ruptures.csv").exists());
    let events = std::fs::read_to_string(out.join("spring_block.events.csv")).unwrap();
    assert!(events.lines().count() > 1, "the spring block slipped: {events}");
    let (summary, _) = run("point_loading.toml", &[], &out);
    assert!(!summary.contains(" ruptures: ") && !out.join("point_loading.ruptures.csv").exists(), "{summary}");
    // A block counts its ruptures and writes them, one row each.
    let (summary, _) = run("paper_triangular.toml", &[], &out);
    let count: usize = summary.split(" ruptures").next().unwrap().rsplit(' ').next().unwrap().parse().unwrap();
    let csv = std::fs::read_to_string(out.join("paper_triangular.ruptures.csv")).unwrap();
    assert_eq!(csv.lines().count() - 1, count, "{summary}");
}

#[test]
fn a_negative_friction_force_drop_is_a_slow_slip_that_the_base_kept_loading() {
    let out = scratch("drop");
    // Every step recorded, so that the recording holds the steps either side of every onset
    // and end, between which the catalog interpolates too.
    run("paper_triangular.toml", &["record.stick_every=1"], &out);
    let recording = rrd::read(&out.join("paper_triangular.rrd")).unwrap();
    let force = &recording.series["contact/friction_force"];
    let rows = |name: &str| -> Vec<Vec<f64>> {
        let csv = std::fs::read_to_string(out.join(name)).unwrap();
        csv.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect()
    };
    let (ruptures, events) = (rows("paper_triangular.ruptures.csv"), rows("paper_triangular.events.csv"));
    let threshold = 3.0e-3; // events.slip_rate_threshold of the case (m/s)
    let mut negative = 0;
    for r in &ruptures {
        let (onset, end, first, last, drop) = (r[0], r[1], r[3], r[4], r[7]);
        // The drop is the total friction force at the onset minus at the end, each linearly
        // interpolated between the steps either side, as the recording's rows give them: equal
        // but for the recording's times, whole nanoseconds (the force rings at up to a few
        // hundred N/m per second after a slip, a few 1e-7 N/m per nanosecond; measured, the
        // two differ by at most 4e-8 N/m).
        let recorded = interpolate(force, onset) - interpolate(force, end);
        println!("rupture at {onset:.2} s: drop {drop:.3} N/m, recording {recorded:.3} N/m ({:.1e})", drop - recorded);
        assert!((drop - recorded).abs() < 1e-6, "drop {drop} N/m against {recorded} N/m from the recording");
        if drop >= 0.0 {
            continue;
        }
        negative += 1;
        // Each of its segment events slipped barely above the threshold, with its traction
        // rising from onset to end: a slow slip below the strength's peak, not a stress drop.
        let members: Vec<&Vec<f64>> =
            events.iter().filter(|e| e[1] >= onset - 1e-9 && e[1] <= end && e[0] >= first && e[0] <= last).collect();
        assert!(!members.is_empty());
        for e in members {
            assert!(e[4] < 2.0 * threshold, "a fast event in a rupture of negative drop: {e:?}");
            assert!(e[6] > e[5], "an event whose traction fell, in a rupture of negative drop: {e:?}");
        }
        assert!(last - first + 1.0 < 10.0, "a whole-surface rupture with a negative drop: {r:?}");
    }
    assert!(negative > 0, "the paper case has slow slips with negative drops (docs/recording.md)");
    // The ruptures that did drop the force include the whole-surface one.
    assert!(ruptures.iter().any(|r| r[5] == 10.0 && r[7] > 100.0), "{ruptures:?}");
}

/// The series' value at `t`, linearly interpolated between the rows around it.
fn interpolate(series: &slipfront::inspect::Series, t: f64) -> f64 {
    let i = series.times.partition_point(|&x| x <= t).clamp(1, series.times.len() - 1);
    let (t0, t1, v0, v1) = (series.times[i - 1], series.times[i], series.values[i - 1], series.values[i]);
    v0 + (v1 - v0) * (t - t0) / (t1 - t0)
}

#[test]
fn every_slip_event_ends_between_two_consecutive_recorded_steps() {
    // In stick the recording keeps one step in `record.stick_every` (50); every step while a
    // segment slips; and the step on which the last slip ends. So each event's end, which the
    // catalog places between the last step above the threshold and the first below it, lies
    // between two rows of consecutive steps: the recording shows every slip stop where it stops.
    let out = scratch("ends");
    run("paper_triangular.toml", &[], &out);
    let recording = rrd::read(&out.join("paper_triangular.rrd")).unwrap();
    let rows = &recording.series["contact/friction_force"];
    let csv = std::fs::read_to_string(out.join("paper_triangular.events.csv")).unwrap();
    let ends: Vec<f64> = csv.lines().skip(1).map(|l| l.split(',').nth(2).unwrap().parse().unwrap()).collect();
    assert!(ends.len() > 20, "the paper case has its slips: {}", ends.len());
    let thinned = rows.steps.windows(2).filter(|w| w[1] - w[0] > 1).count();
    assert!(thinned > 1000, "stick is thinned: {thinned} gaps");
    // The recording's times are whole nanoseconds.
    let ns = 1e-9;
    for end in ends {
        let after = rows.times.partition_point(|&t| t < end - ns);
        assert!(after > 0 && after < rows.times.len(), "an end at {end} s outside the recording");
        let (before_step, after_step) = (rows.steps[after - 1], rows.steps[after]);
        assert_eq!(
            after_step - before_step,
            1,
            "the end at {end} s lies between recorded steps {before_step} and {after_step}"
        );
    }
}

#[test]
fn slip_every_thins_the_slips_and_keeps_every_change_between_stick_and_slip() {
    // The paper case to 450 s (its first rupture, 420 to 430 s) recorded at every slipping
    // step and at every 10th: the catalogs are the same (computed from every step), the thinned
    // rows are rows of the full recording, far fewer through the rupture, and the step where
    // the contact goes from stick to slip is still the first row after the first onset.
    let (all, thin) = (scratch("slip-all"), scratch("slip-thin"));
    run("paper_triangular.toml", &["time.t_end=450"], &all);
    run("paper_triangular.toml", &["time.t_end=450", "record.slip_every=10"], &thin);
    let read = |dir: &Path, name: &str| std::fs::read(dir.join(name)).unwrap();
    for name in ["paper_triangular.events.csv", "paper_triangular.ruptures.csv"] {
        assert!(read(&all, name) == read(&thin, name), "{name} differs");
    }
    let series =
        |dir: &Path| rrd::read(&dir.join("paper_triangular.rrd")).unwrap().series["contact/friction_force"].clone();
    let (full, thinned) = (series(&all), series(&thin));
    for (k, step) in thinned.steps.iter().enumerate() {
        let at = full.steps.binary_search(step).unwrap_or_else(|_| panic!("step {step} is not in the full recording"));
        assert_eq!(full.values[at], thinned.values[k], "step {step}");
    }
    let csv = String::from_utf8(read(&thin, "paper_triangular.events.csv")).unwrap();
    let onset: f64 = csv.lines().nth(1).unwrap().split(',').nth(1).unwrap().parse().unwrap();
    // Through the rupture (from its onset to 430 s) a row per ten steps and the changes.
    let rupture = |s: &slipfront::inspect::Series| s.times.iter().filter(|&&t| (onset..430.0).contains(&t)).count();
    let (in_full, in_thinned) = (rupture(&full), rupture(&thinned));
    println!("through the rupture {in_thinned} rows against {in_full}");
    assert!(in_thinned * 5 < in_full, "through the rupture {in_thinned} rows against {in_full}");
    let first_after = |s: &slipfront::inspect::Series| s.steps[s.times.partition_point(|&t| t < onset)];
    assert_eq!(first_after(&thinned), first_after(&full), "the first row after the onset at {onset} s");
}
