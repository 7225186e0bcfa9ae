//! Perturbed ensembles: what a case says about its later slip events.
//!
//! A block's stick-slip sequence is chaotic once slips begin. In the paper's case a change of the
//! initial `1/R*` by 1e-12 stays at rounding level (1e-11 Pa of traction) for the first 380 s,
//! then grows by an order of magnitude every 5–10 s through the left end's first slips and
//! reaches pascals by 470 s; from then on the event sequence is another one
//! (`cargo run --release --example perturbation`). A changed time step, Newton tolerance or
//! compiler is such a perturbation too. What a single run shows after the first slips is one
//! member of a family; a statement about those events ("the right end slips once") is a
//! statement about the family, and is tested on an ensemble.
//!
//! Member `k` starts from the case with its initial degree of structure moved into the interior
//! of `[1, μ_s/μ_k]` by `k ε (μ_s/μ_k - 1)`; member 0 is the case itself.

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::case::Case;
use crate::catalog::events::Catalog;
use crate::run::{LoopOptions, Outcome, run};
use crate::scene::{self, RunError};

/// One member of an ensemble.
#[derive(Debug)]
pub struct Member {
    /// Its index; 0 is the unperturbed case.
    pub index: usize,
    /// Its initial `1/R*`.
    pub structure0: f64,
    /// Contact segments of its scene.
    pub segments: usize,
    /// Its event catalog (with `1/R*` at every onset), or why it stopped.
    pub catalog: Result<Catalog, RunError>,
}

/// `case` with its initial `1/R*` moved `index × epsilon` of its range into the interior.
pub fn perturbed(case: &Case, index: usize, epsilon: f64) -> Case {
    let mut member = case.clone();
    let f = &mut member.friction;
    let upper = f.mu_s / f.mu_k;
    let towards_interior = if f.structure0 < 0.5 * (1.0 + upper) { 1.0 } else { -1.0 };
    f.structure0 = (f.structure0 + towards_interior * index as f64 * epsilon * (upper - 1.0)).clamp(1.0, upper);
    member
}

/// Runs `case` with only the event catalog observing it; returns the catalog and the number of
/// contact segments.
pub fn catalog(case: &Case) -> Result<(Catalog, usize), RunError> {
    let mut scene = scene::build(case)?;
    let segments = scene.layout().segments.len();
    let options = LoopOptions::for_case(case);
    match run(scene.as_mut(), &case.time, &mut [], options) {
        Outcome::Completed { catalog, .. } => Ok((catalog, segments)),
        Outcome::Failed { error, .. } => Err(error),
        Outcome::Interrupted { .. } | Outcome::Sink(_) => unreachable!("no interrupt flag and no sinks"),
    }
}

/// Runs `members` perturbed copies of `case` (see the module docs) on `threads` threads and
/// returns them in order of their index.
pub fn run_ensemble(case: &Case, members: usize, epsilon: f64, threads: usize) -> Vec<Member> {
    let cases: Vec<Case> = (0..members).map(|index| perturbed(case, index, epsilon)).collect();
    run_cases(&cases, threads)
}

/// Runs `cases` with only their event catalogs observing them, on `threads` threads; member `i`
/// is `cases[i]`, returned in order.
pub fn run_cases(cases: &[Case], threads: usize) -> Vec<Member> {
    let next = AtomicUsize::new(0);
    let done = Mutex::new(Vec::with_capacity(cases.len()));
    std::thread::scope(|scope| {
        for _ in 0..threads.clamp(1, cases.len().max(1)) {
            scope.spawn(|| {
                loop {
                    let index = next.fetch_add(1, Ordering::SeqCst);
                    let Some(member) = cases.get(index) else { break };
                    let (catalog, segments) = match catalog(member) {
                        Ok((catalog, segments)) => (Ok(catalog), segments),
                        Err(e) => (Err(e), 0),
                    };
                    let member = Member { index, structure0: member.friction.structure0, segments, catalog };
                    done.lock().unwrap_or_else(|e| e.into_inner()).push(member);
                }
            });
        }
    });
    let mut done = done.into_inner().unwrap_or_else(|e| e.into_inner());
    done.sort_by_key(|m| m.index);
    done
}

/// The machine's parallelism, for [`run_ensemble`].
pub fn available_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
