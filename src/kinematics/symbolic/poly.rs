//! Polynomials in the textbook's symbols: products of constant lengths (`a2`, `d4`), cosines
//! and sines of joint-angle sums (`c1`, `s23`) and prismatic variables (`d3`, `q3`), each with
//! a real coefficient; and the trigonometric identities the textbook simplifies with. The
//! symbols of the representations of orientation (Sects. 2.4-2.6) are factors too: the angles
//! phi, theta, psi through their cosines and sines (`c_phi`, `s_theta`), the axis `r_x`, and
//! the unit quaternion's `eta`, `epsilon_x`.

use std::collections::BTreeMap;

/// Coefficients below this are zero (they only arise from folded constants like cos(pi/2)).
const ZERO: f64 = 1e-14;

/// A sum of joint variables' angles, theta_i + theta_j + ...: the variable indices (1-based,
/// sorted, distinct). `c23` is `Cos(Angle(vec![2, 3]))`.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Angle(pub Vec<u16>);

impl Angle {
    /// The angle of one variable.
    pub fn one(k: u16) -> Self {
        Angle(vec![k])
    }

    /// The smallest variable index in the sum (what the textbook orders factors by).
    pub fn first(&self) -> u16 {
        self.0.first().copied().unwrap_or(0)
    }

    /// The sum of two angles over disjoint variables, `None` if they share one.
    fn plus(&self, other: &Angle) -> Option<Angle> {
        if self.0.iter().any(|k| other.0.contains(k)) {
            return None;
        }
        let mut v: Vec<u16> = self.0.iter().chain(&other.0).copied().collect();
        v.sort_unstable();
        Some(Angle(v))
    }

    /// The value for the variables' values `theta` (index k at `theta[k - first]`), rad.
    pub fn value(&self, theta: &[f64], first: u16) -> f64 {
        self.0.iter().map(|&k| theta[(k - first) as usize]).sum()
    }
}

/// Sort key of a factor in the textbook's writing order: (kind: length or named scalar 0, trig
/// 1, variable 2; first joint, row or symbol; name or cos 0 / sin 1; the angle's joints).
pub type WritingKey = (u8, u16, u8, Vec<u16>);

/// A named symbol of a representation of orientation, in the textbook's letters (Sects.
/// 2.4-2.6): an angle (rad) or a dimensionless component. Ordered as the book writes products:
/// `c_phi c_theta c_psi`, `r_x r_y`, `eta epsilon_z`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Symbol {
    /// phi, the first Euler angle (ZYZ, ZXZ) or the angle about z of RPY (rad).
    Phi,
    /// theta, the second Euler angle, RPY's angle about y, or the angle of angle and axis (rad).
    Theta,
    /// psi, the third Euler angle or RPY's angle about x (rad).
    Psi,
    /// r_x, the x component of the unit axis r of (2.25).
    Rx,
    /// r_y, the y component of the unit axis r.
    Ry,
    /// r_z, the z component of the unit axis r.
    Rz,
    /// eta, the scalar part of the unit quaternion, cos(theta/2) (2.30).
    Eta,
    /// epsilon_x, the x component of the quaternion's vector part sin(theta/2) r (2.31).
    EpsilonX,
    /// epsilon_y, its y component.
    EpsilonY,
    /// epsilon_z, its z component.
    EpsilonZ,
}

impl Symbol {
    /// The name in plain text and in the JSON grammar: `phi`, `r_x`, `epsilon_z`.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::poly::Symbol;
    /// assert_eq!(Symbol::Theta.name(), "theta");
    /// assert_eq!(Symbol::EpsilonX.name(), "epsilon_x");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Symbol::Phi => "phi",
            Symbol::Theta => "theta",
            Symbol::Psi => "psi",
            Symbol::Rx => "r_x",
            Symbol::Ry => "r_y",
            Symbol::Rz => "r_z",
            Symbol::Eta => "eta",
            Symbol::EpsilonX => "epsilon_x",
            Symbol::EpsilonY => "epsilon_y",
            Symbol::EpsilonZ => "epsilon_z",
        }
    }

    /// The name in LaTeX, in the textbook's letters: `\varphi`, `\vartheta`, `r_x`, `\eta`.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::poly::Symbol;
    /// assert_eq!(Symbol::Phi.latex(), "\\varphi");
    /// assert_eq!(Symbol::EpsilonZ.latex(), "\\epsilon_z");
    /// ```
    pub fn latex(self) -> &'static str {
        match self {
            Symbol::Phi => "\\varphi",
            Symbol::Theta => "\\vartheta",
            Symbol::Psi => "\\psi",
            Symbol::Rx => "r_x",
            Symbol::Ry => "r_y",
            Symbol::Rz => "r_z",
            Symbol::Eta => "\\eta",
            Symbol::EpsilonX => "\\epsilon_x",
            Symbol::EpsilonY => "\\epsilon_y",
            Symbol::EpsilonZ => "\\epsilon_z",
        }
    }

    /// Whether it is an angle (rad), written through its cosine and sine.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::poly::Symbol;
    /// assert!(Symbol::Psi.is_angle());
    /// assert!(!Symbol::Eta.is_angle());
    /// ```
    pub fn is_angle(self) -> bool {
        matches!(self, Symbol::Phi | Symbol::Theta | Symbol::Psi)
    }
}

impl std::fmt::Display for Symbol {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// One symbol of a monomial.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Factor {
    /// A constant DH length, `a2` or `d4` (`name` is 'a' or 'd', `index` the row's subscript).
    Length {
        /// 'a' or 'd'.
        name: char,
        /// The subscript of the textbook's table (row i, or i - 1 for a modified-DH `a`).
        index: u16,
    },
    /// cos of an angle sum: `c1`, `c23`.
    Cos(Angle),
    /// sin of an angle sum: `s1`, `s23`.
    Sin(Angle),
    /// A prismatic joint's variable: `d3` where it is the DH length d of its row, otherwise
    /// `q3` (m).
    Var {
        /// 'd' or 'q'.
        name: char,
        /// The variable's index (1-based).
        index: u16,
    },
    /// A named symbol itself: `r_x`, `eta`, `epsilon_y`.
    Symbol(Symbol),
    /// cos of a named angle: `c_phi`.
    CosOf(Symbol),
    /// sin of a named angle: `s_theta`.
    SinOf(Symbol),
}

impl Factor {
    /// Sort key of the textbook's writing order inside a product: lengths, then cosines and
    /// sines by their first joint (cosine first), then prismatic variables ("a2 c1 c2",
    /// "c1 s2 d3").
    pub fn writing_key(&self) -> WritingKey {
        match self {
            Factor::Length { name, index } => (0, *index, *name as u8, Vec::new()),
            Factor::Cos(a) => (1, a.first(), 0, a.0.clone()),
            Factor::Sin(a) => (1, a.first(), 1, a.0.clone()),
            Factor::Var { name, index } => (2, *index, *name as u8, Vec::new()),
            // a named symbol after the lengths' names ('a', 'd'), which it never meets
            Factor::Symbol(s) => (0, *s as u16, u8::MAX, Vec::new()),
            Factor::CosOf(s) => (1, *s as u16, 0, Vec::new()),
            Factor::SinOf(s) => (1, *s as u16, 1, Vec::new()),
        }
    }

    /// Whether this is a named symbol of orientation (or its cosine or sine).
    ///
    /// ```
    /// use armlab::kinematics::symbolic::poly::{Angle, Factor, Symbol};
    /// assert!(Factor::CosOf(Symbol::Phi).is_named());
    /// assert!(!Factor::Cos(Angle::one(1)).is_named());
    /// ```
    pub fn is_named(&self) -> bool {
        matches!(
            self,
            Factor::Symbol(_) | Factor::CosOf(_) | Factor::SinOf(_)
        )
    }

    /// The sine matching a cosine: `s1` for `c1`, `s_phi` for `c_phi`; `None` for any other
    /// factor.
    fn sine_of(&self) -> Option<Factor> {
        match self {
            Factor::Cos(a) => Some(Factor::Sin(a.clone())),
            Factor::CosOf(s) => Some(Factor::SinOf(*s)),
            _ => None,
        }
    }
}

/// A product of factors with exponents, sorted by factor: the canonical key of a term.
pub type Monomial = Vec<(Factor, u32)>;

/// `m * f`.
pub fn mono_mul(m: &Monomial, f: &Factor) -> Monomial {
    let mut out = m.clone();
    match out.binary_search_by(|(g, _)| g.cmp(f)) {
        Ok(i) => out[i].1 += 1,
        Err(i) => out.insert(i, (f.clone(), 1)),
    }
    out
}

/// `m / f` if `f` divides `m`.
pub fn mono_div(m: &Monomial, f: &Factor) -> Option<Monomial> {
    let i = m.binary_search_by(|(g, _)| g.cmp(f)).ok()?;
    let mut out = m.clone();
    if out[i].1 == 1 {
        out.remove(i);
    } else {
        out[i].1 -= 1;
    }
    Some(out)
}

/// `m1 * m2`.
fn mono_product(m1: &Monomial, m2: &Monomial) -> Monomial {
    let mut out = m1.clone();
    for (f, e) in m2 {
        match out.binary_search_by(|(g, _)| g.cmp(f)) {
            Ok(i) => out[i].1 += e,
            Err(i) => out.insert(i, (f.clone(), *e)),
        }
    }
    out
}

/// Values to evaluate a polynomial with.
pub struct Values<'a> {
    /// Each variable's value, index k at `[k - first]`: the joint angle (rad, revolute) or
    /// displacement (m, prismatic).
    pub variables: &'a [f64],
    /// The index of `variables[0]` (1, or 4 for a wrist whose joints are numbered 4-6).
    pub first: u16,
    /// The constant lengths by name (`"a2"`), m.
    pub lengths: &'a BTreeMap<String, f64>,
}

/// A polynomial: monomials with their coefficients.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Poly {
    /// The terms, keyed by monomial; no zero coefficient is stored.
    pub terms: BTreeMap<Monomial, f64>,
}

impl Poly {
    /// The constant `c` (zero polynomial when |c| is negligible).
    pub fn constant(c: f64) -> Self {
        let mut p = Poly::default();
        p.add_term(Vec::new(), c);
        p
    }

    /// The single factor `f`.
    pub fn factor(f: Factor) -> Self {
        let mut p = Poly::default();
        p.add_term(vec![(f, 1)], 1.0);
        p
    }

    /// Whether this is the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// Adds `c * m`.
    pub fn add_term(&mut self, m: Monomial, c: f64) {
        let entry = self.terms.entry(m).or_insert(0.0);
        *entry += c;
        if entry.abs() < ZERO {
            self.terms.retain(|_, v| v.abs() >= ZERO);
        }
    }

    /// `self + other`.
    pub fn add(&self, other: &Poly) -> Poly {
        let mut out = self.clone();
        for (m, c) in &other.terms {
            out.add_term(m.clone(), *c);
        }
        out
    }

    /// `k * self`.
    pub fn scale(&self, k: f64) -> Poly {
        let mut out = Poly::default();
        for (m, c) in &self.terms {
            out.add_term(m.clone(), c * k);
        }
        out
    }

    /// `self * other`.
    pub fn mul(&self, other: &Poly) -> Poly {
        let mut out = Poly::default();
        for (m1, c1) in &self.terms {
            for (m2, c2) in &other.terms {
                out.add_term(mono_product(m1, m2), c1 * c2);
            }
        }
        out
    }

    /// The value at `values` (an arm's variables and lengths; a named symbol of orientation has
    /// no value there and makes it NaN: see [`Poly::eval_symbols`]).
    pub fn eval(&self, values: &Values) -> f64 {
        self.eval_with(|f| match f {
            Factor::Length { name, index } => values.lengths[&format!("{name}{index}")],
            Factor::Cos(a) => a.value(values.variables, values.first).cos(),
            Factor::Sin(a) => a.value(values.variables, values.first).sin(),
            Factor::Var { index, .. } => values.variables[(*index - values.first) as usize],
            Factor::Symbol(_) | Factor::CosOf(_) | Factor::SinOf(_) => f64::NAN,
        })
    }

    /// The value with each named symbol's value given by `value` (angles in rad); any other
    /// factor (an arm's) has none here and makes it NaN.
    ///
    /// ```
    /// use armlab::kinematics::symbolic::poly::{Factor, Poly, Symbol};
    /// // r_x^2 (1 - c_theta) + c_theta, the first entry of (2.25)
    /// let rx = Poly::factor(Factor::Symbol(Symbol::Rx));
    /// let c = Poly::factor(Factor::CosOf(Symbol::Theta));
    /// let one_minus_c = Poly::constant(1.0).add(&c.scale(-1.0));
    /// let p = rx.mul(&rx).mul(&one_minus_c).add(&c);
    /// let v = p.eval_symbols(|s| match s {
    ///     Symbol::Rx => 0.6,
    ///     Symbol::Theta => 0.5,
    ///     _ => f64::NAN,
    /// });
    /// assert!((v - (0.36 * (1.0 - 0.5f64.cos()) + 0.5f64.cos())).abs() < 1e-15);
    /// ```
    pub fn eval_symbols(&self, value: impl Fn(Symbol) -> f64) -> f64 {
        self.eval_with(|f| match f {
            Factor::Symbol(s) => value(*s),
            Factor::CosOf(s) => value(*s).cos(),
            Factor::SinOf(s) => value(*s).sin(),
            _ => f64::NAN,
        })
    }

    /// The value with each factor's value given by `value`.
    fn eval_with(&self, value: impl Fn(&Factor) -> f64) -> f64 {
        self.terms
            .iter()
            .map(|(m, c)| {
                m.iter()
                    .fold(*c, |acc, (f, e)| acc * value(f).powi(*e as i32))
            })
            .sum()
    }

    /// The variables (1-based) the polynomial depends on.
    pub fn variables(&self) -> Vec<u16> {
        let mut out: Vec<u16> = self
            .terms
            .keys()
            .flatten()
            .flat_map(|(f, _)| match f {
                Factor::Cos(a) | Factor::Sin(a) => a.0.clone(),
                Factor::Var { index, .. } => vec![*index],
                Factor::Length { .. } | Factor::Symbol(_) | Factor::CosOf(_) | Factor::SinOf(_) => {
                    Vec::new()
                }
            })
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Applies the textbook's identities until none applies: cos A cos B - sin A sin B =
    /// cos(A + B), sin A cos B + cos A sin B = sin(A + B) (which is where `c12`, `s23` come
    /// from), and cos^2 A + sin^2 A = 1.
    pub fn simplify(&mut self) {
        while self.combine_once() {}
    }

    fn coef(&self, m: &Monomial) -> f64 {
        self.terms.get(m).copied().unwrap_or(0.0)
    }

    /// Replaces `k m1 + k2 m2` (with m2's coefficient `k2` matching) by `k rest * new`.
    fn replace_pair(&mut self, m1: &Monomial, m2: &Monomial, rest: Monomial, new: Option<Factor>) {
        let k = self.coef(m1);
        self.terms.remove(m1);
        self.terms.remove(m2);
        let m = match new {
            Some(f) => mono_mul(&rest, &f),
            None => rest,
        };
        self.add_term(m, k);
    }

    /// One application of an identity, if any applies.
    fn combine_once(&mut self) -> bool {
        let keys: Vec<Monomial> = self.terms.keys().cloned().collect();
        for m1 in &keys {
            let Some(&k1) = self.terms.get(m1) else {
                continue;
            };
            let same = |k2: f64, sign: f64| (k2 - sign * k1).abs() <= 1e-12 * k1.abs();
            for (i, (f1, e1)) in m1.iter().enumerate() {
                for (j, (f2, _)) in m1.iter().enumerate() {
                    if i == j {
                        continue;
                    }
                    let (new, want_sign, swap) = match (f1, f2) {
                        // c_A c_B - s_A s_B = c_{A+B}
                        (Factor::Cos(a), Factor::Cos(b)) if i < j => (
                            a.plus(b).map(Factor::Cos),
                            -1.0,
                            (Factor::Sin(a.clone()), Factor::Sin(b.clone())),
                        ),
                        // s_A c_B + c_A s_B = s_{A+B}
                        (Factor::Sin(a), Factor::Cos(b)) => (
                            a.plus(b).map(Factor::Sin),
                            1.0,
                            (Factor::Cos(a.clone()), Factor::Sin(b.clone())),
                        ),
                        _ => continue,
                    };
                    let Some(new) = new else { continue };
                    let Some(rest) = mono_div(m1, f1).and_then(|m| mono_div(&m, f2)) else {
                        continue;
                    };
                    let m2 = mono_mul(&mono_mul(&rest, &swap.0), &swap.1);
                    if same(self.coef(&m2), want_sign) {
                        self.replace_pair(m1, &m2, rest, Some(new));
                        return true;
                    }
                }
                // c_A^2 + s_A^2 = 1 (a joint angle's or a named one's)
                if *e1 >= 2
                    && let Some(s) = f1.sine_of()
                {
                    let rest = mono_div(m1, f1).and_then(|m| mono_div(&m, f1));
                    let Some(rest) = rest else { continue };
                    let m2 = mono_mul(&mono_mul(&rest, &s), &s);
                    if same(self.coef(&m2), 1.0) {
                        self.replace_pair(m1, &m2, rest, None);
                        return true;
                    }
                }
            }
        }
        false
    }
}

/// `x` with values within 1e-12 of 0, +-1 made exact (folded twists: cos(pi/2) is 0).
pub fn snap(x: f64) -> f64 {
    for v in [0.0, 1.0, -1.0] {
        if (x - v).abs() < 1e-12 {
            return v;
        }
    }
    x
}

/// cos and sin of `sum_k sign_k theta_k + offset` as polynomials in `c_k`, `s_k`, by the
/// addition formulas, then simplified (so a plain sum of variables becomes `c23`, `s23`).
pub fn cos_sin_of_sum(terms: &[(u16, f64)], offset: f64) -> (Poly, Poly) {
    let mut c = Poly::constant(snap(offset.cos()));
    let mut s = Poly::constant(snap(offset.sin()));
    for &(k, sign) in terms {
        let ck = Poly::factor(Factor::Cos(Angle::one(k)));
        let sk = Poly::factor(Factor::Sin(Angle::one(k))).scale(sign);
        // cos(x + y) = cx cy - sx sy; sin(x + y) = sx cy + cx sy
        let c_new = c.mul(&ck).add(&s.mul(&sk).scale(-1.0));
        let s_new = s.mul(&ck).add(&c.mul(&sk));
        c = c_new;
        s = s_new;
    }
    c.simplify();
    s.simplify();
    (c, s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(k: &[u16]) -> Poly {
        Poly::factor(Factor::Cos(Angle(k.to_vec())))
    }
    fn s(k: &[u16]) -> Poly {
        Poly::factor(Factor::Sin(Angle(k.to_vec())))
    }

    #[test]
    fn the_addition_formulas_make_angle_sums() {
        let mut p = c(&[1])
            .mul(&c(&[2]))
            .add(&s(&[1]).mul(&s(&[2])).scale(-1.0));
        p.simplify();
        assert_eq!(p, c(&[1, 2]));
        let mut p = s(&[1, 2]).mul(&c(&[3])).add(&c(&[1, 2]).mul(&s(&[3])));
        p.simplify();
        assert_eq!(p, s(&[1, 2, 3]));
        let mut p = c(&[4]).mul(&c(&[4])).add(&s(&[4]).mul(&s(&[4])));
        p.simplify();
        assert_eq!(p, Poly::constant(1.0));
    }

    #[test]
    fn a_named_angle_s_cosine_and_sine_squared_sum_to_one() {
        let c = Poly::factor(Factor::CosOf(Symbol::Theta));
        let s = Poly::factor(Factor::SinOf(Symbol::Theta));
        let rx = Poly::factor(Factor::Symbol(Symbol::Rx));
        // r_x c^2 + r_x s^2 = r_x
        let mut p = rx.mul(&c).mul(&c).add(&rx.mul(&s).mul(&s));
        p.simplify();
        assert_eq!(p, rx);
        // no sum of named angles is formed: c_phi c_psi - s_phi s_psi stays
        let two = |a: Symbol, b: Symbol| {
            Poly::factor(Factor::CosOf(a))
                .mul(&Poly::factor(Factor::CosOf(b)))
                .add(
                    &Poly::factor(Factor::SinOf(a))
                        .mul(&Poly::factor(Factor::SinOf(b)))
                        .scale(-1.0),
                )
        };
        let mut p = two(Symbol::Phi, Symbol::Psi);
        p.simplify();
        assert_eq!(p, two(Symbol::Phi, Symbol::Psi));
    }

    #[test]
    fn a_difference_of_angles_stays_in_products() {
        // cos(q2 - q1) = c1 c2 + s1 s2: no name of the grammar says it shorter
        let (cc, _) = cos_sin_of_sum(&[(2, 1.0), (1, -1.0)], 0.0);
        assert_eq!(cc, c(&[1]).mul(&c(&[2])).add(&s(&[1]).mul(&s(&[2]))));
    }
}
