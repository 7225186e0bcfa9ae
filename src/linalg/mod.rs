//! Linear algebra below the finite elements and the integrators: the sparse symmetric
//! matrix with its Cholesky (LU as fallback) factorization and, for a small one, its dense
//! columns, the stencil form of the stiffness
//! that the explicit step multiplies with, and Lanczos' iteration for extreme frequencies.

pub mod dense;
pub mod lanczos;
pub mod sparse;
pub mod stencil;
