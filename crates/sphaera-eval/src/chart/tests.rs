//! Unit tests of the chart helpers and the styled panels.
use super::*;

#[test]
fn tick_labels_are_short() {
    assert_eq!(tick_label(0.001), "0.001");
    assert_eq!(tick_label(0.1), "0.1");
    assert_eq!(tick_label(1.0), "1");
    assert_eq!(tick_label(1e6), "1000000");
    assert_eq!(tick_label(1e-6), "1e-6");
    assert_eq!(tick_label(99.999_999_999_9e-6), "1e-4");
    assert_eq!(tick_label(2.5), "2.5");
}

#[test]
fn styled_panels_draw_both_axes_and_the_legend() -> Result<()> {
    let path = std::env::temp_dir().join(format!("sphaera-eval-styled-{}.svg", std::process::id()));
    let style = |marker, filled| Style {
        color: palette(1),
        marker,
        filled,
        line: true,
    };
    let mut a = Series::new("a");
    a.points = vec![
        (1.0, 20.0),
        (2.0, 5.0),
        (3.0, 2.0),
        (2.0, 0.0),
        (f64::NAN, 1.0),
    ];
    let mut b = Series::new("b");
    b.points = vec![(0.01, 3.0), (10.0, 1.5), (-1.0, 2.0)];
    let levels = [StyledSeries::new(a, style(Marker::Circle, true))];
    // Labels stay with their points when points are dropped (the third is not drawn).
    let times = [
        StyledSeries::new(b, style(Marker::Triangle, false)).with_labels(vec![
            "first label".to_owned(),
            String::new(),
            "dropped label".to_owned(),
        ]),
    ];
    let notes = [Note {
        at: (2.0, 30.0),
        text: "a note".to_owned(),
        color: palette(0),
    }];
    let spec = |title| ChartSpec {
        title,
        x_label: "x units",
        y_label: "y units",
    };
    let panels = [
        StyledPanel {
            spec: spec("levels"),
            x_axis: XAxis::Integers(0.5..3.5),
            series: &levels,
            notes: &notes,
        },
        StyledPanel {
            spec: spec("times"),
            x_axis: XAxis::Log,
            series: &times,
            notes: &[],
        },
    ];
    let legend = [LegendEntry {
        label: "square entry".to_owned(),
        style: style(Marker::Square, false),
    }];
    styled_panels(&path, &panels, &legend)?;
    let svg = std::fs::read_to_string(&path)?;
    for text in [
        "levels",
        "times",
        "x units",
        "y units",
        "square entry",
        "first label",
        "a note",
    ] {
        assert!(svg.contains(text), "{text}");
    }
    assert!(!svg.contains("dropped label"));
    assert!(!svg.contains("figure title"));
    titled_panels(&path, "figure title", &panels, &legend)?;
    let titled = std::fs::read_to_string(&path)?;
    std::fs::remove_file(&path)?;
    assert!(titled.contains("figure title"));
    Ok(())
}

#[test]
fn csv_fields_are_quoted_as_rfc_4180_says() {
    let rows = vec![
        vec![
            "bunny.obj".to_owned(),
            "outline, nearest camera, 2 cells".to_owned(),
            "0.5".to_owned(),
        ],
        vec![
            "say \"hi\"".to_owned(),
            "two\nlines".to_owned(),
            "cr\r".to_owned(),
        ],
        vec![String::new(), "plain".to_owned(), "a,\"b\"".to_owned()],
    ];
    assert_eq!(
        csv_text(&["mesh", "method", "value"], &rows),
        "mesh,method,value\n\
         bunny.obj,\"outline, nearest camera, 2 cells\",0.5\n\
         \"say \"\"hi\"\"\",\"two\nlines\",\"cr\r\"\n\
         ,plain,\"a,\"\"b\"\"\"\n"
    );
}
