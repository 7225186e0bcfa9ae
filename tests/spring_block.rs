//! The spring-block scene against an independent solution of the same ODEs, the
//! Coulomb limit, and the symmetry of the drive.

use slipfront::case::{self, Case};
use slipfront::catalog::events::EventDetector;
use slipfront::frame::Needs;
use slipfront::scene;

fn case_with(overrides: &[&str]) -> Case {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/cases/spring_block.toml")).unwrap();
    // Wilson's method unless the overrides name another.
    let wilson = std::iter::once("time.integrator=wilson");
    let owned: Vec<String> = wilson.chain(overrides.iter().copied()).map(|s| s.to_string()).collect();
    case::from_str(&text, &owned).unwrap()
}

/// Runs the scene through the event detector; returns the events and the block's history
/// `(t, x)` at every step.
fn run(case: &Case) -> (Vec<slipfront::catalog::events::SlipEvent>, Vec<(f64, f64, f64)>) {
    let mut scene = scene::build(case).unwrap();
    let mut detector = EventDetector::new(1, case.slip_rate_threshold(), case.events.merge_within);
    let mut history = Vec::new();
    let frame = scene.frame(Needs::default(), 0.0);
    detector.record(&frame);
    let steps = case.time.steps();
    for k in 1..=steps {
        let target = if k == steps { case.time.t_end } else { k as f64 * case.time.dt };
        let dt = target - scene.time();
        scene.advance(dt).unwrap();
        let frame = scene.frame(Needs::default(), dt);
        detector.record(&frame);
        let [x, _] = frame.block.unwrap();
        history.push((frame.time, x, frame.segments[0].traction_t));
    }
    detector.finish();
    (detector.events().to_vec(), history)
}

/// The spring-block ODEs written out independently of the library (MODEL.md conventions):
/// `y = (x, ẋ, f_t, 1/R*)`, `M ẍ = k (v t - x) + f_t + f0` (`x` from the initial equilibrium,
/// where the spring balances the initial traction `-f0`), `ḟ_t = -α_t (ẋ + Λ t)`,
/// `d(1/R*)/dt = -κ (1/R* - 1) Λ + ξ (1 - μ_k/(μ_s R*))`, `Λ = max(0, eq. 5)`.
struct Ode {
    mu_s: f64,
    mu_k: f64,
    alpha: f64,
    r: f64,
    kappa: f64,
    xi: f64,
    mass: f64,
    k: f64,
    v: f64,
    f_n: f64,
    f0: f64,
}

impl Ode {
    fn lambda(&self, y: &[f64; 4]) -> f64 {
        let (xd, s, z) = (y[1], y[2], y[3]);
        if s == 0.0 {
            return 0.0;
        }
        let sigma = s.signum();
        let mu_f = self.mu_k * self.f_n;
        let ratio = s.abs() / (mu_f * z);
        let a = self.mu_k / self.mu_s;
        let numerator = -self.alpha * xd * sigma - self.xi * ratio * (1.0 - a * z) * mu_f;
        let denominator = self.alpha + self.r * (-ratio.ln()) * z * mu_f - self.kappa * ratio * (z - 1.0) * mu_f;
        (numerator / denominator).max(0.0)
    }

    fn rhs(&self, t: f64, y: &[f64; 4]) -> [f64; 4] {
        let lambda = self.lambda(y);
        let sigma = y[2].signum();
        let a = self.mu_k / self.mu_s;
        [
            y[1],
            (self.k * (self.v * t - y[0]) + y[2] + self.f0) / self.mass,
            -self.alpha * (y[1] + lambda * sigma),
            -self.kappa * (y[3] - 1.0) * lambda + self.xi * (1.0 - a * y[3]),
        ]
    }

    /// One Dormand–Prince 5(4) step: the 5th-order solution and the error estimate.
    fn dopri(&self, t: f64, y: &[f64; 4], h: f64) -> ([f64; 4], f64) {
        const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
        const A: [[f64; 6]; 7] = [
            [0.0; 6],
            [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
            [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
            [19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0],
            [9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0],
            [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
        ];
        const B5: [f64; 7] = [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0, 0.0];
        const B4: [f64; 7] =
            [5179.0 / 57600.0, 0.0, 7571.0 / 16695.0, 393.0 / 640.0, -92097.0 / 339200.0, 187.0 / 2100.0, 1.0 / 40.0];
        let mut k = [[0.0; 4]; 7];
        for i in 0..7 {
            let mut yi = *y;
            for (j, kj) in k.iter().enumerate().take(i) {
                for c in 0..4 {
                    yi[c] += h * A[i][j] * kj[c];
                }
            }
            k[i] = self.rhs(t + C[i] * h, &yi);
        }
        let mut y5 = *y;
        let mut err: f64 = 0.0;
        let scale = [1e-3, 1e-4, 1.0, 1.0];
        for c in 0..4 {
            let mut d5 = 0.0;
            let mut d4 = 0.0;
            for i in 0..7 {
                d5 += B5[i] * k[i][c];
                d4 += B4[i] * k[i][c];
            }
            y5[c] += h * d5;
            err = err.max((h * (d5 - d4)).abs() / (scale[c] + y5[c].abs()));
        }
        (y5, err)
    }

    /// Time at which Λ first exceeds `threshold`, integrating with tolerance `tol`.
    fn first_onset(&self, threshold: f64, tol: f64) -> f64 {
        let (mut t, mut y, mut h) = (0.0, [0.0, 0.0, -self.f0, 2.0], 1e-3);
        loop {
            let (next, err) = self.dopri(t, &y, h);
            if err <= tol {
                if self.lambda(&next) > threshold {
                    // Bisect the crossing with single 5th-order steps from the accepted state.
                    let (mut lo, mut hi) = (0.0, h);
                    while hi - lo > 1e-10 {
                        let mid = 0.5 * (lo + hi);
                        if self.lambda(&self.dopri(t, &y, mid).0) > threshold { hi = mid } else { lo = mid }
                    }
                    return t + 0.5 * (lo + hi);
                }
                t += h;
                y = next;
            }
            h *= (0.9 * (tol / err.max(1e-300)).powf(0.2)).clamp(0.2, 5.0);
        }
    }
}

/// The shipped case's ODEs.
fn shipped_ode() -> Ode {
    Ode {
        mu_s: 0.4,
        mu_k: 0.2,
        alpha: 1e6,
        r: 100.0,
        kappa: 10.0,
        xi: 0.1,
        mass: 1000.0,
        k: 500.0,
        v: 1e-3,
        f_n: 1000.0,
        f0: 1e-7,
    }
}

#[test]
fn first_slip_onset_agrees_with_an_independent_adaptive_solution() {
    let case = case_with(&["time.t_end=800", "time.dt=0.005"]);
    let (events, _) = run(&case);
    let onset = events.first().expect("a slip before 800 s").onset;
    // The reference at 1e-10, converged to 1e-6 against 1e-11; the onset within 1e-4 of it.
    assert_onset_matches_the_ode("wilson", onset, case.slip_rate_threshold(), [1e-10, 1e-11, 1e-6], 1e-4);
}

/// Asserts that `onset` lies within `bound` (relative) of the first onset of the test's own
/// ODE solution at tolerance `tolerance`, after checking that solution against one at
/// `check_tolerance`: they must agree to `converged` (relative).
fn assert_onset_matches_the_ode(
    label: &str,
    onset: f64,
    threshold: f64,
    [tolerance, check_tolerance, converged]: [f64; 3],
    bound: f64,
) {
    let ode = shipped_ode();
    let reference = ode.first_onset(threshold, tolerance);
    let check = ode.first_onset(threshold, check_tolerance);
    assert!((reference - check).abs() < converged * reference, "the reference converged: {reference} vs {check}");
    let relative = (onset - reference).abs() / reference;
    println!("{label} onset {onset} s, reference {reference} s, relative difference {relative:e}");
    assert!(relative < bound, "{label} onset {onset} s vs reference {reference} s: relative {relative:e}");
}

/// Runs `case` through the library's time loop (adaptive steps included); returns its events.
fn run_loop(case: &Case) -> Vec<slipfront::catalog::events::SlipEvent> {
    slipfront::study::ensemble::catalog(case).unwrap().0.events
}

#[test]
fn tsit5_locates_the_first_onset_within_1e9_of_a_tight_independent_solution() {
    // The test's own Dormand–Prince solution at two tight tolerances is the reference; Tsitouras'
    // pair in the library, at tolerance 1e-12, must agree to 1e-9 relative (8e-7 s).
    let case = case_with(&["time.t_end=800", "time.integrator=tsit5", "time.tolerance=1e-12"]);
    let events = run_loop(&case);
    let onset = events.first().expect("a slip before 800 s").onset;
    assert_onset_matches_the_ode("tsit5", onset, case.slip_rate_threshold(), [1e-13, 1e-12, 1e-10], 1e-9);
}

#[test]
fn tsit5_and_wilson_find_the_same_events() {
    // Two integrators of different order and form (rate form, total form with the implicit
    // update), each at a setting for about 2e-5 on the first onset: the same events, onsets
    // and ends within 1e-4 relative, slips within 1 %.
    let wilson = run_loop(&case_with(&["time.dt=0.005"]));
    let tsit5 = run_loop(&case_with(&["time.integrator=tsit5", "time.tolerance=1e-9"]));
    assert_eq!(wilson.len(), tsit5.len(), "wilson {wilson:?}\ntsit5 {tsit5:?}");
    assert!(!wilson.is_empty());
    for (a, b) in wilson.iter().zip(&tsit5) {
        assert!((a.onset - b.onset).abs() < 1e-4 * a.onset, "onsets {} and {}", a.onset, b.onset);
        assert!((a.end - b.end).abs() < 1e-4 * a.end, "ends {} and {}", a.end, b.end);
        assert!((a.slip - b.slip).abs() < 0.01 * a.slip, "slips {} and {}", a.slip, b.slip);
    }
}

#[test]
fn sharpened_transitions_approach_the_coulomb_stress_drop() {
    // Large r makes the elastic-plastic transition sharp, κ ≪ r keeps the structure intact until
    // R reaches 1, and ξ = 0 stops healing: the law tends to Coulomb friction with μ_s → μ_k.
    let case = case_with(&["friction.r=1e5", "friction.kappa=100", "friction.xi=0", "time.dt=0.005"]);
    let (events, history) = run(&case);
    let event = events.first().expect("a slip event");
    // The stress drop is that of the spring force across the event: k [(x₁ - x₀) - v (t₁ - t₀)].
    let x_at = |t: f64| {
        let i = history.partition_point(|h| h.0 < t).min(history.len() - 1);
        history[i].1
    };
    let k = 500.0;
    let drop = k * ((x_at(event.end) - x_at(event.onset)) - 1e-3 * (event.end - event.onset));
    let coulomb = 2.0 * (0.4 - 0.2) * 1000.0;
    println!("stress drop {drop} Pa, Coulomb {coulomb} Pa");
    assert!((drop - coulomb).abs() < 0.05 * coulomb, "stress drop {drop} Pa vs Coulomb {coulomb} Pa");
}

#[test]
fn reversing_the_drive_mirrors_the_traction_exactly() {
    let forward = case_with(&["time.t_end=850"]);
    let backward = case_with(&["time.t_end=850", "scene.velocity=-1e-3"]);
    let (_, a) = run(&forward);
    let (_, b) = run(&backward);
    assert_eq!(a.len(), b.len());
    for ((ta, xa, fa), (tb, xb, fb)) in a.iter().zip(&b) {
        assert_eq!(ta, tb);
        assert_eq!(*xa, -xb);
        assert_eq!(*fa, -fb, "t = {ta}");
    }
}

#[test]
fn adaptive_steps_converge_to_the_independent_onset_as_the_tolerance_tightens() {
    let reference = shipped_ode().first_onset(case_with(&[]).slip_rate_threshold(), 1e-10);
    let mut errors = Vec::new();
    for tolerance in ["1e-5", "1e-6", "1e-7"] {
        let case = case_with(&["time.t_end=800", &format!("time.tolerance={tolerance}")]);
        let (catalog, _) = slipfront::study::ensemble::catalog(&case).unwrap();
        let onset = catalog.events.first().expect("a slip before 800 s").onset;
        let relative = (onset - reference).abs() / reference;
        println!("tolerance {tolerance}: onset {onset} s, reference {reference} s, relative {relative:e}");
        errors.push(relative);
    }
    assert!(errors[2] < errors[0], "the error shrinks with the tolerance: {errors:?}");
    assert!(errors[2] < 1e-4, "tolerance 1e-7: relative onset error {:e}", errors[2]);
}
