//! The friction law alone: the implicit update against the rate form, closed forms and
//! independent integrations.

use nalgebra::Vector2;
use slipfront::case::{Phase, PointSpec};
use slipfront::frame::Needs;
use slipfront::friction::{ContactState, FrictionParams, RStarLaw, law, update};
use slipfront::scene::Scene;
use slipfront::scene::point::PointScene;

fn paper() -> FrictionParams {
    FrictionParams::paper()
}

/// `∫_{R0}^{R} dρ / (-ln ρ)` by composite Gauss–Legendre in `s = -ln ρ` (independent of the
/// solver's exponential integral): `∫_{s(R)}^{s(R0)} e^{-s}/s ds`.
fn r_law_integral(r0: f64, r1: f64) -> f64 {
    let (a, b) = (-r1.ln(), -r0.ln());
    // Graded panels: the integrand e^{-s}/s is steep near s = 0.
    let nodes = [-0.906_179_845_938_664, -0.538_469_310_105_683, 0.0, 0.538_469_310_105_683, 0.906_179_845_938_664];
    let weights = [
        0.236_926_885_056_189,
        0.478_628_670_499_366,
        0.568_888_888_888_889,
        0.478_628_670_499_366,
        0.236_926_885_056_189,
    ];
    let panels = 4000;
    let (la, lb) = (a.ln(), b.ln());
    let mut sum = 0.0;
    for p in 0..panels {
        // Panels uniform in ln s.
        let x0 = la + (lb - la) * p as f64 / panels as f64;
        let x1 = la + (lb - la) * (p + 1) as f64 / panels as f64;
        for (node, w) in nodes.iter().zip(weights) {
            let x = 0.5 * (x0 + x1) + 0.5 * (x1 - x0) * node;
            let s = x.exp();
            // ds = s dx
            sum += w * 0.5 * (x1 - x0) * (-s).exp();
        }
    }
    sum
}

/// The sliding ratio reached from `r0` after plastic slip `p`, by bisection on the quadrature.
fn r_from_law(r0: f64, r: f64, p: f64) -> f64 {
    let (mut lo, mut hi) = (r0, 1.0 - 1e-15);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if r_law_integral(r0, mid) < r * p { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

#[test]
fn monotonic_loading_stays_on_the_subloading_surface_with_r_rising_to_one() {
    let params = paper();
    let f_n = 1000.0;
    let mut state = ContactState::initial(&params, f_n, 1.0);
    let r0 = state.sliding_ratio(&params);
    let (dt, v) = (0.01, -1.0e-3);
    let mut previous_ratio = r0;
    let mut largest_jump: f64 = 0.0;
    let mut checked = 0;
    for step in 1..=30_000 {
        let updated = update(&params, &state, v * dt, dt).unwrap();
        state = updated.state;
        assert!(updated.plastic_increment > 0.0, "loading is plastic at every step (step {step})");
        let lambda = law::plastic_multiplier(&params, &state, Vector2::new(v, 0.0));
        assert!(lambda > 0.0, "eq. (5) gives Λ > 0 in loading (step {step}: {lambda})");
        let ratio = state.sliding_ratio(&params);
        // Near R = 1, R derived from the traction moves by single ulps.
        assert!(ratio >= previous_ratio - 4.0 * f64::EPSILON, "R rises monotonically (step {step})");
        largest_jump = largest_jump.max(ratio - previous_ratio);
        previous_ratio = ratio;
        // The traction lies on the subloading surface whose R follows Ṙ = -r ln(R) Λ.
        if step % 500 == 0 && ratio < 1.0 - 1e-9 {
            let r_law = r_from_law(r0, params.r, state.plastic_slip);
            let surface = state.traction_t.abs() - r_law * state.r_star().recip() * params.mu_k * f_n;
            let relative = surface.abs() / state.traction_t.abs();
            assert!(relative < 1e-9, "step {step}: |f_t| - (R/R*) μ_k f_n = {surface} Pa (relative {relative:e})");
            checked += 1;
        }
    }
    assert!(checked >= 10, "the surface was checked along the loading ({checked} times)");
    assert!(previous_ratio > 1.0 - 1e-9, "R reaches 1: {previous_ratio}");
    assert!(largest_jump < 0.02, "R rises smoothly: largest step increase {largest_jump}");
}

#[test]
fn unloading_has_non_positive_plastic_multiplier_and_is_elastic() {
    let params = paper();
    let mut state = ContactState::initial(&params, 1000.0, 1.0);
    for _ in 0..10_000 {
        state = update(&params, &state, -1e-5, 0.01).unwrap().state;
    }
    let loaded = state.traction_t;
    assert!(loaded > 300.0);
    // Unload until the traction has fallen by 90 %: no sign change yet.
    let v = 1.0e-3;
    while state.traction_t > 0.1 * loaded {
        let lambda = law::plastic_multiplier(&params, &state, Vector2::new(v, 0.0));
        assert!(lambda <= 0.0, "eq. (5) gives Λ ≤ 0 in unloading: {lambda}");
        let updated = update(&params, &state, v * 0.01, 0.01).unwrap();
        assert_eq!(updated.plastic_increment, 0.0);
        assert_eq!(updated.tangent, -params.alpha_t);
        assert_eq!(updated.state.traction_t, state.traction_t - params.alpha_t * v * 0.01);
        state = updated.state;
    }
}

/// Healing alone: `d(1/R*)/dt = γ ξ (1 - a/R*)` with `a = μ_k/μ_s` (n = 1). Writing `z = 1/R*`,
/// `ż = γ ξ (1 - a z)`, so `z(t) = 1/a + (z₀ - 1/a) e^{-γ ξ a t}` and
/// `R*(t) = 1 / z(t)` solves `Ṙ* = -γ ξ R*² (1 - μ_k/(μ_s R*))`.
fn healed_r_star(params: &FrictionParams, z0: f64, t: f64) -> f64 {
    let a = params.kinetic_static_ratio();
    let gamma = params.rstar_scale();
    1.0 / (1.0 / a + (z0 - 1.0 / a) * (-gamma * params.xi * a * t).exp())
}

#[test]
fn healing_in_stick_follows_the_closed_form() {
    for law_kind in [RStarLaw::Consistent, RStarLaw::Eq4] {
        let mut params = paper();
        params.rstar_law = law_kind;
        params.structure0 = 1.0;
        let mut state = ContactState::initial(&params, 1000.0, 1.0);
        let dt = 1e-3;
        let mut worst: f64 = 0.0;
        for step in 1..=100_000 {
            state = update(&params, &state, 0.0, dt).unwrap().state;
            let exact = healed_r_star(&params, 1.0, step as f64 * dt);
            worst = worst.max((state.r_star() - exact).abs());
        }
        assert!(worst < 1e-8, "{law_kind:?}: max |R* - closed form| over 100 s = {worst:e}");
        // The error is the trapezoidal rule's: it falls by 4 when dt halves.
        let error_at = |dt: f64| {
            let mut s = ContactState::initial(&params, 1000.0, 1.0);
            let steps = (10.0 / dt) as usize;
            for _ in 0..steps {
                s = update(&params, &s, 0.0, dt).unwrap().state;
            }
            (s.r_star() - healed_r_star(&params, 1.0, 10.0)).abs()
        };
        let ratio = error_at(0.2) / error_at(0.1);
        assert!((3.8..4.2).contains(&ratio), "{law_kind:?}: error ratio on halving dt = {ratio}");
    }
}

fn point_history() -> PointSpec {
    PointSpec {
        normal_traction: 1000.0,
        normal: Default::default(),
        phases: vec![
            Phase { velocity: -1e-3, duration: 200.0, normal_velocity: 0.0 },
            Phase { velocity: 1e-3, duration: 0.2, normal_velocity: 0.0 },
            Phase { velocity: 0.0, duration: 100.0, normal_velocity: 0.0 },
            Phase { velocity: -1e-3, duration: 99.8, normal_velocity: 0.0 },
        ],
    }
}

fn run_point(params: &FrictionParams, spec: &PointSpec, dt: f64, t_end: f64) -> ContactState {
    let mut scene = PointScene::new(params.clone(), spec.clone());
    let steps = (t_end / dt).round() as u64;
    for k in 1..=steps {
        let target = k as f64 * dt;
        scene.advance(target - scene.time()).unwrap();
    }
    let _ = scene.frame(Needs::default(), dt);
    *scene.state()
}

#[test]
fn point_scene_update_converges_with_order_two() {
    let params = paper();
    let spec = point_history();
    let t_end = 400.0;
    let states: Vec<ContactState> =
        [0.4, 0.2, 0.1, 0.05].iter().map(|&dt| run_point(&params, &spec, dt, t_end)).collect();
    for (name, value) in [
        ("traction", states.iter().map(|s| s.traction_t).collect::<Vec<_>>()),
        ("structure", states.iter().map(|s| s.structure).collect::<Vec<_>>()),
        ("plastic slip", states.iter().map(|s| s.plastic_slip).collect::<Vec<_>>()),
    ] {
        let order = ((value[1] - value[2]) / (value[2] - value[3])).abs().log2();
        assert!((1.8..2.3).contains(&order), "{name}: observed order {order} from {value:?}");
    }
}

#[test]
fn update_tangent_matches_finite_differences_and_tends_to_the_rate_form() {
    let params = paper();
    let mut state = ContactState::initial(&params, 1000.0, 1.0);
    for step in 0..40_000 {
        let dt = 0.01;
        let du = -1e-3 * dt;
        let updated = update(&params, &state, du, dt).unwrap();
        if step % 4000 == 1999 {
            let h = 1e-7 * du.abs();
            let plus = update(&params, &state, du + h, dt).unwrap().state.traction_t;
            let minus = update(&params, &state, du - h, dt).unwrap().state.traction_t;
            let fd = (plus - minus) / (2.0 * h);
            assert!(
                (updated.tangent - fd).abs() <= 1e-5 * params.alpha_t,
                "step {step}: tangent {} vs finite difference {fd}",
                updated.tangent
            );
            // As dt → 0 the update's tangent is the tt entry of C^ep (eq. 7) and Δp/dt is Λ (eq. 5).
            let small = 1e-6;
            let tiny = update(&params, &state, -1e-3 * small, small).unwrap();
            let cep = law::elastoplastic_tensor(&params, &state)[(0, 0)];
            let lambda = law::plastic_multiplier(&params, &state, Vector2::new(-1e-3, 0.0));
            assert!(
                (tiny.tangent - cep).abs() <= 1e-3 * params.alpha_t,
                "step {step}: {} vs C^ep_tt {cep}",
                tiny.tangent
            );
            let rate = tiny.plastic_increment / small;
            assert!((rate - lambda).abs() <= 1e-4 * lambda.abs() + 1e-12, "step {step}: Δp/dt {rate} vs Λ {lambda}");
        }
        state = updated.state;
    }
}

#[test]
fn traction_reversal_passes_through_zero_without_leaving_the_admissible_range() {
    let params = paper();
    let mut state = ContactState::initial(&params, 1000.0, 1.0);
    for _ in 0..20_000 {
        state = update(&params, &state, -1e-5, 0.01).unwrap().state;
    }
    // Drive backwards through f_t = 0 and into sliding the other way, with steps that land
    // exactly on zero and steps that jump across it.
    let mut crossed = false;
    for step in 0..40_000 {
        let du = if step % 7 == 0 { 3e-5 } else { 1e-5 };
        let before = state.traction_t;
        let updated = update(&params, &state, du, 0.01).unwrap();
        state = updated.state;
        crossed |= before > 0.0 && state.traction_t <= 0.0;
        let ratio = state.sliding_ratio(&params);
        assert!(state.traction_t.is_finite() && (0.0..=1.0 + 1e-12).contains(&ratio), "step {step}: R = {ratio}");
        assert!((1.0..=2.0).contains(&state.structure), "step {step}: 1/R* = {}", state.structure);
    }
    assert!(crossed, "the traction changed sign");
    assert!(state.traction_t < -300.0, "sliding the other way: {}", state.traction_t);
}

#[test]
fn reversing_the_drive_mirrors_the_point_scene_exactly() {
    let params = paper();
    let forward = point_history();
    let mut backward = forward.clone();
    for phase in &mut backward.phases {
        phase.velocity = -phase.velocity;
    }
    let a = run_point(&params, &forward, 0.1, 400.0);
    let b = run_point(&params, &backward, 0.1, 400.0);
    assert_eq!(a.traction_t, -b.traction_t);
    assert_eq!(a.structure, b.structure);
    assert_eq!(a.plastic_slip, b.plastic_slip);
}

#[test]
fn rate_form_partials_match_finite_differences() {
    // The partial derivatives the implicit Runge–Kutta stages linearize with: ∂ḟ_t/∂(f_t, 1/R*,
    // v̄_t) and ∂Λ/∂(f_t, 1/R*, v̄_t) of `tangential_rate`, and ∂/∂(1/R*) of eq. (4)'s rate,
    // against central differences of the rates themselves, at loading states from well inside
    // the subloading surface to near it, in both directions, with both r* laws.
    for rstar_law in [RStarLaw::Consistent, RStarLaw::Eq4] {
        let params = FrictionParams { rstar_law, ..paper() };
        for (ratio, structure, v) in [(0.3, 1.2, -2e-3), (0.9, 1.9, -1e-3), (0.99, 1.5, -5e-4)] {
            for direction in [1.0, -1.0] {
                let f_n = 800.0;
                let state = ContactState {
                    traction_t: direction * ratio * params.mu_k * f_n * structure,
                    traction_n: f_n,
                    structure,
                    plastic_slip: 0.0,
                };
                let v = direction * v;
                let at = |f: f64, z: f64, v: f64| {
                    law::tangential_rate(&params, &ContactState { traction_t: f, structure: z, ..state }, v, 0.0)
                };
                let r = at(state.traction_t, structure, v);
                assert!(r.plastic_multiplier > 0.0, "a loading state: {r:?}");
                let lambda = r.plastic_multiplier_partials(&params, &state);
                let (hf, hz, hv) = (1e-6 * state.traction_t.abs(), 1e-7, 1e-7 * v.abs());
                let f = state.traction_t;
                let numeric = [
                    (at(f + hf, structure, v), at(f - hf, structure, v), hf),
                    (at(f, structure + hz, v), at(f, structure - hz, v), hz),
                    (at(f, structure, v + hv), at(f, structure, v - hv), hv),
                ];
                let analytic_rate = [r.d_traction, r.d_structure, r.d_velocity];
                for (k, (plus, minus, h)) in numeric.iter().enumerate() {
                    let d_rate = (plus.rate - minus.rate) / (2.0 * h);
                    let d_lambda = (plus.plastic_multiplier - minus.plastic_multiplier) / (2.0 * h);
                    let close = |a: f64, b: f64| (a - b).abs() <= 1e-5 * a.abs().max(b.abs()) + 1e-9;
                    assert!(close(analytic_rate[k], d_rate), "ḟ_t partial {k}: {} vs {d_rate}", analytic_rate[k]);
                    assert!(close(lambda[k], d_lambda), "Λ partial {k}: {} vs {d_lambda}", lambda[k]);
                }
                let lam = r.plastic_multiplier;
                let slope = law::structure_rate_slope(&params, structure, lam);
                let numeric = (law::structure_rate(&params, structure + hz, lam)
                    - law::structure_rate(&params, structure - hz, lam))
                    / (2.0 * hz);
                assert!((slope - numeric).abs() <= 1e-6 * slope.abs().max(1e-6), "eq. (4) slope {slope} vs {numeric}");
            }
        }
    }
}
