//! What the spatial view draws of a body, at a level of detail a screen can show: every edge of
//! a mesh up to [`MAX_EDGES`]; beyond that its boundary, so that a recording grows with the
//! contacts and the run's events rather than with the body's elements. Contacts are always
//! drawn segment by segment.

use crate::fem::Mesh;
use crate::fem::curve::Segment;
use crate::frame::MeshDrawing;
use crate::frame::drawing::Drawn;

/// Edges drawn in full; a finer mesh draws its boundary only.
pub const MAX_EDGES: usize = 20_000;

/// Grid lines a structured block draws across and along: every node up to these, else every
/// k-th column or row (the outer ones always).
pub const MOST_LINES: (usize, usize) = (101, 21);

/// The drawing of `mesh` with its contacts' segments; with the mesh node of each drawn node.
pub fn of_mesh(mesh: &Mesh, contacts: &[Vec<Segment>]) -> (MeshDrawing, Vec<usize>) {
    let mut edges = edges(mesh);
    if edges.len() > MAX_EDGES {
        edges.retain(|e| e.1 == 1);
    }
    let lines = polylines(edges.iter().map(|e| e.0).collect());
    let mut drawing = Drawn::default();
    let lines: Vec<Vec<u32>> =
        lines.into_iter().map(|line| line.into_iter().map(|n| drawing.index(n)).collect()).collect();
    let contact = contacts.iter().flatten().map(|s| s.nodes.map(|n| drawing.index(n))).collect();
    let offset = 0.12 * extent(mesh);
    let bases = contacts.iter().map(|chain| base_line(chain, &mesh.nodes, offset)).collect();
    let nodes = drawing.nodes.iter().map(|&n| mesh.nodes[n]).collect();
    (MeshDrawing { nodes, lines, contact, bases }, drawing.nodes)
}

/// Every edge of the mesh's cells once, with how many cells share it (1 on the boundary).
fn edges(mesh: &Mesh) -> Vec<([usize; 2], usize)> {
    let mut all: Vec<[usize; 2]> = mesh
        .cells
        .iter()
        .flat_map(|cell| {
            let n = cell.nodes();
            (0..n.len()).map(move |a| {
                let (p, q) = (n[a], n[(a + 1) % n.len()]);
                [p.min(q), p.max(q)]
            })
        })
        .collect();
    all.sort_unstable();
    let mut counted: Vec<([usize; 2], usize)> = Vec::with_capacity(all.len());
    for edge in all {
        match counted.last_mut() {
            Some((last, count)) if *last == edge => *count += 1,
            _ => counted.push((edge, 1)),
        }
    }
    counted
}

/// Edges joined greedily into polylines, fewer strips to send than edges.
fn polylines(edges: Vec<[usize; 2]>) -> Vec<Vec<usize>> {
    let mut by_node: std::collections::HashMap<usize, Vec<usize>> = std::collections::HashMap::new();
    for (k, e) in edges.iter().enumerate() {
        for n in e {
            by_node.entry(*n).or_default().push(k);
        }
    }
    let mut used = vec![false; edges.len()];
    let mut lines = Vec::new();
    for start in 0..edges.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut line = edges[start].to_vec();
        loop {
            let end = *line.last().expect("a line has nodes");
            let next = by_node[&end].iter().copied().find(|&k| !used[k]);
            let Some(k) = next else { break };
            used[k] = true;
            line.push(if edges[k][0] == end { edges[k][1] } else { edges[k][0] });
        }
        lines.push(line);
    }
    lines
}

/// The smaller side of the mesh's bounding box (m).
fn extent(mesh: &Mesh) -> f64 {
    let range = |k: usize| {
        let (low, high) =
            mesh.nodes.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p[k]), b.max(p[k])));
        high - low
    };
    range(0).min(range(1))
}

/// A contact's main body: the chain moved out of the body by `offset` along each node's
/// mean normal.
fn base_line(chain: &[Segment], coordinates: &[[f64; 2]], offset: f64) -> Vec<[f64; 2]> {
    let mut out = Vec::with_capacity(chain.len() + 1);
    for (k, s) in chain.iter().enumerate() {
        let normal = match k.checked_sub(1).map(|p| chain[p].normal) {
            Some(previous) => [0.5 * (previous[0] + s.normal[0]), 0.5 * (previous[1] + s.normal[1])],
            None => s.normal,
        };
        let [x, y] = coordinates[s.nodes[0]];
        out.push([x - offset * normal[0], y - offset * normal[1]]);
    }
    if let Some(last) = chain.last() {
        let [x, y] = coordinates[last.nodes[1]];
        out.push([x - offset * last.normal[0], y - offset * last.normal[1]]);
    }
    out
}
