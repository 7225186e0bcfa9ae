//! The paper's block as a mesh (its Fig. 6: 10 × 1 elements): a rectangle of `nx × ny` equal
//! bilinear quadrilaterals with its four sides as named curves.

use crate::fem::body_mesh::{Cell, Group, Members, Mesh};

/// The names of the rectangle's groups: its surface and its four sides.
pub const BODY: &str = "body";
pub const BOTTOM: &str = "bottom";
pub const RIGHT: &str = "right";
pub const TOP: &str = "top";
pub const LEFT: &str = "left";

/// `nx × ny` rectangular elements over `[0, W] × [0, H]`. Nodes are numbered row by row from
/// the bottom left (node `(i, j)` is `j (nx+1) + i`, at `(i W/nx, j H/ny)`), cells likewise,
/// each counter-clockwise from its bottom-left corner: the canonical order of [`Mesh`].
pub fn rectangle(width: f64, height: f64, nx: usize, ny: usize) -> Mesh {
    let (dx, dy) = (width / nx as f64, height / ny as f64);
    let node = |i: usize, j: usize| j * (nx + 1) + i;
    let nodes = (0..=ny).flat_map(|j| (0..=nx).map(move |i| [i as f64 * dx, j as f64 * dy])).collect();
    let cells = (0..ny)
        .flat_map(|j| {
            (0..nx).map(move |i| Cell::Quad([node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)]))
        })
        .collect();
    let side =
        |name: &str, tag: i32, lines: Vec<[usize; 2]>| Group { name: name.into(), tag, members: Members::Lines(lines) };
    let groups = vec![
        Group { name: BODY.into(), tag: 1, members: Members::Cells((0..nx * ny).collect()) },
        side(BOTTOM, 2, (0..nx).map(|i| [node(i, 0), node(i + 1, 0)]).collect()),
        side(RIGHT, 3, (0..ny).map(|j| [node(nx, j), node(nx, j + 1)]).collect()),
        side(TOP, 4, (0..nx).map(|i| [node(i, ny), node(i + 1, ny)]).collect()),
        side(LEFT, 5, (0..ny).map(|j| [node(0, j), node(0, j + 1)]).collect()),
    ];
    Mesh { nodes, cells, groups, node_tags: Vec::new(), cell_tags: Vec::new() }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rectangle is built in the canonical order that [`Mesh::new`] gives any mesh, so it
    /// skips the sorting: building it through `Mesh::new` changes nothing.
    #[test]
    fn the_rectangle_is_canonical() {
        let mesh = rectangle(10.0, 1.0, 10, 3);
        let canonical = Mesh::new(mesh.nodes.clone(), mesh.cells.clone(), mesh.groups.clone()).unwrap();
        assert_eq!(canonical, mesh);
        assert_eq!(mesh.boundary_chain(BOTTOM).unwrap(), (0..=10).collect::<Vec<_>>());
    }
}
