//! Wilson's θ method as implemented (total form, linear acceleration) against the paper's rate
//! form with a linear jerk, on a single-degree-of-freedom oscillator `ü + ω² u = 0`.

use nalgebra::{Complex, DMatrix};
use slipfront::dynamics::{ContactBoundary, LinearBody, LinearSolver, MainBody, Settings, System, Wilson};
use slipfront::friction::FrictionParams;
use slipfront::linalg::sparse::SymmetricMatrix;

const THETA: f64 = 1.4;

/// Amplification matrix of the library's step on `(u, v, a)` for `ω = omega`, `Δt = 1`.
fn library_amplification(omega: f64) -> DMatrix<f64> {
    solver_amplification(omega, LinearSolver::Full)
}

fn solver_amplification(omega: f64, linear_solver: LinearSolver) -> DMatrix<f64> {
    let mut columns = Vec::new();
    for c in 0..3 {
        let body = LinearBody::new(vec![1.0], SymmetricMatrix::from_triplets(1, &[(0, 0, omega * omega)]));
        let contact = ContactBoundary::single(FrictionParams::paper(), MainBody::at_rest(), Vec::new(), Vec::new());
        let settings = Settings {
            theta: THETA,
            tolerance: 1e-14,
            velocity_scale: 1.0,
            max_iterations: 10,
            energy_tolerance: None,
            linear_solver,
        };
        let mut d = System::new(body, contact, settings).unwrap();
        let mut wilson = Wilson::default();
        let mut unit = [0.0; 3];
        unit[c] = 1.0;
        d.state.displacement[0] = unit[0];
        d.state.velocity[0] = unit[1];
        d.state.acceleration[0] = unit[2];
        wilson.step(&mut d, 1.0).unwrap();
        columns.extend([d.state.displacement[0], d.state.velocity[0], d.state.acceleration[0]]);
    }
    DMatrix::from_column_slice(3, 3, &columns)
}

/// Amplification matrix of the paper's scheme on `(u, v, a, j)`: Wilson's θ on
/// `j + ω² v = 0` with a linear jerk over `τ = θΔt`, `u` integrated from the cubic velocity.
fn rate_form_amplification(omega: f64) -> DMatrix<f64> {
    let (dt, tau) = (1.0, THETA);
    let mut columns = Vec::new();
    for c in 0..4 {
        let mut s = [0.0; 4];
        s[c] = 1.0;
        let [u, v, a, j] = s;
        let c0 = 6.0 / (tau * tau);
        let v_theta = (c0 * v + 6.0 / tau * a + 2.0 * j) / (c0 + omega * omega);
        let j_theta = c0 * (v_theta - v) - 6.0 / tau * a - 2.0 * j;
        let j1 = j + (j_theta - j) / THETA;
        let a1 = a + dt * (j + j1) / 2.0;
        let v1 = v + dt * a + dt * dt * (2.0 * j + j1) / 6.0;
        let u1 = u + dt * v + dt * dt * a / 2.0 + dt.powi(3) * (3.0 * j + j1) / 24.0;
        columns.extend([u1, v1, a1, j1]);
    }
    DMatrix::from_column_slice(4, 4, &columns)
}

fn sorted_eigenvalues(m: DMatrix<f64>) -> Vec<Complex<f64>> {
    let mut e: Vec<Complex<f64>> = m.complex_eigenvalues().iter().copied().collect();
    e.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
    e
}

#[test]
fn the_rate_form_is_the_total_form_plus_an_undamped_drift_mode() {
    for omega in [0.01, 0.1, 0.5, 1.0, 2.0, 10.0, 100.0] {
        let total = sorted_eigenvalues(library_amplification(omega));
        let mut rate = sorted_eigenvalues(rate_form_amplification(omega));
        // Remove the eigenvalue 1 of the rate form's integration constant.
        let drift = rate.iter().position(|z| (z - Complex::new(1.0, 0.0)).norm() < 1e-9).expect("an eigenvalue 1");
        rate.remove(drift);
        for (a, b) in total.iter().zip(&rate) {
            assert!((a - b).norm() < 1e-9, "ω Δt = {omega}: {total:?} vs {rate:?}");
        }
    }
}

#[test]
fn the_implemented_scheme_is_unconditionally_stable_and_dissipative() {
    for omega in [1e-3, 0.1, 1.0, 10.0, 1e3, 1e6] {
        let radius = sorted_eigenvalues(library_amplification(omega)).iter().map(|z| z.norm()).fold(0.0, f64::max);
        assert!(radius <= 1.0, "ω Δt = {omega}: spectral radius {radius}");
    }
    // High frequencies are damped, low ones barely.
    let low = sorted_eigenvalues(library_amplification(1e-3)).iter().map(|z| z.norm()).fold(0.0, f64::max);
    let high = sorted_eigenvalues(library_amplification(1e3)).iter().map(|z| z.norm()).fold(0.0, f64::max);
    assert!(low > 1.0 - 1e-9 && high < 0.8, "ρ(1e-3) = {low}, ρ(1e3) = {high}");
}

/// The condensed Newton iteration (no contact unknowns here) takes the same step.
#[test]
fn the_condensed_solver_takes_the_same_step() {
    for omega in [1e-3, 1.0, 1e3] {
        let full = solver_amplification(omega, LinearSolver::Full);
        let condensed = solver_amplification(omega, LinearSolver::Condensed);
        assert!((&full - &condensed).amax() <= 1e-12 * full.amax(), "ω Δt = {omega}: {full} vs {condensed}");
    }
}
