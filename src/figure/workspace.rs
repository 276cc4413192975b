//! Workspace figures (Sect. 2.10.1, Figs 2.29-2.30): the plane of a planar arm with the regions
//! reached by each posture and the exact boundary arcs; top and side views as a robot data sheet
//! shows them; a 3D point cloud; the joint-space rectangle of Fig. 2.29.
//!
//! The regions, values and curves come from [`workspace::compute_map`] at the plot frame's own
//! pixel size and bounds (a layout pass measures them), so region edges fall on the exact
//! boundary at any output size; this module only paints the map it is handed.

use super::figures::{Figures, PlotFrame, Scene3d};
use super::palette::{CLASS_COLORS, PLAIN, SEVERAL, c32, class_palette, sequential};
use super::plot2d::{Area, ColorBar, Curve, Plot2d};
use super::{FigureError, Theme};
use crate::camera::Preset;
use crate::kinematics::Robot;
use crate::scene::{ArmStyle, Dot, arm_scene};
use crate::workspace::cell::CollisionLayer;
use crate::workspace::figure_data::PlaneMarks;
use crate::workspace::{
    self, COARSE, Content, ContentRequest, CurveKind, CurveRole, FigureData, FigureRequest,
    MapRequest, MapValues, MapView, SampleOptions, StatsOptions, TrackedPoint, WorkspaceMap,
    WorkspaceStats,
};
use egui::Color32;

/// What the figure shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WsView {
    /// The arm plane of a planar arm.
    Plane,
    /// Base-frame x-y.
    Top,
    /// The (r, z) section swept by joint 1.
    Side,
    /// 3D point cloud with the arm.
    ThreeD,
    /// The joint-space rectangle of Fig. 2.29 (two-link arms).
    JointSpace,
}

/// How points are coloured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorBy {
    /// By posture class (regions reached by one posture only, or by several).
    Posture,
    /// By manipulability (largest in the cell), a sequential colour map with a colour bar.
    Manipulability,
    /// The dexterous workspace: the fraction of orientations reachable at each position (for
    /// a planar arm the angle phi, for a spatial arm the approach direction), with a colour bar.
    Dexterity,
    /// One colour.
    None,
}

/// Options of a workspace figure.
#[derive(Debug, Clone, PartialEq)]
pub struct WsFigureOptions {
    /// View.
    pub view: WsView,
    /// Colouring.
    pub color_by: ColorBy,
    /// Joint-space samples (3D view, sampled maps).
    pub samples: usize,
    /// Sampler seed (same seed, same figure).
    pub seed: u64,
    /// Pixels.
    pub size: [u32; 2],
    /// Light or dark.
    pub theme: Theme,
    /// End-effector.
    pub end_effector: usize,
    /// Tracked point of the side and top views (wrist centre or flange).
    pub point: TrackedPoint,
    /// A small caption naming the figure's source (empty for none).
    pub caption: String,
    /// Every text size times this (1: the print layout; the app's projector mode makes the
    /// figure's text readable at the size the tab shows it).
    pub text_scale: f32,
}

impl WsFigureOptions {
    /// These options with every text size times `text_scale`.
    pub fn scaled(mut self, text_scale: f32) -> Self {
        self.text_scale = text_scale;
        self
    }
}

/// A figure and the statistics it was drawn from.
pub struct WsFigure {
    /// The pixels.
    pub image: image::RgbaImage,
    /// Area/volume, bounds, reach.
    pub stats: WorkspaceStats,
    /// Where the plot's data lie in the image (the 2D views; `None` for the 3D one).
    pub frame: Option<PlotFrame>,
}

/// Name of the sequential colour map of the continuous colourings.
pub const COLOR_MAP: &str = "viridis";

/// A workspace figure planned: its frame laid out and what it needs computed
/// ([`Self::request`]). [`paint`] draws it once that is computed
/// ([`crate::workspace::compute_figure_data`]).
#[derive(Debug, Clone)]
pub struct WsPlan {
    /// What the figure needs computed.
    pub request: FigureRequest,
    title: String,
    opts: WsFigureOptions,
    body: PlanBody,
}

/// The body of a planned figure.
#[derive(Debug, Clone)]
enum PlanBody {
    /// A map view: its plot (undecorated) and where its data will lie.
    Map {
        view: MapView,
        plot: Box<Plot2d>,
        frame: PlotFrame,
    },
    /// The 3D point cloud.
    Cloud,
    /// The joint-space rectangle.
    JointSpace,
}

/// Plans a workspace figure of `robot` (named `title`): lays out a map view's frame at its pixel
/// size so that the map can be computed for exactly its cells and data bounds, and says what is
/// to be computed. Cheap: nothing is sampled or solved here.
pub fn plan(
    figs: &mut Figures,
    robot: &Robot,
    title: &str,
    opts: &WsFigureOptions,
) -> Result<WsPlan, FigureError> {
    let planar = workspace::planar_frame(robot, opts.end_effector).is_some();
    let fallback = StatsOptions::for_figure(planar, opts.samples, opts.seed, opts.end_effector);
    let (content, body) = match opts.view {
        WsView::ThreeD => (
            ContentRequest::Cloud(SampleOptions {
                samples: opts.samples.max(1),
                seed: opts.seed,
                end_effector: opts.end_effector,
                classes: opts.color_by == ColorBy::Posture,
                manipulability: opts.color_by == ColorBy::Manipulability,
                keep_joints: false,
            }),
            PlanBody::Cloud,
        ),
        WsView::JointSpace => (ContentRequest::JointRectangle, PlanBody::JointSpace),
        WsView::Plane | WsView::Top | WsView::Side => {
            let view = match (opts.view, planar) {
                (WsView::Plane, true) => MapView::Plane,
                (WsView::Plane | WsView::Top, _) => MapView::Top,
                _ => MapView::Side,
            };
            let (plot, req) = map_plot(figs, robot, title, opts, view)?;
            let body = PlanBody::Map {
                view,
                plot: Box::new(plot.0),
                frame: plot.1,
            };
            (ContentRequest::Map(req), body)
        }
    };
    Ok(WsPlan {
        request: FigureRequest {
            point: opts.point,
            fallback,
            content,
        },
        title: title.to_string(),
        opts: opts.clone(),
        body,
    })
}

/// Paints a planned figure with the data computed for its request.
pub fn paint(
    figs: &mut Figures,
    robot: &Robot,
    plan: &WsPlan,
    data: &FigureData,
) -> Result<WsFigure, FigureError> {
    let (title, opts, stats) = (plan.title.as_str(), &plan.opts, &data.stats);
    let (image, frame) = match (&plan.body, &data.content) {
        (PlanBody::Cloud, Content::Cloud(cloud)) => {
            (three_d(figs, robot, title, opts, stats, cloud)?, None)
        }
        (PlanBody::JointSpace, Content::JointRectangle(rect)) => {
            let (image, frame) = joint_space(figs, title, opts, rect)?;
            (image, Some(frame))
        }
        (PlanBody::Map { view, plot, frame }, Content::Map(map)) => {
            let mut plot = (**plot).clone();
            let numbers = format!(
                "{}, reach {:.3}-{:.3} m",
                measure_text(stats),
                stats.min_reach,
                stats.max_reach
            );
            decorate(&mut plot, map, &numbers, opts, text_color(opts.theme));
            if *view == MapView::Plane
                && let Some(marks) = &data.plane_marks
            {
                add_plane_marks(&mut plot, marks);
            }
            add_exact_fills(&mut plot, map, opts.color_by);
            if let Some(layer) = &map.collision {
                add_cell(&mut plot, map, layer);
            }
            let raster = paint_map(map, opts.color_by);
            let (image, frame) =
                figs.plot_at(opts.size, opts.theme, &plot, Some((raster, frame.bounds)))?;
            (image, Some(frame))
        }
        (body, content) => {
            return Err(FigureError::WrongData {
                wanted: match body {
                    PlanBody::Map { .. } => "a map",
                    PlanBody::Cloud => "a point cloud",
                    PlanBody::JointSpace => "a joint-space rectangle",
                },
                got: match content {
                    Content::Map(_) => "a map",
                    Content::Cloud(_) => "a point cloud",
                    Content::JointRectangle(_) => "a joint-space rectangle",
                },
            });
        }
    };
    Ok(WsFigure {
        image,
        stats: stats.clone(),
        frame,
    })
}

/// Paints a planned map figure with a map that is still forming (handed over by
/// [`crate::workspace::compute_figure_data_forming`]; the rows from `rows_done` down are the
/// coarse look): the subtitle says how far it is instead of the statistics, which come last.
pub fn paint_forming(
    figs: &mut Figures,
    plan: &WsPlan,
    map: &WorkspaceMap,
    rows_done: usize,
) -> Result<(image::RgbaImage, PlotFrame), FigureError> {
    let PlanBody::Map { plot, frame, .. } = &plan.body else {
        return Err(FigureError::WrongData {
            wanted: "a map figure",
            got: "a map",
        });
    };
    let opts = &plan.opts;
    let mut plot = (**plot).clone();
    let stage = if rows_done == 0 {
        format!("forming: a coarse first look (1 cell in {COARSE} per side)")
    } else if rows_done < map.height {
        format!(
            "forming: {rows_done} of {} rows decided, the rest coarse",
            map.height
        )
    } else {
        "forming: refining the rim".to_string()
    };
    decorate(&mut plot, map, &stage, opts, text_color(opts.theme));
    let raster = paint_map(map, opts.color_by);
    figs.leaving_no_trace(|figs| {
        figs.plot_at(opts.size, opts.theme, &plot, Some((raster, frame.bounds)))
    })
}

fn text_color(theme: Theme) -> Color32 {
    if theme == Theme::Dark {
        Color32::from_gray(230)
    } else {
        Color32::from_gray(25)
    }
}

/// "area 1.6723 m² (exact)" or "volume 2.5167 m³ (Pappus)".
fn measure_text(stats: &WorkspaceStats) -> String {
    let how = if stats.measure_method.starts_with("exact") {
        " (exact)"
    } else if stats.measure_method.starts_with("Pappus") {
        " (Pappus)"
    } else {
        ""
    };
    match (stats.area, stats.volume) {
        (Some(a), _) => format!("area {a:.4} m²{how}"),
        (_, Some(v)) => format!("volume {v:.4} m³{how}"),
        _ => String::new(),
    }
}

fn three_d(
    figs: &mut Figures,
    robot: &Robot,
    title: &str,
    opts: &WsFigureOptions,
    stats: &WorkspaceStats,
    cloud: &workspace::PointCloud,
) -> Result<image::RgbaImage, FigureError> {
    let n = opts.samples.max(1);
    let subtitle = format!(
        "{n} samples (seed {}), {}, reach {:.3}-{:.3} m",
        opts.seed,
        measure_text(stats),
        stats.min_reach,
        stats.max_reach
    );

    let q = robot.ready_or_zero();
    let mut scene = arm_scene(
        robot,
        &q,
        &ArmStyle {
            frames: false,
            ..ArmStyle::default()
        },
    )?;
    let legend = cloud_dots(&mut scene, cloud, opts.color_by);
    let pts: Vec<_> = cloud
        .positions
        .iter()
        .step_by((cloud.positions.len() / 2000).max(1))
        .map(|p| nalgebra::Point3::from(*p))
        .collect();
    let mut camera = crate::camera::Camera::default();
    camera.set_preset(Preset::Iso);
    camera.fit_points(&pts, opts.size[0], opts.size[1], 0.8);
    let legend = if opts.color_by == ColorBy::Posture {
        legend[..legend.len().min(cloud.class_names.len())].to_vec()
    } else {
        Vec::new()
    };
    figs.scene(
        opts.size,
        opts.theme,
        &Scene3d {
            title: format!("Workspace of the {title}"),
            subtitle,
            scene: &scene,
            camera,
            legend,
            caption: opts.caption.clone(),
        },
    )
}

/// Adds the cloud's points (at most 300 000) to the scene as dots coloured by class or
/// manipulability; returns the class legend.
fn cloud_dots(
    scene: &mut crate::scene::Scene,
    cloud: &workspace::PointCloud,
    color_by: ColorBy,
) -> Vec<(String, Color32)> {
    let stride = (cloud.positions.len() / 300_000).max(1);
    let (legend, palette) = class_palette(&cloud.class_names);
    let mmax = cloud
        .manipulability
        .as_ref()
        .map_or(1.0, |m| m.iter().copied().fold(1e-12, f32::max));
    for (i, p) in cloud.positions.iter().enumerate().step_by(stride) {
        let c = match (color_by, &cloud.manipulability) {
            (ColorBy::Manipulability, Some(m)) => sequential(m[i] / mmax),
            (ColorBy::Posture, _)
                if !cloud.class_names.is_empty() && (cloud.classes[i] as usize) < 8 =>
            {
                let [r, g, b, _] = palette(1 << cloud.classes[i]);
                [r, g, b]
            }
            _ => PLAIN,
        };
        let color = [
            c[0] as f32 / 255.0,
            c[1] as f32 / 255.0,
            c[2] as f32 / 255.0,
            1.0,
        ];
        scene.dots.push(Dot {
            p: *p,
            color: srgb_to_linear(color),
            size_px: 2.0,
        });
    }
    legend
}

fn joint_space(
    figs: &mut Figures,
    title: &str,
    opts: &WsFigureOptions,
    rect: &workspace::JointRectangle,
) -> Result<(image::RgbaImage, PlotFrame), FigureError> {
    let text = text_color(opts.theme);
    let deg = |q: [f64; 2]| [q[0].to_degrees(), q[1].to_degrees()];
    let mut plot = Plot2d {
        title: format!("Joint space of the {title} (Fig. 2.29)"),
        subtitle: "admissible configurations within the joint limits; posture bands separated by q2 singular lines".into(),
        x_label: "q1 [deg]".into(),
        y_label: "q2 [deg]".into(),
        caption: opts.caption.clone(),
        ..Plot2d::default()
    };
    let (m1, m2) = (
        (rect.q1[1] - rect.q1[0]).to_degrees() * 0.08,
        (rect.q2[1] - rect.q2[0]).to_degrees() * 0.08,
    );
    plot.bounds = [
        rect.q1[0].to_degrees() - m1,
        rect.q1[1].to_degrees() + m1,
        rect.q2[0].to_degrees() - m2,
        rect.q2[1].to_degrees() + 3.0 * m2,
    ];
    for (band, class) in &rect.bands {
        let c = CLASS_COLORS[*class as usize % CLASS_COLORS.len()];
        let (a, b) = (deg([rect.q1[0], band[0]]), deg([rect.q1[1], band[1]]));
        plot.areas.push(Area {
            name: rect
                .class_names
                .get(*class as usize)
                .cloned()
                .unwrap_or_default(),
            points: vec![[a[0], a[1]], [b[0], a[1]], [b[0], b[1]], [a[0], b[1]]],
            fill: Color32::from_rgba_unmultiplied(c[0], c[1], c[2], 150),
        });
    }
    for s in &rect.segments {
        let (a, b) = (deg(rect.points[s.from].q), deg(rect.points[s.to].q));
        plot.curves.push(Curve {
            name: None,
            points: vec![a, b],
            color: text,
            width: if s.kind == CurveKind::Singular {
                1.5
            } else {
                2.5
            },
            dashed: s.kind == CurveKind::Singular,
            ..Curve::default()
        });
    }
    for p in &rect.points {
        let d = deg(p.q);
        plot.labels
            .push((p.label.clone(), [d[0] + m1 * 0.25, d[1] + m2 * 0.25]));
    }
    figs.plot_at(opts.size, opts.theme, &plot, None)
}

/// Axis labels and the title's suffix of a map view.
fn view_labels(view: MapView) -> (&'static str, &'static str, &'static str) {
    match view {
        MapView::Plane => ("x [m] (base frame)", "y [m] (base frame)", ""),
        MapView::Top => ("x [m] (base frame)", "y [m] (base frame)", ", top view"),
        MapView::Side => (
            "r [m] (distance from the base z axis)",
            "z [m] (base frame)",
            ", side view",
        ),
    }
}

/// The undecorated plot of a map view, where its data will lie, and the map to compute for
/// exactly that frame.
fn map_plot(
    figs: &mut Figures,
    robot: &Robot,
    title: &str,
    opts: &WsFigureOptions,
    view: MapView,
) -> Result<((Plot2d, PlotFrame), MapRequest), FigureError> {
    let map_frame = workspace::map_frame(robot, view, opts.point, opts.end_effector)?;
    let extent = map_frame.extent;
    let values = match opts.color_by {
        ColorBy::Dexterity => MapValues::Dexterity,
        ColorBy::Manipulability => MapValues::Manipulability,
        _ => MapValues::Classes,
    };
    let (xl, yl, which) = view_labels(view);
    // The title names the point the map follows, as the compute layer reports it.
    let point = match map_frame.wrist_point {
        Some(TrackedPoint::WristCentre) => " (wrist centre)",
        Some(TrackedPoint::Flange) => " (flange)",
        None => "",
    };
    let plot = Plot2d {
        title: format!("Workspace of the {title}{point}{which}"),
        x_label: xl.into(),
        y_label: yl.into(),
        bounds: workspace::map::padded(&extent, 0.06),
        equal_aspect: true,
        colorbar: (values != MapValues::Classes).then(ColorBar::default),
        caption: opts.caption.clone(),
        ..Plot2d::default()
    };
    let frame = figs.plot_frame(opts.size, opts.theme, &plot)?;
    let req = MapRequest {
        view,
        point: opts.point,
        values,
        cells: frame.px,
        bounds: Some(frame.bounds),
        samples: opts.samples,
        seed: opts.seed,
        end_effector: opts.end_effector,
    };
    Ok(((plot, frame), req))
}

/// Subtitle (the method, then `numbers`: the measure and reach, or how far a forming map is),
/// legend or colour bar, and the map's curves.
fn decorate(
    plot: &mut Plot2d,
    map: &WorkspaceMap,
    numbers: &str,
    opts: &WsFigureOptions,
    text: Color32,
) {
    let how = if map.exact {
        "exact regions"
    } else if map.method.starts_with("sampled") {
        "sampled regions"
    } else {
        "regions from a 64-direction approach scan"
    };
    plot.subtitle = format!("{how}, {numbers}");
    match &map.values {
        Some(v) => {
            let unit = if v.unit.is_empty() {
                String::new()
            } else {
                format!(" [{}]", v.unit)
            };
            plot.colorbar = Some(ColorBar {
                label: format!("{}{unit} (colour map: {COLOR_MAP})", v.name),
                min: v.range[0],
                max: v.range[1],
                colors: (0..64).map(|k| c32(sequential(k as f32 / 63.0))).collect(),
            });
        }
        None if opts.color_by == ColorBy::Posture && map.class_names.len() > 1 => {
            plot.legend = legend(map);
        }
        None => {}
    }
    for c in &map.curves {
        let (color, width, dashed) = match c.role {
            CurveRole::Boundary => (text, 1.6, false),
            CurveRole::PostureBoundary => (text.gamma_multiply(0.55), 1.0, true),
            CurveRole::Candidate => (text.gamma_multiply(0.3), 0.8, true),
        };
        plot.curves.push(Curve {
            name: None,
            points: c.points.clone(),
            color,
            width,
            dashed,
            arcs: c.arc.map(|a| vec![a.into()]).unwrap_or_default(),
            class: match c.role {
                CurveRole::Boundary => "boundary",
                CurveRole::PostureBoundary => "posture-boundary",
                CurveRole::Candidate => "candidate",
            },
        });
    }
}

/// Legend entries of the class combinations the map shows.
fn legend(map: &WorkspaceMap) -> Vec<(String, Color32)> {
    let (entries, _) = class_palette(&map.class_names);
    let n = map.class_names.len().min(CLASS_COLORS.len());
    let shown = |m: u8| map.masks.contains(&m);
    let several = map.masks.iter().any(|m| m.count_ones() > 1);
    entries
        .into_iter()
        .enumerate()
        .filter(|(k, _)| if *k < n { shown(1 << k) } else { several })
        .map(|(_, e)| e)
        .collect()
}

/// Fig. 2.30's singular lines (dashed) and letters on the plane of a two-link arm.
fn add_plane_marks(plot: &mut Plot2d, marks: &PlaneMarks) {
    for points in &marks.singular {
        plot.curves.push(Curve {
            name: None,
            points: points.clone(),
            color: Color32::from_gray(110),
            width: 1.2,
            dashed: true,
            ..Curve::default()
        });
    }
    plot.labels.extend(marks.labels.iter().cloned());
}

/// Fill of an obstacle in a map view.
const OBSTACLE_FILL: Color32 = Color32::from_rgba_premultiplied(54, 54, 60, 120);
/// Outline of an obstacle in a map view.
const OBSTACLE_LINE: Color32 = Color32::from_rgb(60, 60, 68);
/// The hatching of cells reached only through a collision.
const BLOCKED: [u8; 3] = [200, 50, 50];

/// A map in a cell: the obstacles in the view (filled, outlined, named), the legend entry of
/// the cells reached only through a collision, and the caption saying how the collisions were
/// decided.
fn add_cell(plot: &mut Plot2d, map: &WorkspaceMap, layer: &CollisionLayer) {
    let mut whole = Vec::new();
    for o in &layer.obstacles {
        if o.whole_view {
            whole.push(o.name.as_str());
        }
        for (k, piece) in o.pieces.iter().enumerate() {
            plot.areas.push(Area {
                // One legend entry per obstacle.
                name: if k == 0 {
                    format!("{} (obstacle, {})", o.name, o.kind.words())
                } else {
                    String::new()
                },
                points: piece.clone(),
                fill: OBSTACLE_FILL,
            });
        }
        if o.ring.len() < 3 || o.pieces.is_empty() {
            continue;
        }
        let mut ring = o.ring.clone();
        ring.push(o.ring[0]);
        plot.curves.push(Curve {
            name: None,
            points: ring,
            color: OBSTACLE_LINE,
            width: 1.5,
            class: "obstacle",
            ..Curve::default()
        });
        plot.labels.push((o.name.clone(), o.label_at));
    }
    let shown = map
        .masks
        .iter()
        .zip(&layer.blocked)
        .any(|(m, b)| *m == 0 && *b != 0);
    if shown {
        plot.legend
            .push(("reached only through a collision".into(), c32(BLOCKED)));
    }
    let mut caption = vec![layer.method.clone()];
    if !whole.is_empty() {
        caption.push(format!("{} under the whole view", whole.join(", ")));
    }
    caption.push("measure, reach and boundary lines without the obstacles".into());
    if !plot.caption.is_empty() {
        caption.push(plot.caption.clone());
    }
    plot.caption = caption.join("; ");
}

/// The colour of a class mask.
fn class_color(mask: u8, classes: usize, color_by: ColorBy) -> [u8; 3] {
    if color_by != ColorBy::Posture || classes < 2 {
        return PLAIN;
    }
    match mask.count_ones() {
        1 => CLASS_COLORS[(mask.trailing_zeros() as usize).min(CLASS_COLORS.len() - 1)],
        _ => SEVERAL,
    }
}

/// The map's exact regions (planar arms), in the raster's class colours, for a vector figure
/// to fill instead of the raster; none when the map shows values (a colour map stays an image).
fn add_exact_fills(plot: &mut Plot2d, map: &WorkspaceMap, color_by: ColorBy) {
    if map.values.is_some() {
        return;
    }
    let classes = map.class_names.len();
    plot.fills = map
        .fills
        .iter()
        .map(|f| {
            let c = class_color(f.mask, classes, color_by);
            super::plot2d::ArcFill {
                arcs: f.arcs.iter().map(|a| (*a).into()).collect(),
                color: Color32::from_rgba_unmultiplied(c[0], c[1], c[2], 235),
                mask: f.mask,
            }
        })
        .collect();
}

/// The map's pixels: class colours (or the values' colour map), edge cells blended by their
/// sub-samples, transparent where nothing is reached.
fn paint_map(map: &WorkspaceMap, color_by: ColorBy) -> egui::ColorImage {
    let classes = map.class_names.len();
    let (w, h) = (map.width, map.height);
    let value_at = |k: usize| -> Option<[u8; 3]> {
        let v = map.values.as_ref()?;
        let (i, j) = (k % w, k / w);
        let vi = (i * v.dims[0] / w).min(v.dims[0] - 1);
        let vj = (j * v.dims[1] / h).min(v.dims[1] - 1);
        let x = v.data[vj * v.dims[0] + vi];
        let span = (v.range[1] - v.range[0]).max(f64::MIN_POSITIVE);
        Some(if x.is_finite() {
            sequential(((f64::from(x) - v.range[0]) / span) as f32)
        } else {
            sequential(0.0)
        })
    };
    // Cells reached only through a collision: hatched diagonally.
    let blocked_at = |k: usize| match &map.collision {
        Some(layer) if layer.blocked.get(k).is_some_and(|b| *b != 0) => {
            let a = if (k % w + k / w) % 6 < 2 { 170 } else { 45 };
            Color32::from_rgba_unmultiplied(BLOCKED[0], BLOCKED[1], BLOCKED[2], a)
        }
        _ => Color32::TRANSPARENT,
    };
    let pixels = (0..w * h)
        .map(|k| {
            let mut rgb = [0.0f32; 3];
            let mut alpha = 0.0f32;
            for (m, f) in map.coverage(k) {
                if m == 0 {
                    continue;
                }
                let c = value_at(k).unwrap_or_else(|| class_color(m, classes, color_by));
                for (a, b) in rgb.iter_mut().zip(c) {
                    *a += f * f32::from(b);
                }
                alpha += f;
            }
            if alpha <= 0.0 {
                return blocked_at(k);
            }
            let a = (alpha * 235.0).round() as u8;
            let c = rgb.map(|x| (x / alpha).round() as u8);
            Color32::from_rgba_unmultiplied(c[0], c[1], c[2], a)
        })
        .collect();
    egui::ColorImage::new([w, h], pixels)
}

fn srgb_to_linear(c: [f32; 4]) -> [f32; 4] {
    let f = |v: f32| {
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    [f(c[0]), f(c[1]), f(c[2]), c[3]]
}
