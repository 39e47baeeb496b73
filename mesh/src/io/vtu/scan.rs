//! The scan of a VTU file's XML: its tags (checked to nest), the layout of its binary data,
//! its piece and its data arrays, and the raw bytes of its `<AppendedData>`. Nothing read
//! here is a size: sizes are checked against the bytes present when values are read.

use super::super::vtk_binary::Layout;
use crate::MeshError;
use std::path::Path;

/// A `<DataArray>` found in the file.
pub(super) struct Array<'a> {
    /// The name of the enclosing element.
    pub(super) parent: &'a str,
    attributes: Vec<(&'a str, String)>,
    /// The text after the tag and any child elements: ASCII values or base64.
    pub(super) content: &'a str,
    pub(super) line: usize,
}

impl Array<'_> {
    pub(super) fn attribute(&self, key: &str) -> Option<&str> {
        self.attributes
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.as_str())
    }

    pub(super) fn name(&self) -> &str {
        self.attribute("Name").unwrap_or("")
    }

    /// `ascii`, `binary` (inline base64) or `appended`.
    pub(super) fn format(&self) -> &str {
        self.attribute("format").unwrap_or("ascii")
    }

    pub(super) fn components(&self, path: &Path) -> Result<usize, MeshError> {
        self.attribute("NumberOfComponents").map_or(Ok(1), |c| {
            c.parse().map_err(|_| {
                MeshError::parse(
                    path,
                    self.line,
                    format!("expected NumberOfComponents to be an integer, found `{c}`"),
                )
            })
        })
    }
}

/// 1-based line of byte `offset`.
pub(super) fn line_of(bytes: &[u8], offset: usize) -> usize {
    bytes[..offset.min(bytes.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The first non-blank run of `content` outside its child elements: the values of a
/// `<DataArray>`, which VTK may precede or follow with `<InformationKey>` elements.
fn own_text(content: &str) -> &str {
    let mut depth = 0usize;
    let mut pos = 0;
    loop {
        let next = content[pos..].find('<').map_or(content.len(), |i| pos + i);
        let run = &content[pos..next];
        if depth == 0 && !run.trim().is_empty() {
            return run;
        }
        if next == content.len() {
            return "";
        }
        let end = content[next..]
            .find('>')
            .map_or(content.len(), |i| next + i + 1);
        let tag = &content[next..end];
        if tag.starts_with("</") {
            depth = depth.saturating_sub(1);
        } else if !(tag.ends_with("/>") || tag.starts_with("<?") || tag.starts_with("<!")) {
            depth += 1;
        }
        pos = end;
    }
}

/// Splits a file at its `<AppendedData>` tag: the XML up to the end of that tag, and the raw
/// bytes after the `_` that starts the data (offsets of appended arrays count from there).
pub(super) fn split_appended<'b>(
    path: &Path,
    bytes: &'b [u8],
) -> Result<(&'b [u8], Option<&'b [u8]>), MeshError> {
    const TAG: &[u8] = b"<AppendedData";
    let Some(start) = bytes.windows(TAG.len()).position(|w| w == TAG) else {
        return Ok((bytes, None));
    };
    let err = |message: &str| MeshError::parse(path, line_of(bytes, start), message);
    let end = bytes[start..]
        .iter()
        .position(|&b| b == b'>')
        .map(|i| start + i + 1)
        .ok_or_else(|| err("unterminated <AppendedData> tag: expected `>`"))?;
    let underscore = bytes[end..]
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .map(|i| end + i)
        .filter(|&i| bytes[i] == b'_')
        .ok_or_else(|| err("expected `_` to start the data after <AppendedData>"))?;
    if !bytes.trim_ascii_end().ends_with(b"</VTKFile>") {
        return Err(err(
            "the file ends before </VTKFile> after its appended data: it is truncated",
        ));
    }
    Ok((&bytes[..end], Some(&bytes[underscore + 1..])))
}

/// Parses `key="value"` pairs of a tag.
fn attributes<'a>(
    path: &Path,
    line: usize,
    text: &'a str,
) -> Result<Vec<(&'a str, String)>, MeshError> {
    let mut out = Vec::new();
    let mut rest = text.trim();
    while !rest.is_empty() {
        let bad = || {
            MeshError::parse(
                path,
                line,
                format!("expected attributes `key=\"value\"`, found `{rest}`"),
            )
        };
        let eq = rest.find('=').ok_or_else(bad)?;
        let key = rest[..eq].trim();
        let after = rest[eq + 1..].trim_start();
        let quote = after
            .chars()
            .next()
            .filter(|&c| c == '"' || c == '\'')
            .ok_or_else(bad)?;
        let close = after[1..].find(quote).ok_or_else(bad)?;
        out.push((key, unescape(&after[1..1 + close])));
        rest = after[close + 2..].trim_start();
    }
    Ok(out)
}

fn unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

/// What the scan of the XML finds: how binary data is laid out, the piece's size and the
/// data arrays.
pub(super) struct Scan<'a> {
    pub(super) layout: Layout,
    /// A `compressor` other than zlib, refused when a binary array is read.
    pub(super) unsupported_compressor: Option<String>,
    /// The `<Piece>`'s numbers of points and cells.
    pub(super) piece: Option<(usize, usize)>,
    /// Whether an `<UnstructuredGrid>` was found.
    pub(super) grid: bool,
    pub(super) arrays: Vec<Array<'a>>,
}

/// A tag of the XML: where it starts and the text between `<` and `>`.
struct Tag<'a> {
    start: usize,
    body: &'a str,
}

/// An element opened by a tag.
struct Element<'a> {
    /// Where its tag starts.
    start: usize,
    name: &'a str,
    attrs: Vec<(&'a str, String)>,
    /// The name of the enclosing element.
    parent: &'a str,
    /// Where its content starts (`None` for a self-closing tag).
    content: Option<usize>,
}

impl Element<'_> {
    fn attr(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.as_str())
    }
}

/// The error at byte `offset` of `text`.
pub(super) fn error_at(path: &Path, text: &str, offset: usize, message: String) -> MeshError {
    MeshError::parse(path, line_of(text.as_bytes(), offset), message)
}

/// Scans the XML `text` (of a file whose raw appended data follows it if `appended`) for the
/// elements isochor reads, checking that the tags nest.
pub(super) fn scan<'a>(path: &Path, text: &'a str, appended: bool) -> Result<Scan<'a>, MeshError> {
    let mut scan = Scan {
        layout: Layout {
            big_endian: false,
            header64: false,
            zlib: false,
        },
        unsupported_compressor: None,
        piece: None,
        grid: false,
        arrays: Vec::new(),
    };
    let mut stack: Vec<&str> = Vec::new();
    let mut pos = 0;
    while let Some(tag) = next_tag(path, text, &mut pos)? {
        if let Some(name) = tag.body.strip_prefix('/') {
            close(path, text, &tag, name.trim(), stack.pop())?;
            continue;
        }
        let self_closing = tag.body.ends_with('/');
        let body = tag.body.trim_end_matches('/');
        let (name, attribute_text) = body.split_once(char::is_whitespace).unwrap_or((body, ""));
        let attrs = attributes(path, line_of(text.as_bytes(), tag.start), attribute_text)?;
        let element = Element {
            start: tag.start,
            name,
            attrs,
            parent: stack.last().copied().unwrap_or(""),
            content: (!self_closing).then_some(pos),
        };
        scan.open(path, text, element)?;
        if !self_closing {
            stack.push(name);
        }
    }
    match stack.last() {
        // The XML ends at the <AppendedData> tag; the raw data follows.
        Some(&"AppendedData") if appended => Ok(scan),
        Some(open) => Err(error_at(
            path,
            text,
            text.len(),
            format!("unexpected end of file: expected </{open}>"),
        )),
        None => Ok(scan),
    }
}

/// The next tag from `pos` (moved past it), skipping processing instructions and comments.
fn next_tag<'a>(path: &Path, text: &'a str, pos: &mut usize) -> Result<Option<Tag<'a>>, MeshError> {
    while let Some(rel) = text[*pos..].find('<') {
        let start = *pos + rel;
        let rest = &text[start..];
        let (skip, terminator) = if rest.starts_with("<?") {
            (true, "?>")
        } else if rest.starts_with("<!--") {
            (true, "-->")
        } else {
            (false, ">")
        };
        let end = rest.find(terminator).ok_or_else(|| {
            error_at(
                path,
                text,
                start,
                format!("unterminated tag: expected `{terminator}`"),
            )
        })?;
        *pos = start + end + terminator.len();
        if !skip {
            return Ok(Some(Tag {
                start,
                body: &rest[1..end],
            }));
        }
    }
    Ok(None)
}

/// Checks that the closing tag `</name>` closes `open`, the innermost open element.
fn close(
    path: &Path,
    text: &str,
    tag: &Tag,
    name: &str,
    open: Option<&str>,
) -> Result<(), MeshError> {
    match open {
        Some(open) if open == name => Ok(()),
        Some(open) => Err(error_at(
            path,
            text,
            tag.start,
            format!("expected </{open}>, found </{name}>"),
        )),
        None => Err(error_at(
            path,
            text,
            tag.start,
            format!("unexpected closing tag </{name}>"),
        )),
    }
}

impl<'a> Scan<'a> {
    /// Reads the elements isochor uses: the file's layout, the grid, its piece, the appended
    /// data's encoding and the data arrays.
    fn open(&mut self, path: &Path, text: &'a str, e: Element<'a>) -> Result<(), MeshError> {
        let err = |message: String| error_at(path, text, e.start, message);
        match e.name {
            "VTKFile" => self.read_header(&e).map_err(err)?,
            "UnstructuredGrid" => self.grid = true,
            "Piece" if self.piece.is_some() => {
                return Err(err(
                    "files with several <Piece> elements are not supported".into()
                ))
            }
            "Piece" => {
                let count = |key: &str| {
                    e.attr(key)
                        .and_then(|v| v.parse::<usize>().ok())
                        .ok_or_else(|| err(format!("expected <Piece> to have an integer {key}")))
                };
                self.piece = Some((count("NumberOfPoints")?, count("NumberOfCells")?));
            }
            "AppendedData" => {
                let encoding = e.attr("encoding").unwrap_or("none");
                if encoding != "raw" {
                    return Err(err(format!(
                        "AppendedData encoding \"{encoding}\" is not supported (isochor \
                         reads raw appended data)"
                    )));
                }
            }
            "DataArray" => self.data_array(path, text, e)?,
            _ => {}
        }
        Ok(())
    }

    /// The `<VTKFile>` attributes: type, byte order, header type and compressor.
    fn read_header(&mut self, e: &Element) -> Result<(), String> {
        if e.attr("type") != Some("UnstructuredGrid") {
            return Err(format!(
                "expected a VTKFile of type \"UnstructuredGrid\", found {:?}",
                e.attr("type").unwrap_or("none")
            ));
        }
        self.layout.big_endian = match e.attr("byte_order") {
            None | Some("LittleEndian") => false,
            Some("BigEndian") => true,
            Some(other) => {
                return Err(format!(
                    "byte_order \"{other}\" is neither LittleEndian nor BigEndian"
                ))
            }
        };
        self.layout.header64 = match e.attr("header_type") {
            None | Some("UInt32") => false,
            Some("UInt64") => true,
            Some(other) => {
                return Err(format!(
                    "header_type \"{other}\" is neither UInt32 nor UInt64"
                ))
            }
        };
        match e.attr("compressor") {
            None | Some("") => {}
            Some("vtkZLibDataCompressor") => self.layout.zlib = true,
            Some(other) => self.unsupported_compressor = Some(other.to_string()),
        }
        Ok(())
    }

    /// A `<DataArray>`: its format is checked and its own text kept.
    fn data_array(&mut self, path: &Path, text: &'a str, e: Element<'a>) -> Result<(), MeshError> {
        let err = |message: String| error_at(path, text, e.start, message);
        let format = e.attr("format").unwrap_or("ascii");
        if !matches!(format, "ascii" | "binary" | "appended") {
            return Err(err(format!(
                "DataArray format \"{format}\" is not supported (expected ascii, \
                 binary or appended)"
            )));
        }
        let content = match e.content {
            None => "",
            Some(pos) => {
                let close = text[pos..]
                    .find("</DataArray>")
                    .ok_or_else(|| err("expected </DataArray>".into()))?;
                own_text(&text[pos..pos + close])
            }
        };
        self.arrays.push(Array {
            parent: e.parent,
            attributes: e.attrs,
            content,
            line: line_of(text.as_bytes(), e.start),
        });
        Ok(())
    }
}
