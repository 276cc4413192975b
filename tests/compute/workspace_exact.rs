//! The exact planar workspace (Sect. 2.10.1, Problem 2.17) against computations written here,
//! independent of the library's: the two-link areas in closed form, and for the three-link arm a
//! membership test that minimises the joint-limit violation over the free orientation phi
//! (textbook two-link IK of Sect. 2.12.1 for the wrist point, a scan of phi and golden-section
//! refinement), integrated over vertical lines whose section ends are found by bisection.

use armlab::kinematics::models::built_in;
use armlab::model_file::load_model_file;
use armlab::workspace::{ExactPlanar, RegionSet};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_3, PI, SQRT_2, TAU};
use std::path::PathBuf;

/// Problem 2.17: a = 0.5, 0.3, 0.2 m; |q1| <= pi/3, |q2| <= 2 pi/3, |q3| <= pi/2.
const A: [f64; 3] = [0.5, 0.3, 0.2];
const QM: [f64; 3] = [FRAC_PI_3, 2.0 * FRAC_PI_3, FRAC_PI_2];

fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(TAU) - PI
}

/// Largest joint-limit violation (rad) of the elbow branch `sign` (+1: s2 > 0, elbow down)
/// reaching `p` with the last link at angle phi.
fn violation(p: [f64; 2], phi: f64, sign: f64) -> f64 {
    let w = [p[0] - A[2] * phi.cos(), p[1] - A[2] * phi.sin()];
    let c2 = (w[0] * w[0] + w[1] * w[1] - A[0] * A[0] - A[1] * A[1]) / (2.0 * A[0] * A[1]);
    // Out of reach: the violation of the nearest stretched or folded arm, at least the excess,
    // so that the violation rises steadily past the edge of reach.
    let excess = (c2.abs() - 1.0).max(0.0);
    let c2 = c2.clamp(-1.0, 1.0);
    let s2 = sign * (1.0 - c2 * c2).sqrt();
    let q2 = s2.atan2(c2);
    let q1 = w[1].atan2(w[0]) - (A[1] * s2).atan2(A[0] + A[1] * c2);
    let q3 = wrap(phi - q1 - q2);
    let q1 = wrap(q1);
    let limits = (q1.abs() - QM[0])
        .max(q2.abs() - QM[1])
        .max(q3.abs() - QM[2]);
    if excess > 0.0 {
        limits.max(excess)
    } else {
        limits
    }
}

/// Smallest violation over phi: a scan of 192 values, then golden-section search around the
/// three lowest local minima of the scan.
fn min_violation(p: [f64; 2], sign: f64) -> f64 {
    const N: usize = 192;
    let h = TAU / N as f64;
    let v: Vec<f64> = (0..N).map(|k| violation(p, k as f64 * h, sign)).collect();
    let mut minima: Vec<(f64, f64)> = (0..N)
        .filter(|&k| v[k] <= v[(k + N - 1) % N] && v[k] <= v[(k + 1) % N])
        .map(|k| (v[k], k as f64 * h))
        .collect();
    minima.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut best = minima.first().map_or(f64::INFINITY, |m| m.0);
    for &(_, phi) in minima.iter().take(3) {
        let (mut a, mut b) = (phi - h, phi + h);
        let g = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..50 {
            let (c, d) = (b - g * (b - a), a + g * (b - a));
            if violation(p, c, sign) < violation(p, d, sign) {
                b = d;
            } else {
                a = c;
            }
        }
        best = best.min(violation(p, 0.5 * (a + b), sign));
    }
    best
}

fn reachable(p: [f64; 2]) -> bool {
    min_violation(p, 1.0) <= 0.0 || min_violation(p, -1.0) <= 0.0
}

/// The reachable area by vertical lines x = const (midpoint rule, `lines` lines over
/// [-0.4, 1.05]); on each line a scan every 0.02 m finds the section's intervals and bisection
/// their ends.
fn area_by_lines(lines: usize) -> f64 {
    let (x0, x1, y0, y1) = (-0.4, 1.05, -1.05, 1.05);
    let h = (x1 - x0) / lines as f64;
    let mut area = 0.0;
    for i in 0..lines {
        let x = x0 + (i as f64 + 0.5) * h;
        let steps = ((y1 - y0) / 0.02) as usize;
        let y_at = |k: usize| y0 + (y1 - y0) * k as f64 / steps as f64;
        let mut prev = reachable([x, y_at(0)]);
        let mut enter = y0;
        for k in 1..=steps {
            let now = reachable([x, y_at(k)]);
            if now != prev {
                let (mut a, mut b) = (y_at(k - 1), y_at(k));
                for _ in 0..34 {
                    let m = 0.5 * (a + b);
                    if reachable([x, m]) == prev {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                let y = 0.5 * (a + b);
                if now {
                    enter = y;
                } else {
                    area += (y - enter) * h;
                }
            }
            prev = now;
        }
    }
    area
}

#[test]
fn problem_2_17_area_against_an_independent_integration() {
    let e = ExactPlanar::new(&built_in("planar3").unwrap()).unwrap();
    let exact = e.region(RegionSet::Reachable).unwrap();
    let check = area_by_lines(1500);
    let rel = (exact.area - check).abs() / check;
    println!(
        "Problem 2.17: exact {:.8} m^2 (est. error {:.1e}), lines {check:.8} m^2, rel {rel:.2e}",
        exact.area, exact.error
    );
    assert!(rel < 1e-4, "exact {} vs independent {check}", exact.area);
    assert!(exact.error < 1e-6 * exact.area);
    // The posture areas are consistent: with one + with the other = union + both.
    let a = |s| e.region(s).unwrap().area;
    let lhs = a(RegionSet::Class(0)) + a(RegionSet::Class(1));
    let rhs = a(RegionSet::Reachable) + a(RegionSet::AllClasses);
    assert!((lhs - rhs).abs() < 1e-9, "{lhs} vs {rhs}");
    // Mirror symmetry of the limits: both postures reach the same area.
    assert!((a(RegionSet::Class(0)) - a(RegionSet::Class(1))).abs() < 1e-9);
}

/// Deterministic pseudo-random numbers in [0, 1).
fn lcg(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}

#[test]
fn problem_2_17_membership_and_classes_of_random_points() {
    let e = ExactPlanar::new(&built_in("planar3").unwrap()).unwrap();
    assert_eq!(e.class_names(), ["elbow down", "elbow up"]);
    let mut s = 7u64;
    let (mut decided, mut inside) = (0, 0);
    for _ in 0..4000 {
        let p = [-0.4 + 1.45 * lcg(&mut s), -1.05 + 2.1 * lcg(&mut s)];
        let (down, up) = (min_violation(p, 1.0), min_violation(p, -1.0));
        // Points within 1e-7 rad of a limit are too close to the boundary for the check.
        if down.abs() < 1e-7 || up.abs() < 1e-7 {
            continue;
        }
        decided += 1;
        let want = u8::from(down <= 0.0) | u8::from(up <= 0.0) << 1;
        let got = e.membership(p);
        assert_eq!(got.mask, want, "{p:?}: down {down}, up {up}");
        let d = e.signed_distance(p);
        assert_eq!(d > 0.0, want != 0, "{p:?}: distance {d}");
        inside += usize::from(want != 0);
    }
    assert!(decided > 3900 && inside > 1000, "{decided} {inside}");
}

#[test]
fn orientation_measure_is_the_length_of_the_feasible_phi_set() {
    let e = ExactPlanar::new(&built_in("planar3").unwrap()).unwrap();
    for p in [[0.6, 0.1], [0.3, 0.5], [0.75, -0.2], [0.1, -0.6]] {
        let n = 200_000;
        let hits = (0..n)
            .filter(|k| {
                let phi = (*k as f64 + 0.5) / n as f64 * TAU;
                violation(p, phi, 1.0) <= 0.0 || violation(p, phi, -1.0) <= 0.0
            })
            .count();
        let want = hits as f64 / n as f64 * TAU;
        let got = e.membership(p).orientations;
        assert!((got - want).abs() < 1e-4, "{p:?}: {got} vs {want}");
    }
}

/// The two-link arm a1 = a2 = 1, |q1| <= pi/2, |q2| <= 3 pi/4 (derivation in tests/compute/workspace.rs):
/// each posture pi (1 + sqrt2/2), both pi (1 + sqrt2/2) - (sqrt2/2 + 3 pi sqrt2/8), union the sum.
#[test]
fn two_link_exact_areas_equal_their_closed_forms() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/robots/planar2_limited.toml");
    let e = ExactPlanar::new(&load_model_file(&path).unwrap()).unwrap();
    let each = PI * (1.0 + SQRT_2 / 2.0);
    let i = SQRT_2 / 2.0 + 3.0 * PI * SQRT_2 / 8.0;
    for (set, want) in [
        (RegionSet::Reachable, each + i),
        (RegionSet::Class(0), each),
        (RegionSet::Class(1), each),
        (RegionSet::AllClasses, each - i),
    ] {
        let got = e.region(set).unwrap().area;
        assert!(
            (got - want).abs() < 1e-10 * want,
            "{set:?}: {got} vs {want}"
        );
    }
    // The full-range arm reaches the disk of radius 2 with both postures.
    let full = ExactPlanar::new(&built_in("planar2").unwrap()).unwrap();
    for r in full.regions() {
        assert!((r.area - 4.0 * PI).abs() < 1e-10, "{:?}: {}", r.set, r.area);
    }
    assert!((full.signed_distance([0.5, 0.0]) - 1.5).abs() < 1e-12);
    assert!((full.signed_distance([3.0, 0.0]) + 1.0).abs() < 1e-12);
}
