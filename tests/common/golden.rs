//! Golden-image comparison with one stated tolerance.
//!
//! A pixel differs when any channel differs by more than [`CHANNEL_TOLERANCE`]; an image matches
//! when at most [`MAX_DIFFERING_FRACTION`] of its pixels differ (lavapipe is deterministic on
//! one machine; the slack absorbs Mesa/LLVM version differences in anti-aliased edges).
//! `UPDATE_SNAPSHOTS=1` rewrites the goldens; on failure `<name>.new.png` and `<name>.diff.png`
//! are written next to the golden (git-ignored).

use std::path::PathBuf;

/// Largest per-channel difference (0-255) that still counts as equal.
pub const CHANNEL_TOLERANCE: u8 = 24;
/// Largest fraction of differing pixels.
pub const MAX_DIFFERING_FRACTION: f64 = 0.005;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots")
}

/// Compares `img` with `tests/snapshots/<name>.png`.
pub fn assert_golden(name: &str, img: &image::RgbaImage) {
    let path = dir().join(format!("{name}.png"));
    if std::env::var_os("UPDATE_SNAPSHOTS").is_some() {
        img.save(&path).expect("write golden");
        return;
    }
    let golden = image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "golden {} missing ({e}); run with UPDATE_SNAPSHOTS=1 and look at it",
                path.display()
            )
        })
        .to_rgba8();
    assert_eq!(
        golden.dimensions(),
        img.dimensions(),
        "{name}: size differs from the golden"
    );
    let mut diff = image::RgbaImage::new(img.width(), img.height());
    let mut count = 0usize;
    for ((a, b), d) in img.pixels().zip(golden.pixels()).zip(diff.pixels_mut()) {
        let worst =
            a.0.iter()
                .zip(b.0.iter())
                .map(|(x, y)| x.abs_diff(*y))
                .max()
                .unwrap_or(0);
        if worst > CHANNEL_TOLERANCE {
            count += 1;
            *d = image::Rgba([255, 0, 0, 255]);
        } else {
            let g = (a.0[0] as u16 + a.0[1] as u16 + a.0[2] as u16) / 6;
            *d = image::Rgba([g as u8, g as u8, g as u8, 255]);
        }
    }
    let fraction = count as f64 / (img.width() as f64 * img.height() as f64);
    if fraction > MAX_DIFFERING_FRACTION {
        img.save(dir().join(format!("{name}.new.png"))).ok();
        diff.save(dir().join(format!("{name}.diff.png"))).ok();
        panic!(
            "{name}: {count} pixels ({:.3} %) differ from the golden by more than {CHANNEL_TOLERANCE} (allowed {:.3} %); see tests/snapshots/{name}.new.png and .diff.png",
            fraction * 100.0,
            MAX_DIFFERING_FRACTION * 100.0
        );
    }
}
