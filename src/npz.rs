//! NumPy `.npz` archives (what `numpy.savez_compressed` writes and `numpy.load` opens): named
//! arrays of booleans, 16-bit unsigned integers, doubles and text, written and read with
//! ndarray-npy (deflate-compressed zip of `.npy` files). Text is stored as NumPy's fixed-width
//! Unicode (`<U64`: at most [`TEXT_CHARS`] characters per entry, longer text is refused).
//!
//! Reading refuses what armlab did not write the way it writes it (another element type, a
//! missing array) with an error naming the file and the array.

use ndarray::{ArrayD, ArrayViewD, IxDyn};
use ndarray_npy::{
    NpzReader, NpzWriter, ReadDataError, ReadableElement, WritableElement, WriteDataError,
};
use py_literal::Value as PyValue;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Most characters of one text entry.
pub const TEXT_CHARS: usize = 64;

/// The elements of one array, borrowed for writing.
#[derive(Debug, Clone, Copy)]
pub enum NpzSlice<'a> {
    /// `bool` (NumPy `|b1`).
    Bool(&'a [bool]),
    /// `uint16` (`<u2`).
    U16(&'a [u16]),
    /// `float64` (`<f8`).
    F64(&'a [f64]),
    /// Text (`<U64`).
    Text(&'a [String]),
}

/// The elements of one array, read back.
#[derive(Debug, Clone, PartialEq)]
pub enum NpzData {
    /// `bool`.
    Bool(Vec<bool>),
    /// `uint16`.
    U16(Vec<u16>),
    /// `float64`.
    F64(Vec<f64>),
    /// Text.
    Text(Vec<String>),
}

/// A failure reading or writing an archive, naming the file and the array.
#[derive(Debug, Error)]
pub enum NpzError {
    /// The file could not be created, written or opened.
    #[error("{}: {source}", path.display())]
    Io {
        /// The archive.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The zip or `.npy` layer failed for one array.
    #[error("{}: array {name:?}: {message}", path.display())]
    Array {
        /// The archive.
        path: PathBuf,
        /// The array.
        name: String,
        /// What ndarray-npy said.
        message: String,
    },
    /// The shape does not hold the elements given.
    #[error("{}: array {name:?} has {len} elements, its shape {shape:?} holds {expected}", path.display())]
    Shape {
        /// The archive.
        path: PathBuf,
        /// The array.
        name: String,
        /// Elements given.
        len: usize,
        /// The shape.
        shape: Vec<usize>,
        /// Elements the shape holds.
        expected: usize,
    },
    /// A text entry longer than [`TEXT_CHARS`].
    #[error("{}: array {name:?}: text {text:?} is longer than {TEXT_CHARS} characters", path.display())]
    TextTooLong {
        /// The archive.
        path: PathBuf,
        /// The array.
        name: String,
        /// The text (cut).
        text: String,
    },
    /// The file is not a zip archive (so no .npz).
    #[error("{}: not a NumPy .npz archive ({message})", path.display())]
    NotNpz {
        /// The file.
        path: PathBuf,
        /// What the zip reader said.
        message: String,
    },
    /// An array the reader needs is missing or of another type.
    #[error("{}: no array {name:?} of {what} (the file was not written by armlab, or by another version)", path.display())]
    Missing {
        /// The archive.
        path: PathBuf,
        /// The array.
        name: String,
        /// The type expected, in words.
        what: &'static str,
    },
}

/// One fixed-width Unicode entry (`<U64`), padded with NUL as NumPy pads.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Text([char; TEXT_CHARS]);

impl Text {
    fn of(s: &str) -> Option<Self> {
        let mut out = ['\0'; TEXT_CHARS];
        for (n, c) in s.chars().enumerate() {
            *out.get_mut(n)? = c;
        }
        Some(Self(out))
    }

    fn text(&self) -> String {
        self.0.iter().take_while(|&&c| c != '\0').collect()
    }
}

impl WritableElement for Text {
    fn type_descriptor() -> PyValue {
        PyValue::String(format!("<U{TEXT_CHARS}"))
    }

    fn write<W: Write>(&self, mut writer: W) -> Result<(), WriteDataError> {
        for c in self.0 {
            writer.write_all(&(c as u32).to_le_bytes())?;
        }
        Ok(())
    }

    fn write_slice<W: Write>(slice: &[Self], mut writer: W) -> Result<(), WriteDataError> {
        for t in slice {
            t.write(&mut writer)?;
        }
        Ok(())
    }
}

impl ReadableElement for Text {
    fn read_to_end_exact_vec<R: Read>(
        mut reader: R,
        type_desc: &PyValue,
        len: usize,
    ) -> Result<Vec<Self>, ReadDataError> {
        let width = match type_desc {
            PyValue::String(s) => s
                .strip_prefix("<U")
                .and_then(|w| w.parse::<usize>().ok())
                .filter(|&w| w <= TEXT_CHARS),
            _ => None,
        };
        let Some(width) = width else {
            return Err(ReadDataError::WrongDescriptor(type_desc.clone()));
        };
        let mut bytes = vec![0u8; len * width * 4];
        reader
            .read_exact(&mut bytes)
            .map_err(|_| ReadDataError::MissingData)?;
        let mut rest = [0u8; 1];
        if reader.read(&mut rest)? != 0 {
            return Err(ReadDataError::ExtraBytes(1));
        }
        let mut out = Vec::with_capacity(len);
        for entry in bytes.chunks(width * 4) {
            let mut t = ['\0'; TEXT_CHARS];
            for (k, c) in entry.chunks(4).enumerate() {
                let code = u32::from_le_bytes([c[0], c[1], c[2], c[3]]);
                t[k] = char::from_u32(code).ok_or_else(|| {
                    ReadDataError::ParseData(format!("code point {code:#x} is no character").into())
                })?;
            }
            out.push(Text(t));
        }
        Ok(out)
    }
}

/// Writes `arrays` (name, shape, elements) to a compressed `.npz` at `path`, as
/// `numpy.savez_compressed` would.
///
/// # Errors
///
/// A shape that does not hold its elements, text over [`TEXT_CHARS`] characters, or a file
/// that cannot be written; each names the file and the array.
pub fn write_npz(path: &Path, arrays: &[(&str, Vec<usize>, NpzSlice<'_>)]) -> Result<(), NpzError> {
    let io = |source| NpzError::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::create(path).map_err(io)?;
    let mut npz = NpzWriter::new_with_options(
        std::io::BufWriter::new(file),
        zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated)
            .large_file(true),
    );
    for (name, shape, data) in arrays {
        let fail = |message: String| NpzError::Array {
            path: path.to_path_buf(),
            name: name.to_string(),
            message,
        };
        let len = match data {
            NpzSlice::Bool(d) => d.len(),
            NpzSlice::U16(d) => d.len(),
            NpzSlice::F64(d) => d.len(),
            NpzSlice::Text(d) => d.len(),
        };
        let expected: usize = shape.iter().product();
        if expected != len {
            return Err(NpzError::Shape {
                path: path.to_path_buf(),
                name: name.to_string(),
                len,
                shape: shape.clone(),
                expected,
            });
        }
        let dim = IxDyn(shape);
        let added = match data {
            NpzSlice::Bool(d) => npz.add_array(*name, &view(dim, d)),
            NpzSlice::U16(d) => npz.add_array(*name, &view(dim, d)),
            NpzSlice::F64(d) => npz.add_array(*name, &view(dim, d)),
            NpzSlice::Text(d) => {
                let texts = d
                    .iter()
                    .map(|s| {
                        Text::of(s).ok_or_else(|| NpzError::TextTooLong {
                            path: path.to_path_buf(),
                            name: name.to_string(),
                            text: s.chars().take(80).collect(),
                        })
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                npz.add_array(*name, &view(dim, &texts))
            }
        };
        added.map_err(|e| fail(e.to_string()))?;
    }
    npz.finish().map_err(|e| NpzError::Array {
        path: path.to_path_buf(),
        name: String::new(),
        message: e.to_string(),
    })?;
    Ok(())
}

/// A shaped view of a slice whose length the caller checked.
fn view<'a, T>(dim: IxDyn, d: &'a [T]) -> ArrayViewD<'a, T> {
    ArrayViewD::from_shape(dim, d).unwrap_or_else(|_| unreachable!("the length was checked"))
}

/// An open `.npz` archive to read arrays from by name.
pub struct NpzFile {
    path: PathBuf,
    reader: NpzReader<std::io::BufReader<std::fs::File>>,
}

impl std::fmt::Debug for NpzFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NpzFile").field("path", &self.path).finish()
    }
}

impl NpzFile {
    /// Opens the archive at `path`.
    ///
    /// # Errors
    ///
    /// A file that cannot be opened or is no zip archive.
    pub fn open(path: &Path) -> Result<Self, NpzError> {
        let file = std::fs::File::open(path).map_err(|source| NpzError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let reader =
            NpzReader::new(std::io::BufReader::new(file)).map_err(|e| NpzError::NotNpz {
                path: path.to_path_buf(),
                message: e.to_string(),
            })?;
        Ok(Self {
            path: path.to_path_buf(),
            reader,
        })
    }

    /// Array `name` with its shape, as `what` ("bool", "uint16", "float64", "text").
    ///
    /// # Errors
    ///
    /// [`NpzError::Missing`] when there is no such array of that type.
    pub fn read(
        &mut self,
        name: &str,
        what: &'static str,
    ) -> Result<(Vec<usize>, NpzData), NpzError> {
        let missing = || NpzError::Missing {
            path: self.path.clone(),
            name: name.to_string(),
            what,
        };
        fn shaped<T: Clone>(a: ArrayD<T>) -> (Vec<usize>, Vec<T>) {
            let shape = a.shape().to_vec();
            (shape, a.into_iter().collect())
        }
        let out = match what {
            "bool" => self
                .reader
                .by_name::<ndarray::OwnedRepr<bool>, IxDyn>(name)
                .map(|a| {
                    let (s, d) = shaped(a);
                    (s, NpzData::Bool(d))
                }),
            "uint16" => self
                .reader
                .by_name::<ndarray::OwnedRepr<u16>, IxDyn>(name)
                .map(|a| {
                    let (s, d) = shaped(a);
                    (s, NpzData::U16(d))
                }),
            "float64" => self
                .reader
                .by_name::<ndarray::OwnedRepr<f64>, IxDyn>(name)
                .map(|a| {
                    let (s, d) = shaped(a);
                    (s, NpzData::F64(d))
                }),
            _ => self
                .reader
                .by_name::<ndarray::OwnedRepr<Text>, IxDyn>(name)
                .map(|a| {
                    let (s, d) = shaped(a);
                    (s, NpzData::Text(d.iter().map(Text::text).collect()))
                }),
        };
        out.map_err(|_| missing())
    }
}
