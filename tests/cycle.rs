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
