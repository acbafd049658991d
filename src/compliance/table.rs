//! A compliance from measured data: a CSV table of load against approach v(P), or
//! of load against slope v'(P), as a rig or a boundary-element contact solver writes it.
//!
//! The dissipation needs v' (and the small-amplitude law v''), with v' > 0 and
//! v'' ≤ 0. The table gives v' at its loads (from the slope column, or by
//! differentiating the approach column); between them v' is a monotone cubic Hermite
//! interpolant, which is positive and non-increasing wherever its node values are, and
//! has a continuous v''. A second, piecewise-linear interpolant of lower order gives
//! an estimate of the error the table introduces (proofs/table-compliance.md).
//! Loads outside the table are never extrapolated: v' is not finite there.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::SystemTime;

use super::{merged_breakpoints, Compliance};
use crate::real::Real;

/// The fewest rows a table may have: a cubic needs four.
pub const MIN_ROWS: usize = 4;

/// Relative size of a shape violation that counts as rounding in the data, not as a
/// violation: the default smoothing tolerance.
pub const ROUNDING_TOLERANCE: f64 = 1e-12;

/// Which column of the table carries the compliance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TableColumn {
    /// v(P), the approach.
    Approach,
    /// v'(P), the slope.
    Slope,
}

/// Which interpolant of the table a compliance evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum TableInterpolant {
    /// The monotone cubic Hermite v' through all rows (the one W is computed with).
    #[default]
    Cubic,
    /// The same construction from every other row (first and last kept), for the
    /// error estimate: its W differs from the full table's by about (2^p − 1) times the
    /// full table's error, p ≥ 3 the order of the construction.
    HalfTable,
}

/// The order in the load spacing that the table's construction has at least (cubic
/// Hermite pieces with second-order node derivatives), used to scale the half-table
/// difference into an error estimate.
pub const TABLE_ORDER: i32 = 3;

/// A table that cannot be used, with the line of the file at fault where there is one.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TableError {
    /// The file cannot be read or is not CSV.
    #[error("table '{path}': {problem}")]
    File { path: String, problem: String },
    /// One row (line of the file) is wrong.
    #[error("table '{path}' line {line}: {problem}")]
    Row { path: String, line: u64, problem: String },
    /// The cycle reaches loads the table does not cover.
    #[error("table '{path}' covers loads [{first:e}, {last:e}], but the cycle reaches [{low:e}, {high:e}] (from the permanent-stick load P_T or P0 − P1 up to P0 + P1); a table compliance is never extrapolated: extend the table")]
    OutOfRange {
        path: String,
        first: f64,
        last: f64,
        low: f64,
        high: f64,
    },
}

/// A validated table and its two interpolants, in f64 (the precision measured data carry).
#[derive(Debug)]
pub struct ComplianceTable {
    /// The file it came from.
    pub path: String,
    /// Which column gave the compliance.
    pub column: TableColumn,
    /// The loads, strictly increasing.
    pub loads: Vec<f64>,
    /// v' at the loads (after smoothing), the cubic's node values.
    pub slopes: Vec<f64>,
    /// v'' at the loads, the cubic's node derivatives (≤ 0).
    curvatures: Vec<f64>,
    /// The same construction from every other row (None for the half table itself).
    half: Option<Box<ComplianceTable>>,
    /// v at the first load.
    first_approach: f64,
    /// ∫ v' of the cubic from the first load to each load.
    cumulative: Vec<f64>,
    /// The largest relative change smoothing made to the data (0 when none was needed).
    pub smoothing_residual: f64,
}

struct RawTable {
    column: TableColumn,
    lines: Vec<u64>,
    loads: Vec<f64>,
    values: Vec<f64>,
}

fn read_raw(path: &str) -> Result<RawTable, TableError> {
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
    let find = |name: &str| headers.iter().position(|h| h.eq_ignore_ascii_case(name));
    let found: Vec<&str> = headers.iter().collect();
    let needs = "a table needs the columns load and approach, or load and slope";
    let load_column = find("load").ok_or_else(|| {
        file_error(format!(
            "has no 'load' column (its header is '{}'); {needs}",
            found.join(",")
        ))
    })?;
    let (column, value_column) = match (find("approach"), find("slope")) {
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
                "has neither an 'approach' nor a 'slope' column (its header is '{}'); {needs}",
                found.join(",")
            )))
        }
    };
    let value_name = headers.get(value_column).unwrap_or("value").to_string();
    let mut raw = RawTable {
        column,
        lines: Vec::new(),
        loads: Vec::new(),
        values: Vec::new(),
    };
    for record in reader.records() {
        let record = record.map_err(|e| match e.position() {
            Some(position) => TableError::Row {
                path: path.to_string(),
                line: position.line(),
                problem: io_message(&e),
            },
            None => file_error(io_message(&e)),
        })?;
        let line = record.position().map_or(0, |p| p.line());
        if record.iter().all(str::is_empty) {
            continue;
        }
        let row_error = |problem: String| TableError::Row {
            path: path.to_string(),
            line,
            problem,
        };
        let cell = |index: usize, name: &str| -> Result<f64, TableError> {
            let text = record
                .get(index)
                .ok_or_else(|| row_error(format!("has no {name} value (fewer fields than the header)")))?;
            let value: f64 = text
                .parse()
                .map_err(|_| row_error(format!("{name} '{text}' is not a number")))?;
            if !value.is_finite() {
                return Err(row_error(format!("{name} '{text}' is not finite")));
            }
            Ok(value)
        };
        raw.loads.push(cell(load_column, "load")?);
        raw.values.push(cell(value_column, &value_name)?);
        raw.lines.push(line);
    }
    Ok(raw)
}

fn io_message(error: &csv::Error) -> String {
    match error.kind() {
        csv::ErrorKind::Io(io) => io.to_string(),
        csv::ErrorKind::Utf8 { .. } => "is not UTF-8 text".to_string(),
        _ => error.to_string(),
    }
}

/// Weighted least-squares fit of a non-increasing sequence (pool adjacent violators).
fn non_increasing_fit(values: &[f64], weights: &[f64]) -> Vec<f64> {
    // Blocks of (mean, weight, count), merged while a later block rises above an earlier one.
    let mut blocks: Vec<(f64, f64, usize)> = Vec::new();
    for (&value, &weight) in values.iter().zip(weights) {
        blocks.push((value, weight, 1));
        while blocks.len() > 1 {
            let (last, before) = (blocks[blocks.len() - 1], blocks[blocks.len() - 2]);
            if last.0 <= before.0 {
                break;
            }
            let weight = last.1 + before.1;
            let merged = (
                (last.0 * last.1 + before.0 * before.1) / weight,
                weight,
                last.2 + before.2,
            );
            blocks.pop();
            *blocks.last_mut().expect("two blocks") = merged;
        }
    }
    blocks
        .iter()
        .flat_map(|&(mean, _, count)| std::iter::repeat_n(mean, count))
        .collect()
}

/// The derivative at `x[i]` of the polynomial through the points of `stencil` (which holds i).
fn stencil_derivative(x: &[f64], y: &[f64], i: usize, stencil: std::ops::Range<usize>) -> f64 {
    let mut derivative = 0.0;
    for j in stencil.clone() {
        let weight = if j == i {
            stencil.clone().filter(|&k| k != i).map(|k| 1.0 / (x[i] - x[k])).sum()
        } else {
            let numerator: f64 = stencil
                .clone()
                .filter(|&k| k != i && k != j)
                .map(|k| x[i] - x[k])
                .product();
            let denominator: f64 = stencil.clone().filter(|&k| k != j).map(|k| x[j] - x[k]).product();
            numerator / denominator
        };
        derivative += weight * y[j];
    }
    derivative
}

/// Node derivatives of a monotone (non-increasing) cubic Hermite through (x, y): the
/// three-point parabola's slope, limited (Hyman) to keep each cubic piece monotone.
fn monotone_tangents(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let delta: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
    (0..n)
        .map(|i| {
            let (raw, limit) = if i == 0 {
                (
                    delta[0] + (delta[0] - delta[1]) * h[0] / (h[0] + h[1]),
                    3.0 * delta[0].abs(),
                )
            } else if i == n - 1 {
                let (a, b) = (delta[n - 2], delta[n - 3]);
                (a + (a - b) * h[n - 2] / (h[n - 2] + h[n - 3]), 3.0 * a.abs())
            } else {
                let (a, b) = (delta[i - 1], delta[i]);
                (
                    (h[i] * a + h[i - 1] * b) / (h[i - 1] + h[i]),
                    3.0 * a.abs().min(b.abs()),
                )
            };
            // v' does not increase: a node derivative is ≤ 0 and within the Hyman bound.
            raw.min(0.0).max(-limit)
        })
        .collect()
}

impl ComplianceTable {
    /// Reads and validates the table at `path`; violations of v'' ≤ 0 up to `smoothing`
    /// (relative) are removed by a least-squares non-increasing fit of the slopes.
    pub fn read(path: &str, smoothing: f64) -> Result<Self, TableError> {
        let raw = read_raw(path)?;
        let row = |index: usize, problem: String| TableError::Row {
            path: path.to_string(),
            line: raw.lines[index],
            problem,
        };
        let n = raw.loads.len();
        if n < MIN_ROWS {
            return Err(TableError::File {
                path: path.to_string(),
                problem: format!(
                    "has {n} data rows; at least {MIN_ROWS} are needed (a cubic interpolant, and a second one for its error)"
                ),
            });
        }
        for i in 1..n {
            if raw.loads[i] <= raw.loads[i - 1] {
                let word = if raw.loads[i] == raw.loads[i - 1] {
                    "repeats"
                } else {
                    "is below"
                };
                return Err(row(
                    i,
                    format!(
                        "load {} {word} the previous row's {}; loads must increase strictly",
                        raw.loads[i],
                        raw.loads[i - 1]
                    ),
                ));
            }
        }
        let tolerance = smoothing.max(ROUNDING_TOLERANCE);
        let h: Vec<f64> = raw.loads.windows(2).map(|w| w[1] - w[0]).collect();
        // The slopes the shape is checked on: v' itself, or the secants of v.
        let (checked, weights, name) = match raw.column {
            TableColumn::Slope => {
                if let Some(i) = raw.values.iter().position(|&s| s <= 0.0) {
                    return Err(row(
                        i,
                        format!("slope {} is not positive; a contact needs v' > 0", raw.values[i]),
                    ));
                }
                (raw.values.clone(), vec![1.0; n], "slope")
            }
            TableColumn::Approach => {
                for i in 1..n {
                    if raw.values[i] <= raw.values[i - 1] {
                        return Err(row(
                            i,
                            format!(
                                "approach {} does not increase over the previous row's {}; a contact needs v' > 0",
                                raw.values[i],
                                raw.values[i - 1]
                            ),
                        ));
                    }
                }
                let secants: Vec<f64> = (0..n - 1).map(|k| (raw.values[k + 1] - raw.values[k]) / h[k]).collect();
                (secants, h.clone(), "secant slope of the approach")
            }
        };
        let fitted = non_increasing_fit(&checked, &weights);
        let mut residual: f64 = 0.0;
        for (k, (&data, &fit)) in checked.iter().zip(&fitted).enumerate() {
            let relative = (data - fit).abs() / data.abs();
            if relative > tolerance {
                // The rise nearest the value the fit moved most: where the fit had to pool.
                let rise = (1..checked.len())
                    .filter(|&j| checked[j] > checked[j - 1])
                    .min_by_key(|&j| j.abs_diff(k))
                    .unwrap_or(k.max(1));
                // A rise of the slopes at row j; of the secants, at the row between secants j − 1 and j.
                let line_index = rise;
                return Err(row(
                    line_index,
                    format!(
                        "the {name} rises from {:.4e} to {:.4e}: the data are not concave (v'' ≤ 0) here; the nearest concave fit moves them by {relative:.1e} relative, beyond the smoothing tolerance {tolerance:.0e} (raise smoothing= to fit noisy data)",
                        checked[rise - 1],
                        checked[rise]
                    ),
                ));
            }
            residual = residual.max(relative);
        }
        let first_approach = match raw.column {
            TableColumn::Slope => 0.0,
            TableColumn::Approach => raw.values[0],
        };
        let mut table = Self::build(path, raw.column, raw.loads, &fitted, first_approach);
        table.smoothing_residual = if residual > ROUNDING_TOLERANCE { residual } else { 0.0 };
        Ok(table)
    }

    /// The interpolant of validated, shape-fitted data (`fitted`: the slopes, or the
    /// secant slopes of the approach), with its half table.
    fn build(path: &str, column: TableColumn, loads: Vec<f64>, fitted: &[f64], first_approach: f64) -> Self {
        let mut table = Self::build_one(path, column, loads.clone(), fitted, first_approach);
        let n = loads.len();
        let rows: Vec<usize> = (0..n).filter(|&i| i % 2 == 0 || i == n - 1).collect();
        let half_loads: Vec<f64> = rows.iter().map(|&i| loads[i]).collect();
        let half_fitted: Vec<f64> = match column {
            TableColumn::Slope => rows.iter().map(|&i| fitted[i]).collect(),
            // Secants over the wider intervals: width-weighted means of the fine ones.
            TableColumn::Approach => rows
                .windows(2)
                .map(|w| {
                    let rise: f64 = (w[0]..w[1]).map(|k| fitted[k] * (loads[k + 1] - loads[k])).sum();
                    rise / (loads[w[1]] - loads[w[0]])
                })
                .collect(),
        };
        table.half = Some(Box::new(Self::build_one(
            path,
            column,
            half_loads,
            &half_fitted,
            first_approach,
        )));
        table
    }

    fn build_one(path: &str, column: TableColumn, loads: Vec<f64>, fitted: &[f64], first_approach: f64) -> Self {
        let slopes = match column {
            TableColumn::Slope => fitted.to_vec(),
            TableColumn::Approach => {
                let mut approach = vec![first_approach];
                for k in 0..loads.len() - 1 {
                    approach.push(approach[k] + fitted[k] * (loads[k + 1] - loads[k]));
                }
                node_slopes(&loads, &approach, fitted)
            }
        };
        let curvatures = monotone_tangents(&loads, &slopes);
        let mut table = ComplianceTable {
            path: path.to_string(),
            column,
            loads,
            slopes,
            curvatures,
            half: None,
            first_approach,
            cumulative: Vec::new(),
            smoothing_residual: 0.0,
        };
        table.cumulative = std::iter::once(0.0)
            .chain((0..table.loads.len() - 1).scan(0.0, |sum, k| {
                *sum += table.cubic_piece_integral(k, 1.0);
                Some(*sum)
            }))
            .collect();
        table
    }

    /// [first load, last load].
    pub fn range(&self) -> (f64, f64) {
        (self.loads[0], self.loads[self.loads.len() - 1])
    }

    /// Refuses loads [low, high] that leave the table (rounding-level excess allowed).
    pub fn check_covers(&self, low: f64, high: f64) -> Result<(), TableError> {
        let (first, last) = self.range();
        let slack = 1e-12 * first.abs().max(last.abs());
        if low < first - slack || high > last + slack || !low.is_finite() || !high.is_finite() {
            return Err(TableError::OutOfRange {
                path: self.path.clone(),
                first,
                last,
                low,
                high,
            });
        }
        Ok(())
    }

    /// The piece holding `load`, or None outside the table (beyond rounding).
    fn piece(&self, load: f64) -> Option<usize> {
        let (first, last) = self.range();
        let slack = 1e-12 * first.abs().max(last.abs());
        if !(load >= first - slack && load <= last + slack) {
            return None;
        }
        let upper = self.loads.partition_point(|&x| x <= load);
        Some(upper.clamp(1, self.loads.len() - 1) - 1)
    }

    /// ∫ of the cubic v' over piece k from its start to the fraction t of its width.
    fn cubic_piece_integral(&self, k: usize, t: f64) -> f64 {
        let h = self.loads[k + 1] - self.loads[k];
        let (y0, y1, m0, m1) = (
            self.slopes[k],
            self.slopes[k + 1],
            self.curvatures[k],
            self.curvatures[k + 1],
        );
        let (t2, t3, t4) = (t * t, t * t * t, t * t * t * t);
        h * (y0 * (t - t3 + t4 / 2.0)
            + y1 * (t3 - t4 / 2.0)
            + h * m0 * (t2 / 2.0 - 2.0 * t3 / 3.0 + t4 / 4.0)
            + h * m1 * (t4 / 4.0 - t3 / 3.0))
    }
}

/// Node slopes of the approach data: fourth-order (five-point stencils) where they keep
/// the concave shape, the three-point parabola's (second order) elsewhere. `secants` are
/// the (fitted) secant slopes.
fn node_slopes(x: &[f64], v: &[f64], secants: &[f64]) -> Vec<f64> {
    let n = x.len();
    let coarse: Vec<f64> = (0..n)
        .map(|i| {
            let stencil = if i == 0 {
                0..3
            } else if i == n - 1 {
                n - 3..n
            } else {
                i - 1..i + 2
            };
            stencil_derivative(x, v, i, stencil)
        })
        .map(|s| s.max(secants[secants.len() - 1] / 2.0))
        .collect();
    let mut fine = coarse.clone();
    if n >= 5 {
        for (i, slot) in fine.iter_mut().enumerate() {
            let start = i.saturating_sub(2).min(n - 5);
            let candidate = stencil_derivative(x, v, i, start..start + 5);
            // Concave data put v'(x_i) between the neighbouring secants.
            let above = if i == 0 { f64::INFINITY } else { secants[i - 1] };
            let below = if i == n - 1 { 0.0 } else { secants[i] };
            if candidate.is_finite() && candidate > 0.0 && candidate >= below && candidate <= above {
                *slot = candidate;
            }
        }
    }
    fine
}

/// The text after `table:`: the file, then optionally `smoothing=TOL` (relative, ≥ 0).
/// `file=PATH` names the file explicitly.
pub fn parse_table_term(text: &str) -> Result<(String, f64), String> {
    let mut path: Option<String> = None;
    let mut smoothing = 0.0;
    for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        match item.split_once('=').map(|(k, v)| (k.trim(), v.trim())) {
            Some(("smoothing", value)) => {
                smoothing = value
                    .parse::<f64>()
                    .ok()
                    .filter(|s| s.is_finite() && *s >= 0.0)
                    .ok_or_else(|| format!("table smoothing='{value}' is not a number ≥ 0"))?;
            }
            Some(("file", value)) if path.is_none() => path = Some(value.to_string()),
            None if path.is_none() => path = Some(item.to_string()),
            _ => {
                return Err(format!(
                    "table takes a file and optionally smoothing=TOL (table:FILE,smoothing=1e-3), not '{item}'"
                ))
            }
        }
    }
    let path = path.ok_or_else(|| "table needs a file: table:FILE".to_string())?;
    Ok((path, smoothing))
}

/// The table at `path` read once per process (and again when the file changes).
pub fn cached_table(path: &str, smoothing: f64) -> Result<Arc<ComplianceTable>, TableError> {
    type Key = (PathBuf, u64, Option<SystemTime>, u64);
    static CACHE: OnceLock<Mutex<HashMap<Key, Arc<ComplianceTable>>>> = OnceLock::new();
    let stamp = std::fs::metadata(Path::new(path)).ok();
    let key: Key = (
        PathBuf::from(path),
        smoothing.to_bits(),
        stamp.as_ref().and_then(|m| m.modified().ok()),
        stamp.as_ref().map_or(0, |m| m.len()),
    );
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(table) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return Ok(Arc::clone(table));
    }
    let table = Arc::new(ComplianceTable::read(path, smoothing)?);
    cache
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(key, Arc::clone(&table));
    Ok(table)
}

/// A compliance given by a table: one of its interpolants, evaluated at any precision
/// (the node data are f64, exact at every precision).
#[derive(Clone, Debug)]
pub struct TableCompliance {
    /// The data.
    pub table: Arc<ComplianceTable>,
    /// Which interpolant.
    pub interpolant: TableInterpolant,
}

impl TableCompliance {
    /// The data this interpolant runs on.
    fn data(&self) -> &ComplianceTable {
        match (self.interpolant, &self.table.half) {
            (TableInterpolant::HalfTable, Some(half)) => half,
            _ => &self.table,
        }
    }

    /// The data, the piece, its width h and the fraction t of it at `load`; None outside
    /// the table.
    fn locate<R: Real>(&self, load: &R) -> Option<(&ComplianceTable, usize, R, R)> {
        let data = self.data();
        let k = data.piece(load.to_f64_lossy())?;
        let start = R::from_f64(data.loads[k], load.precision());
        let h = R::from_f64(data.loads[k + 1], load.precision()) - &start;
        let t = (load.clone() - &start) / &h;
        Some((data, k, h, t))
    }
}

/// The node values y0, y1 and node derivatives m0, m1 of piece k, at the precision of `like`.
fn piece_nodes<R: Real>(data: &ComplianceTable, k: usize, like: &R) -> (R, R, R, R) {
    let at = |x: f64| R::from_f64(x, like.precision());
    (
        at(data.slopes[k]),
        at(data.slopes[k + 1]),
        at(data.curvatures[k]),
        at(data.curvatures[k + 1]),
    )
}

impl<R: Real> Compliance<R> for TableCompliance {
    fn approach(&self, load: &R) -> R {
        let Some((data, k, h, t)) = self.locate(load) else {
            return load.int(0) / &load.int(0);
        };
        let (y0, y1, m0, m1) = piece_nodes(data, k, load);
        let base = R::from_f64(data.first_approach + data.cumulative[k], load.precision());
        // ∫ of the Hermite basis from 0 to t.
        let (t2, t3) = (t.square(), t.square() * &t);
        let t4 = t2.square();
        let half = t.ratio(1, 2);
        let part = y0 * &(t.clone() - &t3 + &(t4.clone() * &half))
            + &(y1 * &(t3.clone() - &(t4.clone() * &half)))
            + &(h.clone()
                * &(m0 * &(t2 * &half - &(t3.clone() * &t.ratio(2, 3)) + &(t4.clone() * &t.ratio(1, 4)))
                    + &(m1 * &(t4 * &t.ratio(1, 4) - &(t3 * &t.ratio(1, 3))))));
        base + &(part * &h)
    }

    fn slope(&self, load: &R) -> R {
        let Some((data, k, h, t)) = self.locate(load) else {
            return load.int(0) / &load.int(0);
        };
        let (y0, y1, m0, m1) = piece_nodes(data, k, load);
        // Hermite form y0 + t·(y1 − y0) + h·t(1 − t)·[(1 − t)(m0 − δ) − t(m1 − δ)], δ the secant.
        let delta = (y1.clone() - &y0) / &h;
        let one_minus = t.int(1) - &t;
        let bump = (one_minus.clone() * &(m0 - &delta) - &(t.clone() * &(m1 - &delta))) * &t * &one_minus * &h;
        y0.clone() + &((y1 - &y0) * &t) + &bump
    }

    fn curvature(&self, load: &R) -> R {
        let Some((data, k, h, t)) = self.locate(load) else {
            return load.int(0) / &load.int(0);
        };
        let (y0, y1, m0, m1) = piece_nodes(data, k, load);
        // d/dP of the Hermite form: the basis derivatives, the value terms over h.
        let t2 = t.square();
        let d00 = (t2.clone() - &t) * &t.int(6);
        let d10 = t2.clone() * &t.int(3) - &(t.clone() * &t.int(4)) + &t.int(1);
        let d11 = t2 * &t.int(3) - &(t.clone() * &t.int(2));
        (d00 * &(y0 - &y1)) / &h + &(d10 * &m0) + &(d11 * &m1)
    }

    fn breakpoints(&self, like: &R) -> Vec<R> {
        // The interior loads: the first and last bound the table, beyond which v' is not finite.
        let loads = &self.data().loads;
        loads[1..loads.len() - 1]
            .iter()
            .map(|&load| R::from_f64(load, like.precision()))
            .collect()
    }

    fn describe(&self) -> String {
        let data = self.data();
        let (first, last) = data.range();
        format!(
            "table '{}' ({} rows of {}, loads {first:e} to {last:e}; monotone cubic v'{})",
            data.path,
            data.loads.len(),
            match data.column {
                TableColumn::Approach => "approach",
                TableColumn::Slope => "slope",
            },
            match self.interpolant {
                TableInterpolant::Cubic => "",
                TableInterpolant::HalfTable => " from every other row",
            }
        )
    }
}

/// v'_a − v'_b: the compliance whose W is W\[a\] − W\[b\] (W is linear in v'), computed
/// without the cancellation of subtracting two W values.
#[derive(Debug)]
pub struct Difference<R> {
    /// The minuend.
    pub minuend: Box<dyn Compliance<R>>,
    /// The subtrahend.
    pub subtrahend: Box<dyn Compliance<R>>,
}

impl<R: Real> Compliance<R> for Difference<R> {
    fn approach(&self, load: &R) -> R {
        self.minuend.approach(load) - &self.subtrahend.approach(load)
    }
    fn slope(&self, load: &R) -> R {
        self.minuend.slope(load) - &self.subtrahend.slope(load)
    }
    fn curvature(&self, load: &R) -> R {
        self.minuend.curvature(load) - &self.subtrahend.curvature(load)
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        self.minuend.slope_change(reference, offset) - &self.subtrahend.slope_change(reference, offset)
    }
    fn breakpoints(&self, like: &R) -> Vec<R> {
        merged_breakpoints([self.minuend.breakpoints(like), self.subtrahend.breakpoints(like)])
    }
    fn describe(&self) -> String {
        format!("({}) − ({})", self.minuend.describe(), self.subtrahend.describe())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_increasing_fit_pools_violators() {
        let fit = non_increasing_fit(&[3.0, 1.0, 2.0, 0.5], &[1.0; 4]);
        assert_eq!(fit, vec![3.0, 1.5, 1.5, 0.5]);
        let untouched = non_increasing_fit(&[4.0, 3.0, 2.0], &[1.0, 2.0, 3.0]);
        assert_eq!(untouched, vec![4.0, 3.0, 2.0]);
    }

    #[test]
    fn stencil_derivative_is_exact_for_quartics() {
        let x = [0.3, 0.7, 1.2, 1.4, 2.5];
        let y: Vec<f64> = x.iter().map(|&p: &f64| p.powi(4) - 2.0 * p * p + p).collect();
        for i in 0..5 {
            let expected = 4.0 * x[i].powi(3) - 4.0 * x[i] + 1.0;
            assert!((stencil_derivative(&x, &y, i, 0..5) - expected).abs() < 1e-11);
        }
    }

    #[test]
    fn monotone_tangents_reproduce_a_line() {
        let x = [1.0, 2.0, 4.0, 5.0];
        let y: Vec<f64> = x.iter().map(|p| 3.0 - 0.5 * p).collect();
        for m in monotone_tangents(&x, &y) {
            assert!((m + 0.5).abs() < 1e-15);
        }
    }
}
