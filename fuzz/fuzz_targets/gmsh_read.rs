//! `cargo fuzz run gmsh_read`: see `slipfront::fuzzing::gmsh_read`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = slipfront::fuzzing::gmsh_read(data);
});
