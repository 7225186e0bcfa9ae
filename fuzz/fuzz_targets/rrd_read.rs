//! `cargo fuzz run rrd_read`: see `slipfront::fuzzing::rrd_read`.
//!
//! The RRD reader catches panics of the Arrow reader under Rerun's decoder (a known one of
//! arrow-buffer 58 on damaged buffer lengths) and reports them as damage. libFuzzer's panic hook
//! would abort on them anyway, so this target replaces it with a silent one: a caught panic is
//! handled input, while a panic that escapes still aborts at the FFI boundary and is reported.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    static QUIET: std::sync::Once = std::sync::Once::new();
    QUIET.call_once(|| std::panic::set_hook(Box::new(|_| {})));
    let _ = slipfront::fuzzing::rrd_read(data);
});
