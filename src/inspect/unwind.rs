//! Damage that a third-party decoder panics on (the Arrow IPC reader under Rerun's decoder,
//! the `mcap` parser), caught as damage: the panic ends the reading like any other damaged
//! byte, and the default hook's "thread panicked at" message, which would read as a crash of
//! slipfront itself, is not printed.

use std::panic::{AssertUnwindSafe, catch_unwind, set_hook, take_hook};
use std::sync::Mutex;

/// One quiet section at a time: the panic hook is the process's.
static QUIET: Mutex<()> = Mutex::new(());

/// A decoder panicked on damaged data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DecoderPanicked;

/// Runs `decode`; a panic inside it becomes `Err` without a message on stderr.
pub fn quietly<T>(decode: impl FnOnce() -> T) -> Result<T, DecoderPanicked> {
    let _one = QUIET.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let hook = take_hook();
    set_hook(Box::new(|_| {}));
    let result = catch_unwind(AssertUnwindSafe(decode)).map_err(|_| DecoderPanicked);
    set_hook(hook);
    result
}
