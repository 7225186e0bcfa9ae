//! `cargo fuzz run case_parse`: see `slipfront::fuzzing::case_parse`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = slipfront::fuzzing::case_parse(data);
});
