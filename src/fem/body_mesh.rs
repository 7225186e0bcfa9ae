//! PLACEHOLDER until the Gmsh reader's mesh type lands: the general 2-D mesh.

/// A 2-D mesh: nodes, cells, named groups.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    pub nodes: Vec<[f64; 2]>,
    pub cells: Vec<Cell>,
    pub groups: Vec<Group>,
    pub node_tags: Vec<u64>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cell {
    Triangle([usize; 3]),
    Quad([usize; 4]),
}

impl Cell {
    pub fn nodes(&self) -> &[usize] {
        match self {
            Cell::Triangle(n) => n,
            Cell::Quad(n) => n,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    pub name: String,
    pub tag: i32,
    pub members: Members,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Members {
    Cells(Vec<usize>),
    Lines(Vec<[usize; 2]>),
    Points(Vec<usize>),
}

#[derive(Debug, Clone, PartialEq)]
pub struct MeshError {
    pub message: String,
}

impl std::fmt::Display for MeshError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for MeshError {}

impl Mesh {
    pub fn new(nodes: Vec<[f64; 2]>, cells: Vec<Cell>, groups: Vec<Group>) -> Result<Mesh, MeshError> {
        Ok(Mesh { nodes, cells, groups, node_tags: Vec::new() })
    }

    pub fn group(&self, name: &str) -> Result<&Group, MeshError> {
        self.groups.iter().find(|g| g.name == name).ok_or_else(|| MeshError { message: format!("no group {name}") })
    }

    pub fn boundary_chain(&self, group: &str) -> Result<Vec<usize>, MeshError> {
        let Members::Lines(lines) = &self.group(group)?.members else {
            return Err(MeshError { message: "not lines".into() });
        };
        // Orient each line with the body on its left, then chain them.
        let mut oriented = Vec::new();
        for &[a, b] in lines {
            let cell = self.cells.iter().find(|c| c.nodes().contains(&a) && c.nodes().contains(&b)).unwrap();
            let n = cell.nodes();
            let i = n.iter().position(|&x| x == a).unwrap();
            oriented.push(if n[(i + 1) % n.len()] == b { [a, b] } else { [b, a] });
        }
        let start = oriented.iter().find(|l| !oriented.iter().any(|m| m[1] == l[0])).unwrap()[0];
        let mut chain = vec![start];
        while let Some(l) = oriented.iter().find(|l| l[0] == *chain.last().unwrap()) {
            chain.push(l[1]);
        }
        Ok(chain)
    }
}
