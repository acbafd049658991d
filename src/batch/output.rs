//! A batch row as a JSON object with types: numbers as numbers wherever a JSON number
//! (read as binary64, as nearly every reader does) holds the decimal exactly as written,
//! strings where it would lose digits, null where nothing is given.

use std::collections::BTreeMap;

use serde::{Serialize, Serializer};

use super::RowResult;
use crate::compliance::column_name;

/// A value of the JSON output.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JsonValue<'a> {
    /// A number a binary64 holds exactly as its decimal was written.
    Number(f64),
    /// Text, or a decimal that a binary64 would change.
    Text(&'a str),
    /// Absent (an empty cell).
    Null,
}

impl<'a> JsonValue<'a> {
    /// A decimal as a number where that loses nothing, else as text; empty is null.
    pub fn decimal(text: &'a str) -> Self {
        if text.is_empty() {
            return JsonValue::Null;
        }
        exact_binary64(text).map_or(JsonValue::Text(text), JsonValue::Number)
    }

    /// Text as text; empty is null.
    pub fn text(text: &'a str) -> Self {
        if text.is_empty() {
            JsonValue::Null
        } else {
            JsonValue::Text(text)
        }
    }
}

impl Serialize for JsonValue<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            JsonValue::Number(value) => serializer.serialize_f64(*value),
            JsonValue::Text(text) => serializer.serialize_str(text),
            JsonValue::Null => serializer.serialize_none(),
        }
    }
}

/// A decimal's sign, significant digits (no leading or trailing zeros; empty for zero)
/// and the power of ten of its first digit; None when the text is not a plain decimal.
fn normalized(text: &str) -> Option<(bool, String, i64)> {
    let (negative, unsigned) = match text.as_bytes().first()? {
        b'-' => (true, &text[1..]),
        b'+' => (false, &text[1..]),
        _ => (false, text),
    };
    let (mantissa, exponent) = match unsigned.find(['e', 'E']) {
        Some(at) => (&unsigned[..at], unsigned[at + 1..].parse::<i64>().ok()?),
        None => (unsigned, 0),
    };
    let (whole, fraction) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let all_digits = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
    if whole.len() + fraction.len() == 0 || !all_digits(whole) || !all_digits(fraction) {
        return None;
    }
    let digits = format!("{whole}{fraction}");
    let leading = digits.len() - digits.trim_start_matches('0').len();
    let significant = digits.trim_matches('0').to_string();
    let first_power = exponent.checked_add(whole.len() as i64 - 1 - leading as i64)?;
    if significant.is_empty() {
        return Some((false, significant, 0));
    }
    Some((negative, significant, first_power))
}

/// The binary64 whose shortest decimal is `text`'s value exactly, if there is one.
fn exact_binary64(text: &str) -> Option<f64> {
    let written = normalized(text)?;
    let value: f64 = text.parse().ok().filter(|v: &f64| v.is_finite())?;
    (normalized(&format!("{value:e}"))? == written).then_some(value)
}

/// The input columns that are decimals of the case.
const DECIMAL_COLUMNS: [&str; 8] = ["p0", "p1", "q0", "q1", "phi", "friction", "lambda", "nu"];

/// One output row of a batch as a JSON object: the echoed input columns (the case's
/// decimals by [`JsonValue::decimal`], the others as text) and the result fields, W
/// by [`JsonValue::decimal`] (null where absent).
#[derive(Debug, Serialize)]
pub struct BatchRecord<'a> {
    #[serde(flatten)]
    pub inputs: BTreeMap<&'a str, JsonValue<'a>>,
    #[serde(rename = "W")]
    pub w: JsonValue<'a>,
    pub digits: Option<u32>,
    /// The digits proven (by a rigorous enclosure, or exact): 0 for estimated ones.
    pub digits_certified: Option<u32>,
    /// What vouches for W: `exact`, `certified`, `agreement`, `estimate`, `table_error`.
    pub provenance: JsonValue<'a>,
    /// Decimal strings of an interval that contains W (null for an exact value).
    pub enclosure: Option<[&'a str; 2]>,
    pub error_estimate: Option<f64>,
    pub table_error: Option<f64>,
    pub method: JsonValue<'a>,
    pub error: JsonValue<'a>,
}

impl<'a> BatchRecord<'a> {
    /// The record of the echoed (column, cell) pairs of a row and its result.
    pub fn new(cells: impl IntoIterator<Item = (&'a str, &'a str)>, result: &'a RowResult) -> Self {
        let typed = |(name, cell): (&'a str, &'a str)| {
            let decimal = DECIMAL_COLUMNS.contains(&column_name(name).as_str());
            (
                name,
                if decimal {
                    JsonValue::decimal(cell)
                } else {
                    JsonValue::text(cell)
                },
            )
        };
        BatchRecord {
            inputs: cells.into_iter().map(typed).collect(),
            w: JsonValue::decimal(&result.total),
            digits: result.digits,
            digits_certified: result.digits_certified,
            provenance: JsonValue::text(&result.provenance),
            enclosure: result
                .enclosure
                .as_ref()
                .map(|(lower, upper)| [lower.as_str(), upper.as_str()]),
            error_estimate: result.error_estimate,
            table_error: result.table_error,
            method: JsonValue::text(&result.method),
            error: JsonValue::text(&result.error),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_decimal_is_a_number_exactly_where_binary64_keeps_its_digits() {
        for (text, number) in [
            ("1", 1.0),
            ("0.4", 0.4),
            ("-2.5e-3", -2.5e-3),
            ("4.062475792458e-1", 0.4062475792458),
            ("0.00000000000000e0", 0.0),
            ("+7E2", 700.0),
            ("1.7976931348623157e308", f64::MAX),
            ("0.30000000000000004", 0.30000000000000004),
        ] {
            assert_eq!(JsonValue::decimal(text), JsonValue::Number(number), "{text}");
        }
        for text in [
            "0.4pi",
            "4.0624757924582385709e-1",
            "0.1000000000000000000001",
            "1e-400",
            "1e400",
            "inf",
            "NaN",
            "1e",
            ".",
            "1e99999999999999999999",
        ] {
            assert_eq!(JsonValue::decimal(text), JsonValue::Text(text), "{text}");
        }
        assert_eq!(JsonValue::decimal(""), JsonValue::Null);
    }
}
