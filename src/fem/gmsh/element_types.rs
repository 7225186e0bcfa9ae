//! Gmsh's element types: the number a file gives each type, Gmsh's name for it, its dimension
//! and its node count. The table is Gmsh's own: `gmsh.model.mesh.getElementProperties(code)`
//! for every code of Gmsh 4.15.2 that has a fixed node count (polygons, polyhedra and XFEM
//! types have none and are absent, so a file that holds them is refused as unknown).

/// One element type of Gmsh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) struct ElementType {
    /// The type's number in a file (`elm-type`).
    pub code: i32,
    /// Gmsh's name: the shape and its node count (`Triangle 6`).
    pub name: &'static str,
    pub dimension: u8,
    pub nodes: usize,
}

/// The types slipfront reads, by code.
pub(super) const POINT: i32 = 15;
pub(super) const LINE: i32 = 1;
pub(super) const TRIANGLE: i32 = 2;
pub(super) const QUAD: i32 = 3;

/// What slipfront reads of each dimension, for messages.
pub(super) const SUPPORTED_CELLS: &str = "type 2 (Triangle 3) and type 3 (Quadrilateral 4)";
pub(super) const SUPPORTED_LINES: &str = "type 1 (Line 2)";

/// The type numbered `code`, if Gmsh has one.
pub(super) fn element_type(code: i32) -> Option<ElementType> {
    TYPES.iter().find(|t| t.0 == code).map(|&(code, name, dimension, nodes)| ElementType {
        code,
        name,
        dimension,
        nodes,
    })
}

/// The refusal of an element type Gmsh does not have (or whose node count varies).
pub(super) fn unknown(code: i32) -> String {
    format!(
        "element type {code} is not a Gmsh element type with a fixed number of nodes; slipfront reads 2-D cells of \
         {SUPPORTED_CELLS}"
    )
}

/// (code, name, dimension, nodes).
const TYPES: [(i32, &str, u8, usize); 110] = [
    (1, "Line 2", 1, 2),
    (2, "Triangle 3", 2, 3),
    (3, "Quadrilateral 4", 2, 4),
    (4, "Tetrahedron 4", 3, 4),
    (5, "Hexahedron 8", 3, 8),
    (6, "Prism 6", 3, 6),
    (7, "Pyramid 5", 3, 5),
    (8, "Line 3", 1, 3),
    (9, "Triangle 6", 2, 6),
    (10, "Quadrilateral 9", 2, 9),
    (11, "Tetrahedron 10", 3, 10),
    (12, "Hexahedron 27", 3, 27),
    (13, "Prism 18", 3, 18),
    (14, "Pyramid 14", 3, 14),
    (15, "Point", 0, 1),
    (16, "Quadrilateral 8", 2, 8),
    (17, "Hexahedron 20", 3, 20),
    (18, "Prism 15", 3, 15),
    (19, "Pyramid 13", 3, 13),
    (20, "Triangle 9", 2, 9),
    (21, "Triangle 10", 2, 10),
    (22, "Triangle 12", 2, 12),
    (23, "Triangle 15", 2, 15),
    (24, "Triangle 15I", 2, 15),
    (25, "Triangle 21", 2, 21),
    (26, "Line 4", 1, 4),
    (27, "Line 5", 1, 5),
    (28, "Line 6", 1, 6),
    (29, "Tetrahedron 20", 3, 20),
    (30, "Tetrahedron 35", 3, 35),
    (31, "Tetrahedron 56", 3, 56),
    (32, "Tetrahedron 22", 3, 22),
    (33, "Tetrahedron 28", 3, 28),
    (36, "Quadrilateral 16", 2, 16),
    (37, "Quadrilateral 25", 2, 25),
    (38, "Quadrilateral 36", 2, 36),
    (39, "Quadrilateral 12", 2, 12),
    (40, "Quadrilateral 16I", 2, 16),
    (41, "Quadrilateral 20", 2, 20),
    (42, "Triangle 28", 2, 28),
    (43, "Triangle 36", 2, 36),
    (44, "Triangle 45", 2, 45),
    (45, "Triangle 55", 2, 55),
    (46, "Triangle 66", 2, 66),
    (47, "Quadrilateral 49", 2, 49),
    (48, "Quadrilateral 64", 2, 64),
    (49, "Quadrilateral 81", 2, 81),
    (50, "Quadrilateral 100", 2, 100),
    (51, "Quadrilateral 121", 2, 121),
    (52, "Triangle 18", 2, 18),
    (53, "Triangle 21I", 2, 21),
    (54, "Triangle 24", 2, 24),
    (55, "Triangle 27", 2, 27),
    (56, "Triangle 30", 2, 30),
    (57, "Quadrilateral 24", 2, 24),
    (58, "Quadrilateral 28", 2, 28),
    (59, "Quadrilateral 32", 2, 32),
    (60, "Quadrilateral 36I", 2, 36),
    (61, "Quadrilateral 40", 2, 40),
    (62, "Line 7", 1, 7),
    (63, "Line 8", 1, 8),
    (64, "Line 9", 1, 9),
    (65, "Line 10", 1, 10),
    (66, "Line 11", 1, 11),
    (71, "Tetrahedron 84", 3, 84),
    (72, "Tetrahedron 120", 3, 120),
    (73, "Tetrahedron 165", 3, 165),
    (74, "Tetrahedron 220", 3, 220),
    (75, "Tetrahedron 286", 3, 286),
    (79, "Tetrahedron 34", 3, 34),
    (80, "Tetrahedron 40", 3, 40),
    (81, "Tetrahedron 46", 3, 46),
    (82, "Tetrahedron 52", 3, 52),
    (83, "Tetrahedron 58", 3, 58),
    (84, "Line 1", 1, 1),
    (85, "Triangle 1", 2, 1),
    (86, "Quadrilateral 1", 2, 1),
    (87, "Tetrahedron 1", 3, 1),
    (88, "Hexahedron 1", 3, 1),
    (89, "Prism 1", 3, 1),
    (92, "Hexahedron 64", 3, 64),
    (93, "Hexahedron 125", 3, 125),
    (94, "Hexahedron 216", 3, 216),
    (95, "Hexahedron 343", 3, 343),
    (96, "Hexahedron 512", 3, 512),
    (97, "Hexahedron 729", 3, 729),
    (98, "Hexahedron 1000", 3, 1000),
    (99, "Hexahedron 32", 3, 32),
    (100, "Hexahedron 44", 3, 44),
    (101, "Hexahedron 56", 3, 56),
    (102, "Hexahedron 68", 3, 68),
    (103, "Hexahedron 80", 3, 80),
    (104, "Hexahedron 92", 3, 92),
    (105, "Hexahedron 104", 3, 104),
    (118, "Pyramid 30", 3, 30),
    (119, "Pyramid 55", 3, 55),
    (120, "Pyramid 91", 3, 91),
    (121, "Pyramid 140", 3, 140),
    (122, "Pyramid 204", 3, 204),
    (123, "Pyramid 285", 3, 285),
    (124, "Pyramid 385", 3, 385),
    (125, "Pyramid 21", 3, 21),
    (126, "Pyramid 29", 3, 29),
    (127, "Pyramid 37", 3, 37),
    (128, "Pyramid 45", 3, 45),
    (129, "Pyramid 53", 3, 53),
    (130, "Pyramid 61", 3, 61),
    (131, "Pyramid 69", 3, 69),
    (132, "Pyramid 1", 3, 1),
    (137, "Tetrahedron 16", 3, 16),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_read_types_are_as_gmsh_numbers_them() {
        let t = |code| element_type(code).map(|t| (t.name, t.dimension, t.nodes));
        assert_eq!(t(POINT), Some(("Point", 0, 1)));
        assert_eq!(t(LINE), Some(("Line 2", 1, 2)));
        assert_eq!(t(TRIANGLE), Some(("Triangle 3", 2, 3)));
        assert_eq!(t(QUAD), Some(("Quadrilateral 4", 2, 4)));
        assert_eq!(t(9), Some(("Triangle 6", 2, 6)));
        assert_eq!(t(0), None);
        assert_eq!(t(34), None); // a polygon: no fixed node count
    }
}
