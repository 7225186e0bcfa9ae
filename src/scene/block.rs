//! `kind = "block"`: the paper's §3 analysis, a plane-strain elastic block whose bottom is the
//! frictional contact against a moving rigid base. The block is a mesh
//! ([`crate::fem::rectangle`]) with its top fixed and its bottom the contact, assembled and
//! stepped as any body ([`crate::scene::body`]).

use crate::case::{BlockSpec, Case};
use crate::dynamics::{MainBody, Motion, NormalBehaviour, condensation_pays};
use crate::fem::curve::CurvePoint;
use crate::fem::rectangle::{BOTTOM, TOP};
use crate::fem::{
    Assembled, BodyDefinition, Constraint, ContactDefinition, Material, PlaneStrain, assemble, rectangle,
};
use crate::frame::{MeshDrawing, SceneKind};
use crate::friction::FrictionParams;
use crate::scene::body::{BodyScene, Presentation, build};
use crate::scene::drawing::MOST_LINES;
use crate::scene::interface::RunError;

/// Peak memory (bytes) a block of `nx × ny` elements is expected to need: a base of 16 MB plus
/// 200 B × log2(n) per degree of freedom `n = 2 (nx+1)(ny+1)`, the sparse factor's fill growing
/// like `n log n`, plus three dense `k × k` matrices where the contact's `k = nx + 1` unknowns
/// are condensed. Fitted to the peak RSS of 1000×100 measured here (692 MB; the estimate is
/// 8 % higher); at 300×30 and 100×10 it is 12 % lower and 40 % higher (79 MB and 15 MB
/// measured). Adaptive runs, which never condense, need less.
pub fn estimated_memory(nx: usize, ny: usize) -> (f64, f64) {
    let dofs = 2.0 * (nx as f64 + 1.0) * (ny as f64 + 1.0);
    (dofs, body_memory(dofs, nx.saturating_add(1)))
}

/// [`estimated_memory`] of any body of `dofs` degrees of freedom whose contacts have
/// `contact_unknowns` tangential unknowns (bytes).
pub fn body_memory(dofs: f64, contact_unknowns: usize) -> f64 {
    let contact = contact_unknowns as f64;
    let condensed =
        if condensation_pays(dofs as usize, contact_unknowns) { 3.0 * 8.0 * contact * contact } else { 0.0 };
    16.0e6 + 200.0 * dofs * dofs.log2() + condensed
}

/// The paper's block as a scene.
pub type BlockScene = BodyScene;

impl BlockScene {
    /// The block of `spec`: a rectangle mesh, its top fixed, its bottom on the base.
    pub fn new(case: &Case, spec: &BlockSpec) -> Result<Self, RunError> {
        let material = Material {
            elasticity: PlaneStrain { youngs_modulus: spec.youngs_modulus, poisson_ratio: spec.poisson_ratio },
            density: spec.density,
        };
        let base = Motion::constant([spec.base_velocity, 0.0], spec.base_ramp_time);
        let normal_traction = |x: f64| spec.normal_traction.at(x, spec.width);
        let assembled = block(
            spec.width,
            spec.height,
            spec.nx,
            spec.ny,
            material,
            case.friction.clone(),
            (&normal_traction, spec.normal),
            base,
        );
        let drawing = MeshDrawing::rectangle(spec.width, spec.height, spec.nx, spec.ny, Some(MOST_LINES));
        let presentation = Presentation {
            kind: SceneKind::Block,
            drawing,
            driving_velocity: spec.base_velocity.abs(),
            contact_names: vec![BOTTOM.into()],
            axisymmetric: false,
        };
        build(case, assembled, presentation, None)
    }
}

/// The paper's block assembled: `W × H` in `nx × ny` bilinear elements of `material`, its top
/// fixed, its bottom in contact (law `params`, normal traction `normal_traction(x)`, held or
/// evolving) with a base that moves along x as `base` says.
#[allow(clippy::too_many_arguments)]
pub fn block(
    width: f64,
    height: f64,
    nx: usize,
    ny: usize,
    material: Material,
    params: FrictionParams,
    (normal_traction, normal): (&dyn Fn(f64) -> f64, NormalBehaviour),
    base: Motion,
) -> Assembled {
    let mesh = rectangle(width, height, nx, ny);
    let top: Vec<usize> = (ny * (nx + 1)..(ny + 1) * (nx + 1)).collect();
    let at = |p: CurvePoint| normal_traction(p.x);
    let definition = BodyDefinition {
        mesh: &mesh,
        materials: vec![material; mesh.cells.len()],
        constraints: vec![Constraint {
            name: TOP.into(),
            nodes: top,
            components: [true, true],
            motion: Motion::at_rest(),
        }],
        tractions: Vec::new(),
        contacts: vec![ContactDefinition {
            name: BOTTOM.into(),
            chain: mesh.boundary_chain(BOTTOM).expect("the rectangle's bottom is one chain"),
            params,
            main_body: MainBody { motion: base, along_tangent: true },
            normal_traction: Box::new(at),
            normal,
            gap: None,
        }],
        axisymmetric: false,
        gravity: None,
    };
    assemble(&definition).expect("a block's boundaries share no node")
}
