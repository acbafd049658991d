//! Reading a table file: the CSV, its header (names matched with their units set
//! aside) and its rows, each number checked, with the line of the file for every refusal.

use super::{TableColumn, TableError, MIN_ROWS};
use crate::files::MAX_RECORD_BYTES;
use crate::messages::printable;

/// A table as read: which column gives the compliance, and per data row its file line,
/// load and value.
pub(super) struct RawTable {
    pub column: TableColumn,
    pub lines: Vec<u64>,
    pub loads: Vec<f64>,
    pub values: Vec<f64>,
}

impl RawTable {
    /// The error of data row `index`, naming its line.
    pub(super) fn row_error(&self, path: &str, index: usize, problem: String) -> TableError {
        TableError::Row {
            path: path.to_string(),
            line: self.lines[index],
            problem,
        }
    }

    /// Checks what every table needs before its shape: enough rows, strictly increasing
    /// loads, and v' > 0 (positive slopes, or an approach that increases).
    pub(super) fn check_rows(&self, path: &str) -> Result<(), TableError> {
        let n = self.loads.len();
        if n < MIN_ROWS {
            return Err(TableError::File {
                path: path.to_string(),
                problem: format!(
                    "has {n} data rows; at least {MIN_ROWS} are needed (a cubic interpolant, and a second one for its error)"
                ),
            });
        }
        for i in 1..n {
            if self.loads[i] <= self.loads[i - 1] {
                let word = if self.loads[i] == self.loads[i - 1] {
                    "repeats"
                } else {
                    "is below"
                };
                let problem = format!(
                    "load {} {word} the previous row's {}; loads must increase strictly",
                    self.loads[i],
                    self.loads[i - 1]
                );
                return Err(self.row_error(path, i, problem));
            }
        }
        match self.column {
            TableColumn::Slope => match self.values.iter().position(|&s| s <= 0.0) {
                Some(i) => {
                    let problem = format!("slope {} is not positive; a contact needs v' > 0", self.values[i]);
                    Err(self.row_error(path, i, problem))
                }
                None => Ok(()),
            },
            TableColumn::Approach => match (1..n).find(|&i| self.values[i] <= self.values[i - 1]) {
                Some(i) => {
                    let problem = format!(
                        "approach {} does not increase over the previous row's {}; a contact needs v' > 0",
                        self.values[i],
                        self.values[i - 1]
                    );
                    Err(self.row_error(path, i, problem))
                }
                None => Ok(()),
            },
        }
    }
}

/// The name a header cell gives its column: the text before a unit in brackets or
/// parentheses (`Load [N]`, `approach (um)`), trimmed, in lower case.
pub(crate) fn column_name(header: &str) -> String {
    let name = header.split(['[', '(']).next().unwrap_or(header);
    name.trim().to_lowercase()
}

/// The loads and values of the table file at `path` as written, or the first problem of the
/// file or of a row, naming its line. Its length is the list of refusals a table file can
/// earn (not a regular file, unreadable, no header, a record too long, an ambiguous or
/// missing column, a field missing, not a number or not finite), each with its own
/// message, in the one pass over the records that reads the numbers.
pub(super) fn read_raw(path: &str) -> Result<RawTable, TableError> {
    let file_error = |problem: String| TableError::File {
        path: path.to_string(),
        problem,
    };
    // A device or a pipe could be endless: only files are tables.
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file()) {
        return Err(file_error("is not a regular file".to_string()));
    }
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .flexible(true)
        .from_path(path)
        .map_err(|e| file_error(format!("cannot be read: {}", io_message(&e))))?;
    let headers = reader
        .headers()
        .map_err(|e| file_error(format!("has no readable header: {}", io_message(&e))))?
        .clone();
    let found = printable(&headers.iter().collect::<Vec<_>>().join(",")).into_owned();
    if reader.position().byte() > MAX_RECORD_BYTES {
        return Err(file_error(too_long()));
    }
    let find = |name: &str| -> Result<Option<usize>, TableError> {
        let mut matches = headers.iter().enumerate().filter(|(_, h)| column_name(h) == name);
        match (matches.next(), matches.next()) {
            (Some((_, first)), Some((_, second))) => Err(file_error(format!(
                "has two '{name}' columns ('{}' and '{}'); keep one, so that each value is given once",
                printable(first),
                printable(second)
            ))),
            (first, _) => Ok(first.map(|(index, _)| index)),
        }
    };
    let needs = "a table needs the columns load and approach, or load and slope (units in brackets or parentheses are allowed: 'Load [N]')";
    let load_column =
        find("load")?.ok_or_else(|| file_error(format!("has no 'load' column (its header is '{found}'); {needs}")))?;
    let (column, value_column) = match (find("approach")?, find("slope")?) {
        (Some(a), None) => (TableColumn::Approach, a),
        (None, Some(s)) => (TableColumn::Slope, s),
        (Some(_), Some(_)) => {
            return Err(file_error(
                "has both an 'approach' and a 'slope' column; keep one, so that the compliance is given once"
                    .to_string(),
            ))
        }
        (None, None) => {
            return Err(file_error(format!(
                "has neither an 'approach' nor a 'slope' column (its header is '{found}'); {needs}"
            )))
        }
    };
    let value_name = printable(headers.get(value_column).unwrap_or("value")).into_owned();
    let load_name = printable(headers.get(load_column).unwrap_or("load")).into_owned();
    let mut raw = RawTable {
        column,
        lines: Vec::new(),
        loads: Vec::new(),
        values: Vec::new(),
    };
    let mut record = csv::StringRecord::new();
    loop {
        let start = reader.position().byte();
        let more = reader.read_record(&mut record).map_err(|e| match e.position() {
            Some(position) => TableError::Row {
                path: path.to_string(),
                line: position.line(),
                problem: io_message(&e),
            },
            None => file_error(io_message(&e)),
        })?;
        if !more {
            break;
        }
        let line = record.position().map_or(0, |p| p.line());
        let row_error = |problem: String| TableError::Row {
            path: path.to_string(),
            line,
            problem,
        };
        if reader.position().byte() - start > MAX_RECORD_BYTES {
            return Err(row_error(too_long()));
        }
        if record.iter().all(str::is_empty) {
            continue;
        }
        let cell = |index: usize, name: &str| -> Result<f64, TableError> {
            let text = record
                .get(index)
                .ok_or_else(|| row_error(format!("has no {name} value (fewer fields than the header)")))?;
            let value: f64 = text
                .parse()
                .map_err(|_| row_error(format!("{name} '{}' is not a number", printable(text))))?;
            if !value.is_finite() {
                return Err(row_error(format!("{name} '{}' is not finite", printable(text))));
            }
            Ok(value)
        };
        raw.loads.push(cell(load_column, &load_name)?);
        raw.values.push(cell(value_column, &value_name)?);
        raw.lines.push(line);
    }
    Ok(raw)
}

/// Why a record longer than [`MAX_RECORD_BYTES`] is refused.
fn too_long() -> String {
    format!(
        "a record is longer than {} MiB: this is not a table of loads, whose rows are short",
        MAX_RECORD_BYTES >> 20
    )
}

fn io_message(error: &csv::Error) -> String {
    match error.kind() {
        csv::ErrorKind::Io(io) => io.to_string(),
        csv::ErrorKind::Utf8 { .. } => "is not UTF-8 text".to_string(),
        _ => error.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::column_name;

    #[test]
    fn column_names_set_units_and_case_aside() {
        for (header, name) in [
            ("Load [N]", "load"),
            ("load (N)", "load"),
            ("SLOPE", "slope"),
            ("Approach [um]", "approach"),
            ("approach(mm)", "approach"),
            ("  Slope  [mm/N] ", "slope"),
            ("loads", "loads"),
        ] {
            assert_eq!(column_name(header), name, "{header}");
        }
    }
}
