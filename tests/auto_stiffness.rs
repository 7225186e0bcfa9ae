//! `auto` weighs a small body's stiffest mode on its contact's springs: the bound it uses
//! ([`slipfront::fem::stiffest`]) against a dense eigensolver of the assembled body, the same
//! bound from a Gmsh mesh of the same cells, and the choice it makes.

mod common;

use common::load;
use nalgebra::{DMatrix, SymmetricEigen};
use slipfront::dynamics::method::{AUTO_PAIR_STIFFNESS, Method};
use slipfront::dynamics::{Motion, NormalBehaviour};
use slipfront::fem::{Assembled, Material, PlaneStrain};
use slipfront::friction::FrictionParams;
use slipfront::scene::block::block;

/// `ω_max` of the paper's block on an `nx` × `ny` mesh with `params`' elastic springs: the
/// largest eigenvalue of `M^{-1/2} (K + K_t) M^{-1/2}`, formed densely and solved by nalgebra's
/// symmetric eigensolver (`K` holds the contact's normal springs `α_n`, `K_t` adds `α_t`).
fn dense_highest_frequency(nx: usize, ny: usize, params: FrictionParams, normal: NormalBehaviour) -> f64 {
    let material = Material { elasticity: PlaneStrain { youngs_modulus: 1.0e3, poisson_ratio: 0.0 }, density: 1000.0 };
    let base = Motion::constant([1e-3, 0.0], 10.0);
    let alpha_t = params.alpha_t;
    let Assembled { body, contact, .. } = block(10.0, 1.0, nx, ny, material, params, (&|_| 500.0, normal), base);
    let n = body.dofs();
    let mut dense = DMatrix::<f64>::zeros(n, n);
    for (i, j, v) in body.stiffness.entries() {
        dense[(i, j)] += v;
    }
    let mut add = |terms: Vec<(usize, f64)>, modulus: f64, weight: f64| {
        for &(a, c_a) in &terms {
            for &(b, c_b) in &terms {
                dense[(a, b)] += modulus * weight * c_a * c_b;
            }
        }
    };
    for p in &contact.points {
        add(p.tangential.terms().collect(), alpha_t, p.weight);
    }
    let scaled = DMatrix::from_fn(n, n, |i, j| dense[(i, j)] / (body.mass[i] * body.mass[j]).sqrt());
    SymmetricEigen::new(scaled).eigenvalues.iter().copied().fold(0.0, f64::max).sqrt()
}

#[test]
fn the_cell_bound_lies_above_the_assembled_bodys_highest_frequency_and_near_it() {
    // The element eigenvalue inequality makes the bound an upper one; on these meshes it is
    // also close, so that `auto`'s threshold means what it says.
    for (nx, ny, alpha_t, alpha_n, evolving) in [
        (10, 1, 1e6, 1e6, false),
        (10, 1, 1e9, 1e6, false),
        (30, 6, 1e6, 1e6, false),
        (30, 6, 1e8, 1e6, false),
        (10, 1, 1e6, 1e9, false),
        (10, 1, 1e6, 1e12, true),
    ] {
        let normal = if evolving { NormalBehaviour::Evolving } else { NormalBehaviour::Held };
        let params = FrictionParams { alpha_t, alpha_n, ..FrictionParams::paper() };
        let exact = dense_highest_frequency(nx, ny, params, normal);
        let mut sets = vec![
            format!("scene.nx={nx}"),
            format!("scene.ny={ny}"),
            format!("friction.alpha_t={alpha_t:e}"),
            format!("friction.alpha_n={alpha_n:e}"),
        ];
        if evolving {
            sets.push("scene.normal=\"evolving\"".into());
        }
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let case = load("paper_triangular", &sets);
        let bound = case.scene.stiffest_frequency(&case.friction).expect("a block is bounded");
        println!("{nx} x {ny}, α_t {alpha_t:e}, α_n {alpha_n:e} {normal:?}: bound {bound:.3} rad/s, dense {exact:.3}");
        assert!(bound >= exact * (1.0 - 1e-12), "the bound {bound} lies below ω_max = {exact}");
        assert!(bound <= 1.5 * exact, "the bound {bound} is far above ω_max = {exact}");
    }
}

#[test]
fn a_mesh_of_the_blocks_cells_gets_the_blocks_bound() {
    // cases/paper_mesh.toml reads the paper's 10 × 1 block from a Gmsh file: its cells and its
    // contact's edges are found by another path (the mesh's chains) than the block's.
    let block = load("paper_triangular", &[]);
    let mesh = load("paper_mesh", &[]);
    let (a, b) = (
        block.scene.stiffest_frequency(&block.friction).unwrap(),
        mesh.scene.stiffest_frequency(&mesh.friction).unwrap(),
    );
    println!("paper block {a} rad/s, its Gmsh mesh {b} rad/s");
    assert!((a - b).abs() <= 1e-12 * a, "{a} against {b}");
}

#[test]
fn auto_gives_a_body_stiff_on_its_contact_wilsons_method_and_says_why() {
    let chosen = |sets: &[&str]| {
        let case = load("paper_triangular", sets);
        (case.time.method, case.time.chosen_because.unwrap_or_default())
    };
    let (method, why) = chosen(&[]);
    assert_eq!(method, Method::Tsit5, "the paper's block: {why}");
    let (method, why) = chosen(&["friction.alpha_t=1e8"]);
    assert_eq!(method, Method::Tsit5, "α_t = 1e8 turns 4.5 radians per step, under {AUTO_PAIR_STIFFNESS}: {why}");
    let (method, why) = chosen(&["scene.normal=\"evolving\"", "friction.alpha_n=1e12"]);
    assert_eq!(method, Method::Wilson, "{why}");
    assert!(why.contains("turns up to 447 radians in a step of time.dt"), "{why}");
    // The shipped small bodies keep the pair.
    for name in
        ["paper_triangular", "paper_mesh", "uniform_low", "triangular_inverted", "double_shear", "fault_at_depth"]
    {
        let case = load(name, &[]);
        let turn = case.scene.stiffest_frequency(&case.friction).unwrap() * case.time.dt;
        println!("{name}: ω_max dt ≤ {turn:.3}");
        assert_eq!(case.time.method, Method::Tsit5, "{name}: {:?}", case.time.chosen_because);
    }
    let (method, why) = chosen(&["friction.alpha_t=1e9", "time.integrator=\"tsit5\""]);
    assert_eq!((method, why.as_str()), (Method::Tsit5, ""), "a named method is kept");
}
