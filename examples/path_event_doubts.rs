//! How far the event decomposition of a varying-P path runs on enclosures:
//! `cargo run --release --example path_event_doubts [PATHS]` builds the steady cycle of
//! PATHS random force-driven paths (default 80; 2–5 harmonics in P and Q, P0 = 1, f from
//! 0.3 to 1.5, λ from 1 to 2, drawn from seed 2026) in f64 intervals and on 128-bit
//! Arb balls, and counts the comparisons it could not decide, by where they were asked:
//! the memory's update, the test of where a front meets the top (`split`), the crossings.
//! proofs/periodic-loading.md ("Why a varying P is not proven yet") quotes its output.

use microslip::ball::Ball;
use microslip::doubts::locate_doubts;
use microslip::interval::Interval;
use microslip::path::input::read_harmonics;
use microslip::path::{Contact, SteadyCycle};
use microslip::real::{Precision, Real};
use microslip::verify::generators::Draw;

/// One random path's file text and its f and λ.
fn random_path(draws: &mut Draw) -> (String, String, String) {
    let harmonics = 2 + draws.below(4);
    let (normal, tangential) = (draws.uniform(0.05, 0.6), draws.uniform(0.05, 0.5));
    let mut text = format!("k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,{:.4},0\n", draws.uniform(-0.1, 0.1));
    for k in 1..=harmonics {
        let size = 1.0 / (k * harmonics) as f64;
        let mut coefficient = |scale: f64| draws.uniform(-1.0, 1.0) * scale * size;
        let row = [
            coefficient(normal),
            coefficient(normal),
            coefficient(tangential),
            coefficient(tangential),
        ];
        text += &format!("{k},{:.4},{:.4},{:.4},{:.4}\n", row[0], row[1], row[2], row[3]);
    }
    let friction = ["0.3", "0.5", "0.8", "1", "1.5"][draws.below(5)];
    let lambda = ["1", "1.2", "1.5", "2"][draws.below(4)];
    (text, friction.to_string(), lambda.to_string())
}

/// Undecided comparisons: (all, in the memory's update, in the top test, in the crossings),
/// or `None` where the path is refused.
fn doubts<R: Real>(text: &str, friction: &str, lambda: &str, precision: Precision) -> Option<[usize; 4]> {
    let path = read_harmonics::<R>(text, precision).ok()?;
    let contact = Contact {
        friction: R::parse_decimal(friction, precision).ok()?,
        compliance_ratio: R::parse_decimal(lambda, precision).ok()?,
    };
    let (cycle, _, sites) = locate_doubts(|| SteadyCycle::new(&path, &contact));
    cycle.ok()?;
    let count = |test: &dyn Fn(&str) -> bool| sites.iter().filter(|site| test(site)).count();
    Some([
        sites.len(),
        count(&|site| site.contains("Memory<R>::advance") || site.contains("at_largest_x")),
        count(&|site| site.contains("split::{{closure}}") && !site.contains("crossings")),
        count(&|site| site.contains("crossings")),
    ])
}

fn main() {
    let paths: usize = std::env::args().nth(1).and_then(|n| n.parse().ok()).unwrap_or(80);
    let mut draws = Draw::new(2026);
    // Per arithmetic: paths built, paths without a doubt, then the counts by place.
    let mut totals = [[0usize; 5]; 2];
    for _ in 0..paths {
        let (text, friction, lambda) = random_path(&mut draws);
        let counted = [
            doubts::<Interval>(&text, &friction, &lambda, Precision::DOUBLE),
            doubts::<Ball>(&text, &friction, &lambda, Precision::bits(128)),
        ];
        for (total, counts) in totals.iter_mut().zip(counted) {
            let Some(counts) = counts else { continue };
            total[0] += 1;
            total[1] += usize::from(counts[0] == 0);
            for place in 1..4 {
                total[place + 1] += counts[place];
            }
        }
    }
    println!("arithmetic          paths  without a doubt  memory update  top test  crossings");
    for (name, total) in ["f64 intervals", "128-bit balls"].iter().zip(totals) {
        println!(
            "{name:<18} {:>6} {:>16} {:>14} {:>9} {:>10}",
            total[0], total[1], total[2], total[3], total[4]
        );
    }
}
