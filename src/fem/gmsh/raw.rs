//! What a reader takes from a Gmsh file before it is a mesh (nodes with their tags, the elements
//! with the physical groups each is in, the groups' names), and how that becomes a [`Mesh`]:
//! the same for every version of the format.

use super::element_types::{ElementType, LINE, POINT, QUAD, SUPPORTED_CELLS, SUPPORTED_LINES, TRIANGLE};
use super::physical_names::PhysicalName;
use super::source::Source;
use crate::fem::body_mesh::{Cell, Group, Members, Mesh, MeshError, Tags};
use crate::validate::shortest;
use std::collections::HashMap;

/// The most physical groups one element (or entity) may be in. A group's members are listed
/// one by one, so without a bound a small file could ask for a huge mesh: ten thousand tags on
/// an entity of ten thousand elements make a hundred million members.
pub(super) const MAX_GROUPS: usize = 32;

/// The refusal of an element or entity in more than [`MAX_GROUPS`] groups.
pub(super) fn too_many_groups(what: &str) -> String {
    format!("{what} is in more than {MAX_GROUPS} physical groups: slipfront reads at most {MAX_GROUPS} per element")
}

/// A node as the file gives it.
pub(super) struct RawNode {
    pub tag: u64,
    pub xyz: [f64; 3],
    /// The offset of its coordinates in the file.
    pub at: usize,
}

/// What an element is to slipfront.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Kind {
    Point,
    Line,
    Triangle,
    Quad,
    /// A point or curve element of another type (a 3-node line...): refused if it is in a
    /// physical group, ignored otherwise.
    Other(ElementType),
}

impl Kind {
    /// What slipfront makes of an element of type `t`: refused (with the reason) if it is 3-D,
    /// or 2-D and neither a 3-node triangle nor a 4-node quadrilateral.
    pub fn of(t: ElementType) -> Result<Kind, String> {
        let name = format!("type {} ({})", t.code, t.name);
        match (t.dimension, t.code) {
            (0, POINT) => Ok(Kind::Point),
            (1, LINE) => Ok(Kind::Line),
            (2, TRIANGLE) => Ok(Kind::Triangle),
            (2, QUAD) => Ok(Kind::Quad),
            (0 | 1, _) => Ok(Kind::Other(t)),
            (2, _) => Err(format!(
                "{name} is a 2-D element slipfront does not read: it reads {SUPPORTED_CELLS} (first-order \
                 elements: in Gmsh, Mesh.ElementOrder = 1)"
            )),
            _ => Err(format!("{name} is a 3-D element: slipfront reads 2-D meshes, of {SUPPORTED_CELLS}")),
        }
    }

    fn dimension(self) -> u8 {
        match self {
            Kind::Point => 0,
            Kind::Line => 1,
            Kind::Triangle | Kind::Quad => 2,
            Kind::Other(t) => t.dimension,
        }
    }

    /// How many of the element's node tags are kept (`RawElement::nodes`).
    pub fn kept_nodes(self) -> usize {
        match self {
            Kind::Point => 1,
            Kind::Line => 2,
            Kind::Triangle => 3,
            Kind::Quad => 4,
            Kind::Other(_) => 0,
        }
    }
}

/// An element as the file gives it.
pub(super) struct RawElement {
    pub tag: u64,
    pub kind: Kind,
    /// Its first `kind.kept_nodes()` node tags.
    pub nodes: [u64; 4],
    /// The physical groups it is in: an index into [`RawMesh::group_sets`].
    pub groups: usize,
    /// The offset of the element in the file.
    pub at: usize,
}

#[derive(Default)]
pub(super) struct RawMesh {
    pub names: Vec<PhysicalName>,
    pub nodes: Vec<RawNode>,
    pub elements: Vec<RawElement>,
    /// The lists of physical tags that elements are in.
    pub group_sets: Vec<Vec<i32>>,
}

impl RawMesh {
    /// The mesh the file describes: its 2-D cells (in groups or not), the lines and points
    /// that are in groups, and the groups; validated by [`Mesh::tagged`], which names nodes
    /// and cells by their tags.
    pub fn into_mesh(self, src: &Source) -> Result<Mesh, MeshError> {
        let index = self.node_index(src)?;
        let mut groups = Groups::named(&self.names, src)?;
        let (mut cells, mut cell_tags) = (Vec::new(), Vec::new());
        let mut used = vec![false; self.nodes.len()];
        for e in &self.elements {
            let tags = &self.group_sets[e.groups];
            if let Kind::Other(t) = e.kind {
                if let Some(&tag) = tags.first() {
                    let group = groups.name(t.dimension, tag);
                    let (code, name) = (t.code, t.name);
                    return Err(src.error(
                        e.at,
                        format!(
                            "element {} of type {code} ({name}) is in physical group \"{group}\": slipfront reads \
                             curve groups of {SUPPORTED_LINES} and point groups of type 15 (Point)",
                            e.tag
                        ),
                    ));
                }
                continue;
            }
            if e.kind.dimension() < 2 && tags.is_empty() {
                continue; // a line or point in no group: nothing to do with it
            }
            let mut nodes = [0; 4];
            for (k, &tag) in e.nodes[..e.kind.kept_nodes()].iter().enumerate() {
                nodes[k] = *index.get(&tag).ok_or_else(|| {
                    src.error(e.at, format!("element {} names node {tag}, which $Nodes does not define", e.tag))
                })?;
            }
            let members: Vec<Member> = match e.kind {
                Kind::Triangle | Kind::Quad => {
                    let cell = if e.kind == Kind::Quad {
                        Cell::Quad(nodes)
                    } else {
                        Cell::Triangle([nodes[0], nodes[1], nodes[2]])
                    };
                    cell.nodes().iter().for_each(|&n| used[n] = true);
                    cells.push(cell);
                    cell_tags.push(e.tag);
                    tags.iter().map(|&t| Member::Cell(t, cells.len() - 1)).collect()
                }
                Kind::Line => tags.iter().map(|&t| Member::Line(t, [nodes[0], nodes[1]])).collect(),
                _ => tags.iter().map(|&t| Member::Point(t, nodes[0])).collect(),
            };
            members.into_iter().for_each(|m| groups.add(m));
        }
        self.check_plane(&used, src)?;
        let node_tags = self.nodes.iter().map(|n| n.tag).collect();
        let nodes = self.nodes.into_iter().map(|n| [n.xyz[0], n.xyz[1]]).collect();
        Mesh::tagged(nodes, cells, groups.list, Tags { nodes: node_tags, cells: cell_tags })
    }

    /// The index of each node tag; refused if a tag is defined twice.
    fn node_index(&self, src: &Source) -> Result<HashMap<u64, usize>, MeshError> {
        let mut index = HashMap::with_capacity(self.nodes.len());
        for (i, node) in self.nodes.iter().enumerate() {
            if let Some(first) = index.insert(node.tag, i) {
                let first = src.place(self.nodes[first].at);
                return Err(src.error(node.at, format!("node {} is defined twice (first at {first})", node.tag)));
            }
        }
        Ok(index)
    }

    /// Every node a cell uses has a finite z, the same for all: a 2-D mesh lies in one plane.
    fn check_plane(&self, used: &[bool], src: &Source) -> Result<(), MeshError> {
        let mut plane: Option<&RawNode> = None;
        for node in self.nodes.iter().zip(used).filter(|&(_, &u)| u).map(|(n, _)| n) {
            let z = node.xyz[2];
            if !z.is_finite() {
                return Err(src
                    .error(node.at, format!("node {} has z = {}: coordinates must be finite", node.tag, shortest(z))));
            }
            match plane {
                None => plane = Some(node),
                Some(first) if first.xyz[2] != z => {
                    return Err(src.error(
                        node.at,
                        format!(
                            "node {} is at z = {}, node {} at z = {}: a 2-D mesh lies in one plane z = const",
                            node.tag,
                            shortest(z),
                            first.tag,
                            shortest(first.xyz[2])
                        ),
                    ));
                }
                Some(_) => {}
            }
        }
        Ok(())
    }
}

/// One membership: physical tag, and the cell index, line or node index.
enum Member {
    Cell(i32, usize),
    Line(i32, [usize; 2]),
    Point(i32, usize),
}

/// The groups being built, in the order they first appear: named ones as `$PhysicalNames`
/// lists them, then unnamed ones as elements name them.
struct Groups {
    list: Vec<Group>,
    by_key: HashMap<(u8, i32), usize>,
}

impl Groups {
    /// The named groups of dimension 0 to 2 (a 2-D mesh has no volume); refused if the file
    /// names one group twice.
    fn named(names: &[PhysicalName], src: &Source) -> Result<Groups, MeshError> {
        let mut groups = Groups { list: Vec::new(), by_key: HashMap::new() };
        for n in names.iter().filter(|n| n.dimension < 3) {
            if groups.by_key.contains_key(&(n.dimension, n.tag)) {
                let (d, t) = (n.dimension, n.tag);
                return Err(src.error(n.at, format!("physical group {t} of dimension {d} is named twice")));
            }
            let name = if n.name.is_empty() { n.tag.to_string() } else { n.name.clone() };
            groups.insert(n.dimension, n.tag, name);
        }
        Ok(groups)
    }

    fn insert(&mut self, dimension: u8, tag: i32, name: String) -> usize {
        let members = match dimension {
            2 => Members::Cells(Vec::new()),
            1 => Members::Lines(Vec::new()),
            _ => Members::Points(Vec::new()),
        };
        self.list.push(Group { name, tag, members });
        self.by_key.insert((dimension, tag), self.list.len() - 1);
        self.list.len() - 1
    }

    /// The group of dimension `dimension` and tag `tag`, made (named by its tag) if new.
    fn slot(&mut self, dimension: u8, tag: i32) -> usize {
        match self.by_key.get(&(dimension, tag)) {
            Some(&g) => g,
            None => self.insert(dimension, tag, tag.to_string()),
        }
    }

    fn name(&mut self, dimension: u8, tag: i32) -> String {
        let g = self.slot(dimension, tag);
        self.list[g].name.clone()
    }

    fn add(&mut self, member: Member) {
        match member {
            Member::Cell(tag, c) => {
                let g = self.slot(2, tag);
                if let Members::Cells(cells) = &mut self.list[g].members {
                    cells.push(c);
                }
            }
            Member::Line(tag, line) => {
                let g = self.slot(1, tag);
                if let Members::Lines(lines) = &mut self.list[g].members {
                    lines.push(line);
                }
            }
            Member::Point(tag, node) => {
                let g = self.slot(0, tag);
                if let Members::Points(points) = &mut self.list[g].members {
                    points.push(node);
                }
            }
        }
    }
}
