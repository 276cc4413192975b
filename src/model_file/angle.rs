//! Angles written as text in model files: `"pi/2"`, `"-2*pi/3"`, `"-90deg"`, `"1.2rad"`.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_3, FRAC_PI_4, FRAC_PI_6, FRAC_PI_8, PI};

/// Reads an angle string of a model file and returns it in radians.
///
/// Accepted forms (surrounding whitespace ignored):
/// - `[-][k*]pi[/m]` with decimal numbers `k >= 0` and `m > 0`, e.g. `"pi"`, `"-pi/2"`,
///   `"2*pi/3"`, `"0.5 * pi"`; evaluated as `±k * (pi/m)` where `pi/m` is the correctly rounded
///   constant of [`std::f64::consts`] for m = 1, 2, 3, 4, 6, 8 (so `"2*pi/3"` is exactly
///   `2.0 * FRAC_PI_3`) and `PI / m` otherwise;
/// - `<number>deg` or `<number> deg`, e.g. `"-90deg"`, `"45 deg"` (converted with
///   [`f64::to_radians`]);
/// - `<number>rad` or `<number> rad`, e.g. `"1.2rad"`.
///
/// Anything else, including a bare number in a string, `"inf"`, `"nan"` and results that are not
/// finite, gives `None`.
///
/// # Examples
///
/// ```
/// use armlab::model_file::parse_angle;
/// use std::f64::consts::{FRAC_PI_2, FRAC_PI_3};
///
/// assert_eq!(parse_angle("pi/2"), Some(FRAC_PI_2));
/// assert_eq!(parse_angle("-2*pi/3"), Some(-2.0 * FRAC_PI_3));
/// assert_eq!(parse_angle("-90deg"), Some(-FRAC_PI_2));
/// assert_eq!(parse_angle("1.2 rad"), Some(1.2));
/// assert_eq!(parse_angle("1.2"), None); // a bare number belongs outside the string
/// ```
pub fn parse_angle(text: &str) -> Option<f64> {
    let s = text.trim();
    if let Some(num) = s.strip_suffix("deg") {
        return decimal(num.trim_end(), true).map(f64::to_radians);
    }
    if let Some(num) = s.strip_suffix("rad") {
        return decimal(num.trim_end(), true);
    }
    let (sign, rest) = match s.strip_prefix('-') {
        Some(r) => (-1.0, r.trim_start()),
        None => (1.0, s),
    };
    let (k, rest) = match rest.split_once('*') {
        Some((k, r)) => (decimal(k.trim(), false)?, r.trim_start()),
        None => (1.0, rest),
    };
    let rest = rest.strip_prefix("pi")?.trim_start();
    let m = if rest.is_empty() {
        1.0
    } else {
        decimal(rest.strip_prefix('/')?.trim_start(), false)?
    };
    if m == 0.0 {
        return None;
    }
    let pi_over_m = match m {
        1.0 => PI,
        2.0 => FRAC_PI_2,
        3.0 => FRAC_PI_3,
        4.0 => FRAC_PI_4,
        6.0 => FRAC_PI_6,
        8.0 => FRAC_PI_8,
        _ => PI / m,
    };
    let v = sign * k * pi_over_m;
    v.is_finite().then_some(v)
}

/// A plain decimal number (digits, `.`, exponent; a sign only if `signed`), finite.
fn decimal(s: &str, signed: bool) -> Option<f64> {
    let body = if signed {
        s.strip_prefix(['-', '+']).unwrap_or(s)
    } else {
        s
    };
    let starts_ok = body.starts_with(|c: char| c.is_ascii_digit() || c == '.');
    let chars_ok = body
        .chars()
        .all(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '+' | '-'));
    if !(starts_ok && chars_ok) {
        return None;
    }
    s.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// Writes an angle (rad) for a model file: an exact string such as `"pi/2"`, `"-2*pi/3"` or
/// `"-160deg"` when [`parse_angle`] reads that string back to the very same `f64`, otherwise
/// `None` (the caller writes the number).
pub(crate) fn exact_angle_string(value: f64) -> Option<String> {
    if value == 0.0 || !value.is_finite() {
        return None;
    }
    let sign = if value < 0.0 { "-" } else { "" };
    for m in [1u32, 2, 3, 4, 6, 8, 12] {
        for k in (1u32..=4 * m).filter(|&k| gcd(k, m) == 1) {
            let text = match (k, m) {
                (1, 1) => format!("{sign}pi"),
                (1, _) => format!("{sign}pi/{m}"),
                (_, 1) => format!("{sign}{k}*pi"),
                _ => format!("{sign}{k}*pi/{m}"),
            };
            if parse_angle(&text) == Some(value) {
                return Some(text);
            }
        }
    }
    let degrees = value.to_degrees().round();
    let text = format!("{degrees}deg");
    (degrees.abs() <= 720.0 && parse_angle(&text) == Some(value)).then_some(text)
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pi_expressions() {
        assert_eq!(parse_angle("pi"), Some(PI));
        assert_eq!(parse_angle("-pi"), Some(-PI));
        assert_eq!(parse_angle("pi/2"), Some(FRAC_PI_2));
        assert_eq!(parse_angle("-pi/2"), Some(-FRAC_PI_2));
        assert_eq!(parse_angle(" pi / 4 "), Some(FRAC_PI_4));
        assert_eq!(parse_angle("2*pi/3"), Some(2.0 * FRAC_PI_3));
        assert_eq!(parse_angle("- 2 * pi / 3"), Some(-2.0 * FRAC_PI_3));
        assert_eq!(parse_angle("3*pi/2"), Some(3.0 * FRAC_PI_2));
        assert_eq!(parse_angle("0.5*pi"), Some(0.5 * PI));
        assert_eq!(parse_angle("2*pi"), Some(2.0 * PI));
        assert_eq!(parse_angle("5*pi/6"), Some(5.0 * FRAC_PI_6));
        assert_eq!(parse_angle("pi/12"), Some(PI / 12.0));
    }

    #[test]
    fn degrees_and_radians() {
        assert_eq!(parse_angle("-90deg"), Some(-FRAC_PI_2));
        assert_eq!(parse_angle("45 deg"), Some(45f64.to_radians()));
        assert_eq!(parse_angle("+30deg"), Some(30f64.to_radians()));
        assert_eq!(parse_angle("1.2rad"), Some(1.2));
        assert_eq!(parse_angle("-1.5e-1 rad"), Some(-0.15));
        assert_eq!(parse_angle(".5rad"), Some(0.5));
    }

    #[test]
    fn rejects_everything_else() {
        for bad in [
            "",
            "1.2",
            "pi/0",
            "pi/",
            "*pi",
            "2pi",
            "pi*2",
            "pi/2/2",
            "--pi",
            "-2*-pi",
            "tau",
            "PI/2",
            "90",
            "deg",
            "infdeg",
            "nan rad",
            "inf rad",
            "1e400deg",
            "90 degrees",
            "pi/-2",
            "x*pi",
            "pi/2deg",
            "1,5rad",
        ] {
            assert_eq!(parse_angle(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn exact_strings_round_trip() {
        for v in [
            PI,
            -PI,
            FRAC_PI_2,
            -FRAC_PI_2,
            2.0 * FRAC_PI_3,
            3.0 * FRAC_PI_2,
            FRAC_PI_4,
        ] {
            let s = exact_angle_string(v).expect("an exact angle");
            assert_eq!(parse_angle(&s), Some(v), "{s}");
        }
        assert_eq!(exact_angle_string(FRAC_PI_2).as_deref(), Some("pi/2"));
        assert_eq!(exact_angle_string(-PI).as_deref(), Some("-pi"));
        assert_eq!(exact_angle_string(0.3), None);
        assert_eq!(
            exact_angle_string(2.0 * FRAC_PI_3).as_deref(),
            Some("2*pi/3")
        );
        assert_eq!(
            exact_angle_string((-160f64).to_radians()).as_deref(),
            Some("-160deg")
        );
        assert_eq!(exact_angle_string(0.0), None);
    }
}
