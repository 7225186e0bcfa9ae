//! Sweeps the triangular normal stress of the paper's case (its magnitude is only in the
//! paper's Figure 7) and prints, for each triangle, what the paper's four observations need:
//! slips of the end segments in 1000 s, 1/R* at their onsets, how far ruptures nucleated on
//! each side propagate (`first-last(nucleation)`), and the misfit of
//! [`Observations::misfit`] (0 when all hold as the paper states them).
//!
//! cargo run --release --example normal_stress_sweep -- [LEFT,RIGHT ...] [--dt DT] [--set KEY=VALUE ...]

use slipfront::case;
use slipfront::scene::{self, Needs};
use slipfront::sink::events::{EventDetector, ruptures};
use slipfront::sink::observations::Observations;

fn main() {
    let mut pairs: Vec<(f64, f64)> = Vec::new();
    let mut overrides: Vec<String> = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--set" {
            overrides.push(args.next().expect("--set KEY=VALUE"));
        } else if arg == "--dt" {
            overrides.push(format!("time.dt={}", args.next().expect("--dt DT")));
        } else {
            let (l, r) = arg.split_once(',').expect("LEFT,RIGHT");
            pairs.push((l.parse().unwrap(), r.parse().unwrap()));
        }
    }
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/cases/paper_triangular.toml")).unwrap();
    println!(
        "| left Pa | right Pa | slips A (left end) | slips F (right end) | 1/R* before A's re-slips | 1/R* before F's slips | ruptures nucleated in the left half | in the right half | misfit |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for (left, right) in pairs {
        let mut sets = overrides.clone();
        sets.push(format!("scene.normal_traction.left={left}"));
        sets.push(format!("scene.normal_traction.right={right}"));
        let case = case::from_str(&text, &sets).unwrap();
        let mut scene = scene::build(&case).unwrap();
        let segments = scene.layout().segments.len();
        let mut detector = EventDetector::new(segments, case.slip_rate_threshold(), case.events.merge_within);
        let needs = Needs { segment_state: true, ..Needs::default() };
        detector.record(&scene.frame(needs, 0.0));
        let steps = case.time.steps();
        let mut failed = None;
        for k in 1..=steps {
            let target = if k == steps { case.time.t_end } else { k as f64 * case.time.dt };
            let dt = target - scene.time();
            if let Err(e) = scene.advance(dt) {
                failed = Some(e);
                break;
            }
            detector.record(&scene.frame(needs, dt));
        }
        detector.finish();
        if let Some(e) = failed {
            println!("| {left} | {right} | failed: {e} |");
            continue;
        }
        let events = detector.events();
        let rs = ruptures(events);
        let o = Observations::measure(events, &rs, segments);
        let list = |v: &[f64]| v.iter().map(|z| format!("{z:.2}")).collect::<Vec<_>>().join(" ");
        let reach = |left_side: bool| {
            rs.iter()
                .filter(|r| (r.nucleation_segment < segments / 2) == left_side)
                .map(|r| format!("{}-{}({})", r.first_segment, r.last_segment, r.nucleation_segment))
                .collect::<Vec<_>>()
                .join(" ")
        };
        println!(
            "| {left} | {right} | {} | {} | {} | {} | {} | {} | {:.1} |",
            o.left_onsets.len(),
            o.right_onsets.len(),
            list(&o.left_reslip_structure),
            list(&o.right_structure),
            reach(true),
            reach(false),
            o.misfit()
        );
    }
}
