//! `armlab symbolic`: the direct kinematics in the textbook's notation.
//!
//! The evidence is independent of the code under test: the JSON strings are parsed and
//! expanded here by a small parser of the documented grammar (as a computer-algebra system
//! would), then (1) evaluated and compared with the robot's numerical FK at random joint
//! values, and (2) compared term by term with the excerpt's equations, typed in by hand.

#![cfg(feature = "app")]

use armlab::kinematics::Robot;
use armlab::kinematics::models::BUILT_INS;
use armlab::kinematics::symbolic::{Options, derive};
use std::collections::BTreeMap;

/// An expanded polynomial over atom names (`c23`, `a2`): sorted atom lists with coefficients.
type Expanded = BTreeMap<Vec<String>, f64>;

/// A recursive-descent parser of the grammar: names, numbers, `+ - * / ^`, parentheses.
struct Parser<'a> {
    s: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn skip(&mut self) {
        while self.i < self.s.len() && self.s[self.i] == b' ' {
            self.i += 1;
        }
    }
    fn peek(&mut self) -> Option<u8> {
        self.skip();
        self.s.get(self.i).copied()
    }
    fn sum(&mut self) -> Expanded {
        let mut acc = self.product();
        while let Some(op @ (b'+' | b'-')) = self.peek() {
            self.i += 1;
            let rhs = self.product();
            let sign = if op == b'+' { 1.0 } else { -1.0 };
            acc = add(&acc, &scale(&rhs, sign));
        }
        acc
    }
    fn product(&mut self) -> Expanded {
        let mut acc = self.power();
        loop {
            match self.peek() {
                Some(b'*') => {
                    self.i += 1;
                    let rhs = self.power();
                    acc = mul(&acc, &rhs);
                }
                Some(b'/') => {
                    self.i += 1;
                    let rhs = self.power();
                    let d = constant_value(&rhs).expect("division by a number only");
                    acc = scale(&acc, 1.0 / d);
                }
                _ => return acc,
            }
        }
    }
    fn power(&mut self) -> Expanded {
        let base = self.unary();
        if self.peek() == Some(b'^') {
            self.i += 1;
            let e = constant_value(&self.unary()).expect("an integer exponent") as u32;
            let mut acc = constant(1.0);
            for _ in 0..e {
                acc = mul(&acc, &base);
            }
            return acc;
        }
        base
    }
    fn unary(&mut self) -> Expanded {
        match self.peek() {
            Some(b'-') => {
                self.i += 1;
                scale(&self.unary(), -1.0)
            }
            Some(b'(') => {
                self.i += 1;
                let e = self.sum();
                assert_eq!(self.peek(), Some(b')'), "unbalanced parentheses");
                self.i += 1;
                e
            }
            Some(c) if c.is_ascii_digit() || c == b'.' => {
                let start = self.i;
                while self.i < self.s.len()
                    && (self.s[self.i].is_ascii_digit()
                        || matches!(self.s[self.i], b'.' | b'e')
                        || (self.s[self.i] == b'-' && self.s[self.i - 1] == b'e'))
                {
                    self.i += 1;
                }
                let text = std::str::from_utf8(&self.s[start..self.i]).unwrap();
                constant(text.parse().unwrap_or_else(|_| panic!("number {text:?}")))
            }
            Some(c) if c.is_ascii_alphabetic() => {
                let start = self.i;
                while self.i < self.s.len()
                    && (self.s[self.i].is_ascii_alphanumeric() || self.s[self.i] == b'_')
                {
                    self.i += 1;
                }
                let name = std::str::from_utf8(&self.s[start..self.i]).unwrap();
                let mut e = Expanded::new();
                e.insert(vec![name.to_string()], 1.0);
                e
            }
            other => panic!(
                "unexpected {:?} at {} in {:?}",
                other.map(char::from),
                self.i,
                std::str::from_utf8(self.s).unwrap()
            ),
        }
    }
}

fn parse(s: &str) -> Expanded {
    let mut p = Parser {
        s: s.as_bytes(),
        i: 0,
    };
    let e = p.sum();
    assert_eq!(p.peek(), None, "trailing text in {s:?}");
    e
}

fn constant(c: f64) -> Expanded {
    let mut e = Expanded::new();
    if c != 0.0 {
        e.insert(Vec::new(), c);
    }
    e
}

fn constant_value(e: &Expanded) -> Option<f64> {
    match e.len() {
        0 => Some(0.0),
        1 => e.get(&Vec::new()).copied(),
        _ => None,
    }
}

fn add(a: &Expanded, b: &Expanded) -> Expanded {
    let mut out = a.clone();
    for (m, c) in b {
        *out.entry(m.clone()).or_insert(0.0) += c;
    }
    out.retain(|_, c| c.abs() > 1e-13);
    out
}

fn scale(a: &Expanded, k: f64) -> Expanded {
    a.iter().map(|(m, c)| (m.clone(), c * k)).collect()
}

fn mul(a: &Expanded, b: &Expanded) -> Expanded {
    let mut out = Expanded::new();
    for (m1, c1) in a {
        for (m2, c2) in b {
            let mut m: Vec<String> = m1.iter().chain(m2).cloned().collect();
            m.sort();
            *out.entry(m).or_insert(0.0) += c1 * c2;
        }
    }
    out.retain(|_, c| c.abs() > 1e-13);
    out
}

/// The value of an atom: `c23` = cos(q2 + q3) (indices read per the grammar), lengths from
/// the symbols, prismatic variables from `q`.
fn atom_value(
    name: &str,
    q: &BTreeMap<u16, f64>,
    lengths: &BTreeMap<String, f64>,
    sep: bool,
) -> f64 {
    if let Some(v) = lengths.get(name) {
        return *v;
    }
    let (head, rest) = name.split_at(1);
    let indices: Vec<u16> = if sep {
        rest.split('_').map(|k| k.parse().unwrap()).collect()
    } else if head == "c" || head == "s" {
        rest.chars()
            .map(|k| k.to_digit(10).unwrap() as u16)
            .collect()
    } else {
        vec![rest.parse().unwrap()]
    };
    let angle: f64 = indices.iter().map(|k| q[k]).sum();
    match head {
        "c" => angle.cos(),
        "s" => angle.sin(),
        "d" | "q" => angle,
        _ => panic!("unknown atom {name}"),
    }
}

fn evaluate(
    e: &Expanded,
    q: &BTreeMap<u16, f64>,
    lengths: &BTreeMap<String, f64>,
    sep: bool,
) -> f64 {
    e.iter()
        .map(|(m, c)| {
            c * m
                .iter()
                .map(|a| atom_value(a, q, lengths, sep))
                .product::<f64>()
        })
        .sum()
}

fn pseudo_random(seed: u64, n: usize, lo: f64, hi: f64) -> Vec<f64> {
    let mut x = seed ^ 0x9e37_79b9_7f4a_7c15;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            lo + (hi - lo) * ((x >> 11) as f64 / (1u64 << 53) as f64)
        })
        .collect()
}

/// A joint vector inside the limits (the closed chains only close there).
fn random_q(robot: &Robot, seed: u64) -> Vec<f64> {
    let ranges = robot.sampling_ranges();
    let u = pseudo_random(seed, ranges.len(), 0.0, 1.0);
    ranges
        .iter()
        .zip(u)
        .map(|(r, t)| r[0] + (r[1] - r[0]) * (0.1 + 0.8 * t))
        .collect()
}

/// Checks the JSON strings of `T` (base to flange), parsed here, against the robot's FK.
fn check_against_fk(robot: &Robot, ee: usize, numbers: bool, seeds: u64) {
    let sk = derive(robot, ee, &Options { numbers }).unwrap();
    let doc = cli_json(&sk);
    let t: Vec<Vec<Expanded>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| parse(doc["T"][i][j].as_str().unwrap()))
                .collect()
        })
        .collect();
    let lengths: BTreeMap<String, f64> = if numbers {
        BTreeMap::new()
    } else {
        sk.symbols.clone()
    };
    for seed in 0..seeds {
        let q = random_q(robot, seed + 11);
        let values = sk.variable_values(robot, &q).unwrap();
        let by_index: BTreeMap<u16, f64> = sk
            .variables
            .iter()
            .zip(&values)
            .map(|(v, x)| (v.index, *x))
            .collect();
        let m = nalgebra::Matrix4::from_fn(|i, j| {
            evaluate(&t[i][j], &by_index, &lengths, sk.separate_indices)
        });
        let world = sk.base.to_homogeneous() * m * sk.tool.to_homogeneous();
        let expected = robot.fk_ee(&q, ee).unwrap().to_homogeneous();
        let err = (world - expected).abs().max();
        let scale = 1.0 + expected.abs().max();
        // a derived table with CAD noise rounded says by how much (at most 1e-9 m)
        let rounded = sk.rounded.unwrap_or(0.0);
        assert!(rounded <= 1e-9 * scale, "rounded by {rounded}");
        assert!(
            err < 1e-12 * scale + 3.0 * rounded,
            "{} ee {ee} numbers {numbers} q {q:?}: |symbolic - FK| = {err:e}\nsymbolic {world}\nFK {expected}",
            robot.name
        );
    }
}

/// The JSON document as the CLI writes it (the library function behind it).
fn cli_json(sk: &armlab::kinematics::symbolic::SymbolicKinematics) -> serde_json::Value {
    armlab::cli::symbolic_json(sk)
}

#[test]
fn every_built_in_symbolic_t_equals_its_fk() {
    for b in BUILT_INS {
        let robot = (b.build)();
        for ee in 0..robot.end_effectors().len() {
            check_against_fk(&robot, ee, false, 6);
            check_against_fk(&robot, ee, true, 3);
        }
    }
}

#[test]
fn model_files_and_urdf_arms_symbolic_t_equals_their_fk() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/urdf_corpus/");
    for name in [
        "ur5_robot.urdf",
        "kuka_iiwa14.urdf",
        "abb_irb2400.urdf",
        "unitree_z1.urdf",
    ] {
        let robot = armlab::model_file::load_model(&format!("{dir}{name}")).unwrap();
        check_against_fk(&robot, 0, false, 4);
    }
    let robot = armlab::model_file::load_model(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/robots/puma560.toml"
    ))
    .unwrap();
    check_against_fk(&robot, 0, false, 4);
}

/// `expected` (typed from the book) and `actual` (our JSON string) are the same polynomial in
/// the same atoms: the same terms, with the same compressed angle sums.
fn assert_same_terms(what: &str, actual: &str, expected: &str) {
    let a = parse(actual);
    let e = parse(expected);
    let diff = add(&a, &scale(&e, -1.0));
    assert!(
        diff.is_empty(),
        "{what}: armlab writes {actual:?}, the book {expected:?}; they differ by {diff:?}"
    );
}

fn json_of(model: &str) -> serde_json::Value {
    let robot = armlab::kinematics::models::built_in(model).unwrap();
    cli_json(&derive(&robot, 0, &Options::default()).unwrap())
}

/// Every entry of the rows given (typed from the book) has the same terms as `T`'s.
fn assert_rows(doc: &serde_json::Value, book: &[[&str; 4]]) {
    for (i, row) in book.iter().enumerate() {
        for (j, e) in row.iter().enumerate() {
            assert_same_terms(&format!("T[{i}][{j}]"), entry(doc, i, j), e);
        }
    }
}

fn entry(doc: &serde_json::Value, i: usize, j: usize) -> &str {
    doc["T"][i][j].as_str().unwrap()
}

#[test]
fn the_three_link_planar_arm_reads_like_2_63() {
    let doc = json_of("planar3");
    // (2.63), typed from the book
    let book = [
        ["c123", "-s123", "0", "a1*c1 + a2*c12 + a3*c123"],
        ["s123", "c123", "0", "a1*s1 + a2*s12 + a3*s123"],
        ["0", "0", "1", "0"],
        ["0", "0", "0", "1"],
    ];
    assert_rows(&doc, &book);
    assert_eq!(entry(&doc, 0, 3), "a1*c1 + a2*c12 + a3*c123");
    assert_eq!(doc["p_W"], serde_json::Value::Null);
}

#[test]
fn the_anthropomorphic_arm_reads_like_2_66_and_2_95_to_2_97() {
    let doc = json_of("anthropomorphic3r");
    // (2.66)
    let book = [
        ["c1*c23", "-c1*s23", "s1", "c1*(a2*c2 + a3*c23)"],
        ["s1*c23", "-s1*s23", "-c1", "s1*(a2*c2 + a3*c23)"],
        ["s23", "c23", "0", "a2*s2 + a3*s23"],
    ];
    assert_rows(&doc, &book);
    // (2.95)-(2.97), factored as the book writes them
    assert_eq!(entry(&doc, 0, 3), "c1*(a2*c2 + a3*c23)");
    assert_eq!(entry(&doc, 1, 3), "s1*(a2*c2 + a3*c23)");
    assert_eq!(entry(&doc, 2, 3), "a2*s2 + a3*s23");
}

#[test]
fn the_arm_with_spherical_wrist_reads_like_2_70() {
    let doc = json_of("anthropomorphic_spherical_wrist");
    // (2.70): n, s, a, p of the anthropomorphic arm with spherical wrist
    let n = [
        "c1*(c23*(c4*c5*c6 - s4*s6) - s23*s5*c6) + s1*(s4*c5*c6 + c4*s6)",
        "s1*(c23*(c4*c5*c6 - s4*s6) - s23*s5*c6) - c1*(s4*c5*c6 + c4*s6)",
        "s23*(c4*c5*c6 - s4*s6) + c23*s5*c6",
    ];
    let s = [
        "c1*(-c23*(c4*c5*s6 + s4*c6) + s23*s5*s6) + s1*(-s4*c5*s6 + c4*c6)",
        "s1*(-c23*(c4*c5*s6 + s4*c6) + s23*s5*s6) - c1*(-s4*c5*s6 + c4*c6)",
        "-s23*(c4*c5*s6 + s4*c6) - c23*s5*s6",
    ];
    let a = [
        "c1*(c23*c4*s5 + s23*c5) + s1*s4*s5",
        "s1*(c23*c4*s5 + s23*c5) - c1*s4*s5",
        "s23*c4*s5 - c23*c5",
    ];
    let p = [
        "a2*c1*c2 + d4*c1*s23 + d6*(c1*(c23*c4*s5 + s23*c5) + s1*s4*s5)",
        "a2*s1*c2 + d4*s1*s23 + d6*(s1*(c23*c4*s5 + s23*c5) - c1*s4*s5)",
        "a2*s2 - d4*c23 + d6*(s23*c4*s5 - c23*c5)",
    ];
    for (j, col) in [n, s, a, p].iter().enumerate() {
        for (i, e) in col.iter().enumerate() {
            assert_same_terms(&format!("T[{i}][{j}]"), entry(&doc, i, j), e);
        }
    }
    // the wrist point: (2.70) with d6 = 0, the origin of frame 4
    let pw = doc["p_W"].as_array().expect("a spherical wrist");
    assert_same_terms("p_Wx", pw[0].as_str().unwrap(), "c1*(a2*c2 + d4*s23)");
    assert_same_terms("p_Wz", pw[2].as_str().unwrap(), "a2*s2 - d4*c23");
}

#[test]
fn the_spherical_arm_wrist_and_stanford_manipulator_read_like_the_book() {
    // Spherical arm, Sect. 2.9.3
    let doc = json_of("spherical_arm");
    let book = [
        ["c1*c2", "-s1", "c1*s2", "c1*s2*d3 - s1*d2"],
        ["s1*c2", "c1", "s1*s2", "s1*s2*d3 + c1*d2"],
        ["-s2", "0", "c2", "c2*d3"],
    ];
    assert_rows(&doc, &book);
    // Spherical wrist, Sect. 2.9.5, numbered 4-6 as in the book
    let doc = json_of("spherical_wrist");
    let book = [
        ["c4*c5*c6 - s4*s6", "-c4*c5*s6 - s4*c6", "c4*s5", "c4*s5*d6"],
        ["s4*c5*c6 + c4*s6", "-s4*c5*s6 + c4*c6", "s4*s5", "s4*s5*d6"],
        ["-s5*c6", "s5*s6", "c5", "c5*d6"],
    ];
    assert_rows(&doc, &book);
    // Stanford manipulator, Sect. 2.9.6: p of (2.68) and its wrist point
    let doc = json_of("stanford");
    let p = [
        "c1*s2*d3 - s1*d2 + (c1*(c2*c4*s5 + s2*c5) - s1*s4*s5)*d6",
        "s1*s2*d3 + c1*d2 + (s1*(c2*c4*s5 + s2*c5) + c1*s4*s5)*d6",
        "c2*d3 + (-s2*c4*s5 + c2*c5)*d6",
    ];
    for (i, e) in p.iter().enumerate() {
        assert_same_terms(&format!("p[{i}]"), entry(&doc, i, 3), e);
    }
    let pw = doc["p_W"].as_array().unwrap();
    assert_same_terms("p_W", pw[2].as_str().unwrap(), "c2*d3");
}

#[test]
fn numbers_substitute_the_lengths() {
    let robot = armlab::kinematics::models::built_in("anthropomorphic3r").unwrap();
    let doc = cli_json(&derive(&robot, 0, &Options { numbers: true }).unwrap());
    assert_same_terms("p_x", entry(&doc, 0, 3), "c1*(c2 + c23)");
    assert_eq!(doc["symbols"]["a2"], 1.0);
}

fn armlab(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .output()
        .expect("run armlab")
}

fn stdout(args: &[&str]) -> String {
    let o = armlab(args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).unwrap()
}

#[test]
fn the_issue_s_commands_print_the_book_s_forms() {
    // `armlab symbolic planar3` prints (2.63)'s entries in the textbook's form
    let text = stdout(&["symbolic", "planar3"]);
    for e in [
        "c123",
        "-s123",
        "a1c1 + a2c12 + a3c123",
        "a1s1 + a2s12 + a3s123",
    ] {
        assert!(text.contains(e), "{e} missing from\n{text}");
    }
    // `armlab symbolic anthropomorphic3r` prints p = (c1(a2c2 + a3c23), ...)
    let text = stdout(&["symbolic", "anthropomorphic3r"]);
    assert!(
        text.contains("p = (c1(a2c2 + a3c23), s1(a2c2 + a3c23), a2s2 + a3s23)"),
        "{text}"
    );
    // --numbers substitutes the lengths (a2 = a3 = 1 m)
    let text = stdout(&["symbolic", "anthropomorphic3r", "--numbers"]);
    assert!(
        text.contains("p = (c1(c2 + c23), s1(c2 + c23), s2 + s23)"),
        "{text}"
    );
    // the wrist point of a decoupled arm, as in (2.95)-(2.97) with d4 for a3
    let text = stdout(&["symbolic", "anthropomorphic_spherical_wrist"]);
    assert!(text.contains("p_Wx = c1(a2c2 + d4s23)"), "{text}");
}

#[test]
fn latex_markdown_and_json_formats() {
    let latex = stdout(&["symbolic", "anthropomorphic3r", "--format", "latex"]);
    assert!(latex.contains("\\begin{bmatrix}"), "{latex}");
    assert!(
        latex.contains("c_{1}\\left(a_{2}c_{2} + a_{3}c_{23}\\right)"),
        "{latex}"
    );
    let md = stdout(&["symbolic", "planar3", "--format", "markdown"]);
    assert!(
        md.contains("$$") && md.contains("a_{1}c_{1} + a_{2}c_{12} + a_{3}c_{123}"),
        "{md}"
    );
    let doc: serde_json::Value =
        serde_json::from_str(&stdout(&["symbolic", "puma560", "--format", "json"])).unwrap();
    for key in ["model", "convention", "symbols", "A", "T", "p_W"] {
        assert!(doc.get(key).is_some(), "no {key}");
    }
    assert_eq!(doc["convention"], "standard");
    assert_eq!(doc["A"].as_array().unwrap().len(), 6);
    assert_eq!(doc["A"][0]["from"], 0);
    assert_eq!(doc["A"][0]["to"], 1);
    assert_eq!(doc["A"][0]["matrix"].as_array().unwrap().len(), 4);
    assert!((doc["symbols"]["a2"].as_f64().unwrap() - 0.4318).abs() < 1e-15);
    assert_eq!(doc["p_W"].as_array().unwrap().len(), 3);
    // every string parses in the grammar
    for row in doc["T"].as_array().unwrap() {
        for e in row.as_array().unwrap() {
            parse(e.as_str().unwrap());
        }
    }
}

#[test]
fn a_urdf_arm_reads_in_dh_symbols_and_bad_input_is_one_line() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/urdf_corpus/");
    let text = stdout(&["symbolic", &format!("{dir}ur5_robot.urdf")]);
    assert!(text.contains("a2c2 + a3c23"), "{text}");
    assert!(text.contains("c234"), "{text}");
    let o = armlab(&["symbolic", "no_such_robot"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(String::from_utf8_lossy(&o.stderr).lines().count(), 1);
}

// ---------------------------------------------------------------------------------------------
// `armlab symbolic --rotation`: the matrices of Sects. 2.4-2.6 in symbols.

use armlab::kinematics::symbolic::rotation::{REPRESENTATIONS, Representation, derive_rotation};

type M3 = [[f64; 3]; 3];

/// The elementary rotations (2.6)-(2.8), written out here.
fn rot_x(a: f64) -> M3 {
    let (c, s) = (a.cos(), a.sin());
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}
fn rot_y(a: f64) -> M3 {
    let (c, s) = (a.cos(), a.sin());
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}
fn rot_z(a: f64) -> M3 {
    let (c, s) = (a.cos(), a.sin());
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}
fn mul3(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}
fn product(ms: &[M3]) -> M3 {
    ms.iter().fold(rot_z(0.0), |acc, m| mul3(&acc, m))
}

/// The rotation by `theta` about the unit axis `r` as the book derives (2.25): align r with z
/// (alpha about z, beta about y), turn about z, undo the alignment,
/// R = Rz(alpha) Ry(beta) Rz(theta) Ry(-beta) Rz(-alpha).
fn about_axis(theta: f64, r: [f64; 3]) -> M3 {
    let alpha = r[1].atan2(r[0]);
    let beta = r[2].clamp(-1.0, 1.0).acos();
    product(&[
        rot_z(alpha),
        rot_y(beta),
        rot_z(theta),
        rot_y(-beta),
        rot_z(-alpha),
    ])
}

fn rotation_json(rep: Representation) -> serde_json::Value {
    armlab::cli::symbolic_rotation_json(&derive_rotation(rep))
}

fn rotation_entry(doc: &serde_json::Value, i: usize, j: usize) -> &str {
    doc["R"][i][j].as_str().unwrap()
}

/// The book's matrix of each representation, typed in the grammar from (2.18), (2.21), (2.25),
/// (2.33), and for ZXZ (Problem 2.1) the product Rz(phi) Rx(theta) Rz(psi) multiplied out by
/// hand.
fn book_rotation(rep: Representation) -> [[&'static str; 3]; 3] {
    match rep {
        Representation::Zxz => [
            [
                "c_phi*c_psi - s_phi*c_theta*s_psi",
                "-c_phi*s_psi - s_phi*c_theta*c_psi",
                "s_phi*s_theta",
            ],
            [
                "s_phi*c_psi + c_phi*c_theta*s_psi",
                "-s_phi*s_psi + c_phi*c_theta*c_psi",
                "-c_phi*s_theta",
            ],
            ["s_theta*s_psi", "s_theta*c_psi", "c_theta"],
        ],
        Representation::Zyz => [
            [
                "c_phi*c_theta*c_psi - s_phi*s_psi",
                "-c_phi*c_theta*s_psi - s_phi*c_psi",
                "c_phi*s_theta",
            ],
            [
                "s_phi*c_theta*c_psi + c_phi*s_psi",
                "-s_phi*c_theta*s_psi + c_phi*c_psi",
                "s_phi*s_theta",
            ],
            ["-s_theta*c_psi", "s_theta*s_psi", "c_theta"],
        ],
        Representation::Rpy => [
            [
                "c_phi*c_theta",
                "c_phi*s_theta*s_psi - s_phi*c_psi",
                "c_phi*s_theta*c_psi + s_phi*s_psi",
            ],
            [
                "s_phi*c_theta",
                "s_phi*s_theta*s_psi + c_phi*c_psi",
                "s_phi*s_theta*c_psi - c_phi*s_psi",
            ],
            ["-s_theta", "c_theta*s_psi", "c_theta*c_psi"],
        ],
        Representation::AxisAngle => [
            [
                "r_x^2*(1 - c_theta) + c_theta",
                "r_x*r_y*(1 - c_theta) - r_z*s_theta",
                "r_x*r_z*(1 - c_theta) + r_y*s_theta",
            ],
            [
                "r_x*r_y*(1 - c_theta) + r_z*s_theta",
                "r_y^2*(1 - c_theta) + c_theta",
                "r_y*r_z*(1 - c_theta) - r_x*s_theta",
            ],
            [
                "r_x*r_z*(1 - c_theta) - r_y*s_theta",
                "r_y*r_z*(1 - c_theta) + r_x*s_theta",
                "r_z^2*(1 - c_theta) + c_theta",
            ],
        ],
        Representation::Quaternion => [
            [
                "2*(eta^2 + epsilon_x^2) - 1",
                "2*(epsilon_x*epsilon_y - eta*epsilon_z)",
                "2*(epsilon_x*epsilon_z + eta*epsilon_y)",
            ],
            [
                "2*(epsilon_x*epsilon_y + eta*epsilon_z)",
                "2*(eta^2 + epsilon_y^2) - 1",
                "2*(epsilon_y*epsilon_z - eta*epsilon_x)",
            ],
            [
                "2*(epsilon_x*epsilon_z - eta*epsilon_y)",
                "2*(epsilon_y*epsilon_z + eta*epsilon_x)",
                "2*(eta^2 + epsilon_z^2) - 1",
            ],
        ],
    }
}

#[test]
fn rotation_matrices_read_like_2_18_2_21_2_25_2_33_and_problem_2_1() {
    for rep in REPRESENTATIONS {
        let doc = rotation_json(rep);
        let book = book_rotation(rep);
        for (i, row) in book.iter().enumerate() {
            for (j, e) in row.iter().enumerate() {
                let what = format!("{rep} R[{i}][{j}]");
                let actual = rotation_entry(&doc, i, j);
                assert_same_terms(&what, actual, e);
                // simplified: no unit factor and no multiplication by one written out
                assert!(
                    !actual.starts_with("1*") && !actual.contains(" 1*") && !actual.contains("*1"),
                    "{what}: {actual}"
                );
            }
        }
        // `symbols` names exactly the atoms of the entries, each with its meaning
        let mut atoms: Vec<String> = (0..9)
            .flat_map(|k| parse(rotation_entry(&doc, k / 3, k % 3)).into_keys())
            .flatten()
            .collect();
        atoms.sort();
        atoms.dedup();
        let mut listed: Vec<String> = doc["symbols"]
            .as_object()
            .unwrap()
            .keys()
            .cloned()
            .collect();
        listed.sort();
        assert_eq!(atoms, listed, "{rep}");
        assert_eq!(doc["rotation"], rep.name());
        assert_eq!(doc["grammar"], json_of("planar3")["grammar"], "one grammar");
    }
}

#[test]
fn rotation_matrices_are_grouped_as_the_book_writes_them() {
    let doc = rotation_json(Representation::AxisAngle);
    // (2.25): every entry has (1 - c_theta) once, the diagonal r_k^2(1 - c_theta) + c_theta
    for (i, k) in ["x", "y", "z"].iter().enumerate() {
        assert_eq!(
            rotation_entry(&doc, i, i),
            format!("r_{k}^2*(1 - c_theta) + c_theta")
        );
        for j in 0..3 {
            assert_eq!(
                rotation_entry(&doc, i, j).matches("(1 - c_theta)").count(),
                1
            );
        }
    }
    assert_eq!(
        rotation_entry(&doc, 0, 1),
        "r_x*r_y*(1 - c_theta) - r_z*s_theta"
    );
    let doc = rotation_json(Representation::Quaternion);
    // (2.33): 2(eta^2 + epsilon_k^2) - 1 on the diagonal, 2(...) off it
    for (i, k) in ["x", "y", "z"].iter().enumerate() {
        assert_eq!(
            rotation_entry(&doc, i, i),
            format!("2*(eta^2 + epsilon_{k}^2) - 1")
        );
        for j in (0..3).filter(|&j| j != i) {
            let e = rotation_entry(&doc, i, j);
            assert!(e.starts_with("2*(") && e.ends_with(')'), "{e}");
        }
    }
    assert_eq!(
        rotation_entry(&doc, 0, 1),
        "2*(epsilon_x*epsilon_y - eta*epsilon_z)"
    );
}

/// The values of the atoms `c_phi`, `r_x`, `eta`, ... for the evaluator (passed as its lengths).
fn atoms(values: &[(&str, f64)]) -> BTreeMap<String, f64> {
    let mut out = BTreeMap::new();
    for &(name, v) in values {
        if ["phi", "theta", "psi"].contains(&name) {
            out.insert(format!("c_{name}"), v.cos());
            out.insert(format!("s_{name}"), v.sin());
        } else {
            out.insert(name.to_string(), v);
        }
    }
    out
}

/// The JSON strings of `rep`, parsed here, evaluated at `values` and compared with `expected`.
fn check_rotation(rep: Representation, values: &[(&str, f64)], expected: &M3) {
    let doc = rotation_json(rep);
    let a = atoms(values);
    let none = BTreeMap::new();
    for (i, row) in expected.iter().enumerate() {
        for (j, want) in row.iter().enumerate() {
            let v = evaluate(&parse(rotation_entry(&doc, i, j)), &none, &a, false);
            assert!(
                (v - want).abs() < 1e-13,
                "{rep} R[{i}][{j}] at {values:?}: symbols give {v}, the elementary product {want}"
            );
        }
    }
}

#[test]
fn rotation_matrices_equal_the_elementary_products_at_100_angle_sets() {
    use std::f64::consts::PI;
    for k in 0..100u64 {
        let u = pseudo_random(k + 1000, 7, -1.0, 1.0);
        let (phi, theta, psi) = (PI * u[0], PI * u[1], PI * u[2]);
        let angles = [("phi", phi), ("theta", theta), ("psi", psi)];
        let zxz = product(&[rot_z(phi), rot_x(theta), rot_z(psi)]);
        check_rotation(Representation::Zxz, &angles, &zxz);
        let zyz = product(&[rot_z(phi), rot_y(theta), rot_z(psi)]);
        check_rotation(Representation::Zyz, &angles, &zyz);
        let rpy = product(&[rot_z(phi), rot_y(theta), rot_x(psi)]);
        check_rotation(Representation::Rpy, &angles, &rpy);
        // angle and axis: a random unit axis
        let n = (u[3] * u[3] + u[4] * u[4] + u[5] * u[5]).sqrt().max(1e-3);
        let r = [u[3] / n, u[4] / n, u[5] / n];
        let expected = about_axis(theta, r);
        let values = [
            ("theta", theta),
            ("r_x", r[0]),
            ("r_y", r[1]),
            ("r_z", r[2]),
        ];
        check_rotation(Representation::AxisAngle, &values, &expected);
        // the quaternion of the same rotation, (2.30)-(2.31): eta = cos(theta/2),
        // epsilon = sin(theta/2) r
        let (c, s) = ((theta / 2.0).cos(), (theta / 2.0).sin());
        let values = [
            ("eta", c),
            ("epsilon_x", s * r[0]),
            ("epsilon_y", s * r[1]),
            ("epsilon_z", s * r[2]),
        ];
        check_rotation(Representation::Quaternion, &values, &expected);
    }
}

#[test]
fn the_rotation_commands_print_the_book_s_notation() {
    let text = stdout(&["symbolic", "--rotation", "zxz"]);
    assert!(
        text.contains("r11 = c_phi c_psi - s_phi c_theta s_psi"),
        "{text}"
    );
    assert!(text.contains("R = Rz(phi) Rx'(theta) Rz''(psi)"), "{text}");
    let latex = stdout(&["symbolic", "--rotation", "zxz", "--format", "latex"]);
    assert!(
        latex.contains("c_\\varphi c_\\psi - s_\\varphi c_\\vartheta s_\\psi"),
        "{latex}"
    );
    let text = stdout(&["symbolic", "--rotation", "axis-angle"]);
    assert!(
        text.contains("r11 = r_x^2(1 - c_theta) + c_theta"),
        "{text}"
    );
    assert!(
        text.contains("r12 = r_x r_y(1 - c_theta) - r_z s_theta"),
        "{text}"
    );
    let text = stdout(&["symbolic", "--rotation", "quaternion"]);
    assert!(text.contains("r11 = 2(eta^2 + epsilon_x^2) - 1"), "{text}");
    assert!(
        text.contains("r12 = 2(epsilon_x epsilon_y - eta epsilon_z)"),
        "{text}"
    );
    let md = stdout(&["symbolic", "--rotation", "rpy", "--format", "markdown"]);
    assert!(
        md.contains("$$") && md.contains("c_\\varphi c_\\vartheta"),
        "{md}"
    );
    for rep in ["zxz", "zyz", "rpy", "axis-angle", "quaternion"] {
        let doc: serde_json::Value = serde_json::from_str(&stdout(&[
            "symbolic",
            "--rotation",
            rep,
            "--format",
            "json",
        ]))
        .unwrap();
        assert_eq!(doc["rotation"], rep);
        assert_eq!(doc["R"].as_array().unwrap().len(), 3);
        for key in [
            "equation",
            "formula",
            "variables",
            "symbols",
            "constraint",
            "grammar",
        ] {
            assert!(doc.get(key).is_some(), "{rep}: no {key}");
        }
    }
}
