//! How user text appears in messages: control characters (a NUL byte, a carriage return,
//! an escape sequence) are written as escapes, so that a message stays one line and
//! cannot drive the terminal; and a misspelt name is answered with the nearest known one.

use std::borrow::Cow;
use std::fmt::Write;

/// `text` with every control character written as an escape (`\0`, `\t`, `\n`, `\r`,
/// `\u{1b}`); other text, non-ASCII letters included, is kept as it is.
///
/// ```
/// use microslip::messages::printable;
///
/// assert_eq!(printable("persón"), "persón");
/// assert_eq!(printable("a\0b\u{1b}[31m\n"), "a\\0b\\u{1b}[31m\\n");
/// ```
pub fn printable(text: &str) -> Cow<'_, str> {
    if !text.chars().any(char::is_control) {
        return Cow::Borrowed(text);
    }
    let mut shown = String::with_capacity(text.len() + 8);
    for character in text.chars() {
        match character {
            '\0' => shown.push_str("\\0"),
            '\t' => shown.push_str("\\t"),
            '\n' => shown.push_str("\\n"),
            '\r' => shown.push_str("\\r"),
            control if control.is_control() => {
                let _ = write!(shown, "\\u{{{:x}}}", u32::from(control));
            }
            other => shown.push(other),
        }
    }
    Cow::Owned(shown)
}

/// The known name nearest a misspelt `word`, if one is near enough to be what was meant
/// (by the Jaro similarity the command line's own suggestions use, above 0.7).
///
/// ```
/// use microslip::messages::nearest;
///
/// let families = ["power", "persson", "hertz"];
/// assert_eq!(nearest("persón", &families), Some("persson"));
/// assert_eq!(nearest("hertzz", &families), Some("hertz"));
/// assert_eq!(nearest("zzz", &families), None);
/// ```
pub fn nearest<'a>(word: &str, known: &[&'a str]) -> Option<&'a str> {
    let word = word.to_lowercase();
    known
        .iter()
        .map(|&name| (strsim::jaro(&word, name), name))
        .filter(|&(similarity, _)| similarity > 0.7)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, name)| name)
}

/// ` (did you mean `NAME`?)` for the name nearest `word`, or nothing.
pub fn did_you_mean(word: &str, known: &[&str]) -> String {
    nearest(word, known).map_or(String::new(), |name| format!(" (did you mean `{name}`?)"))
}
