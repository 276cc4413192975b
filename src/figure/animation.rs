//! Animations painted: each frame of an [`Animation`] (computed by [`crate::animation`]) drawn
//! by the figures' 3D renderer with one fixed camera, its caption under the title; a tool path
//! gets its joint-rate plot beside the view. Encoded as GIF (a NeuQuant palette per frame,
//! frames quantized in parallel) or APNG (lossless).

use super::figures::{Figures, Scene3d};
use super::plot2d::{Curve, Plot2d};
use super::self_motion::JOINT_COLORS;
use super::{FigureError, Theme};
use crate::animation::{Animation, Shot};
use crate::camera::{Camera, Preset};
use crate::kinematics::{Pose, Robot};
use crate::scene::{ArmStyle, Label, Line, Scene, arm_scene, point32};
use egui::Color32;
use rayon::prelude::*;

/// Share of the page the 3D view keeps beside (or, on a portrait page, over) a plot.
const VIEW_SHARE: f32 = 0.58;

/// Every frame of `anim` at `size` pixels (a tool path's joint-rate plot beside its view on a
/// landscape page, under it on a portrait one).
pub fn frames(
    figs: &mut Figures,
    robot: &Robot,
    anim: &Animation,
    size: [u32; 2],
    theme: Theme,
) -> Result<Vec<image::RgbaImage>, FigureError> {
    let beside = size[0] >= size[1];
    let view = match anim.rates {
        Some(_) if beside => [((size[0] as f32 * VIEW_SHARE) as u32).max(64), size[1]],
        Some(_) => [size[0], ((size[1] as f32 * VIEW_SHARE) as u32).max(64)],
        None => size,
    };
    let camera = framing(robot, anim, view)?;
    let extent = arm_extent(robot, &anim.shots[0].q)?;
    let mut out = Vec::with_capacity(anim.shots.len());
    for shot in &anim.shots {
        let scene = shot_scene(robot, anim, shot, extent)?;
        let img = figs.scene(
            view,
            theme,
            &Scene3d {
                title: anim.title.clone(),
                subtitle: shot.caption.clone(),
                caption: String::new(),
                scene: &scene,
                camera,
                legend: Vec::new(),
            },
        )?;
        let Some(rates) = &anim.rates else {
            out.push(img);
            continue;
        };
        let plot = rate_plot(robot, rates, shot.time);
        let (rest, at) = if beside {
            ([size[0] - view[0], size[1]], [i64::from(view[0]), 0])
        } else {
            ([size[0], size[1] - view[1]], [0, i64::from(view[1])])
        };
        let chart = figs.plot(rest, theme, &plot, None)?;
        let mut page = image::RgbaImage::new(size[0], size[1]);
        image::imageops::overlay(&mut page, &img, 0, 0);
        image::imageops::overlay(&mut page, &chart, at[0], at[1]);
        out.push(page);
    }
    Ok(out)
}

/// One camera for the whole animation: iso view of every frame's arm (a sample of them) and
/// the trace.
fn framing(robot: &Robot, anim: &Animation, size: [u32; 2]) -> Result<Camera, FigureError> {
    let mut points = Vec::new();
    let step = (anim.shots.len() / 24).max(1);
    for s in anim.shots.iter().step_by(step) {
        points.extend(crate::scene::arm_points(robot, &s.q)?);
        for g in &s.ghosts {
            points.extend(crate::scene::arm_points(robot, g)?);
        }
    }
    points.extend(anim.trace.iter().map(point32));
    let mut camera = Camera::default();
    camera.set_preset(Preset::Iso);
    camera.fit_points(&points, size[0], size[1], 0.8);
    camera.pan(0.0, 0.04);
    Ok(camera)
}

/// The size of the arm (m): the largest distance of a joint from the base, at least 0.1 m.
fn arm_extent(robot: &Robot, q: &[f64]) -> Result<f64, FigureError> {
    let base = robot.base.translation.vector;
    Ok(robot
        .fk_frames(q)?
        .iter()
        .map(|f| (f.translation.vector - base).norm())
        .fold(0.1, f64::max))
}

/// The scene of one frame: the arm, its ghosts, the DH frames, the trace.
fn shot_scene(
    robot: &Robot,
    anim: &Animation,
    shot: &Shot,
    extent: f64,
) -> Result<Scene, FigureError> {
    let dh = !shot.frames.is_empty() || shot.moving.is_some();
    let style = ArmStyle {
        frames: false,
        frame_labels: false,
        alpha: if dh { 0.35 } else { 1.0 },
        ..ArmStyle::default()
    };
    let mut scene = arm_scene(robot, &shot.q, &style)?;
    let ghost = ArmStyle {
        grid: false,
        alpha: 0.22,
        ..style
    };
    for g in shot.ghosts.iter().filter(|g| **g != shot.q) {
        let mut s = arm_scene(robot, g, &ghost)?;
        s.labels.clear();
        scene.extend(s);
    }
    let len = 0.16 * extent;
    for (name, pose) in &shot.frames {
        triad(&mut scene, pose, name, len, 2.5, 0.75);
    }
    if let Some((name, pose)) = &shot.moving {
        triad(&mut scene, pose, &format!("{name}'"), 1.3 * len, 5.0, 1.0);
    }
    for w in anim.trace.windows(2) {
        scene.lines.push(Line {
            a: point32(&w[0]).into(),
            b: point32(&w[1]).into(),
            color: [0.45, 0.1, 0.6, 1.0],
            width_px: 3.0,
        });
    }
    Ok(scene)
}

/// A frame triad (x red, y green, z blue) of `len` m with labels `x{name}`, `z{name}`.
fn triad(scene: &mut Scene, pose: &Pose, name: &str, len: f64, width: f32, alpha: f32) {
    let o = pose.translation.vector;
    for (k, c) in crate::scene::AXIS_COLORS.iter().enumerate() {
        let tip = o + pose.rotation * nalgebra::Vector3::ith(k, len);
        let color = [c[0], c[1], c[2], alpha];
        scene.lines.push(Line {
            a: point32(&o).into(),
            b: point32(&tip).into(),
            color,
            width_px: width,
        });
        if k != 1 {
            scene.labels.push(Label {
                p: point32(&tip).into(),
                text: format!("{}{name}", ["x", "y", "z"][k]),
                color,
                movable: false,
            });
        }
    }
}

/// The joint rates over time with a cursor at `now` (s).
fn rate_plot(robot: &Robot, rates: &crate::animation::Rates, now: f64) -> Plot2d {
    let (lo, hi) = rates
        .qdot
        .iter()
        .flatten()
        .fold((0.0f64, 0.0f64), |(a, b), v| (a.min(*v), b.max(*v)));
    let pad = 0.1 * (hi - lo).max(1e-3);
    let t_end = rates.t.last().copied().unwrap_or(1.0).max(1e-3);
    let mut plot = Plot2d {
        title: "Joint rates".into(),
        subtitle: format!("tool speed {:.3} m/s along a straight line", rates.speed),
        x_label: "t [s]".into(),
        y_label: "joint rate [rad/s, m/s]".into(),
        bounds: [0.0, t_end, lo - pad, hi + pad],
        ..Plot2d::default()
    };
    for j in 0..robot.dof() {
        let c = JOINT_COLORS[j % JOINT_COLORS.len()];
        plot.curves.push(Curve {
            name: Some(format!("q{}", j + 1)),
            points: rates
                .t
                .iter()
                .zip(&rates.qdot)
                .map(|(t, v)| [*t, v[j]])
                .collect(),
            color: Color32::from_rgb(c[0], c[1], c[2]),
            width: 1.8,
            ..Curve::default()
        });
    }
    plot.curves.push(Curve {
        points: vec![[now, lo - pad], [now, hi + pad]],
        color: Color32::from_gray(60),
        width: 1.2,
        dashed: true,
        ..Curve::default()
    });
    plot
}

/// Frame delays (1/100 s, GIF's unit) of `n` frames at `fps`, rounded so that they add up to
/// the exact duration.
pub fn gif_delays(n: usize, fps: u32) -> Vec<u16> {
    let at = |k: usize| (100.0 * k as f64 / f64::from(fps.max(1))).round() as i64;
    (0..n).map(|k| (at(k + 1) - at(k)).max(1) as u16).collect()
}

/// What can go wrong while encoding an animation.
#[derive(Debug, thiserror::Error)]
pub enum EncodeError {
    /// The GIF encoder failed (or writing failed).
    #[error("GIF encoding: {0}")]
    Gif(#[from] gif::EncodingError),
    /// The PNG encoder failed (or writing failed).
    #[error("APNG encoding: {0}")]
    Png(#[from] png::EncodingError),
    /// No frames, or frames too large for the format.
    #[error("cannot encode {frames} frames of {width}x{height} (GIF is limited to 65535 px)")]
    Size {
        /// Frames.
        frames: usize,
        /// Width (px).
        width: u32,
        /// Height (px).
        height: u32,
    },
}

/// Index of the transparent colour of GIF frames after the first (unchanged pixels).
const CLEAR: u8 = 255;

/// Writes `frames` (all one size) as a looping GIF at `fps`. One 255-colour palette for the
/// whole animation (NeuQuant over pixels sampled from a dozen frames), colours mapped through a
/// 15-bit lookup table, frames indexed in parallel; each frame after the first is only the
/// rectangle that changed, its unchanged pixels transparent (so the static grid and background
/// cost nothing).
pub fn encode_gif(
    frames: &[image::RgbaImage],
    fps: u32,
    out: impl std::io::Write,
) -> Result<(), EncodeError> {
    let (w, h) = frames.first().map_or((0, 0), image::RgbaImage::dimensions);
    if frames.is_empty() || w > 65535 || h > 65535 {
        return Err(EncodeError::Size {
            frames: frames.len(),
            width: w,
            height: h,
        });
    }
    let (palette, lut) = shared_palette(frames);
    let indexed: Vec<Vec<u8>> = frames
        .par_iter()
        .map(|img| {
            img.pixels()
                .map(|p| {
                    lut[usize::from(p[0] >> 3) << 10
                        | usize::from(p[1] >> 3) << 5
                        | usize::from(p[2] >> 3)]
                })
                .collect()
        })
        .collect();
    let delays = gif_delays(frames.len(), fps);
    let mut enc = gif::Encoder::new(out, w as u16, h as u16, &palette)?;
    enc.set_repeat(gif::Repeat::Infinite)?;
    let (wu, hu) = (w as usize, h as usize);
    for (k, px) in indexed.iter().enumerate() {
        let mut frame = gif::Frame {
            delay: delays[k],
            dispose: gif::DisposalMethod::Keep,
            ..gif::Frame::default()
        };
        if k == 0 {
            frame.width = w as u16;
            frame.height = h as u16;
            frame.buffer = std::borrow::Cow::Borrowed(px);
        } else {
            let prev = &indexed[k - 1];
            let (x0, y0, x1, y1) = changed_box(prev, px, wu, hu).unwrap_or((0, 0, 1, 1));
            let mut buf = Vec::with_capacity((x1 - x0) * (y1 - y0));
            for y in y0..y1 {
                for x in x0..x1 {
                    let i = y * wu + x;
                    buf.push(if px[i] == prev[i] { CLEAR } else { px[i] });
                }
            }
            frame.left = x0 as u16;
            frame.top = y0 as u16;
            frame.width = (x1 - x0) as u16;
            frame.height = (y1 - y0) as u16;
            frame.transparent = Some(CLEAR);
            frame.buffer = std::borrow::Cow::Owned(buf);
        }
        enc.write_frame(&frame)?;
    }
    Ok(())
}

/// The palette (255 colours, RGB bytes) of an animation and a lookup table from 15-bit colour
/// (5 bits a channel) to palette index.
fn shared_palette(frames: &[image::RgbaImage]) -> (Vec<u8>, Vec<u8>) {
    let step = (frames.len() / 12).max(1);
    let mut sample: Vec<u8> = Vec::new();
    for img in frames.iter().step_by(step) {
        // Every 7th pixel: enough for the few dozen colours of a rendered arm.
        for p in img.pixels().step_by(7) {
            sample.extend_from_slice(&[p[0], p[1], p[2], 255]);
        }
    }
    let nq = color_quant::NeuQuant::new(10, 255, &sample);
    let palette = nq.color_map_rgb();
    let lut: Vec<u8> = (0..1usize << 15)
        .into_par_iter()
        .map(|c| {
            let ch = |s: usize| (((c >> s) & 31) << 3 | 4) as u8;
            nq.index_of(&[ch(10), ch(5), ch(0), 255]) as u8
        })
        .collect();
    (palette, lut)
}

/// The smallest rectangle `(x0, y0, x1, y1)` (end exclusive) holding every pixel that differs.
fn changed_box(a: &[u8], b: &[u8], w: usize, h: usize) -> Option<(usize, usize, usize, usize)> {
    let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0, 0);
    for y in 0..h {
        let (ra, rb) = (&a[y * w..(y + 1) * w], &b[y * w..(y + 1) * w]);
        if ra == rb {
            continue;
        }
        let first = ra.iter().zip(rb).position(|(p, q)| p != q).unwrap_or(0);
        let last = w - ra
            .iter()
            .rev()
            .zip(rb.iter().rev())
            .position(|(p, q)| p != q)
            .unwrap_or(0);
        x0 = x0.min(first);
        x1 = x1.max(last);
        y0 = y0.min(y);
        y1 = y + 1;
    }
    (x1 > x0).then_some((x0, y0, x1, y1))
}

/// Writes `frames` as a looping APNG at `fps` (delay 1/fps exactly), lossless.
pub fn encode_apng(
    frames: &[image::RgbaImage],
    fps: u32,
    out: impl std::io::Write,
) -> Result<(), EncodeError> {
    let (w, h) = frames.first().map_or((0, 0), image::RgbaImage::dimensions);
    if frames.is_empty() {
        return Err(EncodeError::Size {
            frames: 0,
            width: w,
            height: h,
        });
    }
    let mut enc = png::Encoder::new(out, w, h);
    enc.set_color(png::ColorType::Rgba);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::Fast);
    enc.set_animated(frames.len() as u32, 0)?;
    enc.set_frame_delay(1, fps.clamp(1, 65535) as u16)?;
    let mut writer = enc.write_header()?;
    for f in frames {
        writer.write_image_data(f.as_raw())?;
    }
    writer.finish()?;
    Ok(())
}
