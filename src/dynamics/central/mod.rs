//! Explicit central differences for the body, with the implicit friction update of each step.
//!
//! Wilson's θ method ([`crate::dynamics::wilson`]) solves a system of the whole body per step; on a fine
//! mesh that solve is most of the cost (a 1000 × 100 block: two sparse triangular solves with
//! a factor of 200 000 unknowns, about 0.15 s a step). Dynamic rupture codes integrate the body
//! explicitly instead, with a diagonal (lumped) mass, so that a step costs one product with `K`
//! (e.g. Day et al., *Comparison of finite difference and boundary integral solutions to
//! three-dimensional spontaneous rupture*, JGR 110 (2005); Kaneko, Lapusta & Ampuero, JGR 113
//! (2008)). This module does that for the total form of eq. (14), `M a + K u = f⁰ + f_c - f_c(0)`,
//! by the velocity form of central differences (Newmark's β = 0, γ = ½):
//!
//! * `v_{n+½} = v_n + ½h a_n`, `u_{n+1} = u_n + h v_{n+½}`;
//! * each contact point is advanced over `[t_n, t_{n+1}]` by the paper's implicit friction
//!   update ([`crate::friction::update`], eqs. 4–9 over the step) with the relative slip
//!   increment `Ñ (u_{n+1} - u_n) - Δu_base` of eq. (13), which is now known;
//! * `a_{n+1} = M⁻¹ (f⁰(t_{n+1}) - K u_{n+1} + f_c - f_c(0))`, `v_{n+1} = v_{n+½} + ½h a_{n+1}`.
//!
//! The scheme is second order and does not dissipate: the body's modes keep their energy, where
//! Wilson's `θ = 1.4` damps those with `ωΔt` near 1 and above. It is stable while
//! `h ω_max ≤ 2`, for the highest angular frequency `ω_max` of `M⁻¹ (K + K_t)`, where `K_t`
//! holds the contact's elastic tangential springs `α_t ∫ Ñᵀ Ñ ds` (the friction update never
//! responds more stiffly than `α_t`). [`highest_frequency`] finds `ω_max` by Lanczos'
//! iteration; each frame of the case's `dt` is then taken as the fewest equal sub-steps of at
//! most [`STABILITY_SHARE`]` × 2/ω_max`. On the paper's 10 × 1 mesh `ω_max ≈ 45 rad/s` and a
//! frame of 0.01 s is one step; on 1000 × 100 `ω_max ≈ 470 rad/s`, three sub-steps of 3.3 ms.
//!
//! A friction update that fails in a way shorter steps cure (`1/R*` leaving its range in the
//! trapezoidal rule of eq. 4, the consistency solve not converging) is repeated in two halves
//! of the same slip, down to `h / 2^MAX_HALVINGS`; the body's step is not repeated.

mod kick;

use rayon::prelude::*;

use kick::{Forces, Kick, Rows};

use crate::dynamics::body::{LinearBody, LoadAt};
use crate::dynamics::contact::ContactBoundary;
use crate::dynamics::control::AdaptiveError;
use crate::dynamics::error::{MAX_HALVINGS, StepError};
use crate::dynamics::integrator::Integrator;
use crate::dynamics::memory::{CentralMemory, IntegratorMemory, check_points, mismatch};
use crate::dynamics::state::State;
use crate::dynamics::system::System;
use crate::friction::{ContactState, FrictionError, FrictionParams, Restart, Update, update_with};
use crate::linalg::lanczos::largest_eigenvalue;
use crate::linalg::stencil::TemplateMatrix;

/// Share of the stability limit `2/ω_max` that the sub-steps use: it covers Lanczos'
/// estimate, which approaches `ω_max` from below (see [`highest_frequency`]).
pub const STABILITY_SHARE: f64 = 0.9;

/// Lanczos iterations for `ω_max`.
const LANCZOS_STEPS: usize = 100;

/// What central differences keep between steps.
pub struct CentralDifference {
    /// The highest angular frequency of the body with elastic contact springs (rad/s).
    omega_max: f64,
    /// `K` by runs of equal node stencils, where the body has node pairs; else its compressed
    /// form serves.
    stiffness: Option<TemplateMatrix>,
    /// The runs of `stiffness` in one group per parallel task.
    chunks: Vec<(usize, usize, usize)>,
    /// `K u`.
    stiffness_force: Vec<f64>,
    /// `u` with each node's two values exchanged (see [`TemplateMatrix`]).
    swapped: Vec<f64>,
    /// `u` and its swapped copy after the next drift, written while the product reads `u`.
    next_displacement: Vec<f64>,
    next_swapped: Vec<f64>,
    /// `1/m` per degree of freedom.
    inverse_mass: Vec<f64>,
    /// The degrees of freedom the contact points act on, ascending.
    contact_dofs: Vec<usize>,
    /// `f_c - f_c(0)`: nonzero only on `contact_dofs`.
    contact_force: Vec<f64>,
    /// Each contact point's interpolated displacement `Ñ u` at the last step.
    contact_displacement: Vec<f64>,
    /// Each contact point's last consistency solve, to start its next.
    restarts: Vec<Option<Restart>>,
    /// Each contact point's update of the step.
    updates: Vec<Result<Update, FrictionError>>,
    /// Degrees of freedom per parallel task: all of them on small bodies.
    chunk: usize,
    /// Contact points per parallel task.
    point_chunk: usize,
}

impl CentralDifference {
    fn new(body: &LinearBody, contact: &ContactBoundary, displacement: &[f64]) -> Self {
        // The tangential degrees of freedom, and the normal ones where a contact's normal evolves.
        let mut contact_dofs: Vec<usize> = contact
            .points
            .iter()
            .enumerate()
            .flat_map(|(k, p)| {
                let normal = if contact.evolves(k) { p.normal } else { Default::default() };
                p.tangential.terms().chain(normal.terms().collect::<Vec<_>>()).map(|(dof, _)| dof).collect::<Vec<_>>()
            })
            .collect();
        contact_dofs.sort_unstable();
        contact_dofs.dedup();
        let parallel = body.dofs() >= PARALLEL_FROM_DOFS;
        let stiffness = TemplateMatrix::new(&body.stiffness);
        let chunks = stiffness.as_ref().map_or_else(Vec::new, |s| s.chunks(if parallel { CHUNKS } else { 1 }));
        Self {
            omega_max: highest_frequency(body, contact),
            stiffness,
            chunks,
            stiffness_force: vec![0.0; body.dofs()],
            swapped: vec![0.0; body.dofs()],
            next_displacement: vec![0.0; body.dofs()],
            next_swapped: vec![0.0; body.dofs()],
            inverse_mass: body.mass.iter().map(|m| 1.0 / m).collect(),
            contact_dofs,
            contact_force: vec![0.0; body.dofs()],
            contact_displacement: contact.points.iter().map(|p| p.interpolate(displacement)).collect(),
            restarts: vec![None; contact.points.len()],
            updates: vec![Err(FrictionError::NotConverged { residual: f64::NAN }); contact.points.len()],
            // Even, so that each chunk holds whole nodes.
            chunk: if parallel { 2 * body.dofs().div_ceil(16) } else { body.dofs().max(2) },
            point_chunk: if parallel { 64 } else { contact.points.len().max(1) },
        }
    }

    /// The largest sub-step taken (s).
    pub fn stable_step(&self) -> f64 {
        2.0 * STABILITY_SHARE / self.omega_max
    }
}

/// The highest angular frequency `ω_max` (rad/s) of `M⁻¹ (K + K_t)`, `K_t = α_t Σ w Ñᵀ Ñ` the
/// contact's elastic tangential springs: the square root of the largest eigenvalue of the
/// symmetric `M^{-½} (K + K_t) M^{-½}`, by [`LANCZOS_STEPS`] steps of Lanczos' iteration
/// ([`largest_eigenvalue`]). The largest Ritz value approaches the largest eigenvalue from
/// below; `tests/central_difference.rs` compares it with a dense eigensolver.
pub fn highest_frequency(body: &LinearBody, contact: &ContactBoundary) -> f64 {
    let n = body.dofs();
    let scale: Vec<f64> = body.mass.iter().map(|m| 1.0 / m.sqrt()).collect();
    let mut scaled = vec![0.0; n];
    let apply = |x: &[f64], y: &mut [f64]| {
        scaled.iter_mut().zip(x.iter().zip(&scale)).for_each(|(s, (x, c))| *s = x * c);
        body.stiffness.mul_vec(&scaled, y);
        for (k, point) in contact.points.iter().enumerate() {
            point.scatter(contact.params(k).alpha_t * point.weight * point.interpolate(&scaled), y);
        }
        y.iter_mut().zip(&scale).for_each(|(y, c)| *y *= c);
    };
    largest_eigenvalue(n, LANCZOS_STEPS, apply).sqrt()
}

impl CentralDifference {
    /// Central differences for `system`, from its current state.
    pub fn for_system(system: &System) -> Self {
        Self::new(&system.body, &system.contact, &system.state.displacement)
    }

    /// Advances by `dt` in the fewest equal sub-steps of at most [`CentralDifference::stable_step`],
    /// reported as one step: `plastic_increment` holds the slip of all of them. Each sub-step
    /// is a drift, the contact's update over it and a kick; the kick between two sub-steps
    /// does the next one's drift in the same pass ([`Kick::WholeAndDrift`]).
    pub fn step(&mut self, system: &mut System, dt: f64) -> Result<(), StepError> {
        let substeps = (dt / self.stable_step()).ceil().max(1.0) as u64;
        let h = dt / substeps as f64;
        let start = system.state.time;
        system.state.plastic_increment.iter_mut().for_each(|p| *p = 0.0);
        self.drift(&mut system.state, h);
        for i in 0..substeps {
            let time = start + i as f64 * h;
            self.update_contact(system, time, h)?;
            let kick = if i + 1 < substeps { Kick::WholeAndDrift } else { Kick::Half };
            if !self.kick(system, time + h, h, kick) {
                return Err(StepError::NonFinite);
            }
        }
        let s = &mut system.state;
        s.time = start + dt;
        s.step += 1;
        Ok(())
    }

    /// `v += h/2 a`, `u += h v`, and the swapped copy of `u` the stencil product reads.
    fn drift(&mut self, s: &mut State, h: f64) {
        let chunk = self.chunk;
        s.displacement
            .par_chunks_mut(chunk)
            .zip(s.velocity.par_chunks_mut(chunk))
            .zip(s.acceleration.par_chunks(chunk))
            .zip(self.swapped.par_chunks_mut(chunk))
            .for_each(|(((displacement, velocity), acceleration), swapped)| {
                for ((u, v), a) in displacement.iter_mut().zip(velocity.iter_mut()).zip(acceleration) {
                    *v += 0.5 * h * a;
                    *u += h * *v;
                }
                TemplateMatrix::swap_pairs(displacement, swapped);
            });
    }

    /// Every contact point's implicit friction update over the sub-step (eq. 13), and the
    /// contact forces `f_c - f_c(0)` they exert.
    fn update_contact(&mut self, system: &mut System, time: f64, h: f64) -> Result<(), StepError> {
        let s = &mut system.state;
        let contact = &system.contact;
        let base = contact.base_slips(time, time + h);
        let (points, displacement) = (&contact.points, &s.displacement);
        self.updates
            .par_iter_mut()
            .zip(s.contact.par_iter())
            .zip(self.restarts.par_iter())
            .zip(self.contact_displacement.par_iter_mut())
            .enumerate()
            .with_min_len(self.point_chunk)
            .for_each(|(k, (((update, state), &restart), previous))| {
                let now = points[k].interpolate(displacement);
                let slip = now - *previous - base[k];
                *previous = now;
                let normal =
                    contact.evolves(k).then(|| (state.traction_n, contact.normal_traction_at(k, displacement)));
                *update = update_in_halves(contact.params(k), state, slip, normal, h, restart, 0);
            });
        for &dof in &self.contact_dofs {
            self.contact_force[dof] = -system.initial_contact_force[dof];
        }
        contact.scatter_normal_corrections(displacement, &mut self.contact_force);
        for (k, point) in points.iter().enumerate() {
            let updated = match &self.updates[k] {
                Ok(updated) => *updated,
                Err(error) => return Err(StepError::Friction { point: k, state: s.contact[k], error: error.clone() }),
            };
            s.contact[k] = updated.state;
            s.plastic_increment[k] += updated.plastic_increment;
            self.restarts[k] = updated.restart;
            point.scatter(point.weight * updated.state.traction_t, &mut self.contact_force);
        }
        Ok(())
    }

    /// `a = M⁻¹ (f⁰ - K u + f_c - f_c(0))` at `t` by chunks of nodes (`K u` of the chunk, then
    /// its rows), and the kick `kick` with it; after [`Kick::WholeAndDrift`] the next drift's
    /// displacement becomes `u`. After [`Kick::Half`], whether every displacement and velocity
    /// is finite.
    fn kick(&mut self, system: &mut System, t: f64, h: f64, kick: Kick) -> bool {
        let s = &mut system.state;
        let body = &system.body;
        let load_at = body.load_at(t);
        let load_sum: Vec<f64>;
        let load = match &load_at {
            LoadAt::None => None,
            LoadAt::One(pattern, g) => Some((*pattern, *g)),
            LoadAt::Several(_) => {
                load_sum = (0..body.dofs()).map(|r| load_at.at(r)).collect();
                Some((&load_sum[..], 1.0))
            }
        };
        let mut buffers = [
            std::mem::take(&mut self.stiffness_force),
            std::mem::take(&mut self.next_displacement),
            std::mem::take(&mut self.next_swapped),
        ];
        let forces = Forces {
            contact_force: &self.contact_force,
            inverse_mass: &self.inverse_mass,
            load,
            displacement: &s.displacement,
        };
        let [stiffness_force, next_displacement, next_swapped] = &mut buffers;
        let all_rows = Rows {
            first: 0,
            acceleration: &mut s.acceleration,
            velocity: &mut s.velocity,
            stiffness_force,
            next_displacement,
            next_swapped,
        };
        let finite = match &self.stiffness {
            Some(stiffness) => {
                let tasks = split_rows(all_rows, &self.chunks);
                tasks
                    .into_par_iter()
                    .zip(&self.chunks)
                    .map(|(rows, &(begin, end, _))| {
                        stiffness.mul_chunk((begin, end), forces.displacement, &self.swapped, rows.stiffness_force);
                        rows.kick(kick, h, &forces)
                    })
                    .reduce(|| true, |a, b| a && b)
            }
            None => {
                body.stiffness.mul_vec(forces.displacement, all_rows.stiffness_force);
                all_rows.kick(kick, h, &forces)
            }
        };
        let [stiffness_force, next_displacement, next_swapped] = buffers;
        self.stiffness_force = stiffness_force;
        (self.next_displacement, self.next_swapped) = (next_displacement, next_swapped);
        if kick == Kick::WholeAndDrift {
            std::mem::swap(&mut s.displacement, &mut self.next_displacement);
            std::mem::swap(&mut self.swapped, &mut self.next_swapped);
        }
        finite
    }
}

/// `rows` split into the consecutive chunks `(_, _, nodes)` of two rows per node.
fn split_rows<'a>(mut rows: Rows<'a>, chunks: &[(usize, usize, usize)]) -> Vec<Rows<'a>> {
    let mut parts = Vec::with_capacity(chunks.len());
    for &(_, _, nodes) in chunks {
        let n = 2 * nodes;
        let (acceleration, a_rest) = std::mem::take(&mut rows.acceleration).split_at_mut(n);
        let (velocity, v_rest) = std::mem::take(&mut rows.velocity).split_at_mut(n);
        let (stiffness_force, k_rest) = std::mem::take(&mut rows.stiffness_force).split_at_mut(n);
        let (next_displacement, u_rest) = std::mem::take(&mut rows.next_displacement).split_at_mut(n);
        let (next_swapped, s_rest) = std::mem::take(&mut rows.next_swapped).split_at_mut(n);
        parts.push(Rows {
            first: rows.first,
            acceleration,
            velocity,
            stiffness_force,
            next_displacement,
            next_swapped,
        });
        rows = Rows {
            first: rows.first + n,
            acceleration: a_rest,
            velocity: v_rest,
            stiffness_force: k_rest,
            next_displacement: u_rest,
            next_swapped: s_rest,
        };
    }
    parts
}

impl Integrator for CentralDifference {
    fn advance(&mut self, system: &mut System, limit: f64) -> Result<f64, AdaptiveError> {
        self.step(system, limit).map(|()| limit).map_err(AdaptiveError::Step)
    }

    fn memory(&self) -> IntegratorMemory {
        IntegratorMemory::Central(CentralMemory {
            restarts: self.restarts.clone(),
            contact_displacement: self.contact_displacement.clone(),
            omega_max: self.omega_max,
        })
    }

    fn restore(&mut self, system: &System, memory: IntegratorMemory) -> Result<(), String> {
        let IntegratorMemory::Central(memory) = memory else {
            return Err(mismatch(format!("saved by {}, the case steps with central differences", memory.name())));
        };
        let points = system.contact.points.len();
        check_points(&memory.restarts, points, "restarts")?;
        check_points(&memory.contact_displacement, points, "contact displacements")?;
        if !(memory.omega_max.is_finite() && memory.omega_max > 0.0) {
            return Err(mismatch("the highest frequency is not a positive number"));
        }
        self.restarts = memory.restarts;
        self.contact_displacement = memory.contact_displacement;
        self.omega_max = memory.omega_max;
        Ok(())
    }
}

/// Groups of rows per product with `K` on large bodies: a group's `K u`, velocities and
/// displacements stay in the core's cache between the product and the kick.
const CHUNKS: usize = 64;

/// Degrees of freedom from which a step's loops are shared among threads (`rayon`): below
/// this, handing out the work costs more than it saves.
const PARALLEL_FROM_DOFS: usize = 20_000;

/// The friction update of one point over `h`, repeated as two halves of the slip over `h/2`
/// where shorter steps cure its failure (see the module documentation). An evolving normal
/// traction goes from `normal.0` to `normal.1` over the step (through its mean in halves).
fn update_in_halves(
    params: &FrictionParams,
    state: &ContactState,
    slip: f64,
    normal: Option<(f64, f64)>,
    h: f64,
    restart: Option<Restart>,
    depth: u32,
) -> Result<Update, FrictionError> {
    match update_with(params, state, slip, normal.map(|n| n.1), h, restart) {
        Err(error) if depth < MAX_HALVINGS && error.cured_by_shorter_steps() => {
            let (first_half, second_half) = match normal {
                Some((start, end)) => {
                    let middle = 0.5 * (start + end);
                    (Some((start, middle)), Some((middle, end)))
                }
                None => (None, None),
            };
            let first = update_in_halves(params, state, 0.5 * slip, first_half, 0.5 * h, None, depth + 1)?;
            let second =
                update_in_halves(params, &first.state, 0.5 * slip, second_half, 0.5 * h, first.restart, depth + 1)?;
            Ok(Update { plastic_increment: first.plastic_increment + second.plastic_increment, ..second })
        }
        result => result,
    }
}
