//! Rerun recordings: the schema pinned, values equal to the run's, read by the
//! official tools, `check` catching damage, the stored blueprint, and the stuck limit read back
//! from a recording.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::load;
use slipfront::case::Case;
use slipfront::catalog::events::Catalog;
use slipfront::frame::Ending;
use slipfront::frame::Quantity;
use slipfront::frame::{Frame, Layout, SegmentSample};
use slipfront::inspect::check::{Expectations, check};
use slipfront::inspect::{Recording, rrd};
use slipfront::record::schema;
use slipfront::record::schema::RecordingPlan;
use slipfront::run::{LoopOptions, Outcome, run};
use slipfront::scene;
use slipfront::sink::rerun::{RerunSink, Viewer, open_stream};
use slipfront::sink::{Sink, SinkError};
use slipfront::validate::shortest;

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slipfront-rec-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn case_path(name: &str) -> String {
    format!("{}/cases/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

/// Runs the CLI and returns the recording's path.
fn run_cli(name: &str, sets: &[&str], out: &Path) -> PathBuf {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_slipfront"));
    cmd.args(["run", &case_path(name), "--quiet", "--out-dir"]).arg(out);
    for s in sets {
        cmd.args(["--set", s]);
    }
    let status = cmd.status().unwrap();
    assert!(status.success(), "slipfront run {name} failed");
    out.join(format!("{name}.rrd"))
}

fn check_cli(path: &Path, expect: Option<&Path>) -> (i32, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_slipfront"));
    cmd.arg("check").arg(path);
    if let Some(e) = expect {
        cmd.arg("--expect").arg(e);
    }
    let out = cmd.output().unwrap();
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    (out.status.code().unwrap_or(-1), text)
}

#[test]
fn the_schema_is_pinned() {
    let out = scratch("schema");
    let block = rrd::read(&run_cli("paper_triangular", &["time.t_end=20"], &out)).unwrap();
    let mut expected: Vec<String> = Vec::new();
    for k in 0..10 {
        for q in ["traction_t", "traction_n", "R", "R_star", "structure", "slip_rate", "slip"] {
            expected.push(format!("contact/{q}[{k}]"));
        }
    }
    for j in 0..=10 {
        expected.push(format!("body/u_x[{j}]"));
        expected.push(format!("body/u_y[{j}]"));
    }
    expected.extend(["contact/friction_force", "base/u_x"].map(String::from));
    let series: Vec<String> = block.series.keys().cloned().collect();
    let mut sorted = expected.clone();
    sorted.sort();
    assert_eq!(series, sorted, "block series");
    let mut entities: Vec<String> = [
        "__properties/case",
        "__properties/run",
        "base/u_x",
        "body/u_x",
        "body/u_y",
        "contact/friction_force",
        "contact/state",
        "profile/kinetic_strength",
        "profile/slip_rate",
        "profile/static_strength",
        "profile/structure",
        "profile/traction_t",
        "slipfront/ending",
        "slipfront/run",
        "spacetime/axes",
        "spacetime/now",
        "spacetime/slip_rate",
        "spatial/base",
        "spatial/contact",
        "spatial/mesh",
    ]
    .map(String::from)
    .to_vec();
    entities.extend(Quantity::ALL.map(|q| format!("contact/{}", q.name())));
    entities.sort();
    // One entity per quantity, not per segment: the viewer slows with hundreds of entities.
    assert_eq!(block.entities.iter().cloned().collect::<Vec<_>>(), entities, "block entities");
    // A static component hides the same component logged over time: the contact's colours, which
    // show its state at every frame, must not be static.
    let path = out.join("paper_triangular.rrd");
    let colours = rerun::LineStrips2D::descriptor_colors().component;
    let (mut static_colours, mut temporal_colours) = (0, 0);
    for message in rerun::external::re_log_encoding::DecoderApp::decode_eager(std::io::BufReader::new(
        std::fs::File::open(&path).unwrap(),
    ))
    .unwrap()
    {
        if let rerun::log::LogMsg::ArrowMsg(_, arrow) = message.unwrap() {
            let chunk = rerun::log::Chunk::from_arrow_msg(&arrow).unwrap();
            if chunk.entity_path().to_string() == "/spatial/contact" && chunk.components().get_array(colours).is_some()
            {
                if chunk.is_static() { static_colours += 1 } else { temporal_colours += 1 }
            }
        }
    }
    assert_eq!((static_colours, temporal_colours > 0), (0, true), "spatial/contact colours");
    // Series names and colours are static.
    let spring = rrd::read(&run_cli("spring_block", &["time.integrator=wilson", "time.t_end=20"], &out)).unwrap();
    let mut expected: Vec<String> =
        Quantity::ALL.iter().map(|q| schema::instance_series(&schema::segment_entity(*q), 0)).collect();
    expected.extend(["contact/friction_force", "base/u_x", "block/x", "block/v"].map(String::from));
    expected.sort();
    assert_eq!(spring.series.keys().cloned().collect::<Vec<_>>(), expected, "spring-block series");
    assert!(spring.entities.contains("spatial/spring"));
    // Timelines: step counts from 0, sim_time is seconds.
    let s = &spring.series["block/x"];
    assert_eq!(s.steps[0], 0);
    assert_eq!(s.times[0], 0.0);
    assert!((s.times.last().unwrap() - 20.0).abs() < 1e-9);
    let info: schema::RunInfo = toml::from_str(&spring.static_texts["slipfront/run"]).unwrap();
    assert!((s.times[1] - s.steps[1] as f64 * info.dt).abs() < 1e-9, "sim_time = step × dt");
}

/// Keeps every frame, to compare with what the recording holds.
#[derive(Default)]
struct Frames(std::rc::Rc<std::cell::RefCell<Vec<Frame>>>);

impl Sink for Frames {
    fn needs(&self) -> slipfront::frame::Needs {
        slipfront::frame::Needs { segment_state: true, surface_nodes: true, mesh: false }
    }
    fn begin(&mut self, _: &Layout) -> Result<(), SinkError> {
        Ok(())
    }
    fn record(&mut self, frame: &Frame) -> Result<(), SinkError> {
        self.0.borrow_mut().push(frame.clone());
        Ok(())
    }
    fn finish(&mut self, _: Ending, _: Option<&Frame>, _: &Catalog) -> Result<(), SinkError> {
        Ok(())
    }
}

/// Runs `case` through a Rerun sink and a frame collector in the same run.
fn run_recorded(case: &Case, path: &Path) -> (Vec<Frame>, Catalog) {
    let mut scene = scene::build(case).unwrap();
    let stream = open_stream(Some(path), &Viewer::None, "test", None).unwrap().unwrap();
    let plan = RecordingPlan::for_case("test", case);
    let frames = Frames::default();
    let collected = frames.0.clone();
    let mut sinks: Vec<Box<dyn Sink>> = vec![Box::new(RerunSink::new(stream, plan)), Box::new(frames)];
    let options = LoopOptions::for_case(case);
    let Outcome::Completed { catalog, .. } = run(scene.as_mut(), &case.time, &mut sinks, options) else {
        panic!("the run did not complete")
    };
    drop(sinks);
    let frames = collected.borrow().clone();
    (frames, catalog)
}

/// The value of a series entity in a frame, by the documented schema.
fn value_of(entity: &str, frame: &Frame) -> f64 {
    match entity {
        "contact/friction_force" => frame.friction_force,
        "base/u_x" => frame.base_displacement,
        "block/x" => frame.block.unwrap()[0],
        "block/v" => frame.block.unwrap()[1],
        _ => {
            // `contact/{quantity}[k]` or `body/u_x[j]`: every segment and node is recorded here.
            let (path, index) = entity.trim_end_matches(']').split_once('[').unwrap();
            let index: usize = index.parse().unwrap();
            match path {
                "body/u_x" => frame.surface_nodes[index][0],
                "body/u_y" => frame.surface_nodes[index][1],
                _ => {
                    let name = path.strip_prefix("contact/").unwrap();
                    let q = Quantity::ALL.iter().find(|q| q.name() == name).unwrap();
                    q.of(&frame.segments[index])
                }
            }
        }
    }
}

#[test]
fn recorded_values_equal_the_run_and_the_official_sdk_reads_them() {
    let out = scratch("values");
    let path = out.join("spring.rrd");
    let case = load("spring_block", &["time.t_end=850"]);
    let (frames, catalog) = run_recorded(&case, &path);
    assert!(!catalog.events.is_empty(), "the run slipped");
    let recording = rrd::read(&path).unwrap();
    let mut compared = 0;
    for (entity, series) in &recording.series {
        for (i, &step) in series.steps.iter().enumerate() {
            let frame = &frames[step as usize];
            assert_eq!(frame.step as i64, step);
            // sim_time is stored in integer nanoseconds.
            assert!((series.times[i] - frame.time).abs() < 1e-9, "{entity} time at step {step}");
            let expected = value_of(entity, frame);
            assert!(
                series.values[i] == expected,
                "{entity} at step {step}: recorded {} vs run {expected}",
                series.values[i]
            );
            compared += 1;
        }
    }
    println!("{compared} recorded values equal the run's");
    // Every step while slipping, every 50th in stick.
    let rows = &recording.series["block/x"].steps;
    let slipping: Vec<i64> =
        frames.iter().filter(|f| f.segments[0].slip_rate > case.slip_rate_threshold()).map(|f| f.step as i64).collect();
    assert!(slipping.iter().all(|s| rows.binary_search(s).is_ok()), "a slipping step was not recorded");
    assert!(rows.windows(2).all(|w| w[1] - w[0] <= 50), "a stick gap longer than 50 steps");

    // The official Python SDK, an independent reader.
    let entities = ["contact/friction_force", "block/x", "contact/structure[0]", "contact/R[0]"];
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/python/read_recording.py");
    let Some(output) = official_python(script, &path, &entities) else { return };
    let mut lines = 0;
    for line in output.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let (entity, step, time, value): (&str, usize, f64, f64) =
            (fields[0], fields[1].parse().unwrap(), fields[2].parse().unwrap(), fields[3].parse().unwrap());
        let frame = &frames[step];
        assert!((time - frame.time).abs() < 1e-9, "{entity} at step {step}: time {time} vs {}", frame.time);
        assert_eq!(value, value_of(entity, frame), "{entity} at step {step} as read by the Rerun SDK");
        lines += 1;
    }
    assert_eq!(lines, 4 * rows.len(), "the SDK read every row of the four columns");
    println!("the Rerun SDK read {lines} values, all equal to the run's");
}

/// Runs the official Python reader; `None` (with a message) where it is not installed and the
/// environment does not require it.
fn official_python(script: &str, path: &Path, entities: &[&str]) -> Option<String> {
    let output = Command::new("python3").arg(script).arg(path).args(entities).output();
    match output {
        Ok(out) if out.status.success() => Some(String::from_utf8(out.stdout).unwrap()),
        Ok(out) if out.status.code() == Some(3) => {
            skip("the official Rerun Python SDK (pip install \"rerun-sdk[datafusion]==0.36.*\")")
        }
        Ok(out) => panic!("the Rerun SDK failed to read {}: {}", path.display(), String::from_utf8_lossy(&out.stderr)),
        Err(_) => skip("python3"),
    }
}

fn skip<T>(what: &str) -> Option<T> {
    assert!(
        std::env::var_os("SLIPFRONT_REQUIRE_OFFICIAL_TOOLS").is_none(),
        "{what} is required (SLIPFRONT_REQUIRE_OFFICIAL_TOOLS is set) but missing"
    );
    eprintln!("SKIPPED: {what} is not installed; the independent check did not run");
    None
}

#[test]
fn rerun_rrd_verify_accepts_the_recording() {
    let out = scratch("verify");
    let path = run_cli("paper_triangular", &["time.t_end=600"], &out);
    // `python3 -m rerun` is the CLI of the official SDK, wherever pip put its scripts.
    let result = Command::new("python3").args(["-m", "rerun", "rrd", "verify"]).arg(&path).output();
    match result {
        Ok(out) if String::from_utf8_lossy(&out.stderr).contains("No module named rerun") => {
            skip::<()>("the `rerun` CLI (pip install \"rerun-sdk[datafusion]==0.36.*\")");
        }
        Ok(out) => {
            let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
            assert!(out.status.success(), "rerun rrd verify failed:\n{text}");
            assert!(text.contains("verified without error"), "{text}");
        }
        Err(_) => {
            skip::<()>("python3");
        }
    }
}

#[test]
fn check_passes_a_fresh_recording_and_its_expectations() {
    let out = scratch("pass");
    let path = run_cli("paper_triangular", &["time.t_end=600"], &out);
    let expect = out.join("expect.toml");
    std::fs::write(
        &expect,
        "[events]\nslip_events = [1, 100]\nruptures = [1, 10]\n\n[[at]]\nentity = \"contact/structure\"\nsegment = 0\ntime = 300.0\nmin = 1.0\nmax = 2.0\n",
    )
    .unwrap();
    let (code, text) = check_cli(&path, Some(&expect));
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("PASS") && text.contains("contact/structure[0] = "), "{text}");
    // An expectation that does not hold is a mismatch (exit 1).
    std::fs::write(&expect, "[[at]]\nentity = \"contact/friction_force\"\ntime = 300.0\nmax = 0.0\n").unwrap();
    let (code, text) = check_cli(&path, Some(&expect));
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("FAIL: at[0]: contact/friction_force = "), "{text}");
}

#[test]
fn an_expectation_at_a_time_outside_the_recording_fails_naming_its_span() {
    let out = scratch("outside");
    let path = run_cli("spring_block", &["time.t_end=100"], &out);
    let recording = rrd::read(&path).unwrap();
    let force = &recording.series["contact/friction_force"];
    assert_eq!((force.times[0], *force.times.last().unwrap()), (0.0, 100.0), "the run's rows span 0 to 100 s");
    let expect = out.join("expect.toml");
    let at = |time: &str| {
        std::fs::write(&expect, format!("[[at]]\nentity = \"contact/friction_force\"\ntime = {time}\nmin = -1e300\n"))
            .unwrap();
        check_cli(&path, Some(&expect))
    };
    // Past the end by rounding (a ten-millionth): the last row, as the run's end is.
    let (code, text) = at("100.00001");
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains(&format!(
            "contact/friction_force = {} at t = 100 s, in [-1e300, inf]",
            shortest(*force.values.last().unwrap())
        )),
        "{text}"
    );
    // Past the end by more: not the last row's value, a failure that says the span.
    for (time, side) in
        [("100.001", "after the last row"), ("5000", "after the last row"), ("-0.5", "before the first row")]
    {
        let (code, text) = at(time);
        assert_eq!(code, 1, "time = {time}: {text}");
        assert!(
            text.contains(&format!(
                "FAIL: at[0].time = {time} s is {side} of the recording: contact/friction_force spans t = 0 to 100 s"
            )),
            "time = {time}: {text}"
        );
        assert!(!text.contains("contact/friction_force = "), "time = {time}: no value is reported: {text}");
    }
}

#[test]
fn a_recording_says_how_its_run_was_stepped() {
    // The run description names the integrator and, for adaptive steps, its tolerance; `check`
    // reads them back, and accepts a Tsit5 recording whose times are those of adaptive steps
    // ending on slip-threshold crossings.
    let out = scratch("stepping");
    let sets = ["time.integrator=tsit5", "time.tolerance=1e-9", "time.t_end=850"];
    let (code, text) = check_cli(&run_cli("spring_block", &sets, &out), None);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("t_end = 850 s by Tsitouras' 5(4) pair from a step of 0.005 s, tolerance 1e-9 per step"),
        "{text}"
    );
    assert!(text.contains("2 slip events"), "the spring block slips twice before 850 s: {text}");
    let (code, text) = check_cli(&run_cli("spring_block", &["time.integrator=wilson", "time.t_end=50"], &out), None);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("t_end = 50 s in 10000 steps of 0.005 s"), "{text}");
    assert!(!text.contains("auto"), "a named integrator is not said to be chosen: {text}");
    // With no integrator named, the recording says which `auto` chose and why.
    let (code, text) = check_cli(&run_cli("spring_block", &["time.t_end=50"], &out), None);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("by Tsitouras' 5(4) pair"), "{text}");
    assert!(text.contains("time.integrator = \"auto\" chose tsit5: a body of 1 unknown (at most 1000)"), "{text}");
    let (code, text) = check_cli(&run_cli("spring_block", &["time.accuracy=1e-5", "time.t_end=50"], &out), None);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("tolerance 3.3333333333333334e-8 per step (time.accuracy = 1e-5)"), "{text}");
    let sets = ["time.integrator=wilson", "time.tolerance=1e-6", "time.t_end=50"];
    let (code, text) = check_cli(&run_cli("spring_block", &sets, &out), None);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("in adaptive Wilson steps from 0.005 s, tolerance 1e-6 per simulated second"), "{text}");
}

/// Rewrites a recording without the chunks of `entity`.
fn without_entity(from: &Path, to: &Path, entity: &str) {
    use rerun::external::re_log_encoding::{DecoderApp, Encoder};
    use rerun::log::{Chunk, LogMsg};
    let file = std::io::BufReader::new(std::fs::File::open(from).unwrap());
    let kept: Vec<LogMsg> = DecoderApp::decode_eager(file)
        .unwrap()
        .map(|m| m.unwrap())
        .filter(|m| match m {
            LogMsg::ArrowMsg(_, arrow) => {
                Chunk::from_arrow_msg(arrow).unwrap().entity_path().to_string() != format!("/{entity}")
            }
            _ => true,
        })
        .collect();
    let bytes = Encoder::encode(kept.into_iter().map(Ok)).unwrap();
    std::fs::write(to, bytes).unwrap();
}

#[test]
fn check_catches_a_missing_entity() {
    let out = scratch("missing");
    let path = run_cli("paper_triangular", &["time.t_end=50"], &out);
    let damaged = out.join("missing.rrd");
    without_entity(&path, &damaged, "contact/slip");
    let (code, text) = check_cli(&damaged, None);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("FAIL: missing series contact/slip[3]"), "{text}");
    without_entity(&path, &damaged, "spatial/contact");
    let (code, text) = check_cli(&damaged, None);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("FAIL: missing entity spatial/contact"), "{text}");
}

#[test]
fn check_catches_a_nan() {
    let out = scratch("nan");
    let path = out.join("nan.rrd");
    let stream = open_stream(Some(&path), &Viewer::None, "nan", None).unwrap().unwrap();
    let plan = RecordingPlan {
        case: "nan".into(),
        t_end: 1.0,
        dt: 0.1,
        steps: 10,
        integrator: Default::default(),
        tolerance: None,
        recording_id: None,
        chosen_because: None,
        accuracy: None,
        slip_rate_threshold: 0.01,
        mu_k: None,
        parameters: Default::default(),
        overrides: Vec::new(),
        spec: slipfront::case::RecordSpec { stick_every: 1, ..Default::default() },
    };
    let mut sink = RerunSink::new(stream, plan);
    let layout = scene::build(&load("spring_block", &[])).unwrap().layout().clone();
    sink.begin(&layout).unwrap();
    for step in 0..=10u64 {
        let mut sample =
            SegmentSample { traction_t: -1.0, traction_n: 1000.0, r_star: 0.5, structure: 2.0, ..Default::default() };
        if step == 7 {
            sample.structure = f64::NAN;
        }
        let frame = Frame {
            step,
            time: step as f64 * 0.1,
            dt: if step == 0 { 0.0 } else { 0.1 },
            segments: vec![sample],
            block: Some([0.0, 0.0]),
            ..Frame::default()
        };
        sink.record(&frame).unwrap();
    }
    sink.finish(Ending::Completed, None, &Catalog::default()).unwrap();
    let recording: Recording = rrd::read(&path).unwrap();
    let report = check(&recording, &Expectations::default());
    assert!(
        report.problems.iter().any(|p| p.contains("contact/structure[0] = NaN at step 7")),
        "{:?}",
        report.problems
    );
    let (code, _) = check_cli(&path, None);
    assert_eq!(code, 1);
}

#[test]
fn check_catches_a_truncated_file_and_refuses_a_non_recording() {
    let out = scratch("truncated");
    let path = run_cli("paper_triangular", &["time.t_end=100"], &out);
    let bytes = std::fs::read(&path).unwrap();
    let cut = out.join("cut.rrd");
    std::fs::write(&cut, &bytes[..bytes.len() * 6 / 10]).unwrap();
    let (code, text) = check_cli(&cut, None);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("FAIL: no ending record"), "{text}");
    let garbage = out.join("garbage.rrd");
    std::fs::write(&garbage, b"this is not a recording").unwrap();
    let (code, text) = check_cli(&garbage, None);
    assert_eq!(code, 2, "{text}");
    assert!(text.contains("is not a Rerun recording"), "{text}");
    let (code, text) = check_cli(&out.join("absent.rrd"), None);
    assert_eq!(code, 2, "{text}");
}

#[test]
fn the_blueprint_is_stored_with_its_views() {
    use slipfront::sink::blueprint::*;
    let out = scratch("blueprint");
    let recording = rrd::read(&run_cli("paper_triangular", &["time.t_end=20"], &out)).unwrap();
    let view = |name: &str| {
        recording
            .views
            .iter()
            .find(|v| v.name.starts_with(name))
            .unwrap_or_else(|| panic!("no view {name}: {:?}", recording.views))
    };
    let block = view(VIEW_BLOCK);
    assert_eq!((block.class.as_str(), block.origin.as_str()), ("2D", "/spatial"));
    let spacetime = view(VIEW_SPACETIME);
    assert_eq!((spacetime.class.as_str(), spacetime.origin.as_str()), ("2D", "/spacetime"));
    let lanes = view(VIEW_STATE);
    assert_eq!(
        (lanes.class.as_str(), lanes.contents.as_slice()),
        ("StateTimeline", &["/contact/state".to_string()][..])
    );
    let strength = view(VIEW_STRENGTH);
    assert_eq!(strength.class, "BarChart");
    assert_eq!(
        strength.contents,
        ["/profile/static_strength", "/profile/kinetic_strength", "/profile/traction_t"].map(String::from)
    );
    // The probe plots: one entity per quantity (the probes A-F are picked in the blueprint),
    // the whole run on the time axis, and no legend over the data.
    let traction = view(VIEW_TRACTION);
    assert_eq!(traction.class, "TimeSeries");
    assert!(traction.name.contains("at A to F"), "{}", traction.name);
    assert_eq!(traction.contents, ["/contact/traction_t".to_string()]);
    let mut properties = traction.properties.clone();
    properties.sort();
    assert_eq!(properties, ["PlotLegend", "TimeAxis"]);
    assert_eq!(view(VIEW_STRUCTURE).contents, ["/contact/structure".to_string()]);
    assert_eq!(view(VIEW_DISPLACEMENT).contents, ["/body/u_x", "/base/u_x"].map(String::from));
    let events = view(VIEW_EVENTS);
    assert_eq!((events.class.as_str(), events.origin.as_str()), ("TextLog", "/events"));
    assert_eq!(recording.views.len(), 10);
}

#[test]
fn stuck_limit_read_from_the_recording_matches_the_closed_form() {
    let out = scratch("stuck");
    let path = run_cli(
        "paper_triangular",
        &[
            "time.integrator=wilson",
            "friction.mu_s=400",
            "friction.mu_k=200",
            "time.t_end=50",
            "scene.normal_traction={kind=\"uniform\", value=1000}",
        ],
        &out,
    );
    let recording = rrd::read(&path).unwrap();
    let force = &recording.series["contact/friction_force"];
    let base = &recording.series["base/u_x"];
    let (w, h, g, alpha) = (10.0, 1.0, 500.0, 1.0e6);
    let mut checked = 0;
    for i in 0..force.times.len() {
        if force.times[i] < 40.0 {
            continue;
        }
        let expected = w * base.values[i] / (h / g + 1.0 / alpha);
        let relative = (force.values[i] - expected).abs() / expected;
        assert!(relative < 5e-3, "t = {}: recorded {} vs closed form {expected}", force.times[i], force.values[i]);
        checked += 1;
    }
    assert!(checked > 10, "rows after 40 s: {checked}");
}

/// Sends `signal` to a long paper-case run after 3 s and checks the exit code and that the
/// recording, the MCAP log and the catalog are finished files.
fn interrupt_with(signal: &str, expected_code: i32) {
    let out = scratch(&format!("sig{signal}"));
    let mcap = out.join("run.mcap");
    let child = Command::new(env!("CARGO_BIN_EXE_slipfront"))
        .args(["run", &case_path("paper_triangular"), "--quiet", "--set", "time.t_end=100000", "--mcap"])
        .arg(&mcap)
        .arg("--out-dir")
        .arg(&out)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_secs(3));
    let killed = Command::new("kill").args([&format!("-{signal}"), &child.id().to_string()]).status().unwrap();
    assert!(killed.success());
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(expected_code), "exit status after SIG{signal}: {stderr}");
    assert!(stderr.contains(&format!("interrupted by SIG{signal} after ")), "{stderr}");
    for path in [out.join("paper_triangular.rrd"), mcap] {
        let (code, text) = check_cli(&path, None);
        assert_eq!(code, 0, "{}: {text}", path.display());
        assert!(text.contains("run interrupted"), "{}: {text}", path.display());
    }
    let catalog = std::fs::read_to_string(out.join("paper_triangular.events.csv")).unwrap();
    assert!(catalog.starts_with("segment,onset_s,end_s,"), "the catalog was written");
}

#[test]
fn an_interrupted_run_leaves_finished_recordings() {
    interrupt_with("INT", 130);
}

#[test]
fn a_terminated_run_leaves_finished_recordings() {
    interrupt_with("TERM", 143);
}

#[test]
fn a_full_disk_stops_the_run_with_a_clear_error_and_finishes_the_other_outputs() {
    // /dev/full fails every write with ENOSPC, as a full disk does.
    for option in ["--mcap", "--events"] {
        let out = scratch(&format!("full{option}"));
        let output = Command::new(env!("CARGO_BIN_EXE_slipfront"))
            .args(["run", &case_path("spring_block"), "--quiet", "--set", "time.t_end=20", option, "/dev/full"])
            .arg("--out-dir")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{option}: {stderr}");
        assert!(stderr.contains("/dev/full") && stderr.contains("No space left on device"), "{option}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        let (code, text) = check_cli(&out.join("spring_block.rrd"), None);
        assert_eq!(code, 0, "{option}: {text}");
        // Both files fail as they start (their headers are written first), so the recording
        // keeps the initial state of a failed run.
        assert!(text.contains("run failed: 1 rows per series up to t = 0 s"), "{option}: {text}");
    }
}

#[test]
fn a_failed_run_leaves_a_finished_recording_up_to_its_last_good_step() {
    let out = scratch("failed");
    // Steps of 1 s are too coarse for the spring block's slip: Wilson's method creates energy
    // through it, and the energy guard stops the run in step 799 (t = 799 s) with the step to
    // change.
    let output = Command::new(env!("CARGO_BIN_EXE_slipfront"))
        .args(["run", &case_path("spring_block"), "--quiet", "--set", "time.integrator=wilson"])
        .args(["--set", "time.dt=1", "--out-dir"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    for part in ["run failed at step 799 (t = 798 s)", "energy balance does not close", "time.dt"] {
        assert!(stderr.contains(part), "no {part:?} in {stderr}");
    }
    let (code, text) = check_cli(&out.join("spring_block.rrd"), None);
    assert_eq!(code, 0, "{text}");
    // The last good step (798, at t = 798 s) is recorded, whether or not the decimation of
    // stick steps would have kept it.
    assert!(text.contains("run failed: ") && text.contains("rows per series up to t = 798 s"), "{text}");
}

#[test]
fn streaming_to_a_viewer_and_writing_the_file_work_together() {
    // The official CLI's headless gRPC proxy stands in for a viewer.
    let port = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
    // `python3 -m rerun` starts the real binary as a child: run it in its own process group,
    // detached from our output, and end the whole group.
    use std::os::unix::process::CommandExt;
    let server = Command::new("python3")
        .args(["-m", "rerun", "--serve-grpc", "--port", &port.to_string()])
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .process_group(0)
        .spawn();
    let Ok(mut server) = server else {
        skip::<()>("python3");
        return;
    };
    let group = format!("-{}", server.id());
    let stop = move |server: &mut std::process::Child| {
        let _ = Command::new("kill").args(["-TERM", "--", &group]).status();
        let _ = server.wait();
    };
    let up = (0..100).any(|_| {
        std::thread::sleep(std::time::Duration::from_millis(100));
        std::net::TcpStream::connect(("127.0.0.1", port)).is_ok()
    });
    if !up {
        stop(&mut server);
        skip::<()>("the `rerun` CLI's gRPC server (pip install \"rerun-sdk[datafusion]==0.36.*\")");
        return;
    }
    let out = scratch("connect");
    let status = Command::new(env!("CARGO_BIN_EXE_slipfront"))
        .args(["run", &case_path("paper_triangular"), "--quiet", "--set", "time.t_end=300"])
        .args(["--connect", &format!("rerun+http://127.0.0.1:{port}/proxy"), "--out-dir"])
        .arg(&out)
        .status()
        .unwrap();
    stop(&mut server);
    assert!(status.success(), "run with --connect");
    let (code, text) = check_cli(&out.join("paper_triangular.rrd"), None);
    assert_eq!(code, 0, "{text}");
}

#[test]
fn a_value_changed_inside_a_readable_recording_fails_check() {
    // One bit flipped at each of 1 000 positions spread over a recording. Every mutant that still
    // decodes but whose series differ from the original's (a bit in a value, a step or a time,
    // carried through the chunk's compression) must fail `check`: the series digests written
    // with the run's ending tell damage from data. A mutant whose damaged Arrow message makes
    // the decoder abort (`slipfront::cli::isolated`) is first weeded out by decoding it in a
    // child, `slipfront __decode-rrd`, as `check` itself does.
    let out = scratch("mutants");
    let path = run_cli("spring_block", &["time.integrator=wilson", "time.t_end=20"], &out);
    let bytes = std::fs::read(&path).unwrap();
    let original = rrd::from_bytes(&bytes, "original").unwrap();
    assert!(check(&original, &Expectations::default()).passed());
    let mutant_path = out.join("mutant.rrd");
    let (mut changed, mut aborted, mut passed_changed) = (0, 0, Vec::new());
    let positions = 1000.min(bytes.len());
    for k in 0..positions {
        let at = k * bytes.len() / positions;
        let mut mutant = bytes.clone();
        mutant[at] ^= 1 << (k % 8);
        std::fs::write(&mutant_path, &mutant).unwrap();
        let child = Command::new(env!("CARGO_BIN_EXE_slipfront")).arg("__decode-rrd").arg(&mutant_path).status();
        if !child.unwrap().success() {
            aborted += 1;
            continue;
        }
        let Ok(recording) = rrd::from_bytes(&mutant, "mutant") else { continue };
        if recording.series == original.series {
            continue;
        }
        changed += 1;
        if check(&recording, &Expectations::default()).passed() {
            passed_changed.push(at);
        }
    }
    println!("{changed} of {positions} mutants decode with changed series; {aborted} abort the decoder");
    assert!(changed > 0, "no mutant changed a series: the test proves nothing");
    assert!(passed_changed.is_empty(), "mutants with changed series that pass check, at bytes {passed_changed:?}");
}

#[test]
fn a_killed_run_leaves_its_recording_as_far_as_its_log() {
    // SIGKILL, which no handler sees (the out-of-memory killer, a batch system's time limit):
    // both files hand what they buffer to the disk at least every second and every `ROWS` rows
    // (`slipfront::sink::cadence`), so the recording reads back as far as the MCAP log, within
    // that cadence: each holds every row up to its last hand-over, at most `ROWS` rows before
    // the kill. Chunks filled by rows alone, with no clock, left a run of Wilson's method killed
    // after 5 s with its recording at 1 395 s of simulated time while its log held 1 726 s.
    use std::os::unix::process::CommandExt;
    let out = scratch("killed");
    let log = out.join("log.mcap");
    let mut child = Command::new(env!("CARGO_BIN_EXE_slipfront"))
        .args(["run", &case_path("paper_triangular"), "--quiet", "--set", "time.integrator=wilson"])
        .args(["--set", "time.t_end=100000", "--mcap", log.to_str().unwrap(), "--out-dir"])
        .arg(&out)
        .process_group(0)
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_secs(4));
    child.kill().unwrap();
    child.wait().unwrap();
    let recording = rrd::read(&out.join("paper_triangular.rrd")).unwrap();
    let rows = recording.series["contact/friction_force"].steps.len();
    let logged = slipfront::inspect::mcap::read(&log).unwrap().frames.len();
    println!("killed after 4 s: {rows} rows in the recording, {logged} in the log");
    assert!(rows > 1 && logged > 1, "rows: recording {rows}, log {logged}");
    let cadence = slipfront::sink::cadence::ROWS;
    assert!(rows + cadence >= logged, "the recording holds {rows} rows, the log {logged}");
}

#[test]
fn every_distinct_run_has_its_own_deterministic_recording_id() {
    // A Rerun server merges recordings that share an id into one dataset segment: two runs of
    // the same case must share it, any two that differ in a value must not, and a replayed MCAP
    // log is the run it logged.
    let out = scratch("ids");
    let id = |sets: &[&str], dir: &str| {
        let dir = out.join(dir);
        std::fs::create_dir_all(&dir).unwrap();
        rrd::read(&run_cli("spring_block", sets, &dir)).unwrap().recording_id.expect("a recording id")
    };
    let first = id(&["time.t_end=5"], "a");
    assert_eq!(first, id(&["time.t_end=5"], "b"), "the same run twice");
    assert!(first.starts_with("spring_block-"), "{first}");
    assert_ne!(first, id(&["time.t_end=5", "friction.structure0=1.999999999"], "c"), "another 1/R*");
    assert_ne!(first, id(&["time.t_end=5.000000001"], "d"), "another t_end");
    let log = out.join("log.mcap");
    let status = Command::new(env!("CARGO_BIN_EXE_slipfront"))
        .args(["run", &case_path("spring_block"), "--quiet", "--no-rrd", "--set", "time.t_end=5", "--mcap"])
        .arg(&log)
        .arg("--out-dir")
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let replayed = out.join("replayed.rrd");
    let status = Command::new(env!("CARGO_BIN_EXE_slipfront"))
        .arg("replay")
        .arg(&log)
        .arg("--rrd")
        .arg(&replayed)
        .status()
        .unwrap();
    assert!(status.success());
    assert_eq!(rrd::read(&replayed).unwrap().recording_id.as_deref(), Some(first.as_str()), "the replay");
}

#[test]
fn check_names_the_layout_of_a_recording_from_an_older_slipfront() {
    // A spring-block recording written by slipfront 0.1.0, one entity per segment and quantity.
    let old = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/rrd_read/bad-old-layout.rrd");
    let (code, text) = check_cli(&old, None);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("lays its series out as \"entity per segment\" (written by slipfront 0.1.0)")
            && text.contains("this slipfront reads \"instances\""),
        "{text}"
    );
}

#[test]
fn check_verifies_the_series_digests_of_this_slipfront_and_of_those_before() {
    // Digests are 64-bit xxh3 now (16 hexadecimal digits); a recording written before holds
    // 32-bit xxh32 ones (8 digits), which `check` still verifies against its rows.
    let digest_widths = |path: &Path| -> Vec<usize> {
        let recording = rrd::read(path).unwrap();
        let ending: schema::RunEnding = toml::from_str(&recording.static_texts[schema::RUN_ENDING]).unwrap();
        ending.digests.values().map(String::len).collect()
    };
    let before = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/rrd_read/ok-spring_block.rrd");
    let out = scratch("digests");
    let now = run_cli("spring_block", &["time.t_end=20"], &out);
    for (path, width) in [(before.as_path(), 8), (now.as_path(), 16)] {
        let widths = digest_widths(path);
        assert!(!widths.is_empty() && widths.iter().all(|w| *w == width), "{}: {widths:?}", path.display());
        let (code, text) = check_cli(path, None);
        assert_eq!(code, 0, "{}: {text}", path.display());
    }
}

#[test]
fn the_official_sdk_reads_every_instance_and_the_run_properties() {
    // The paper case has ten segments and eleven surface nodes: multi-instance columns.
    let out = scratch("instances");
    let path = out.join("paper.rrd");
    let case = load("paper_triangular", &["time.integrator=wilson", "time.t_end=30"]);
    let (frames, _) = run_recorded(&case, &path);
    let mut names: Vec<String> = (0..10).map(|k| format!("contact/traction_t[{k}]")).collect();
    names.extend((0..11).map(|j| format!("body/u_x[{j}]")));
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/python/read_recording.py");
    let arguments: Vec<&str> = names.iter().map(String::as_str).collect();
    let Some(output) = official_python(script, &path, &arguments) else { return };
    let rows = rrd::read(&path).unwrap().series["contact/friction_force"].steps.len();
    let mut compared = 0;
    for line in output.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let (name, step, value): (&str, usize, f64) =
            (fields[0], fields[1].parse().unwrap(), fields[3].parse().unwrap());
        assert_eq!(value, value_of(name, &frames[step]), "{name} at step {step} as read by the Rerun SDK");
        compared += 1;
    }
    assert_eq!(compared, names.len() * rows, "the SDK read every row of every instance");

    // The run's properties are columns of the dataset's segment table.
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/python/read_properties.py");
    let Some(output) = official_python(script, &path, &[]) else { return };
    let property = |column: &str| {
        output
            .lines()
            .find_map(|l| l.split_once(&format!(",{column},")).map(|(_, v)| v.to_string()))
            .unwrap_or_else(|| panic!("no {column} in\n{output}"))
    };
    assert_eq!(property("property:case:friction_mu_s"), "0.4");
    assert_eq!(property("property:case:scene_nx"), "10.0");
    assert_eq!(property("property:case:time_t_end"), "30.0");
    assert_eq!(property("property:run:overrides"), "time.integrator=wilson time.t_end=30");
    assert_eq!(property("property:run:integrator"), "wilson");
    assert_eq!(property("property:run:slipfront_version"), env!("CARGO_PKG_VERSION"));
}
