//! Reachability-map figures (issue 49): the data each figure paints read off a small Puma map,
//! checked against the arrays indexed here (C order over (nx, ny, nz, N, R), the Fibonacci
//! directions from the formulas); the painted cells' colours against the colour map
//! written here; goldens of the three kinds; SVG and PNG files written through the command
//! line's flags, and bad flags refused naming the flag. The painting needs a graphics adapter
//! (Mesa's lavapipe on machines without a GPU).

use crate::common::golden::assert_golden;
use armlab::cli::reachability_figures::{MapFigureArgs, check_figure_args, write_figures};
use armlab::figure::Theme;
use armlab::figure::figures::Figures;
use armlab::figure::reachability::{
    MapFigureError, MapFigureKind, MapFigureSpec, SliceView, figure_data, paint, postures_size,
};
use armlab::kinematics::models::built_in;
use armlab::reachability::{MapControl, MapOptions, ReachabilityMap, compute_reachability};
use clap::Parser;
use std::f64::consts::PI;
use std::sync::OnceLock;

const N: usize = 20;
const R: usize = 2;

/// The Puma 560 at 20 cm, 20 directions, 2 rolls, and its base position.
fn puma_map() -> &'static (ReachabilityMap, [f64; 3]) {
    static MAP: OnceLock<(ReachabilityMap, [f64; 3])> = OnceLock::new();
    MAP.get_or_init(|| {
        let puma = built_in("puma560").expect("puma");
        let opts = MapOptions {
            voxel_m: 0.2,
            directions: N,
            rolls: R,
            ..MapOptions::default()
        };
        let map = compute_reachability(&puma, &opts, None, MapControl::default()).expect("map");
        let b = puma.base.translation.vector;
        (map, [b.x, b.y, b.z])
    })
}

/// Flat sample index of (i, j, k, d, r), C order, written here.
fn at(map: &ReachabilityMap, [i, j, k]: [usize; 3], d: usize, r: usize) -> usize {
    let [_, ny, nz] = map.grid.dims;
    (((i * ny + j) * nz + k) * N + d) * R + r
}

/// The Fibonacci direction i of n.
fn fibonacci(i: usize, n: usize) -> [f64; 3] {
    let z = 1.0 - (2 * i + 1) as f64 / n as f64;
    let rho = (1.0 - z * z).sqrt();
    let phi = i as f64 * PI * (3.0 - 5f64.sqrt());
    [rho * phi.cos(), rho * phi.sin(), z]
}

/// The voxel (i, j, k) of cell (u, w) of a slice of `view` at `layer`.
fn voxel_of(view: SliceView, layer: usize, u: usize, w: usize) -> [usize; 3] {
    match view {
        SliceView::Side => [u, layer, w],
        SliceView::Top => [u, w, layer],
    }
}

#[test]
fn the_index_slice_holds_each_voxels_fraction_of_samples_reached() {
    let (map, base) = puma_map();
    let [nx, ny, nz] = map.grid.dims;
    let data = figure_data(map, *base, &MapFigureSpec::default()).expect("data");
    // The default side view is cut through the base: the layer whose cell holds its y.
    let j = ((base[1] - map.grid.origin[1]) / 0.2 + 0.5).floor() as usize;
    assert_eq!(data.slice.layer, j);
    assert!((data.slice.plane_m - (map.grid.origin[1] + 0.2 * j as f64)).abs() < 1e-12);
    assert_eq!(data.slice.dims, [nx, nz]);
    assert!(data.along.is_empty() && data.posture_rolls.is_empty());
    let mut reached_cells = 0;
    for w in 0..nz {
        for u in 0..nx {
            let v = voxel_of(SliceView::Side, j, u, w);
            let count = (0..N)
                .flat_map(|d| (0..R).map(move |r| (d, r)))
                .filter(|&(d, r)| map.reachable[at(map, v, d, r)])
                .count();
            let want = count as f64 / (N * R) as f64;
            assert_eq!(data.index[w * nx + u], want, "cell ({u}, {w})");
            reached_cells += usize::from(count > 0);
        }
    }
    assert!(reached_cells > 10, "{reached_cells} cells reached");
    // The cells' outer edges.
    let g = &map.grid;
    let want = [
        g.origin[0] - 0.1,
        g.origin[0] + 0.2 * (nx as f64 - 0.5),
        g.origin[2] - 0.1,
        g.origin[2] + 0.2 * (nz as f64 - 0.5),
    ];
    for (a, b) in data.slice.bounds.iter().zip(want) {
        assert!((a - b).abs() < 1e-12, "{:?} vs {want:?}", data.slice.bounds);
    }
    // The figure shows every reached cell of every layer, and the base.
    let e = data.extent;
    for v in 0..nx * ny * nz {
        if map.reachable[v * N * R..(v + 1) * N * R].iter().any(|&x| x) {
            let (i, k) = (v / (ny * nz), v % nz);
            let (x, z) = (g.origin[0] + 0.2 * i as f64, g.origin[2] + 0.2 * k as f64);
            assert!(e[0] <= x - 0.1 && x + 0.1 <= e[1] && e[2] <= z - 0.1 && z + 0.1 <= e[3]);
        }
    }
    assert!(e[0] <= base[0] && base[0] <= e[1] && e[2] <= base[2] && base[2] <= e[3]);
}

#[test]
fn the_direction_slice_counts_the_rolls_reached_along_the_nearest_sample_direction() {
    let (map, base) = puma_map();
    let [nx, ny, nz] = map.grid.dims;
    for asked in [[0.0, 0.0, -1.0], [1.0, 0.2, 0.1], [0.0, -3.0, 0.5]] {
        let spec = MapFigureSpec {
            kind: MapFigureKind::Direction,
            view: SliceView::Top,
            slice_m: None,
            direction: asked,
        };
        let data = figure_data(map, *base, &spec).expect("data");
        // The nearest direction, by brute force over the formulas.
        let norm = asked.iter().map(|v| v * v).sum::<f64>().sqrt();
        let cos = |i: usize| {
            let d = fibonacci(i, N);
            (d[0] * asked[0] + d[1] * asked[1] + d[2] * asked[2]) / norm
        };
        let best = (0..N).max_by(|&a, &b| cos(a).total_cmp(&cos(b))).unwrap();
        let chosen = data.direction.expect("a direction");
        assert_eq!(chosen.index, best, "asked {asked:?}");
        assert!((chosen.angle_rad - cos(best).acos()).abs() < 1e-12);
        // The default top layer: where the rolls reached along it add up to the most.
        let along = |v: [usize; 3]| {
            (0..R)
                .filter(|&r| map.reachable[at(map, v, best, r)])
                .count()
        };
        let sums: Vec<usize> = (0..nz)
            .map(|k| {
                (0..nx)
                    .flat_map(|i| (0..ny).map(move |j| [i, j, k]))
                    .map(along)
                    .sum()
            })
            .collect();
        let top = sums.iter().max().unwrap();
        assert_eq!(sums[data.slice.layer], *top, "{sums:?}");
        assert_eq!(data.slice.dims, [nx, ny]);
        for w in 0..ny {
            for u in 0..nx {
                let v = voxel_of(SliceView::Top, data.slice.layer, u, w);
                assert_eq!(
                    usize::from(data.along[w * nx + u]),
                    along(v),
                    "cell ({u}, {w})"
                );
            }
        }
    }
}

#[test]
fn the_posture_slice_counts_each_postures_rolls() {
    let (map, base) = puma_map();
    let [nx, _, nz] = map.grid.dims;
    let spec = MapFigureSpec {
        kind: MapFigureKind::Postures,
        view: SliceView::Side,
        slice_m: Some(0.1),
        direction: [0.0, 0.0, -1.0],
    };
    let data = figure_data(map, *base, &spec).expect("data");
    let j = ((0.1 - map.grid.origin[1]) / 0.2 + 0.5).floor() as usize;
    assert_eq!(data.slice.layer, j);
    let d = data.direction.expect("a direction").index;
    assert_eq!(
        d,
        N - 1,
        "the last Fibonacci direction is the one nearest straight down"
    );
    assert_eq!(data.posture_rolls.len(), 8);
    let mut seen = 0;
    for (b, cells) in data.posture_rolls.iter().enumerate() {
        for w in 0..nz {
            for u in 0..nx {
                let v = voxel_of(SliceView::Side, j, u, w);
                let want = (0..R)
                    .filter(|&r| map.postures[at(map, v, d, r)] >> b & 1 == 1)
                    .count();
                assert_eq!(
                    usize::from(cells[w * nx + u]),
                    want,
                    "bit {b} cell ({u}, {w})"
                );
                seen += want;
            }
        }
    }
    assert!(seen > 0);
}

#[test]
fn bad_slices_and_directions_are_refused() {
    let (map, base) = puma_map();
    let g = &map.grid;
    let top = g.origin[2] + 0.2 * (g.dims[2] as f64 - 0.5);
    let spec = MapFigureSpec {
        view: SliceView::Top,
        slice_m: Some(top + 0.01),
        ..MapFigureSpec::default()
    };
    match figure_data(map, *base, &spec) {
        Err(e @ MapFigureError::SliceOutside { axis: 'z', .. }) => {
            let text = e.to_string();
            assert!(text.contains(&format!("{:.3}", top)), "{text}");
        }
        other => panic!("{other:?}"),
    }
    // Just inside the last cell's edge is its layer.
    let inside = MapFigureSpec {
        slice_m: Some(top - 1e-6),
        ..spec
    };
    assert_eq!(
        figure_data(map, *base, &inside).unwrap().slice.layer,
        g.dims[2] - 1
    );
    let zero = MapFigureSpec {
        kind: MapFigureKind::Direction,
        direction: [0.0; 3],
        ..MapFigureSpec::default()
    };
    assert!(matches!(
        figure_data(map, *base, &zero),
        Err(MapFigureError::ZeroDirection { .. })
    ));
}

/// The colour map (viridis-like) at t in [0, 1], from its five stops.
fn viridis(t: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 5] = [
        [68.0, 1.0, 84.0],
        [59.0, 82.0, 139.0],
        [33.0, 145.0, 140.0],
        [94.0, 201.0, 98.0],
        [253.0, 231.0, 37.0],
    ];
    let x = t.clamp(0.0, 1.0) * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f64;
    std::array::from_fn(|k| (STOPS[i][k] + (STOPS[i + 1][k] - STOPS[i][k]) * f).round() as u8)
}

#[test]
fn index_cells_are_painted_in_the_colour_of_their_index_where_the_data_lie() {
    let (map, base) = puma_map();
    let data = figure_data(map, *base, &MapFigureSpec::default()).expect("data");
    let mut figs = Figures::new().unwrap_or_else(|e| panic!("{e}"));
    let fig = paint(&mut figs, map, &data, [800, 600], Theme::Light).expect("painted");
    assert_golden("reachability_puma560_index_side", &fig.image);
    let frame = fig.frames[0];
    let [l, t, r, b] = frame.rect_px;
    let [x0, x1, y0, y1] = frame.bounds;
    let [nx, nz] = data.slice.dims;
    let g = &map.grid;
    // The base marker and the reach circle are drawn over the cells: skip cells they cross.
    let (reach, rc) = (map.reach_m, map.reach_centre);
    let (mut checked, mut coloured) = (0, 0);
    for w in 0..nz {
        for u in 0..nx {
            let (x, z) = (g.origin[0] + 0.2 * u as f64, g.origin[2] + 0.2 * w as f64);
            let near_base = (x - base[0]).hypot(z - base[2]) < 0.15;
            let dy = data.slice.plane_m - rc[1];
            let circle = (reach * reach - dy * dy).max(0.0).sqrt();
            let on_circle = ((x - rc[0]).hypot(z - rc[2]) - circle).abs() < 0.15;
            if near_base || on_circle {
                continue;
            }
            // The grid's lines cross the cells: of five points in the cell (its centre and
            // four towards its corners), at least three show the cell's own colour.
            let pixels: Vec<[u8; 4]> = [
                (0.0, 0.0),
                (-0.3, -0.3),
                (0.3, -0.3),
                (-0.3, 0.3),
                (0.3, 0.3),
            ]
            .iter()
            .map(|(dx, dz)| {
                let (x, z) = (x + 0.2 * dx, z + 0.2 * dz);
                let px = l as f64 + (x - x0) / (x1 - x0) * (r - l) as f64;
                let py = b as f64 - (z - y0) / (y1 - y0) * (b - t) as f64;
                fig.image.get_pixel(px.round() as u32, py.round() as u32).0
            })
            .collect();
            let index = data.index[w * nx + u];
            let matching = if index > 0.0 {
                coloured += 1;
                let want = viridis(index);
                let near = |p: &&[u8; 4]| (0..3).all(|k| p[k].abs_diff(want[k]) <= 2);
                pixels.iter().filter(near).count()
            } else {
                pixels
                    .iter()
                    .filter(|p| p[..3].iter().all(|&c| c > 200))
                    .count()
            };
            assert!(matching >= 3, "cell ({u}, {w}) index {index}: {pixels:?}");
            checked += 1;
        }
    }
    assert!(
        coloured > 10 && checked > coloured,
        "{coloured} of {checked}"
    );
}

#[test]
fn direction_and_posture_figures_match_their_goldens() {
    let (map, base) = puma_map();
    let mut figs = Figures::new().unwrap_or_else(|e| panic!("{e}"));
    let down = MapFigureSpec {
        kind: MapFigureKind::Direction,
        view: SliceView::Top,
        ..MapFigureSpec::default()
    };
    let data = figure_data(map, *base, &down).expect("data");
    let fig = paint(&mut figs, map, &data, [800, 600], Theme::Light).expect("painted");
    assert_golden("reachability_puma560_down_top", &fig.image);
    let postures = MapFigureSpec {
        kind: MapFigureKind::Postures,
        ..down
    };
    let data = figure_data(map, *base, &postures).expect("data");
    let size = postures_size(map);
    assert_eq!(
        size,
        [1600, 300 + 800],
        "8 postures: 4 x 2 panels of 400 px under a header"
    );
    let mut figs = Figures::new().unwrap_or_else(|e| panic!("{e}"));
    let fig = paint(&mut figs, map, &data, size, Theme::Light).expect("painted");
    assert_eq!(fig.frames.len(), 8);
    // Each panel's frame lies in its own panel.
    for (b, f) in fig.frames.iter().enumerate() {
        let (col, row) = ((b % 4) as f32, (b / 4) as f32);
        let [l, t, r, bt] = f.rect_px;
        assert!(
            l >= col * 400.0 && r <= (col + 1.0) * 400.0,
            "panel {b}: {l} {r}"
        );
        assert!(t >= 300.0 + row * 400.0 && bt <= 300.0 + (row + 1.0) * 400.0);
    }
    assert_golden("reachability_puma560_postures_down_top", &fig.image);
}

/// `armlab reachability`'s figure flags, parsed as its command line parses them.
#[derive(Parser)]
struct Flags {
    #[command(flatten)]
    figures: MapFigureArgs,
}

fn flags(args: &[&str]) -> MapFigureArgs {
    Flags::try_parse_from(std::iter::once("armlab").chain(args.iter().copied()))
        .unwrap_or_else(|e| panic!("{args:?}: {e}"))
        .figures
}

#[test]
fn figure_files_are_written_by_extension() {
    let (map, base) = puma_map();
    let dir = std::env::temp_dir().join(format!("armlab-reach-figs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (png, svg) = (dir.join("index.png"), dir.join("down.svg"));
    let args = flags(&[
        "--figure",
        png.to_str().unwrap(),
        "--figure",
        svg.to_str().unwrap(),
        "--figure-kind",
        "index",
        "--figure-kind",
        "direction",
        "--view",
        "top",
        "--direction",
        "0,0,-1",
        "--figure-size",
        "640x480",
    ]);
    let written = write_figures(map, *base, &args).expect("written");
    assert_eq!(written, vec![png.clone(), svg.clone()]);
    let img = image::open(&png).expect("a PNG").to_rgba8();
    assert_eq!(img.dimensions(), (640, 480));
    let text = std::fs::read_to_string(&svg).expect("an SVG");
    armlab::figure::vector::parse_svg(&text).expect("the SVG parses");
    assert!(
        text.contains("Where the Puma 560 can point along d_19"),
        "title"
    );
    let angle = (-fibonacci(N - 1, N)[2]).acos().to_degrees();
    assert!(
        text.contains(&format!("{angle:.1}°")),
        "the angle from straight down"
    );
    assert!(text.contains("rolls reached about d_19"), "colour bar");
    assert!(
        text.contains("data:image/png;base64,"),
        "the cells embedded"
    );
    // A posture map's panels are composed into one SVG page: every posture's panel is there.
    let postures = dir.join("postures.svg");
    let args = flags(&[
        "--figure",
        postures.to_str().unwrap(),
        "--figure-kind",
        "postures",
    ]);
    write_figures(map, *base, &args).expect("written");
    let text = std::fs::read_to_string(&postures).expect("an SVG");
    armlab::figure::vector::parse_svg(&text).expect("the SVG parses");
    assert!(text.contains("width=\"1600\" height=\"1100\""));
    for name in &map.posture_names {
        assert!(
            text.contains(&format!(">{name}</text>")),
            "the panel of {name}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_figure_flags_are_refused_naming_the_flag() {
    let (map, _) = puma_map();
    let bad = |args: &[&str]| {
        check_figure_args(&flags(args), Some(&map.grid))
            .expect_err("refused")
            .to_string()
    };
    let e = bad(&[
        "--figure", "a.png", "--figure", "b.png", "--view", "side", "--view", "top", "--view",
        "top",
    ]);
    assert!(
        e.contains("--view is given 3 times for 2 --figure files"),
        "{e}"
    );
    let e = bad(&["--figure", "a.jpg"]);
    assert!(
        e.contains(".png, .svg or .pdf") && e.ends_with("a.jpg"),
        "{e}"
    );
    let e = bad(&["--view", "top"]);
    assert!(e.contains("--view is given without --figure"), "{e}");
    let e = bad(&["--figure", "a.png", "--view", "top", "--slice-m", "-9"]);
    assert!(e.contains("z = -9 m is outside the map's grid"), "{e}");
    let e = Flags::try_parse_from(["armlab", "--figure", "a.png", "--direction", "0,0,0"])
        .err()
        .expect("refused")
        .to_string();
    assert!(e.contains("has no length"), "{e}");
    let e = Flags::try_parse_from(["armlab", "--figure", "a.png", "--direction", "1,2"])
        .err()
        .expect("refused")
        .to_string();
    assert!(e.contains("is not X,Y,Z"), "{e}");
    // Good flags pass.
    check_figure_args(
        &flags(&["--figure", "a.PNG", "--figure", "b.svg", "--slice-m", "0.1"]),
        Some(&map.grid),
    )
    .expect("accepted");
}
