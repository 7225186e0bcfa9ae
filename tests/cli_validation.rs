//! Every validation rule: a malformed case or `--set` gives the exact message and
//! exit code 2, before anything runs.

use std::path::PathBuf;

mod common;

use common::{binary, case_path as case};

fn scratch_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slipfront-cli-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `slipfront run CASE --set ...` and returns (exit code, stderr).
fn run_case(path: &str, sets: &[&str]) -> (i32, String) {
    let out_dir = scratch_dir("out");
    let mut cmd = binary();
    cmd.arg("run").arg(path).arg("--quiet").arg("--out-dir").arg(&out_dir);
    for s in sets {
        cmd.arg("--set").arg(s);
    }
    let output = cmd.output().unwrap();
    (output.status.code().unwrap_or(-1), String::from_utf8_lossy(&output.stderr).into_owned())
}

fn expect_invalid(path: &str, sets: &[&str], message: &str) {
    let (code, stderr) = run_case(path, sets);
    assert_eq!(code, 2, "--set {sets:?}: exit code {code}, stderr: {stderr}");
    assert!(stderr.contains(message), "--set {sets:?}: expected `{message}` in:\n{stderr}");
}

#[test]
fn friction_rules() {
    let c = case("spring_block.toml");
    let rules: &[(&str, &str)] = &[
        ("friction.mu_k=0.5", "friction.mu_k = 0.5 must be less than friction.mu_s = 0.4"),
        ("friction.mu_k=0.4", "friction.mu_k = 0.4 must be less than friction.mu_s = 0.4"),
        ("friction.mu_s=-1", "friction.mu_s = -1 must be greater than 0"),
        ("friction.mu_k=0", "friction.mu_k = 0 must be greater than 0"),
        ("friction.alpha_n=0", "friction.alpha_n = 0 must be greater than 0"),
        ("friction.alpha_t=-5", "friction.alpha_t = -5 must be greater than 0"),
        ("friction.r=0", "friction.r = 0 must be greater than 0"),
        ("friction.kappa=-1", "friction.kappa = -1 must be greater than or equal to 0"),
        ("friction.m=0", "friction.m = 0 must be greater than 0"),
        ("friction.xi=-0.1", "friction.xi = -0.1 must be greater than or equal to 0"),
        ("friction.n=-2", "friction.n = -2 must be greater than 0"),
        ("friction.f0=-1e-7", "friction.f0 = -1e-7 must be greater than or equal to 0"),
        (
            "friction.structure0=2.5",
            "friction.structure0 = 2.5 must lie in [1, friction.mu_s/friction.mu_k] = [1, 2] (the degree of structure 1/R*)",
        ),
        (
            "friction.structure0=0.5",
            "friction.structure0 = 0.5 must lie in [1, friction.mu_s/friction.mu_k] = [1, 2] (the degree of structure 1/R*)",
        ),
        ("friction.mu_s=nan", "friction.mu_s = NaN must be a finite number"),
        ("friction.alpha_t=inf", "friction.alpha_t = inf must be a finite number"),
        ("friction.structure0=-inf", "friction.structure0 = -inf must be a finite number"),
    ];
    for (set, message) in rules {
        expect_invalid(&c, &[set], message);
    }
}

#[test]
fn time_rules() {
    let c = case("spring_block.toml");
    expect_invalid(&c, &["time.t_end=0"], "time.t_end = 0 must be greater than 0");
    expect_invalid(&c, &["time.dt=-0.01"], "time.dt = -0.01 must be greater than 0");
    expect_invalid(&c, &["time.dt=2000"], "time.dt = 2000 must not exceed time.t_end = 1000");
    expect_invalid(
        &c,
        &["time.dt=1e-9"],
        "time.dt = 1e-9 gives 1.000e12 steps for time.t_end = 1000 s; at most 1e9 are allowed",
    );
    expect_invalid(
        &c,
        &["time.integrator=wilson", "time.tolerance=0"],
        "time.tolerance = 0 must lie in (0, 0.1] (a relative local error per second, 1/s)",
    );
    expect_invalid(&c, &["time.tolerance=nan"], "time.tolerance = NaN must be a finite number");
    expect_invalid(
        &c,
        &["time.integrator=wilson", "time.dt_max=1"],
        "time.dt_max = 1 only applies to adaptive stepping: set time.tolerance too",
    );
    expect_invalid(
        &c,
        &["time.accuracy=1e-6", "time.tolerance=1e-8"],
        "time.accuracy = 0.000001 sets the tolerance itself: give time.accuracy or time.tolerance, not both",
    );
    expect_invalid(
        &c,
        &["time.accuracy=0.5"],
        "time.accuracy = 0.5 must lie in [1e-9, 1e-2] (a relative error of slip-onset times)",
    );
    expect_invalid(&c, &["time.accuracy=nan"], "time.accuracy = NaN must be a finite number");
    expect_invalid(
        &c,
        &["time.integrator=cycle", "time.accuracy=1e-6"],
        "time.accuracy = 0.000001 does not apply to time.integrator = \"cycle\"",
    );
    expect_invalid(
        &c,
        &["time.integrator=cycle", "time.tolerance=0.5"],
        "time.tolerance = 0.5 must lie in (0, 0.1] (the largest change of a contact point's traction",
    );
    expect_invalid(
        &c,
        &["time.integrator=wilson", "time.accuracy=1e-9", "time.t_end=1e6"],
        "time.accuracy = 1e-9 asks wilson for steps of 0.000025 s: 4.000e10 steps for t_end = 1000000 s, more than \
         the 1e9 allowed",
    );
    expect_invalid(
        &c,
        &["time.tolerance=1e-6", "time.dt_max=5000"],
        "time.dt_max = 5000 must lie in (0, time.t_end = 1000]",
    );
    expect_invalid(
        &case("point_loading.toml"),
        &["time.tolerance=1e-6"],
        "time.tolerance = 0.000001 is for dynamic scenes (spring_block, block, mesh); a point scene prescribes its motion",
    );
    expect_invalid(
        &c,
        &["time.integrator=tsit5", "time.tolerance=0.5"],
        "time.tolerance = 0.5 must lie in [1e-13, 0.1] (a relative local error per step of tsit5; below that, \
         rounding in the time itself can exceed it at a slip's onset)",
    );
    expect_invalid(
        &c,
        &["time.integrator=rk4"],
        "time.integrator: unknown variant `rk4`, expected one of `auto`, `wilson`, `tsit5`, `sdirk4`, `central`, `cycle`",
    );
    expect_invalid(
        &c,
        &["time.integrator=central", "time.tolerance=1e-5"],
        "time.tolerance = 0.00001 does not apply to time.integrator = \"central\", which takes fixed frames of \
         time.dt sub-stepped to its stability limit",
    );
    // Out of range too, but for central differences the only useful error is that they take none.
    let (code, stderr) = run_case(&c, &["time.integrator=central", "time.tolerance=0.5"]);
    assert_eq!(code, 2, "stderr: {stderr}");
    assert!(stderr.contains("time.tolerance = 0.5 does not apply to time.integrator = \"central\""), "{stderr}");
    assert!(!stderr.contains("must lie in"), "a second, misleading error: {stderr}");
    expect_invalid(
        &case("point_loading.toml"),
        &["time.integrator=central"],
        "time.integrator = central is for dynamic scenes (spring_block, block, mesh); a point scene prescribes its motion",
    );
    expect_invalid(
        &case("point_loading.toml"),
        &["time.integrator=tsit5"],
        "time.integrator = tsit5 is for dynamic scenes (spring_block, block, mesh); a point scene prescribes its motion",
    );
    expect_invalid(
        &case("point_loading.toml"),
        &["time.integrator=sdirk4"],
        "time.integrator = sdirk4 is for dynamic scenes (spring_block, block, mesh); a point scene prescribes its motion",
    );
    expect_invalid(
        &c,
        &["time.integrator=sdirk4", "time.tolerance=0.5"],
        "time.tolerance = 0.5 must lie in [1e-11, 0.1] (a relative local error per step of sdirk4; below that, \
         rounding in its stages can exceed it through the slips)",
    );
    // Below its floor SDIRK4 would fail in a slip, hundreds of seconds into the run. The floor
    // itself, 1e-11, is accepted: tests/stress.rs runs SDIRK4 there.
    expect_invalid(
        &c,
        &["time.integrator=sdirk4", "time.tolerance=1e-12"],
        "time.tolerance = 1e-12 must lie in [1e-11, 0.1]",
    );
    expect_invalid(
        &c,
        &["time.theta=1.2"],
        "time.theta = 1.2 must lie in [1.37, 3] (Wilson's method is unconditionally stable for θ ≥ 1.37)",
    );
}

#[test]
fn scene_rules() {
    let sb = case("spring_block.toml");
    expect_invalid(&sb, &["scene.mass=0"], "scene.mass = 0 must be greater than 0");
    expect_invalid(&sb, &["scene.stiffness=-500"], "scene.stiffness = -500 must be greater than 0");
    expect_invalid(&sb, &["scene.velocity=nan"], "scene.velocity = NaN must be a finite number");
    expect_invalid(&sb, &["scene.normal_traction=-1"], "scene.normal_traction = -1 must be greater than or equal to 0");
    expect_invalid(&sb, &["events.slip_rate_threshold=0"], "events.slip_rate_threshold = 0 must be greater than 0");
    expect_invalid(
        &sb,
        &["probes.nodes=[{name=\"N\", index=0}]"],
        "probes.nodes[0] = \"N\" is not allowed: a spring_block scene has no nodes",
    );

    let pt = case("point_loading.toml");
    expect_invalid(&pt, &["scene.phases=[]"], "scene.phases = [] must list at least one {velocity, duration} phase");
    expect_invalid(&pt, &["scene.phases.1.duration=0"], "scene.phases[1].duration = 0 must be greater than 0");
    expect_invalid(&pt, &["scene.phases.0.velocity=inf"], "scene.phases[0].velocity = inf must be a finite number");
    expect_invalid(&pt, &["scene.normal_traction=-3"], "scene.normal_traction = -3 must be greater than or equal to 0");
}

#[test]
fn block_rules() {
    let b = case("paper_triangular.toml");
    expect_invalid(&b, &["scene.width=0"], "scene.width = 0 must be greater than 0");
    expect_invalid(&b, &["scene.height=-1"], "scene.height = -1 must be greater than 0");
    expect_invalid(&b, &["scene.nx=0"], "scene.nx = 0 must be at least 1");
    expect_invalid(&b, &["scene.ny=0"], "scene.ny = 0 must be at least 1");
    expect_invalid(&b, &["scene.youngs_modulus=0"], "scene.youngs_modulus = 0 must be greater than 0");
    expect_invalid(&b, &["scene.poisson_ratio=0.5"], "scene.poisson_ratio = 0.5 must lie in [0, 0.5)");
    expect_invalid(&b, &["scene.density=-1000"], "scene.density = -1000 must be greater than 0");
    expect_invalid(&b, &["scene.base_velocity=inf"], "scene.base_velocity = inf must be a finite number");
    expect_invalid(
        &b,
        &["scene.normal_traction.right=-10"],
        "scene.normal_traction.right = -10 must be greater than or equal to 0",
    );
    expect_invalid(
        &b,
        &["scene.normal_traction={kind=\"table\", x=[0, 5], value=[1, 2]}"],
        "scene.normal_traction.x = [0.0, 5.0] must cover the contact, from 0 to scene.width = 10 m",
    );
    expect_invalid(
        &b,
        &["scene.normal_traction={kind=\"table\", x=[0, 10, 5], value=[1, 2, 3]}"],
        "scene.normal_traction.x = [0.0, 10.0, 5.0] must be finite and strictly increasing",
    );
    expect_invalid(
        &b,
        &["scene.normal_traction={kind=\"table\", x=[0, 10], value=[1]}"],
        "scene.normal_traction.x = [0.0, 10.0] must have at least 2 entries, as many as scene.normal_traction.value (1)",
    );
    expect_invalid(
        &b,
        &["probes.segments=[{name=\"Z\", index=10}]"],
        "probes.segments[0].index = 10 must be below 10 (the scene has 10 segments, numbered from 0 along its contacts)",
    );
    expect_invalid(&b, &["probes.nodes=[{name=\" \", index=3}]"], "probes.nodes[0].name = \" \" must not be empty");
    expect_invalid(
        &b,
        &["probes.segments=[{name=\"Z\", index=2, x=2.5}]"],
        "probes.segments[0] = \"Z\" must give exactly one of index (its number), x (m) or at ([x, y] in m)",
    );
    expect_invalid(&b, &["probes.nodes=[{name=\"N\", x=nan}]"], "probes.nodes[0].x = NaN must be a finite number");
    expect_invalid(
        &b,
        &["probes.nodes=[{name=\"N\", at=[1, inf]}]"],
        "probes.nodes[0].at[1] = inf must be a finite number",
    );
}

#[test]
fn record_rules() {
    let b = case("paper_triangular.toml");
    expect_invalid(&b, &["record.stick_every=0"], "record.stick_every = 0 must be at least 1");
    expect_invalid(&b, &["record.magnification=0"], "record.magnification = 0 must be greater than 0");
    expect_invalid(
        &b,
        &["record.segments=[3, 12]"],
        "record.segments[1] = 12 must be below 10 (the scene has 10 segments, numbered from 0 along its contacts)",
    );
    expect_invalid(
        &case("spring_block.toml"),
        &["record.nodes=[0]"],
        "record.nodes[0] = 0 is not allowed: a spring_block scene has no nodes",
    );
    expect_invalid(&b, &["record.quantities=[\"traction_t\", \"mu\"]"], "record.quantities[1]: unknown variant `mu`");
    expect_invalid(
        &b,
        &["record.segments=\"some\""],
        "record.segments: unknown selection \"some\", expected \"all\", \"probes\", \"auto\" or a list of indices",
    );
}

/// The keys of a contact's normal behaviour: each refused naming the key, the value and the
/// rule; an array item may be named in `--set` as messages name it (`contacts[0]`) or dotted.
#[test]
fn normal_behaviour_rules() {
    let cylinder = case("cylinder_on_base.toml");
    expect_invalid(
        &cylinder,
        &["scene.contacts[0].normal=\"held\""],
        "scene.contacts[0].gap = {...} needs scene.contacts[0].normal = \"evolving\": a held contact has no gap",
    );
    expect_invalid(
        &cylinder,
        &["scene.contacts.0.normal=\"bogus\""],
        "scene.contacts[0].normal: unknown variant `bogus`, expected `held` or `evolving`",
    );
    expect_invalid(
        &cylinder,
        &["scene.contacts[0].base_velocity=[0.1, 0.2]"],
        "scene.contacts[0].base_velocity = [vx, vy] of an evolving contact must be a number, a speed along the \
         contact",
    );
    expect_invalid(
        &cylinder,
        &["scene.contacts[0].gap={kind=\"uniform\", value=-1}"],
        "scene.contacts[0].gap.value = -1 must be greater than or equal to 0",
    );
    expect_invalid(
        &cylinder,
        &["scene.contacts[0].gap={kind=\"table\", along=\"x\", at=[-0.1, 0.1], value=[0, 0.01]}"],
        "scene.contacts[0].gap.at = [-0.1, …, 0.1] must cover the contact, whose Gauss points lie from \
         -0.8545627637135176 to 0.8545627637739784 m in x",
    );
    expect_invalid(
        &cylinder,
        &["scene.contacts[0].gap={kind=\"lithostatic\", level=0, unit_weight=1}"],
        "scene.contacts[0].gap = {kind = \"lithostatic\", ...} must be uniform, linear or a table: a gap is a \
         distance (m), not a stress",
    );
    expect_invalid(
        &cylinder,
        &["scene.contacts[1].normal=\"held\""],
        "scene.contacts.1 must index an existing item of the array (0 to 0)",
    );
    expect_invalid(
        &case("point_loading.toml"),
        &["scene.phases[0].normal_velocity=1e-3"],
        "scene.phases[0].normal_velocity = 0.001 needs scene.normal = \"evolving\": a held normal traction does not \
         move",
    );
    expect_invalid(
        &case("spring_block.toml"),
        &["scene.normal=\"evolving\""],
        "scene.normal: unknown field `normal`, expected one of `mass`, `stiffness`, `velocity`, `normal_traction`",
    );
}

#[test]
fn viewer_options_are_checked_before_solving() {
    let out = scratch_dir("viewer");
    let output = binary()
        .args([
            "run",
            &case("spring_block.toml"),
            "--quiet",
            "--connect",
            "rerun+http://127.0.0.1:9/proxy",
            "--out-dir",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("--connect rerun+http://127.0.0.1:9/proxy: no Rerun viewer is listening there"),
        "{stderr}"
    );
    let output = binary()
        .args(["run", &case("spring_block.toml"), "--quiet", "--connect", "http:/nonsense", "--out-dir"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("not a Rerun viewer URL"));
    // --spawn with no `rerun` on PATH says so.
    let output = binary()
        .args(["run", &case("spring_block.toml"), "--quiet", "--spawn", "--out-dir"])
        .arg(&out)
        .env("PATH", "/nonexistent")
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("`rerun` is not on PATH"));
    // --spawn with `rerun` on PATH but no display says what works instead, and not --spawn.
    let bin = out.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    std::fs::write(bin.join("rerun"), "#!/bin/sh\nexit 1\n").unwrap();
    std::fs::set_permissions(bin.join("rerun"), std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
    let output = binary()
        .args(["run", &case("spring_block.toml"), "--quiet", "--spawn", "--out-dir"])
        .arg(&out)
        .env("PATH", &bin)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("this session has no display"), "{stderr}");
    assert!(stderr.contains(&format!("`rerun {}`", out.join("spring_block.rrd").display())), "{stderr}");
    assert!(stderr.contains("--connect rerun+http://HOST:9876/proxy"), "{stderr}");
    assert!(!stderr.contains("use --spawn"), "{stderr}");
    // --rrd and --no-rrd exclude each other.
    let output = binary().args(["run", &case("spring_block.toml"), "--rrd", "x.rrd", "--no-rrd"]).output().unwrap();
    assert_eq!(output.status.code(), Some(2));
}

#[test]
fn several_violations_are_all_reported() {
    let (code, stderr) = run_case(&case("spring_block.toml"), &["friction.mu_k=0.5", "time.dt=-1"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("friction.mu_k = 0.5 must be less than friction.mu_s = 0.4"), "{stderr}");
    assert!(stderr.contains("time.dt = -1 must be greater than 0"), "{stderr}");
}

#[test]
fn malformed_files_and_overrides() {
    let c = case("spring_block.toml");
    // Shape errors from the deserializer, with the key path.
    expect_invalid(&c, &["friction.mu_s=\"high\""], "friction.mu_s: invalid type: string \"high\", expected f64");
    expect_invalid(&c, &["friction.mu_x=1"], "friction.mu_x: unknown field `mu_x`");
    expect_invalid(
        &c,
        &["scene.kind=\"pendulum\""],
        "scene.kind: unknown variant `pendulum`, expected one of `point`, `spring_block`, `block`, `mesh`",
    );
    expect_invalid(&c, &["time.dt=[1, 2]"], "time.dt: invalid type: sequence, expected f64");
    expect_invalid(
        &c,
        &["friction.rstar_law=eq5"],
        "friction.rstar_law: unknown variant `eq5`, expected `consistent` or `eq4`",
    );
    expect_invalid(
        &c,
        &["colour=1"],
        "colour: unknown field `colour`, expected one of `friction`, `time`, `scene`, `events`, `probes`",
    );
    // Malformed --set arguments.
    expect_invalid(&c, &["time.t_end"], "--set time.t_end: expected KEY=VALUE, e.g. --set time.t_end=50");
    expect_invalid(&c, &["=5"], "--set =5: the key must be a dotted path such as time.t_end");
    expect_invalid(&c, &["time..dt=5"], "--set time..dt=5: the key must be a dotted path such as time.t_end");
    expect_invalid(&c, &["time.dt="], "--set time.dt=: the value is empty");
    expect_invalid(&c, &["time.dt.x=1"], "--set time.dt.x: time.dt is a value, not a table, so it has no keys");
    let pt = case("point_loading.toml");
    expect_invalid(
        &pt,
        &["scene.phases.9.velocity=1"],
        "--set scene.phases.9.velocity: scene.phases.9 must index an existing item of the array (0 to 3)",
    );

    // Files: missing keys, unknown keys, not TOML, missing file.
    let dir = scratch_dir("files");
    let text = std::fs::read_to_string(&c).unwrap();
    let missing = dir.join("missing.toml");
    std::fs::write(&missing, text.replace("mu_s = 0.4", "")).unwrap();
    expect_invalid(missing.to_str().unwrap(), &[], "friction: TOML parse error at line 5, column 1");
    expect_invalid(missing.to_str().unwrap(), &[], "missing field `mu_s`");
    let unknown = dir.join("unknown.toml");
    std::fs::write(&unknown, text.replace("[time]", "[time]\nstep = 3")).unwrap();
    expect_invalid(unknown.to_str().unwrap(), &[], "time.step: TOML parse error at line 20, column 1");
    expect_invalid(unknown.to_str().unwrap(), &[], "unknown field `step`, expected one of `t_end`, `dt`, `theta`");
    let garbage = dir.join("garbage.toml");
    std::fs::write(&garbage, "[friction\nmu_s = ").unwrap();
    expect_invalid(garbage.to_str().unwrap(), &[], "TOML parse error at line 1");
    expect_invalid(dir.join("absent.toml").to_str().unwrap(), &[], "cannot read case file");
}

#[test]
fn an_unwritable_output_folder_is_refused_before_solving() {
    let dir = scratch_dir("ro");
    let blocker = dir.join("file");
    std::fs::write(&blocker, b"x").unwrap();
    let output = binary()
        .args(["run", &case("spring_block.toml"), "--quiet", "--out-dir"])
        .arg(blocker.join("sub"))
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("cannot create output folder"), "{stderr}");
}

#[test]
fn bad_arguments_exit_with_two() {
    let output = binary().args(["run"]).output().unwrap();
    assert_eq!(output.status.code(), Some(2));
    let output = binary().args(["run", "x.toml", "--frobnicate"]).output().unwrap();
    assert_eq!(output.status.code(), Some(2));
    let output = binary().args(["launch"]).output().unwrap();
    assert_eq!(output.status.code(), Some(2));
}

#[test]
fn hostile_scene_values_name_their_key() {
    let b = case("paper_triangular.toml");
    let sb = case("spring_block.toml");
    let rules: &[(&str, &str, &str)] = &[
        (&b, "scene.nx=\"ten\"", "scene.nx: invalid type: string \"ten\", expected usize"),
        (&b, "scene.nx=-1", "scene.nx: invalid value: integer `-1`, expected usize"),
        (&b, "scene.ny=1.5", "scene.ny: invalid type: floating point `1.5`, expected usize"),
        (&sb, "scene.mass=[1]", "scene.mass: invalid type: sequence, expected f64"),
        (&sb, "scene.kind=3", "scene.kind: invalid type: integer, expected a string"),
        (
            &sb,
            "scene.extra=1",
            "scene.extra: unknown field `extra`, expected one of `mass`, `stiffness`, `velocity`, `normal_traction`",
        ),
        (
            &b,
            "scene.normal_traction.kind=\"cubic\"",
            "scene.normal_traction.kind: unknown variant `cubic`, expected one of `uniform`, `linear`, `table`",
        ),
        (
            &b,
            "scene.normal_traction={kind=\"table\", x=[0, 10], value=[\"a\", 2]}",
            "scene.normal_traction: invalid type: string \"a\", expected f64",
        ),
        (&sb, "time.dt=1e400", "time.dt: invalid type: string \"1e400\", expected f64"),
        (&sb, "events.x=1", "events.x: unknown field `x`, expected `slip_rate_threshold` or `merge_within`"),
        (&sb, "friction=3", "friction: invalid type: integer `3`, expected struct FrictionParams"),
    ];
    for (path, set, message) in rules {
        expect_invalid(path, &[set], message);
    }
}

#[test]
fn a_mesh_too_large_for_memory_is_refused_with_an_estimate() {
    let b = case("paper_triangular.toml");
    // 2e10 degrees of freedom: about 137 TB by the estimate, more than any machine here has.
    let (code, stderr) = run_case(&b, &["scene.nx=100000", "scene.ny=100000"]);
    assert_eq!(code, 2, "{stderr}");
    for part in ["scene.nx × scene.ny = 100000 × 100000 is too large", "2.000e10 degrees of freedom", "TB of memory"]
    {
        assert!(stderr.contains(part), "no {part:?} in {stderr}");
    }
    assert!(stderr.contains("is available; use a coarser mesh"), "{stderr}");
}

#[test]
fn hostile_files() {
    let dir = scratch_dir("hostile");
    let text = std::fs::read_to_string(case("spring_block.toml")).unwrap();
    let write = |name: &str, contents: &[u8]| {
        let path = dir.join(name);
        std::fs::write(&path, contents).unwrap();
        path.to_str().unwrap().to_owned()
    };
    // TOML's own nan and inf literals reach the same finiteness rule as --set.
    let nan = write("nan.toml", text.replace("mu_s = 0.4", "mu_s = nan").as_bytes());
    expect_invalid(&nan, &[], "friction.mu_s = NaN must be a finite number");
    let inf = write("inf.toml", text.replace("mu_s = 0.4", "mu_s = -inf").as_bytes());
    expect_invalid(&inf, &[], "friction.mu_s = -inf must be a finite number");
    let empty = write("empty.toml", b"");
    expect_invalid(&empty, &[], "missing field `friction`");
    let binary = write("binary.toml", &[0xff, 0xfe, 0x00, 0x80, 0x41]);
    expect_invalid(&binary, &[], "it is not UTF-8 text");
    expect_invalid(dir.to_str().unwrap(), &[], "it is a folder, not a regular file");
    let no_kind = write("no_kind.toml", text.replace("kind = \"spring_block\"", "").as_bytes());
    expect_invalid(&no_kind, &[], "missing field `kind`");
    let no_mass = write("no_mass.toml", text.replace("mass = 1000.0", "").as_bytes());
    expect_invalid(&no_mass, &[], "missing field `mass`");
    let twice = write("twice.toml", format!("{text}\n[time]\ndt = 1\n").as_bytes());
    expect_invalid(&twice, &[], "TOML parse error");
}

/// Gravity and axisymmetry belong to a mesh; a lithostatic normal traction needs its level and
/// a coefficient that is not negative; an axisymmetric mesh lies in `x >= 0`; a weight the
/// contacts cannot hold stuck is refused before the run. Each names the key and what is allowed.
#[test]
fn axisymmetry_gravity_and_lithostatic_rules() {
    let mesh_only = "applies to a body drawn as a mesh (kind = \"mesh\")";
    expect_invalid(
        &case("spring_block.toml"),
        &["scene.gravity=[0.0, -9.81]"],
        &format!("scene.gravity: {mesh_only}; a spring_block scene has no body to weigh or revolve"),
    );
    expect_invalid(
        &case("point_loading.toml"),
        &["scene.axisymmetric=true"],
        &format!("scene.axisymmetric: {mesh_only}; a point scene has no body to weigh or revolve"),
    );
    expect_invalid(
        &case("paper_triangular.toml"),
        &["scene.gravity=[0.0, -9.81]"],
        &format!("scene.gravity: {mesh_only}; a block scene is the paper's plane-strain block, weightless"),
    );
    let pile = case("pile_pullout.toml");
    expect_invalid(
        &pile,
        &["scene.contacts.0.normal_traction={kind=\"lithostatic\", unit_weight=17658.0, coefficient=0.5}"],
        "scene.contacts[0].normal_traction.level = none is needed: the height y (m) of the surface that depth is \
         measured down from",
    );
    expect_invalid(
        &pile,
        &["scene.contacts.0.normal_traction.coefficient=-0.5"],
        "scene.contacts[0].normal_traction.coefficient = -0.5 must not be negative: K is 1 under a horizontal \
         surface and K0",
    );
    let rotated = format!("scene.file=\"{}/tests/meshes/block_rotated.msh\"", env!("CARGO_MANIFEST_DIR"));
    expect_invalid(
        &case("paper_mesh.toml"),
        &[&rotated, "scene.axisymmetric=true"],
        "scene.axisymmetric = true needs every node at r = x >= 0: the mesh crosses the axis x = 0",
    );
    expect_invalid(
        &case("fault_at_depth.toml"),
        &["scene.gravity=[0.0, -9.81]"],
        "scene.gravity = [0, -9.81] m/s² loads contact \"fault\" beyond its static strength before anything moves",
    );
}
