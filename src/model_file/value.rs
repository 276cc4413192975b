//! Typed access to the spanned TOML tree: every accessor reports the field path and position.

use super::angle::parse_angle;
use super::error::{Location, ModelFileError as E};
use crate::kinematics::pose::{Pose, pose_from_matrix};
use nalgebra::Matrix4;
use std::ops::Range;
use std::path::Path;
use toml::Spanned;
use toml::de::{DeArray, DeTable, DeValue};

/// A spanned TOML value.
pub(super) type Val<'i> = Spanned<DeValue<'i>>;
/// Byte range in the file.
pub(super) type Span = Range<usize>;
/// Result of this layer.
pub(super) type Res<T> = Result<T, E>;

/// The file's text and name, to turn byte spans into [`Location`]s.
pub(super) struct Ctx<'a> {
    pub(super) text: &'a str,
    pub(super) path: &'a Path,
}

impl Ctx<'_> {
    /// 1-based line and column (in characters) of the start of `span`.
    pub(super) fn at(&self, span: &Span) -> Location {
        let mut start = span.start.min(self.text.len());
        while !self.text.is_char_boundary(start) {
            start -= 1;
        }
        let before = &self.text[..start];
        let line = before.matches('\n').count() + 1;
        let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        Location {
            path: self.path.to_path_buf(),
            line,
            column,
        }
    }

    /// A field's value as a number (integer or float), finite.
    pub(super) fn number(&self, field: &str, v: &Val) -> Res<f64> {
        match v.get_ref() {
            DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
                Ok(n) => Ok(n as f64),
                Err(_) => Err(self.non_finite(field, v, i.to_string())),
            },
            DeValue::Float(x) => match x.as_str().parse::<f64>() {
                Ok(n) if n.is_finite() => Ok(n),
                _ => Err(self.non_finite(field, v, x.as_str().to_string())),
            },
            _ => Err(self.wrong_type(field, "a number", v)),
        }
    }

    /// A field's value as an angle in radians: a number, or a string read by [`parse_angle`].
    pub(super) fn angle(&self, field: &str, v: &Val) -> Res<f64> {
        match v.get_ref() {
            DeValue::String(s) => parse_angle(s).ok_or_else(|| E::BadAngle {
                field: field.to_string(),
                text: s.to_string(),
                at: self.at(&v.span()),
            }),
            DeValue::Integer(_) | DeValue::Float(_) => self.number(field, v),
            _ => Err(self.wrong_type(
                field,
                "a number or an angle string like \"pi/2\" or \"-90deg\"",
                v,
            )),
        }
    }

    /// An angle (`angular`) or a length in metres (a plain number).
    pub(super) fn scalar(&self, field: &str, v: &Val, angular: bool) -> Res<f64> {
        if angular {
            self.angle(field, v)
        } else if matches!(v.get_ref(), DeValue::String(_)) {
            Err(self.wrong_type(field, "a number (metres; angle strings are for angles)", v))
        } else {
            self.number(field, v)
        }
    }

    /// A string field.
    pub(super) fn string<'v>(&self, field: &str, v: &'v Val) -> Res<&'v str> {
        match v.get_ref() {
            DeValue::String(s) => Ok(s.as_ref()),
            _ => Err(self.wrong_type(field, "a string", v)),
        }
    }

    /// An integer field.
    pub(super) fn integer(&self, field: &str, v: &Val) -> Res<i64> {
        match v.get_ref() {
            DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix())
                .map_err(|_| self.wrong_type(field, "a joint number (an integer)", v)),
            _ => Err(self.wrong_type(field, "a joint number (an integer)", v)),
        }
    }

    /// An array field.
    pub(super) fn array<'v, 'i>(
        &self,
        field: &str,
        v: &'v Val<'i>,
        expected: &'static str,
    ) -> Res<&'v DeArray<'i>> {
        match v.get_ref() {
            DeValue::Array(a) => Ok(a),
            _ => Err(self.wrong_type(field, expected, v)),
        }
    }

    /// An array with exactly `n` elements.
    pub(super) fn array_n<'v, 'i>(
        &self,
        field: &str,
        v: &'v Val<'i>,
        n: usize,
        expected: &'static str,
    ) -> Res<&'v DeArray<'i>> {
        let a = self.array(field, v, expected)?;
        if a.len() == n {
            Ok(a)
        } else {
            Err(E::WrongLength {
                field: field.to_string(),
                expected,
                found: a.len(),
                at: self.at(&v.span()),
            })
        }
    }

    /// A row-major 4x4 homogeneous matrix that must be a rigid transform.
    pub(super) fn pose(&self, field: &str, v: &Val) -> Res<Pose> {
        const WHAT: &str = "a 4x4 matrix (an array of 4 rows of 4 numbers)";
        let rows = self.array_n(field, v, 4, WHAT)?;
        let mut m = Matrix4::zeros();
        for (r, row) in rows.iter().enumerate() {
            let rf = format!("{field}[{}]", r + 1);
            let cols = self.array_n(&rf, row, 4, "a matrix row of 4 numbers")?;
            for (c, x) in cols.iter().enumerate() {
                m[(r, c)] = self.number(&format!("{rf}[{}]", c + 1), x)?;
            }
        }
        pose_from_matrix(&m).map_err(|reason| E::NotRigid {
            field: field.to_string(),
            reason,
            at: self.at(&v.span()),
        })
    }

    /// "expected X, found Y" for `v`.
    pub(super) fn wrong_type(&self, field: &str, expected: &'static str, v: &Val) -> E {
        let found = match v.get_ref() {
            DeValue::String(s) => format!("string \"{s}\""),
            DeValue::Integer(i) => format!("integer {i}"),
            DeValue::Float(x) => format!("float {x}"),
            DeValue::Boolean(b) => format!("boolean {b}"),
            other => other.type_str().to_string(),
        };
        E::WrongType {
            field: field.to_string(),
            expected,
            found,
            at: self.at(&v.span()),
        }
    }

    fn non_finite(&self, field: &str, v: &Val, text: String) -> E {
        E::NonFinite {
            field: field.to_string(),
            text,
            at: self.at(&v.span()),
        }
    }
}

/// A TOML table with its position and path, whose keys are checked against the schema.
pub(super) struct Table<'t, 'i> {
    /// The entries.
    pub(super) table: &'t DeTable<'i>,
    /// The table header (`[[joints]]`) or the whole document.
    pub(super) span: Span,
    /// The table's path, "" for the top level.
    pub(super) field: String,
}

impl<'t, 'i> Table<'t, 'i> {
    /// Views `v` as a table (error naming `field` if it is not one).
    pub(super) fn of(ctx: &Ctx, field: String, v: &'t Val<'i>) -> Res<Self> {
        match v.get_ref() {
            DeValue::Table(table) => Ok(Self {
                table,
                span: v.span(),
                field,
            }),
            _ => Err(ctx.wrong_type(&field, "a table", v)),
        }
    }

    /// The path of `key` in this table.
    pub(super) fn path(&self, key: &str) -> String {
        if self.field.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.field)
        }
    }

    /// The value of `key`, if present.
    pub(super) fn get(&self, key: &str) -> Option<&'t Val<'i>> {
        self.table.get(key)
    }

    /// The value of `key`, or a "missing required field" error at the table.
    pub(super) fn required(&self, ctx: &Ctx, key: &str) -> Res<&'t Val<'i>> {
        self.get(key).ok_or_else(|| self.missing(ctx, key))
    }

    /// The "missing required field" error for `key`, at the table.
    pub(super) fn missing(&self, ctx: &Ctx, key: &str) -> E {
        E::Missing {
            field: self.path(key),
            at: ctx.at(&self.span),
        }
    }

    /// The span of `key` itself (for errors about a key rather than its value).
    pub(super) fn key_span(&self, key: &str) -> Span {
        self.table
            .get_key_value(key)
            .map_or(self.span.clone(), |(k, _)| k.span())
    }

    /// Rejects the first key (in file order) that is not in `allowed`.
    pub(super) fn check_keys(&self, ctx: &Ctx, allowed: &[&str]) -> Res<()> {
        let unknown = self
            .table
            .iter()
            .filter(|(k, _)| !allowed.contains(&k.get_ref().as_ref()))
            .min_by_key(|(k, _)| k.span().start);
        match unknown {
            None => Ok(()),
            Some((k, _)) => Err(E::UnknownKey {
                field: self.path(k.get_ref()),
                key: k.get_ref().to_string(),
                allowed: allowed.join(", "),
                at: ctx.at(&k.span()),
            }),
        }
    }

    /// The array of tables under `key` (absent = empty), each with its path `key[i]`.
    pub(super) fn tables(&self, ctx: &Ctx, key: &str) -> Res<Vec<Table<'t, 'i>>> {
        let Some(v) = self.get(key) else {
            return Ok(Vec::new());
        };
        let field = self.path(key);
        let a = ctx.array(&field, v, "an array of tables ([[...]] sections)")?;
        a.iter()
            .enumerate()
            .map(|(i, t)| Table::of(ctx, format!("{field}[{}]", i + 1), t))
            .collect()
    }
}
