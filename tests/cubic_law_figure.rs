//! The cubic law's error figure (proofs/cubic-law-remainder.md): every true
//! error |W − W₁|/|W| from certified W lies below its proven band, the true error falls
//! like P1/P0, and how far above it the band lies.
#![cfg(all(feature = "cli", feature = "certified"))]

use std::sync::OnceLock;

use microslip::figures::cubic_law::{
    amplitudes, band_ratios, cubic_law_csv, cubic_law_errors, cubic_law_figure, median, ErrorPoint, CSV_HEADER, PANELS,
    PHASES, RATIO_AMPLITUDE,
};
use microslip::figures::evaluate::fitted_log_slope;
use microslip::figures::Progress;

/// The figure's points on its own grid, computed once for the tests of this file.
fn points() -> &'static [ErrorPoint] {
    static POINTS: OnceLock<Vec<ErrorPoint>> = OnceLock::new();
    POINTS.get_or_init(|| {
        cubic_law_errors(&amplitudes(), &Progress::new(0, &|_, _| {})).expect("the cubic law's error computes")
    })
}

/// The rows of the CSV as (panel, φ/π, P1/P0, true, bound, ratio).
fn csv_rows() -> Vec<(String, f64, f64, f64, f64, f64)> {
    let text = cubic_law_csv(points()).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(CSV_HEADER.join(",").as_str()));
    lines
        .map(|line| {
            let cells: Vec<&str> = line.split(',').collect();
            assert_eq!(cells.len(), CSV_HEADER.len(), "{line}");
            let number = |i: usize| cells[i].parse::<f64>().unwrap_or_else(|_| panic!("{line}: cell {i}"));
            (
                cells[0].to_string(),
                number(1),
                number(2),
                number(3),
                number(4),
                number(8),
            )
        })
        .collect()
}

#[test]
fn the_csv_has_a_row_per_point_and_every_true_error_lies_below_its_proven_band() {
    let grid = amplitudes();
    assert_eq!(grid.len(), 31);
    assert_eq!((grid[0], grid[30]), (0.001, 0.5));
    let rows = csv_rows();
    assert_eq!(rows.len(), PANELS.len() * PHASES.len() * grid.len());
    let mut expected = Vec::new();
    for panel in PANELS {
        for phase in PHASES {
            for p1 in &grid {
                expected.push((panel.name.to_string(), phase, *p1));
            }
        }
    }
    for ((panel, phase, p1, truth, bound, ratio), (want_panel, want_phase, want_p1)) in rows.iter().zip(&expected) {
        assert_eq!((panel, *phase, *p1), (want_panel, *want_phase, *want_p1));
        assert!(
            *truth > 0.0 && truth < bound,
            "{panel} φ = {phase}π, P1 = {p1}: {truth} vs {bound}"
        );
        assert!(
            (ratio / (bound / truth) - 1.0).abs() < 0.01,
            "{ratio} vs {}",
            bound / truth
        );
    }
    // The certified W has its 30 digits, W₁ its 20.
    let text = cubic_law_csv(points()).unwrap();
    let first = text.lines().nth(1).unwrap();
    let cells: Vec<&str> = first.split(',').collect();
    assert_eq!(
        cells[5].split('e').next().unwrap().replace(['.', '-'], "").len(),
        30,
        "{first}"
    );
    assert_eq!(
        cells[6].split('e').next().unwrap().replace(['.', '-'], "").len(),
        20,
        "{first}"
    );
}

#[test]
fn the_true_error_falls_like_p1_over_p0_at_small_amplitude() {
    for panel in PANELS {
        for phase in PHASES {
            let smallest: Vec<(f64, f64)> = points()
                .iter()
                .filter(|p| p.panel == panel.name && p.phase_over_pi == phase)
                .take(3)
                .map(|p| (p.p1_over_p0, p.true_relative_error))
                .collect();
            assert_eq!(smallest.len(), 3);
            let slope = fitted_log_slope(&smallest);
            assert!(
                (0.9..=1.1).contains(&slope),
                "{} φ = {phase}π: slope {slope}",
                panel.name
            );
        }
    }
}

#[test]
fn the_proven_band_lies_a_few_times_above_the_true_error_up_to_p1_over_p0_of_a_tenth() {
    let ratios = band_ratios(points());
    let counted = amplitudes().iter().filter(|&&p1| p1 <= RATIO_AMPLITUDE).count();
    assert_eq!(ratios.len(), PANELS.len() * PHASES.len());
    for ratio in &ratios {
        println!(
            "{} φ = {}π: bound/true median {:.2}, max {:.2} over {} points",
            ratio.panel, ratio.phase_over_pi, ratio.median, ratio.max, ratio.points
        );
        assert_eq!(ratio.points, counted, "P1/P0 from 0.001 to 0.1");
        assert!(ratio.median >= 1.0 && ratio.max >= ratio.median);
        // The target, on every curve, near in-phase loading too: the sides of the
        // kernel each meet the range of v''' (proofs/cubic-law-remainder.md).
        assert!(
            ratio.median <= 10.0,
            "{} φ = {}π: median bound/true {}",
            ratio.panel,
            ratio.phase_over_pi,
            ratio.median
        );
    }
    // The target: within 10 times the true error for ordinary cases.
    let all: Vec<f64> = points()
        .iter()
        .filter(|p| p.p1_over_p0 <= RATIO_AMPLITUDE)
        .map(ErrorPoint::band_over_true)
        .collect();
    let overall = median(all);
    println!("overall median bound/true {overall:.2}");
    assert!(overall <= 10.0, "median bound/true {overall}");
}

#[test]
fn the_figure_draws_a_true_and_a_proven_curve_per_phase_on_each_panel() {
    let figure = cubic_law_figure(points());
    assert!(figure.log_log);
    assert_eq!(figure.guide_slope, Some(1.0));
    assert_eq!(figure.panels.len(), 2);
    for panel in &figure.panels {
        assert_eq!(panel.curves.len(), 2 * PHASES.len());
        for pair in panel.curves.chunks(2) {
            let (truth, bound) = (&pair[0], &pair[1]);
            assert_eq!(truth.samples.len(), 31);
            for (t, b) in truth.samples.iter().zip(&bound.samples) {
                assert_eq!(t.0, b.0);
                assert!(t.1 < b.1, "{}: {t:?} vs {b:?}", truth.label);
            }
        }
    }
}

#[test]
fn median_takes_the_middle_of_an_odd_count_and_the_mean_of_the_middle_two_of_an_even_one() {
    assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
    assert_eq!(median(vec![4.0, 1.0, 3.0, 2.0]), 2.5);
    assert!(median(Vec::new()).is_nan());
}

#[test]
fn an_amplitude_whose_half_its_f64_cannot_state_exactly_is_refused() {
    // The shortest decimal of the f64 half of 0.38212353486933043 is 0.19106176743466521,
    // not 0.191061767434665215: the case's ρ would not be the figure's 1/2.
    let refused = cubic_law_errors(&[0.38212353486933043], &Progress::new(0, &|_, _| {})).unwrap_err();
    let message = refused.to_string();
    assert!(message.contains("give P1 with fewer digits"), "{message}");
    assert!(message.contains("P1/P0 = 0.38212353486933043"), "{message}");
    // A few digits are stated exactly.
    assert_eq!(
        cubic_law_errors(&[0.0123], &Progress::new(0, &|_, _| {}))
            .unwrap()
            .len(),
        6
    );
}
