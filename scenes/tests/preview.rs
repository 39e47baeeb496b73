//! `preview.png`: a valid PNG of the deformed body that shows the cantilever's sag, and the
//! `[output]` keys `preview`, `preview_field` and `preview_rest`.

use crate::common::scratch;
use isochor_scenes::{load_scene, run_named, Override, SceneError};
use std::path::Path;

/// The body's area of the picture: left of the color bar, below the title.
const AREA_RIGHT: usize = 670;
const AREA_TOP: usize = 50;
/// The rest outline's grey.
const OUTLINE: [u8; 3] = [128, 128, 128];

fn overrides(sets: &[&str]) -> Vec<Override> {
    sets.iter().map(|s| Override::parse(s).unwrap()).collect()
}

/// Runs the cantilever with `sets` into `out`.
fn run(out: &Path, sets: &[&str]) -> isochor_scenes::RunResult {
    run_named("cantilever", None, &overrides(sets), Some(out), false, None)
        .unwrap()
        .0
}

/// An RGB picture, rows top first.
struct Picture {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

impl Picture {
    fn pixel(&self, x: usize, y: usize) -> &[u8] {
        &self.rgb[3 * (y * self.width + x)..3 * (y * self.width + x) + 3]
    }

    /// Pixels of the body's area that satisfy `f`, as `(x, y)`.
    fn find(&self, f: impl Fn(&[u8]) -> bool) -> Vec<(usize, usize)> {
        (AREA_TOP..self.height)
            .flat_map(|y| (0..AREA_RIGHT).map(move |x| (x, y)))
            .filter(|&(x, y)| f(self.pixel(x, y)))
            .collect()
    }
}

/// Shaded viridis has unequal channels; the background, outline and text are grey.
fn is_body(p: &[u8]) -> bool {
    p.iter().max().unwrap() - p.iter().min().unwrap() > 10
}

/// Checks the PNG signature and the IHDR chunk, then decodes the picture.
fn decode(path: &Path) -> Picture {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap()) as usize;
    let (width, height) = (be(16), be(20));
    assert_eq!((width, height), (800, 600));
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    let mut rgb = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut rgb).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    rgb.truncate(info.buffer_size());
    Picture { width, height, rgb }
}

/// The cantilever clamped at x = 0 sags under gravity along -y, which the picture draws
/// down: near the free end, the lowest pixel of the deformed body lies below the lowest pixel
/// of the rest outline.
#[test]
fn the_cantilever_preview_shows_the_sag() {
    let dir = scratch("preview-sag");
    let out = dir.join("out");
    let result = run(&out, &[]);
    assert!(result.converged);
    let picture = decode(&out.join("preview.png"));
    let body = picture.find(is_body);
    let outline = picture.find(|p| p == OUTLINE);
    assert!(body.len() > 10_000, "{} body pixels", body.len());
    assert!(outline.len() > 500, "{} outline pixels", outline.len());
    // The rest outline spans the beam from the clamp (left) to the free end (right).
    let left = outline.iter().map(|p| p.0).min().unwrap();
    let right = outline.iter().map(|p| p.0).max().unwrap();
    let column = left + (right - left) * 4 / 5;
    let lowest = |pixels: &[(usize, usize)]| {
        pixels
            .iter()
            .filter(|p| p.0.abs_diff(column) <= 3)
            .map(|p| p.1)
            .max()
            .unwrap()
    };
    let (body_low, rest_low) = (lowest(&body), lowest(&outline));
    eprintln!(
        "outline x {left}..{right}, column {column}: lowest body row {body_low}, rest {rest_low}"
    );
    assert!(
        body_low > rest_low + 10,
        "the body's lowest row {body_low} must lie well below the rest outline's {rest_low}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `preview_field` and `preview_rest` change the picture; without the outline there is no
/// outline grey.
#[test]
fn preview_field_and_rest_outline_are_chosen_by_keys() {
    let dir = scratch("preview-keys");
    for field in ["von_mises", "mean_stress", "J", "displacement"] {
        let out = dir.join(field);
        run(
            &out,
            &[
                "res=1",
                &format!("preview_field={field}"),
                "preview_rest=false",
            ],
        );
        let picture = decode(&out.join("preview.png"));
        assert!(picture.find(is_body).len() > 5_000, "{field}");
        assert!(picture.find(|p| p == OUTLINE).is_empty(), "{field}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_unknown_preview_field_is_an_error_naming_the_key_and_the_values() {
    for set in ["preview_field=stress", "output.preview_field=stress"] {
        let err = load_scene("cantilever", None, &overrides(&[set])).unwrap_err();
        assert!(matches!(err, SceneError::Invalid { .. }), "{err}");
        let message = err.to_string();
        for needle in [
            "output.preview_field",
            "stress",
            "displacement",
            "von_mises",
            "mean_stress",
            "`J`",
        ] {
            assert!(message.contains(needle), "{needle} missing: {message}");
        }
    }
}

/// `preview` follows `plots` unless given.
#[test]
fn preview_false_or_no_plots_writes_no_picture() {
    let dir = scratch("preview-off");
    for (name, sets, expected) in [
        ("off", &["preview=false"][..], false),
        ("no-plots", &["plots=false"][..], false),
        ("only-preview", &["plots=false", "preview=true"][..], true),
    ] {
        let out = dir.join(name);
        let mut all = vec!["res=1", "vtu=false"];
        all.extend(sets);
        run(&out, &all);
        assert!(out.join("summary.json").is_file());
        assert_eq!(out.join("preview.png").is_file(), expected, "{name}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A run that fails still draws its last accepted state.
#[test]
fn a_failed_run_draws_its_last_accepted_state() {
    let dir = scratch("preview-failed");
    let out = dir.join("out");
    let result = run(
        &out,
        &[
            "res=1",
            "steps=2",
            "increments=fixed",
            "solver.max_iterations=2",
        ],
    );
    assert!(result.error.is_some());
    let picture = decode(&out.join("preview.png"));
    assert!(picture.find(is_body).len() > 5_000);
    std::fs::remove_dir_all(&dir).unwrap();
}
