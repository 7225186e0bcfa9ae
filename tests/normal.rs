//! A contact whose normal traction evolves (`normal = "evolving"`): `ḟ_n = -α_n v̄_n` from its
//! initial value, eq. (5)'s normal term in the friction law, opening where `f_n` would fall to 0.
//!
//! Each test is against something independent: the consistency condition integrated by the
//! test's own Runge–Kutta method, Newton's second law on a rigid block on an incline, the energy
//! balance of a block thrown off its base, Hertz's line contact and Cattaneo–Mindlin's stick zone.
//! `cargo test --release --test normal -- --nocapture` prints every measurement.

mod common;

use nalgebra::Vector2;
use slipfront::case::{self, Case, SceneSpec};
use slipfront::friction::{ContactState, FrictionParams, law};
use slipfront::scene::Scene;
use slipfront::scene::body::BodyScene;
use slipfront::scene::point::PointScene;

// ---------------------------------------------------------------------------------------------
// The rate law against an independent integration.

/// The constants of the point: Table 1 with healing and decay both active, and an initial
/// traction of a tenth of the strength: from Table 1's `f0 = 1e-7 Pa`, `R` starts at 2.5e-10,
/// where `-ln R` moves on a time scale of 1e-10 s that no fixed step of the reference resolves.
fn point_params() -> FrictionParams {
    FrictionParams { xi: 0.5, f0: 40.0, ..FrictionParams::paper() }
}

/// The rates `(ḟ_t, ḟ_n, d(1/R*)/dt, Λ)` of a contact point, derived here from the model's
/// ingredients and not from eq. (5): the elastic law `ḟ = C^e (v̄ + Λ t)` (MODEL.md's signs),
/// `Ṙ = -r ln(R) Λ`, the consistent `R*` rule, and consistency of the subloading surface
/// `|f_t| = R μ_k f_n (1/R*)`. The consistency rate is affine in `Λ`, so `Λ` is its root from
/// two evaluations; loading where it is positive (eq. 9).
fn independent_rates(p: &FrictionParams, [f_t, f_n, z]: [f64; 3], [v_t, v_n]: [f64; 2]) -> [f64; 4] {
    let sigma = f_t.signum();
    let ratio = f_t.abs() / (p.mu_k * f_n * z);
    let a = p.mu_k / p.mu_s;
    let consistency = |lambda: f64| {
        let df_t = -p.alpha_t * (v_t + sigma * lambda);
        let df_n = -p.alpha_n * v_n;
        let dratio = -p.r * ratio.ln() * lambda;
        let dz = -p.kappa * (z - 1.0).powf(p.m) * lambda + p.xi * (1.0 - a * z).max(0.0).powf(p.n);
        sigma * df_t - p.mu_k * (dratio * z * f_n + ratio * dz * f_n + ratio * z * df_n)
    };
    let (c0, c1) = (consistency(0.0), consistency(1.0));
    let lambda = (-c0 / (c1 - c0)).max(0.0);
    let df_t = -p.alpha_t * (v_t + sigma * lambda);
    let dz = -p.kappa * (z - 1.0).powf(p.m) * lambda + p.xi * (1.0 - a * z).max(0.0).powf(p.n);
    [df_t, -p.alpha_n * v_n, dz, lambda]
}

/// `(v̄_t, v̄_n, duration)`: loading to slip under a constant normal traction, then slipping
/// while the contact is pressed (`v̄_n < 0`), unloaded normally (`v̄_n > 0`, the surface shrinks
/// onto the traction), unloaded tangentially, and healing in a hold.
const HISTORY: [(f64, f64, f64); 6] =
    [(-1e-3, 0.0, 3.0), (-1e-3, -2e-4, 2.0), (-1e-3, 3e-4, 2.0), (0.0, 2e-4, 1.0), (2e-5, 0.0, 1.0), (0.0, 0.0, 2.0)];

/// The initial normal traction of the point (Pa).
const F_N0: f64 = 1000.0;

/// The history integrated by the classical Runge–Kutta method of order 4 over `steps` steps
/// per phase: `(f_t, f_n, 1/R*)` at each phase's end.
fn independent_history(p: &FrictionParams, steps: usize) -> Vec<[f64; 3]> {
    let mut y = [p.f0, F_N0, p.structure0];
    let mut ends = Vec::new();
    for (v_t, v_n, duration) in HISTORY {
        let h = duration / steps as f64;
        let f = |y: [f64; 3]| {
            let r = independent_rates(p, y, [v_t, v_n]);
            [r[0], r[1], r[2]]
        };
        let add = |y: [f64; 3], k: [f64; 3], c: f64| [y[0] + c * k[0], y[1] + c * k[1], y[2] + c * k[2]];
        for _ in 0..steps {
            let k1 = f(y);
            let k2 = f(add(y, k1, 0.5 * h));
            let k3 = f(add(y, k2, 0.5 * h));
            let k4 = f(add(y, k3, h));
            for i in 0..3 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        ends.push(y);
    }
    ends
}

/// The point scene (the implicit friction update) through [`HISTORY`] at steps of `dt`.
fn point_history(p: &FrictionParams, dt: f64) -> Vec<[f64; 3]> {
    let phases = HISTORY
        .iter()
        .map(|(v, n, d)| format!("{{ velocity = {v:e}, normal_velocity = {n:e}, duration = {d:e} }}"))
        .collect::<Vec<_>>()
        .join(", ");
    let t_end: f64 = HISTORY.iter().map(|h| h.2).sum();
    let text = format!(
        "[friction]\nmu_s = {}\nmu_k = {}\nalpha_n = {:e}\nalpha_t = {:e}\nr = {}\nkappa = {}\nm = 1.0\nxi = {}\n\
         n = 1.0\nstructure0 = {}\nf0 = {:e}\n[time]\nt_end = {t_end}\ndt = {dt:e}\n[scene]\nkind = \"point\"\n\
         normal = \"evolving\"\nnormal_traction = {F_N0:e}\nphases = [{phases}]\n",
        p.mu_s, p.mu_k, p.alpha_n, p.alpha_t, p.r, p.kappa, p.xi, p.structure0, p.f0
    );
    let case = case::from_str_at(&text, &[], std::path::Path::new(".")).unwrap_or_else(|e| panic!("{e}"));
    let SceneSpec::Point(spec) = case.scene.clone() else { panic!("a point") };
    let mut scene = PointScene::new(case.friction.clone(), spec);
    let mut ends = Vec::new();
    let mut end = 0.0;
    for (_, _, duration) in HISTORY {
        end += duration;
        while scene.time() < end - 1e-9 {
            scene.advance(dt.min(end - scene.time())).unwrap();
        }
        let s = scene.state();
        ends.push([s.traction_t, s.traction_n, s.structure]);
    }
    ends
}

/// Largest difference of two histories, tractions against the static strength `μ_s f_n⁰` and
/// `1/R*` against its range.
fn history_difference(p: &FrictionParams, a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    let strength = p.mu_s * F_N0;
    let range = p.max_structure() - 1.0;
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            ((x[0] - y[0]).abs() / strength).max((x[1] - y[1]).abs() / strength).max((x[2] - y[2]).abs() / range)
        })
        .fold(0.0, f64::max)
}

/// The rate law of `src/friction/law.rs` with its normal terms equals the rates derived here
/// from the consistency condition, to 1e-12 of their scale, over random states and sliding
/// velocities of both signs, normal ones included (eq. 5's `α_n (R/R*) μ_k n·v̄`); its 2 × 2
/// `C^ep v̄ + C^c t` of eqs. (7)–(8) gives the same `ḟ_t` and `ḟ_n = -α_n v̄_n`.
#[test]
fn the_rate_law_with_normal_terms_is_the_consistency_condition() {
    let p = point_params();
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut uniform = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut worst, mut loading) = (0.0_f64, 0);
    for _ in 0..4000 {
        let f_n = 100.0 + 2000.0 * uniform();
        let z = 1.0 + (p.max_structure() - 1.0) * uniform();
        let ratio = 1e-6 + (1.0 - 2e-6) * uniform();
        let f_t = ratio * p.mu_k * f_n * z * if uniform() < 0.5 { -1.0 } else { 1.0 };
        let v = [2e-3 * (uniform() - 0.5), 2e-3 * (uniform() - 0.5)];
        let [df_t, df_n, dz, lambda] = independent_rates(&p, [f_t, f_n, z], v);
        let state = ContactState { traction_t: f_t, traction_n: f_n, structure: z, plastic_slip: 0.0 };
        let r = law::tangential_rate(&p, &state, v[0], v[1]);
        let (full, full_lambda) = law::traction_rate(&p, &state, Vector2::new(v[0], v[1]));
        let scale = p.alpha_t * 1e-3;
        let errors = [
            (r.rate - df_t).abs() / scale,
            (r.plastic_multiplier - lambda).abs() / 1e-3,
            (law::structure_rate(&p, z, r.plastic_multiplier) - dz).abs() / (p.max_structure() - 1.0),
            (full.x - df_t).abs() / scale,
            (full.y - df_n).abs() / scale,
            (full_lambda - lambda).abs() / 1e-3,
        ];
        worst = errors.iter().fold(worst, |w, e| w.max(*e));
        loading += usize::from(lambda > 0.0);
    }
    println!("rate law: 4000 states ({loading} loading), largest difference {worst:.1e} of the rates' scale");
    assert!(loading > 1000 && loading < 3000, "{loading} loading states: both branches must be exercised");
    assert!(worst < 1e-12, "the rate law differs from the consistency condition by {worst:e}");
}

/// The point scene's implicit update with an evolving normal traction, through loading, slip
/// under normal loading and unloading, tangential unloading and a hold, against the test's own
/// Runge–Kutta integration of [`independent_rates`] (its error estimated by halving its step:
/// 7e-12). At steps of 1e-4 s and below the update lies within 1e-8 of the strength (measured
/// 1e-11 to 2e-11, the reference's own error: the `R` rule is integrated exactly, `f_n` is exact,
/// and the trapezoidal rule on `1/R*` errs by 1e-13 here).
#[test]
fn the_evolving_point_follows_the_independent_integration() {
    let p = point_params();
    let reference = independent_history(&p, 40_000);
    let check = independent_history(&p, 20_000);
    let own_error = history_difference(&p, &reference, &check);
    let mut errors = Vec::new();
    for dt in [1e-4, 5e-5, 2.5e-5] {
        errors.push(history_difference(&p, &point_history(&p, dt), &reference));
    }
    println!(
        "evolving point: reference's own error {own_error:.1e}; the update at dt = 1e-4, 5e-5, 2.5e-5 s: {:.2e}, \
         {:.2e}, {:.2e} (ratios {:.2}, {:.2}); final f_n {:.3} Pa, f_t {:.4} Pa, 1/R* {:.6}",
        errors[0],
        errors[1],
        errors[2],
        errors[0] / errors[1],
        errors[1] / errors[2],
        reference.last().unwrap()[1],
        reference.last().unwrap()[0],
        reference.last().unwrap()[2],
    );
    assert!(own_error < 1e-10, "the reference's own error is {own_error:e}");
    assert!(errors.iter().all(|e| *e < 1e-8), "the update is {errors:?} from the reference");
}

// ---------------------------------------------------------------------------------------------
// The paper's block with its normal traction evolving.

/// What the normal traction of the paper's block did in a run: its largest relative change
/// while loading (before `before` s) at the points of the middle six segments and at those of
/// the two at each end, over the whole run (with when and where), the left end's change at
/// `before`, the statics of the change at `before`, and the run's first onset and number of
/// events.
struct PaperRun {
    middle: f64,
    ends: f64,
    left_end: f64,
    largest: (f64, f64, usize),
    statics: Statics,
    onset: f64,
    events: usize,
}

/// The change of the contact's normal force and its moment about `x = 0`, `Σ w Δf_n` (N/m)
/// and `Σ w x Δf_n` (N), against the unchanged total `Σ w f_n⁰` and the friction force
/// `F = Σ w f_t` (N/m).
#[derive(Default)]
struct Statics {
    force: f64,
    initial: f64,
    moment: f64,
    friction: f64,
}

fn statics(system: &slipfront::dynamics::System, initial: &[f64], xs: &[f64]) -> Statics {
    let rows = system.contact.points.iter().zip(&system.state.contact).zip(initial).zip(xs);
    rows.fold(Statics::default(), |s, (((p, c), f0), x)| Statics {
        force: s.force + p.weight * (c.traction_n - f0),
        initial: s.initial + p.weight * f0,
        moment: s.moment + p.weight * x * (c.traction_n - f0),
        friction: s.friction + p.weight * c.traction_t,
    })
}

fn paper_run(overrides: &[&str], before: f64) -> PaperRun {
    let case = common::load("paper_triangular", overrides);
    let SceneSpec::Block(spec) = &case.scene else { panic!("a block") };
    let mut scene = slipfront::scene::block::BlockScene::new(&case, spec).unwrap();
    let initial: Vec<f64> = scene.system().contact.traction_n.clone();
    // Two Gauss points on each 1 m segment, at 1/2 ∓ 1/(2√3) of it.
    let gauss = 0.5 / 3.0_f64.sqrt();
    let xs: Vec<f64> =
        (0..initial.len()).map(|k| (k / 2) as f64 + 0.5 + if k % 2 == 0 { -gauss } else { gauss }).collect();
    let (mut middle, mut ends, mut largest) = (0.0_f64, 0.0_f64, (0.0_f64, 0.0, 0));
    let (mut left_end, mut at_before) = (0.0, Statics::default());
    let points = initial.len();
    while scene.time() < case.time.t_end - 1e-9 {
        let left = case.time.t_end - scene.time();
        let to_before = before - scene.time();
        let dt = if to_before > 1e-9 { case.time.dt.min(left).min(to_before) } else { case.time.dt.min(left) };
        scene.advance(dt).unwrap();
        let (t, state) = (scene.time(), &scene.system().state.contact);
        for (k, (c, f0)) in state.iter().zip(&initial).enumerate() {
            let change = (c.traction_n - f0) / f0;
            if change.abs() > largest.0 {
                largest = (change.abs(), t, k);
            }
            if t <= before + 1e-9 {
                if k < 4 || k + 4 >= points {
                    ends = ends.max(change.abs());
                } else {
                    middle = middle.max(change.abs());
                }
            }
        }
        if (t - before).abs() < 1e-9 {
            left_end = (state[0].traction_n - initial[0]) / initial[0];
            at_before = statics(scene.system(), &initial, &xs);
        }
    }
    let onsets = common::onsets(&case);
    let (onset, events) = (onsets.first().map_or(f64::NAN, |o| o.1), onsets.len());
    PaperRun { middle, ends, left_end, largest, statics: at_before, onset, events }
}

/// The paper's block under an evolving normal traction, `f_n = f_n⁰ - α_n u_n`: its normal
/// traction changes only as the block's underside moves vertically. Nothing loads the block
/// vertically, but the friction force `F` that the base exerts along its underside and the
/// right edge's reaction, which holds the block against it along its height, form a couple:
/// the contact must carry its moment, `Σ w x Δf_n = -F y_R` with `y_R` the height of the
/// reaction, while its total normal force stays `Σ w f_n⁰`. So the left end is pressed harder
/// and the right end eased, by tractions that grow with the load, concentrated at the ends
/// (the contact, `α_n` = 1e6 Pa/m, is a thousand times stiffer than the block, `E/H` = 1e3
/// Pa/m, which so cannot tilt as a whole) and alternating from one Gauss point to the next
/// there; in the middle they are small. The first slip, which starts at the left end, starts later where that end
/// is pressed harder.
///
/// Measured with the default integrator (Tsit5), 2026-11-26 (`cargo test --release --test
/// normal paper_case -- --nocapture`): until 420 s `f_n` within 4.5 % of its initial value
/// on the middle six segments, 64 % at the ends (+64 % at the left end's first point: the run's
/// largest, at 417.6 s, before the first slip); at 420 s the normal force changed by −4e-11 of
/// 7750 N/m and its moment is `F` = 2000 N/m times 0.4995 m, the right edge's mid-height; first
/// onset 3.75 s later than held (423.95 s against 420.20 s). Asserted: statics to 1e-9 of the
/// total and 1 % of the lever arm, the middle within 10 %, the contact never opening (a change
/// below 100 %), the left end pressed harder and the onset later, by less than 10 s.
#[test]
fn the_paper_case_with_an_evolving_normal_traction() {
    let held = paper_run(&[], 420.0);
    let run = paper_run(&["scene.normal=\"evolving\""], 420.0);
    let Statics { force, initial, moment, friction } = run.statics;
    let lever = -moment / friction;
    println!(
        "paper case, evolving normal: until 420 s f_n within {:.3} % of its initial value on the middle six \
         segments, within {:.2} % at the two at each end (the left end's first point {:+.3} % at 420 s); within \
         {:.1} % over 1000 s (the largest at point {}, t = {:.2} s); at 420 s the normal force changed by \
         {force:.2e} N/m of {initial:.0} N/m, its moment {moment:.2} N = -F × {lever:.4} m with F = {friction:.1} \
         N/m; first onset {:.4} s against {:.4} s held ({:+.3} s); {} slip events against {}",
        100.0 * run.middle,
        100.0 * run.ends,
        100.0 * run.left_end,
        100.0 * run.largest.0,
        run.largest.2,
        run.largest.1,
        run.onset,
        held.onset,
        run.onset - held.onset,
        run.events,
        held.events
    );
    assert_eq!(held.largest.0, 0.0, "a held normal traction moved");
    assert!(force.abs() < 1e-9 * initial, "the contact's normal force changed by {force} N/m");
    assert!((lever - 0.5).abs() < 0.005, "the couple's lever arm is {lever} m, not the right edge's mid-height");
    assert!(run.middle > 0.0 && run.middle < 0.1, "f_n moved by {} in the middle while loading", run.middle);
    assert!(run.ends < 1.0, "f_n moved by {} at the ends while loading: the contact opened", run.ends);
    assert!(run.left_end > 0.0, "the left end is not pressed harder: {}", run.left_end);
    assert!(
        run.onset > held.onset && run.onset - held.onset < 10.0,
        "first onset {} s against {} s",
        run.onset,
        held.onset
    );
}

// ---------------------------------------------------------------------------------------------
// Bodies on a base: an incline, a block thrown off and landing, a cylinder (Hertz).

/// A case of `tests/meshes/` from its text.
fn mesh_case(text: &str, overrides: &[&str]) -> Case {
    let owned: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let dir = format!("{}/tests/meshes", env!("CARGO_MANIFEST_DIR"));
    case::from_str_at(text, &owned, std::path::Path::new(&dir)).unwrap_or_else(|e| panic!("{e}"))
}

/// The mean of a nodal `field` (a displacement or velocity of the free unknowns) over the
/// nodes of `case`'s mesh, in x and y.
fn node_mean(case: &Case, field: &[f64]) -> [f64; 2] {
    let SceneSpec::Mesh(spec) = &case.scene else { panic!("a mesh case") };
    let loaded = spec.loaded();
    let assembled = slipfront::fem::assemble(&spec.definition(loaded)).unwrap();
    let nodes = loaded.mesh.nodes.len();
    let sum = (0..nodes)
        .map(|n| assembled.dofs.displacement(n, field, 0.0))
        .fold([0.0, 0.0], |s, u| [s[0] + u[0], s[1] + u[1]]);
    [sum[0] / nodes as f64, sum[1] / nodes as f64]
}

/// A stiff block (2 m × 0.5 m, `E = 1 GPa`, contact moduli 1e8 Pa/m) under its own weight on a
/// base inclined at `tan θ = 0.4`, between the kinetic coefficient 0.2 and the static one
/// `μ_k (1/R*₀) = 0.6`; its normal traction evolves from zero, so its weight alone presses it.
const INCLINE: &str = r#"
[friction]
mu_s = 0.6
mu_k = 0.2
alpha_n = 1.0e8
alpha_t = 1.0e8
r = 1.0e4
kappa = 100.0
m = 1.0
xi = 0.0
n = 1.0
structure0 = 3.0
f0 = 1.0e-7

[time]
t_end = 2.0
dt = 0.001

[events]
slip_rate_threshold = 1.0e-3

[scene]
kind = "mesh"
file = "block_on_base.msh"
gravity = [3.643343, -9.108356]   # 9.81 m/s² at tan θ = 0.4 to the base (x down the slope)

[[scene.materials]]
group = "block"
youngs_modulus = 1.0e9
poisson_ratio = 0.25
density = 2000.0

[[scene.contacts]]
group = "base"
normal = "evolving"
normal_traction = { kind = "uniform", value = 0.0 }
base_phases = [{ velocity = 0.0, duration = 0.5 }, { velocity = -1.0 }]
base_ramp_time = 0.02
"#;

/// On the incline the block starts at rest in equilibrium, its contact pressed by its weight
/// alone (the normal traction it starts from is the weight's share, `ρ g cos θ H`), and holds
/// for 0.5 s (at most 1e-6 m/s, a millionth of the speeds it slides at): `tan θ = 0.4` is below the static coefficient `μ_k (1/R*₀) = 0.6` (its largest
/// point, where the weight's moment presses least, carries 0.55). Then the base is jerked up
/// the slope (1 m/s in 0.02 s), the contact slips, its structure decays to `1/R* = 1`, and the
/// block slides down at `g (sin θ - μ_k cos θ) = 1.822 m/s²` (measured over
/// its last second, as a least-squares slope of its mean velocity), with every integrator.
/// A slope steeper than `μ_k (1/R*₀)` cannot start at rest: the case is refused.
#[test]
fn a_stiff_block_holds_on_an_incline_and_slides_at_kinetic_friction() {
    let (g, tan) = (9.81, 0.4_f64);
    let (sin, cos) = (tan / (1.0 + tan * tan).sqrt(), 1.0 / (1.0 + tan * tan).sqrt());
    let expected = g * (sin - 0.2 * cos);
    for integrator in ["auto", "wilson", "sdirk4", "central"] {
        let case = mesh_case(INCLINE, &[&format!("time.integrator=\"{integrator}\"")]);
        let SceneSpec::Mesh(spec) = &case.scene else { panic!("a mesh case") };
        let mut scene = slipfront::scene::mesh::scene(&case, spec).unwrap();
        let weight_share = 2000.0 * g * cos * 0.5;
        let pressed = scene.system().state.contact.iter().map(|c| c.traction_n).sum::<f64>()
            / scene.system().state.contact.len() as f64;
        let (mut held, mut samples) = (0.0_f64, Vec::new());
        let (mut friction, mut normal, mut open, mut count) = (0.0, 0.0, 0, 0);
        let mut structure: f64 = 3.0;
        while scene.time() < case.time.t_end - 1e-9 {
            let left = case.time.t_end - scene.time();
            scene.advance(case.time.dt.min(left)).unwrap();
            let system = scene.system();
            let v = system.state.velocity.iter().zip(&system.body.mass).step_by(2).map(|(v, m)| v * m).sum::<f64>()
                / system.body.mass.iter().step_by(2).sum::<f64>();
            if scene.time() >= 1.0 {
                let total = |f: &dyn Fn(&ContactState) -> f64| {
                    system.contact.points.iter().zip(&system.state.contact).map(|(p, c)| p.weight * f(c)).sum::<f64>()
                };
                friction += total(&|c| c.traction_t);
                normal += total(&|c| c.traction_n);
                open += system.state.contact.iter().filter(|c| c.traction_n <= 0.0).count();
                count += 1;
            }
            assert!(v.is_finite(), "{integrator}: the block's velocity is {v}");
            if scene.time() <= 0.5 + 1e-9 {
                held = held.max(v.abs());
            } else if scene.time() >= 1.0 {
                samples.push((scene.time(), v));
                structure = system.state.contact.iter().fold(1.0, |m, c| m.max(c.structure));
            }
        }
        let n = samples.len() as f64;
        let (mt, mv) = samples.iter().fold((0.0, 0.0), |s, (t, v)| (s.0 + t / n, s.1 + v / n));
        let slope = samples.iter().map(|(t, v)| (t - mt) * (v - mv)).sum::<f64>()
            / samples.iter().map(|(t, _)| (t - mt) * (t - mt)).sum::<f64>();
        // Newton's second law on the block with the friction force it felt: M a = M g_x + F.
        let mass: f64 = 2000.0 * 2.0 * 0.5;
        let from_friction = g * sin + friction / count as f64 / mass;
        let ratio = -friction / normal;
        let open_share = open as f64 / (count * scene.system().state.contact.len()) as f64;
        println!(
            "incline, {integrator}: over its last second the friction force is {ratio:.5} of the normal force \
             (μ_k = 0.2), contact points open {:.2} % of the time; M a = M g sin θ + F gives {from_friction:.5} m/s²",
            100.0 * open_share
        );
        println!(
            "incline, {integrator}: pressed by {pressed:.2} Pa (weight's share {weight_share:.2} Pa); held for 0.5 s \
             (speed at most {held:.1e} m/s); slides at {slope:.5} m/s² against g (sin θ - μ_k cos θ) = {expected:.5} \
             ({:+.2e} relative), 1/R* at most {structure:.6} from 1 s",
            (slope - expected) / expected
        );
        assert!((pressed - weight_share).abs() < 1e-6 * weight_share, "{integrator}: pressed by {pressed} Pa");
        assert!(held < 1e-6, "{integrator}: the block moved at {held} m/s while it should hold");
        assert!((slope - from_friction).abs() < 0.01 * expected, "{integrator}: {slope} m/s² against {from_friction}");
        assert!((slope - expected).abs() < 0.05 * expected, "{integrator}: slides at {slope} m/s²");
    }
    // Steeper than the static coefficient: tan θ = 0.61.
    let owned = ["scene.gravity=[5.16, -8.46]".to_string()];
    let dir = format!("{}/tests/meshes", env!("CARGO_MANIFEST_DIR"));
    let refused = case::from_str_at(INCLINE, &owned, std::path::Path::new(&dir)).expect_err("refused").to_string();
    println!("incline at tan θ = 0.61: {refused}");
    assert!(refused.contains("scene.gravity") && refused.contains("static strength"), "{refused}");
}

/// A block (2 m × 0.5 m, `tests/meshes/thrown_block.toml`) resting under its own weight on an
/// evolving contact is thrown off its base by a traction on its top of twice its weight for 0.05 s, flies, lands and bounces, with
/// every integrator. While the contact is open everywhere both its tractions are zero; nothing
/// is NaN; it lands again (some point pressed after the flight). In the flight, with the
/// traction gone and the contact open, only gravity acts: Newton's second law says the block's
/// vertical momentum `Σ m v_y` falls at exactly `M g`, whatever its vibration (`K` has no net
/// force on a rigid translation), and every integrator here keeps that linear invariant to
/// rounding. With Wilson's method the energy ledger balances: the work of the traction and
/// gravity's settled share equal kinetic, strain and contact energy, friction's dissipation and
/// the integrator's own, which stays within `time.energy_tolerance` (1 %) of the work put in.
///
/// Measured (2026-11-26, `cargo test --release --test normal thrown -- --nocapture`): each
/// integrator lifts it by 26.3 mm and lands it three times in 0.6 s; over its first flight
/// (0.07 to 0.18 s, 1099 to 1662 steps) the momentum falls at `M g` within 5.2e-14 relative and
/// lies on a line within 4e-14 of `M g t`; Wilson's ledger closes within 1.8e-3 of the work.
#[test]
fn a_block_thrown_off_its_base_lands_again() {
    for integrator in ["wilson", "tsit5", "sdirk4", "central"] {
        thrown_block(integrator);
    }
}

fn thrown_block(integrator: &str) {
    let case = mesh_case(include_str!("meshes/thrown_block.toml"), &[&format!("time.integrator=\"{integrator}\"")]);
    let SceneSpec::Mesh(spec) = &case.scene else { panic!("a mesh case") };
    let loaded = spec.loaded();
    let assembled = slipfront::fem::assemble(&spec.definition(loaded)).unwrap();
    let nodes = loaded.mesh.nodes.len();
    let mut scene = slipfront::scene::mesh::scene(&case, spec).unwrap();
    let vertical = |field: &[f64]| (0..nodes).map(|n| assembled.dofs.displacement(n, field, 0.0)[1]).sum::<f64>();
    let mass = vertical(&scene.system().body.mass);
    let (mut open_steps, mut landings, mut was_open) = (0, 0, false);
    let mut height: f64 = 0.0;
    let mut flight: Vec<(f64, f64)> = Vec::new();
    while scene.time() < case.time.t_end - 1e-9 {
        let left = case.time.t_end - scene.time();
        scene.advance(case.time.dt.min(left)).unwrap();
        let system = scene.system();
        let s = &system.state;
        assert!(
            s.displacement.iter().chain(&s.velocity).all(|x| x.is_finite())
                && s.contact.iter().all(|c| c.traction_t.is_finite() && c.traction_n.is_finite()),
            "{integrator}: not finite at t = {} s",
            s.time
        );
        let open = s.contact.iter().all(|c| c.traction_n <= 0.0);
        if open {
            open_steps += 1;
            assert!(
                s.contact.iter().all(|c| c.traction_t == 0.0 && c.traction_n == 0.0),
                "{integrator}: an open contact pulls"
            );
            if s.time > 0.07 && landings == 0 {
                let momentum: Vec<f64> = system.body.mass.iter().zip(&s.velocity).map(|(m, v)| m * v).collect();
                flight.push((s.time, vertical(&momentum)));
            }
        } else if was_open {
            landings += 1;
        }
        was_open = open;
        height = height.max(node_mean(&case, &s.displacement)[1]);
    }
    // The momentum's rate over the flight, from its first and last samples (it is linear).
    let (&(t0, p0), &(t1, p1)) = (flight.first().expect("a flight"), flight.last().unwrap());
    let fall = (p1 - p0) / (t1 - t0) / mass;
    let line = flight.iter().map(|(t, p)| (p - p0 - (t - t0) * (p1 - p0) / (t1 - t0)).abs()).fold(0.0, f64::max);
    println!(
        "thrown block, {integrator}: open for {open_steps} steps of at most 1e-4 s, rose {height:.4} m, landed \
         {landings} times in 0.6 s; in the flight ({t0:.3} to {t1:.3} s, {} steps) Σ m v_y falls at {fall:.9} m/s² \
         × M ({:+.1e} relative to g), off a line by {:.1e} of M g t",
        flight.len(),
        (-fall - 9.81) / 9.81,
        line / (mass * 9.81 * (t1 - t0)),
    );
    assert!(open_steps > 100, "{integrator}: the block did not lift off ({open_steps} open steps)");
    assert!(landings >= 1, "{integrator}: the block did not land again");
    assert!(flight.len() > 100, "{integrator}: a flight of {} steps", flight.len());
    assert!((-fall - 9.81).abs() < 1e-9 * 9.81, "{integrator}: the flying block falls at {fall} m/s²");
    assert!(line < 1e-9 * mass * 9.81 * (t1 - t0), "{integrator}: the momentum is {line} off a line");
    if let Some(ledger) = scene.system().energy() {
        let work = ledger.work_base + ledger.work_load + ledger.initial;
        let share = ledger.numerical() / work;
        println!(
            "thrown block, {integrator}: work {work:.2} J/m, kinetic {:.3}, strain {:.3}, contact {:.3}, dissipated \
             {:.3}, the integrator's own {:.3e} ({share:+.2e} of the work)",
            ledger.kinetic,
            ledger.strain,
            ledger.contact_elastic,
            ledger.dissipation,
            ledger.numerical()
        );
        assert!(share.abs() < 0.01, "{integrator}: the energy balance is off by {share} of the work");
    } else {
        assert_ne!(integrator, "wilson", "Wilson keeps a ledger");
    }
}

/// The lower half of a cylinder (radius 1 m, `E = 10 MPa`, `ν = 0.3`) on a rigid flat base
/// through its evolving contact along the lower arc, its flat top moved: down by about 2 cm,
/// held, then sideways by 7 mm. The gap of each contact point is its height above the base (the
/// profile `y`); the contact is stiff (`α_n = α_t = 1e11 Pa/m`, a penetration of 7 µm under
/// the peak pressure) and without structure (`1/R*₀ = 1`, `ξ = 0`: the static coefficient is
/// `μ_k = 0.3`), its transition sharp (`r = 1e6 /m`). The push stops at 0.6 s, where the
/// tangential force is about half of `μ P`: a push of 2 cm slid the whole contact after the
/// first 1.2 cm (the contact's tangential stiffness is about 3e6 N/m per m).
const CYLINDER: &str = r#"
[friction]
mu_s = 0.6
mu_k = 0.3
alpha_n = 1.0e11
alpha_t = 1.0e11
r = 1.0e6
kappa = 0.0
m = 1.0
xi = 0.0
n = 1.0
structure0 = 1.0
f0 = 0.0

[time]
t_end = 0.6
dt = 0.002
integrator = "wilson"
energy_tolerance = 1.0e9

[scene]
kind = "mesh"
file = "half_cylinder.msh"

[[scene.materials]]
group = "cylinder"
youngs_modulus = 1.0e7
poisson_ratio = 0.3
density = 100.0

[[scene.boundaries]]
group = "top"
phases = [
  { velocity = [0.0, -0.1], duration = 0.2 },
  { velocity = [0.0, 0.0], duration = 0.2 },
  { velocity = [0.035, 0.0], duration = 0.2 },
  { velocity = [0.0, 0.0] },
]
ramp_time = 0.05

[[scene.contacts]]
group = "arc"
normal = "evolving"
normal_traction = { kind = "uniform", value = 0.0 }
gap = { kind = "linear", along = "y", at = [0.0, 1.0], value = [0.0, 1.0] }
"#;

/// [`CYLINDER`]'s plane-strain modulus against a rigid base, `E* = E/(1 - ν²)` with its `ν = 0.3`.
const CYLINDER_E_STAR: f64 = 1.0e7 / (1.0 - 0.3 * 0.3);

/// Each contact point's x (m) along the cylinder's arc, in the contact's order.
fn contact_point_x(case: &Case) -> Vec<f64> {
    let SceneSpec::Mesh(spec) = &case.scene else { panic!("a mesh case") };
    let loaded = spec.loaded();
    let nodes = &loaded.mesh.nodes;
    slipfront::fem::curve::segments(&loaded.contact_chains[0], nodes)
        .iter()
        .flat_map(|s| s.gauss_points(nodes).map(|g| g.position.x))
        .collect()
}

/// Each segment's centre x and the mean of `value` over its two contact points, weighted as
/// the contact integrates them (what the recording shows of a segment).
fn segment_means(
    points: &[slipfront::dynamics::ContactPoint],
    xs: &[f64],
    states: &[ContactState],
    value: impl Fn(&ContactState) -> f64,
) -> Vec<(f64, f64)> {
    (0..points.len() / 2)
        .map(|k| {
            let (a, b) = (2 * k, 2 * k + 1);
            let w = points[a].weight + points[b].weight;
            (0.5 * (xs[a] + xs[b]), (points[a].weight * value(&states[a]) + points[b].weight * value(&states[b])) / w)
        })
        .collect()
}

/// The pressure of each segment of `scene`'s contact (its centre x, its mean `f_n`), the
/// contact's total normal force `P` and its tangential force `Q` (N/m).
fn cylinder_contact(scene: &BodyScene, xs: &[f64]) -> (Vec<(f64, f64)>, f64, f64) {
    let system = scene.system();
    let (points, states) = (&system.contact.points, &system.state.contact);
    let total = |f: fn(&ContactState) -> f64| points.iter().zip(states).map(|(p, c)| p.weight * f(c)).sum::<f64>();
    (segment_means(points, xs, states, |c| c.traction_n), total(|c| c.traction_n), total(|c| c.traction_t))
}

/// Runs [`CYLINDER`] with `overrides` to `t` (s) and returns the scene and the contact points' x.
fn cylinder_at(overrides: &[&str], t: f64) -> (BodyScene, Vec<f64>) {
    let case = mesh_case(CYLINDER, overrides);
    let SceneSpec::Mesh(spec) = &case.scene else { panic!("a mesh case") };
    let xs = contact_point_x(&case);
    let mut scene = slipfront::scene::mesh::scene(&case, spec).unwrap();
    advance_to(&mut scene, case.time.dt, t);
    (scene, xs)
}

/// Advances `scene` by steps of at most `dt` (s) to `t` (s), every displacement finite.
fn advance_to(scene: &mut BodyScene, dt: f64, t: f64) {
    while scene.time() < t - 1e-9 {
        scene.advance(dt.min(t - scene.time())).unwrap();
        let s = &scene.system().state;
        assert!(s.displacement.iter().all(|x| x.is_finite()), "not finite at {} s", s.time);
    }
}

/// Hertz's half-width `a = √(4PR/(πE*))` and peak `p₀ = 2P/(πa)` for `P` (N/m) on [`CYLINDER`]
/// (`R` = 1 m), and the half-width and peak least-squares fitted to the segments' `pressure` as
/// `p² = p₀² (1 - x²/a²)` over the segments above a third of the peak.
fn hertz_and_fit(pressure: &[(f64, f64)], total: f64) -> ([f64; 2], [f64; 2]) {
    let a_hertz = (4.0 * total / (std::f64::consts::PI * CYLINDER_E_STAR)).sqrt();
    let peak = pressure.iter().fold(0.0_f64, |m, p| m.max(p.1));
    let fit: Vec<(f64, f64)> = pressure.iter().filter(|p| p.1 > peak / 3.0).map(|&(x, p)| (x * x, p * p)).collect();
    let n = fit.len() as f64;
    let (mx, my) = fit.iter().fold((0.0, 0.0), |s, (x, y)| (s.0 + x / n, s.1 + y / n));
    let slope = fit.iter().map(|(x, y)| (x - mx) * (y - my)).sum::<f64>()
        / fit.iter().map(|(x, _)| (x - mx).powi(2)).sum::<f64>();
    let p0_squared = my - slope * mx;
    ([a_hertz, 2.0 * total / (std::f64::consts::PI * a_hertz)], [(p0_squared / -slope).sqrt(), p0_squared.sqrt()])
}

/// Hertz's line contact on the half-cylinder ([`CYLINDER`] pressed without friction,
/// `μ_k = 0.01`, at 0.4 s): the contact's total `P` gives Hertz's half-width
/// `a = √(4PR/(πE*))`, `E* = E/(1 - ν²)` against a rigid base, and pressure
/// `p = (2P/πa²) √(a² - x²)`. Compared per segment (the weighted mean of its two contact points):
/// the points' own values alternate from one to the next, by up to 90 % of the peak, because a
/// penalty this stiff (`α_n h/E = 50`) puts two constraints on each edge of bilinear cells that
/// can follow one; their sum, and so each segment's mean and the total `P`, are not affected.
///
/// Measured (2026-11-26, this test's fit; `h` the cells' size at the contact): the fitted
/// half-width is 3.2 % narrower than Hertz's at `h` = 5 mm and 2.1 % at 2.5 mm, the peak 3.2 % and
/// 2.2 % higher, the profile inside `0.9 a` within 4.9 % and 3.0 % of `p₀`. About 1.1 points of
/// it go with `h`; the rest, about 1 %, is the contact's frame: each point's normal is its own
/// segment's (docs/model.md), tilted by `x/R` from the base's, so the inward tangential
/// displacement of Hertz's surface, `(1-2ν)(1+ν)P/(2E)` = 3 mm at the edge, closes the gap by
/// `u_x x/R`, up to `(1-2ν)πa/(4R(1-ν))` = 5 % of it there, which narrows the contact. Pressed
/// by 1 cm (`a/R` = 0.078 instead of 0.11) the half-width is 1.2 % narrower. So on this 5 mm mesh
/// `a` and `p₀` lie within 3.5 % of Hertz's and the profile within 5.5 % of `p₀`; outside `a + 2h`
/// the contact is open.
#[test]
fn a_cylinder_pressed_without_friction_gives_hertz() {
    let (scene, xs) = cylinder_at(&["friction.mu_k=0.01", "friction.mu_s=0.02"], 0.4);
    let (pressure, total, _) = cylinder_contact(&scene, &xs);
    let ([a_hertz, p0_hertz], [a_fit, p0_fit]) = hertz_and_fit(&pressure, total);
    let h = 0.005;
    let profile = pressure
        .iter()
        .filter(|p| p.0.abs() < 0.9 * a_hertz)
        .map(|&(x, p)| (p - p0_hertz * (1.0 - (x / a_hertz).powi(2)).sqrt()).abs() / p0_hertz)
        .fold(0.0, f64::max);
    let open_beyond = pressure.iter().filter(|p| p.0.abs() > a_hertz + 2.0 * h).all(|p| p.1 == 0.0);
    println!(
        "Hertz: P = {total:.1} N/m; half-width fitted {a_fit:.5} m against {a_hertz:.5} m ({:+.2} %), peak \
         {p0_fit:.0} Pa against {p0_hertz:.0} Pa ({:+.2} %); inside 0.9 a the pressure within {:.2} % of p₀ \
         of Hertz's; {} segments pressed",
        100.0 * (a_fit / a_hertz - 1.0),
        100.0 * (p0_fit / p0_hertz - 1.0),
        100.0 * profile,
        pressure.iter().filter(|p| p.1 > 0.0).count()
    );
    assert!((a_fit / a_hertz - 1.0).abs() < 0.035, "half-width {a_fit} m against {a_hertz} m");
    assert!((p0_fit / p0_hertz - 1.0).abs() < 0.035, "peak {p0_fit} Pa against {p0_hertz} Pa");
    assert!(profile < 0.055, "the pressure is {profile} of p₀ from Hertz's");
    assert!(open_beyond, "a segment beyond a + 2h is pressed");
}

/// Cattaneo–Mindlin's stick zone on the half-cylinder ([`CYLINDER`]).
///
/// Their theory starts from Hertz's contact with no tangential traction and assumes that the
/// tangential traction does not change the pressure (Goodman's approximation). So the cylinder is
/// pressed without friction (`μ_k = 0.01` to 0.4 s, [`a_cylinder_pressed_without_friction_gives_hertz`]:
/// its points slide as they close and carry at most 1 % of their pressure along the base), then
/// friction is switched on (`μ_k = 0.3`, no structure, so the static coefficient is `μ = μ_k
/// (1/R*₀) = 0.3`) and its top pushed sideways by 7 mm. Pressed with friction instead, the
/// contact's points stick as they close and hold Hertz's inward surface displacement back
/// (Spence's problem): it is 7 % narrower and carries opposite tangential tractions on its two
/// halves before any push, which their theory does not have.
///
/// At 0.6 s, the push's end, `Q < μ P`: the contact slips near its edges and sticks in its
/// middle, `|x| < c`, `c = a √(1 - Q/(μP))` with `a` this contact's fitted half-width at 0.4 s. A
/// segment sticks where `|f_t| < 0.98 μ f_n` (in the slip zone the traction lies on the sliding
/// surface, `R → 1`). What is left beyond a cell is Goodman's approximation: the Dundurs
/// constant of the pair, `β = (1 - 2ν)/(2(1 - ν))` = 0.29 with `ν = 0.3` (not nearer 0.5, where
/// it vanishes, because bilinear cells lock there), couples the push into the pressure, which
/// shifts the stick zone along the push.
///
/// Measured (2026-11-26, `cargo test --release --test normal cattaneo -- --nocapture`): pressed
/// to `P` = 119.6 kN/m with `|Q|` = 246 N/m (0.2 % of `P`) and a half-width 3.2 % narrower than
/// Hertz's (the mesh's, as without friction); pushed to `Q/(μP)` = 0.564, the stick zone's
/// half-width is 0.0745 m against Cattaneo–Mindlin's 0.0753 m (−0.7 % of `a`, 0.15 of a cell) and
/// its centre +7.4 mm (6.5 % of `a`) along the push. Asserted: the half-width within one cell `h`
/// (a segment sticks or not: the zone's edges are known to a cell), the centre within 10 % of `a`.
#[test]
fn a_cylinder_pressed_then_pushed_sideways_sticks_in_its_middle_as_cattaneo_mindlin() {
    let (mut scene, xs) = cylinder_at(&["friction.mu_k=0.01", "friction.mu_s=0.02"], 0.4);
    let (pressure, total, q_pressed) = cylinder_contact(&scene, &xs);
    let ([a_hertz, _], [a, _]) = hertz_and_fit(&pressure, total);
    let (mu, h) = (0.3, 0.005);
    for surface in &mut scene.system_mut().contact.surfaces {
        (surface.params.mu_k, surface.params.mu_s) = (mu, 2.0 * mu);
    }
    advance_to(&mut scene, 0.002, 0.6);
    let system = scene.system();
    let (normal, total, q) = cylinder_contact(&scene, &xs);
    let q = q.abs();
    let tangential = segment_means(&system.contact.points, &xs, &system.state.contact, |c| c.traction_t);
    let stick: Vec<f64> = normal
        .iter()
        .zip(&tangential)
        .filter(|((_, f_n), (_, f_t))| *f_n > 0.0 && f_t.abs() < 0.98 * mu * f_n)
        .map(|((x, _), _)| *x)
        .collect();
    let (left, right) = stick.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, r), x| (l.min(*x), r.max(*x)));
    let c_measured = 0.5 * (right - left);
    let c_theory = a * (1.0 - q / (mu * total)).sqrt();
    println!(
        "Cattaneo–Mindlin: pressed without friction to P = {total:.1} N/m (|Q| = {:.2} N/m), half-width {a:.5} m \
         ({:+.2} % of Hertz's); pushed, Q = {q:.1} N/m, Q/(μP) = {:.3}; stick zone from {left:.4} to {right:.4} m, \
         half-width {c_measured:.4} m against a √(1 - Q/μP) = {c_theory:.4} m ({:+.2} % of a, {:+.2} h), centred at \
         {:+.4} m; {} segments stick",
        q_pressed.abs(),
        100.0 * (a / a_hertz - 1.0),
        q / (mu * total),
        100.0 * (c_measured - c_theory) / a,
        (c_measured - c_theory) / h,
        0.5 * (left + right),
        stick.len()
    );
    assert!(q_pressed.abs() < 0.01 * total, "pressed without friction, Q = {q_pressed} N/m");
    assert!(q / (mu * total) > 0.2 && q / (mu * total) < 0.9, "Q/μP = {}", q / (mu * total));
    assert!((c_measured - c_theory).abs() < h, "stick half-width {c_measured} m against {c_theory} m");
    assert!((0.5 * (left + right)).abs() < 0.1 * a, "the stick zone is centred at {} m", 0.5 * (left + right));
}

/// A body with a held and an evolving contact says per contact which segments can open: the
/// double-shear sample (`cases/double_shear.toml`) with its right contact evolving. The layout
/// goes into the recording and the MCAP log, and a replay marks a segment open only where it
/// says its contact evolves, so a held contact's unpressed segment is never shown open.
#[test]
fn a_body_with_a_held_and_an_evolving_contact_says_which_can_open() {
    let case = common::load("double_shear", &["scene.contacts[1].normal=\"evolving\""]);
    let SceneSpec::Mesh(spec) = &case.scene else { panic!("a mesh case") };
    let scene = slipfront::scene::mesh::scene(&case, spec).unwrap();
    let layout = scene.layout();
    let ranges = layout.contact_ranges();
    assert_eq!(ranges.len(), 2, "two contacts");
    assert!(layout.evolving_normal);
    assert!(ranges[0].1.clone().all(|k| !layout.segment_evolves(k)), "the held left contact's segments");
    assert!(ranges[1].1.clone().all(|k| layout.segment_evolves(k)), "the evolving right contact's segments");
}
