//! The end of a run by a signal (SIGINT, SIGTERM, SIGHUP): the temporary files of the
//! outputs being written are removed first, then the process ends as the signal would
//! have ended it, so that no output is half-written and no temporary file is left.

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
use signal_hook::iterator::Signals;

use super::report::Failure;

/// Watches for the signals on a thread of its own for the rest of the run.
pub fn install() -> Result<(), Failure> {
    let mut signals = Signals::new([SIGINT, SIGTERM, SIGHUP])
        .map_err(|error| Failure::failed(format!("cannot watch for signals: {error}")))?;
    std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                microslip::files::abandon_temporaries();
                let _ = signal_hook::low_level::emulate_default_handler(signal);
                std::process::exit(128 + signal);
            }
        })
        .map(drop)
        .map_err(|error| Failure::failed(format!("cannot watch for signals: {error}")))
}
