//! Reading Rerun recordings (`slipfront check`): damaged or hostile bytes give a recording or
//! an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(recording) = slipfront::inspect::rrd::from_bytes(data, "fuzz.rrd") {
        let expect = slipfront::inspect::check::Expectations::default();
        let _ = slipfront::inspect::check::check(&recording, &expect);
    }
});
