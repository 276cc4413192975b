//! Issue 47: the orientation exercises (`euler`, `compose`, `axis-angle`, `quaternion`), checked
//! against computations written here, not armlab's: the elementary rotations (2.6)-(2.8) and
//! their products multiplied out by hand, the inverse formulas written out ((2.19)-(2.23) and
//! Problem 2.1's ZXZ, (2.27)-(2.28) with Problem 2.5's half turn, (2.34)-(2.35)), and the key
//! read as plain JSON.
//!
//! Every correct answer (either Euler solution, members of a singular family, Q and -Q,
//! (theta, r) and (-theta, -r), any axis at theta = 0) gets full marks. Every named single
//! mistake is made on the key by its own wrong computation here; the grader's verdict is held
//! against a brute force written here: the mistakes whose reading of the answer gives the key's
//! rotation. Where only one explains the answer, the grader must name exactly it.

use armlab::exercise::orientation::parse_answer;
use armlab::exercise::{Answer, Grade, Key, Kind, Mistake, generate, grade};
use serde_json::Value;
use std::f64::consts::PI;

type M = [[f64; 3]; 3];

fn rx(a: f64) -> M {
    let (s, c) = a.sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}

fn ry(a: f64) -> M {
    let (s, c) = a.sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}

fn rz(a: f64) -> M {
    let (s, c) = a.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn mul(a: &M, b: &M) -> M {
    let mut out = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            out[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

fn tr(a: &M) -> M {
    let mut out = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            out[i][j] = a[j][i];
        }
    }
    out
}

fn diff(a: &M, b: &M) -> f64 {
    (0..9)
        .map(|k| (a[k / 3][k % 3] - b[k / 3][k % 3]).abs())
        .fold(0.0, f64::max)
}

/// The same rotation within the key's tolerance.
fn close(a: &M, b: &M) -> bool {
    diff(a, b) <= 1e-3
}

fn elementary(axis: &str, a: f64) -> M {
    match axis {
        "x" => rx(a),
        "y" => ry(a),
        "z" => rz(a),
        _ => panic!("axis {axis:?}"),
    }
}

/// The convention's product multiplied out here: ZYZ (2.18), ZXZ (Problem 2.1), RPY (2.21).
fn euler_matrix(conv: &str, a: [f64; 3]) -> M {
    let (mid, last) = match conv {
        "zyz" => (ry(a[1]), rz(a[2])),
        "zxz" => (rx(a[1]), rz(a[2])),
        "rpy" => (ry(a[1]), rx(a[2])),
        _ => panic!("convention {conv:?}"),
    };
    mul(&mul(&rz(a[0]), &mid), &last)
}

/// The key as plain JSON, and as armlab reads it (for `grade`).
fn keys(kind: Kind, seed: u64, student: usize) -> (Value, Key) {
    let sheet = generate(kind, None, seed, student).unwrap();
    let json = serde_json::to_string(&sheet.key).unwrap();
    (serde_json::from_str(&json).unwrap(), sheet.key)
}

fn matrix_of(v: &Value) -> M {
    let rows = v.as_array().expect("3 rows");
    assert_eq!(rows.len(), 3);
    let mut m = [[0.0; 3]; 3];
    for (i, row) in rows.iter().enumerate() {
        let row = row.as_array().expect("3 numbers");
        assert_eq!(row.len(), 3);
        for j in 0..3 {
            m[i][j] = row[j].as_f64().unwrap();
        }
    }
    m
}

/// Grades an answer file's text (read as `armlab exercise check` reads it).
fn graded(key: &Key, text: &str) -> Grade {
    let a = parse_answer(key.kind, text, "answer.txt").unwrap_or_else(|e| panic!("{e}: {text}"));
    let g = grade(key, &Answer::Orientation(a)).unwrap();
    assert_eq!((g.max, g.items.len()), (1, 1), "{g:?}");
    g
}

fn line(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.12}"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn right(key: &Key, text: &str, what: &str) {
    let g = graded(key, text);
    assert_eq!(g.score, 1, "{what}: {text:?} {:?}", g.items);
    assert_eq!(g.items[0].mistake, None);
}

/// A wrong answer made by `made`: the grader names a mistake the brute force finds; exactly
/// `made` where it is the only one. Returns whether it was the only one.
fn wrong(key: &Key, text: &str, made: Mistake, explains: &[Mistake]) -> bool {
    assert!(
        explains.contains(&made),
        "the brute force misses {made:?} for {text:?}: {explains:?}"
    );
    let g = graded(key, text);
    assert_eq!(g.score, 0, "{made:?} graded right: {text:?}");
    let named = g.items[0].mistake;
    assert!(
        named.is_some_and(|m| explains.contains(&m)),
        "{made:?}: named {named:?}, the brute force says {explains:?} ({})",
        g.items[0].feedback
    );
    if explains.len() == 1 {
        assert_eq!(named, Some(made), "{}", g.items[0].feedback);
        assert!(g.items[0].feedback.starts_with(&made.to_string()));
    }
    explains.len() == 1
}

// ---------------------------------------------------------------------------------------------
// euler

const CONVENTIONS: [&str; 3] = ["zyz", "zxz", "rpy"];

/// psi from the residual (Rz(phi) Rmid(theta))^T R = Rlast(psi).
fn residual_psi(conv: &str, m: &M, phi: f64, theta: f64) -> f64 {
    let mid = if conv == "zxz" { rx(theta) } else { ry(theta) };
    let res = mul(&tr(&mul(&rz(phi), &mid)), m);
    if conv == "rpy" {
        res[2][1].atan2(res[1][1])
    } else {
        res[1][0].atan2(res[0][0])
    }
}

/// Every answer written here for `m` in `conv`: both solutions of (2.19)-(2.20), Problem 2.1,
/// (2.22)-(2.23); at a singular case (s_theta = 0, c_theta = 0 for RPY) three members of the
/// family for each theta. Each is checked to give `m` before it is used. Also says whether `m`
/// is singular.
fn euler_answers(conv: &str, m: &M) -> (Vec<[f64; 3]>, bool) {
    let rpy = conv == "rpy";
    let middle = if rpy {
        m[2][1].hypot(m[2][2])
    } else {
        m[0][2].hypot(m[1][2])
    };
    let singular = middle < 1e-9;
    let mut out = Vec::new();
    for sign in [1.0, -1.0] {
        let theta = if rpy {
            (-m[2][0]).atan2(sign * middle)
        } else {
            (sign * middle).atan2(m[2][2])
        };
        let phis = if singular {
            vec![0.0, 0.7, -2.2]
        } else {
            vec![match conv {
                "zyz" => (sign * m[1][2]).atan2(sign * m[0][2]),
                "zxz" => (sign * m[0][2]).atan2(-sign * m[1][2]),
                _ => (sign * m[1][0]).atan2(sign * m[0][0]),
            }]
        };
        for phi in phis {
            out.push([phi, theta, residual_psi(conv, m, phi, theta)]);
        }
    }
    for a in &out {
        assert!(diff(&euler_matrix(conv, *a), m) < 1e-9, "{conv} {a:?}");
    }
    (out, singular)
}

/// The brute force: each named mistake's reading of the answer `a` (rad, as the file was read),
/// kept where it gives `m`.
fn euler_explanations(conv: &str, m: &M, a: [f64; 3]) -> Vec<Mistake> {
    let fits = |c: &str, x: [f64; 3], target: &M| close(&euler_matrix(c, x), target);
    let mut out = Vec::new();
    if fits(conv, a.map(f64::to_radians), m) {
        out.push(Mistake::DegreesAsRadians);
    }
    if fits(conv, a.map(f64::to_degrees), m) {
        out.push(Mistake::RadiansAsDegrees);
    }
    if fits(conv, a, &tr(m)) {
        out.push(Mistake::Transpose);
    }
    if CONVENTIONS.iter().any(|c| *c != conv && fits(c, a, m)) {
        out.push(Mistake::OtherConvention);
    }
    if fits(conv, [a[2], a[1], a[0]], m) {
        out.push(Mistake::ReversedOrder);
    }
    for k in 0..3 {
        let mut b = a;
        b[k] = -b[k];
        if fits(conv, b, m) {
            out.push(Mistake::AngleSign);
        }
    }
    out
}

#[test]
fn euler_sheets_take_every_solution_and_name_each_single_mistake() {
    let mut singular_sheets = 0;
    let mut conventions = std::collections::HashSet::new();
    let mut unique = std::collections::HashMap::<Mistake, usize>::new();
    for student in 1..=40 {
        let (json, key) = keys(Kind::Euler, 12, student);
        assert_eq!(json["kind"], "euler");
        let conv = json["convention"].as_str().unwrap().to_string();
        conventions.insert(conv.clone());
        let m = matrix_of(&json["matrix"]);
        assert!(json.get("sequence").is_none() && json.get("model").is_none());
        let (answers, singular) = euler_answers(&conv, &m);
        singular_sheets += usize::from(singular);
        for a in &answers {
            right(&key, &line(a), "a solution");
            let deg = a.map(|v| (v.to_degrees() * 100.0).round() / 100.0);
            right(&key, &format!("# deg\n{}", line(&deg)), "in degrees");
            right(
                &key,
                &format!("{}, {}, {}", a[0] + 2.0 * PI, a[1], a[2] - 2.0 * PI),
                "2 pi",
            );
        }
        let a = answers[0];
        let others: Vec<&str> = CONVENTIONS.iter().copied().filter(|c| *c != conv).collect();
        // (mistake, the answer file it makes)
        let mut made: Vec<(Mistake, String)> = vec![
            (Mistake::DegreesAsRadians, line(&a.map(f64::to_degrees))),
            (Mistake::RadiansAsDegrees, format!("# deg\n{}", line(&a))),
            (
                Mistake::Transpose,
                line(&euler_answers(&conv, &tr(&m)).0[0]),
            ),
            (
                Mistake::OtherConvention,
                line(&euler_answers(others[0], &m).0[0]),
            ),
            (
                Mistake::OtherConvention,
                line(&euler_answers(others[1], &m).0[0]),
            ),
            (Mistake::ReversedOrder, line(&[a[2], a[1], a[0]])),
        ];
        for k in 0..3 {
            let mut b = a;
            b[k] = -b[k];
            made.push((Mistake::AngleSign, line(&b)));
        }
        for (mistake, text) in made {
            let read = parse_answer(Kind::Euler, &text, "t").unwrap();
            let armlab::exercise::OrientationAnswer::Euler(read) = read else {
                panic!()
            };
            if close(&euler_matrix(&conv, read), &m) {
                continue; // this slip changes nothing here (an angle of 0, a singular case)
            }
            let explains = euler_explanations(&conv, &m, read);
            if wrong(&key, &text, mistake, &explains) {
                *unique.entry(mistake).or_default() += 1;
            }
        }
    }
    assert!(singular_sheets >= 2, "{singular_sheets} singular sheets");
    assert_eq!(conventions.len(), 3, "{conventions:?}");
    for m in [
        Mistake::DegreesAsRadians,
        Mistake::RadiansAsDegrees,
        Mistake::Transpose,
        Mistake::OtherConvention,
        Mistake::ReversedOrder,
        Mistake::AngleSign,
    ] {
        assert!(
            unique.get(&m).copied().unwrap_or(0) >= 3,
            "{m:?}: {unique:?}"
        );
    }
}

/// The issue's example: ZYZ given, ZXZ answered, named with both conventions.
#[test]
fn the_other_convention_is_named_with_both() {
    for student in 1..=60 {
        let (json, key) = keys(Kind::Euler, 4, student);
        if json["convention"] != "zyz" {
            continue;
        }
        let m = matrix_of(&json["matrix"]);
        let (zxz, singular) = euler_answers("zxz", &m);
        if singular {
            continue;
        }
        let g = graded(&key, &line(&zxz[0]));
        assert_eq!(g.items[0].mistake, Some(Mistake::OtherConvention));
        assert_eq!(
            g.items[0].feedback,
            "the other convention (ZYZ given, ZXZ answered)"
        );
        return;
    }
    panic!("no regular ZYZ sheet in the class");
}

// ---------------------------------------------------------------------------------------------
// compose

/// A step of the key's sequence, read as plain JSON: (frame, axis, angle in rad).
type JsonStep = (String, String, f64);

fn sequence_of(v: &Value) -> Vec<JsonStep> {
    v.as_array()
        .expect("a list")
        .iter()
        .map(|s| {
            let o = s.as_object().unwrap();
            let mut names: Vec<&str> = o.keys().map(String::as_str).collect();
            names.sort_unstable();
            assert_eq!(names, ["angle", "axis", "frame"]);
            let frame = o["frame"].as_str().unwrap().to_string();
            assert!(frame == "current" || frame == "fixed", "{frame}");
            let axis = o["axis"].as_str().unwrap().to_string();
            (frame, axis, o["angle"].as_f64().unwrap())
        })
        .collect()
}

/// The product by the rules of Sect. 2.3: about the current frame on the right, about the fixed
/// frame on the left.
fn product(steps: &[JsonStep]) -> M {
    let mut r = rx(0.0);
    for (frame, axis, angle) in steps {
        let e = elementary(axis, *angle);
        r = if frame == "current" {
            mul(&r, &e)
        } else {
            mul(&e, &r)
        };
    }
    r
}

fn with_frames(steps: &[JsonStep], from: &str, to: &str) -> Vec<JsonStep> {
    steps
        .iter()
        .map(|(f, a, x)| {
            let f = if f == from { to } else { f.as_str() };
            (f.to_string(), a.clone(), *x)
        })
        .collect()
}

fn matrix_text(m: &M, decimals: usize) -> String {
    m.iter()
        .map(|r| {
            r.iter()
                .map(|v| format!("{v:.decimals$}"))
                .collect::<Vec<_>>()
                .join(", ")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The brute force for a matrix answer: each named mistake's wrong product of the sequence,
/// kept where it is the answer.
fn compose_explanations(steps: &[JsonStep], answer: &M) -> Vec<Mistake> {
    let mut out = Vec::new();
    let has = |f: &str| steps.iter().any(|s| s.0 == f);
    if has("current") && close(&product(&with_frames(steps, "current", "fixed")), answer) {
        out.push(Mistake::FixedForCurrent);
    }
    if has("fixed") && close(&product(&with_frames(steps, "fixed", "current")), answer) {
        out.push(Mistake::CurrentForFixed);
    }
    let reversed: Vec<JsonStep> = steps.iter().rev().cloned().collect();
    if close(&product(&reversed), answer) {
        out.push(Mistake::ReversedOrder);
    }
    if close(&tr(&product(steps)), answer) {
        out.push(Mistake::Transpose);
    }
    let degrees: Vec<JsonStep> = steps
        .iter()
        .map(|(f, a, x)| (f.clone(), a.clone(), x.to_degrees()))
        .collect();
    if close(&product(&degrees), answer) {
        out.push(Mistake::DegreesAsRadians);
    }
    for k in 0..steps.len() {
        let mut b = steps.to_vec();
        b[k].2 = -b[k].2;
        if close(&product(&b), answer) {
            out.push(Mistake::AngleSign);
        }
    }
    out
}

#[test]
fn compose_sheets_grade_the_product_and_name_each_single_mistake() {
    let mut unique = std::collections::HashMap::<Mistake, usize>::new();
    let mut patterns = std::collections::HashSet::new();
    for student in 1..=40 {
        let (json, key) = keys(Kind::Compose, 21, student);
        assert_eq!(json["kind"], "compose");
        assert!(json.get("matrix").is_none() && json.get("convention").is_none());
        let steps = sequence_of(&json["sequence"]);
        assert!((2..=4).contains(&steps.len()));
        let frames: std::collections::BTreeSet<&str> = steps.iter().map(|s| s.0.as_str()).collect();
        patterns.insert(frames.into_iter().collect::<Vec<_>>().join("+"));
        let r = product(&steps);
        right(&key, &matrix_text(&r, 12), "the product");
        right(&key, &matrix_text(&r, 4), "four decimals");
        right(
            &key,
            &format!("# my answer\n\n{}\n", matrix_text(&r, 6)),
            "comments",
        );
        let mut made: Vec<(Mistake, M)> = vec![
            (
                Mistake::FixedForCurrent,
                product(&with_frames(&steps, "current", "fixed")),
            ),
            (
                Mistake::CurrentForFixed,
                product(&with_frames(&steps, "fixed", "current")),
            ),
            (
                Mistake::ReversedOrder,
                product(&steps.iter().rev().cloned().collect::<Vec<_>>()),
            ),
            (Mistake::Transpose, tr(&r)),
            (
                Mistake::DegreesAsRadians,
                product(
                    &steps
                        .iter()
                        .map(|(f, a, x)| (f.clone(), a.clone(), x.to_degrees()))
                        .collect::<Vec<_>>(),
                ),
            ),
        ];
        for k in 0..steps.len() {
            let mut b = steps.clone();
            b[k].2 = -b[k].2;
            made.push((Mistake::AngleSign, product(&b)));
        }
        for (mistake, answer) in made {
            if close(&answer, &r) {
                continue; // the same matrix here: no mistake to see
            }
            let explains = compose_explanations(&steps, &answer);
            if wrong(&key, &matrix_text(&answer, 9), mistake, &explains) {
                *unique.entry(mistake).or_default() += 1;
            }
        }
    }
    assert_eq!(patterns.len(), 3, "{patterns:?}");
    for m in [
        Mistake::FixedForCurrent,
        Mistake::CurrentForFixed,
        Mistake::ReversedOrder,
        Mistake::Transpose,
        Mistake::DegreesAsRadians,
        Mistake::AngleSign,
    ] {
        assert!(
            unique.get(&m).copied().unwrap_or(0) >= 2,
            "{m:?}: {unique:?}"
        );
    }
}

/// The issue's words for a sequence about the current axes composed about the fixed ones.
#[test]
fn fixed_axes_for_current_ones_is_said_in_the_issue_s_words() {
    for student in 1..=40 {
        let (json, key) = keys(Kind::Compose, 5, student);
        let steps = sequence_of(&json["sequence"]);
        if steps.iter().any(|s| s.0 != "current") {
            continue;
        }
        let g = graded(
            &key,
            &matrix_text(&product(&with_frames(&steps, "current", "fixed")), 9),
        );
        assert_eq!(
            g.items[0].feedback,
            "you composed about the fixed axes; the sequence turns about the current ones"
        );
        return;
    }
    panic!("no sequence about current axes only");
}

// ---------------------------------------------------------------------------------------------
// axis-angle

/// R = I + sin(theta) K + (1 - cos(theta)) K^2, K the cross-product matrix of r (Rodrigues'
/// form, another way to (2.25)).
fn rodrigues(theta: f64, r: [f64; 3]) -> M {
    let k = [[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]];
    let k2 = mul(&k, &k);
    let (s, c) = theta.sin_cos();
    let mut out = rx(0.0);
    for i in 0..3 {
        for j in 0..3 {
            out[i][j] += s * k[i][j] + (1.0 - c) * k2[i][j];
        }
    }
    out
}

/// theta and r of `m`: (2.27)-(2.28); at theta = pi from the diagonal, signs from the
/// off-diagonal terms (Problem 2.5); at theta = 0 the axis z.
fn axis_angle_of(m: &M) -> (f64, [f64; 3]) {
    let mut theta = ((m[0][0] + m[1][1] + m[2][2] - 1.0) / 2.0)
        .clamp(-1.0, 1.0)
        .acos();
    if PI - theta < 1e-6 {
        theta = PI; // acos near -1 keeps only half the digits
    }
    let r = if theta < 1e-9 {
        [0.0, 0.0, 1.0]
    } else if theta == PI {
        let mag = [0, 1, 2].map(|i| ((m[i][i] + 1.0) / 2.0).max(0.0).sqrt());
        let k = (0..3).max_by(|&a, &b| mag[a].total_cmp(&mag[b])).unwrap();
        [0, 1, 2].map(|j| {
            if j == k {
                mag[j]
            } else {
                mag[j] * (m[k][j] + m[j][k]).signum()
            }
        })
    } else {
        let s2 = 2.0 * theta.sin();
        [
            (m[2][1] - m[1][2]) / s2,
            (m[0][2] - m[2][0]) / s2,
            (m[1][0] - m[0][1]) / s2,
        ]
    };
    assert!(diff(&rodrigues(theta, r), m) < 1e-9, "{theta} {r:?}");
    (theta, r)
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The brute force for `theta x y z` (rad, as read).
fn axis_angle_explanations(m: &M, t: f64, r: [f64; 3]) -> Vec<Mistake> {
    let n = norm(&r);
    let unit = (n - 1.0).abs() <= 1e-3;
    let fits = |t: f64, r: [f64; 3], target: &M| unit && close(&rodrigues(t, r), target);
    let mut out = Vec::new();
    if !unit && n > 0.0 && close(&rodrigues(t, r.map(|v| v / n)), m) {
        out.push(Mistake::NonUnitAxis);
    }
    if fits(t.to_radians(), r, m) {
        out.push(Mistake::DegreesAsRadians);
    }
    if fits(t.to_degrees(), r, m) {
        out.push(Mistake::RadiansAsDegrees);
    }
    if fits(t, r, &tr(m)) {
        out.push(Mistake::Transpose);
    }
    if fits(2.0 * t, r, m) {
        out.push(Mistake::HalfAngle);
    }
    out
}

/// Every right answer of an axis-angle key whose rotation is (t, r), worked out here: (t, r),
/// (-t, -r), t + 2 pi, degrees; a half turn about -r; at t = 0 any axis. Returns whether the
/// sheet is a half turn, and whether it is no turn.
fn axis_angle_right_answers(key: &Key, t: f64, r: [f64; 3]) -> (bool, bool) {
    let neg = r.map(|v| -v);
    right(key, &line(&[t, r[0], r[1], r[2]]), "(theta, r)");
    right(key, &line(&[-t, neg[0], neg[1], neg[2]]), "(-theta, -r)");
    right(
        key,
        &line(&[t + 2.0 * PI, r[0], r[1], r[2]]),
        "theta + 2 pi",
    );
    let deg = format!(
        "# deg\n{:.4}, {:.6}, {:.6}, {:.6}",
        t.to_degrees(),
        r[0],
        r[1],
        r[2]
    );
    right(key, &deg, "degrees");
    if PI - t < 1e-6 {
        right(
            key,
            &line(&[t, neg[0], neg[1], neg[2]]),
            "a half turn about -r",
        );
    }
    if t < 1e-9 {
        let any = [0.48, -0.6, 0.64];
        right(
            key,
            &line(&[0.0, any[0], any[1], any[2]]),
            "no turn, any axis",
        );
    }
    (PI - t < 1e-6, t < 1e-9)
}

#[test]
fn axis_angle_sheets_take_both_signs_any_axis_at_zero_and_name_each_slip() {
    let (mut half_turns, mut none) = (0, 0);
    let mut unique = std::collections::HashMap::<Mistake, usize>::new();
    for student in 1..=60 {
        let (json, key) = keys(Kind::AxisAngle, 8, student);
        assert_eq!(json["kind"], "axis-angle");
        let m = matrix_of(&json["matrix"]);
        let (t, r) = axis_angle_of(&m);
        let (half, zero) = axis_angle_right_answers(&key, t, r);
        half_turns += usize::from(half);
        none += usize::from(zero);
        let neg = r.map(|v| -v);
        let made = [
            (
                Mistake::NonUnitAxis,
                line(&[t, 2.0 * r[0], 2.0 * r[1], 2.0 * r[2]]),
            ),
            (
                Mistake::DegreesAsRadians,
                line(&[t.to_degrees(), r[0], r[1], r[2]]),
            ),
            (
                Mistake::RadiansAsDegrees,
                format!("# deg\n{}", line(&[t, r[0], r[1], r[2]])),
            ),
            (Mistake::Transpose, line(&[t, neg[0], neg[1], neg[2]])),
            (Mistake::HalfAngle, line(&[t / 2.0, r[0], r[1], r[2]])),
        ];
        for (mistake, text) in made {
            let read = parse_answer(Kind::AxisAngle, &text, "t").unwrap();
            let armlab::exercise::OrientationAnswer::AxisAngle { angle, axis } = read else {
                panic!()
            };
            let unit = (norm(&axis) - 1.0).abs() <= 1e-3;
            if (unit || angle.abs() < 1e-9) && close(&rodrigues(angle, axis), &m) {
                continue; // right here (the transpose of a half turn, no turn at all)
            }
            let explains = axis_angle_explanations(&m, angle, axis);
            if wrong(&key, &text, mistake, &explains) {
                *unique.entry(mistake).or_default() += 1;
            }
        }
    }
    assert!(
        half_turns >= 2 && none >= 1,
        "{half_turns} half turns, {none} none"
    );
    for m in [
        Mistake::NonUnitAxis,
        Mistake::DegreesAsRadians,
        Mistake::RadiansAsDegrees,
        Mistake::Transpose,
        Mistake::HalfAngle,
    ] {
        assert!(
            unique.get(&m).copied().unwrap_or(0) >= 3,
            "{m:?}: {unique:?}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// quaternion

/// R(eta, epsilon) = (eta^2 - eps^T eps) I + 2 eps eps^T + 2 eta S(eps), another form of (2.33).
fn quaternion_matrix(q: [f64; 4]) -> M {
    let [n, x, y, z] = q;
    let e = [x, y, z];
    let s = [[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]];
    let mut out = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let id = if i == j {
                n * n - norm(&e).powi(2)
            } else {
                0.0
            };
            out[i][j] = id + 2.0 * e[i] * e[j] + 2.0 * n * s[i][j];
        }
    }
    out
}

/// eta and epsilon of `m`, (2.34)-(2.35); at eta = 0 (a half turn) the signs of epsilon from
/// the off-diagonal terms, the largest component positive.
fn quaternion_of(m: &M) -> [f64; 4] {
    let eta = 0.5 * (m[0][0] + m[1][1] + m[2][2] + 1.0).max(0.0).sqrt();
    // a half turn: the square root of a rounding error is no eta
    let eta = if eta < 1e-6 { 0.0 } else { eta };
    let mag = [
        0.5 * (m[0][0] - m[1][1] - m[2][2] + 1.0).max(0.0).sqrt(),
        0.5 * (m[1][1] - m[2][2] - m[0][0] + 1.0).max(0.0).sqrt(),
        0.5 * (m[2][2] - m[0][0] - m[1][1] + 1.0).max(0.0).sqrt(),
    ];
    let skew = [m[2][1] - m[1][2], m[0][2] - m[2][0], m[1][0] - m[0][1]];
    let eps = if eta > 1e-6 {
        [0, 1, 2].map(|i| if skew[i] >= 0.0 { mag[i] } else { -mag[i] })
    } else {
        let k = (0..3).max_by(|&a, &b| mag[a].total_cmp(&mag[b])).unwrap();
        [0, 1, 2].map(|j| {
            if j == k {
                mag[j]
            } else {
                mag[j] * (m[k][j] + m[j][k]).signum()
            }
        })
    };
    let q = [eta, eps[0], eps[1], eps[2]];
    assert!(diff(&quaternion_matrix(q), m) < 1e-9, "{q:?}");
    q
}

/// The brute force for `eta ex ey ez` as read.
fn quaternion_explanations(m: &M, q: [f64; 4]) -> Vec<Mistake> {
    let n = norm(&q);
    let unit = (n - 1.0).abs() <= 1e-3;
    let fits = |q: [f64; 4], target: &M| unit && close(&quaternion_matrix(q), target);
    let mut out = Vec::new();
    if !unit && n > 0.0 && close(&quaternion_matrix(q.map(|v| v / n)), m) {
        out.push(Mistake::NonUnitQuaternion);
    }
    if fits([q[3], q[0], q[1], q[2]], m) {
        out.push(Mistake::EpsilonFirst);
    }
    if fits(q, &tr(m)) {
        out.push(Mistake::Transpose);
    }
    let s = norm(&q[1..]);
    if s > 1e-3 {
        let theta = s.atan2(q[0]);
        let (sh, ch) = (theta / 2.0).sin_cos();
        if fits([ch, sh * q[1] / s, sh * q[2] / s, sh * q[3] / s], m) {
            out.push(Mistake::FullAngle);
        }
    }
    out
}

#[test]
fn quaternion_sheets_take_q_and_minus_q_and_name_each_slip() {
    let mut unique = std::collections::HashMap::<Mistake, usize>::new();
    let mut half_turns = 0;
    for student in 1..=60 {
        let (json, key) = keys(Kind::Quaternion, 8, student);
        assert_eq!(json["kind"], "quaternion");
        let m = matrix_of(&json["matrix"]);
        let q = quaternion_of(&m);
        half_turns += usize::from(q[0] < 1e-6);
        right(&key, &line(&q), "Q");
        right(&key, &line(&q.map(|v| -v)), "-Q");
        right(
            &key,
            &format!("{:.5},{:.5},{:.5},{:.5}", q[0], q[1], q[2], q[3]),
            "rounded",
        );
        let (theta, r) = {
            let s = norm(&q[1..]);
            let theta = 2.0 * s.atan2(q[0]);
            let r = if s > 0.0 {
                [q[1] / s, q[2] / s, q[3] / s]
            } else {
                [0.0, 0.0, 1.0]
            };
            (theta, r)
        };
        let made = [
            (Mistake::NonUnitQuaternion, q.map(|v| 2.0 * v)),
            (Mistake::EpsilonFirst, [q[1], q[2], q[3], q[0]]),
            (Mistake::Transpose, [q[0], -q[1], -q[2], -q[3]]),
            (
                Mistake::FullAngle,
                [
                    theta.cos(),
                    theta.sin() * r[0],
                    theta.sin() * r[1],
                    theta.sin() * r[2],
                ],
            ),
        ];
        for (mistake, answer) in made {
            if (norm(&answer) - 1.0).abs() <= 1e-3 && close(&quaternion_matrix(answer), &m) {
                continue; // right here (no turn: Q = {1, 0})
            }
            if mistake == Mistake::FullAngle && theta.sin() < 1e-3 {
                continue; // {cos(pi), 0}: no axis left to see the slip by
            }
            let explains = quaternion_explanations(&m, answer);
            if wrong(&key, &line(&answer), mistake, &explains) {
                *unique.entry(mistake).or_default() += 1;
            }
        }
    }
    assert!(half_turns >= 2, "{half_turns} half turns");
    for m in [
        Mistake::NonUnitQuaternion,
        Mistake::EpsilonFirst,
        Mistake::Transpose,
        Mistake::FullAngle,
    ] {
        assert!(
            unique.get(&m).copied().unwrap_or(0) >= 3,
            "{m:?}: {unique:?}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// every kind

/// Random numbers are no answer: never full marks (and a mistake is named only where the brute
/// force of its kind finds it).
#[test]
fn random_answers_get_no_marks() {
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for kind in [
        Kind::Euler,
        Kind::Compose,
        Kind::AxisAngle,
        Kind::Quaternion,
    ] {
        for student in 1..=10 {
            let (_, key) = keys(kind, 99, student);
            for _ in 0..20 {
                let n = if kind == Kind::Compose {
                    9
                } else if kind == Kind::Euler {
                    3
                } else {
                    4
                };
                let numbers: Vec<f64> = (0..n).map(|_| 6.0 * uniform() - 3.0).collect();
                let text = if kind == Kind::Compose {
                    numbers.chunks(3).map(line).collect::<Vec<_>>().join("\n")
                } else {
                    line(&numbers)
                };
                let g = graded(&key, &text);
                assert_eq!(g.score, 0, "{kind:?} {text:?}");
            }
        }
    }
}

/// A class is the same for the same seed, different from student to student, and its keys carry
/// the issue's JSON keys at the top level.
#[test]
fn classes_are_deterministic_different_and_keyed_as_the_issue_says() {
    for (kind, name, given) in [
        (Kind::Euler, "euler", ["matrix", "convention"].as_slice()),
        (Kind::Compose, "compose", ["sequence"].as_slice()),
        (Kind::AxisAngle, "axis-angle", ["matrix"].as_slice()),
        (Kind::Quaternion, "quaternion", ["matrix"].as_slice()),
    ] {
        let mut seen = std::collections::HashSet::new();
        for student in 1..=20 {
            let (json, key) = keys(kind, 3, student);
            assert_eq!(json["kind"], name);
            for field in given {
                assert!(json.get(*field).is_some(), "{name}: no {field}");
            }
            if let Some(c) = json.get("convention") {
                assert!(["zyz", "zxz", "rpy"].contains(&c.as_str().unwrap()));
            }
            assert!(
                seen.insert(json.to_string()),
                "{name} sheet {student} repeats"
            );
            assert_eq!(keys(kind, 3, student).1, key);
            let q = key.question.clone();
            assert!(q.contains("hand it in") && q.starts_with("# "), "{q}");
        }
    }
    // the sequence is stated in degrees in the question, in its order
    let (json, key) = keys(Kind::Compose, 3, 1);
    for (i, (frame, axis, angle)) in sequence_of(&json["sequence"]).iter().enumerate() {
        let words = format!(
            "{}. by {}° about the {axis} axis of the {frame} frame",
            i + 1,
            angle.to_degrees().round()
        );
        assert!(
            key.question.contains(&words),
            "{words} not in {}",
            key.question
        );
    }
    // an old key (no matrix, no sequence) still reads; an orientation key needs its question
    let fk = generate(
        Kind::Fk,
        Some(&armlab::kinematics::models::built_in("planar3").unwrap()),
        1,
        1,
    )
    .unwrap();
    let back: Key = serde_json::from_str(&serde_json::to_string(&fk.key).unwrap()).unwrap();
    assert_eq!(back, fk.key);
    let bare: Key =
        serde_json::from_str(r#"{"kind": "euler", "matrix": [[1,0,0],[0,1,0],[0,0,1]]}"#).unwrap();
    let e = grade(&bare, &Answer::Rows(vec![vec![0.0, 0.0, 0.0]])).unwrap_err();
    assert!(e.to_string().contains("convention"), "{e}");
    let bare: Key = serde_json::from_str(
        r#"{"kind": "euler", "convention": "zyz", "matrix": [[1,0,0],[0,1,0],[0,0,1]]}"#,
    )
    .unwrap();
    let g = grade(&bare, &Answer::Rows(vec![vec![0.4, 0.0, -0.4]])).unwrap();
    assert_eq!(g.score, 1, "{g:?}");
}

/// A bad answer file is refused with its file, line and field named.
#[test]
fn the_answer_parser_names_file_line_and_field() {
    let cases = [
        (Kind::Euler, "0.1 0.2\n", "line 1, field psi: missing"),
        (
            Kind::Euler,
            "# deg\n10 20 abc\n",
            "line 2, field psi: \"abc\" is not a number",
        ),
        (
            Kind::Euler,
            "1 2 3 4\n",
            "line 1, field psi: 1 number(s) too many",
        ),
        (Kind::Euler, "1 2 3\n4 5 6\n", "line 2: a line too many"),
        (Kind::Euler, "", "line 1, field phi: missing"),
        (
            Kind::AxisAngle,
            "1, 0, inf, 0\n",
            "line 1, field y: \"inf\" is not a finite number",
        ),
        (Kind::Quaternion, "1 0 0\n", "line 1, field ez: missing"),
        (
            Kind::Compose,
            "1 0 0\n0 1 0\n",
            "line 3, field r31: missing",
        ),
        (
            Kind::Compose,
            "1 0 0\n# row two\n0 1 x\n0 0 1\n",
            "line 3, field r23: \"x\" is not a number",
        ),
    ];
    for (kind, text, want) in cases {
        let e = parse_answer(kind, text, "student-07.txt")
            .unwrap_err()
            .to_string();
        assert!(e.contains("student-07.txt"), "{e}");
        assert!(e.contains(want), "{kind:?} {text:?}: {e}");
    }
    // `# deg` turns the angles only: theta of axis-angle, not its axis; no number of a matrix
    let a = parse_answer(Kind::AxisAngle, "# deg\n90 0 0 1", "a").unwrap();
    assert_eq!(
        a,
        armlab::exercise::OrientationAnswer::AxisAngle {
            angle: 90f64.to_radians(),
            axis: [0.0, 0.0, 1.0]
        }
    );
    let a = parse_answer(Kind::Compose, "# deg\n1 0 0\n0 1 0\n0 0 1", "a").unwrap();
    assert_eq!(
        a,
        armlab::exercise::OrientationAnswer::Matrix([
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0]
        ])
    );
}

/// Grading one orientation answer takes at most 1 ms (issue 47's goal; far less in practice).
#[test]
fn grading_one_answer_takes_under_a_millisecond() {
    for kind in [
        Kind::Euler,
        Kind::Compose,
        Kind::AxisAngle,
        Kind::Quaternion,
    ] {
        let (_, key) = keys(kind, 1, 1);
        let text = match kind {
            Kind::Compose => "0.1 0.2 0.3\n0.4 0.5 0.6\n0.7 0.8 0.9\n",
            Kind::Euler => "0.1 0.2 0.3\n",
            _ => "0.1 0.2 0.3 0.4\n",
        };
        let start = std::time::Instant::now();
        let n = 200;
        for _ in 0..n {
            let a = parse_answer(kind, text, "a").unwrap();
            std::hint::black_box(grade(&key, &Answer::Orientation(a)).unwrap());
        }
        let each = start.elapsed().as_secs_f64() / n as f64;
        assert!(each < 1e-3, "{kind:?}: {:.1} us a grade", each * 1e6);
    }
}
