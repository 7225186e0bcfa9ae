//! What the spatial view draws of a body ([`MeshDrawing`]): the reference positions of the
//! nodes it draws, the lines through them, each contact segment and each main body.

use serde::{Deserialize, Serialize};

/// The drawing of a body, fixed for a run; each frame adds the drawn nodes' displacements.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshDrawing {
    /// Reference positions of the drawn nodes (m).
    pub nodes: Vec<[f64; 2]>,
    /// Polylines of the mesh, as indices into [`Self::nodes`].
    pub lines: Vec<Vec<u32>>,
    /// Each contact segment's end nodes, in the order of the layout's segments.
    pub contact: Vec<[u32; 2]>,
    /// Each contact's main body, drawn still just outside the contact (m).
    pub bases: Vec<Vec<[f64; 2]>>,
}

impl MeshDrawing {
    /// The drawing of a structured `nx × ny` rectangle `W × H` whose nodes are numbered row by
    /// row from the bottom left, with the mesh node of each drawn node: the bottom row in full
    /// (the contact, its base below it), grid rows and columns through every node, or, with
    /// `most = (columns, rows)`, through every k-th column and row (the outer ones always).
    pub fn rectangle(
        width: f64,
        height: f64,
        nx: usize,
        ny: usize,
        most: Option<(usize, usize)>,
    ) -> (Self, Vec<usize>) {
        let picks = |n: usize, most: Option<usize>| -> Vec<usize> {
            let stride = most.map_or(1, |most| n.div_ceil(most.max(2) - 1).max(1));
            let mut picked: Vec<usize> = (0..=n).step_by(stride).collect();
            if picked.last() != Some(&n) {
                picked.push(n);
            }
            picked
        };
        let (columns, rows) = (picks(nx, most.map(|m| m.0)), picks(ny, most.map(|m| m.1)));
        let node = |i: usize, j: usize| j * (nx + 1) + i;
        let mut drawn = Drawn::default();
        let bottom: Vec<u32> = (0..=nx).map(|i| drawn.index(node(i, 0))).collect();
        let mut lines = vec![bottom.clone()];
        lines.extend(
            rows.iter().filter(|&&j| j > 0).map(|&j| columns.iter().map(|&i| drawn.index(node(i, j))).collect()),
        );
        lines.extend(columns.iter().map(|&i| rows.iter().map(|&j| drawn.index(node(i, j))).collect()));
        let (dx, dy) = (width / nx as f64, height / ny as f64);
        let base = -0.12 * height.min(width);
        let nodes = drawn.nodes.iter().map(|&n| [(n % (nx + 1)) as f64 * dx, (n / (nx + 1)) as f64 * dy]).collect();
        let contact = (0..nx).map(|k| [bottom[k], bottom[k + 1]]).collect();
        (Self { nodes, lines, contact, bases: vec![vec![[0.0, base], [width, base]]] }, drawn.nodes)
    }
}

/// The nodes a drawing uses, in the order first used, and each one's index.
#[derive(Default)]
pub struct Drawn {
    pub nodes: Vec<usize>,
    index: std::collections::HashMap<usize, u32>,
}

impl Drawn {
    /// The drawing's index of mesh node `node`, added if new.
    pub fn index(&mut self, node: usize) -> u32 {
        *self.index.entry(node).or_insert_with(|| {
            self.nodes.push(node);
            (self.nodes.len() - 1) as u32
        })
    }
}

/// The block's mesh as recordings and logs from before general meshes describe it.
#[derive(Deserialize)]
struct StructuredMesh {
    width: f64,
    height: f64,
    nx: usize,
    ny: usize,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum EitherForm {
    Drawing(MeshDrawing),
    Structured(StructuredMesh),
}

/// Reads a layout's drawing in either form: today's, or the structured block's of older logs
/// (whose frames hold every node, row by row from the bottom left, as [`MeshDrawing::rectangle`]).
pub(crate) fn either_form<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<Option<MeshDrawing>, D::Error> {
    Ok(Option::<EitherForm>::deserialize(deserializer)?.map(|form| match form {
        EitherForm::Drawing(drawing) => drawing,
        EitherForm::Structured(m) => MeshDrawing::rectangle(m.width, m.height, m.nx, m.ny, None).0,
    }))
}
