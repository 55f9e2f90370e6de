//! Figures with plotters: line charts (linear or log axes), filled contour maps and
//! maps of a quantity over two parameters,
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

/// Line colours, indexed by [`Line::color`].
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
    /// Legend entry.
    pub name: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates.
    pub y: Vec<f64>,
    /// Index into [`PALETTE`].
    pub color: usize,
    /// Drawn dashed.
    pub dashed: bool,
    /// Draw markers at the points (for sparse data, e.g. one per Δt).
    pub markers: bool,
    /// A text beside each point (empty: none), e.g. the Δt of a run.
    pub point_labels: Vec<String>,
    /// Points drawn with a ring around their marker, e.g. the paper's setting.
    pub emphasis: Vec<usize>,
    /// The lower edge of a band filled from it up to the line, translucent in the
    /// line's colour (empty: no band), e.g. an energy stacked on another.
    pub band: Vec<f64>,
}

impl Line {
    /// A solid line without markers.
    pub fn new(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>, color: usize) -> Self {
        Line {
            name: name.into(),
            x,
            y,
            color,
            dashed: false,
            markers: false,
            point_labels: Vec::new(),
            emphasis: Vec::new(),
            band: Vec::new(),
        }
    }
    /// Drawn dashed.
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }
    /// With markers at the points.
    pub fn markers(mut self) -> Self {
        self.markers = true;
        self
    }
    /// A text beside each point.
    pub fn point_labels(mut self, labels: Vec<String>) -> Self {
        self.point_labels = labels;
        self
    }
    /// Rings around the points at these indices.
    pub fn emphasis(mut self, points: Vec<usize>) -> Self {
        self.emphasis = points;
        self
    }
    /// A band filled from `lower` (at the same abscissae) up to the line.
    pub fn band(mut self, lower: Vec<f64>) -> Self {
        self.band = lower;
        self
    }
}

/// A line chart.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    /// Title above the chart.
    pub title: String,
    /// X axis label, with its unit.
    pub x_label: String,
    /// Y axis label, with its unit.
    pub y_label: String,
    /// A line of text under the chart (settings, provenance).
    pub footer: String,
    /// The lines; the first is the result the others are compared with.
    pub lines: Vec<Line>,
    /// Vertical marker lines with labels.
    pub vlines: Vec<(f64, String)>,
    /// Horizontal marker lines with labels (a threshold), dashed, across the chart.
    pub hlines: Vec<(f64, String)>,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
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
    /// The figure's file.
    pub path: String,
    /// What plotters reported.
    #[source]
    pub source: DrawError,
}

/// The result of drawing.
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
    /// Draws the figure on `root`.
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
    let mut ys = range(
        c.lines
            .iter()
            .flat_map(|l| l.y.iter().cloned())
            .chain(c.hlines.iter().map(|h| h.0)),
        c.log_y,
    );
    if c.headroom > 0.0 {
        ys.1 = if c.log_y {
            ys.1 * (ys.1 / ys.0).powf(c.headroom)
        } else {
            ys.1 + c.headroom * (ys.1 - ys.0)
        };
    }
    let corner = place_legend(c, xs, &mut ys);
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
                .x_label_formatter(&|v| axis_tick(*v, c.log_x, xs))
                .y_label_formatter(&|v| axis_tick(*v, c.log_y, ys))
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
            for (y, label) in &c.hlines {
                // Black: no line of the palette is.
                let style = ShapeStyle::from(&BLACK).stroke_width(2);
                ch.draw_series(DashedLineSeries::new(vec![(xs.0, *y), (xs.1, *y)], 10, 6, style))
                    .map_err(err)?
                    .label(label.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
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
                if !l.band.is_empty() {
                    let edge: Vec<(f64, f64)> =
                        l.x.iter()
                            .zip(&l.band)
                            .map(|(a, b)| (*a, *b))
                            .filter(|(a, b)| a.is_finite() && b.is_finite())
                            .rev()
                            .collect();
                    let outline: Vec<(f64, f64)> = pts.iter().copied().chain(edge).collect();
                    ch.draw_series(std::iter::once(Polygon::new(outline, color.mix(0.3).filled())))
                        .map_err(err)?;
                }
                let ann = if l.dashed {
                    ch.draw_series(DashedLineSeries::new(pts.clone(), 8, 5, style))
                        .map_err(err)?
                } else {
                    ch.draw_series(LineSeries::new(pts.clone(), style)).map_err(err)?
                };
                if l.band.is_empty() {
                    ann.label(l.name.as_str())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
                } else {
                    ann.label(l.name.as_str())
                        .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 20, y + 6)], color.mix(0.3).filled()));
                }
                if l.markers {
                    ch.draw_series(pts.iter().map(|p| Circle::new(*p, 4, color.filled())))
                        .map_err(err)?;
                }
                let finite = |k: &usize| {
                    let (a, b) = (l.x[*k], l.y[*k]);
                    a.is_finite() && b.is_finite() && (!c.log_x || a > 0.0) && (!c.log_y || b > 0.0)
                };
                ch.draw_series(
                    l.emphasis
                        .iter()
                        .filter(|k| **k < l.x.len() && finite(k))
                        .map(|&k| Circle::new((l.x[k], l.y[k]), 9, color.stroke_width(2))),
                )
                .map_err(err)?;
                ch.draw_series(
                    (0..l.point_labels.len().min(l.x.len()))
                        .filter(|k| finite(k) && !l.point_labels[*k].is_empty())
                        .map(|k| {
                            EmptyElement::at((l.x[k], l.y[k]))
                                + Text::new(
                                    l.point_labels[k].clone(),
                                    (7, 3),
                                    ("sans-serif", 12).into_font().color(&color),
                                )
                        }),
                )
                .map_err(err)?;
            }
            ch.configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(180, 180, 180))
                .label_font(("sans-serif", 15))
                .position(corner.position())
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

/// A corner of the plotting area for the legend.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Corner {
    UpperRight,
    UpperLeft,
    LowerRight,
    LowerLeft,
}

impl Corner {
    fn position(self) -> SeriesLabelPosition {
        match self {
            Corner::UpperRight => SeriesLabelPosition::UpperRight,
            Corner::UpperLeft => SeriesLabelPosition::UpperLeft,
            Corner::LowerRight => SeriesLabelPosition::LowerRight,
            Corner::LowerLeft => SeriesLabelPosition::LowerLeft,
        }
    }
}

/// The legend's box as fractions of the plotting area (about 880 × 500 px; entries of
/// 15 px text, 20 px apart, a 20 px swatch and padding).
fn legend_box(c: &Chart) -> (f64, f64) {
    let names = c
        .lines
        .iter()
        .map(|l| l.name.as_str())
        .chain(c.vlines.iter().map(|v| v.1.as_str()))
        .chain(c.hlines.iter().map(|v| v.1.as_str()));
    let chars = names.clone().map(|n| n.chars().count()).max().unwrap_or(0);
    let entries = names.count();
    (
        (chars as f64 * 8.5 + 60.0) / 880.0,
        (entries as f64 * 21.0 + 30.0) / 500.0,
    )
}

/// Where the legend goes so that it covers no data: the first corner (upper right,
/// upper left, lower right, lower left) whose box holds no point of any line (nor
/// segment, sampled), preferring one that also misses the vertical markers; when every
/// corner holds data, the y range is raised until the top corners are clear.
fn place_legend(c: &Chart, xs: (f64, f64), ys: &mut (f64, f64)) -> Corner {
    let tx = |v: f64, log: bool| if log { v.ln() } else { v };
    let norm = |v: f64, r: (f64, f64), log: bool| (tx(v, log) - tx(r.0, log)) / (tx(r.1, log) - tx(r.0, log));
    let usable = |x: f64, y: f64| x.is_finite() && y.is_finite() && (!c.log_x || x > 0.0) && (!c.log_y || y > 0.0);
    let mut data: Vec<(f64, f64)> = Vec::new();
    for l in &c.lines {
        let pts: Vec<(f64, f64)> =
            l.x.iter()
                .zip(&l.y)
                .filter(|(x, y)| usable(**x, **y))
                .map(|(x, y)| (norm(*x, xs, c.log_x), norm(*y, *ys, c.log_y)))
                .collect();
        data.extend(&pts);
        for w in pts.windows(2) {
            data.extend((1..16).map(|k| {
                let s = k as f64 / 16.0;
                (w[0].0 + s * (w[1].0 - w[0].0), w[0].1 + s * (w[1].1 - w[0].1))
            }));
        }
    }
    for (y, _) in &c.hlines {
        let y = norm(*y, *ys, c.log_y);
        data.extend((0..=32).map(|k| (k as f64 / 32.0, y)));
    }
    let markers: Vec<f64> = c.vlines.iter().map(|v| norm(v.0, xs, c.log_x)).collect();
    let (w, h) = legend_box(c);
    let inside = |corner: Corner, (x, y): (f64, f64)| {
        let in_x = match corner {
            Corner::UpperRight | Corner::LowerRight => x >= 1.0 - w,
            _ => x <= w,
        };
        let in_y = match corner {
            Corner::UpperRight | Corner::UpperLeft => y >= 1.0 - h,
            _ => y <= h,
        };
        in_x && in_y
    };
    let corners = [
        Corner::UpperRight,
        Corner::UpperLeft,
        Corner::LowerRight,
        Corner::LowerLeft,
    ];
    let clear = |k: &Corner| !data.iter().any(|p| inside(*k, *p));
    let misses_markers = |k: &Corner| !markers.iter().any(|x| inside(*k, (*x, 1.0 - h / 2.0)));
    if let Some(k) = corners
        .iter()
        .find(|k| clear(k) && misses_markers(k))
        .or_else(|| corners.iter().find(|k| clear(k)))
    {
        return *k;
    }
    // Raise the top so that the data stay below the legend's box.
    let top = data.iter().map(|p| p.1).fold(0.0, f64::max);
    let scale = top / (1.0 - h - 0.02);
    if c.log_y {
        ys.1 = (ys.0.ln() + scale * (ys.1.ln() - ys.0.ln())).exp();
    } else {
        ys.1 = ys.0 + scale * (ys.1 - ys.0);
    }
    Corner::UpperRight
}

/// Tick labels of an axis: [`fmt_tick`] on linear axes; on log axes only at 1, 2 and
/// 5 times a power of ten (1 only over more than two decades), so labels never
/// collide.
fn axis_tick(v: f64, log: bool, range: (f64, f64)) -> String {
    if !log || v <= 0.0 {
        return fmt_tick(v);
    }
    let mantissa = v / 10f64.powf(v.log10().floor());
    let decades = (range.1 / range.0).log10();
    let nice: &[f64] = if decades > 2.0 { &[1.0] } else { &[1.0, 2.0, 5.0] };
    if nice.iter().any(|m| (mantissa - m).abs() < 1e-6 * m) || (mantissa - 10.0).abs() < 1e-5 {
        fmt_tick(v)
    } else {
        String::new()
    }
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

/// A map of a nodal field on a structured grid of quadrilaterals: each cell coloured by
/// the mean of its corners, with a colour bar, and contour lines of the nodal values.
pub struct Contour {
    /// Title above the map.
    pub title: String,
    /// Unit of the values, for the colour bar.
    pub unit: String,
    /// Cells: corner coordinates (x, y) and value.
    pub cells: Vec<([(f64, f64); 4], f64)>,
    /// The nodal values on a uniform lattice, for the contour lines (none: fill only).
    pub lattice: Option<Lattice>,
    /// Points marked on the map, with their labels (an impact point, gages).
    pub marks: Vec<((f64, f64), String)>,
}

/// A polyline in data coordinates.
pub type Polyline = Vec<(f64, f64)>;

/// Values at the nodes of a uniform lattice: `values[j * x.len() + i]` at `(x[i], y[j])`.
#[derive(Debug, Clone)]
pub struct Lattice {
    /// Lattice abscissae, ascending.
    pub x: Vec<f64>,
    /// Lattice ordinates, ascending.
    pub y: Vec<f64>,
    /// The values, row by row.
    pub values: Vec<f64>,
}

impl Lattice {
    /// The lattice of scattered nodal values `(x, y, value)`, when they fill a uniform
    /// rectangular lattice (every node once, equal spacing); `None` otherwise.
    pub fn from_nodes(nodes: &[(f64, f64, f64)]) -> Option<Lattice> {
        let axis = |pick: fn(&(f64, f64, f64)) -> f64| -> Option<Vec<f64>> {
            let mut v: Vec<f64> = nodes.iter().map(pick).collect();
            v.sort_by(f64::total_cmp);
            let span = (v.last()? - v.first()?).abs().max(f64::MIN_POSITIVE);
            v.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * span);
            let step = (v[v.len() - 1] - v[0]) / (v.len() - 1).max(1) as f64;
            let uniform = v.windows(2).all(|w| ((w[1] - w[0]) - step).abs() <= 1e-6 * step);
            (v.len() > 1 && uniform).then_some(v)
        };
        let (x, y) = (axis(|n| n.0)?, axis(|n| n.1)?);
        if nodes.len() != x.len() * y.len() {
            return None;
        }
        let index = |axis: &[f64], v: f64| ((v - axis[0]) / (axis[1] - axis[0])).round() as usize;
        let mut values = vec![f64::NAN; nodes.len()];
        for n in nodes {
            let (i, j) = (index(&x, n.0), index(&y, n.1));
            let slot = values.get_mut(j * x.len() + i)?;
            if !slot.is_nan() {
                return None;
            }
            *slot = n.2;
        }
        values.iter().all(|v| !v.is_nan()).then_some(Lattice { x, y, values })
    }

    /// Contour lines at each level: polylines in the lattice's coordinates (marching
    /// squares, linear interpolation along the cell edges).
    pub fn isolines(&self, levels: &[f64]) -> Vec<(f64, Vec<Polyline>)> {
        let (nx, ny) = (self.x.len(), self.y.len());
        let (dx, dy) = (self.x[1] - self.x[0], self.y[1] - self.y[0]);
        // contour places value k at pixel centre k + 0.5: shift the origin by half a step.
        let builder = contour::ContourBuilder::new(nx, ny, true)
            .x_origin(self.x[0] - 0.5 * dx)
            .y_origin(self.y[0] - 0.5 * dy)
            .x_step(dx)
            .y_step(dy);
        let Ok(lines) = builder.lines(&self.values, levels) else {
            return Vec::new();
        };
        // A ring that reaches the lattice's edge runs half a step outside it there (the
        // region's border, not an isoline): keep only the runs of points inside.
        let (x0, x1, y0, y1) = (self.x[0], self.x[nx - 1], self.y[0], self.y[ny - 1]);
        let inside = |p: &(f64, f64)| {
            p.0 >= x0 - 1e-9 * dx.abs()
                && p.0 <= x1 + 1e-9 * dx.abs()
                && p.1 >= y0 - 1e-9 * dy.abs()
                && p.1 <= y1 + 1e-9 * dy.abs()
        };
        lines
            .iter()
            .map(|l| {
                let mut paths: Vec<Vec<(f64, f64)>> = Vec::new();
                for ring in &l.geometry().0 {
                    let mut run: Vec<(f64, f64)> = Vec::new();
                    for p in ring.0.iter().map(|p| (p.x, p.y)) {
                        if inside(&p) {
                            run.push(p);
                        } else if run.len() > 1 {
                            paths.push(std::mem::take(&mut run));
                        } else {
                            run.clear();
                        }
                    }
                    if run.len() > 1 {
                        paths.push(run);
                    }
                }
                (l.threshold(), paths)
            })
            .collect()
    }
}

/// Contour levels of a field whose largest magnitude is `vmax`: ±k·vmax/5, k = 1…4.
pub fn contour_levels(vmax: f64) -> Vec<f64> {
    (1..5)
        .flat_map(|k| [-(k as f64), k as f64])
        .map(|k| k * vmax / 5.0)
        .collect()
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
        if let Some(lat) = &p.lattice {
            for (level, paths) in lat.isolines(&contour_levels(vmax)) {
                let style = ShapeStyle::from(&RGBColor(40, 40, 40)).stroke_width(1);
                for path in paths {
                    // Negative levels dashed, positive solid (the usual convention).
                    if level < 0.0 {
                        ch.draw_series(DashedLineSeries::new(path, 4, 3, style)).map_err(err)?;
                    } else {
                        ch.draw_series(LineSeries::new(path, style)).map_err(err)?;
                    }
                }
            }
        }
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

/// A quantity over a grid of two parameters: each grid point a cell reaching halfway
/// to its neighbours, coloured on a sequential scale from the smallest value to the
/// largest, with contour lines where the grid is uniform and rings on marked points.
pub struct HeatMap {
    /// Title above the map.
    pub title: String,
    /// The first parameter's axis label (with its unit) and its values, ascending.
    pub x_label: String,
    /// The first parameter's values, ascending.
    pub x: Vec<f64>,
    /// The second parameter's axis label (with its unit).
    pub y_label: String,
    /// The second parameter's values, ascending.
    pub y: Vec<f64>,
    /// The quantity's name and unit, for the colour bar.
    pub unit: String,
    /// The values, `values[j * x.len() + i]` at `(x[i], y[j])`; NaN: none (grey).
    pub values: Vec<f64>,
    /// Points drawn with a ring.
    pub rings: Vec<(f64, f64)>,
    /// What the footer says.
    pub footer: String,
}

/// Writes a [`HeatMap`] as `stem.png` and `stem.svg`.
pub fn heat_map(map: &HeatMap, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    write_figure(map, stem)
}

impl Figure for HeatMap {
    fn size(&self) -> (u32, u32) {
        (900, 700)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Res
    where
        DB::ErrorType: 'static,
    {
        draw_heat_map(self, root)
    }
}

/// A sequential map from pale yellow (0) through green and blue to dark purple (1).
fn sequential(t: f64) -> RGBColor {
    const STOPS: [(f64, f64, f64); 5] = [
        (253.0, 231.0, 37.0),
        (94.0, 201.0, 98.0),
        (33.0, 145.0, 140.0),
        (59.0, 82.0, 139.0),
        (68.0, 1.0, 84.0),
    ];
    let t = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let k = (t.floor() as usize).min(STOPS.len() - 2);
    let (a, b, s) = (STOPS[k], STOPS[k + 1], t - k as f64);
    let m = |x: f64, y: f64| (x + (y - x) * s).round() as u8;
    RGBColor(m(a.0, b.0), m(a.1, b.1), m(a.2, b.2))
}

/// The edges of the cells around ascending values: halfway between neighbours, the
/// outer ones as far out as the inner.
fn cell_edges(v: &[f64]) -> Vec<f64> {
    if v.len() == 1 {
        let h = (v[0].abs() * 0.05).max(f64::MIN_POSITIVE);
        return vec![v[0] - h, v[0] + h];
    }
    let mut e = vec![v[0] - 0.5 * (v[1] - v[0])];
    e.extend(v.windows(2).map(|w| 0.5 * (w[0] + w[1])));
    let n = v.len();
    e.push(v[n - 1] + 0.5 * (v[n - 1] - v[n - 2]));
    e
}

fn draw_heat_map<DB: DrawingBackend>(m: &HeatMap, root: &DrawingArea<DB, Shift>) -> Res
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    let root = root
        .margin(10, 0, 0, 0)
        .titled(&m.title, ("sans-serif", 22))
        .map_err(err)?;
    let (body, foot) = root.split_vertically(620);
    foot.draw_text(
        &m.footer,
        &("sans-serif", 14).into_font().color(&RGBColor(90, 90, 90)),
        (12, 8),
    )
    .map_err(err)?;
    let (area, bar) = body.split_horizontally(760);
    let finite = || m.values.iter().copied().filter(|v| v.is_finite());
    let lo = finite().fold(f64::INFINITY, f64::min);
    let hi = finite().fold(f64::NEG_INFINITY, f64::max);
    let (lo, hi) = if lo.is_finite() { (lo, hi.max(lo)) } else { (0.0, 1.0) };
    let scale = |v: f64| if hi > lo { (v - lo) / (hi - lo) } else { 0.5 };
    let (xe, ye) = (cell_edges(&m.x), cell_edges(&m.y));
    let mut ch = ChartBuilder::on(&area)
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d(xe[0]..xe[xe.len() - 1], ye[0]..ye[ye.len() - 1])
        .map_err(err)?;
    ch.configure_mesh()
        .disable_mesh()
        .x_desc(&m.x_label)
        .y_desc(&m.y_label)
        .label_style(("sans-serif", 14))
        .x_label_formatter(&|v| fmt_tick(*v))
        .y_label_formatter(&|v| fmt_tick(*v))
        .draw()
        .map_err(err)?;
    let nx = m.x.len();
    ch.draw_series(m.values.iter().enumerate().map(|(k, &v)| {
        let (i, j) = (k % nx, k / nx);
        let colour = if v.is_finite() {
            sequential(scale(v))
        } else {
            RGBColor(200, 200, 200)
        };
        Rectangle::new([(xe[i], ye[j]), (xe[i + 1], ye[j + 1])], colour.filled())
    }))
    .map_err(err)?;
    let nodes: Vec<(f64, f64, f64)> = m
        .values
        .iter()
        .enumerate()
        .map(|(k, &v)| (m.x[k % nx], m.y[k / nx], v))
        .collect();
    if let Some(lat) = Lattice::from_nodes(&nodes).filter(|_| hi > lo && m.values.iter().all(|v| v.is_finite())) {
        let levels: Vec<f64> = (1..5).map(|k| lo + (hi - lo) * k as f64 / 5.0).collect();
        let style = ShapeStyle::from(&RGBColor(255, 255, 255)).stroke_width(1);
        for (_, paths) in lat.isolines(&levels) {
            for path in paths {
                ch.draw_series(LineSeries::new(path, style)).map_err(err)?;
            }
        }
    }
    ch.draw_series(
        m.rings
            .iter()
            .map(|&p| Circle::new(p, 7, ShapeStyle::from(&RGBColor(214, 39, 40)).stroke_width(3))),
    )
    .map_err(err)?;
    // Colour bar: the smallest value at the bottom, the largest at the top.
    let (bx, by, h) = (14, 40, 480);
    for k in 0..h {
        let t = 1.0 - k as f64 / (h - 1) as f64;
        bar.draw(&Rectangle::new(
            [(bx, by + k), (bx + 24, by + k + 1)],
            sequential(t).filled(),
        ))
        .map_err(err)?;
    }
    let font = ("sans-serif", 14).into_font().color(&BLACK);
    bar.draw_text(&m.unit, &font, (bx - 6, by - 26)).map_err(err)?;
    for k in 0..=4 {
        let t = k as f64 / 4.0;
        let y = by + ((1.0 - t) * (h - 1) as f64) as i32 - 7;
        bar.draw_text(&fmt_tick(lo + (hi - lo) * t), &font, (bx + 30, y))
            .map_err(err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(f: impl Fn(f64, f64) -> f64) -> Vec<(f64, f64, f64)> {
        let mut nodes = Vec::new();
        for j in 0..=8 {
            for i in 0..=10 {
                let (x, y) = (-1.0 + 0.2 * i as f64, 0.5 * j as f64);
                nodes.push((x, y, f(x, y)));
            }
        }
        nodes
    }

    /// A linear field w = x: its isoline at level c is the segment x = c, across the
    /// whole lattice and no further (no border ring).
    #[test]
    fn isolines_of_a_linear_field_are_straight() {
        let lat = Lattice::from_nodes(&grid(|x, _| x)).expect("a uniform lattice");
        let lines = lat.isolines(&[0.3, -0.5]);
        assert_eq!(lines.len(), 2);
        for (level, paths) in lines {
            assert!(!paths.is_empty(), "level {level}");
            for p in paths.iter().flatten() {
                assert!((p.0 - level).abs() < 1e-12, "point {p:?} off x = {level}");
                assert!((-1e-12..=4.0 + 1e-12).contains(&p.1), "point {p:?} outside the lattice");
            }
            let ys: Vec<f64> = paths.iter().flatten().map(|p| p.1).collect();
            let span =
                ys.iter().cloned().fold(f64::NEG_INFINITY, f64::max) - ys.iter().cloned().fold(f64::INFINITY, f64::min);
            assert!(span > 3.0, "the isoline crosses the lattice (span {span})");
        }
    }

    /// A circular bump: each isoline is a circle of the radius where the field takes
    /// the level (to the lattice's interpolation error).
    #[test]
    fn isolines_of_a_cone_are_circles() {
        let lat = Lattice::from_nodes(&grid(|x, y| 2.0 - (x * x + (y - 2.0) * (y - 2.0)).sqrt())).unwrap();
        for (level, paths) in lat.isolines(&[1.5, 1.0]) {
            let r = 2.0 - level;
            assert!(!paths.is_empty(), "level {level}");
            for p in paths.iter().flatten() {
                let d = (p.0 * p.0 + (p.1 - 2.0) * (p.1 - 2.0)).sqrt();
                assert!(
                    (d - r).abs() < 0.05,
                    "level {level}: point {p:?} at radius {d}, expected {r}"
                );
            }
        }
    }

    #[test]
    fn lattice_refuses_scattered_or_repeated_nodes() {
        let mut nodes = grid(|x, _| x);
        nodes.pop();
        assert!(Lattice::from_nodes(&nodes).is_none(), "a node missing");
        let mut nodes = grid(|x, _| x);
        nodes[3].0 += 0.05;
        assert!(Lattice::from_nodes(&nodes).is_none(), "a node off the lattice");
    }

    fn chart(lines: Vec<Line>) -> Chart {
        Chart {
            lines,
            ..Default::default()
        }
    }

    /// A rising line fills the upper right and the lower left: the legend goes upper
    /// left, and its box holds no point of the line.
    #[test]
    fn legend_takes_an_empty_corner() {
        let x: Vec<f64> = (0..100).map(|k| k as f64).collect();
        let c = chart(vec![Line::new("rising", x.clone(), x.clone(), 0)]);
        let mut ys = range(x.iter().cloned(), false);
        let xs = ys;
        assert_eq!(place_legend(&c, xs, &mut ys), Corner::UpperLeft);
        assert_eq!(ys, xs, "no room needed");
    }

    /// Data in every corner: the top is raised until no point lies in the legend's box.
    #[test]
    fn legend_over_full_data_raises_the_top() {
        let x: Vec<f64> = (0..200).map(|k| k as f64 / 199.0).collect();
        let y: Vec<f64> = x.iter().map(|v| (40.0 * v).sin()).collect();
        let c = chart(vec![
            Line::new("a", x.clone(), y.clone(), 0),
            Line::new("b", x.clone(), y.iter().map(|v| -v).collect(), 1),
        ]);
        let xs = range(x.iter().cloned(), false);
        let mut ys = range(y.iter().cloned(), false);
        let before = ys;
        assert_eq!(place_legend(&c, xs, &mut ys), Corner::UpperRight);
        assert!(ys.1 > before.1);
        let (_, h) = legend_box(&c);
        let top = y.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        assert!((top - ys.0) / (ys.1 - ys.0) < 1.0 - h, "the data stay below the legend");
    }

    #[test]
    fn log_ticks_label_only_round_values() {
        let r = (1e-5, 1e-1);
        assert_eq!(axis_tick(1e-3, true, r), "1.0e-3");
        assert_eq!(axis_tick(3e-3, true, r), "");
        assert_eq!(axis_tick(5e-3, true, r), "");
        let r = (1e-4, 2e-3);
        assert_eq!(axis_tick(5e-4, true, r), "5.0e-4");
        assert_eq!(axis_tick(7e-4, true, r), "");
        assert_eq!(axis_tick(7e-4, false, r), "7.0e-4");
    }
}
