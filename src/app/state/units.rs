//! Display units of the app (degrees or radians for angles, millimetres for lengths) and the
//! parsing of numeric entries typed by the user.

use crate::model_file::parse_angle;
use thiserror::Error;

/// Millimetres per metre: lengths are shown in mm and stored in m.
pub const MM_PER_M: f64 = 1000.0;

/// How angles are shown and typed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AngleUnit {
    /// Degrees (the default).
    #[default]
    Degrees,
    /// Radians.
    Radians,
}

impl AngleUnit {
    /// Unit symbol: "°" or "rad".
    pub fn symbol(self) -> &'static str {
        match self {
            AngleUnit::Degrees => "°",
            AngleUnit::Radians => "rad",
        }
    }

    /// An angle in radians expressed in this unit.
    pub fn from_rad(self, rad: f64) -> f64 {
        match self {
            AngleUnit::Degrees => rad.to_degrees(),
            AngleUnit::Radians => rad,
        }
    }

    /// An angle in this unit expressed in radians.
    pub fn to_rad(self, v: f64) -> f64 {
        match self {
            AngleUnit::Degrees => v.to_radians(),
            AngleUnit::Radians => v,
        }
    }
}

/// What a number typed by the user measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// An angle: stored in rad, shown in the [`AngleUnit`].
    Angle,
    /// A length: stored in m, shown in mm.
    Length,
}

impl Quantity {
    /// The display unit symbol ("°", "rad" or "mm").
    pub fn symbol(self, unit: AngleUnit) -> &'static str {
        match self {
            Quantity::Angle => unit.symbol(),
            Quantity::Length => "mm",
        }
    }

    /// A stored value (rad or m) in display units (the angle unit or mm).
    pub fn to_display(self, si: f64, unit: AngleUnit) -> f64 {
        match self {
            Quantity::Angle => unit.from_rad(si),
            Quantity::Length => si * MM_PER_M,
        }
    }

    /// A display value (the angle unit or mm) in stored units (rad or m).
    pub fn from_display(self, v: f64, unit: AngleUnit) -> f64 {
        match self {
            Quantity::Angle => unit.to_rad(v),
            Quantity::Length => v / MM_PER_M,
        }
    }
}

/// Why a typed entry was not accepted. The text stays in its cell, marked with this reason.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EntryError {
    /// Nothing typed.
    #[error("empty entry: type a number")]
    Empty,
    /// Not readable as a number.
    #[error("\"{0}\" is not a number")]
    NotANumber(String),
    /// NaN or infinite.
    #[error("\"{0}\" is not a finite number")]
    NonFinite(String),
    /// The lower limit would be above the upper limit.
    #[error("lower limit {lower} is above upper limit {upper}")]
    LimitsInverted {
        /// Lower limit as shown (with unit).
        lower: String,
        /// Upper limit as shown (with unit).
        upper: String,
    },
    /// This cell cannot be edited for this joint (e.g. theta of a revolute joint is its variable).
    #[error("{0}")]
    NotEditable(&'static str),
    /// The model rejected the value.
    #[error("{0}")]
    Rejected(String),
}

/// Reads a typed value and returns it in stored units (rad or m).
///
/// A plain number is in display units (the angle unit, or mm). Explicit units are accepted too:
/// angles as in model files (`"pi/2"`, `"-90deg"`, `"1.2rad"`, see [`parse_angle`]) or with a
/// trailing `°`; lengths with a trailing `mm`, `cm` or `m`. NaN and infinities are rejected.
pub fn parse_entry(text: &str, quantity: Quantity, unit: AngleUnit) -> Result<f64, EntryError> {
    let s = text.trim();
    if s.is_empty() {
        return Err(EntryError::Empty);
    }
    let finite = |v: f64| {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(EntryError::NonFinite(s.to_string()))
        }
    };
    if let Ok(v) = s.parse::<f64>() {
        return finite(quantity.from_display(finite(v)?, unit));
    }
    let bad = || EntryError::NotANumber(s.to_string());
    let number = |t: &str| t.trim().parse::<f64>().map_err(|_| bad()).and_then(finite);
    match quantity {
        Quantity::Angle => {
            if let Some(n) = s.strip_suffix('°') {
                return finite(number(n)?.to_radians());
            }
            parse_angle(s).ok_or_else(bad)
        }
        Quantity::Length => {
            for (suffix, per_m) in [("mm", MM_PER_M), ("cm", 100.0), ("m", 1.0)] {
                if let Some(n) = s.strip_suffix(suffix) {
                    return finite(number(n)? / per_m);
                }
            }
            Err(bad())
        }
    }
}

/// A stored value (rad or m) as display text without unit: at most 6 decimals, trailing zeros
/// removed ("90", "431.8", "-0.7854").
pub fn format_entry(si: f64, quantity: Quantity, unit: AngleUnit) -> String {
    format_number(quantity.to_display(si, unit), 6)
}

/// A number with at most `max_decimals` decimals, trailing zeros removed, and never "-0" (a
/// value that rounds to zero is shown as "0", not with the sign of a rounding error).
pub fn format_number(v: f64, max_decimals: usize) -> String {
    let s = format!("{v:.max_decimals$}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" || s.is_empty() {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// `v`, or +0 if it shows as zero at `decimals` decimals: for fixed-decimal readouts, which
/// would otherwise print a rounding error as "-0.0".
pub fn without_negative_zero(v: f64, decimals: i32) -> f64 {
    if v.abs() < 0.5 * 10f64.powi(-decimals) {
        0.0
    } else {
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_never_show_negative_zero() {
        assert_eq!(format_number(-1e-17, 2), "0");
        assert_eq!(format_number(-0.004, 2), "0");
        assert_eq!(format_number(-0.006, 2), "-0.01");
        assert_eq!(format_number(90.0, 2), "90");
        assert_eq!(format_number(431.8, 1), "431.8");
        assert_eq!(format_number(-12.25, 1), "-12.2");
        assert_eq!(format!("{:.1}", without_negative_zero(-0.04, 1)), "0.0");
        assert_eq!(format!("{:.1}", without_negative_zero(-0.06, 1)), "-0.1");
        assert_eq!(format!("{:.2}", without_negative_zero(-1e-15, 2)), "0.00");
    }

    #[test]
    fn entries_in_display_or_explicit_units() {
        let deg = AngleUnit::Degrees;
        let ang = |t: &str| parse_entry(t, Quantity::Angle, deg);
        let len = |t: &str| parse_entry(t, Quantity::Length, deg);
        assert_eq!(ang("180").unwrap(), std::f64::consts::PI);
        assert_eq!(ang("pi/2").unwrap(), std::f64::consts::FRAC_PI_2);
        assert_eq!(ang(" 1.5rad ").unwrap(), 1.5);
        assert_eq!(
            parse_entry("1.5", Quantity::Angle, AngleUnit::Radians).unwrap(),
            1.5
        );
        assert_eq!(len("431.8").unwrap(), 0.4318);
        assert_eq!(len("0.5 m").unwrap(), 0.5);
        assert_eq!(len("20cm").unwrap(), 0.2);
        assert_eq!(len("12 mm").unwrap(), 0.012);
        assert_eq!(len(""), Err(EntryError::Empty));
        assert_eq!(len("nan"), Err(EntryError::NonFinite("nan".into())));
        assert_eq!(len("1e999"), Err(EntryError::NonFinite("1e999".into())));
        assert_eq!(ang("abc"), Err(EntryError::NotANumber("abc".into())));
        assert_eq!(len("5 deg"), Err(EntryError::NotANumber("5 deg".into())));
    }

    #[test]
    fn formatting_trims_zeros() {
        let deg = AngleUnit::Degrees;
        assert_eq!(
            format_entry(std::f64::consts::FRAC_PI_2, Quantity::Angle, deg),
            "90"
        );
        assert_eq!(format_entry(0.4318, Quantity::Length, deg), "431.8");
        assert_eq!(format_entry(-1e-12, Quantity::Length, deg), "0");
        assert_eq!(
            format_entry(0.25, Quantity::Angle, AngleUnit::Radians),
            "0.25"
        );
    }
}
