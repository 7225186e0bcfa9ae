//! Assembly of the block of the paper's §3.2 into `M`, `K` and the contact boundary.

use nalgebra::Vector2;

use crate::dynamics::{ContactBoundary, ContactPoint, CounterBody, LinearBody, Motion, Projection};
use crate::fem::element::{GAUSS_2, PlaneStrain, lumped_mass, stiffness};
use crate::fem::mesh::StructuredMesh;
use crate::friction::FrictionParams;
use crate::linalg::sparse::SymmetricMatrix;

/// The assembled block: the linear body and its frictional bottom.
#[derive(Debug, Clone)]
pub struct Block {
    pub mesh: StructuredMesh,
    pub body: LinearBody,
    pub contact: ContactBoundary,
}

impl Block {
    /// Contact points of segment `k` (the bottom edge of element `(k, 0)`): two Gauss points.
    pub fn segment_points(&self, segment: usize) -> std::ops::Range<usize> {
        2 * segment..2 * segment + 2
    }
}

/// Assembles the block. The top row is fixed; the bottom edge is the contact boundary with
/// two Gauss points per segment, each with its own friction state and the normal traction
/// `normal_traction(x)`; the base accelerates smoothly from rest over `base_ramp` seconds to
/// `base_velocity` along x.
///
/// Normal direction: the base is rigid, and the contact's elastic normal modulus `α_n` (the
/// normal part of `C^e`) ties the bottom to it, so a change of normal displacement changes the
/// normal traction by `-α_n Δu_y`. This spring is linear and joins `K`. The friction law sees
/// the prescribed normal traction, held constant in time as the paper assumes (§3.2), so that
/// the initial distribution alone governs the frictional strength. Without the spring the
/// bottom could sink into the base, and the free ends of the block would rotate.
pub fn assemble(
    mesh: StructuredMesh,
    material: PlaneStrain,
    density: f64,
    params: FrictionParams,
    normal_traction: impl Fn(f64) -> f64,
    base_velocity: f64,
    base_ramp: f64,
) -> Block {
    let (dx, dy) = (mesh.dx(), mesh.dy());
    // All elements are the same rectangle: one element matrix serves.
    let corners = [Vector2::new(0.0, 0.0), Vector2::new(dx, 0.0), Vector2::new(dx, dy), Vector2::new(0.0, dy)];
    let ke = stiffness(&material, &corners);
    let n = mesh.dofs();
    let mut mass = vec![0.0; n];
    let node_mass = lumped_mass(density, dx, dy);
    let mut triplets = Vec::with_capacity(64 * mesh.nx * mesh.ny);
    for j in 0..mesh.ny {
        for i in 0..mesh.nx {
            let nodes = mesh.element_nodes(i, j);
            let dofs: Vec<Option<usize>> = nodes
                .iter()
                .flat_map(|&id| match mesh.node_dofs(id) {
                    Some([x, y]) => [Some(x), Some(y)],
                    None => [None, None],
                })
                .collect();
            for (a, da) in dofs.iter().enumerate() {
                let Some(row) = *da else { continue };
                mass[row] += node_mass;
                for (b, db) in dofs.iter().enumerate() {
                    if let Some(col) = *db {
                        triplets.push((row, col, ke[(a, b)]));
                    }
                }
            }
        }
    }
    let mut points = Vec::with_capacity(2 * mesh.nx);
    let mut tractions = Vec::with_capacity(2 * mesh.nx);
    for k in 0..mesh.nx {
        let [left_x, left_y] = mesh.node_dofs(mesh.surface_node(k)).expect("bottom nodes are free");
        let [right_x, right_y] = mesh.node_dofs(mesh.surface_node(k + 1)).expect("bottom nodes are free");
        for &xi in &GAUSS_2 {
            let x = mesh.contact_point_x(k, xi);
            let shape = [0.5 * (1.0 - xi), 0.5 * (1.0 + xi)];
            let weight = 0.5 * dx;
            points.push(ContactPoint {
                tangential: Projection::new([(left_x, shape[0]), (right_x, shape[1])]),
                normal: Projection::new([(left_y, shape[0]), (right_y, shape[1])]),
                weight,
                surface: 0,
                tangent: [1.0, 0.0],
                loading_direction: if base_velocity < 0.0 { -1.0 } else { 1.0 },
            });
            tractions.push(normal_traction(x));
            // Normal spring: α_n ∫ Ñᵀ Ñ ds on the y degrees of freedom.
            let normal = [left_y, right_y];
            for a in 0..2 {
                for b in 0..2 {
                    triplets.push((normal[a], normal[b], params.alpha_n * weight * shape[a] * shape[b]));
                }
            }
        }
    }
    let body = LinearBody::new(mass, SymmetricMatrix::from_triplets(n, &triplets));
    let counter_body = CounterBody { motion: Motion::constant([base_velocity, 0.0], base_ramp), along_tangent: true };
    let contact = ContactBoundary::single(params, counter_body, points, tractions);
    Block { mesh, body, contact }
}
