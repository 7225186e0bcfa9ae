//! Linear algebra below the finite elements and the integrators: the sparse symmetric
//! matrix with its Cholesky (LU as fallback) factorization, and the stencil form of the
//! stiffness that the explicit step multiplies with.

pub mod sparse;
pub mod stencil;
