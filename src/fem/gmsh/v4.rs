//! MSH 4.1, ASCII and binary alike (the [`Source`] reads each number as a word or as
//! little-endian bytes): `$Entities` carry the physical tags, `$Nodes` and `$Elements` come in
//! blocks, one per entity, and an element's groups are its entity's.

use super::element_types::{ElementType, element_type, unknown};
use super::physical_names;
use super::raw::{Kind, MAX_GROUPS, RawElement, RawMesh, RawNode, too_many_groups};
use super::source::Source;
use crate::fem::body_mesh::MeshError;
use std::collections::HashMap;

/// An entity: its dimension and tag.
type EntityKey = (u8, i32);

/// The entities that element blocks name, in order of first mention; an element's
/// `RawElement::groups` is its entity's index here.
#[derive(Default)]
struct EntityRefs {
    keys: Vec<(EntityKey, usize)>,
    index: HashMap<EntityKey, usize>,
}

/// Reads the sections after `$MeshFormat`.
pub(super) fn read(src: &mut Source) -> Result<RawMesh, MeshError> {
    let mut raw = RawMesh::default();
    let mut entities: Option<HashMap<EntityKey, Vec<i32>>> = None;
    let mut refs = EntityRefs::default();
    while let Some((name, at)) = src.section()? {
        match name.as_str() {
            "$PhysicalNames" => raw.names.extend(physical_names::read(src)?),
            "$Entities" => entities = Some(read_entities(src)?),
            "$Nodes" => read_nodes(src, &mut raw.nodes)?,
            "$Elements" => read_elements(src, &mut raw.elements, &mut refs)?,
            "$MeshFormat" => return Err(src.error(at, "a second $MeshFormat: a file holds one mesh")),
            _ => src.skip_section(&name)?,
        }
    }
    for &((dimension, tag), at) in &refs.keys {
        let tags = match &entities {
            // A file without $Entities puts no element in a group.
            None => Vec::new(),
            Some(entities) => entities.get(&(dimension, tag)).cloned().ok_or_else(|| {
                let kind = ["point", "curve", "surface", "volume"][usize::from(dimension.min(3))];
                src.error(at, format!("this element block names {kind} {tag}, which $Entities does not list"))
            })?,
        };
        raw.group_sets.push(tags);
    }
    Ok(raw)
}

/// A dimension (0 to 3) from the file.
fn dimension(src: &mut Source, what: &str) -> Result<u8, MeshError> {
    let at = src.here();
    let d = src.int(what)?;
    u8::try_from(d)
        .ok()
        .filter(|&d| d <= 3)
        .ok_or_else(|| src.error(at, format!("{what} is {d}: dimensions are 0 to 3")))
}

/// `$Entities`: the physical tags of every entity. Points give their position, other entities
/// their bounding box and bounding entities, which are skipped.
fn read_entities(src: &mut Source) -> Result<HashMap<EntityKey, Vec<i32>>, MeshError> {
    let mut counts = [0; 4];
    for count in &mut counts {
        *count = src.size("a number of entities")?;
    }
    let mut entities = HashMap::new();
    for (dimension, &count) in (0u8..).zip(&counts) {
        for _ in 0..count {
            let at = src.here();
            let tag = src.int("an entity's tag")?;
            for _ in 0..if dimension == 0 { 3 } else { 6 } {
                src.real("an entity's coordinate")?;
            }
            let n = src.size("an entity's number of physical tags")?;
            if n > MAX_GROUPS as u64 {
                return Err(src.error(at, too_many_groups(&format!("entity {tag} of dimension {dimension}"))));
            }
            let mut physical = Vec::with_capacity(src.capacity(n, src.min_bytes(4)));
            for _ in 0..n {
                physical.push(src.int("a physical tag")?);
            }
            if dimension > 0 {
                for _ in 0..src.size("an entity's number of bounding entities")? {
                    src.int("a bounding entity's tag")?;
                }
            }
            entities.insert((dimension, tag), physical);
        }
    }
    src.end_section("$Entities")?;
    Ok(entities)
}

/// The first line of `$Nodes` or `$Elements`: how many blocks, and how many nodes (elements)
/// they hold in all; the smallest and largest tags are not needed.
struct Header {
    section: &'static str,
    what: &'static str,
    blocks: u64,
    declared: u64,
    at: usize,
}

impl Header {
    fn read(src: &mut Source, section: &'static str, what: &'static str) -> Result<Header, MeshError> {
        let at = src.here();
        let blocks = src.size(&format!("the number of {what} blocks"))?;
        let declared = src.size(&format!("the number of {what}s"))?;
        src.size(&format!("the smallest {what} tag"))?;
        src.size(&format!("the largest {what} tag"))?;
        Ok(Header { section, what, blocks, declared, at })
    }

    /// The blocks hold as many as the header declares.
    fn check(&self, src: &Source, total: u64) -> Result<(), MeshError> {
        if total == self.declared {
            return Ok(());
        }
        let (section, what, declared) = (self.section, self.what, self.declared);
        Err(src.error(self.at, format!("{section} declares {declared} {what}s, and its blocks hold {total}")))
    }
}

/// `$Nodes`: blocks of node tags then coordinates (then parametric coordinates, skipped).
fn read_nodes(src: &mut Source, nodes: &mut Vec<RawNode>) -> Result<(), MeshError> {
    let header = Header::read(src, "$Nodes", "node")?;
    nodes.reserve(src.capacity(header.declared, 4 * src.min_bytes(8)));
    let mut total = 0u64;
    for _ in 0..header.blocks {
        let block_at = src.here();
        let entity_dimension = dimension(src, "a node block's entity dimension")?;
        src.int("a node block's entity tag")?;
        let parametric = src.int("a node block's parametric flag")?;
        if !matches!(parametric, 0 | 1) {
            return Err(src.error(block_at, format!("a node block's parametric flag is {parametric}: it is 0 or 1")));
        }
        let count = src.size("a node block's number of nodes")?;
        let mut tags = Vec::with_capacity(src.capacity(count, src.min_bytes(8)));
        for _ in 0..count {
            tags.push(src.size("a node tag")?);
        }
        let skipped = if parametric == 1 { entity_dimension } else { 0 };
        for tag in tags {
            let at = src.here();
            let xyz = [src.real("an x")?, src.real("a y")?, src.real("a z")?];
            for _ in 0..skipped {
                src.real("a parametric coordinate")?;
            }
            nodes.push(RawNode { tag, xyz, at });
        }
        total += count;
    }
    header.check(src, total)?;
    src.end_section("$Nodes")
}

/// `$Elements`: blocks of elements of one type on one entity.
fn read_elements(src: &mut Source, elements: &mut Vec<RawElement>, refs: &mut EntityRefs) -> Result<(), MeshError> {
    let header = Header::read(src, "$Elements", "element")?;
    elements.reserve(src.capacity(header.declared, 2 * src.min_bytes(8)));
    let mut total = 0u64;
    for _ in 0..header.blocks {
        let block_at = src.here();
        let block_dimension = dimension(src, "an element block's entity dimension")?;
        let entity = src.int("an element block's entity tag")?;
        let code = src.int("an element type")?;
        let count = src.size("an element block's number of elements")?;
        let (t, kind) = block_kind(src, block_at, block_dimension, code)?;
        let key = (block_dimension, entity);
        let groups = *refs.index.entry(key).or_insert_with(|| {
            refs.keys.push((key, block_at));
            refs.keys.len() - 1
        });
        for k in 0..count {
            let at = src.here();
            let tag = src.size("an element tag")?;
            let mut nodes = [0; 4];
            for n in 0..t.nodes {
                let node = src.size("a node tag")?;
                if n < kind.kept_nodes() {
                    nodes[n] = node;
                }
            }
            // Of an element type slipfront does not read, one element stands for the block.
            if k == 0 || !matches!(kind, Kind::Other(_)) {
                elements.push(RawElement { tag, kind, nodes, groups, at });
            }
        }
        total += count;
    }
    header.check(src, total)?;
    src.end_section("$Elements")
}

/// What the elements of a block are to slipfront; refused if Gmsh has no type `code`, if the
/// type's dimension is not the block's, or if slipfront does not read such elements.
fn block_kind(src: &Source, at: usize, dimension: u8, code: i32) -> Result<(ElementType, Kind), MeshError> {
    let t = element_type(code).ok_or_else(|| src.error(at, unknown(code)))?;
    if t.dimension != dimension {
        let (name, d) = (t.name, t.dimension);
        return Err(src.error(
            at,
            format!("an element block of dimension {dimension} holds type {code} ({name}), of dimension {d}"),
        ));
    }
    Ok((t, Kind::of(t).map_err(|why| src.error(at, why))?))
}
