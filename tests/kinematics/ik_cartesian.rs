//! Issue 27, prismatic joints where a family allows them: the Cartesian (gantry) arm, three
//! prismatic joints whose axes are not in one plane, alone (position target, one solution) and
//! with a spherical wrist (pose target, two: the wrist's flip). Checked against computations
//! written here: a forward kinematics of the DH rows multiplied out in the test, and a
//! brute-force Newton search over all six joints that finds no solution the solver missed.

use crate::common;

use common::closed_form::*;
use nalgebra::Matrix4;
use rand::{Rng, SeedableRng};

/// A prismatic row: theta and alpha constant, d = q + offset, with limits (m).
fn pr(a: f64, alpha: f64, theta: f64, offset: f64, limits: [f64; 2]) -> Row {
    dj(
        P,
        DhRow {
            a,
            alpha,
            d: 0.0,
            theta,
        },
        offset,
        limits,
    )
}

/// (a, alpha, theta, offset, limits) of three prismatic rows: a gantry whose second axis is
/// tilted (60 degrees from the first instead of 90) and whose links have lengths, so that
/// nothing is axis-aligned.
type Prismatic = (f64, f64, f64, f64, [f64; 2]);
const GANTRY: [Prismatic; 3] = [
    (0.1, -PI / 3.0, 0.0, 0.3, [0.0, 1.2]),
    (0.05, -FRAC_PI_2, -FRAC_PI_2, 0.2, [0.0, 1.0]),
    (0.0, 0.0, 0.4, 0.1, [0.0, 0.8]),
];

fn gantry(wrist: bool) -> Robot {
    let mut rows: Vec<Row> = GANTRY
        .iter()
        .map(|&(a, alpha, theta, off, lim)| pr(a, alpha, theta, off, lim))
        .collect();
    if wrist {
        rows.push(rv(0.0, -FRAC_PI_2, 0.15, 0.0));
        rows.push(rv(0.0, FRAC_PI_2, 0.0, 0.0));
        rows.push(rv(0.0, 0.0, 0.12, 0.0));
    }
    Robot::from_dh(
        "gantry",
        Convention::Standard,
        &rows,
        Pose::translation(0.2, -0.1, 0.3) * rot_z(0.4),
        Pose::translation(0.0, 0.02, 0.05) * rot_y(0.2),
    )
    .unwrap()
}

/// The standard DH matrix `Rz(theta) Tz(d) Tx(a) Rx(alpha)`, written out (2.52).
fn dh(a: f64, alpha: f64, d: f64, theta: f64) -> Matrix4<f64> {
    let (st, ct) = theta.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    Matrix4::new(
        ct,
        -st * ca,
        st * sa,
        a * ct,
        st,
        ct * ca,
        -ct * sa,
        a * st,
        0.0,
        sa,
        ca,
        d,
        0.0,
        0.0,
        0.0,
        1.0,
    )
}

/// The gantry's forward kinematics multiplied out here, base and tool included.
fn fk_here(q: &[f64]) -> Matrix4<f64> {
    let base = (Pose::translation(0.2, -0.1, 0.3) * rot_z(0.4)).to_homogeneous();
    let tool = (Pose::translation(0.0, 0.02, 0.05) * rot_y(0.2)).to_homogeneous();
    let mut t = base;
    for (i, &(a, alpha, theta, off, _)) in GANTRY.iter().enumerate() {
        t *= dh(a, alpha, q[i] + off, theta);
    }
    if q.len() == 6 {
        t *= dh(0.0, -FRAC_PI_2, 0.15, q[3]);
        t *= dh(0.0, FRAC_PI_2, 0.0, q[4]);
        t *= dh(0.0, 0.0, 0.12, q[5]);
    }
    t * tool
}

/// Position (m) and rotation (Frobenius norm of the difference) errors by [`fk_here`].
fn errors_here(q: &[f64], t: &Pose) -> (f64, f64) {
    let m = fk_here(q);
    let want = t.to_homogeneous();
    let dp = (m.fixed_view::<3, 1>(0, 3) - want.fixed_view::<3, 1>(0, 3)).norm();
    let dr = (m.fixed_view::<3, 3>(0, 0) - want.fixed_view::<3, 3>(0, 0)).norm();
    (dp, dr)
}

/// Newton over all six joints on [`fk_here`], from `q` (see `common::closed_form::newton_on`).
fn newton_here(t: &Pose, q: Vec<f64>) -> Option<Vec<f64>> {
    newton_on(|q: &[f64]| fk_here(q), t, q)
}

#[test]
fn a_cartesian_arm_alone_is_a_linear_system_with_one_solution() {
    let r = gantry(false);
    let c = cf(&r);
    assert_eq!(*c.family(), Family::Cartesian);
    assert_eq!(c.name(), "Cartesian arm");
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    for _ in 0..200 {
        let q: Vec<f64> = r
            .limits()
            .iter()
            .map(|l| rng.random_range(l[0]..=l[1]))
            .collect();
        let p = fk_here(&q).fixed_view::<3, 1>(0, 3).into_owned();
        let res = c.solve(&r, &Target::Position(p)).unwrap();
        assert_eq!(res.status, IkStatus::Ok);
        assert_eq!(res.solutions.len(), 1, "{}", show(&res));
        let s = &res.solutions[0];
        assert!(s.q.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-12));
    }
}

#[test]
fn a_gantry_with_a_spherical_wrist_has_both_wrist_postures_and_no_other_solution() {
    let r = gantry(true);
    let c = cf(&r);
    assert_eq!(
        *c.family(),
        Family::Decoupled6 {
            arm: ArmKind::Cartesian
        }
    );
    assert_eq!(c.family().generic_solution_count(), 2);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let mut converged = 0;
    for _ in 0..40 {
        let q: Vec<f64> = r
            .limits()
            .iter()
            .map(|l| rng.random_range(l[0].max(-3.0)..=l[1].min(3.0)))
            .collect();
        let t = pose_from_matrix(&fk_here(&q)).unwrap();
        let res = c.solve(&r, &Target::Pose(t)).unwrap();
        assert_eq!(res.status, IkStatus::Ok);
        assert_eq!(res.solutions.len(), 2, "{}", show(&res));
        for s in &res.solutions {
            let (dp, dr) = errors_here(&s.q, &t);
            assert!(dp < 1e-10 && dr < 1e-10, "{dp:e} {dr:e}\n{}", show(&res));
        }
        assert!(res.solutions.iter().any(|s| same_q(&r, &s.q, &q, 1e-9)));
        // The two differ by the wrist's flip only, and are labelled so.
        let [a, b] = [&res.solutions[0], &res.solutions[1]];
        assert!((0..3).all(|i| (a.q[i] - b.q[i]).abs() < 1e-9));
        assert_ne!(a.posture, b.posture);
        assert!(a.posture.to_string().contains("wrist") && b.posture.to_string().contains("wrist"));
        // Brute force: Newton from starts spread over twice the prismatic ranges and every
        // angle.
        for _ in 0..50 {
            let start: Vec<f64> = r
                .limits()
                .iter()
                .map(|l| {
                    let (lo, hi) = (l[0].max(-PI), l[1].min(PI));
                    let w = hi - lo;
                    rng.random_range(lo - 0.5 * w..=hi + 0.5 * w)
                })
                .collect();
            if let Some(found) = newton_here(&t, start) {
                converged += 1;
                assert!(
                    res.solutions.iter().any(|s| same_q(&r, &s.q, &found, 1e-6)),
                    "Newton found {found:?}, not among\n{}",
                    show(&res)
                );
            }
        }
    }
    // (Many starts end at a half turn of the wrist, a stationary point of the residual.)
    assert!(converged > 250, "only {converged} of 2000 starts converged");
}

#[test]
fn three_prismatic_axes_in_one_plane_are_not_a_cartesian_arm() {
    // Axes z0, z1, z2 all horizontal-free: alpha = 0 keeps every axis along z0.
    let rows = [
        pr(0.1, 0.0, 0.0, 0.0, [0.0, 1.0]),
        pr(0.2, 0.0, 0.5, 0.0, [0.0, 1.0]),
        pr(0.0, 0.0, 0.0, 0.0, [0.0, 1.0]),
    ];
    let r = Robot::from_dh(
        "flat",
        Convention::Standard,
        &rows,
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    assert!(
        ClosedForm::detect(&r)
            .map(|c| *c.family() != Family::Cartesian)
            .unwrap_or(true)
    );
}

/// The gantry's wrist-centre workspace is the box its three prismatic ranges span (0.8 x 1.0
/// x 1.0 m = 0.8 m^3, seen from the top as [0, 0.8] x [0, 1]); it has no closed-form section
/// (joint 1 is prismatic), so it is sampled, and the sampling tracks the wrist centre, not the
/// flange (the figure said "wrist centre" and showed the flange, 0.1 m larger all round).
#[test]
fn the_gantrys_wrist_centre_workspace_is_its_box() {
    use armlab::workspace::{MapView, StatsOptions, TrackedPoint, map_extent, map_statistics};
    let r = armlab::model_file::load_model("assets/robots/gantry_wrist.toml").unwrap();
    let top = map_extent(&r, MapView::Top, TrackedPoint::WristCentre, 0).unwrap();
    let want = [0.0, 0.8, 0.0, 1.0];
    let got = [top.min[0], top.max[0], top.min[1], top.max[1]];
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() < 0.02, "top view {got:?}, want {want:?}");
    }
    let flange = map_extent(&r, MapView::Top, TrackedPoint::Flange, 0).unwrap();
    assert!(flange.min[0] < -0.05 && flange.max[0] > 0.85, "{flange:?}");
    let mut opts = StatsOptions::default();
    opts.grid.resolution = 48;
    opts.samples = 50_000;
    let stats = map_statistics(&r, TrackedPoint::WristCentre, &opts).unwrap();
    let v = stats.volume.unwrap();
    assert!((v - 0.8).abs() < 0.8 * 0.03, "volume {v}");
}
