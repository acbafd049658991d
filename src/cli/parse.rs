//! Value parsers shared by every subcommand: each admits a stated range and says so
//! when a value is outside it (the message completes "--flag must ...").

use std::num::NonZeroUsize;
use std::time::Duration;

use microslip::answer::agreed::MAX_DIGITS;
use microslip::phase::ExactPhase;

/// The longest time budget accepted: 1e6 s (about 11.6 days). Larger values would
/// overflow the clock's arithmetic and mean "no limit", which is not on offer.
pub const MAX_SECONDS: f64 = 1e6;

/// A time budget in seconds: a positive number up to [`MAX_SECONDS`].
pub fn seconds(text: &str) -> Result<Duration, String> {
    let range = format!("must be a positive number of seconds, at most {MAX_SECONDS:e}");
    let value: f64 = text.trim().parse().map_err(|_| range.clone())?;
    if value.is_finite() && value > 0.0 && value <= MAX_SECONDS {
        Ok(Duration::from_secs_f64(value))
    } else {
        Err(range)
    }
}

/// A number of significant digits, 1 to [`MAX_DIGITS`].
pub fn digits(text: &str) -> Result<u32, String> {
    let range = format!("must be between 1 and {MAX_DIGITS}");
    match text.trim().parse::<u32>() {
        Ok(value) if (1..=MAX_DIGITS).contains(&value) => Ok(value),
        _ => Err(range),
    }
}

/// A count of at least `min`.
fn count_at_least(text: &str, min: usize) -> Result<usize, String> {
    let range = format!("must be a whole number of at least {min}");
    match text.trim().parse::<usize>() {
        Ok(value) if value >= min => Ok(value),
        Ok(_) => Err(range),
        Err(_) if !text.trim().starts_with('-') && text.trim().bytes().all(|b| b.is_ascii_digit()) => {
            Err(format!("{range} and at most {}", usize::MAX))
        }
        Err(_) => Err(range),
    }
}

/// The most worker threads accepted: far beyond any core count, short of what would
/// exhaust the system's threads before any work began.
pub const MAX_JOBS: usize = 1024;

/// A number of worker threads, 1 to [`MAX_JOBS`].
pub fn jobs(text: &str) -> Result<NonZeroUsize, String> {
    let range = format!("must be a whole number of threads from 1 to {MAX_JOBS}");
    match text.trim().parse::<usize>() {
        Ok(value) if value <= MAX_JOBS => NonZeroUsize::new(value).ok_or(range),
        _ => Err(range),
    }
}

/// Elements of the coarsest simulated bed (at least 20).
pub fn elements(text: &str) -> Result<usize, String> {
    count_at_least(text, 20)
}

/// Load steps per cycle of the coarsest simulation (at least 40).
pub fn steps(text: &str) -> Result<usize, String> {
    count_at_least(text, 40)
}

/// A relative tolerance in (0, 1).
pub fn tolerance(text: &str) -> Result<f64, String> {
    let range = "must be a number between 0 and 1 (exclusive), e.g. 1e-6".to_string();
    match text.trim().parse::<f64>() {
        Ok(value) if value > 0.0 && value < 1.0 => Ok(value),
        _ => Err(range),
    }
}

/// A seed: any whole number from 0 to 2^64 − 1.
pub fn seed(text: &str) -> Result<u64, String> {
    text.trim()
        .parse::<u64>()
        .map_err(|_| format!("must be a whole number from 0 to {}", u64::MAX))
}

/// A warning for a phase written as a bare number beyond a full turn (|φ| > 2π, `--phi 72`):
/// it is read as radians, as written, though degrees were likely meant. None for any
/// other phase (one in π or degrees, a smaller number, or none at all).
pub fn radians_warning(name: &str, text: &str) -> Option<String> {
    let phase = ExactPhase::parse(text).ok()?;
    let (multiple, offset) = phase.parts();
    let radians = offset.to_f64();
    if *multiple != 0 || radians.abs() <= std::f64::consts::TAU {
        return None;
    }
    let written = text.trim();
    let turns = radians / 180.0;
    let in_pi = format!("{turns}");
    let as_pi = if in_pi.len() <= 8 {
        format!("{in_pi}pi")
    } else {
        "0.4pi".to_string()
    };
    Some(format!(
        "{name} {written} is read as {written} radians (more than 2π); for degrees write {written}deg, or a multiple of π such as {as_pi}"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_bare_numbers_beyond_a_turn_are_warned_of() {
        let warning = radians_warning("--phi", "72").unwrap();
        assert!(warning.contains("72deg") && warning.contains("0.4pi"), "{warning}");
        assert!(radians_warning("--phi", "-100").unwrap().contains("-100deg"));
        for quiet in ["6.28", "72deg", "72°", "3pi", "0.4pi", "pi+7", "x", "1e-3"] {
            assert_eq!(radians_warning("--phi", quiet), None, "{quiet}");
        }
    }

    #[test]
    fn budgets_are_positive_and_bounded() {
        assert_eq!(seconds("2.5").unwrap(), Duration::from_millis(2500));
        for bad in ["0", "-1", "1e19", "1e300", "inf", "nan", "x", ""] {
            assert!(seconds(bad).is_err(), "{bad}");
        }
        assert!(seconds("1e6").is_ok());
    }

    #[test]
    fn digits_counts_and_tolerances_are_checked_against_their_ranges() {
        assert_eq!(digits("30").unwrap(), 30);
        for bad in ["0", "-1", "1001", "4294967296", "x"] {
            assert!(digits(bad).is_err(), "{bad}");
        }
        assert_eq!(elements("20").unwrap(), 20);
        assert!(elements("19").is_err() && elements("-5").is_err() && steps("39").is_err());
        assert!(elements("99999999999999999999999").unwrap_err().contains("at most"));
        assert!(tolerance("1e-6").is_ok() && tolerance("0").is_err() && tolerance("1").is_err());
        assert!(seed("18446744073709551615").is_ok() && seed("-1").is_err());
        assert_eq!(jobs("3").unwrap().get(), 3);
        assert_eq!(jobs("1024").unwrap().get(), MAX_JOBS);
        for bad in ["0", "-1", "1025", "99999999999999999999999", "x", ""] {
            assert!(jobs(bad).unwrap_err().contains("from 1 to 1024"), "{bad}");
        }
    }
}
