//! Printing polynomials the way the textbook writes them: common factors taken out
//! (`c1(a2c2 + a3c23)`, (2.95)), terms in the book's order, in plain text, LaTeX, or the
//! machine-readable grammar of the JSON output.

use super::poly::{Angle, Factor, Monomial, Poly, Symbol, WritingKey, mono_div};

/// One term of a factored sum: `coef * factors * (group)`, the group a sum of its own (or
/// nothing, meaning 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Term {
    /// The numeric coefficient.
    pub coef: f64,
    /// The factors, in the textbook's writing order.
    pub factors: Monomial,
    /// A parenthesised sum multiplying the factors; empty for none.
    pub group: Vec<Term>,
}

/// How to write a factored expression.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// The textbook's juxtaposition: `c1(a2c2 + a3c23)`.
    Text,
    /// LaTeX: `c_{1}(a_{2}c_{2} + a_{3}c_{23})`.
    Latex,
    /// The grammar a computer-algebra system parses: `c1*(a2*c2 + a3*c23)`.
    Json,
}

/// `p` factored: common factors out, then grouped by the length or angle that the most terms
/// share (lengths first, then the lowest joint), recursively.
pub fn factor(p: &Poly) -> Vec<Term> {
    let terms: Vec<(Monomial, f64)> = p.terms.iter().map(|(m, c)| (m.clone(), *c)).collect();
    let mut out = factor_terms(terms, false);
    sort_sum(&mut out);
    out
}

/// The terms as they are, ungrouped.
fn plain(terms: Vec<(Monomial, f64)>) -> Vec<Term> {
    terms
        .into_iter()
        .map(|(factors, coef)| Term {
            coef,
            factors,
            group: Vec::new(),
        })
        .collect()
}

/// Factors a sum. `hoist_sign`: inside a group, an all-negative sum gives its sign to the
/// factor outside (`-c1(s4c5c6 + c4s6)` rather than `c1(-s4c5c6 - c4s6)`).
fn factor_terms(terms: Vec<(Monomial, f64)>, hoist_sign: bool) -> Vec<Term> {
    if terms.len() <= 1 {
        return plain(terms);
    }
    let common = common_monomial(&terms);
    let numeric = common_coefficient(&terms, !common.is_empty() || hoist_sign);
    if !common.is_empty() || numeric != 1.0 {
        let inner = terms
            .into_iter()
            .map(|(m, c)| {
                let m = common.iter().fold(m, |m, (f, e)| {
                    (0..*e).fold(m, |m, _| mono_div(&m, f).expect("a common factor"))
                });
                (m, c / numeric)
            })
            .collect();
        let mut group = factor_terms(inner, false);
        sort_sum(&mut group);
        return vec![absorb(numeric, common, group)];
    }
    let Some(f) = grouping_factor(&terms) else {
        return numeric_group(terms);
    };
    let (with, rest): (Vec<_>, Vec<_>) = terms
        .into_iter()
        .partition(|(m, _)| mono_div(m, &f).is_some());
    let with = with
        .into_iter()
        .map(|(m, c)| (mono_div(&m, &f).expect("partitioned on f"), c))
        .collect();
    let mut group = factor_terms(with, true);
    sort_sum(&mut group);
    let mut out = vec![absorb(1.0, vec![(f, 1)], group)];
    out.extend(factor_terms(rest, false));
    out
}

/// Where no symbol is shared, the terms whose coefficients are the same whole number (2 or
/// more; some terms, not all) grouped behind it, as (2.33) writes `2(eta^2 + epsilon_x^2) - 1`;
/// the terms as they are otherwise. Such a number is the algebra's (the 2 of a half angle);
/// an arm's lengths with `--numbers` are grouped only where two are the same whole metres.
fn numeric_group(terms: Vec<(Monomial, f64)>) -> Vec<Term> {
    let whole = |c: f64| c.abs() >= 2.0 && c.abs() <= 1e6 && c.fract() == 0.0;
    let shared = terms.iter().map(|(_, c)| c.abs()).find(|&k| {
        whole(k) && {
            let n = terms.iter().filter(|(_, c)| c.abs() == k).count();
            n >= 2 && n < terms.len()
        }
    });
    let Some(k) = shared else {
        return plain(terms);
    };
    let (with, rest): (Vec<_>, Vec<_>) = terms.into_iter().partition(|(_, c)| c.abs() == k);
    let with = with.into_iter().map(|(m, c)| (m, c / k)).collect();
    let mut group = factor_terms(with, true);
    sort_sum(&mut group);
    let mut out = vec![absorb(k, Vec::new(), group)];
    out.extend(factor_terms(rest, false));
    out
}

/// `coef * factors * (group)`, merging a one-term group into the factors.
fn absorb(coef: f64, factors: Monomial, mut group: Vec<Term>) -> Term {
    // the sum in parentheses starts with a plus: -s2(c4c5c6 - s4s6), not s2(-c4c5c6 + s4s6)
    let mut coef = coef;
    if group.first().is_some_and(|t| t.coef < 0.0) && !factors.is_empty() {
        coef = -coef;
        for t in &mut group {
            t.coef = -t.coef;
        }
    }
    if let [only] = group.as_slice() {
        let mut merged = factors;
        for (f, e) in &only.factors {
            for _ in 0..*e {
                merged = super::poly::mono_mul(&merged, f);
            }
        }
        return Term {
            coef: coef * only.coef,
            factors: merged,
            group: only.group.clone(),
        };
    }
    Term {
        coef,
        factors,
        group,
    }
}

/// The factors every term has (smallest exponent).
fn common_monomial(terms: &[(Monomial, f64)]) -> Monomial {
    let mut common = terms[0].0.clone();
    for (m, _) in &terms[1..] {
        common.retain_mut(|(f, e)| match m.iter().find(|(g, _)| g == f) {
            Some((_, e2)) => {
                *e = (*e).min(*e2);
                true
            }
            None => false,
        });
    }
    common
}

/// A numeric factor of every coefficient: their common magnitude when all are equal (so
/// `0.5c2 + 0.5c23` with `--numbers` reads `0.5(c2 + c23)`), and the sign when all are
/// negative and `sign_too`.
fn common_coefficient(terms: &[(Monomial, f64)], sign_too: bool) -> f64 {
    let first = terms[0].1.abs();
    let equal = terms
        .iter()
        .all(|(_, c)| (c.abs() - first).abs() <= 1e-12 * first);
    let negative = sign_too && terms.iter().all(|(_, c)| *c < 0.0);
    let magnitude = if equal { first } else { 1.0 };
    if negative { -magnitude } else { magnitude }
}

/// The factor to group by: the length in the most terms (at least two), else the cosine or
/// sine of the lowest joint in at least two terms, else a prismatic variable in two terms.
fn grouping_factor(terms: &[(Monomial, f64)]) -> Option<Factor> {
    let mut counts: Vec<(Factor, usize)> = Vec::new();
    for (m, _) in terms {
        for (f, _) in m {
            match counts.iter_mut().find(|(g, _)| g == f) {
                Some((_, n)) => *n += 1,
                None => counts.push((f.clone(), 1)),
            }
        }
    }
    counts.retain(|(_, n)| *n >= 2);
    let kind = |f: &Factor| f.writing_key().0;
    for wanted in 0..3 {
        let best = counts
            .iter()
            .filter(|(f, _)| kind(f) == wanted)
            .min_by(|(f1, n1), (f2, n2)| {
                let by_count = n2.cmp(n1);
                match wanted {
                    // a length: the most shared, then the lowest row
                    0 => by_count.then(f1.writing_key().cmp(&f2.writing_key())),
                    // an angle or variable: the lowest joint, then the most shared
                    _ => (f1.writing_key().1)
                        .cmp(&f2.writing_key().1)
                        .then(by_count)
                        .then(f1.writing_key().cmp(&f2.writing_key())),
                }
            });
        if let Some((f, _)) = best {
            return Some(f.clone());
        }
    }
    None
}

/// Sort key of a term in a sum: terms without a constant length first (`c1(...) + s1(...)`,
/// `c1s2d3 - s1d2`), then by their factors in writing order (`a1c1 + a2c12 + a3c123`).
fn sum_key(t: &Term) -> (bool, Vec<WritingKey>) {
    let mut keys: Vec<_> = t.factors.iter().map(|(f, _)| f.writing_key()).collect();
    keys.sort();
    let has_length = t
        .factors
        .iter()
        .any(|(f, _)| matches!(f, Factor::Length { .. }));
    (has_length, keys)
}

/// Sorts a sum; where it would start with a minus, the first positive term moves to the front
/// (`a2s2 - d4c23`, `s1(...) - c1s4s5`, as the book writes them).
fn sort_sum(terms: &mut [Term]) {
    terms.sort_by_key(sum_key);
    if terms.first().is_some_and(|t| t.coef < 0.0)
        && let Some(i) = terms.iter().position(|t| t.coef > 0.0)
    {
        terms[..=i].rotate_right(1);
    }
}

/// A number as the grammar writes it: up to 12 significant digits, no exponent for the
/// lengths of arms.
pub fn number(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if v.abs() >= 1e-4 && v.abs() < 1e7 {
        let digits = (11 - v.abs().log10().floor() as i32).clamp(0, 15) as usize;
        let s = format!("{v:.digits$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        if s == "-0" { "0".into() } else { s }
    } else {
        // 12 significant digits, trailing zeros of the mantissa dropped: 1.5e-9
        let s = format!("{v:.11e}");
        match s.split_once('e') {
            Some((m, e)) if m.contains('.') => {
                format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
            }
            _ => s,
        }
    }
}

/// The name of an angle sum's indices: `23`, or `1_12` when indices are separated.
fn angle_indices(a: &Angle, separate: bool) -> String {
    let parts: Vec<String> = a.0.iter().map(|k| k.to_string()).collect();
    parts.join(if separate { "_" } else { "" })
}

/// A named symbol after `head` (`c_`, `s_` or nothing) in a style: `c_phi`, `r_x`, `eta`
/// (text and JSON), `c_\varphi`, `\eta` (LaTeX).
fn write_named(head: &str, symbol: Symbol, style: Style) -> String {
    match style {
        Style::Latex => format!("{head}{}", symbol.latex()),
        _ => format!("{head}{}", symbol.name()),
    }
}

/// One factor (with its exponent) in a style.
fn write_factor(f: &Factor, e: u32, style: Style, separate: bool) -> String {
    let (head, sub) = match f {
        Factor::Length { name, index } | Factor::Var { name, index } => {
            (name.to_string(), index.to_string())
        }
        Factor::Cos(a) => ("c".into(), angle_indices(a, separate)),
        Factor::Sin(a) => ("s".into(), angle_indices(a, separate)),
        Factor::Symbol(s) => (write_named("", *s, style), String::new()),
        Factor::CosOf(s) => (write_named("c_", *s, style), String::new()),
        Factor::SinOf(s) => (write_named("s_", *s, style), String::new()),
    };
    let base = match style {
        _ if f.is_named() => head,
        Style::Latex => format!("{head}_{{{}}}", sub.replace('_', ",")),
        _ => format!("{head}{sub}"),
    };
    match (e, style) {
        (1, _) => base,
        (e, Style::Latex) => format!("{base}^{{{e}}}"),
        (e, _) => format!("{base}^{e}"),
    }
}

/// A term without its sign.
fn write_unsigned(t: &Term, style: Style, separate: bool) -> String {
    // each part with whether it is a named symbol (`c_phi`), which text and LaTeX set apart
    // from its neighbours by a space (`c_phi c_psi`, `c_\varphi c_\psi`) where the arms'
    // one-letter names are juxtaposed (`c1s23`)
    let mut parts: Vec<(String, bool)> = Vec::new();
    let magnitude = t.coef.abs();
    let bare = t.factors.is_empty() && t.group.is_empty();
    if bare || (magnitude - 1.0).abs() > 1e-15 {
        parts.push((number(magnitude), false));
    }
    let mut factors = t.factors.clone();
    factors.sort_by_key(|(f, _)| f.writing_key());
    for (f, e) in &factors {
        parts.push((write_factor(f, *e, style, separate), f.is_named()));
    }
    let mut s = String::new();
    for (i, (p, named)) in parts.iter().enumerate() {
        // a number followed by a factor in text needs nothing; two numbers never meet
        if i > 0 {
            match style {
                Style::Json => s.push('*'),
                _ if *named || parts[i - 1].1 => s.push(' '),
                _ => {}
            }
        }
        s.push_str(p);
    }
    if !t.group.is_empty() {
        let inner = write_sum(&t.group, style, separate);
        if style == Style::Json && !parts.is_empty() {
            s.push('*');
        }
        match style {
            Style::Latex => s.push_str(&format!("\\left({inner}\\right)")),
            _ => s.push_str(&format!("({inner})")),
        }
    }
    s
}

/// A sum of terms with signs: `a2s2 - d4c23`.
pub fn write_sum(terms: &[Term], style: Style, separate: bool) -> String {
    if terms.is_empty() {
        return "0".into();
    }
    let mut s = String::new();
    for (i, t) in terms.iter().enumerate() {
        let negative = t.coef < 0.0;
        match (i, negative) {
            (0, true) => s.push('-'),
            (0, false) => {}
            (_, true) => s.push_str(" - "),
            (_, false) => s.push_str(" + "),
        }
        s.push_str(&write_unsigned(t, style, separate));
    }
    s
}

/// `p` factored and written in `style`; `separate` separates angle indices with `_`.
pub fn write(p: &Poly, style: Style, separate: bool) -> String {
    write_sum(&factor(p), style, separate)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(name: char, index: u16) -> Poly {
        Poly::factor(Factor::Length { name, index })
    }
    fn c(k: &[u16]) -> Poly {
        Poly::factor(Factor::Cos(Angle(k.to_vec())))
    }
    fn s(k: &[u16]) -> Poly {
        Poly::factor(Factor::Sin(Angle(k.to_vec())))
    }

    #[test]
    fn the_wrist_point_of_2_95_comes_out_factored() {
        let p = f('a', 2)
            .mul(&c(&[1]))
            .mul(&c(&[2]))
            .add(&f('a', 3).mul(&c(&[1])).mul(&c(&[2, 3])));
        assert_eq!(write(&p, Style::Text, false), "c1(a2c2 + a3c23)");
        assert_eq!(write(&p, Style::Json, false), "c1*(a2*c2 + a3*c23)");
        assert_eq!(
            write(&p, Style::Latex, false),
            "c_{1}\\left(a_{2}c_{2} + a_{3}c_{23}\\right)"
        );
    }

    fn named(s: Symbol) -> Poly {
        Poly::factor(Factor::Symbol(s))
    }

    #[test]
    fn named_symbols_are_spaced_and_whole_numbers_grouped() {
        // (2.33)'s r11 as the engine expands it: 2 eta^2 + 2 epsilon_x^2 - 1
        let eta = named(Symbol::Eta);
        let ex = named(Symbol::EpsilonX);
        let p = eta
            .mul(&eta)
            .add(&ex.mul(&ex))
            .scale(2.0)
            .add(&Poly::constant(-1.0));
        assert_eq!(write(&p, Style::Text, false), "2(eta^2 + epsilon_x^2) - 1");
        assert_eq!(write(&p, Style::Json, false), "2*(eta^2 + epsilon_x^2) - 1");
        assert_eq!(
            write(&p, Style::Latex, false),
            "2\\left(\\eta^{2} + \\epsilon_x^{2}\\right) - 1"
        );
        // both negative: the sign goes outside, and the sum starts with its positive term
        assert_eq!(
            write(&p.scale(-1.0), Style::Text, false),
            "1 - 2(eta^2 + epsilon_x^2)"
        );
        // (2.25)'s r12: r_x r_y (1 - c) - r_z s
        let c = Poly::factor(Factor::CosOf(Symbol::Theta));
        let sn = Poly::factor(Factor::SinOf(Symbol::Theta));
        let rxy = named(Symbol::Rx).mul(&named(Symbol::Ry));
        let p = rxy
            .add(&rxy.mul(&c).scale(-1.0))
            .add(&named(Symbol::Rz).mul(&sn).scale(-1.0));
        assert_eq!(
            write(&p, Style::Text, false),
            "r_x r_y(1 - c_theta) - r_z s_theta"
        );
        assert_eq!(
            write(&p, Style::Latex, false),
            "r_x r_y\\left(1 - c_\\vartheta\\right) - r_z s_\\vartheta"
        );
    }

    #[test]
    fn equal_lengths_of_an_arm_are_not_grouped() {
        // the Puma's a2 = d4 = 0.4318 m with --numbers: a coincidence of values, not algebra
        let p = c(&[2])
            .scale(0.4318)
            .add(&c(&[2, 3]).scale(0.0203))
            .add(&s(&[2, 3]).scale(0.4318));
        assert_eq!(
            write(&p, Style::Text, false),
            "0.4318c2 + 0.0203c23 + 0.4318s23"
        );
    }

    #[test]
    fn signs_and_numbers() {
        let p = s(&[1]).mul(&s(&[2, 3])).scale(-1.0);
        assert_eq!(write(&p, Style::Text, false), "-s1s23");
        assert_eq!(write(&Poly::constant(0.4318), Style::Json, false), "0.4318");
        assert_eq!(number(-1.5e-9), "-1.5e-9");
        assert_eq!(number(0.15005), "0.15005");
    }
}
