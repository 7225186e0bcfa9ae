//! Sweeps the triangular normal stress of the paper's case (its magnitude is only in the
//! paper's Figure 7). Each triangle is run as a perturbed ensemble ([`slipfront::study::ensemble`]),
//! because the events after the first slips are chaotic, and the table gives, per triangle, in
//! how many members each of the paper's observations 1–3 holds ([`Verdict`]), with the members'
//! median slip counts at the ends and mean `1/R*` before the ends' slips.
//!
//! cargo run --release --example normal_stress_sweep -- [LEFT,RIGHT ...] [--members N] [--epsilon E] [--set KEY=VALUE ...]
//!
//! `--members 1` gives the shipped case alone, with its ruptures. The members are stepped by
//! Wilson's method unless `--set time.integrator=...` names another.

use slipfront::case;
use slipfront::catalog::observations::{Observations, Verdict, median};
use slipfront::study::ensemble::{available_threads, run_ensemble};

fn main() {
    let mut pairs: Vec<(f64, f64)> = Vec::new();
    // Wilson's method (the paper's, with which docs/paper.md's sweep was measured) unless a
    // `--set time.integrator=...` names another.
    let mut overrides: Vec<String> = vec!["time.integrator=wilson".into()];
    let (mut members, mut epsilon) = (8, 1e-9);
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = |name: &str| args.next().unwrap_or_else(|| panic!("{name} needs a value"));
        match arg.as_str() {
            "--set" => overrides.push(value("--set")),
            "--dt" => overrides.push(format!("time.dt={}", value("--dt"))),
            "--members" => members = value("--members").parse().expect("--members N"),
            "--epsilon" => epsilon = value("--epsilon").parse().expect("--epsilon E"),
            _ => {
                let (l, r) = arg.split_once(',').expect("LEFT,RIGHT");
                pairs.push((l.parse().expect("LEFT in Pa"), r.parse().expect("RIGHT in Pa")));
            }
        }
    }
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/cases/paper_triangular.toml")).unwrap();
    println!(
        "| left Pa | right Pa | 1. left end | 2. right end | 3. propagation | all three | slips A | slips F | 1/R* before A's re-slips | 1/R* before F's slips |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (left, right) in pairs {
        let mut sets = overrides.clone();
        sets.push(format!("scene.normal_traction.left={left}"));
        sets.push(format!("scene.normal_traction.right={right}"));
        let case = case::from_str(&text, &sets).unwrap();
        let runs = run_ensemble(&case, members, epsilon, available_threads());
        let mut observed: Vec<(Observations, Verdict)> = Vec::new();
        for member in &runs {
            match &member.catalog {
                Ok(catalog) => {
                    let o = Observations::measure(&catalog.events, &catalog.ruptures, member.segments);
                    let v = o.verdict();
                    observed.push((o, v));
                    if members == 1 {
                        for r in &catalog.ruptures {
                            eprintln!(
                                "rupture {:.1}-{:.1} s: segments {}-{} (nucleated at {})",
                                r.onset, r.end, r.first_segment, r.last_segment, r.nucleation_segment
                            );
                        }
                    }
                }
                Err(e) => eprintln!("{left},{right} member {}: {e}", member.index),
            }
        }
        let count = |f: fn(&Verdict) -> bool| format!("{}/{}", observed.iter().filter(|(_, v)| f(v)).count(), members);
        let med =
            |f: fn(&Observations) -> usize| median(&observed.iter().map(|(o, _)| f(o) as f64).collect::<Vec<_>>());
        let pooled_mean = |f: fn(&Observations) -> &Vec<f64>| {
            let all: Vec<f64> = observed.iter().flat_map(|(o, _)| f(o).iter().copied()).collect();
            if all.is_empty() { "-".to_string() } else { format!("{:.2}", all.iter().sum::<f64>() / all.len() as f64) }
        };
        println!(
            "| {left} | {right} | {} | {} | {} | {} | {} | {} | {} | {} |",
            count(|v| v.left_end),
            count(|v| v.right_end),
            count(|v| v.propagation),
            count(|v| v.all()),
            med(|o| o.left_onsets.len()),
            med(|o| o.right_onsets.len()),
            pooled_mean(|o| &o.left_reslip_structure),
            pooled_mean(|o| &o.right_structure),
        );
    }
}
