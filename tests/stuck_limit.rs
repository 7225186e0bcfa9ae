//! The stuck limit: with a static strength no load reaches (`μ_s = 100`, `μ_k = 50` on the
//! paper case) nothing slips, the block is a linear undamped system under a slowly growing
//! load, and the friction force follows the load. Its only oscillation is the small ringing
//! that the start of the drive excites in the contact's 7 Hz mode: about 1e-4 N/m rms in a
//! converged solution (SciPy's Radau and DOP853 on the same model), 1.8e-4 N/m by central
//! differences, which neither damp nor amplify it, and 5e-6 N/m by Wilson's method and SDIRK4,
//! which damp it. Every integrator at its default setting must keep it within ten times the
//! converged size. Tsitouras' pair, like every explicit fifth-order pair, amplifies undamped
//! modes at the steps its error control takes (`|R(iy)| > 1` for `y > 0.478`), and grew it to
//! 7 N/m within 100 s until its steps were bounded so that no mode grows more than 2× over a
//! run (`slipfront::dynamics::method`).

mod common;

use common::load;
use slipfront::case::SceneSpec;
use slipfront::scene::Scene;
use slipfront::scene::block::BlockScene;

/// Root-mean-square residual (N/m) of the friction force about its least-squares line over
/// `60 s ≤ t ≤ 100 s`, sampled at the end of every step the integrator takes.
fn ringing(overrides: &[&str]) -> f64 {
    let mut all = vec!["time.t_end=100", "friction.mu_s=100", "friction.mu_k=50"];
    all.extend_from_slice(overrides);
    let case = load("paper_triangular", &all);
    let SceneSpec::Block(spec) = &case.scene else { panic!("a block case") };
    let mut block = BlockScene::new(&case, spec).unwrap();
    let fixed = case.time.adaptive_tolerance().is_none();
    let mut samples = Vec::new();
    while block.time() < case.time.t_end - 1e-9 {
        let left = case.time.t_end - block.time();
        let dt = block.advance(if fixed { case.time.dt.min(left) } else { left }).unwrap();
        let frame = block.frame(Default::default(), dt);
        let fastest = frame.segments.iter().map(|s| s.slip_rate.abs()).fold(0.0, f64::max);
        assert!(fastest < SLIP_RATE, "a segment slips at {fastest:e} m/s at {} s", block.time());
        if block.time() >= 60.0 {
            samples.push((block.time(), frame.friction_force));
        }
    }
    let n = samples.len() as f64;
    let (mean_t, mean_f) = samples.iter().fold((0.0, 0.0), |(a, b), (t, f)| (a + t / n, b + f / n));
    let (stt, stf) =
        samples.iter().fold((0.0, 0.0), |(a, b), (t, f)| (a + (t - mean_t).powi(2), b + (t - mean_t) * (f - mean_f)));
    let slope = stf / stt;
    let squares: f64 = samples.iter().map(|(t, f)| (f - mean_f - slope * (t - mean_t)).powi(2)).sum();
    (squares / n).sqrt()
}

/// The event threshold of the paper case (m/s): no segment may reach it.
const SLIP_RATE: f64 = 3e-3;

/// Ringing allowed: ten times the converged solution's.
const ALLOWED: f64 = 1e-3;

#[test]
fn wilson_keeps_the_stuck_block_at_rest() {
    let r = ringing(&["time.integrator=wilson"]);
    println!("wilson: {r:e} N/m rms");
    assert!(r <= ALLOWED, "{r:e} N/m rms");
}

#[test]
fn tsit5_keeps_the_stuck_block_at_rest() {
    let r = ringing(&["time.integrator=tsit5"]);
    println!("tsit5: {r:e} N/m rms");
    assert!(r <= ALLOWED, "{r:e} N/m rms");
}

#[test]
fn sdirk4_keeps_the_stuck_block_at_rest() {
    let r = ringing(&["time.integrator=sdirk4"]);
    println!("sdirk4: {r:e} N/m rms");
    assert!(r <= ALLOWED, "{r:e} N/m rms");
}

#[test]
fn central_differences_keep_the_stuck_block_at_rest() {
    let r = ringing(&["time.integrator=central"]);
    println!("central: {r:e} N/m rms");
    assert!(r <= ALLOWED, "{r:e} N/m rms");
}
