//! The rules of the doubling sequence (16 … 256 points) stored once at high precision,
//! so that a run at a new precision rounds them instead of computing them.
//!
//! A command-line run of verified digits meets every table cold: computing the 256-point
//! table alone costs more than the integrals it serves. The stored nodes and weights are
//! this module's own computation ([`super::compute_node_table`] at [`STORED_BITS`]),
//! written by the ignored test `writes_the_stored_tables` and checked against a fresh
//! computation by `stored_tables_equal_computed_ones`; any precision up to
//! [`SERVED_BITS`] is served from them, each value rounded once.

use std::sync::OnceLock;

use rug::Float;

use super::NodeTable;
use crate::real::{Precision, Real};

/// The precision the tables are stored at.
const STORED_BITS: u32 = 640;

/// The highest working precision served from storage: 64 bits below the stored one, so
/// that rounding the stored value is rounding the exact one.
pub(super) const SERVED_BITS: u32 = STORED_BITS - 64;

/// The rules stored: the sizes the quadrature engine and its verification use.
const STORED_POINTS: [usize; 5] = [16, 32, 64, 128, 256];

/// Lines `points node weight`, hexadecimal, for the nodes ≥ 0 of each rule in increasing order.
const TEXT: &str = include_str!("stored_tables.txt");

/// Nodes ≥ 0 and their weights of one stored rule, at the stored precision.
struct Half {
    nodes: Vec<Float>,
    weights: Vec<Float>,
}

fn stored_half(points: usize) -> Option<&'static Half> {
    static HALVES: [OnceLock<Option<Half>>; STORED_POINTS.len()] = [const { OnceLock::new() }; STORED_POINTS.len()];
    let index = STORED_POINTS.iter().position(|&p| p == points)?;
    HALVES[index]
        .get_or_init(|| {
            let parse = |text: &str| {
                Float::parse_radix(text, 16)
                    .ok()
                    .map(|v| Float::with_val(STORED_BITS, v))
            };
            let mut half = Half {
                nodes: Vec::new(),
                weights: Vec::new(),
            };
            for line in TEXT.lines() {
                let mut fields = line.split_whitespace();
                if fields.next()?.parse::<usize>().ok()? != points {
                    continue;
                }
                half.nodes.push(parse(fields.next()?)?);
                half.weights.push(parse(fields.next()?)?);
            }
            (half.nodes.len() == points.div_ceil(2)).then_some(half)
        })
        .as_ref()
}

/// Whether the `points`-point rule at `precision` is served from storage: stored, and the
/// precision above f64 and at most [`SERVED_BITS`].
pub(super) fn serves(points: usize, precision: Precision) -> bool {
    precision > Precision::DOUBLE && precision.in_bits() <= SERVED_BITS && STORED_POINTS.contains(&points)
}

/// The stored `points`-point rule rounded to `precision`, when it is stored and the
/// precision is above f64 and at most [`SERVED_BITS`].
pub(super) fn stored_table<R: Real>(points: usize, precision: Precision) -> Option<NodeTable<R>> {
    if !serves(points, precision) {
        return None;
    }
    let half = stored_half(points)?;
    let round = |x: &Float| R::from_float(x, precision);
    // Nodes < 0 mirror those > 0 (the middle node of an odd rule, 0, is stored once).
    let mirrored = points / 2;
    let mut nodes: Vec<R> = half.nodes[half.nodes.len() - mirrored..]
        .iter()
        .rev()
        .map(|x| -round(x))
        .collect();
    let mut weights: Vec<R> = half.weights[half.weights.len() - mirrored..]
        .iter()
        .rev()
        .map(round)
        .collect();
    nodes.extend(half.nodes.iter().map(round));
    weights.extend(half.weights.iter().map(round));
    Some(NodeTable { nodes, weights })
}

#[cfg(test)]
mod tests {
    use super::super::compute_node_table;
    use super::*;

    #[test]
    #[ignore = "writes src/quad/gauss_legendre/stored_tables.txt (run by hand when the sizes change)"]
    fn writes_the_stored_tables() {
        let mut text = String::new();
        for points in STORED_POINTS {
            let table = compute_node_table::<Float>(points, Precision::bits(STORED_BITS));
            for (node, weight) in table.nodes.iter().zip(&table.weights).skip(points / 2) {
                text.push_str(&format!(
                    "{points} {} {}\n",
                    node.to_string_radix(16, None),
                    weight.to_string_radix(16, None)
                ));
            }
        }
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/quad/gauss_legendre/stored_tables.txt");
        std::fs::write(path, text).expect("write the stored tables");
    }

    #[test]
    fn stored_tables_equal_computed_ones() {
        for bits in [64, 113, 212, 256, 333, 512, SERVED_BITS] {
            let precision = Precision::bits(bits);
            for points in STORED_POINTS {
                let stored = stored_table::<Float>(points, precision).expect("stored");
                let computed = compute_node_table::<Float>(points, precision);
                assert_eq!(stored.nodes.len(), points);
                // Both within a few units of the last place (the computed one is not rounded once).
                let ulp = Float::with_val(bits, Float::i_exp(1, 8 - bits as i32));
                for (a, b) in stored.nodes.iter().zip(&computed.nodes) {
                    assert!(
                        Float::with_val(bits, a - b).abs() <= ulp,
                        "{points} points, {bits} bits: node {a} against {b}"
                    );
                }
                for (a, b) in stored.weights.iter().zip(&computed.weights) {
                    let relative = Float::with_val(bits, a - b).abs() / b;
                    assert!(relative <= ulp, "{points} points, {bits} bits: weight {a} against {b}");
                }
            }
        }
        assert!(stored_table::<Float>(512, Precision::bits(256)).is_none());
        assert!(stored_table::<Float>(32, Precision::bits(SERVED_BITS + 1)).is_none());
        assert!(stored_table::<f64>(32, Precision::DOUBLE).is_none());
    }
}
