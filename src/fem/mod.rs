//! Finite elements of the body: the mesh, its elements, the curves of its boundaries and
//! contacts, and assembly into the equation of motion (14).

pub mod assembly;
pub mod axisymmetric;
pub mod body_mesh;
pub mod curve;
pub mod element;
pub mod equilibrium;
pub mod gmsh;
pub mod rectangle;
pub mod stiffest;

pub use assembly::{
    Assembled, AssemblyError, BodyDefinition, Constraint, ContactDefinition, Dofs, Material, NodeDof, Traction,
    TractionLoad, assemble,
};
pub use body_mesh::{Cell, Group, Members, Mesh, MeshError};
pub use element::PlaneStrain;
pub use rectangle::rectangle;
