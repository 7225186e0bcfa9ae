//! The Gmsh reader (`slipfront::fem::gmsh`) on files written by Gmsh 4.15.2 (committed under
//! `cases/meshes/`, written by `scripts/paper_block_meshes.py`, so no test needs Gmsh), and on
//! damaged or hostile variants of them: every form reads to the same canonical mesh, which is
//! the one expected by hand; every bad input is refused with a message that says what and where.

use slipfront::fem::body_mesh::{Cell, Members, Mesh};
use slipfront::fem::gmsh::{MAX_FILE_BYTES, parse, read};
use std::path::PathBuf;

fn mesh_file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("cases/meshes").join(name)
}

fn read_mesh(name: &str) -> Mesh {
    read(&mesh_file(name)).unwrap_or_else(|e| panic!("{e}"))
}

fn text(name: &str) -> String {
    std::fs::read_to_string(mesh_file(name)).unwrap()
}

/// The refusal of `bytes` as a file called `m.msh`.
fn refusal(bytes: impl AsRef<[u8]>) -> String {
    match parse(bytes.as_ref(), "m.msh") {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    }
}

/// The paper block as it must read, derived by hand: node (i, j) at (i, j) m has index
/// 11 j + i (sorted by y, then x); quad k is (k, k+1, k+12, k+11), counter-clockwise from its
/// smallest node. The file's node tags: point i + 1 at (i, 0), point 22 - i at (i, 1).
fn check_paper_block(mesh: &Mesh) {
    let nodes: Vec<[f64; 2]> = (0..2).flat_map(|j| (0..11).map(move |i| [i as f64, j as f64])).collect();
    assert_eq!(mesh.nodes, nodes);
    let cells: Vec<Cell> = (0..10).map(|k| Cell::Quad([k, k + 1, k + 12, k + 11])).collect();
    assert_eq!(mesh.cells, cells);
    let names: Vec<&str> = mesh.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["bottom", "right", "top", "left", "body"]);
    assert_eq!(mesh.group("body").unwrap().members, Members::Cells((0..10).collect()));
    assert_eq!(mesh.boundary_chain("bottom").unwrap(), (0..=10).collect::<Vec<_>>());
    assert_eq!(mesh.boundary_chain("top").unwrap(), (11..=21).rev().collect::<Vec<_>>());
    assert_eq!(mesh.boundary_chain("right").unwrap(), [10, 21]);
    assert_eq!(mesh.boundary_chain("left").unwrap(), [11, 0]);
}

/// `a` and `b` are the same mesh: nodes bit for bit, cells, groups (lines as sets when
/// `line_order` is false: a file may list a group's lines in another order).
fn assert_same_mesh(a: &Mesh, b: &Mesh, line_order: bool) {
    let bits = |m: &Mesh| m.nodes.iter().flat_map(|p| p.map(f64::to_bits)).collect::<Vec<_>>();
    assert_eq!(bits(a), bits(b));
    assert_eq!(a.cells, b.cells);
    let groups = |m: &Mesh| {
        let mut groups = m.groups.clone();
        for g in groups.iter_mut().filter(|_| !line_order) {
            if let Members::Lines(lines) = &mut g.members {
                lines.sort_unstable();
            }
        }
        groups
    };
    assert_eq!(groups(a), groups(b));
}

#[test]
fn every_form_of_the_paper_block_reads_to_the_same_expected_mesh() {
    let ascii = read_mesh("paper_block.msh");
    check_paper_block(&ascii);
    let tags: Vec<u64> = (0..2).flat_map(|j| (0..11).map(move |i| if j == 0 { i + 1 } else { 22 - i })).collect();
    assert_eq!(ascii.node_tags, tags);
    assert_eq!(ascii.cell_tags, (23..33).collect::<Vec<u64>>());
    for other in ["paper_block_binary.msh", "paper_block_v2.msh"] {
        let mesh = read_mesh(other);
        assert_same_mesh(&mesh, &ascii, true);
        assert_eq!((&mesh.node_tags, &mesh.cell_tags), (&ascii.node_tags, &ascii.cell_tags), "{other}");
    }
}

#[test]
fn shuffled_tags_blocks_and_clockwise_cells_read_to_the_same_mesh() {
    // Sparse random tags, blocks in reverse order, every quad's nodes reversed (clockwise).
    let shuffled_text = text("paper_block_shuffled.msh");
    assert!(shuffled_text.contains("\n2 1 3 10\n76919 18951 89791 28674 16361 \n"), "the first quad, clockwise");
    let shuffled = read_mesh("paper_block_shuffled.msh");
    check_paper_block(&shuffled);
    assert_same_mesh(&shuffled, &read_mesh("paper_block.msh"), false);
    // The quad above, (0, 0) (0, 1) (1, 1) (1, 0) in the file, is cell 0, turned counter-clockwise.
    assert_eq!(shuffled.cell_tags[0], 76919);
    assert_eq!(
        shuffled.cells[0].nodes().iter().map(|&n| shuffled.node_tags[n]).collect::<Vec<_>>(),
        [16361, 28674, 89791, 18951]
    );
    for tags in [&shuffled.node_tags, &shuffled.cell_tags] {
        let (min, max) = (tags.iter().min().unwrap(), tags.iter().max().unwrap());
        assert!(max - min + 1 > tags.len() as u64 * 100, "sparse: {min}..={max} for {}", tags.len());
    }
}

#[test]
fn save_all_keeps_cells_in_no_group_and_ignores_points_in_no_group() {
    // Written with Mesh.SaveAll = 1 after the group "body" was removed: its quads and the four
    // corner points (type 15) are in the file, in no physical group.
    assert!(text("paper_block_saveall.msh").contains("\n0 1 15 1\n"), "the file holds point elements");
    let all = read_mesh("paper_block_saveall.msh");
    let paper = read_mesh("paper_block.msh");
    assert_eq!((&all.nodes, &all.cells, &all.cell_tags), (&paper.nodes, &paper.cells, &paper.cell_tags));
    let names: Vec<&str> = all.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["bottom", "right", "top", "left"]);
    assert_eq!(all.groups[..], paper.groups[..4]);
}

#[test]
fn an_element_in_two_groups_is_one_element_in_both() {
    // MSH 2.2 writes each triangle, line and point once per group (14 element lines); MSH 4.1
    // puts the groups on the entities, and this one also gives the curve nodes' parameter.
    let v2 = read_mesh("triangles_v2.msh");
    assert!(text("triangles_v2.msh").contains("\n$Elements\n14\n"));
    assert_eq!(v2.cells.len(), 4);
    let parametric = read_mesh("triangles_parametric.msh");
    assert!(text("triangles_parametric.msh").contains("\n0.9999999999973842 0 0 0.4999999999986921\n"));
    assert_same_mesh(&parametric, &v2, true);
    let groups: Vec<(&str, i32, &Members)> = v2.groups.iter().map(|g| (g.name.as_str(), g.tag, &g.members)).collect();
    // Nodes by y then x: (0,0) (1,0) (2,0) (0,1) (1,1) (2,1); the unnamed group 7 comes last.
    let all = Members::Cells(vec![0, 1, 2, 3]);
    let bottom = Members::Lines(vec![[0, 1], [1, 2]]);
    let origin = Members::Points(vec![0]);
    assert_eq!(
        groups,
        [
            ("origin", 10, &origin),
            ("also origin", 11, &origin),
            ("bottom", 8, &bottom),
            ("base", 9, &bottom),
            ("body", 1, &all),
            ("7", 7, &all)
        ]
    );
}

/// A MSH 2.2 file: nodes `tag x y z`, elements `tag type ntags tags... nodes...`.
fn msh22(nodes: &[&str], elements: &[&str]) -> String {
    format!(
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n{}\n{}\n$EndNodes\n$Elements\n{}\n{}\n$EndElements\n",
        nodes.len(),
        nodes.join("\n"),
        elements.len(),
        elements.join("\n")
    )
}

#[test]
fn any_numbering_and_orientation_reads_to_one_canonical_mesh() {
    // Two triangles of the unit square, clockwise, with sparse tags listed out of order, an
    // unused node out of the plane, and a 3-node line in no group (ignored).
    let file = msh22(
        &["900 1 1 0", "7 0 0 0", "31 5 5 5", "1000 1 0 0", "3 0 1 0"],
        &["5 2 2 4 1 7 3 1000", "60 2 2 4 1 1000 3 900", "8 8 2 0 1 7 1000 3"],
    );
    let mesh = parse(file.as_bytes(), "m.msh").unwrap();
    assert_eq!(mesh.nodes, [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]);
    assert_eq!(mesh.node_tags, [7, 1000, 3, 900]);
    assert_eq!(mesh.cells, [Cell::Triangle([0, 1, 2]), Cell::Triangle([1, 3, 2])]);
    assert_eq!(mesh.cell_tags, [5, 60]);
    assert_eq!((mesh.groups[0].name.as_str(), &mesh.groups[0].members), ("4", &Members::Cells(vec![0, 1])));
}

/// The paper block in MSH 2.2 with line `n` (from 1) replaced by `line`.
fn paper_v2_with(n: usize, line: &str) -> String {
    let text = text("paper_block_v2.msh");
    let mut lines: Vec<&str> = text.lines().collect();
    lines[n - 1] = line;
    lines.join("\n") + "\n"
}

#[test]
fn what_is_not_a_mesh_file_is_refused() {
    let not_msh = "m.msh: line 1: not a Gmsh mesh file: it does not start with $MeshFormat";
    assert_eq!(refusal("solid cube\nfacet normal 0 0 1\n"), not_msh);
    assert_eq!(refusal(""), not_msh);
    assert_eq!(refusal([0u8, 159, 146, 150, 255]), not_msh);
    let supported = "slipfront reads MSH 4.1 (ASCII or binary) and MSH 2.2 (ASCII)";
    assert_eq!(
        refusal(paper_v2_with(2, "4.0 0 8")),
        format!("m.msh: line 2: MSH version 4.0 is not read: {supported}")
    );
    assert_eq!(refusal(paper_v2_with(2, "2.2 1 8")), format!("m.msh: line 2: MSH 2.2 binary is not read: {supported}"));
    assert_eq!(
        refusal(paper_v2_with(1, "$MeshFormat $Nodes")),
        "m.msh: line 1: MSH version $Nodes is not read: ".to_owned() + supported
    );
}

#[test]
fn a_truncated_file_is_refused_saying_where() {
    let text = text("paper_block_v2.msh");
    let cut = &text[..text.find("24 3 2 1 1 2 3 20").unwrap() + "24 3 2 1 1 2 3 20".len()];
    assert_eq!(refusal(cut), "m.msh: line 62: the file ends where a node tag should be: it is truncated");
    let no_end = text.replace("$EndElements\n", "");
    assert_eq!(refusal(no_end), "m.msh: line 71: the file ends where $EndElements should be: it is truncated");
    let binary = std::fs::read(mesh_file("paper_block_binary.msh")).unwrap();
    let half = binary.len() / 2;
    let e = refusal(&binary[..half]);
    assert!(
        e.starts_with(&format!("m.msh: byte {half}: the file ends where "))
            && e.ends_with("should be: it is truncated"),
        "{e}"
    );
    // Every shorter prefix of every form is refused, none panics.
    for name in ["paper_block.msh", "paper_block_binary.msh", "paper_block_v2.msh", "triangles_parametric.msh"] {
        let bytes = std::fs::read(mesh_file(name)).unwrap();
        let end = bytes.iter().rposition(|b| !b.is_ascii_whitespace()).unwrap();
        for n in 0..end {
            assert!(parse(&bytes[..n], "m.msh").is_err(), "{name} cut to {n} bytes was accepted");
        }
    }
}

#[test]
fn a_binary_file_in_another_byte_order_or_size_t_is_refused() {
    let binary = std::fs::read(mesh_file("paper_block_binary.msh")).unwrap();
    assert_eq!(&binary[..24], b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00");
    let mut big_endian = binary.clone();
    big_endian[20..24].copy_from_slice(&[0, 0, 0, 1]);
    assert_eq!(
        refusal(&big_endian),
        "m.msh: byte 20: the file is big-endian: slipfront reads little-endian binary files"
    );
    let mut size_4 = binary.clone();
    size_4[18] = b'4';
    assert_eq!(
        refusal(&size_4),
        "m.msh: byte 18: the file's size_t is 4 bytes: slipfront reads binary files with an 8-byte size_t (64-bit Gmsh)"
    );
}

#[test]
fn unsupported_elements_are_refused_by_gmsh_number_and_name() {
    let cells = "type 2 (Triangle 3) and type 3 (Quadrilateral 4)";
    assert_eq!(
        refusal(paper_v2_with(61, "23 9 2 1 1 1 2 21 22 3 4")),
        format!(
            "m.msh: line 61: element 23: type 9 (Triangle 6) is a 2-D element slipfront does not read: it reads {cells} \
             (first-order elements: in Gmsh, Mesh.ElementOrder = 1)"
        )
    );
    assert_eq!(
        refusal(paper_v2_with(61, "23 4 2 1 1 1 2 21 22")),
        format!(
            "m.msh: line 61: element 23: type 4 (Tetrahedron 4) is a 3-D element: slipfront reads 2-D meshes, of {cells}"
        )
    );
    assert_eq!(
        refusal(paper_v2_with(61, "23 200 2 1 1 1 2 21 22")),
        format!(
            "m.msh: line 61: element type 200 is not a Gmsh element type with a fixed number of nodes; slipfront reads 2-D cells of {cells}"
        )
    );
    // A 3-node line in the group "bottom" is refused; in no group, it is ignored.
    assert_eq!(
        refusal(paper_v2_with(39, "1 8 2 2 1 1 2 3")),
        "m.msh: line 39: element 1 of type 8 (Line 3) is in physical group \"bottom\": slipfront reads curve groups of \
         type 1 (Line 2) and point groups of type 15 (Point)"
    );
    let ignored = parse(paper_v2_with(39, "1 8 2 0 1 1 2 3").as_bytes(), "m.msh").unwrap();
    assert_eq!(ignored.group("bottom").unwrap().members.len(), 9);
    // MSH 4.1: a block of second-order triangles, refused at its header.
    let v4 = text("paper_block.msh").replace("\n2 1 3 10\n", "\n2 1 9 10\n");
    let line = v4.lines().position(|l| l == "2 1 9 10").unwrap() + 1;
    assert!(
        refusal(&v4)
            .starts_with(&format!("m.msh: line {line}: type 9 (Triangle 6) is a 2-D element slipfront does not read"))
    );
}

#[test]
fn bad_nodes_are_refused_naming_their_tags() {
    assert_eq!(
        refusal(paper_v2_with(14, "1 nan 0 0")),
        "m.msh: node 1 is at (NaN, 0): coordinates must be finite numbers"
    );
    assert_eq!(
        refusal(paper_v2_with(14, "1 0 -inf 0")),
        "m.msh: node 1 is at (0, -inf): coordinates must be finite numbers"
    );
    assert_eq!(
        refusal(paper_v2_with(14, "1 0 0 NaN")),
        "m.msh: line 14: node 1 has z = NaN: coordinates must be finite"
    );
    assert_eq!(
        refusal(paper_v2_with(15, "2 0 0 0")),
        "m.msh: node 1 and node 2 are both at (0, 0): each point of the mesh must be one node"
    );
    assert_eq!(
        refusal(paper_v2_with(35, "22 0 1 0.5")),
        "m.msh: line 35: node 22 is at z = 0.5, node 1 at z = 0: a 2-D mesh lies in one plane z = const"
    );
    assert_eq!(refusal(paper_v2_with(35, "21 0 1 0")), "m.msh: line 35: node 21 is defined twice (first at line 34)");
    assert_eq!(
        refusal(paper_v2_with(61, "23 3 2 1 1 1 2 21 99")),
        "m.msh: line 61: element 23 names node 99, which $Nodes does not define"
    );
    // A plane other than z = 0, and an unused node outside it, are fine.
    let text = text("paper_block_v2.msh").replace(" 0\n", " 2.5\n").replace("$Nodes\n22\n", "$Nodes\n23\n99 5 5 -1\n");
    assert_eq!(parse(text.as_bytes(), "m.msh").unwrap().nodes, read_mesh("paper_block_v2.msh").nodes);
}

#[test]
fn degenerate_and_inverted_cells_are_refused_naming_their_tags() {
    assert_eq!(
        refusal(paper_v2_with(61, "23 3 2 1 1 1 2 22 21")),
        "m.msh: element 23 (nodes 1 2 22 21) is inverted at some corners: its Jacobian changes sign from corner to \
         corner (a non-convex or self-crossing quadrilateral); a quadrilateral must be convex"
    );
    // Node 21 moved from (1, 1) to (0.5, 0.1): element 23 becomes a dart, non-convex.
    assert!(
        refusal(paper_v2_with(34, "21 0.5 0.1 0"))
            .starts_with("m.msh: element 23 (nodes 1 2 21 22) is inverted at some corners")
    );
    let flat = msh22(&["1 0 0 0", "2 1 0 0", "3 2 0 0"], &["1 2 2 1 1 1 2 3"]);
    assert_eq!(
        refusal(flat),
        "m.msh: element 1 (nodes 1 2 3) is degenerate: its three nodes are on one line (a zero Jacobian at node 1); \
         a cell must enclose an area"
    );
    let no_cells = text("paper_block_v2.msh");
    let no_cells = no_cells[..no_cells.find("23 3 2").unwrap()].replace("\n32\n", "\n22\n") + "$EndElements\n";
    assert_eq!(refusal(no_cells), "m.msh: the mesh has no 2-D cell (triangle or quadrilateral)");
}

#[test]
fn inconsistent_blocks_are_refused() {
    let v4 = text("paper_block.msh");
    let line_of = |text: &str, l: &str| text.lines().position(|x| x == l).unwrap() + 1;
    let miscounted = v4.replace("$Nodes\n45 22 1 22\n", "$Nodes\n45 23 1 22\n");
    let at = line_of(&miscounted, "45 23 1 22");
    assert_eq!(refusal(miscounted), format!("m.msh: line {at}: $Nodes declares 23 nodes, and its blocks hold 22"));
    let lost = v4.replace("\n2 1 3 10\n", "\n2 9 3 10\n");
    let at = line_of(&lost, "2 9 3 10");
    assert_eq!(
        refusal(lost),
        format!("m.msh: line {at}: this element block names surface 9, which $Entities does not list")
    );
    let twice = v4.replace("$EndPhysicalNames", "$EndPhysicalNames\n$MeshFormat\n4.1 0 8\n$EndMeshFormat");
    assert!(refusal(twice).ends_with("a second $MeshFormat: a file holds one mesh"));
}

#[test]
fn an_element_in_more_than_32_groups_is_refused() {
    // Each group lists its members one by one: tags times elements must stay near the file's size.
    let copies: Vec<String> = (1..=33).map(|k| format!("{k} 2 2 {k} 1 1 2 3")).collect();
    let copies: Vec<&str> = copies.iter().map(String::as_str).collect();
    let v2 = msh22(&["1 0 0 0", "2 1 0 0", "3 0 1 0"], &copies);
    assert_eq!(
        refusal(v2),
        "m.msh: line 44: element 33 (with its copies) is in more than 32 physical groups: slipfront reads at most 32 \
         per element"
    );
    let tags: Vec<String> = (1..=33).map(|k| k.to_string()).collect();
    let surface = format!("1 0 0 0 2 1 0 33 {} 4 1 2 3 4 ", tags.join(" "));
    let v4 = text("triangles_parametric.msh").replace("1 0 0 0 2 1 0 2 1 7 4 1 2 3 4 ", &surface);
    let line = v4.lines().position(|l| l == surface).unwrap() + 1;
    assert_eq!(
        refusal(v4),
        format!(
            "m.msh: line {line}: entity 1 of dimension 2 is in more than 32 physical groups: slipfront reads at most 32 per element"
        )
    );
}

#[test]
fn declared_counts_allocate_nothing_the_file_cannot_hold() {
    let header = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    let e = refusal(format!("{header}$Nodes\n18446744073709551615\n1 0 0 0\n$EndNodes\n"));
    assert_eq!(e, "m.msh: line 7: expected a node tag, found \"$EndNodes\"");
    let e = refusal(format!("{header}$Elements\n18446744073709551615\n$EndElements\n"));
    assert_eq!(e, "m.msh: line 6: expected an element tag, found \"$EndElements\"");
    // MSH 4.1 binary: 2^64 - 1 node blocks, then a block of 2^64 - 1 nodes.
    let mut binary = b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n$Nodes\n".to_vec();
    binary.extend([u64::MAX, u64::MAX, 1, 1].iter().flat_map(|n| n.to_le_bytes()));
    binary.extend([0i32, 1, 0].iter().flat_map(|n| n.to_le_bytes()));
    binary.extend(u64::MAX.to_le_bytes());
    binary.extend(7u64.to_le_bytes());
    let e = refusal(&binary);
    assert_eq!(e, format!("m.msh: byte {}: the file ends where a node tag should be: it is truncated", binary.len()));
}

#[test]
fn what_is_not_a_regular_file_or_too_large_is_refused_before_reading() {
    let dir = std::env::temp_dir().join(format!("slipfront-mesh-reader-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let large = dir.join("large.msh");
    std::fs::File::create(&large).unwrap().set_len(MAX_FILE_BYTES + 1).unwrap(); // sparse: no disk used
    let e = read(&large).unwrap_err().to_string();
    assert_eq!(e, format!("{}: is larger than 1073741824 bytes (1 GiB), the largest mesh file read", large.display()));
    let fifo = dir.join("fifo.msh");
    let path = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    assert_eq!(unsafe { libc::mkfifo(path.as_ptr(), 0o600) }, 0);
    let not_regular = "is not a regular file (a directory, a device or a pipe): a mesh is read from a file";
    for path in [fifo.as_path(), std::path::Path::new("/dev/zero"), dir.as_path()] {
        assert_eq!(read(path).unwrap_err().to_string(), format!("{}: {not_regular}", path.display()));
    }
    let missing = dir.join("missing.msh");
    assert!(read(&missing).unwrap_err().to_string().starts_with(&format!("{}: cannot be read: ", missing.display())));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn boundary_chains_of_a_file_name_its_node_and_element_tags() {
    // The paper block in MSH 2.2, with lines moved into the group "bottom" (physical tag 2).
    let with_lines = |moved: &[usize], extra: &[&str]| {
        let text = text("paper_block_v2.msh");
        let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
        for &element in moved {
            let fields: Vec<&str> = lines[38 + element - 1].split(' ').collect();
            lines[38 + element - 1] = [&fields[..3], &["2"], &fields[4..]].concat().join(" ");
        }
        lines[37] = (32 + extra.len()).to_string();
        lines.splice(70..70, extra.iter().map(|s| s.to_string()));
        parse((lines.join("\n") + "\n").as_bytes(), "m.msh").unwrap()
    };
    let chain_error = |mesh: Mesh| mesh.boundary_chain("bottom").unwrap_err().to_string();
    // Bottom then up the right side (element 11): one chain, the body on its left.
    let mesh = with_lines(&[11], &[]);
    let tags: Vec<u64> = mesh.boundary_chain("bottom").unwrap().iter().map(|&n| mesh.node_tags[n]).collect();
    assert_eq!(tags, (1..=12).collect::<Vec<u64>>());
    assert_eq!(
        chain_error(with_lines(&[12], &[])),
        "physical group \"bottom\" has 2 disjoint pieces (from node 1 to node 11, from node 12 to node 13): a \
         boundary chain is one open chain of lines"
    );
    assert_eq!(
        chain_error(with_lines(&(11..=22).collect::<Vec<_>>(), &[])),
        "physical group \"bottom\" is a closed loop of 22 lines (through node 1): a boundary chain has two ends; \
         split the curve into two groups"
    );
    assert_eq!(
        chain_error(with_lines(&[], &["33 1 2 2 1 2 21"])),
        "physical group \"bottom\" has the line from node 2 to node 21, an edge of element 23 (nodes 1 2 21 22) and \
         element 24 (nodes 2 3 20 21): it is inside the body, not on its boundary"
    );
    assert_eq!(
        chain_error(with_lines(&[], &["33 1 2 2 1 1 21"])),
        "physical group \"bottom\" has the line from node 1 to node 21, which is not an edge of any cell"
    );
}
