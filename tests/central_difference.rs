//! Explicit central differences ([`slipfront::dynamics::central`]): their stability
//! limit against a dense eigensolver, and their second-order convergence on the paper case
//! against Tsitouras' 5(4) pair at a tight tolerance, a different method on a different form of
//! the equations (the rate form).

mod common;

use common::traction_errors_against_tsit5;
use nalgebra::{DMatrix, SymmetricEigen};
use slipfront::dynamics::central::highest_frequency;
use slipfront::dynamics::{Motion, NormalBehaviour};
use slipfront::fem::{Assembled, Material, PlaneStrain};
use slipfront::friction::FrictionParams;
use slipfront::scene::block::block;

#[test]
fn lanczos_finds_the_highest_frequency_of_a_dense_eigensolver() {
    // A 30 × 6 block (372 unknowns, more than Lanczos' 100 steps) with the paper's contact:
    // the largest eigenvalue of M^{-1/2} (K + K_t) M^{-1/2}, formed densely and solved by
    // nalgebra's symmetric eigensolver, against `highest_frequency`.
    let material = Material { elasticity: PlaneStrain { youngs_modulus: 1.0e3, poisson_ratio: 0.0 }, density: 1000.0 };
    let params = FrictionParams::paper();
    let alpha_t = params.alpha_t;
    let base = Motion::constant([1e-3, 0.0], 10.0);
    let Assembled { body, contact, .. } =
        block(10.0, 1.0, 30, 6, material, params, (&|_| 500.0, NormalBehaviour::Held), base);
    let n = body.dofs();
    let mut dense = DMatrix::<f64>::zeros(n, n);
    for (i, j, v) in body.stiffness.entries() {
        dense[(i, j)] += v;
    }
    for p in &contact.points {
        for (a, c_a) in p.tangential.terms() {
            for (b, c_b) in p.tangential.terms() {
                dense[(a, b)] += alpha_t * p.weight * c_a * c_b;
            }
        }
    }
    let scaled = DMatrix::from_fn(n, n, |i, j| dense[(i, j)] / (body.mass[i] * body.mass[j]).sqrt());
    let largest = SymmetricEigen::new(scaled).eigenvalues.iter().copied().fold(0.0, f64::max);
    let exact = largest.sqrt();
    let lanczos = highest_frequency(&body, &contact);
    let relative = (lanczos - exact).abs() / exact;
    println!("ω_max: Lanczos {lanczos} rad/s, dense {exact} rad/s, relative {relative:e}");
    assert!(relative < 1e-6, "Lanczos {lanczos} against {exact}");
}

#[test]
fn central_differences_converge_at_second_order_to_tsit5_on_the_paper_case() {
    // Every segment's traction every 5 s up to 400 s (the ramp, its elastic ringing and the
    // creep before the first slips at 420 s), by central differences at dt = 0.02, 0.01 and
    // 0.005 s (one sub-step per frame: the stable step is 0.04 s on 10 × 1), against Tsit5 at
    // tolerance 1e-11, itself checked at 1e-10. Measured: errors 9.0e-4, 2.9e-4, 7.7e-5 Pa
    // (ratios 3.1 and 3.8, tending to 4), the reference's own 1.1e-6 Pa.
    let runs = [0.02, 0.01, 0.005].map(|dt| ["time.integrator=central".to_string(), format!("time.dt={dt}")]);
    let (converged, errors) = traction_errors_against_tsit5("1e-11", "1e-10", &runs);
    println!("reference converged to {converged:e} Pa; central differences' errors {errors:?} Pa");
    assert!(converged < 0.05 * errors[2], "the reference is far finer than the finest step");
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        // Second order halves the step for a quarter of the error; first order would give 2.
        assert!(ratio > 3.0, "errors {errors:?}: ratio {ratio} is not second order");
    }
    assert!(errors[1] < 1e-3, "dt = 0.01 s within 1 mPa of tractions of hundreds of Pa: {errors:?}");
}

/// A block whose spacing is no binary fraction (300 × 30 over 10 m × 1 m: 1/30 m) has node
/// coordinates rounded differently from cell to cell, yet its congruent cells share one element
/// matrix, so the stiffness forms runs of equal node stencils row by row, which the explicit
/// step's fast product needs: at most four per grid row (its first node, its interior, its last
/// node, and the rows beside the contact and the fixed top). Each cell's own matrix gives 450
/// runs here, and on 1000 × 100 made the explicit step 3 times slower. The stencil product
/// equals the compressed one to rounding.
#[test]
fn a_structured_block_of_inexact_spacing_forms_runs_of_equal_stencils() {
    let material = Material { elasticity: PlaneStrain { youngs_modulus: 1.0e3, poisson_ratio: 0.0 }, density: 1000.0 };
    let base = Motion::constant([1e-3, 0.0], 10.0);
    let (nx, ny) = (300, 30);
    let Assembled { body, .. } =
        block(10.0, 1.0, nx, ny, material, FrictionParams::paper(), (&|_| 500.0, NormalBehaviour::Held), base);
    let templates = slipfront::linalg::stencil::TemplateMatrix::new(&body.stiffness).unwrap();
    println!("{} runs of equal stencils over {} nodes", templates.runs(), body.dofs() / 2);
    assert!(templates.runs() <= 4 * ny, "{} runs over {ny} free grid rows", templates.runs());
    let x: Vec<f64> = (0..body.dofs()).map(|i| (i as f64 * 0.37).sin()).collect();
    let (mut fast, mut compressed) = (vec![0.0; x.len()], vec![0.0; x.len()]);
    templates.mul_vec(&x, &mut fast);
    body.stiffness.mul_vec(&x, &mut compressed);
    let scale = compressed.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let worst = fast.iter().zip(&compressed).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale;
    assert!(worst < 1e-13, "stencil product differs from the compressed one by {worst:e} of its largest");
}
