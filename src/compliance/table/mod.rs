//! A compliance from measured data: a CSV table of load against approach v(P), or
//! of load against slope v'(P), as a rig or a boundary-element contact solver writes it.
//!
//! The dissipation needs v' (and the small-amplitude law v''), with v' > 0 and
//! v'' ≤ 0. The table gives v' at its loads (from the slope column, or by
//! differentiating the approach column); between them v' is a monotone cubic Hermite
//! interpolant of ln v' in ln P (of v' in P where a load is ≤ 0), which is positive and
//! non-increasing wherever its node values are, has a continuous v'', and is exact for
//! power laws. The same construction from the even rows and from the odd rows, weighed
//! by how much coarser each is on the table's actual spacing, and on the values moved by
//! their rounding, gives an estimate of the error interpolating the table introduces
//! (proofs/table-compliance.md); nothing of the error of the data themselves.
//! Loads outside the table are never extrapolated: v' is not finite there.

mod interpolant;
mod read;
mod shape;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::SystemTime;

use super::Compliance;
use crate::messages::{did_you_mean, printable};
use crate::real::Real;
pub use interpolant::Coordinates;
use interpolant::Piecewise;
pub(crate) use read::column_name;
use read::{read_raw, RawTable};
use shape::{approach_node_slopes, concave_data};

/// The fewest rows a table may have: a cubic needs four.
pub const MIN_ROWS: usize = 4;

/// Relative size of a shape violation that counts as rounding in the data, not as a
/// violation: the default smoothing tolerance (raised, for the secants of an approach,
/// to the rounding of the difference of two values).
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
    /// The monotone cubic through all rows (the one W is computed with).
    #[default]
    Cubic,
    /// The same construction from the even rows (first and last kept), for the error
    /// estimate: its W differs from the full table's by about (2^p − 1) times the full
    /// table's error, p the order of the construction.
    HalfTable,
    /// The same from the odd rows (first and last kept): a second such estimate, which
    /// does not share the first one's accidental cancellations.
    OtherHalfTable,
    /// The same construction on all rows with each value moved by 4 ulps (`DATA_ROUNDING`)
    /// relative, up and down on alternate rows, and each interior load the other way
    /// (where that keeps them in order; the ends stay, so the table covers what it
    /// covered): how far rounding of the data and of the construction's arithmetic moves
    /// W, which derivatives over rows close together amplify and halving the rows does not
    /// show.
    DataRounding,
}

/// The order in the load spacing that the table's construction has (cubic Hermite
/// pieces with fourth-order node derivatives), used to scale the half-table
/// differences into an error estimate.
pub const TABLE_ORDER: i32 = 4;

/// The relative move of each value in [`TableInterpolant::DataRounding`]: a few units
/// of f64 rounding, as the data and the arithmetic on them carry.
pub const DATA_ROUNDING: f64 = 4.0 * f64::EPSILON;

/// A table that cannot be used, with the line of the file at fault where there is one.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TableError {
    /// The file cannot be read or is not CSV.
    #[error("table '{path}': {problem}")]
    File {
        /// The table's file.
        path: String,
        /// What is wrong with it.
        problem: String,
    },
    /// One row (line of the file) is wrong.
    #[error("table '{path}' line {line}: {problem}")]
    Row {
        /// The table's file.
        path: String,
        /// The line of the file (1 is the first).
        line: u64,
        /// What is wrong with the row.
        problem: String,
    },
    /// The cycle reaches loads the table does not cover.
    #[error("table '{path}' covers loads [{first:e}, {last:e}], but the cycle reaches [{low:e}, {high:e}] (from the permanent-stick load P_T or P0 − P1 up to P0 + P1); a table compliance is never extrapolated: extend the table")]
    OutOfRange {
        /// The table's file.
        path: String,
        /// The table's first load.
        first: f64,
        /// The table's last load.
        last: f64,
        /// The lowest load the cycle reaches.
        low: f64,
        /// The highest load the cycle reaches.
        high: f64,
    },
}

/// A validated table and its interpolant, in f64 (the precision measured data carry),
/// with the same construction from its even rows and from its odd rows for the error
/// estimate.
#[derive(Debug)]
pub struct ComplianceTable {
    /// The file it came from.
    pub path: String,
    /// Which column gave the compliance.
    pub column: TableColumn,
    /// The loads, strictly increasing.
    pub loads: Vec<f64>,
    /// v' at the loads (after smoothing), the interpolant's node values.
    pub slopes: Vec<f64>,
    /// The coordinates of the cubic pieces (log–log unless a load is ≤ 0).
    pub coordinates: Coordinates,
    /// The cubic v'.
    interpolant: Piecewise,
    /// The construction from the even rows and from the odd rows, first and last row
    /// kept in both (empty for those tables themselves).
    halves: Vec<ComplianceTable>,
    /// The construction on the data moved by their rounding (empty for the derived tables).
    rounded: Vec<ComplianceTable>,
    /// v at the first load.
    first_approach: f64,
    /// The largest relative change smoothing made to the data (0 when none was needed).
    pub smoothing_residual: f64,
}

impl ComplianceTable {
    /// Reads and validates the table at `path`; violations of v'' ≤ 0 up to `smoothing`
    /// (relative) are removed by a least-squares non-increasing fit of the slopes.
    pub fn read(path: &str, smoothing: f64) -> Result<Self, TableError> {
        let raw = read_raw(path)?;
        raw.check_rows(path)?;
        let (values, residual) = concave_data(&raw, smoothing, path)?;
        // Log–log where the loads allow it, unless the data are better predicted in the
        // load itself (linear or quadratic v', say): the coordinates whose half tables
        // predict the rows they leave out more closely.
        let mut table = Self::with_halves(path, &raw, &values, Coordinates::for_loads(&raw.loads));
        if table.coordinates == Coordinates::LogLog {
            let linear = Self::with_halves(path, &raw, &values, Coordinates::Linear);
            if linear.half_table_discrepancy() < table.half_table_discrepancy() {
                table = linear;
            }
        }
        table.smoothing_residual = if residual > ROUNDING_TOLERANCE { residual } else { 0.0 };
        Ok(table)
    }

    /// The table of `values` at the raw loads in `coordinates`, with its two half tables
    /// (even rows, odd rows, the first and last kept in both) and the table of the data
    /// moved by their rounding, which its error estimate compares.
    fn with_halves(path: &str, raw: &RawTable, values: &[f64], coordinates: Coordinates) -> Self {
        let n = raw.loads.len();
        let build = |loads: &[f64], values: &[f64]| Self::build(path, raw.column, coordinates, loads, values);
        let mut table = build(&raw.loads, values);
        for parity in [0, 1] {
            let rows: Vec<usize> = (0..n).filter(|&i| i % 2 == parity || i == 0 || i == n - 1).collect();
            let pick = |data: &[f64]| rows.iter().map(|&i| data[i]).collect::<Vec<f64>>();
            table.halves.push(build(&pick(&raw.loads), &pick(values)));
        }
        let alternate = |i: usize| if i % 2 == 0 { DATA_ROUNDING } else { -DATA_ROUNDING };
        let moved: Vec<f64> = values
            .iter()
            .enumerate()
            .map(|(i, v)| v * (1.0 + alternate(i)))
            .collect();
        let mut moved_loads: Vec<f64> = raw
            .loads
            .iter()
            .enumerate()
            .map(|(i, p)| {
                if i == 0 || i == n - 1 {
                    *p
                } else {
                    p * (1.0 - alternate(i))
                }
            })
            .collect();
        if moved_loads.windows(2).any(|pair| pair[1] <= pair[0]) {
            moved_loads = raw.loads.clone();
        }
        table.rounded.push(build(&moved_loads, &moved));
        table
    }

    /// The interpolant of validated, shape-fitted data: `values` are the slopes, or the
    /// approach, at `loads`.
    fn build(path: &str, column: TableColumn, coordinates: Coordinates, loads: &[f64], values: &[f64]) -> Self {
        let (mut slopes, first_approach) = match column {
            TableColumn::Slope => (values.to_vec(), 0.0),
            TableColumn::Approach => (approach_slopes(coordinates, loads, values), values[0]),
        };
        // Non-increasing to the last bit, whatever rounding did on the way.
        for i in 1..slopes.len() {
            slopes[i] = slopes[i].min(slopes[i - 1]);
        }
        // Slopes that differ by rounding only are a constant v' (a linear approach), whose
        // W is exactly 0: rounding noise would otherwise be all there is to integrate.
        let (largest, smallest) = (slopes[0], slopes[slopes.len() - 1]);
        if largest - smallest <= ROUNDING_TOLERANCE * largest {
            let mean = slopes.iter().sum::<f64>() / slopes.len() as f64;
            slopes.iter_mut().for_each(|s| *s = mean);
        }
        ComplianceTable {
            path: path.to_string(),
            column,
            loads: loads.to_vec(),
            interpolant: Piecewise::new(coordinates, loads.to_vec(), &slopes),
            slopes,
            coordinates,
            halves: Vec::new(),
            rounded: Vec::new(),
            first_approach,
            smoothing_residual: 0.0,
        }
    }

    /// The largest relative difference between a half table's v' and the table's own at
    /// the rows that half leaves out.
    fn half_table_discrepancy(&self) -> f64 {
        let mut largest: f64 = 0.0;
        for half in &self.halves {
            for (load, slope) in self.loads.iter().zip(&self.slopes) {
                largest = largest.max((half.interpolant.slope(load) - slope).abs() / slope);
            }
        }
        largest
    }

    /// [first load, last load].
    pub fn range(&self) -> (f64, f64) {
        self.interpolant.range()
    }

    /// How much coarser each half table is than the table where W reads it, loads
    /// [low, high]: Σ H^(p+1) over the half's pieces against Σ h^(p+1) over the table's
    /// (gaps in the interpolant's abscissa, p = [`TABLE_ORDER`]). An error of order p
    /// gathers h^p over each piece of width h, so this is the factor by which the half's
    /// error exceeds the table's where that error is spread evenly: 2^p for even spacing,
    /// down to 1 where merging a piece with its neighbour hardly widens it.
    pub fn half_refinements(&self, low: f64, high: f64) -> Vec<f64> {
        let gathered = |loads: &[f64]| -> f64 {
            loads
                .windows(2)
                .filter(|piece| piece[1] > low && piece[0] < high)
                .map(|piece| {
                    let width = self.coordinates.abscissa(&piece[1]) - self.coordinates.abscissa(&piece[0]);
                    width.powi(TABLE_ORDER + 1)
                })
                .sum()
        };
        let own = gathered(&self.loads);
        self.halves.iter().map(|half| gathered(&half.loads) / own).collect()
    }

    /// Whether the interpolated v' is one constant (every node slope the same, as a
    /// linear approach's are once rounding is removed): then v'' ≡ 0, in the half tables
    /// too, and W is exactly 0.
    pub fn has_constant_slope(&self) -> bool {
        self.slopes.windows(2).all(|pair| pair[0] == pair[1])
    }

    /// Refuses loads [low, high] that leave the table (by more than rounding of the load).
    pub fn check_covers(&self, low: f64, high: f64) -> Result<(), TableError> {
        let (first, last) = self.range();
        let inside = |load: f64| load.is_finite() && self.interpolant.piece(load).is_some();
        if !(inside(low) && inside(high)) {
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
}

/// The node slopes v'(P_i) of (concave, fitted) approach data, differentiated where the
/// data are smoothest: ln v against ln P where both are positive (a power law is then a
/// line), v against ln P for other positive loads, v against P otherwise.
fn approach_slopes(coordinates: Coordinates, loads: &[f64], approach: &[f64]) -> Vec<f64> {
    let secants: Vec<f64> = loads
        .windows(2)
        .zip(approach.windows(2))
        .map(|(p, v)| (v[1] - v[0]) / (p[1] - p[0]))
        .collect();
    let logs = |data: &[f64]| data.iter().map(|x| x.ln()).collect::<Vec<f64>>();
    match coordinates {
        Coordinates::LogLog if approach.iter().all(|&v| v > 0.0) => {
            let to_slope = |i: usize, d: f64| d * approach[i] / loads[i];
            approach_node_slopes(loads, approach, &secants, &logs(loads), &logs(approach), to_slope)
        }
        Coordinates::LogLog => {
            approach_node_slopes(loads, approach, &secants, &logs(loads), approach, |i, d| d / loads[i])
        }
        Coordinates::Linear => approach_node_slopes(loads, approach, &secants, loads, approach, |_, d| d),
    }
}

/// The keys of a `table:` term: its file (also written bare, `table:FILE`) and the
/// smoothing tolerance.
pub const TABLE_KEYS: [&str; 2] = ["file", "smoothing"];

/// The text after `table:`: the file, then optionally `smoothing=TOL` (relative, ≥ 0).
/// `file=PATH` names the file explicitly. Each is given once.
pub fn parse_table_term(text: &str) -> Result<(String, f64), String> {
    let [file_key, smoothing_key] = TABLE_KEYS;
    let mut path: Option<String> = None;
    let mut smoothing: Option<f64> = None;
    let usage = "table takes a file and optionally smoothing=TOL (table:FILE,smoothing=1e-3)";
    for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let (key, value) = match item.split_once('=') {
            Some((key, value)) => (key.trim(), value.trim()),
            None => (file_key, item),
        };
        let twice = |given: bool| {
            if given {
                Err(format!("table gives '{key}' twice ({}); give it once", printable(text)))
            } else {
                Ok(())
            }
        };
        if key == smoothing_key {
            twice(smoothing.is_some())?;
            smoothing = Some(
                value
                    .parse::<f64>()
                    .ok()
                    .filter(|s| s.is_finite() && *s >= 0.0)
                    .ok_or_else(|| format!("table smoothing='{}' is not a number ≥ 0", printable(value)))?,
            );
        } else if key == file_key {
            twice(path.is_some())?;
            path = Some(value.to_string());
        } else {
            return Err(format!(
                "{usage}, not '{}'{}",
                printable(item),
                did_you_mean(key, &TABLE_KEYS)
            ));
        }
    }
    let path = path.ok_or_else(|| "table needs a file: table:FILE".to_string())?;
    Ok((path, smoothing.unwrap_or(0.0)))
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
        let half = |index: usize| self.table.halves.get(index).unwrap_or(&self.table);
        match self.interpolant {
            TableInterpolant::Cubic => &self.table,
            TableInterpolant::HalfTable => half(0),
            TableInterpolant::OtherHalfTable => half(1),
            TableInterpolant::DataRounding => self.table.rounded.first().unwrap_or(&self.table),
        }
    }
}

/// The parts each knot interval is cut in for the range of a table's v'' or v'''.
const SUBDIVISIONS: usize = 8;

impl<R: Real> Compliance<R> for TableCompliance {
    fn approach(&self, load: &R) -> R {
        let data = self.data();
        data.interpolant.integral(load) + &R::from_f64(data.first_approach, load.precision())
    }

    fn slope(&self, load: &R) -> R {
        self.data().interpolant.slope(load)
    }

    fn curvature(&self, load: &R) -> R {
        self.data().interpolant.curvature(load)
    }

    fn slope_derivative(&self, order: usize, load: &R) -> Option<R> {
        // v' and v'' are continuous; v''' jumps at the knots and is no value there.
        match order {
            0 => Some(self.slope(load)),
            1 => Some(self.curvature(load)),
            _ => None,
        }
    }

    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        // v'' is continuous and v''' bounded on each piece, which is what the remainder of
        // the cubic law needs (v'' absolutely continuous); v'''' has Dirac masses at the
        // knots, and no range. Each knot interval is cut in SUBDIVISIONS parts, each
        // evaluated on a ball that covers it.
        let interpolant = &self.data().interpolant;
        let value = |load: &R| (order == 2 || order == 3).then(|| interpolant.higher_derivative(order, load));
        let (from, to) = (low.to_f64_lossy(), high.to_f64_lossy());
        let mut cuts = vec![low.clone()];
        for knot in interpolant.knots_between(from, to).chain(std::iter::once(to)) {
            let start = cuts.last().expect("a first cut").to_f64_lossy();
            for i in 1..SUBDIVISIONS {
                let cut = start + (knot - start) * i as f64 / SUBDIVISIONS as f64;
                cuts.push(R::from_f64(cut, low.precision()));
            }
            cuts.push(if knot == to {
                high.clone()
            } else {
                R::from_f64(knot, low.precision())
            });
        }
        let mut values = cuts.windows(2).map(|ends| value(&ends[0].union(&ends[1])));
        let first = values.next()??;
        let (mut least, mut greatest) = (first.clone(), first);
        for value in values {
            let value = value?;
            (least, greatest) = (least.min_of(&value), greatest.max_of(&value));
        }
        (least.is_finite() && greatest.is_finite()).then_some((least, greatest))
    }

    fn admissible_by_form(&self, low: &R, high: &R) -> bool {
        // By construction: positive node slopes, and a Fritsch–Carlson monotone cubic on each
        // piece, so v' > 0 and v'' ≤ 0 on the whole table (proofs/table-compliance.md); a
        // range outside the table is refused where its coverage is checked.
        let _ = (low, high);
        true
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
            "table '{}' ({} rows of {}, loads {first:e} to {last:e}; monotone cubic {}{})",
            data.path,
            data.loads.len(),
            match data.column {
                TableColumn::Approach => "approach",
                TableColumn::Slope => "slope",
            },
            match data.coordinates {
                Coordinates::LogLog => "ln v' in ln P",
                Coordinates::Linear => "v' in P",
            },
            match self.interpolant {
                TableInterpolant::Cubic => "",
                TableInterpolant::HalfTable => " from the even rows",
                TableInterpolant::OtherHalfTable => " from the odd rows",
                TableInterpolant::DataRounding => " with its values moved by their rounding",
            }
        )
    }
}
