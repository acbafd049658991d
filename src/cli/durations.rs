//! How long the quick runs take, as measured on 2 cores (release build): the one place
//! the help states it from.

/// How long `microslip verify --quick` takes.
pub const VERIFY_QUICK: &str = "about 1 s on 2 cores";

/// How long `microslip accuracy --quick` takes.
pub const ACCURACY_QUICK: &str = "under 1 s on 2 cores";
