//! Reading MCAP logs (`slipfront check` and `slipfront replay`): damaged or hostile bytes give
//! a log or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(log) = slipfront::mcap_log::reader::from_bytes(data, "fuzz.mcap") {
        let _ = slipfront::replay::replayed_recording(&log);
    }
});
