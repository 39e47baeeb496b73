//! The binary layer of VTK XML files: arrays compressed with zlib in blocks (VTK's
//! `vtkZLibDataCompressor`) or stored raw behind a byte count, with `UInt32` or `UInt64`
//! headers in either byte order, inline base64 text, and the numeric types of `DataArray`s.
//! Decoders never trust a size beyond the bytes actually present.

use flate2::read::ZlibDecoder;
use flate2::write::ZlibEncoder;
use flate2::Compression;
use rayon::prelude::*;
use std::borrow::Cow;
use std::fmt;
use std::io::{self, Read, Write};

/// Uncompressed size of a block of a written array (VTK's default).
const BLOCK_SIZE: usize = 1 << 15;

/// zlib level of written blocks: on a 64K-tet frame, level 3 wrote the smallest file of levels
/// 1 to 6 (miniz_oxide), in a third of the time of the default level 6.
const LEVEL: u32 = 3;

/// Deflate expands a block by at most about this factor: a bound for memory reserved up front.
const MAX_INFLATION: usize = 1032;

/// Appends `bytes` to `out` as VTK's zlib-compressed array with a `UInt64` little-endian
/// header: the number of blocks, the block size, the size of a partial last block (0 if it is
/// full), the compressed size of each block; then the blocks. Blocks are compressed in
/// parallel.
pub(super) fn append_compressed(out: &mut Vec<u8>, bytes: &[u8]) -> io::Result<()> {
    let blocks = bytes
        .par_chunks(BLOCK_SIZE)
        .map(|block| {
            let mut z = ZlibEncoder::new(Vec::new(), Compression::new(LEVEL));
            z.write_all(block)?;
            z.finish()
        })
        .collect::<io::Result<Vec<_>>>()?;
    let header = [blocks.len(), BLOCK_SIZE, bytes.len() % BLOCK_SIZE]
        .into_iter()
        .chain(blocks.iter().map(Vec::len));
    for word in header {
        out.extend_from_slice(&(word as u64).to_le_bytes());
    }
    blocks.iter().for_each(|b| out.extend_from_slice(b));
    Ok(())
}

/// How the binary arrays of a file are laid out (attributes of `<VTKFile>`).
#[derive(Debug, Clone, Copy)]
pub(super) struct Layout {
    /// `byte_order="BigEndian"`.
    pub big_endian: bool,
    /// `header_type="UInt64"` (else `UInt32`).
    pub header64: bool,
    /// `compressor="vtkZLibDataCompressor"` (else raw arrays behind a byte count).
    pub zlib: bool,
}

impl Layout {
    /// The bytes of the array at the start of `data` (a header, then raw or compressed data;
    /// bytes after the array are ignored), which must be `expected` bytes long.
    pub fn array<'d>(&self, data: &'d [u8], expected: usize) -> Result<Cow<'d, [u8]>, String> {
        if self.zlib {
            self.inflate(data, expected).map(Cow::Owned)
        } else {
            let size = self.word(data, 0)?;
            let body = &data[self.header_size()..];
            let bytes = body.get(..size).ok_or_else(|| {
                format!(
                    "its header declares {size} bytes but only {} follow",
                    body.len()
                )
            })?;
            check_size(bytes.len(), expected, "its header declares")?;
            Ok(Cow::Borrowed(bytes))
        }
    }

    /// Decompresses the blocks of a zlib-compressed array.
    fn inflate(&self, data: &[u8], expected: usize) -> Result<Vec<u8>, String> {
        let blocks = self.word(data, 0)?;
        let block_size = self.word(data, 1)?;
        let last = self.word(data, 2)?;
        let h = self.header_size();
        let header_len = blocks
            .checked_add(3)
            .and_then(|words| words.checked_mul(h))
            .filter(|&len| len <= data.len())
            .ok_or_else(|| {
                format!(
                    "its compression header declares {blocks} blocks, more than the {} bytes \
                     left in the file can describe",
                    data.len()
                )
            })?;
        if last > block_size {
            return Err(format!(
                "its compression header declares a last block of {last} bytes, larger than \
                 the block size {block_size}"
            ));
        }
        let total = match blocks {
            0 => Some(0),
            b => (b - 1)
                .checked_mul(block_size)
                .and_then(|full| full.checked_add(if last == 0 { block_size } else { last })),
        }
        .ok_or("its compression header declares more bytes than memory can hold")?;
        check_size(total, expected, "its compression header declares")?;
        let mut out = Vec::new();
        let mut at = header_len;
        for i in 0..blocks {
            let compressed = self.word(data, 3 + i)?;
            let block = at
                .checked_add(compressed)
                .and_then(|end| data.get(at..end))
                .ok_or_else(|| {
                    format!(
                        "block {i} of {compressed} compressed bytes runs past the end of the \
                         file ({} bytes left)",
                        data.len() - at
                    )
                })?;
            at += compressed;
            let size = if i + 1 == blocks && last != 0 {
                last
            } else {
                block_size
            };
            out.reserve(size.min(compressed.saturating_mul(MAX_INFLATION)));
            let before = out.len();
            ZlibDecoder::new(block)
                .take(size as u64 + 1)
                .read_to_end(&mut out)
                .map_err(|e| format!("block {i} is not valid zlib data: {e}"))?;
            if out.len() - before != size {
                return Err(format!(
                    "block {i} decompresses to {} bytes, expected {size}",
                    out.len() - before
                ));
            }
        }
        Ok(out)
    }

    fn header_size(&self) -> usize {
        if self.header64 {
            8
        } else {
            4
        }
    }

    /// Header word `i` of `data`.
    fn word(&self, data: &[u8], i: usize) -> Result<usize, String> {
        let h = self.header_size();
        let bytes = i
            .checked_mul(h)
            .and_then(|start| data.get(start..start.checked_add(h)?))
            .ok_or_else(|| format!("the file ends inside its header ({} bytes)", data.len()))?;
        let word = if self.header64 {
            let b = bytes.try_into().expect("8 bytes");
            if self.big_endian {
                u64::from_be_bytes(b)
            } else {
                u64::from_le_bytes(b)
            }
        } else {
            let b = bytes.try_into().expect("4 bytes");
            u64::from(if self.big_endian {
                u32::from_be_bytes(b)
            } else {
                u32::from_le_bytes(b)
            })
        };
        usize::try_from(word).map_err(|_| format!("header word {word} exceeds memory"))
    }
}

/// An error unless an array of `size` bytes is the `expected` size.
fn check_size(size: usize, expected: usize, what: &str) -> Result<(), String> {
    if size == expected {
        Ok(())
    } else {
        Err(format!("{what} {size} bytes, expected {expected}"))
    }
}

/// Decodes base64 `text` that may be several padded pieces in a row (VTK encodes the header
/// of a compressed array apart from its blocks); whitespace is skipped.
pub(super) fn decode_base64(text: &str) -> Result<Vec<u8>, String> {
    let mut out = Vec::with_capacity(text.len() / 4 * 3);
    let (mut group, mut filled, mut padding) = (0u32, 0, 0);
    for (i, c) in text
        .bytes()
        .filter(|c| !c.is_ascii_whitespace())
        .enumerate()
    {
        let value = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            b'=' if filled >= 2 => {
                padding += 1;
                0
            }
            _ => {
                return Err(format!(
                    "base64 character {i} is not valid: {:?}",
                    c as char
                ))
            }
        };
        if padding > 0 && c != b'=' {
            return Err(format!("base64 character {i} follows padding in its group"));
        }
        group = (group << 6) | u32::from(value);
        filled += 1;
        if filled == 4 {
            out.extend_from_slice(&group.to_be_bytes()[1..4 - padding]);
            (group, filled, padding) = (0, 0, 0);
        }
    }
    if filled != 0 {
        return Err("the base64 text ends inside a group of 4 characters".into());
    }
    Ok(out)
}

/// A numeric `DataArray` type.
#[derive(Debug, Clone, Copy)]
pub(super) enum Scalar {
    Int { bytes: usize, signed: bool },
    Float { bytes: usize },
}

impl Scalar {
    /// The type named by a `type` attribute.
    pub fn from_vtk(name: &str) -> Option<Scalar> {
        let (signed, bits) = if let Some(bits) = name.strip_prefix("UInt") {
            (false, bits)
        } else if let Some(bits) = name.strip_prefix("Int") {
            (true, bits)
        } else {
            return match name {
                "Float32" => Some(Scalar::Float { bytes: 4 }),
                "Float64" => Some(Scalar::Float { bytes: 8 }),
                _ => None,
            };
        };
        let bytes = match bits {
            "8" => 1,
            "16" => 2,
            "32" => 4,
            "64" => 8,
            _ => return None,
        };
        Some(Scalar::Int { bytes, signed })
    }

    /// Bytes per value.
    pub fn size(self) -> usize {
        match self {
            Scalar::Int { bytes, .. } | Scalar::Float { bytes } => bytes,
        }
    }

    /// The value stored in `b` (`self.size()` bytes).
    pub fn read(self, b: &[u8], big_endian: bool) -> Num {
        let mut word = [0u8; 8];
        let n = b.len();
        if big_endian {
            word[8 - n..].copy_from_slice(b);
            word.reverse();
        } else {
            word[..n].copy_from_slice(b);
        }
        let bits = u64::from_le_bytes(word);
        match self {
            Scalar::Int { signed: false, .. } => Num::Int(i128::from(bits)),
            Scalar::Int { bytes, .. } => {
                let shift = 64 - 8 * bytes as u32;
                Num::Int(i128::from((bits << shift) as i64 >> shift))
            }
            Scalar::Float { bytes: 4 } => Num::Float(f64::from(f32::from_bits(bits as u32))),
            Scalar::Float { .. } => Num::Float(f64::from_bits(bits)),
        }
    }
}

/// A value read from a binary array.
#[derive(Debug, Clone, Copy)]
pub(super) enum Num {
    Int(i128),
    Float(f64),
}

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Num::Int(v) => write!(f, "{v}"),
            Num::Float(v) => write!(f, "{v:?}"),
        }
    }
}

/// A type the arrays of a VTU file are read into, from text or from a binary value.
pub(super) trait Number: std::str::FromStr {
    /// The value, if it is one of this type.
    fn from_num(n: Num) -> Option<Self>;
}

impl Number for f64 {
    fn from_num(n: Num) -> Option<f64> {
        Some(match n {
            Num::Int(v) => v as f64,
            Num::Float(v) => v,
        })
    }
}

impl Number for usize {
    fn from_num(n: Num) -> Option<usize> {
        match n {
            Num::Int(v) => v.try_into().ok(),
            Num::Float(_) => None,
        }
    }
}

impl Number for i32 {
    fn from_num(n: Num) -> Option<i32> {
        match n {
            Num::Int(v) => v.try_into().ok(),
            Num::Float(_) => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_pieces_decode_in_a_row() {
        assert_eq!(decode_base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(decode_base64("aGk=\n d29ybGQ=").unwrap(), b"hiworld");
        assert_eq!(decode_base64("").unwrap(), b"");
        assert!(decode_base64("aGk").is_err());
        assert!(decode_base64("a=Gk").is_err());
        assert!(decode_base64("aG=k").is_err());
        assert!(decode_base64("aGk*").is_err());
    }

    #[test]
    fn scalars_read_in_both_byte_orders() {
        let i16 = Scalar::from_vtk("Int16").unwrap();
        assert!(matches!(i16.read(&[0xfe, 0xff], false), Num::Int(-2)));
        assert!(matches!(i16.read(&[0xff, 0xfe], true), Num::Int(-2)));
        let u8 = Scalar::from_vtk("UInt8").unwrap();
        assert!(matches!(u8.read(&[200], false), Num::Int(200)));
        let f32 = Scalar::from_vtk("Float32").unwrap();
        assert!(matches!(f32.read(&1.5f32.to_be_bytes(), true), Num::Float(v) if v == 1.5));
        assert!(Scalar::from_vtk("Int128").is_none());
        assert!(Scalar::from_vtk("String").is_none());
    }

    #[test]
    fn compressed_arrays_round_trip_across_blocks() {
        let layout = Layout {
            big_endian: false,
            header64: true,
            zlib: true,
        };
        for len in [0, 5, BLOCK_SIZE, 2 * BLOCK_SIZE + 3] {
            let bytes: Vec<u8> = (0..len).map(|i| (i * 7 % 251) as u8).collect();
            let mut out = Vec::new();
            append_compressed(&mut out, &bytes).unwrap();
            assert_eq!(layout.array(&out, len).unwrap(), &bytes[..]);
            assert!(layout.array(&out, len + 1).is_err());
            assert!(layout.array(&out[..out.len() - 1], len).is_err());
        }
    }
}
