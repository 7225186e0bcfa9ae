//! `cargo fuzz run mcap_read`: see `slipfront::fuzzing::mcap_read`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = slipfront::fuzzing::mcap_read(data);
});
