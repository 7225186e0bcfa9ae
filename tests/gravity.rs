//! A body under its own weight starts in static equilibrium, against closed forms.
//!
//! A column of width `W` and height `H` (tests/meshes/column.geo, 2 × 20 bilinear cells),
//! plane strain, `ν = 0.25`, its sides on rollers (u_x = 0), its top free, resting on its base,
//! the frictional contact, under gravity `g = (0, -9.81)`. Its exact state is one-dimensional:
//! `σ_yy = -ρ g (H - y)`, linear in y; `u_y` is quadratic, and linear elements with the
//! consistent body force reproduce it at the nodes, so their strain at an element's centre (the
//! slope of the chord) is the exact strain there: `σ_yy` at element centres is exact, whatever
//! the mesh. The contact carries the whole weight `ρ g H W`.

use slipfront::case::{self, Case, SceneSpec};
use slipfront::fem::equilibrium::Equilibrium;
use slipfront::fem::{PlaneStrain, assemble};
use slipfront::scene::Scene;

const RHO: f64 = 2000.0;
const G: f64 = 9.81;
const E: f64 = 1.0e7;
const NU: f64 = 0.25;
const H: f64 = 10.0;
const W: f64 = 1.0;

const COLUMN: &str = r#"
[friction]
mu_s = 0.4
mu_k = 0.2
alpha_n = 1.0e9
alpha_t = 1.0e9
r = 100.0
kappa = 10.0
m = 1.0
xi = 0.1
n = 1.0
structure0 = 2.0
f0 = 1.0e-7

[time]
t_end = 1.0
dt = 0.01

[scene]
kind = "mesh"
file = "column.msh"
gravity = [0.0, -9.81]

[[scene.materials]]
group = "column"
youngs_modulus = 1.0e7
poisson_ratio = 0.25
density = 2000.0

[[scene.boundaries]]
group = "left"
fixed = "x"

[[scene.boundaries]]
group = "right"
fixed = "x"

[[scene.contacts]]
group = "base"
normal_traction = { kind = "lithostatic", level = 10.0, unit_weight = 19620.0, coefficient = 1.0 }
"#;

fn column(overrides: &[&str]) -> Case {
    let owned: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let dir = format!("{}/tests/meshes", env!("CARGO_MANIFEST_DIR"));
    case::from_str_at(COLUMN, &owned, std::path::Path::new(&dir)).unwrap_or_else(|e| panic!("{e}"))
}

/// `σ_yy` at the centre of every cell of the settled column equals `-ρ g (H - y)` to 1e-6 of
/// `ρ g H` (measured 1.5e-14); the normal springs of the contact carry the weight to 1e-9
/// (measured 8.5e-15), and so does the lithostatic normal traction the case prescribes
/// (1.5e-16); the sides on rollers leave `ε_xx` at 0; the base carries no shear (6.5e-10 Pa,
/// rounding), so the friction state starts at `f0`.
#[test]
fn a_column_under_its_own_weight_starts_in_static_equilibrium() {
    let case = column(&[]);
    let SceneSpec::Mesh(spec) = &case.scene else { panic!("a mesh case") };
    let loaded = spec.loaded();
    let equilibrium: &Equilibrium = loaded.equilibrium.as_ref().expect("gravity settles the body");
    let assembled = assemble(&spec.definition(loaded)).unwrap();
    let u = |node: usize| assembled.dofs.displacement(node, &equilibrium.displacement, 0.0);
    let material = PlaneStrain { youngs_modulus: E, poisson_ratio: NU };
    let d = material.elasticity();
    let weight = RHO * G * H * W;
    let mut worst: f64 = 0.0;
    for cell in &loaded.mesh.cells {
        let n = cell.nodes();
        assert_eq!(n.len(), 4);
        let p = |k: usize| loaded.mesh.nodes[n[k]];
        // A rectangle, counter-clockwise from its bottom left: the bilinear field's strains at
        // its centre are the mean differences across it.
        // A rectangle: the bilinear field's strains at its centre are the differences of the
        // means of its opposite sides.
        let y = 0.25 * (0..4).map(|k| p(k)[1]).sum::<f64>();
        let x = 0.25 * (0..4).map(|k| p(k)[0]).sum::<f64>();
        let side = |upper: bool, axis: usize| -> (f64, f64) {
            let on: Vec<usize> = (0..4).filter(|&k| (p(k)[axis] > [x, y][axis]) == upper).collect();
            let mean = |f: &dyn Fn(usize) -> f64| on.iter().map(|&k| f(k)).sum::<f64>() / on.len() as f64;
            (mean(&|k| p(k)[axis]), mean(&|k| u(n[k])[axis]))
        };
        let ((x0, ux0), (x1, ux1)) = (side(false, 0), side(true, 0));
        let ((y0, uy0), (y1, uy1)) = (side(false, 1), side(true, 1));
        let (exx, eyy) = ((ux1 - ux0) / (x1 - x0), (uy1 - uy0) / (y1 - y0));
        let syy = d[(1, 0)] * exx + d[(1, 1)] * eyy;
        let exact = -RHO * G * (H - y);
        worst = worst.max((syy - exact).abs() / (RHO * G * H));
        assert!(exx.abs() < 1e-12, "ε_xx = {exx} at y = {y}");
    }
    let springs = Equilibrium::total(&assembled, &equilibrium.traction_n);
    let prescribed = Equilibrium::total(&assembled, &assembled.contact.traction_n);
    let shear = equilibrium.traction_t.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    println!(
        "column: σ_yy at cell centres within {worst:.1e} of ρg(H - y); weight {weight} N/m, carried by the \
         normal springs {springs} N/m, prescribed {prescribed} N/m; largest shear on the base {shear:.1e} Pa"
    );
    assert!(worst < 1e-6, "σ_yy off by {worst} of ρgH");
    assert!((springs - weight).abs() < 1e-9 * weight, "{springs} N/m carried, weight {weight}");
    assert!((prescribed - weight).abs() < 1e-9 * weight, "{prescribed} N/m prescribed, weight {weight}");
    assert!(shear < 1e-9 * RHO * G * H, "the base carries a shear of {shear} Pa");
}

/// The run starts at rest in that equilibrium, so its first second (100 frames of 0.01 s,
/// with the default integrator and with Wilson's) holds it: the kinetic energy stays below
/// 1e-12 of the strain energy of the settlement, 5.4e3 J/m (measured 6.3e-52 J/m with Tsit5,
/// 8.6e-42 with Wilson's method), and no node moves from it by more than 1e-12 of the
/// settlement, 0.082 m (measured 4.4e-28 and 9.2e-24 m): rounding. Were the weight released at
/// the first step rather than balanced, the column would ring with kinetic energy of the order
/// of that strain energy.
#[test]
fn the_first_steps_hold_the_equilibrium() {
    for integrator in ["auto", "wilson"] {
        let case = column(&[&format!("time.integrator=\"{integrator}\"")]);
        let SceneSpec::Mesh(spec) = &case.scene else { panic!("a mesh case") };
        let loaded = spec.loaded();
        let equilibrium = loaded.equilibrium.as_ref().unwrap();
        let assembled = assemble(&spec.definition(loaded)).unwrap();
        let force = assembled.body_force.as_ref().unwrap();
        let strain: f64 = 0.5 * force.iter().zip(&equilibrium.displacement).map(|(f, u)| f * u).sum::<f64>();
        let settlement = (0..loaded.mesh.nodes.len())
            .map(|i| assembled.dofs.displacement(i, &equilibrium.displacement, 0.0)[1].abs())
            .fold(0.0, f64::max);
        let mut scene = slipfront::scene::mesh::scene(&case, spec).unwrap();
        let (mut kinetic, mut moved): (f64, f64) = (0.0, 0.0);
        while scene.time() < case.time.t_end - 1e-9 {
            let left = case.time.t_end - scene.time();
            scene.advance(case.time.dt.min(left)).unwrap();
            let system = scene.system();
            kinetic = kinetic.max(system.body.kinetic_energy(&system.state.velocity));
            moved = moved.max(system.state.displacement.iter().fold(0.0, |m, u| m.max(u.abs())));
        }
        println!(
            "column, {integrator}: strain energy of the settlement {strain:.3e} J/m, settlement {settlement:.3e} m; \
             over 1 s: kinetic energy at most {kinetic:.1e} J/m, displacement from it at most {moved:.1e} m"
        );
        assert!(strain > 0.0 && settlement > 0.0);
        assert!(kinetic <= 1e-12 * strain, "{integrator}: kinetic energy {kinetic} J/m");
        assert!(moved <= 1e-12 * settlement, "{integrator}: moved {moved} m");
    }
}
