//! The symbolic kinematics written out whole: plain text for the terminal, LaTeX to paste into
//! a handout, Markdown (with LaTeX blocks) for notes. Pure string building; the CLI and the app
//! print or copy what this returns.

use super::expr::{Style, number, write};
use super::poly::{Factor, Poly, Symbol};
use super::rotation::{Representation, SymbolicRotation};
use super::{SymMatrix, SymbolicKinematics};
use crate::kinematics::JointKind;
use std::fmt::Write as _;

/// Above this many characters an entry of `T` is listed on its own line instead of in a grid.
const GRID_WIDTH: usize = 28;

/// Each entry of `m` (a 4x4 transform or a 3x3 rotation) written in `style`.
pub fn strings<const N: usize>(
    m: &[[Poly; N]; N],
    style: Style,
    separate: bool,
) -> [[String; N]; N] {
    std::array::from_fn(|i| std::array::from_fn(|j| write(&m[i][j], style, separate)))
}

/// The position column (x, y, z) written in `style`.
pub fn position(m: &SymMatrix, style: Style, separate: bool) -> [String; 3] {
    std::array::from_fn(|i| write(&m[i][3], style, separate))
}

/// A vector of three polynomials written in `style`.
pub fn vector(v: &[Poly; 3], style: Style, separate: bool) -> [String; 3] {
    std::array::from_fn(|i| write(&v[i], style, separate))
}

/// The textbook's name of the variable of row `to` (1-based): `q1` (the joint vector's
/// component), shown with the joint it drives.
fn variable_list(sk: &SymbolicKinematics) -> String {
    sk.variables
        .iter()
        .map(|v| {
            let what = match v.kind {
                JointKind::Prismatic => "m",
                _ => "rad",
            };
            let passive = match v.source {
                super::Source::Passive(_) => ", follows the loop",
                super::Source::Actuated(_) => "",
            };
            format!("q{} = joint {:?} ({what}{passive})", v.index, v.joint)
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A matrix as an aligned grid, each line indented by two spaces.
fn grid(cells: &[[String; 4]; 4]) -> String {
    let widths: Vec<usize> = (0..4)
        .map(|j| {
            cells
                .iter()
                .map(|r| r[j].chars().count())
                .max()
                .unwrap_or(1)
        })
        .collect();
    let mut s = String::new();
    for row in cells {
        let line: Vec<String> = row
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c:<w$}"))
            .collect();
        let _ = writeln!(s, "  [ {} ]", line.join("   "));
    }
    s
}

/// The names of the entries of T by column: n, s, a (the unit vectors of the end-effector
/// frame, (2.49)) and p.
const COLUMNS: [&str; 4] = ["n", "s", "a", "p"];
const AXES: [&str; 3] = ["x", "y", "z"];

/// A matrix as a grid if its entries are short, otherwise as the textbook's column vectors
/// n, s, a, p entry by entry, as (2.70) is printed.
fn matrix_text(m: &SymMatrix, separate: bool) -> String {
    let cells = strings(m, Style::Text, separate);
    let longest = cells.iter().flatten().map(|c| c.len()).max().unwrap_or(0);
    if longest <= GRID_WIDTH {
        return grid(&cells);
    }
    let mut s = String::new();
    for (j, col) in COLUMNS.iter().enumerate() {
        for (i, axis) in AXES.iter().enumerate() {
            let _ = writeln!(s, "  {col}_{axis} = {}", cells[i][j]);
        }
    }
    s
}

/// The unit of a length symbol's value.
fn symbol_list(sk: &SymbolicKinematics) -> String {
    sk.symbols
        .iter()
        .map(|(k, v)| format!("{k} = {} m", number(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The frames the product maps between: (0, n) for an arm, (3, 6) for the wrist alone.
pub fn span(sk: &SymbolicKinematics) -> (usize, usize) {
    match (sk.links.first(), sk.links.last()) {
        (Some(a), Some(b)) => (a.from, b.to),
        _ => (0, 0),
    }
}

/// The whole derivation in plain text.
pub fn text(sk: &SymbolicKinematics, numbers: bool) -> String {
    let sep = sk.separate_indices;
    let mut s = String::new();
    let derived = match (sk.derived_dh, sk.rounded) {
        (true, Some(r)) => format!(
            ", the DH table derived from the model's joint origins and axes, CAD noise rounded: \
             the end-effector moves by at most {r:.1e} m"
        ),
        (true, None) => ", the DH table derived from the model's joint origins and axes".into(),
        _ => String::new(),
    };
    let _ = writeln!(s, "{} ({} convention{derived})", sk.model, sk.convention);
    let _ = writeln!(s, "variables: {}", variable_list(sk));
    let _ = writeln!(
        s,
        "notation: c1 = cos(q1), s1 = sin(q1), c23 = cos(q2 + q3), s23 = sin(q2 + q3)"
    );
    if !sk.symbols.is_empty() {
        let verb = if numbers { "substituted" } else { "symbols" };
        let _ = writeln!(s, "{verb}: {}", symbol_list(sk));
    }
    for link in &sk.links {
        let _ = writeln!(
            s,
            "\nA_{}^{}(q{}) =   joint {:?}",
            link.to, link.from, link.to, link.joint
        );
        s.push_str(&matrix_text(&link.matrix, sep));
    }
    let product: Vec<String> = sk
        .links
        .iter()
        .map(|l| format!("A_{}^{}", l.to, l.from))
        .collect();
    let t = sk.t();
    let (lo, hi) = span(sk);
    let _ = writeln!(s, "\nT_{hi}^{lo} = {} =", product.join(" "));
    s.push_str(&matrix_text(&t, sep));
    let p = position(&t, Style::Text, sep);
    let _ = writeln!(s, "\np = ({}, {}, {})", p[0], p[1], p[2]);
    if let Some((k, pw)) = &sk.wrist {
        let w = vector(pw, Style::Text, sep);
        let _ = writeln!(
            s,
            "p_W = ({}, {}, {})   (the wrist point: origin of frame {k})",
            w[0], w[1], w[2]
        );
        for (axis, e) in AXES.iter().zip(&w) {
            let _ = writeln!(s, "  p_W{axis} = {e}");
        }
    }
    if sk.base != crate::kinematics::Pose::identity()
        || sk.tool != crate::kinematics::Pose::identity()
    {
        let _ = writeln!(
            s,
            "\nThe end-effector pose is T = T_b T_{hi}^{lo} T_e with the model's constant base T_b \
             and tool T_e."
        );
    }
    s
}

/// A matrix (a 4x4 transform or a 3x3 rotation) in LaTeX (`bmatrix`).
pub fn latex_matrix<const N: usize>(m: &[[Poly; N]; N], separate: bool) -> String {
    let cells = strings(m, Style::Latex, separate);
    let rows: Vec<String> = cells.iter().map(|r| r.join(" & ")).collect();
    format!(
        "\\begin{{bmatrix}}\n{}\n\\end{{bmatrix}}",
        rows.join(" \\\\\n")
    )
}

/// The LaTeX name of variable k (`\vartheta_{1}`, `d_{3}`).
fn latex_variable(sk: &SymbolicKinematics, k: usize) -> String {
    match sk.variables.get(k.wrapping_sub(1)).map(|v| v.kind) {
        Some(JointKind::Prismatic) => format!("q_{{{k}}}"),
        _ => format!("\\vartheta_{{{k}}}"),
    }
}

/// Each `A_i^{i-1}(q_i) = ...` and then `T_n^0 = ...` as a LaTeX equation.
fn matrix_equations(sk: &SymbolicKinematics) -> Vec<String> {
    let sep = sk.separate_indices;
    let mut out: Vec<String> = sk
        .links
        .iter()
        .map(|link| {
            format!(
                "A_{{{}}}^{{{}}}({}) = {}",
                link.to,
                link.from,
                latex_variable(sk, link.to),
                latex_matrix(&link.matrix, sep)
            )
        })
        .collect();
    let (lo, hi) = span(sk);
    out.push(format!(
        "T_{{{hi}}}^{{{lo}}} = {}",
        latex_matrix(&sk.t(), sep)
    ));
    out
}

/// The derivation as LaTeX display equations (for `amsmath`), one per matrix.
pub fn latex(sk: &SymbolicKinematics) -> String {
    let sep = sk.separate_indices;
    let mut s = String::new();
    for eq in matrix_equations(sk) {
        let _ = writeln!(s, "{eq}\n");
    }
    if let Some((_, pw)) = &sk.wrist {
        let w = vector(pw, Style::Latex, sep);
        let _ = writeln!(
            s,
            "\\boldsymbol{{p}}_W = \\begin{{bmatrix}} {} \\\\ {} \\\\ {} \\end{{bmatrix}}",
            w[0], w[1], w[2]
        );
    }
    s
}

/// The derivation as Markdown with `$$` LaTeX blocks (GitHub, mdBook with MathJax, Jupyter).
pub fn markdown(sk: &SymbolicKinematics, numbers: bool) -> String {
    let sep = sk.separate_indices;
    let mut s = String::new();
    let _ = writeln!(s, "# Direct kinematics of the {}\n", sk.model);
    let _ = writeln!(
        s,
        "Convention: {} DH. Notation: $c_{{1}} = \\cos\\vartheta_{{1}}$, $s_{{23}} = \\sin(\\vartheta_{{2}} + \\vartheta_{{3}})$.\n",
        sk.convention
    );
    if !sk.symbols.is_empty() {
        let verb = if numbers {
            "Substituted lengths"
        } else {
            "Lengths"
        };
        let _ = writeln!(s, "{verb}: {}.\n", symbol_list(sk));
    }
    for eq in matrix_equations(sk) {
        let _ = writeln!(s, "$$\n{eq}\n$$\n");
    }
    if let Some((_, pw)) = &sk.wrist {
        let w = vector(pw, Style::Latex, sep);
        for (axis, e) in AXES.iter().zip(&w) {
            let _ = writeln!(s, "$$p_{{W{axis}}} = {e}$$\n");
        }
    }
    s
}

/// What a symbol of a rotation stands for, in words: `cos(phi)`, `the unit axis' x
/// component`; `None` for an arm's factor (`c1`, `a2`), which the arm's text explains.
///
/// ```
/// use armlab::kinematics::symbolic::document::meaning;
/// use armlab::kinematics::symbolic::poly::{Angle, Factor, Symbol};
/// assert_eq!(meaning(&Factor::SinOf(Symbol::Theta)).unwrap(), "sin(theta)");
/// assert_eq!(
///     meaning(&Factor::Symbol(Symbol::Eta)).unwrap(),
///     "the quaternion's scalar part"
/// );
/// assert!(meaning(&Factor::Cos(Angle::one(1))).is_none());
/// ```
pub fn meaning(f: &Factor) -> Option<String> {
    Some(match f {
        Factor::CosOf(s) => format!("cos({s})"),
        Factor::SinOf(s) => format!("sin({s})"),
        Factor::Symbol(s) => match s {
            Symbol::Rx => "the unit axis' x component".into(),
            Symbol::Ry => "the unit axis' y component".into(),
            Symbol::Rz => "the unit axis' z component".into(),
            Symbol::Eta => "the quaternion's scalar part".into(),
            Symbol::EpsilonX => "the quaternion's vector part, x component".into(),
            Symbol::EpsilonY => "the quaternion's vector part, y component".into(),
            Symbol::EpsilonZ => "the quaternion's vector part, z component".into(),
            Symbol::Phi | Symbol::Theta | Symbol::Psi => format!("the angle {s} (rad)"),
        },
        _ => return None,
    })
}

/// The units of a rotation's variables, in words: `phi, theta, psi (rad)`.
fn rotation_variables(r: &SymbolicRotation) -> String {
    let names = |v: &[Symbol]| v.iter().map(|s| s.name()).collect::<Vec<_>>().join(", ");
    let v = r.representation.variables();
    match r.representation {
        Representation::AxisAngle => {
            format!("{} (rad), r = ({}) a unit vector", v[0], names(&v[1..]))
        }
        Representation::Quaternion => format!(
            "eta = cos(theta/2), epsilon = ({}) = sin(theta/2) r (2.30)-(2.31)",
            names(&v[1..])
        ),
        _ => format!("{} (rad)", names(v)),
    }
}

/// A rotation matrix in plain text: what it represents, its variables and symbols, then each
/// entry `r11 = c_phi c_psi - s_phi c_theta s_psi`, as `armlab symbolic --rotation` prints it.
///
/// ```
/// use armlab::kinematics::symbolic::document::rotation_text;
/// use armlab::kinematics::symbolic::rotation::{Representation, derive_rotation};
/// let text = rotation_text(&derive_rotation(Representation::Rpy));
/// assert!(text.contains("R = Rz(phi) Ry(theta) Rx(psi)"), "{text}");
/// assert!(text.contains("r31 = -s_theta"), "{text}");
/// ```
pub fn rotation_text(r: &SymbolicRotation) -> String {
    let rep = r.representation;
    let mut s = String::new();
    let _ = writeln!(s, "{}, {}: {}", rep.title(), rep.equation(), rep.formula());
    let _ = writeln!(s, "variables: {}", rotation_variables(r));
    let notation: Vec<String> = r
        .symbols()
        .iter()
        .filter(|f| matches!(f, Factor::CosOf(_) | Factor::SinOf(_)))
        .filter_map(|f| {
            Some(format!(
                "{} = {}",
                write_symbol(f, Style::Text),
                meaning(f)?
            ))
        })
        .collect();
    if !notation.is_empty() {
        let _ = writeln!(s, "notation: {}", notation.join(", "));
    }
    if let Some(norm) = rep.constraint() {
        let _ = writeln!(s, "with {} = 1", write(&norm, Style::Text, false));
    }
    let cells = strings(&r.matrix, Style::Text, false);
    let _ = writeln!(s, "\nR =");
    for (i, row) in cells.iter().enumerate() {
        for (j, e) in row.iter().enumerate() {
            let _ = writeln!(s, "  r{}{} = {e}", i + 1, j + 1);
        }
    }
    s
}

/// One factor alone, as the entries write it (`c_phi`).
fn write_symbol(f: &Factor, style: Style) -> String {
    write(&Poly::factor(f.clone()), style, false)
}

/// The left-hand side of the rotation's equation in LaTeX: `R(\varphi, \vartheta, \psi)`.
fn rotation_lhs(r: &SymbolicRotation) -> String {
    match r.representation {
        Representation::AxisAngle => "R(\\vartheta, \\boldsymbol{r})".into(),
        Representation::Quaternion => "R(\\eta, \\boldsymbol{\\epsilon})".into(),
        rep => {
            let v: Vec<&str> = rep.variables().iter().map(|s| s.latex()).collect();
            format!("R({})", v.join(", "))
        }
    }
}

/// A rotation matrix as a LaTeX display equation (for `amsmath`), in the textbook's letters:
/// `c_\varphi c_\psi - s_\varphi c_\vartheta s_\psi`.
///
/// ```
/// use armlab::kinematics::symbolic::document::rotation_latex;
/// use armlab::kinematics::symbolic::rotation::{Representation, derive_rotation};
/// let latex = rotation_latex(&derive_rotation(Representation::Zxz));
/// assert!(latex.starts_with("R(\\varphi, \\vartheta, \\psi) = \\begin{bmatrix}"));
/// assert!(latex.contains("c_\\varphi c_\\psi - s_\\varphi c_\\vartheta s_\\psi"));
/// ```
pub fn rotation_latex(r: &SymbolicRotation) -> String {
    format!("{} = {}\n", rotation_lhs(r), latex_matrix(&r.matrix, false))
}

/// A rotation matrix as Markdown with a `$$` LaTeX block (GitHub, mdBook with MathJax,
/// Jupyter).
///
/// ```
/// use armlab::kinematics::symbolic::document::rotation_markdown;
/// use armlab::kinematics::symbolic::rotation::{Representation, derive_rotation};
/// let md = rotation_markdown(&derive_rotation(Representation::Quaternion));
/// assert!(md.starts_with("# Unit quaternion, (2.33)"), "{md}");
/// assert!(md.contains("2\\left(\\eta^{2} + \\epsilon_x^{2}\\right) - 1"), "{md}");
/// ```
pub fn rotation_markdown(r: &SymbolicRotation) -> String {
    let rep = r.representation;
    let mut s = String::new();
    let _ = writeln!(s, "# {}, {}\n", rep.title(), rep.equation());
    let _ = writeln!(
        s,
        "`{}`; variables: {}.\n",
        rep.formula(),
        rotation_variables(r)
    );
    let _ = writeln!(s, "$$\n{}\n$$", rotation_latex(r).trim_end());
    s
}
