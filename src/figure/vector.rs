//! Vector figures: what a figure's egui pass painted ([`UiCapture`]) written as SVG, with the
//! exact circular arcs of the workspace boundaries as SVG `A` commands, text as text and images
//! (a raster map, a 3D view) embedded as PNG; and that SVG turned into a PDF with its fonts
//! embedded ([`svg_to_pdf`], the `app` feature).
//!
//! Every figure is an egui layout ([`super::figures::Figures`]), so one writer covers them all and the
//! vector file has the PNG's layout by construction. A plot curve that is a union of circular
//! arcs ([`PlotArc`]) is painted during a capture in a tag colour of its own; the writer swaps
//! the tagged polyline for the exact arcs, in the same place in the paint order and clip.

use crate::ui_render::offscreen::UiCapture;
use egui::epaint::{ClippedShape, Shape};
use egui::{Color32, Pos2, Rect, TextureId};
use std::collections::HashMap;
use std::fmt::Write as _;

/// A circular arc in plot (data) coordinates: the points `centre + radius (cos t, sin t)` for
/// `t` from `start` to `start + sweep` (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlotArc {
    /// Centre (plot units).
    pub centre: [f64; 2],
    /// Radius (plot units).
    pub radius: f64,
    /// First angle (rad).
    pub start: f64,
    /// Signed sweep (rad).
    pub sweep: f64,
}

impl From<crate::workspace::exact::Arc> for PlotArc {
    fn from(a: crate::workspace::exact::Arc) -> Self {
        Self {
            centre: a.centre,
            radius: a.radius,
            start: a.start,
            sweep: a.sweep,
        }
    }
}

/// A curve of exact arcs a plot painted in a tag colour during a capture, with the plot's frame
/// (points) and the data bounds shown in it.
#[derive(Debug, Clone)]
pub(crate) struct TaggedArcs {
    /// The colour the stand-in polyline was painted in.
    pub tag: Color32,
    /// The arcs (plot units), in order along the curve.
    pub arcs: Vec<PlotArc>,
    /// The real stroke colour.
    pub color: Color32,
    /// Stroke width (points).
    pub width: f32,
    /// Dashed (egui_plot's loose dashes: 10 points on, 16.18 off).
    pub dashed: bool,
    /// `class` of the SVG path (`boundary` for a workspace boundary).
    pub class: &'static str,
    /// The plot frame (points).
    pub frame: Rect,
    /// `[x_min, x_max, y_min, y_max]` shown in the frame.
    pub bounds: [f64; 4],
    /// A filled region (`color` its fill, the arcs closed into loops) of this class mask,
    /// rather than a stroked curve.
    pub fill: Option<u8>,
}

/// The egui memory slot of the tagged curves of the pass being captured.
fn tags_id() -> egui::Id {
    egui::Id::unique("armlab.vector.tags")
}

/// The egui memory slot of the "capturing" flag.
fn capturing_id() -> egui::Id {
    egui::Id::unique("armlab.vector.capturing")
}

/// Whether the pass is being captured for a vector figure (plots then tag their arc curves).
pub(crate) fn capturing(ctx: &egui::Context) -> bool {
    ctx.data(|d| d.get_temp::<bool>(capturing_id()).unwrap_or(false))
}

/// Turns tagging on or off, and forgets the tags of an earlier figure.
pub(crate) fn set_capturing(ctx: &egui::Context, on: bool) {
    ctx.data_mut(|d| {
        d.insert_temp(capturing_id(), on);
        d.remove_temp::<Vec<TaggedArcs>>(tags_id());
    });
}

/// The tag colour of curve `k` (< 4096): an opaque colour figures do not use (green 254, red
/// 1-16), unique per curve. (An invalid premultiplied colour would not survive egui_plot, which
/// passes colours through linear RGBA.)
pub(crate) fn tag_color(k: usize) -> Color32 {
    Color32::from_rgb(1 + ((k >> 8) & 0x0f) as u8, 0xfe, (k & 0xff) as u8)
}

/// Whether a colour is a tag colour ([`tag_color`]).
fn is_tag(c: Color32) -> bool {
    c.a() == 255 && c.g() == 0xfe && (1..=16).contains(&c.r())
}

/// Records a tagged curve (a later pass with the same tag replaces it).
pub(crate) fn register(ctx: &egui::Context, t: TaggedArcs) {
    ctx.data_mut(|d| {
        let list = d.get_temp_mut_or_default::<Vec<TaggedArcs>>(tags_id());
        list.retain(|o| o.tag != t.tag);
        list.push(t);
    });
}

/// The tagged curves of the last pass.
pub(crate) fn tags(ctx: &egui::Context) -> Vec<TaggedArcs> {
    ctx.data(|d| d.get_temp::<Vec<TaggedArcs>>(tags_id()).unwrap_or_default())
}

/// One figure as vectors: what its egui passes painted (one per panel, a multi-panel figure
/// having several), with their exact arcs.
#[derive(Debug, Clone)]
pub struct VectorPage {
    /// Page size (px).
    pub size: [u32; 2],
    /// The panels, in paint order.
    pub panels: Vec<VectorPanel>,
}

/// One egui pass of a figure placed on its page.
#[derive(Debug, Clone)]
pub struct VectorPanel {
    /// Top-left corner on the page (px).
    pub offset: [u32; 2],
    /// Shapes, clips and images.
    pub capture: UiCapture,
    pub(crate) arcs: Vec<TaggedArcs>,
}

impl VectorPage {
    /// A page of one panel filling it.
    pub(crate) fn single(capture: UiCapture, arcs: Vec<TaggedArcs>) -> Self {
        Self {
            size: capture.size,
            panels: vec![VectorPanel {
                offset: [0, 0],
                capture,
                arcs,
            }],
        }
    }

    /// A page of `size` px made of `pages` placed at their offsets (a figure of panels).
    pub fn compose(size: [u32; 2], pages: Vec<([u32; 2], VectorPage)>) -> Self {
        let panels = pages
            .into_iter()
            .flat_map(|(o, p)| {
                p.panels.into_iter().map(move |mut panel| {
                    panel.offset = [panel.offset[0] + o[0], panel.offset[1] + o[1]];
                    panel
                })
            })
            .collect();
        Self { size, panels }
    }
}

/// Family names written for egui's fonts (those [`font_database`] loads for the PDF).
#[cfg(feature = "app")]
const SANS: &str = "Ubuntu";
/// What the SVG asks for: egui's Ubuntu Light where the reader has it, else a sans-serif.
const SANS_LIST: &str = "Ubuntu, 'Ubuntu Light', sans-serif";
const MONO_LIST: &str = "Hack, monospace";
#[cfg(feature = "app")]
const MONO: &str = "Hack";

/// Writes `page` as a standalone SVG document (pixel units, the PNG's size).
pub fn to_svg(page: &VectorPage) -> String {
    let [w, h] = page.size;
    let mut defs = String::new();
    let mut body = String::new();
    if let Some(first) = page.panels.first() {
        let _ = writeln!(
            body,
            "<rect width=\"{w}\" height=\"{h}\" fill=\"{}\"/>",
            hex(first.capture.background)
        );
    }
    for (k, panel) in page.panels.iter().enumerate() {
        let prefix = if page.panels.len() > 1 {
            format!("p{k}")
        } else {
            String::new()
        };
        let [ox, oy] = panel.offset;
        let moved = ox != 0 || oy != 0;
        if moved {
            let _ = writeln!(body, "<g transform=\"translate({ox} {oy})\">");
        }
        write_panel(panel, &prefix, &mut defs, &mut body);
        if moved {
            body.push_str("</g>\n");
        }
    }
    let mut svg = String::with_capacity(body.len() + defs.len() + 512);
    let _ = writeln!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" \
         width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">"
    );
    svg.push_str(
        "<!-- armlab figure: egui's layout as vectors; workspace boundaries are exact arcs -->\n",
    );
    if !defs.is_empty() {
        svg.push_str("<defs>\n");
        svg.push_str(&defs);
        svg.push_str("</defs>\n");
    }
    svg.push_str(&body);
    svg.push_str("</svg>\n");
    svg
}

/// Writes one panel's shapes to `body` (its clips and images to `defs`, ids prefixed).
fn write_panel(panel: &VectorPanel, prefix: &str, defs: &mut String, body: &mut String) {
    let c = &panel.capture;
    let ppp = c.pixels_per_point;
    let [w, h] = c.size;
    if panel.offset != [0, 0] {
        let _ = writeln!(
            body,
            "<rect width=\"{w}\" height=\"{h}\" fill=\"{}\"/>",
            hex(c.background)
        );
    }
    let mut w_ = SvgWriter {
        out: String::with_capacity(64 * 1024),
        ppp,
        prefix,
        clips: HashMap::new(),
        defs: std::mem::take(defs),
        images: HashMap::new(),
        arcs: &panel.arcs,
        done_tags: Vec::new(),
    };
    let canvas = Rect::from_min_size(Pos2::ZERO, egui::vec2(w as f32 / ppp, h as f32 / ppp));
    for ClippedShape {
        clip_rect, shape, ..
    } in &c.shapes
    {
        w_.out.clear();
        w_.shape(shape, c);
        if w_.out.is_empty() {
            continue;
        }
        if clip_rect.contains_rect(canvas) {
            body.push_str(&w_.out);
        } else {
            let id = w_.clip_id(*clip_rect);
            let _ = writeln!(body, "<g clip-path=\"url(#{id})\">");
            body.push_str(&w_.out);
            body.push_str("</g>\n");
        }
    }
    *defs = w_.defs;
}

/// The state of one SVG document being written.
struct SvgWriter<'a> {
    /// The current shape's elements.
    out: String,
    ppp: f32,
    /// Prefix of element ids (unique per panel).
    prefix: &'a str,
    clips: HashMap<[u32; 4], String>,
    defs: String,
    /// Images already written to `defs` (texture id -> element id).
    images: HashMap<TextureId, String>,
    arcs: &'a [TaggedArcs],
    done_tags: Vec<Color32>,
}

impl SvgWriter<'_> {
    /// Pixels of a length in points, rounded to 1/1000 px.
    fn px(&self, v: f32) -> f32 {
        (v * self.ppp * 1000.0).round() / 1000.0
    }

    /// `x y` of a point in pixels.
    fn pt(&self, p: Pos2) -> String {
        format!("{} {}", self.px(p.x), self.px(p.y))
    }

    /// The id of a clip path for `r` (points), defined once.
    fn clip_id(&mut self, r: Rect) -> String {
        let key = [r.min.x, r.min.y, r.max.x, r.max.y].map(f32::to_bits);
        if let Some(id) = self.clips.get(&key) {
            return id.clone();
        }
        let id = format!("{}clip{}", self.prefix, self.clips.len());
        let _ = writeln!(
            self.defs,
            "<clipPath id=\"{id}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>",
            self.px(r.min.x),
            self.px(r.min.y),
            self.px(r.width()),
            self.px(r.height())
        );
        self.clips.insert(key, id.clone());
        id
    }

    /// Writes one shape (and its children).
    fn shape(&mut self, shape: &Shape, c: &UiCapture) {
        match shape {
            Shape::Noop | Shape::Callback(_) => {}
            Shape::Vec(v) => v.iter().for_each(|s| self.shape(s, c)),
            Shape::Circle(s) => {
                let (cx, cy, r) = (self.px(s.center.x), self.px(s.center.y), self.px(s.radius));
                let paint = paint_attrs(s.fill, s.stroke.color, self.px(s.stroke.width));
                let _ = writeln!(
                    self.out,
                    "<circle cx=\"{cx}\" cy=\"{cy}\" r=\"{r}\"{paint}/>"
                );
            }
            Shape::Ellipse(s) => {
                let paint = paint_attrs(s.fill, s.stroke.color, self.px(s.stroke.width));
                let _ = writeln!(
                    self.out,
                    "<ellipse cx=\"{}\" cy=\"{}\" rx=\"{}\" ry=\"{}\" transform=\"rotate({} {} {})\"{paint}/>",
                    self.px(s.center.x),
                    self.px(s.center.y),
                    self.px(s.radius.x),
                    self.px(s.radius.y),
                    s.angle.to_degrees(),
                    self.px(s.center.x),
                    self.px(s.center.y)
                );
            }
            Shape::LineSegment { points, stroke } => {
                if self.tagged(stroke.color) {
                    return;
                }
                let paint = paint_attrs(Color32::TRANSPARENT, stroke.color, self.px(stroke.width));
                let _ = writeln!(
                    self.out,
                    "<path d=\"M{}L{}\"{paint}/>",
                    self.pt(points[0]),
                    self.pt(points[1])
                );
            }
            Shape::Path(p) => {
                let color = stroke_color(&p.stroke.color);
                if self.tagged(color) {
                    return;
                }
                self.polyline(&p.points, p.closed, p.fill, color, p.stroke.width);
            }
            Shape::Rect(r) => self.rect(r, c),
            Shape::Text(t) => self.text(t),
            Shape::Mesh(m) => self.mesh(m, c),
            Shape::QuadraticBezier(b) => {
                let [p0, p1, p2] = b.points;
                let d = format!("M{}Q{} {}", self.pt(p0), self.pt(p1), self.pt(p2));
                self.curve(d, b.closed, b.fill, &b.stroke);
            }
            Shape::CubicBezier(b) => {
                let [p0, p1, p2, p3] = b.points;
                let (a, c_, e) = (self.pt(p1), self.pt(p2), self.pt(p3));
                let d = format!("M{}C{a} {c_} {e}", self.pt(p0));
                self.curve(d, b.closed, b.fill, &b.stroke);
            }
            Shape::Band(b) => self.band(b),
        }
    }

    /// A Bezier curve's path `d` (without its closing `Z`).
    fn curve(
        &mut self,
        mut d: String,
        closed: bool,
        fill: Color32,
        stroke: &egui::epaint::PathStroke,
    ) {
        if closed {
            d.push('Z');
        }
        let paint = paint_attrs(fill, stroke_color(&stroke.color), self.px(stroke.width));
        let _ = writeln!(self.out, "<path d=\"{d}\"{paint}/>");
    }

    /// A band of samples (egui_plot's dense lines): its outline as a polygon.
    fn band(&mut self, b: &egui::epaint::BandShape) {
        if self.tagged(b.fill) || b.points.is_empty() {
            return;
        }
        let mut pts: Vec<Pos2> = b.points.iter().map(|p| Pos2::new(p.x, p.y.min)).collect();
        pts.extend(b.points.iter().rev().map(|p| Pos2::new(p.x, p.y.max)));
        if b.angle != 0.0 {
            let rot = egui::emath::Rot2::from_angle(b.angle);
            pts.iter_mut()
                .for_each(|p| *p = (rot * p.to_vec2()).to_pos2());
        }
        self.polyline(&pts, true, b.fill, b.stroke.color, b.stroke.width);
    }

    /// Whether `color` is the tag of an exact curve: writes the curve the first time (its
    /// later dashes are skipped).
    fn tagged(&mut self, color: Color32) -> bool {
        if !is_tag(color) {
            return false;
        }
        let Some(t) = self.arcs.iter().find(|t| t.tag == color) else {
            return false;
        };
        if self.done_tags.contains(&color) {
            return true;
        }
        self.done_tags.push(color);
        if let Some(mask) = t.fill {
            let (c, o) = unmultiply(t.color);
            let _ = writeln!(
                self.out,
                "<path class=\"{}\" data-mask=\"{mask}\" d=\"{}\" fill=\"{c}\" fill-opacity=\"{o:.3}\" \
                 fill-rule=\"nonzero\" stroke=\"none\"/>",
                t.class,
                loops_path(t, self.ppp)
            );
            return true;
        }
        let d = arcs_path(t, self.ppp);
        let dash = if t.dashed {
            format!(
                " stroke-dasharray=\"{} {}\"",
                self.px(10.0),
                // egui_plot's `dashed_loose`: 10 px dashes, gaps of 10 px times 0.618.
                self.px(10.0 * 0.618_034)
            ) + " stroke-linecap=\"butt\""
        } else {
            " stroke-linecap=\"round\"".to_owned()
        };
        let paint = paint_attrs(Color32::TRANSPARENT, t.color, self.px(t.width));
        // The plot's frame (px) and the data bounds shown in it, so that a reader can take the
        // path back to plot units.
        let f = t.frame;
        let ppp = f64::from(self.ppp);
        let _ = writeln!(
            self.out,
            "<path class=\"{}\" d=\"{d}\"{paint}{dash} \
             data-frame=\"{} {} {} {}\" data-bounds=\"{} {} {} {}\"/>",
            t.class,
            f64::from(f.min.x) * ppp,
            f64::from(f.min.y) * ppp,
            f64::from(f.max.x) * ppp,
            f64::from(f.max.y) * ppp,
            t.bounds[0],
            t.bounds[1],
            t.bounds[2],
            t.bounds[3]
        );
        true
    }

    /// A polyline or polygon.
    fn polyline(
        &mut self,
        points: &[Pos2],
        closed: bool,
        fill: Color32,
        stroke: Color32,
        width: f32,
    ) {
        if points.len() < 2 {
            return;
        }
        let mut d = String::with_capacity(points.len() * 16);
        for (k, p) in points.iter().enumerate() {
            d.push(if k == 0 { 'M' } else { 'L' });
            d.push_str(&self.pt(*p));
        }
        if closed {
            d.push('Z');
        }
        let paint = paint_attrs(fill, stroke, self.px(width));
        let _ = writeln!(
            self.out,
            "<path d=\"{d}\"{paint} stroke-linejoin=\"round\"/>"
        );
    }

    /// A rectangle, or an image when it is filled with a texture.
    fn rect(&mut self, r: &egui::epaint::RectShape, c: &UiCapture) {
        if let Some(brush) = &r.brush {
            self.image(brush.fill_texture_id, r.rect, brush.uv, c);
            return;
        }
        let radius = self.px(r.corner_radius.nw as f32);
        let paint = paint_attrs(r.fill, r.stroke.color, self.px(r.stroke.width));
        let _ = writeln!(
            self.out,
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" rx=\"{radius}\"{paint}/>",
            self.px(r.rect.min.x),
            self.px(r.rect.min.y),
            self.px(r.rect.width()),
            self.px(r.rect.height())
        );
    }

    /// A mesh: a textured quad is an image; coloured triangles are polygons.
    fn mesh(&mut self, m: &egui::epaint::Mesh, c: &UiCapture) {
        if m.texture_id != TextureId::default() && c.images.contains_key(&m.texture_id) {
            let mut rect = Rect::NOTHING;
            let mut uv = Rect::NOTHING;
            for v in &m.vertices {
                rect.extend_with(v.pos);
                uv.extend_with(v.uv);
            }
            self.image(m.texture_id, rect, uv, c);
            return;
        }
        for tri in m.indices.chunks_exact(3) {
            let v = [tri[0], tri[1], tri[2]].map(|i| m.vertices[i as usize]);
            let color = v[0].color;
            if color.a() == 0 {
                continue;
            }
            let pts: Vec<Pos2> = v.iter().map(|v| v.pos).collect();
            self.polyline(&pts, true, color, Color32::TRANSPARENT, 0.0);
        }
    }

    /// An image of texture `id` over `rect` (points), showing the part `uv` of it.
    fn image(&mut self, id: TextureId, rect: Rect, uv: Rect, c: &UiCapture) {
        let Some(img) = c.images.get(&id) else {
            return;
        };
        let [iw, ih] = [img.size[0] as f32, img.size[1] as f32];
        let elem = match self.images.get(&id) {
            Some(e) => e.clone(),
            None => {
                let e = format!("{}img{}", self.prefix, self.images.len());
                let png = png_base64(img);
                let _ = writeln!(
                    self.defs,
                    "<image id=\"{e}\" width=\"{iw}\" height=\"{ih}\" preserveAspectRatio=\"none\" \
                     style=\"image-rendering:pixelated\" xlink:href=\"data:image/png;base64,{png}\"/>"
                );
                self.images.insert(id, e.clone());
                e
            }
        };
        // Scale the whole image so that its `uv` part covers `rect`.
        let (uw, uh) = (uv.width().max(1e-6) * iw, uv.height().max(1e-6) * ih);
        let sx = self.px(rect.width()) / uw;
        let sy = self.px(rect.height()) / uh;
        let tx = self.px(rect.min.x) - uv.min.x * iw * sx;
        let ty = self.px(rect.min.y) - uv.min.y * ih * sy;
        let clip = self.clip_id(rect);
        let _ = writeln!(
            self.out,
            "<g clip-path=\"url(#{clip})\"><use xlink:href=\"#{elem}\" transform=\"matrix({sx} 0 0 {sy} {tx} {ty})\"/></g>"
        );
    }

    /// Text: one `<text>` per run of glyphs of one format, at the first glyph's baseline.
    fn text(&mut self, t: &egui::epaint::TextShape) {
        let galley = &t.galley;
        let job = &galley.job;
        // The format of each glyph: the sections' byte ranges over the job's text, in the
        // order the glyphs follow (newlines have no glyph).
        let mut formats = job
            .text
            .char_indices()
            .filter(|(_, ch)| *ch != '\n')
            .map(|(i, _)| {
                job.sections
                    .iter()
                    .position(|s| s.byte_range.start.0 <= i && i < s.byte_range.end.0)
                    .unwrap_or(0)
            });
        for placed in &galley.rows {
            // (section, x, baseline y, end x, text)
            let mut runs: Vec<(usize, f32, f32, f32, String)> = Vec::new();
            for g in &placed.row.glyphs {
                let section = formats.next().unwrap_or(0);
                let x = t.pos.x + placed.pos.x + g.pos.x;
                let y = t.pos.y + placed.pos.y + g.pos.y;
                match runs.last_mut() {
                    Some(r) if r.0 == section && (r.2 - y).abs() < 0.01 => {
                        r.3 = x + g.advance_width;
                        r.4.push(g.chr);
                    }
                    _ => runs.push((section, x, y, x + g.advance_width, g.chr.to_string())),
                }
            }
            for run in runs {
                self.text_run(t, run);
            }
        }
    }

    /// One run of glyphs of one format: `(section, x, baseline y, end x, text)` (points).
    fn text_run(&mut self, t: &egui::epaint::TextShape, run: (usize, f32, f32, f32, String)) {
        let (section, x, y, end, text) = run;
        if text.trim().is_empty() {
            return;
        }
        let Some(s) = t.galley.job.sections.get(section) else {
            return;
        };
        let f = &s.format;
        let color = match (t.override_text_color, f.color == Color32::PLACEHOLDER) {
            (Some(o), _) => o,
            (None, true) => t.fallback_color,
            (None, false) => f.color,
        };
        let family = match f.font_id.family {
            egui::FontFamily::Monospace => MONO_LIST,
            _ => SANS_LIST,
        };
        let mut extra = String::new();
        if t.angle != 0.0 {
            let (px, py) = (self.px(t.pos.x), self.px(t.pos.y));
            let _ = write!(
                extra,
                " transform=\"rotate({} {px} {py})\"",
                t.angle.to_degrees()
            );
        }
        if f.italics {
            extra.push_str(" font-style=\"italic\"");
        }
        let (fill, opacity) = unmultiply(color);
        if opacity < 1.0 {
            let _ = write!(extra, " fill-opacity=\"{opacity:.3}\"");
        }
        let _ = writeln!(
            self.out,
            "<text x=\"{}\" y=\"{}\" font-family=\"{family}\" font-size=\"{}\" \
             textLength=\"{}\" lengthAdjust=\"spacingAndGlyphs\" fill=\"{fill}\"{extra} \
             xml:space=\"preserve\">{}</text>",
            self.px(x),
            self.px(y),
            self.px(f.font_id.size),
            self.px(end - x),
            escape(&text)
        );
    }
}

/// The SVG path of a filled region whose boundary arcs come in any order: the arcs chained into
/// closed loops (each arc continued by an unused one starting where it ends, a loop closed when
/// none does), each loop one subpath ending in `Z`. The region is where the arcs' winding
/// numbers sum to 1, and the sum is the same however the arcs are grouped into closed loops, so
/// `fill-rule="nonzero"` fills exactly the region whichever arc continues a junction of several. Loops that do not close (the arcs' ends more than
/// `tol` apart) are reported by `None`.
fn chain_loops(arcs: &[PlotArc], tol: f64) -> Option<Vec<Vec<PlotArc>>> {
    let dist = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    let at = |a: &PlotArc, t: f64| {
        [
            a.centre[0] + a.radius * t.cos(),
            a.centre[1] + a.radius * t.sin(),
        ]
    };
    let first = |a: &PlotArc| at(a, a.start);
    let last = |a: &PlotArc| at(a, a.start + a.sweep);
    // Arcs shorter than the tolerance (where two boundaries cross at a point) only join others.
    let arcs: Vec<PlotArc> = arcs
        .iter()
        .filter(|a| (a.radius * a.sweep).abs() >= tol)
        .copied()
        .collect();
    let mut used = vec![false; arcs.len()];
    let mut loops = Vec::new();
    while let Some(i0) = used.iter().position(|u| !u) {
        used[i0] = true;
        let mut chain = vec![arcs[i0]];
        let origin = first(&arcs[i0]);
        loop {
            let end = chain.last().map_or(origin, last);
            // The nearest unused arc starting at this end.
            let next = (0..arcs.len())
                .filter(|&i| !used[i])
                .map(|i| (i, dist(first(&arcs[i]), end)))
                .filter(|&(_, d)| d < tol)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            match next {
                Some((i, _)) => {
                    used[i] = true;
                    chain.push(arcs[i]);
                }
                None if dist(end, origin) < tol => break,
                None => return None,
            }
        }
        loops.push(chain);
    }
    Some(loops)
}

/// The SVG path of a filled region (see [`chain_loops`]): one `Z`-closed subpath per loop. Arcs
/// that do not close into loops (not seen on the exact planar regions) fall back to one fan
/// `M 0 0 L start A ... end Z` per arc from the page's corner, whose winding numbers also sum to
/// the region's, though some PDF rasterizers show the cancelling sides as hairlines.
fn loops_path(t: &TaggedArcs, ppp: f32) -> String {
    let span = (t.bounds[1] - t.bounds[0])
        .abs()
        .max((t.bounds[3] - t.bounds[2]).abs());
    let mut d = String::new();
    if let Some(loops) = chain_loops(&t.arcs, 1e-7 * span.max(1e-9)) {
        for arcs in loops {
            // Each arc continues the subpath (its own `M` dropped after the first: ends within
            // the tolerance but not within `arcs_path`'s would otherwise start a new subpath,
            // which a filler closes with a chord).
            for (k, a) in arcs.iter().enumerate() {
                let piece = arcs_path(
                    &TaggedArcs {
                        arcs: vec![*a],
                        ..t.clone()
                    },
                    ppp,
                );
                let cut = if k == 0 {
                    0
                } else {
                    piece.find('A').unwrap_or(0)
                };
                d.push_str(&piece[cut..]);
            }
            d.push('Z');
        }
        return d;
    }
    for a in &t.arcs {
        let piece = TaggedArcs {
            arcs: vec![*a],
            ..t.clone()
        };
        let arc = arcs_path(&piece, ppp);
        d.push_str("M0 0L");
        d.push_str(arc.trim_start_matches('M'));
        d.push('Z');
    }
    d
}

/// The SVG path of a tagged curve: each arc as an `A` command (split at half turns), in pixels.
fn arcs_path(t: &TaggedArcs, ppp: f32) -> String {
    let [x0, x1, y0, y1] = t.bounds;
    let f = t.frame;
    let sx = f.width() as f64 * ppp as f64 / (x1 - x0);
    let sy = f.height() as f64 * ppp as f64 / (y1 - y0);
    let left = f.min.x as f64 * ppp as f64;
    let bottom = f.max.y as f64 * ppp as f64;
    let to_px = |p: [f64; 2]| [left + (p[0] - x0) * sx, bottom - (p[1] - y0) * sy];
    let mut d = String::new();
    let mut last: Option<[f64; 2]> = None;
    for a in &t.arcs {
        let at = |th: f64| {
            to_px([
                a.centre[0] + a.radius * th.cos(),
                a.centre[1] + a.radius * th.sin(),
            ])
        };
        let p0 = at(a.start);
        let joined = last.is_some_and(|l| (l[0] - p0[0]).hypot(l[1] - p0[1]) < 1e-6);
        if !joined {
            let _ = write!(d, "M{:.6} {:.6}", p0[0], p0[1]);
        }
        // At most a quarter turn per command: the large-arc flag is always 0, and the centre a
        // reader recovers from the endpoints is well conditioned (near a half turn it is not:
        // the chord is nearly the diameter). The y axis points down in SVG: a counter-clockwise
        // sweep in the plot is clockwise on the page (flag 0).
        let pieces = ((a.sweep.abs() / std::f64::consts::FRAC_PI_2).ceil() as usize).max(1);
        for k in 1..=pieces {
            let p = at(a.start + a.sweep * k as f64 / pieces as f64);
            let sweep_flag = u8::from(a.sweep < 0.0);
            let _ = write!(
                d,
                "A{:.6} {:.6} 0 0 {sweep_flag} {:.6} {:.6}",
                a.radius * sx,
                a.radius * sy,
                p[0],
                p[1]
            );
            last = Some(p);
        }
    }
    d
}

/// The colour of a stroke (a gradient's is not used by figures).
fn stroke_color(c: &egui::epaint::ColorMode) -> Color32 {
    match c {
        egui::epaint::ColorMode::Solid(c) => *c,
        egui::epaint::ColorMode::UV(_) => Color32::GRAY,
    }
}

/// `fill` and `stroke` attributes (`none` for transparent).
fn paint_attrs(fill: Color32, stroke: Color32, width: f32) -> String {
    let mut s = String::new();
    let (f, fo) = unmultiply(fill);
    if fill.a() == 0 {
        s.push_str(" fill=\"none\"");
    } else {
        let _ = write!(s, " fill=\"{f}\"");
        if fo < 1.0 {
            let _ = write!(s, " fill-opacity=\"{fo:.3}\"");
        }
    }
    if stroke.a() > 0 && width > 0.0 {
        let (c, o) = unmultiply(stroke);
        let _ = write!(s, " stroke=\"{c}\" stroke-width=\"{width}\"");
        if o < 1.0 {
            let _ = write!(s, " stroke-opacity=\"{o:.3}\"");
        }
    }
    s
}

/// A premultiplied colour as `#rrggbb` and an opacity.
fn unmultiply(c: Color32) -> (String, f32) {
    let a = c.a();
    if a == 0 {
        return ("#000000".into(), 0.0);
    }
    let [r, g, b, _] = c.to_srgba_unmultiplied();
    (format!("#{r:02x}{g:02x}{b:02x}"), a as f32 / 255.0)
}

/// `#rrggbb` of an opaque colour.
fn hex(c: Color32) -> String {
    unmultiply(c).0
}

/// XML text escaping.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// An image as base64 PNG.
fn png_base64(img: &egui::ColorImage) -> String {
    let [w, h] = img.size;
    let rgba: Vec<u8> = img
        .pixels
        .iter()
        .flat_map(|p| p.to_srgba_unmultiplied())
        .collect();
    let mut bytes = Vec::new();
    if let Some(im) = image::RgbaImage::from_raw(w as u32, h as u32, rgba) {
        let _ = super::encode_png(&im, &mut bytes);
    }
    base64(&bytes)
}

/// Standard base64 with padding.
fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// What can go wrong while writing a PDF.
#[cfg(feature = "app")]
#[derive(Debug, thiserror::Error)]
pub enum PdfError {
    /// The SVG did not parse (a bug of the writer above).
    #[error("the figure's SVG did not parse: {detail}")]
    Svg {
        /// usvg's message.
        detail: String,
    },
    /// svg2pdf failed.
    #[error("converting the figure to PDF failed: {detail}")]
    Convert {
        /// svg2pdf's message.
        detail: String,
    },
}

/// egui's own fonts (the ones the PNG is drawn with), for usvg's text layout and the PDF's
/// embedded subsets.
#[cfg(feature = "app")]
pub fn font_database() -> svg2pdf::usvg::fontdb::Database {
    let mut db = svg2pdf::usvg::fontdb::Database::new();
    for data in [
        epaint_default_fonts::UBUNTU_LIGHT,
        epaint_default_fonts::HACK_REGULAR,
    ] {
        db.load_font_data(data.to_vec());
    }
    db.set_sans_serif_family(SANS);
    db.set_monospace_family(MONO);
    db
}

/// Parses an SVG with egui's fonts (what the tests and the PDF writer read it with).
#[cfg(feature = "app")]
pub fn parse_svg(svg: &str) -> Result<svg2pdf::usvg::Tree, PdfError> {
    let opt = svg2pdf::usvg::Options {
        fontdb: std::sync::Arc::new(font_database()),
        font_family: SANS.into(),
        ..Default::default()
    };
    svg2pdf::usvg::Tree::from_str(svg, &opt).map_err(|e| PdfError::Svg {
        detail: e.to_string(),
    })
}

/// A one-page PDF of an SVG written by [`to_svg`]: vector paths, text as text in egui's fonts
/// (embedded subsets, so it can be selected and searched), images embedded.
#[cfg(feature = "app")]
pub fn svg_to_pdf(svg: &str) -> Result<Vec<u8>, PdfError> {
    let tree = parse_svg(svg)?;
    svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions::default(),
    )
    .map_err(|e| PdfError::Convert {
        detail: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_examples() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }
}
