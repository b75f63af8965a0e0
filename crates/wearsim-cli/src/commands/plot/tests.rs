//! The drawing of the library's figures: every style, band and legend swatch of a hand-made figure,
//! and a figure that is only a note, each written as PNG, SVG and CSV.

use super::*;
use wearsim::study::figures::{Axis, Band, Color, LegendEntry, Panel, Point, Series, Style, Swatch};

fn point(x: f64, y: f64, hollow: bool, no_wear: bool) -> Point {
    Point {
        x,
        y,
        low: y * 0.5,
        high: y * 1.5,
        hollow,
        no_wear,
        breakdown: false,
    }
}

fn every_style() -> Figure {
    let axis = |label: &str, log| Axis {
        label: label.into(),
        log,
        fallback: (1e-4, 1e-2),
    };
    let series = |label: &str, style, points| Series {
        label: label.into(),
        color: Color::Palette(1),
        marker: 2,
        style,
        points,
        reference: false,
    };
    let means = vec![
        point(1e-3, 2e-4, false, false),
        Point {
            breakdown: true,
            ..point(2e-3, 1e-4, true, false)
        },
        point(3e-3, 0.0, false, true),
    ];
    let line = vec![point(1e-3, 1e-4, false, false), point(3e-3, 3e-4, false, false)];
    Figure {
        entry: "fig4",
        name: "every_style".into(),
        title: "every style".into(),
        panels: vec![Panel {
            x: axis("p_N", true),
            y: axis("W", true),
            x_band: Some(Band {
                low: 1e-3,
                high: 1.5e-3,
                color: Color::Light,
            }),
            y_band: Some(Band {
                low: 1e-4,
                high: 2e-4,
                color: Color::Band,
            }),
            diagonal: true,
            series: vec![
                series("means, with a comma", Style::Means, means),
                series("line", Style::Line { dashed: true, width: 1 }, line.clone()),
                series("markers", Style::Markers, line),
            ],
        }],
        legend_title: "the legend's title".into(),
        legend: [
            Swatch::LineMarker,
            Swatch::Line { dashed: true },
            Swatch::Marker,
            Swatch::Hollow,
            Swatch::AtAxis,
            Swatch::Band,
            Swatch::Ring,
        ]
        .into_iter()
        .enumerate()
        .map(|(i, swatch)| LegendEntry {
            label: format!("entry {i}"),
            color: Color::Grey,
            marker: i,
            swatch,
        })
        .collect(),
        note: None,
        report: Vec::new(),
    }
}

#[test]
fn every_style_and_a_note_are_drawn_with_their_numbers() {
    let note = Figure {
        note: Some("nothing to draw here".into()),
        name: "a_note".into(),
        panels: Vec::new(),
        legend: Vec::new(),
        ..every_style()
    };
    let dir = tempfile::tempdir().unwrap();
    draw(&[every_style(), note], dir.path(), dir.path()).unwrap();
    for name in ["every_style", "a_note"] {
        let png = std::fs::metadata(dir.path().join(format!("{name}.png"))).unwrap().len();
        let svg = std::fs::read_to_string(dir.path().join(format!("{name}.svg"))).unwrap();
        assert!(
            png > 500 && svg.len() > 300,
            "{name}: {png} bytes of PNG, {} of SVG",
            svg.len()
        );
    }
    let svg = std::fs::read_to_string(dir.path().join("every_style.svg")).unwrap();
    assert!(svg.contains("the legend&apos;s title") || svg.contains("the legend's title"));
    assert!((0..7).all(|i| svg.contains(&format!("entry {i}"))));
    assert!(std::fs::read_to_string(dir.path().join("a_note.svg"))
        .unwrap()
        .contains("nothing to draw here"));
    let csv = std::fs::read_to_string(dir.path().join("every_style.csv")).unwrap();
    assert_eq!(csv, every_style().to_csv());
    // Seven points and two bands; the label with a comma quoted.
    assert_eq!(csv.lines().count(), 1 + 7 + 2, "{csv}");
    assert!(
        csv.contains("\"means, with a comma\",point,1e-3,2e-4,1e-4,3.0000000000000003e-4,false,false,false"),
        "{csv}"
    );
    // The ringed point, a load in the breakdown regime.
    assert!(
        csv.contains(",point,2e-3,1e-4,5e-5,1.5000000000000001e-4,true,false,true"),
        "{csv}"
    );
}
