//! The paper's observations across time integrators: the 32-member ensemble of the paper case
//! (initial `1/R*` moved by `k × 1e-9` of its range, `slipfront::study::ensemble`) run with each
//! integrator, and for each the members in which each observation holds (`Verdict`), with
//! Wilson's 95 % score interval for a binomial proportion, and the ensemble's medians.
//!
//! Wilson's θ = 1.4 damps the block's ringing numerically; SDIRK4 damps it less, Tsitouras' pair
//! (with its steps bounded so that it amplifies no mode more than 2× per 1000 s) and central
//! differences hardly at all. If the paper's conclusions came from numerical damping, the
//! counts would differ by more than their intervals.
//!
//! cargo run --release --example integrator_ensemble [-- --members 32]

use std::time::Instant;

use slipfront::case;
use slipfront::catalog::observations::{Observations, Verdict, median};
use slipfront::study::ensemble::{available_threads, run_ensemble};

/// Spread of the members' initial `1/R*`, as a fraction of its range (as in `tests/paper_case.rs`).
const EPSILON: f64 = 1e-9;

/// The integrators compared, as `--set` overrides of the paper case.
const SETTINGS: [(&str, &[&str]); 4] = [
    ("Wilson, dt = 0.01 s", &["time.integrator=wilson"]),
    ("SDIRK4, tolerance 1e-7", &["time.integrator=sdirk4"]),
    ("central differences, dt = 0.01 s", &["time.integrator=central"]),
    ("Tsit5, tolerance 1e-8", &["time.integrator=tsit5"]),
];

/// Wilson's score interval for `k` successes in `n` trials at 95 %.
fn score_interval(k: usize, n: usize) -> (f64, f64) {
    let (k, n, z) = (k as f64, n as f64, 1.959_963_984_540_054);
    let p = k / n;
    let centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
    let half = z / (1.0 + z * z / n) * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt();
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mut members = 32;
    while let Some(a) = args.next() {
        match (a.as_str(), args.next()) {
            ("--members", Some(n)) => members = n.parse().expect("--members takes a count"),
            _ => panic!("usage: integrator_ensemble [--members N]"),
        }
    }
    let path = format!("{}/cases/paper_triangular.toml", env!("CARGO_MANIFEST_DIR"));
    println!(
        "| integrator | 1. left end | 2. right end | 3. propagation | all three | median slips at A | median slips at F \
         | pooled mean 1/R* before A re-slips | median slip at F / at A | wall |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (label, sets) in SETTINGS {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let base = case::load(std::path::Path::new(&path), &sets).expect("the paper case loads");
        let started = Instant::now();
        let ensemble = run_ensemble(&base, members, EPSILON, available_threads());
        let wall = started.elapsed().as_secs_f64();
        let observed: Vec<Observations> = ensemble
            .iter()
            .map(|m| {
                let catalog = m.catalog.as_ref().unwrap_or_else(|e| panic!("{label}, member {}: {e}", m.index));
                Observations::measure(&catalog.events, &catalog.ruptures, m.segments)
            })
            .collect();
        let held = |f: fn(&Verdict) -> bool| {
            let k = observed.iter().filter(|o| f(&o.verdict())).count();
            let (lo, hi) = score_interval(k, members);
            format!("{k} of {members} ({:.0}–{:.0} %)", 100.0 * lo, 100.0 * hi)
        };
        let medians = |f: fn(&Observations) -> f64| median(&observed.iter().map(f).collect::<Vec<_>>());
        let pooled: Vec<f64> = observed.iter().flat_map(|o| o.left_reslip_structure.iter().copied()).collect();
        let pooled_mean = pooled.iter().sum::<f64>() / pooled.len().max(1) as f64;
        let left_slip = medians(|o| if o.left_slips.is_empty() { 0.0 } else { median(&o.left_slips) });
        let right_slip = medians(|o| o.right_slips.first().copied().unwrap_or(0.0));
        println!(
            "| {label} | {} | {} | {} | {} | {} | {} | {pooled_mean:.2} | {:.1} | {wall:.0} s |",
            held(|v| v.left_end),
            held(|v| v.right_end),
            held(|v| v.propagation),
            held(|v| v.all()),
            medians(|o| o.left_onsets.len() as f64),
            medians(|o| o.right_onsets.len() as f64),
            right_slip / left_slip,
        );
    }
}
