//! The base placement heat map (issue 49): at each base position of the floor grid, the best
//! fraction of the task poses reached over the yaws, coloured from dark (none) to yellow (all),
//! with axes in metres, the tasks' positions marked (named, or numbered in file order when a
//! name is longer than 4 characters), and the best placements marked (ranked),
//! the best with an arrow along its yaw (the base's x axis). Positions whose base hits an obstacle
//! at every yaw are grey. Paints the [`PlacementMap`] it is handed
//! ([`crate::reachability::place()`] computes it).

use super::figures::Figures;
use super::palette::{UNSURE_GREY, c32, sequential};
use super::plot2d::{ColorBar, Curve, Plot2d};
use super::{FigureError, Theme};
use crate::reachability::PlacementMap;
use egui::Color32;
use std::f64::consts::TAU;

/// Colour of the best placements' marks (vermillion, colour-blind safe).
const BEST: [u8; 3] = [213, 94, 0];

/// The plot, the heat raster and the bounds the raster covers (`[x0, x1, y0, y1]`, m: the grid
/// cells, each `step` wide around its base position).
pub fn placement_plot(map: &PlacementMap, title: &str) -> (Plot2d, egui::ColorImage, [f64; 4]) {
    let g = &map.grid;
    let (nx, ny) = (g.x.len(), g.y.len());
    let half = 0.5 * g.step;
    let cells = [
        g.x[0] - half,
        g.x[nx - 1] + half,
        g.y[0] - half,
        g.y[ny - 1] + half,
    ];
    let heat = map.heat();
    let mut img = egui::ColorImage::new([nx, ny], vec![Color32::TRANSPARENT; nx * ny]);
    let mut blocked_anywhere = false;
    for i in 0..nx {
        for j in 0..ny {
            let all_blocked =
                (0..g.yaw.len()).all(|k| map.blocked.get(g.index(i, j, k)).copied() == Some(true));
            blocked_anywhere |= all_blocked;
            let c = if all_blocked {
                UNSURE_GREY
            } else {
                sequential(heat[i * ny + j] as f32)
            };
            // Image rows go down, y goes up.
            img.pixels[(ny - 1 - j) * nx + i] = c32(c);
        }
    }
    let span = (cells[1] - cells[0]).max(cells[3] - cells[2]);
    let mut bounds = cells;
    for t in &map.tasks {
        let p = t.world_from_tool.translation.vector;
        bounds = [
            bounds[0].min(p.x - 0.05 * span),
            bounds[1].max(p.x + 0.05 * span),
            bounds[2].min(p.y - 0.05 * span),
            bounds[3].max(p.y + 0.05 * span),
        ];
    }
    let mut plot = Plot2d {
        title: title.into(),
        subtitle: subtitle(map),
        x_label: "x [m]".into(),
        y_label: "y [m]".into(),
        bounds,
        equal_aspect: true,
        colorbar: Some(ColorBar {
            label: format!(
                "fraction of the {} tasks reached, best over {} yaws (sequential map, dark to \
                 yellow)",
                map.tasks.len(),
                g.yaw.len()
            ),
            min: 0.0,
            max: 1.0,
            colors: (0..64).map(|k| c32(sequential(k as f32 / 63.0))).collect(),
        }),
        ..Plot2d::default()
    };
    if blocked_anywhere {
        plot.legend.push((
            "base hits an obstacle at every yaw".into(),
            c32(UNSURE_GREY),
        ));
    }
    mark_tasks(map, span, &mut plot);
    mark_best(map, span, &mut plot);
    (plot, img, cells)
}

/// One line under the title: the grid, the solver and the best placement.
fn subtitle(map: &PlacementMap) -> String {
    let g = &map.grid;
    let best = match map.best.first() {
        Some(b) => format!(
            "best: x {:.3} m, y {:.3} m, yaw {:.1} deg, {} of {} tasks",
            b.detail.x,
            b.detail.y,
            b.detail.yaw.to_degrees(),
            b.reached,
            map.tasks.len()
        ),
        None => "no base position reaches any task".into(),
    };
    format!(
        "{} x {} base positions at {} m, {} yaws, {}{}; {best}",
        g.x.len(),
        g.y.len(),
        g.step,
        g.yaw.len(),
        map.solver,
        if map.collisions {
            ", collisions checked"
        } else {
            ""
        }
    )
}

/// A cross at each task's position (white under black, seen on any colour), labelled with its
/// name when every name is short (at most 4 characters), else with its number in the file
/// (1-based), which the text report and the JSON also give.
fn mark_tasks(map: &PlacementMap, span: f64, plot: &mut Plot2d) {
    let r = 0.012 * span;
    let short = map.tasks.iter().all(|t| t.name.chars().count() <= 4);
    for (k, t) in map.tasks.iter().enumerate() {
        let p = t.world_from_tool.translation.vector;
        for (color, width) in [(Color32::WHITE, 3.5), (Color32::BLACK, 1.5)] {
            for (dx, dy) in [(1.0, 1.0), (1.0, -1.0)] {
                plot.curves.push(Curve {
                    name: (k == 0 && color == Color32::BLACK && dx * dy > 0.0)
                        .then(|| "task (tool position)".to_string()),
                    points: vec![[p.x - dx * r, p.y - dy * r], [p.x + dx * r, p.y + dy * r]],
                    color,
                    width,
                    class: "task",
                    ..Curve::default()
                });
            }
        }
        let label = if short {
            t.name.clone()
        } else {
            (k + 1).to_string()
        };
        plot.labels.push((label, [p.x + 1.6 * r, p.y + 1.6 * r]));
    }
}

/// The best placement: a ring and an arrow along its yaw; the next ones: small rings with their
/// rank.
fn mark_best(map: &PlacementMap, span: f64, plot: &mut Plot2d) {
    let ring = |c: [f64; 2], r: f64| -> Vec<[f64; 2]> {
        (0..=32)
            .map(|k| {
                let a = TAU * k as f64 / 32.0;
                [c[0] + r * a.cos(), c[1] + r * a.sin()]
            })
            .collect()
    };
    for (rank, b) in map.best.iter().enumerate().rev() {
        let c = [b.detail.x, b.detail.y];
        let r = if rank == 0 { 0.02 } else { 0.012 } * span;
        plot.curves.push(Curve {
            name: (rank == 0).then(|| "best placement, arrow: its yaw".to_string()),
            points: ring(c, r),
            color: c32(BEST),
            width: if rank == 0 { 3.0 } else { 2.0 },
            class: "placement",
            ..Curve::default()
        });
        if rank > 0 {
            plot.labels
                .push((format!("{}", rank + 1), [c[0] + r, c[1] - 2.0 * r]));
            continue;
        }
        let (s, co) = b.detail.yaw.sin_cos();
        let len = 0.1 * span;
        let tip = [c[0] + len * co, c[1] + len * s];
        let head = 0.025 * span;
        let back = |turn: f64| {
            let (s2, c2) = (b.detail.yaw + std::f64::consts::PI + turn).sin_cos();
            [tip[0] + head * c2, tip[1] + head * s2]
        };
        for points in [vec![c, tip], vec![back(0.45), tip, back(-0.45)]] {
            plot.curves.push(Curve {
                points,
                color: c32(BEST),
                width: 3.0,
                class: "placement",
                ..Curve::default()
            });
        }
    }
}

/// Renders the heat map of `map` to an image of `size` pixels (and, when `figures` captures
/// vectors, its SVG).
pub fn placement_figure(
    figures: &mut Figures,
    map: &PlacementMap,
    title: &str,
    size: [u32; 2],
    theme: Theme,
) -> Result<image::RgbaImage, FigureError> {
    let (plot, img, cells) = placement_plot(map, title);
    Ok(figures.plot_at(size, theme, &plot, Some((img, cells)))?.0)
}
