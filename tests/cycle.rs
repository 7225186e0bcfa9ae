//! Earthquake-cycle stepping ([`slipfront::dynamics::cycle`]): the slowest mode that decides
//! when a step is quasi-static, against a dense eigensolver; `auto`'s choice for a plate-rate
//! drive; and the shipped `cases/cycle_slow_loading.toml`'s ruptures against the slip budget of
//! a steady cycle, which no step rule enters.

mod common;

use std::path::PathBuf;

use common::{binary, case_path, load};
use nalgebra::{DMatrix, SymmetricEigen};
use slipfront::dynamics::cycle::slowest_frequency;
use slipfront::dynamics::method::Method;
use slipfront::dynamics::{Motion, NormalBehaviour, Settings, System};
use slipfront::fem::{Assembled, Material, PlaneStrain};
use slipfront::friction::FrictionParams;
use slipfront::scene::block::block;

/// The paper's block on an `nx` × `ny` mesh with the paper's contact.
fn paper_block(nx: usize, ny: usize) -> System {
    let material = Material { elasticity: PlaneStrain { youngs_modulus: 1.0e3, poisson_ratio: 0.0 }, density: 1000.0 };
    let base = Motion::constant([1e-9, 0.0], 1e4);
    let params = FrictionParams::paper();
    let Assembled { body, contact, .. } =
        block(10.0, 1.0, nx, ny, material, params, (&|x| 350.0 + 85.0 * x, NormalBehaviour::Held), base);
    System::new(body, contact, Settings::default()).unwrap()
}

/// `ω_min` of `system` on its contact's tangential springs: the smallest eigenvalue of
/// `M^{-1/2} (K + K_t) M^{-1/2}`, formed densely and solved by nalgebra's symmetric eigensolver
/// (`K` holds the contact's normal springs).
fn dense_slowest_frequency(system: &System) -> f64 {
    let (body, contact) = (&system.body, &system.contact);
    let n = body.dofs();
    let mut dense = DMatrix::<f64>::zeros(n, n);
    for (i, j, v) in body.stiffness.entries() {
        dense[(i, j)] += v;
    }
    for (k, p) in contact.points.iter().enumerate() {
        let terms: Vec<(usize, f64)> = p.tangential.terms().collect();
        for &(a, c_a) in &terms {
            for &(b, c_b) in &terms {
                dense[(a, b)] += contact.params(k).alpha_t * p.weight * c_a * c_b;
            }
        }
    }
    let scaled = DMatrix::from_fn(n, n, |i, j| dense[(i, j)] / (body.mass[i] * body.mass[j]).sqrt());
    SymmetricEigen::new(scaled).eigenvalues.iter().copied().fold(f64::INFINITY, f64::min).sqrt()
}

#[test]
fn the_slowest_mode_is_the_dense_eigensolvers_approached_from_above() {
    for (nx, ny) in [(10, 1), (30, 6)] {
        let system = paper_block(nx, ny);
        let (found, dense) = (slowest_frequency(&system).unwrap(), dense_slowest_frequency(&system));
        println!("{nx} x {ny}: Lanczos {found:.9} rad/s, dense {dense:.9} rad/s");
        assert!(found >= dense * (1.0 - 1e-12), "{nx} x {ny}: {found} below the dense {dense}");
        assert!((found - dense) / dense < 1e-9, "{nx} x {ny}: {found} against the dense {dense}");
    }
}

#[test]
fn auto_gives_a_plate_rate_drive_cycle_steps_and_the_papers_drive_keeps_its_pair() {
    let slow = load("cycle_slow_loading", &[]);
    assert_eq!(slow.time.method, Method::Cycle, "{:?}", slow.time.chosen_because);
    let why = slow.time.chosen_because.unwrap();
    assert!(why.contains("radians of its stiffest mode"), "{why}");
    // The same block at the paper's drive (1 mm/s): 6.3 radians, Tsitouras' pair as before.
    let paper = load("cycle_slow_loading", &["scene.base_velocity=1e-3", "time.t_end=1000", "time.dt_max=10"]);
    assert_eq!(paper.time.method, Method::Tsit5, "{:?}", paper.time.chosen_because);
}

/// One row of a ruptures CSV.
struct Rupture {
    onset: f64,
    nucleation: usize,
    segments: usize,
    max_slip: f64,
}

fn ruptures(path: &PathBuf) -> Vec<Rupture> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (onset, nucleation, segments, slip) =
        (column("onset_s"), column("nucleation_segment"), column("segments_slipped"), column("max_slip_m"));
    lines
        .map(|line| {
            let cells: Vec<&str> = line.split(',').collect();
            Rupture {
                onset: cells[onset].parse().unwrap(),
                nucleation: cells[nucleation].parse().unwrap(),
                segments: cells[segments].parse().unwrap(),
                max_slip: cells[slip].parse().unwrap(),
            }
        })
        .collect()
}

#[test]
fn the_plate_rate_case_slips_what_the_plate_loaded_in_each_cycle() {
    // Two cycles of the shipped case (its first 25 years), no integrator named.
    let dir = std::env::temp_dir().join(format!("slipfront-cycle-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let output = binary()
        .args(["run", &case_path("cycle_slow_loading.toml"), "--no-rrd", "--quiet", "--out-dir"])
        .arg(&dir)
        .args(["--set", "time.t_end=8e8"])
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let all = ruptures(&dir.join("cycle_slow_loading.ruptures.csv"));
    let large: Vec<&Rupture> = all.iter().filter(|r| r.max_slip > 0.01).collect();
    assert_eq!(large.len(), 2, "two system-size ruptures in 25 years, not {}", large.len());
    // The kinematic budget of a cycle: the base moves v Δt between ruptures (from the end of
    // the ramp's half for the first), the block's top is held, and each rupture releases the
    // strain the base loaded, up to the traction it leaves (under 1 % of the strength).
    let (v, ramp) = (1e-9, 1e4);
    let mut since = 0.5 * ramp;
    for (k, r) in large.iter().enumerate() {
        let loaded = v * (r.onset - since);
        let share = r.max_slip / loaded;
        println!(
            "rupture {k}: onset {:.6e} s, slip {:.5} m, the base moved {loaded:.5} m: {share:.4}",
            r.onset, r.max_slip
        );
        assert_eq!(r.segments, 10, "rupture {k} spans the contact");
        assert_eq!(r.nucleation, 0, "rupture {k} starts at the low-stress end");
        assert!((share - 1.0).abs() < 0.02, "rupture {k} slips {share} of what the base loaded");
        since = r.onset;
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `(time, friction force)` of every recorded step of the shipped case to `t_end`, with the
/// overrides `sets`, read back through `slipfront export`.
fn friction_force_history(t_end: &str, sets: &[&str]) -> Vec<(f64, f64)> {
    let dir = std::env::temp_dir().join(format!("slipfront-cycle-force-{}-{}", std::process::id(), sets.len()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut run = binary();
    run.args(["run", &case_path("cycle_slow_loading.toml"), "--no-rrd", "--quiet", "--out-dir"]).arg(&dir);
    run.args(["--mcap"]).arg(dir.join("run.mcap"));
    for set in [format!("time.t_end={t_end}"), "record.stick_every=1".to_string()]
        .iter()
        .chain(&sets.iter().map(|s| s.to_string()).collect::<Vec<_>>())
    {
        run.args(["--set", set]);
    }
    let output = run.output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let csv = dir.join("run.csv");
    let output = binary().arg("export").arg(dir.join("run.mcap")).arg("-o").arg(&csv).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (time, force) = (column("sim_time_s"), column("friction_force_N_per_m"));
    let history = lines
        .map(|line| {
            let cells: Vec<&str> = line.split(',').collect();
            (cells[time].parse().unwrap(), cells[force].parse().unwrap())
        })
        .collect();
    let _ = std::fs::remove_dir_all(&dir);
    history
}

#[test]
fn long_steps_through_the_ramp_keep_the_block_in_equilibrium() {
    // The base's first 2e5 s (its ramp is 1e4 s) in the default steps, which grow to a day,
    // against steps of at most 1 s (200 000 of them, each shorter than 100 radians of the
    // slowest mode, so on the dynamic path with the case's θ = 2), a converged reference of
    // the same equations. Where the long steps recorded, the friction force (the base's pull
    // on the block, the stuck limit of about 5e3 N/m per metre the base moved) must agree with
    // the reference's to 1 %. Long steps that left the block behind the base had the contact
    // carry the base's motion alone, a force up to 2000 times the stuck limit's.
    let long = friction_force_history("2e5", &["time.dt_max=1e5"]);
    let short = friction_force_history("2e5", &["time.dt_max=1"]);
    let at = |t: f64| {
        let k = short.partition_point(|&(s, _)| s < t).clamp(1, short.len() - 1);
        let ((t0, f0), (t1, f1)) = (short[k - 1], short[k]);
        f0 + (f1 - f0) * (t - t0) / (t1 - t0)
    };
    let compared: Vec<(f64, f64, f64)> =
        long.iter().filter(|&&(t, _)| t >= 100.0).map(|&(t, f)| (t, f, at(t))).collect();
    assert!(compared.len() >= 10, "{} steps compared", compared.len());
    for (t, f, reference) in compared {
        println!("t = {t:.1} s: {f:.6} N/m against {reference:.6}");
        assert!((f - reference).abs() <= 1e-2 * reference.abs(), "at {t} s: {f} N/m against {reference}");
    }
}
