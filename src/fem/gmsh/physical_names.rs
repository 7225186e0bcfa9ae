//! The `$PhysicalNames` section, the same in MSH 2.2 and 4.1 (and ASCII in binary files too):
//! `count`, then `dimension tag "name"` per group.

use super::source::Source;
use crate::fem::body_mesh::MeshError;

/// The name a file gives the physical group `tag` of dimension `dimension`.
pub(super) struct PhysicalName {
    pub dimension: u8,
    pub tag: i32,
    pub name: String,
    /// The offset of the entry in the file.
    pub at: usize,
}

/// Reads the section after its header, through `$EndPhysicalNames`.
pub(super) fn read(src: &mut Source) -> Result<Vec<PhysicalName>, MeshError> {
    let (count, _) = src.parsed::<u64>("the number of physical names")?;
    let mut names = Vec::with_capacity(src.capacity(count, "0 1 \"\"\n".len()));
    for _ in 0..count {
        let (dimension, at) = src.parsed::<u8>("a physical group's dimension (0 to 3)")?;
        if dimension > 3 {
            return Err(src.error(at, format!("a physical group of dimension {dimension}: dimensions are 0 to 3")));
        }
        let (tag, _) = src.parsed::<i32>("a physical group's tag")?;
        let name = src.quoted("a physical group's name")?;
        names.push(PhysicalName { dimension, tag, name, at });
    }
    src.end_section("$PhysicalNames")?;
    Ok(names)
}
