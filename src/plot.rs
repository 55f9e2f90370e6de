//! Figures with plotters: line charts (linear or log axes) and filled contour maps,
//! each written as PNG (for reading) and SVG (for papers), with the bundled DejaVu
//! Sans font so they render the same on a bare machine.

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

static FONT: Once = Once::new();

fn register_font() {
    FONT.call_once(|| {
        plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            include_bytes!("../assets/fonts/DejaVuSans.ttf"),
        )
        .unwrap_or_else(|_| panic!("the bundled font is a valid TrueType font"));
    });
}

pub const PALETTE: [RGBColor; 7] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(0, 0, 0),
    RGBColor(140, 86, 75),
];

/// One line of a chart.
#[derive(Debug, Clone)]
pub struct Line {
    pub name: String,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub color: usize,
    pub dashed: bool,
    /// Draw markers at the points (for sparse data, e.g. one per Δt).
    pub markers: bool,
}

impl Line {
    pub fn new(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>, color: usize) -> Self {
        Line {
            name: name.into(),
            x,
            y,
            color,
            dashed: false,
            markers: false,
        }
    }
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }
    pub fn markers(mut self) -> Self {
        self.markers = true;
        self
    }
}

/// A line chart.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub footer: String,
    pub lines: Vec<Line>,
    /// Vertical marker lines with labels.
    pub vlines: Vec<(f64, String)>,
    pub log_x: bool,
    pub log_y: bool,
    /// Extra room above the data, as a fraction of its range, for the legend.
    pub headroom: f64,
    /// A panel under the chart with each other line minus the first (interpolated
    /// on the other line's points): the difference of a reference from the result.
    /// Linear axes only.
    pub difference: Option<String>,
}

/// A plotters failure while drawing, with its message.
#[derive(Debug, Clone, thiserror::Error)]
#[error("{0}")]
pub struct DrawError(String);

/// A figure that could not be written.
#[derive(Debug, Clone, thiserror::Error)]
#[error("drawing {path}: {source}")]
pub struct PlotError {
    pub path: String,
    #[source]
    pub source: DrawError,
}

pub type Res = Result<(), DrawError>;

/// Any plotters error as a [`DrawError`].
pub fn err<E: std::fmt::Display>(e: E) -> DrawError {
    DrawError(e.to_string())
}

fn range(v: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in v.filter(|x| x.is_finite() && (!log || *x > 0.0)) {
        lo = lo.min(x);
        hi = hi.max(x);
    }
    if !lo.is_finite() {
        return (if log { 1e-16 } else { 0.0 }, 1.0);
    }
    if log {
        (lo / 1.5, hi * 1.5)
    } else {
        let pad = 0.05 * (hi - lo).max(hi.abs().max(1e-300) * 1e-9);
        (lo - pad, hi + pad)
    }
}

/// A figure that draws itself on any plotters backend.
pub trait Figure {
    /// Size in pixels (PNG) and user units (SVG).
    fn size(&self) -> (u32, u32);
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Res
    where
        DB::ErrorType: 'static;
}

/// Writes a figure as `stem.png` and `stem.svg`; returns both paths.
pub fn write_figure(fig: &impl Figure, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    register_font();
    let png = stem.with_extension("png");
    let svg = stem.with_extension("svg");
    let at = |p: &Path| {
        let path = p.display().to_string();
        move |source| PlotError { path, source }
    };
    {
        let root = BitMapBackend::new(&png, fig.size()).into_drawing_area();
        fig.draw(&root)
            .and_then(|_| root.present().map_err(err))
            .map_err(at(&png))?;
    }
    {
        let root = SVGBackend::new(&svg, fig.size()).into_drawing_area();
        fig.draw(&root)
            .and_then(|_| root.present().map_err(err))
            .map_err(at(&svg))?;
    }
    Ok(vec![png, svg])
}

impl Figure for Chart {
    fn size(&self) -> (u32, u32) {
        (1000, if self.difference.is_some() { 900 } else { 640 })
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Res
    where
        DB::ErrorType: 'static,
    {
        draw_line_chart(self, root)
    }
}

/// Writes a line chart as `stem.png` and `stem.svg`; returns both paths.
pub fn line_chart(chart: &Chart, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    write_figure(chart, stem)
}

fn draw_line_chart<DB: DrawingBackend>(c: &Chart, root: &DrawingArea<DB, Shift>) -> Res
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    let (upper, lower) = root.split_vertically(610);
    let lower = match &c.difference {
        Some(label) if !c.log_x && !c.log_y => {
            let (panel, foot) = lower.split_vertically(260);
            draw_difference(c, label, &panel)?;
            foot
        }
        _ => lower,
    };
    lower
        .draw_text(
            &c.footer,
            &("sans-serif", 14).into_font().color(&RGBColor(90, 90, 90)),
            (12, 8),
        )
        .map_err(err)?;
    let xs = range(c.lines.iter().flat_map(|l| l.x.iter().cloned()), c.log_x);
    let mut ys = range(c.lines.iter().flat_map(|l| l.y.iter().cloned()), c.log_y);
    if c.headroom > 0.0 {
        ys.1 = if c.log_y {
            ys.1 * (ys.1 / ys.0).powf(c.headroom)
        } else {
            ys.1 + c.headroom * (ys.1 - ys.0)
        };
    }
    let mut b = ChartBuilder::on(&upper);
    b.caption(&c.title, ("sans-serif", 22))
        .margin(14)
        .x_label_area_size(48)
        .y_label_area_size(90);
    macro_rules! body {
        ($chart:expr) => {{
            let mut ch = $chart;
            ch.configure_mesh()
                .x_desc(c.x_label.as_str())
                .y_desc(c.y_label.as_str())
                .label_style(("sans-serif", 15))
                .axis_desc_style(("sans-serif", 17))
                .x_label_formatter(&|v| fmt_tick(*v))
                .y_label_formatter(&|v| fmt_tick(*v))
                .light_line_style(RGBColor(235, 235, 235))
                .draw()
                .map_err(err)?;
            // Published readings dashed grey; our values solid, in their own colours.
            for (k, (x, label)) in c.vlines.iter().enumerate() {
                let pts = vec![(*x, ys.0), (*x, ys.1)];
                if label.starts_with("paper") || label.starts_with("measured") {
                    let style = ShapeStyle::from(&RGBColor(110, 110, 110)).stroke_width(2);
                    ch.draw_series(DashedLineSeries::new(pts, 6, 6, style))
                        .map_err(err)?
                        .label(label.as_str())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
                } else {
                    let color = [RGBColor(23, 190, 207), RGBColor(188, 189, 34), RGBColor(227, 119, 194)][k % 3];
                    let style = ShapeStyle::from(&color).stroke_width(2);
                    ch.draw_series(std::iter::once(PathElement::new(pts, style)))
                        .map_err(err)?
                        .label(label.as_str())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
                }
            }
            for l in &c.lines {
                let color = PALETTE[l.color % PALETTE.len()];
                let style = ShapeStyle::from(&color).stroke_width(2);
                let pts: Vec<(f64, f64)> = l
                    .x
                    .iter()
                    .zip(&l.y)
                    .map(|(a, b)| (*a, *b))
                    .filter(|(a, b)| a.is_finite() && b.is_finite() && (!c.log_x || *a > 0.0) && (!c.log_y || *b > 0.0))
                    .collect();
                let ann = if l.dashed {
                    ch.draw_series(DashedLineSeries::new(pts.clone(), 8, 5, style))
                        .map_err(err)?
                } else {
                    ch.draw_series(LineSeries::new(pts.clone(), style)).map_err(err)?
                };
                ann.label(l.name.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
                if l.markers {
                    ch.draw_series(pts.iter().map(|p| Circle::new(*p, 4, color.filled())))
                        .map_err(err)?;
                }
            }
            ch.configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(180, 180, 180))
                .label_font(("sans-serif", 15))
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(err)?;
        }};
    }
    match (c.log_x, c.log_y) {
        (false, false) => body!(b.build_cartesian_2d(xs.0..xs.1, ys.0..ys.1).map_err(err)?),
        (true, true) => body!(b
            .build_cartesian_2d((xs.0..xs.1).log_scale(), (ys.0..ys.1).log_scale())
            .map_err(err)?),
        (false, true) => body!(b
            .build_cartesian_2d(xs.0..xs.1, (ys.0..ys.1).log_scale())
            .map_err(err)?),
        (true, false) => body!(b
            .build_cartesian_2d((xs.0..xs.1).log_scale(), ys.0..ys.1)
            .map_err(err)?),
    }
    Ok(())
}

/// The difference panel: every line after the first minus the first, at the other
/// line's points within the first's range.
fn draw_difference<DB: DrawingBackend>(c: &Chart, label: &str, area: &DrawingArea<DB, Shift>) -> Res
where
    DB::ErrorType: 'static,
{
    let Some(base) = c.lines.first() else {
        return Ok(());
    };
    let (lo, hi) = (
        base.x.iter().cloned().fold(f64::INFINITY, f64::min),
        base.x.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
    );
    let diffs: Vec<(&Line, Vec<(f64, f64)>)> = c.lines[1..]
        .iter()
        .map(|l| {
            let pts =
                l.x.iter()
                    .zip(&l.y)
                    .filter(|(x, y)| x.is_finite() && y.is_finite() && **x >= lo && **x <= hi)
                    .map(|(x, y)| (*x, y - crate::numerics::interp(&base.x, &base.y, *x)))
                    .collect();
            (l, pts)
        })
        .collect();
    let xs = range(c.lines.iter().flat_map(|l| l.x.iter().cloned()), false);
    let ys = range(diffs.iter().flat_map(|d| d.1.iter().map(|p| p.1)).chain([0.0]), false);
    let mut ch = ChartBuilder::on(area)
        .margin_left(14)
        .margin_right(14)
        .x_label_area_size(30)
        .y_label_area_size(90)
        .build_cartesian_2d(xs.0..xs.1, ys.0..ys.1)
        .map_err(err)?;
    ch.configure_mesh()
        .y_desc(label)
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        .x_label_formatter(&|v| fmt_tick(*v))
        .y_label_formatter(&|v| fmt_tick(*v))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(err)?;
    ch.draw_series(std::iter::once(PathElement::new(
        vec![(xs.0, 0.0), (xs.1, 0.0)],
        ShapeStyle::from(&PALETTE[base.color % PALETTE.len()]).stroke_width(1),
    )))
    .map_err(err)?;
    for (l, pts) in diffs {
        let style = ShapeStyle::from(&PALETTE[l.color % PALETTE.len()]).stroke_width(2);
        if l.dashed {
            ch.draw_series(DashedLineSeries::new(pts, 8, 5, style)).map_err(err)?;
        } else {
            ch.draw_series(LineSeries::new(pts, style)).map_err(err)?;
        }
    }
    Ok(())
}

/// Tick labels: plain for moderate magnitudes, scientific otherwise.
pub fn fmt_tick(v: f64) -> String {
    let a = v.abs();
    if a < 1e-12 {
        "0".into()
    } else if (1e-2..1e4).contains(&a) {
        let s = format!("{v:.3}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        format!("{v:.1e}")
    }
}

/// A filled map of a nodal field on a structured grid of quadrilaterals: each cell
/// coloured by the mean of its corners, with a colour bar.
pub struct Contour {
    pub title: String,
    pub unit: String,
    /// Cells: corner coordinates (x, y) and value.
    pub cells: Vec<([(f64, f64); 4], f64)>,
    /// Points marked on the map, with their labels (an impact point, gages).
    pub marks: Vec<((f64, f64), String)>,
}

fn colormap(t: f64) -> RGBColor {
    // A perceptually ordered blue–white–red diverging map.
    let t = t.clamp(0.0, 1.0);
    let (a, b, s) = if t < 0.5 {
        ((49.0, 54.0, 149.0), (247.0, 247.0, 247.0), t / 0.5)
    } else {
        ((247.0, 247.0, 247.0), (165.0, 0.0, 38.0), (t - 0.5) / 0.5)
    };
    let m = |x: f64, y: f64| (x + (y - x) * s) as u8;
    RGBColor(m(a.0, b.0), m(a.1, b.1), m(a.2, b.2))
}

/// A row of contour maps (one per panel) with a title and a footer.
struct ContourRow<'a> {
    panels: &'a [Contour],
    title: &'a str,
    footer: &'a str,
}

impl Figure for ContourRow<'_> {
    fn size(&self) -> (u32, u32) {
        (380 * self.panels.len() as u32 + 120, 470)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Res
    where
        DB::ErrorType: 'static,
    {
        draw_contours(self.panels, root, self.title, self.footer)
    }
}

/// Writes a row of contour maps (one per panel) as `stem.png` and `stem.svg`.
pub fn contours(panels: &[Contour], stem: &Path, overall_title: &str, footer: &str) -> Result<Vec<PathBuf>, PlotError> {
    write_figure(
        &ContourRow {
            panels,
            title: overall_title,
            footer,
        },
        stem,
    )
}

fn draw_contours<DB: DrawingBackend>(
    panels: &[Contour],
    root: &DrawingArea<DB, Shift>,
    title: &str,
    footer: &str,
) -> Res
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    let root = root
        .margin(10, 0, 0, 0)
        .titled(title, ("sans-serif", 22))
        .map_err(err)?;
    let (body, foot) = root.split_vertically(400);
    foot.draw_text(
        footer,
        &("sans-serif", 14).into_font().color(&RGBColor(90, 90, 90)),
        (12, 8),
    )
    .map_err(err)?;
    let (maps, bar) = body.split_horizontally(380 * panels.len() as u32);
    for (area, p) in maps.split_evenly((1, panels.len())).iter().zip(panels) {
        // One scale per panel: each is coloured by its own largest |value|.
        let vmax = p.cells.iter().map(|c| c.1.abs()).fold(0.0f64, f64::max).max(1e-300);
        let xs = range(p.cells.iter().flat_map(|c| c.0.iter().map(|q| q.0)), false);
        let ys = range(p.cells.iter().flat_map(|c| c.0.iter().map(|q| q.1)), false);
        let mut ch = ChartBuilder::on(area)
            .caption(
                format!("{}, |max| {} {}", p.title, fmt_tick(vmax), p.unit),
                ("sans-serif", 17),
            )
            .margin(8)
            .x_label_area_size(36)
            .y_label_area_size(44)
            .build_cartesian_2d(xs.0..xs.1, ys.0..ys.1)
            .map_err(err)?;
        ch.configure_mesh()
            .disable_mesh()
            .x_desc(format!("x [{}]", p.unit))
            .y_desc(format!("y [{}]", p.unit))
            .label_style(("sans-serif", 13))
            .x_label_formatter(&|v| fmt_tick(*v))
            .y_label_formatter(&|v| fmt_tick(*v))
            .draw()
            .map_err(err)?;
        ch.draw_series(
            p.cells
                .iter()
                .map(|(q, v)| Polygon::new(q.to_vec(), colormap(0.5 + 0.5 * v / vmax).filled())),
        )
        .map_err(err)?;
        ch.draw_series(p.marks.iter().map(|(pt, label)| {
            EmptyElement::at(*pt)
                + Cross::new((0, 0), 6, BLACK.stroke_width(2))
                + Text::new(label.clone(), (9, -18), ("sans-serif", 14).into_font().color(&BLACK))
        }))
        .map_err(err)?;
    }
    // Colour bar: value / max |value|.
    let (bx, by) = (20, 30);
    for k in 0..300 {
        let t = 1.0 - k as f64 / 299.0;
        bar.draw(&Rectangle::new(
            [(bx, by + k), (bx + 24, by + k + 1)],
            colormap(t).filled(),
        ))
        .map_err(err)?;
    }
    for (t, label) in [
        (0.0, "+|max|".to_string()),
        (0.5, "0".to_string()),
        (1.0, "−|max|".to_string()),
    ] {
        bar.draw_text(
            &label,
            &("sans-serif", 13).into_font().color(&BLACK),
            (bx + 28, by + (t * 299.0) as i32 - 6),
        )
        .map_err(err)?;
    }
    Ok(())
}
