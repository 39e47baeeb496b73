//! The values of a data array: ASCII tokens, inline base64 or appended raw binary, exactly
//! as many as expected and never more than the bytes present hold.

use super::super::vtk_binary::{decode_base64, Layout, Number, Scalar};
use super::scan::{line_of, Array};
use crate::MeshError;
use std::borrow::Cow;
use std::path::Path;

/// The file being read: its XML text and the bytes of its `<AppendedData>`.
pub(super) struct Source<'a> {
    pub(super) path: &'a Path,
    pub(super) text: &'a str,
    pub(super) appended: Option<&'a [u8]>,
    pub(super) layout: Layout,
    /// A `compressor` other than zlib, refused when a binary array is read.
    pub(super) unsupported_compressor: Option<String>,
}

/// Exactly `expected` values of an array, ASCII or binary.
pub(super) fn values<T: Number>(
    src: &Source,
    a: &Array,
    expected: usize,
) -> Result<Vec<T>, MeshError> {
    match a.format() {
        "ascii" => ascii_values(src.path, src.text, a, expected),
        _ => binary_values(src, a, expected),
    }
}

/// The values of an inline base64 (`binary`) or `appended` array, whose bytes must be exactly
/// `expected` values of its `type`.
fn binary_values<T: Number>(src: &Source, a: &Array, expected: usize) -> Result<Vec<T>, MeshError> {
    let fail = |message: String| {
        MeshError::parse(
            src.path,
            a.line,
            format!("data array \"{}\": {message}", a.name()),
        )
    };
    if let Some(c) = &src.unsupported_compressor {
        return Err(fail(format!(
            "compressor \"{c}\" is not supported (isochor reads vtkZLibDataCompressor or \
             uncompressed data)"
        )));
    }
    let kind = a.attribute("type").unwrap_or("");
    let scalar = Scalar::from_vtk(kind)
        .ok_or_else(|| fail(format!("type \"{kind}\" is not a numeric VTK type")))?;
    let size = expected
        .checked_mul(scalar.size())
        .ok_or_else(|| fail("more values than memory can hold".into()))?;
    let inline;
    let data: &[u8] = if a.format() == "binary" {
        inline = decode_base64(a.content)
            .map_err(|e| fail(format!("its inline binary data is not base64: {e}")))?;
        &inline
    } else {
        let offset = a
            .attribute("offset")
            .ok_or_else(|| fail("expected an offset into the appended data".into()))?;
        let offset: usize = offset.trim().parse().map_err(|_| {
            fail(format!(
                "expected offset to be an integer, found `{offset}`"
            ))
        })?;
        let appended = src
            .appended
            .ok_or_else(|| fail("the file has no <AppendedData> for this appended array".into()))?;
        appended.get(offset..).ok_or_else(|| {
            fail(format!(
                "offset {offset} is past the end of the appended data ({} bytes)",
                appended.len()
            ))
        })?
    };
    let bytes: Cow<[u8]> = src.layout.array(data, size).map_err(fail)?;
    bytes
        .chunks_exact(scalar.size())
        .enumerate()
        .map(|(i, b)| {
            let n = scalar.read(b, src.layout.big_endian);
            T::from_num(n).ok_or_else(|| {
                fail(format!(
                    "value {i} ({n}) is not a {}",
                    std::any::type_name::<T>()
                ))
            })
        })
        .collect()
}

/// Exactly `expected` whitespace-separated values of an ASCII array, or an error at the line
/// of the offending token.
fn ascii_values<T: Number>(
    path: &Path,
    text: &str,
    a: &Array,
    expected: usize,
) -> Result<Vec<T>, MeshError> {
    let mut out = Vec::new();
    for (i, token) in a.content.split_ascii_whitespace().enumerate() {
        let value = token.parse().map_err(|_| {
            MeshError::parse(
                path,
                token_line(text, a, i),
                format!(
                    "data array \"{}\": expected a {} value, found `{token}`",
                    a.name(),
                    std::any::type_name::<T>()
                ),
            )
        })?;
        if out.len() == expected {
            return Err(MeshError::parse(
                path,
                token_line(text, a, i),
                format!(
                    "data array \"{}\": more than the expected {expected} values",
                    a.name()
                ),
            ));
        }
        out.push(value);
    }
    if out.len() < expected {
        return Err(MeshError::parse(
            path,
            a.line,
            format!(
                "data array \"{}\" has {} values, expected {expected}",
                a.name(),
                out.len()
            ),
        ));
    }
    Ok(out)
}

/// Line of the `i`-th value of array `a` (or of its tag if there are fewer values, or if it
/// is binary).
pub(super) fn token_line(text: &str, a: &Array, i: usize) -> usize {
    if a.format() != "ascii" {
        return a.line;
    }
    a.content
        .split_ascii_whitespace()
        .nth(i)
        .map_or(a.line, |t| {
            line_of(
                text.as_bytes(),
                t.as_ptr() as usize - text.as_ptr() as usize,
            )
        })
}
