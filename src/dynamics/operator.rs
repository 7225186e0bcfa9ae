//! Newton's operator of the implicit integrators, `c₀ M + K + K_c`, assembled in one sparse
//! pattern and factored.
//!
//! Wilson's step (`c₀ = 6/τ²`, [`crate::dynamics::wilson`]) and the SDIRK stages (`c₀ = 1/(hγ)²`,
//! [`crate::dynamics::rate_form::sdirk4`]) both solve with it. `K_c = -Σ w Ñᵀ (∂f_t/∂ū) Ñ` is eq. (14)'s contact
//! tangent. The explicit integrators never need it, so [`crate::dynamics::System`] builds it at its
//! first use: on a fine mesh the pattern is as large as `K`'s, and its symbolic analysis takes
//! as long as the rest of the set-up.

use crate::dynamics::body::LinearBody;
use crate::dynamics::contact::ContactBoundary;
use crate::linalg::sparse::{Cholesky, FactorError, SymmetricMatrix};

/// `c₀ M + K + K_c`: its pattern, where each part's entries go in it, and its factorization.
pub(super) struct Operator {
    matrix: SymmetricMatrix,
    /// Position of each diagonal entry (the mass term).
    diagonal: Vec<usize>,
    /// Position of each entry of `K`, in `K`'s order.
    stiffness_entries: Vec<usize>,
    /// Positions of each contact point's coupling of its tangential degrees of freedom, pair by
    /// pair in the order of [`crate::dynamics::Projection::terms`].
    point_entries: Vec<Vec<usize>>,
    /// The same for the normal degrees of freedom of points whose normal traction evolves
    /// (empty for the others): an open point's spring is taken away there.
    normal_entries: Vec<Vec<usize>>,
    cholesky: Cholesky,
    /// The mass coefficient and contact stiffnesses factored last; `None` after a failure.
    factored: Option<(f64, Vec<f64>)>,
}

impl Operator {
    /// The pattern of `K`, the diagonal and every contact coupling, analyzed for factoring.
    pub fn new(body: &LinearBody, contact: &ContactBoundary) -> Result<Self, FactorError> {
        let n = body.dofs();
        let mut triplets: Vec<(usize, usize, f64)> = body.stiffness.entries().collect();
        triplets.extend((0..n).map(|i| (i, i, 0.0)));
        for (k, p) in contact.points.iter().enumerate() {
            for (a, _) in p.tangential.terms() {
                for (b, _) in p.tangential.terms() {
                    triplets.push((a, b, 0.0));
                }
            }
            if contact.evolves(k) {
                for (a, _) in p.normal.terms() {
                    for (b, _) in p.normal.terms() {
                        triplets.push((a, b, 0.0));
                    }
                }
            }
        }
        let matrix = SymmetricMatrix::from_triplets(n, &triplets);
        let diagonal = (0..n).map(|i| matrix.position(i, i).expect("diagonal in pattern")).collect();
        let stiffness_entries = body
            .stiffness
            .entries()
            .map(|(i, j, _)| matrix.position(i, j).expect("K's pattern is in the operator's"))
            .collect();
        let point_entries = contact
            .points
            .iter()
            .map(|p| {
                let terms = || p.tangential.terms();
                terms()
                    .flat_map(|(a, _)| terms().map(move |(b, _)| (a, b)))
                    .map(|(a, b)| matrix.position(a, b).expect("contact entry in pattern"))
                    .collect()
            })
            .collect();
        let normal_entries = contact
            .points
            .iter()
            .enumerate()
            .map(|(k, p)| {
                if !contact.evolves(k) {
                    return Vec::new();
                }
                let terms = || p.normal.terms();
                terms()
                    .flat_map(|(a, _)| terms().map(move |(b, _)| (a, b)))
                    .map(|(a, b)| matrix.position(a, b).expect("normal entry in pattern"))
                    .collect()
            })
            .collect();
        let cholesky = Cholesky::analyze(&matrix)?;
        Ok(Self { matrix, diagonal, stiffness_entries, point_entries, normal_entries, cholesky, factored: None })
    }

    /// The mass coefficient and contact stiffnesses factored last, if the last factoring
    /// succeeded.
    pub fn factored(&self) -> Option<&(f64, Vec<f64>)> {
        self.factored.as_ref()
    }

    /// Assembles and factors `c₀ M + K + K_c` unless the factored one is the same;
    /// `contact_stiffness` holds each point's `-w ∂f_t/∂ū`, and where a contact's normal evolves
    /// then each point's change of its normal spring
    /// ([`crate::dynamics::ContactBoundary::normal_stiffness`]).
    pub fn factor(
        &mut self,
        body: &LinearBody,
        contact: &ContactBoundary,
        c0: f64,
        contact_stiffness: &[f64],
    ) -> Result<(), FactorError> {
        if let Some((c, k)) = &self.factored
            && *c == c0
            && k.as_slice() == contact_stiffness
        {
            return Ok(());
        }
        let values = self.matrix.values_mut();
        values.iter_mut().for_each(|v| *v = 0.0);
        for (&pos, &k) in self.stiffness_entries.iter().zip(body.stiffness.values()) {
            values[pos] += k;
        }
        for (i, &pos) in self.diagonal.iter().enumerate() {
            values[pos] += c0 * body.mass[i];
        }
        let m = contact.points.len();
        for ((point, entries), &k) in contact.points.iter().zip(&self.point_entries).zip(contact_stiffness) {
            let terms = || point.tangential.terms();
            let pairs = terms().flat_map(|(_, c_a)| terms().map(move |(_, c_b)| (c_a, c_b)));
            for (&entry, (c_a, c_b)) in entries.iter().zip(pairs) {
                values[entry] += k * c_a * c_b;
            }
        }
        for ((point, entries), &k) in
            contact.points.iter().zip(&self.normal_entries).zip(contact_stiffness.get(m..).unwrap_or(&[]))
        {
            let terms = || point.normal.terms();
            let pairs = terms().flat_map(|(_, c_a)| terms().map(move |(_, c_b)| (c_a, c_b)));
            for (&entry, (c_a, c_b)) in entries.iter().zip(pairs) {
                values[entry] += k * c_a * c_b;
            }
        }
        // Until it succeeds, nothing is factored.
        self.factored = None;
        self.cholesky.factor(&self.matrix)?;
        self.factored = Some((c0, contact_stiffness.to_vec()));
        Ok(())
    }

    /// Solves with the operator [`Self::factor`] factored last, in place.
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        self.cholesky.solve_in_place(rhs);
    }
}
