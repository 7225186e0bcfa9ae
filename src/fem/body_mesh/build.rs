//! [`Mesh::new`]: from raw nodes, cells and groups to the canonical, validated mesh.

use super::error::{cell_label, node_label};
use super::shape::{Shape, shape};
use super::{Cell, Group, Members, Mesh, MeshError, Tags};
use crate::validate::shortest;
use std::collections::HashSet;

impl Mesh {
    /// Builds a mesh from raw nodes/cells/groups: drops nodes no cell uses (a line or point
    /// group naming such a node is an error), renumbers canonically, orients every cell
    /// counter-clockwise (a clockwise cell is reordered, not refused), and validates.
    pub fn new(nodes: Vec<[f64; 2]>, cells: Vec<Cell>, groups: Vec<Group>) -> Result<Mesh, MeshError> {
        Mesh::tagged(nodes, cells, groups, Tags::default())
    }

    /// [`Mesh::new`] for nodes and cells that have tags in a file: refusals name them by their
    /// tags, and the mesh keeps them (`node_tags`, `cell_tags`, in canonical order).
    ///
    /// Refused: no cell; a cell naming a node that does not exist or naming one twice; a
    /// coordinate that is not finite; two used nodes at the same point; a cell with a zero
    /// Jacobian at a corner, or one that changes sign (non-convex, self-crossing); two cells
    /// that run along the same edge in the same direction (they overlap); a group naming a cell
    /// or node that does not exist or a node no cell uses; a line from a node to itself; two
    /// groups with one name.
    pub fn tagged(nodes: Vec<[f64; 2]>, cells: Vec<Cell>, groups: Vec<Group>, tags: Tags) -> Result<Mesh, MeshError> {
        check_tags(&tags, nodes.len(), cells.len())?;
        if cells.is_empty() {
            return Err(MeshError::new("the mesh has no 2-D cell (triangle or quadrilateral)"));
        }
        check_cell_nodes(&cells, nodes.len(), &tags)?;
        let nodes: Vec<[f64; 2]> = nodes.into_iter().map(|[x, y]| [x + 0.0, y + 0.0]).collect(); // -0 is 0
        check_finite(&nodes, &tags)?;
        let order = canonical_nodes(&nodes, &cells, &tags)?;
        let mut new_index = vec![usize::MAX; nodes.len()];
        for (new, &old) in order.iter().enumerate() {
            new_index[old] = new;
        }
        let cells = oriented(cells, &nodes, &tags)?;
        check_overlaps(&cells, &tags)?;
        let (cells, cell_order) = canonical_cells(cells, &new_index);
        let node_tags = if tags.nodes.is_empty() { Vec::new() } else { order.iter().map(|&i| tags.nodes[i]).collect() };
        let cell_tags =
            if tags.cells.is_empty() { Vec::new() } else { cell_order.iter().map(|&i| tags.cells[i]).collect() };
        let nodes = order.iter().map(|&i| nodes[i]).collect();
        let mut new_cell = vec![0; cell_order.len()];
        for (new, &old) in cell_order.iter().enumerate() {
            new_cell[old] = new;
        }
        let groups = canonical_groups(groups, &new_index, &new_cell, &tags)?;
        Ok(Mesh { nodes, cells, groups, node_tags, cell_tags })
    }
}

/// The tag lists are empty or have one tag per node (per cell).
fn check_tags(tags: &Tags, nodes: usize, cells: usize) -> Result<(), MeshError> {
    for (what, len, count) in [("node", tags.nodes.len(), nodes), ("cell", tags.cells.len(), cells)] {
        if len != 0 && len != count {
            return Err(MeshError::new(format!("{len} {what} tags for {count} {what}s: give one per {what}, or none")));
        }
    }
    Ok(())
}

/// Every cell names existing nodes, each once.
fn check_cell_nodes(cells: &[Cell], node_count: usize, tags: &Tags) -> Result<(), MeshError> {
    for (c, cell) in cells.iter().enumerate() {
        let n = cell.nodes();
        let label = || cell_label(&tags.cells, &tags.nodes, c, n);
        if let Some(&missing) = n.iter().find(|&&i| i >= node_count) {
            return Err(MeshError::new(format!("{} names node #{missing}; there are {node_count} nodes", label())));
        }
        if let Some(k) = (1..n.len()).find(|&k| n[..k].contains(&n[k])) {
            let twice = node_label(&tags.nodes, n[k]);
            return Err(MeshError::new(format!("{} names {twice} twice: a cell's corners must be distinct", label())));
        }
    }
    Ok(())
}

/// Every coordinate is finite.
fn check_finite(nodes: &[[f64; 2]], tags: &Tags) -> Result<(), MeshError> {
    match nodes.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
        None => Ok(()),
        Some(i) => Err(MeshError::new(format!(
            "{} is at ({}, {}): coordinates must be finite numbers",
            node_label(&tags.nodes, i),
            shortest(nodes[i][0]),
            shortest(nodes[i][1])
        ))),
    }
}

/// The nodes that cells use, in canonical order (by y, then x); refused if two are at one point.
fn canonical_nodes(nodes: &[[f64; 2]], cells: &[Cell], tags: &Tags) -> Result<Vec<usize>, MeshError> {
    let mut used = vec![false; nodes.len()];
    for cell in cells {
        for &n in cell.nodes() {
            used[n] = true;
        }
    }
    let mut order: Vec<usize> = (0..nodes.len()).filter(|&i| used[i]).collect();
    order.sort_by(|&a, &b| nodes[a][1].total_cmp(&nodes[b][1]).then(nodes[a][0].total_cmp(&nodes[b][0])));
    if let Some(w) = order.windows(2).find(|w| nodes[w[0]] == nodes[w[1]]) {
        let [x, y] = nodes[w[0]];
        let (a, b) = (w[0].min(w[1]), w[0].max(w[1]));
        return Err(MeshError::new(format!(
            "{} and {} are both at ({}, {}): each point of the mesh must be one node",
            node_label(&tags.nodes, a),
            node_label(&tags.nodes, b),
            shortest(x),
            shortest(y)
        )));
    }
    Ok(order)
}

/// Every cell counter-clockwise: a clockwise one reversed, a flat or folded one refused.
fn oriented(mut cells: Vec<Cell>, nodes: &[[f64; 2]], tags: &Tags) -> Result<Vec<Cell>, MeshError> {
    for (c, cell) in cells.iter_mut().enumerate() {
        let label = || cell_label(&tags.cells, &tags.nodes, c, cell.nodes());
        match shape(cell.nodes(), nodes) {
            Shape::CounterClockwise => {}
            Shape::Clockwise => cell.nodes_mut()[1..].reverse(),
            Shape::Flat { corner } => {
                let at = node_label(&tags.nodes, cell.nodes()[corner]);
                let why = match cell {
                    Cell::Triangle(_) => "its three nodes are on one line".to_owned(),
                    Cell::Quad(_) => format!("its two edges at {at} are on one line"),
                };
                return Err(MeshError::new(format!(
                    "{} is degenerate: {why} (a zero Jacobian at {at}); a cell must enclose an area",
                    label()
                )));
            }
            Shape::Folded => {
                return Err(MeshError::new(format!(
                    "{} is inverted at some corners: its Jacobian changes sign from corner to corner (a non-convex \
                     or self-crossing quadrilateral); a quadrilateral must be convex",
                    label()
                )));
            }
        }
    }
    Ok(cells)
}

/// Refuses two cells that run along one edge in the same direction: counter-clockwise cells
/// that share an edge run along it in opposite directions, so these overlap.
fn check_overlaps(cells: &[Cell], tags: &Tags) -> Result<(), MeshError> {
    let mut edges: Vec<([usize; 2], usize)> = Vec::with_capacity(4 * cells.len());
    for (c, cell) in cells.iter().enumerate() {
        let n = cell.nodes();
        edges.extend((0..n.len()).map(|k| ([n[k], n[(k + 1) % n.len()]], c)));
    }
    edges.sort_unstable();
    match edges.windows(2).find(|w| w[0].0 == w[1].0) {
        None => Ok(()),
        Some(w) => {
            let label = |c: usize| cell_label(&tags.cells, &tags.nodes, c, cells[c].nodes());
            let [a, b] = w[0].0;
            Err(MeshError::new(format!(
                "{} and {} overlap: both run from {} to {} once turned counter-clockwise; cells may share an edge \
                 only from opposite sides",
                label(w[0].1),
                label(w[1].1),
                node_label(&tags.nodes, a),
                node_label(&tags.nodes, b)
            )))
        }
    }
}

/// The cells renumbered, each rotated to start at its smallest node, and sorted by their node
/// lists; with, for each canonical cell, its index in the input.
fn canonical_cells(cells: Vec<Cell>, new_index: &[usize]) -> (Vec<Cell>, Vec<usize>) {
    let mut cells: Vec<(Cell, usize)> = cells
        .into_iter()
        .enumerate()
        .map(|(c, mut cell)| {
            let n = cell.nodes_mut();
            n.iter_mut().for_each(|i| *i = new_index[*i]);
            let first = (0..n.len()).min_by_key(|&k| n[k]).unwrap_or(0);
            n.rotate_left(first);
            (cell, c)
        })
        .collect();
    cells.sort_unstable_by(|a, b| a.0.nodes().cmp(b.0.nodes()));
    cells.into_iter().unzip()
}

/// The groups with their members renumbered: cells ascending, lines and points in the input's
/// order. Refused: a member that does not exist, a node no cell uses, a line from a node to
/// itself, two groups with one name.
fn canonical_groups(
    groups: Vec<Group>,
    new_index: &[usize],
    new_cell: &[usize],
    tags: &Tags,
) -> Result<Vec<Group>, MeshError> {
    let mut names = HashSet::new();
    let mut out = Vec::with_capacity(groups.len());
    for group in groups {
        if !names.insert(group.name.clone()) {
            return Err(MeshError::new(format!(
                "two physical groups are called \"{}\": each group needs its own name",
                group.name
            )));
        }
        let refuse = |what: String| MeshError::new(format!("physical group \"{}\": {what}", group.name));
        let node = |i: usize| -> Result<usize, MeshError> {
            match new_index.get(i) {
                None => Err(refuse(format!("names node #{i}; there are {} nodes", new_index.len()))),
                Some(&usize::MAX) => Err(refuse(format!(
                    "names {}, which no cell uses: a group may name only the mesh's nodes",
                    node_label(&tags.nodes, i)
                ))),
                Some(&new) => Ok(new),
            }
        };
        let members = match &group.members {
            Members::Cells(cells) => {
                let mut renumbered = Vec::with_capacity(cells.len());
                for &c in cells {
                    let new = new_cell
                        .get(c)
                        .ok_or_else(|| refuse(format!("names cell #{c}; there are {} cells", new_cell.len())))?;
                    renumbered.push(*new);
                }
                renumbered.sort_unstable();
                renumbered.dedup();
                Members::Cells(renumbered)
            }
            Members::Lines(lines) => {
                let mut renumbered = Vec::with_capacity(lines.len());
                for &[a, b] in lines {
                    if a == b {
                        return Err(refuse(format!("has a line from {} to itself", node_label(&tags.nodes, a))));
                    }
                    renumbered.push([node(a)?, node(b)?]);
                }
                Members::Lines(renumbered)
            }
            Members::Points(points) => Members::Points(points.iter().map(|&p| node(p)).collect::<Result<_, _>>()?),
        };
        out.push(Group { members, ..group });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two unit squares side by side, given clockwise and out of order, with an unused node.
    fn two_squares() -> (Vec<[f64; 2]>, Vec<Cell>) {
        let nodes = vec![[2.0, 1.0], [9.0, 9.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 0.0], [0.0, 0.0]];
        let cells = vec![Cell::Quad([5, 2, 4, 0]), Cell::Quad([3, 4, 2, 6])];
        (nodes, cells)
    }

    #[test]
    fn cells_are_turned_counter_clockwise_and_renumbered() {
        let (nodes, cells) = two_squares();
        let groups = vec![
            Group { name: "right".into(), tag: 4, members: Members::Cells(vec![0]) },
            Group { name: "base".into(), tag: 1, members: Members::Lines(vec![[6, 2], [2, 5]]) },
            Group { name: "corner".into(), tag: 2, members: Members::Points(vec![0]) },
        ];
        let tags = Tags { nodes: vec![10, 11, 12, 13, 14, 15, 16], cells: vec![100, 101] };
        let mesh = Mesh::tagged(nodes, cells, groups, tags).unwrap();
        // By y then x: (0,0) (1,0) (2,0) (0,1) (1,1) (2,1); the unused node (9, 9) is gone.
        assert_eq!(mesh.nodes, vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 1.0]]);
        assert_eq!(mesh.node_tags, vec![16, 12, 15, 13, 14, 10]);
        assert_eq!(mesh.cells, vec![Cell::Quad([0, 1, 4, 3]), Cell::Quad([1, 2, 5, 4])]);
        assert_eq!(mesh.cell_tags, vec![101, 100]);
        assert_eq!(mesh.groups[0].members, Members::Cells(vec![1]));
        assert_eq!(mesh.groups[1].members, Members::Lines(vec![[0, 1], [1, 2]]));
        assert_eq!(mesh.groups[2].members, Members::Points(vec![5]));
    }

    #[test]
    fn minus_zero_is_zero() {
        let nodes = vec![[-0.0, -0.0], [1.0, -0.0], [0.0, 1.0]];
        let mesh = Mesh::new(nodes, vec![Cell::Triangle([0, 1, 2])], Vec::new()).unwrap();
        assert!(mesh.nodes.iter().flatten().all(|x| x.is_sign_positive()));
    }

    fn refusal(nodes: Vec<[f64; 2]>, cells: Vec<Cell>, groups: Vec<Group>) -> String {
        Mesh::new(nodes, cells, groups).unwrap_err().to_string()
    }

    #[test]
    fn bad_meshes_are_refused_saying_why() {
        let tri = || vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let cell = || vec![Cell::Triangle([0, 1, 2])];
        assert_eq!(refusal(tri(), Vec::new(), Vec::new()), "the mesh has no 2-D cell (triangle or quadrilateral)");
        assert_eq!(
            refusal(tri(), vec![Cell::Triangle([0, 1, 3])], Vec::new()),
            "cell #0 (nodes #0 #1 #3) names node #3; there are 3 nodes"
        );
        assert!(
            refusal(tri(), vec![Cell::Triangle([0, 1, 1])], Vec::new())
                .ends_with("names node #1 twice: a cell's corners must be distinct")
        );
        let nan = vec![[0.0, 0.0], [f64::NAN, 0.0], [0.0, 1.0]];
        assert_eq!(refusal(nan, cell(), Vec::new()), "node #1 is at (NaN, 0): coordinates must be finite numbers");
        let same = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
        let e = refusal(same, vec![Cell::Triangle([0, 1, 2]), Cell::Triangle([3, 2, 0])], Vec::new());
        assert_eq!(e, "node #1 and node #3 are both at (1, 0): each point of the mesh must be one node");
        let line = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
        assert!(refusal(line, cell(), Vec::new()).contains("is degenerate: its three nodes are on one line"));
        let group = |members| vec![Group { name: "g".into(), tag: 1, members }];
        let unused = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 5.0]];
        assert_eq!(
            refusal(unused, cell(), group(Members::Points(vec![3]))),
            "physical group \"g\": names node #3, which no cell uses: a group may name only the mesh's nodes"
        );
        assert!(
            refusal(tri(), cell(), group(Members::Lines(vec![[1, 1]]))).ends_with("has a line from node #1 to itself")
        );
        assert!(refusal(tri(), cell(), group(Members::Cells(vec![1]))).ends_with("names cell #1; there are 1 cells"));
        let twice = vec![group(Members::Cells(vec![0])).remove(0), group(Members::Points(vec![0])).remove(0)];
        assert_eq!(
            refusal(tri(), cell(), twice),
            "two physical groups are called \"g\": each group needs its own name"
        );
    }

    #[test]
    fn overlapping_cells_are_refused() {
        // The same triangle twice (once clockwise), and a triangle folded over its neighbour.
        let nodes = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.2]];
        let e = refusal(nodes.clone(), vec![Cell::Triangle([0, 1, 2]), Cell::Triangle([2, 1, 0])], Vec::new());
        assert!(e.contains("overlap: both run from"), "{e}");
        let e = refusal(nodes, vec![Cell::Triangle([0, 1, 2]), Cell::Triangle([0, 1, 3])], Vec::new());
        let expected =
            "cell #0 (nodes #0 #1 #2) and cell #1 (nodes #0 #1 #3) overlap: both run from node #0 to node #1";
        assert!(e.starts_with(expected), "{e}");
    }
}
