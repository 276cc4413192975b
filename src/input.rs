//! Reading outside text: files with a size cap, lines with a length cap, and rows of numbers
//! (joint vectors, targets, points) with errors that name the source, the line and the field.
//! Nothing is computed until every row has parsed. A file, a line or a row too large for
//! armlab is refused with the limit in words, before it is read into memory.

use std::io::{BufRead, Read};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Most bytes read from a model file (TOML or URDF): 16 MiB.
pub const MAX_MODEL_BYTES: u64 = 16 << 20;
/// Most bytes read from a data file (joint vectors, targets, points, measurements): 256 MiB.
pub const MAX_DATA_BYTES: u64 = 256 << 20;
/// Most bytes in one line of a data file: 1 MiB (a row of 10,000 numbers takes ~250 kB).
pub const MAX_LINE_BYTES: usize = 1 << 20;

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
        /// The offending text (cut to 40 characters).
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
    /// The file could not be read (or is larger than armlab reads).
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A line longer than [`MAX_LINE_BYTES`].
    #[error("{source_name}: line longer than {max} bytes")]
    LineTooLong {
        /// Where (`file:line`).
        source_name: String,
        /// The limit (bytes).
        max: usize,
    },
    /// The file has no data rows.
    #[error("{}: no data rows (blank lines and # comments only)", path.display())]
    Empty {
        /// The file.
        path: PathBuf,
    },
}

/// Human-readable size: "1.0 GB", "16 MiB"-style figures for messages.
fn size_words(bytes: u64) -> String {
    match bytes {
        b if b >= 1 << 30 => format!("{:.1} GiB", b as f64 / (1u64 << 30) as f64),
        b if b >= 1 << 20 => format!("{:.1} MiB", b as f64 / (1u64 << 20) as f64),
        b => format!("{b} bytes"),
    }
}

fn too_large(what: &str, max_bytes: u64) -> std::io::Error {
    std::io::Error::new(
        std::io::ErrorKind::InvalidData,
        format!(
            "larger than the {} armlab reads from {what}",
            size_words(max_bytes)
        ),
    )
}

/// Reads a UTF-8 file (or standard input for `-`) of at most `max_bytes`, refusing a larger one
/// before reading it (its size is in the error); `what` names the kind ("a model file").
pub fn read_text(path: &Path, max_bytes: u64, what: &str) -> std::io::Result<String> {
    let mut text = String::new();
    if path == Path::new("-") {
        std::io::stdin()
            .lock()
            .take(max_bytes + 1)
            .read_to_string(&mut text)?;
    } else {
        let file = std::fs::File::open(path)?;
        let len = file.metadata()?.len();
        if len > max_bytes {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!(
                    "the file is {}, larger than the {} armlab reads from {what}",
                    size_words(len),
                    size_words(max_bytes)
                ),
            ));
        }
        std::io::BufReader::new(file)
            .take(max_bytes + 1)
            .read_to_string(&mut text)?;
    }
    if text.len() as u64 > max_bytes {
        return Err(too_large(what, max_bytes));
    }
    Ok(text)
}

/// Reads a regular file (a device such as /dev/zero would be read forever) of at most
/// `max_bytes`, refusing a larger one with its size in the error; `what` names the kind
/// ("a mesh").
pub fn read_bytes(path: &Path, max_bytes: u64, what: &str) -> std::io::Result<Vec<u8>> {
    let refuse = |why: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, why);
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(refuse(format!("{}: not a regular file", path.display())));
    }
    let too_large = |len: u64| {
        refuse(format!(
            "{}: the file is {} MiB, larger than the {} MiB armlab reads from {what}",
            path.display(),
            len >> 20,
            max_bytes >> 20
        ))
    };
    if meta.len() > max_bytes {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(max_bytes + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// Cuts a field's text for a message (at most 40 characters).
fn excerpt(text: &str) -> String {
    match text.char_indices().nth(40) {
        Some((i, _)) => format!("{}...", &text[..i]),
        None => text.to_string(),
    }
}

/// Parses `"1, 2.5, -3e-2"` (or `"1 2.5 -3e-2"`, whitespace alone) into numbers: every field
/// must be a finite number and there must be exactly `expected` of them. The fields are counted
/// before any is stored, so a huge row costs no memory.
pub fn parse_row(
    text: &str,
    source_name: &str,
    expected: usize,
    what: &'static str,
) -> Result<Vec<f64>, InputError> {
    // Commas, or whitespace alone ("16 numbers" as a pose is usually written).
    let fields = || -> Box<dyn Iterator<Item = &str>> {
        if text.trim().is_empty() {
            Box::new(std::iter::empty())
        } else if text.contains(',') {
            Box::new(text.split(',').map(str::trim))
        } else {
            Box::new(text.split_whitespace())
        }
    };
    let got = fields().count();
    if got != expected {
        // Say which field is bad first when one is (e.g. "1,,3" or "1,x").
        if let Some((i, f)) = fields()
            .take(expected.max(1))
            .enumerate()
            .find(|(_, f)| !f.parse::<f64>().is_ok_and(f64::is_finite))
        {
            return Err(InputError::NotANumber {
                source_name: source_name.into(),
                field: i + 1,
                text: excerpt(f),
            });
        }
        return Err(InputError::Count {
            source_name: source_name.into(),
            what,
            expected,
            got,
        });
    }
    let mut out = Vec::with_capacity(expected);
    for (i, f) in fields().enumerate() {
        match f.parse::<f64>() {
            Ok(v) if v.is_finite() => out.push(v),
            _ => {
                return Err(InputError::NotANumber {
                    source_name: source_name.into(),
                    field: i + 1,
                    text: excerpt(f),
                });
            }
        }
    }
    Ok(out)
}

/// Parses the text of a rows file: comma-separated rows, `#` comments and blank lines ignored,
/// each row with exactly `expected` numbers. Errors name `source_name:line`. Returns each row
/// with its 1-based line number.
pub fn parse_rows(
    text: &str,
    source_name: &str,
    expected: usize,
    what: &'static str,
) -> Result<Vec<(usize, Vec<f64>)>, InputError> {
    let mut rows = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let where_ = || format!("{source_name}:{}", n + 1);
        if line.len() > MAX_LINE_BYTES {
            return Err(InputError::LineTooLong {
                source_name: where_(),
                max: MAX_LINE_BYTES,
            });
        }
        let data = line.split('#').next().unwrap_or("").trim();
        if data.is_empty() {
            continue;
        }
        rows.push((n + 1, parse_row(data, &where_(), expected, what)?));
    }
    Ok(rows)
}

/// Reads a rows file (or standard input for `-`, at most [`MAX_DATA_BYTES`]) and parses it with
/// [`parse_rows`]; a file without data rows is an error.
pub fn read_numbered_rows(
    path: &Path,
    expected: usize,
    what: &'static str,
) -> Result<Vec<(usize, Vec<f64>)>, InputError> {
    let text = read_data_text(path)?;
    let rows = parse_rows(&text, &path.display().to_string(), expected, what)?;
    if rows.is_empty() {
        return Err(InputError::Empty {
            path: path.to_path_buf(),
        });
    }
    Ok(rows)
}

/// [`read_numbered_rows`] without the line numbers.
pub fn read_rows(
    path: &Path,
    expected: usize,
    what: &'static str,
) -> Result<Vec<Vec<f64>>, InputError> {
    Ok(read_numbered_rows(path, expected, what)?
        .into_iter()
        .map(|(_, r)| r)
        .collect())
}

/// Reads a data file (or `-`) of at most [`MAX_DATA_BYTES`], refusing a line longer than
/// [`MAX_LINE_BYTES`] as it streams (a 1 GB line is never held in memory).
pub fn read_data_text(path: &Path) -> Result<String, InputError> {
    let read_err = |source| InputError::Read {
        path: path.to_path_buf(),
        source,
    };
    let reader: Box<dyn BufRead> = if path == Path::new("-") {
        Box::new(std::io::stdin().lock())
    } else {
        let file = std::fs::File::open(path).map_err(read_err)?;
        let len = file.metadata().map_err(read_err)?.len();
        if len > MAX_DATA_BYTES {
            return Err(read_err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!(
                    "the file is {}, larger than the {} armlab reads from a data file",
                    size_words(len),
                    size_words(MAX_DATA_BYTES)
                ),
            )));
        }
        Box::new(std::io::BufReader::new(file))
    };
    let mut reader = reader.take(MAX_DATA_BYTES + 1);
    let mut text = String::new();
    let mut line = Vec::new();
    for n in 1.. {
        line.clear();
        let got = (&mut reader)
            .take(MAX_LINE_BYTES as u64 + 2)
            .read_until(b'\n', &mut line)
            .map_err(read_err)?;
        if got == 0 {
            break;
        }
        let body = line.strip_suffix(b"\n").unwrap_or(&line);
        if body.strip_suffix(b"\r").unwrap_or(body).len() > MAX_LINE_BYTES {
            return Err(InputError::LineTooLong {
                source_name: format!("{}:{n}", path.display()),
                max: MAX_LINE_BYTES,
            });
        }
        let s = std::str::from_utf8(&line).map_err(|e| {
            read_err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("line {n} is not UTF-8 text ({e})"),
            ))
        })?;
        text.push_str(s);
        if text.len() as u64 > MAX_DATA_BYTES {
            return Err(read_err(too_large("a data file", MAX_DATA_BYTES)));
        }
    }
    Ok(text)
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
