//! Ctrl-C (SIGINT) and SIGTERM: the first ends the run after the current step, so that the
//! recording, the metrics and the exports hold every finished step and the file is closed
//! properly (it verifies); a second one exits at once.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// Exit code of a run ended by a signal (128 + SIGINT, the shell's convention).
pub(crate) const EXIT_INTERRUPTED: u8 = 130;

/// The flag the runner reads between steps, set by the first signal. The handler is
/// installed once; if it cannot be (another handler owns the signal), the run simply
/// cannot be interrupted cleanly and the flag stays unset.
pub(crate) fn stop_flag() -> Arc<AtomicBool> {
    let flag = Arc::new(AtomicBool::new(false));
    let seen = flag.clone();
    let installed = ctrlc::set_handler(move || {
        if seen.swap(true, Ordering::SeqCst) {
            eprintln!("\nsecond signal: stopping now (the recording may be incomplete)");
            std::process::exit(i32::from(EXIT_INTERRUPTED));
        }
        eprintln!("\nsignal: stopping after the current step (again to stop at once)");
    });
    if let Err(e) = installed {
        eprintln!("note: Ctrl-C will not end the run cleanly: {e}");
    }
    flag
}
