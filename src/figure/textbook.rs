//! The excerpt's figures from one call (`armlab figure NAME`): Figs 2.29-2.33 and Problem 2.17,
//! drawn with the textbook's labels by the same renderer and plot code as every other figure.
//! The numbers come from the compute layers ([`crate::construction`], the closed
//! form, the exact workspace); this module only paints them.

use super::figures::{Figures, Scene3d};
use super::palette::{CLASS_COLORS, c32};
use super::plot2d::{Curve, Plot2d};
use super::vector::VectorPage;
use super::workspace::{ColorBy, WsFigureOptions, WsView};
use super::{FigureError, Theme};
use crate::camera::Preset;
use crate::construction::textbook::{Subject, WorkspaceView};
use crate::construction::{TwoLinkConstruction, WristPoint};
use crate::kinematics::Robot;
use crate::scene::{ArmStyle, Dot, Label, Line, arm_scene, point32};
use egui::Color32;
use nalgebra::Vector3;

/// An isometric camera framing `points`, the picture a little below the title.
fn framing(points: &[nalgebra::Point3<f32>], size: [u32; 2]) -> crate::camera::Camera {
    let mut camera = crate::camera::Camera::default();
    camera.set_preset(Preset::Iso);
    camera.fit_points(points, size[0], size[1], 0.75);
    camera.pan(0.0, 0.04);
    camera
}

/// The caption naming a figure's source.
fn after(fig: &str) -> String {
    format!("after {fig} of Siciliano et al., Robotics: Modelling, Planning and Control")
}

/// The workspace figure's options of a workspace subject (Figs 2.29-2.30, Problem 2.17): the
/// arm, its title and the options to plan it with ([`super::workspace::plan`]); `None` for the
/// other figures.
pub fn workspace_options<'s>(
    subject: &'s Subject,
    name: &str,
    size: [u32; 2],
    theme: Theme,
) -> Option<(&'s Robot, &'static str, WsFigureOptions)> {
    let Subject::Workspace { robot, title, view } = subject else {
        return None;
    };
    let opts = WsFigureOptions {
        view: match view {
            WorkspaceView::JointSpace => WsView::JointSpace,
            WorkspaceView::Plane => WsView::Plane,
        },
        color_by: ColorBy::Posture,
        samples: 100_000,
        seed: 1,
        size,
        theme,
        end_effector: 0,
        point: crate::workspace::TrackedPoint::WristCentre,
        caption: after(Subject::source(name)),
        text_scale: 1.0,
    };
    Some((robot, title, opts))
}

/// Paints figure `name` from its subject at `size` pixels; the workspace subjects are workspace
/// figures (see [`workspace_options`]) and are refused here.
pub fn paint(
    figs: &mut Figures,
    subject: &Subject,
    size: [u32; 2],
    theme: Theme,
) -> Result<image::RgbaImage, FigureError> {
    match subject {
        Subject::TwoLinkPostures(k) => two_link_postures(figs, k, size, theme),
        Subject::SphericalWrist { robot, q, wrist } => {
            spherical_wrist(figs, robot, q, wrist, size, theme)
        }
        Subject::FourConfigurations {
            robot,
            p,
            solutions,
        } => anthropomorphic_configurations(figs, robot, p, solutions, size, theme),
        Subject::Workspace { .. } => Err(FigureError::WrongData {
            wanted: "a scene",
            got: "a workspace subject",
        }),
    }
}

/// A curve of Fig. 2.31.
fn line(
    name: Option<String>,
    points: Vec<[f64; 2]>,
    color: Color32,
    width: f32,
    dashed: bool,
) -> Curve {
    Curve {
        name,
        points,
        color,
        width,
        dashed,
        ..Curve::default()
    }
}

/// An arc of Fig. 2.31 (radius `r` about `c`, from `a0` to `a1` rad) as a solid curve that a
/// vector figure writes as a true arc.
fn arc_curve(c: [f64; 2], r: f64, a0: f64, a1: f64, color: Color32, width: f32) -> Curve {
    Curve {
        arcs: vec![crate::figure::vector::PlotArc {
            centre: c,
            radius: r,
            start: a0,
            sweep: a1 - a0,
        }],
        ..line(None, arc(c, r, a0, a1), color, width, false)
    }
}

/// Points of an arc of radius `r` about `c` from angle `a0` to `a1` (rad).
fn arc(c: [f64; 2], r: f64, a0: f64, a1: f64) -> Vec<[f64; 2]> {
    let n = 48;
    (0..=n)
        .map(|k| {
            let a = a0 + (a1 - a0) * k as f64 / n as f64;
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        })
        .collect()
}

/// Fig. 2.31: both postures of the two-link arm (a1 = a2 = 1 m) for one point, with the angles
/// of the cosine-theorem construction.
fn two_link_postures(
    figs: &mut Figures,
    k: &TwoLinkConstruction,
    size: [u32; 2],
    theme: Theme,
) -> Result<image::RgbaImage, FigureError> {
    let p = k.p;
    let ink = if theme == Theme::Dark {
        Color32::from_gray(220)
    } else {
        Color32::from_gray(30)
    };
    let mut plot = Plot2d {
        title: "Admissible postures of a two-link planar arm (Fig. 2.31)".into(),
        subtitle: format!(
            "p_W = ({:.2}, {:.2}) m, a1 = a2 = 1 m: c2 = {:.4}, theta2 = +-{:.2} deg; alpha = \
             Atan2(p_Wy, p_Wx) = {:.2} deg, beta = {:.2} deg; theta1 = alpha + beta (elbow up), \
             alpha - beta (elbow down)",
            p[0],
            p[1],
            k.c2,
            k.postures[1].theta2.to_degrees(),
            k.alpha.to_degrees(),
            k.beta.to_degrees()
        ),
        caption: after("Fig. 2.31"),
        x_label: "x [m]".into(),
        y_label: "y [m]".into(),
        bounds: [-0.4, 2.0, -0.5, 1.6],
        equal_aspect: true,
        ..Plot2d::default()
    };
    plot.curves
        .push(line(None, vec![[0.0, 0.0], p], ink, 1.0, true));
    plot.curves
        .push(arc_curve([0.0, 0.0], 0.35, 0.0, k.alpha, ink, 1.5));
    plot.labels.push((
        "α".into(),
        [0.42 * (k.alpha / 2.0).cos(), 0.42 * (k.alpha / 2.0).sin()],
    ));
    for (i, pos) in k.postures.iter().enumerate() {
        add_posture(&mut plot, k, i, pos);
    }
    plot.labels.push(("W".into(), [p[0] + 0.06, p[1] + 0.06]));
    plot.labels.push(("O".into(), [-0.08, -0.08]));
    figs.plot(size, theme, &plot, None)
}

/// One posture of Fig. 2.31: its links in its colour, beta at O, theta2 at the elbow, its name.
fn add_posture(
    plot: &mut Plot2d,
    k: &TwoLinkConstruction,
    i: usize,
    pos: &crate::construction::TwoLinkPosture,
) {
    let p = k.p;
    let color = c32(CLASS_COLORS[i]);
    plot.curves.push(line(
        Some(pos.name.to_string()),
        vec![[0.0, 0.0], pos.elbow, p],
        color,
        4.0,
        false,
    ));
    // beta between the line O-W and link 1; theta2 between link 1's extension and link 2.
    let r = 0.55 + 0.12 * i as f64;
    plot.curves
        .push(arc_curve([0.0, 0.0], r, k.alpha, pos.theta1, color, 1.5));
    let mid = 0.5 * (k.alpha + pos.theta1);
    plot.labels
        .push(("β".into(), [(r + 0.08) * mid.cos(), (r + 0.08) * mid.sin()]));
    let ext = [pos.elbow[0] * 1.35, pos.elbow[1] * 1.35];
    plot.curves
        .push(line(None, vec![pos.elbow, ext], color, 1.0, true));
    let a_end = pos.theta1 + pos.theta2;
    plot.curves
        .push(arc_curve(pos.elbow, 0.25, pos.theta1, a_end, color, 1.5));
    let m2 = pos.theta1 + 0.5 * pos.theta2;
    plot.labels.push((
        format!("θ2 = {:.1}°", pos.theta2.to_degrees()),
        [
            pos.elbow[0] + 0.38 * m2.cos(),
            pos.elbow[1] + 0.38 * m2.sin(),
        ],
    ));
    let out = if pos.theta2 < 0.0 {
        [-0.3, 0.08]
    } else {
        [0.05, -0.12]
    };
    plot.labels.push((
        pos.name.to_string(),
        [pos.elbow[0] + out[0], pos.elbow[1] + out[1]],
    ));
}

/// Fig. 2.32: the anthropomorphic arm with spherical wrist, with p_e, a_e, d6 and p_W.
fn spherical_wrist(
    figs: &mut Figures,
    robot: &Robot,
    q: &[f64; 6],
    w: &WristPoint,
    size: [u32; 2],
    theme: Theme,
) -> Result<image::RgbaImage, FigureError> {
    // Translucent bodies, no frames: the vectors at the wrist stay visible.
    let style = ArmStyle {
        frames: false,
        frame_labels: false,
        alpha: 0.45,
        ..ArmStyle::default()
    };
    let mut scene = arm_scene(robot, q, &style)?;
    add_wrist_marks(&mut scene, w);
    // Top: the whole arm; bottom: the wrist close up, the same scene.
    let panel = [size[0], size[1] / 2];
    let whole = framing(&crate::scene::arm_points(robot, q)?, panel);
    // The close-up: the wrist, p_e and the tip of a_e filling the panel, seen from the side of
    // a_e (so the segment -d6 a_e is long on the page and its label stands clear of p_W's).
    let r = 0.5 * w.d6;
    let tip = w.p_e + w.a_e * (1.5 * w.d6);
    let mut near: Vec<nalgebra::Point3<f32>> = [-1.0, 1.0]
        .iter()
        .flat_map(|sx| [-1.0, 1.0].map(|sy| (sx, sy)))
        .flat_map(|(sx, sy)| {
            [-1.0, 1.0].map(|sz| point32(&(w.p_w + Vector3::new(sx * r, sy * r, sz * r))))
        })
        .collect();
    near.extend([point32(&w.p_e), point32(&tip)]);
    let mut close = crate::camera::Camera::default();
    close.set_preset(Preset::Iso);
    close.yaw = (w.a_e.y.atan2(w.a_e.x) + std::f64::consts::FRAC_PI_2) as f32;
    close.pitch = 0.5;
    close.fit_points(&near, panel[0], panel[1], 0.7);
    let subtitle = format!(
        "p_W = p_e - d6 a_e (2.93) = ({:.3}, {:.3}, {:.3}) m: it depends on q1-q3 only",
        w.p_w.x, w.p_w.y, w.p_w.z
    );
    let mut out = image::RgbaImage::new(size[0], size[1]);
    let mut pages = Vec::new();
    for (k, (title, camera)) in [
        ("Manipulator with spherical wrist (Fig. 2.32)", whole),
        ("the wrist close up", close),
    ]
    .into_iter()
    .enumerate()
    {
        let img = figs.scene(
            panel,
            theme,
            &Scene3d {
                title: title.into(),
                subtitle: if k == 0 {
                    subtitle.clone()
                } else {
                    String::new()
                },
                scene: &scene,
                camera,
                legend: Vec::new(),
                caption: if k == 1 {
                    after("Fig. 2.32")
                } else {
                    String::new()
                },
            },
        )?;
        image::imageops::overlay(&mut out, &img, 0, i64::from(k as u32 * panel[1]));
        pages.extend(figs.take_vector().map(|p| ([0, k as u32 * panel[1]], p)));
    }
    if figs.capturing() {
        figs.set_composite(VectorPage::compose(size, pages));
    }
    Ok(out)
}

/// The vectors of Fig. 2.32: -d6 a_e from p_e to p_W (red), a_e (blue), the points, labels.
fn add_wrist_marks(scene: &mut crate::scene::Scene, w: &WristPoint) {
    let (pe, pw) = (point32(&w.p_e), point32(&w.p_w));
    let tip = point32(&(w.p_e + w.a_e * (1.5 * w.d6)));
    let red = [0.85, 0.15, 0.1, 1.0];
    let blue = [0.1, 0.3, 0.85, 1.0];
    scene.lines.push(Line {
        a: pe.into(),
        b: pw.into(),
        color: red,
        width_px: 4.0,
    });
    scene.lines.push(Line {
        a: pe.into(),
        b: tip.into(),
        color: blue,
        width_px: 3.0,
    });
    for (p, c) in [(pe, blue), (pw, red)] {
        scene.dots.push(Dot {
            p: p.into(),
            color: c,
            size_px: 12.0,
        });
    }
    let label = |p: Vector3<f64>, text: String, color| Label {
        p: point32(&p).into(),
        text,
        color,
        movable: true,
    };
    let mid = 0.5 * (w.p_e + w.p_w);
    scene.labels.extend([
        label(w.p_e, "p_e".into(), blue),
        label(w.p_w, "p_W (wrist point)".into(), red),
        label(w.p_e + w.a_e * (1.5 * w.d6), "a_e".into(), blue),
        label(mid, format!("-d6 a_e, d6 = {:.3} m", w.d6), red),
    ]);
}

/// Fig. 2.33: the four solutions of the anthropomorphic arm for one wrist position, in a 2 x 2
/// grid of panels seen by one camera, each in its posture colour with its frames (the
/// shoulder-left links lie on the shoulder-right ones; only the frames turn).
fn anthropomorphic_configurations(
    figs: &mut Figures,
    robot: &Robot,
    p: &Vector3<f64>,
    solutions: &[(String, [f64; 3], usize)],
    size: [u32; 2],
    theme: Theme,
) -> Result<image::RgbaImage, FigureError> {
    let panel = [size[0] / 2, size[1] / 2];
    let mut points = Vec::new();
    for (_, q, _) in solutions {
        points.extend(crate::scene::arm_points(robot, q)?);
    }
    let camera = framing(&points, panel);
    let mut out = image::RgbaImage::new(size[0], size[1]);
    let mut pages = Vec::new();
    for (slot, (label, q, k)) in solutions.iter().enumerate() {
        let c8 = CLASS_COLORS[*k % CLASS_COLORS.len()];
        let c = [c8[0], c8[1], c8[2]].map(|v| f32::from(v) / 255.0);
        let style = ArmStyle {
            link: [c[0], c[1], c[2], 1.0],
            frames: true,
            frame_labels: true,
            ..ArmStyle::default()
        };
        let mut scene = arm_scene(robot, q, &style)?;
        scene.dots.push(Dot {
            p: point32(p).into(),
            color: [0.1, 0.1, 0.12, 1.0],
            size_px: 10.0,
        });
        let deg = q
            .iter()
            .map(|v| format!("{:.1}", v.to_degrees()))
            .collect::<Vec<_>>();
        let img = figs.scene(
            panel,
            theme,
            &Scene3d {
                title: format!("Fig. 2.33: {label}"),
                subtitle: format!(
                    "theta = ({}) deg; p_W = ({:.3}, {:.3}, {:.3}) m",
                    deg.join(", "),
                    p.x,
                    p.y,
                    p.z
                ),
                scene: &scene,
                camera,
                legend: Vec::new(),
                caption: if slot + 1 == solutions.len() {
                    after("Fig. 2.33")
                } else {
                    String::new()
                },
            },
        )?;
        let (x, y) = ((slot as u32 % 2) * panel[0], (slot as u32 / 2) * panel[1]);
        image::imageops::overlay(&mut out, &img, i64::from(x), i64::from(y));
        pages.extend(figs.take_vector().map(|p| ([x, y], p)));
    }
    if figs.capturing() {
        figs.set_composite(VectorPage::compose(size, pages));
    }
    Ok(out)
}
