//! MSH 2.2 ASCII: `$Nodes` as `tag x y z` lines, `$Elements` as `tag type ntags tags... nodes...`
//! lines whose first tag is the physical group (0: none). An element in several groups is
//! written once per group: its copies are merged into one element in all of them.

use super::element_types::{element_type, unknown};
use super::physical_names;
use super::raw::{Kind, MAX_GROUPS, RawElement, RawMesh, RawNode, too_many_groups};
use super::source::Source;
use crate::fem::body_mesh::MeshError;
use std::collections::HashMap;

/// Reads the sections after `$MeshFormat`.
pub(super) fn read(src: &mut Source) -> Result<RawMesh, MeshError> {
    let mut raw = RawMesh::default();
    let mut sets = GroupSets::default();
    while let Some((name, at)) = src.section()? {
        match name.as_str() {
            "$PhysicalNames" => raw.names.extend(physical_names::read(src)?),
            "$Nodes" => read_nodes(src, &mut raw.nodes)?,
            "$Elements" => read_elements(src, &mut raw.elements, &mut sets)?,
            "$MeshFormat" => return Err(src.error(at, "a second $MeshFormat: a file holds one mesh")),
            _ => src.skip_section(&name)?,
        }
    }
    raw.group_sets = sets.lists;
    Ok(raw)
}

/// `$Nodes`: `count`, then `tag x y z` per node.
fn read_nodes(src: &mut Source, nodes: &mut Vec<RawNode>) -> Result<(), MeshError> {
    let (count, _) = src.parsed::<u64>("the number of nodes")?;
    nodes.reserve(src.capacity(count, "1 0 0 0\n".len()));
    for _ in 0..count {
        let (tag, at) = src.parsed::<u64>("a node tag")?;
        let xyz = [src.real("an x")?, src.real("a y")?, src.real("a z")?];
        nodes.push(RawNode { tag, xyz, at });
    }
    src.end_section("$Nodes")
}

/// `$Elements`: `count`, then `tag type ntags physical entity [partitions...] nodes...` per
/// element.
fn read_elements(src: &mut Source, elements: &mut Vec<RawElement>, sets: &mut GroupSets) -> Result<(), MeshError> {
    let (count, _) = src.parsed::<u64>("the number of elements")?;
    elements.reserve(src.capacity(count, "1 15 0 1\n".len()));
    // The first copy of each cell, by its type and nodes, to merge the copies into.
    let mut cells: HashMap<(Kind, [u64; 4]), usize> = HashMap::new();
    for _ in 0..count {
        let (tag, at) = src.parsed::<u64>("an element tag")?;
        let (code, _) = src.parsed::<i32>("an element type")?;
        let t = element_type(code).ok_or_else(|| src.error(at, unknown(code)))?;
        let kind = Kind::of(t).map_err(|why| src.error(at, format!("element {tag}: {why}")))?;
        let (tags, _) = src.parsed::<u64>("an element's number of tags")?;
        let mut physical = None;
        for k in 0..tags {
            let (value, _) = src.parsed::<i32>("an element tag (physical group, entity, partitions)")?;
            if k == 0 && value != 0 {
                physical = Some(value);
            }
        }
        let mut nodes = [0; 4];
        for n in 0..t.nodes {
            let (node, _) = src.parsed::<u64>("a node tag")?;
            if n < kind.kept_nodes() {
                nodes[n] = node;
            }
        }
        let first = match kind {
            Kind::Triangle | Kind::Quad => cells.get(&(kind, nodes)).copied(),
            _ => None,
        };
        match first {
            Some(e) => {
                let merged = sets.with(elements[e].groups, physical);
                if sets.lists[merged].len() > MAX_GROUPS {
                    return Err(src.error(at, too_many_groups(&format!("element {tag} (with its copies)"))));
                }
                elements[e].groups = merged;
            }
            None => {
                if matches!(kind, Kind::Triangle | Kind::Quad) {
                    cells.insert((kind, nodes), elements.len());
                }
                let empty = sets.empty();
                let groups = sets.with(empty, physical);
                elements.push(RawElement { tag, kind, nodes, groups, at });
            }
        }
    }
    src.end_section("$Elements")
}

/// The distinct lists of physical tags that elements are in, each stored once.
#[derive(Default)]
struct GroupSets {
    lists: Vec<Vec<i32>>,
    index: HashMap<Vec<i32>, usize>,
}

impl GroupSets {
    fn intern(&mut self, list: Vec<i32>) -> usize {
        if let Some(&i) = self.index.get(&list) {
            return i;
        }
        self.lists.push(list.clone());
        self.index.insert(list, self.lists.len() - 1);
        self.lists.len() - 1
    }

    /// The empty list: in no group.
    fn empty(&mut self) -> usize {
        self.intern(Vec::new())
    }

    /// List `set` with `physical` added (if it is not there already).
    fn with(&mut self, set: usize, physical: Option<i32>) -> usize {
        match physical {
            Some(p) if !self.lists[set].contains(&p) => {
                let mut list = self.lists[set].clone();
                list.push(p);
                self.intern(list)
            }
            _ => set,
        }
    }
}
