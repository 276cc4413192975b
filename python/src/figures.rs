//! Figures for notebooks: the same renderer as `armlab render`, `armlab workspace` and
//! `armlab figure`, each figure returned as PNG bytes and SVG text (the vector capture of the
//! same drawing), so that Jupyter shows it inline and `Figure.save` writes PNG, SVG or PDF.
//!
//! One renderer (a wgpu device on the machine's adapter; Mesa's lavapipe without a GPU) is made
//! on the first figure and kept; figures are drawn one at a time, with the GIL released.

use crate::arrays::checked;
use crate::errors::{FigureError, IntoPy, value_error};
use crate::robot::CoreRobot;
use armlab::camera::{Camera, Preset};
use armlab::figure::figures::{Figures, Scene3d};
use armlab::figure::workspace::{ColorBy, WsFigureOptions, WsView};
use armlab::figure::{FigureError as RustFigureError, Theme};
use armlab::render::Gpu;
use armlab::workspace::TrackedPoint;
use numpy::PyReadonlyArrayDyn;
use pyo3::prelude::*;
use std::sync::Mutex;

/// The graphics device, opened on first use and kept.
static GPU: Mutex<Option<Gpu>> = Mutex::new(None);

/// Renderers on the kept device, one per pass: a renderer carries egui's state from one figure
/// to the next (the edges' anti-aliasing came out different on a second figure), and a fresh
/// one makes every figure the same bytes as the command line's, whatever was drawn before.
fn figures() -> PyResult<Figures> {
    let mut gpu = GPU.lock().unwrap_or_else(|p| p.into_inner());
    if gpu.is_none() {
        *gpu = Some(
            Gpu::new_headless()
                .map_err(RustFigureError::from)
                .py_err()?,
        );
    }
    Figures::with_gpu(gpu.clone().expect("opened above")).py_err()
}

/// A drawn figure: PNG bytes and the SVG of the same drawing.
pub type Drawn = (Vec<u8>, String);

/// Runs `draw` twice: once for the pixels, once with vector capture on for the SVG (a figure
/// drawn for vectors paints its exact regions as vectors, not pixels, so the two are separate
/// passes; the PNG is then byte for byte what the command line writes).
pub fn draw(
    py: Python<'_>,
    draw: impl Fn(&mut Figures) -> Result<image::RgbaImage, RustFigureError> + Send + Sync,
) -> PyResult<Drawn> {
    py.detach(|| {
        let mut figs = figures()?;
        let img = draw(&mut figs).py_err()?;
        let mut png = Vec::new();
        armlab::figure::encode_png(&img, &mut png)
            .map_err(|e| FigureError::new_err(format!("cannot encode the PNG: {e}")))?;
        let mut figs = figures()?;
        figs.capture_vectors(true);
        draw(&mut figs).py_err()?;
        let svg = figs
            .take_vector()
            .map(|page| armlab::figure::vector::to_svg(&page))
            .ok_or_else(|| FigureError::new_err("the figure was not captured as vectors"))?;
        Ok((png, svg))
    })
}

/// A theme by name.
pub fn theme(name: &str) -> PyResult<Theme> {
    match name {
        "light" => Ok(Theme::Light),
        "dark" => Ok(Theme::Dark),
        other => Err(value_error(format!(
            "theme = {other:?}: use \"light\" or \"dark\""
        ))),
    }
}

/// A size (width, height) in pixels, each 16 to 8192.
pub fn size(width: u32, height: u32) -> PyResult<[u32; 2]> {
    if (16..=8192).contains(&width) && (16..=8192).contains(&height) {
        Ok([width, height])
    } else {
        Err(value_error(format!(
            "size = ({width}, {height}): each side must be 16 to 8192 pixels"
        )))
    }
}

/// The arm at `q` seen from `view` ("iso", "front", "side", "top"), with its DH frames when
/// `frames`: `(png, svg)`.
#[pyfunction]
#[pyo3(signature = (robot, q, view="iso", width=800, height=600, frames=false, theme="light"))]
#[allow(clippy::too_many_arguments)]
pub fn render(
    py: Python<'_>,
    robot: &Bound<'_, CoreRobot>,
    q: PyReadonlyArrayDyn<'_, f64>,
    view: &str,
    width: u32,
    height: u32,
    frames: bool,
    theme: &str,
) -> PyResult<Drawn> {
    let r = robot.get();
    let q = checked(&q, "q", &[Some(r.robot.dof())], "one value per joint")?.into_owned();
    let preset = match view {
        "iso" => Preset::Iso,
        "front" => Preset::Front,
        "side" => Preset::Side,
        "top" => Preset::Top,
        other => {
            return Err(value_error(format!(
                "view = {other:?}: use \"iso\", \"front\", \"side\" or \"top\""
            )));
        }
    };
    let (size, theme) = (size(width, height)?, self::theme(theme)?);
    let style = armlab::scene::ArmStyle {
        frames,
        frame_labels: frames,
        ..armlab::scene::ArmStyle::default()
    };
    let mut scene = armlab::scene::arm_scene(&r.robot, &q, &style).py_err()?;
    if r.robot.end_effectors().len() > 1 {
        armlab::scene::label_driven_chain_only(&mut scene, &r.robot, 0);
    }
    let points = armlab::scene::arm_points(&r.robot, &q).py_err()?;
    let mut camera = Camera::default();
    camera.set_preset(preset);
    camera.fit_points(&points, size[0], size[1], 0.75);
    camera.pan(0.0, 0.04);
    // The subtitle as `armlab render` writes it (degrees and metres, six decimals), so that the
    // same configuration gives the same pixels.
    let shown: Vec<String> = q
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            let v = if r.revolute[k] { v.to_degrees() } else { v };
            format!("{:.6}", if v.abs() < 5e-7 { 0.0 } else { v })
        })
        .collect();
    let subtitle = format!("[{}]", shown.join(", ")).replace(".000000", "");
    let fig = Scene3d {
        title: r.robot.name.clone(),
        subtitle: format!("q = {subtitle} (deg; m for prismatic joints)"),
        scene: &scene,
        camera,
        legend: Vec::new(),
        caption: String::new(),
    };
    draw(py, |figs| figs.scene(size, theme, &fig))
}

/// The options of a workspace figure from the Python keywords.
#[allow(clippy::too_many_arguments)] // the keywords of `Robot.workspace`, one by one
pub fn workspace_options(
    r: &CoreRobot,
    view: Option<&str>,
    point: &str,
    color_by: &str,
    samples: usize,
    seed: u64,
    size: [u32; 2],
    theme: Theme,
) -> PyResult<WsFigureOptions> {
    let planar = armlab::workspace::planar_frame(&r.robot, 0).is_some();
    let view = match view {
        Some("plane") | None if planar => WsView::Plane,
        Some("plane") | Some("top") | None => WsView::Top,
        Some("side") => WsView::Side,
        Some("3d") => WsView::ThreeD,
        Some("joint-space") | Some("joint_space") => WsView::JointSpace,
        Some(other) => {
            return Err(value_error(format!(
                "view = {other:?}: use \"plane\", \"top\", \"side\", \"3d\" or \"joint-space\""
            )));
        }
    };
    let color_by = match color_by {
        "posture" => ColorBy::Posture,
        "manipulability" => ColorBy::Manipulability,
        "dexterity" => ColorBy::Dexterity,
        "none" => ColorBy::None,
        other => {
            return Err(value_error(format!(
                "color_by = {other:?}: use \"posture\", \"manipulability\", \"dexterity\" or \
                 \"none\""
            )));
        }
    };
    let point = match point {
        "wrist-centre" | "wrist_centre" | "wrist-center" | "wrist_center" => {
            TrackedPoint::WristCentre
        }
        "flange" => TrackedPoint::Flange,
        other => {
            return Err(value_error(format!(
                "point = {other:?}: use \"wrist-centre\" or \"flange\""
            )));
        }
    };
    if samples == 0 || samples > 100_000_000 {
        return Err(value_error("samples must be between 1 and 100000000"));
    }
    Ok(WsFigureOptions {
        view,
        color_by,
        samples,
        seed,
        size,
        theme,
        end_effector: 0,
        point,
        caption: String::new(),
        text_scale: 1.0,
    })
}

/// Figure `name` of the excerpt (2.29, 2.30, ... as `armlab figure --list` lists them):
/// `(png, svg)`.
#[pyfunction]
#[pyo3(signature = (name, width=1200, height=900, theme="light"))]
pub fn textbook_figure(
    py: Python<'_>,
    name: &str,
    width: u32,
    height: u32,
    theme: &str,
) -> PyResult<Drawn> {
    let (size, theme) = (size(width, height)?, self::theme(theme)?);
    let name = name.to_string();
    draw(py, move |figs| {
        armlab::headless::textbook_figure(figs, &name, size, theme)
    })
}

/// A PDF of an SVG figure (fonts embedded as subsets, text kept as text).
#[pyfunction]
pub fn svg_to_pdf(svg: &str) -> PyResult<Vec<u8>> {
    armlab::figure::vector::svg_to_pdf(svg)
        .map_err(|e| FigureError::new_err(format!("cannot make the PDF: {e}")))
}
