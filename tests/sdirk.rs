//! The L-stable SDIRK 4(3) on the rate form ([`slipfront::dynamics::rate_form::sdirk4`]) against
//! Tsitouras' explicit 5(4) pair at a tight tolerance on the paper case: the same equations, an
//! independent method (explicit, fifth order, no Newton solves).

mod common;

use common::{load, onset_error, onsets, traction_errors_against_tsit5};

#[test]
fn sdirk_tractions_converge_to_tsit5_as_the_tolerance_tightens() {
    // Every segment's traction every 5 s up to 400 s (the ramp, the body's ringing and the
    // creep before the first slips at 420 s), at SDIRK tolerances 1e-8, 1e-9 and 1e-10 against
    // Tsit5 at 1e-12, itself checked at 1e-11. Looser tolerances stall near 1.2e-4 Pa (1e-7 of
    // the tractions): steps longer than the contact mode's period (ω ≈ 45 rad/s) damp its
    // ringing, as Wilson's method does, where both explicit reference runs keep it.
    let runs = ["1e-8", "1e-9", "1e-10"].map(|t| ["time.integrator=sdirk4".to_string(), format!("time.tolerance={t}")]);
    let (converged, errors) = traction_errors_against_tsit5("1e-12", "1e-11", &runs);
    println!("reference converged to {converged:e} Pa; SDIRK's errors {errors:?} Pa");
    assert!(converged < 0.2 * errors[2], "the reference is far finer than the tightest tolerance");
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        // A per-step tolerance 10× tighter: the error of a method whose steps follow it falls
        // about 10× too; 3 leaves room for the step sequence changing.
        assert!(ratio > 3.0, "errors {errors:?}: a tenth of the tolerance gives only {ratio}× less error");
    }
}

#[test]
fn sdirk_onsets_converge_to_tsit5_as_the_tolerance_tightens() {
    // The first slips (four events from 420 s to 430 s) up to 450 s, at SDIRK tolerances 1e-6,
    // 1e-7 and 1e-8 against Tsit5 at 1e-12, itself checked at 1e-11.
    let t_end = "time.t_end=450";
    let reference = onsets(&load("paper_triangular", &[t_end, "time.integrator=tsit5", "time.tolerance=1e-12"]));
    let check = onsets(&load("paper_triangular", &[t_end, "time.integrator=tsit5", "time.tolerance=1e-11"]));
    assert!(reference.len() >= 3, "the reference has the first slips: {reference:?}");
    let converged = onset_error(&check, &reference).expect("the check has the reference's events");
    let errors: Vec<f64> = ["1e-6", "1e-7", "1e-8"]
        .iter()
        .map(|tolerance| {
            let tolerance = format!("time.tolerance={tolerance}");
            let run = onsets(&load("paper_triangular", &[t_end, "time.integrator=sdirk4", &tolerance]));
            onset_error(&run, &reference).unwrap_or_else(|| panic!("{tolerance}: events {run:?}, not {reference:?}"))
        })
        .collect();
    println!("reference converged to {converged:e}; SDIRK's relative onset errors {errors:?}");
    assert!(converged < 0.1 * errors[2], "the reference is far finer than the tightest tolerance");
    for pair in errors.windows(2) {
        assert!(pair[0] > 3.0 * pair[1], "errors {errors:?} do not fall with the tolerance");
    }
}
