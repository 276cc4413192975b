//! Circular arcs in the plane and the arrangement that turns boundary candidates into the exact
//! boundary of a region: every candidate is split where it meets another, and each piece is kept
//! when the region lies on exactly one side of it (tested with the exact membership just inside
//! and just outside the piece's midpoint), oriented with the region on its left.

use std::f64::consts::TAU;

/// An arc of a circle (plane coordinates, m): the points `centre + radius (cos t, sin t)` for
/// `t` from `start` to `start + sweep` (rad; counter-clockwise when `sweep > 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// Centre (m).
    pub centre: [f64; 2],
    /// Radius (m).
    pub radius: f64,
    /// Angle of the first point (rad).
    pub start: f64,
    /// Signed angle swept (rad); the region bounded lies on the left of the direction of travel.
    pub sweep: f64,
}

impl Arc {
    /// The point at angle `t` (rad) of the circle.
    #[inline]
    pub fn at(&self, t: f64) -> [f64; 2] {
        let (s, c) = t.sin_cos();
        [
            self.centre[0] + self.radius * c,
            self.centre[1] + self.radius * s,
        ]
    }

    /// First point.
    pub fn first(&self) -> [f64; 2] {
        self.at(self.start)
    }

    /// Last point.
    pub fn last(&self) -> [f64; 2] {
        self.at(self.start + self.sweep)
    }

    /// Length (m).
    pub fn length(&self) -> f64 {
        self.radius * self.sweep.abs()
    }

    /// `1/2 * integral of (x dy - y dx)` along the arc (m^2): summed over a closed boundary
    /// with the region on the left, the region's area (Green's theorem).
    pub fn green(&self) -> f64 {
        let (t0, t1) = (self.start, self.start + self.sweep);
        let [cx, cy] = self.centre;
        let r = self.radius;
        0.5 * (r * cx * (t1.sin() - t0.sin()) - r * cy * (t1.cos() - t0.cos()) + r * r * (t1 - t0))
    }

    /// Distance (m) from `p` to the arc.
    pub fn distance(&self, p: [f64; 2]) -> f64 {
        let d = [p[0] - self.centre[0], p[1] - self.centre[1]];
        let rho = d[0].hypot(d[1]);
        let t = d[1].atan2(d[0]);
        let (lo, span) = if self.sweep >= 0.0 {
            (self.start, self.sweep)
        } else {
            (self.start + self.sweep, -self.sweep)
        };
        if (t - lo).rem_euclid(TAU) <= span {
            return (rho - self.radius).abs();
        }
        let dist = |q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
        dist(self.first()).min(dist(self.last()))
    }

    /// Points along the arc, at most `max_step` (m) apart (and at least 2).
    pub fn polyline(&self, max_step: f64) -> Vec<[f64; 2]> {
        let n = ((self.length() / max_step.max(1e-12)).ceil() as usize).clamp(1, 100_000);
        (0..=n)
            .map(|k| self.at(self.start + self.sweep * k as f64 / n as f64))
            .collect()
    }
}

/// A circle and the angular intervals of it that are candidates: `[a, b]` with `0 <= a < 2 pi`,
/// `a < b <= a + 2 pi` (rad).
#[derive(Debug, Clone)]
struct Circle {
    centre: [f64; 2],
    radius: f64,
    spans: Vec<[f64; 2]>,
}

/// Is `t` (rad) inside `[a, b]` modulo 2 pi, with `tol` slack?
fn on_span(t: f64, [a, b]: [f64; 2], tol: f64) -> bool {
    (t - a + tol).rem_euclid(TAU) <= b - a + 2.0 * tol
}

/// Merges candidate arcs lying on the same circle (centres and radii within `tol`, m).
fn circles(cands: &[Arc], tol: f64) -> Vec<Circle> {
    let mut out: Vec<Circle> = Vec::new();
    for a in cands {
        if a.radius <= tol || a.sweep == 0.0 {
            continue;
        }
        let (lo, span) = if a.sweep > 0.0 {
            (a.start, a.sweep)
        } else {
            (a.start + a.sweep, -a.sweep)
        };
        let span = if span >= TAU - 1e-12 {
            [0.0, TAU]
        } else {
            let s = lo.rem_euclid(TAU);
            [s, s + span]
        };
        let same = out.iter_mut().find(|c| {
            (c.centre[0] - a.centre[0]).hypot(c.centre[1] - a.centre[1]) <= tol
                && (c.radius - a.radius).abs() <= tol
        });
        match same {
            Some(c) => c.spans.push(span),
            None => out.push(Circle {
                centre: a.centre,
                radius: a.radius,
                spans: vec![span],
            }),
        }
    }
    for c in &mut out {
        c.spans = merge_spans(std::mem::take(&mut c.spans));
    }
    out
}

/// Union of angular intervals (rad), as disjoint intervals.
fn merge_spans(mut s: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    if s.iter().any(|x| x[1] - x[0] >= TAU - 1e-12) {
        return vec![[0.0, TAU]];
    }
    // Unroll to [0, 4 pi), merge on the line, then fold back.
    s.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let mut m: Vec<[f64; 2]> = Vec::new();
    for x in s {
        match m.last_mut() {
            Some(l) if x[0] <= l[1] + 1e-13 => l[1] = l[1].max(x[1]),
            _ => m.push(x),
        }
    }
    // An interval running past 2 pi may overlap the first ones.
    while m.len() > 1 {
        let last = *m.last().expect("non-empty");
        if last[1] - TAU + 1e-13 >= m[0][0] {
            let first = m.remove(0);
            let l = m.last_mut().expect("non-empty");
            l[1] = l[1].max(first[1] + TAU);
            if l[1] - l[0] >= TAU - 1e-12 {
                return vec![[0.0, TAU]];
            }
        } else {
            break;
        }
    }
    m
}

/// Angles (rad) on circle `a` of its intersections with circle `b`.
fn crossings(a: &Circle, b: &Circle) -> Vec<f64> {
    let d = [b.centre[0] - a.centre[0], b.centre[1] - a.centre[1]];
    let dist = d[0].hypot(d[1]);
    if dist <= 1e-15
        || dist > a.radius + b.radius + 1e-12
        || dist < (a.radius - b.radius).abs() - 1e-12
    {
        return Vec::new();
    }
    let base = d[1].atan2(d[0]);
    let c = ((a.radius * a.radius + dist * dist - b.radius * b.radius) / (2.0 * a.radius * dist))
        .clamp(-1.0, 1.0);
    let h = c.acos();
    if h < 1e-12 {
        vec![base]
    } else {
        vec![base + h, base - h]
    }
}

/// The exact boundary of a region among candidate arcs: the pieces with the region on exactly one
/// side, oriented counter-clockwise around the region. `inside` is the exact membership test;
/// `scale` (m) sets the tolerances (1e-9 of it to merge circles, 1e-8 of it for the side tests).
pub(crate) fn boundary(cands: &[Arc], scale: f64, inside: &dyn Fn([f64; 2]) -> bool) -> Vec<Arc> {
    let cs = circles(cands, 1e-9 * scale);
    let mut out = Vec::new();
    for (i, c) in cs.iter().enumerate() {
        let mut cuts: Vec<f64> = Vec::new();
        for (j, o) in cs.iter().enumerate() {
            if i == j {
                continue;
            }
            for t in crossings(c, o) {
                if o.spans.iter().any(|&s| {
                    let to = [
                        c.centre[0] + c.radius * t.cos() - o.centre[0],
                        c.centre[1] + c.radius * t.sin() - o.centre[1],
                    ];
                    on_span(to[1].atan2(to[0]), s, 1e-12)
                }) {
                    cuts.push(t);
                }
            }
        }
        for &span in &c.spans {
            let mut ts: Vec<f64> = cuts
                .iter()
                .filter(|&&t| on_span(t, span, 0.0))
                .map(|&t| span[0] + (t - span[0]).rem_euclid(TAU))
                .filter(|&t| t > span[0] && t < span[1])
                .collect();
            ts.push(span[0]);
            ts.push(span[1]);
            ts.sort_by(f64::total_cmp);
            ts.dedup_by(|a, b| (*a - *b).abs() < 1e-13);
            for w in ts.windows(2) {
                if let Some(a) = classify(c, w[0], w[1], scale, inside) {
                    out.push(a);
                }
            }
        }
    }
    out
}

/// The piece `[t0, t1]` of circle `c` as a boundary arc with the region on its left, or `None`
/// when the region is on both sides or on neither.
fn classify(
    c: &Circle,
    t0: f64,
    t1: f64,
    scale: f64,
    inside: &dyn Fn([f64; 2]) -> bool,
) -> Option<Arc> {
    let tm = 0.5 * (t0 + t1);
    let chord = c.radius * (t1 - t0);
    let eps = (1e-8 * scale).min(0.05 * chord).min(0.5 * c.radius);
    if eps <= 0.0 {
        return None;
    }
    let (s, co) = tm.sin_cos();
    let at = |r: f64| [c.centre[0] + r * co, c.centre[1] + r * s];
    let (inner, outer) = (inside(at(c.radius - eps)), inside(at(c.radius + eps)));
    if inner == outer {
        return None;
    }
    // Counter-clockwise about the centre has the centre side on the left.
    let (start, sweep) = if inner { (t0, t1 - t0) } else { (t1, t0 - t1) };
    Some(Arc {
        centre: c.centre,
        radius: c.radius,
        start,
        sweep,
    })
}

/// How well the pieces close into loops: the largest distance (m) from a piece's end to the
/// nearest start of another piece (0 for a closed boundary up to rounding).
pub(crate) fn closure_gap(pieces: &[Arc]) -> f64 {
    let starts: Vec<[f64; 2]> = pieces.iter().map(Arc::first).collect();
    pieces
        .iter()
        .map(|p| {
            let e = p.last();
            starts
                .iter()
                .map(|s| (s[0] - e[0]).hypot(s[1] - e[1]))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}
