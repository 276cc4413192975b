//! Vector figures (`--out F.svg`, `--out F.pdf`): the SVG parses (usvg), its workspace
//! boundary is made of true arcs whose enclosed area, integrated here from the path commands,
//! equals the area computed here independently (polar integration of the closed-form reachable
//! angles) to 1e-6; text is text; the PDF parses, embeds its font, has selectable text, and
//! rendered by poppler (`pdftoppm`) it matches the PNG of the same figure.
//! Needs a graphics adapter (Mesa's lavapipe) and, for the PDF check, `poppler-utils`.

use std::path::{Path, PathBuf};
use std::process::Command;

fn armlab(args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .output()
        .expect("run armlab");
    assert!(
        o.status.success(),
        "armlab {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("armlab-vector-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The value of attribute `name` in an element's text.
fn attr<'a>(element: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = element.find(&key)? + key.len();
    let end = element[start..].find('"')? + start;
    Some(&element[start..end])
}

/// The `<path ...>` elements of class `class`.
fn paths_of_class<'a>(svg: &'a str, class: &str) -> Vec<&'a str> {
    let needle = format!("<path class=\"{class}\"");
    svg.match_indices(&needle)
        .map(|(i, _)| {
            let end = svg[i..].find("/>").unwrap() + i;
            &svg[i..end]
        })
        .collect()
}

/// `1/2 * integral of (x dy - y dx)` over an SVG path made of M, L and A commands (absolute),
/// the arcs taken from their endpoint parameters as the SVG specification (F.6.5) defines them.
fn green_of_path(d: &str) -> f64 {
    let mut tokens: Vec<String> = Vec::new();
    let mut cur = String::new();
    for ch in d.chars() {
        if ch.is_ascii_alphabetic() && ch != 'e' {
            if !cur.is_empty() {
                tokens.push(std::mem::take(&mut cur));
            }
            tokens.push(ch.to_string());
        } else if ch == ' ' || ch == ',' {
            if !cur.is_empty() {
                tokens.push(std::mem::take(&mut cur));
            }
        } else if ch == '-' && !cur.is_empty() && !cur.ends_with('e') {
            tokens.push(std::mem::take(&mut cur));
            cur.push(ch);
        } else {
            cur.push(ch);
        }
    }
    if !cur.is_empty() {
        tokens.push(cur);
    }
    let mut it = tokens.iter();
    let num =
        |it: &mut std::slice::Iter<'_, String>| -> f64 { it.next().unwrap().parse().unwrap() };
    let (mut x, mut y) = (0.0f64, 0.0f64);
    let mut total = 0.0;
    while let Some(cmd) = it.next() {
        match cmd.as_str() {
            "M" => {
                x = num(&mut it);
                y = num(&mut it);
            }
            "L" => {
                let (x1, y1) = (num(&mut it), num(&mut it));
                total += 0.5 * (x * y1 - y * x1);
                (x, y) = (x1, y1);
            }
            "A" => {
                let (rx, ry) = (num(&mut it), num(&mut it));
                let _rot = num(&mut it);
                let (large, sweep) = (num(&mut it) != 0.0, num(&mut it) != 0.0);
                let (x1, y1) = (num(&mut it), num(&mut it));
                assert!((rx - ry).abs() < 1e-5 * rx, "a circular arc: {rx} {ry}");
                let r = rx;
                // Centre from the endpoints (F.6.5.2 with phi = 0, rx = ry).
                let (mx, my) = (0.5 * (x - x1), 0.5 * (y - y1));
                let h2 = (r * r - mx * mx - my * my).max(0.0);
                let k = (h2 / (mx * mx + my * my)).sqrt() * if large == sweep { -1.0 } else { 1.0 };
                let (cx, cy) = (k * my + 0.5 * (x + x1), -k * mx + 0.5 * (y + y1));
                let t0 = (y - cy).atan2(x - cx);
                let mut dt = (y1 - cy).atan2(x1 - cx) - t0;
                // sweep = 1: increasing angle (clockwise on the page, y down).
                if sweep && dt < 0.0 {
                    dt += std::f64::consts::TAU;
                }
                if !sweep && dt > 0.0 {
                    dt -= std::f64::consts::TAU;
                }
                let t1 = t0 + dt;
                total += 0.5
                    * (r * cx * (t1.sin() - t0.sin()) - r * cy * (t1.cos() - t0.cos())
                        + r * r * dt);
                (x, y) = (x1, y1);
            }
            "Z" => {}
            other => panic!("unexpected path command {other} in {d}"),
        }
    }
    total
}

/// The area (m^2) enclosed by the `boundary` paths of a workspace SVG, back in plot units.
fn boundary_area(svg: &str) -> f64 {
    let paths = paths_of_class(svg, "boundary");
    assert!(!paths.is_empty(), "no boundary paths");
    let mut px2 = 0.0;
    let mut scale = 0.0;
    for p in &paths {
        let d = attr(p, "d").unwrap();
        assert!(
            !d.contains('L'),
            "the boundary is arcs, not a polyline: {d}"
        );
        assert!(d.contains('A'), "{d}");
        px2 += green_of_path(d);
        scale = area_scale(p);
    }
    // The page's y axis points down: a boundary with the region on its left in the plane has
    // it on its right on the page, so the page integral is minus the area.
    -px2 / scale
}

/// The reachable set of a two-link arm (lengths a1, a2, limits) by polar integration: at radius
/// r the elbow angle is +-acos(...), each within its limits gives an interval of polar angles
/// [q1_min + beta, q1_max + beta]; the measure of their union times r, integrated over r by
/// adaptive Simpson. Independent of armlab's arrangement of arcs.
fn two_link_area(a1: f64, a2: f64, q1: [f64; 2], q2: [f64; 2]) -> f64 {
    use std::f64::consts::TAU;
    let measure = |r: f64| -> f64 {
        let c = ((r * r - a1 * a1 - a2 * a2) / (2.0 * a1 * a2)).clamp(-1.0, 1.0);
        let e = c.acos();
        let mut ivs: Vec<[f64; 2]> = Vec::new();
        for q in [e, -e] {
            if q >= q2[0] && q <= q2[1] {
                let beta = (a2 * q.sin()).atan2(a1 + a2 * q.cos());
                ivs.push([q1[0] + beta, q1[1] + beta]);
            }
        }
        if e == 0.0 || (e - std::f64::consts::PI).abs() < 1e-15 {
            ivs.truncate(1);
        }
        // Union on the circle: sample-free, by unrolling onto [lo, lo + 2pi).
        if ivs.iter().any(|iv| iv[1] - iv[0] >= TAU) {
            return TAU;
        }
        match ivs.len() {
            0 => 0.0,
            1 => (ivs[0][1] - ivs[0][0]).min(TAU),
            _ => {
                let (a, b) = (ivs[0], ivs[1]);
                let la = (a[1] - a[0]).min(TAU);
                let lb = (b[1] - b[0]).min(TAU);
                // Overlap of two arcs on the circle: shift b by multiples of 2pi.
                let mut overlap = 0.0;
                for k in -2..=2 {
                    let s = k as f64 * TAU;
                    overlap += (a[1].min(b[1] + s) - a[0].max(b[0] + s)).max(0.0);
                }
                (la + lb - overlap).min(TAU)
            }
        }
    };
    let f = |r: f64| r * measure(r);
    /// Adaptive Simpson on [a, b] with f at a, the middle and b, and the whole-interval estimate.
    fn simpson(
        f: &dyn Fn(f64) -> f64,
        [a, b]: [f64; 2],
        [fa, fm, fb]: [f64; 3],
        whole: f64,
        tol: f64,
        depth: u32,
    ) -> f64 {
        let m = 0.5 * (a + b);
        let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
        let (flm, frm) = (f(lm), f(rm));
        let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
        let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
        if depth == 0 || (left + right - whole).abs() <= 15.0 * tol {
            return left + right + (left + right - whole) / 15.0;
        }
        simpson(f, [a, m], [fa, flm, fm], left, 0.5 * tol, depth - 1)
            + simpson(f, [m, b], [fm, frm, fb], right, 0.5 * tol, depth - 1)
    }
    let (lo, hi) = ((a1 - a2).abs(), a1 + a2);
    // Split where the elbow angle crosses a limit (kinks of the integrand).
    let mut cuts = vec![lo, hi];
    for q in [q2[0], q2[1], 0.0] {
        let r = (a1 * a1 + a2 * a2 + 2.0 * a1 * a2 * q.cos()).sqrt();
        if r > lo && r < hi {
            cuts.push(r);
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let (fa, fm, fb) = (f(a), f(0.5 * (a + b)), f(b));
            simpson(
                &f,
                [a, b],
                [fa, fm, fb],
                (b - a) / 6.0 * (fa + 4.0 * fm + fb),
                1e-13,
                40,
            )
        })
        .sum()
}

#[test]
fn the_independent_area_integral_knows_simple_cases() {
    // Full rotation: the annulus between |a1 - a2| and a1 + a2.
    let a = two_link_area(
        1.0,
        0.5,
        [-10.0, 10.0],
        [-std::f64::consts::PI, std::f64::consts::PI],
    );
    let exact = std::f64::consts::PI * (1.5f64.powi(2) - 0.5f64.powi(2));
    assert!((a - exact).abs() < 1e-9 * exact, "{a} vs {exact}");
    // One elbow side: the map is one-to-one, area = (q1 range) a1 a2 (cos q2min - cos q2max).
    let a = two_link_area(1.0, 0.7, [0.0, 1.0], [0.2, 1.3]);
    let exact = 1.0 * 0.7 * (0.2f64.cos() - 1.3f64.cos());
    assert!((a - exact).abs() < 1e-9 * exact, "{a} vs {exact}");
}

#[test]
fn workspace_svg_boundary_is_exact_arcs_enclosing_the_exact_area() {
    use std::f64::consts::PI;
    for (what, args, a1, a2, q1, q2) in [
        // Figs 2.29-2.30's arm: a1 = a2 = 1 m, -pi/2 <= q1 <= pi/2, -3pi/4 <= q2 <= pi/2.
        (
            "fig2.30",
            vec!["figure", "2.30"],
            1.0,
            1.0,
            [-PI / 2.0, PI / 2.0],
            [-0.75 * PI, PI / 2.0],
        ),
        (
            "planar2",
            vec!["workspace", "planar2"],
            1.0,
            1.0,
            [-PI, PI],
            [-PI, PI],
        ),
    ] {
        let path = tmp(&format!("{what}.svg"));
        let mut a: Vec<&str> = args.clone();
        let p = path.to_str().unwrap().to_string();
        a.extend(["--out", &p]);
        armlab(&a);
        let svg = std::fs::read_to_string(&path).unwrap();
        armlab::figure::vector::parse_svg(&svg).unwrap_or_else(|e| panic!("{what}: {e}"));
        let area = boundary_area(&svg);
        let exact = two_link_area(a1, a2, q1, q2);
        assert!(
            (area - exact).abs() <= 1e-6 * exact,
            "{what}: the SVG's boundary encloses {area} m^2, the exact area is {exact} m^2"
        );
        assert!(svg.len() <= 300_000, "{what}: {} bytes", svg.len());
    }
}

/// The area (m^2) of the filled region paths of class mask `mask` (`class="region"`).
fn region_area(svg: &str, mask: u8) -> f64 {
    let paths: Vec<&str> = paths_of_class(svg, "region")
        .into_iter()
        .filter(|p| attr(p, "data-mask") == Some(&mask.to_string()))
        .collect();
    assert_eq!(paths.len(), 1, "one region of mask {mask}");
    let d = attr(paths[0], "d").unwrap();
    assert!(d.contains('A') && d.ends_with('Z'), "{d}");
    // Closed loops of arcs (or, failing that, fans from the page's corner whose radial sides
    // cancel): Green's integral over them is the region's area (on the page, y down, with the
    // opposite sign); the scale is the boundary paths' frame and bounds.
    let scale = area_scale(paths_of_class(svg, "boundary")[0]);
    -green_of_path(&d.replace('Z', "")) / scale
}

/// Page px^2 per plot unit^2 of a tagged path, from its `data-frame` (px) and `data-bounds`.
fn area_scale(path: &str) -> f64 {
    let nums = |key: &str| -> Vec<f64> {
        attr(path, key)
            .unwrap()
            .split(' ')
            .map(|v| v.parse().unwrap())
            .collect()
    };
    let (f, b) = (nums("data-frame"), nums("data-bounds"));
    (f[2] - f[0]) / (b[1] - b[0]) * (f[3] - f[1]) / (b[3] - b[2])
}

/// The posture regions of an exact map are disjoint filled paths bounded by the exact arcs (no
/// raster): elbow down alone + elbow up alone + both = the reachable area.
#[test]
fn exact_regions_are_filled_arc_paths() {
    use std::f64::consts::PI;
    let path = tmp("fig230-fills.svg");
    armlab(&["figure", "2.30", "--out", path.to_str().unwrap()]);
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(
        !svg.contains("<image"),
        "the regions are vectors, not an embedded raster"
    );
    let (a, b, both) = (
        region_area(&svg, 1),
        region_area(&svg, 2),
        region_area(&svg, 3),
    );
    let exact = two_link_area(1.0, 1.0, [-PI / 2.0, PI / 2.0], [-0.75 * PI, PI / 2.0]);
    let union = a + b + both;
    assert!(
        (union - exact).abs() <= 1e-6 * exact,
        "{a} + {b} + {both} = {union}, the exact area is {exact}"
    );
    // Elbow down (q2 in [0, pi/2], alone or with elbow up) is one-to-one over its joint box:
    // (q1 range) a1 a2 (cos 0 - cos pi/2).
    let elbow_down = PI * (1.0 - (PI / 2.0).cos());
    assert!(
        (a + both - elbow_down).abs() < 1e-6 * elbow_down
            || (b + both - elbow_down).abs() < 1e-6 * elbow_down,
        "one class alone plus both is the elbow-down region ({elbow_down}): {a}, {b}, {both}"
    );
    assert!(a > 0.1 && b > 0.1 && both > 0.1, "{a}, {b}, {both}");
}

#[test]
fn problem_2_17_svg_has_arcs_and_text() {
    let path = tmp("p217.svg");
    armlab(&["figure", "problem-2.17", "--out", path.to_str().unwrap()]);
    let svg = std::fs::read_to_string(&path).unwrap();
    let tree = armlab::figure::vector::parse_svg(&svg).unwrap();
    assert_eq!(tree.size().width(), 1200.0);
    assert!(svg.contains(">Workspace of the three-link arm of Problem 2.17</text>"));
    assert!(svg.contains(">x [m] (base frame)</text>"));
    let boundary = paths_of_class(&svg, "boundary");
    assert!(boundary.len() >= 4, "{} boundary paths", boundary.len());
    // Dashed posture boundaries stay dashed arcs.
    let inner = paths_of_class(&svg, "posture-boundary");
    assert!(!inner.is_empty());
    assert!(
        inner
            .iter()
            .all(|p| attr(p, "stroke-dasharray").is_some() && attr(p, "d").unwrap().contains('A'))
    );
    // The reported exact area (the subtitle) is what the arcs enclose.
    let subtitle_area: f64 = svg
        .split("area ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.trim_end_matches("m²").parse().ok())
        .expect("the area in the subtitle");
    let area = boundary_area(&svg);
    assert!(
        (area - subtitle_area).abs() < 1e-4,
        "{area} vs {subtitle_area}"
    );
}

/// Mean absolute difference (0-255) of two same-size images after a 4x4 box average (text is
/// anti-aliased differently by egui and poppler; shapes and colours must agree).
fn blurred_difference(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    let (w, h) = a.dimensions();
    assert_eq!((w, h), b.dimensions());
    let mut total = 0.0;
    let mut n = 0.0;
    for by in 0..h / 4 {
        for bx in 0..w / 4 {
            for c in 0..3 {
                let mean = |img: &image::RgbaImage| -> f64 {
                    let mut s = 0.0;
                    for y in 0..4 {
                        for x in 0..4 {
                            s += f64::from(img.get_pixel(bx * 4 + x, by * 4 + y)[c]);
                        }
                    }
                    s / 16.0
                };
                total += (mean(a) - mean(b)).abs();
                n += 1.0;
            }
        }
    }
    total / n
}

fn pdftoppm(pdf: &Path, out_stem: &Path) -> image::RgbaImage {
    let o = Command::new("pdftoppm")
        .args(["-png", "-r", "72", "-singlefile"])
        .arg(pdf)
        .arg(out_stem)
        .output()
        .unwrap_or_else(|e| {
            panic!("pdftoppm could not run ({e}): install poppler-utils (apt-get install poppler-utils)")
        });
    assert!(
        o.status.success(),
        "pdftoppm: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let mut png = out_stem.as_os_str().to_owned();
    png.push(".png");
    image::open(PathBuf::from(png)).unwrap().to_rgba8()
}

#[test]
fn pdf_figures_parse_embed_their_font_and_match_the_png() {
    for (name, args) in [
        ("problem-2.17", vec!["figure", "problem-2.17"]),
        ("fig2.32", vec!["figure", "2.32"]),
    ] {
        let pdf = tmp(&format!("{name}.pdf"));
        let png = tmp(&format!("{name}.png"));
        for out in [&pdf, &png] {
            let mut a = args.clone();
            a.extend(["--out", out.to_str().unwrap()]);
            armlab(&a);
        }
        let bytes = std::fs::read(&pdf).unwrap();
        assert!(bytes.starts_with(b"%PDF-"), "{name}: not a PDF");
        let text = String::from_utf8_lossy(&bytes);
        assert!(text.contains("/FontFile2"), "{name}: the font is embedded");
        assert!(text.contains("Ubuntu-Light"), "{name}: egui's font");
        // Selectable text: poppler extracts the title.
        let o = Command::new("pdftotext")
            .arg(&pdf)
            .arg("-")
            .output()
            .expect("pdftotext (poppler-utils)");
        let extracted = String::from_utf8_lossy(&o.stdout);
        let title = if name == "fig2.32" {
            "Manipulator with spherical wrist"
        } else {
            "Workspace of the three-link arm"
        };
        assert!(extracted.contains(title), "{name}: {extracted}");
        let rendered = pdftoppm(&pdf, &tmp(&format!("{name}-pdf")));
        let reference = image::open(&png).unwrap().to_rgba8();
        let diff = blurred_difference(&rendered, &reference);
        eprintln!("{name}: PDF vs PNG, mean difference {diff:.3}/255 after a 4x4 average");
        // Stated tolerance: 4/255 mean difference after a 4x4 average.
        assert!(
            diff < 4.0,
            "{name}: the PDF differs from the PNG by {diff:.2}/255 on average"
        );
    }
}
