//! `kind = "mesh"`: a plane-strain body drawn in Gmsh, with the materials, boundaries and
//! contacts its case names ([`crate::case::mesh`]), assembled and stepped as any body
//! ([`crate::scene::body`]).

use crate::case::Case;
use crate::case::mesh::MeshSpec;
use crate::fem::assemble;
use crate::frame::SceneKind;
use crate::scene::body::{BodyScene, Presentation, build};
use crate::scene::drawing;
use crate::scene::interface::RunError;

/// The body of a mesh case.
pub fn scene(case: &Case, spec: &MeshSpec) -> Result<BodyScene, RunError> {
    let loaded = spec.loaded();
    let assembled =
        assemble(&spec.definition(loaded)).map_err(|e| RunError { step: 0, time: 0.0, segment: None, message: e.0 })?;
    let presentation = Presentation {
        kind: SceneKind::Mesh,
        drawing: drawing::of_mesh(&loaded.mesh, &assembled.contacts),
        // A body nothing moves (one settling under its weight) still needs a velocity scale.
        driving_velocity: case.scene.driving_velocity(),
        contact_names: spec.contacts.iter().map(|c| c.group.clone()).collect(),
        axisymmetric: spec.axisymmetric,
    };
    build(case, assembled, presentation, loaded.equilibrium.as_ref())
}
