//! The initial state of a body under gravity: static equilibrium with every contact stuck.
//!
//! A body with weight cannot start from rest without its weight being carried, or the first
//! step would release it as a jolt. Before the dynamics, the body's weight `f_g = ∫ Nᵀ ρ g dV`
//! is therefore balanced statically, with every loaded contact point held by the elastic part of
//! eq. (6)'s `C^e` (its main body at rest): the tangential spring `α_t` (stuck, no slip yet) and
//! the normal spring `α_n` already in `K`,
//!
//! `(K + K_t) u_g = f_g`, `K_t = Σ w α_t (t·Ñ)ᵀ (t·Ñ)` over the loaded points,
//!
//! a loaded point being one with `f_n > 0` on a held contact, and one without an initial gap on
//! an evolving contact (whose normal traction the weight itself may give); an evolving point
//! with a gap carries nothing, so its normal spring leaves `K` here.
//!
//! solved once by the sparse Cholesky factor of [`crate::linalg::sparse`]. Each point then
//! carries the tangential traction `f_t = -α_t t·Ñ u_g` (the traction the main body exerts on
//! the body, eq. 6 with `v̄ᵖ = 0`) and its normal spring `-α_n n·Ñ u_g`.
//!
//! The run starts at rest in that equilibrium: the body is linear, so the dynamics of eq. (14)
//! is that of the displacement from `u_g`, and the weight, balanced once, leaves it; what
//! gravity changes is the contact's initial tangential traction, which joins the friction state
//! ([`crate::dynamics::System::start_from_tractions`]).

use crate::fem::assembly::Assembled;
use crate::linalg::sparse::{Cholesky, SymmetricMatrix};

/// The static equilibrium under gravity.
#[derive(Debug, Clone, PartialEq)]
pub struct Equilibrium {
    /// `u_g` on the free degrees of freedom (m), from the unloaded mesh.
    pub displacement: Vec<f64>,
    /// Each contact point's tangential traction `f_t` (Pa), along its tangent; 0 where
    /// `f_n = 0` (such a point carries no shear).
    pub traction_t: Vec<f64>,
    /// Each contact point's normal spring traction `-α_n n·Ñ u_g` (Pa, positive in
    /// compression): the share of the weight the contact carries, which the prescribed normal
    /// traction of a held contact does not follow; an evolving one starts from the prescribed
    /// traction plus it.
    pub traction_n: Vec<f64>,
}

impl Equilibrium {
    /// `Σ w f` over the contact points of `assembled` for tractions `traction` (N/m, or N
    /// around a ring).
    pub fn total(assembled: &Assembled, traction: &[f64]) -> f64 {
        assembled.contact.points.iter().zip(traction).map(|(p, f)| p.weight * f).sum()
    }
}

/// Solves `(K + K_t) u_g = f_g` for `assembled` (module documentation); `None` without
/// gravity. Refused, saying why, where the body is not held (its operator is singular: a part
/// that no boundary and no loaded contact holds would fall).
pub fn under_gravity(assembled: &Assembled) -> Option<Result<Equilibrium, String>> {
    let force = assembled.body_force.as_ref()?;
    Some(solve(assembled, force))
}

fn solve(assembled: &Assembled, force: &[f64]) -> Result<Equilibrium, String> {
    let (body, contact) = (&assembled.body, &assembled.contact);
    let n = body.dofs();
    let mut triplets: Vec<(usize, usize, f64)> = body.stiffness.entries().collect();
    for (k, point) in contact.points.iter().enumerate() {
        if contact.evolves(k) && contact.gap[k] > 0.0 {
            let spring = -point.weight * contact.params(k).alpha_n;
            for (a, ca) in point.normal.terms() {
                for (b, cb) in point.normal.terms() {
                    triplets.push((a, b, spring * ca * cb));
                }
            }
        }
        if !loaded(contact, k) {
            continue;
        }
        let spring = point.weight * contact.params(k).alpha_t;
        for (a, ca) in point.tangential.terms() {
            for (b, cb) in point.tangential.terms() {
                triplets.push((a, b, spring * ca * cb));
            }
        }
    }
    let matrix = SymmetricMatrix::from_triplets(n, &triplets);
    let not_held = "the body has no static equilibrium under scene.gravity: some part of it is held by no fixed \
                    boundary and no loaded contact, and would fall; fix it, or give its contacts a normal traction";
    let cholesky = Cholesky::new(&matrix).map_err(|_| not_held.to_string())?;
    let mut displacement = force.to_vec();
    cholesky.solve_in_place(&mut displacement);
    let mut residual = vec![0.0; n];
    matrix.mul_vec(&displacement, &mut residual);
    let scale = force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    let imbalance = residual.iter().zip(force).fold(0.0_f64, |m, (r, f)| m.max((r - f).abs()));
    if imbalance.is_nan() || imbalance > 1e-8 * scale {
        return Err(not_held.to_string());
    }
    let traction_t = (0..contact.points.len())
        .map(|k| {
            if loaded(contact, k) {
                -contact.params(k).alpha_t * contact.points[k].tangential.apply(&displacement)
            } else {
                0.0
            }
        })
        .collect();
    let traction_n = (0..contact.points.len())
        .map(|k| -contact.params(k).alpha_n * contact.points[k].normal.apply(&displacement))
        .collect();
    Ok(Equilibrium { displacement, traction_t, traction_n })
}

/// Whether contact point `k` is held stuck in the equilibrium: pressed by a held normal
/// traction, or without a gap on an evolving contact.
pub fn loaded(contact: &crate::dynamics::ContactBoundary, k: usize) -> bool {
    if contact.evolves(k) { contact.gap[k] <= 0.0 } else { contact.traction_n[k] > 0.0 }
}
