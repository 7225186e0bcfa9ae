//! Assembly of a body into the equation of motion (14): lumped `M`, `K`, the external loads and
//! the contact boundary `S_c` (paper §2.2).
//!
//! Every body goes through here, the paper's block included ([`crate::fem::rectangle`]): the
//! cells in the mesh's canonical order, each element matrix computed from its corners relative
//! to its first, so that a mesh's numbering and its position in the plane do not change the
//! sums; then each contact's normal springs, segment by segment along its chain.

use nalgebra::Vector2;

use crate::dynamics::contact::padded;
use crate::dynamics::{
    ContactBoundary, ContactPoint, ContactSurface, LinearBody, Load, LoadHistory, MainBody, Motion, NormalBehaviour,
    Projection,
};
use crate::fem::axisymmetric;
use crate::fem::body_mesh::{Cell, Mesh};
use crate::fem::curve::{CurvePoint, Segment, segments};
use crate::fem::element::{
    PlaneStrain, lumped_mass, shape_integrals, signed_double_area, stiffness, triangle_stiffness,
};
use crate::friction::FrictionParams;
use crate::linalg::sparse::SymmetricMatrix;

/// What a region of the body is made of.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    pub elasticity: PlaneStrain,
    /// `ρ` (kg/m³).
    pub density: f64,
}

/// A boundary whose displacement is prescribed (eq. 10's `S_v`): the `components` (x, y) of
/// its `nodes` follow `motion` from their initial position; at rest, they are fixed.
#[derive(Debug, Clone)]
pub struct Constraint {
    pub name: String,
    pub nodes: Vec<usize>,
    pub components: [bool; 2],
    pub motion: Motion,
}

/// A traction prescribed on a chain of boundary edges (eq. 10's `S_t`).
#[derive(Debug, Clone)]
pub struct TractionLoad {
    pub chain: Vec<usize>,
    pub traction: Traction,
    /// The traction rises smoothly from 0 over this time (s); 0 applies it at once.
    pub ramp: f64,
    /// It acts this long (s), then falls back to 0 over `ramp`; `None`: to the end.
    pub duration: Option<f64>,
}

/// The traction of a [`TractionLoad`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Traction {
    /// A vector in x and y (Pa).
    Vector([f64; 2]),
    /// A pressure (Pa), pushing along the inward normal.
    Pressure(f64),
}

/// A frictional contact along a chain of boundary edges, against a rigid main body.
pub struct ContactDefinition<'a> {
    pub name: String,
    pub chain: Vec<usize>,
    pub params: FrictionParams,
    pub main_body: MainBody,
    /// The normal traction `f_n` (Pa) at a Gauss point: held constant, or its initial value.
    pub normal_traction: Box<dyn Fn(CurvePoint) -> f64 + 'a>,
    /// Whether `f_n` is held or evolves.
    pub normal: NormalBehaviour,
    /// The initial normal gap (m) at a Gauss point of an evolving contact; none: 0.
    pub gap: Option<Box<dyn Fn(CurvePoint) -> f64 + 'a>>,
}

/// A body to assemble: its mesh, each cell's material, its boundaries and contacts.
pub struct BodyDefinition<'a> {
    pub mesh: &'a Mesh,
    /// The material of each cell, in the mesh's order.
    pub materials: Vec<Material>,
    pub constraints: Vec<Constraint>,
    pub tractions: Vec<TractionLoad>,
    pub contacts: Vec<ContactDefinition<'a>>,
    /// Whether the mesh is the half-plane `r = x ≥ 0`, `z = y` of a body of revolution
    /// ([`crate::fem::axisymmetric`]): every integral weighted by `2π r`, `u_r = 0` on the
    /// axis, forces in N. Otherwise plane strain, per unit thickness.
    pub axisymmetric: bool,
    /// The acceleration of gravity `g` (m/s², in the mesh's x and y), whose body force `ρ g`
    /// the body starts in equilibrium with ([`crate::fem::equilibrium`]); `None`: weightless.
    pub gravity: Option<[f64; 2]>,
}

/// The name of the constraint that holds `u_r = 0` on the axis of an axisymmetric body.
pub const AXIS: &str = "the axis (r = 0)";

/// Where each node's displacement lives: a free unknown, or a prescribed motion.
#[derive(Debug, Clone, PartialEq)]
pub enum NodeDof {
    Free(usize),
    /// Following constraint `k`'s motion ([`Dofs::motions`]).
    Prescribed(usize),
}

/// The degrees of freedom of every node's x and y, and the motions of the prescribed ones.
#[derive(Debug, Clone)]
pub struct Dofs {
    pub nodes: Vec<[NodeDof; 2]>,
    pub motions: Vec<Motion>,
    pub free: usize,
}

impl Dofs {
    /// The displacement of `node` at `t` (m) for the free unknowns `u`.
    #[inline]
    pub fn displacement(&self, node: usize, u: &[f64], t: f64) -> [f64; 2] {
        let component = |c: usize| match &self.nodes[node][c] {
            NodeDof::Free(i) => u[*i],
            NodeDof::Prescribed(k) if self.motions[*k].is_at_rest() => 0.0,
            NodeDof::Prescribed(k) => self.motions[*k].displacement_at(t)[c],
        };
        [component(0), component(1)]
    }

    fn free(&self, node: usize, component: usize) -> Option<usize> {
        match self.nodes[node][component] {
            NodeDof::Free(i) => Some(i),
            NodeDof::Prescribed(_) => None,
        }
    }
}

/// The assembled body.
pub struct Assembled {
    pub body: LinearBody,
    pub contact: ContactBoundary,
    pub dofs: Dofs,
    /// Each contact's segments, in order along its chain; contact points `2k`, `2k + 1` of
    /// the boundary belong to the `k`-th segment counted over all contacts.
    pub contacts: Vec<Vec<Segment>>,
    /// The body force of gravity on the free degrees of freedom, `∫ Nᵀ ρ g dV` (N/m per unit
    /// thickness, N for a ring); `None` without gravity. It is not one of `body.loads`: the
    /// run starts in equilibrium with it, and the unknowns are measured from there.
    pub body_force: Option<Vec<f64>>,
}

/// Why a body cannot be assembled: conflicting boundaries, a moving boundary on a contact.
#[derive(Debug, Clone, PartialEq)]
pub struct AssemblyError(pub String);

impl std::fmt::Display for AssemblyError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// Checks what [`assemble`] refuses without assembling: boundaries that prescribe a node's
/// motion differently, a contact node that a boundary moves.
pub fn check(definition: &BodyDefinition) -> Result<(), AssemblyError> {
    let dofs = number(definition, &constraints(definition))?;
    for contact in &definition.contacts {
        refuse_moving_nodes(contact, &dofs, &definition.mesh.nodes)?;
    }
    Ok(())
}

/// Assembles `definition` (module documentation).
pub fn assemble(definition: &BodyDefinition) -> Result<Assembled, AssemblyError> {
    let mesh = definition.mesh;
    let constraints = constraints(definition);
    let dofs = number(definition, &constraints)?;
    let n = dofs.free;
    let mut mass = vec![0.0; n];
    let mut body_force = definition.gravity.map(|_| vec![0.0; n]);
    let mut triplets = Vec::with_capacity(64 * mesh.cells.len());
    // -K_fp per prescribed component that moves, summed over the constraint's nodes.
    let mut moving: Vec<[Option<Vec<f64>>; 2]> = constraints
        .iter()
        .map(|c| c.components.map(|on| (on && !c.motion.is_at_rest()).then(|| vec![0.0; n])))
        .collect();
    let mut congruent = Congruent::new(&mesh.nodes, definition.axisymmetric);
    for (cell, material) in mesh.cells.iter().zip(&definition.materials) {
        let parts = congruent.element(cell, &mesh.nodes, material, definition);
        let matrix = &parts.stiffness;
        let nodes = cell.nodes();
        let dof_of = |a: usize| &dofs.nodes[nodes[a / 2]][a % 2];
        for a in 0..2 * nodes.len() {
            let NodeDof::Free(row) = *dof_of(a) else { continue };
            mass[row] += parts.mass[a / 2];
            if let (Some(force), Some(g)) = (&mut body_force, definition.gravity) {
                force[row] += parts.weight[a / 2] * g[a % 2];
            }
            for b in 0..2 * nodes.len() {
                match *dof_of(b) {
                    NodeDof::Free(col) => triplets.push((row, col, matrix[(a, b)])),
                    NodeDof::Prescribed(k) => {
                        if let Some(pattern) = &mut moving[k][b % 2] {
                            pattern[row] -= matrix[(a, b)];
                        }
                    }
                }
            }
        }
    }
    let (contact, contacts) = contact_boundary(definition, &dofs, &mut triplets)?;
    let mut body = LinearBody::new(mass, SymmetricMatrix::from_triplets(n, &triplets));
    for (constraint, patterns) in constraints.iter().zip(moving) {
        for (component, pattern) in patterns.into_iter().enumerate() {
            if let Some(pattern) = pattern {
                let history = LoadHistory::Displacement { motion: constraint.motion.clone(), component };
                body.loads.push(Load { pattern, history });
            }
        }
    }
    for load in &definition.tractions {
        body.loads.push(traction_load(load, &mesh.nodes, &dofs, definition.axisymmetric));
    }
    Ok(Assembled { body, contact, dofs, contacts, body_force })
}

/// Cells kept to be matched by the next ones: a structured mesh repeats its last few shapes.
const KEPT_SHAPES: usize = 8;

/// The parts (stiffness, masses, weights) of recent cells, reused for a congruent cell: one of the same kind and
/// material whose corners, relative to its first, agree within the rounding of the coordinates
/// they were computed from (`4 ε max |X|`). A structured mesh whose spacing is not a binary
/// fraction (0.01 m) has node coordinates rounded differently from cell to cell, so its
/// congruent cells' matrices would otherwise differ in their last ~10 bits, and no run of
/// equal node stencils would form ([`crate::linalg::stencil`]): the explicit step's fast
/// product would fall back to the compressed matrix, 3 times slower on 1000 × 100. Sharing the
/// first such cell's matrix moves `K` by no more than the coordinates' own rounding.
struct Congruent {
    /// Corners agreeing within this (m) are the same; none for an axisymmetric body.
    tolerance: Option<f64>,
    /// The kept shapes, the latest last.
    shapes: Vec<Shape>,
}

/// A cell's shape and what it gives.
struct Shape {
    material: Material,
    /// Its corners relative to its first (m): 3 or 4.
    corners: Vec<Vector2<f64>>,
    parts: CellParts,
}

impl Congruent {
    /// A cache for the cells of a body on `coordinates`; an axisymmetric body's cells depend
    /// on their absolute radii, so none of them is shared.
    fn new(coordinates: &[[f64; 2]], axisymmetric: bool) -> Self {
        let largest = coordinates.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
        let tolerance = (!axisymmetric).then_some(4.0 * f64::EPSILON * largest);
        Self { tolerance, shapes: Vec::new() }
    }

    /// [`element`] of `cell`, or the kept parts of a congruent cell.
    fn element(
        &mut self,
        cell: &Cell,
        coordinates: &[[f64; 2]],
        material: &Material,
        definition: &BodyDefinition,
    ) -> CellParts {
        let Some(tolerance) = self.tolerance else {
            return element(cell, coordinates, material, definition);
        };
        let corners = relative_corners(cell, coordinates);
        let same = |shape: &&Shape| {
            shape.corners.len() == corners.len()
                && shape.material == *material
                && shape.corners.iter().zip(&corners).all(|(a, b)| (a - b).abs().max() <= tolerance)
        };
        if let Some(found) = self.shapes.iter().rev().find(same) {
            return found.parts.clone();
        }
        let parts = element(cell, coordinates, material, definition);
        if self.shapes.len() == KEPT_SHAPES {
            self.shapes.remove(0);
        }
        self.shapes.push(Shape { material: *material, corners, parts: parts.clone() });
        parts
    }
}

/// The corners of `cell` relative to its first (m).
fn relative_corners(cell: &Cell, coordinates: &[[f64; 2]]) -> Vec<Vector2<f64>> {
    let nodes = cell.nodes();
    let origin = coordinates[nodes[0]];
    nodes.iter().map(|&n| Vector2::new(coordinates[n][0] - origin[0], coordinates[n][1] - origin[1])).collect()
}

/// The case's constraints, and for an axisymmetric body [`AXIS`]: `u_r = 0` at every node
/// on `r = 0`, where the hoop strain `u_r/r` would otherwise be unbounded.
fn constraints(definition: &BodyDefinition) -> Vec<Constraint> {
    let mut all = definition.constraints.clone();
    if definition.axisymmetric {
        let nodes: Vec<usize> =
            (0..definition.mesh.nodes.len()).filter(|&i| definition.mesh.nodes[i][0] == 0.0).collect();
        if !nodes.is_empty() {
            all.push(Constraint { name: AXIS.into(), nodes, components: [true, false], motion: Motion::at_rest() });
        }
    }
    all
}

/// What one cell gives the assembly.
#[derive(Clone)]
struct CellParts {
    /// Its stiffness, degrees of freedom `(x₀, y₀, x₁, y₁, …)`.
    stiffness: nalgebra::DMatrix<f64>,
    /// Each corner's lumped mass.
    mass: Vec<f64>,
    /// Each corner's share of the cell's mass for the body force, `∫ N_a ρ dV` (the row sums
    /// of the consistent mass); empty without gravity.
    weight: Vec<f64>,
}

/// The parts of `cell` ([`CellParts`]). A plane-strain cell is computed from its corners
/// relative to its first, so that its position in the plane does not change the sums; an
/// axisymmetric one from its absolute radii, which its hoop strain and weight `2π r` need.
fn element(cell: &Cell, coordinates: &[[f64; 2]], material: &Material, definition: &BodyDefinition) -> CellParts {
    let nodes = cell.nodes();
    let origin = if definition.axisymmetric { [0.0, 0.0] } else { coordinates[nodes[0]] };
    let local = |a: usize| Vector2::new(coordinates[nodes[a]][0] - origin[0], coordinates[nodes[a]][1] - origin[1]);
    let rho = material.density;
    let matrix = |size: usize, values: &[f64]| nalgebra::DMatrix::from_column_slice(size, size, values);
    match (cell, definition.axisymmetric) {
        (Cell::Quad(_), true) => {
            let ring = axisymmetric::quad(&material.elasticity, &[local(0), local(1), local(2), local(3)]);
            let mass: Vec<f64> = ring.volumes.iter().map(|v| rho * v).collect();
            CellParts { stiffness: matrix(8, ring.stiffness.as_slice()), weight: mass.clone(), mass }
        }
        (Cell::Triangle(_), true) => {
            let ring = axisymmetric::triangle(&material.elasticity, &[local(0), local(1), local(2)]);
            let mass: Vec<f64> = ring.volumes.iter().map(|v| rho * v).collect();
            CellParts { stiffness: matrix(6, ring.stiffness.as_slice()), weight: mass.clone(), mass }
        }
        (Cell::Quad(_), false) => {
            let corners = [local(0), local(1), local(2), local(3)];
            let area = 0.5 * signed_double_area(&corners);
            let k = stiffness(&material.elasticity, &corners);
            let weight = match definition.gravity {
                Some(_) => shape_integrals(&corners).iter().map(|v| rho * v).collect(),
                None => Vec::new(),
            };
            CellParts { stiffness: matrix(8, k.as_slice()), mass: vec![lumped_mass(rho, area, 4); 4], weight }
        }
        (Cell::Triangle(_), false) => {
            let corners = [local(0), local(1), local(2)];
            let area = 0.5 * signed_double_area(&corners);
            let k = triangle_stiffness(&material.elasticity, &corners);
            let mass = vec![lumped_mass(rho, area, 3); 3];
            CellParts { stiffness: matrix(6, k.as_slice()), weight: mass.clone(), mass }
        }
    }
}

/// Numbers the free degrees of freedom node by node, x before y, and records which constraint
/// holds each prescribed one. Two boundaries that prescribe one component of a node differently
/// are refused.
fn number(definition: &BodyDefinition, constraints: &[Constraint]) -> Result<Dofs, AssemblyError> {
    let mesh = definition.mesh;
    let mut holder: Vec<[Option<usize>; 2]> = vec![[None, None]; mesh.nodes.len()];
    for (k, constraint) in constraints.iter().enumerate() {
        for &node in &constraint.nodes {
            for c in (0..2).filter(|&c| constraint.components[c]) {
                match holder[node][c] {
                    Some(other) if constraints[other].motion != constraint.motion => {
                        let [x, y] = mesh.nodes[node];
                        return Err(AssemblyError(format!(
                            "the node at ({}, {}) is on boundaries \"{}\" and \"{}\", which prescribe its {} motion \
                             differently; make the groups share no node, or prescribe the same motion",
                            crate::validate::shortest(x),
                            crate::validate::shortest(y),
                            constraints[other].name,
                            constraint.name,
                            ["x", "y"][c]
                        )));
                    }
                    Some(_) => {}
                    None => holder[node][c] = Some(k),
                }
            }
        }
    }
    let mut free = 0;
    let nodes = holder
        .iter()
        .map(|held| {
            held.map(|h| match h {
                Some(k) => NodeDof::Prescribed(k),
                None => {
                    free += 1;
                    NodeDof::Free(free - 1)
                }
            })
        })
        .collect();
    Ok(Dofs { nodes, motions: constraints.iter().map(|c| c.motion.clone()).collect(), free })
}

/// The contact points of every contact (two Gauss points per segment, eq. 13) and the normal
/// springs `α_n ∫ (n·Ñ)ᵀ (n·Ñ) ds` they add to `K`.
///
/// Normal direction: the main body is rigid, and the contact's elastic normal modulus `α_n`
/// (the normal part of `C^e`) ties the body to it, so a change of normal displacement changes
/// the normal traction by `-α_n Δu_n`. This spring is linear and joins `K`. Under a held normal
/// traction the friction law sees the prescribed one, constant in time as the paper assumes
/// (§3.2), so that the initial distribution alone governs the frictional strength; under an
/// evolving one it sees `f_n⁰ - α_n (g₀ + Δu_n)`, and where that would not be positive the
/// integrators take the spring away again ([`ContactBoundary::normal_correction`]).
fn contact_boundary(
    definition: &BodyDefinition,
    dofs: &Dofs,
    triplets: &mut Vec<(usize, usize, f64)>,
) -> Result<(ContactBoundary, Vec<Vec<Segment>>), AssemblyError> {
    let coordinates = &definition.mesh.nodes;
    let mut boundary =
        ContactBoundary { surfaces: Vec::new(), points: Vec::new(), traction_n: Vec::new(), gap: Vec::new() };
    let mut all = Vec::new();
    for (surface, contact) in definition.contacts.iter().enumerate() {
        let first = boundary.points.len();
        refuse_moving_nodes(contact, dofs, coordinates)?;
        let chain = segments(&contact.chain, coordinates);
        for segment in &chain {
            let [a, b] = segment.nodes;
            for mut gauss in segment.gauss_points(coordinates) {
                if definition.axisymmetric {
                    // The ring the point stands for: its traction acts around the circumference.
                    gauss.weight *= 2.0 * std::f64::consts::PI * gauss.position.x;
                }
                let [na, nb] = gauss.shape;
                let along = |direction: [f64; 2]| {
                    Projection::new(
                        [(a, 0, na), (a, 1, na), (b, 0, nb), (b, 1, nb)]
                            .into_iter()
                            .filter_map(|(node, c, shape)| dofs.free(node, c).map(|dof| (dof, direction[c] * shape))),
                    )
                };
                let normal = along(segment.normal);
                for (da, ca) in normal.terms() {
                    for (db, cb) in normal.terms() {
                        triplets.push((da, db, contact.params.alpha_n * gauss.weight * ca * cb));
                    }
                }
                boundary.points.push(ContactPoint {
                    tangential: along(segment.tangent),
                    normal,
                    weight: gauss.weight,
                    surface,
                    tangent: segment.tangent,
                    loading_direction: loading_direction(&contact.main_body, segment.tangent),
                });
                boundary.traction_n.push((contact.normal_traction)(gauss.position));
                boundary.gap.push(contact.gap.as_ref().map_or(0.0, |gap| gap(gauss.position)));
            }
        }
        let (points, terms) = padded(boundary.points.split_off(first));
        boundary.points.extend(points);
        boundary.surfaces.push(ContactSurface {
            params: contact.params.clone(),
            main_body: contact.main_body.clone(),
            normal: contact.normal,
            points: first..boundary.points.len(),
            terms,
        });
        all.push(chain);
    }
    Ok((boundary, all))
}

/// A node of a contact may be fixed (the contact sees it still), but not moved by a boundary:
/// its prescribed motion would have to enter the contact's slip.
fn refuse_moving_nodes(
    contact: &ContactDefinition,
    dofs: &Dofs,
    coordinates: &[[f64; 2]],
) -> Result<(), AssemblyError> {
    for &node in &contact.chain {
        for held in &dofs.nodes[node] {
            if let NodeDof::Prescribed(k) = held
                && !dofs.motions[*k].is_at_rest()
            {
                let [x, y] = coordinates[node];
                return Err(AssemblyError(format!(
                    "the node at ({}, {}) is on contact \"{}\" and on a boundary that moves it; a contact's nodes may \
                     be fixed but not moved: make the groups share no node",
                    crate::validate::shortest(x),
                    crate::validate::shortest(y),
                    contact.name
                )));
            }
        }
    }
    Ok(())
}

/// The sign of the initial tangential traction `f0`: the way the main body first drags the
/// body along `tangent` (+1 where it does not move along it).
fn loading_direction(main_body: &MainBody, tangent: [f64; 2]) -> f64 {
    let first = main_body.motion.first_velocity().unwrap_or([0.0, 0.0]);
    let along = if main_body.along_tangent { first[0] } else { tangent[0] * first[0] + tangent[1] * first[1] };
    if along < 0.0 { -1.0 } else { 1.0 }
}

/// `∫ Nᵀ t̄ ds` over the chain's segments: each end of a segment of length `L` carries `t̄ L/2`;
/// around a ring, `∫ Nᵀ t̄ 2π r ds`, each end `t̄ 2π L (2 r_a + r_b)/6` (`r_a` its own radius).
fn traction_load(load: &TractionLoad, coordinates: &[[f64; 2]], dofs: &Dofs, axisymmetric: bool) -> Load {
    let mut pattern = vec![0.0; dofs.free];
    for segment in segments(&load.chain, coordinates) {
        let traction = match load.traction {
            Traction::Vector(t) => t,
            Traction::Pressure(p) => [p * segment.normal[0], p * segment.normal[1]],
        };
        let [ra, rb] = segment.ends.map(|e| e[0]);
        for (end, node) in segment.nodes.into_iter().enumerate() {
            let share = if axisymmetric {
                let (own, other) = if end == 0 { (ra, rb) } else { (rb, ra) };
                2.0 * std::f64::consts::PI * segment.length * (2.0 * own + other) / 6.0
            } else {
                0.5 * segment.length
            };
            for (c, t) in traction.iter().enumerate() {
                if let Some(dof) = dofs.free(node, c) {
                    pattern[dof] += share * t;
                }
            }
        }
    }
    let history = match load.duration {
        None => LoadHistory::Ramp { ramp: load.ramp },
        Some(duration) => LoadHistory::Pulse { ramp: load.ramp, duration },
    };
    Load { pattern, history }
}
