//! The entry points the fuzz targets (`fuzz/`) drive, shared with the regression tests that
//! replay what the fuzzer found (`tests/fuzz_regressions.rs`). Each takes arbitrary bytes and
//! must return, never panic; the result says whether the input was accepted.

/// Case parsing and validation: the bytes are a case file's text, then optionally a `\0` and
/// `--set` overrides, one per line.
pub fn case_parse(data: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(data) else { return false };
    let (case, overrides) = text.split_once('\0').unwrap_or((text, ""));
    let overrides: Vec<String> = overrides.lines().map(str::to_owned).collect();
    match crate::case::from_str(case, &overrides) {
        Ok(case) => {
            // A valid case describes itself, and sizes itself, without panicking either.
            let _ = case.slip_rate_threshold();
            let _ = case.time.steps();
            if let crate::case::SceneSpec::Block(b) = &case.scene {
                let _ = crate::scene::block::estimated_memory(b.nx, b.ny);
            }
            true
        }
        Err(e) => {
            // Every refusal says why.
            assert!(!e.to_string().is_empty(), "an empty error message");
            false
        }
    }
}

/// Reading an MCAP log as `slipfront check` and `slipfront replay` do.
pub fn mcap_read(data: &[u8]) -> bool {
    match crate::inspect::mcap::from_bytes(data, "input.mcap") {
        Ok(log) => crate::study::replay::replayed_recording(&log).is_ok(),
        Err(_) => false,
    }
}

/// Reading and checking a Rerun recording as `slipfront check` does; accepted if it passes.
pub fn rrd_read(data: &[u8]) -> bool {
    match crate::inspect::rrd::from_bytes(data, "input.rrd") {
        Ok(recording) => {
            let report = crate::inspect::check::check(&recording, &Default::default());
            let _ = report.render();
            report.passed()
        }
        Err(_) => false,
    }
}

/// Reading a Gmsh mesh file as a scene does: parse, then the boundary chain of the first
/// groups. An accepted mesh is canonical: building it again from its own nodes, cells and
/// groups gives it back unchanged.
pub fn gmsh_read(data: &[u8]) -> bool {
    match crate::fem::gmsh::parse(data, "input.msh") {
        Ok(mesh) => {
            for group in mesh.groups.iter().take(8) {
                let _ = mesh.boundary_chain(&group.name);
            }
            let again = crate::fem::body_mesh::Mesh::new(mesh.nodes.clone(), mesh.cells.clone(), mesh.groups.clone());
            let again = again.expect("a mesh that was accepted is accepted again");
            assert_eq!((&again.nodes, &again.cells, &again.groups), (&mesh.nodes, &mesh.cells, &mesh.groups));
            true
        }
        Err(e) => {
            assert!(!e.to_string().is_empty(), "an empty error message");
            false
        }
    }
}
