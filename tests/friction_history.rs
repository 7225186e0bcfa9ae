//! The paper case's friction-force history before its first slips, with no integrator named
//! (`auto`: Tsitouras' pair at its default tolerance), against a converged solution: the same
//! pair at tolerance 1e-12, itself checked against 1e-11. From 100 s (after the base's ramp and
//! its transient) to 400 s (the first slips are at 420 s) the block creeps towards its first
//! rupture; its total friction force (N/m) must stay within 1e-3 N/m of the converged one, the
//! size of the stuck block's ringing allowed by `tests/stuck_limit.rs`.
//!
//! `cargo test --release --test friction_history -- --nocapture` prints the errors.

mod common;

use common::load;
use slipfront::case::{Case, SceneSpec};
use slipfront::frame::Needs;
use slipfront::scene::Scene;
use slipfront::scene::block::BlockScene;

/// The window compared (s).
const FROM: f64 = 100.0;
const TO: f64 = 400.0;

/// `(t, total friction force)` after every step of `case` up to `TO`, each step as the run
/// loop takes it (no step shortened to land anywhere).
fn history(case: &Case) -> Vec<(f64, f64)> {
    let SceneSpec::Block(spec) = &case.scene else { panic!("a block case") };
    let mut block = BlockScene::new(case, spec).unwrap();
    assert!(case.time.adaptive_tolerance().is_some(), "an adaptive method");
    let mut out = Vec::new();
    while block.time() < TO {
        let dt = block.advance(f64::INFINITY).unwrap();
        out.push((block.time(), block.frame(Needs::default(), dt).friction_force));
    }
    out
}

/// `reference` (times rising, steps short against the force's variation) linearly interpolated
/// at `t`.
fn at(reference: &[(f64, f64)], t: f64) -> f64 {
    let k = reference.partition_point(|(s, _)| *s < t).clamp(1, reference.len() - 1);
    let ((t0, f0), (t1, f1)) = (reference[k - 1], reference[k]);
    f0 + (f1 - f0) * (t - t0) / (t1 - t0)
}

/// The largest difference (N/m) between `run` and `reference` at `run`'s steps in the window.
fn largest_difference(run: &[(f64, f64)], reference: &[(f64, f64)]) -> f64 {
    run.iter().filter(|(t, _)| (FROM..=TO).contains(t)).map(|&(t, f)| (f - at(reference, t)).abs()).fold(0.0, f64::max)
}

#[test]
fn the_default_friction_force_before_the_first_slips_is_within_1e_3_n_per_m_of_a_converged_run() {
    let tight = |tolerance: &str| history(&load("paper_triangular", &["time.integrator=tsit5", tolerance]));
    let reference = tight("time.tolerance=1e-12");
    let check = tight("time.tolerance=1e-11");
    let default = history(&load("paper_triangular", &[]));
    let size = default.iter().filter(|(t, _)| (FROM..=TO).contains(t)).map(|(_, f)| f.abs()).fold(0.0, f64::max);
    let converged = largest_difference(&check, &reference);
    let error = largest_difference(&default, &reference);
    println!(
        "friction force {FROM}-{TO} s (up to {size:.1} N/m): default (auto) differs from Tsit5 at 1e-12 by at most \
         {error:.2e} N/m over {} steps; Tsit5 at 1e-11 by {converged:.2e} N/m",
        default.iter().filter(|(t, _)| (FROM..=TO).contains(t)).count()
    );
    assert!(size > 100.0, "the block is loaded by then: {size} N/m");
    assert!(converged < 1e-4, "the reference is converged to well within the bound: {converged:e} N/m");
    assert!(error < 1e-3, "the default's friction force is {error:e} N/m from the converged one");
}
