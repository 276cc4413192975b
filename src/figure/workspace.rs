//! Workspace figures (Sect. 2.10.1, Figs 2.29-2.30): the plane of a planar arm with the regions
//! reached by each posture and the exact boundary arcs; top and side views as a robot data sheet
//! shows them; a 3D point cloud; the joint-space rectangle of Fig. 2.29.

use super::figures::{Figures, Scene3d};
use super::palette::{CLASS_COLORS, PLAIN, c32, class_palette, sequential, shown_legend};
use super::plot2d::{Area, Curve, Plot2d};
use super::raster::ClassRaster;
use super::{FigureError, Theme};
use crate::camera::Preset;
use crate::kinematics::Robot;
use crate::scene::{ArmStyle, Dot, arm_scene};
use crate::workspace::{
    self, Aabb, BoundaryOptions, CurveKind, GridOptions, SampleOptions, StatsOptions, View,
    WorkspaceStats,
};
use egui::Color32;

/// What the figure shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WsView {
    /// The arm plane of a planar arm.
    Plane,
    /// World x-y.
    Top,
    /// World x-z.
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
    /// By manipulability (largest in the pixel), a sequential colour map.
    Manipulability,
    /// The dexterous workspace: the fraction of orientations reachable at each position (for
    /// a planar arm the angle phi, for a spatial arm the approach direction), shown apart from
    /// the reachable workspace.
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
    /// Joint-space samples.
    pub samples: usize,
    /// Sampler seed (same seed, same figure).
    pub seed: u64,
    /// Pixels.
    pub size: [u32; 2],
    /// Light or dark.
    pub theme: Theme,
    /// End-effector.
    pub end_effector: usize,
}

/// A figure and the statistics it was drawn from.
pub struct WsFigure {
    /// The pixels.
    pub image: image::RgbaImage,
    /// Area/volume, bounds, reach.
    pub stats: WorkspaceStats,
}

fn padded(b: &Aabb, axes: [usize; 2], pad: f64) -> [f64; 4] {
    let (x0, x1, y0, y1) = (
        b.min[axes[0]],
        b.max[axes[0]],
        b.min[axes[1]],
        b.max[axes[1]],
    );
    let m = ((x1 - x0).max(y1 - y0) * pad).max(1e-3);
    [x0 - m, x1 + m, y0 - m, y1 + m]
}

/// Raster resolution for a plot of `size` pixels over `bounds` at about one cell per 2 pixels.
fn raster_dims(size: [u32; 2], bounds: [f64; 4], max_cells: f64) -> [u32; 2] {
    let aspect = (bounds[1] - bounds[0]) / (bounds[3] - bounds[2]);
    let h = (size[1] as f64 * 0.85)
        .min((max_cells / aspect).sqrt())
        .max(16.0);
    [((h * aspect).round() as u32).max(16), h.round() as u32]
}

/// Makes a workspace figure. `progress(fraction)` is called as work proceeds.
pub fn workspace_figure(
    figs: &mut Figures,
    robot: &Robot,
    title: &str,
    opts: &WsFigureOptions,
    progress: &(dyn Fn(f32) + Sync),
) -> Result<WsFigure, FigureError> {
    let want_classes = opts.color_by == ColorBy::Posture;
    let n = opts.samples.max(1);
    let samples = workspace::sample(
        robot,
        &SampleOptions {
            samples: n,
            seed: opts.seed,
            end_effector: opts.end_effector,
            classes: want_classes,
            manipulability: opts.color_by == ColorBy::Manipulability,
            keep_joints: false,
        },
        &|done| progress(0.6 * done as f32 / n as f32),
    )?;
    let planar = workspace::planar_frame(robot, opts.end_effector).is_some();
    let grid = GridOptions {
        resolution: if planar { 256 } else { 48 },
        orientations: 16,
        samples: n.min(200_000),
        seed: opts.seed,
        end_effector: opts.end_effector,
        ..GridOptions::default()
    };
    let stats = workspace::statistics(
        robot,
        &StatsOptions {
            grid: grid.clone(),
            samples: n.min(200_000),
            boundary: BoundaryOptions::default(),
        },
        &|_| {},
    )?;
    progress(0.8);
    let exact = if planar {
        workspace::planar_boundary(robot, &BoundaryOptions::default()).ok()
    } else {
        None
    };
    let measure = match (stats.area, stats.volume) {
        (Some(a), _) => format!("area {a:.4} m²"),
        (_, Some(v)) => format!("volume {v:.4} m³"),
        _ => String::new(),
    };
    let subtitle = format!(
        "{n} samples (seed {}), {measure}, reach {:.3}-{:.3} m, grid {}",
        opts.seed, stats.min_reach, stats.max_reach, stats.resolution
    );
    let text = if opts.theme == Theme::Dark {
        Color32::from_gray(230)
    } else {
        Color32::from_gray(25)
    };
    let image = match opts.view {
        WsView::ThreeD => {
            let q = robot
                .config("ready")
                .map_or_else(|| vec![0.0; robot.dof()], <[f64]>::to_vec);
            let mut scene = arm_scene(
                robot,
                &q,
                &ArmStyle {
                    frames: false,
                    ..ArmStyle::default()
                },
            )?;
            let cloud = workspace::point_cloud(&samples);
            let stride = (cloud.positions.len() / 300_000).max(1);
            let (legend, palette) = class_palette(&cloud.class_names);
            let mmax = cloud
                .manipulability
                .as_ref()
                .map_or(1.0, |m| m.iter().copied().fold(1e-12, f32::max));
            for (i, p) in cloud.positions.iter().enumerate().step_by(stride) {
                let c = match (opts.color_by, &cloud.manipulability) {
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
                },
            )?
        }
        WsView::JointSpace => {
            let rect = workspace::joint_rectangle(robot)?;
            let deg = |q: [f64; 2]| [q[0].to_degrees(), q[1].to_degrees()];
            let mut plot = Plot2d {
                title: format!("Joint space of the {title} (Fig. 2.29)"),
                subtitle: "admissible configurations within the joint limits; posture bands separated by q2 singular lines".into(),
                x_label: "q1 [deg]".into(),
                y_label: "q2 [deg]".into(),
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
                });
            }
            for p in &rect.points {
                let d = deg(p.q);
                plot.labels
                    .push((p.label.clone(), [d[0] + m1 * 0.25, d[1] + m2 * 0.25]));
            }
            figs.plot(opts.size, opts.theme, &plot, None)?
        }
        WsView::Plane | WsView::Top | WsView::Side => {
            let view = match (opts.view, planar) {
                (WsView::Plane, true) => View::Plane,
                (WsView::Plane | WsView::Top, _) => View::Top,
                _ => View::SideRZ,
            };
            let proj = workspace::project(robot, &samples, view);
            let mut b = Aabb::EMPTY;
            for p in &proj.points {
                b.extend([p[0], p[1], 0.0]);
            }
            if let (Some(e), View::Plane) = (&exact, view) {
                for p in e.curves.iter().flat_map(|c| &c.points) {
                    b.extend([p[0], p[1], 0.0]);
                }
            }
            let bounds = padded(&b, [0, 1], 0.06);
            // Exact (IK per cell) rasters at about the plot's pixel size; sampled ones at a few
            // samples per cell so regions read as areas.
            let exact_regions = matches!(opts.color_by, ColorBy::Posture | ColorBy::Dexterity)
                && view == View::Plane
                && planar;
            // A redundant planar arm scans phi per cell: keep its IK count near 2 million.
            const PHI_SCAN: usize = 24;
            let tester = if exact_regions {
                workspace::ReachTester::new(robot, PHI_SCAN)
            } else {
                None
            };
            let cells = match &tester {
                Some(t) if t.orientations() > 1 => 2.0e6 / t.orientations() as f64,
                Some(_) => 4.0e5,
                None => (n as f64 / 3.0).max(1e4),
            };
            let dims = raster_dims(opts.size, bounds, cells);
            let mut raster = ClassRaster::new(dims[0], dims[1], bounds);
            let mut legend = Vec::new();
            let image = match opts.color_by {
                ColorBy::Dexterity => {
                    // Fraction of orientations reached per pixel: exact (closed-form IK per
                    // pixel) for planar arms, the grid analysis projected (largest along the
                    // view direction) for spatial arms.
                    let (w, h) = (dims[0] as usize, dims[1] as usize);
                    let mut frac = vec![-1.0f32; w * h];
                    if let Some(t) = &tester {
                        use rayon::prelude::*;
                        frac = (0..w * h)
                            .into_par_iter()
                            .map(|i| {
                                let (u, v) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                                let x = bounds[0] + u / w as f64 * (bounds[1] - bounds[0]);
                                let y = bounds[3] - v / h as f64 * (bounds[3] - bounds[2]);
                                let r = t.test_plane([x, y]);
                                if r.mask == 0 {
                                    -1.0
                                } else {
                                    r.reached as f32 / r.tried.max(1) as f32
                                }
                            })
                            .collect();
                    } else {
                        let g = workspace::analyze_grid(
                            robot,
                            &GridOptions {
                                resolution: 40,
                                ..grid.clone()
                            },
                            &|_| {},
                        )?;
                        for i in 0..g.masks.len() {
                            if g.masks[i] == 0 {
                                continue;
                            }
                            let c = g.world_centre(i);
                            let (a, b) = match view {
                                View::SideRZ => (
                                    (c[0] - robot.base.translation.x)
                                        .hypot(c[1] - robot.base.translation.y),
                                    c[2],
                                ),
                                _ => (c[0], c[1]),
                            };
                            // Paint the cell's whole footprint so the coarse grid reads as an area.
                            let cs = g.grid.cell_size();
                            let (hx, hy) = (0.5 * cs[0].max(cs[1]), 0.5 * cs[2].max(cs[1]));
                            let (hy, hx) = if matches!(view, View::SideRZ) {
                                (hy, hx)
                            } else {
                                (0.5 * cs[1], 0.5 * cs[0])
                            };
                            let to_px = |x: f64, y: f64| -> (f64, f64) {
                                (
                                    (x - bounds[0]) / (bounds[1] - bounds[0]) * w as f64,
                                    (bounds[3] - y) / (bounds[3] - bounds[2]) * h as f64,
                                )
                            };
                            let (u0, v0) = to_px(a - hx, b + hy);
                            let (u1, v1) = to_px(a + hx, b - hy);
                            let (u0, u1) = (
                                u0.floor().max(0.0) as usize,
                                (u1.ceil().max(0.0) as usize).min(w),
                            );
                            let (v0, v1) = (
                                v0.floor().max(0.0) as usize,
                                (v1.ceil().max(0.0) as usize).min(h),
                            );
                            for v in v0..v1 {
                                for u in u0..u1 {
                                    let k = v * w + u;
                                    frac[k] = frac[k].max(g.orientation_fraction[i]);
                                }
                            }
                        }
                    }
                    legend = vec![
                        ("few orientations".into(), c32(sequential(0.0))),
                        ("all orientations (dexterous)".into(), c32(sequential(1.0))),
                    ];
                    let pixels = frac
                        .iter()
                        .map(|&f| {
                            if f < 0.0 {
                                Color32::TRANSPARENT
                            } else {
                                let c = sequential(f);
                                Color32::from_rgb(c[0], c[1], c[2])
                            }
                        })
                        .collect();
                    egui::ColorImage::new([w, h], pixels)
                }
                ColorBy::Posture if exact_regions => {
                    // Exact regions: closed-form IK at every raster cell centre.
                    if let Some(t) = &tester {
                        let (w, h) = (dims[0] as usize, dims[1] as usize);
                        use rayon::prelude::*;
                        let masks: Vec<u32> = (0..w * h)
                            .into_par_iter()
                            .map(|i| {
                                let (u, v) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                                let x = bounds[0] + u / w as f64 * (bounds[1] - bounds[0]);
                                let y = bounds[3] - v / h as f64 * (bounds[3] - bounds[2]);
                                u32::from(t.test_plane([x, y]).mask)
                            })
                            .collect();
                        raster.masks = masks;
                        let (l, palette) = class_palette(t.class_names());
                        legend = l;
                        raster.to_image(palette)
                    } else {
                        raster.splat(proj.points.iter().copied().zip(std::iter::repeat(0)));
                        raster.to_image(|_| [PLAIN[0], PLAIN[1], PLAIN[2], 235])
                    }
                }
                ColorBy::Posture => {
                    let classes = proj.classes.clone().unwrap_or_default();
                    raster.splat(
                        proj.points
                            .iter()
                            .copied()
                            .zip(classes.iter().copied().chain(std::iter::repeat(0))),
                    );
                    raster.close_holes();
                    raster.mark_unsure(super::raster::MIN_EVIDENCE);
                    let (l, palette) = class_palette(&proj.class_names);
                    legend = shown_legend(l, proj.class_names.len(), &raster);
                    raster.to_image(palette)
                }
                ColorBy::Manipulability => {
                    let m = samples.manipulability.clone().unwrap_or_default();
                    let mmax = m.iter().copied().fold(1e-12, f32::max);
                    let mut best = vec![-1.0f32; raster.masks.len()];
                    for (p, v) in proj.points.iter().zip(&m) {
                        if let Some(i) = raster.pixel(p[0], p[1]) {
                            best[i] = best[i].max(*v / mmax);
                        }
                    }
                    legend = vec![
                        ("low manipulability".into(), c32(sequential(0.0))),
                        ("high manipulability".into(), c32(sequential(1.0))),
                    ];
                    let pixels = best
                        .iter()
                        .map(|&t| {
                            if t < 0.0 {
                                Color32::TRANSPARENT
                            } else {
                                let c = sequential(t);
                                Color32::from_rgb(c[0], c[1], c[2])
                            }
                        })
                        .collect();
                    egui::ColorImage::new([dims[0] as usize, dims[1] as usize], pixels)
                }
                ColorBy::None => {
                    raster.splat(proj.points.iter().copied().zip(std::iter::repeat(0)));
                    raster.close_holes();
                    raster.to_image(|_| [PLAIN[0], PLAIN[1], PLAIN[2], 235])
                }
            };
            let (xl, yl) = match view {
                View::Plane => ("x [m] (base frame)", "y [m] (base frame)"),
                View::Top => ("x [m]", "y [m]"),
                _ => ("r [m] (horizontal distance from the base axis)", "z [m]"),
            };
            let which = match view {
                View::Plane => "",
                View::Top => ", top view",
                _ => ", side view",
            };
            let mut plot = Plot2d {
                title: format!("Workspace of the {title}{which}"),
                subtitle,
                x_label: xl.into(),
                y_label: yl.into(),
                bounds,
                equal_aspect: true,
                legend,
                ..Plot2d::default()
            };
            if let (Some(e), View::Plane) = (&exact, view) {
                // Two-link arms: the arcs of Fig. 2.30, bold. Three-link arms: every boundary
                // candidate, thin (the boundary is the outermost of them).
                let two_link = e.rectangle.is_some();
                for c in &e.curves {
                    let color = if c.kind == CurveKind::Singular {
                        Color32::from_gray(110)
                    } else if two_link {
                        text
                    } else {
                        text.gamma_multiply(0.45)
                    };
                    let width = if two_link { 1.6 } else { 0.9 };
                    plot.curves.push(Curve {
                        name: None,
                        points: c.points.clone(),
                        color,
                        width,
                        dashed: c.kind == CurveKind::Singular,
                    });
                }
                if e.rectangle.is_some() {
                    for c in &e.curves {
                        if let (Some(first), Some(last)) = (c.points.first(), c.points.last()) {
                            let name = c.label.chars().collect::<Vec<_>>();
                            if name.len() == 2 && name.iter().all(char::is_ascii_uppercase) {
                                plot.labels.push((name[0].to_string(), *first));
                                plot.labels.push((name[1].to_string(), *last));
                            }
                        }
                    }
                    plot.labels.sort_by(|a, b| a.0.cmp(&b.0));
                    plot.labels.dedup_by(|a, b| a.0 == b.0);
                }
            }
            figs.plot(opts.size, opts.theme, &plot, Some(image))?
        }
    };
    progress(1.0);
    Ok(WsFigure { image, stats })
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
