//! Case parsing: any text, with any `--set` overrides, must give a case or an error, never a
//! panic. The input is the case text, then optional override lines after a `\0`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let (case, overrides) = text.split_once('\0').unwrap_or((text, ""));
    let overrides: Vec<String> = overrides.lines().map(str::to_owned).collect();
    if let Ok(case) = slipfront::case::from_str(case, &overrides) {
        // A valid case must describe itself without panicking either.
        let _ = case.slip_rate_threshold();
    }
});
