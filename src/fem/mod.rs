//! Finite elements of the body: mesh, element, and assembly into the equation of motion (14).

pub mod assembly;
pub mod body_mesh;
pub mod element;
pub mod gmsh;
pub mod mesh;

pub use assembly::{Block, assemble};
pub use element::PlaneStrain;
pub use mesh::StructuredMesh;
