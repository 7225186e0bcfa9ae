//! The plane-strain block: closed forms and hand derivations.

use slipfront::case::SceneSpec;
use slipfront::case::{self, Case};
use slipfront::frame::Needs;
use slipfront::scene::Scene;
use slipfront::scene::block::BlockScene;

fn paper_case(overrides: &[&str]) -> Case {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/cases/paper_triangular.toml")).unwrap();
    // Wilson's method: the tests below are of its Newton iteration and linear solvers.
    let wilson = std::iter::once("time.integrator=wilson");
    let owned: Vec<String> = wilson.chain(overrides.iter().copied()).map(|s| s.to_string()).collect();
    case::from_str(&text, &owned).unwrap()
}

fn block_scene(case: &Case) -> BlockScene {
    let SceneSpec::Block(spec) = &case.scene else { panic!("a block case") };
    BlockScene::new(case, spec).unwrap()
}

/// Stuck limit (MODEL.md): the block is a shear column of stiffness G/H per unit area in
/// series with the contact spring α_t, so once transients decay the total friction force is
/// `W u_base / (H/G + 1/α_t)`. One element high (as the paper's mesh), a Q4 strip with ν = 0 is
/// exactly such a column. (Several elements high, the mesh resolves the traction-free ends,
/// where the shear stress vanishes: a 20 × 4 mesh carries 5 % less, which is physics the
/// closed form leaves out.)
#[test]
fn stuck_contact_carries_the_shear_column_force() {
    for (nx, ny, dt) in [(10, 1, 0.01_f64), (40, 1, 0.01)] {
        let case = paper_case(&[
            "friction.mu_s=400",
            "friction.mu_k=200",
            "scene.normal_traction={kind=\"uniform\", value=1000}",
            &format!("scene.nx={nx}"),
            &format!("scene.ny={ny}"),
            "time.t_end=50",
            &format!("time.dt={dt}"),
        ]);
        let mut scene = block_scene(&case);
        let (w, h, g, alpha) = (10.0, 1.0, 500.0, 1.0e6);
        let mut worst: f64 = 0.0;
        let steps = (50.0 / dt).round() as usize;
        for k in 1..=steps {
            scene.advance(k as f64 * dt - scene.time()).unwrap();
            if scene.time() >= 40.0 && k % 100 == 0 {
                let frame = scene.frame(Needs::default(), dt);
                let expected = w * frame.base_displacement / (h / g + 1.0 / alpha);
                worst = worst.max((frame.friction_force - expected).abs() / expected);
                // Nothing slips.
                assert!(frame.segments.iter().all(|s| s.slip_rate < 1e-6));
            }
        }
        println!("{nx}x{ny}: worst relative difference over t in [40, 50] s: {worst:e}");
        assert!(worst < 5e-3, "{nx}x{ny}: stuck force differs from the closed form by {worst:e}");
    }
}

/// Period of the bottom-left node's horizontal oscillation, from up-crossings of its mean.
fn measured_period(case: &Case, initial_velocity: f64, dt: f64, periods: f64, expected: f64) -> f64 {
    let mut scene = block_scene(case);
    let surface_nodes = scene.layout().surface_nodes.len();
    {
        let d = scene.system_mut();
        // The block's bottom nodes are its first, node i owning unknowns 2i (x) and 2i + 1 (y).
        for i in 0..surface_nodes {
            d.state.velocity[2 * i] = initial_velocity;
        }
        // The energy balance starts from this initial condition.
        d.track_energy();
    }
    let steps = (periods * expected / dt).round() as usize;
    let mut samples = Vec::with_capacity(steps);
    let needs = Needs { surface_nodes: true, ..Needs::default() };
    for k in 1..=steps {
        scene.advance(k as f64 * dt - scene.time()).unwrap();
        samples.push((scene.time(), scene.frame(needs, dt).surface_nodes[0][0]));
    }
    let mean = samples.iter().map(|s| s.1).sum::<f64>() / samples.len() as f64;
    let crossings: Vec<f64> = samples
        .windows(2)
        .filter(|w| w[0].1 < mean && w[1].1 >= mean)
        .map(|w| w[0].0 + (mean - w[0].1) / (w[1].1 - w[0].1) * (w[1].0 - w[0].0))
        .collect();
    assert!(crossings.len() >= 4, "too few oscillations: {}", crossings.len());
    (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64
}

/// Free vibration of the one-element-high mesh, derived by hand. With `ν = 0` a uniform
/// horizontal motion `U` of the bottom row under a fixed top is an exact uniform shear of each
/// Q4 element, whose nodal forces are `τ dx/2` per element and node (`τ = G U/H`): an interior
/// bottom node feels `G U dx/H` and carries the lumped mass `ρ dx H/2`, an end node half of
/// both. So the mode is uniform and
///
/// * free bottom: `ω² = 2G/(ρH²)`,
/// * stuck bottom (elastic contact, consistent matrix `α_t ∫ÑᵀÑ`, row sum `α_t dx`):
///   `ω² = 2(G/H + α_t)/(ρH)`.
///
/// (The continuum's `V_s/4H` and `V_s/2H` differ: one element cannot represent the sine.)
#[test]
fn free_vibration_periods_match_the_hand_derived_values() {
    let (rho, g, h, alpha): (f64, f64, f64, f64) = (1000.0, 500.0, 1.0, 1.0e6);
    // Free bottom: no normal traction, so no shear is transmitted; the base is at rest.
    let free = paper_case(&["scene.normal_traction={kind=\"uniform\", value=0}", "scene.base_velocity=0"]);
    let expected_free = 2.0 * std::f64::consts::PI / (2.0 * g / (rho * h * h)).sqrt();
    let dt = 1e-3 * expected_free;
    let period = measured_period(&free, 1e-3, dt, 6.0, expected_free);
    println!("free bottom: period {period} s, hand-derived {expected_free} s");
    assert!((period - expected_free).abs() < 1e-3 * expected_free, "free: {period} vs {expected_free}");

    // Stuck bottom: friction so strong that the contact stays elastic.
    let stuck = paper_case(&[
        "friction.mu_s=4000",
        "friction.mu_k=2000",
        "scene.normal_traction={kind=\"uniform\", value=1000}",
        "scene.base_velocity=0",
    ]);
    let expected_stuck = 2.0 * std::f64::consts::PI / (2.0 * (g / h + alpha) / (rho * h)).sqrt();
    let dt = 1e-3 * expected_stuck;
    let period = measured_period(&stuck, 1e-6, dt, 6.0, expected_stuck);
    println!("stuck bottom: period {period} s, hand-derived {expected_stuck} s");
    assert!((period - expected_stuck).abs() < 1e-3 * expected_stuck, "stuck: {period} vs {expected_stuck}");
}

/// The Newton iteration condensed onto the contact (`LinearSolver::Condensed`, the default for
/// large bodies) against the full one, the independent formulation it replaces, on a 40 × 4
/// block driven fast. While the contact only loads (to 10 s) every step's nodal displacements
/// and contact tractions agree to 5e-10 of their size (measured), the order of the Newton
/// tolerance. The first slips (from about 12 s) are an instability that amplifies any
/// difference, as the chaos of the paper case shows; there the condensed run must stay as close
/// to the full one as the full one itself stays to a run with a 100× tighter Newton tolerance
/// (within a factor 10): solver differences no larger than the tolerance's own.
#[test]
fn condensed_newton_follows_the_full_one_through_slip() {
    use slipfront::dynamics::LinearSolver;
    let case = paper_case(&[
        "scene.nx=40",
        "scene.ny=4",
        "scene.base_velocity=0.02",
        "scene.base_ramp_time=1",
        "probes.nodes=[]",
        "probes.segments=[]",
    ]);
    let mut full = block_scene(&case);
    let mut tight = block_scene(&case);
    let mut condensed = block_scene(&case);
    full.system_mut().settings.linear_solver = LinearSolver::Full;
    tight.system_mut().settings.linear_solver = LinearSolver::Full;
    tight.system_mut().settings.tolerance *= 0.01;
    condensed.system_mut().settings.linear_solver = LinearSolver::Condensed;
    let largest = |v: &mut dyn Iterator<Item = f64>| v.fold(1e-300_f64, |m, x| m.max(x.abs()));
    // Worst relative differences (displacement, traction) of `b` from `a`.
    let differences = |a: &BlockScene, b: &BlockScene| {
        let (a, b) = (&a.system().state, &b.system().state);
        let du = largest(&mut a.displacement.iter().zip(&b.displacement).map(|(x, y)| x - y))
            / largest(&mut a.displacement.iter().copied());
        let dt = largest(&mut a.contact.iter().zip(&b.contact).map(|(x, y)| x.traction_t - y.traction_t))
            / largest(&mut a.contact.iter().map(|c| c.traction_t));
        (du, dt)
    };
    let worse = |(a, b): (f64, f64), (c, d): (f64, f64)| (a.max(c), b.max(d));
    let (mut loading, mut slipping, mut tolerance_own) = ((0.0, 0.0), (0.0, 0.0), (0.0, 0.0));
    let mut slipped = false;
    for step in 1..=2000 {
        for scene in [&mut full, &mut tight, &mut condensed] {
            scene.advance(0.01).unwrap();
        }
        let solver = differences(&full, &condensed);
        if step <= 1000 {
            loading = worse(loading, solver);
        } else {
            slipping = worse(slipping, solver);
            tolerance_own = worse(tolerance_own, differences(&full, &tight));
        }
        // A slip event: plastic slip faster than the case's threshold (3 mm/s).
        slipped |= full.system().state.plastic_increment.iter().any(|p| *p > 0.003 * 0.01);
    }
    println!(
        "worst relative differences (displacement, traction): loading {loading:?}; through slip {slipping:?}, \
         where a 100x tighter tolerance moves the full run by {tolerance_own:?}"
    );
    assert!(slipped, "the run must reach slip");
    assert!(loading.0 <= 1e-9 && loading.1 <= 1e-9, "while loading: {loading:?}");
    assert!(
        slipping.0 <= 10.0 * tolerance_own.0 && slipping.1 <= 10.0 * tolerance_own.1,
        "through slip: {slipping:?} against the tolerance's own {tolerance_own:?}"
    );
}
