//! Every built-in opens at a pose a lesson can start from: away from singularities (checked here
//! by the Jacobian's singular values, computed independently of the singularity analyser) and,
//! for the closed-form arms, with every posture of its tool pose inside the joint limits, so all
//! of them (the Puma's elbow-down ones included) can be shown. The Puma's "ready" is a wrist
//! singularity (theta5 = 0): it once opened there, with rank 5 and 7 solutions.

use armlab::kinematics::ik::Target;
use armlab::kinematics::ik::closed_form::ClosedForm;
use armlab::kinematics::models::BUILT_INS;
use armlab::kinematics::opening::opening_pose;

/// sigma_min / sigma_max of the Jacobian's position rows (and orientation rows for six joints
/// or more), by nalgebra's SVD.
fn conditioning(robot: &armlab::kinematics::Robot, q: &[f64]) -> f64 {
    let j = robot.jacobian(q, 0).unwrap();
    let rows: Vec<usize> = if robot.dof() >= 6 {
        (0..6).collect()
    } else {
        (0..3).collect()
    };
    let cols = robot.dof().min(rows.len());
    let m = nalgebra::DMatrix::from_fn(rows.len(), robot.dof(), |r, c| j[(rows[r], c)]);
    let sv = m.svd(false, false).singular_values;
    let mut v: Vec<f64> = sv.iter().copied().collect();
    v.sort_by(|a, b| b.total_cmp(a));
    v[cols - 1] / v[0]
}

#[test]
fn every_built_in_opens_regular_with_its_postures_inside_the_limits() {
    for b in BUILT_INS {
        let robot = (b.build)();
        let o = opening_pose(&robot);
        assert!(robot.within_limits(&o.q, 1e-12), "{}: {:?}", b.name, o.q);
        if let Ok(cf) = ClosedForm::detect(&robot) {
            let pose = robot.fk_ee(&o.q, 0).unwrap();
            let r = cf.solve(&robot, &Target::Pose(pose)).unwrap();
            let inside = r.solutions.iter().filter(|s| s.within_limits).count();
            assert_eq!(
                inside,
                r.solutions.len(),
                "{}: {} of {} postures inside the limits at {:?} ({:?})",
                b.name,
                inside,
                r.solutions.len(),
                o.q,
                o.note
            );
        }
    }
}

#[test]
fn the_puma_opens_off_its_wrist_singularity_with_all_eight_postures() {
    let robot = armlab::kinematics::models::built_in("puma560").unwrap();
    let ready = robot.config("ready").unwrap().to_vec();
    assert!(conditioning(&robot, &ready) < 1e-9, "ready is singular");
    let o = opening_pose(&robot);
    assert!(conditioning(&robot, &o.q) > 0.01, "{:?}", o.q);
    let note = o.note.expect("the note says why not ready");
    assert!(note.contains("singularity"), "{note}");
    let cf = ClosedForm::detect(&robot).unwrap();
    let r = cf
        .solve(&robot, &Target::Pose(robot.fk_ee(&o.q, 0).unwrap()))
        .unwrap();
    assert_eq!(r.solutions.len(), 8);
    assert!(r.solutions.iter().all(|s| s.within_limits));
    let elbow_down = r
        .solutions
        .iter()
        .filter(|s| s.posture.to_string().contains("elbow down"))
        .count();
    assert_eq!(elbow_down, 4);
}

#[test]
fn a_ready_pose_that_shows_the_arm_well_is_kept() {
    for name in ["anthropomorphic_spherical_wrist", "planar2", "dlr", "panda"] {
        let robot = armlab::kinematics::models::built_in(name).unwrap();
        let o = opening_pose(&robot);
        assert_eq!(o.q, robot.config("ready").unwrap(), "{name}");
        assert!(o.note.is_none());
    }
}
