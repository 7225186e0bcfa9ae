//! The signals that stop a command cleanly: Ctrl-C, a user's or a batch system's kill, a
//! closed terminal, and the user signals schedulers send ahead of a time limit. The first one
//! asks the command to stop after its current step and finish its outputs; a second ends the
//! process at once. The exit code is 128 + the signal's number, as a shell expects.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use crate::cli::common::EXIT_INTERRUPTED;
use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM, SIGUSR1, SIGUSR2};

/// The stopping signals and their names.
const STOPPING: [(i32, &str); 5] =
    [(SIGINT, "SIGINT"), (SIGTERM, "SIGTERM"), (SIGHUP, "SIGHUP"), (SIGUSR1, "SIGUSR1"), (SIGUSR2, "SIGUSR2")];

/// The stop request of a command.
pub struct Stop {
    /// Set when a stopping signal arrives.
    pub flag: Arc<AtomicBool>,
    signal: Arc<AtomicUsize>,
}

impl Stop {
    /// Catches the stopping signals from now on.
    pub fn catch() -> Self {
        let flag = Arc::new(AtomicBool::new(false));
        let signal = Arc::new(AtomicUsize::new(0));
        for (number, _) in STOPPING {
            // Registering can only fail for signals that cannot be caught; these can.
            let _ = signal_hook::flag::register_conditional_shutdown(number, 128 + number, flag.clone());
            let _ = signal_hook::flag::register(number, flag.clone());
            let _ = signal_hook::flag::register_usize(number, signal.clone(), number as usize);
        }
        Self { flag, signal }
    }

    /// Whether a stopping signal has arrived.
    pub fn requested(&self) -> bool {
        self.flag.load(Ordering::SeqCst)
    }

    /// The exit code and name of the signal that stopped the command.
    pub fn exit(&self) -> (u8, &'static str) {
        let signal = self.signal.load(Ordering::SeqCst);
        match STOPPING.iter().find(|(n, _)| *n as usize == signal) {
            Some(&(n, name)) => (128 + n as u8, name),
            None => (EXIT_INTERRUPTED, "SIGINT"),
        }
    }
}
