//! Twin runs of a case, the second with `--set` overrides (e.g. a perturbed `structure0`):
//! prints, every `--every` seconds, the largest difference in segment traction and slip
//! rate between them, so that the growth of a perturbation can be read off.
//!
//! cargo run --release --example perturbation -- CASE.toml --set friction.structure0=2.000000000002 [--every 10]

use slipfront::case;
use slipfront::frame::Needs;
use slipfront::scene;

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("CASE.toml");
    // Wilson's method (with which the ensemble docs measured the growth) unless a `--set
    // time.integrator=...` names another.
    let mut sets = vec!["time.integrator=wilson".to_string()];
    let mut every = 10.0;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--set" => sets.push(args.next().expect("KEY=VALUE")),
            "--every" => every = args.next().expect("SECONDS").parse().expect("number"),
            _ => panic!("unknown argument {a}"),
        }
    }
    let text = std::fs::read_to_string(&path).unwrap();
    let a_case = case::from_str(&text, &sets[..1]).unwrap();
    let b_case = case::from_str(&text, &sets).unwrap();
    let mut a = scene::build(&a_case).unwrap();
    let mut b = scene::build(&b_case).unwrap();
    let needs = Needs { segment_state: true, ..Needs::default() };
    let steps = a_case.time.steps();
    let mut next_print = every;
    println!("t_s,max_dtraction_pa,max_dslip_rate_m_s,dfriction_force,max_slip_rate_a");
    for k in 1..=steps {
        let target = if k == steps { a_case.time.t_end } else { k as f64 * a_case.time.dt };
        let dt = target - a.time();
        a.advance(dt).unwrap();
        b.advance(dt).unwrap();
        if target >= next_print - 1e-9 {
            next_print += every;
            let fa = a.frame(needs, dt);
            let fb = b.frame(needs, dt);
            let dtr = fa
                .segments
                .iter()
                .zip(&fb.segments)
                .map(|(x, y)| (x.traction_t - y.traction_t).abs())
                .fold(0.0, f64::max);
            let dsr = fa
                .segments
                .iter()
                .zip(&fb.segments)
                .map(|(x, y)| (x.slip_rate - y.slip_rate).abs())
                .fold(0.0, f64::max);
            let sr = fa.segments.iter().map(|x| x.slip_rate).fold(0.0, f64::max);
            println!("{target:.2},{dtr:.3e},{dsr:.3e},{:.3e},{sr:.3e}", fa.friction_force - fb.friction_force);
        }
    }
}
