//! The pile of `cases/pile_pullout.toml` against the closed forms of a shaft's friction.
//!
//! A rigid shaft of radius `R` embedded `L` in soil, pulled steadily until its whole length
//! slides, carries the kinetic shaft friction: `μ_k f_n` on every point of its surface, so
//!
//! - under a uniform normal traction `f_n`: `F_k = 2π R L μ_k f_n`;
//! - under the lithostatic `f_n = K γ z`: `F_k = ∫₀ᴸ 2π R μ_k K γ z dz = π R μ_k K γ L²`.
//!
//! The static friction of the structured contact is `μ_k (1/R*₀)`, so a shaft whose every
//! point reached its static strength at once would peak at the same forms with `μ_k (1/R*₀)`.
//! The run's peak stays below that (how far, and why, below).
//!
//! Each run pulls the shaft at 1 cm/s from rest (a 1 s ramp) for 12 s in frames of 0.01 s, with healing off
//! (`ξ = 0`), so that 11 cm of slip decay the structure to `1/R* - 1 = e^{-κ p}` (eq. 4 with
//! `m = 1`), 2e-5 of its start, and the sliding ratio `R` to 1.

mod common;

use slipfront::case::{Case, SceneSpec};
use slipfront::frame::Needs;
use slipfront::scene::Scene;

const R: f64 = 0.3;
const L: f64 = 10.0;
const MU_K: f64 = 0.25;
const STRUCTURE0: f64 = 2.0;
const K0: f64 = 0.5;
const GAMMA: f64 = 17658.0;

/// The pile case pulled at 1 cm/s for 12 s without healing, with `overrides`.
fn pulled(overrides: &[&str]) -> Case {
    let mut all = vec![
        "friction.xi=0",
        "time.t_end=12",
        "time.dt=0.01",
        "scene.contacts.0.base_phases=[{velocity=[0.0, 0.01]}]",
        "events.slip_rate_threshold=5e-3",
    ];
    all.extend_from_slice(overrides);
    common::load("pile_pullout", &all)
}

/// `(time, force, displacement)` of every frame: the total friction force (N, along the
/// contact's tangent, which runs down the shaft) and the shaft's displacement up.
fn pull(case: &Case) -> Vec<(f64, f64, f64)> {
    let SceneSpec::Mesh(spec) = &case.scene else { panic!("a mesh case") };
    let mut scene = slipfront::scene::mesh::scene(case, spec).unwrap();
    let mut history = Vec::new();
    while scene.time() < case.time.t_end - 1e-9 {
        let left = case.time.t_end - scene.time();
        let dt = scene.advance(case.time.dt.min(left)).unwrap();
        let frame = scene.frame(Needs::default(), dt);
        history.push((frame.time, frame.friction_force, frame.base_displacement));
    }
    history
}

/// The pull-out force (N, up) at its peak, and its mean over the last second (fully sliding).
fn peak_and_kinetic(history: &[(f64, f64, f64)]) -> (f64, f64) {
    let peak = history.iter().map(|h| -h.1).fold(f64::NEG_INFINITY, f64::max);
    let last: Vec<f64> = history.iter().filter(|h| h.0 > 11.0).map(|h| -h.1).collect();
    (peak, last.iter().sum::<f64>() / last.len() as f64)
}

/// Uniform `f_n = 50 kPa`: the kinetic pull-out force equals `2π R L μ_k f_n` = 235.6 kN within
/// 1e-3 (measured 2.0e-5: the structure's `e^{-κ p}` left after 11 cm of slip). The peak is
/// below `2π R L μ_k (1/R*₀) f_n` = 471.2 kN, at 0.846 of it: a rigid shaft in elastic soil
/// loads its points unequally (most at the fixed base and the free surface), so the first to
/// slip soften while the rest still climb, and no point of the subloading surface reaches its
/// static strength without plastic slip, which decays its structure on the way (eq. 4): the
/// model has no purely elastic range (asserted between 0.8 and 1).
#[test]
fn the_kinetic_pull_out_force_of_a_uniform_shaft_is_2_pi_r_l_mu_k_f_n() {
    let f_n = 5.0e4;
    let case = pulled(&[&format!("scene.contacts.0.normal_traction={{kind=\"uniform\", value={f_n}}}")]);
    let (peak, kinetic) = peak_and_kinetic(&pull(&case));
    let closed = 2.0 * std::f64::consts::PI * R * L * MU_K * f_n;
    let (k_error, p_ratio) = ((kinetic - closed).abs() / closed, peak / (closed * STRUCTURE0));
    println!(
        "uniform: kinetic {kinetic:.1} N against {closed:.1} N ({k_error:.1e}); peak {peak:.1} N, {p_ratio:.3} of the static form"
    );
    assert!(k_error < 1e-3, "kinetic {kinetic} N against {closed} N");
    assert!((0.8..1.0).contains(&p_ratio), "peak {peak} N: {p_ratio} of {}", closed * STRUCTURE0);
}

/// Lithostatic `f_n = K0 γ z`: the kinetic pull-out force equals `π R μ_k K0 γ L²` = 208.0 kN
/// within 1e-3 (measured 2.0e-5); the peak is 0.844 of `π R μ_k (1/R*₀) K0 γ L²`, as under a
/// uniform traction, though for a further reason: the ground surface, weakest, slips first, and the slip front
/// runs down the shaft (the onsets of its upper three quarters in order of depth), so the upper
/// shaft is already sliding near kinetic friction when the deepest points peak (asserted
/// between 0.75 and 1). The stress concentration at the shaft's tip nucleates a second front,
/// which runs up from the tip and meets the first (measured: down from 0.596 s at the surface,
/// up from 0.750 s at the tip's segment, meeting at 8.6 m depth at 0.833 s).
#[test]
fn the_kinetic_pull_out_force_of_a_lithostatic_shaft_is_pi_r_mu_k_k_gamma_l_squared() {
    let case = pulled(&[]);
    let history = pull(&case);
    let (peak, kinetic) = peak_and_kinetic(&history);
    let closed = std::f64::consts::PI * R * MU_K * K0 * GAMMA * L * L;
    let (k_error, p_ratio) = ((kinetic - closed).abs() / closed, peak / (closed * STRUCTURE0));
    println!(
        "lithostatic: kinetic {kinetic:.1} N against {closed:.1} N ({k_error:.1e}); peak {peak:.1} N, {p_ratio:.3} of the static form"
    );
    assert!(k_error < 1e-3, "kinetic {kinetic} N against {closed} N");
    assert!((0.75..1.0).contains(&p_ratio), "peak {peak} N: {p_ratio} of {}", closed * STRUCTURE0);
    let onsets = common::onsets(&case);
    let mut first = vec![f64::INFINITY; 40];
    for (segment, onset) in onsets {
        first[segment] = first[segment].min(onset);
    }
    println!("first onsets down the shaft: {:.3?}", &first[..]);
    assert!(first.iter().all(|t| t.is_finite()), "every segment slips");
    let upper = &first[..30];
    assert!(upper.windows(2).all(|w| w[1] > w[0]), "the slip front runs down the upper shaft: {first:?}");
    assert!(first[39] < first[30], "the tip nucleates its own slip: {first:?}");
}

/// The shaft's forces are totals around the circumference, so every unit a user reads says N,
/// not N/m: the ruptures CSV's header, the recorded friction force's series name (as the
/// official Rerun SDK reads it from the file) and `check`'s summary. A run of the shipped case
/// to 1.5 s, past the first slip at the surface (0.76 s), through the binary as a user runs it.
#[test]
fn a_pile_run_names_its_forces_in_n_in_the_catalog_the_recording_and_check() {
    let out = std::env::temp_dir().join(format!("slipfront-pile-units-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let run = common::binary()
        .args(["run", &common::case_path("pile_pullout.toml"), "--set", "time.t_end=1.5", "--out-dir"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(run.status.success(), "run: {}", String::from_utf8_lossy(&run.stderr));

    let ruptures = std::fs::read_to_string(out.join("pile_pullout.ruptures.csv")).unwrap();
    let header = ruptures.lines().next().unwrap();
    assert_eq!(header.rsplit(',').next(), Some("friction_force_drop_n"), "the ruptures header: {header}");
    assert!(ruptures.lines().count() > 1, "the run to 1.5 s has a rupture: {ruptures}");

    let rrd = out.join("pile_pullout.rrd");
    let check = common::binary().arg("check").arg(&rrd).output().unwrap();
    let printed = String::from_utf8_lossy(&check.stdout);
    assert!(check.status.success(), "check: {printed}{}", String::from_utf8_lossy(&check.stderr));
    assert!(
        printed.lines().any(|l| l.ends_with("contact/friction_force is the total around the circumference, in N")),
        "check names the force's unit: {printed}"
    );
    assert!(!printed.contains("N/m"), "check prints no force per metre: {printed}");

    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/python/read_series_names.py");
    let names = std::process::Command::new("python3").arg(script).arg(&rrd).arg("contact/friction_force").output();
    match names {
        Ok(o) if o.status.success() => {
            let text = String::from_utf8(o.stdout).unwrap();
            let name: Vec<&str> = text.lines().skip(1).map(|l| l.splitn(3, ',').nth(2).unwrap()).collect();
            assert_eq!(name, ["friction force (N)"], "the recorded series' name: {text}");
        }
        Ok(o) if o.status.code() == Some(3) => {
            common::skip_missing::<()>("the official Rerun Python SDK (pip install \"rerun-sdk[datafusion]==0.36.*\")");
        }
        Ok(o) => panic!("{script}: {}", String::from_utf8_lossy(&o.stderr)),
        Err(_) => {
            common::skip_missing::<()>("python3");
        }
    }
    std::fs::remove_dir_all(&out).unwrap();
}
