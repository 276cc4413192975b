//! Joint vectors and numeric rows from the command line and from input files, with errors that
//! name the source, the line and the field. Nothing is computed until every row has parsed.

use std::path::{Path, PathBuf};
use thiserror::Error;

/// A bad number list, located.
#[derive(Debug, Error)]
pub enum InputError {
    /// A field that is not a finite number.
    #[error("{source_name}: value {field} ({text:?}) is not a finite number")]
    NotANumber {
        /// Where (e.g. `--q` or `poses.txt:3`).
        source_name: String,
        /// 1-based field number in the row.
        field: usize,
        /// The offending text.
        text: String,
    },
    /// Wrong number of fields.
    #[error("{source_name}: expected {expected} {what}, got {got}")]
    Count {
        /// Where.
        source_name: String,
        /// What was expected (e.g. "joint values").
        what: &'static str,
        /// Expected count.
        expected: usize,
        /// Count found.
        got: usize,
    },
    /// The file could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file has no data rows.
    #[error("{}: no data rows (blank lines and # comments only)", path.display())]
    Empty {
        /// The file.
        path: PathBuf,
    },
}

/// Parses `"1, 2.5, -3e-2"` (or `"1 2.5 -3e-2"`, whitespace alone) into numbers: every field must be a finite number and there must be
/// exactly `expected` of them. `scale[k]` multiplies field k (e.g. degrees to radians).
pub fn parse_row(
    text: &str,
    source_name: &str,
    expected: usize,
    what: &'static str,
) -> Result<Vec<f64>, InputError> {
    // Commas, or whitespace alone ("16 numbers" as a pose is usually written).
    let fields: Vec<&str> = if text.contains(',') {
        text.split(',').map(str::trim).collect()
    } else {
        text.split_whitespace().collect()
    };
    let fields: Vec<&str> = if fields.len() == 1 && fields[0].is_empty() {
        Vec::new()
    } else {
        fields
    };
    let mut out = Vec::with_capacity(fields.len());
    for (i, f) in fields.iter().enumerate() {
        match f.parse::<f64>() {
            Ok(v) if v.is_finite() => out.push(v),
            _ => {
                return Err(InputError::NotANumber {
                    source_name: source_name.into(),
                    field: i + 1,
                    text: (*f).into(),
                });
            }
        }
    }
    if out.len() != expected {
        return Err(InputError::Count {
            source_name: source_name.into(),
            what,
            expected,
            got: out.len(),
        });
    }
    Ok(out)
}

/// Reads a file (or standard input for `-`) of comma-separated rows, `#` comments and blank
/// lines ignored, each row with exactly `expected` numbers. Errors name `file:line`.
pub fn read_rows(
    path: &Path,
    expected: usize,
    what: &'static str,
) -> Result<Vec<Vec<f64>>, InputError> {
    let text = if path == Path::new("-") {
        std::io::read_to_string(std::io::stdin())
    } else {
        std::fs::read_to_string(path)
    }
    .map_err(|source| InputError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let mut rows = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let data = line.split('#').next().unwrap_or("").trim();
        if data.is_empty() {
            continue;
        }
        let where_ = format!("{}:{}", path.display(), n + 1);
        rows.push(parse_row(data, &where_, expected, what)?);
    }
    if rows.is_empty() {
        return Err(InputError::Empty {
            path: path.to_path_buf(),
        });
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_parse_and_fail_precisely() {
        assert_eq!(
            parse_row(" 1, -2.5 ,3e-1", "--q", 3, "joint values").unwrap(),
            vec![1.0, -2.5, 0.3]
        );
        let e = parse_row("1,NaN,3", "--q", 3, "joint values")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "--q: value 2 (\"NaN\") is not a finite number");
        let e = parse_row("1,,3", "f:4", 3, "joint values")
            .unwrap_err()
            .to_string();
        assert!(e.contains("value 2"), "{e}");
        let e = parse_row("1,2", "--q", 3, "joint values")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "--q: expected 3 joint values, got 2");
        assert!(parse_row("", "--q", 1, "joint values").is_err());
        assert!(parse_row("inf", "--q", 1, "joint values").is_err());
    }
}
