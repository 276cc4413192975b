//! A 2D figure drawn with egui_plot: title, axes with ticks and units, a legend, curves, point
//! labels, and a large point set shown as one image. The app's plot tab draws the same thing.

use super::vector::{self, PlotArc, TaggedArcs};
use egui::Color32;

/// Tag numbers of the exact fills (after those of the curves).
const FILL_TAGS: usize = 3072;
use egui_plot::{Corner, Legend, Line, LineStyle, Plot, PlotImage, PlotPoint, Points, Text};

/// A polyline in plot coordinates.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Curve {
    /// Legend name, or `None` to keep it out of the legend.
    pub name: Option<String>,
    /// Points (plot units).
    pub points: Vec<[f64; 2]>,
    /// Colour.
    pub color: Color32,
    /// Width (points).
    pub width: f32,
    /// Dashed line.
    pub dashed: bool,
    /// The same curve as exact circular arcs, when it is made of them (empty otherwise): a
    /// vector figure writes these as SVG arcs instead of the polyline.
    pub arcs: Vec<PlotArc>,
    /// What the curve is, for a vector figure's `class` attribute (`boundary` for the boundary
    /// of a workspace); empty for none.
    pub class: &'static str,
}

/// A filled polygon in plot coordinates (drawn under the curves).
#[derive(Debug, Clone, PartialEq)]
pub struct Area {
    /// Legend name.
    pub name: String,
    /// Vertices (the polygon closes itself).
    pub points: Vec<[f64; 2]>,
    /// Fill colour (alpha is respected).
    pub fill: Color32,
}

/// A region bounded by circular arcs (plot coordinates, the region on each arc's left), filled.
/// A vector figure writes it as a filled path in place of the raster under the curves; the PNG
/// shows the raster.
#[derive(Debug, Clone, PartialEq)]
pub struct ArcFill {
    /// The boundary arcs, in any order.
    pub arcs: Vec<PlotArc>,
    /// Fill colour.
    pub color: Color32,
    /// What the region is (the class mask of an exact map), written as `data-mask`.
    pub mask: u8,
}

/// Everything a 2D figure shows.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Plot2d {
    /// Title above the plot.
    pub title: String,
    /// One line under the title (data source, resolution, statistics).
    pub subtitle: String,
    /// A small caption under the subtitle naming the figure's source (e.g. "after Fig. 2.31 of
    /// Siciliano et al."); empty for none.
    pub caption: String,
    /// x axis label with unit, e.g. `x [m]`.
    pub x_label: String,
    /// y axis label with unit.
    pub y_label: String,
    /// Visible bounds `[x_min, x_max, y_min, y_max]`.
    pub bounds: [f64; 4],
    /// Keep one unit in x as long as one unit in y.
    pub equal_aspect: bool,
    /// Filled areas.
    pub areas: Vec<Area>,
    /// Exact regions a vector figure fills instead of the raster (painted in order).
    pub fills: Vec<ArcFill>,
    /// Curves.
    pub curves: Vec<Curve>,
    /// Text labels at points (e.g. the letters of Fig. 2.30).
    pub labels: Vec<(String, [f64; 2])>,
    /// Legend swatches: name and colour (for the raster's classes).
    pub legend: Vec<(String, Color32)>,
    /// A colour bar for a continuous raster (drawn under the title).
    pub colorbar: Option<ColorBar>,
}

/// A horizontal colour bar: the colour map from `min` to `max` with ticks and a label.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ColorBar {
    /// What the colours mean, with unit and the map's name, e.g. `deviation [mm] (viridis-like)`.
    pub label: String,
    /// Value at the left end.
    pub min: f64,
    /// Value at the right end.
    pub max: f64,
    /// The map sampled evenly from min to max.
    pub colors: Vec<Color32>,
}

impl ColorBar {
    /// Tick values: 5 evenly spaced "nice" numbers within [min, max].
    pub fn ticks(&self) -> Vec<f64> {
        let span = self.max - self.min;
        if !(span > 0.0 && span.is_finite()) {
            return vec![self.min];
        }
        let raw = span / 4.0;
        let mag = 10f64.powf(raw.log10().floor());
        let step = [1.0, 2.0, 2.5, 5.0, 10.0]
            .iter()
            .map(|m| m * mag)
            .find(|s| span / s <= 5.0)
            .unwrap_or(10.0 * mag);
        let first = (self.min / step).ceil() * step;
        (0..=10)
            .map(|k| first + k as f64 * step)
            .take_while(|v| *v <= self.max + 1e-9 * span)
            .collect()
    }
}

/// Paints `bar` as a strip `width` points wide, ticks and label under it.
fn colorbar(ui: &mut egui::Ui, bar: &ColorBar) {
    let width = (ui.available_width() * 0.5).max(120.0);
    ui.vertical_centered(|ui| {
        let (rect, _) = ui.allocate_exact_size(egui::vec2(width, 12.0), egui::Sense::hover());
        let n = bar.colors.len().max(1);
        for (k, c) in bar.colors.iter().enumerate() {
            let x0 = rect.left() + rect.width() * k as f32 / n as f32;
            let x1 = rect.left() + rect.width() * (k + 1) as f32 / n as f32;
            let r = egui::Rect::from_min_max(
                egui::pos2(x0, rect.top()),
                egui::pos2(x1 + 0.5, rect.bottom()),
            );
            ui.painter().rect_filled(r, 0.0, *c);
        }
        let text = ui.visuals().text_color();
        let span = (bar.max - bar.min).max(f64::MIN_POSITIVE);
        for t in bar.ticks() {
            let x = rect.left() + rect.width() * ((t - bar.min) / span) as f32;
            ui.painter().line_segment(
                [
                    egui::pos2(x, rect.bottom()),
                    egui::pos2(x, rect.bottom() + 4.0),
                ],
                egui::Stroke::new(1.0, text),
            );
            ui.painter().text(
                egui::pos2(x, rect.bottom() + 5.0),
                egui::Align2::CENTER_TOP,
                format!("{}", (t * 1e6).round() / 1e6),
                super::font(ui.ctx(), 11.0),
                text,
            );
        }
        ui.add_space(16.0);
        ui.label(egui::RichText::new(&bar.label).small());
    });
}

/// Where a plot was drawn: its frame (points, in the ui's coordinates) and the data bounds
/// shown in it `[x_min, x_max, y_min, y_max]` (after growing for an equal aspect).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlotFrame {
    /// The frame rectangle (points).
    pub rect: egui::Rect,
    /// The data bounds shown.
    pub bounds: [f64; 4],
}

/// Shows `plot` in `ui`, with `image` (a raster covering exactly `plot.bounds`) under the curves.
pub fn show(ui: &mut egui::Ui, plot: &Plot2d, image: Option<egui::TextureId>) -> PlotFrame {
    show_at(ui, plot, image.map(|id| (id, plot.bounds)))
}

/// Shows `plot` in `ui` with `image` covering the given bounds under the curves; returns the
/// frame.
pub fn show_at(
    ui: &mut egui::Ui,
    plot: &Plot2d,
    image: Option<(egui::TextureId, [f64; 4])>,
) -> PlotFrame {
    ui.vertical_centered(|ui| {
        ui.add_space(4.0);
        ui.heading(&plot.title);
        if !plot.subtitle.is_empty() {
            ui.label(egui::RichText::new(&plot.subtitle).small());
        }
        if !plot.caption.is_empty() {
            ui.label(egui::RichText::new(&plot.caption).small().italics().weak());
        }
    });
    if let Some(bar) = &plot.colorbar {
        colorbar(ui, bar);
    }
    let [x0, x1, y0, y1] = drawable_bounds(plot.bounds);
    let text_color = ui.visuals().text_color();
    let p = Plot::new(("figure", plot.title.as_str()))
        .x_axis_label(plot.x_label.clone())
        .y_axis_label(plot.y_label.clone())
        .legend(
            Legend::default()
                .position(Corner::RightTop)
                .background_alpha(0.85),
        )
        .show_grid(true)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .allow_boxed_zoom(false)
        .show_x(false)
        .show_y(false)
        .default_x_bounds(x0, x1)
        .default_y_bounds(y0, y1)
        .set_margin_fraction(egui::vec2(0.0, 0.0));
    let capturing = vector::capturing(ui.ctx());
    let resp = p.show(ui, |pui| {
        draw_items(pui, plot, image, text_color, capturing)
    });
    let b = resp.transform.bounds();
    let frame = PlotFrame {
        rect: *resp.transform.frame(),
        bounds: [b.min()[0], b.max()[0], b.min()[1], b.max()[1]],
    };
    if capturing {
        register_exact(ui.ctx(), plot, &frame);
    }
    frame
}

/// Registers a capture's exact pieces (the fills' and curves' arcs, in plot units, and the frame
/// they are drawn in) for the vector writer to swap for their tag-coloured stand-ins.
fn register_exact(ctx: &egui::Context, plot: &Plot2d, frame: &PlotFrame) {
    for (k, f) in plot.fills.iter().enumerate() {
        vector::register(
            ctx,
            TaggedArcs {
                tag: vector::tag_color(FILL_TAGS + k),
                arcs: f.arcs.clone(),
                color: f.color,
                width: 0.0,
                dashed: false,
                class: "region",
                frame: frame.rect,
                bounds: frame.bounds,
                fill: Some(f.mask),
            },
        );
    }
    for (k, c) in plot.curves.iter().enumerate() {
        if !c.arcs.is_empty() {
            vector::register(
                ctx,
                TaggedArcs {
                    tag: vector::tag_color(k),
                    arcs: c.arcs.clone(),
                    color: c.color,
                    width: c.width,
                    dashed: c.dashed,
                    class: c.class,
                    frame: frame.rect,
                    bounds: frame.bounds,
                    fill: None,
                },
            );
        }
    }
}

/// Bounds egui_plot can show: finite, each side at least a millimetre-scale width wide (a
/// workspace shrunk to a point or a segment, e.g. every length edited to zero, has zero extent,
/// and egui_plot panics on `min == max`). Degenerate sides are widened about their centre.
pub fn drawable_bounds(b: [f64; 4]) -> [f64; 4] {
    let side = |lo: f64, hi: f64| -> [f64; 2] {
        if !(lo.is_finite() && hi.is_finite()) {
            return [-1.0, 1.0];
        }
        let (lo, hi) = (lo.min(hi), lo.max(hi));
        let min_width = 1e-3 * lo.abs().max(hi.abs()).max(1.0);
        if hi - lo >= min_width {
            return [lo, hi];
        }
        let c = 0.5 * (lo + hi);
        [c - 0.5 * min_width.max(1.0), c + 0.5 * min_width.max(1.0)]
    };
    let [x0, x1] = side(b[0], b[1]);
    let [y0, y1] = side(b[2], b[3]);
    [x0, x1, y0, y1]
}

/// The items of a plot: the equal-aspect bounds, the raster image, areas, legend swatches,
/// curves and labels.
fn draw_items(
    pui: &mut egui_plot::PlotUi<'_>,
    plot: &Plot2d,
    image: Option<(egui::TextureId, [f64; 4])>,
    text_color: Color32,
    capturing: bool,
) {
    let [x0, x1, y0, y1] = drawable_bounds(plot.bounds);
    let equal = plot.equal_aspect;
    if equal {
        // One metre as long in x as in y: grow the shorter side of the bounds to the frame's
        // aspect (egui_plot's data_aspect would crop instead).
        let frame = *pui.transform().frame();
        let aspect = (frame.width() / frame.height().max(1.0)) as f64;
        let (w, h) = (x1 - x0, y1 - y0);
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let (w, h) = if w / h < aspect {
            (h * aspect, h)
        } else {
            (w, w / aspect)
        };
        pui.set_plot_bounds(egui_plot::PlotBounds::from_min_max(
            [cx - 0.5 * w, cy - 0.5 * h],
            [cx + 0.5 * w, cy + 0.5 * h],
        ));
    }
    let exact_fills = capturing && !plot.fills.is_empty();
    for k in 0..plot.fills.len() {
        if exact_fills {
            // A stand-in the vector writer swaps for the filled region, here in the paint order.
            let tag = vector::tag_color(FILL_TAGS + k);
            pui.line(
                Line::new("", vec![[x0, y0], [x0, y0]])
                    .color(tag)
                    .allow_hover(false)
                    .allow_band(false),
            );
        }
    }
    if let Some((id, [x0, x1, y0, y1])) = image.filter(|_| !exact_fills) {
        let c = PlotPoint::new(0.5 * (x0 + x1), 0.5 * (y0 + y1));
        pui.image(PlotImage::new(
            "",
            id,
            c,
            egui::vec2((x1 - x0) as f32, (y1 - y0) as f32),
        ));
    }
    for a in &plot.areas {
        pui.polygon(
            egui_plot::Polygon::new(a.name.clone(), a.points.clone())
                .fill_color(a.fill)
                .stroke(egui::Stroke::new(0.0, a.fill)),
        );
    }
    for (name, color) in &plot.legend {
        // A swatch in the legend: one invisible point of the class colour.
        pui.points(
            Points::new(name.clone(), vec![[x0, y0]])
                .color(*color)
                .radius(0.0),
        );
    }
    add_curves(pui, plot, capturing);
    let size = super::font(pui.ctx(), 15.0).size;
    for (text, at) in &plot.labels {
        pui.text(
            Text::new(
                "",
                PlotPoint::new(at[0], at[1]),
                egui::RichText::new(text).strong().size(size),
            )
            .color(text_color),
        );
    }
}

/// The plot's curves (a curve of exact arcs painted in its tag colour during a vector
/// capture, see [`vector`]).
fn add_curves(pui: &mut egui_plot::PlotUi<'_>, plot: &Plot2d, capturing: bool) {
    for (k, c) in plot.curves.iter().enumerate() {
        let tagged = capturing && !c.arcs.is_empty();
        let mut name = c.name.clone().unwrap_or_default();
        if tagged && !name.is_empty() {
            // The legend keeps the real colour: a one-point line of it carries the name, and the
            // tagged stand-in goes unnamed.
            pui.line(Line::new(std::mem::take(&mut name), vec![c.points[0]]).color(c.color));
        }
        let color = if tagged {
            vector::tag_color(k)
        } else {
            c.color
        };
        let mut line = Line::new(name, c.points.clone())
            .color(color)
            .width(c.width);
        if tagged {
            // One path the writer can swap for the arcs (not egui_plot's bands of samples).
            line = line.allow_band(false);
        }
        if c.dashed && !tagged {
            line = line.style(LineStyle::dashed_loose());
        }
        if c.name.is_none() || tagged {
            line = line.allow_hover(false);
        }
        pui.line(line);
    }
}
