//! Recording the 3D view (the toolbar's Record button): the scene and camera of each frame the
//! view draws, kept at most [`FPS`] times a second, drawn again by the figures' renderer and
//! written as a GIF when the recording stops.

use crate::camera::Camera;
use crate::figure::Theme;
use crate::figure::figures::{Figures, Scene3d};
use crate::scene::Scene;

/// Frames kept per second (the GIF's rate).
pub const FPS: u32 = 10;

/// The most frames a recording keeps (30 s); later frames are dropped.
pub const MAX_FRAMES: usize = 300;

/// A recording in progress: what the 3D view showed, frame by frame.
#[derive(Debug)]
pub struct Recorder {
    frames: Vec<(Scene, Camera)>,
    /// The view's size at the first frame (px, even).
    size: [u32; 2],
    dark: bool,
    started: std::time::Instant,
    last: Option<f64>,
}

impl Default for Recorder {
    fn default() -> Self {
        Self {
            frames: Vec::new(),
            size: [0, 0],
            dark: false,
            started: std::time::Instant::now(),
            last: None,
        }
    }
}

impl Recorder {
    /// Keeps the view's scene and camera if a frame is due (1/[`FPS`] s after the last kept one);
    /// `size` is the view's size (px). Returns whether it was kept.
    pub fn offer(&mut self, scene: &Scene, camera: Camera, size: [u32; 2], dark: bool) -> bool {
        let now = self.started.elapsed().as_secs_f64();
        self.offer_at(scene, camera, size, dark, now)
    }

    /// [`Self::offer`] at time `now` (s since the recording started).
    pub fn offer_at(
        &mut self,
        scene: &Scene,
        camera: Camera,
        size: [u32; 2],
        dark: bool,
        now: f64,
    ) -> bool {
        let due = self
            .last
            .is_none_or(|t| now - t >= 1.0 / f64::from(FPS) - 1e-3);
        if !due || self.frames.len() >= MAX_FRAMES || size[0] < 16 || size[1] < 16 {
            return false;
        }
        if self.frames.is_empty() {
            self.size = size.map(|v| v & !1);
            self.dark = dark;
        }
        self.last = Some(now);
        self.frames.push((scene.clone(), camera));
        true
    }

    /// Frames kept so far.
    pub fn len(&self) -> usize {
        self.frames.len()
    }

    /// No frame kept yet.
    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    /// Draws the kept frames at the view's size (labels included) and encodes them as a
    /// looping GIF at [`FPS`].
    pub fn finish(self) -> Result<Vec<u8>, String> {
        if self.frames.is_empty() {
            return Err("nothing was recorded (the 3D view drew no frame)".into());
        }
        let mut figs = Figures::new().map_err(|e| e.to_string())?;
        let theme = if self.dark { Theme::Dark } else { Theme::Light };
        let mut images = Vec::with_capacity(self.frames.len());
        for (scene, camera) in &self.frames {
            let fig = Scene3d {
                title: String::new(),
                subtitle: String::new(),
                caption: String::new(),
                scene,
                camera: *camera,
                legend: Vec::new(),
            };
            images.push(
                figs.scene(self.size, theme, &fig)
                    .map_err(|e| e.to_string())?,
            );
        }
        let mut gif = Vec::new();
        crate::figure::animation::encode_gif(&images, FPS, &mut gif).map_err(|e| e.to_string())?;
        Ok(gif)
    }
}

/// The Record button: starts a recording in `slot`, or stops the one there and saves what was
/// recorded as `armlab-<stem>-<n>.gif` (a download in a browser, see
/// [`super::files::deliver_bytes`]); the message for the status bar either way.
pub fn toggle(
    slot: &mut Option<Recorder>,
    picker: &mut dyn super::file_picker::FilePicker,
    stem: &str,
) -> Result<String, String> {
    let Some(rec) = slot.take() else {
        *slot = Some(Recorder::default());
        return Ok("recording the 3D view: press Stop to save it as a GIF".into());
    };
    let n = rec.len();
    rec.finish()
        .and_then(|gif| super::files::deliver_bytes(picker, &gif, stem, ("gif", "image/gif")))
        .map(|m| format!("{m} ({n} frames)"))
        .map_err(|e| format!("recording failed: {e}"))
}
