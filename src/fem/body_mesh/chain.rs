//! [`Mesh::boundary_chain`]: a curve group as one open chain of boundary nodes, ordered with the
//! body on the left.

use super::error::cell_label;
use super::{Members, Mesh, MeshError};
use std::collections::{BTreeMap, HashMap, HashSet};

/// An edge of the mesh's cells, by its sorted nodes: the direction in which the first cell
/// that has it runs along it (counter-clockwise, so that cell is on its left), and the cells
/// that have it.
struct Side {
    from: usize,
    to: usize,
    cells: Vec<usize>,
}

impl Mesh {
    /// The nodes of a curve group as ONE open chain of boundary edges, ordered so that the
    /// body lies on the LEFT of the direction of travel (counter-clockwise around the body).
    /// Refused, saying what was found: a line that is not an edge of exactly one cell (an
    /// interior line, or not a mesh edge), a branch (a node with 3+ lines), a closed loop,
    /// several disjoint pieces, a group of another dimension, an empty group.
    pub fn boundary_chain(&self, group: &str) -> Result<Vec<usize>, MeshError> {
        let found = self.group(group)?;
        let refuse = |what: String| MeshError::new(format!("physical group \"{group}\" {what}"));
        let Members::Lines(lines) = &found.members else {
            let what = found.members.describe();
            return Err(refuse(format!("is a {what}: a boundary chain is made of the lines of a curve group")));
        };
        if lines.is_empty() {
            return Err(refuse("has no lines: a boundary chain needs at least one".to_owned()));
        }
        let next = self.boundary_steps(lines).map_err(refuse)?;
        self.one_open_chain(&next).map_err(refuse)
    }

    /// Every edge of every cell, by its sorted nodes.
    fn sides(&self) -> HashMap<[usize; 2], Side> {
        let mut sides: HashMap<[usize; 2], Side> = HashMap::with_capacity(3 * self.cells.len());
        for (c, cell) in self.cells.iter().enumerate() {
            let n = cell.nodes();
            for k in 0..n.len() {
                let (from, to) = (n[k], n[(k + 1) % n.len()]);
                let side = sides.entry([from.min(to), from.max(to)]).or_insert(Side { from, to, cells: Vec::new() });
                side.cells.push(c);
            }
        }
        sides
    }

    /// The group's lines as steps along the boundary, `next[from] = to`, each in the direction
    /// that keeps its cell on the left. Refused: a line on no cell or on two, a branch, or two
    /// lines leaving (or reaching) one node.
    fn boundary_steps(&self, lines: &[[usize; 2]]) -> Result<BTreeMap<usize, usize>, String> {
        let sides = self.sides();
        let line = |[a, b]: [usize; 2]| format!("the line from {} to {}", self.node_label(a), self.node_label(b));
        let (mut next, mut previous, mut degree) = (BTreeMap::new(), HashMap::new(), BTreeMap::new());
        let mut seen = HashSet::with_capacity(lines.len());
        for &[a, b] in lines {
            if !seen.insert([a.min(b), a.max(b)]) {
                continue; // the same line twice: once is enough
            }
            let side = match sides.get(&[a.min(b), a.max(b)]) {
                None => return Err(format!("has {}, which is not an edge of any cell", line([a, b]))),
                Some(side) if side.cells.len() > 1 => {
                    let cells: Vec<String> = side.cells.iter().map(|&c| self.cell_label(c)).collect();
                    return Err(format!(
                        "has {}, an edge of {}: it is inside the body, not on its boundary",
                        line([a, b]),
                        cells.join(" and ")
                    ));
                }
                Some(side) => side,
            };
            *degree.entry(side.from).or_insert(0) += 1;
            *degree.entry(side.to).or_insert(0) += 1;
            next.insert(side.from, side.to);
            previous.insert(side.to, side.from);
        }
        if let Some((&node, &lines)) = degree.iter().find(|&(_, &d)| d >= 3) {
            let at = self.node_label(node);
            return Err(format!(
                "branches at {at}: {lines} of its lines meet there; a boundary chain is one open path"
            ));
        }
        if next.len() + previous.len() < 2 * seen.len() {
            let pinch = degree.keys().find(|&n| degree[n] == 2 && next.contains_key(n) != previous.contains_key(n));
            let at = pinch.map_or_else(String::new, |&n| format!(" at {}", self.node_label(n)));
            return Err(format!(
                "has two lines that both leave or both reach one node{at}, going around the body: the body touches \
                 itself there, and a boundary chain cannot pass through"
            ));
        }
        Ok(next)
    }

    /// The one open chain that `next` makes; refused if it makes a closed loop or several pieces.
    fn one_open_chain(&self, next: &BTreeMap<usize, usize>) -> Result<Vec<usize>, String> {
        let reached: HashSet<usize> = next.values().copied().collect();
        let mut pieces = Vec::new();
        let mut walked = HashSet::new();
        let mut chain = Vec::new();
        for &start in next.keys().filter(|n| !reached.contains(n)) {
            let (mut nodes, mut at) = (vec![start], start);
            while let Some(&to) = next.get(&at) {
                walked.insert(at);
                nodes.push(to);
                at = to;
            }
            pieces.push(format!("from {} to {}", self.node_label(start), self.node_label(at)));
            chain = nodes;
        }
        let mut loops = 0;
        for &start in next.keys() {
            if walked.contains(&start) {
                continue;
            }
            loops += 1;
            let mut at = Some(start);
            while let Some(n) = at.filter(|&n| walked.insert(n)) {
                at = next.get(&n).copied();
            }
            pieces.push(format!("a closed loop through {}", self.node_label(start)));
        }
        match (pieces.len(), loops) {
            (1, 0) => Ok(chain),
            (1, _) => Err(format!(
                "is a closed loop of {} lines (through {}): a boundary chain has two ends; split the curve into two groups",
                next.len(),
                self.node_label(*next.keys().next().unwrap_or(&0))
            )),
            (n, _) => {
                let shown = pieces.iter().take(4).cloned().collect::<Vec<_>>().join(", ");
                let more = if n > 4 { format!(" and {} more", n - 4) } else { String::new() };
                Err(format!("has {n} disjoint pieces ({shown}{more}): a boundary chain is one open chain of lines"))
            }
        }
    }

    /// How a message names cell `c`: `element 23 (nodes 1 2 21 22)`, or by indices.
    fn cell_label(&self, c: usize) -> String {
        cell_label(&self.cell_tags, &self.node_tags, c, self.cells[c].nodes())
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Cell, Group};
    use super::*;

    /// A 3 x 2 grid of unit squares: node (i, j) is j * 4 + i, for i in 0..4, j in 0..3.
    fn grid(groups: Vec<(&str, Members)>) -> Mesh {
        let nodes = (0..3).flat_map(|j| (0..4).map(move |i| [i as f64, j as f64])).collect();
        let cells = (0..2).flat_map(|j| (0..3).map(move |i| j * 4 + i)).map(|n| Cell::Quad([n, n + 1, n + 5, n + 4]));
        let groups = groups.into_iter().enumerate();
        let groups = groups.map(|(k, (name, members))| Group { name: name.into(), tag: k as i32, members }).collect();
        Mesh::new(nodes, cells.collect(), groups).unwrap()
    }

    fn refusal(lines: Vec<[usize; 2]>) -> String {
        grid(vec![("g", Members::Lines(lines))]).boundary_chain("g").unwrap_err().to_string()
    }

    #[test]
    fn chains_keep_the_body_on_their_left_whatever_the_lines_order_and_direction() {
        // The bottom from right to left, each line backwards: the chain runs left to right.
        let mesh = grid(vec![
            ("bottom", Members::Lines(vec![[3, 2], [1, 0], [2, 1]])),
            ("top", Members::Lines(vec![[8, 9], [9, 10]])),
        ]);
        assert_eq!(mesh.boundary_chain("bottom").unwrap(), vec![0, 1, 2, 3]);
        assert_eq!(mesh.boundary_chain("top").unwrap(), vec![10, 9, 8]);
        // Around a corner: up the right side, then left along the top.
        let mesh = grid(vec![("corner", Members::Lines(vec![[10, 11], [3, 7], [11, 7]]))]);
        assert_eq!(mesh.boundary_chain("corner").unwrap(), vec![3, 7, 11, 10]);
    }

    #[test]
    fn broken_chains_are_refused_saying_what_was_found() {
        assert_eq!(
            refusal(vec![[4, 5], [5, 6]]),
            "physical group \"g\" has the line from node #4 to node #5, an edge of cell #0 (nodes #0 #1 #5 #4) and \
             cell #3 (nodes #4 #5 #9 #8): it is inside the body, not on its boundary"
        );
        assert!(
            refusal(vec![[0, 5]]).ends_with("has the line from node #0 to node #5, which is not an edge of any cell")
        );
        assert!(refusal(vec![[0, 1], [2, 3]]).ends_with(
            "has 2 disjoint pieces (from node #0 to node #1, from node #2 to node #3): a boundary chain is one open chain of lines"
        ));
        let around = vec![[0, 1], [1, 2], [2, 3], [3, 7], [7, 11], [11, 10], [10, 9], [9, 8], [8, 4], [4, 0]];
        assert!(refusal(around).ends_with("is a closed loop of 10 lines (through node #0): a boundary chain has two ends; split the curve into two groups"));
    }

    #[test]
    fn a_branch_and_groups_of_other_kinds_are_refused() {
        // Three boundary lines meet at a node only where the body touches itself: two triangles
        // that share one corner (a bow tie), whose four sides at that corner are all boundary.
        let nodes = vec![[0.0, 0.0], [1.0, 1.0], [0.0, 2.0], [2.0, 0.0], [2.0, 2.0]];
        let cells = vec![Cell::Triangle([0, 1, 2]), Cell::Triangle([1, 3, 4])];
        let group = |lines| vec![Group { name: "g".into(), tag: 1, members: Members::Lines(lines) }];
        let mesh = Mesh::new(nodes.clone(), cells.clone(), group(vec![[0, 1], [1, 2], [1, 3]])).unwrap();
        let e = mesh.boundary_chain("g").unwrap_err().to_string();
        assert!(
            e.ends_with("branches at node #2: 3 of its lines meet there; a boundary chain is one open path"),
            "{e}"
        );
        // Two lines that both reach the shared corner: the chain would have to jump across it.
        let mesh = Mesh::new(nodes, cells, group(vec![[0, 1], [4, 1]])).unwrap();
        let e = mesh.boundary_chain("g").unwrap_err().to_string();
        assert!(e.contains("two lines that both leave or both reach one node at node #2"), "{e}");
        let mesh = grid(vec![("body", Members::Cells(vec![0])), ("empty", Members::Lines(Vec::new()))]);
        assert_eq!(
            mesh.boundary_chain("body").unwrap_err().to_string(),
            "physical group \"body\" is a surface (dimension 2, 1 cell): a boundary chain is made of the lines of a curve group"
        );
        assert_eq!(
            mesh.boundary_chain("empty").unwrap_err().to_string(),
            "physical group \"empty\" has no lines: a boundary chain needs at least one"
        );
        assert!(
            mesh.boundary_chain("none").unwrap_err().to_string().starts_with("the mesh has no physical group \"none\"")
        );
    }
}
