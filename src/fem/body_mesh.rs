//! A 2-D mesh of any body: triangles and quadrilaterals in canonical order, with the physical
//! groups that name its materials (surfaces), boundaries and contacts (curves) and points.
//!
//! [`Mesh::new`] builds one from raw nodes, cells and groups, as a reader of a mesh file gives
//! them (see `crate::fem::gmsh`), and validates it; [`Mesh::boundary_chain`] turns a curve group
//! into the ordered nodes of a boundary.

mod build;
mod chain;
mod error;
mod shape;

pub use error::{MeshError, Place};

/// A validated 2-D mesh in canonical order: two meshes of the same body, whatever the numbering
/// and orientation of their files, are equal.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Node coordinates (m), in canonical order: sorted by y, then x (f64::total_cmp).
    pub nodes: Vec<[f64; 2]>,
    /// 2-D cells, counter-clockwise, each starting at its smallest node index, sorted by
    /// their node lists (lexicographic). Indices into `nodes`.
    pub cells: Vec<Cell>,
    /// Physical groups, in the file's order of first appearance.
    pub groups: Vec<Group>,
    /// The tag (the file's number) of each node, by canonical index; empty for a mesh not read
    /// from a file.
    pub node_tags: Vec<u64>,
    /// The tag (the file's number) of each cell, by canonical index; empty for a mesh not read
    /// from a file.
    pub cell_tags: Vec<u64>,
}

/// A 2-D cell: a 3-node triangle or a 4-node (bilinear) quadrilateral, by node indices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cell {
    Triangle([usize; 3]),
    Quad([usize; 4]),
}

impl Cell {
    /// The cell's node indices, in order around it.
    pub fn nodes(&self) -> &[usize] {
        match self {
            Cell::Triangle(n) => n,
            Cell::Quad(n) => n,
        }
    }

    /// The cell's node indices, mutably, in order around it.
    fn nodes_mut(&mut self) -> &mut [usize] {
        match self {
            Cell::Triangle(n) => n,
            Cell::Quad(n) => n,
        }
    }
}

/// A named set of cells, lines or points (a Gmsh physical group).
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// The group's name; an unnamed Gmsh group is named by its tag (`"7"`).
    pub name: String,
    /// The group's tag in the file it was read from.
    pub tag: i32,
    pub members: Members,
}

/// The members of a group, by the dimension of the group.
#[derive(Clone, Debug, PartialEq)]
pub enum Members {
    /// dimension 2: indices into `cells`, ascending
    Cells(Vec<usize>),
    /// dimension 1: 2-node line elements as node pairs (canonical node indices), in file order
    Lines(Vec<[usize; 2]>),
    /// dimension 0: node indices
    Points(Vec<usize>),
}

impl Members {
    /// 2 for cells, 1 for lines, 0 for points.
    pub fn dimension(&self) -> usize {
        match self {
            Members::Cells(_) => 2,
            Members::Lines(_) => 1,
            Members::Points(_) => 0,
        }
    }

    /// How many cells, lines or points the group holds.
    pub fn len(&self) -> usize {
        match self {
            Members::Cells(m) => m.len(),
            Members::Lines(m) => m.len(),
            Members::Points(m) => m.len(),
        }
    }

    /// Whether the group holds nothing.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// How the group is described to a user: `surface (dimension 2, 10 cells)`.
    pub fn describe(&self) -> String {
        let n = self.len();
        let (kind, what) = match self {
            Members::Cells(_) => ("surface", if n == 1 { "cell" } else { "cells" }),
            Members::Lines(_) => ("curve", if n == 1 { "line" } else { "lines" }),
            Members::Points(_) => ("point", if n == 1 { "point" } else { "points" }),
        };
        format!("{kind} (dimension {}, {n} {what})", self.dimension())
    }
}

/// The file's numbers of the nodes and cells given to [`Mesh::tagged`], so that its refusals
/// name them as the user knows them. Either list may be empty (then refusals name a node or
/// cell by its index in the input, as `node #3`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tags {
    pub nodes: Vec<u64>,
    pub cells: Vec<u64>,
}

impl Mesh {
    /// The group called `name`; refused with the list of the groups the mesh has, each with
    /// its dimension.
    pub fn group(&self, name: &str) -> Result<&Group, MeshError> {
        self.groups.iter().find(|g| g.name == name).ok_or_else(|| {
            let known: Vec<String> =
                self.groups.iter().map(|g| format!("\"{}\" {}", g.name, g.members.describe())).collect();
            let known = if known.is_empty() { "none".to_owned() } else { known.join(", ") };
            MeshError::new(format!("the mesh has no physical group \"{name}\"; its groups: {known}"))
        })
    }

    /// How a message names canonical node `i`: `node 17` (its tag) or `node #3` (its index).
    pub fn node_label(&self, i: usize) -> String {
        error::node_label(&self.node_tags, i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_group_is_refused_with_the_groups_there_are() {
        let nodes = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let groups = vec![
            Group { name: "body".into(), tag: 1, members: Members::Cells(vec![0]) },
            Group { name: "base".into(), tag: 2, members: Members::Lines(vec![[0, 1]]) },
            Group { name: "corner".into(), tag: 3, members: Members::Points(vec![0, 2]) },
        ];
        let mesh = Mesh::new(nodes, vec![Cell::Triangle([0, 1, 2])], groups).unwrap();
        assert_eq!(mesh.group("base").unwrap().tag, 2);
        let e = mesh.group("bottom").unwrap_err().to_string();
        assert_eq!(
            e,
            "the mesh has no physical group \"bottom\"; its groups: \"body\" surface (dimension 2, 1 cell), \
             \"base\" curve (dimension 1, 1 line), \"corner\" point (dimension 0, 2 points)"
        );
    }
}
