//! `cargo fuzz run rrd_read`: see `slipfront::fuzzing::rrd_read`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = slipfront::fuzzing::rrd_read(data);
});
