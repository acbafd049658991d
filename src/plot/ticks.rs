//! Tick labels: linear axes without spurious digits or a negative zero, logarithmic
//! axes (drawn in log10 of the value) as powers of ten.

use std::ops::Range;

/// The label of a tick at `value` on a linear axis spanning `range`: rounded to a
/// thousandth of the span (what a tick can mean), trailing zeros removed, zero as "0".
pub fn linear(value: f64, range: &Range<f64>) -> String {
    let span = (range.end - range.start).abs();
    if !(span.is_finite() && span > 0.0 && value.is_finite()) {
        return format!("{value}");
    }
    let unit_exponent = span.log10().floor() as i32 - 3;
    let unit = 10f64.powi(unit_exponent);
    let rounded = (value / unit).round() * unit;
    if rounded == 0.0 {
        return "0".to_string();
    }
    let magnitude = range.start.abs().max(range.end.abs());
    if !(1e-3..1e5).contains(&magnitude) {
        // Mantissa digits down to the unit.
        let digits = (rounded.abs().log10().floor() as i32 - unit_exponent).max(0) as usize;
        let text = format!("{rounded:.digits$e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        return format!("{}e{exponent}", trim_zeros(mantissa));
    }
    let decimals = (-unit_exponent).max(0) as usize;
    trim_zeros(&format!("{rounded:.decimals$}")).to_string()
}

fn trim_zeros(text: &str) -> &str {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.')
    } else {
        text
    }
}

/// The label of a tick at `exponent` on a logarithmic axis: 10 to that power, with
/// the exponent in superscript ("10⁻¹⁰"), or the value itself between decades.
pub fn power_of_ten(exponent: f64) -> String {
    if (exponent - exponent.round()).abs() < 1e-9 {
        let superscript: String = format!("{}", exponent.round() as i64)
            .chars()
            .map(|c| match c {
                '-' => '⁻',
                digit => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][digit.to_digit(10).unwrap_or(0) as usize],
            })
            .collect();
        format!("10{superscript}")
    } else {
        let value = 10f64.powf(exponent);
        let text = format!("{value:.1e}");
        let (mantissa, power) = text.split_once('e').unwrap_or((&text, "0"));
        format!(
            "{}×{}",
            trim_zeros(mantissa),
            power_of_ten(power.parse().unwrap_or(0.0))
        )
    }
}

/// How many ticks a logarithmic axis over `range` (in log10) gets: at most one per
/// decade and at most `most`, so that every tick falls on a whole power of ten.
pub fn decade_ticks(range: &Range<f64>, most: usize) -> usize {
    ((range.end - range.start).abs().floor() as usize + 1).clamp(2, most)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_have_no_negative_zero_and_no_rounding_noise() {
        let range = -1.05..1.05;
        assert_eq!(linear(-1e-17, &range), "0");
        assert_eq!(linear(-0.0, &range), "0");
        assert_eq!(linear(0.30000000000000004, &range), "0.3");
        assert_eq!(linear(-0.6, &range), "-0.6");
        assert_eq!(linear(12.0, &(0.0..40.0)), "12");
        assert_eq!(linear(2.5e-6, &(0.0..1e-5)), "2.5e-6");
        assert_eq!(linear(-1.2e-20, &(-1e-5..1e-5)), "0");
        assert_eq!(linear(150000.0, &(0.0..200000.0)), "1.5e5");
    }

    #[test]
    fn log_ticks_are_powers_of_ten() {
        assert_eq!(power_of_ten(-10.0), "10⁻¹⁰");
        assert_eq!(power_of_ten(0.0), "10⁰");
        assert_eq!(power_of_ten(3.0), "10³");
        assert_eq!(power_of_ten(-0.5), "3.2×10⁻¹");
        assert_eq!(decade_ticks(&(-16.0..1.0), 12), 12);
        assert_eq!(decade_ticks(&(-6.0..0.0), 12), 7);
    }
}
