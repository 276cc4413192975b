//! Scripted drags of the target through singularities and the workspace boundary with the
//! posture lock on, and the naming of singular configurations.

use super::*;

/// Drags the target of the anthropomorphic arm with spherical wrist radially outwards, through
/// the elbow singularity at the workspace boundary (arm stretched, |p_W| = a2 + d4 = 1 m) and
/// 30 mm beyond, then back, with the posture lock on and the orientation held.
///
/// Bound on each step while the target is reached: with dx the distance (m) from the last target
/// the arm reached,
/// `|dq|_inf <= K dx + 4 sqrt(dx / L)`, where K = 3 / sigma_min(J(q0)) (the linear estimate
/// |dq| <= |dx| / sigma_min away from the singularity, with a factor 3 of margin) and the square
/// root term is the exact behaviour at the stretched elbow, whose angle from the stretched
/// pose is 2 sqrt(delta / L) for a wrist centre delta inside the boundary (L = a2 = d4 = 0.5 m;
/// shoulder and wrist joints move by at most twice the elbow's change).
#[test]
fn drag_across_the_boundary_and_elbow_singularity_with_the_lock_on() {
    let mut s = state(ASW);
    let robot = s.robot().clone();
    let t0 = robot.fk(&Q_GENERIC).unwrap();
    s.set_target(0, t0).unwrap();
    let q0 = s.q().to_vec();
    assert!(max_step(&robot, &q0, &Q_GENERIC) < 1e-9);
    s.set_lock(true);
    let label = s.target(0).unwrap().posture.unwrap();
    let wrist = |t: &Pose| t.translation.vector - t.rotation * Vector3::z() * 0.1;
    let w0 = wrist(&t0);
    let u = w0.normalize();
    let beyond = 1.0 - w0.norm() + 0.03;
    let mut path: Vec<f64> = (0..)
        .map(|i| i as f64 * 0.005)
        .take_while(|&x| x <= beyond)
        .collect();
    let back: Vec<f64> = (0..)
        .map(|i| beyond - i as f64 * 0.007)
        .take_while(|&x| x >= 0.0)
        .collect();
    path.extend(back);
    path.push(0.0);
    let (k_lin, l) = (3.0 / smallest_sv(&robot, &q0), 0.5);
    let (mut q_prev, mut last_reached) = (q0.clone(), t0);
    let (mut frozen, mut resumed) = (0, 0);
    for &x in &path {
        let t = Pose::from_parts(
            Translation3::from(t0.translation.vector + u * x),
            t0.rotation,
        );
        let reach = s.set_target(0, t).unwrap().clone();
        let q = s.q().to_vec();
        assert!(q.iter().all(|v| v.is_finite()));
        let out = wrist(&t).norm() - 1.0;
        if out > 1e-9 {
            match reach {
                Reach::Unreachable { distance } => assert!((distance - out).abs() < 1e-9),
                other => panic!("at {x}: {other:?}"),
            }
            assert_eq!(q, q_prev, "frozen outside the workspace");
            assert!(s.ghosts(0).is_empty());
            frozen += 1;
            continue;
        }
        assert!(reach.is_reached(), "at {x}: {reach:?}");
        assert!(pose_gap(&fk(&s, 0), &t) < 1e-9);
        let dx = (t.translation.vector - last_reached.translation.vector).norm();
        let bound = k_lin * dx + 4.0 * (dx / l).sqrt();
        let step = max_step(&robot, &q, &q_prev);
        assert!(step <= bound, "at {x}: |dq| = {step} > {bound} (dx = {dx})");
        if frozen > 0 && resumed == 0 {
            resumed += 1;
        }
        assert_eq!(
            s.target(0).unwrap().posture.map(|p| p.to_string()),
            Some(label.to_string())
        );
        let current = s.ghosts(0).into_iter().find(|g| g.selected).unwrap();
        assert_eq!(current.posture.to_string(), label.to_string(), "at {x}");
        (q_prev, last_reached) = (q, t);
    }
    assert!(
        frozen >= 5 && resumed == 1,
        "frozen {frozen}, resumed {resumed}"
    );
    assert!(max_step(&robot, s.q(), &q0) < 1e-9, "back where it started");
}

/// Drags the target through the wrist singularity: the targets are the poses of a joint path
/// on which theta5 goes from 0.3 to -0.3 rad in steps of 0.02 (through exactly 0). The arm
/// follows that path exactly (no flip of theta4 and theta6 by pi). Under the lock the label
/// "wrist no flip" (theta5 > 0) changes meaning there: the branch continues as "wrist flip" and
/// the lock follows it, saying so.
#[test]
fn drag_through_the_wrist_singularity_with_the_lock_on() {
    let mut s = state(ASW);
    let robot = s.robot().clone();
    let q_at = |i: i32| {
        let mut q = Q_GENERIC.to_vec();
        q[4] = f64::from(15 - i) * 0.02;
        q
    };
    s.set_target(0, robot.fk(&q_at(0)).unwrap()).unwrap();
    s.set_lock(true);
    let start = s.target(0).unwrap().posture.unwrap().to_string();
    assert!(start.ends_with("wrist no flip"), "{start}");
    let mut q_prev = s.q().to_vec();
    for i in 1..=30 {
        let reach = s
            .set_target(0, robot.fk(&q_at(i)).unwrap())
            .unwrap()
            .clone();
        assert!(reach.is_reached(), "{i}: {reach:?}");
        let q = s.q().to_vec();
        assert!(q.iter().all(|v| v.is_finite()));
        assert!(max_step(&robot, &q, &q_at(i)) < 1e-6, "{i}: {q:?}");
        assert!(max_step(&robot, &q, &q_prev) < 0.02 + 1e-6);
        if i == 15 {
            let r = s.readouts(0).unwrap();
            assert!(r.singularity.unwrap().has(SingularityKind::Wrist));
        }
        q_prev = q;
    }
    let now = s.target(0).unwrap().posture.unwrap().to_string();
    assert_eq!(now, start.replace("wrist no flip", "wrist flip"));
    assert!(s.messages().iter().any(|m| m.text.contains("continues as")));
}
