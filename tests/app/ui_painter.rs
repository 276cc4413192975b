//! armlab's UI painter on hand-made meshes: consecutive meshes are drawn in one call only
//! where that changes no pixel (no clip rectangle cuts them), and a mesh its clip rectangle
//! cuts is still cut. Needs a graphics adapter (Mesa's lavapipe without a GPU).

use armlab::render::Gpu;
use armlab::ui_render::offscreen::{FIGURE_FORMAT, canvas};
use armlab::ui_render::painter::{UiFrame, UiPainter};
use egui::epaint::{ClippedPrimitive, ImageDelta, Mesh, Primitive, TextureId};
use egui::{Color32, ColorImage, Rect, TextureOptions, pos2};

fn rect(min: [f32; 2], max: [f32; 2]) -> Rect {
    Rect::from_min_max(pos2(min[0], min[1]), pos2(max[0], max[1]))
}

/// A filled rectangle clipped to `clip`.
fn quad(r: Rect, color: Color32, clip: Rect) -> ClippedPrimitive {
    let mut mesh = Mesh::default();
    mesh.add_colored_rect(r, color);
    ClippedPrimitive {
        clip_rect: clip,
        primitive: Primitive::Mesh(mesh),
    }
}

/// At one and two pixels per point (a high-density screen).
#[test]
fn merged_draws_keep_every_clip_rectangle() {
    let gpu = Gpu::new_headless().unwrap_or_else(|e| panic!("{e}"));
    for scale in [1u32, 2] {
        paint_and_check(&gpu, scale);
    }
}

/// Paints four rectangles (64x64 points) at `scale` pixels per point and checks every pixel of
/// the points that matter.
fn paint_and_check(gpu: &Gpu, scale: u32) {
    let size = [64 * scale, 64 * scale];
    let (red, green, blue) = (Color32::RED, Color32::GREEN, Color32::BLUE);
    let everything = rect([0.0, 0.0], [64.0, 64.0]);
    let prims = vec![
        // Inside its clip rectangle.
        quad(rect([0.0, 0.0], [20.0, 20.0]), red, everything),
        // Cut: only [30, 40) x [30, 40) may be green.
        quad(
            rect([10.0, 10.0], [60.0, 60.0]),
            green,
            rect([30.0, 30.0], [40.0, 40.0]),
        ),
        // Inside (an unbounded clip rectangle), then inside exactly at its edges.
        quad(rect([40.0, 0.0], [60.0, 20.0]), blue, Rect::EVERYTHING),
        quad(
            rect([0.0, 40.0], [20.0, 60.0]),
            blue,
            rect([0.0, 40.0], [20.0, 60.0]),
        ),
    ];
    // egui's font texture, here one white texel (every uv reads white).
    let mut textures = egui::TexturesDelta::default();
    textures.set.insert(
        TextureId::default(),
        [ImageDelta::full(
            ColorImage::new([1, 1], vec![Color32::WHITE]),
            TextureOptions::NEAREST,
        )]
        .into_iter()
        .collect(),
    );
    let frame = UiFrame {
        prims,
        textures: std::sync::Mutex::new(textures),
        size_px: size,
        pixels_per_point: scale as f32,
    };
    let texture = canvas(&gpu.device, size, true);
    let view = texture.create_view(&Default::default());
    let mut painter = UiPainter::new(&gpu.device, FIGURE_FORMAT);
    painter.render_frame(&gpu.device, &gpu.queue, &view, &frame, Color32::BLACK);
    // The cut mesh is a draw of its own; the two uncut blue ones after it share one.
    assert_eq!(painter.draw_calls(), 3);
    let image = armlab::render::read_texture_rgba(&gpu.device, &gpu.queue, &texture).unwrap();
    // The colour of every pixel of point (x, y).
    let at = |x: u32, y: u32| {
        let colours: Vec<Color32> = (0..scale * scale)
            .map(|k| {
                let p = image.get_pixel(x * scale + k % scale, y * scale + k / scale);
                Color32::from_rgba_premultiplied(p[0], p[1], p[2], p[3])
            })
            .collect();
        assert!(
            colours.iter().all(|c| *c == colours[0]),
            "point ({x}, {y}) at {scale} px/pt: {colours:?}"
        );
        colours[0]
    };
    assert_eq!(at(5, 5), red);
    assert_eq!(at(35, 35), green);
    assert_eq!(at(30, 30), green);
    assert_eq!(at(39, 39), green);
    // Outside the green mesh's clip rectangle, though inside the mesh.
    for (x, y) in [(25, 25), (29, 35), (40, 35), (35, 40), (50, 50), (15, 35)] {
        assert_eq!(at(x, y), Color32::BLACK, "({x}, {y}) at {scale} px/pt");
    }
    assert_eq!(at(50, 10), blue);
    assert_eq!(at(10, 50), blue);
    assert_eq!(at(19, 59), blue);
    assert_eq!(at(10, 62), Color32::BLACK);
}
